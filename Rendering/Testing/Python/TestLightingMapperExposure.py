# SPDX-License-Identifier: BSD-3-Clause
"""vtkApertureLightingMapper with the STANDARD lighting model (VTK's lighting, no aperture
arrays needed): exposure is applied in its fragment shader: on a flat, uniformly lit square,
+1 EV doubles and -1 EV halves the pixel values of exposure 0 (up to 8-bit rounding), and
exposure 0 matches VTK's own mapper exactly."""
import math
import sys

from vtkmodules.test import Testing
from vtkmodules.vtkFiltersSources import vtkPlaneSource
from vtkmodules.vtkRenderingCore import (
    vtkActor,
    vtkLight,
    vtkPolyDataMapper,
    vtkRenderer,
    vtkRenderWindow,
)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (OpenGL factory overrides)

import aperture
from aperture import scene


def render(mapper, size=64):
    plane = vtkPlaneSource()
    mapper.SetInputConnection(plane.GetOutputPort())
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(0.5, 0.5, 0.5)
    actor.GetProperty().SetAmbient(0.0)
    actor.GetProperty().SetDiffuse(0.5)
    actor.GetProperty().SetSpecular(0.0)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    renderer.AutomaticLightCreationOff()
    light = vtkLight()
    light.SetLightTypeToSceneLight()
    light.SetPositional(False)
    light.SetPosition(0, 0, 1)
    light.SetFocalPoint(0, 0, 0)
    renderer.AddLight(light)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(size, size)
    window.AddRenderer(renderer)
    renderer.ResetCamera()
    renderer.GetActiveCamera().Zoom(3.0)  # the plane fills the window
    return scene.rgb_pixels(window).reshape(-1, 3).astype(float).mean(axis=0)


class TestLightingMapperExposure(Testing.vtkTest):
    def testExposure(self):
        base = render(vtkPolyDataMapper())
        self.assertTrue(60 < base[0] < 70, base)  # 0.5 * 0.5 * 255 = 63.75
        values = {}
        for ev in (-1.0, 0.0, 1.0):
            mapper = aperture.vtkApertureLightingMapper()
            mapper.SetLightingModel(mapper.STANDARD)
            mapper.SetExposure(ev)
            values[ev] = render(mapper)
        for c in range(3):
            self.assertEqual(values[0.0][c], base[c])
            self.assertLessEqual(abs(values[1.0][c] - 2 * base[c]), 1.0)
            self.assertLessEqual(abs(values[-1.0][c] - 0.5 * base[c]), 1.0)

    def testRange(self):
        mapper = aperture.vtkApertureLightingMapper()
        mapper.SetExposure(100.0)
        self.assertEqual(mapper.GetExposure(), 30.0)

    def testAutoExposure(self):
        # 2^-EV = L = 0.8 (E_sun sin e + pi L_sky) / pi, e at least 12 degrees (scene.py): a
        # grey sun of 1000 W/m2 overhead gives L = 800 / pi; at 5 degrees it counts as 12; a sky
        # of 100 W/m2/sr alone gives L = 80. No light at all (a night frame) has no exposure to
        # set: 0 EV (until 2026-12-06, 19.93 EV, from the floor of 1e-6 on L).
        grey = (1000.0, 1000.0, 1000.0)
        self.assertAlmostEqual(scene.auto_exposure(grey, 90.0, (0, 0, 0)),
                               -math.log2(800.0 / math.pi), places=6)
        self.assertAlmostEqual(scene.auto_exposure(grey, 5.0, (0, 0, 0)),
                               -math.log2(800.0 * math.sin(math.radians(12.0)) / math.pi),
                               places=6)
        self.assertAlmostEqual(scene.auto_exposure((0, 0, 0), 30.0, (100.0, 100.0, 100.0)),
                               -math.log2(80.0), places=6)
        self.assertEqual(scene.auto_exposure((0, 0, 0), -30.0, (0, 0, 0)), 0.0)


if __name__ == "__main__":
    Testing.main([(TestLightingMapperExposure, "test")])
