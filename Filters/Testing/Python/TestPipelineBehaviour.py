# SPDX-License-Identifier: BSD-3-Clause
"""Aperture's filters behave like VTK's own in a pipeline: progress events, re-execution when
a property changes (and only then), and streaming: a DEM meshed piece by piece (the reader
reading only each piece's rows) gives exactly the vertices of the whole mesh, in the same
frame."""
import sys

import numpy as np
from vtkmodules.test import Testing
from vtkmodules.util.numpy_support import vtk_to_numpy

import aperture


class TestPipelineBehaviour(Testing.vtkTest):
    def setUp(self):
        try:
            self.path = aperture.default_dem()
        except FileNotFoundError:
            Testing.skip()

    def testProgressEvents(self):
        reader = aperture.vtkApertureDEMReader()
        reader.SetFileName(self.path)
        mesher = aperture.vtkApertureTerrainMesh()
        mesher.SetInputConnection(reader.GetOutputPort())
        seen = {"reader": [], "mesher": []}
        reader.AddObserver("ProgressEvent", lambda o, e: seen["reader"].append(o.GetProgress()))
        mesher.AddObserver("ProgressEvent", lambda o, e: seen["mesher"].append(o.GetProgress()))
        mesher.Update()
        for name, values in seen.items():
            self.assertTrue(values, name)
            self.assertEqual(values[-1], 1.0, name)
            self.assertEqual(values, sorted(values), name)

    def testReexecution(self):
        reader = aperture.vtkApertureDEMReader()
        reader.SetFileName(self.path)
        mesher = aperture.vtkApertureTerrainMesh()
        mesher.SetInputConnection(reader.GetOutputPort())
        runs = []
        mesher.AddObserver("StartEvent", lambda o, e: runs.append(1))
        mesher.Update()
        mesher.Update()
        self.assertEqual(len(runs), 1)
        z1 = mesher.GetOutput().GetBounds()[5]
        mesher.SetVerticalExaggeration(3.0)
        mesher.Update()
        self.assertEqual(len(runs), 2)
        # Heights scale about the ellipsoid: the top of the mesh triples (within the curvature
        # drop, which exaggeration does not scale: < 100 m over 16 km).
        self.assertLess(abs(mesher.GetOutput().GetBounds()[5] - 3.0 * z1), 2.0 * 100.0)
        reader.SetDecimation(2)
        mesher.Update()
        self.assertEqual(len(runs), 3)
        self.assertEqual(mesher.GetOutput().GetNumberOfPoints(), 201 * 172)

    def testStreamingPieces(self):
        reader = aperture.vtkApertureDEMReader()
        reader.SetFileName(self.path)
        whole = aperture.vtkApertureTerrainMesh()
        whole.SetInputConnection(reader.GetOutputPort())
        whole.Update()
        full = vtk_to_numpy(whole.GetOutput().GetPoints().GetData()).reshape(344, 403, 3)
        full_origin = whole.GetOutput().GetFieldData().GetArray("FrameOrigin").GetTuple(0)

        # Every cell of the DEM in some piece: the reader, which splits piece requests into
        # extents itself, used to intersect its own split with the mesh's (two pieces gave
        # two quarters of the DEM, diagonally opposite), which rows alone did not show.
        for pieces in (2, 3, 4):
            covered = np.zeros((344, 403), dtype=bool)
            for piece in range(pieces):
                r = aperture.vtkApertureDEMReader()
                r.SetFileName(self.path)
                m = aperture.vtkApertureTerrainMesh()
                m.SetInputConnection(r.GetOutputPort())
                m.UpdatePiece(piece, pieces, 0)
                image = r.GetOutput()
                ext = image.GetExtent()
                self.assertLess((ext[1] - ext[0] + 1) * (ext[3] - ext[2] + 1), 344 * 403)
                out = m.GetOutput()
                origin = out.GetFieldData().GetArray("FrameOrigin").GetTuple(0)
                self.assertEqual(origin, full_origin)  # one frame for every piece
                pts = vtk_to_numpy(out.GetPoints().GetData()).reshape(ext[3] - ext[2] + 1,
                                                                      ext[1] - ext[0] + 1, 3)
                np.testing.assert_array_equal(pts, full[ext[2]:ext[3] + 1, ext[0]:ext[1] + 1])
                covered[ext[2]:ext[3] + 1, ext[0]:ext[1] + 1] = True
            self.assertTrue(covered.all(), "%d pieces miss %d cells"
                            % (pieces, np.count_nonzero(~covered)))

    def testStreamingSkyProductsOntoMesh(self):
        # reader -> sky visibility (2 km) -> mesh, piece by piece: the mesh asks the sky filter
        # for its block, which reads the block and its halo; every piece's SkyViewFactor and
        # BentNormal on the mesh are the whole run's at the same points, bit for bit.
        def pipeline():
            r = aperture.vtkApertureDEMReader()
            r.SetFileName(self.path)
            sky = aperture.vtkApertureSkyVisibility()
            sky.SetInputConnection(r.GetOutputPort())
            sky.SetMaximumDistance(2000.0)
            m = aperture.vtkApertureTerrainMesh()
            m.SetInputConnection(sky.GetOutputPort())
            return r, sky, m

        _, _, whole = pipeline()
        whole.Update()
        names = ("SkyViewFactor", "BentNormal")
        full = {n: vtk_to_numpy(whole.GetOutput().GetPointData().GetArray(n)).reshape(344, 403, -1)
                for n in names}
        covered = np.zeros((344, 403), dtype=bool)
        for piece in range(2):
            r, sky, m = pipeline()
            m.UpdatePiece(piece, 2, 0)
            ext = sky.GetOutput().GetExtent()
            self.assertLess(ext[1] - ext[0] + 1, 403)  # a piece, not the whole
            rext = r.GetOutput().GetExtent()
            self.assertTrue(rext[0] <= ext[0] and rext[1] >= ext[1])  # the halo was read
            for n in names:
                got = vtk_to_numpy(m.GetOutput().GetPointData().GetArray(n))
                np.testing.assert_array_equal(
                    got.reshape(ext[3] - ext[2] + 1, ext[1] - ext[0] + 1, -1),
                    full[n][ext[2]:ext[3] + 1, ext[0]:ext[1] + 1])
            covered[ext[2]:ext[3] + 1, ext[0]:ext[1] + 1] = True
        self.assertTrue(covered.all())


if __name__ == "__main__":
    Testing.main([(TestPipelineBehaviour, "test")])
