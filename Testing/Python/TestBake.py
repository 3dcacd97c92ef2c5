# SPDX-License-Identifier: BSD-3-Clause
"""`aperture bake` as a user runs it: GeoTIFF bands named after the products (angles in
degrees, BentNormal_E/N/U, HorizonAngles per azimuth), the DEM's georeference, units,
definitions and provenance in the metadata, the EXR with the same products, results that do
not depend on --threads, the products carried onto the terrain mesh, and one-line errors."""
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import unittest

import numpy as np
from osgeo import gdal, osr

from privileges import unprivileged
from rasters import make_dem
from usage import usage_error

gdal.UseExceptions()
BUILD = os.environ.get("APERTURE_BUILD_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
APERTURE = os.path.join(BUILD, "bin", "aperture")
SOURCE = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def run(*args):
    p = subprocess.run([APERTURE] + [str(a) for a in args], capture_output=True, text=True,
                       timeout=300)
    return p.returncode, p.stdout, p.stderr


def bands(path):
    """{description: array (north row first)} and the dataset's metadata."""
    ds = gdal.Open(path)
    out = {}
    for b in range(1, ds.RasterCount + 1):
        band = ds.GetRasterBand(b)
        meta = band.GetMetadata()
        # (GDAL's band unit, which gdalinfo and QGIS show, the UNITS item but for ratios)
        assert band.GetUnitType() == ("" if meta.get("UNITS") == "1" else meta.get("UNITS", "")), (
            path, band.GetDescription(), band.GetUnitType())
        out[band.GetDescription()] = (band.ReadAsArray().astype(np.float64), meta)
    meta = ds.GetMetadata()
    gt = ds.GetGeoTransform()
    srs = ds.GetSpatialRef().ExportToWkt() if ds.GetSpatialRef() else None
    ds = None
    return out, meta, gt, srs


def zeros_vrt(path, n, cell=30):
    """n x n float32 cells of `cell` m in UTM 11N, no sources: zeros, nothing on disk."""
    ds = gdal.GetDriverByName("VRT").Create(path, n, n, 1, gdal.GDT_Float32)
    ds.SetGeoTransform((500000, cell, 0, 4000000, 0, -cell))
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(32611)
    ds.SetSpatialRef(srs)
    ds = None
    return path


def usable_memory():
    """The memory a bake plans with, bytes (the machine's physical memory, or the process's
    control group's limit less 128 MiB where lower), and what its messages call it ("of memory
    ...")."""
    import aperture
    sky = aperture.vtkApertureSkyVisibility  # (test_ap_memory and TestSkyVisibility test these)
    return sky.GetUsableMemory(), sky.GetUsableMemoryOwner()


def human_bytes(n):
    """n bytes as the filters print them: 3 decimals of the largest unit up to TiB."""
    units = ("bytes", "KiB", "MiB", "GiB", "TiB")
    k = max([0] + [k for k in range(5) if n >= 1024 ** k])
    return "%.3f %s" % (n / 1024.0 ** k, units[k])


def rough_dem(path, shape, seed, hole=None):
    """Rough terrain (a random walk's cumulative sums) of `shape` in UTM 11N, 30 m cells, with
    nodata in the rows and columns of `hole` (a pair of slices); returns path."""
    rng = np.random.default_rng(seed)
    z = np.cumsum(np.cumsum(rng.normal(0, 1, shape), 0), 1).astype(np.float32)
    if hole:
        z[hole] = -9999
    make_dem(path, z, (500000, 30, 0, 4000000, 0, -30), 32611)
    return path


def elevation_digest(path, rows=slice(None), columns=slice(None)):
    """BLAKE2b-128 (hex) of the 32-bit float elevations of band 1 of the DEM at `path` (its
    nodata as NaN) in `rows` and `columns` of the file (north first), as bakes record them in
    SOURCE_ELEVATION_DIGEST (the README, 'aperture bake'): read by GDAL, not by the reader."""
    import hashlib
    ds = gdal.Open(path)
    band = ds.GetRasterBand(1)
    z = band.ReadAsArray().astype("<f4")[rows, columns]
    if band.GetNoDataValue() is not None:
        z[z == np.float32(band.GetNoDataValue())] = np.nan
    return hashlib.blake2b(np.ascontiguousarray(z).tobytes(), digest_size=16).hexdigest()


def cpu_seconds(pid):
    """The CPU time of process `pid` so far: utime + stime of every thread, /proc/PID/stat."""
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def signals_at_default():
    """For preexec_fn: SIGINT, SIGTERM and SIGHUP at their defaults in the child, whatever this
    test inherited (a background job ignores SIGINT, nohup SIGHUP, and the command keeps that)."""
    import signal
    for number in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
        signal.signal(number, signal.SIG_DFL)


class TestBake(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="aperture-bake-")
        # A V-valley (floor north-south) in UTM, 30 m cells, sides at 30 degrees: the floor's
        # SkyViewFactor is 1 - 2 alpha / pi and DiffuseSkyFactor cos(alpha) (ALGORITHMS.md 2.4).
        x = (np.arange(81) - 40) * 30.0
        z = np.tile(np.tan(math.radians(30)) * np.abs(x), (60, 1)).astype(np.float32)
        z[5, 5] = -9999
        cls.dem = os.path.join(cls.tmp, "valley.tif")
        make_dem(cls.dem, z, (500000 - 40 * 30 - 15, 30, 0, 4000000, 0, -30), 32611)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def path(self, name):
        return os.path.join(self.tmp, name)

    def bake_on_tmpfs(self, folder, mount_options, *args):
        """`aperture bake *args` with a tmpfs (`mount_options`, e.g. "size=256k") on `folder` in
        a mount namespace of its own; skips the test where none can be mounted (needs root and
        unshare). The process; its stdout ends with the folder's listing before the tmpfs goes
        ("left: ...")."""
        if not shutil.which("unshare"):
            self.skipTest("no unshare (util-linux)")
        script = ('mount -t tmpfs -o "$2" tmpfs "$1" || exit 99; d="$1"; shift 2; "$@"; s=$?; '
                  'echo "left: $(ls -A "$d")"; exit $s')
        p = subprocess.run(["unshare", "-m", "sh", "-c", script, "sh", folder, mount_options,
                            APERTURE, "bake", *args], capture_output=True, text=True,
                           timeout=300)
        if p.returncode == 99 or "left:" not in p.stdout:
            self.skipTest("no tmpfs of our own here: %s" % p.stderr.strip())
        return p

    def test_bands_units_metadata(self):
        out, exr = self.path("all.tif"), self.path("all.exr")
        status, stdout, err = run("bake", self.dem, out, "--products", "all", "--directions",
                                  "360", "--exr", exr, "--no-curvature")
        self.assertEqual(status, 0, err)
        self.assertIn("wrote", stdout)
        b, meta, gt, srs = bands(out)
        names = list(b)
        self.assertEqual(names[:8], ["VisibleSolidAngle", "ApertureRadius", "BentNormal_E",
                                     "BentNormal_N", "BentNormal_U", "SkyViewFactor",
                                     "DiffuseSkyFactor", "PositiveOpenness"])
        self.assertEqual(names[8], "EdgeTruncated")
        self.assertEqual(names[9], "HorizonAngles_az000.00")
        self.assertEqual(names[9 + 90], "HorizonAngles_az090.00")
        self.assertEqual(len(names), 9 + 360)
        # the valley floor, mid-way: closed forms (360 sectors; the two along-axis sectors end
        # at the DEM's north and south edges)
        svf = b["SkyViewFactor"][0][30, 40]
        self.assertAlmostEqual(svf, 1 - 2 * math.radians(30) / math.pi, delta=3e-3)
        self.assertAlmostEqual(b["DiffuseSkyFactor"][0][30, 40], math.cos(math.radians(30)),
                               delta=1e-4)
        # angles in degrees: the floor's horizon east (90 deg) is the side's slope. The DEM is
        # drawn in UTM grid metres, but ground distances are 1/k0 = 1/0.9996 longer near the
        # central meridian, so the side rises at atan(0.9996 tan 30) = 29.990 deg on the ground.
        self.assertAlmostEqual(b["HorizonAngles_az090.00"][0][30, 40],
                               math.degrees(math.atan(0.9996 * math.tan(math.radians(30)))),
                               delta=1e-3)
        self.assertAlmostEqual(b["ApertureRadius"][0][30, 40],
                               math.degrees(math.acos(2 * math.radians(30) / math.pi)), delta=0.1)
        self.assertEqual(b["ApertureRadius"][1]["UNITS"], "degree")
        self.assertEqual(b["VisibleSolidAngle"][1]["UNITS"], "sr")
        self.assertIn("Zaksek", b["SkyViewFactor"][1]["DEFINITION"])
        self.assertIn("Dozier", b["DiffuseSkyFactor"][1]["DEFINITION"])
        self.assertTrue(np.isnan(b["SkyViewFactor"][0][5, 5]))  # nodata stays nodata
        self.assertTrue(np.isnan(b["EdgeTruncated"][0][5, 5]))
        for key, value in (("DIRECTIONS", "360"), ("MAX_DISTANCE_M", "unlimited"),
                           ("EARTH_CURVATURE", "off"), ("ANGLE_UNIT", "degree")):
            self.assertEqual(meta[key], value)
        self.assertIn("Timonen", meta["ALGORITHM"])
        self.assertIn("on other projected DEMs each cell's distances at its own ground scale "
                      "and its sectors weighted by their share of the ground's directions",
                      meta["ALGORITHM"])
        # the kernel's march_columns, far_march_columns and automatic near fields (documented
        # defaults 64, 1024, 32 and 8), read from it, not restated
        self.assertIn("at most 64 columns", meta["ALGORITHM"])
        self.assertIn("at most 1024 columns, every cell's ray sampled", meta["ALGORITHM"])
        self.assertIn("for the first 32 (swept sectors) or 8 (far-marched sectors) columns",
                      meta["ALGORITHM"])
        # the help states them in words (the parser is built before the VTK modules load): it
        # must say the same
        status, out, err = run("bake", "--help")
        self.assertEqual(status, 0, err)
        self.assertIn("up to 64 cells", " ".join(out.split()))
        self.assertIn("up to 1024 cells", " ".join(out.split()))
        self.assertIn("(default 0: 32 where the horizon sweep runs, 8 where rays are sampled",
                      " ".join(out.split()))
        self.assertTrue(meta["APERTURE_VERSION"])
        # what was read of the DEM: band 1 of the whole grid
        self.assertEqual(meta["SOURCE_BAND"], "1")
        for key in ("SOURCE_WINDOW", "SOURCE_OVERVIEW", "SOURCE_DECIMATION",
                    "SOURCE_CRS_OVERRIDE"):
            self.assertNotIn(key, meta)
        # same georeference as the DEM
        _, _, gt_dem, srs_dem = bands(self.dem)
        self.assertEqual(gt, gt_dem)
        a, b_ = osr.SpatialReference(), osr.SpatialReference()
        a.ImportFromWkt(srs)
        b_.ImportFromWkt(srs_dem)
        self.assertTrue(a.IsSame(b_))
        # the EXR: the same products, read back with Aperture's own reader
        import aperture
        from vtkmodules.util.numpy_support import vtk_to_numpy
        r = aperture.vtkApertureEXRReader()
        r.SetFileName(exr)
        r.Update()
        pd = r.GetOutput().GetPointData()
        svf_exr = vtk_to_numpy(pd.GetArray("SkyViewFactor")).reshape(60, 81)
        np.testing.assert_array_equal(np.flipud(svf_exr), b["SkyViewFactor"][0].astype(np.float32))
        self.assertEqual(pd.GetArray("BentNormal").GetNumberOfComponents(), 3)
        # HorizonAngles: one layer of 360 channels (HorizonAngles.az090_00: a '.' inside the
        # azimuth would make OpenEXR tools see a layer per sector), read back as one array
        horizons = pd.GetArray("HorizonAngles")
        self.assertEqual(horizons.GetNumberOfComponents(), 360)
        self.assertEqual(horizons.GetComponentName(90), "az090_00")
        np.testing.assert_array_equal(
            np.flipud(vtk_to_numpy(horizons)[:, 90].reshape(60, 81)),
            b["HorizonAngles_az090.00"][0].astype(np.float32))
        self.assertEqual(r.GetMetadataValue("aperture:directions"), "360")
        # each channel's unit and definition, the same as the GeoTIFF band's (HorizonAngles
        # once for its 360 bands)
        for name, band in (("SkyViewFactor", "SkyViewFactor"), ("BentNormal", "BentNormal_E"),
                           ("DiffuseSkyFactor", "DiffuseSkyFactor"),
                           ("HorizonAngles", "HorizonAngles_az090.00")):
            self.assertEqual(r.GetMetadataValue("aperture:unit:" + name), b[band][1]["UNITS"])
            self.assertEqual(r.GetMetadataValue("aperture:definition:" + name),
                             b[band][1]["DEFINITION"])

    def test_exr_half(self):
        # --exr-type half: 16-bit channels (as exrheader and OpenEXR's own decoder, through the
        # reader, see them), each value the GeoTIFF's float rounded to 11 significant bits
        # (within 2^-11 of it, relative; 2^-25 near zero, half's subnormals; NaN on the nodata
        # cell), the file smaller than the float one; --exr-type without --exr is an error.
        import aperture
        from vtkmodules.util.numpy_support import vtk_to_numpy
        out = self.path("half.tif")
        sizes = {}
        for kind in ("float", "half"):
            exr = self.path("%s.exr" % kind)
            status, _, err = run("bake", self.dem, out, "-d", "8", "--exr", exr,
                                 "--exr-type", kind, "--products",
                                 "SkyViewFactor,BentNormal,PositiveOpenness")
            self.assertEqual(status, 0, err)
            sizes[kind] = os.path.getsize(exr)
        b, _, _, _ = bands(out)
        r = aperture.vtkApertureEXRReader()
        r.SetFileName(self.path("half.exr"))
        r.Update()
        pd = r.GetOutput().GetPointData()
        for name, band, component in (("SkyViewFactor", "SkyViewFactor", None),
                                      ("BentNormal", "BentNormal_U", 2),
                                      ("PositiveOpenness", "PositiveOpenness", None)):
            got = vtk_to_numpy(pd.GetArray(name)).astype(np.float64)
            got = np.flipud((got[:, component] if component is not None else got).reshape(60, 81))
            want = b[band][0]
            self.assertTrue(np.array_equal(np.isnan(got), np.isnan(want)), name)
            self.assertTrue(np.isnan(want[5, 5]), name)  # (the DEM's nodata cell)
            ok = ~np.isnan(want)
            error = np.abs(got[ok] - want[ok])
            self.assertTrue(np.all(error <= np.abs(want[ok]) * 2.0 ** -11 + 2.0 ** -25), name)
            self.assertGreater(error.max(), 0.0, name)  # (rounded: not the float file)
        self.assertLess(sizes["half"], 0.7 * sizes["float"])
        if shutil.which("exrheader"):
            header = subprocess.run(["exrheader", self.path("half.exr")], capture_output=True,
                                    text=True).stdout
            self.assertIn("SkyViewFactor, 16-bit floating-point", header)
        self.assertEqual(usage_error(self, "bake", run("bake", self.dem, out, "--exr-type",
                                                       "half")),
                         "aperture bake: error: --exr-type half needs --exr OUT.exr\n")

    def test_read_provenance(self):
        # a product of a window, a decimated grid or an overridden CRS records what was read
        out = self.path("window.tif")
        status, _, err = run("bake", self.dem, out, "--products", "SkyViewFactor", "-d", "8",
                             "--radius", "600", "--srcwin", 4, 6, 60, 40, "--decimate", 2,
                             "--srs", "EPSG:32611", "--band", 1)
        self.assertEqual(status, 0, err)
        b, meta, gt, _ = bands(out)
        self.assertEqual(b["SkyViewFactor"][0].shape, (20, 30))
        self.assertEqual(gt[1], 60.0)
        self.assertEqual(meta["SOURCE_BAND"], "1")
        self.assertEqual(meta["SOURCE_WINDOW"],
                         "4 6 60 40 (xoff yoff xsize ysize; its horizons see the DEM around it)")
        self.assertEqual(meta["SOURCE_DECIMATION"], "2 x 2 blocks averaged")
        self.assertEqual(meta["SOURCE_CRS_OVERRIDE"], "EPSG:32611")
        self.assertNotIn("SOURCE_OVERVIEW", meta)
        self.assertEqual(meta["SOURCE_ELEVATION_UNIT"], "1 m (none in the file: metres)")
        # a size of 0 (to the edge) is recorded as the cells it reached (0 until 2026-12-07)
        status, _, err = run("bake", self.dem, out, "--products", "SkyViewFactor", "-d", "8",
                             "--radius", "300", "--srcwin", 4, 6, 0, 0)
        self.assertEqual(status, 0, err)
        b, meta, _, _ = bands(out)
        self.assertEqual(b["SkyViewFactor"][0].shape, (54, 77))  # (of 60 x 81)
        self.assertEqual(meta["SOURCE_WINDOW"],
                         "4 6 77 54 (xoff yoff xsize ysize; its horizons see the DEM around it)")

    def test_elevation_in_feet(self):
        # The class's valley with its heights in feet and no unit said: --zfactor ft bakes the
        # valley (the floor's SkyViewFactor 1 - 2 alpha / pi, alpha = 30 degrees, as the metre
        # DEM's); without it the sides rise at atan(tan 30 / 0.3048) = 62 degrees.
        ds = gdal.Open(self.dem)
        z, gt = ds.GetRasterBand(1).ReadAsArray(), ds.GetGeoTransform()
        ds = None
        feet = np.where(z == -9999, -9999, z / 0.3048).astype(np.float32)
        dem = self.path("valley-feet.tif")
        make_dem(dem, feet, gt, 32611)
        svf = {}
        for name, options in (("metres", (self.dem,)), ("zfactor", (dem, "--zfactor", "ft")),
                              ("none", (dem,))):
            out = self.path("feet-%s.tif" % name)
            status, _, err = run("bake", *options, out, "--products", "SkyViewFactor", "-d", 360,
                                 "--no-curvature")
            self.assertEqual(status, 0, err)
            self.assertEqual(err, "")  # (a projected CRS in metres: no unit is no warning)
            b, meta, _, _ = bands(out)
            svf[name] = b["SkyViewFactor"][0]
            if name == "zfactor":
                self.assertEqual(meta["SOURCE_ELEVATION_UNIT"], "0.3048 m (--zfactor)")
        # (elevations rounded to float32 twice: 1e-5 of the valley's 693 m height)
        np.testing.assert_allclose(svf["zfactor"], svf["metres"], atol=1e-5)
        self.assertAlmostEqual(svf["zfactor"][30, 40], 1 - 2 * math.radians(30) / math.pi,
                               delta=3e-3)
        alpha = math.atan(0.9996 * math.tan(math.radians(30)) / 0.3048)
        self.assertAlmostEqual(svf["none"][30, 40], 1 - 2 * alpha / math.pi, delta=3e-3)

    def test_gdal_virtual_path(self):
        # GDAL's virtual file systems are read as GDAL reads them: a DEM inside a zip (as SRTM
        # tiles come) bakes to the same values as the file itself
        import zipfile
        archive = self.path("dem.zip")
        with zipfile.ZipFile(archive, "w") as z:
            z.write(self.dem, "tiles/dem.tif")
        inside = "/vsizip/%s/tiles/dem.tif" % archive
        plain, zipped = self.path("plain.tif"), self.path("zipped.tif")
        for dem, out in ((self.dem, plain), (inside, zipped)):
            status, _, err = run("bake", dem, out, "--products", "SkyViewFactor", "-d", "8",
                                 "--radius", "600")
            self.assertEqual(status, 0, err)
        (a, _, gt, srs), (b, meta, gt_b, srs_b) = bands(plain), bands(zipped)
        np.testing.assert_array_equal(a["SkyViewFactor"][0], b["SkyViewFactor"][0])
        self.assertEqual((gt, srs), (gt_b, srs_b))
        self.assertEqual(meta["SOURCE_DEM"], inside)  # (not normalised: /vsizip/tmp/... is
        status, out, err = run("info", inside, "--json")  # relative to the working folder)
        self.assertEqual(status, 0, err)
        self.assertEqual(json.loads(out)["file"], inside)
        # a member the archive does not have: GDAL tries it (no local stat of a virtual path),
        # then the path is said not to exist (GDAL's VSIStatL), as a missing file is
        status, _, err = run("bake", inside + ".no", zipped)
        self.assertEqual(status, 1, err)
        self.assertEqual("aperture: error: file '%s.no' does not exist\n" % inside, err)

    def test_windows_tile_the_whole_bake(self):
        # --srcwin bakes the window's cells with horizons that see the DEM around it (the sky
        # filter reads the window and a halo as wide as --radius, all of the DEM without one),
        # so windows baked one by one are the whole bake's cells, bit for bit, with the
        # georeference of their place in it; a window alone would truncate horizons at its
        # edges. Rough terrain with nodata in UTM; the embedded lat/lon DEM; a decimated grid
        # (blocks aligned to the raster, a window covering every block it touches).
        rough = rough_dem(self.path("rough.tif"), (170, 200), 5, np.s_[60:64, 90:97])
        import aperture
        jacksboro = aperture.default_dem()

        def bake(dem, name, *options):
            out = self.path(name)
            status, _, err = run("bake", dem, out, "-q", *options)
            self.assertEqual(status, 0, err)
            b, _, gt, srs = bands(out)
            return b, gt, srs

        def check(dem, options, windows, block=1):
            whole, gt, srs = bake(dem, "whole.tif", *options)
            names = sorted(whole)
            for k, (x, y, w, h) in enumerate(windows):
                part, pgt, psrs = bake(dem, "part%d.tif" % k, "--srcwin", x, y, w, h, *options)
                self.assertEqual(sorted(part), names)
                # the decimated cells covering the window (the file's rows, north first)
                c0, r0 = x // block, y // block
                ny, nx = whole[names[0]][0].shape
                c1 = nx if w == 0 else min(nx, -(-(x + w) // block))
                r1 = ny if h == 0 else min(ny, -(-(y + h) // block))
                for name in names:
                    np.testing.assert_array_equal(part[name][0], whole[name][0][r0:r1, c0:c1],
                                                  err_msg="%s of window %d" % (name, k))
                np.testing.assert_allclose(pgt, (gt[0] + c0 * gt[1], gt[1], 0.0,
                                                 gt[3] + r0 * gt[5], 0.0, gt[5]),
                                           rtol=0, atol=1e-9 * gt[1])
                self.assertEqual(psrs, srs)
            return whole

        # six windows tiling the rough DEM (two reaching the edges with sizes of 0)
        windows = [(0, 0, 70, 55), (70, 0, 61, 55), (131, 0, 0, 55),
                   (0, 55, 70, 0), (70, 55, 61, 115), (131, 55, 69, 0)]
        whole = check(rough, ["--radius", "1500", "-d", "16", "--products", "all"], windows)
        self.assertEqual(len(whole), 9 + 16)  # the products, BentNormal's 3 bands, 16 horizons
        # flagged only near the DEM's edges, not the windows' (1500 m: 50 cells; NaN on nodata)
        self.assertFalse((whole["EdgeTruncated"][0][52:118, 52:148] == 1).any())
        self.assertTrue((whole["EdgeTruncated"][0][:, 0] == 1).all())
        # without a radius (the whole DEM is read), a window inside and one at a corner
        check(rough, ["-d", "8"], [(40, 30, 50, 60), (150, 120, 0, 0)])
        # lat/lon (3 arc-second cells, about 70 x 92 m)
        check(jacksboro, ["--radius", "2000", "-d", "12"], [(100, 150, 60, 40), (0, 0, 30, 20)])
        # decimated by 3: 66 x 56 cells of the raster's blocks; windows cover every block
        # they touch (the first: columns 3..19, rows 6..19 of the decimated grid)
        check(rough, ["--radius", "1500", "-d", "8", "--decimate", "3"],
              [(10, 20, 50, 40), (180, 150, 0, 0)], block=3)

    def test_strips_of_a_lat_lon_window(self):
        # The sky filter's halo comes from the cell sizes of the rows near what it computes, so
        # on a lat/lon DEM a strip near the pole reads more columns than one in the middle
        # (84 to 60 N here: 448 columns around a 100-column window at the top, fewer lower
        # down). The plan took the middle row's halo for every strip, so with 6 MiB it planned
        # strips of 512 rows that the sky filter then refused at the top; it now plans from
        # the widest, and the strips equal the bake at once.
        rng = np.random.default_rng(2)
        z = np.cumsum(np.cumsum(rng.normal(0, 1, (2400, 600)), 0), 1).astype(np.float32)
        dem = self.path("strips-latlon.tif")
        make_dem(dem, z, (10, 0.01, 0, 84, 0, -0.01), 4326)
        common = ["--srcwin", 200, 0, 100, 2400, "--radius", 20000, "-d", 8]
        status, _, err = run("bake", dem, self.path("strips-latlon-once.tif"), *common)
        self.assertEqual(status, 0, err)
        once, _, _, _ = bands(self.path("strips-latlon-once.tif"))
        for memory in ("6M", "8M"):
            out = self.path("strips-latlon-%s.tif" % memory)
            status, stdout, err = run("bake", dem, out, *common, "--max-memory", memory)
            self.assertEqual(status, 0, err)
            self.assertIn(" strips of ", stdout)
            got, _, _, _ = bands(out)
            for name, (values, _) in once.items():
                np.testing.assert_array_equal(got[name][0], values, name)

    def test_grids_of_billions_of_cells(self):
        # VRTs of 2^31 - 1 cells a side, no sources. The halo of a window came from the cell
        # sizes of every row of the grid, 128 bytes a row at once (the process was killed for
        # memory), and at the grid's last row it overflowed int (a negative extent, a
        # traceback); it now comes from the rows within the radius, and the sweep, which places
        # pieces within 10^9 cells of the grid's corner, refuses such grids by name.
        def vrt(name, crs, gt):
            path = self.path(name)
            with open(path, "w") as f:
                f.write('<VRTDataset rasterXSize="2147483647" rasterYSize="2147483647">'
                        "<SRS>%s</SRS><GeoTransform>%s</GeoTransform>"
                        '<VRTRasterBand dataType="Float32" band="1">'
                        "<NoDataValue>-9999</NoDataValue></VRTRasterBand></VRTDataset>"
                        % (crs, ", ".join(str(v) for v in gt)))
            return path

        latlon = vrt("billions-latlon.vrt", "EPSG:4326", (0, 1e-8, 0, 10, 0, -1e-8))
        # (its central column on the zone's central meridian, where the scale is 0.9996)
        utm = vrt("billions-utm.vrt", "EPSG:32616",
                  (500000 - 0.0005 * 2147483647, 0.001, 0, 4000000, 0, -0.001))
        import aperture
        from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as sddp
        # cell sizes east and north: at 10 N (WGS 84's radii of curvature), and 1 mm
        a, e2, lat = 6378137.0, 0.00669437999014, math.radians(10.0)
        w = math.sqrt(1 - e2 * math.sin(lat) ** 2)
        step = math.radians(1e-8)
        for path, cell in ((latlon, (a / w * math.cos(lat) * step, a * (1 - e2) / w ** 3 * step)),
                           (utm, (0.001 / 0.9996, 0.001 / 0.9996))):
            reader = aperture.vtkApertureDEMReader()
            reader.SetFileName(path)
            sky = aperture.vtkApertureSkyVisibility()
            sky.SetInputConnection(reader.GetOutputPort())
            sky.SetMaximumDistance(1.0)
            sky.UpdateInformation()
            whole = reader.GetOutputInformation(0).Get(sddp.WHOLE_EXTENT())
            self.assertEqual(whole, (0, 2147483646, 0, 2147483646, 0, 0))
            read = [0] * 6
            start = time.monotonic()
            self.assertTrue(sky.ComputeInputExtent((0, 99, 2147483547, 2147483646, 0, 0), read))
            self.assertLess(time.monotonic() - start, 5.0)
            # 1 m over the cells (1.096 mm east and 1.106 mm north at 10 N for lat/lon, 1.0004
            # mm in UTM), and 2
            hx, hy = (math.ceil(1.0 / c) + 2 for c in cell)
            self.assertEqual(tuple(read), (0, 99 + hx, 2147483547 - hy, 2147483646, 0, 0), path)
            status, out, err = run("bake", path, self.path("billions.tif"),
                                   "--srcwin", 0, 0, 100, 100, "--radius", 1)
            self.assertEqual((status, out), (1, ""), err)
            self.assertEqual(err.strip(), "aperture: error: bake: the DEM's grid of 2147483647 x "
                             "2147483647 cells has more than the 1000000001 cells a side the "
                             "sweep can place its pieces in; bake a decimated DEM")
            # The whole grid, and (lat/lon) a column of it through every row, in a moment: the
            # halo came from every row's cell sizes, an hour's geodesics for 2^31 rows (the
            # bake of the whole grid with a radius ignored Ctrl-C meanwhile) until 2026-12-07;
            # a lat/lon grid's smallest cells of a run of rows are at its ends or the equator.
            start = time.monotonic()
            self.assertTrue(sky.ComputeInputExtent(whole, read))
            self.assertEqual(tuple(read), whole)
            if path == latlon:
                self.assertTrue(sky.ComputeInputExtent((0, 99, 0, 2147483646, 0, 0), read))
                # (the narrowest cells, at the south row: 21.47 degrees south of 10 N)
                south = math.radians(10.0 - 2147483646e-8)
                w = math.sqrt(1 - e2 * math.sin(south) ** 2)
                hx = math.ceil(1.0 / (a / w * math.cos(south) * step)) + 2
                self.assertEqual(tuple(read), (0, 99 + hx, 0, 2147483646, 0, 0))
            status, out, err = run("bake", path, self.path("billions.tif"), "--radius", 1)
            self.assertEqual((status, out), (1, ""), err)
            self.assertLess(time.monotonic() - start, 60.0)

    def test_window_of_a_large_dem(self):
        # A window of a 60000^2 DEM (13.4 GiB of elevations, a 75 GB bake) with a radius reads
        # only the window and the DEM within the radius around it: 100 + 2 x 102 columns (3000 m
        # of 30 m cells and 2 more), so it takes a moment; flat ground: no horizon above 0.
        big = zeros_vrt(self.path("window-big.vrt"), 60000)
        out = self.path("window-big.tif")
        exr = self.path("window-big.exr")
        status, stdout, err = run("bake", big, out, "--srcwin", 30000, 20000, 100, 80,
                                  "--radius", 3000, "-d", 8, "--exr", exr)
        self.assertEqual(status, 0, err)
        self.assertIn("for 100 x 80 cells", stdout)
        import aperture
        r = aperture.vtkApertureEXRReader()
        r.SetFileName(exr)
        r.Update()
        self.assertEqual(r.GetOutput().GetDimensions(), (100, 80, 1))
        b, meta, gt, _ = bands(out)
        self.assertEqual(b["SkyViewFactor"][0].shape, (80, 100))
        np.testing.assert_array_equal(b["SkyViewFactor"][0], 1.0)
        np.testing.assert_array_equal(b["EdgeTruncated"][0], 0.0)
        self.assertEqual(gt, (500000 + 30000 * 30, 30, 0, 4000000 - 20000 * 30, 0, -30))
        # Without a radius every cell of the DEM may be on a horizon: it is all read, and the
        # bake is refused before reading. The sky filter needs 21 bytes a cell of the DEM (its
        # float copy 4, the sweep's state 17) and 41 a cell of the window (the products 37,
        # EdgeTruncated as float beside its byte flags, and the window's copy of the
        # elevations 4): 75600328000 bytes = 70.408 GiB, beside the elevations' 13.411 GiB.
        memory, owner = usable_memory()
        def refused(text, *args):
            status, _, err = run("bake", *args)
            self.assertEqual(status, 1, err)
            self.assertEqual(err.strip(), "aperture: error: %s; bake a window with --srcwin and "
                             "a --radius (only the DEM within the radius around it is read), "
                             "use --decimate or --overview, or bake fewer --products" % text)

        # A DEM larger than the memory leaves nothing to compare with: 2e6^2 cells, 14.552 TiB
        # of elevations, 21 bytes a cell of it and 41 a cell of the window; strips would read
        # the same DEM, so they are not offered. (Of 1 m: 30 m cells would reach 60,000 km
        # south of the equator, off the projection's domain, which is refused first.)
        huge = zeros_vrt(self.path("window-huge.vrt"), 2000000, cell=1)
        huge_out = self.path("window-huge.tif")
        if memory < 4.0 * 2000000 ** 2:
            refused("the products of 100 x 100 cells, with the 2000000 x 2000000 cells of DEM "
                    "around them, need about %s, and the DEM's 14.552 TiB alone exceed the %s "
                    "of memory %s" % (human_bytes(21.0 * 4e12 + 41.0 * 1e4), human_bytes(memory),
                                      owner),
                    huge, huge_out, "--srcwin", 0, 0, 100, 100)
            refused("a 2000000 x 2000000 DEM with these products needs about %s, and the DEM's "
                    "14.552 TiB alone exceed the %s of memory %s"
                    % (human_bytes((21.0 + 41.0 - 4.0) * 4e12), human_bytes(memory), owner),
                    huge, huge_out)
            self.assertFalse(os.path.exists(huge_out))
        # (the 30 m one, a window of it too, at once: its south row has no place on the Earth)
        off = zeros_vrt(self.path("window-off.vrt"), 2000000)
        for window in ([], ["--srcwin", 0, 0, 100, 100]):
            start = time.monotonic()
            status, _, err = run("bake", off, huge_out, *window)
            self.assertEqual(status, 1, err)
            self.assertTrue(err.startswith(
                "aperture: error: no metric cell size: the row of cells at y = -5.6e+07 (grid "
                "row 0, counted from the south) has no geographic coordinates"), err)
            self.assertLess(time.monotonic() - start, 30.0)
        self.assertFalse(os.path.exists(huge_out))
        if memory > 84 << 30:
            self.skipTest("this machine has the memory to bake it")
        refused("the products of 100 x 80 cells, with the 60000 x 60000 cells of DEM around "
                "them, need about 70.408 GiB, more than the %s of memory %s beside the DEM's "
                "13.411 GiB" % (human_bytes(memory - 4.0 * 60000 ** 2), owner),
                big, out, "--srcwin", 30000, 20000, 100, 80, "-d", 8)

    def test_strips(self):
        # A bake that does not fit --max-memory (the products and the sweep's state) is written
        # in strips of whole 256-row tiles, each computing its own cells from itself and its
        # halo: the same file contents as at once, bit for bit. Rough terrain with nodata,
        # 700 x 150 cells, 1500 m (a halo of 52 rows), 8 directions and every product
        # (HorizonAngles too): 90 bytes a cell at once, 9450000 bytes = 9.012 MiB. Strips of 256
        # rows read 360 rows (21 bytes a cell: the float copy and the sweep's state) and hold 73
        # bytes a cell of their own (the products and their copy of the elevations): 3937200
        # bytes = 3.755 MiB; of 512 rows 7.197 MiB.
        dem = rough_dem(self.path("strips.tif"), (700, 150), 8, np.s_[300:305, 40:48])
        options = ["--radius", 1500, "-d", 8, "--products", "all"]
        whole_out, strips_out = self.path("strips-whole.tif"), self.path("strips-out.tif")
        whole_exr, strips_exr = self.path("strips-whole.exr"), self.path("strips-out.exr")
        status, _, err = run("bake", dem, whole_out, *options, "--exr", whole_exr)
        self.assertEqual(status, 0, err)
        status, stdout, err = run("bake", dem, strips_out, *options, "--max-memory", "5M",
                                  "--exr", strips_exr)
        self.assertEqual(status, 0, err)
        self.assertIn("in 3 strips of 256 rows: the whole did not fit in --max-memory", stdout)
        # the EXR from the same strips (each computed once), the same file byte for byte
        with open(whole_exr, "rb") as a, open(strips_exr, "rb") as b:
            self.assertEqual(a.read(), b.read())
        whole, whole_meta, whole_gt, whole_srs = bands(whole_out)
        strips, meta, gt, srs = bands(strips_out)
        self.assertEqual(list(strips), list(whole))
        for name in whole:
            np.testing.assert_array_equal(strips[name][0], whole[name][0], err_msg=name)
            self.assertEqual(strips[name][1], whole[name][1])  # units, definitions
        self.assertEqual((meta, gt, srs), (whole_meta, whole_gt, whole_srs))
        # (with the digest of the elevations baked, which render --baked compares, the same
        # from strips: the DEM's own, nodata cells in it)
        self.assertEqual(meta["SOURCE_ELEVATION_DIGEST"].split(" ", 1)[0], elevation_digest(dem))
        # a window in strips: the window's cells of the whole bake; its EXR (georeferenced
        # at the window) the same as the window's at once
        window_options = options + ["--srcwin", 20, 100, 100, 560]
        status, _, err = run("bake", dem, whole_out, *window_options, "--exr", whole_exr)
        self.assertEqual(status, 0, err)
        status, stdout, err = run("bake", dem, strips_out, *window_options, "--max-memory", "3M",
                                  "--exr", strips_exr)
        self.assertEqual(status, 0, err)
        self.assertIn("for 100 x 560 cells", stdout)
        self.assertIn("in 3 strips of 256 rows", stdout)
        window, meta, _, _ = bands(strips_out)
        self.assertEqual(meta["SOURCE_ELEVATION_DIGEST"].split(" ", 1)[0],
                         elevation_digest(dem, np.s_[100:660], np.s_[20:120]))
        for name in whole:
            np.testing.assert_array_equal(window[name][0], whole[name][0][100:660, 20:120],
                                          err_msg=name)
        with open(whole_exr, "rb") as a, open(strips_exr, "rb") as b:
            self.assertEqual(a.read(), b.read())
        # without a radius every strip reads the whole DEM: the same values
        status, _, err = run("bake", dem, whole_out, "-d", 8, "--products", "all")
        self.assertEqual(status, 0, err)
        status, stdout, err = run("bake", dem, strips_out, "-d", 8, "--products", "all",
                                  "--max-memory", "5M")
        self.assertEqual(status, 0, err)
        self.assertIn("in 3 strips of 256 rows", stdout)
        self.assertEqual(err, "")
        unlimited, _, _, _ = bands(whole_out)
        in_strips, _, _, _ = bands(strips_out)
        for name in unlimited:
            np.testing.assert_array_equal(in_strips[name][0], unlimited[name][0], err_msg=name)
        # a warning that every strip gives (here an undeclared nodata value of -32768 in each)
        # is printed once
        odd = rough_dem(self.path("strips-odd.tif"), (700, 150), 8)
        ds = gdal.Open(odd, gdal.GA_Update)
        band = ds.GetRasterBand(1)
        band.DeleteNoDataValue()
        for row in (10, 300, 600):
            band.WriteArray(np.full((2, 2), -32768, np.float32), 5, row)
        ds = None
        status, stdout, err = run("bake", odd, strips_out, *options, "--max-memory", "5M")
        self.assertEqual(status, 0, err)
        self.assertIn("in 3 strips of 256 rows", stdout)
        self.assertEqual(len(err.strip().splitlines()), 1, err)
        self.assertIn("aperture: warning: elevations range from -32768 to ", err)
        # too little memory for one tile row: refused before anything is written; bad sizes
        status, _, err = run("bake", dem, self.path("strips-refused.tif"), *options,
                             "--max-memory", "2M", "--exr", self.path("strips-refused.exr"))
        self.assertEqual(status, 1, err)
        self.assertEqual(err.strip(), "aperture: error: a 150 x 700 DEM with these products "
                         "needs about 9.012 MiB (HorizonAngles take 4 bytes per cell and "
                         "direction), more than --max-memory 2.000 MiB, and strips of 256 rows "
                         "(the GeoTIFF's tiles) would not fit either: the products of 150 x 256 "
                         "cells, with the 150 x 360 cells of DEM around them, need about 3.755 "
                         "MiB (HorizonAngles take 4 bytes per cell and direction), more than "
                         "--max-memory 2.000 MiB; bake a window with --srcwin and a --radius "
                         "(only the DEM within the radius around it is read), use --decimate or "
                         "--overview, or bake fewer --products")
        self.assertFalse(os.path.exists(self.path("strips-refused.tif")))
        self.assertFalse(os.path.exists(self.path("strips-refused.exr")))
        for bad in ("0", "-3M", "lots", "1e3", "B", "1BB"):
            status, _, err = run("bake", dem, self.path("strips-refused.tif"),
                                 "--max-memory=" + bad)
            self.assertEqual(status, 2, err)
            self.assertIn("is not a size (512, 300K, 1.5G, 2T, 4096B)", err)
        # B alone is bytes (it was taken as MiB), a bare number MiB
        for size, said in (("100B", "100 bytes"), ("3", "3.000 MiB"), ("2KiB", "2.000 KiB")):
            status, _, err = run("bake", dem, self.path("strips-refused.tif"), *options,
                                 "--max-memory", size)
            self.assertEqual(status, 1, err)
            self.assertIn("more than --max-memory %s," % said, err)
        # integers beyond a C int: a usage error, not an OverflowError from a setter
        for option in ("--threads", "--compress-level", "--band", "--decimate", "--overview"):
            status, _, err = run("bake", dem, self.path("strips-refused.tif"), option,
                                 "99999999999")
            self.assertEqual(status, 2, err)
            self.assertIn("99999999999 is out of range (-2147483648..2147483647)", err)
            self.assertNotIn("Traceback", err)

    def test_gridline_registered_window(self):
        # A global grid whose first and last columns are one meridian (361 of 1 degree) is
        # refused, a window of it too: its cells are measured on the whole raster; the message
        # says that --srcwin cannot drop the column (it advised gdal_translate -srcwin alone,
        # which a user of --srcwin took for the same thing, until 2026-12-07)
        dem = self.path("gridline.tif")
        make_dem(dem, np.full((181, 361), 100.0, np.float32), (-180.5, 1, 0, 90.5, 0, -1), 4326)
        status, _, err = run("bake", dem, self.path("w.tif"), "--radius", 300000, "--srcwin", 10,
                             10, 50, 50, "-q")
        self.assertEqual(status, 1, err)
        self.assertIn("(gdal_translate -srcwin 0 1 360 179; with -of VRT it copies nothing); "
                      "--srcwin cannot: the cells of a window are measured on the whole raster",
                      err)
        self.assertEqual(len(err.splitlines()), 1, err)
        # refused before a cell is read, a window or all of it: a VRT whose source is gone
        # opens, but fails to read (the whole grid was read first, or refused for memory,
        # until 2026-12-07)
        vrt = self.path("gridline.vrt")
        gdal.Translate(vrt, dem, format="VRT")
        os.remove(dem)
        for window in ((), ("--srcwin", 10, 10, 50, 50)):
            status, _, err = run("bake", vrt, self.path("w.tif"), "-q", *window)
            self.assertEqual(status, 1, err)
            self.assertIn("(a gridline-registered global grid)", err)
            self.assertEqual("--srcwin cannot" in err, bool(window), err)
            self.assertNotIn("GDAL failed reading", err)

    def test_global_dem(self):
        # A global lat/lon DEM (720 columns of 0.5 degree, 75 S to 75 N): its east and west
        # edges join. The same products with the grid's seam 300 columns further on; in strips
        # (each reading every column: their halos cross the antimeridian) and for a window at
        # the seam as at once; no EdgeTruncated cell at either side; EDGES says so.
        lon = -180 + 0.5 * (np.arange(720) + 0.5)
        lat = 75 - 0.5 * (np.arange(300) + 0.5)
        hills = 2500 * np.exp(-((lon[None, :] - 179.0) ** 2 + (lat[:, None] - 10) ** 2) / 2.0)
        rng = np.random.default_rng(4)
        z = (hills + 300 * rng.random((300, 720))).astype(np.float32)
        dem, rolled = self.path("globe.tif"), self.path("globe-seam-elsewhere.tif")
        make_dem(dem, z, (-180, 0.5, 0, 75, 0, -0.5), 4326)
        make_dem(rolled, np.roll(z, -300, axis=1), (-30, 0.5, 0, 75, 0, -0.5), 4326)
        options = ["--radius", 300000, "-d", 8, "--products", "all"]
        outs = {name: self.path("globe-%s.tif" % name) for name in
                ("whole", "rolled", "strips", "window")}
        # (--max-memory 19.4M holds the whole but for its 2 x 23 joined columns, which the
        # plan counts: 19.64 MiB with them; strips of 256 rows fit)
        for name, args in (("whole", (dem,)), ("rolled", (rolled,)),
                           ("strips", (dem, "--max-memory", "19.4M")),
                           ("window", (dem, "--srcwin", 0, 100, 12, 50))):
            status, stdout, err = run("bake", *args, outs[name], *options)
            self.assertEqual(status, 0, err)
            self.assertEqual(name == "strips", "in 2 strips of 256 rows" in stdout, stdout)
        whole, meta, _, _ = bands(outs["whole"])
        self.assertIn("the DEM spans 360 degrees of longitude: its east and west edges join",
                      meta["EDGES"])
        self.assertEqual(whole["EdgeTruncated"][0][20:280, [0, -1]].max(), 0.0)
        rolled_bands = bands(outs["rolled"])[0]
        strips, window = bands(outs["strips"])[0], bands(outs["window"])[0]
        for name in whole:
            np.testing.assert_array_equal(np.roll(rolled_bands[name][0], 300, axis=1),
                                          whole[name][0], err_msg=name)
            np.testing.assert_array_equal(strips[name][0], whole[name][0], err_msg=name)
            np.testing.assert_array_equal(window[name][0], whole[name][0][100:150, 0:12],
                                          err_msg=name)
        # the hills just east of the antimeridian, seen westwards from its other side
        self.assertGreater(whole["HorizonAngles_az270.00"][0][130, 0], 1.0)

    def test_sea(self):
        # Parts of a DEM may be nodata alone, with the DEM they read around them (a coastal
        # tile's strips and windows out at sea): their products are nodata, as the whole
        # bake's are there; only a DEM with no data at all is an error. The strips and windows
        # below were each refused ("every cell of the DEM is nodata") before 2026-12-05.
        # 700 x 150 cells; 1500 m: a halo of 52 rows; strips of 256 rows.
        options = ["--radius", 1500, "-d", 8, "--products", "all"]

        def same_in_strips(dem):
            """The bake at once and in strips, the same bit for bit (the EXR byte for byte);
            the bands at once."""
            paths = [self.path(name) for name in ("sea-once.tif", "sea-once.exr",
                                                  "sea-strips.tif", "sea-strips.exr")]
            status, _, err = run("bake", dem, paths[0], *options, "--exr", paths[1])
            self.assertEqual((status, err), (0, ""))
            status, stdout, err = run("bake", dem, paths[2], *options, "--max-memory", "5M",
                                      "--exr", paths[3])
            self.assertEqual((status, err), (0, ""))
            self.assertIn("in 3 strips of 256 rows", stdout)
            whole, strips = bands(paths[0])[0], bands(paths[2])[0]
            for name in whole:
                np.testing.assert_array_equal(strips[name][0], whole[name][0], err_msg=name)
            with open(paths[1], "rb") as a, open(paths[3], "rb") as b:
                self.assertEqual(a.read(), b.read())
            return whole

        # land in the northern 200 rows, the rest sea (the southern two strips: sea alone)
        dem = rough_dem(self.path("coast.tif"), (700, 150), 11, np.s_[200:, :])
        whole = same_in_strips(dem)
        self.assertTrue(np.isnan(whole["SkyViewFactor"][0][200:]).all())
        self.assertTrue(np.isnan(whole["EdgeTruncated"][0][200:]).all())
        self.assertTrue(np.isfinite(whole["SkyViewFactor"][0][:200]).all())
        # the sea in the north (the first strip: the rest is searched for data), land in the
        # south
        south = same_in_strips(rough_dem(self.path("south.tif"), (700, 150), 12, np.s_[:500, :]))
        self.assertTrue(np.isfinite(south["SkyViewFactor"][0][500:]).all())
        # a window out at sea (its rows 400..599 and the 52 around them: no data) is written,
        # nodata, with a warning; so is one whose search reaches the shore (silent until
        # 2026-12-06), at once and in strips; one holding a cell of land is not warned about
        sea = self.path("coast-sea.tif")
        status, _, err = run("bake", dem, sea, *options, "--srcwin", 10, 400, 100, 200,
                             "--exr", self.path("coast-sea.exr"))
        self.assertEqual(status, 0, err)
        self.assertEqual(err, "aperture: warning: every cell of the DEM read for --srcwin 10 400 "
                         "100 200 (the window and 1500 m around it) is nodata, and so is every "
                         "product\n")
        window = bands(sea)[0]
        self.assertEqual(sorted(window), sorted(whole))
        for name in whole:
            np.testing.assert_array_equal(window[name][0], whole[name][0][400:600, 10:110],
                                          err_msg=name)
        for strips in ([], ["--max-memory", "3M"]):  # (2 strips, without HorizonAngles)
            status, out, err = run("bake", dem, sea, *options[:4], "--srcwin", 10, 240, 100,
                                   400, *strips)
            self.assertEqual((status, err), (0, "aperture: warning: every cell of --srcwin 10 "
                             "240 100 400 is nodata (the DEM around it has data), and so is "
                             "every product\n"))
            self.assertIn("strips" if strips else "wrote", out)
        status, _, err = run("bake", dem, sea, *options[:4], "--srcwin", 10, 199, 100, 400,
                             "--max-memory", "3M")
        self.assertEqual((status, err), (0, ""))
        # no data anywhere: an error at once (the reader's) and in strips (when the first strip
        # has none, the rest of the DEM is read for data before any is baked), no output left
        void = rough_dem(self.path("void.tif"), (700, 150), 11, np.s_[:, :])
        for extra in ([], ["--max-memory", "5M"]):
            out, exr = self.path("void-out.tif"), self.path("void-out.exr")
            status, _, err = run("bake", void, out, *options, "--exr", exr, *extra)
            self.assertEqual((status, err), (1, "aperture: error: every cell of '%s' band 1 is "
                                                "nodata\n" % void), extra)
            self.assertFalse(os.path.exists(out))
            self.assertFalse(os.path.exists(exr))

    def test_reader_refusal_in_options(self):
        # The reader's own refusal (a grid past the machine's memory, reached here by a
        # --max-memory beyond it) is worded in the command's options, as every other message.
        memory, owner = usable_memory()
        if memory > 4.0 * 100000 ** 2:
            self.skipTest("this machine could read 100000^2 floats")
        huge = zeros_vrt(self.path("huge.vrt"), 100000)
        status, _, err = run("bake", huge, self.path("huge.tif"), "--max-memory", "10T")
        self.assertEqual(status, 1, err)
        self.assertIn("reading 100000 x 100000 cells of '%s' needs 37.253 GiB as float32" % huge,
                      err)
        self.assertTrue(err.strip().endswith(
            "; read a part with --srcwin, or use --decimate or --overview"), err)

    def test_partial_blocks(self):
        # --decimate's partial blocks at the east and south edges are left out with a warning
        # (silently until 2026-12-06) where the window reaches them, and only there: a bake
        # reads the whole grid for any window (it warned for windows far from the edges), and
        # names the factors that keep every cell (none where the sizes have no common one)
        dem = make_dem(self.path("d95.tif"), np.arange(95 * 90, dtype=np.float32).reshape(90, 95),
                       (500000, 30, 0, 4000000, 0, -30), 32611)
        said = ("aperture: warning: '%s': decimation by 4 leaves out its last 3 columns (east)%s, "
                "partial 4 x 4 blocks; a factor dividing %s keeps every cell (5)\n")
        out = self.path("partial.tif")
        for options, expected in (
                (["--srcwin", 0, 0, 40, 40], ""),
                (["--srcwin", 50, 0, 0, 40], said % (dem, "", "95")),
                ([], said % (dem, " and its last 2 rows (south)", "95 and 90")),
                (["--decimate", 5], "")):
            status, _, err = run("bake", dem, out, "-q", "-d", 8, "--decimate", 4, *options)
            self.assertEqual((status, err), (0, expected), options)
        status, _, err = run("info", dem, "--no-stats", "--decimate", 2)
        self.assertEqual(err, "aperture: warning: '%s': decimation by 2 leaves out its last "
                         "column (east), partial 2 x 2 blocks; a factor dividing 95 keeps every "
                         "cell (5)\n" % dem)

    def test_window_errors(self):
        rng = np.random.default_rng(6)
        z = rng.normal(0, 10, (170, 200)).astype(np.float32)
        dem = self.path("window-errors.tif")
        make_dem(dem, z, (500000, 30, 0, 4000000, 0, -30), 32611)
        out = self.path("window-errors-out.tif")
        for options, message in (
                (["--srcwin", 190, 0, 20, 10],
                 "--srcwin 190 0 20 10 is not inside the 200 x 170 raster"),
                (["--srcwin", 0, 0, 0, 171],
                 "--srcwin 0 0 0 171 is not inside the 200 x 170 raster"),
                # 200 = 66 x 3 + 2: the last two columns are a partial block, dropped
                (["--srcwin", 198, 0, 0, 0, "--decimate", 3],
                 "--srcwin 198 0 0 0 covers no cell of the 66 x 56 grid read (decimation drops "
                 "the partial blocks at the east and south edges)")):
            status, stdout, err = run("bake", dem, out, *options)
            self.assertEqual(status, 1, err)
            self.assertEqual(err.strip(), "aperture: error: " + message, options)
            self.assertFalse(os.path.exists(out))
        # (a mistake in the option itself: a usage error)
        self.assertEqual(usage_error(self, "bake", run("bake", dem, out, "--srcwin", 0, -1, 5,
                                                       5)),
                         "aperture bake: error: --srcwin values must not be negative\n")
        self.assertFalse(os.path.exists(out))

    def test_threads_do_not_matter(self):
        # 900 m (30 columns) is marched ray by ray, 2000 m (67) swept through the hulls
        for radius in ("900", "2000"):
            self.check_threads_do_not_matter(radius)

    def check_threads_do_not_matter(self, radius):
        outs, files, exrs = [], [], []
        # more threads than this machine has cores are its cores, without TBB's warning
        for t in (1, 2, 4 * (os.cpu_count() or 1)):
            out = self.path("t%d_r%s.tif" % (t, radius))
            exr = self.path("t%d_r%s.exr" % (t, radius))
            status, _, err = run("bake", self.dem, out, "--threads", t, "--radius", radius,
                                 "--exr", exr)
            self.assertEqual(status, 0, err)
            self.assertNotIn("TBB", err)
            outs.append(bands(out)[0])
            with open(out, "rb") as f:
                files.append(f.read())
            with open(exr, "rb") as f:
                exrs.append(f.read())
        for other in range(1, len(outs)):
            for name in outs[0]:
                np.testing.assert_array_equal(outs[0][name][0], outs[other][name][0])
            # GeoTIFF tiles and EXR chunks are compressed on --threads threads too: the same
            # files, byte for byte
            self.assertEqual(files[0], files[other])
            self.assertEqual(exrs[0], exrs[other])

    def test_compress_level(self):
        # the level changes the file's bytes, never its values
        outs, files = [], []
        for level in ("1", "9"):
            out = self.path("level%s.tif" % level)
            args = ["--compress-level", level] if level != "1" else []  # 1: the default
            status, _, err = run("bake", self.dem, out, "--radius", "900", *args)
            self.assertEqual(status, 0, err)
            outs.append(bands(out)[0])
            with open(out, "rb") as f:
                files.append(f.read())
        self.assertNotEqual(files[0], files[1])
        for name in outs[0]:
            np.testing.assert_array_equal(outs[0][name][0], outs[1][name][0])

    def test_nodata_value(self):
        # --nodata -9999: the GeoTIFF's nodata cells hold it and every band declares it, for
        # tools that take no NaN (an ASCII grid said NODATA_value nan); its data cells are the
        # default bake's (the writer's test covers strips); the EXR keeps NaN
        import aperture
        from vtkmodules.util.numpy_support import vtk_to_numpy
        default, m9999, exr = (self.path(n) for n in ("nan.tif", "m9999.tif", "m9999.exr"))
        status, _, err = run("bake", self.dem, default, "--radius", "900", "-q")
        self.assertEqual(status, 0, err)
        nan_bands = bands(default)[0]
        status, _, err = run("bake", self.dem, m9999, "--radius", "900", "-q", "--nodata",
                             "-9999", "--exr", exr)
        self.assertEqual(status, 0, err)
        ds = gdal.Open(m9999)
        self.assertEqual({ds.GetRasterBand(b).GetNoDataValue()
                          for b in range(1, ds.RasterCount + 1)}, {-9999.0})
        ds = None
        for name, (values, _) in bands(m9999)[0].items():
            expected = nan_bands[name][0]
            self.assertTrue(np.isnan(expected[5, 5]), name)  # (the DEM's nodata cell)
            np.testing.assert_array_equal(values, np.where(np.isnan(expected), -9999.0,
                                                           expected), err_msg=name)
        asc = self.path("m9999.asc")
        gdal.Translate(asc, m9999, format="AAIGrid", bandList=[4])
        with open(asc) as f:
            self.assertIn("NODATA_value  -9999", f.read(300))
        r = aperture.vtkApertureEXRReader()
        r.SetFileName(exr)
        r.Update()
        svf = vtk_to_numpy(r.GetOutput().GetPointData().GetArray("SkyViewFactor"))
        self.assertEqual(int(np.isnan(svf).sum()), 1)
        self.assertIn("argument --nodata: inf is not a Float32 number (nor nan)",
                      usage_error(self, "bake", run("bake", self.dem, m9999, "--nodata",
                                                    "inf")))
        # -FLT_MAX as numpy prints it and as ESRI writes it, a hair beyond it in double (refused
        # until 2026-12-07): the bands declare -FLT_MAX, which the nodata cells hold
        lowest = float(np.finfo(np.float32).min)
        for text in ("-3.4028235e38", "-3.40282346639e+038"):
            status, _, err = run("bake", self.dem, m9999, "--radius", "900", "-q", "-d", "8",
                                 "--products", "SkyViewFactor", "--nodata", text)
            self.assertEqual(status, 0, err)
            ds = gdal.Open(m9999)
            band = ds.GetRasterBand(1)
            self.assertEqual(band.GetNoDataValue(), lowest, text)
            self.assertEqual(float(band.ReadAsArray()[5, 5]), lowest, text)
            ds = None
        self.assertIn("argument --nodata: 3.4028235677973366e38 is not a Float32 number",
                      usage_error(self, "bake", run("bake", self.dem, m9999, "--nodata",
                                                    "3.4028235677973366e38")))
        # a value some product takes is said in a warning: its cells of that value read as
        # nodata (--nodata 0 took every EdgeTruncated cell of 0 without a word)
        for nodata, products, hits in (
                ("0", "SkyViewFactor,EdgeTruncated",
                 "SkyViewFactor (0 to 1) and EdgeTruncated (0 or 1)"),
                ("45", None, "ApertureRadius (0 to 90) and PositiveOpenness (0 to 180)"),
                ("0.5", "EdgeTruncated", None), ("-100", "all", None),
                ("1.0000001", "EdgeTruncated", "EdgeTruncated (0 or 1)"),  # (GDAL's width)
                ("-90", "HorizonAngles", "HorizonAngles (-90 to 90)")):
            status, _, err = run("bake", self.dem, m9999, "--radius", "900", "-q", "-d", "8",
                                 "--nodata", nodata,
                                 *(("--products", products) if products else ()))
            self.assertEqual(status, 0, err)
            self.assertEqual(err, "aperture: warning: --nodata %s is also a value of %s: cells "
                             "of that value will read as nodata; a value no product takes, "
                             "such as -9999, or the default nan, would not\n" % (nodata, hits)
                             if hits else "", nodata)

    def test_odd_terrain(self):
        # a lat/lon DEM whose north edge is the pole (the edge comes out a rounding error
        # beyond 90 degrees), and a flat DEM at 3e37 m: products in range, the plain's exact
        rng = np.random.default_rng(7)
        polar = self.path("polar.tif")
        make_dem(polar, (rng.random((40, 40)) * 100).astype(np.float32),
                 (-180, 9, 0, 90, 0, -0.05), 4326)
        flat = self.path("flat.tif")
        make_dem(flat, np.full((20, 20), 3e37, np.float32), (500000, 30, 0, 4e6, 0, -30), 32611)
        for dem in (polar, flat):
            out = self.path("odd.tif")
            status, _, err = run("bake", dem, out, "--products", "VisibleSolidAngle,SkyViewFactor")
            self.assertEqual(status, 0, err)
            b = bands(out)[0]
            svf, vsa = b["SkyViewFactor"][0], b["VisibleSolidAngle"][0]
            self.assertTrue(np.all((svf >= 0) & (svf <= 1)), dem)
            self.assertTrue(np.all((vsa >= 0) & (vsa <= 2 * math.pi + 1e-5)), dem)
            if dem == flat:
                np.testing.assert_allclose(svf, 1.0, atol=1e-6)
                np.testing.assert_allclose(vsa, 2 * math.pi, atol=1e-5)

    def test_products_option(self):
        out = self.path("two.tif")
        status, _, err = run("bake", self.dem, out, "--products", "skyviewfactor,BentNormal")
        self.assertEqual(status, 0, err)
        self.assertEqual(list(bands(out)[0]), ["SkyViewFactor", "BentNormal_E", "BentNormal_N",
                                               "BentNormal_U"])
        # bands in the list's order (the table's order until 2026-12-07), a name twice once,
        # 'all' in the table's order where it stands
        status, _, err = run("bake", self.dem, out, "--products",
                             "EdgeTruncated,PositiveOpenness,edgetruncated", "-d", 4)
        self.assertEqual(status, 0, err)
        self.assertEqual(list(bands(out)[0]), ["EdgeTruncated", "PositiveOpenness"])
        status, _, err = run("bake", self.dem, out, "--products", "PositiveOpenness,all", "-d", 4)
        self.assertEqual(status, 0, err)
        self.assertEqual(list(bands(out)[0]), [
            "PositiveOpenness", "VisibleSolidAngle", "ApertureRadius", "BentNormal_E",
            "BentNormal_N", "BentNormal_U", "SkyViewFactor", "DiffuseSkyFactor", "EdgeTruncated",
            "HorizonAngles_az000.00", "HorizonAngles_az090.00", "HorizonAngles_az180.00",
            "HorizonAngles_az270.00"])

    def test_errors(self):
        out = self.path("x.tif")
        for args, expected in (
                (("--directions", "3"), "--directions must be within 4..360"),
                (("--directions", "361"), "--directions must be within 4..360"),
                (("--radius", "-5"), "--radius must be a positive distance"),
                (("--radius", "inf"), "(inf given; leave --radius out for an unlimited search)"),
                (("--radius", "0"), "(0 given; leave --radius out"),
                (("--refraction", "1"), "--refraction must be within [0, 1)"),
                (("--no-curvature", "--refraction", "0.13"), "--refraction bends rays over the "
                 "curved Earth; --no-curvature has none"),
                (("--products", "Slope"), "unknown product 'Slope'"),
                (("--compress", "FOO"), "unknown GeoTIFF compression 'FOO'"),
                # (the level named only when given: it said '--compress-level 1' unasked)
                (("--compress", "JPEG"), "error: --compress JPEG: GeoTIFF compression 'JPEG' "
                 "cannot store floating-point bands"),
                (("--compress-level", "13"), "outside DEFLATE's range 1-12"),
                # (ignored before without a word)
                (("--compress", "LZW", "--compress-level", "9"), "--compress-level applies to "
                 "DEFLATE, ZSTD and LZMA, which have levels, not to --compress LZW"),
                (("--compress", ""), "--compress is empty"),  # (wrote an uncompressed file)
                # (the codec named first, not its level)
                (("--compress", "FOO", "--compress-level", "5"),
                 "unknown GeoTIFF compression 'FOO'"),
                (("--exr", ""), "--exr is empty"),
                (("--srs", ""), "--srs is empty")):
            # (mistakes in the options themselves, each a usage error: these said 1 and no
            # usage, where argparse's own checks, --max-memory 0, said 2, until 2026-12-06)
            self.assertIn(expected, usage_error(self, "bake", run("bake", self.dem, out, *args)))
            self.assertFalse(os.path.exists(out))
        # a raster without any CRS: no metric cell size can be derived
        nocrs = self.path("nocrs.tif")
        ds = gdal.GetDriverByName("GTiff").Create(nocrs, 5, 5, 1, gdal.GDT_Float32)
        ds.SetGeoTransform((0, 1, 0, 5, 0, -1))
        ds = None
        status, _, err = run("bake", nocrs, out)
        self.assertEqual(status, 1)
        self.assertIn("no coordinate reference system", err)
        status, _, err = run("bake", self.dem)
        self.assertEqual(status, 2)
        self.assertEqual(usage_error(self, "bake", run("bake", self.dem, "")),
                         "aperture bake: error: the output name OUT.tif is empty\n")
        # an EXR under another name is written, with a warning
        status, _, err = run("bake", self.dem, out, "--radius", "300", "--exr", out + ".png")
        self.assertEqual(status, 0, err)
        self.assertIn("warning: %s.png is written as an OpenEXR file" % out, err)

    def test_interrupt_in_a_start_event(self):
        # A Ctrl-C that Python handles in a StartEvent observer (the bake counts its strips in
        # one) sets AbortExecute just before the executive resets it. The interrupt guard sets
        # it again at the next progress event, so the sky filter stops after its first sector
        # of 32 instead of running to the end (a strip of minutes, on a large DEM).
        import signal
        import aperture
        from aperture.cli import _abort_on_interrupt
        reader = aperture.vtkApertureDEMReader()
        reader.SetFileName(rough_dem(self.path("start-event.tif"), (200, 150), 12))
        reader.Update()
        sky = aperture.vtkApertureSkyVisibility()
        sky.SetInputConnection(reader.GetOutputPort())
        sky.SetNumberOfThreads(1)
        sky.AddObserver("StartEvent", lambda obj, _: signal.raise_signal(signal.SIGINT))
        progress = []
        sky.AddObserver("ProgressEvent", lambda obj, _: progress.append(obj.GetProgress()))
        with self.assertRaises(KeyboardInterrupt):
            with _abort_on_interrupt(sky):
                sky.Update()
        self.assertTrue(progress, "the sweep never ran")
        self.assertLessEqual(max(progress), 1.0 / 32 + 1e-9, progress)

    def test_interrupt(self):
        # Ctrl-C during the sweep stops it after the sector in progress (the filter's
        # AbortExecute, set from the signal handler that its progress observer lets run), exits
        # 130 and writes nothing. Rough 2048^2 terrain without a radius: about 10 s of CPU in the
        # sweep here, interrupted once the bake has used 2 s of CPU (imports and reading take
        # about 0.4). What the bake spends after the signal is measured in CPU time, not wall
        # time, so that a loaded machine (a parallel ctest) cannot fail it: one sector of 32 is
        # about 0.3 s of CPU on two threads, the rest of the sweep at least 6 s. The same in
        # strips (--max-memory), where the writers remove the files they had begun; and with
        # the signal taken by a worker thread, as the kernel does with a Ctrl-C when the main
        # thread blocks signals (it does while it starts a thread, which VTK 9.1's SMP backend
        # does for every parallel loop, some 100 times in this bake): Python then runs its
        # handler only when asked to check, and a VTK update holds the GIL to its end, so the
        # bake used to run to its end before exiting 130 (this test's flake, 1 run in ~10).
        # SIGTERM (`timeout`, a batch system) likewise, exiting 143: it used to end the process
        # at once, leaving the strips' outputs begun; and SIGHUP (the terminal or ssh session
        # closed), exiting 129, which until 2026-12-05 left the GeoTIFF half written under its
        # own name and OpenEXR's temporary file.
        import ctypes
        import errno
        import signal
        import time
        dem = rough_dem(self.path("interrupt.tif"), (2048, 2048), 11)
        out = self.path("interrupt-out.tif")
        tgkill = ctypes.CDLL(None, use_errno=True).tgkill  # (glibc >= 2.30)

        def worker(pid):  # a thread other than the main one that takes SIGINT, or None
            for tid in sorted(int(t) for t in os.listdir("/proc/%d/task" % pid)):
                try:
                    with open("/proc/%d/task/%d/status" % (pid, tid)) as f:
                        status = dict(line.split(":", 1) for line in f if ":" in line)
                except FileNotFoundError:
                    continue  # (a thread that ended)
                if tid != pid and not int(status["SigBlk"], 16) & 1 << (signal.SIGINT - 1):
                    return tid
            return None

        exr = self.path("interrupt-out.exr")
        strips = ["--radius", "20000", "--max-memory", "100M", "--exr", exr]
        before = sorted(os.listdir(self.tmp))  # (OpenEXR's temporary file included, after)
        two = ["--threads", "2"]  # (a worker thread on any machine)
        for options, to_worker, number, code in (
                ([], False, signal.SIGINT, 130), (two, True, signal.SIGINT, 130),
                (strips + two, True, signal.SIGINT, 130), (strips, False, signal.SIGTERM, 143),
                (strips, False, signal.SIGHUP, 129)):
            p = subprocess.Popen([APERTURE, "bake", dem, out, "-q"] + options,
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                 preexec_fn=signals_at_default)
            start = time.perf_counter()
            while cpu_seconds(p.pid) < 2.0 or (to_worker and worker(p.pid) is None):
                self.assertLess(time.perf_counter() - start, 120, "the bake never got the CPU")
                self.assertIsNone(p.poll(), "the bake ended before it was interrupted")
                time.sleep(0.02)
            sent, sent_at = cpu_seconds(p.pid), time.perf_counter()
            if to_worker:
                # (VTK 9.1's threads last one parallel loop, 0.1-1 s here: one may end between
                # the listing and the signal)
                while True:
                    tid = worker(p.pid)
                    if tid is not None and tgkill(p.pid, tid, number) == 0:
                        break
                    self.assertTrue(tid is None or ctypes.get_errno() == errno.ESRCH,
                                    os.strerror(ctypes.get_errno()))
                    self.assertIsNone(p.poll(), "the bake ended before it was interrupted")
            else:
                p.send_signal(number)
            # (the outputs are a line at most: read to the end, then reap the bake with its own
            # CPU time, which RUSAGE_CHILDREN would mix with any other child reaped meanwhile)
            stdout, stderr = p.stdout.read(), p.stderr.read()
            _, status, usage = os.wait4(p.pid, 0)
            p.returncode = os.waitstatus_to_exitcode(status)
            p.stdout.close()
            p.stderr.close()
            used = usage.ru_utime + usage.ru_stime
            what = "%s, %s%s: %.2f s of CPU when interrupted, %.2f at the end, %.2f s later" % (
                options, signal.Signals(number).name, " to a worker thread" if to_worker else "",
                sent, used, time.perf_counter() - sent_at)
            self.assertEqual(p.returncode, code, "%s; %s" % (what, stderr))
            self.assertEqual((stdout, stderr), ("", ""), what)
            self.assertEqual(sorted(os.listdir(self.tmp)), before, what)
            self.assertLess(used - sent, 1.0, what)

    def test_interrupt_keeps_earlier_outputs(self):
        # An interrupt while the outputs are being written leaves each whole: the earlier file
        # of its name as it was, or (if its writer had just finished) the new one; never a
        # temporary file. The command removed the outputs it had begun, so the earlier files
        # it had not replaced yet were deleted (the README promises that they stay), until
        # 2026-12-07. Rough 512^2 terrain, 32 directions and every product, DEFLATE's slowest
        # level (3.6 s of writing): at once (SIGTERM while the GeoTIFF's temporary file exists)
        # and in 2 strips (--max-memory; once both temporary files exist, after the first).
        import signal
        import time
        folder = self.path("interrupt-earlier")
        os.makedirs(folder)
        dem = rough_dem(os.path.join(folder, "dem.tif"), (512, 512), 13)
        out, exr = os.path.join(folder, "out.tif"), os.path.join(folder, "out.exr")
        for options, temporaries in (([], 1), (["--max-memory", "30M"], 2)):
            status, _, err = run("bake", dem, out, "--exr", exr, "-q", "-d", 4)  # (the earlier)
            self.assertEqual(status, 0, err)
            earlier = {}
            for path in (out, exr):
                with open(path, "rb") as f:
                    earlier[path] = f.read()
            p = subprocess.Popen([APERTURE, "bake", dem, out, "--exr", exr, "-q", "-d", "32",
                                  "--products", "all", "--compress-level", "9"] + options,
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                 preexec_fn=signals_at_default)
            start = time.perf_counter()
            while len([n for n in os.listdir(folder) if n.startswith(".")]) < temporaries:
                self.assertLess(time.perf_counter() - start, 120, "no temporary file appeared")
                self.assertIsNone(p.poll(), "the bake ended before it was interrupted")
                time.sleep(0.002)
            p.send_signal(signal.SIGTERM)
            stdout, stderr = p.communicate(timeout=300)
            self.assertEqual((p.returncode, stdout), (143, ""), options)
            self.assertEqual(sorted(os.listdir(folder)), ["dem.tif", "out.exr", "out.tif"])
            replaced = []
            for path in (out, exr):
                with open(path, "rb") as f:
                    if f.read() != earlier[path]:
                        replaced.append(path)
            if out in replaced:  # (its writer finished before the signal: the new GeoTIFF)
                self.assertEqual(len(bands(out)[0]), 9 + 32, options)
                # (beside the EXR of before: said)
                self.assertEqual(stderr, "aperture: note: interrupted: %s written in full; %s "
                                 "left as it was\n" % (out, exr))
            else:
                self.assertEqual(stderr, "", options)
            # (the EXR is written after the GeoTIFF at once, beside it in strips)
            self.assertNotIn(exr, replaced, options)
        # Interrupted while the EXR is written, after the new GeoTIFF: the GeoTIFF stays, and a
        # note says the two are of two bakes, or that there is no EXR (on one thread, 64
        # directions: 73 channels, about a second of EXR): each case once, in up to 6 tries
        # (one is tried again where the EXR was written before the signal took effect)
        done = set()  # (with an earlier EXR, and without)
        for attempt in range(6):
            status, _, err = run("bake", dem, out, "--exr", exr, "-q", "-d", 4)  # (the earlier)
            self.assertEqual(status, 0, err)
            with open(exr, "rb") as f:
                earlier_exr = f.read()
            if attempt % 2:
                os.remove(exr)  # (none before: "not written")
            inode = os.stat(out).st_ino
            p = subprocess.Popen([APERTURE, "bake", dem, out, "--exr", exr, "-q", "-d", "64",
                                  "--products", "all", "--threads", "1"],
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                 preexec_fn=signals_at_default)
            while p.poll() is None and not (
                    os.stat(out).st_ino != inode and
                    any(n.startswith(".") for n in os.listdir(folder))):
                time.sleep(0.002)
            p.send_signal(signal.SIGTERM)
            stdout, stderr = p.communicate(timeout=300)
            written = False
            if os.path.exists(exr):
                with open(exr, "rb") as f:
                    written = f.read() != earlier_exr
            if written:
                # (the EXR was written before the signal took effect: the bake ends 0, or 143
                # within its guard, or -15 after it; no note of an output not written)
                self.assertIn(p.returncode, (0, 143, -15), stderr)
                self.assertNotIn("not written", stderr)
                self.assertNotIn("left as it was", stderr)
                continue
            self.assertEqual((p.returncode, stdout), (143, ""), stderr)
            self.assertEqual(stderr, "aperture: note: interrupted: %s written in full; %s %s\n"
                             % (out, exr, "not written" if attempt % 2 else "left as it was"))
            self.assertEqual(len(bands(out)[0]), 9 + 64)
            if not attempt % 2:
                with open(exr, "rb") as f:
                    self.assertEqual(f.read(), earlier_exr)
            self.assertEqual(sorted(os.listdir(folder)),
                             ["dem.tif"] + ([] if attempt % 2 else ["out.exr"]) + ["out.tif"])
            done.add(attempt % 2)
            if len(done) == 2:
                break
        else:
            self.fail("the bake wrote its EXR before the signal too often (%s)" % done)

    def test_ignored_signals_stay_ignored(self):
        # A bake started with SIGINT and SIGHUP ignored (`nohup aperture bake ... &` from a
        # script: a background job ignores Ctrl-C, nohup the terminal's closing) keeps them
        # ignored through the sweep and the write, and finishes; its handlers ended it with
        # status 129 when the terminal closed, until 2026-12-06. SIGTERM, not ignored, still
        # stops it. Rough 2048^2 terrain, 8 directions: about 3 s of CPU, the signals sent
        # once the bake has used 1.2 s (imports and reading take about 0.5).
        import signal
        import time
        dem = rough_dem(self.path("ignored.tif"), (2048, 2048), 12)
        out = self.path("ignored-out.tif")

        def like_nohup_in_the_background():
            signals_at_default()
            signal.signal(signal.SIGINT, signal.SIG_IGN)
            signal.signal(signal.SIGHUP, signal.SIG_IGN)

        for sent, code in (((signal.SIGHUP, signal.SIGINT), 0), ((signal.SIGTERM,), 143)):
            p = subprocess.Popen([APERTURE, "bake", dem, out, "-q", "-d", "8"],
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                 preexec_fn=like_nohup_in_the_background)
            start = time.perf_counter()
            while cpu_seconds(p.pid) < 1.2:
                self.assertLess(time.perf_counter() - start, 120, "the bake never got the CPU")
                self.assertIsNone(p.poll(), "the bake ended before the signals")
                time.sleep(0.02)
            for number in sent:
                p.send_signal(number)
            stdout, stderr = p.communicate(timeout=300)
            self.assertEqual((p.returncode, stdout, stderr), (code, "", ""), sent)
            self.assertEqual(os.path.exists(out), code == 0, sent)
            if code == 0:
                self.assertEqual(len(bands(out)[0]), 9)
                os.remove(out)

    def control_group(self, controller, v1_limits, v2_limits):
        """A new Linux control group with limits of `controller` ("memory", "cpu"): files and
        values written in it, `v1_limits` under cgroup v1 (below this process's own group of
        that controller) or `v2_limits` under v2 (below the root group); removed at the test's
        end. Its cgroup.procs file. Skips the test where none can be made (not root, a
        container without its own cgroup namespace)."""
        name = "aperture-test-%s-%d" % (controller, os.getpid())
        own = ""
        try:
            with open("/proc/self/cgroup") as f:
                lines = [line.rstrip("\n").split(":", 2) for line in f]
        except OSError:
            lines = []
        for _, controllers, path in lines:
            if controller in controllers.split(","):
                own = path
        if os.path.isfile("/sys/fs/cgroup/memory/memory.limit_in_bytes"):  # v1
            group, limits = "/sys/fs/cgroup/%s%s/%s" % (controller, own.rstrip("/"), name), \
                v1_limits
        else:  # v2
            group, limits = "/sys/fs/cgroup/" + name, v2_limits
        try:
            os.mkdir(group)
        except OSError as e:
            self.skipTest("no control group can be made here: %s" % e)
        self.addCleanup(os.rmdir, group)
        procs = os.path.join(group, "cgroup.procs")
        try:
            for file, value in limits:
                with open(os.path.join(group, file), "w") as f:
                    f.write("%s\n" % value)
            subprocess.run(["true"], check=True, preexec_fn=lambda: self.join(procs))
        except (OSError, subprocess.SubprocessError) as e:
            self.skipTest("no %s limit can be set here: %s" % (controller, e))
        return procs

    def memory_group(self, limit):
        """control_group with a memory limit of `limit` bytes."""
        return self.control_group("memory", [("memory.limit_in_bytes", limit)],
                                  [("memory.max", limit)])

    @staticmethod
    def join(procs):
        """Move the calling process into the control group of `procs` (its cgroup.procs)."""
        with open(procs, "w") as f:
            f.write("%d\n" % os.getpid())

    def test_control_group_memory_limit(self):
        # Inside a control group with a memory limit (a container run with --memory), the
        # machine's physical memory is not what the bake may use: past the group's limit the
        # kernel ends the process. The bake plans with the lower of the two: a DEM whose bake
        # needs about 560 MiB (3000^2 cells of 30 m, the default products) is baked in strips
        # under a limit of 400 MiB. Before 2026-12-05 it was baked at once and the process
        # killed (status -9).
        procs = self.memory_group(400 << 20)

        def join():
            self.join(procs)

        dem = zeros_vrt(self.path("group.vrt"), 3000)
        out = self.path("group.tif")
        p = subprocess.run([APERTURE, "bake", dem, out, "--radius", "300", "-d", "4"],
                           capture_output=True, text=True, timeout=300, preexec_fn=join)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("for 3000 x 3000 cells", p.stdout)
        self.assertIn("strips of", p.stdout)
        self.assertIn("the whole did not fit in memory", p.stdout)
        ds = gdal.Open(out)
        self.assertEqual((ds.RasterXSize, ds.RasterYSize), (3000, 3000))
        ds = None
        # render of that DEM (a mesh of 9 million points, about 790 MiB, and drawing it) is
        # refused by name before anything is allocated, instead of the process being killed;
        # so is one of 1200^2 points, whose mesh would fit but not its drawing (the process was
        # killed while rendering, status -9), and the factor the refusal names renders in the
        # same group. (Under Xvfb, itself in the group: a few MiB.)
        xvfb = os.path.join(SOURCE, "Utilities", "with-xvfb.sh")
        small = zeros_vrt(self.path("group-small.vrt"), 1200)
        for n, grid in ((3000, dem), (1200, small)):
            p = subprocess.run([xvfb, APERTURE, "render", grid, "-o", self.path("group.png"),
                                "--lighting", "standard", "--size", "400x300"],
                               capture_output=True, text=True, timeout=300, preexec_fn=join)
            self.assertEqual(p.returncode, 1, p.stderr)
            self.assertIn("rendering a mesh of %d x %d points in a picture of 400 x 300 pixels "
                          "needs about" % (n, n), p.stderr)
            self.assertIn("under its control group's limit", p.stderr)
            factor = re.search(r"; --decimate (\d+)(?: or --size \d+x\d+)? would fit$",
                               p.stderr.strip())
            self.assertTrue(factor, p.stderr)
        self.assertIn("(the mesh 126.343 MiB, the picture 7.782 MiB, drawing them and the rest",
                      p.stderr)
        p = subprocess.run([xvfb, APERTURE, "render", small, "-o", self.path("group.png"),
                            "--lighting", "standard", "--size", "400x300", "--decimate",
                            factor.group(1)], capture_output=True, text=True, timeout=300,
                           preexec_fn=join)
        self.assertEqual(p.returncode, 0, p.stderr)
        # and a process in it says what it may use: the limit less 128 MiB for itself
        code = ("import aperture; s = aperture.vtkApertureSkyVisibility; "
                "print(s.GetUsableMemory(), s.IsMemoryGrouped())")
        p = subprocess.run([os.path.join(BUILD, "bin", "aperture-python"), "-c", code],
                           capture_output=True, text=True, timeout=120, preexec_fn=join)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual(p.stdout.split(), [str(272 << 20), "True"])

    def test_address_space_limit(self):
        # Under an address-space limit (`ulimit -v`), allocations fail instead of the kernel
        # ending the process: a render of 3000^2 points under 1.5 GiB died of an uncaught
        # std::bad_alloc in VTK's drawing (SIGABRT, status 134) until 2026-12-06, the limit
        # unknown to the memory checks. Now the memory a process may use is at most what the
        # limit leaves beside the address space it has reserved, and the render is refused by
        # name with a factor that fits, which then renders under the same limit; the bake of
        # that DEM fits in strips.
        import resource

        def limit():
            resource.setrlimit(resource.RLIMIT_AS, (1536 << 20, resource.RLIM_INFINITY))

        dem = zeros_vrt(self.path("ulimit.vrt"), 3000)
        xvfb = os.path.join(SOURCE, "Utilities", "with-xvfb.sh")
        env = dict(os.environ, LP_NUM_THREADS="2")  # (each of llvmpipe's takes address space)
        p = subprocess.run([xvfb, APERTURE, "render", dem, "-o", self.path("ulimit.png"),
                            "--lighting", "standard", "--size", "400x300"],
                           capture_output=True, text=True, timeout=300, preexec_fn=limit, env=env)
        self.assertEqual(p.returncode, 1, p.stderr)
        self.assertIn("rendering a mesh of 3000 x 3000 points in a picture of 400 x 300 pixels "
                      "needs about", p.stderr)
        self.assertIn("of memory this process may use under its address-space limit "
                      "(ulimit -v) beside the ", p.stderr)
        factor = re.search(r"; --decimate (\d+)(?: or --size \d+x\d+)? would fit$",
                           p.stderr.strip())
        self.assertTrue(factor, p.stderr)
        p = subprocess.run([xvfb, APERTURE, "render", dem, "-o", self.path("ulimit.png"),
                            "--lighting", "standard", "--size", "400x300", "--decimate",
                            factor.group(1)], capture_output=True, text=True, timeout=300,
                           preexec_fn=limit, env=env)
        self.assertEqual(p.returncode, 0, p.stderr)
        p = subprocess.run([APERTURE, "bake", dem, self.path("ulimit.tif"), "--radius", "300",
                            "-d", "32", "--products", "all"],
                           capture_output=True, text=True, timeout=300, preexec_fn=limit)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("strips of", p.stdout)

    def test_render_picture_memory(self):
        # The picture counts too: a 16384^2 render took 10 GB and, under a lower limit, aborted
        # on std::bad_alloc (status 134) until 2026-12-07. Under 2 GiB of address space a
        # 9000^2 picture with --exr is refused by name with a --size that fits, which renders
        # under the same limit. And a DEM whose mesh cannot fit is refused before it is read:
        # 46341^2 cells (8 GiB of elevations, which under this limit would have failed to
        # allocate) were read for 23 s first. (llvmpipe's threads as on this 2-core machine:
        # each takes address space, which the check counts, LP_NUM_THREADS as Mesa does.)
        import resource
        env = dict(os.environ, LP_NUM_THREADS="2")

        def limit():
            resource.setrlimit(resource.RLIMIT_AS, (2 << 30, resource.RLIM_INFINITY))

        dem = zeros_vrt(self.path("picture.vrt"), 100)
        xvfb = os.path.join(SOURCE, "Utilities", "with-xvfb.sh")
        args = [xvfb, APERTURE, "render", dem, "-o", self.path("picture.png"), "--exr",
                self.path("picture.exr"), "--sun-el", "30", "--multisamples", "0", "-q"]
        p = subprocess.run(args + ["--size", "9000x9000"], capture_output=True, text=True,
                           timeout=300, preexec_fn=limit, env=env)
        self.assertEqual(p.returncode, 1, p.stderr)
        self.assertIn("rendering a mesh of 100 x 100 points in a picture of 9000 x 9000 pixels "
                      "needs about 7.041 GiB", p.stderr)
        # (81 million pixels of 92 bytes: the framebuffers and the EXR's float read-back)
        self.assertIn("(the mesh 1015.625 KiB, the picture 6.940 GiB,", p.stderr)
        size = re.search(r"; --size (\d+)x(\d+) would fit$", p.stderr.strip())
        self.assertTrue(size, p.stderr)
        self.assertEqual(size.group(1), size.group(2))  # (the aspect kept)
        self.assertGreater(int(size.group(1)), 1000)
        p = subprocess.run(args + ["--size", "%sx%s" % size.groups()], capture_output=True,
                           text=True, timeout=300, preexec_fn=limit, env=env)
        self.assertEqual(p.returncode, 0, p.stderr)
        huge = zeros_vrt(self.path("picture-huge.vrt"), 46341)
        p = subprocess.run([xvfb, APERTURE, "render", huge, "-o", self.path("picture.png"),
                            "--lighting", "standard", "--size", "200x150"],
                           capture_output=True, text=True, timeout=120, preexec_fn=limit,
                           env=env)
        self.assertEqual(p.returncode, 1, p.stderr)
        self.assertIn("rendering a mesh of 46341 x 46341 points in a picture of 200 x 150 "
                      "pixels needs about", p.stderr)
        self.assertIn(" that OpenGL maps and the elevations take; --decimate ", p.stderr)

    def test_usable_cores(self):
        # --threads 0 (the default) is every core the process may use: the machine's, or fewer
        # where its CPU affinity (taskset, a container's --cpuset-cpus) or its control group's
        # CPU quota (--cpus) allows fewer; before 2026-12-05 it was the machine's, which in a
        # container with a quota of one CPU started a thread per host core.
        code = ("import aperture, numpy as np; from vtkmodules.vtkCommonDataModel import "
                "vtkImageData; from vtkmodules.util.numpy_support import numpy_to_vtk; "
                "s = aperture.vtkApertureSkyVisibility; im = vtkImageData(); "
                "im.SetDimensions(300, 300, 1); im.SetSpacing(30, 30, 1); "
                "im.SetOrigin(400000, 5000000, 0); a = numpy_to_vtk(np.random.default_rng(1)"
                ".uniform(0, 300, 90000).astype(np.float32), deep=1); a.SetName('Elevation'); "
                "im.GetPointData().SetScalars(a); g = aperture.vtkApertureGeoreference(); "
                "g.SetCRS('EPSG:32633'); g.AttachToImage(im); f = s(); f.SetInputData(im); "
                "f.SetMaximumDistance(600); f.Update(); "
                "print(s.GetUsableCores(), f.GetNumberOfThreadsUsed())")
        python = os.path.join(BUILD, "bin", "aperture-python")

        def cores(preexec=None):
            p = subprocess.run([python, "-c", code], capture_output=True, text=True,
                               timeout=120, preexec_fn=preexec)
            self.assertEqual(p.returncode, 0, p.stderr)
            return [int(v) for v in p.stdout.split()]

        usable, used = cores()
        self.assertLessEqual(used, usable)
        self.assertLessEqual(usable, len(os.sched_getaffinity(0)))
        first = min(os.sched_getaffinity(0))
        self.assertEqual(cores(lambda: os.sched_setaffinity(0, {first})), [1, 1])
        if usable < 2:
            self.skipTest("one core here: a CPU quota could not lower the count")
        procs = self.control_group("cpu", [("cpu.cfs_period_us", 100000),
                                           ("cpu.cfs_quota_us", 100000)],
                                   [("cpu.max", "100000 100000")])
        self.assertEqual(cores(lambda: self.join(procs)), [1, 1])

    def test_render_memory_held_once(self):
        # Under an address-space limit the usable memory is what the limit leaves beside all
        # the process has mapped: what it holds is in that already. Until 2026-12-06 render's
        # check subtracted its resident memory again (150 MB and the DEM, refusing renders that
        # fit). A process said to hold a PiB renders 10 x 10 points under the limit, and is
        # refused without it, naming what it holds.
        import resource

        def limit():
            resource.setrlimit(resource.RLIMIT_AS, (4 << 30, resource.RLIM_INFINITY))
        script = ("import argparse\n"
                  "from aperture import cli\n"
                  "from aperture.errors import ApertureError\n"
                  "cli._resident_bytes = lambda: 1 << 50\n"
                  "try:\n"
                  "    cli._check_render_memory(argparse.Namespace(decimate=1, size=(16, 16), "
                  "multisamples=0, exr=None), 10, 10, False, False, 0)\n"
                  "    print('fits')\n"
                  "except ApertureError as e:\n"
                  "    print(e)\n")
        python = os.path.join(BUILD, "bin", "aperture-python")
        p = subprocess.run([python, "-c", script], capture_output=True, text=True, timeout=120,
                           preexec_fn=limit)
        self.assertEqual((p.returncode, p.stdout), (0, "fits\n"), p.stderr)
        p = subprocess.run([python, "-c", script], capture_output=True, text=True, timeout=120)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertTrue(p.stdout.startswith("rendering a mesh of 10 x 10 points in a picture of "
                                            "16 x 16 pixels needs about "), p.stdout)
        self.assertTrue(p.stdout.strip().endswith(
            " beside the 1.000 PiB that this process holds and the elevations take"), p.stdout)

    def test_out_of_memory(self):
        # A DEM that fits the machine's memory but not the process's address space (ulimit -v):
        # a one-line error naming the size and what to do, not an abort on std::bad_alloc
        # (the reader, and the terrain mesh behind a reader that succeeded, used to abort).
        import resource
        if usable_memory()[0] < 8 << 30:
            self.skipTest("the reader refuses 3.4 GiB on this machine before allocating")
        limit = 3 << 30

        def capped():
            resource.setrlimit(resource.RLIMIT_AS, (limit, limit))

        big = zeros_vrt(self.path("big.vrt"), 30000)  # 3.35 GiB of elevations
        out = self.path("big-out.tif")
        # (bake refuses this DEM before reading it on machines with less than 50 GiB: below;
        # info reads it in strips of 256 MiB, unless --max-memory allows more)
        p = subprocess.run([APERTURE, "info", big, "--max-memory", "4G"], capture_output=True,
                           text=True, timeout=300, preexec_fn=capped)
        self.assertEqual(p.returncode, 1, p.stderr)
        self.assertEqual(len(p.stderr.strip().splitlines()), 1, p.stderr)
        self.assertIn("out of memory reading 30000 x 30000 cells of '%s' (the elevations "
                      "alone take 3.353 GiB as float32); read a part with --srcwin, or use "
                      "--decimate or --overview" % big, p.stderr)
        # A bake that needs more than the machine's physical memory is refused before the DEM
        # is read (under Linux's overcommit it would be killed mid-sweep, not fail to
        # allocate): 30000^2 cells with HorizonAngles at 360 directions need 1498 bytes a cell
        # in the sky filter (1440 of horizons, 37 of the other products with EdgeTruncated as
        # float beside its byte flags, its float copy 4 and the sweep's state 17):
        # 1.3482e12 bytes = 1.226 TiB, beside the elevations' 4 bytes a cell, 3.353 GiB. In
        # strips of 256 rows (no radius: each reads the whole DEM) 21 bytes a cell of the DEM
        # and 1481 of the strip's: 3.0274e10 bytes = 28.195 GiB.
        memory, owner = usable_memory()
        if memory > 3.0274e10 + 4.0 * 30000 ** 2:
            self.skipTest("this machine could bake it in strips")
        left = human_bytes(memory - 4.0 * 30000 ** 2)
        p = subprocess.run([APERTURE, "bake", big, out, "-d", "360", "--products", "all"],
                           capture_output=True, text=True, timeout=300)
        self.assertEqual(p.returncode, 1, p.stderr)
        self.assertEqual(p.stderr.strip(), "aperture: error: a 30000 x 30000 DEM with these "
                         "products needs about 1.226 TiB (HorizonAngles take 4 bytes per cell "
                         "and direction), more than the %s of memory %s beside the DEM's "
                         "3.353 GiB, and strips of 256 rows (the GeoTIFF's tiles) would not fit "
                         "either: the products of 30000 x 256 cells, with the 30000 x 30000 "
                         "cells of DEM around them, need about 28.195 GiB (HorizonAngles take 4 "
                         "bytes per cell and direction), more than the %s of memory %s beside "
                         "the DEM's 3.353 GiB; bake a window with --srcwin and a --radius (only "
                         "the DEM within the radius around it is read), use --decimate or "
                         "--overview, or bake fewer --products" % (left, owner, left, owner))
        self.assertFalse(os.path.exists(out))
        # 12000^2: the reader's 0.54 GiB fits, the mesh's points, normals and triangles do not:
        # refused before anything is allocated, the address-space limit known (since
        # 2026-12-06), and past that check (a MemoryLimit of a TiB) the allocation that fails
        # is named
        script = ("import aperture, sys\n"
                  "from aperture.errors import Watcher, ApertureError\n"
                  "w = Watcher()\n"
                  "r = w.watch(aperture.vtkApertureDEMReader())\n"
                  "r.SetFileName(sys.argv[1])\n"
                  "m = w.watch(aperture.vtkApertureTerrainMesh())\n"
                  "m.SetMemoryLimit(int(sys.argv[2]))\n"
                  "m.SetInputConnection(r.GetOutputPort())\n"
                  "try:\n"
                  "    w.update(m)\n"
                  "except ApertureError as e:\n"
                  "    print(e, m.GetOutput().GetNumberOfPoints())\n")
        python = os.path.join(BUILD, "bin", "aperture-python")
        mesh = zeros_vrt(self.path("mesh.vrt"), 12000)
        p = subprocess.run([python, "-c", script, mesh, "0"], capture_output=True, text=True,
                           timeout=300, preexec_fn=capped)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertTrue(p.stdout.startswith("a mesh of 12000 x 12000 points needs about 12.338 "
                                            "GiB, more than the "), p.stdout)
        self.assertTrue(p.stdout.strip().endswith(
            " of memory this process may use under its address-space limit (ulimit -v); "
            "decimate the DEM 0"), p.stdout)
        p = subprocess.run([python, "-c", script, mesh, str(1 << 40)], capture_output=True,
                           text=True, timeout=300, preexec_fn=capped)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("out of memory: a mesh of 12000 x 12000 points needs about", p.stdout)
        self.assertTrue(p.stdout.strip().endswith("MiB; decimate the DEM 0"), p.stdout)

    def test_full_disk(self):
        # A disk that fills up while an output is written: GDAL says only "Write error at
        # scanline ..."; the message says the disk is full, and no partial file is left; at
        # once and in strips (--max-memory), where the GeoTIFF writer keeps GDAL's reason for
        # EndStrips (the message was "a strip failed; EndStrips() removes the file"). With the
        # EXR on the full disk, the message says what became of the GeoTIFF: written in full
        # (at once, before the EXR) or removed unfinished (in strips, written beside it). A
        # 256 KiB tmpfs in a mount namespace of its own (needs root: skipped otherwise).
        folder = self.path("full")
        os.makedirs(folder)
        dem = rough_dem(self.path("full-dem.tif"), (600, 300), 7)
        full_tif, full_exr = os.path.join(folder, "out.tif"), os.path.join(folder, "out.exr")
        tif = self.path("full-beside.tif")
        strips = ["--max-memory", "6M"]
        cases = [  # (outputs, options, what the message ends with, the GeoTIFF beside is left)
            ([full_tif], [], " (the disk is full)", None),
            ([full_tif], strips, " (the disk is full)", None),
            ([tif, "--exr", full_exr], [], " (%s was written in full)" % tif, True),
            ([tif, "--exr", full_exr], strips, " (the unfinished %s was discarded)" % tif, False)]
        for outputs, options, ending, beside in cases:
            if os.path.exists(tif):
                os.remove(tif)
            p = self.bake_on_tmpfs(folder, "size=256k", dem, *outputs, "-d", "8", "--radius",
                                   "600", "-q", *options)
            label = "%s %s: %s" % (outputs, options, p.stderr)
            self.assertEqual(p.returncode, 1, label)
            self.assertIn("left: \n", p.stdout)  # (the folder, seen before the tmpfs goes)
            if beside is None:
                self.assertIn("aperture: error: writing %s: GDAL failed writing '%s': "
                              % (full_tif, full_tif), p.stderr)
            else:
                self.assertIn("aperture: error: writing %s: OpenEXR failed writing '%s': "
                              % (full_exr, full_exr), p.stderr)
                self.assertIn("No space left on device", p.stderr)
                self.assertEqual(os.path.exists(tif), beside, label)
            if beside:
                ds = gdal.Open(tif)  # (whole: every band, to the last row)
                self.assertEqual(ds.RasterCount, 9)
                self.assertIsNotNone(ds.GetRasterBand(9).ReadAsArray())
                ds = None
            self.assertTrue(p.stderr.strip().endswith(ending), label)
            self.assertEqual(len(p.stderr.strip().splitlines()), 1, label)

    def test_unwritable_outputs(self):
        # An output folder that takes no new files (read-only, no permission) is refused before
        # the DEM is read, not after a sweep of hours: a read-only tmpfs in a mount namespace of
        # our own (needs root: skipped otherwise), for the GeoTIFF and for the EXR (the
        # GeoTIFF beside it not begun). An existing read-only file likewise (GDAL cannot
        # replace it), by a process without root's override of file permissions. And an
        # output that is no file: a folder (the EXR's message was "Unable to rename temporary
        # file"), a pipe, and as root a copy of /dev/null's node (a bake to /dev/null as root
        # ran its sweep, then GDAL failed writing it and the writer removed /dev/null).
        import stat
        tif = self.path("unwritable-beside.tif")
        specials = [(self.tmp, "a folder", stat.S_ISDIR)]
        os.mkfifo(self.path("pipe.tif"))
        specials.append((self.path("pipe.tif"), "a pipe", stat.S_ISFIFO))
        if os.geteuid() == 0:
            os.mknod(self.path("null.tif"), stat.S_IFCHR | 0o666, os.makedev(1, 3))
            specials.append((self.path("null.tif"), "a device", stat.S_ISCHR))
        for special, kind, is_kind in specials:
            for outputs, name in (([special], "OUT.tif"), ([tif, "--exr", special], "--exr")):
                status, stdout, err = run("bake", self.dem, *outputs)
                self.assertEqual((status, stdout), (1, ""), err)
                self.assertEqual(err, "aperture: error: cannot write %s %s: it is %s, not a "
                                 "file\n" % (name, special, kind))
                self.assertFalse(os.path.exists(tif))
                self.assertTrue(is_kind(os.stat(special).st_mode))
        # A name the folder cannot take (too long here; characters a FAT stick refuses), found
        # before the DEM is read, not by the writer after the sweep. Nothing is left. A name
        # just as long as the folder takes is written, the EXR too: its writer's temporary file
        # has a short name of its own (OpenEXR's, "tmp.<pid><name>", was too long for it, and
        # such a name was refused until 2026-12-06).
        longest = os.pathconf(self.tmp, "PC_NAME_MAX")
        before = sorted(os.listdir(self.tmp))
        long_tif = self.path("t" * (longest - 3) + ".tif")  # (one character too many)
        long_exr = self.path("e" * (longest - 3) + ".exr")
        for outputs, name, path in (([long_tif], "OUT.tif", long_tif),
                                    ([tif, "--exr", long_exr], "--exr", long_exr)):
            status, stdout, err = run("bake", self.dem, *outputs)
            self.assertEqual((status, stdout), (1, ""), err)
            self.assertEqual(err, "aperture: error: cannot write %s %s: File name too long\n"
                             % (name, path))
            self.assertEqual(sorted(os.listdir(self.tmp)), before)
        exr = self.path("e" * (longest - 4) + ".exr")
        status, stdout, err = run("bake", self.dem, tif, "--exr", exr, "--radius", "300")
        self.assertEqual((status, err), (0, ""))
        self.assertEqual(sorted(os.listdir(self.tmp)), sorted(before + [os.path.basename(tif),
                                                                        os.path.basename(exr)]))
        os.remove(tif)
        os.remove(exr)
        folder = self.path("read-only")
        os.makedirs(folder)
        for outputs, name, path in (([os.path.join(folder, "out.tif")], "OUT.tif",
                                     os.path.join(folder, "out.tif")),
                                    ([tif, "--exr", os.path.join(folder, "out.exr")], "--exr",
                                     os.path.join(folder, "out.exr"))):
            p = self.bake_on_tmpfs(folder, "size=64k,ro", self.dem, *outputs)
            self.assertEqual((p.returncode, p.stdout), (1, "left: \n"), p.stderr)
            self.assertEqual(p.stderr, "aperture: error: cannot write %s %s: the folder does not "
                             "take new files (Read-only file system)\n" % (name, path))
            self.assertFalse(os.path.exists(tif))
        # (root runs the bake without the capabilities that let it write read-only files)
        locked = self.path("locked.tif")
        with open(locked, "w") as f:
            f.write("keep")
        os.chmod(locked, 0o444)
        p = subprocess.run(unprivileged(self, locked, "write") +
                           [APERTURE, "bake", self.dem, locked],
                           capture_output=True, text=True, timeout=300)
        self.assertEqual(p.returncode, 1, p.stderr)
        self.assertEqual(p.stderr, "aperture: error: cannot write OUT.tif %s: the file "
                         "exists and is read-only\n" % locked)
        with open(locked) as f:
            self.assertEqual(f.read(), "keep")

    def test_writers_keep_read_only_files(self):
        # The writers write aside and rename into place, which a read-only file's folder
        # allows: they replaced such a file, which an open for writing refuses (the command
        # line refused it, the Python API did not), until 2026-12-07. A child without root's
        # power over permissions writes the DEM with each writer over a read-only file, and
        # through a symbolic link to one.
        script = """if True:
            import sys
            import aperture
            from vtkmodules.util.misc import calldata_type
            from vtkmodules.util.vtkConstants import VTK_STRING

            @calldata_type(VTK_STRING)
            def on_error(obj, event, message):
                print(message, file=sys.stderr)
            reader = aperture.vtkApertureDEMReader()
            reader.SetFileName(aperture.default_dem())
            for writer in (aperture.vtkApertureDEMWriter(), aperture.vtkApertureEXRWriter()):
                writer.AddObserver("ErrorEvent", on_error)
                for path in sys.argv[1:]:
                    writer.SetInputConnection(reader.GetOutputPort())
                    writer.SetFileName(path)
                    print(writer.Write(), flush=True)
            """
        folder = self.path("read-only-files")
        os.makedirs(folder)
        paths = []
        for name in ("locked.tif", "locked.exr"):
            paths.append(os.path.join(folder, name))
            with open(paths[-1], "w") as f:
                f.write("keep")
            os.chmod(paths[-1], 0o444)
        link = os.path.join(folder, "link.tif")
        os.symlink("locked.tif", link)
        p = subprocess.run(unprivileged(self, paths[0], "write") +
                           [os.path.join(BUILD, "bin", "aperture-python"), "-c", script,
                            paths[0], link, paths[1]],
                           capture_output=True, text=True, timeout=300)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual(p.stdout.split(), ["0"] * 6, p.stderr)
        for path in paths + [link]:
            self.assertIn("cannot write '%s': the file exists and is read-only" % path, p.stderr)
        for path in paths:
            with open(path) as f:
                self.assertEqual(f.read(), "keep")
        self.assertEqual(sorted(os.listdir(folder)), ["link.tif", "locked.exr", "locked.tif"])

    def test_threads_refused(self):
        # When the system refuses threads (here: each would get an 8 GiB stack, in 4 GiB of
        # address space), the sky filter says so instead of terminating the process
        # (std::thread throws); --threads 1 starts none and bakes.
        if (os.cpu_count() or 1) < 2:
            self.skipTest("one core: no threads to refuse")
        import resource

        def limits():
            resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))
            resource.setrlimit(resource.RLIMIT_STACK, (8 << 30, 8 << 30))
        out = self.path("threads.tif")
        for threads in (2, 1):
            p = subprocess.run([APERTURE, "bake", self.dem, out, "-d", "8", "--threads",
                                str(threads)], preexec_fn=limits, capture_output=True,
                               text=True, timeout=300)
            if threads == 2:
                self.assertEqual(p.returncode, 1, p.stderr)
                self.assertTrue(p.stderr.startswith(
                    "aperture: error: bake: could not start 2 threads ("), p.stderr)
                self.assertTrue(p.stderr.strip().endswith(
                    "); use fewer --threads (1 starts none)"), p.stderr)
                self.assertFalse(os.path.exists(out))
            else:
                self.assertEqual(p.returncode, 0, p.stderr)
                self.assertTrue(os.path.exists(out))
        # the EXR writer alike (the bake's sky filter fails first: the writer alone)
        exr = self.path("threads.exr")
        script = ("import aperture\n"
                  "from vtkmodules.vtkImagingCore import vtkRTAnalyticSource\n"
                  "s = vtkRTAnalyticSource()\n"
                  "s.SetWholeExtent(0, 63, 0, 63, 0, 0)\n"
                  "w = aperture.vtkApertureEXRWriter()\n"
                  "w.SetInputConnection(s.GetOutputPort())\n"
                  "w.SetFileName(%r)\n"
                  "w.SetNumberOfThreads(2)\n"
                  "print('written', w.Write())\n" % exr)
        p = subprocess.run([os.path.join(BUILD, "bin", "aperture-python"), "-c", script],
                           preexec_fn=limits, capture_output=True, text=True, timeout=300)
        self.assertIn("written 0", p.stdout, p.stderr)
        self.assertIn("writing '%s': could not start 2 threads (" % exr, p.stderr)
        self.assertIn("); use fewer threads (NumberOfThreads; 1 starts none)", p.stderr)
        self.assertFalse(os.path.exists(exr))

    def test_writes_through_links(self):
        # An output that is a symbolic link (latest.tif -> frames/0042.tif) is written at its
        # target, the link kept, and a file replaced keeps its permissions. Until 2026-12-06
        # both writers replaced the link with a file of their own, leaving the target as it
        # was, and reset a private (0600) file to 0644.
        frames = self.path("frames")
        os.makedirs(frames)
        names = {"tif": "OUT.tif", "exr": "--exr"}
        for ext in names:
            target = os.path.join(frames, "0042." + ext)
            with open(target, "wb") as f:
                f.write(b"an older frame")
            os.chmod(target, 0o600)
            os.symlink(os.path.join("frames", "0042." + ext), self.path("latest." + ext))
        os.symlink(os.path.join("frames", "0043.exr"), self.path("next.exr"))  # (dangling)
        status, _, err = run("bake", self.dem, self.path("latest.tif"), "--exr",
                             self.path("latest.exr"), "--products", "SkyViewFactor", "-q")
        self.assertEqual(status, 0, err)
        for ext in names:
            self.assertTrue(os.path.islink(self.path("latest." + ext)), ext)
            target = os.path.join(frames, "0042." + ext)
            self.assertEqual(os.stat(target).st_mode & 0o777, 0o600, ext)
            with open(target, "rb") as f:
                self.assertNotEqual(f.read(14), b"an older frame", ext)
        ds = gdal.Open(os.path.join(frames, "0042.tif"))
        self.assertEqual(ds.GetRasterBand(1).GetDescription(), "SkyViewFactor")
        ds = None
        status, _, err = run("bake", self.dem, self.path("o.tif"), "--exr",
                             self.path("next.exr"), "--products", "SkyViewFactor", "-q")
        self.assertEqual(status, 0, err)
        self.assertTrue(os.path.islink(self.path("next.exr")))
        self.assertTrue(os.path.isfile(os.path.join(frames, "0043.exr")))
        self.assertEqual(sorted(os.listdir(frames)), ["0042.exr", "0042.tif", "0043.exr"])

    def test_south_up(self):
        # A south-up DEM (positive pixel height, its first row the southern one) gives the
        # products of the same DEM north-up, written north-up with a note saying so (it was
        # silent, and the README said "in the DEM's own grid").
        north = rough_dem(self.path("north-up.tif"), (120, 90), 21)
        ds = gdal.Open(north)
        z = ds.GetRasterBand(1).ReadAsArray()
        gt = ds.GetGeoTransform()
        ds = None
        south = make_dem(self.path("south-up.tif"), z[::-1],
                         (gt[0], gt[1], 0, gt[3] + gt[5] * z.shape[0], 0, -gt[5]), 32611)
        results = []
        for dem in (north, south):
            out = dem[:-4] + "-out.tif"
            status, _, err = run("bake", dem, out, "-d", "8", "--products", "SkyViewFactor")
            self.assertEqual(status, 0, err)
            results.append((bands(out), err))
        (north_bands, _, north_gt, _), north_err = results[0]
        (south_bands, _, south_gt, _), south_err = results[1]
        self.assertEqual(south_gt, north_gt)
        self.assertTrue(np.array_equal(south_bands["SkyViewFactor"][0],
                                       north_bands["SkyViewFactor"][0]))
        self.assertNotIn("south-up", north_err)
        self.assertIn("aperture: note: the DEM is south-up (its first row is its southern one); "
                      "%s is written north-up: the same cells and CRS, its rows in the reverse "
                      "order\n" % self.path("south-up-out.tif"), south_err)
        status, _, err = run("bake", south, self.path("south-up-out.tif"), "-d", "8", "-q")
        self.assertEqual((status, err), (0, ""))

    def test_replaces_sidecars(self):
        # A bake over an earlier output removes that file's GDAL sidecars, as GDAL's own Create
        # does: its overviews (.ovr, the old values QGIS shows when zoomed out), its
        # .aux.xml (statistics of the old values, and a georeference GDAL prefers to the
        # file's) and an external mask (.msk); the EXR's .aux.xml too (GDAL built with its EXR
        # driver reads it). Until 2026-12-06 they stayed and GDAL read them with the new file.
        # One that cannot be removed (here a folder) is named in a warning.
        out, exr = self.path("sidecars.tif"), self.path("sidecars.exr")
        status, _, err = run("bake", self.dem, out, "--products", "ApertureRadius", "-q")
        self.assertEqual(status, 0, err)
        ds = gdal.Open(out)
        self.assertEqual(ds.BuildOverviews("AVERAGE", [2, 4]), 0)  # (read-only: out.tif.ovr)
        ds.GetRasterBand(1).ComputeStatistics(False)
        ds = None
        with open(out + ".aux.xml", "a"):
            pass
        with open(exr + ".aux.xml", "w") as f:
            f.write("<PAMDataset><GeoTransform>0, 1, 0, 0, 0, -1</GeoTransform></PAMDataset>\n")
        for name in (out + ".ovr", out + ".aux.xml"):
            self.assertTrue(os.path.isfile(name), name)
        with open(out + ".msk", "w") as f:
            f.write("an old mask")
        status, _, err = run("bake", self.dem, out, "--exr", exr, "--products", "SkyViewFactor",
                             "-q")
        self.assertEqual((status, err), (0, ""))
        self.assertEqual(sorted(n for n in os.listdir(self.tmp) if n.startswith("sidecars")),
                         ["sidecars.exr", "sidecars.tif"])
        ds = gdal.Open(out)
        band = ds.GetRasterBand(1)
        self.assertEqual((band.GetDescription(), band.GetOverviewCount()), ("SkyViewFactor", 0))
        self.assertIsNone(band.GetMetadataItem("STATISTICS_MAXIMUM"))
        ds = None
        os.mkdir(out + ".ovr")
        status, _, err = run("bake", self.dem, out, "--products", "SkyViewFactor", "-q")
        self.assertEqual(status, 0, err)
        self.assertEqual(err, "aperture: warning: wrote '%s', but the previous file's sidecar "
                         "'%s.ovr' stays beside the new one (Is a directory), and GDAL reads it "
                         "with it: remove it\n" % (out, out))
        os.rmdir(out + ".ovr")

    def test_does_not_overwrite(self):
        # An output that is the input DEM, or two outputs in one file, are refused before any
        # work: the EXR would silently replace the GeoTIFF, the bands the DEM.
        dem = self.path("mine.tif")
        shutil.copy(self.dem, dem)
        with open(dem, "rb") as f:
            before = f.read()
        link = self.path("link.tif")
        os.link(dem, link)
        same = self.path("same.tif")
        ovr = self.path("o.tif.ovr")  # (a DEM named as o.tif's overviews, which a bake removes)
        shutil.copy(self.dem, ovr)
        os.symlink("o.tif", self.path("to-o.tif"))
        for args, expected in (
                ((ovr, self.path("o.tif")), "OUT.tif %s: writing it removes %s (GDAL's sidecar "
                 "of a file of that name), which is the DEM" % (self.path("o.tif"), ovr)),
                # (through a link to o.tif, and one output's sidecar being the other: both
                # were removed after the bake until the review of f445182)
                ((ovr, self.path("to-o.tif")), "OUT.tif %s: writing it removes %s (GDAL's "
                 "sidecar of a file of that name), which is the DEM" % (self.path("to-o.tif"),
                                                                        ovr)),
                ((dem, self.path("b.exr.msk"), "--exr", self.path("b.exr")), "--exr %s: writing "
                 "it removes %s (GDAL's sidecar of a file of that name), which is OUT.tif %s" % (
                     self.path("b.exr"), self.path("b.exr.msk"), self.path("b.exr.msk"))),
                ((dem, dem), "OUT.tif %s is the same file as the DEM" % dem),
                ((dem, link), "OUT.tif %s is the same file as the DEM" % link),
                ((dem, os.path.join(self.tmp, ".", "mine.tif")), "is the same file as the DEM"),
                ((dem, same, "--exr", same), "--exr %s is the same file as OUT.tif" % same),
                ((dem, same, "--exr", dem), "--exr %s is the same file as the DEM" % dem)):
            status, _, err = run("bake", *args)
            self.assertEqual(status, 1, err)
            self.assertEqual(len(err.strip().splitlines()), 1, err)
            self.assertIn(expected, err)
        # ... nor one of the files GDAL reads for the DEM: a VRT's source (in strips, each
        # strip read the source again after the first was written over it)
        vrt = self.path("mine.vrt")
        gdal.BuildVRT(vrt, [dem]).FlushCache()
        for args, expected in (
                ((vrt, dem, "--max-memory", "30M"),
                 "OUT.tif %s is one of the files the DEM %s reads (%s)" % (dem, vrt, dem)),
                ((vrt, same, "--exr", link), "--exr %s is one of the files the DEM" % link)):
            status, _, err = run("bake", *args)
            self.assertEqual(status, 1, err)
            self.assertEqual(len(err.strip().splitlines()), 1, err)
            self.assertIn(expected, err)
        # ... nor the archive or compressed file a GDAL virtual path reads it from (until
        # 2026-12-06 the bake replaced the .zip the DEM was in by a GeoTIFF)
        import gzip
        import zipfile
        archive, packed = self.path("dems.zip"), self.path("mine.tif.gz")
        with zipfile.ZipFile(archive, "w") as z:
            z.write(dem, "in/mine.tif")
        with open(packed, "wb") as f:
            f.write(gzip.compress(before))
        saved = {}
        for path in (archive, packed):
            with open(path, "rb") as f:
                saved[path] = f.read()
        for args, expected in (
                (("/vsizip/%s/in/mine.tif" % archive, archive),
                 "OUT.tif %s is the file the DEM (/vsizip/%s/in/mine.tif) is read from"
                 % (archive, archive)),
                (("/vsizip/{%s}/in/mine.tif" % archive, same, "--exr", archive),
                 "--exr %s is the file the DEM" % archive),
                (("/vsigzip/" + packed, packed),
                 "OUT.tif %s is the file the DEM (/vsigzip/%s) is read from" % (packed, packed))):
            status, _, err = run("bake", *args)
            self.assertEqual(status, 1, err)
            self.assertEqual(len(err.strip().splitlines()), 1, err)
            self.assertIn(expected, err)
        for path, content in saved.items():
            with open(path, "rb") as f:
                self.assertEqual(f.read(), content, path)
        with open(dem, "rb") as f:
            self.assertEqual(f.read(), before)
        self.assertFalse(os.path.exists(same))
        missing = os.path.join(self.tmp, "no-such-folder")
        for args in ((dem, os.path.join(missing, "o.tif")),
                     (dem, same, "--exr", os.path.join(missing, "o.exr"))):
            status, _, err = run("bake", *args)
            self.assertEqual(status, 1, err)
            self.assertIn("the output folder %s does not exist" % missing, err)
        # through a symbolic link to a missing folder: before the bake (after it, naming the
        # writer's temporary file, until 2026-12-07), and nothing made
        dangling = self.path("dangling.tif")
        os.symlink(os.path.join("no-such-folder", "o.tif"), dangling)
        for args in ((dem, dangling), (dem, same, "--exr", dangling)):
            status, stdout, err = run("bake", *args)
            self.assertEqual((status, stdout), (1, ""), err)
            self.assertEqual(err, "aperture: error: the output folder %s does not exist (%s is "
                             "a symbolic link to %s)\n" % (missing, dangling,
                                                           os.path.join(missing, "o.tif")))
        self.assertFalse(os.path.exists(same))
        os.remove(dangling)
        # the main output is always a GeoTIFF: an .exr name is refused, others get a warning
        self.assertIn("p.exr is written as a GeoTIFF; name it .tif and give --exr",
                      usage_error(self, "bake", run("bake", dem, self.path("p.exr"))))
        self.assertFalse(os.path.exists(self.path("p.exr")))
        status, _, err = run("bake", dem, self.path("p.img"), "--products", "SkyViewFactor")
        self.assertEqual(status, 0, err)
        self.assertIn("warning: %s is written as a GeoTIFF" % self.path("p.img"), err)
        ds = gdal.Open(self.path("p.img"))
        self.assertEqual(ds.GetDriver().ShortName, "GTiff")
        ds = None

    def test_progress_on_a_terminal(self):
        # As gdaldem: GDAL's progress line on stderr when it is a terminal, none with -q or
        # when it is not (every other test here reads stderr through a pipe: nothing there).
        from terminal import run_with_terminal_stderr
        out = self.path("progress.tif")
        for quiet in (False, True):
            p, seen = run_with_terminal_stderr([APERTURE, "bake", self.dem, out] +
                                               (["-q"] if quiet else []), timeout=300)
            self.assertEqual(p.returncode, 0)
            # (-q also drops the summary line, as gdaldem -q its non-error output)
            self.assertEqual(p.stdout.startswith("wrote %s: " % out), not quiet, p.stdout)
            self.assertEqual(p.stdout == "", quiet, p.stdout)
            expected = "" if quiet else \
                "0...10...20...30...40...50...60...70...80...90...100 - done.\r\n"
            self.assertEqual(seen.decode(), expected)

    def test_progress_follows_every_step(self):
        # The display follows each step's own progress, weighted by its rough cost: the read,
        # the sweep and every output's write, so it keeps moving while large outputs are
        # written (it stood at 95 % through the whole write before, which with every
        # HorizonAngles band of a 3601^2 DEM took 13 of 25 s). Run in this process, the
        # terminal's display replaced by a recorder that notes which step each call came from
        # (the Python frame running it: _read for the reader, Watcher.update for the sky
        # filter, the writers' otherwise), at once and in 3 strips (see test_strips), with
        # every product at 8 directions (16 GeoTIFF bands) and an EXR.
        import contextlib
        import io
        from aperture import cli
        dem = rough_dem(self.path("progress-steps.tif"), (700, 150), 8)
        options = ["--radius", "1500", "-d", "8", "--products", "all"]
        calls = []

        class Recorder:
            open = False

            def __init__(self, stream):
                pass

            def __call__(self, fraction):
                names, frame = set(), sys._getframe()
                while frame:
                    names.add(frame.f_code.co_name)
                    frame = frame.f_back
                calls.append(("read" if "_read" in names else
                              "sky" if "update" in names else "write", fraction))

        class Terminal:
            def isatty(self):
                return True

            def __getattr__(self, name):
                return getattr(sys.__stderr__, name)

        display, stderr = cli._TermProgress, sys.stderr
        cli._TermProgress, sys.stderr = Recorder, Terminal()
        try:
            for strips in ([], ["--max-memory", "5M"]):
                del calls[:]
                out = self.path("progress-steps-%d.tif" % len(strips))
                with contextlib.redirect_stdout(io.StringIO()) as stdout:
                    status = cli.main(["bake", dem, out, "--exr", out + ".exr"] + options
                                      + strips)
                self.assertEqual(status, 0)
                self.assertIn("wrote", stdout.getvalue())
                fractions = [f for _, f in calls]
                self.assertEqual((fractions[0], fractions[-1]), (0.0, 1.0))
                self.assertEqual(fractions, sorted(fractions))
                steps = [step for step, _ in calls[1:]]  # (after the display's start)
                written = [f for step, f in calls if step == "write"]
                swept = [f for step, f in calls if step == "sky"]
                # the writes report as they go (each band, each batch of EXR chunks), not once
                self.assertGreaterEqual(len(set(written)), 10, calls)
                if not strips:
                    # read, swept, written, in that order; the writes move the display by a
                    # large share (16 bands and 16 channels against 8 directions)
                    self.assertIn("read", steps)
                    self.assertEqual(steps, sorted(steps, key=["read", "sky", "write"].index))
                    self.assertGreater(written[-1] - swept[-1], 0.5, calls)
                else:
                    # strip by strip: each strip's writes before the next strip's sweep
                    self.assertLess(written[0], swept[-1], calls)
                    self.assertGreaterEqual(steps.count("sky"), 3 * 8)
        finally:
            cli._TermProgress, sys.stderr = display, stderr

    def test_mesh_carries_products(self):
        import aperture
        from vtkmodules.util.numpy_support import vtk_to_numpy
        reader = aperture.vtkApertureDEMReader()
        reader.SetFileName(self.dem)
        skyv = aperture.vtkApertureSkyVisibility()
        skyv.SetInputConnection(reader.GetOutputPort())
        mesh = aperture.vtkApertureTerrainMesh()
        mesh.SetInputConnection(skyv.GetOutputPort())
        mesh.Update()
        out = mesh.GetOutput()
        for name in ("SkyViewFactor", "ApertureRadius"):
            np.testing.assert_array_equal(
                vtk_to_numpy(out.GetPointData().GetArray(name)),
                vtk_to_numpy(skyv.GetOutput().GetPointData().GetArray(name)))
        # BentNormal leaves each point's local East-North-Up for the mesh's frame (exact
        # rotations: TestApertureTerrainMesh): still unit vectors, turned by about the angle
        # between the two frames' verticals, distance / Earth radius (a little more with the
        # turn about the vertical), the least at the centre.
        local = vtk_to_numpy(skyv.GetOutput().GetPointData().GetArray("BentNormal"))
        frame = vtk_to_numpy(out.GetPointData().GetArray("BentNormal"))
        valid = ~np.isnan(local[:, 0])
        np.testing.assert_array_equal(np.isnan(frame), ~valid[:, None].repeat(3, axis=1))
        local, frame = local[valid], frame[valid]
        np.testing.assert_allclose(np.linalg.norm(frame, axis=1), 1.0, atol=1e-6)
        # (the angle from the chord, in double: arccos of a float dot product near 1 is
        # coarser than these angles)
        chord = np.linalg.norm(frame.astype(np.float64) - local.astype(np.float64), axis=1)
        turn = 2.0 * np.arcsin(0.5 * chord)
        xy = vtk_to_numpy(out.GetPoints().GetData())[valid, :2]
        distance = np.hypot(xy[:, 0], xy[:, 1])
        self.assertTrue(np.all(turn <= 2.0 * distance / 6.3e6 + 1e-6), turn.max())
        self.assertGreater(turn.max(), 0.3 * distance.max() / 6.4e6)
        self.assertLess(turn[np.argmin(distance)], 1e-5)


if __name__ == "__main__":
    if not os.path.exists(APERTURE):
        print("skipped: %s not built" % APERTURE)
        sys.exit(125)
    sys.exit(0 if unittest.main(exit=False).result.wasSuccessful() else 1)
