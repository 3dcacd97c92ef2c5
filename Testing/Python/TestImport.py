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
