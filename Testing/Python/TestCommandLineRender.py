# SPDX-License-Identifier: BSD-3-Clause
"""`aperture render` end to end (runs under Xvfb): a PNG of the requested size that is not
blank, for both views, and one-line errors for bad options."""
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

from usage import usage_error

BUILD = os.environ.get("APERTURE_BUILD_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
APERTURE = os.path.join(BUILD, "bin", "aperture")
# why the terrain is black with the sun's centre below the horizon (the aperture lighting)
UNLIT = ("the sky models have no twilight, and the sun lights nothing until its centre is up: "
         "'aperture sun' gives sunrise and sunset for its upper limb, earlier and later (minutes; "
         "near the poles, days)")


def run(*args):
    p = subprocess.run([APERTURE] + [str(a) for a in args], capture_output=True, text=True,
                       timeout=300)
    return p.returncode, p.stdout, p.stderr


def render_rgb(test, out, *args):
    """Render to `out` (200 x 120, the sun at azimuth 225, elevation 20) and return its RGB."""
    status, _, stderr = run("render", "-o", out, "--size", "200x120", "--sun-az", "225",
                            "--sun-el", "20", *args)
    test.assertEqual(status, 0, stderr)
    test.assertNotIn("have no sky in", stderr)  # (a --baked bake of the DEM lights every cell)
    return png_pixels_and_text(out)[0]


def png_pixels_and_text(path):
    """A PNG's RGB pixels (int) and its text chunks (a dict)."""
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    text = {reader.GetTextKey(k): reader.GetTextValue(k)
            for k in range(reader.GetNumberOfTextChunks())}
    return vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3].astype(int), text


def exr_rgba(path):
    """An EXR's RGBA floats, as the project's reader reads them."""
    import aperture
    reader = aperture.vtkApertureEXRReader()
    reader.SetFileName(path)
    reader.Update()
    return vtk_to_numpy(reader.GetOutput().GetPointData().GetArray("RGBA"))


def write_picture(path, driver, planes, kind=None, palette=None):
    """Write `planes` (2-D arrays, row 0 north) as the bands of a picture with GDAL's `driver`,
    of GDAL type `kind` (default bytes), the first with a colour table of `palette` (RGB)."""
    from osgeo import gdal
    h, w = planes[0].shape
    mem = gdal.GetDriverByName("MEM").Create("", w, h, len(planes), kind or gdal.GDT_Byte)
    for k, plane in enumerate(planes):
        mem.GetRasterBand(k + 1).WriteArray(plane)
    if palette:
        table = gdal.ColorTable()
        for k, colour in enumerate(palette):
            table.SetColorEntry(k, colour + (255,))
        mem.GetRasterBand(1).SetRasterColorTable(table)
    gdal.GetDriverByName(driver).CreateCopy(path, mem)


class TestCommandLineRender(unittest.TestCase):
    def test_views(self):
        with tempfile.TemporaryDirectory() as tmp:
            for view, size in (("top", (320, 200)), ("oblique", (200, 150))):
                out = os.path.join(tmp, view + ".png")
                status, stdout, stderr = run("render", "-o", out, "--view", view,
                                             "--size", "%dx%d" % size)
                self.assertEqual(status, 0, stderr)
                self.assertIn("wrote " + out, stdout)
                reader = vtkPNGReader()
                reader.SetFileName(out)
                reader.Update()
                image = reader.GetOutput()
                self.assertEqual(image.GetDimensions()[:2], size)
                rgb = vtk_to_numpy(image.GetPointData().GetScalars())[:, :3].astype(float)
                # Terrain, not an empty background: many distinct shades, mostly non-white.
                self.assertGreater(rgb.std(), 20.0)
                self.assertGreater((rgb.sum(axis=1) < 700).mean(), 0.3)

    def test_exr(self):
        # The linear radiance in the EXR, exposed and tone mapped as the shader does, gives the
        # PNG's pixels: the two come from the same lighting (the EXR unclamped, in W/m2/sr).
        import re
        import numpy as np
        import aperture
        with tempfile.TemporaryDirectory() as tmp:
            png, exr = os.path.join(tmp, "a.png"), os.path.join(tmp, "a.exr")
            status, stdout, stderr = run("render", "-o", png, "--exr", exr, "--size", "240x160",
                                         "--at", "2026-12-21T15:30", "--tz", "America/New_York",
                                         "--view", "top", "--multisamples", "0")
            self.assertEqual(status, 0, stderr)
            self.assertIn("wrote " + exr, stdout)
            # -q: no 'wrote' lines (added 2026-12-06), the same files
            quiet_png, quiet_exr = os.path.join(tmp, "q.png"), os.path.join(tmp, "q.exr")
            status, quiet_out, stderr = run("render", "-o", quiet_png, "--exr", quiet_exr,
                                            "--size", "240x160", "--at", "2026-12-21T15:30",
                                            "--tz", "America/New_York", "--view", "top",
                                            "--multisamples", "0", "-q")
            self.assertEqual((status, quiet_out), (0, ""), stderr)
            for a, b in ((png, quiet_png), (exr, quiet_exr)):
                with open(a, "rb") as fa, open(b, "rb") as fb:
                    self.assertEqual(fa.read(), fb.read(), b)
            reader = aperture.vtkApertureEXRReader()
            reader.SetFileName(exr)
            reader.Update()
            # the display exposure, recorded in the EXR to 9 decimals (stdout rounds to 2)
            ev = float(reader.GetMetadataValue("aperture:display_exposure_ev"))
            self.assertAlmostEqual(ev, float(re.search(r"exposure (-?[0-9.]+) EV",
                                                       stdout).group(1)), delta=0.006)
            self.assertIn("W/m^2/sr", reader.GetMetadataValue("aperture:quantity"))
            image = reader.GetOutput()
            self.assertEqual(image.GetDimensions()[:2], (240, 160))
            rgba = vtk_to_numpy(image.GetPointData().GetArray("RGBA")).reshape(160, 240, 4)
            if shutil.which("exrheader"):  # OpenEXR's own tool (Debian package openexr)
                header = subprocess.run(["exrheader", exr], capture_output=True, text=True)
                self.assertEqual(header.returncode, 0, header.stderr)
                self.assertIn("R, 32-bit floating-point", header.stdout)
            shown, text = png_pixels_and_text(png)
            shown = shown.reshape(160, 240, 3).astype(float)
            # the PNG records what the EXR does of the sun, the time and the exposure, as
            # text chunks (until 2026-12-06 a time-lapse's frames said nothing of their sun)
            for key in ("aperture:software", "aperture:sun_azimuth_deg",
                        "aperture:sun_elevation_deg", "aperture:time_utc",
                        "aperture:display_exposure_ev"):
                self.assertEqual(text.get(key), reader.GetMetadataValue(key), key)
            self.assertEqual(text["aperture:time_utc"], "2026-12-21T20:30:00Z")
            self.assertRegex(text["aperture:sun_azimuth_deg"], r"^2[0-9][0-9]\.[0-9]{6}$")
        terrain = rgba[:, :, :3].sum(axis=2) > 0
        self.assertGreater(terrain.mean(), 0.3)
        self.assertGreater(rgba[:, :, :3][terrain].max(), 1.0)  # radiance, not 8-bit colour
        t = 1.0 - np.exp(-rgba[:, :, :3] * 2.0 ** ev)
        srgb = np.where(t <= 0.0031308, 12.92 * t, 1.055 * np.power(t, 1 / 2.4) - 0.055)
        diff = np.abs(np.round(255 * srgb) - shown)[terrain]
        # one 8-bit level: float32 in the shader against float64 here, and the EXR's floats
        self.assertLessEqual(diff.max(), 1.0)
        self.assertGreater(np.mean(diff == 0), 0.95)

    def test_time_lapse(self):
        # --frames: one bake, one mesh, the sun moved every --step minutes (a time-lapse had to
        # be made by a render per frame, each baking again, or by the example viewer). Each
        # frame is the picture a render at its time gives, with one exposure for all: the
        # automatic one of the frame whose sun is highest.
        import datetime
        import json
        import numpy as np
        import aperture
        size = ("--size", "160x120")
        with tempfile.TemporaryDirectory() as tmp:
            png, exr = os.path.join(tmp, "f-%02d.png"), os.path.join(tmp, "f-%02d.exr")
            status, stdout, stderr = run("render", "--at", "2026-06-21T04:00", "--tz",
                                         "America/New_York", "--frames", 6, "--step", 180,
                                         "-o", png, "--exr", exr, *size)
            self.assertEqual(status, 0, stderr)
            self.assertEqual(stderr, "aperture: warning: the sun is below the horizon in 1 of "
                                     "the 6 frames (0): the terrain is unlit there (%s): "
                                     "black\n" % UNLIT)
            self.assertEqual(sorted(os.listdir(tmp)), sorted(
                ["f-%02d.png" % k for k in range(6)] + ["f-%02d.exr" % k for k in range(6)]))
            self.assertEqual(len(stdout.splitlines()), 12, stdout)
            frames = [png_pixels_and_text(png % k) for k in range(6)]
            start = datetime.datetime(2026, 6, 21, 8, tzinfo=datetime.timezone.utc)
            for k, (_, text) in enumerate(frames):
                at = (start + datetime.timedelta(hours=3 * k)).strftime("%Y-%m-%dT%H:%M:%SZ")
                self.assertEqual((text["aperture:time_utc"], text["aperture:frame"],
                                  text["aperture:frames"]), (at, "%d" % k, "6"))
                # and on the clock of --tz, with the zone (UTC alone until 2026-12-07)
                local = (start + datetime.timedelta(hours=3 * k - 4)).strftime(
                    "%Y-%m-%dT%H:%M:%S-04:00")
                self.assertEqual((text["aperture:time_local"], text["aperture:time_zone"]),
                                 (local, "America/New_York"))
                # the sun of each frame is the one 'aperture sun' gives for its time and place
                status, out, err = run("sun", "--at", at, "--dem", aperture.default_dem(),
                                       "--json")
                self.assertEqual(status, 0, err)
                sun = json.loads(out)
                self.assertAlmostEqual(float(text["aperture:sun_azimuth_deg"]),
                                       sun["azimuth_deg"], delta=2e-6)
                self.assertAlmostEqual(float(text["aperture:sun_elevation_deg"]),
                                       sun["elevation_deg"], delta=2e-6)
            exposures = {text["aperture:display_exposure_ev"] for _, text in frames}
            self.assertEqual(len(exposures), 1, exposures)
            # the automatic exposure of the highest sun, 17:00Z (elevation 74.6 degrees)
            self.assertGreater(float(frames[3][1]["aperture:sun_elevation_deg"]), 74.0)
            noon = os.path.join(tmp, "noon.png")
            status, _, stderr = run("render", "--at", "2026-06-21T17:00Z", "-o", noon, *size)
            self.assertEqual(status, 0, stderr)
            self.assertEqual(png_pixels_and_text(noon)[1]["aperture:display_exposure_ev"],
                             exposures.pop())
            # frame 4 is the render at its time, at the frames' exposure: the same radiance
            # (bit for bit) and picture (the exposure given rounded to 9 decimals)
            single_png, single_exr = os.path.join(tmp, "s.png"), os.path.join(tmp, "s.exr")
            status, _, stderr = run("render", "--at", "2026-06-21T20:00Z", "-o", single_png,
                                    "--exr", single_exr, "--exposure",
                                    frames[4][1]["aperture:display_exposure_ev"], *size)
            self.assertEqual(status, 0, stderr)
            self.assertTrue(np.array_equal(exr_rgba(exr % 4), exr_rgba(single_exr)))
            self.assertLessEqual(np.abs(png_pixels_and_text(single_png)[0] -
                                        frames[4][0]).max(), 1)
            # (each frame antialiased alike: the EXR's one sample per pixel was kept for the
            # frames after the first, whose PNGs differed from the render by up to 62 levels)
            # the sun below the horizon: black terrain; the others lit, and all different
            self.assertEqual(exr_rgba(exr % 0)[:, :3].max(), 0.0)
            for k in range(1, 6):
                self.assertGreater(exr_rgba(exr % k)[:, :3].max(), 1.0, k)
                self.assertGreater(np.abs(frames[k][0] - frames[k - 1][0]).max(), 20, k)
            # SIGTERM (a batch system's limit) ends a time-lapse between frames: every frame
            # written is whole, PNG and EXR, and the message says which (it ended the process
            # in a PNG's write, leaving half of it, until 2026-12-06)
            import signal
            import time
            stop = os.path.join(tmp, "stop")
            os.mkdir(stop)
            p = subprocess.Popen([APERTURE, "render", "--frames", "60", "--at",
                                  "2026-06-21T12:00Z", "--size", "640x480", "--multisamples",
                                  "0", "-q", "-o",
                                  os.path.join(stop, "s-%02d.png"), "--exr",
                                  os.path.join(stop, "s-%02d.exr")],
                                 stderr=subprocess.PIPE, text=True,
                                 preexec_fn=lambda: signal.signal(signal.SIGTERM, signal.SIG_DFL))
            deadline = time.time() + 120
            while not os.path.exists(os.path.join(stop, "s-02.png")) and time.time() < deadline:
                time.sleep(0.05)
            p.send_signal(signal.SIGTERM)
            _, stderr = p.communicate(timeout=120)
            self.assertEqual(p.returncode, 143, stderr)
            written = sorted(os.listdir(stop))
            last = len(written) // 2 - 1
            self.assertGreaterEqual(last, 1, written)
            self.assertLess(last, 59, written)
            self.assertEqual(stderr, "aperture: interrupted: frames 0-%d of 60 written\n" % last)
            self.assertEqual(written, sorted(["s-%02d.%s" % (k, e) for k in range(last + 1)
                                              for e in ("png", "exr")]))
            for k in range(last + 1):
                self.assertEqual(png_pixels_and_text(os.path.join(stop, "s-%02d.png" % k))[0]
                                 .shape, (640 * 480, 3))
                self.assertEqual(exr_rgba(os.path.join(stop, "s-%02d.exr" % k)).shape,
                                 (640 * 480, 4))
            # started with SIGINT and SIGHUP ignored (`nohup aperture render ... &` in a script),
            # a time-lapse keeps them ignored and writes every frame (its handlers ended it at the
            # next frame, status 129, when the terminal closed, until 2026-12-06)
            def like_nohup_in_the_background():
                for number in (signal.SIGINT, signal.SIGHUP):
                    signal.signal(number, signal.SIG_IGN)

            kept = os.path.join(tmp, "kept")
            os.mkdir(kept)
            p = subprocess.Popen([APERTURE, "render", "--frames", "12", "--at",
                                  "2026-06-21T12:00Z", "--size", "320x240", "--multisamples",
                                  "0", "-q", "-o", os.path.join(kept, "k-%d.png")],
                                 stderr=subprocess.PIPE, text=True,
                                 preexec_fn=like_nohup_in_the_background)
            deadline = time.time() + 120
            while not os.path.exists(os.path.join(kept, "k-1.png")) and time.time() < deadline:
                time.sleep(0.02)
            p.send_signal(signal.SIGHUP)
            p.send_signal(signal.SIGINT)
            _, stderr = p.communicate(timeout=120)
            self.assertEqual((p.returncode, stderr), (0, ""))
            self.assertEqual(sorted(os.listdir(kept)), sorted("k-%d.png" % k for k in range(12)))
            # frames of an earlier, longer series that the name's pattern also names are said
            # in a warning (they stayed without a word, and a video of the pattern showed them)
            old = os.path.join(tmp, "old")
            os.mkdir(old)
            for name in ("o-1.png", "o-5.png", "o-12.png", "o-x.png", "o-3.exr", "o-03.png"):
                open(os.path.join(old, name), "w").close()
            status, _, stderr = run("render", "--at", "2026-06-21T12:00Z", "--frames", 3, "-o",
                                    old + "//o-%d.png", "--multisamples", 0, *size)
            self.assertEqual(status, 0, stderr)
            self.assertIn("aperture: warning: --output: 2 files (%s to %s) beyond this series' 3 "
                          "frames match its name, from an earlier series: a video made from the "
                          "name would include them\n" % (old + "/o-5.png", old + "/o-12.png"),
                          stderr)
            status, _, stderr = run("render", "--at", "2026-06-21T12:00Z", "--frames", 13, "-o",
                                    os.path.join(old, "o-%d.png"), "--multisamples", 0, *size)
            self.assertEqual(status, 0, stderr)
            self.assertNotIn("earlier series", stderr)
            # a frame that cannot be written (here over a limit on file sizes: the night's
            # black frames fit, the first lit one does not) ends the series with the reason
            # and the frames written (it said "cannot write the PNG name" alone)
            import resource

            def small_files():
                resource.setrlimit(resource.RLIMIT_FSIZE, (6000, 6000))
            limited = os.path.join(tmp, "limited")
            os.mkdir(limited)
            p = subprocess.run([APERTURE, "render", "--at", "2026-06-21T08:00Z", "--frames", "4",
                                "--step", "60", "-o", os.path.join(limited, "l-%d.png"),
                                "--multisamples", "0", "-q", *size], preexec_fn=small_files,
                               capture_output=True, text=True, timeout=300)
            self.assertEqual(p.returncode, 1, p.stderr)
            written = sorted(os.listdir(limited))
            self.assertGreaterEqual(len(written), 1, p.stderr)
            self.assertTrue(p.stderr.endswith(
                "aperture: error: cannot write the PNG %s: the write failed (out of space, or "
                "over a limit on file sizes) (frame%s %s of 4 written)\n" % (
                    os.path.join(limited, "l-%d.png" % len(written)),
                    "s" if len(written) > 1 else "", "0" if len(written) == 1 else
                    "0-%d" % (len(written) - 1))), p.stderr)
            # VTK's lighting moves its light alike: a frame is the render at its time
            status, _, stderr = run("render", "--lighting", "standard", "--at",
                                    "2026-06-21T14:00Z", "--frames", 3, "--step", 240, "-o",
                                    os.path.join(tmp, "v-%d.png"), "-q", *size)
            self.assertEqual(status, 0, stderr)
            status, _, stderr = run("render", "--lighting", "standard", "--at",
                                    "2026-06-21T22:00Z", "-o", os.path.join(tmp, "v.png"), "-q",
                                    *size)
            self.assertEqual(status, 0, stderr)
            self.assertTrue(np.array_equal(png_pixels_and_text(os.path.join(tmp, "v.png"))[0],
                                           png_pixels_and_text(os.path.join(tmp, "v-2.png"))[0]))
            self.assertGreater(np.abs(png_pixels_and_text(os.path.join(tmp, "v-0.png"))[0] -
                                      png_pixels_and_text(os.path.join(tmp, "v-2.png"))[0]).max(),
                               20)
            # %3d pads with zeros, as %03d and ffmpeg do (spaces until 2026-12-07: ffmpeg -i
            # w-%3d.png found none), and a frame of an earlier series so named is said
            padded = os.path.join(tmp, "padded")
            os.mkdir(padded)
            open(os.path.join(padded, "w-002.png"), "w").close()
            status, _, stderr = run("render", "--at", "2026-06-21T12:00Z", "--frames", 2, "-o",
                                    os.path.join(padded, "w-%3d.png"), "--multisamples", 0,
                                    *size)
            self.assertEqual(status, 0, stderr)
            self.assertEqual(sorted(os.listdir(padded)), ["w-000.png", "w-001.png", "w-002.png"])
            self.assertIn("--output: %s beyond this series' 2 frames matches its name" %
                          os.path.join(padded, "w-002.png"), stderr)
            # a name with a frame number but no --frames: one picture by that name, said (it
            # was written without a word)
            single = os.path.join(padded, "one-%03d.png")
            status, _, stderr = run("render", "--at", "2026-06-21T12:00Z", "-o", single,
                                    "--multisamples", 0, "-q", *size)
            self.assertEqual(status, 0, stderr)
            self.assertEqual(stderr, "aperture: warning: --output %s holds a frame number, but "
                                     "without --frames one picture is written, by that name\n"
                             % single)
            self.assertTrue(os.path.isfile(single))

    def test_moving_the_sun_uploads_no_geometry(self):
        # what a time-lapse's frames rely on: scene.set_sun changes the mapper's uniforms (and
        # the sky model's small table) only, and aim_light moves VTK's light
        import numpy as np
        import aperture
        from aperture import scene
        reader = aperture.vtkApertureDEMReader()
        reader.SetFileName(aperture.default_dem())
        reader.SetDecimation(4)
        sky = aperture.vtkApertureSkyVisibility()
        sky.SetInputConnection(reader.GetOutputPort())
        mesher = aperture.vtkApertureTerrainMesh()
        mesher.SetInputConnection(sky.GetOutputPort())
        mesher.Update()
        sun = aperture.vtkApertureSolarPosition()
        self.assertTrue(sun.SetTime("2026-06-21T14:00Z"))
        sun.SetPlaceFromImage(reader.GetOutput())
        self.assertTrue(sun.Compute())
        window, _, mapper = scene.build_aperture(mesher.GetOutput(), sun, size=(96, 64),
                                                 sky_mode="model", multisamples=0)
        before = scene.rgb_pixels(window).astype(int)
        uploads = mapper.GetGeometryUploads()
        sun.SetUnixTime(sun.GetUnixTime() + 6 * 3600.0)
        self.assertTrue(sun.Compute())
        sun_rgb, _ = scene.set_sun(mapper, sun, "model")
        after = scene.rgb_pixels(window).astype(int)
        self.assertEqual(mapper.GetGeometryUploads(), uploads)
        self.assertGreater(np.abs(after - before).max(), 20)
        rgb = [0.0] * 3
        sun.GetSunColor(rgb)
        self.assertEqual(sun_rgb, rgb)
        window, renderer = scene.build(mesher.GetOutput(), size=(96, 64), light_azimuth=90,
                                       light_elevation=30, multisamples=0)
        east = scene.rgb_pixels(window).astype(int)
        scene.aim_light(renderer, 270, 30)
        west = scene.rgb_pixels(window).astype(int)
        self.assertGreater(np.abs(east - west).max(), 20)
        scene.aim_light(renderer, 270, -5)  # (below the horizon: unlit, no ambient either)
        terrain = west.sum(axis=2) < 3 * 250  # (the background is white)
        self.assertGreater(terrain.mean(), 0.2)
        self.assertEqual(scene.rgb_pixels(window).astype(int)[terrain].max(), 0)
        with self.assertRaises(ValueError):
            scene.aim_light(renderer, 270, 91)

    def test_exr_standard_lighting(self):
        # With VTK's own lighting too the EXR holds the light before the exposure, and it and
        # the PNG record the exposure given. Until 2026-12-06 that EXR was scaled by 2^EV and
        # said 0 EV, while its PNG said 2.
        import numpy as np
        import aperture
        common = ("--lighting", "standard", "--size", "160x120", "--view", "top",
                  "--sun-az", "225", "--sun-el", "30", "--multisamples", "0")
        with tempfile.TemporaryDirectory() as tmp:
            pictures = {}
            for ev in ("0", "1"):
                png, exr = (os.path.join(tmp, ev + ext) for ext in (".png", ".exr"))
                status, stdout, stderr = run("render", "-o", png, "--exr", exr, "--exposure",
                                             ev, *common)
                self.assertEqual(status, 0, stderr)
                self.assertIn("(linear radiance, VTK lighting, float)", stdout)
                reader = aperture.vtkApertureEXRReader()
                reader.SetFileName(exr)
                reader.Update()
                self.assertEqual(reader.GetMetadataValue("aperture:display_exposure_ev"),
                                 "%.9f" % float(ev))
                self.assertIn("VTK lighting", reader.GetMetadataValue("aperture:quantity"))
                shown, text = png_pixels_and_text(png)
                self.assertEqual(text["aperture:display_exposure_ev"], "%.9f" % float(ev))
                rgba = vtk_to_numpy(reader.GetOutput().GetPointData().GetArray("RGBA"))
                pictures[ev] = (rgba.reshape(120, 160, 4)[:, :, :3].astype(float),
                                shown.reshape(120, 160, 3).astype(float))
        linear, shown = pictures["1"]
        terrain = linear.sum(axis=2) > 0
        self.assertGreater(terrain.mean(), 0.3)
        # the same light whatever the exposure (the EXR's floats, read back from one drawing)
        self.assertLess(np.abs(linear - pictures["0"][0]).max(), 1e-6)
        # the PNG: the light doubled, clamped, in 8 bits (no tone mapping in VTK's lighting)
        expected = np.round(255.0 * np.minimum(1.0, 2.0 * linear))
        self.assertLessEqual(np.abs(expected - shown)[terrain].max(), 1.0)
        self.assertGreater(np.abs(pictures["0"][1] - shown)[terrain].max(), 20.0)

    def test_bad_options(self):
        with tempfile.TemporaryDirectory() as tmp:
            pipe = os.path.join(tmp, "baked.tif")  # (GDAL's open of it waited for ever)
            os.mkfifo(pipe)
            for args, expected in ((("--light-el", "95"), "--sun-el must be within"),
                                   (("--baked", pipe), "cannot read the baked file %s: it is a "
                                    "pipe, not a file" % pipe),
                                   (("--albedo", pipe), "the albedo image %s is a pipe, not a "
                                    "file" % pipe),
                                   (("--sun-scale", "0"), "--sun-scale must be"),
                                   (("--at", "2026-06-21T12:00Z", "--sun-az", "10"), "not both"),
                                   (("--albedo", "/nonexistent.png"), "does not exist"),
                                   (("--baked", "/nonexistent.tif"), "cannot read the baked"),
                                   (("--exaggeration", "-1"), "--exaggeration must be within"),
                                   (("--radius", "-5"), "--radius must be a positive distance"),
                                   (("--srcwin", "999", "0", "5", "5"),
                                    "--srcwin 999 0 5 5 is not inside the 403 x 344 raster"),
                                   (("-o", os.path.join(tmp, "no", "x.png")), "does not exist"),
                                   # options another one makes meaningless, each ignored
                                   # without a word before
                                   (("--lighting", "standard", "--albedo", "x.png"),
                                    "--albedo applies only with --lighting aperture"),
                                   (("--lighting", "standard", "--sky", "model", "--sun-scale",
                                     "2", "--turbidity", "3"), "--sun-scale, --sky, --turbidity "
                                    "apply only with --lighting aperture"),
                                   (("--baked", "b.tif", "--radius", "100"), "--radius is the "
                                    "search distance of an aperture baked here"),
                                   (("--tz", "Europe/Zurich"), "--tz Europe/Zurich needs --at"),
                                   (("--exr-type", "half"), "--exr-type half needs --exr"),
                                   (("--exposure", "1e308"), "--exposure must be within -30..30"),
                                   (("--size", "16384x16384", "--exr", "x.exr"),
                                    "16384x16384 is too large for it"),
                                   (("-o", ""), "--output is empty"),
                                   # a time-lapse given wrongly
                                   (("--frames", "3", "--at", "2026-06-21T12:00Z", "-o",
                                     os.path.join(tmp, "x.png")), "--frames 3 writes 3 pictures: "
                                    "give --output a name with the frame number, such as "
                                    "frame-%03d.png"),
                                   (("--frames", "2"), "--frames needs --at"),
                                   (("--step", "5"), "--step 5 needs --frames"),
                                   (("--frames", "0", "--at", "2026-06-21T12:00Z"),
                                    "--frames must be within 1..10000"),
                                   (("--frames", "2", "--at", "2026-06-21T12:00Z", "--step",
                                     "0.001"), "--step must be a number of minutes of at least"),
                                   (("--frames", "2", "--at", "2026-06-21T12:00Z", "-o",
                                     os.path.join(tmp, "f-%q.png")),
                                    "the frame number is written %d, %4d or %04d in the name "
                                    "(once), and a % sign itself %%"),
                                   # (%c made a NUL and a '/' of frames 0 and 47: a traceback;
                                   # a width of 10^8 took a GB and seconds)
                                   (("--frames", "2", "--at", "2026-06-21T12:00Z", "-o",
                                     os.path.join(tmp, "f-%c.png")), "written %d, %4d or %04d"),
                                   (("--frames", "2", "--at", "2026-06-21T12:00Z", "-o",
                                     os.path.join(tmp, "f-%100000000d.png")),
                                    "written %d, %4d or %04d"),
                                   (("--frames", "2", "--at", "2026-06-21T12:00Z", "-o",
                                     os.path.join(tmp, "f-%d-%d.png")), "in the name (once)"),
                                   (("--frames", "3", "--at", "6000-12-31T23:00Z", "--step",
                                     "60", "-o", os.path.join(tmp, "late-%d.png")),
                                    "frame 1 of --frames 3, 60 minutes after --at "
                                    "6000-12-31T23:00Z: the time in the year 6001 is outside "
                                    "the years the algorithm covers"),
                                   # ... found before the DEM is read or the frames' names
                                   # checked (10 s for these 10,000, until 2026-12-07)
                                   (("/nonexistent/dem.tif", "--frames", "10000", "--at",
                                     "2026-06-21T12:00Z", "--step", "1e9", "-o",
                                     os.path.join(tmp, "later-%d.png")),
                                    "frame 3 of --frames 10000, 3e+09 minutes after --at "
                                    "2026-06-21T12:00Z: the time in the year 7730 is outside"),
                                   (("--frames", "11", "--at", "2026-06-21T12:00Z", "-o",
                                     os.path.join(tmp, "a%d.png"), "--exr",
                                     os.path.join(tmp, "a%d0.png")),
                                    "frame 10 of --output and frame 1 of --exr are one file, "
                                    + os.path.join(tmp, "a10.png")),
                                   (("--albedo", ""), "--albedo is empty"),
                                   (("--baked", ""), "--baked is empty"),
                                   # a dangling link as a middle frame: refused before the DEM
                                   # is read (after frames 0-1, until 2026-12-07)
                                   (("--frames", "4", "--at", "2026-06-21T12:00Z", "-o",
                                     os.path.join(tmp, "s-%d.png")),
                                    "the output folder /nonexistent/folder does not exist (%s is "
                                    "a symbolic link to /nonexistent/folder/f.png)"
                                    % os.path.join(tmp, "s-2.png"))):
                if not os.path.islink(os.path.join(tmp, "s-2.png")):
                    os.symlink("/nonexistent/folder/f.png", os.path.join(tmp, "s-2.png"))
                # (into tmp, should a refusal ever fail: not aperture.png here)
                out = () if "-o" in args else ("-o", os.path.join(tmp, "refused.png"))
                result = run("render", *out, *args)
                if any(about_files in expected for about_files in (
                        "cannot read the baked", "the albedo image", "does not exist",
                        "is not inside the", "are one file")):
                    status, stdout, stderr = result
                    self.assertEqual(status, 1, stderr)
                    self.assertEqual(len(stderr.strip().splitlines()), 1, stderr)
                    self.assertIn(expected, stderr)
                else:  # (a mistake in the options themselves)
                    self.assertIn(expected, usage_error(self, "render", result))
            # an output over a file the DEM reads: a VRT's source
            from osgeo import gdal
            sys.path.insert(0, os.path.join(BUILD, "lib", "python3.11", "dist-packages"))
            import aperture
            source = os.path.join(tmp, "dem.tif")
            shutil.copy(aperture.default_dem(), source)
            vrt = os.path.join(tmp, "dem.vrt")
            gdal.BuildVRT(vrt, [source]).FlushCache()
            with open(source, "rb") as f:
                before = f.read()
            for lighting in ("aperture", "standard"):  # (baked here, or not)
                status, _, stderr = run("render", vrt, "-o", source, "--lighting", lighting)
                self.assertEqual(status, 1, stderr)
                self.assertIn("--output %s is one of the files the DEM %s reads" % (source, vrt),
                              stderr)
            with open(source, "rb") as f:
                self.assertEqual(f.read(), before)
            # a PNG under another name is written, with a warning
            jpg = os.path.join(tmp, "x.jpg")
            status, _, stderr = run("render", "-o", jpg, "--size", "64x48", "--multisamples", 0)
            self.assertEqual(status, 0, stderr)
            self.assertIn("warning: %s is written as a PNG" % jpg, stderr)
            status, _, stderr = run("render", "--size", "10x10")
            self.assertEqual(status, 2)
            self.assertIn("width and height must be within 16..16384", stderr)
            for camera, expected in (("10", "expected AZ,EL"), ("0,2", "within 5..90"),
                                     ("0,30,-1", "zoom must be positive"),
                                     ("0,30,1e308", "zoom must be within 0.001..10000")):
                status, _, stderr = run("render", "--camera", camera)
                self.assertEqual(status, 2, stderr)
                self.assertIn(expected, stderr)

    def test_albedo(self):
        # A picture draped over the DEM, read with GDAL: quadrants north-west red, north-east
        # green, south-west blue, south-east white land where the top view puts them, as 8-bit
        # RGB, as 16-bit RGB and as a palette (alone, or with an alpha band) alike.
        import numpy as np
        from osgeo import gdal
        h, w = 60, 80
        north, west = np.arange(h)[:, None] < h // 2, np.arange(w)[None, :] < w // 2
        rgb = np.zeros((h, w, 3), np.uint8)  # row 0 north
        rgb[north & west] = (255, 0, 0)
        rgb[north & ~west] = (0, 255, 0)
        rgb[~north & west] = (0, 0, 255)
        rgb[~north & ~west] = (255, 255, 255)

        with tempfile.TemporaryDirectory() as tmp:
            paths = {k: os.path.join(tmp, k)
                     for k in ("rgb.png", "rgb16.tif", "palette.png", "palette-alpha.tif")}
            write_picture(paths["rgb.png"], "PNG", [rgb[:, :, k] for k in range(3)])
            write_picture(paths["rgb16.tif"], "GTiff", [rgb[:, :, k].astype(np.uint16) * 257
                                                        for k in range(3)], gdal.GDT_UInt16)
            index = (north & ~west) + 2 * (~north & west) + 3 * (~north & ~west)
            colours = [(255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 255)]
            write_picture(paths["palette.png"], "PNG", [index.astype(np.uint8)], palette=colours)
            write_picture(paths["palette-alpha.tif"], "GTiff",
                          [index.astype(np.uint8), np.full((h, w), 255, np.uint8)],
                          palette=colours)
            pictures = {k: render_rgb(self, os.path.join(tmp, k + ".out.png"), "--view", "top",
                                      "--albedo", path) for k, path in paths.items()}
            # A georeferenced picture is draped the same way: without a word when it covers
            # the DEM (the embedded one: its bounds), with a warning when it covers more.
            for name, grow, warned in (("fits.tif", 0.0, False), ("larger.tif", 0.5, True)):
                path = os.path.join(tmp, name)
                west, south, east, north = -84.41375, 36.1595833333, -84.0779166667, 36.44625
                write_picture(path, "GTiff", [rgb[:, :, k] for k in range(3)])
                ds = gdal.Open(path, gdal.GA_Update)
                dx, dy = (east - west) / w, (north - south) / h
                ds.SetGeoTransform((west - grow * w * dx, (1 + 2 * grow) * dx, 0.0, north, 0.0,
                                    -(1 + grow) * dy))
                ds.SetProjection("EPSG:4326")
                ds = None
                out = os.path.join(tmp, name + ".png")
                status, _, stderr = run("render", "-o", out, "--size", "200x120", "--sun-az",
                                        "225", "--sun-el", "20", "--view", "top", "--albedo", path)
                self.assertEqual(status, 0, stderr)
                if warned:
                    self.assertEqual(stderr, "aperture: warning: the albedo image %s covers "
                                     "longitude -84.581667..-83.910000, latitude "
                                     "36.016250..36.446250, the DEM -84.413750..-84.077917, "
                                     "36.159583..36.446250: the picture is stretched over the "
                                     "whole DEM, not placed by its georeference (clip it to the "
                                     "DEM's bounds, e.g. with gdalwarp -te)\n" % path)
                else:
                    self.assertEqual(stderr, "")
                    np.testing.assert_array_equal(png_pixels_and_text(out)[0],
                                                  pictures["rgb.png"])
        for k in ("rgb16.tif", "palette.png", "palette-alpha.tif"):
            np.testing.assert_array_equal(pictures[k], pictures["rgb.png"], err_msg=k)
        picture = pictures["rgb.png"].reshape(120, 200, 3)[::-1]  # (PNG rows from the bottom)
        r, g, b = (picture[:, :, k] for k in range(3))
        rows, cols = np.mgrid[0:120, 0:200]
        terrain = picture.sum(axis=2) < 700  # (not the white background)
        middle = (cols[terrain].mean(), rows[terrain].mean())
        for name, where, left, top in (("red", (r > 2 * g + 20) & (r > 2 * b + 20), True, True),
                                       ("green", (g > 2 * r + 20) & (g > 2 * b + 20), False,
                                        True),
                                       ("blue", (b > 2 * r + 20) & (b > 2 * g + 20), True,
                                        False)):
            self.assertGreater(where.sum(), 0.15 * terrain.sum(), name)
            self.assertEqual(cols[where].mean() < middle[0], left, name)
            self.assertEqual(rows[where].mean() < middle[1], top, name)

    def test_albedo_errors(self):
        # A damaged picture (VTK's PNG reader crashed on it), elevations, too many bands: one line
        # each, before anything is baked.
        import numpy as np
        from osgeo import gdal
        with tempfile.TemporaryDirectory() as tmp:
            whole, cut = os.path.join(tmp, "whole.png"), os.path.join(tmp, "cut.png")
            write_picture(whole, "PNG", [np.random.default_rng(k).integers(0, 255, (64, 64))
                                         .astype(np.uint8) for k in range(3)])
            with open(whole, "rb") as f, open(cut, "wb") as g:
                g.write(f.read()[:300])
            heights = os.path.join(tmp, "heights.tif")
            gdal.GetDriverByName("GTiff").Create(heights, 8, 8, 1, gdal.GDT_Float32)
            signed = os.path.join(tmp, "signed.tif")  # (said "8- or 16-bit" until 2026-12-06)
            gdal.GetDriverByName("GTiff").Create(signed, 8, 8, 1, gdal.GDT_Int16)
            five = os.path.join(tmp, "five.tif")
            gdal.GetDriverByName("GTiff").Create(five, 8, 8, 5, gdal.GDT_Byte)
            for path, expected in (
                    (cut, "cannot read the albedo image %s: " % cut),
                    (heights, "the albedo image %s has Float32 samples (elevations?); --albedo "
                              "takes a picture of unsigned 8- or 16-bit samples" % heights),
                    (signed, "the albedo image %s has Int16 samples (elevations?); --albedo "
                             "takes a picture of unsigned 8- or 16-bit samples" % signed),
                    (five, "the albedo image %s has 5 bands; --albedo takes 1 (grey), 2 (grey, "
                           "alpha), 3 (RGB) or 4 (RGBA)" % five)):
                status, _, stderr = run("render", "-o", os.path.join(tmp, "x.png"),
                                        "--albedo", path)
                self.assertEqual(status, 1, stderr)
                self.assertEqual(len(stderr.strip().splitlines()), 1, stderr)
                self.assertIn(expected, stderr)

    def test_sky_model(self):
        import numpy as np
        # The sky model over each aperture lights the shade towards the sun more than
        # a uniform sky of the same total: the pictures differ, slightly, and stay alike.
        pictures = {}
        with tempfile.TemporaryDirectory() as tmp:
            for sky in ("constant", "model"):
                out = os.path.join(tmp, sky + ".png")
                status, _, stderr = run("render", "-o", out, "--size", "200x120", "--sky", sky,
                                        "--sun-az", "225", "--sun-el", "20", "--exposure", "-6")
                self.assertEqual(status, 0, stderr)
                pictures[sky] = png_pixels_and_text(out)[0]
        diff = pictures["model"].astype(float) - pictures["constant"]
        self.assertGreater(abs(diff).max(), 2)
        self.assertLess(abs(diff.mean()), 10)
        # shading per vertex: nearly the same picture (this mesh has about pixel-sized cells)
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "v.png")
            status, _, stderr = run("render", "-o", out, "--size", "200x120", "--shading",
                                    "vertex", "--sun-az", "225", "--sun-el", "20",
                                    "--exposure", "-6")
            self.assertEqual(status, 0, stderr)
            vertex = png_pixels_and_text(out)[0]
        diff = vertex.astype(float) - pictures["constant"]
        self.assertLess(abs(diff.mean()), 3)
        self.assertLess(np.median(abs(diff)), 4)

    def test_camera(self):
        # Looking from the north instead of the south turns the picture around: the bright
        # south-west-facing mountains change sides.
        halves = {}
        with tempfile.TemporaryDirectory() as tmp:
            for camera in ("180,35", "0,35"):
                out = os.path.join(tmp, "c.png")
                status, _, stderr = run("render", "-o", out, "--size", "200x120", "--camera",
                                        camera, "--sun-az", "225", "--sun-el", "20")
                self.assertEqual(status, 0, stderr)
                rgb = png_pixels_and_text(out)[0]
                g = rgb.reshape(120, 200, 3).astype(float).mean(axis=2)
                halves[camera] = (g[:, :100].mean(), g[:, 100:].mean())
        self.assertNotAlmostEqual(halves["180,35"][0] - halves["180,35"][1],
                                  halves["0,35"][0] - halves["0,35"][1], delta=3.0)
        # a negative azimuth after --camera (argparse alone took it for an option) is the
        # same camera as its positive turn
        with tempfile.TemporaryDirectory() as tmp:
            pictures = [render_rgb(self, os.path.join(tmp, "%d.png" % k), "--camera", camera)
                        for k, camera in enumerate(("-150,35", "210,35"))]
        self.assertTrue((pictures[0] == pictures[1]).all())

    def test_time_of_day_viewer(self):
        # Examples/time_of_day_viewer.py: its slider's hours to the nearest minute (until
        # 2026-12-06 6.995 h put the sun at 06:00, an hour early, in the last half minute of
        # every hour), and a zone or date it cannot use refused up front (it ran on under the
        # mapper's default sun, exit 0). New York is 4 hours behind UTC in June.
        import argparse
        import importlib.util
        path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Examples",
                            "time_of_day_viewer.py")
        spec = importlib.util.spec_from_file_location("time_of_day_viewer", path)
        example = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(example)
        viewer = example.Viewer(argparse.Namespace(dem=None, date="2026-06-21",
                                                   tz="America/New_York"))
        for hour, utc in ((6.99, "2026-06-21T10:59"), (6.995, "2026-06-21T11:00"),
                          (12.992, "2026-06-21T17:00"), (17.9999, "2026-06-21T22:00"),
                          (23.999, "2026-06-22T03:59"), (-1.0, "2026-06-21T04:00")):
            viewer.set_hour(hour)
            self.assertEqual(viewer.sun.GetTimeString(), utc + ":00Z", hour)
        # --frames with a frame number in -o writes every frame, a time-lapse (until
        # 2026-12-06 only the last); a name without one gets the last frame only
        import numpy as np
        with tempfile.TemporaryDirectory() as tmp:
            viewer.frames(3, os.path.join(tmp, "f-%02d.png"))
            viewer.frames(2, os.path.join(tmp, "last.png"))
            self.assertEqual(sorted(os.listdir(tmp)),
                             ["f-00.png", "f-01.png", "f-02.png", "last.png"])
            frames = []
            for name in ("f-00.png", "f-01.png", "f-02.png", "last.png"):
                reader = vtkPNGReader()
                reader.SetFileName(os.path.join(tmp, name))
                reader.Update()
                self.assertEqual(reader.GetOutput().GetDimensions()[:2], (1000, 700))
                frames.append(vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())
                              .astype(float))
            # morning, noon and evening light differ; the last of 3 and of 2 are both 18:00
            self.assertGreater(np.abs(frames[0] - frames[1]).mean(), 2.0)
            self.assertGreater(np.abs(frames[1] - frames[2]).mean(), 2.0)
            self.assertEqual(np.abs(frames[2] - frames[3]).max(), 0.0)
            with self.assertRaises(SystemExit) as e:
                viewer.frames(2, os.path.join(tmp, "bad%.png"))
            self.assertIn("a frame number is written %d or %03d", str(e.exception))
        for tz, date, message in (
                ("Foo/Bar", "2026-06-21", "time zone 'Foo/Bar': unknown"),
                ("America/New_York", "2026-02-30", "2026-02-30")):
            with self.assertRaises(SystemExit) as e:
                example.Viewer(argparse.Namespace(dem=None, date=date, tz=tz))
            self.assertTrue(str(e.exception).startswith("time_of_day_viewer: "), e.exception)
            self.assertIn(message, str(e.exception))

    def test_many_dark_frames(self):
        # Past 7 stretches of dark frames the warning names the first 6, the last and their
        # count (a year of hourly frames made one line of 4.8 kB): 25 nights at 6 h steps,
        # 00, 06 and 12 UTC dark in Tennessee in December (sunrise 07:30 local, 12:30 UTC)
        with tempfile.TemporaryDirectory() as tmp:
            status, _, stderr = run("render", "-o", os.path.join(tmp, "m-%03d.png"), "--size",
                                    "16x16", "--multisamples", 0, "--at", "2026-12-01T00:00Z",
                                    "--frames", 100, "--step", 360, "-q")
            self.assertEqual(status, 0, stderr)
            self.assertIn("the sun is below the horizon in 75 of the 100 frames (0-2, 4-6, 8-10, "
                          "12-14, 16-18, 20-22, ..., 96-98: 25 stretches)", stderr)
        # (7 stretches named in full, 8 shortened)
        sys.path.insert(0, os.path.join(BUILD, "lib", "python3.11", "dist-packages"))
        from aperture.cli import _ranges_text
        self.assertEqual(_ranges_text(range(0, 14, 2)), "0, 2, 4, 6, 8, 10, 12")
        self.assertEqual(_ranges_text(range(0, 16, 2)), "0, 2, 4, 6, 8, 10, ..., 14: 8 stretches")

    def test_night(self):
        # The sun below the horizon lights nothing (no twilight in the sky models): a black
        # picture, with a warning saying why. VTK's standard lighting too: it lit the slopes
        # facing a light 11 degrees below the horizon, and the rest at its ambient level.
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "night.png")
            for lighting in ("aperture", "standard"):
                for el in ("-5", "-0.01", "-90"):
                    status, stdout, stderr = run("render", "-o", out, "--size", "200x120",
                                                 "--sun-az", "315", "--sun-el", el,
                                                 "--lighting", lighting)
                    self.assertEqual(status, 0, stderr)
                    # (why, for the lighting drawn: the sky models' reason was given for
                    # VTK's lighting too until 2026-12-06)
                    self.assertIn("aperture: warning: the sun is %.2f degrees below the horizon: "
                                  "the terrain is unlit (%s): black" % (
                                      -float(el), UNLIT if lighting == "aperture" else
                                      "VTK's light, from the sun's direction, is below it"),
                                  stderr)
                    rgb = png_pixels_and_text(out)[0]
                    # the terrain, black; all else the white background, and the grey of
                    # the two blended at its outline: no pixel with a colour
                    self.assertGreater((rgb.sum(axis=1) == 0).mean(), 0.3, (lighting, el))
                    self.assertTrue(((rgb == rgb[:, :1]).all(axis=1)).all(), (lighting, el))
                # black terrain filling the view, no background beside it: the picture the
                # driver drew, not a failure to draw (refused as one until 2026-12-06), and no
                # light to expose for (0 EV; it said 19.93)
                status, stdout, stderr = run("render", "-o", out, "--size", "200x120",
                                             "--sun-az", "315", "--sun-el", "-5", "--lighting",
                                             lighting, "--view", "top", "--camera", "0,90,3")
                self.assertEqual(status, 0, stderr)
                # (VTK's lighting has no exposure: it said 0.00 EV)
                self.assertIn("exposure 0.00 EV)" if lighting == "aperture" else
                              "elevation -5.00 deg, VTK lighting)", stdout)
                rgb = png_pixels_and_text(out)[0]
                self.assertEqual(int(rgb.max()), 0, lighting)
                # at the horizon and above: lit (the sky, and slopes facing the sun), and no
                # warning
                for el in ("0", "1"):
                    status, _, stderr = run("render", "-o", out, "--size", "200x120",
                                            "--sun-az", "315", "--sun-el", el, "--lighting",
                                            lighting)
                    self.assertEqual((status, "warning" in stderr), (0, False), stderr)
                    rgb = png_pixels_and_text(out)[0]
                    self.assertLess((rgb.sum(axis=1) == 0).mean(), 0.01, (lighting, el))

    def test_continent_at_night(self):
        # The light is the DEM centre's sun for all of the DEM: a continent (130-60 W, 20-55 N)
        # is black while the sun is down at its centre (37.5 N, 95 W), though it stands above
        # its north-west (until 2026-12-07 the warning said only that the sun was down). At
        # 2025-06-21T02:40Z, 6.0 h after noon at the north-west cell (54.5 N, 129.5 W), the sun
        # there is at asin(sin 54.5 sin 23.44 + cos 54.5 cos 23.44 cos 90.1) = 18.84 degrees
        # (declination 23.44, the equation of time -1.7 min), 0.05 more refracted; one hour
        # later 11, then 3.5, then -2.7: a series of 5 hourly frames has the sun up over part
        # of the DEM in its first three.
        from osgeo import gdal, osr
        import numpy as np
        with tempfile.TemporaryDirectory() as tmp:
            dem = os.path.join(tmp, "continent.tif")
            ds = gdal.GetDriverByName("GTiff").Create(dem, 71, 36, 1, gdal.GDT_Float32)
            ds.SetGeoTransform((-130, 1, 0, 55, 0, -1))
            ref = osr.SpatialReference()
            ref.ImportFromEPSG(4326)
            ds.SetSpatialRef(ref)
            ds.GetRasterBand(1).WriteArray(
                np.random.default_rng(4).random((36, 71)).astype(np.float32) * 500)
            ds = None
            status, _, stderr = run("render", dem, "-o", os.path.join(tmp, "night.png"),
                                    "--size", "200x120", "--view", "top", "--at",
                                    "2025-06-21T02:40Z", "-q")
            self.assertEqual(status, 0, stderr)
            found = re.search(r"black; the light is the DEM centre's, though over part of the "
                              r"DEM the sun is up \(([0-9.]+) degrees at 54.50 N, 129.50 W\): "
                              r"render that part \(--srcwin\)$", stderr.strip())
            self.assertTrue(found, stderr)
            self.assertAlmostEqual(float(found.group(1)), 18.89, delta=0.2)
            status, _, stderr = run("render", dem, "-o", os.path.join(tmp, "night-%d.png"),
                                    "--size", "64x48", "--view", "top", "--at",
                                    "2025-06-21T02:40Z", "--frames", "5", "--step", "60", "-q")
            self.assertEqual(status, 0, stderr)
            self.assertIn("the sun is below the horizon in 5 of the 5 frames (0-4): the terrain "
                          "is unlit there (" + UNLIT + "): black; in 0-2 the "
                          "light is the DEM centre's, though over part of the DEM the sun is up "
                          "(render that part: --srcwin)", stderr)

    def test_local_crs(self):
        # A site grid in a local CRS renders with the sun given by its direction, as the same
        # grid on UTM's central meridian does (grid north true north there; ground cells 0.04%
        # larger); a time needs a place, which it has not: refused, as is `sun --dem` of it.
        import numpy as np
        from osgeo import gdal
        gdal.UseExceptions()
        y, x = np.mgrid[0:90, 0:120] * 30.0
        z = (250 * np.sin(x / 500) * np.cos(y / 400) + 80 * np.sin(x / 150 + y / 210) + 400)
        pictures = {}
        with tempfile.TemporaryDirectory() as tmp:
            for name, crs in (("local", 'LOCAL_CS["mine grid",UNIT["metre",1]]'),
                              ("utm", "EPSG:32631")):
                path = os.path.join(tmp, name + ".tif")
                ds = gdal.GetDriverByName("GTiff").Create(path, 120, 90, 1, gdal.GDT_Float32)
                ds.SetGeoTransform((500000.0 - 1800.0, 30.0, 0.0, 1000000.0, 0.0, -30.0))
                ds.SetProjection(crs)
                ds.GetRasterBand(1).WriteArray(z.astype(np.float32))
                ds = None
                pictures[name] = render_rgb(self, os.path.join(tmp, name + ".png"), path)
            diff = np.abs(pictures["local"] - pictures["utm"]).max(axis=1)
            self.assertGreater(pictures["local"].std(), 20.0)  # terrain, lit
            self.assertLess(diff.mean(), 0.05)
            # (the outline moves by 0.04%: a few of its pixels change)
            self.assertLess((diff > 2).mean(), 0.002)
            local = os.path.join(tmp, "local.tif")
            status, _, stderr = run("render", local, "-o", os.path.join(tmp, "x.png"),
                                    "--at", "2026-06-21T12:00Z")
            self.assertEqual(status, 1, stderr)
            self.assertIn("local CRS (a site grid, no place on the Earth), where the sun has no "
                          "position for a time: give its direction with --sun-az/--sun-el", stderr)
            status, _, stderr = run("sun", "--dem", local, "--at", "2026-06-21T12:00Z")
            self.assertEqual(status, 1, stderr)
            self.assertIn("is in a local CRS (a site grid, no place on the Earth); give the "
                          "site's place with --lat/--lon", stderr)

    def test_no_picture_to_make(self):
        # A DEM whose valid cells are all isolated among nodata has no triangle to draw, and one
        # whose centre holds an undeclared nodata value no height for the light: each refused
        # by name instead of a blank or meaningless picture.
        import numpy as np
        from osgeo import gdal
        gdal.UseExceptions()
        with tempfile.TemporaryDirectory() as tmp:
            for name, z, expected in (
                    ("checkerboard", np.where(np.indices((30, 40)).sum(axis=0) % 2, -9999.0, 5.0),
                     "meshing: no 2 x 2 block of the DEM's points has three valid corners, which "
                     "a triangle needs: its valid points (600) are too few or too scattered among "
                     "nodata"),
                    ("voids", np.full((30, 40), -32768.0),
                     "the light: the site's height, -32768 m (the DEM's elevation at its centre: "
                     "a nodata value the DEM does not declare, or heights not in metres?), is "
                     "outside -1000..10000 m")):
                path = os.path.join(tmp, name + ".tif")
                ds = gdal.GetDriverByName("GTiff").Create(path, 40, 30, 1, gdal.GDT_Float32)
                ds.SetGeoTransform((400000.0, 30.0, 0.0, 5000000.0, 0.0, -30.0))
                ds.SetProjection("EPSG:32633")
                ds.GetRasterBand(1).SetNoDataValue(-9999.0)
                ds.GetRasterBand(1).WriteArray(z.astype(np.float32))
                ds = None
                out = os.path.join(tmp, name + ".png")
                status, _, stderr = run("render", path, "-o", out)
                self.assertEqual(status, 1, stderr)
                self.assertIn(expected, stderr)
                self.assertFalse(os.path.exists(out))

    def test_grid_wider_than_the_earth(self):
        # A gridline-registered global grid (361 columns of 1 degree) is refused before a cell
        # is read, with either lighting and with --srcwin: a VRT whose source is gone opens but
        # fails to read (VTK's lighting read it all before the mesher refused it, until
        # 2026-12-07). A window narrower than the Earth is drawn with VTK's lighting.
        import numpy as np
        from osgeo import gdal
        gdal.UseExceptions()
        with tempfile.TemporaryDirectory() as tmp:
            tif, vrt = os.path.join(tmp, "gridline.tif"), os.path.join(tmp, "gridline.vrt")
            ds = gdal.GetDriverByName("GTiff").Create(tif, 361, 181, 1, gdal.GDT_Float32)
            ds.SetGeoTransform((-180.5, 1.0, 0.0, 90.5, 0.0, -1.0))
            ds.SetProjection("EPSG:4326")
            ds.GetRasterBand(1).Fill(100.0)
            ds = None
            status, _, stderr = run("render", tif, "-o", os.path.join(tmp, "w.png"), "-q",
                                    "--lighting", "standard", "--srcwin", 10, 10, 50, 50,
                                    "--size", "64x48")
            self.assertEqual(status, 0, stderr)
            gdal.Translate(vrt, tif, format="VRT")
            os.remove(tif)
            for options in (("--lighting", "standard"), ("--srcwin", 10, 10, 50, 50), ()):
                status, _, stderr = run("render", vrt, "-o", os.path.join(tmp, "g.png"), "-q",
                                        *options)
                self.assertEqual(status, 1, stderr)
                self.assertIn("(a gridline-registered global grid)", stderr)
                self.assertNotIn("GDAL failed reading", stderr)
                self.assertEqual(len(stderr.splitlines()), 1, stderr)

    def test_implausible_elevations_named_once(self):
        # Spots of an undeclared nodata value, or cells of 3 arc-seconds taken for metres: the
        # picture is made, with one warning naming the range (the sky filter's; the mesher's
        # would say the same), and the mesher's alone with VTK's lighting (no bake).
        import numpy as np
        from osgeo import gdal
        gdal.UseExceptions()
        with tempfile.TemporaryDirectory() as tmp:
            z = np.add.outer(np.arange(60.0), np.arange(80.0)) * 3
            spots = z.copy()
            spots[5:7, 5:7] = -32768
            for heights, cell, expected in (
                    (spots, 30.0, "elevations range from -32768 to 414 m, beyond any on Earth"),
                    (z, 1 / 1200.0, "elevations range over 414 m on a grid of ")):
                path = os.path.join(tmp, "dem.tif")
                ds = gdal.GetDriverByName("GTiff").Create(path, 80, 60, 1, gdal.GDT_Float32)
                ds.SetGeoTransform((400000.0, cell, 0.0, 5000000.0, 0.0, -cell))
                ds.SetProjection("EPSG:32633")
                ds.GetRasterBand(1).WriteArray(heights.astype(np.float32))
                ds = None
                for lighting, what in (("aperture", "Sky products computed from them"),
                                       ("standard", "A mesh and pictures made of them")):
                    status, _, stderr = run("render", path, "-o", os.path.join(tmp, "x.png"),
                                            "--size", "200x120", "--lighting", lighting)
                    self.assertEqual(status, 0, stderr)
                    lines = stderr.strip().splitlines()
                    self.assertEqual(len(lines), 1, stderr)
                    self.assertIn("aperture: warning: " + expected, lines[0])
                    self.assertIn(what, lines[0])

    def test_baked(self):
        # A bake of this DEM lights it as the render's own bake does (the GeoTIFF keeps the
        # aperture radius in degrees as float32: a level at most); a bake of another grid of
        # the same size, or in another CRS, is refused instead of lighting the wrong terrain.
        import numpy as np
        from osgeo import gdal
        gdal.UseExceptions()
        sys.path.insert(0, os.path.join(BUILD, "lib", "python3.11", "dist-packages"))
        import aperture
        dem = aperture.default_dem()
        pictures = {}
        with tempfile.TemporaryDirectory() as tmp:
            baked = os.path.join(tmp, "baked.tif")
            status, _, stderr = run("bake", dem, baked, "-q", "--exr",
                                    os.path.join(tmp, "baked.exr"))
            self.assertEqual(status, 0, stderr)
            for name, extra in (("own", ()), ("baked", ("--baked", baked))):
                pictures[name] = render_rgb(self, os.path.join(tmp, name + ".png"), *extra)
            diff = np.abs(pictures["baked"] - pictures["own"])
            self.assertLessEqual(diff.max(), 1)
            self.assertLess(diff.mean(), 0.01)

            # A window: its aperture, baked here, sees the DEM around it within --radius, as
            # bake --srcwin's does; a bake of the window alone (its horizons cut at its edges)
            # lights it otherwise.
            window = ("--srcwin", 100, 80, 160, 120)
            around = os.path.join(tmp, "around.tif")
            alone_dem = os.path.join(tmp, "alone-dem.tif")
            alone = os.path.join(tmp, "alone.tif")
            status, _, stderr = run("bake", dem, around, "-q", "--radius", 4000, *window)
            self.assertEqual(status, 0, stderr)
            gdal.Translate(alone_dem, dem, srcWin=list(window[1:]))
            status, _, stderr = run("bake", alone_dem, alone, "-q", "--radius", 4000)
            self.assertEqual(status, 0, stderr)
            for name, extra in (("window", ("--radius", 4000)), ("around", ("--baked", around)),
                                ("alone", ("--baked", alone))):
                pictures[name] = render_rgb(self, os.path.join(tmp, name + ".png"), dem,
                                            *window, *extra)
            diff = np.abs(pictures["around"] - pictures["window"])
            self.assertLessEqual(diff.max(), 1)
            self.assertLess(diff.mean(), 0.01)
            diff = np.abs(pictures["alone"] - pictures["window"])
            self.assertGreater(diff.max(), 8)
            # A bake of the whole DEM serves any window of it read alike (its cells are read;
            # it was refused, "is 403 x 344 cells, the DEM 160 x 120", until 2026-12-06): the
            # picture an unlimited aperture baked here gives
            for name, extra in (("whole", ("--baked", baked)), ("unlimited", ())):
                pictures[name] = render_rgb(self, os.path.join(tmp, name + ".png"), dem,
                                            *window, *extra)
            self.assertTrue(np.array_equal(pictures["whole"], pictures["unlimited"]))
            # (and not what a 4 km radius gives: the test would hold for a bake of any radius)
            self.assertGreater(np.abs(pictures["whole"] - pictures["window"]).max(), 4)
            # (not a window of other cells: decimated, or off the bake's cell corners)
            half = os.path.join(tmp, "half-cell.tif")
            ds = gdal.GetDriverByName("GTiff").CreateCopy(half, gdal.Open(dem))
            gt = list(ds.GetGeoTransform())
            ds.SetGeoTransform([gt[0] + 0.5 * gt[1]] + gt[1:])
            ds = None
            for source, extra, expected in (
                    (dem, ("--decimate", 2), "0.001666666667, 0, 36.37958333, 0, "
                     "-0.001666666667), 80 x 60): bake this DEM with the same reading options (a "
                     "bake of all of it serves any --srcwin)"),
                    (half, (), "covers another grid than the DEM")):
                status, _, stderr = run("render", source, *window, "--baked", baked, *extra,
                                        "-o", os.path.join(tmp, "x.png"), "--size", "200x120")
                self.assertEqual(status, 1, stderr)
                self.assertIn(expected, stderr)

            src = gdal.Open(dem)
            gt = list(src.GetGeoTransform())
            for name, change, expected in (
                    ("shifted.tif", lambda ds: ds.SetGeoTransform([gt[0] + 10 * gt[1]] + gt[1:]),
                     "covers another grid than the DEM"),
                    ("nad83.tif", lambda ds: ds.SetProjection("EPSG:4269"),
                     "is in another CRS (NAD83) than the DEM (WGS 84)"),
                    # (a traceback until 2026-12-06: int(round(nan)))
                    ("nan.tif", lambda ds: ds.SetGeoTransform([math.nan] + gt[1:]),
                     "covers another grid than the DEM (geotransform (nan, "),
                    ("feet.tif",
                     lambda ds: ds.SetMetadataItem("SOURCE_ELEVATION_UNIT", "0.3048 m (--zfactor)"),
                     "was baked from elevations in units of 0.3048 m (--zfactor); the DEM is read "
                     "in units of 1 m (the band's unit 'metre'): render with the bake's "
                     "--zfactor")):
                other = os.path.join(tmp, name)
                ds = gdal.GetDriverByName("GTiff").CreateCopy(other, gdal.Open(baked))
                change(ds)
                ds = None
                status, _, stderr = run("render", "-o", os.path.join(tmp, "x.png"), "--size",
                                        "200x120", "--baked", other)
                self.assertEqual(status, 1, stderr)
                self.assertEqual(len(stderr.strip().splitlines()), 1, stderr)
                self.assertIn(expected, stderr)
            # complex samples: refused by name (numpy warned, with its source line, and the
            # real parts were taken until 2026-12-07)
            other = os.path.join(tmp, "complex.tif")
            gdal.Translate(other, baked, outputType=gdal.GDT_CFloat32)
            status, _, stderr = run("render", "-o", os.path.join(tmp, "x.png"), "--size",
                                    "200x120", "--baked", other)
            self.assertEqual((status, len(stderr.strip().splitlines())), (1, 1), stderr)
            self.assertIn("complex.tif band BentNormal_E holds complex numbers (CFloat32), not "
                          "the products 'aperture bake' writes: bake this DEM", stderr)
            # the bake's EXR: said so (GDAL's "not recognized as a supported file format" until
            # 2026-12-06)
            status, _, stderr = run("render", "-o", os.path.join(tmp, "x.png"), "--size",
                                    "200x120", "--baked", os.path.join(tmp, "baked.exr"))
            self.assertEqual((status, len(stderr.strip().splitlines())), (1, 1), stderr)
            self.assertIn("baked.exr is an OpenEXR file: --baked takes the GeoTIFF 'aperture "
                          "bake' writes", stderr)
            # (a bake in the unit is taken in it)
            feet = os.path.join(tmp, "feet-baked.tif")
            status, _, stderr = run("bake", dem, feet, "-q", "--zfactor", "ft", "--products",
                                    "ApertureRadius,BentNormal")
            self.assertEqual(status, 0, stderr)
            status, _, stderr = run("render", "-o", os.path.join(tmp, "x.png"), "--size",
                                    "200x120", "--baked", feet, "--zfactor", "ft")
            self.assertEqual(status, 0, stderr)
            # nor is a DEM of the same cells in the same unit the bake's terrain when its
            # heights are others: this DEM with one cell 1 m higher (another DEM of the grid,
            # or an edit since, drew the bake's shadows silently until 2026-12-07)
            edited = os.path.join(tmp, "edited.tif")
            ds = gdal.GetDriverByName("GTiff").CreateCopy(edited, gdal.Open(dem))
            z = ds.GetRasterBand(1).ReadAsArray()
            z[170, 200] += 1
            ds.GetRasterBand(1).WriteArray(z)
            ds = None
            for source, expected in ((dem, 0), (edited, 1)):
                status, _, stderr = run("render", source, "-o", os.path.join(tmp, "x.png"),
                                        "--size", "200x120", "--baked", baked)
                self.assertEqual(status, expected, stderr)
            self.assertEqual(stderr.strip(), "aperture: error: %s was baked from other elevations "
                             "than this DEM's on the same cells (another DEM of the grid, or "
                             "this one since changed): bake this DEM again" % baked)
            # a DEM in a compound CRS: its bake is in the horizontal part (the vertical gave
            # every band its height unit) and is taken
            compound = os.path.join(tmp, "compound.tif")
            status, _, stderr = run("bake", dem, compound, "-q", "--srs", "EPSG:4326+5703",
                                    "--products", "ApertureRadius,BentNormal")
            self.assertEqual(status, 0, stderr)
            ds = gdal.Open(compound)
            self.assertFalse(ds.GetSpatialRef().IsCompound())
            # (each band its product's unit, not the vertical CRS's metre)
            self.assertEqual([ds.GetRasterBand(b).GetUnitType() for b in (1, 2)], ["degree", ""])
            ds = None
            status, _, stderr = run("render", "-o", os.path.join(tmp, "x.png"), "--size",
                                    "200x120", "--baked", compound, "--srs", "EPSG:4326+5703")
            self.assertEqual(status, 0, stderr)
            # nor from another band of a DEM of several (a bake of band 2 lit band 1's
            # terrain); a DEM of one band may be such a band copied out, and takes it
            band2 = os.path.join(tmp, "band2.tif")
            ds = gdal.GetDriverByName("GTiff").CreateCopy(band2, gdal.Open(baked))
            ds.SetMetadataItem("SOURCE_BAND", "2")
            ds = None
            two = os.path.join(tmp, "two-bands.tif")
            ds = gdal.GetDriverByName("GTiff").Create(two, src.RasterXSize, src.RasterYSize, 2,
                                                      gdal.GDT_Float32)
            ds.SetGeoTransform(src.GetGeoTransform())
            ds.SetProjection(src.GetProjection())
            for b in (1, 2):
                ds.GetRasterBand(b).WriteArray(src.GetRasterBand(1).ReadAsArray())
            ds = None
            for args, expected in (((two, "--band", 1), "was baked from band 2 of its DEM; this "
                                    "DEM is read from band 1: render with the bake's --band"),
                                   ((two, "--band", 2), None), ((dem,), None)):
                status, _, stderr = run("render", *args, "-o", os.path.join(tmp, "x.png"),
                                        "--size", "200x120", "--baked", band2)
                self.assertEqual(status, 1 if expected else 0, stderr)
                if expected:
                    self.assertIn(expected, stderr)
            src = None
            # a bake without sky where the DEM has heights (of the DEM before its voids were
            # filled; values no bake has): drawn black, and said (silent until 2026-12-06)
            holes = os.path.join(tmp, "holes.tif")
            ds = gdal.GetDriverByName("GTiff").CreateCopy(holes, gdal.Open(baked))
            names = {ds.GetRasterBand(b).GetDescription(): b for b in range(1, ds.RasterCount + 1)}
            radius = ds.GetRasterBand(names["ApertureRadius"]).ReadAsArray()
            radius[:10, :] = np.nan  # 10 rows of 403 cells: 4030
            radius[10, :5] = -1.0  # (5 more)
            ds.GetRasterBand(names["ApertureRadius"]).WriteArray(radius)
            east = ds.GetRasterBand(names["BentNormal_E"]).ReadAsArray()
            east[11, :7] = 0.5  # (not a unit vector: 7 more)
            ds.GetRasterBand(names["BentNormal_E"]).WriteArray(east)
            ds = None
            status, _, stderr = run("render", "-o", os.path.join(tmp, "x.png"), "--size",
                                    "200x120", "--baked", holes)
            self.assertEqual(status, 0, stderr)
            self.assertIn("warning: 4042 of the DEM's cells with heights (2.9%%) have no sky in "
                          "%s (nodata, or no unit BentNormal and ApertureRadius of 0..180 "
                          "degrees): they are drawn black; bake this DEM again" % holes, stderr)
            # a damaged bake (cut short, uncompressed: its header whole, its tiles missing):
            # GDAL's message, not a traceback
            whole = os.path.join(tmp, "whole.tif")
            status, _, stderr = run("bake", dem, whole, "-q", "--compress", "NONE")
            self.assertEqual(status, 0, stderr)
            cut = os.path.join(tmp, "cut.tif")
            with open(whole, "rb") as f, open(cut, "wb") as g:
                g.write(f.read(os.path.getsize(whole) // 3))
            status, _, stderr = run("render", "-o", os.path.join(tmp, "x.png"), "--size",
                                    "200x120", "--baked", cut)
            self.assertEqual(status, 1, stderr)
            self.assertEqual(len(stderr.strip().splitlines()), 1, stderr)
            self.assertIn("cannot read the baked file %s: " % cut, stderr)


if __name__ == "__main__":
    sys.exit(0 if unittest.main(exit=False).result.wasSuccessful() else 1)
