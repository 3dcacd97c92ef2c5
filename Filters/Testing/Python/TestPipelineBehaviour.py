# SPDX-License-Identifier: BSD-3-Clause
"""Aperture's filters behave like VTK's own in a pipeline: progress events, re-execution when
a property changes (and only then), and streaming: a DEM meshed piece by piece (the reader
reading only each piece's rows) gives exactly the vertices of the whole mesh, in the same
frame."""
import itertools
import os
import shutil
import sys
import tempfile

import numpy as np
from osgeo import gdal, osr
from vtkmodules.test import Testing
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkCommonExecutionModel import vtkExtentTranslator

import aperture


def global_image(z):
    """A global DEM of 36 x 18 points of 10 degrees, pole to pole, its elevations z (36 * 18
    values, row by row from the south), as an image in EPSG:4326."""
    image = vtkImageData()
    image.SetDimensions(36, 18, 1)
    image.SetOrigin(-175.0, -85.0, 0.0)
    image.SetSpacing(10.0, 10.0, 1.0)
    values = numpy_to_vtk(z, deep=1)
    values.SetName("Elevation")
    image.GetPointData().SetScalars(values)
    geo = aperture.vtkApertureGeoreference()
    if not (geo.SetCRS("EPSG:4326") and geo.AttachToImage(image)):
        raise RuntimeError(geo.GetErrorMessage())
    return image


def write_dem(path, z, gt, epsg, nodata=None):
    """A one-band float32 GeoTIFF of the elevations z (row 0 north); returns path."""
    ds = gdal.GetDriverByName("GTiff").Create(path, z.shape[1], z.shape[0], 1, gdal.GDT_Float32)
    ds.SetGeoTransform(gt)
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(epsg)
    ds.SetSpatialRef(srs)
    if nodata is not None:
        ds.GetRasterBand(1).SetNoDataValue(nodata)
    ds.GetRasterBand(1).WriteArray(z)
    ds = None
    return path


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

    def testFailedUpdateLeavesNothing(self):
        # An update that fails leaves an empty output, as VTK's own filters do, not the last
        # run's elevations in an image of no points: vtkImageData::PrepareForNewData keeps
        # the scalars, which the sky filter's output shares with its input (until 2026-12-07
        # a failed run kept "Elevation", 0 points and an empty extent).
        from aperture.errors import Watcher
        reader = aperture.vtkApertureDEMReader()
        reader.SetFileName(self.path)
        reader.SetDecimation(8)
        reader.PartialBlockWarningOff()
        sky = aperture.vtkApertureSkyVisibility()
        sky.SetInputConnection(reader.GetOutputPort())
        mesher = aperture.vtkApertureTerrainMesh()
        mesher.SetInputConnection(sky.GetOutputPort())
        for stage, setter, value in [(sky, "SetNumberOfDirections", 3),
                                     (sky, "SetRefractionCoefficient", 1.5),
                                     (reader, "SetBandIndex", 1)]:
            watch = Watcher()
            for algorithm in (reader, sky, mesher):
                watch.watch(algorithm)
                watch.watch(algorithm.GetExecutive())
            mesher.Update()
            self.assertFalse(watch.errors, watch.errors)
            self.assertEqual(sky.GetOutput().GetPointData().GetNumberOfArrays(), 8)
            self.assertGreater(mesher.GetOutput().GetNumberOfPoints(), 0)
            getattr(stage, setter)(value)
            if stage is reader:  # (a raster whose every cell is nodata, found once read)
                folder = tempfile.mkdtemp()
                self.addCleanup(shutil.rmtree, folder)
                reader.SetFileName(write_dem(os.path.join(folder, "nodata.tif"),
                                             np.full((20, 30), -9999.0),
                                             (300000, 30, 0, 5000000, 0, -30), 32633, -9999))
                reader.SetDecimation(1)
            mesher.Update()
            self.assertTrue(watch.errors, setter)
            output = stage.GetOutput()  # (downstream of it, VTK runs nothing)
            self.assertEqual(output.GetNumberOfPoints(), 0, setter)
            self.assertEqual(output.GetPointData().GetNumberOfArrays(), 0, setter)
            getattr(stage, setter)({"SetNumberOfDirections": 32,
                                    "SetRefractionCoefficient": 0.13,
                                    "SetBandIndex": 1}[setter])
            if stage is reader:
                reader.SetFileName(self.path)
                reader.SetDecimation(8)

    def testMeshRefusesAGridUnread(self):
        # A whole lat/lon grid the mesher refuses is refused before its reader reads a cell (a
        # global grid was read whole first, until 2026-12-07): wider than the Earth (a
        # gridline-registered global grid, also in Web Mercator), or beyond a pole. A piece is
        # meshed on its own grid, once read; a grid that can be meshed is, after a refusal.
        from aperture.errors import Watcher
        folder = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, folder)
        gridline = write_dem(os.path.join(folder, "gridline.tif"), np.ones((20, 361)),
                             (-180.5, 1, 0, 10, 0, -1), 4326)
        polar = write_dem(os.path.join(folder, "polar.tif"), np.ones((10, 10)),
                          (0, 1, 0, 95, 0, -1), 4326)
        c = 20037508.342789244 / 180  # (a degree of longitude in Web Mercator)
        mercator = write_dem(os.path.join(folder, "mercator.tif"), np.ones((20, 361)),
                             (-180.5 * c, c, 0, 10 * c, 0, -c), 3857)
        reader = aperture.vtkApertureDEMReader()
        mesher = aperture.vtkApertureTerrainMesh()
        mesher.SetInputConnection(reader.GetOutputPort())
        w = Watcher()
        for algorithm in (reader, mesher):
            w.watch(algorithm)
            w.watch(algorithm.GetExecutive())
        for path, message in ((gridline, "the grid spans 361 degrees of longitude"),
                              (polar, "the grid's north edge is at latitude 95, beyond"),
                              (mercator, "the grid spans 361 degrees of longitude")):
            reader.SetFileName(path)
            mesher.Update()
            self.assertTrue(w.errors, path)
            self.assertIn(message, w.errors[0])
            self.assertEqual(reader.GetOutput().GetNumberOfPoints(), 0, path)
            self.assertEqual(mesher.GetOutput().GetNumberOfPoints(), 0, path)
            w.clear()
        reader.SetFileName(gridline)
        mesher.UpdatePiece(0, 2, 0)
        self.assertEqual(w.errors, [])
        self.assertGreater(mesher.GetOutput().GetNumberOfPoints(), 0)
        reader.SetFileName(self.path)
        mesher.Update()
        self.assertEqual(w.errors, [])
        self.assertEqual(mesher.GetOutput().GetNumberOfPoints(), 344 * 403)

    def testThreadCountsLeaveVTKAlone(self):
        # An update on fewer threads than the cores leaves the process's VTK as it found it:
        # VTK 9.1's LocalScope gave the count to the backend active before the scope's own,
        # and Debian's default, TBB, kept it (its thread limit and estimate: 1 after one
        # update on one thread, for every later VTK filter) until 2026-12-07. In a process
        # of its own, with TBB active (the default here; skipped where VTK has no TBB).
        import subprocess
        script = """
import numpy as np
from vtkmodules.vtkCommonCore import vtkSMPTools
import aperture
if not vtkSMPTools.SetBackend("TBB") or vtkSMPTools.GetEstimatedNumberOfThreads() < 2:
    print("skip")
    raise SystemExit
before = vtkSMPTools.GetEstimatedNumberOfThreads()
reader = aperture.vtkApertureDEMReader()
reader.SetFileName(aperture.default_dem())
reader.SetDecimation(8)
reader.PartialBlockWarningOff()
sky = aperture.vtkApertureSkyVisibility()
sky.SetInputConnection(reader.GetOutputPort())
sky.SetNumberOfThreads(1)
sky.Update()
seen = [(vtkSMPTools.GetBackend(), vtkSMPTools.GetEstimatedNumberOfThreads())]
for writer, name in ((aperture.vtkApertureEXRWriter(), "out.exr"),
                     (aperture.vtkApertureDEMWriter(), "out.tif")):
    writer.SetInputConnection(sky.GetOutputPort())
    writer.SetFileName(name)
    writer.SetNumberOfThreads(1)
    writer.Write()
    seen.append((vtkSMPTools.GetBackend(), vtkSMPTools.GetEstimatedNumberOfThreads()))
print(before, seen)
"""
        folder = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, folder)
        p = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                           cwd=folder, timeout=120)
        self.assertEqual(p.returncode, 0, p.stderr[-2000:])
        if p.stdout.strip() == "skip":
            self.skipTest("VTK has no TBB backend, or this machine one core")
        before, seen = p.stdout.split(" ", 1)
        self.assertEqual(seen.strip(), repr([("TBB", int(before))] * 3))

    def testSkyPassesCellData(self):
        # The sky filter passes the input's cell data over the output's cells, as VTK's image
        # filters do (until 2026-12-06 it dropped it; point and field data passed).
        from vtkmodules.util.numpy_support import numpy_to_vtk
        reader = aperture.vtkApertureDEMReader()
        reader.SetFileName(self.path)
        reader.Update()
        image = reader.GetOutput().NewInstance()
        image.DeepCopy(reader.GetOutput())
        nx, ny, _ = image.GetDimensions()
        ids = numpy_to_vtk(np.arange(image.GetNumberOfCells(), dtype=np.float64), deep=1)
        ids.SetName("CellId")
        image.GetCellData().AddArray(ids)
        sky = aperture.vtkApertureSkyVisibility()
        sky.SetInputData(image)
        sky.SetMaximumDistance(2000.0)
        sky.Update()
        out = sky.GetOutput().GetCellData().GetArray("CellId")
        self.assertIsNotNone(out)
        self.assertTrue(np.array_equal(vtk_to_numpy(out), np.arange(image.GetNumberOfCells())))

        def piece(extent):  # (a new filter each: an output that covers a request is kept)
            sky = aperture.vtkApertureSkyVisibility()
            sky.SetInputData(image)
            sky.SetMaximumDistance(2000.0)
            sky.UpdateExtent(extent)
            self.assertEqual(sky.GetOutput().GetExtent(), extent)
            return sky.GetOutput()
        got = vtk_to_numpy(piece((10, 40, 20, 50, 0, 0)).GetCellData().GetArray("CellId"))
        j, i = np.mgrid[20:50, 10:40]
        self.assertTrue(np.array_equal(got, (j * (nx - 1) + i).ravel()))
        # a piece one column wide has line cells, not the input's quads: none passed
        column = piece((10, 10, 20, 50, 0, 0))
        self.assertEqual(column.GetCellData().GetNumberOfArrays(), 0)
        self.assertEqual(column.GetPointData().GetArray("SkyViewFactor").GetNumberOfTuples(), 31)

    def testClipDataOff(self):
        # vtkImageClip with ClipData off (VTK's default) narrows the whole extent but passes
        # all of its input on: VTK's filters and writers use only the whole extent's data.
        # The sky filter used all of it (the clipped-off hill still shaded the clip, and no
        # cell near the clip's west edge was EdgeTruncated), and both writers wrote all of it,
        # origin included, until 2026-12-07 (in strips they wrote the clip).
        from vtkmodules.util.numpy_support import numpy_to_vtk
        from vtkmodules.vtkCommonExecutionModel import vtkTrivialProducer
        from vtkmodules.vtkImagingCore import vtkImageClip
        from vtkmodules.vtkCommonDataModel import vtkImageData
        j, i = np.mgrid[0:40, 0:60]
        image = vtkImageData()
        image.SetDimensions(60, 40, 1)
        image.SetSpacing(10.0, 10.0, 1.0)
        image.SetOrigin(500000.0, 5000000.0, 0.0)
        z = 300.0 * np.exp(-((i - 30.0) ** 2 + (j - 20.0) ** 2) / 200.0) + 0.001 * (i + 60 * j)
        array = numpy_to_vtk(z.ravel().astype(np.float32), deep=1)
        array.SetName("Elevation")
        image.GetPointData().SetScalars(array)
        geo = aperture.vtkApertureGeoreference()
        self.assertTrue(geo.SetCRS("EPSG:32633") and geo.AttachToImage(image))
        producer = vtkTrivialProducer()
        producer.SetOutput(image)

        clips = []  # (kept: a consumer does not keep its producer alive)
        for clip_data in (0, 1):
            clips.append(vtkImageClip())
            clips[-1].SetInputConnection(producer.GetOutputPort())
            clips[-1].SetOutputWholeExtent(35, 59, 5, 34, 0, 0)  # east of the hill's top
            clips[-1].SetClipData(clip_data)
        products = {}
        for clip_data in (0, 1):
            sky = aperture.vtkApertureSkyVisibility()
            sky.SetInputConnection(clips[clip_data].GetOutputPort())
            sky.SetMaximumDistance(100.0)
            sky.Update()
            out = sky.GetOutput()
            self.assertEqual(out.GetExtent(), (35, 59, 5, 34, 0, 0))
            products[clip_data] = {n: vtk_to_numpy(out.GetPointData().GetArray(n)).copy()
                                   for n in ("SkyViewFactor", "EdgeTruncated")}
        for n in ("SkyViewFactor", "EdgeTruncated"):
            np.testing.assert_array_equal(products[0][n], products[1][n], n)
        # the clip's west edge is the DEM's: its cells within the 100 m see the edge
        edge = products[0]["EdgeTruncated"].reshape(30, 25)
        self.assertTrue(edge[:, :10].all())

        tmp = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, tmp)
        for writer, reader, name in (
                (aperture.vtkApertureDEMWriter, aperture.vtkApertureDEMReader, "c.tif"),
                (aperture.vtkApertureEXRWriter, aperture.vtkApertureEXRReader, "c.exr")):
            for strips in (0, 7):
                w = writer()
                w.SetInputConnection(clips[0].GetOutputPort())
                w.SetFileName(os.path.join(tmp, name))
                w.SetStripRows(strips)
                self.assertEqual(w.Write(), 1)
                r = reader()
                r.SetFileName(os.path.join(tmp, name))
                r.Update()
                got = r.GetOutput()
                self.assertEqual(got.GetDimensions(), (25, 30, 1), (name, strips))
                self.assertEqual(got.GetOrigin()[:2], (500350.0, 5000050.0), (name, strips))
                back = vtk_to_numpy(got.GetPointData().GetArray("Elevation")).reshape(30, 25)
                np.testing.assert_array_equal(back, z[5:35, 35:60].astype(np.float32))

    def testWrapColumnsOfAnImageGivenAsData(self):
        # A global DEM given with SetInputData wraps as one read: GetWrapColumns, for planning
        # an update's memory, said 0 for it until 2026-12-07 (its CRS is in its field data, not
        # in the pipeline information a reader publishes).
        image = global_image(np.linspace(0.0, 900.0, 36 * 18).astype(np.float32))
        sky = aperture.vtkApertureSkyVisibility()
        sky.SetInputData(image)
        sky.UpdateInformation()
        self.assertEqual(sky.GetWrapColumns([0, 35, 0, 17, 0, 0]), 18)
        sky.SetMaximumDistance(3000e3)  # over 30 of the top row's 97 km cells: half the DEM
        self.assertEqual(sky.GetWrapColumns([0, 35, 0, 17, 0, 0]), 18)
        sky.SetMaximumDistance(200e3)  # a few of them
        self.assertTrue(2 <= sky.GetWrapColumns([0, 35, 0, 17, 0, 0]) < 18)
        self.assertEqual(sky.GetWrapColumns([0, 30, 0, 17, 0, 0]), 0)  # not every column

    def testMeshPieceMemoryUnderAddressLimit(self):
        # Under an address-space limit (ulimit -v) the memory left already excludes the crop
        # of a piece out of an image given whole: a 512 x 512 piece of a 1024^2 image that
        # carries 400 MiB of other arrays (its crop about 100 MiB, its mesh 33 MiB) fits in
        # 420 MiB above what the process has mapped. Until 2026-12-06 the crop counted again
        # and the piece was refused ("needs about 235 MiB, more than the 110 MiB ...").
        import subprocess
        script = """
import resource
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import vtkImageData
import aperture
from aperture.errors import Watcher
image = vtkImageData()
image.SetDimensions(1024, 1024, 1)
image.SetSpacing(30, 30, 1)
values = numpy_to_vtk(np.zeros(1024 * 1024, dtype=np.float32), deep=1)
values.SetName("Elevation")
image.GetPointData().SetScalars(values)
other = numpy_to_vtk(np.zeros((1024 * 1024, 50), dtype=np.float64), deep=1)
other.SetName("Other")
image.GetPointData().AddArray(other)
geo = aperture.vtkApertureGeoreference()
assert geo.SetCRS("EPSG:32633")
geo.AttachToImage(image)
w = Watcher()
mesher = w.watch(aperture.vtkApertureTerrainMesh())
mesher.SetInputData(image)
with open("/proc/self/status") as status:
    vm = next(int(line.split()[1]) for line in status if line.startswith("VmSize:"))
resource.setrlimit(resource.RLIMIT_AS, ((vm + 420 * 1024) * 1024, resource.RLIM_INFINITY))
mesher.UpdatePiece(0, 4, 0)
print(w.errors[0] if w.errors else mesher.GetOutput().GetNumberOfPoints())
"""
        p = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                           timeout=120)
        self.assertEqual(p.returncode, 0, p.stderr[-2000:])
        self.assertEqual(p.stdout, "%d\n" % (512 * 512))

    def testAbortWhileMeshing(self):
        # AbortExecute set from a progress observer (the command line's Ctrl-C) stops the
        # mesher within the band of rows after it (a twentieth of the points' work), leaving
        # an empty mesh; it used to be checked only once every point was placed, so a DEM of
        # 10^8 points ran on for half a minute.
        reader = aperture.vtkApertureDEMReader()
        reader.SetFileName(self.path)
        reader.Update()
        mesher = aperture.vtkApertureTerrainMesh()
        mesher.SetInputConnection(reader.GetOutputPort())
        progress = []

        def observe(obj, _):
            progress.append(obj.GetProgress())
            if 0.1 < obj.GetProgress() < 1.0:
                obj.SetAbortExecute(1)

        mesher.AddObserver("ProgressEvent", observe)
        failures = []  # (the update fails, as the sky filter's does when aborted)
        executive = mesher.GetExecutive()
        executive.AddObserver("ErrorEvent", lambda o, e: failures.append(e))
        mesher.Update()
        self.assertEqual(len(failures), 1)
        self.assertEqual(mesher.GetOutput().GetNumberOfPoints(), 0)
        self.assertTrue(any(0.1 < p < 1.0 for p in progress), progress)
        self.assertLessEqual(max(progress), 0.1 + 0.6 / 20 + 1e-9, progress)
        # The next Update runs it again, to its end, with nothing else changed (as the
        # reader and the sky filter do): it handed out the empty aborted mesh again, silently,
        # unless the caller marked the mesher modified, until 2026-12-06.
        mesher.RemoveAllObservers()
        starts = []
        mesher.AddObserver("StartEvent", lambda o, e: starts.append(e))
        mesher.Update()
        self.assertEqual(len(starts), 1)
        self.assertEqual(mesher.GetOutput().GetNumberOfPoints(), 344 * 403)
        mesher.Update()  # (and, done, not again)
        self.assertEqual(len(starts), 1)

    def testPiecesWithoutPoints(self):
        # More pieces than VTK's split has points to give: the pieces it leaves empty are empty
        # meshes, so that the pieces' triangles add up to the whole mesh's. They meshed what
        # the input still held from the update before (1000 pieces of 20 x 20 points summed
        # 609 whole meshes with SetInputData; a reader's input its previous piece with its
        # margin) until 2026-12-06.
        from vtkmodules.vtkCommonExecutionModel import vtkExtentTranslator
        tmp = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, tmp, True)
        path = write_dem(os.path.join(tmp, "small.tif"),
                         np.add.outer(np.arange(20.0), np.arange(20.0) ** 1.5),
                         (500000, 30, 0, 4000600, 0, -30), 32611)
        reader = aperture.vtkApertureDEMReader()
        reader.SetFileName(path)
        reader.Update()
        image = reader.GetOutput()
        translator = vtkExtentTranslator()
        for normals in (True, False):
            for given in (True, False):
                m = aperture.vtkApertureTerrainMesh()
                m.SetComputeNormals(normals)
                if given:
                    m.SetInputData(image)
                else:
                    r = aperture.vtkApertureDEMReader()
                    r.SetFileName(path)
                    m.SetInputConnection(r.GetOutputPort())
                for pieces in (361, 400, 1000):
                    triangles = 0
                    for piece in range(pieces):
                        m.UpdatePiece(piece, pieces, 0)
                        ext = [0] * 6
                        translator.PieceToExtentThreadSafe(piece, pieces, 0,
                                                           [0, 19, 0, 19, 0, 0], ext,
                                                           vtkExtentTranslator.BLOCK_MODE, 0)
                        if ext[1] < ext[0] or ext[3] < ext[2]:
                            self.assertEqual(m.GetOutput().GetNumberOfPoints(), 0)
                        triangles += m.GetOutput().GetNumberOfPolys()
                    self.assertEqual(triangles, 2 * 19 * 19, (normals, given, pieces))

    def testStreamingPieces(self):
        from vtkmodules.vtkCommonExecutionModel import vtkExtentTranslator
        translator = vtkExtentTranslator()

        def piece_extent(piece, pieces):
            ext = [0] * 6
            translator.PieceToExtentThreadSafe(piece, pieces, 0, [0, 402, 0, 343, 0, 0], ext,
                                               vtkExtentTranslator.BLOCK_MODE, 0)
            return ext

        reader = aperture.vtkApertureDEMReader()
        reader.SetFileName(self.path)
        whole = aperture.vtkApertureTerrainMesh()
        whole.SetInputConnection(reader.GetOutputPort())
        whole.Update()
        full = vtk_to_numpy(whole.GetOutput().GetPoints().GetData()).reshape(344, 403, 3)
        full_normals = vtk_to_numpy(whole.GetOutput().GetPointData().GetNormals()).reshape(
            344, 403, 3)
        full_origin = whole.GetOutput().GetFieldData().GetArray("FrameOrigin").GetTuple(0)

        # Every cell of the DEM in some piece: the reader, which splits piece requests into
        # extents itself, used to intersect its own split with the mesh's (two pieces gave
        # two quarters of the DEM, diagonally opposite), which rows alone did not show. The
        # reader reads the piece and one point more on every side where the DEM goes on, for
        # the piece's boundary normals to be the whole mesh's, bit for bit (they took their
        # neighbours on one side only until 2026-12-06, up to 9 degrees off: a seam of shading
        # between pieces); without normals, the piece alone.
        for normals in (True, False):
            for pieces in (2, 3, 4):
                covered = np.zeros((344, 403), dtype=bool)
                for piece in range(pieces):
                    r = aperture.vtkApertureDEMReader()
                    r.SetFileName(self.path)
                    m = aperture.vtkApertureTerrainMesh()
                    m.SetComputeNormals(normals)
                    m.SetInputConnection(r.GetOutputPort())
                    m.UpdatePiece(piece, pieces, 0)
                    ext = piece_extent(piece, pieces)
                    grown = [max(0, ext[0] - 1), min(402, ext[1] + 1),
                             max(0, ext[2] - 1), min(343, ext[3] + 1), 0, 0]
                    self.assertEqual(r.GetOutput().GetExtent(),
                                     tuple(grown if normals else ext))
                    self.assertLess((ext[1] - ext[0] + 1) * (ext[3] - ext[2] + 1), 344 * 403)
                    out = m.GetOutput()
                    origin = out.GetFieldData().GetArray("FrameOrigin").GetTuple(0)
                    self.assertEqual(origin, full_origin)  # one frame for every piece
                    shape = (ext[3] - ext[2] + 1, ext[1] - ext[0] + 1, 3)
                    pts = vtk_to_numpy(out.GetPoints().GetData()).reshape(shape)
                    np.testing.assert_array_equal(pts,
                                                  full[ext[2]:ext[3] + 1, ext[0]:ext[1] + 1])
                    if normals:
                        np.testing.assert_array_equal(
                            vtk_to_numpy(out.GetPointData().GetNormals()).reshape(shape),
                            full_normals[ext[2]:ext[3] + 1, ext[0]:ext[1] + 1])
                    else:
                        self.assertIsNone(out.GetPointData().GetNormals())
                    covered[ext[2]:ext[3] + 1, ext[0]:ext[1] + 1] = True
                self.assertTrue(covered.all(), "%d pieces miss %d cells"
                                % (pieces, np.count_nonzero(~covered)))

        # The same pieces from an input that already holds the whole DEM: the reader updated
        # whole before, and an image given with SetInputData. Each piece meshes its own
        # extent (each meshed the whole input: n pieces, n whole meshes), the cells of the
        # pieces adding up to the whole's, the normals the whole's.
        image = reader.GetOutput()
        for source in ("reader", "image"):
            m = aperture.vtkApertureTerrainMesh()
            if source == "reader":
                m.SetInputConnection(reader.GetOutputPort())
            else:
                m.SetInputData(image)
            cells = 0
            for piece in range(3):
                m.UpdatePiece(piece, 3, 0)
                ext = piece_extent(piece, 3)
                out = m.GetOutput()
                pts = vtk_to_numpy(out.GetPoints().GetData())
                self.assertEqual(len(pts), (ext[1] - ext[0] + 1) * (ext[3] - ext[2] + 1), source)
                shape = (ext[3] - ext[2] + 1, ext[1] - ext[0] + 1, 3)
                np.testing.assert_array_equal(pts.reshape(shape),
                                              full[ext[2]:ext[3] + 1, ext[0]:ext[1] + 1])
                np.testing.assert_array_equal(
                    vtk_to_numpy(out.GetPointData().GetNormals()).reshape(shape),
                    full_normals[ext[2]:ext[3] + 1, ext[0]:ext[1] + 1])
                cells += out.GetNumberOfCells()
            self.assertEqual(cells, whole.GetOutput().GetNumberOfCells(), source)
            self.assertEqual(image.GetExtent(), (0, 402, 0, 343, 0, 0))  # (left whole)
            # a piece that does not exist is empty (it was the whole DEM's mesh, or a part)
            for piece in (3, 7):
                m.UpdatePiece(piece, 3, 0)
                self.assertEqual(m.GetOutput().GetNumberOfPoints(), 0, (source, piece))
                self.assertEqual(m.GetOutput().GetNumberOfCells(), 0, (source, piece))

    def testStreamingNormalsOfSitesAndHoles(self):
        # A piece's boundary normals from the margin read around it, bit for bit the whole
        # mesh's: on a site grid in a local CRS in feet (its points placed on the local sphere)
        # and on a UTM one, both with nodata points next to pieces' edges (their neighbours'
        # normals take the diagonals instead, as in the whole mesh).
        from vtkmodules.vtkCommonDataModel import vtkImageData
        from vtkmodules.util.numpy_support import numpy_to_vtk
        from vtkmodules.vtkCommonExecutionModel import vtkExtentTranslator
        nx, ny = 40, 30
        y, x = np.mgrid[0:ny, 0:nx]
        z = (20 * np.sin(x / 3.0) * np.cos(y / 4.0)).astype(np.float32)
        z[5, 7] = z[14, 20] = z[15, 19] = np.nan
        for crs in ('LOCAL_CS["site",UNIT["foot",0.3048]]', "EPSG:32633"):
            image = vtkImageData()
            image.SetDimensions(nx, ny, 1)
            image.SetSpacing(2.0, 2.0, 1.0)
            image.SetOrigin(400000.0, 5000000.0, 0.0)
            values = numpy_to_vtk(z.ravel(), deep=1)
            values.SetName("Elevation")
            image.GetPointData().SetScalars(values)
            geo = aperture.vtkApertureGeoreference()
            self.assertTrue(geo.SetCRS(crs))
            geo.AttachToImage(image)
            whole = aperture.vtkApertureTerrainMesh()
            whole.SetInputData(image)
            whole.Update()
            full = vtk_to_numpy(whole.GetOutput().GetPointData().GetNormals()).reshape(ny, nx, 3)
            self.assertEqual(np.isnan(full[:, :, 0]).sum(), 3)
            for pieces in (2, 3, 5):
                for piece in range(pieces):
                    m = aperture.vtkApertureTerrainMesh()
                    m.SetInputData(image)
                    m.UpdatePiece(piece, pieces, 0)
                    e = [0] * 6
                    vtkExtentTranslator().PieceToExtentThreadSafe(
                        piece, pieces, 0, [0, nx - 1, 0, ny - 1, 0, 0], e,
                        vtkExtentTranslator.BLOCK_MODE, 0)
                    got = vtk_to_numpy(m.GetOutput().GetPointData().GetNormals())
                    np.testing.assert_array_equal(
                        got.reshape(e[3] - e[2] + 1, e[1] - e[0] + 1, 3),
                        full[e[2]:e[3] + 1, e[0]:e[1] + 1], err_msg="%s %d/%d" % (crs, piece,
                                                                                 pieces))

    def testStreamingGlobalDEM(self):
        # A global DEM (2-degree cells, pole to pole) read piece by piece: its pieces are bands
        # of whole rows (the CRS the reader publishes says the DEM wraps around), so each joins
        # its east and west edges with one copied vertex a row, the first and last close their
        # poles, and every vertex (the copies too) is the whole mesh's. Through the sky filter
        # as well. With blocks, the pieces at the antimeridian would leave a gap.
        tmp = tempfile.mkdtemp(prefix="aperture-globe-")
        self.addCleanup(shutil.rmtree, tmp, True)
        path = os.path.join(tmp, "globe.tif")
        nx, ny = 180, 90
        rng = np.random.default_rng(7)
        ds = gdal.GetDriverByName("GTiff").Create(path, nx, ny, 1, gdal.GDT_Float32)
        ds.SetGeoTransform((-180, 2, 0, 90, 0, -2))
        srs = osr.SpatialReference()
        srs.ImportFromEPSG(4326)
        ds.SetSpatialRef(srs)
        ds.GetRasterBand(1).WriteArray((3000 * rng.random((ny, nx))).astype(np.float32))
        ds = None

        def pipeline(sky):
            r = aperture.vtkApertureDEMReader()
            r.SetFileName(path)
            m = aperture.vtkApertureTerrainMesh()
            if sky:
                s = aperture.vtkApertureSkyVisibility()
                s.SetInputConnection(r.GetOutputPort())
                s.SetNumberOfDirections(8)
                s.SetMaximumDistance(500000.0)
                m.SetInputConnection(s.GetOutputPort())
            else:
                m.SetInputConnection(r.GetOutputPort())
            return r, m

        for sky in (False, True):
            _, whole = pipeline(sky)
            whole.Update()
            full = vtk_to_numpy(whole.GetOutput().GetPoints().GetData())
            self.assertEqual(len(full), nx * ny + ny)
            self.assertEqual(whole.GetOutput().GetNumberOfCells(),
                             2 * nx * (ny - 1) + 2 * (nx - 2))
            grid, seam = full[:nx * ny].reshape(ny, nx, 3), full[nx * ny:]
            np.testing.assert_array_equal(seam, grid[:, 0])
            full_normals = vtk_to_numpy(whole.GetOutput().GetPointData().GetNormals())
            cells = 0
            for piece in range(3):
                r, m = pipeline(sky)
                m.UpdatePiece(piece, 3, 0)
                out = m.GetOutput()
                self.assertEqual(r.GetOutput().GetExtent()[:2], (0, nx - 1))
                # the piece's rows: whole rows and their seam copies
                rows = out.GetNumberOfPoints() // (nx + 1)
                self.assertEqual(out.GetNumberOfPoints(), rows * (nx + 1))
                self.assertLess(rows, ny)
                pts = vtk_to_numpy(out.GetPoints().GetData())
                # (its first row in the whole mesh; the heights are random)
                j0 = int(np.flatnonzero((grid[:, 0] == pts[0]).all(axis=1))[0])
                np.testing.assert_array_equal(pts[:rows * nx], grid[j0:j0 + rows].reshape(-1, 3))
                np.testing.assert_array_equal(pts[rows * nx:], seam[j0:j0 + rows])
                # (the normals too, of the bands' boundary rows among them)
                got = vtk_to_numpy(out.GetPointData().GetNormals())
                np.testing.assert_array_equal(got[:rows * nx],
                                              full_normals[j0 * nx:(j0 + rows) * nx])
                np.testing.assert_array_equal(got[rows * nx:],
                                              full_normals[nx * ny + j0:nx * ny + j0 + rows])
                poles = (j0 == 0) + (j0 + rows == ny)
                self.assertEqual(poles, 0 if piece == 1 else 1)
                self.assertEqual(out.GetNumberOfCells(), 2 * nx * (rows - 1) + poles * (nx - 2))
                cells += out.GetNumberOfCells()
            # (neighbouring bands share a row of points, not of quads)
            self.assertEqual(cells, whole.GetOutput().GetNumberOfCells())

        # given with SetInputData, whole: the image itself says it wraps around, so its pieces
        # are bands with their seams again (not blocks, which would leave the antimeridian open)
        r = aperture.vtkApertureDEMReader()
        r.SetFileName(path)
        r.Update()
        m = aperture.vtkApertureTerrainMesh()
        m.SetInputData(r.GetOutput())
        cells = 0
        for piece in range(3):
            m.UpdatePiece(piece, 3, 0)
            out = m.GetOutput()
            self.assertEqual(out.GetNumberOfPoints() % (nx + 1), 0)
            self.assertLess(out.GetNumberOfPoints(), ny * (nx + 1))
            cells += out.GetNumberOfCells()
        self.assertEqual(cells, 2 * nx * (ny - 1) + 2 * (nx - 2))

    def testGhostLevels(self):
        # A piece asked for with ghost levels (UpdatePiece(p, n, g), as ParaView's ranks ask)
        # is meshed over g more points on every side where the DEM goes on, each cell and point
        # there marked in vtkGhostType (DUPLICATECELL, DUPLICATEPOINT), and the output says it
        # has g levels: its own cells are the piece's, the others the neighbours', every one
        # the whole mesh's. Until 2026-12-07 the levels were ignored (the same cells as level 0,
        # no vtkGhostType, yet DATA_NUMBER_OF_GHOST_LEVELS g). Level 0 adds no array.
        from vtkmodules.vtkCommonDataModel import vtkDataObject, vtkDataSetAttributes
        from vtkmodules.vtkCommonExecutionModel import vtkExtentTranslator
        from vtkmodules.vtkFiltersParallel import vtkRemoveGhosts
        translator = vtkExtentTranslator()

        def triangles(mesh, ghost=None):
            """The triangles as sorted tuples of their corners (ghost: only those that are,
            or are not, ghosts)."""
            if mesh.GetNumberOfPoints() == 0:  # (an empty piece)
                return []
            pts = vtk_to_numpy(mesh.GetPoints().GetData())
            ids = vtk_to_numpy(mesh.GetPolys().GetConnectivityArray()).reshape(-1, 3)
            if ghost is not None:
                marks = vtk_to_numpy(mesh.GetCellData().GetArray("vtkGhostType"))
                ids = ids[(marks == vtkDataSetAttributes.DUPLICATECELL) == ghost]
            return sorted(tuple(sorted(map(tuple, pts[t].tolist()))) for t in ids)

        reader = aperture.vtkApertureDEMReader()
        reader.SetFileName(self.path)
        reader.SetDecimation(2)  # (172 x 201 points)
        reader.PartialBlockWarningOff()
        whole = aperture.vtkApertureTerrainMesh()
        whole.SetInputConnection(reader.GetOutputPort())
        whole.Update()
        full = vtk_to_numpy(whole.GetOutput().GetPoints().GetData()).reshape(172, 201, 3)
        full_normals = vtk_to_numpy(whole.GetOutput().GetPointData().GetNormals()).reshape(
            172, 201, 3)
        for normals, pieces, levels in itertools.product((True, False), (2, 3), (0, 1, 2)):
            cells = 0
            for piece in range(pieces):
                r = aperture.vtkApertureDEMReader()
                r.SetFileName(self.path)
                r.SetDecimation(2)
                r.PartialBlockWarningOff()
                m = aperture.vtkApertureTerrainMesh()
                m.SetComputeNormals(normals)
                m.SetInputConnection(r.GetOutputPort())
                m.UpdatePiece(piece, pieces, levels)
                out = m.GetOutput()
                own = [0] * 6
                translator.PieceToExtentThreadSafe(piece, pieces, 0, [0, 200, 0, 171, 0, 0], own,
                                                   vtkExtentTranslator.BLOCK_MODE, 0)
                ext = [max(0, own[0] - levels), min(200, own[1] + levels),
                       max(0, own[2] - levels), min(171, own[3] + levels), 0, 0]
                self.assertEqual(ext != own, levels > 0)
                read = [max(0, ext[0] - 1), min(200, ext[1] + 1),
                        max(0, ext[2] - 1), min(171, ext[3] + 1), 0, 0]
                self.assertEqual(r.GetOutput().GetExtent(), tuple(read if normals else ext))
                shape = (ext[3] - ext[2] + 1, ext[1] - ext[0] + 1, 3)
                np.testing.assert_array_equal(
                    vtk_to_numpy(out.GetPoints().GetData()).reshape(shape),
                    full[ext[2]:ext[3] + 1, ext[0]:ext[1] + 1])
                if normals:
                    np.testing.assert_array_equal(
                        vtk_to_numpy(out.GetPointData().GetNormals()).reshape(shape),
                        full_normals[ext[2]:ext[3] + 1, ext[0]:ext[1] + 1])
                self.assertEqual(out.GetInformation().Get(
                    vtkDataObject.DATA_NUMBER_OF_GHOST_LEVELS()), levels)
                self.assertEqual(out.GetNumberOfCells(),
                                 2 * (ext[1] - ext[0]) * (ext[3] - ext[2]))
                if not levels:
                    self.assertIsNone(out.GetCellData().GetArray("vtkGhostType"))
                    self.assertIsNone(out.GetPointData().GetArray("vtkGhostType"))
                    cells += out.GetNumberOfCells()
                    continue
                # the points outside the piece's own extent, and the cells of their quads
                j, i = np.mgrid[ext[2]:ext[3] + 1, ext[0]:ext[1] + 1]
                outside = (i < own[0]) | (i > own[1]) | (j < own[2]) | (j > own[3])
                np.testing.assert_array_equal(
                    vtk_to_numpy(out.GetPointData().GetArray("vtkGhostType")),
                    np.where(outside.ravel(), vtkDataSetAttributes.DUPLICATEPOINT, 0))
                kept = vtkRemoveGhosts()
                kept.SetInputData(out)
                kept.Update()
                self.assertEqual(kept.GetOutput().GetNumberOfCells(),
                                 2 * (own[1] - own[0]) * (own[3] - own[2]))
                self.assertEqual(triangles(kept.GetOutput()), triangles(out, False))
                cells += kept.GetOutput().GetNumberOfCells()
            self.assertEqual(cells, whole.GetOutput().GetNumberOfCells())

        # A global DEM (10-degree cells pole to pole, given with SetInputData): bands of whole
        # rows, their ghost rows with their seam quads and a pole's cap, marked; the bands' own
        # triangles are the whole mesh's, every triangle one of them.
        m = aperture.vtkApertureTerrainMesh()
        m.SetInputData(global_image(np.random.default_rng(3).uniform(0.0, 3000.0, 36 * 18)))
        m.Update()
        every = triangles(m.GetOutput())
        self.assertEqual(len(every), 2 * 36 * 17 + 2 * 34)  # (the quads, the two caps)
        # More pieces than rows (17 rows of quads): bands of one row or none, each with its
        # seam, one of them owning each cap (one-row bands share a cap's row of points: both
        # counted it their own, 1324 triangles for 1292, until review; and VTK's Y slabs cut
        # such bands across the columns, where the seam was lost, 1256 at level 0).
        for pieces, levels in ((2, 1), (3, 2), (5, 1), (17, 0), (18, 1), (25, 2)):
            own, ghosts = [], 0
            for piece in range(pieces):
                m.UpdatePiece(piece, pieces, levels)
                out = m.GetOutput()
                self.assertEqual(out.GetNumberOfPoints() % 37, 0)  # (whole rows, seam copies)
                if levels == 0:
                    own += triangles(out)
                    continue
                mine, theirs = triangles(out, False), triangles(out, True)
                self.assertTrue(set(theirs) <= set(every))
                own += mine
                ghosts += len(theirs)
            self.assertEqual(sorted(own), every, (pieces, levels))
            # (each band's ghost rows: its neighbours' quads, seams included, and a cap within
            # reach; the bands are at least levels + 1 rows apart from a pole)
            self.assertGreaterEqual(ghosts, min(pieces - 1, 16) * levels * 2 * 36)
        # Behind a sky filter given the image with SetInputData: bands with their seams too
        # (the sky filter published no CRS for such an image, so the pieces were blocks
        # without seams, 1190 triangles in 3 pieces, until 2026-12-07)
        sky = aperture.vtkApertureSkyVisibility()
        sky.SetInputData(m.GetInput())
        sky.SetMaximumDistance(100e3)
        m.SetInputConnection(sky.GetOutputPort())
        for pieces in (3, 7):
            own = []
            for piece in range(pieces):
                m.UpdatePiece(piece, pieces, 0)
                own += triangles(m.GetOutput())
            self.assertEqual(sorted(own), every, pieces)

    def testPiecesBehindAFilterDroppingTheCRS(self):
        # Behind a VTK filter that drops the CRS from the pipeline information
        # (vtkImageShiftScale), a global DEM's pieces are blocks, without seams, whatever was
        # updated before: they were bands after a whole update and blocks after a piece (the
        # image held decided), and RequestData could decide otherwise than the request's plan
        # (a review of 2026-12-07 counted 140 triangles twice in 13 pieces).
        from vtkmodules.vtkImagingCore import vtkImageShiftScale
        folder = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, folder)
        path = write_dem(os.path.join(folder, "globe.tif"),
                         np.random.default_rng(1).uniform(0.0, 3000.0, (18, 36)),
                         (-180, 10, 0, 90, 0, -10), 4326)
        for whole_first in (False, True):
            reader = aperture.vtkApertureDEMReader()
            reader.SetFileName(path)
            shift = vtkImageShiftScale()
            shift.SetInputConnection(reader.GetOutputPort())
            shift.SetOutputScalarTypeToFloat()
            m = aperture.vtkApertureTerrainMesh()
            m.SetInputConnection(shift.GetOutputPort())
            if whole_first:  # (the image itself says it wraps: the whole mesh has its seam)
                m.Update()
                self.assertEqual(m.GetOutput().GetNumberOfCells(), 2 * 36 * 17 + 2 * 34)
            for pieces in (3, 13):
                cells = 0
                for piece in range(pieces):
                    m.UpdatePiece(piece, pieces, 0)
                    out = m.GetOutput()
                    ext = [0] * 6
                    translator = vtkExtentTranslator()
                    translator.PieceToExtentThreadSafe(piece, pieces, 0, [0, 35, 0, 17, 0, 0],
                                                       ext, vtkExtentTranslator.BLOCK_MODE, 0)
                    self.assertEqual(out.GetNumberOfPoints(),
                                     (ext[1] - ext[0] + 1) * (ext[3] - ext[2] + 1))
                    cells += out.GetNumberOfCells()
                self.assertEqual(cells, 2 * 35 * 17, (whole_first, pieces))

    def testGhostMarksAddToTheInputs(self):
        # A vtkGhostType the input carries (HIDDENPOINT here) keeps its marks: the ghost layers'
        # DUPLICATEPOINT is added to them (they were overwritten until review).
        from vtkmodules.vtkCommonCore import vtkUnsignedCharArray
        image = global_image(np.zeros(36 * 18))
        hidden = vtkUnsignedCharArray()
        hidden.SetName("vtkGhostType")
        hidden.SetNumberOfTuples(36 * 18)
        hidden.Fill(2)  # (vtkDataSetAttributes.HIDDENPOINT)
        image.GetPointData().AddArray(hidden)
        m = aperture.vtkApertureTerrainMesh()
        m.SetInputData(image)
        m.UpdatePiece(0, 2, 1)
        marks = vtk_to_numpy(m.GetOutput().GetPointData().GetArray("vtkGhostType"))
        # (band 0: rows 0-8 its own, row 9 a ghost row; 37 points a row with the seam's copy)
        self.assertEqual(len(marks), 37 * 10)
        self.assertEqual(sorted(set(marks.tolist())), [2, 3])
        self.assertEqual(int((marks == 3).sum()), 37)

    def testMeshGeoTransformIsTheGridMeshed(self):
        # The mesh's GeoTransform is that of the grid it meshed, the image's geometry: VTK's
        # filters pass the field data of the grid before on (vtkExtractVOI with a sample rate
        # of 2 here: the whole DEM at half the cells), which the mesh carried until
        # 2026-12-07, while the sky filter wrote its own grid's. A piece's is the piece's.
        from vtkmodules.vtkImagingCore import vtkExtractVOI

        def field(data):
            values = data.GetFieldData().GetArray("GeoTransform")
            return [values.GetValue(k) for k in range(6)]

        reader = aperture.vtkApertureDEMReader()
        reader.SetFileName(self.path)
        reader.Update()
        g = field(reader.GetOutput())  # (the file's: 403 x 344 cells of 1/1200 degree)
        voi = vtkExtractVOI()
        voi.SetInputConnection(reader.GetOutputPort())
        voi.SetVOI(100, 299, 50, 249, 0, 0)
        voi.SetSampleRate(2, 2, 1)
        mesher = aperture.vtkApertureTerrainMesh()
        mesher.SetInputConnection(voi.GetOutputPort())
        mesher.Update()
        self.assertEqual(field(voi.GetOutput()), g)  # (VTK passed the file's on)
        # 100 x 100 points 2 cells apart: the west edge half a new cell west of column 100's
        # centre, the north edge half a new cell north of row 248's (rows counted from the
        # south: the file's row 343 - 248 from the north)
        want = [g[0] + 100 * g[1] - 0.5 * g[1], 2 * g[1], 0.0,
                g[3] + (343 - 248) * g[5] - 0.5 * g[5], 0.0, 2 * g[5]]
        np.testing.assert_allclose(field(mesher.GetOutput()), want, rtol=0, atol=1e-9)
        sky = aperture.vtkApertureSkyVisibility()
        sky.SetInputConnection(voi.GetOutputPort())
        sky.SetMaximumDistance(1000.0)
        sky.SetNumberOfDirections(8)
        sky.Update()
        self.assertEqual(field(sky.GetOutput()), field(mesher.GetOutput()))
        from vtkmodules.vtkCommonExecutionModel import vtkExtentTranslator
        ext = [0] * 6
        vtkExtentTranslator().PieceToExtentThreadSafe(1, 2, 0, [0, 402, 0, 343, 0, 0], ext,
                                                      vtkExtentTranslator.BLOCK_MODE, 0)
        pieces = aperture.vtkApertureTerrainMesh()
        pieces.SetInputConnection(reader.GetOutputPort())
        pieces.UpdatePiece(1, 2, 0)
        want = [g[0] + ext[0] * g[1], g[1], 0.0, g[3] + (343 - ext[3]) * g[5], 0.0, g[5]]
        self.assertNotEqual(want, g)
        np.testing.assert_allclose(field(pieces.GetOutput()), want, rtol=0, atol=1e-9)

    def testDefaultGeometryWarned(self):
        # An image made by hand whose field data says where its cells are but whose origin and
        # spacing were left VTK's (0 and 1): the filters take the geometry (Rasters.md), cells
        # of one CRS unit, and say so; silent until 2026-12-07 (SkyViewFactor 0.21 instead of
        # 0.79 on a window of 30 m cells). So is one whose GeoTransform has cells of one unit
        # elsewhere (a 1 m LiDAR grid: not warned about until review). An image whose geometry
        # is set is not warned about, nor one whose GeoTransform is its default geometry's.
        # The writers (which wrote such a lat/lon image to 343 degrees north) and the sun's
        # place give the same warning (silent until 2026-12-07).
        from aperture.errors import Watcher
        folder = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, folder)

        def stages():
            """Every stage given an image, each with a function that gives it one."""
            for cls in (aperture.vtkApertureSkyVisibility, aperture.vtkApertureTerrainMesh):
                def update(stage, image):
                    stage.SetInputData(image)
                    stage.Update()
                yield cls(), update

            for cls, name in ((aperture.vtkApertureDEMWriter, "dem.tif"),
                              (aperture.vtkApertureEXRWriter, "dem.exr")):
                def write(stage, image, name=name):
                    stage.SetInputData(image)
                    stage.SetFileName(os.path.join(folder, name))
                    stage.Write()
                    self.assertEqual(stage.GetErrorCode(), 0, stage)
                yield cls(), write
            yield aperture.vtkApertureSolarPosition(), lambda stage, image: (
                self.assertTrue(stage.SetPlaceFromImage(image), stage.GetErrorMessage()))

            def directions(stage, image):
                stage.SetUnixTime(1.7e9)
                # (a grid in a local CRS has no place on the Earth: refused, after the warning)
                self.assertEqual(stage.AddSunDirectionArray(image, "Sun"),
                                 image.GetFieldData().GetAbstractArray("CRS").GetValue(0)
                                 .startswith("GEOGCRS"), stage.GetErrorMessage())
            yield aperture.vtkApertureSolarPosition(), directions
        reader = aperture.vtkApertureDEMReader()
        reader.SetFileName(self.path)
        reader.SetDecimation(4)
        reader.PartialBlockWarningOff()
        reader.Update()
        gt = reader.GetOutput().GetFieldData().GetArray("GeoTransform")
        x0, dx, y0, dy = (gt.GetValue(k) for k in (0, 1, 3, 5))
        for case in ("default", "set", "unit cells", "unit cells elsewhere", "unit cells turned",
                     "unit cells north-west"):
            image = vtkImageData()
            image.DeepCopy(reader.GetOutput())
            if case != "set":
                image.SetOrigin(0.0, 0.0, 0.0)
                image.SetSpacing(1.0, 1.0, 1.0)
            if case.startswith("unit cells"):
                geo = aperture.vtkApertureGeoreference()
                self.assertTrue(geo.SetCRS('LOCAL_CS["site",UNIT["kilometre",1000]]') and
                                geo.AttachToImage(image))
            moved = image.GetFieldData().GetArray("GeoTransform")
            if case == "unit cells elsewhere":  # (the grid 500 km east, 4000 km north)
                moved.SetValue(0, moved.GetValue(0) + 500.0)
                moved.SetValue(3, moved.GetValue(3) + 4000.0)
            if case == "unit cells turned":  # (a rotated GeoTransform: no default geometry's)
                moved.SetValue(2, 0.3)
            if case == "unit cells north-west":  # (the documented miss: a corner beyond it)
                moved.SetValue(0, moved.GetValue(0) - 100.0)
                moved.SetValue(3, moved.GetValue(3) + 1000.0)
            for stage, give in stages():
                w = Watcher()
                w.watch(stage)
                give(stage, image)
                if case == "default":
                    self.assertEqual(len(w.warnings), 1, (stage, w.warnings))
                    self.assertTrue(w.warnings[0].startswith(
                        "the image's origin and spacing are VTK's defaults (0 0 and 1 1), but "
                        "its field data's GeoTransform has cells of %.12g x %.12g from x "
                        "%.12g, y %.12g: the image's geometry is used, cells of 1 CRS unit at "
                        "the CRS's origin; set the " % (dx, -dy, x0, y0) +
                        "image's origin and spacing (SetOrigin, SetSpacing: a cell centre and "
                        "the cell size)"), w.warnings[0])
                    self.assertIn("0.00333333333333 x 0.00333333333333", w.warnings[0])
                elif case in ("unit cells elsewhere", "unit cells turned"):
                    self.assertEqual(len(w.warnings), 1, (stage, w.warnings))
                    # (the default grid's edges, -0.5 and rows - 0.5, moved)
                    self.assertIn("GeoTransform has cells of 1 x 1 from x %g, y %g: the "
                                  "image's geometry is used"
                                  % ((499.5, image.GetDimensions()[1] - 0.5 + 4000.0)
                                     if case.endswith("elsewhere")
                                     else (-0.5, image.GetDimensions()[1] - 0.5)),
                                  w.warnings[0])
                else:
                    self.assertEqual(w.warnings, [], (case, stage))
            if case == "unit cells":
                # (a piece of it, and a crop: their GeoTransform, the whole grid's, is larger
                # than their extents; warned about for an hour of review)
                from vtkmodules.vtkImagingCore import vtkExtractVOI
                voi = vtkExtractVOI()
                voi.SetInputData(image)
                voi.SetVOI(10, 30, 5, 25, 0, 0)
                for stage in (aperture.vtkApertureSkyVisibility(),
                              aperture.vtkApertureTerrainMesh()):
                    w = Watcher()
                    w.watch(stage)
                    stage.SetInputConnection(voi.GetOutputPort())
                    stage.Update()
                    stage.SetInputData(image)
                    stage.UpdatePiece(1, 2, 1)
                    self.assertEqual(w.warnings, [], stage)
        # A sky filter given such an image, a mesher behind it, the grid beyond the north pole
        # (one-degree cells from latitude 0, 172 rows): the sky filter warns before it refuses
        # the grid (it published the image's CRS, so the mesher refused the grid before the sky
        # filter ran and warned, for an hour of review)
        reader.SetDecimation(2)
        reader.Update()
        image = vtkImageData()
        image.DeepCopy(reader.GetOutput())
        image.SetOrigin(0.0, 0.0, 0.0)
        image.SetSpacing(1.0, 1.0, 1.0)
        sky = aperture.vtkApertureSkyVisibility()
        sky.SetInputData(image)
        mesher = aperture.vtkApertureTerrainMesh()
        mesher.SetInputConnection(sky.GetOutputPort())
        w, refusal = Watcher(), Watcher()
        w.watch(sky)
        refusal.watch(sky.GetExecutive())
        refusal.watch(mesher)
        refusal.watch(mesher.GetExecutive())
        mesher.Update()
        self.assertEqual(len(w.warnings), 1, w.warnings)
        self.assertIn("the image's origin and spacing are VTK's defaults", w.warnings[0])
        self.assertTrue(w.errors and "beyond the pole" in w.errors[0], w.errors)
        # One whose default geometry is a grid that can be measured (360 columns of a degree:
        # a global grid) is published all the same: the mesher's pieces are bands with their
        # seams, adding up to the whole mesh (blocks without seams, 158 triangles short in 4
        # pieces, for an hour of review)
        image = vtkImageData()
        image.SetDimensions(360, 80, 1)
        image.SetOrigin(0.25, 0.25, 0.0)
        image.SetSpacing(0.5, 0.5, 1.0)
        geo = aperture.vtkApertureGeoreference()
        self.assertTrue(geo.SetCRS("EPSG:4326") and geo.AttachToImage(image))
        image.SetOrigin(0.0, 0.0, 0.0)
        image.SetSpacing(1.0, 1.0, 1.0)
        heights = numpy_to_vtk(np.random.default_rng(5).uniform(0.0, 500.0, 360 * 80), deep=1)
        heights.SetName("Elevation")
        image.GetPointData().SetScalars(heights)
        sky = aperture.vtkApertureSkyVisibility()
        sky.SetInputData(image)
        sky.SetMaximumDistance(50e3)
        mesher.SetInputConnection(sky.GetOutputPort())
        w = Watcher()
        w.watch(sky)
        mesher.Update()
        whole = mesher.GetOutput().GetNumberOfCells()
        self.assertEqual(whole, 2 * 360 * 79)  # (the seam's quads too)
        cells = 0
        for piece in range(4):
            mesher.UpdatePiece(piece, 4, 0)
            cells += mesher.GetOutput().GetNumberOfCells()
        self.assertEqual(cells, whole)
        self.assertTrue(w.warnings and "VTK's defaults" in w.warnings[0], w.warnings)

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
        from vtkmodules.vtkCommonExecutionModel import vtkExtentTranslator
        covered = np.zeros((344, 403), dtype=bool)
        for piece in range(2):
            r, sky, m = pipeline()
            m.UpdatePiece(piece, 2, 0)
            ext = [0] * 6  # (the mesh's piece; the sky filter's output has the normals' margin)
            vtkExtentTranslator().PieceToExtentThreadSafe(
                piece, 2, 0, [0, 402, 0, 343, 0, 0], ext, vtkExtentTranslator.BLOCK_MODE, 0)
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
