# SPDX-License-Identifier: BSD-3-Clause
"""vtkApertureLightingMapper on synthetic meshes whose lighting has a closed form, read back
pixel by pixel from top-down orthographic renders (no tone mapping, exposure chosen so the
values stay below 1, no multisampling):

- open flat ground: the radiance is albedo/pi x (Esun sin e + pi Lsky), within 1% (8-bit
  quantisation is 0.2-0.4% at these levels, single precision far less);
- a pit whose aperture (20 deg) is narrower than the sun's zenith angle: sky light only,
  albedo/pi x pi Lsky sin^2 rp, and darker than open ground;
- an aperture rim swept across the sun: the penumbra (10% to 90% of full sun) widens
  monotonically with the sun's scale (1, 5, 20);
- GPU against the CPU reference (ap_light.c, double precision) at every vertex, for both
  intersection modes and both Lambert modes, with a sky table, and shading per vertex; and
  with every aperture rim crossing the real sun's disc (the lens formulas in float);
- moving the sun or switching a mode re-uploads no geometry; bad input gives an error and a
  documented fallback.
"""
import math
import sys

import numpy as np
from vtkmodules.test import Testing
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkCommand, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

import aperture
from aperture import scene

N = 48  # vertices per side; one pixel per vertex


def grid_mesh(normal, bent, radius):
    """An N x N grid of vertices at integer (x, y), z = 0, two triangles per quad, with the
    given per-vertex arrays (callables of (i, j) or constants)."""
    pts = vtkPoints()
    ij = [(i, j) for j in range(N) for i in range(N)]
    pts.SetNumberOfPoints(len(ij))
    for k, (i, j) in enumerate(ij):
        pts.SetPoint(k, float(i), float(j), 0.0)
    cells = vtkCellArray()
    for j in range(N - 1):
        for i in range(N - 1):
            a, b, c, d = j * N + i, j * N + i + 1, (j + 1) * N + i + 1, (j + 1) * N + i
            cells.InsertNextCell(3, (a, b, c))
            cells.InsertNextCell(3, (a, c, d))
    mesh = vtkPolyData()
    mesh.SetPoints(pts)
    mesh.SetPolys(cells)
    value = lambda f, i, j: f(i, j) if callable(f) else f
    for name, f, comps in (("Normals", normal, 3), ("BentNormal", bent, 3),
                           ("ApertureRadius", radius, 1)):
        data = np.array([value(f, i, j) for i, j in ij], dtype=np.float32).reshape(-1, comps)
        if comps == 1:
            data = data.ravel()
        array = numpy_to_vtk(np.ascontiguousarray(data), deep=1)
        array.SetName(name)
        mesh.GetPointData().AddArray(array)
    return mesh


def unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def sun_dir(azimuth, elevation):
    a, e = math.radians(azimuth), math.radians(elevation)
    return [math.cos(e) * math.sin(a), math.cos(e) * math.cos(a), math.sin(e)]


class Scene:
    """A top-down orthographic view in which pixel (i, j) shows vertex (i, j)."""

    def __init__(self, mesh, albedo=(0.5, 0.5, 0.5)):
        self.mapper = aperture.vtkApertureLightingMapper()
        self.mapper.SetInputData(mesh)
        self.mapper.ScalarVisibilityOff()
        self.actor = vtkActor()
        self.actor.SetMapper(self.mapper)
        self.actor.GetProperty().SetColor(*albedo)
        self.renderer = vtkRenderer()
        self.renderer.AddActor(self.actor)
        self.renderer.SetBackground(0, 0, 0)
        self.window = vtkRenderWindow()
        self.window.SetOffScreenRendering(1)
        self.window.SetMultiSamples(0)
        self.window.SetSize(N, N)
        self.window.AddRenderer(self.renderer)
        camera = self.renderer.GetActiveCamera()
        camera.ParallelProjectionOn()
        c = (N - 1) / 2.0
        camera.SetFocalPoint(c, c, 0.0)
        camera.SetPosition(c, c, 100.0)
        camera.SetViewUp(0, 1, 0)
        camera.SetParallelScale(N / 2.0)
        self.renderer.ResetCameraClippingRange()

    def pixels(self):
        """(N, N, 3) array, [j, i] = pixel over vertex (i, j)."""
        return scene.rgb_pixels(self.window)


UP = (0.0, 0.0, 1.0)
ESUN = (1000.0, 900.0, 800.0)
LSKY = (30.0, 35.0, 45.0)


ALBEDO = (0.6, 0.55, 0.5)
INNER = np.zeros((N, N), bool)
INNER[1:-1, 1:-1] = True  # border pixels lie on the mesh's edge
INNER = INNER.ravel()


def linear_scene(mesh, exposure):
    s = Scene(mesh)
    m = s.mapper
    m.SetSunIrradiance(*ESUN)
    m.SetSkyRadiance(*LSKY)
    m.SetToneMapping(False)
    m.SetExposure(exposure)
    return s


class TestApertureLighting(Testing.vtkTest):
    def testFlatGround(self):
        # Open flat ground: n = b = up, rp = 90 deg; sun at 40 deg elevation, fully visible.
        s = linear_scene(grid_mesh(UP, UP, math.pi / 2), exposure=-8.0)
        for lambert in (s.mapper.CENTROID, s.mapper.EXACT_CAP):
            for intersection in (s.mapper.EXACT, s.mapper.SMOOTHSTEP):
                s.mapper.SetLambertMode(lambert)
                s.mapper.SetIntersectionMode(intersection)
                s.mapper.SetSunDirection(sun_dir(200.0, 40.0))
                got = s.pixels()[5:-5, 5:-5].reshape(-1, 3).mean(axis=0)
                e = math.radians(40.0)
                # the sky fills the aperture except the sun's own (tiny) share
                expected = [0.5 / math.pi * (es * math.sin(e) + math.pi * ls) * 2 ** -8 * 255
                            for es, ls in zip(ESUN, LSKY)]
                for c in range(3):
                    self.assertAlmostEqual(got[c] / expected[c], 1.0, delta=0.01,
                                           msg="%d/%d: %s vs %s" % (lambert, intersection,
                                                                    got, expected))

    def testLinearCapture(self):
        # Read back unclamped from a float framebuffer (vtkApertureLinearCapture), open ground
        # gives its closed-form radiance to single precision, values far above 1 included, and
        # a varied mesh the CPU reference's radiance at every vertex (median 1e-6 relative).
        s = linear_scene(grid_mesh(UP, UP, math.pi / 2), exposure=0.0)
        s.mapper.SetSunDirection(sun_dir(200.0, 40.0))
        image = aperture.vtkApertureLinearCapture().Capture(s.renderer)
        rgba = vtk_to_numpy(image.GetPointData().GetArray("Radiance")).reshape(N, N, 4)
        e = math.radians(40.0)
        for c in range(3):
            expected = 0.5 / math.pi * (ESUN[c] * math.sin(e) + math.pi * LSKY[c])
            got = rgba[5:-5, 5:-5, c]
            self.assertGreater(expected, 100.0)
            self.assertLess(np.abs(got / expected - 1.0).max(), 1e-4, (got.mean(), expected))
        # every vertex of a varied mesh, both Lambert modes, a widened sun
        mesh = random_mesh()
        s = linear_scene(mesh, exposure=0.0)
        s.mapper.SetSunDirection(sun_dir(150.0, 35.0))
        s.mapper.SetSunScale(20.0)
        from vtkmodules.vtkCommonCore import vtkDoubleArray
        for lambert in (s.mapper.CENTROID, s.mapper.EXACT_CAP):
            s.mapper.SetLambertMode(lambert)
            image = aperture.vtkApertureLinearCapture().Capture(s.renderer)
            gpu = vtk_to_numpy(image.GetPointData().GetArray("Radiance")).reshape(N, N, 4)
            cpu = vtkDoubleArray()
            self.assertTrue(s.mapper.ComputeReference(mesh, (0.5, 0.5, 0.5), cpu, None))
            cpu = vtk_to_numpy(cpu).reshape(N, N, 3)
            inner = (slice(1, -1), slice(1, -1))
            rel = np.abs(gpu[inner][..., :3] - cpu[inner]) / np.maximum(cpu[inner], 1.0)
            # Single precision: typically 1e-6; near the aperture's rim the cap intersection
            # and the lens centroid subtract nearly equal terms (ALGORITHMS.md 1.2: the area
            # is good to 4e-4 in float there), so a few points reach ~1e-3.
            self.assertLess(np.median(rel), 1e-5, lambert)
            self.assertLess(np.percentile(rel, 99), 1e-3, lambert)
            self.assertLess(rel.max(), 5e-3, lambert)

    def testEdgeInputsAsTheReference(self):
        # Inputs at the edges of the model's ranges, on open flat ground (sun at 40 deg, the
        # closed form albedo/pi (Esun sin e + pi Lsky)), the GPU shading per pixel and per
        # vertex and the CPU reference alike (until 2026-12-07: an aperture radius of +inf,
        # which the model takes as pi/2, interpolated to NaN per pixel, black; normals 5e-4
        # too long, as half floats round unit vectors, were nodata, NaN, in the reference; a
        # sun radius under 1e-6 rad failed the reference naming no parameter).
        from vtkmodules.vtkCommonCore import vtkDoubleArray
        e = math.radians(40.0)
        expected = [0.5 / math.pi * (es * math.sin(e) + math.pi * ls) for es, ls in
                    zip(ESUN, LSKY)]
        long_up = (0.0, 0.0, 1.0005)  # |v|^2 - 1 = 1e-3
        for name, mesh, scale in (("+inf radius", grid_mesh(UP, UP, math.inf), 1.0),
                                  ("long normals", grid_mesh(long_up, long_up, math.pi / 2), 1.0),
                                  ("point sun", grid_mesh(UP, UP, math.pi / 2), 1e-4)):
            s = linear_scene(mesh, exposure=0.0)
            s.mapper.SetSunDirection(sun_dir(200.0, 40.0))
            s.mapper.SetSunScale(scale)
            cpu = vtkDoubleArray()
            self.assertTrue(s.mapper.ComputeReference(mesh, (0.5, 0.5, 0.5), cpu, None), name)
            cpu = vtk_to_numpy(cpu).reshape(N, N, 3)
            for frequency in (s.mapper.PER_FRAGMENT, s.mapper.PER_VERTEX):
                s.mapper.SetShadingFrequency(frequency)
                image = aperture.vtkApertureLinearCapture().Capture(s.renderer)
                gpu = vtk_to_numpy(image.GetPointData().GetArray("Radiance")).reshape(N, N, 4)
                for c in range(3):
                    for got in (gpu[5:-5, 5:-5, c], cpu[5:-5, 5:-5, c]):
                        self.assertLess(np.abs(got / expected[c] - 1.0).max(), 1e-4,
                                        (name, frequency, c, got.min(), expected[c]))
        # Normals of tiny or huge lengths: lit alike, scaled by their largest component before
        # they are normalised (squares of 1e-19 underflow in float: the GPU flushed them and
        # drew black where the reference lit them), or nodata alike where that component is
        # below 2^-100 or 2^62 and above; a subnormal component beside a normal one (which a
        # GPU flushes to 0) no matter
        for normal, lit in (((0.0, 0.0, 1e-25), True), ((1e-19, 1e-19, 1e-19), True),
                            ((0.0, 0.0, 1e20), False), ((0.0, 0.0, 1e-39), False),
                            ((0.0, 0.0, 1e-31), False), ((2e-38, 1e-38, 2e-38), False),
                            ((1e-30, 1e-38, 1e-30), True)):
            mesh = grid_mesh(normal, UP, math.pi / 2)
            s = linear_scene(mesh, exposure=0.0)
            s.mapper.SetSunDirection(sun_dir(200.0, 40.0))
            cpu = vtkDoubleArray()
            self.assertTrue(s.mapper.ComputeReference(mesh, (0.5, 0.5, 0.5), cpu, None))
            cpu = vtk_to_numpy(cpu).reshape(N, N, 3)
            if not lit:
                self.assertTrue(np.isnan(cpu).all(), normal)
            for frequency in (s.mapper.PER_FRAGMENT, s.mapper.PER_VERTEX):
                s.mapper.SetShadingFrequency(frequency)
                image = aperture.vtkApertureLinearCapture().Capture(s.renderer)
                gpu = vtk_to_numpy(image.GetPointData().GetArray("Radiance")).reshape(N, N, 4)
                inner = gpu[5:-5, 5:-5, :3]
                if not lit:
                    self.assertEqual(np.abs(inner).max(), 0.0, (normal, frequency))
                    continue
                # (the tilted normal (1, 1, 1)/sqrt 3 is no flat ground: against the reference)
                for got in (inner, cpu[5:-5, 5:-5]):
                    self.assertTrue(np.isfinite(got).all(), (normal, frequency))
                rel = np.abs(inner - cpu[5:-5, 5:-5]) / np.maximum(cpu[5:-5, 5:-5], 1.0)
                self.assertLess(rel.max(), 1e-4, (normal, frequency))
                if normal[0] == 0.0:
                    self.assertLess(np.abs(inner[..., 0] / expected[0] - 1.0).max(), 1e-4)

    def testWideTriangleRadii(self):
        # Radii are interpolated across a triangle as they are, the model taking pi/2 for
        # more: a quad over the view whose radius runs from 0.2 at x = 0 to 3.0 at its east
        # edge (a radius of a cap, up to pi), flat open ground, sun 40 deg up: from the column
        # where the interpolated radius passes pi/2 (23 of 47) the point is open ground.
        # (A clamp to pi/2 before interpolating, 53fbfbc, reached pi/2 only at the edge.)
        pts = vtkPoints()
        for x, y in ((0, 0), (N - 1, 0), (N - 1, N - 1), (0, N - 1)):
            pts.InsertNextPoint(float(x), float(y), 0.0)
        cells = vtkCellArray()
        cells.InsertNextCell(3, (0, 1, 2))
        cells.InsertNextCell(3, (0, 2, 3))
        mesh = vtkPolyData()
        mesh.SetPoints(pts)
        mesh.SetPolys(cells)
        for name, data in (("Normals", [UP] * 4), ("BentNormal", [UP] * 4),
                           ("ApertureRadius", [0.2, 3.0, 3.0, 0.2])):
            array = numpy_to_vtk(np.array(data, dtype=np.float32), deep=1)
            array.SetName(name)
            mesh.GetPointData().AddArray(array)
        s = linear_scene(mesh, exposure=0.0)
        s.mapper.SetSunDirection(sun_dir(200.0, 40.0))
        image = aperture.vtkApertureLinearCapture().Capture(s.renderer)
        gpu = vtk_to_numpy(image.GetPointData().GetArray("Radiance")).reshape(N, N, 4)
        e = math.radians(40.0)
        expected = 0.5 / math.pi * (ESUN[0] * math.sin(e) + math.pi * LSKY[0])
        self.assertLess(np.abs(gpu[5:-5, 28:-3, 0] / expected - 1.0).max(), 1e-4)
        # (and where the radius is below the sun's zenith angle, 50 deg, the sky alone: dark)
        self.assertLess(gpu[5:-5, 3:10, 0].max(), 0.2 * expected)

    def testPit(self):
        rp = math.radians(20.0)
        pit = linear_scene(grid_mesh(UP, UP, rp), exposure=-5.0)
        pit.mapper.SetSunDirection(sun_dir(180.0, 40.0))  # zenith 50 deg > 20 deg + radius
        got = pit.pixels()[5:-5, 5:-5].reshape(-1, 3).mean(axis=0)
        expected = [0.5 / math.pi * ls * math.pi * math.sin(rp) ** 2 * 2 ** -5 * 255
                    for ls in LSKY]
        for c in range(3):
            self.assertAlmostEqual(got[c] / expected[c], 1.0, delta=0.02, msg=str(got))
        # the same pit with the sun overhead is lit
        pit.mapper.SetSunDirection(UP)
        self.assertGreater(pit.pixels()[5:-5, 5:-5].mean(), 2 * got.mean())

    def testPenumbraWidens(self):
        # The aperture axis tilts away from the sun along x, so the sun (scaled) crosses the
        # aperture rim between the columns: the lit fraction falls from 1 to 0 across a band
        # whose width grows with the sun's radius.
        rp = math.radians(40.0)
        sun_zenith = 40.0

        def bent(i, j):
            tilt = math.radians(-30.0 + 60.0 * i / (N - 1))  # axis zenith angle along x
            return (math.sin(tilt), 0.0, math.cos(tilt))
        s = linear_scene(grid_mesh(UP, bent, rp), exposure=-9.0)
        s.mapper.SetSkyRadiance(0, 0, 0)
        s.mapper.SetSunDirection(-math.sin(math.radians(sun_zenith)), 0.0,
                                 math.cos(math.radians(sun_zenith)))
        widths = []
        for scale in (1.0, 5.0, 20.0):
            s.mapper.SetSunScale(scale)
            row = s.pixels()[N // 2, :, 1].astype(float)
            full = row[:4].mean()
            self.assertGreater(full, 50)
            lit = row / full
            inside = np.where((lit < 0.9) & (lit > 0.1))[0]
            widths.append(len(inside))
            self.assertLess(row[-4:].max(), 1.0)  # fully shadowed beyond the band
        self.assertEqual(widths, sorted(widths), widths)
        self.assertGreater(widths[2], widths[0] + 4, widths)

    def checkAgainstReference(self, s, mesh, key, worst, share=0.99):
        """The GPU picture of scene s against the CPU reference of its mapper at every inner
        pixel: at most one 8-bit level apart and more than `share` of them equal. Both sides
        round the same quantity to 8 bits; it differs only by single-precision rounding on the
        GPU (the exact cap area is float-safe to 4e-4 relative, ALGORITHMS.md 1.2; the rest is
        ~1e-6), which moves a value across a rounding edge at some pixels but can never move it
        by two levels (a level is 0.4%). Records (largest difference, share equal) as
        worst[key]; returns the reference, (N*N, 3) ints."""
        gpu = s.pixels().reshape(-1, 3).astype(int)
        cpu = reference_display(s.mapper, mesh, ALBEDO)
        diff = np.abs(gpu - cpu)[INNER]
        worst[key] = (int(diff.max()), round(float(np.mean(diff == 0)), 4))
        self.assertLessEqual(int(diff.max()), 1, (key, worst))
        self.assertGreater(np.mean(diff == 0), share, (key, worst))
        return cpu

    def testGPUAgainstCPU(self):
        mesh = random_mesh()
        s = Scene(mesh, albedo=ALBEDO)
        m = s.mapper
        m.SetSunIrradiance(*ESUN)
        m.SetSkyRadiance(*LSKY)
        m.SetExposure(-7.5)
        worst = {}
        for scale in (1.0, 20.0):
            m.SetSunScale(scale)
            m.SetSunDirection(sun_dir(150.0, 35.0))
            for lambert in (m.CENTROID, m.EXACT_CAP):
                for intersection in (m.EXACT, m.SMOOTHSTEP):
                    m.SetLambertMode(lambert)
                    m.SetIntersectionMode(intersection)
                    cpu = self.checkAgainstReference(s, mesh, (scale, lambert, intersection),
                                                     worst)
                    self.assertGreater(cpu.std(), 10.0)  # a varied picture, not a constant
        # The sky filled from a table of cap means (here an arbitrary smooth, coloured one):
        # the shader's lookup against ap_light_sky_lookup.
        from vtkmodules.vtkCommonCore import vtkFloatArray
        na, ne, nr = 16, 6, 5
        i, j, k = np.meshgrid(np.arange(na), np.arange(ne), np.arange(nr), indexing="ij")
        values = np.stack([20 + 10 * np.sin(2 * np.pi * (i + 0.5) / na), 25 + 4 * j + 0 * i,
                           30 + 6 * k + 0 * i], -1).astype(np.float32)
        table = numpy_to_vtk(np.ascontiguousarray(values.transpose(2, 1, 0, 3).reshape(-1, 3)),
                             deep=1)
        m.SetSkyTable(table, na, ne, nr)
        m.SetSunScale(1.0)
        for lambert in (m.CENTROID, m.EXACT_CAP):
            m.SetLambertMode(lambert)
            self.checkAgainstReference(s, mesh, ("table", lambert), worst)
        # Per-vertex shading: the same values at the vertices (pixels show vertices here).
        m.SetShadingFrequency(m.PER_VERTEX)
        for lambert in (m.CENTROID, m.EXACT_CAP):
            m.SetLambertMode(lambert)
            self.checkAgainstReference(s, mesh, ("per-vertex", lambert), worst)
        m.SetShadingFrequency(m.PER_FRAGMENT)
        m.SetSkyTable(None, 0, 0, 0)
        print("GPU vs CPU, (largest 8-bit difference, share of equal pixels) per (sun scale, "
              "Lambert, intersection):", worst)

    def testGPUAgainstCPUAtTheRim(self):
        # Every vertex's aperture rim crosses the real sun's disc (partial overlap everywhere):
        # the lens formulas in float against the CPU reference in double where they are most
        # delicate, for both Lambert modes.
        rl = math.radians(0.26667)
        sun = unit(sun_dir(150.0, 35.0))
        rng = np.random.default_rng(11)
        count = N * N
        radii = rng.uniform(0.2, 1.4, count)
        d = radii + rng.uniform(-0.95, 0.95, count) * rl
        # a bent normal d away from the sun, in a random plane through it
        helper = np.array([0.0, 0.0, 1.0])
        e1 = unit(np.cross(sun, helper))
        e2 = np.cross(sun, e1)
        turn = rng.uniform(0, 2 * math.pi, count)
        axis = np.cos(turn)[:, None] * e1 + np.sin(turn)[:, None] * e2
        bents = np.cos(d)[:, None] * sun + np.sin(d)[:, None] * axis
        normals = np.array([unit(sun + 0.3 * rng.normal(size=3)) for _ in range(count)])
        mesh = grid_mesh(lambda i, j: normals[j * N + i], lambda i, j: bents[j * N + i],
                         lambda i, j: radii[j * N + i])
        s = Scene(mesh, albedo=ALBEDO)
        m = s.mapper
        m.SetSunIrradiance(*ESUN)
        m.SetSkyRadiance(*LSKY)
        m.SetExposure(-7.5)
        m.SetSunDirection(sun)
        worst = {}
        for lambert in (m.CENTROID, m.EXACT_CAP):
            m.SetLambertMode(lambert)
            # One 8-bit level at most, as testGPUAgainstCPU; but here every pixel carries the
            # float lens error (up to 2e-4 relative for the sun against an aperture rim,
            # measured against double; ~0.03 of a level at these values), so a few percent
            # of the pixels cross a rounding edge (the shader before the angle-addition lens:
            # 95.2% equal; now 97%).
            cpu = self.checkAgainstReference(s, mesh, lambert, worst, share=0.95)
            self.assertGreater(cpu.std(), 10.0)  # partly lit suns: a varied picture
        print("GPU vs CPU at the rim (largest 8-bit difference, share equal) per Lambert:",
              worst)

    def testNoGeometryUploads(self):
        # moving the sun sets uniforms; switching a mode or the shading frequency compiles
        # another shader variant: neither uploads the geometry again
        s = linear_scene(grid_mesh(UP, UP, 1.0), exposure=-8.0)
        m = s.mapper
        s.pixels()
        uploads = m.GetGeometryUploads()
        for k, az in enumerate(range(0, 360, 45)):
            m.SetSunDirection(sun_dir(az, 30.0))
            m.SetExposure(-7.0)
            m.SetSunScale(3.0)
            m.SetIntersectionMode(m.SMOOTHSTEP if k % 2 else m.EXACT)
            m.SetLambertMode(m.EXACT_CAP if k % 4 < 2 else m.CENTROID)
            m.SetShadingFrequency(m.PER_VERTEX if k % 3 == 0 else m.PER_FRAGMENT)
            s.pixels()
        self.assertEqual(m.GetGeometryUploads(), uploads)

    def testBadInput(self):
        errors = []
        mesh = grid_mesh(UP, UP, 1.0)
        mesh.GetPointData().RemoveArray("BentNormal")
        s = linear_scene(mesh, exposure=0.0)
        s.mapper.AddObserver(vtkCommand.ErrorEvent, lambda o, e: errors.append(e))
        picture = s.pixels()
        self.assertIn("no point array 'BentNormal'", s.mapper.GetInputProblem())
        self.assertTrue(errors)
        self.assertGreater(picture.mean(), 10)  # drawn with standard lighting instead
        # wrongly sized
        short = numpy_to_vtk(np.zeros(10, np.float32), deep=1)
        short.SetName("ApertureRadius")
        mesh2 = grid_mesh(UP, UP, 1.0)
        mesh2.GetPointData().AddArray(short)
        s2 = linear_scene(mesh2, exposure=0.0)
        s2.mapper.AddObserver(vtkCommand.ErrorEvent, lambda o, e: errors.append(e))
        s2.pixels()
        self.assertIn("expected 1 and %d" % (N * N), s2.mapper.GetInputProblem())
        # NaN (nodata) vertices are black
        s3 = linear_scene(grid_mesh(UP, UP, lambda i, j: float("nan") if i < N // 2 else 1.0),
                          exposure=-8.0)
        p = s3.pixels()
        self.assertEqual(int(p[5:-5, 2:N // 2 - 2].max()), 0)
        self.assertGreater(p[5:-5, N // 2 + 2:-2].mean(), 10)
        # zero sun direction: an error, the previous direction kept
        s3.mapper.AddObserver(vtkCommand.ErrorEvent, lambda o, e: errors.append(e))
        before = len(errors)
        s3.mapper.SetSunDirection(0, 0, 0)
        self.assertEqual(len(errors), before + 1)
        self.assertEqual(tuple(s3.mapper.GetSunDirection()), (0.0, 0.0, 1.0))
        # negative EV darkens (a valid exposure), it is not an error
        s3.mapper.SetExposure(-12.0)
        self.assertLess(s3.pixels().mean(), p.mean())


    def testStandardLightingStandsIn(self):
        # Where the aperture model cannot draw, VTK's lighting stands in as a plain
        # vtkPolyDataMapper draws it. Until 2026-12-06 it was scaled by the model's Exposure
        # (black at -7 EV), and edges over the surface (VTK's geometry shader, which dropped
        # the model's arrays) were black with no word.
        from vtkmodules.vtkRenderingCore import vtkPolyDataMapper
        mesh = grid_mesh(UP, UP, 1.0)
        plain = Scene(mesh)
        plain.actor.SetMapper(vtkPolyDataMapper())
        plain.actor.GetMapper().SetInputData(mesh)
        plain.actor.GetMapper().ScalarVisibilityOff()
        plain.window.SetSize(4 * N, 4 * N)  # (edges one pixel wide, cells four)
        vtk_lit = plain.pixels().astype(int)
        self.assertGreater(vtk_lit.mean(), 50)
        missing = grid_mesh(UP, UP, 1.0)
        missing.GetPointData().RemoveArray("BentNormal")
        s = linear_scene(missing, exposure=-7.0)
        s.window.SetSize(4 * N, 4 * N)
        errors = []
        s.mapper.AddObserver(vtkCommand.ErrorEvent, lambda o, e: errors.append(e))
        self.assertLessEqual(np.abs(s.pixels().astype(int) - vtk_lit).max(), 1)
        self.assertTrue(errors)

        s = linear_scene(mesh, exposure=-8.0)
        s.mapper.SetSunDirection(sun_dir(0.0, 30.0))
        s.window.SetSize(4 * N, 4 * N)
        s.mapper.AddObserver(vtkCommand.ErrorEvent, lambda o, e: errors.append(e))
        aperture_lit = s.pixels().astype(int)
        del errors[:]
        s.actor.GetProperty().EdgeVisibilityOn()
        s.actor.GetProperty().SetEdgeColor(1.0, 0.0, 0.0)
        p = s.pixels().astype(int)
        self.assertTrue(errors)
        self.assertIn("geometry shader", s.mapper.GetInputProblem())
        red = (p[:, :, 0] > 200) & (p[:, :, 1] < 60) & (p[:, :, 2] < 60)
        self.assertGreater(red.mean(), 0.2)  # the edges, drawn
        self.assertGreater((p[:, :, 1] > 50).mean(), 0.2)  # and the surface between them, lit
        plain.actor.GetProperty().EdgeVisibilityOn()
        plain.actor.GetProperty().SetEdgeColor(1.0, 0.0, 0.0)
        self.assertLessEqual(np.abs(p - plain.pixels().astype(int)).max(), 1)
        s.actor.GetProperty().EdgeVisibilityOff()
        del errors[:]
        self.assertEqual(np.abs(s.pixels().astype(int) - aperture_lit).max(), 0)
        self.assertFalse(errors)
        self.assertEqual(s.mapper.GetInputProblem(), "")

    def testScriptVertexAttributesKept(self):
        # A script's own vertex attribute for its own shader replacement stays mapped when the
        # model maps its arrays (until 2026-12-06 every mapping was removed: it read 0).
        from vtkmodules.vtkCommonDataModel import vtkDataObject
        mesh = grid_mesh(UP, UP, lambda i, j: 0.2 if i < N // 2 else 1.0)
        s = linear_scene(mesh, exposure=-8.0)
        s.mapper.MapDataArrayToVertexAttribute(
            "scriptRadius", "ApertureRadius", vtkDataObject.FIELD_ASSOCIATION_POINTS, -1)
        sp = s.actor.GetShaderProperty()
        sp.AddVertexShaderReplacement("//VTK::Normal::Dec", True, "//VTK::Normal::Dec\n"
                                      "in float scriptRadius;\nout float scriptRadiusVSOut;",
                                      False)
        sp.AddVertexShaderReplacement("//VTK::Normal::Impl", True, "//VTK::Normal::Impl\n"
                                      "  scriptRadiusVSOut = scriptRadius;", False)
        sp.AddFragmentShaderReplacement("//VTK::Normal::Dec", True, "//VTK::Normal::Dec\n"
                                        "in float scriptRadiusVSOut;", False)
        sp.AddFragmentShaderReplacement("//VTK::Picking::Impl", True, "//VTK::Picking::Impl\n"
                                        "  if (scriptRadiusVSOut < 0.5) "
                                        "gl_FragData[0] = vec4(1.0, 0.0, 0.0, 1.0);", False)
        p = s.pixels().astype(int)
        red = (p[:, :, 0] == 255) & (p[:, :, 1] == 0) & (p[:, :, 2] == 0)
        self.assertTrue(red[2:-2, 2:N // 2 - 2].all())
        self.assertFalse(red[2:-2, N // 2 + 2:-2].any())
        self.assertEqual(s.mapper.GetInputProblem(), "")

def random_mesh(seed=7):
    """Random normals (up to 50 deg tilt), bent normals (45 deg) and apertures (9-83 deg)."""
    rng = np.random.default_rng(seed)
    count = N * N

    def tilt(max_deg):
        az = rng.uniform(0, 2 * math.pi, count)
        t = np.radians(rng.uniform(0, max_deg, count))
        return np.stack([np.sin(t) * np.sin(az), np.sin(t) * np.cos(az), np.cos(t)], -1)
    normals, bents = tilt(50.0), tilt(45.0)
    radii = rng.uniform(0.15, 1.45, count)
    return grid_mesh(lambda i, j: normals[j * N + i], lambda i, j: bents[j * N + i],
                     lambda i, j: radii[j * N + i])


def reference_display(mapper, mesh, albedo):
    """The CPU reference's 8-bit display values per vertex, (N*N, 3) ints."""
    out = vtkUnsignedCharArrayFactory()
    ok = mapper.ComputeReference(mesh, albedo, None, out)
    assert ok, mapper.GetInputProblem()
    return vtk_to_numpy(out).reshape(-1, 3).astype(int)


def vtkUnsignedCharArrayFactory():
    from vtkmodules.vtkCommonCore import vtkUnsignedCharArray
    return vtkUnsignedCharArray()


if __name__ == "__main__":
    Testing.main([(TestApertureLighting, "test")])
