# SPDX-License-Identifier: BSD-3-Clause
"""Regression images of the embedded DEM lit by vtkApertureLightingMapper (aperture.scene, the
code `aperture render` uses), each baseline looked at before it was committed, plus checks
that need no baseline:

- summer midday (2026-06-21 13:40 EDT) is brighter than a low winter evening sun
  (2026-12-21 16:15 EST) in linear radiance (the pictures are each auto-exposed), and in the
  evening the slopes facing the sun (south-west) are brighter than those facing away;
- smoothstep and exact intersections give nearly the same picture (mean within 3%) but not the
  same pixels;
- a widened sun (x20) softens the evening's shadow edges: less local contrast;
- sky only (sun below the horizon): no directional light, so sun-facing and opposite slopes
  are alike, and valleys are darker than ridges;
- an albedo texture (stripes) shows through the lighting;
- aperture.scene refuses bad arguments by name before any drawing (and set_sun's constant sky
  replaces a model's table).

Set APERTURE_WRITE_IMAGES=folder to write the rendered images there (for new baselines).
"""
import math
import os
import stat
import sys
import tempfile

import numpy as np
from vtkmodules.test import Testing
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPolyData
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkRenderingCore import vtkTexture

import aperture
from aperture import scene

SIZE = (320, 220)
_MESH = {}


def mesh_and_dem():
    if not _MESH:
        reader = aperture.vtkApertureDEMReader()
        reader.SetFileName(aperture.default_dem())
        sky = aperture.vtkApertureSkyVisibility()
        sky.SetInputConnection(reader.GetOutputPort())
        mesher = aperture.vtkApertureTerrainMesh()
        mesher.SetInputConnection(sky.GetOutputPort())
        mesher.SetVerticalExaggeration(2.0)
        mesher.Update()
        _MESH["mesh"], _MESH["dem"] = mesher.GetOutput(), reader.GetOutput()
    return _MESH["mesh"], _MESH["dem"]


def sun_at(when=None, direction=None):
    _, dem = mesh_and_dem()
    sun = aperture.vtkApertureSolarPosition()
    assert sun.SetPlaceFromImage(dem)
    if when:
        assert sun.SetTime(when) and sun.Compute(), sun.GetErrorMessage()
    else:
        assert sun.ComputeForDirection(*direction)
    return sun


def render(name, sun, **options):
    mesh, _ = mesh_and_dem()
    window, renderer, mapper = scene.build_aperture(mesh, sun, size=SIZE, multisamples=0,
                                                    **options)
    folder = os.environ.get("APERTURE_WRITE_IMAGES")
    if folder:
        scene.write_png(window, os.path.join(folder, name + ".png"))
    rgb = scene.rgb_pixels(window)
    return window, renderer, rgb[::-1].astype(float)  # row 0 at the top


def terrain(rgb):
    """Pixels of the terrain (not the white background)."""
    return rgb[rgb.sum(axis=2) < 750]


def aspect_means(renderer, rgb, mesh):
    """Mean luminance of south-west-facing and north-east-facing terrain pixels (by the mesh
    normal at the vertex projected into each pixel)."""
    normals = vtk_to_numpy(mesh.GetPointData().GetArray("Normals"))
    sw, ne = [], []
    for k in range(0, mesh.GetNumberOfPoints(), 7):
        n = normals[k]
        if n[2] > 0.97:
            continue  # flat
        facing = (n[0] * -0.707 + n[1] * -0.707) / math.hypot(n[0], n[1])
        p = mesh.GetPoint(k)
        renderer.SetWorldPoint(p[0], p[1], p[2], 1.0)
        renderer.WorldToDisplay()
        x, y, _ = renderer.GetDisplayPoint()
        i, j = int(round(x)), SIZE[1] - 1 - int(round(y))
        if 0 <= i < SIZE[0] and 0 <= j < SIZE[1]:
            value = rgb[j, i].mean()
            (sw if facing > 0.7 else ne if facing < -0.7 else []).append(value)
    return np.mean(sw), np.mean(ne)


def mean_radiance(window, renderer, rgb):
    """Mean linear radiance (W/m2/sr, the mean of R, G and B) of the terrain pixels of a
    rendered scene, read back unclamped at EV 0 without tone mapping."""
    mapper = renderer.GetActors().GetLastActor().GetMapper()
    mapper.SetExposure(0.0)
    mapper.SetToneMapping(False)
    image = aperture.vtkApertureLinearCapture().Capture(renderer)
    radiance = vtk_to_numpy(image.GetPointData().GetArray("Radiance"))
    radiance = radiance.reshape(SIZE[1], SIZE[0], 4)[::-1, :, :3]  # row 0 at the top
    return radiance[rgb.sum(axis=2) < 750].mean()


def local_contrast(rgb):
    g = rgb.mean(axis=2)
    return np.abs(np.diff(g, axis=1))[g[:, 1:] < 250].mean()


class TestRenderApertureDEM(Testing.vtkTest):
    def compare(self, window, name):
        if os.environ.get("APERTURE_WRITE_IMAGES"):
            return  # writing new candidate baselines: nothing to compare with
        Testing.compareImage(window, Testing.getAbsImagePath(name + ".png"))

    def testSummerAndWinter(self):
        mesh, _ = mesh_and_dem()
        summer = sun_at("2026-06-21T13:40-04:00")
        winter = sun_at("2026-12-21T16:15-05:00")
        self.assertGreater(summer.GetElevation(), 70)
        self.assertTrue(5 < winter.GetElevation() < 12, winter.GetElevation())
        ws, _, s_rgb = render("TestApertureSummerMidday", summer)
        self.compare(ws, "TestApertureSummerMidday")
        ww, wren, w_rgb = render("TestApertureWinterEvening", winter)
        self.compare(ww, "TestApertureWinterEvening")
        # both auto-exposed, yet the low sun leaves most slopes in shade
        self.assertGreater(terrain(s_rgb).std(axis=0).mean(), 1.0)
        sw, ne = aspect_means(wren, w_rgb, mesh)
        self.assertGreater(sw, ne + 20, (sw, ne))
        # In radiance, the midday sun at 72 degrees lights the terrain several times as much
        # as the evening's at 8 (on level ground sin 72 / sin 8 = 6.8 for the beam alone, whose
        # clear-sky irradiance is also weaker through the evening's longer air path)
        ratio = (mean_radiance(ws, ws.GetRenderers().GetFirstRenderer(), s_rgb) /
                 mean_radiance(ww, wren, w_rgb))
        self.assertGreater(ratio, 3.0)  # (4.5 measured)

    def testSmoothstepAndWideSun(self):
        winter = sun_at("2026-12-21T16:15-05:00")
        _, _, exact = render("exact", winter)
        ws, _, smooth = render("TestApertureSmoothstep", winter, intersection="smoothstep")
        self.compare(ws, "TestApertureSmoothstep")
        self.assertAlmostEqual(terrain(smooth).mean() / terrain(exact).mean(), 1.0, delta=0.03)
        self.assertGreater(np.abs(smooth - exact).max(), 5)
        ww, _, wide = render("TestApertureWideSun", winter, sun_scale=20.0)
        self.compare(ww, "TestApertureWideSun")
        self.assertLess(local_contrast(wide), local_contrast(exact))

    def testUnknownOptions(self):
        # a misspelt mode is an error, not the default mode drawn without a word
        mesh, _ = mesh_and_dem()
        sun = sun_at(direction=(225.0, 30.0))
        for options, named in (({"intersection": "smooth"}, "intersection must be exact or "
                                "smoothstep, not 'smooth'"),
                               ({"lambert": "exact"}, "lambert must be centroid or exactcap"),
                               ({"shading": "fragment"}, "shading must be pixel or vertex"),
                               ({"view": "side"}, "view must be one of"),
                               ({"sky_mode": "tabled"}, "sky_mode must be constant or model")):
            with self.assertRaises(ValueError) as caught:
                scene.build_aperture(mesh, sun, size=SIZE, **options)
            self.assertIn(named, str(caught.exception))

    def testBadArguments(self):
        # Each a clear exception naming the argument, before anything is drawn (until
        # 2026-12-06 these drew a wrong picture, kept an old value with a VTK error on stderr,
        # raised ZeroDivisionError, or crashed: write_png's text=[("Comment", None)])
        mesh, _ = mesh_and_dem()
        sun = sun_at(direction=(225.0, 30.0))
        for options, error, named in (
                ({"sun_scale": 0.0}, ValueError, "sun_scale must be above 0, not 0.0"),
                ({"sun_scale": float("nan")}, ValueError, "sun_scale must be finite"),
                ({"sky": (-1.0, -1.0, -1.0)}, ValueError, "sky must be at least 0, not -1.0"),
                ({"sky": (float("nan"),) * 3}, ValueError, "sky must be finite"),
                ({"sky": (40.0, 46.0)}, TypeError, "sky must be 3 numbers"),
                ({"exposure": float("nan")}, ValueError, "exposure must be finite"),
                ({"exposure": "bright"}, TypeError, "exposure must be a number, not 'bright'"),
                ({"size": (0, 0)}, ValueError, "size must be at least 1, not 0"),
                ({"size": (-10, -10)}, ValueError, "size must be at least 1, not -10"),
                ({"size": (100.5, 80)}, ValueError, "size must be whole pixels"),
                ({"multisamples": -1}, ValueError, "multisamples must be within [0, 16]"),
                ({"camera": (180.0, 35.0, 0.0)}, ValueError,
                 "camera zoom must be within [0.001, 10000], not 0.0"),
                ({"camera": (float("nan"), 35.0)}, ValueError, "camera azimuth must be finite"),
                ({"camera": 180.0}, TypeError, "camera must be (azimuth, elevation)"),
                ({"camera": "180,35"}, TypeError, "camera must be (azimuth, elevation)"),
                ({"exposure": "5"}, TypeError, "exposure must be a number, not '5'"),
                ({"sun_scale": "2"}, TypeError, "sun_scale must be a number, not '2'"),
                ({"sky": "123"}, TypeError, "sky must be 3 numbers, not '123'"),
                ({"size": ("64", "48")}, TypeError, "size must be a number, not '64'"),
                ({"multisamples": True}, TypeError, "multisamples must be a number, not True"),
                ({"background": (1.0, 1.0)}, TypeError, "background must be 3 numbers")):
            with self.assertRaises(error, msg=options) as caught:
                scene.build_aperture(mesh, sun, **options)
            self.assertIn(named, str(caught.exception))
        for options, named in (({"light_azimuth": float("nan")}, "light azimuth must be finite"),
                               ({"light_elevation": float("nan")}, "light elevation must be"),
                               ({"exposure": float("inf")}, "exposure must be finite"),
                               ({"size": (40, 0)}, "size must be at least 1")):
            with self.assertRaises(ValueError, msg=options) as caught:
                scene.build(mesh, **options)
            self.assertIn(named, str(caught.exception))
        # a sun not computed is refused with `sky` given too (it was drawn all white)
        with self.assertRaises(ValueError):
            scene.build_aperture(mesh, aperture.vtkApertureSolarPosition(), sky=(40, 46, 58))
        # a mesh without the aperture's arrays (it was drawn with VTK's lighting instead)
        plain = vtkPolyData()
        plain.ShallowCopy(mesh)
        plain.GetPointData().RemoveArray("BentNormal")
        with self.assertRaises(ValueError) as caught:
            scene.build_aperture(plain, sun)
        self.assertIn("the mesh has no point array 'BentNormal'", str(caught.exception))
        # set_sun: a mistyped sky mode, and a mapper left unchanged by a refused call
        _, _, mapper = scene.build_aperture(mesh, sun, size=SIZE, sky_mode="model")
        self.assertIsNotNone(mapper.GetSkyTable())
        for mode in ("Model", "uniform"):
            with self.assertRaises(ValueError) as caught:
                scene.set_sun(mapper, sun, mode)
            self.assertIn("sky_mode must be constant or model", str(caught.exception))
        with self.assertRaises(ValueError):
            scene.set_sun(mapper, aperture.vtkApertureSolarPosition(), "constant", sky=(1, 1, 1))
        self.assertIsNotNone(mapper.GetSkyTable())
        # ... and a constant sky takes the model's table away (it stayed, and `sky` was unseen)
        scene.set_sun(mapper, sun, "constant", sky=(400.0, 400.0, 400.0))
        self.assertIsNone(mapper.GetSkyTable())
        self.assertEqual(list(mapper.GetSkyRadiance()), [400.0, 400.0, 400.0])
        # numbers as numpy gives them are numbers
        scene.build_aperture(mesh, sun, size=np.array([64, 48]), multisamples=np.int64(0),
                             camera=np.array([180.0, 35.0]), exposure=np.float32(-3.0))
        # aim_light is for build()'s renderers: an aperture one has no light of its own, nor
        # once drawn, when VTK has made one
        window, renderer, _ = scene.build_aperture(mesh, sun, size=(64, 48), multisamples=0)
        ambient = renderer.GetActors().GetLastActor().GetProperty().GetAmbient()
        for drawn in (False, True):
            if drawn:
                window.Render()
            with self.assertRaises(ValueError) as caught:
                scene.aim_light(renderer, 270.0, 30.0)
            self.assertIn("a renderer made by build()", str(caught.exception))
            self.assertEqual(renderer.GetActors().GetLastActor().GetProperty().GetAmbient(),
                             ambient)
        # colours of an elevation range that is not one
        with self.assertRaises(ValueError):
            scene.hypsometric_colors(100.0, 0.0)
        nodata = vtkPolyData()
        nodata.ShallowCopy(mesh)
        z = numpy_to_vtk(np.full(mesh.GetNumberOfPoints(), np.nan, np.float32), deep=1)
        z.SetName("Elevation")
        nodata.GetPointData().AddArray(z)
        with self.assertRaises(ValueError) as caught:
            scene.elevation_range(nodata)
        self.assertIn("has no finite value (all nodata)", str(caught.exception))

    def testPngText(self):
        mesh, _ = mesh_and_dem()
        window, _, _ = scene.build_aperture(mesh, sun_at(direction=(225.0, 30.0)), size=(40, 30),
                                            multisamples=0)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "t.png")
            for text, error in (([("Comment", None)], TypeError), ([("Comment",)], TypeError),
                                ([("", "x")], ValueError), ([("k" * 80, "x")], ValueError),
                                ([(" Title", "x")], ValueError), ([("Титул", "x")], ValueError),
                                ([("Comment", "a\0b")], ValueError),
                                ([("Comment", "€")], ValueError)):
                with self.assertRaises(error, msg=text):
                    scene.write_png(window, path, text=text)
                self.assertFalse(os.path.exists(path), text)
            # a folder, or a name in a folder that does not exist: said so, before VTK's writer
            # tries (it printed "Ran out of disk space; deleting file(s)")
            with open(os.path.join(tmp, "file"), "w"):
                pass
            for name, said in ((tmp, "it is a folder"),
                               (os.path.join(tmp, "no", "t.png"), "the folder %s does not exist"
                                % os.path.join(tmp, "no")),
                               (os.path.join(tmp, "file", "t.png"), "%s is not a folder"
                                % os.path.join(tmp, "file"))):
                with self.assertRaises(OSError) as caught:
                    scene.write_png(window, name)
                self.assertEqual(str(caught.exception), "cannot write the PNG %s: %s"
                                 % (name, said))
            # Latin-1 written as Latin-1 (VTK alone would write the UTF-8 bytes of "Zürich")
            scene.write_png(window, path, text=[("Place", "Zürich"), ("Author", "Ægir")])
            with open(path, "rb") as f:
                self.assertIn(b"tEXtPlace\0Z\xfcrich", f.read())
            reader = vtkPNGReader()
            reader.SetFileName(path)
            reader.Update()
            self.assertEqual(reader.GetNumberOfTextChunks(), 2)
            # written aside and renamed into place: a failed write (over a limit on file
            # sizes here, as on a full disk) leaves an earlier file as it was (until 2026-12-07
            # it was gone) and no temporary file; a file replaced keeps its permissions, and a
            # symbolic link stays one, its target written
            import resource
            import signal
            keep = os.path.join(tmp, "keep.png")
            with open(keep, "wb") as f:
                f.write(b"an earlier frame")
            os.chmod(keep, 0o640)
            limits = resource.getrlimit(resource.RLIMIT_FSIZE)
            handler = signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
            resource.setrlimit(resource.RLIMIT_FSIZE, (100, limits[1]))
            try:
                with self.assertRaises(OSError) as caught:
                    scene.write_png(window, keep)
            finally:
                resource.setrlimit(resource.RLIMIT_FSIZE, limits)
                signal.signal(signal.SIGXFSZ, handler)
            self.assertIn("cannot write the PNG %s: the write failed" % keep,
                          str(caught.exception))
            with open(keep, "rb") as f:
                self.assertEqual(f.read(), b"an earlier frame")
            self.assertEqual([n for n in os.listdir(tmp) if n.endswith(".tmp")], [])
            scene.write_png(window, keep)
            self.assertEqual(os.stat(keep).st_mode & 0o777, 0o640)
            with open(keep, "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
            link = os.path.join(tmp, "latest.png")
            os.symlink("keep.png", link)
            os.remove(keep)
            umask = os.umask(0o027)
            try:
                self.assertEqual(scene.write_png(window, link), link)
            finally:
                os.umask(umask)
            self.assertTrue(os.path.islink(link) and os.path.isfile(keep))
            self.assertEqual(os.stat(keep).st_mode & 0o777, 0o640)  # (as open() makes a file)
            # what is no file is not renamed over (a pipe became a PNG)
            fifo = os.path.join(tmp, "fifo.png")
            os.mkfifo(fifo)
            with self.assertRaises(OSError) as caught:
                scene.write_png(window, fifo)
            self.assertEqual(str(caught.exception),
                             "cannot write the PNG %s: it is not a file" % fifo)
            self.assertTrue(stat.S_ISFIFO(os.stat(fifo).st_mode))

    def testSkyOnly(self):
        mesh, _ = mesh_and_dem()
        below = sun_at(direction=(225.0, -5.0))
        window, renderer, rgb = render("TestApertureSkyOnly", below, sky=(40.0, 46.0, 58.0),
                                       exposure=-5.5)
        self.compare(window, "TestApertureSkyOnly")
        sw, ne = aspect_means(renderer, rgb, mesh)
        self.assertLess(abs(sw - ne), 6, (sw, ne))
        self.assertGreater(terrain(rgb).mean(), 40)

    def testAlbedoTexture(self):
        # Stripes of albedo 0.2 and 0.8 running north-south, eight across the DEM.
        stripes = np.tile(np.where((np.arange(256) // 32) % 2 == 0, 50, 205).astype(np.uint8),
                          (256, 1))
        image = vtkImageData()
        image.SetDimensions(256, 256, 1)
        data = numpy_to_vtk(np.repeat(stripes.ravel()[:, None], 3, axis=1), deep=1)
        image.GetPointData().SetScalars(data)
        texture = vtkTexture()
        texture.SetInputData(image)
        winter = sun_at("2026-12-21T12:30-05:00")
        window, _, rgb = render("TestApertureAlbedo", winter, texture=texture)
        self.compare(window, "TestApertureAlbedo")
        # the stripes show: the picture's columns alternate dark and light
        columns = rgb[SIZE[1] // 2 - 20:SIZE[1] // 2 + 20].mean(axis=(0, 2))
        self.assertGreater(columns.max() - columns.min(), 80)


if __name__ == "__main__":
    Testing.main([(TestRenderApertureDEM, "test")])
