# SPDX-License-Identifier: BSD-3-Clause
"""A global DEM (2-degree cells, 360 degrees of longitude, pole to pole) drawn from beyond its
antimeridian, the seam of its grid, with an image draped by the mesh's texture coordinates: the
globe is closed there and the image continues across it. The image's last column (red) lies
west of the seam and its first (green) east of it, every pixel of the seam's line on the disc
is drawn, red and green meet there, and no other colour appears beside the seam. Before the
mesh joined the edges, a gap of a cell ran down the middle (the globe's far side, seen from
inside, showed through it); a seam quad without its own vertices would have squeezed the
whole image into that column. Both poles, seen from
their sides, are closed too."""
import numpy as np
from vtkmodules.test import Testing
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow, vtkTexture)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL implementations)

import aperture
from aperture import scene

NX, NY, SIZE = 180, 90, 400
A = 6378137.0  # WGS 84; the frame's origin (latitude 0, longitude 0) lies A above the centre
RED, GREEN, GREY = (255, 0, 0), (0, 255, 0), (128, 128, 128)


def global_mesh():
    dem = vtkImageData()
    dem.SetDimensions(NX, NY, 1)
    dem.SetOrigin(-179.0, -89.0, 0.0)
    dem.SetSpacing(2.0, 2.0, 1.0)
    z = numpy_to_vtk(np.zeros(NX * NY, np.float32), deep=1)
    z.SetName("Elevation")
    dem.GetPointData().SetScalars(z)
    geo = aperture.vtkApertureGeoreference()
    geo.SetCRS("EPSG:4326")
    geo.AttachToImage(dem)
    mesher = aperture.vtkApertureTerrainMesh()
    mesher.SetInputData(dem)
    mesher.Update()
    return mesher.GetOutput()


def drape():
    """An image of the globe's cells: grey, its first column green and its last red."""
    rgb = np.empty((NY, NX, 3), np.uint8)
    rgb[:] = GREY
    rgb[:, 0] = GREEN
    rgb[:, -1] = RED
    image = vtkImageData()
    image.SetDimensions(NX, NY, 1)
    colours = numpy_to_vtk(rgb.reshape(-1, 3), deep=1)
    image.GetPointData().SetScalars(colours)
    texture = vtkTexture()
    texture.SetInputData(image)
    texture.InterpolateOff()  # (the texels' own colours)
    return texture


def picture(mesh, position, up):
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(mesh)
    mapper.ScalarVisibilityOff()
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.SetTexture(drape())
    actor.GetProperty().SetAmbient(1.0)  # unlit: the texture's colours as they are
    actor.GetProperty().SetDiffuse(0.0)
    actor.GetProperty().SetSpecular(0.0)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(0.0, 0.0, 1.0)
    window = vtkRenderWindow()
    window.SetSize(SIZE, SIZE)
    window.SetMultiSamples(0)
    window.AddRenderer(renderer)
    camera = renderer.GetActiveCamera()
    camera.SetFocalPoint(0.0, 0.0, -A)
    camera.SetPosition(*position)
    camera.SetViewUp(*up)
    camera.SetViewAngle(30.0)
    renderer.ResetCameraClippingRange()
    return window, scene.rgb_pixels(window).astype(int)


class TestRenderGlobalDEM(Testing.vtkTest):
    def testSeamAndPoles(self):
        mesh = global_mesh()
        # beyond the antimeridian on the equator (the frame's -z side), north up: east is to
        # the right, so the seam runs down the middle with red west of it, green east
        window, rgb = picture(mesh, (0.0, 0.0, -A - 5.0 * A), (0.0, 1.0, 0.0))
        background = (rgb == (0, 0, 255)).all(axis=2)
        disc = ~background
        rows = np.flatnonzero(disc[:, SIZE // 2])
        self.assertGreater(len(rows), SIZE // 3, "no globe in the picture")
        # the disc's middle 80% of rows: every pixel on and beside the seam drawn
        top, bottom = rows[0], rows[-1]
        inner = slice(top + (bottom - top) // 10, bottom - (bottom - top) // 10)
        middle = rgb[inner, SIZE // 2 - 12:SIZE // 2 + 12]
        self.assertFalse((middle == (0, 0, 255)).all(axis=2).any(),
                         "background shows through at the seam")
        red = (middle == RED).all(axis=2)
        green = (middle == GREEN).all(axis=2)
        grey = (middle == GREY).all(axis=2)
        self.assertTrue((red | green | grey).all(), "other colours beside the seam")
        for r in range(middle.shape[0]):
            reds, greens = np.flatnonzero(red[r]), np.flatnonzero(green[r])
            self.assertTrue(len(reds) and len(greens), "row %d lacks a side of the seam" % r)
            # (through a gap the globe's far side would show, grey, between them)
            self.assertEqual(greens.min(), reds.max() + 1,
                             "row %d: red and green do not meet at the seam" % r)
        # the poles, seen from beside them: drawn all round (no hole in the middle)
        for pole in (1.0, -1.0):
            window, rgb = picture(mesh, (0.0, pole * 6.0 * A, -A), (0.0, 0.0, 1.0))
            centre = rgb[SIZE // 2 - 8:SIZE // 2 + 8, SIZE // 2 - 8:SIZE // 2 + 8]
            self.assertFalse((centre == (0, 0, 255)).all(axis=2).any(),
                             "a hole at the %s pole" % ("north" if pole > 0 else "south"))


if __name__ == "__main__":
    Testing.main([(TestRenderGlobalDEM, "test")])
