# SPDX-License-Identifier: BSD-3-Clause
"""Regression image of the embedded DEM, top view, north up, VTK lighting from the north-west
(aperture.scene, the same code `aperture render` uses). Besides the baseline comparison, the
picture's orientation is checked without the baseline: Cross Mountain (the highest cell, 11.6 km
south of the DEM centre) must project into the lower half of the image."""
import sys

from vtkmodules.test import Testing
from vtkmodules.util.numpy_support import vtk_to_numpy

import aperture
from aperture import scene


class TestRenderDefaultDEM(Testing.vtkTest):
    def testTopView(self):
        try:
            path = aperture.default_dem()
        except FileNotFoundError:
            Testing.skip()
        reader = aperture.vtkApertureDEMReader()
        reader.SetFileName(path)
        mesher = aperture.vtkApertureTerrainMesh()
        mesher.SetInputConnection(reader.GetOutputPort())
        mesher.Update()
        mesh = mesher.GetOutput()
        window, renderer = scene.build(mesh, size=(300, 300), view="top", multisamples=0)
        window.Render()

        # North up: the summit vertex lands in the lower (southern) half, right of centre.
        z = vtk_to_numpy(mesh.GetPointData().GetArray("Elevation"))
        summit = mesh.GetPoint(int(z.argmax()))
        renderer.SetWorldPoint(summit[0], summit[1], summit[2], 1.0)
        renderer.WorldToDisplay()
        x, y, _ = renderer.GetDisplayPoint()
        self.assertLess(y, 150 - 40, "the summit is not in the southern part of the picture")
        self.assertGreater(x, 150, "the summit is not east of the centre")
        # The summit is drawn in the light summit colour.
        rgb = scene.rgb_pixels(window)
        pixel = rgb[int(round(y)), int(round(x)), :3]
        self.assertGreater(int(pixel.min()), 140, "summit pixel %s is not light" % (pixel,))

        Testing.compareImage(window, Testing.getAbsImagePath("TestRenderDefaultDEM.png"))


if __name__ == "__main__":
    Testing.main([(TestRenderDefaultDEM, "test")])
