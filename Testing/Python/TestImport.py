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


if __name__ == "__main__":
    sys.exit(0 if unittest.main(exit=False).result.wasSuccessful() else 1)
