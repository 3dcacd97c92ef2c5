# SPDX-License-Identifier: BSD-3-Clause
"""scene.grab when the OpenGL driver draws nothing: Mesa's llvmpipe cannot make a multisampled
framebuffer beyond 2 GiB (`aperture render --size 12000x12000` at the default 8 samples, which
VTK lowers to 4) and says nothing; the PNG was all black, exit 0, until 2026-12-06. grab now
renders such a picture again without multisampling and warns, and raises when even that is
blank. The real case takes half a minute of llvmpipe (checked by hand at 11600 x 11600); here
the driver's blank read-back is stood in for, over a real render of a small window."""
import sys

from vtkmodules.test import Testing
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkFiltersSources import vtkPlaneSource
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkRenderer, vtkRenderWindow
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (OpenGL factory overrides)

from aperture import scene


def window(background, samples=4):
    plane = vtkPlaneSource()
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(plane.GetOutputPort())
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(*background)
    w = vtkRenderWindow()
    w.SetOffScreenRendering(1)
    w.SetMultiSamples(samples)
    w.SetSize(48, 32)
    w.AddRenderer(renderer)
    return w


class TestBlankPicture(Testing.vtkTest):
    def setUp(self):
        self.real = scene._render_pixels
        self.calls = []

    def tearDown(self):
        scene._render_pixels = self.real

    def blank_when(self, condition):
        """The driver's read-back, zeroed whenever condition(window) holds."""
        def render(w):
            image = self.real(w)
            self.calls.append(w.GetMultiSamples())
            if condition(w):
                vtk_to_numpy(image.GetPointData().GetScalars())[:] = 0
            return image
        scene._render_pixels = render

    def testMultisampledBlankIsRenderedAgain(self):
        self.blank_when(lambda w: w.GetMultiSamples() > 0)
        w = window((1.0, 1.0, 1.0))
        warnings = []
        pixels = scene.rgb_pixels(w, on_warning=warnings.append)
        # (the picture, the background alone, the picture again without multisampling)
        self.assertEqual(self.calls, [4, 4, 0])
        self.assertEqual(w.GetMultiSamples(), 0)  # (kept: the EXR capture renders it again)
        self.assertEqual(pixels.shape, (32, 48, 3))
        self.assertEqual(int(pixels.max()), 255)  # the white background, drawn
        self.assertEqual(warnings, [
            "the OpenGL driver drew nothing with 4 samples per pixel at 48 x 32 (its "
            "multisampled framebuffer's limit); the picture is rendered without antialiasing, "
            "as with --multisamples 0 (a smaller --size keeps it)"])

    def testBlankWithoutMultisamplingIsAnError(self):
        self.blank_when(lambda w: True)
        for samples, calls in ((4, [4, 4, 0, 0]), (0, [0, 0])):
            del self.calls[:]
            with self.assertRaises(RuntimeError) as e:
                scene.grab(window((1.0, 1.0, 1.0), samples))
            self.assertEqual(str(e.exception), "the OpenGL driver drew nothing into a picture "
                             "of 48 x 32 pixels (beyond its framebuffer's limits?)")
            self.assertEqual(self.calls, calls)

    def testDrawnPicturesAreLeftAlone(self):
        # a drawn picture is rendered once; over a black background a black picture may be
        # what was drawn (a sun below the horizon), so it is not rendered again
        self.blank_when(lambda w: True)
        warnings = []
        scene.grab(window((0.0, 0.0, 0.0)), on_warning=warnings.append)
        self.assertEqual((self.calls, warnings), ([4], []))
        self.blank_when(lambda w: False)
        del self.calls[:]
        scene.grab(window((1.0, 1.0, 1.0)), on_warning=warnings.append)
        self.assertEqual((self.calls, warnings), ([4], []))

    def testPictureBeyondTwoGiB(self):
        # A picture of 2 GiB or more of RGB is refused before anything is rendered: VTK's
        # window-to-image filter counts its bytes in 32 bits, and 27000 x 27000 pixels aborted
        # the process (std::bad_alloc) until 2026-12-07; one row less than 2 GiB is drawn (not
        # here: half a minute of llvmpipe drawing nothing beyond its 16384)
        self.blank_when(lambda w: False)
        w = window((1.0, 1.0, 1.0))
        for size in ((27000, 27000), (32768, 21846), (2 ** 31 // 3 + 1, 1)):
            w.SetSize(*size)
            with self.assertRaises(RuntimeError) as e:
                scene.write_png(w, "never.png")
            self.assertEqual(str(e.exception), "a picture of %d x %d pixels is 2 GiB or more of "
                             "RGB, which VTK cannot read back: render a smaller one" % size)
        self.assertEqual(self.calls, [])
        self.assertLess(3 * 32768 * 21845, 2 ** 31)

    def testUnlitViewFillingTerrain(self):
        # Terrain unlit (a night frame of a time-lapse) filling the view over a white
        # background is a black picture the driver drew: the background, drawn alone, shows
        # the driver works, and the picture is kept, multisampled, without a word. Until
        # 2026-12-06 such frames were refused as "the OpenGL driver drew nothing".
        self.blank_when(lambda w: False)
        w = window((1.0, 1.0, 1.0))
        renderer = w.GetRenderers().GetFirstRenderer()
        actor = renderer.GetActors().GetLastActor()
        actor.GetProperty().SetColor(0.0, 0.0, 0.0)
        actor.GetProperty().SetSpecular(0.0)
        renderer.ResetCamera()
        renderer.GetActiveCamera().Zoom(3.0)  # (the plane beyond every edge of the view)
        warnings = []
        pixels = scene.rgb_pixels(w, on_warning=warnings.append)
        self.assertEqual(int(pixels.max()), 0)
        self.assertEqual((self.calls, warnings), ([4, 4], []))
        self.assertEqual(w.GetMultiSamples(), 4)
        self.assertTrue(actor.GetVisibility())  # (shown again after the background's check)


if __name__ == "__main__":
    Testing.main([(TestBlankPicture, "test")])
