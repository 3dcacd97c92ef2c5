# SPDX-License-Identifier: BSD-3-Clause
"""`import aperture` works with /usr/bin/python3 and exposes the wrapped classes."""
import sys
import unittest


class TestImport(unittest.TestCase):
    def test_classes(self):
        import aperture
        for name in ("vtkApertureDEMReader", "vtkApertureDEMWriter", "vtkApertureGeoreference",
                     "vtkApertureTerrainMesh", "vtkApertureLightingMapper"):
            cls = getattr(aperture, name)
            obj = cls()
            self.assertEqual(obj.GetClassName(), name)
        self.assertRegex(aperture.__version__, r"^\d+\.\d+\.\d+$")

    def test_rendering_on_demand(self):
        # The Rendering module is imported when one of its classes is first asked for, in
        # every way of asking; the package's list of them is the module's.
        import subprocess
        code = ("import sys, aperture; before = 'aperture.ApertureRendering' in sys.modules; "
                "%s; print(before, 'aperture.ApertureRendering' in sys.modules)")
        for ask in ("aperture.vtkApertureLinearCapture()",
                    "from aperture import vtkApertureLightingMapper",
                    "exec('from aperture import *'); vtkApertureLightingMapper()"):
            p = subprocess.run([sys.executable, "-c", code % ask], capture_output=True,
                               text=True, timeout=120)
            self.assertEqual(p.stdout.split(), ["False", "True"], p.stderr)
        import aperture
        from aperture import ApertureRendering
        self.assertEqual(set(aperture._RENDERING),
                         {n for n in dir(ApertureRendering) if n.startswith("vtkAperture")})
        self.assertTrue(set(aperture._RENDERING) <= set(dir(aperture)))
        with self.assertRaises(AttributeError):
            aperture.vtkApertureNothing

    def test_vtk_pipeline_types(self):
        # The classes are real VTK algorithms that connect to VTK's own.
        from vtkmodules.vtkImagingCore import vtkImageShiftScale
        import aperture
        shift = vtkImageShiftScale()
        mesh = aperture.vtkApertureTerrainMesh()
        mesh.SetInputConnection(shift.GetOutputPort())
        self.assertTrue(mesh.IsA("vtkPolyDataAlgorithm"))
        self.assertTrue(aperture.vtkApertureDEMReader().IsA("vtkImageAlgorithm"))

    def test_cli_main_puts_vtk_output_back(self):
        # aperture.cli.main quiets VTK's console output while it runs, and only then: until
        # 2026-12-06 a script's own failing update printed nothing after one call of it
        import subprocess
        code = ("import sys, aperture, aperture.cli\n"
                "r = aperture.vtkApertureDEMReader()\n"
                "r.SetFileName('/nonexistent/before.tif')\n"
                "r.Update()\n"
                "status = aperture.cli.main(['info', '/nonexistent/cli.tif'])\n"
                "r.SetFileName('/nonexistent/after.tif')\n"
                "r.Update()\n"
                "sys.exit(status)\n")
        p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           timeout=120)
        self.assertEqual(p.returncode, 1, p.stderr)
        self.assertIn("file '/nonexistent/before.tif' does not exist", p.stderr)
        self.assertIn("aperture: error: file '/nonexistent/cli.tif' does not exist\n", p.stderr)
        self.assertIn("file '/nonexistent/after.tif' does not exist", p.stderr)
        self.assertEqual(p.stderr.count("cli.tif"), 1, p.stderr)  # (VTK's own kept off)

    def test_watcher_update(self):
        # aperture.errors.Watcher.update raises on every failure, not only the first: until
        # 2026-12-06 a second update of a reader that had failed returned an empty image (VTK's
        # executive took the failed run as up to date), as did an extent outside the raster
        import os
        import tempfile
        import numpy as np
        from osgeo import gdal
        import aperture
        from aperture.errors import ApertureError, Watcher, quiet_vtk_output
        quiet_vtk_output()
        watcher = Watcher()
        reader = watcher.watch(aperture.vtkApertureDEMReader())
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "dem.tif")
            reader.SetFileName(path)
            for _ in range(3):
                with self.assertRaises(ApertureError) as caught:
                    watcher.update(reader, "reading")
                self.assertEqual(str(caught.exception), "reading: file '%s' does not exist"
                                 % path)
            dataset = gdal.GetDriverByName("GTiff").Create(path, 5, 4, 1, gdal.GDT_Float32)
            dataset.SetGeoTransform([500000.0, 30.0, 0.0, 5000000.0, 0.0, -30.0])
            dataset.SetProjection("EPSG:32633")
            dataset.GetRasterBand(1).WriteArray(np.arange(20, dtype=np.float32).reshape(4, 5))
            dataset = None
            # the file there now: read at once, without a Modified() of the caller's
            self.assertEqual(watcher.update(reader).GetDimensions(), (5, 4, 1))
            for extent in ([0, 9, 0, 3, 0, 0], [3, 2, 0, 3, 0, 0], [-1, 2, 0, 3, 0, 0],
                           [0, 2, 0, 3]):
                with self.assertRaises(ApertureError, msg=extent) as caught:
                    watcher.update(reader, extent=extent)
                self.assertIn("is not a non-empty part of the whole extent [0, 4, 0, 3, 0, 0]",
                              str(caught.exception))
            # (the whole image, read before, holds the part asked for)
            image = watcher.update(reader, extent=[1, 2, 0, 3, 0, 0])
            self.assertEqual(image.GetExtent(), (0, 4, 0, 3, 0, 0))


if __name__ == "__main__":
    sys.exit(0 if unittest.main(exit=False).result.wasSuccessful() else 1)
