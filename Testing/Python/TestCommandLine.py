# SPDX-License-Identifier: BSD-3-Clause
"""The `aperture` command line as a user runs it (the build tree's bin/aperture launcher):
help, `info` (text and --json) on the embedded DEM, on projected and lat/lon rasters in several
GDAL formats made here with GDAL's Python bindings, and one clear line on stderr with exit
status 1 for every bad input."""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import numpy as np
from osgeo import gdal, osr

from privileges import unprivileged
from usage import usage_error

gdal.UseExceptions()

BUILD = os.environ.get("APERTURE_BUILD_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
APERTURE = os.path.join(BUILD, "bin", "aperture")
CELL3 = 1.0 / 1200.0


def run(*args, env=None):
    """Run the command line; returns (status, stdout, stderr)."""
    p = subprocess.run([APERTURE] + [str(a) for a in args], capture_output=True, text=True,
                       env=env, timeout=120)
    return p.returncode, p.stdout, p.stderr


def make_raster(path, rows, gt, srs="EPSG:32611", nodata=None, driver="GTiff", bands=1,
                gcps=None, options=()):
    """Write `rows` (a 2-D array, first row = first file row) with GDAL (`options`: the
    driver's creation options)."""
    rows = np.asarray(rows, dtype=np.float64)
    ny, nx = rows.shape
    mem = gdal.GetDriverByName("MEM").Create("", nx, ny, bands, gdal.GDT_Float32)
    if gt is not None:
        mem.SetGeoTransform(gt)
    if srs:
        ref = osr.SpatialReference()
        ref.SetFromUserInput(srs)
        if gcps:
            mem.SetGCPs(gcps, ref)
        else:
            mem.SetSpatialRef(ref)
    for b in range(1, bands + 1):
        band = mem.GetRasterBand(b)
        if nodata is not None:
            band.SetNoDataValue(nodata)
        band.WriteArray(rows + 1000.0 * (b - 1))
    out = gdal.GetDriverByName(driver).CreateCopy(path, mem, options=list(options))
    out.FlushCache()
    out = None
    mem = None
    return path


class CommandLineTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="aperture-cli-")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def path(self, name):
        return os.path.join(self.tmp, name)

    def info(self, *args):
        status, out, err = run("info", "--json", *args)
        self.assertEqual(status, 0, err)
        return json.loads(out), err

    def assert_error(self, expected, *args, env=None):
        """Exit status 1, exactly one line on stderr naming the problem, nothing on stdout."""
        status, out, err = run(*args, env=env)
        self.assertEqual(status, 1, "stdout: %s\nstderr: %s" % (out, err))
        lines = err.strip().splitlines()
        self.assertEqual(len(lines), 1, err)
        self.assertTrue(lines[0].startswith("aperture: error: "), lines[0])
        self.assertIn(expected, lines[0])
        self.assertEqual(out, "")

    def assert_usage_error(self, expected, command, *args, env=None):
        """A mistake in the options themselves: a usage error naming it."""
        self.assertIn(expected, usage_error(self, command, run(command, *args, env=env)))


class TestHelp(CommandLineTest):
    def test_no_arguments_explains_subcommands(self):
        for args in ((), ("--help",)):
            status, out, _ = run(*args)
            self.assertEqual(status, 0)
            self.assertIn("info", out)
            self.assertIn("render", out)
            self.assertIn("usage: aperture", out)

    def test_subcommand_help(self):
        status, out, _ = run("info", "--help")
        self.assertEqual(status, 0)
        self.assertIn("--json", out)
        self.assertIn("--srcwin", out)

    def test_usage_error(self):
        status, _, err = run("info", "--band")
        self.assertEqual(status, 2)
        self.assertIn("expected one argument", err)
        # an unknown option is said in the command's usage (it was the top level's), and a
        # long option is not taken from its first letters, as GDAL's tools take none ('--no'
        # was --no-curvature in bake, --no-stats in info)
        cases = [(args, "aperture %s: error: unrecognized arguments: %s" % (args[0], unknown))
                 for args, unknown in ((("info", "--bogus"), "--bogus"), (("info", "--no"), "--no"),
                                       (("bake", "x.tif", "y.tif", "--dir", "8"), "--dir 8"),
                                       (("sun", "--at", "2026-06-21T12:00Z", "--lat", "0", "--lo",
                                         "0"), "--lo 0"))]
        # gdaldem's options get what to give instead (unrecognized alone until 2026-12-07)
        cases += [
                (("bake", "x.tif", "y.tif", "-co", "COMPRESS=ZSTD", "-co", "TILED=YES", "-of",
                  "GTiff"), "unrecognized arguments: -co COMPRESS=ZSTD -co TILED=YES -of GTiff. "
                            "-co: GDAL's creation options are not taken: --compress CODEC and "
                            "--compress-level N choose the compression (the GeoTIFF is tiled, "
                            "with the floating-point predictor, BigTIFF when it needs to be); "
                            "-of: bake writes a GeoTIFF (and an OpenEXR file with --exr), "
                            "whatever the name\n"),
                (("render", "x.tif", "-z", "2"), "unrecognized arguments: -z 2. -z: "
                                                 "--exaggeration stretches the heights drawn; "
                                                 "--zfactor Z gives the metres of an elevation "
                                                 "unit\n"),
                (("info", "x.tif", "-s", "111120", "-compute_edges"),
                 "arguments: -s 111120 -compute_edges. -s: cell sizes come in metres from the "
                 "DEM's CRS, lat/lon included; --zfactor Z gives the metres of an elevation unit; "
                 "-compute_edges: every cell is computed"),
                # (argparse read render's -of as -o f, and the value of a -co before the DEM
                # as the DEM: the hints did not show; one hint an option, by its name)
                (("render", "x.tif", "-of", "PNG"), "unrecognized arguments: -of PNG. -of: "
                                                   "render writes a PNG (and an OpenEXR file "
                                                   "with --exr)\n"),
                (("bake", "-co", "COMPRESS=ZSTD", "-co=TILED=YES", "in.tif", "out.tif"),
                 "unrecognized arguments: -co COMPRESS=ZSTD -co=TILED=YES. -co: GDAL's creation "
                 "options are not taken: --compress CODEC and --compress-level N choose the "
                 "compression (the GeoTIFF is tiled, with the floating-point predictor, BigTIFF "
                 "when it needs to be)\n"),
                # (values taken up to an option; --config's KEY=VALUE form is one; GDAL 3.11's
                # --co)
                (("render", "x.tif", "-z", "--exaggeration", "2"),
                 "unrecognized arguments: -z. -z: --exaggeration stretches"),
                (("bake", "--config", "GDAL_CACHEMAX=512", "in.tif", "out.tif"),
                 "unrecognized arguments: --config GDAL_CACHEMAX=512. --config: GDAL's "
                 "configuration options are read from the environment"),
                (("bake", "--co", "COMPRESS=ZSTD", "in.tif", "out.tif"),
                 "unrecognized arguments: --co COMPRESS=ZSTD. --co: GDAL's creation options"),
                # (one hint for the options that share it: twice until 2026-12-07)
                (("bake", "-co", "A=B", "--co", "C=D", "-co", "E=F", "in.tif", "out.tif"),
                 "unrecognized arguments: -co A=B --co C=D -co E=F. -co, --co: GDAL's creation "
                 "options are not taken: --compress CODEC and --compress-level N choose the "
                 "compression (the GeoTIFF is tiled, with the floating-point predictor, BigTIFF "
                 "when it needs to be)\n")]
        for args, said in cases:
            status, out, err = run(*args)
            self.assertEqual((status, out), (2, ""), err)
            self.assertIn("usage: aperture %s " % args[0], err)
            self.assertIn(said, err)
        # --help beside one is the help, as beside any other unknown argument (the hint until
        # 2026-12-07); after "--" it is an argument
        for help_option in ("--help", "-h"):
            status, out, err = run("bake", "-co", "X", help_option)
            self.assertEqual((status, err), (0, ""), err)
            self.assertIn("--compress CODEC", out)
        status, _, err = run("bake", "-co", "X", "--", "--help")
        self.assertEqual(status, 2, err)
        self.assertIn("unrecognized arguments: -co X. -co: GDAL's creation options", err)


class TestLauncher(CommandLineTest):
    def test_modules_that_do_not_load(self):
        # A launcher without its package beside it (a broken install; also what too little
        # memory to load VTK and GDAL looks like): one line naming where it looked, no traceback
        folder = self.path("lonely/bin")
        os.makedirs(folder)
        launcher = os.path.join(folder, "aperture")
        shutil.copy(APERTURE, launcher)
        env = dict(os.environ, PYTHONPATH="")
        p = subprocess.run([launcher, "--help"], capture_output=True, text=True, env=env,
                           timeout=60)
        if p.returncode == 0:
            self.skipTest("an installed aperture package is on this machine's path")
        self.assertEqual(p.returncode, 1, p.stderr)
        line = p.stderr.strip()
        self.assertEqual(len(line.splitlines()), 1, line)
        self.assertTrue(line.startswith("aperture: error: cannot load Aperture's Python modules "
                                        "(from %s/" % os.path.join(self.tmp, "lonely")), line)
        self.assertTrue(line.endswith("): No module named 'aperture'"), line)


    def test_folder_realpath(self):
        # The frames' checks resolve each folder once (10,000 frames took 8 s of realpath
        # until 2026-12-07): the same path as os.path.realpath for names in a folder reached
        # through a link, names that are links (to a file, to a link, dangling), "..", "."
        # and relative names, existing or not.
        from aperture import cli
        base = self.path("real")
        os.makedirs(os.path.join(base, "a", "b"))
        os.symlink(os.path.join(base, "a", "b"), os.path.join(base, "via"))
        os.symlink("a/b", os.path.join(base, "rel"))
        open(os.path.join(base, "a", "b", "f.png"), "w").close()
        os.symlink(os.path.join(base, "a", "b", "f.png"), os.path.join(base, "a", "link.png"))
        os.symlink("link.png", os.path.join(base, "a", "chain.png"))
        os.symlink("/nonexistent/x.png", os.path.join(base, "a", "dangling.png"))
        names = ["via/f.png", "via/new.png", "rel/f.png", "via/../a/link.png", "a/chain.png",
                 "a/dangling.png", "a/b/..", "a/.", "a/", "via", "x.png", "./via/f.png",
                 "via//f.png"]
        real = cli._folder_realpath()
        cwd = os.getcwd()
        try:
            os.chdir(base)
            for name in names + [os.path.join(base, n) for n in names]:
                self.assertEqual(real(name), os.path.realpath(name), name)
        finally:
            os.chdir(cwd)

    def test_interrupt_while_importing(self):
        # render loads VTK's rendering modules on its first use (aperture.scene): a Ctrl-C
        # meanwhile is KeyboardInterrupt (exit 130), though VTK's module loader turns it into
        # an ImportError (a traceback and exit 1 until 2026-12-06) or swallows it. Modules
        # here that do either with a SIGINT they send themselves; a plain ImportError stays
        # one, and an ignored SIGINT stays ignored.
        import signal
        from aperture import cli
        folder = self.path("modules")
        os.makedirs(folder)
        body = ("import os, signal\ntry:\n    os.kill(os.getpid(), signal.SIGINT)\n"
                "    for _ in range(1000):\n        pass\nexcept KeyboardInterrupt:\n    %s\n")
        for name, what in (("converts", 'raise ImportError("Failed to load vtkSomething")'),
                           ("swallows", "pass"), ("broken", "pass")):
            with open(os.path.join(folder, "aperture_test_%s.py" % name), "w") as f:
                f.write('raise ImportError("no such library")\n' if name == "broken" else
                        body % what)
        sys.path.insert(0, folder)
        previous = signal.signal(signal.SIGINT, signal.default_int_handler)
        try:
            for name in ("converts", "swallows"):
                with self.assertRaises(KeyboardInterrupt, msg=name):
                    cli._interruptible_import("aperture_test_" + name)
                self.assertIs(signal.getsignal(signal.SIGINT), signal.default_int_handler)
            with self.assertRaisesRegex(ImportError, "no such library"):
                cli._interruptible_import("aperture_test_broken")
            sys.modules.pop("aperture_test_swallows")
            signal.signal(signal.SIGINT, signal.SIG_IGN)
            self.assertEqual(cli._interruptible_import("aperture_test_swallows").__name__,
                             "aperture_test_swallows")
            self.assertIs(signal.getsignal(signal.SIGINT), signal.SIG_IGN)
            # (a thread other than the main one cannot set handlers: it imports plainly)
            import threading
            signal.signal(signal.SIGINT, signal.default_int_handler)
            got = []
            thread = threading.Thread(target=lambda: got.append(
                cli._interruptible_import("aperture_test_swallows").__name__))
            thread.start()
            thread.join()
            self.assertEqual(got, ["aperture_test_swallows"])
        finally:
            signal.signal(signal.SIGINT, previous)
            sys.path.remove(folder)

    def test_interrupt_while_loading(self):
        # Ctrl-C in the first few tenths of a second, while VTK and GDAL load: VTK's module
        # loader turned the KeyboardInterrupt into an ImportError, reported as "cannot load
        # Aperture's Python modules" (exit 1), or swallowed it, and the bake ran to its end
        # (exit 0), until 2026-12-06. Now exit 130, as for any interrupt, at every moment from
        # the launcher's first line (before it, in Python's own start-up, the signal ends the
        # process, -2, or Python prints a KeyboardInterrupt). The delays count from the moment
        # VTK's first library is mapped, not from the start: on a loaded machine Python's own
        # start-up took longer than the 0.1 s the first delay was.
        import signal
        import time
        dem = self.path("loading.tif")
        rng = np.random.default_rng(5)
        make_raster(dem, np.cumsum(rng.normal(0, 5, (500, 500)), axis=0),
                    (500000, 30, 0, 4000000, 0, -30))

        def vtk_loading(pid):
            deadline = time.monotonic() + 60.0
            while time.monotonic() < deadline:
                with open("/proc/%d/maps" % pid) as maps:
                    if "libvtkCommonCore" in maps.read():
                        return True
                time.sleep(0.001)
            return False

        for delay in (0.0, 0.03, 0.06, 0.09, 0.12, 0.16, 0.2):
            # (SIGINT at its default in the child: a test run as a background job inherits it
            # ignored, as a shell's background jobs do, and the command keeps that)
            p = subprocess.Popen([APERTURE, "bake", "-q", dem, self.path("loading-out.tif")],
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                 preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
            self.assertTrue(vtk_loading(p.pid))
            time.sleep(delay)
            p.send_signal(signal.SIGINT)
            out, err = p.communicate(timeout=120)
            self.assertEqual(p.returncode, 130, (delay, err))
            self.assertEqual((out, err), ("", ""), delay)


    def test_closed_stdout(self):
        # A reader that stops early (`aperture info --json x | head -1`): the command ends
        # quietly with the status of a tool that SIGPIPE ends, 141, as gdalinfo does; it
        # printed a BrokenPipeError traceback before 2026-12-05. The bake's outputs, written
        # before its summary line, are whole.
        dem = self.path("pipe.tif")
        make_raster(dem, np.add.outer(np.arange(20.0), np.arange(30.0)),
                    (500000, 30, 0, 4000000, 0, -30))
        out = self.path("pipe-out.tif")
        # Python's stdout is buffered (as on a fresh machine) or not (PYTHONUNBUFFERED=1, as in
        # some CI environments, which hid the buffered case until 2026-12-06: the pipe's error
        # came at the interpreter's exit, status 120 with "Exception ignored")
        unbuffered = dict(os.environ, PYTHONUNBUFFERED="1")
        buffered = {k: v for k, v in os.environ.items() if k != "PYTHONUNBUFFERED"}
        for args in (("info", "--json", dem), ("bake", "--help"), ("bake", "--radius"),
                     ("bake", dem, out, "--radius", 300, "-d", 8)):
            for env in (buffered, unbuffered):
                read, write = os.pipe()
                os.close(read)  # (every write to the pipe now fails: EPIPE)
                try:
                    p = subprocess.run([APERTURE] + [str(a) for a in args], stdout=write,
                                       stderr=subprocess.PIPE, text=True, timeout=120,
                                       env=env)
                finally:
                    os.close(write)
                # (a usage error's text goes to stderr, its status 2 whatever stdout is)
                expected = (2, "usage") if args == ("bake", "--radius") else (141, "")
                self.assertEqual((p.returncode, p.stderr[:5]), expected,
                                 (args, "PYTHONUNBUFFERED" in env, p.stderr))
        status, _, err = run("info", out, "--band", 4)  # (the bake's file, whole)
        self.assertEqual(status, 0, err)
        ds = gdal.Open(out)
        self.assertEqual(ds.RasterCount, 9)
        self.assertTrue(np.isfinite(ds.GetRasterBand(4).ReadAsArray()).all())
        ds = None


    def test_stdout_unwritable(self):
        # `python3 -m aperture` with stdout closed (no launcher to put /dev/null there:
        # sys.stdout is None) runs as it did; a stdout that fails to take the output (a full
        # disk: /dev/full) is one line and status 1, not a traceback (both 2026-12-06)
        dem = self.path("unwritable.tif")
        make_raster(dem, np.ones((6, 7)), (500000, 30, 0, 4000000, 0, -30))
        python = os.path.join(BUILD, "bin", "aperture-python")
        command = [python, "-m", "aperture", "info", "--json", dem]
        p = subprocess.run(command, stderr=subprocess.PIPE, text=True,
                           preexec_fn=lambda: os.close(1), timeout=120)
        self.assertEqual((p.returncode, p.stderr), (0, ""))
        with open("/dev/full", "w") as full:
            p = subprocess.run(command, stdout=full, stderr=subprocess.PIPE, text=True,
                               timeout=120)
        self.assertEqual((p.returncode, p.stderr), (1, "aperture: error: cannot write the "
                                                       "standard output: No space left on "
                                                       "device\n"))

    def test_closed_stderr(self):
        # Run with stderr closed (`2>&-`), warnings and errors went to stdout (Python's
        # sys.stderr is then None, and print(file=None) prints to stdout), into the JSON of
        # `info --json`; and the first file opened took descriptor 2, for GDAL's and VTK's
        # messages to land in. The launcher puts /dev/null there.
        dem = self.path("closed.tif")
        make_raster(dem, np.ones((6, 7)), (500000, 30, 0, 4000000, 0, -30), bands=2)
        for args, status in ((("info", "--json", dem), 0),
                             (("info", "--json", self.path("missing.tif")), 1)):
            p = subprocess.run([APERTURE] + list(args), stdout=subprocess.PIPE, text=True,
                               preexec_fn=lambda: os.close(2), timeout=120)
            self.assertEqual(p.returncode, status, p.stdout)
            if status == 0:  # (the note on the second band is gone, not in the JSON)
                self.assertEqual(json.loads(p.stdout)["size"], [7, 6])
            else:
                self.assertEqual(p.stdout, "")


    def test_names_not_utf8(self):
        # File names that are not UTF-8 (Latin-1 from an older system): VTK's Python wrapping
        # cannot pass them as strings, and `info` and `bake` stopped with a UnicodeEncodeError
        # traceback before 2026-12-05. They are read and written now, printed as the bytes
        # they are; a missing one is named, and a reader's error that names one (which VTK
        # cannot pass on to Python) names the file.
        folder = os.fsencode(self.tmp)
        dem = os.path.join(folder, b"h\xf6he.tif")  # "hoehe" with o-umlaut in Latin-1
        make_raster(self.path("utf8.tif"), np.add.outer(np.arange(20.0), np.arange(30.0)),
                    (500000, 30, 0, 4000000, 0, -30))
        os.rename(self.path("utf8.tif"), dem)  # (GDAL's Python bindings take str names only)

        def run_bytes(*args):
            p = subprocess.run([os.fsencode(APERTURE)] + list(args), capture_output=True,
                               timeout=120)
            return p.returncode, p.stdout, p.stderr

        status, out, err = run_bytes(b"info", dem)
        self.assertEqual((status, err), (0, b""))
        self.assertIn(b"File:       " + dem + b" (GTiff, band 1 of 1)", out)
        tif, exr = os.path.join(folder, b"\xe9t\xe9.tif"), os.path.join(folder, b"\xe9t\xe9.exr")
        status, out, err = run_bytes(b"bake", dem, tif, b"--exr", exr, b"--radius", b"300")
        self.assertEqual((status, err), (0, b""))
        self.assertTrue(out.startswith(b"wrote " + tif + b" and " + exr + b": "), out)
        self.assertGreater(os.path.getsize(tif), 0)
        self.assertGreater(os.path.getsize(exr), 0)
        status, out, err = run_bytes(b"info", tif, b"--band", b"4")  # (its SkyViewFactor)
        self.assertEqual((status, err), (0, b""))
        missing = os.path.join(folder, b"m\xfcde.tif")
        status, out, err = run_bytes(b"info", missing)
        self.assertEqual((status, out, err),
                         (1, b"", b"aperture: error: file '" + missing + b"' does not exist\n"))
        garbage = os.path.join(folder, b"m\xfcll.tif")
        with open(garbage, "wb") as f:
            f.write(b"not a raster")
        status, out, err = run_bytes(b"info", garbage)
        self.assertEqual((status, out), (1, b""))
        self.assertEqual(err, b"aperture: error: vtkApertureDEMReader failed on '" + garbage +
                         b"' (its message could not be passed on: the file name is not "
                         b"UTF-8)\n")


class TestInfo(CommandLineTest):
    def test_default_dem_json(self):
        d, err = self.info()
        self.assertEqual(err, "")
        self.assertEqual(d["size"], [403, 344])
        self.assertEqual(d["crs"], "WGS 84")
        self.assertTrue(d["geographic"])
        # the CRS's code and the geotransform (GDAL's order) of the grid read, north up: a
        # north-up file's, as gdalinfo -json gives it
        self.assertEqual(d["crs_code"], "EPSG:4326")
        self.assertEqual(len(d["geotransform"]), 6)
        for got, want in zip(d["geotransform"], [-84.41375, CELL3, 0, 36.44625, 0, -CELL3]):
            self.assertAlmostEqual(got, want, places=10)
        # (a compound CRS of two coded parts as --srs takes it; none for a PROJ string)
        p = make_raster(self.path("coded.tif"), np.ones((4, 5)), (1000, 10, 0, 2000, 0, -10))
        for srs, code in (("EPSG:2263+6360", "EPSG:2263+6360"), ("EPSG:32611", "EPSG:32611"),
                          ("+proj=utm +zone=11 +datum=WGS84", None)):
            self.assertEqual(self.info(p, "--srs", srs)[0]["crs_code"], code, srs)
        self.assertEqual(self.info(p)[0]["geotransform"], [1000, 10, 0, 2000, 0, -10])
        for got, want in zip(d["bounds_lonlat"], [-84.41375, 36.1595833333, -84.0779166667,
                                                  36.44625]):
            self.assertAlmostEqual(got, want, places=8)
        self.assertAlmostEqual(d["centre_lonlat"][0], -84.2458333333, places=8)
        self.assertAlmostEqual(d["centre_lonlat"][1], 36.3029166667, places=8)
        self.assertEqual(d["elevation_range"], [236.0, 1076.0])
        self.assertEqual(d["nodata_count"], 0)
        # 3 arc-seconds at 36.30 N on WGS 84: N cos(lat) dlon and M dlat (closed forms).
        a, f = 6378137.0, 1 / 298.257223563
        e2 = f * (2 - f)
        phi = math.radians(d["centre_lonlat"][1])
        w = math.sqrt(1 - e2 * math.sin(phi) ** 2)
        self.assertAlmostEqual(d["cell_size_m"][0], a / w * math.cos(phi) * math.radians(CELL3),
                               places=4)
        self.assertAlmostEqual(d["cell_size_m"][1], a * (1 - e2) / w ** 3 * math.radians(CELL3),
                               places=4)

    def test_global_dem(self):
        # A lat/lon grid of all longitudes says its east and west edges join (the bake sees
        # across them); one column fewer, or the default DEM, does not.
        for columns, wraps in ((144, True), (143, False)):
            p = make_raster(self.path("globe%d.tif" % columns), np.ones((30, columns)),
                            (-180, 2.5, 0, 37.5, 0, -2.5), srs="EPSG:4326")
            d, _ = self.info(p)
            self.assertIs(d["wraps_around"], wraps)
            status, out, err = run("info", p)
            self.assertEqual(status, 0, err)
            self.assertEqual("all longitudes: the east and west edges join" in out, wraps, out)
        self.assertIs(self.info()[0]["wraps_around"], False)

    def test_grid_wider_than_the_earth(self):
        # A gridline-registered global grid (361 columns of 1 degree, rows on the poles) is
        # described, with the refusal bake and render give as a warning: info is where one
        # looks at the grid that message says to cut (info refused it until 2026-12-07).
        p = make_raster(self.path("gridline.tif"), np.ones((181, 361)),
                        (-180.5, 1, 0, 90.5, 0, -1), srs="EPSG:4326")
        status, out, err = run("info", "--json", p)
        self.assertEqual(status, 0, err)
        d = json.loads(out)
        self.assertEqual((d["size"], d["bounds_lonlat"], d["wraps_around"]),
                         ([361, 181], [-180.5, -90.5, 180.5, 90.5], False))
        self.assertEqual(err, "aperture: warning: the grid spans 361 degrees of longitude (361 "
                         "columns of 1 degrees), more than the 360 around the Earth: its first "
                         "and last columns are one meridian (a gridline-registered global "
                         "grid); drop the last column and the rows centred on a pole first "
                         "(gdal_translate -srcwin 0 1 360 179; with -of VRT it copies "
                         "nothing); bake and render refuse it\n")
        # beyond a pole by more than the rows centred on it, refused as any grid is (the
        # description skipped that check for a grid so wide, until review); by less than half
        # a cell too, where no row is centred on the pole (described until review: a row was
        # taken as centred on it when its centre was not beyond it)
        for name, columns, west, north in (("wide-polar", 40, -200, 120),
                                           ("wide-polar-near", 37, -185, 94)):
            p = make_raster(self.path(name + ".tif"), np.ones((10, columns)),
                            (west, 10, 0, north, 0, -10), srs="EPSG:4326")
            status, out, err = run("info", "--no-stats", p)
            self.assertEqual(status, 1, err)
            self.assertIn("aperture: error: the grid's north edge is at latitude %d, beyond the "
                          "north pole" % north, err)

    def test_cylindrical_grid_wider_than_the_earth(self):
        # Web Mercator and equirectangular grids are counted by their columns' longitude step
        # too (361 columns of one degree were described "from -180 to -179" and baked without
        # a word, until 2026-12-07): described, bounds beyond 180 as a lat/lon grid's, with
        # the refusal bake gives as a warning.
        e = 20037508.342789244
        c = e / 180
        for srs, rows, north, hint, bounds in (
                ("EPSG:3857", 20, 2e6, "drop the last column first (gdal_translate -srcwin 0 0 "
                 "360 20;", [-180.5, None, 180.5, None]),
                ("EPSG:4087", 181, 0.5 * e + 0.5 * c, "drop the last column and the rows "
                 "centred on a pole first (gdal_translate -srcwin 0 1 360 179;",
                 [-180.5, -90.5, 180.5, 90.5])):
            p = make_raster(self.path("wide%s.tif" % srs[5:]), np.ones((rows, 361)),
                            (-e - 0.5 * c, c, 0, north, 0, -c), srs=srs)
            status, out, err = run("info", "--json", "--no-stats", p)
            self.assertEqual(status, 0, err)
            d = json.loads(out)
            self.assertEqual((d["size"], d["wraps_around"]), ([361, rows], False))
            for got, want in zip(d["bounds_lonlat"], bounds):
                if want is not None:
                    self.assertAlmostEqual(got, want, places=9)
            self.assertIn("aperture: warning: the grid spans 361 degrees of longitude (361 "
                          "columns of 1 degrees), more than the 360 around the Earth: its "
                          "first and last columns are one meridian (a gridline-registered "
                          "global grid); " + hint, err)
            self.assert_error(hint, "bake", p, self.path("wide-bake.tif"))
            self.assertFalse(os.path.exists(self.path("wide-bake.tif")))
        # from 10 E: 10 to 371, as the same grid in lat/lon (turned about the grid's middle,
        # -350 to 11, until review), also with a central meridian and a false easting that put
        # x = 0 beyond the antimeridian; two columns of 200 degrees: 10 to 410 (10 to -310
        # from a whole column's step, until review)
        shifted = "+proj=merc +lon_0=150 +x_0=-5000000 +datum=WGS84 +units=m +type=crs"
        for srs, west, cell, columns in (("EPSG:3857", 10 * c, c, 361),
                                         ("EPSG:4326", 10, 1, 361),
                                         (shifted, -5e6 - 140 * c, c, 361),
                                         ("EPSG:3857", 10 * c, 200 * c, 2)):
            degree = 1 if srs == "EPSG:4326" else c  # (a degree of longitude, CRS units)
            p = make_raster(self.path("wide-east.tif"), np.ones((20, columns)),
                            (west, cell, 0, 20 * degree, 0, -degree), srs=srs)
            status, out, err = run("info", "--json", "--no-stats", p)
            self.assertEqual(status, 0, err)
            bounds = json.loads(out)["bounds_lonlat"]
            span = columns * cell / degree
            self.assertAlmostEqual(bounds[0], 10.0, places=9, msg=srs)
            self.assertAlmostEqual(bounds[2], 10.0 + span, places=9, msg=srs)

    def test_beyond_the_pole(self):
        # A lat/lon grid whose top rows lie beyond the north pole (a wrong origin) is described
        # by no bounds on the Earth: an error, as the bake's; one ending on the pole is fine.
        for north, error in ((90.2, "the grid's north edge is at latitude 90.2, beyond the "
                                    "north pole: a wrong origin, cell size or unit?"),
                             (90.0, None)):
            p = make_raster(self.path("polar%g.tif" % north), np.ones((20, 20)),
                            (10, 0.01, 0, north, 0, -0.01), srs="EPSG:4326")
            if error:
                self.assert_error(error, "info", p)
                self.assert_error("reaches latitude", "bake", p, self.path("polar.tif"))
            else:
                self.assertAlmostEqual(self.info(p)[0]["bounds_lonlat"][3], 90.0, places=9)

    def test_default_dem_text(self):
        status, out, _ = run("info")
        self.assertEqual(status, 0)
        self.assertIn("403 x 344 cells", out)
        self.assertIn("WGS 84 (geographic)", out)
        self.assertIn("74.85 m east x 92.47 m north", out)
        self.assertIn("west -84.413750, south 36.159583, east -84.077917, north 36.446250", out)
        self.assertIn("236.00 .. 1076.00 m", out)

    def test_projected_dem(self):
        # 30 m UTM 11N cells centred on the central meridian (117 W): ground cells are 30 / k0.
        rows = np.arange(20 * 21, dtype=float).reshape(20, 21)
        rows[3, 4] = -9999
        rows[0, 0] = -9999
        p = make_raster(self.path("utm.tif"), rows,
                        (500000 - 10.5 * 30, 30, 0, 4000000, 0, -30), nodata=-9999)
        d, _ = self.info(p)
        self.assertEqual(d["size"], [21, 20])
        self.assertEqual(d["crs"], "WGS 84 / UTM zone 11N")
        self.assertFalse(d["geographic"])
        self.assertEqual(d["cell_size"], [30.0, 30.0])
        self.assertAlmostEqual(d["cell_size_m"][0], 30 / 0.9996, places=4)
        self.assertAlmostEqual(d["cell_size_m"][1], 30 / 0.9996, places=4)
        self.assertAlmostEqual(d["centre_lonlat"][0], -117.0, places=9)
        west, south, east, north = d["bounds_lonlat"]
        self.assertAlmostEqual(-117.0 - west, east + 117.0, places=9)
        self.assertEqual(d["nodata_count"], 2)
        self.assertEqual(d["nodata_value"], -9999)
        self.assertEqual(d["elevation_range"], [1.0, 419.0])
        # JSON has no infinity: a nodata value of -inf is a string, as NaN's is (it was a
        # ValueError traceback)
        rows[rows == -9999] = -np.inf
        p = make_raster(self.path("inf.tif"), rows,
                        (500000 - 10.5 * 30, 30, 0, 4000000, 0, -30), nodata=-np.inf)
        d, _ = self.info(p)
        self.assertEqual((d["nodata_value"], d["nodata_count"]), ("-inf", 2))

    def test_formats(self):
        # The same terrain as Arc/Info ASCII grid (+ .prj), SRTM .hgt and DTED level 0.
        hgt = np.fromfunction(lambda r, c: 100 + r + 2 * c, (1201, 1201))
        p = make_raster(self.path("N36W085.hgt"), hgt,
                        (-85 - CELL3 / 2, CELL3, 0, 37 + CELL3 / 2, 0, -CELL3),
                        srs="EPSG:4326", driver="SRTMHGT")
        d, _ = self.info(p)
        self.assertEqual(d["driver"], "SRTMHGT")
        self.assertEqual(d["size"], [1201, 1201])
        self.assertAlmostEqual(d["bounds_lonlat"][0], -85 - CELL3 / 2, places=9)
        self.assertAlmostEqual(d["bounds_lonlat"][3], 37 + CELL3 / 2, places=9)
        # North-up: the top-left sample (first row, first column) is 100, the bottom-left 1300.
        self.assertEqual(d["elevation_range"], [100.0, 100.0 + 1200 + 2400])

        dt = 30.0 / 3600.0
        dted = np.fromfunction(lambda r, c: 50 + r + c, (121, 121))
        p = make_raster(self.path("w085_n36.dt0"), dted,
                        (-85 - dt / 2, dt, 0, 37 + dt / 2, 0, -dt), srs="EPSG:4326",
                        driver="DTED")
        d, _ = self.info(p)
        self.assertEqual(d["driver"], "DTED")
        self.assertEqual(d["size"], [121, 121])
        self.assertEqual(d["elevation_range"], [50.0, 290.0])

        asc = np.arange(12, dtype=float).reshape(3, 4)
        p = make_raster(self.path("grid.asc"), asc, (600000, 100, 0, 5200000, 0, -100),
                        srs="EPSG:32632", driver="AAIGrid")
        d, _ = self.info(p)
        self.assertEqual(d["driver"], "AAIGrid")
        self.assertEqual(d["crs"], "WGS 84 / UTM zone 32N")
        self.assertEqual(d["elevation_range"], [0.0, 11.0])

    def test_huge_elevations(self):
        # the range of cells beyond 1e38 (float32 up to 3.4e38) as they are: VTK 9.1's
        # GetRange clamps to +-1e38, and the range said 1e38 where no cell has it (and its
        # warning repeated it) until 2026-12-06
        for sign in (1, -1):
            rows = np.full((4, 5), sign * 2e38)
            rows[1, 2] = sign * 2.2e38
            p = make_raster(self.path("huge.tif"), rows, (500000, 30, 0, 4000000, 0, -30))
            d, err = self.info(p)
            ends = [float(np.float32(sign * 2e38)), float(np.float32(sign * 2.2e38))]
            self.assertEqual(d["elevation_range"], sorted(ends))
            self.assertIn("elevations range from %g to %g m" % tuple(sorted(ends)), err)

    def test_bands_windows_decimation(self):
        rows = np.arange(6 * 8, dtype=float).reshape(6, 8)
        p = make_raster(self.path("bands.tif"), rows, (500000, 30, 0, 4000000, 0, -30), bands=3)
        d, err = self.info(p)
        self.assertIn("has 3 bands; reading band 1 as elevation (choose one with --band)", err)
        self.assertEqual(len(err.strip().splitlines()), 1)
        self.assertEqual(d["elevation_range"], [0.0, 47.0])
        d, err = self.info(p, "--band", 3)
        self.assertEqual(err, "")
        self.assertEqual(d["elevation_range"], [2000.0, 2047.0])
        d, _ = self.info(p, "--band", 1, "--srcwin", 2, 1, 3, 4)
        self.assertEqual(d["size"], [3, 4])
        # the reader's complaint in the command line's words
        self.assert_error("--srcwin 6 1 3 4 is not inside the 8 x 6 raster",
                          "info", p, "--band", 1, "--srcwin", 6, 1, 3, 4)
        self.assertEqual(d["elevation_range"], [10.0, 36.0])
        # a size of 0 reaches the edge (rows 1..5, columns 2..4: 10 .. 44)
        d, _ = self.info(p, "--srcwin", 2, 1, 3, 0)
        self.assertEqual(d["size"], [3, 5])
        self.assertEqual(d["elevation_range"], [10.0, 44.0])
        d, _ = self.info(p, "--band", 1, "--decimate", 2)
        self.assertEqual(d["size"], [4, 3])
        self.assertEqual(d["cell_size"], [60.0, 60.0])
        # Block (0,0) = {0, 1, 8, 9} -> 4.5; block (3,2) = {38, 39, 46, 47} -> 42.5.
        self.assertEqual(d["elevation_range"], [4.5, 42.5])

    def test_srs_override(self):
        rows = np.ones((4, 4))
        p = make_raster(self.path("nocrs.tif"), rows, (500000, 30, 0, 4000000, 0, -30), srs=None)
        self.assert_error("has no coordinate reference system; give one with --srs EPSG:xxxx; "
                          "a site grid with no place on the Earth: --srs "
                          "'LOCAL_CS[\"grid\",UNIT[\"metre\",1]]'", "info", p)
        d, err = self.info(p, "--srs", "EPSG:32611")
        self.assertEqual(d["crs"], "WGS 84 / UTM zone 11N")
        self.assertEqual(err, "")
        # A wrong guess: a projected CRS given to a lat/lon grid (cells of 3 arc-seconds taken
        # for metres) makes a relief no terrain has, said as the filters say it; and heights
        # beyond the Earth's (an undeclared nodata value) likewise.
        ramp = np.add.outer(np.arange(4.0), np.arange(4.0)) * 50  # 0 .. 300 m
        g = make_raster(self.path("degrees.tif"), ramp, (-84.4, 1 / 1200, 0, 36.4, 0, -1 / 1200),
                        srs=None)
        d, err = self.info(g, "--srs", "EPSG:32611")
        self.assertTrue(err.startswith("aperture: warning: elevations range over 300 m on a "
                                       "grid of "), err)
        self.assertIn("steeper than any terrain: a CRS whose unit does not fit the grid's "
                      "coordinates (degrees taken for metres?), or heights not in metres? Sky "
                      "products and pictures made of them are meaningless", err)
        self.assertEqual(len(err.splitlines()), 1, err)
        _, err = self.info(g, "--srs", "EPSG:4326")
        self.assertEqual(err, "")
        pit = make_raster(self.path("pit.tif"), np.where(ramp > 100, ramp, -32768.0),
                          (500000, 30, 0, 4000000, 0, -30), srs="EPSG:32611")
        _, err = self.info(pit)
        self.assertIn("aperture: warning: elevations range from -32768 to 300 m, beyond any on "
                      "Earth", err)

    def test_elevation_unit(self):
        # A state-plane DEM in US survey feet whose band has no unit: its heights are read as
        # metres, with a warning in the options' words; --zfactor says what they are.
        rows = np.full((4, 5), 1000.0)
        p = make_raster(self.path("stateplane.tif"), rows, (1000000, 100, 0, 200000, 0, -100),
                        srs="EPSG:2263")
        d, err = self.info(p)
        self.assertEqual(err.strip(), (
            "aperture: warning: '%s' band 1 has no elevation unit and its CRS is in "
            "US survey foot; elevations are read as metres: if they are in feet, say so with "
            "--zfactor 0.3048006096 (US survey feet) or 0.3048 (feet); 1 keeps metres without "
            "this warning" % p))
        self.assertEqual(d["elevation_range"], [1000.0, 1000.0])
        self.assertEqual(d["elevation_unit_m"], 1.0)
        self.assertEqual(d["elevation_unit_source"], "none in the file: metres")
        us_foot = 1200.0 / 3937.0
        # (the unit names the reader knows for bands, one table: vtkApertureDEMReader)
        for z, metres in (("us-ft", us_foot), ("US-FT", us_foot), ("ft", 0.3048),
                          ("0.3048", 0.3048), ("1", 1.0), ("m", 1.0),
                          ("US survey foot", us_foot), ("feet", 0.3048), ("metre", 1.0),
                          ("cm", 0.01), ("centimetres", 0.01), ("dm", 0.1)):
            d, err = self.info(p, "--zfactor", z)
            self.assertEqual(err, "")
            self.assertEqual(d["elevation_unit_m"], metres)
            self.assertEqual(d["elevation_unit_source"], "--zfactor")
            # (float32 elevations: 1000 * metres rounded once)
            self.assertEqual(d["elevation_range"], [float(np.float32(1000.0 * metres))] * 2)
        status, out, _ = run("info", p, "--zfactor", "us-ft")
        self.assertIn("Elevation:  304.80 .. 304.80 m (unit: 0.3048006096 m, --zfactor)", out)
        # A band with a unit needs no option; --zfactor overrides it.
        m = make_raster(self.path("metres.tif"), rows, (500000, 30, 0, 4000000, 0, -30))
        ds = gdal.Open(m, gdal.GA_Update)
        ds.GetRasterBand(1).SetUnitType("ft")
        ds = None
        d, err = self.info(m)
        self.assertEqual(err, "")
        self.assertEqual(d["elevation_unit_source"], "the band's unit 'ft'")
        self.assertEqual(d["elevation_range"], [float(np.float32(304.8))] * 2)
        d, _ = self.info(m, "--zfactor", "m")
        self.assertEqual(d["elevation_range"], [1000.0, 1000.0])

    def test_bad_zfactor(self):
        # ("feet" is a unit's name the reader knows: accepted since 2026-12-05)
        for z in ("0", "-0.3048", "nan", "inf", "furlong", "", "1e308"):
            status, out, err = run("info", "--zfactor", z)
            self.assertEqual(status, 2, err)
            self.assertIn("argument --zfactor: must be a positive number of metres per "
                          "elevation unit up to 10000, or a unit: m, ft, us-ft, cm, dm, mm or "
                          "km (or their "
                          "names: metre, foot, US survey foot, centimetre, ...), not %r" % z,
                          err)
            self.assertEqual(out, "")


class TestBadInput(CommandLineTest):
    def test_missing_file(self):
        self.assert_error("does not exist", "info", self.path("nowhere.tif"))

    def test_empty_path(self):
        # an empty DEM argument (an unset variable in a script) is not the embedded DEM
        # (a usage error, as every other empty option is, since 2026-12-06)
        self.assert_usage_error("the DEM path is empty", "info", "")
        self.assert_usage_error("the DEM path is empty", "bake", "", self.path("out.tif"))
        self.assertFalse(os.path.exists(self.path("out.tif")))
        self.assert_usage_error("the DEM path is empty", "sun", "--dem", "", "--at",
                                "2026-06-21T12:00:00Z")

    def test_not_a_raster(self):
        p = self.path("readme.tif")
        with open(p, "w") as f:
            f.write("not a raster\n")
        self.assert_error("GDAL cannot open", "info", p)
        self.assertNotIn("OpenEXR", run("info", p)[2])

    def test_exr_given_as_dem(self):
        # The bake's own EXR given where a DEM goes (Debian's GDAL reads no EXR): the message
        # says what the file is and what reads it, instead of only "not a raster format".
        dem = make_raster(self.path("small.tif"), np.random.default_rng(2).random((20, 30)) * 50,
                          (500000, 30, 0, 4000000, 0, -30))
        exr = self.path("small.exr")
        status, _, err = run("bake", dem, self.path("small-out.tif"), "--exr", exr, "-q")
        self.assertEqual(status, 0, err)
        self.assert_error("GDAL cannot open '%s' as a raster: not a raster format GDAL "
                          "recognises (it is an OpenEXR file, which this GDAL does not read: "
                          "the products of 'aperture bake --exr' are read by "
                          "vtkApertureEXRReader; bake from the DEM or its GeoTIFF)" % exr,
                          "info", exr)

    def test_truncated_file(self):
        # A GeoTIFF cut in half (its header survives, its pixels do not).
        rows = np.random.default_rng(1).random((400, 400)) * 1000
        p = make_raster(self.path("cut.tif"), rows, (500000, 30, 0, 4000000, 0, -30))
        with open(p, "r+b") as f:
            f.truncate(os.path.getsize(p) // 2)
        self.assert_error("GDAL failed reading", "info", p)

    def test_damaged_samples(self):
        # A JPEG cut in half: GDAL fills its missing rows with grey and says so only in a
        # warning, which the reader passed over until 2026-12-07 (half the cells a flat 128 m
        # without a word); it is a warning of the command now, and the description is made.
        mem = gdal.GetDriverByName("MEM").Create("", 300, 200, 1, gdal.GDT_Byte)
        mem.SetGeoTransform((500000, 30, 0, 4000000, 0, -30))
        ref = osr.SpatialReference()
        ref.ImportFromEPSG(32611)
        mem.SetSpatialRef(ref)
        mem.GetRasterBand(1).WriteArray(
            np.random.default_rng(3).integers(0, 255, (200, 300)).astype(np.uint8))
        p = self.path("cut.jpg")
        gdal.GetDriverByName("JPEG").CreateCopy(p, mem).FlushCache()
        mem = None
        with open(p, "r+b") as f:
            f.truncate(os.path.getsize(p) // 2)
        status, out, err = run("info", p)
        self.assertEqual(status, 0, err)
        self.assertIn("Size:       300 x 200 cells", out)
        # (GDAL's own words vary with its version and libjpeg's)
        self.assertEqual(len(err.splitlines()), 1, err)
        self.assertTrue(err.startswith("aperture: warning: GDAL warned while reading '%s' band "
                                       "1: " % p), err)
        self.assertIn("Premature end of JPEG file", err)
        self.assertTrue(err.endswith(" (the elevations read may be damaged: a truncated or "
                                     "corrupt file?)\n"), err)

    def test_subdatasets(self):
        # GDAL's names of subdatasets, which are no file, are read (refused as missing files
        # until 2026-12-07): a GeoTIFF's second image, a netCDF file's variable; a container
        # of variables given by its file's name names them in its error.
        rows = np.arange(12.0).reshape(3, 4) * 10
        tif = make_raster(self.path("pages.tif"), rows, (500000, 30, 0, 4000000, 0, -30))
        status, out, err = run("info", "GTIFF_DIR:1:" + tif)
        self.assertEqual(status, 0, err)
        self.assertIn("File:       GTIFF_DIR:1:%s (GTiff, band 1 of 1)" % tif, out)
        self.assertIn("Size:       4 x 3 cells", out)
        missing = self.path("nothing.tif")
        self.assert_error("file 'NOSUCH:%s' does not exist" % missing, "info",
                          "NOSUCH:" + missing)
        # a file it names exists: GDAL's reason; a pipe it names: refused (GDAL's open of one
        # would wait for a writer)
        self.assert_error("GDAL cannot open 'GTIFF_DIR:5:%s' as a raster: " % tif, "info",
                          "GTIFF_DIR:5:" + tif)  # (GDAL's own words vary)
        for fifo in (self.path("pipe.tif"), self.path("a:pipe.tif")):  # (a colon in its path)
            os.mkfifo(fifo)
            self.assert_error("'GTIFF_DIR:1:%s' names a pipe ('%s'), not a file" % (fifo, fifo),
                              "info", "GTIFF_DIR:1:" + fifo)
        if gdal.GetDriverByName("netCDF") is None:
            self.skipTest("this GDAL has no netCDF driver")
        nc = self.path("cube.nc")
        ds = gdal.GetDriverByName("netCDF").Create(nc, 4, 3, 2, gdal.GDT_Float32)
        ds.SetGeoTransform((500000, 30, 0, 4000000, 0, -30))
        ref = osr.SpatialReference()
        ref.ImportFromEPSG(32611)
        ds.SetSpatialRef(ref)
        for b in (1, 2):
            ds.GetRasterBand(b).WriteArray(rows.astype(np.float32) + 1000 * b)
        ds = None
        self.assert_error("'%s' has no raster bands; it holds 2 subdatasets, each read by its "
                          "name: NETCDF:\"%s\":Band1, NETCDF:\"%s\":Band2" % (nc, nc, nc),
                          "info", nc)
        status, out, err = run("info", '--json', 'NETCDF:"%s":Band2' % nc)
        self.assertEqual(status, 0, err)
        description = json.loads(out)
        self.assertEqual(description["elevation_range"], [2000.0, 2110.0])

    def test_undeclared_minus_9999(self):
        # A margin of -9999, a common nodata value that the file does not declare, lies within
        # the Earth's heights, so that nothing named it (a 10 km cliff in the render); now a
        # warning does. Not where the file declares it, nor for a band with a scale.
        rows = np.full((200, 300), 250.0)  # (9 x 6 km: not steeper than terrain)
        rows[:, :3] = -9999.0
        gt = (500000, 30, 0, 4000000, 0, -30)
        plain = make_raster(self.path("margin.tif"), rows, gt)
        status, out, err = run("info", plain)
        self.assertEqual(status, 0, err)
        self.assertEqual(err, "aperture: warning: '%s' band 1 has cells of -9999, a common "
                         "nodata value the file does not declare: read as heights of -9999 "
                         "(declare it: gdal_edit.py -a_nodata -9999)\n" % plain)
        self.assertIn("Nodata:     0 cells", out)
        declared = make_raster(self.path("margin-declared.tif"), rows, gt, nodata=-9999.0)
        self.assertEqual(run("info", declared)[2], "")
        masked = self.path("margin-masked.tif")
        gdal.Translate(masked, plain)
        ds = gdal.Open(masked, gdal.GA_Update)
        ds.GetRasterBand(1).CreateMaskBand(gdal.GMF_PER_DATASET)
        ds.GetRasterBand(1).GetMaskBand().WriteArray(np.where(rows == -9999.0, 0, 255)
                                                     .astype(np.uint8))
        ds = None
        self.assertEqual(run("info", masked)[2], "")  # (a mask makes them nodata)
        ds = gdal.Open(plain, gdal.GA_Update)
        ds.GetRasterBand(1).SetScale(0.5)
        ds = None
        self.assertEqual(run("info", plain)[2], "")

    def test_undeclared_infinities(self):
        # Infinite cells that no nodata value declares are nodata, as the reader's header says,
        # and a warning says so (silent until 2026-12-07); not where the file declares them.
        rows = np.full((200, 300), 250.0)
        rows[5, 5], rows[6, 6] = np.inf, -np.inf
        gt = (500000, 30, 0, 4000000, 0, -30)
        plain = make_raster(self.path("infinite.tif"), rows, gt)
        status, out, err = run("info", plain)
        self.assertEqual(status, 0, err)
        self.assertEqual(err, "aperture: warning: '%s' band 1 has infinite cells (+inf or -inf), "
                         "which its nodata value does not declare: read as nodata\n" % plain)
        self.assertIn("Nodata:     2 cells", out)
        rows[5, 5] = -np.inf
        declared = make_raster(self.path("infinite-declared.tif"), rows, gt, nodata=-np.inf)
        status, out, err = run("info", declared)
        self.assertEqual((status, err), (0, ""))
        self.assertIn("Nodata:     2 cells (nodata value -inf)", out)
        # Finite samples beyond the float32 range (a Float64 band's -1.79e308, an undeclared
        # nodata value) are nodata as well, said too (silent until 2026-12-07, with info's
        # count of them beside the declared value): not where the file declares them.
        lowest = -1.7976931348623157e308
        for name, values, nodata, warned in (("huge", (1e300, lowest), None, True),
                                             ("huge-and-declared", (1e300, lowest), lowest, True),
                                             ("declared", (lowest, lowest), lowest, False)):
            path = self.path(name + ".tif")
            ds = gdal.GetDriverByName("GTiff").Create(path, 30, 20, 1, gdal.GDT_Float64)
            ds.SetGeoTransform(gt)
            ds.SetProjection("EPSG:32611")
            rows = np.full((20, 30), 250.0)
            rows[2, 2], rows[3, 3] = values
            ds.GetRasterBand(1).WriteArray(rows)
            if nodata is not None:
                ds.GetRasterBand(1).SetNoDataValue(nodata)
            ds = None
            status, out, err = run("info", path)
            self.assertEqual(status, 0, err)
            self.assertEqual(err, "aperture: warning: '%s' band 1 has cells beyond the range of "
                             "float32 elevations (3.4e38), which its nodata value does not "
                             "declare (-1.79e308, say: an undeclared nodata value?): read as "
                             "nodata\n" % path if warned else "", name)
            self.assertIn("Nodata:     2 cells", out)
        # once, also when read in strips that each have some (one per strip until 2026-12-07)
        path = self.path("huge-strips.tif")
        ds = gdal.GetDriverByName("GTiff").Create(path, 2000, 400, 1, gdal.GDT_Float64)
        ds.SetGeoTransform(gt)
        ds.SetProjection("EPSG:32611")
        rows = np.full((400, 2000), 250.0)
        rows[5, 5], rows[395, 5] = 1e300, np.inf
        rows[390, 6], rows[10, 6] = 1e300, -np.inf
        ds.GetRasterBand(1).WriteArray(rows)
        ds = None
        status, out, err = run("info", path, "--max-memory", 1)
        self.assertEqual(status, 0, err)
        self.assertEqual(err.count("cells beyond the range of float32"), 1, err)
        self.assertEqual(err.count("has infinite cells"), 1, err)
        self.assertEqual(len(err.splitlines()), 2, err)
        self.assertIn("Nodata:     4 cells", out)

    def test_missing_band(self):
        p = make_raster(self.path("one.tif"), np.ones((3, 3)), (500000, 30, 0, 4000000, 0, -30))
        self.assert_error("band 5 does not exist", "info", p, "--band", "5")
        for band in ("0", "-1"):
            self.assert_usage_error("--band must be 1 or more (%s given)" % band,
                                    "info", p, "--band", band)

    def test_complex_band(self):
        p = self.path("complex.tif")
        ds = gdal.GetDriverByName("GTiff").Create(p, 3, 3, 1, gdal.GDT_CFloat32)
        ds.SetGeoTransform((500000, 30, 0, 4000000, 0, -30))
        ds.SetProjection("EPSG:32611")
        ds.GetRasterBand(1).Fill(100.0, 5.0)
        ds = None
        self.assert_error("'%s' band 1 holds complex numbers (CFloat32), not elevations" % p,
                          "info", p)

    def test_too_small(self):
        p = make_raster(self.path("tiny.tif"), np.ones((1, 1)), (500000, 30, 0, 4000000, 0, -30))
        self.assert_error("at least 2 x 2", "info", p)

    def test_rotated(self):
        p = make_raster(self.path("rot.tif"), np.ones((3, 3)), (500000, 30, 5, 4000000, 5, -30))
        self.assert_error("rotated geotransform", "info", p)

    def test_infinite_origin(self):
        # named as the origin's problem (it said "an unsupported geotransform (pixel width 30,
        # pixel height -30)")
        p = make_raster(self.path("inf.tif"), np.ones((3, 3)), (np.inf, 30, 0, 4000000, 0, -30))
        self.assert_error("'%s' has a geotransform whose origin is not finite (inf, 4e+06); set "
                          "its corners first (gdal_edit.py -a_ullr)" % p, "info", p)

    def test_pixel_size_not_a_number(self):
        # named as the pixel size's problem: a NaN width was "a rotated geotransform (rotation
        # terms 0, 0)" until 2026-12-07, an infinite one "an origin that is not finite" (GDAL
        # computes an .asc file's origin from it)
        for name, gt, shown in (("nan.tif", (500000, np.nan, 0, 4000000, 0, -30), "nan, -30"),
                                ("inf.tif", (500000, 30, 0, 4000000, 0, -np.inf), "30, -inf")):
            p = make_raster(self.path(name), np.ones((3, 3)), gt)
            self.assert_error("'%s' has a geotransform whose pixel size is not a finite number "
                              "(width %s, height %s, rotation terms 0, 0); set its corners "
                              "first (gdal_edit.py -a_ullr)" % ((p,) + tuple(shown.split(", "))),
                              "info", p)
        asc = self.path("nan.asc")
        with open(asc, "w") as f:
            f.write("ncols 3\nnrows 3\nxllcorner 500000\nyllcorner 4000000\ncellsize inf\n"
                    "1 2 3\n4 5 6\n7 8 9\n")
        self.assert_error("has a geotransform whose pixel size is not a finite number",
                          "info", asc, "--srs", "EPSG:32611")

    def test_unreadable(self):
        # a DEM without read permission, or in a folder that may not be entered: said so (GDAL
        # called the first "not a raster format GDAL recognises", and the second did "not
        # exist", until 2026-12-06); the EXR reader too ("not an OpenEXR file")
        p = make_raster(self.path("locked.tif"), np.ones((3, 3)), (500000, 30, 0, 4000000, 0, -30))
        folder = self.path("closed")
        os.mkdir(folder)
        inside = make_raster(os.path.join(folder, "a.tif"), np.ones((3, 3)),
                             (500000, 30, 0, 4000000, 0, -30))
        exr = self.path("locked.exr")
        with open(exr, "wb") as f:
            f.write(b"\x76\x2f\x31\x01")
        for path in (p, exr):
            os.chmod(path, 0)
        os.chmod(folder, 0)
        try:
            for path in (p, inside):
                r = subprocess.run(unprivileged(self, path, "read") + [APERTURE, "info", path],
                                   capture_output=True, text=True, timeout=120)
                self.assertEqual((r.returncode, r.stderr), (
                    1, "aperture: error: cannot read '%s': Permission denied\n" % path))
            script = ("import aperture, sys\nr = aperture.vtkApertureEXRReader()\n"
                      "r.SetFileName(sys.argv[1])\nr.Update()")
            r = subprocess.run(unprivileged(self, exr, "read") +
                               [os.path.join(BUILD, "bin", "aperture-python"), "-c", script, exr],
                               capture_output=True, text=True, timeout=120)
            self.assertIn("cannot read '%s': Permission denied" % exr, r.stderr)
            self.assertNotIn("OpenEXR file", r.stderr)
        finally:
            os.chmod(folder, 0o755)

    def test_no_georeference(self):
        p = make_raster(self.path("plain.tif"), np.ones((3, 3)), None, srs=None)
        self.assert_error("'%s' has no georeference (no geotransform); give it a grid first "
                          "(gdal_translate -a_ullr ULX ULY LRX LRY, with -a_srs CRS, to a "
                          "GeoTIFF)" % p, "info", p)

    def test_gcps_only(self):
        gcps = [gdal.GCP(10.0 + 0.01 * x, 45.0 - 0.01 * y, 0.0, x, y)
                for x, y in ((0, 0), (3, 0), (0, 3), (3, 3))]
        p = make_raster(self.path("gcps.tif"), np.ones((3, 3)), None, srs="EPSG:4326", gcps=gcps)
        self.assert_error("ground control points; warp it to a grid first", "info", p)

    def test_zero_pixel_size(self):
        # A pixel size of 0: nothing to warp, corners to set. GTiff keeps such a geotransform
        # as it is when copied, but a file created with one holds a tie point without a
        # scale, which reads back as one ground control point.
        p = make_raster(self.path("zero.tif"), np.ones((3, 3)), (500000, 0, 0, 4000000, 0, 0))
        self.assert_error("'%s' has a pixel size of 0 in its geotransform (width 0, height 0); "
                          "set its corners first (gdal_edit.py -a_ullr)" % p, "info", p)
        p = self.path("zero-created.tif")
        ds = gdal.GetDriverByName("GTiff").Create(p, 3, 3, 1, gdal.GDT_Float32)
        ds.SetGeoTransform((500000, 0, 0, 4000000, 0, -30))
        ds.GetRasterBand(1).Fill(1.0)
        ds = None
        self.assert_error("'%s' is georeferenced only by 1 ground control point, too few to place "
                          "a grid; set its corners first (gdal_edit.py -a_ullr)" % p, "info", p)

    def test_local_crs(self):
        # A site grid: metric cells from its unit, no place on the Earth. info and bake work
        # (the bake in the grid's axes, on a sphere of the mean radius: TestSkyVisibility);
        # the sun for a time needs a place and says so (render with --sun-az/--sun-el:
        # TestCommandLineRender).
        p = make_raster(self.path("local.tif"), [[1.0, 2.0, 3.0], [2.0, 5.0, 4.0]],
                        (0, 10, 0, 20, 0, -10), srs='LOCAL_CS["mine grid",UNIT["foot",0.3048]]')
        d, _ = self.info(p)
        self.assertTrue(d["local"])
        self.assertFalse(d["geographic"])
        self.assertEqual(d["cell_size_m"], [3.048, 3.048])
        self.assertIsNone(d["bounds_lonlat"])
        self.assertIsNone(d["centre_lonlat"])
        status, out, err = run("info", p)
        self.assertEqual(status, 0, err)
        self.assertIn("CRS:        mine grid (local: a site grid)", out)
        self.assertIn("Bounds:     none in degrees (a local CRS has no geographic coordinates)",
                      out)
        baked = self.path("local-sky.tif")
        status, _, err = run("bake", p, baked, "-q", "--zfactor", "ft")
        self.assertEqual((status, err), (0, ""))
        ds = gdal.Open(baked)
        self.assertIn("clockwise from the grid's +y axis", ds.GetMetadataItem("SECTORS"))
        self.assertIn("mean Earth radius", ds.GetMetadataItem("EARTH_CURVATURE"))
        self.assertTrue(ds.GetSpatialRef().IsLocal())
        ds = None
        self.assert_error("the DEM %s is in a local CRS (a site grid, no place on the Earth); "
                          "give the site's place with --lat/--lon instead of --dem" % p, "sun",
                          "--dem", p,
                          "--zfactor", "ft", "--at", "2026-06-21T12:00Z")

    def test_geocentric_crs(self):
        # PROJ takes a geocentric CRS's x, y as X, Y at Z = 0 (the equator): refused by name.
        p = make_raster(self.path("geocentric.tif"), np.ones((3, 3)),
                        (4000000, 30, 0, 4000000, 0, -30), srs="EPSG:4978")
        for command in ("info", "bake"):
            with self.subTest(command=command):
                args = [p] if command == "info" else [p, self.path("out.tif")]
                self.assert_error("the CRS 'WGS 84' is geocentric (Earth-centred X, Y, Z), which "
                                  "no DEM grid is in", command, *args)

    def test_all_nodata(self):
        # described, as gdalinfo describes it (refused as an error until 2026-12-06); the
        # commands that compute from the elevations refuse it by name
        p = make_raster(self.path("empty.tif"), np.full((3, 4), -1.0),
                        (500000, 30, 0, 4000000, 0, -30), nodata=-1)
        d, err = self.info(p)
        self.assertEqual((d["size"], d["elevation_range"], d["nodata_count"], d["nodata_value"],
                          err), ([4, 3], None, 12, -1.0, ""))
        status, out, err = run("info", p)
        self.assertEqual((status, err), (0, ""))
        self.assertIn("\nElevation:  none: every cell is nodata (unit: 1 m, none in the file: "
                      "metres)\nNodata:     12 cells, all (nodata value -1.0)", out)
        self.assert_error("every cell of '%s' band 1 is nodata" % p, "bake", p,
                          self.path("empty-sky.tif"))

    def huge_vrt(self, name, size):
        """A VRT of size x size cells of 1 m in UTM 11N, nodata -1, whose top-left 3 x 3 cells
        come from a file (1, 2, 3 in the top row, 4 in the others; a NaN) and the rest is
        nodata; nothing of it is on disk but those 9 cells."""
        small = make_raster(self.path(name + "-source.tif"),
                            [[1, 2, 3], [4, float("nan"), 4], [4, 4, 4]],
                            (500000, 1, 0, 4000000, 0, -1))
        vrt = self.path(name + ".vrt")
        with open(vrt, "w") as f:
            f.write('<VRTDataset rasterXSize="%d" rasterYSize="%d">\n'
                    '  <SRS>EPSG:32611</SRS>\n'
                    '  <GeoTransform>500000, 1, 0, 4000000, 0, -1</GeoTransform>\n'
                    '  <VRTRasterBand dataType="Float32" band="1">\n'
                    '    <NoDataValue>-1</NoDataValue><SimpleSource>\n'
                    '    <SourceFilename relativeToVRT="0">%s</SourceFilename>\n'
                    '    <SourceBand>1</SourceBand></SimpleSource></VRTRasterBand>\n'
                    '</VRTDataset>\n' % (size, size, small))
        return vrt

    def test_larger_than_memory(self):
        # A DEM of 10^12 cells (3.6 TiB as float32) is described from its header at once with
        # --no-stats (before: refused, as info read every cell at once), its statistics null.
        vrt = self.huge_vrt("huge", 1000000)
        d, err = self.info(vrt, "--no-stats")
        self.assertEqual(err, "")
        self.assertEqual(d["size"], [1000000, 1000000])
        self.assertEqual(d["cell_size"], [1.0, 1.0])
        self.assertEqual((d["elevation_range"], d["nodata_count"], d["nodata_value"]),
                         (None, None, -1.0))
        status, out, err = run("info", vrt, "--no-stats")
        self.assertEqual((status, err), (0, ""))
        self.assertIn("1000000 x 1000000 cells", out)
        self.assertIn("Elevation:  not read (--no-stats) (unit: 1 m, none in the file: metres)",
                      out)
        self.assertIn("Nodata:     not counted (--no-stats) (nodata value -1.0)", out)

    def test_statistics_in_strips(self):
        # Without --no-stats the elevations are read in strips of rows (256 MiB, or
        # --max-memory): past 1 GiB with a note naming the way out. 16500^2 cells (1.01 GiB):
        # the range of the 8 cells with data and the count of the rest, read in 5 strips.
        vrt = self.huge_vrt("large", 16500)
        d, err = self.info(vrt)
        self.assertEqual(err, "aperture: note: reading the elevations of all 16500 x 16500 "
                              "cells (1.014 GiB as float32) for their range and nodata count, "
                              "in strips; --no-stats describes the DEM without reading them\n")
        self.assertEqual((d["elevation_range"], d["nodata_count"]), ([1.0, 4.0], 16500 ** 2 - 8))
        # Strips of one row up to the whole DEM give the same facts, for cells with data in
        # some strips and none in others (the nodata rows at the top, and in the middle).
        # --max-memory holds a strip and a block of the file (GDAL reads a block whole): here
        # blocks of one row (1200 bytes), as the strips.
        rows = np.full((9, 300), -9999.0)
        rows[4, 7], rows[4, 8], rows[6, 299], rows[8, 0] = 17.5, -3.25, 12.0, float("nan")
        one_row = ["BLOCKYSIZE=1"]
        p = make_raster(self.path("strips.tif"), rows, (500000, 30, 0, 4000000, 0, -30),
                        nodata=-9999, options=one_row)
        whole, err = self.info(p)
        self.assertEqual(err, "")
        self.assertEqual((whole["elevation_range"], whole["nodata_count"]),
                         ([-3.25, 17.5], 9 * 300 - 3))
        for limit in ("2.4K", "3.6K", "6K", "100K"):  # (a block, then 1, 2, 4 rows, all)
            with self.subTest(limit=limit):
                d, err = self.info(p, "--max-memory", limit)
                self.assertEqual((d, err), (whole, ""))
        # a row beyond --max-memory: refused by name
        self.assert_error("reading 300 x 1 cells of '%s' needs 1.172 KiB as float32, more than "
                          "--max-memory 1.000 KiB" % p, "info", p, "--max-memory", "1K")
        # every cell nodata, read at once or in strips: described so
        empty = make_raster(self.path("strips-empty.tif"), np.full((9, 300), -9999.0),
                            (500000, 30, 0, 4000000, 0, -30), nodata=-9999, options=one_row)
        for limit in ([], ["--max-memory", "2.4K"]):
            d, err = self.info(empty, *limit)
            self.assertEqual((d["elevation_range"], d["nodata_count"], err), (None, 2700, ""))
        # a window of nodata in a file with data: the window's, read at once or in strips
        coast = np.full((9, 300), 12.5)
        coast[:, :100] = -9999.0
        coast_path = make_raster(self.path("strips-coast.tif"), coast,
                                 (500000, 30, 0, 4000000, 0, -30), nodata=-9999,
                                 options=one_row)
        for limit in ([], ["--max-memory", "1500"]):  # (a block, and strips of 7 rows)
            d, err = self.info(coast_path, "--srcwin", 0, 0, 10, 9, *limit)
            self.assertEqual((d["size"], d["elevation_range"], d["nodata_count"], err),
                             ([10, 9], None, 90, ""))
        d, _ = self.info(coast_path, "--srcwin", 95, 0, 10, 9)
        self.assertEqual((d["elevation_range"], d["nodata_count"]), ([12.5, 12.5], 45))
        # (a command that needs a height refuses such a window by name, in the command line's
        # words; until 2026-12-06 the message said every cell of the file was nodata)
        self.assert_error("every cell of --srcwin 0 0 10 9 of '%s' band 1 is nodata"
                          % coast_path, "sun", "--dem", coast_path, "--srcwin", 0, 0, 10, 9,
                          "--at", "2026-06-21T12:00Z")

    def test_progress_on_a_terminal(self):
        # GDAL's progress line on stderr, when it is a terminal and the DEM is read in more
        # than one strip (as gdalinfo -stats); no note below 1 GiB.
        from terminal import run_with_terminal_stderr
        rows = np.arange(40 * 300, dtype=float).reshape(40, 300) / 2  # (heights of the Earth)
        # (blocks of a row, 1200 bytes: --max-memory holds one and strips of 2 rows)
        p = make_raster(self.path("progress.tif"), rows, (500000, 30, 0, 4000000, 0, -30),
                        options=["BLOCKYSIZE=1"])
        # -q silences it, as gdaldem's (added 2026-12-06; the description is printed all the
        # same)
        for limit, expected in ((["--max-memory", "3.6K"],
                                 "0...10...20...30...40...50...60...70...80...90...100 - "
                                 "done.\r\n"), ([], ""), (["--max-memory", "3.6K", "-q"], "")):
            r, seen = run_with_terminal_stderr([APERTURE, "info", "--json", p] + limit,
                                               timeout=120)
            self.assertEqual(r.returncode, 0)
            self.assertEqual(json.loads(r.stdout)["elevation_range"], [0.0, 5999.5])
            self.assertEqual(seen.decode(), expected)

    def test_bad_options(self):
        self.assert_usage_error("--decimate must be 1 or more", "info", "--decimate", "0")
        # messages of the reader and the light in the command line's words (they named
        # SubWindow and Turbidity, properties, until 2026-12-06)
        # (the steps that made the grid too small in the options' words, only those given:
        # until 2026-12-06 all three for any)
        self.assert_error("gives a 0 x 0 grid (after --decimate); at least 2 x 2", "info",
                          "--decimate", "1000")
        p = make_raster(self.path("row.tif"), np.ones((1, 5)), (500000, 30, 0, 4000000, 0, -30))
        self.assert_error("'%s' is a 5 x 1 raster; at least 2 x 2 cells are needed" % p, "info",
                          p)
        p = make_raster(self.path("small.tif"), np.ones((4, 4)), (500000, 30, 0, 4000000, 0, -30))
        self.assert_error("gives a 1 x 2 grid (after --srcwin and --decimate)", "info", p,
                          "--srcwin", "0", "0", "1", "4", "--decimate", "2")
        sun = ("sun", "--lat", "40", "--lon", "0", "--at", "2026-06-21T12:00Z")
        # (the light's ranges are options' ranges: usage errors, as the command's own checks)
        self.assert_usage_error("argument --turbidity: 11 is outside 2..10", *sun,
                                "--turbidity", "11")
        self.assert_usage_error("argument --linke-turbidity: 9 is outside 1..8", *sun,
                                "--linke-turbidity", "9")
        # -1, the reader's "none", was taken silently as full resolution (until 2026-12-06)
        for level in ("-1", "-2"):
            self.assert_usage_error("--overview must be 0 or more (%s given)" % level, "info",
                                    "--overview", level)
        # (checked at parsing: a usage error, as an unknown --tz is)
        self.assert_usage_error("argument --srs: GDAL cannot parse the CRS 'EPSG:999999999'",
                                "info", "--srs", "EPSG:999999999")

    def test_render_without_display(self):
        env = dict(os.environ)
        env.pop("DISPLAY", None)
        self.assert_error("needs an X display", "render", "-o", self.path("x.png"), env=env)
        # the options' own mistakes first, as usage errors (they were hidden behind this one)
        for args, expected in ((("--multisamples", "99"), "--multisamples must be within"),
                               (("--exposure", "99"), "--exposure must be within -30..30"),
                               (("--at", "bogus"), "cannot read the time 'bogus'"),
                               (("--sun-el", "100"), "--sun-el must be within [-90, 90]")):
            self.assert_usage_error(expected, "render", "-o", self.path("x.png"), *args,
                                    env=env)
        # a DISPLAY no server answers (a stale ssh one): VTK aborted the process (status -6)
        # with its message silenced; now named first (no X server runs on :4242 here)
        env["DISPLAY"] = ":4242"
        self.assert_error("cannot connect to the X display ':4242' (DISPLAY): no X server "
                          "answers there; run under xvfb-run -a", "render", "-o",
                          self.path("x.png"), env=env)

    def test_render_does_not_overwrite(self):
        # checked before anything is read or rendered, so no display is needed
        env = dict(os.environ)
        env.pop("DISPLAY", None)
        png = self.path("same.png")
        self.assert_error("--exr %s is the same file as --output" % png,
                          "render", "-o", png, "--exr", png, env=env)
        dem = self.path("keep.tif")
        make_raster(dem, [[1.0, 2.0], [3.0, 4.0]], (500000, 30, 0, 4000000, 0, -30))
        with open(dem, "rb") as f:
            before = f.read()
        self.assert_error("--output %s is the same file as the DEM" % dem,
                          "render", dem, "-o", dem, env=env)
        with open(dem, "rb") as f:
            self.assertEqual(f.read(), before)
        self.assertFalse(os.path.exists(png))
        missing = self.path("no-such-folder")
        self.assert_error("the output folder %s does not exist" % missing,
                          "render", "-o", png, "--exr", os.path.join(missing, "x.exr"), env=env)


if __name__ == "__main__":
    if not os.path.exists(APERTURE):
        print("skipped: %s not built" % APERTURE)
        sys.exit(125)
    sys.exit(0 if unittest.main(exit=False).result.wasSuccessful() else 1)
