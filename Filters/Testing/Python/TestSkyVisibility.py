# SPDX-License-Identifier: BSD-3-Clause
"""vtkApertureSkyVisibility on real and synthetic DEMs, against references computed another way:

- the embedded (real, lat/lon) DEM: horizons of a few hundred cells against a brute-force
  marcher (numpy, below) that steps along constant-azimuth lines on the WGS 84 ellipsoid with
  its own radii of curvature, bilinear heights and a curvature-with-refraction drop — no
  GeographicLib, no hulls, no sweep; SkyViewFactor from those reference horizons;
- the same analytic terrain as a UTM DEM and as a lat/lon DEM: equal products at equal
  ground points;
- bit-identical results for any thread count; streamed sub-extents equal the whole run;
- every documented error.
"""
import itertools
import math
import re
import os
import sys

import numpy as np
from osgeo import osr
from vtkmodules.test import Testing
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData

import aperture

A_WGS84, F_WGS84 = 6378137.0, 1 / 298.257223563
E2 = F_WGS84 * (2 - F_WGS84)


def radii(lat):
    """Meridional and prime-vertical radii of curvature of WGS 84 (m) at latitudes (rad)."""
    w2 = 1 - E2 * np.sin(lat) ** 2
    return A_WGS84 * (1 - E2) / w2 ** 1.5, A_WGS84 / np.sqrt(w2)


def meridian_arc(lat0, lat):
    """Signed meridian arc of WGS 84 (m) from latitude lat0 to each of lat (rad, any shape):
    Simpson's rule over 64 steps of the meridional radius."""
    lat = np.asarray(lat, dtype=np.float64)
    t = np.linspace(0.0, 1.0, 65)[:, None] * (lat.ravel() - lat0)[None, :] + lat0
    w = np.ones(65)
    w[1:-1:2], w[2:-1:2] = 4, 2
    return ((w[:, None] * radii(t)[0]).sum(0) * (lat.ravel() - lat0) / 192).reshape(lat.shape)


def make_image(z, x0, y0, dx, dy, crs, dtype=np.float32):
    """A DEM image (row 0 south) with its CRS attached; elevations of `dtype`."""
    ny, nx = z.shape
    image = vtkImageData()
    image.SetDimensions(nx, ny, 1)
    image.SetOrigin(x0, y0, 0)
    image.SetSpacing(dx, dy, 1)
    values = numpy_to_vtk(np.ascontiguousarray(z, dtype=dtype).ravel(), deep=1)
    values.SetName("Elevation")
    image.GetPointData().SetScalars(values)
    if crs:
        geo = aperture.vtkApertureGeoreference()
        assert geo.SetCRS(crs)
        geo.AttachToImage(image)
    return image


def sky(image, **options):
    f = aperture.vtkApertureSkyVisibility()
    f.SetInputData(image) if isinstance(image, vtkImageData) else f.SetInputConnection(image)
    for key, value in options.items():
        getattr(f, "Set" + key)(value)
    f.Update()
    return f


def usable_memory():
    """The sky filter's default memory limit before the input's size, bytes (the machine's
    physical memory, or the process's control group's limit less 128 MiB where lower), and what
    its messages call it ("of memory ...")."""
    sky = aperture.vtkApertureSkyVisibility
    return sky.GetUsableMemory(), ("this process may use under its control group's limit"
                                   if sky.IsMemoryGrouped() else "this machine has")


def array(data, name):
    a = data.GetPointData().GetArray(name)
    return vtk_to_numpy(a).astype(np.float64)


def flat_earth_products(test, z, x0, y0, cell, crs, directions):
    """The sky filter's output (HorizonAngles too) on a flat Earth within 5 km, asserting that
    it runs without errors or warnings."""
    from aperture.errors import Watcher
    watch = Watcher()
    f = watch.watch(aperture.vtkApertureSkyVisibility())
    f.SetInputData(make_image(z, x0, y0, cell, cell, crs))
    f.SetMaximumDistance(5000.0)
    f.SetEarthCurvature(False)
    f.SetNumberOfDirections(directions)
    f.SetComputeHorizonAngles(True)
    f.Update()
    test.assertEqual((watch.errors, watch.warnings), ([], []))
    return f.GetOutput()


def brute_force_latlon(z, lon0, lat0, cell, i, j, azimuths, k=0.13, maxd=math.inf):
    """Horizon elevation angles (rad) of cell (i, j) of a lat/lon DEM (row 0 south, cell
    centres at lon0 + i cell, lat0 + j cell, degrees) by marching constant-azimuth rays on the
    ellipsoid: steps of 1/16 cell, and geometrically shorter ones near the observer (on a
    bilinear patch the angle is often largest as the distance tends to 0); also the points
    where the ray crosses a grid line (kinks of the surface, often peaks along the ray), the
    last of them on the DEM's edge, between the steps around them, and the point at the search
    distance maxd (m)."""
    ny, nx = z.shape
    lat_c = math.radians(lat0 + (ny - 1) / 2 * cell)
    M0, N0 = radii(lat_c)
    out = []
    z0 = z[j, i]
    for phi in azimuths:
        R = 1 / (math.cos(phi) ** 2 / M0 + math.sin(phi) ** 2 / N0)
        c = (1 - k) / (2 * R)
        lat = math.radians(lat0 + j * cell)
        M, N = radii(lat)
        step = 0.0625 * math.radians(cell) * M
        diagonal = math.radians(cell) * M * math.hypot(nx, ny) * 1.5  # beyond any exit
        diagonal = min(diagonal, maxd + 2 * step)
        near = step * 1.5 ** -np.arange(1, 34)
        dists = np.concatenate([near[::-1], step * np.arange(1, int(diagonal / step) + 2)])
        # positions by integrating the rhumb line with the local radii
        dlat = np.diff(np.concatenate([[0.0], dists])) * math.cos(phi)
        lats = lat + np.cumsum(dlat / radii(lat)[0])
        _, Ns = radii(lats)
        lons = math.radians(lon0 + i * cell) + np.cumsum(
            np.diff(np.concatenate([[0.0], dists])) * math.sin(phi) / (Ns * np.cos(lats)))
        ci = (np.degrees(lons) - lon0) / cell
        cj = (np.degrees(lats) - lat0) / cell
        inside = (ci >= 0) & (cj >= 0) & (ci <= nx - 1) & (cj <= ny - 1) & (dists <= maxd)
        stop = np.argmin(inside) if not inside.all() else len(inside)
        if 0 < stop < len(dists) and dists[stop] > maxd:
            # the point at the search distance, if the ray is still on the grid there
            w = (maxd - dists[stop - 1]) / (dists[stop] - dists[stop - 1])
            pi = ci[stop - 1] + w * (ci[stop] - ci[stop - 1])
            pj = cj[stop - 1] + w * (cj[stop] - cj[stop - 1])
            if 0 <= pi <= nx - 1 and 0 <= pj <= ny - 1:
                ci, cj = np.append(ci[:stop], pi), np.append(cj[:stop], pj)
                dists = np.append(dists[:stop], maxd)
                stop += 1
        # grid-line crossings between steps idx and idx + 1 (idx < stop: up to the exit)
        extra = []
        for q in (ci, cj):
            idx = np.nonzero(np.floor(q[:-1]) != np.floor(q[1:]))[0]
            idx = idx[idx < stop]
            line = np.maximum(np.floor(q[idx]), np.floor(q[idx + 1]))
            w = (line - q[idx]) / (q[idx + 1] - q[idx])
            extra.append((idx, w))
        idx = np.concatenate([e[0] for e in extra])
        w = np.concatenate([e[1] for e in extra])
        xi = ci[idx] + w * (ci[idx + 1] - ci[idx])
        xj = cj[idx] + w * (cj[idx + 1] - cj[idx])
        xd = dists[idx] + w * (dists[idx + 1] - dists[idx])
        # a crossing between the last step on the grid and the first off it may lie beyond
        # the edge (a row crossed after the ray left through a column): not on the terrain
        on = ((xi >= -1e-9) & (xj >= -1e-9) & (xi <= nx - 1 + 1e-9) & (xj <= ny - 1 + 1e-9))
        xi, xj, xd = np.clip(xi[on], 0, nx - 1), np.clip(xj[on], 0, ny - 1), xd[on]
        ci, cj = np.concatenate([ci[:stop], xi]), np.concatenate([cj[:stop], xj])
        d = np.concatenate([dists[:stop], xd])
        keep = d <= maxd
        ci, cj, d = ci[keep], cj[keep], d[keep]
        if len(d) == 0:
            out.append(-math.pi / 2)
            continue
        a = np.minimum(ci.astype(int), nx - 2)
        b = np.minimum(cj.astype(int), ny - 2)
        fi, fj = ci - a, cj - b
        h = ((1 - fi) * (1 - fj) * z[b, a] + fi * (1 - fj) * z[b, a + 1]
             + (1 - fi) * fj * z[b + 1, a] + fi * fj * z[b + 1, a + 1])
        out.append(math.atan(np.max((h - z0) / d - c * d)))
    return np.array(out)


class TestSkyVisibility(Testing.vtkTest):
    def testRealDEMAgainstBruteForce(self):
        try:
            path = aperture.default_dem()
        except FileNotFoundError:
            Testing.skip()
        reader = aperture.vtkApertureDEMReader()
        reader.SetFileName(path)
        reader.Update()
        dem = reader.GetOutput()
        nx, ny, _ = dem.GetDimensions()
        z = array(dem, "Elevation").reshape(ny, nx)
        lon0, lat0, _ = dem.GetOrigin()
        cell = dem.GetSpacing()[0]
        # unlimited (the sweep): the bounds; 1500 m (16 to 20 columns of 3 arc-seconds,
        # marched ray by ray): the reference's own surface, so far tighter
        for distance, mae, p99, svf_mae in ((0.0, 0.05, 0.5, 0.002), (1500.0, 0.002, 0.02, 1e-4)):
            self.check_real_dem(reader, z, lon0, lat0, cell, distance, mae, p99, svf_mae)

    def check_real_dem(self, reader, z, lon0, lat0, cell, distance, mae, p99, svf_mae):
        ny, nx = z.shape
        f = sky(reader.GetOutputPort(), ComputeHorizonAngles=True, MaximumDistance=distance)
        D = 32
        h = array(f.GetOutput(), "HorizonAngles").reshape(ny, nx, D)
        svf = array(f.GetOutput(), "SkyViewFactor").reshape(ny, nx)
        rng = np.random.default_rng(7)
        cells = [(int(i), int(j)) for i, j in zip(rng.integers(5, nx - 5, 240),
                                                   rng.integers(5, ny - 5, 240))]
        azimuths = np.arange(D) * 2 * math.pi / D
        errors, svf_errors = [], []
        for i, j in cells:
            ref = brute_force_latlon(z, lon0, lat0, cell, i, j, azimuths,
                                     maxd=distance or math.inf)
            errors.extend(np.degrees(np.abs(h[j, i] - ref)))
            svf_ref = 1 - np.mean(np.sin(np.maximum(ref, 0)))
            svf_errors.append(abs(svf[j, i] - svf_ref))
        errors = np.array(errors)
        print("real DEM, radius %s: %d cell-directions, MAE %.4f deg, p99 %.4f deg, max %.3f "
              "deg; SVF MAE %.5f" % (distance or "unlimited", len(errors), errors.mean(),
                                     np.percentile(errors, 99), errors.max(),
                                     np.mean(svf_errors)))
        self.assertLessEqual(errors.mean(), mae)
        self.assertLessEqual(np.percentile(errors, 99), p99)
        self.assertLessEqual(np.mean(svf_errors), svf_mae)

    def testUTMAndLatLonAgree(self):
        # One analytic terrain on the ground (UTM 32N metres), sampled on a 30 m UTM grid and
        # on a 1 arc-second lat/lon grid over the same area; products compared at the UTM
        # cells' positions (lat/lon products interpolated bilinearly there). The terrain is
        # smooth on the scale of a cell, so the grids differ only in where they sample it.
        def terrain(e, n):
            return (600 * np.exp(-((e - 502000) ** 2 + (n - 5201000) ** 2) / 1.2e6)
                    + 200 * np.sin(e / 900) * np.cos(n / 700) + 500)

        utm = osr.SpatialReference()
        utm.ImportFromEPSG(32632)
        geo = osr.SpatialReference()
        geo.ImportFromEPSG(4326)
        geo.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
        utm.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
        to_utm = osr.CoordinateTransformation(geo, utm)
        to_geo = osr.CoordinateTransformation(utm, geo)

        e0, n0, step, nu = 499000.0, 5198000.0, 30.0, 200
        E, N = np.meshgrid(e0 + step * np.arange(nu), n0 + step * np.arange(nu))
        utm_image = make_image(terrain(E, N), e0, n0, step, step, "EPSG:32632")

        cell = 1.0 / 3600
        lon_a, lat_a, _ = to_geo.TransformPoint(e0 - 200, n0 - 200)
        lon_b, lat_b, _ = to_geo.TransformPoint(e0 + step * nu + 200, n0 + step * nu + 200)
        lons = lon_a + cell * np.arange(int((lon_b - lon_a) / cell))
        lats = lat_a + cell * np.arange(int((lat_b - lat_a) / cell))
        LON, LAT = np.meshgrid(lons, lats)
        pts = np.array(to_utm.TransformPoints(np.column_stack([LON.ravel(), LAT.ravel()])))
        zg = terrain(pts[:, 0], pts[:, 1]).reshape(LON.shape)
        geo_image = make_image(zg, lons[0], lats[0], cell, cell, "EPSG:4326")

        options = dict(MaximumDistance=3000.0)
        a = sky(utm_image, **options).GetOutput()
        b = sky(geo_image, **options).GetOutput()
        # UTM cells well inside both grids, where both searches see 3 km of terrain
        sel = (slice(110, 190, 7), slice(110, 190, 7))
        Es, Ns = E[sel].ravel(), N[sel].ravel()
        ll = np.array(to_geo.TransformPoints(np.column_stack([Es, Ns])))
        gi = (ll[:, 0] - lons[0]) / cell
        gj = (ll[:, 1] - lats[0]) / cell

        def sample(img, name, k=None):
            values = array(img, name)
            nxg = img.GetDimensions()[0]
            if k is not None:
                values = values[:, k]
            grid = values.reshape(-1, nxg)
            i0, j0 = gi.astype(int), gj.astype(int)
            fi, fj = gi - i0, gj - j0
            return ((1 - fi) * (1 - fj) * grid[j0, i0] + fi * (1 - fj) * grid[j0, i0 + 1]
                    + (1 - fi) * fj * grid[j0 + 1, i0] + fi * fj * grid[j0 + 1, i0 + 1])

        nxu = a.GetDimensions()[0]
        for name, tol in (("SkyViewFactor", 0.004), ("DiffuseSkyFactor", 0.003),
                          ("VisibleSolidAngle", 0.03)):
            ua = array(a, name).reshape(-1, nxu)[sel].ravel()
            gb = sample(b, name)
            err = np.abs(ua - gb)
            print("UTM vs lat/lon %s: mean |diff| %.5f, max %.5f" % (name, err.mean(), err.max()))
            self.assertLess(err.mean(), tol, name)
        # Bent normals are East-North-Up on both (the UTM one rotated by the convergence).
        for k, comp in enumerate("EN"):
            ua = array(a, "BentNormal")[:, k].reshape(-1, nxu)[sel].ravel()
            gb = sample(b, "BentNormal", k)
            self.assertLess(np.abs(ua - gb).mean(), 0.005, "BentNormal_" + comp)

    def testThreadsAndPieces(self):
        # 600 m on 25 m cells (24 columns) is marched ray by ray; 2000 m (80 columns) is swept
        self.check_threads_and_piece((90, 110), 600.0, (40, 69, 30, 59))
        self.check_threads_and_piece((250, 250), 2000.0, (100, 129, 100, 129))
        # a piece off the DEM's centre, in a corner region
        self.check_threads_and_piece((250, 250), 2000.0, (30, 59, 170, 199))
        # lat/lon at 45 N, 0.0003 deg (23.6 m east, 33.4 m north), marched and swept: the
        # sweep's lines bend with the cell size, on the whole DEM's lattice of rhumb lines
        # (before that they started from the piece's edge: SVF up to 9e-4 off, mean 2e-6)
        self.check_threads_and_piece((250, 250), 600.0, (30, 59, 170, 199), latlon=True)
        self.check_threads_and_piece((250, 250), 2000.0, (100, 129, 100, 129), latlon=True)
        self.check_threads_and_piece((250, 250), 2000.0, (30, 59, 170, 199), latlon=True)
        # a tall lat/lon DEM (60-63 N, 0.001 deg): the halo's columns come from the rows within
        # the distance of the piece (55.5 m east at its northern edge: 39 columns), not from the
        # DEM's smallest cells far north (50.7 m: 42), which a window of a grid of millions of
        # rows could not measure
        self.check_threads_and_piece((3000, 120), 2000.0, (40, 69, 100, 129), latlon=True,
                                     south=60.0, step=0.001, band_columns=39)

    def testThreadsUsedOnASmallGrid(self):
        # On a small grid VTK's pool runs short ranges in the calling thread too, and the
        # tally of distinct threads said 3 for NumberOfThreads 2 (until 2026-12-06): at most
        # the threads asked for, and the cores.
        z = np.random.default_rng(8).uniform(0, 300, (50, 60)).astype(np.float32)
        image = make_image(z, 400000, 5000000, 30, 30, "EPSG:32633")
        cores = aperture.vtkApertureSkyVisibility.GetUsableCores()
        for threads in (1, 2, 0):
            f = sky(image, NumberOfThreads=threads, MaximumDistance=600.0)
            self.assertGreaterEqual(f.GetNumberOfThreadsUsed(), 1)
            self.assertLessEqual(f.GetNumberOfThreadsUsed(),
                                 min(threads, cores) if threads else cores, threads)

    def check_threads_and_piece(self, shape, distance, piece_extent, latlon=False, south=45.0,
                                step=0.0003, band_columns=None):
        ny, nx = shape
        rng = np.random.default_rng(3)
        z = (np.cumsum(np.cumsum(rng.normal(size=shape), 0), 1) * 3.0).astype(np.float32)
        z[40, 50] = np.nan
        if latlon:
            image = make_image(z, 10.0, south, step, step, "EPSG:4326")
            # the rows' metric cell sizes east and north
            lat = np.radians(south + step * np.arange(ny))
            m, n = radii(lat)
            rows_dx, rows_dy = n * np.cos(lat) * np.radians(step), m * np.radians(step)
        else:
            image = make_image(z, 400000, 5000000, 25, 25, "EPSG:32633")
            rows_dx, rows_dy = np.full(ny, 25.0), np.full(ny, 25.0)
        names = ("SkyViewFactor", "BentNormal", "HorizonAngles", "EdgeTruncated")
        # The thread count is honoured on every update, not only the first in the process
        # (Debian's VTK 9.1 TBB backend ran a second LocalScope(1) on every core).
        counts = (1, 2, 0, 1)
        filters = [sky(image, NumberOfThreads=t, MaximumDistance=distance,
                       ComputeHorizonAngles=True) for t in counts]
        cores = aperture.vtkApertureSkyVisibility.GetUsableCores()  # (affinity, CPU quota)
        self.assertLessEqual(cores, os.cpu_count() or 1)
        self.assertLessEqual(cores, len(os.sched_getaffinity(0)))
        used = [f.GetNumberOfThreadsUsed() for f in filters]
        for t, u in zip(counts, used):
            self.assertGreaterEqual(u, 1)
            self.assertLessEqual(u, min(t, cores) if t else cores, (counts, used))
        if cores > 1:
            self.assertGreater(max(used), 1, used)  # so that the comparison below means something
        runs = [f.GetOutput() for f in filters]
        for name in names:
            for other in runs[1:]:
                np.testing.assert_array_equal(array(runs[0], name), array(other, name))
        self.assertTrue(np.isnan(array(runs[0], "SkyViewFactor")[40 * nx + 50]))
        self.assertTrue(np.isfinite(array(runs[0], "SkyViewFactor")[40 * nx + 49]))
        # A sub-extent (streaming): the filter reads only the region grown by the search
        # distance, and gives exactly the whole run's values there, marched or swept: what
        # depends on the whole DEM (centre, curvature radii, meridian convergence, the sweep's
        # lattice of lines) comes from the whole extent, and every ray sees the same terrain
        # within the distance. (Before the lines were laid on the whole DEM's lattice they
        # started from the piece's edge: up to 0.005 in SVF here.)
        x0, x1, y0, y1 = piece_extent
        f = aperture.vtkApertureSkyVisibility()
        reader_like = aperture.vtkApertureDEMWriter()  # (write the DEM to read it back)
        import tempfile
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "dem.tif")
            reader_like.SetInputData(image)
            reader_like.SetFileName(path)
            reader_like.Write()
            reader = aperture.vtkApertureDEMReader()
            reader.SetFileName(path)
            f.SetInputConnection(reader.GetOutputPort())
            f.SetMaximumDistance(distance)
            none = aperture.vtkApertureSkyVisibility()
            none.AddObserver("ErrorEvent", lambda *_: None)
            self.assertFalse(none.ComputeInputExtent((x0, x1, y0, y1, 0, 0), [0] * 6))
            f.UpdateInformation()
            # the input extent a request reads, asked before anything runs (as the bake plans)
            planned = [0] * 6
            self.assertTrue(f.ComputeInputExtent((x0, x1, y0, y1, 0, 0), planned))
            f.UpdateExtent((x0, x1, y0, y1, 0, 0))
            piece = f.GetOutput()
            read = reader.GetOutput().GetExtent()
        self.assertEqual(piece.GetExtent(), (x0, x1, y0, y1, 0, 0))
        # the halo: the distance over the smallest metric cell sizes east and north of the rows
        # it spans around the piece, and 2 cells more
        hy, band = -1, slice(y0, y1 + 1)
        while True:
            grown = math.ceil(distance / np.min(rows_dy[band])) + 2
            if grown == hy:
                break
            hy, band = grown, slice(max(0, y0 - grown), min(ny - 1, y1 + grown) + 1)
        hx = math.ceil(distance / np.min(rows_dx[band])) + 2
        if band_columns is not None:
            self.assertEqual(hx, band_columns)
            self.assertLess(hx, math.ceil(distance / np.min(rows_dx)) + 2)
        self.assertEqual(read, (max(0, x0 - hx), min(nx - 1, x1 + hx),
                                max(0, y0 - hy), min(ny - 1, y1 + hy), 0, 0))
        self.assertEqual(tuple(planned), read)
        for name in ("SkyViewFactor", "EdgeTruncated", "BentNormal", "DiffuseSkyFactor"):
            whole = array(runs[0], name).reshape(ny, nx, -1)[y0:y1 + 1, x0:x1 + 1]
            got = array(piece, name).reshape(y1 - y0 + 1, x1 - x0 + 1, -1)
            np.testing.assert_array_equal(got, whole, name)

    def testFileUnits(self):
        # AnglesInDegrees and FloatEdgeTruncated (what aperture bake writes): the angles are
        # the radians times 180/pi rounded once to float, EdgeTruncated the same flags as float
        # with NaN on nodata, every other array the same bits; the memory estimate counts the
        # float flags (4 bytes) beside the kernel's byte flags (1).
        z = np.random.default_rng(9).uniform(0, 300, (40, 50))
        z[7, 9] = z[30, 41] = np.nan
        image = make_image(z, 400000, 5000000, 30, 30, "EPSG:32633")
        options = dict(ComputeHorizonAngles=True, NumberOfDirections=12, MaximumDistance=900.0)
        plain = sky(image, **options)
        files = sky(image, AnglesInDegrees=True, FloatEdgeTruncated=True, **options)
        for name in ("ApertureRadius", "PositiveOpenness", "HorizonAngles"):
            radians = array(plain.GetOutput(), name)
            got = array(files.GetOutput(), name)
            np.testing.assert_array_equal(got, np.float32(radians * (180.0 / math.pi)))
            self.assertGreater(np.nanmax(np.abs(got)), 1.0)  # degrees, not radians
        for name in ("VisibleSolidAngle", "BentNormal", "SkyViewFactor", "DiffuseSkyFactor"):
            np.testing.assert_array_equal(array(files.GetOutput(), name),
                                          array(plain.GetOutput(), name))
        flags = files.GetOutput().GetPointData().GetArray("EdgeTruncated")
        self.assertEqual(flags.GetDataTypeAsString(), "float")
        self.assertEqual(plain.GetOutput().GetPointData().GetArray("EdgeTruncated")
                         .GetDataTypeAsString(), "unsigned char")
        got, expected = array(files.GetOutput(), "EdgeTruncated"), array(plain.GetOutput(),
                                                                          "EdgeTruncated")
        nodata = np.isnan(z.ravel())
        self.assertTrue(np.isnan(got[nodata]).all())
        np.testing.assert_array_equal(got[~nodata], expected[~nodata])
        self.assertTrue(0 < expected.sum() < expected.size)  # both flag values occur
        self.assertEqual(files.EstimateBytes(1.0) - plain.EstimateBytes(1.0), 4.0)

    def testPieceRequests(self):
        # UpdatePiece (ParaView's ranks, vtkPStreaming...) becomes a sub-extent of the output,
        # which RequestUpdateExtent grows by the halo: each piece is its block of the whole
        # run, bit for bit, and the pieces cover the DEM. Projected with a radius (UTM; polar
        # stereographic and LAEA Europe with 2 km cells, whose cells take their ground metrics
        # from a lattice over the whole DEM; Web Mercator at 60 N, whose rows have their own
        # cell sizes as lat/lon ones do), and the embedded lat/lon DEM through its reader,
        # unlimited (the whole DEM as the halo).
        z = np.random.default_rng(4).uniform(0, 300, (50, 70))
        projected = make_image(z, 400000, 5000000, 30, 30, "EPSG:32633")
        polar = make_image(z, 300000, -2500000, 2000, 2000, "EPSG:3413")
        laea = make_image(z, 5300000, 4700000, 2000, 2000, "EPSG:3035")
        mercator = make_image(z, 1000000, 8400000, 60, 60, "EPSG:3857")
        reader = aperture.vtkApertureDEMReader()
        try:
            reader.SetFileName(aperture.default_dem())
        except FileNotFoundError:
            reader = None
        cases = [(projected, 600.0, 4), (projected, 600.0, 7), (polar, 12000.0, 5),
                 (laea, 12000.0, 6), (mercator, 600.0, 5)]
        if reader:
            cases.append((reader.GetOutputPort(), 0.0, 3))
        for source, distance, pieces in cases:
            whole = sky(source, MaximumDistance=distance)
            nx, ny, _ = whole.GetOutput().GetDimensions()
            expected = {name: array(whole.GetOutput(), name).reshape(ny, nx, -1)
                        for name in ("SkyViewFactor", "BentNormal", "EdgeTruncated")}
            covered = np.zeros((ny, nx), dtype=bool)
            for piece in range(pieces):
                f = aperture.vtkApertureSkyVisibility()
                if isinstance(source, vtkImageData):
                    f.SetInputData(source)
                else:
                    f.SetInputConnection(source)
                f.SetMaximumDistance(distance)
                f.UpdatePiece(piece, pieces, 0)
                e = f.GetOutput().GetExtent()
                self.assertLess((e[1] - e[0] + 1) * (e[3] - e[2] + 1), nx * ny)
                for name, values in expected.items():
                    got = array(f.GetOutput(), name).reshape(e[3] - e[2] + 1, e[1] - e[0] + 1, -1)
                    np.testing.assert_array_equal(got, values[e[2]:e[3] + 1, e[0]:e[1] + 1])
                covered[e[2]:e[3] + 1, e[0]:e[1] + 1] = True
            self.assertTrue(covered.all())

    def testPiecesOfNodata(self):
        # A piece whose input (its extent and halo) has no data, a stretch of sea, gets nodata
        # products, bit for bit the whole run's there (NaN; EdgeTruncated 0 as bytes, NaN as
        # float), and InputAllNodata says so; before 2026-12-05 it failed the update ("every
        # cell of the DEM is nodata"), which broke a coastal DEM's streaming. Only an input of
        # the whole DEM with no data is an error. Data in the northern 20 of 60 rows; 300 m of
        # 30 m cells: a halo of 12 rows, so rows 0..20 read rows 0..32, all nodata. (Through
        # the reader: the halo needs the CRS before data flows.)
        import tempfile
        from aperture.errors import Watcher
        z = np.random.default_rng(8).uniform(0, 300, (60, 70))
        z[:40] = np.nan
        names = ("VisibleSolidAngle", "ApertureRadius", "BentNormal", "SkyViewFactor",
                 "DiffuseSkyFactor", "PositiveOpenness", "EdgeTruncated", "HorizonAngles")

        def dem(z, path):
            writer = aperture.vtkApertureDEMWriter()
            writer.SetInputData(make_image(z, 400000, 5000000, 30, 30, "EPSG:32633"))
            writer.SetFileName(path)
            self.assertEqual(writer.Write(), 1)
            return path

        def run(path, extent, distance=300.0, floats=False):
            # (path: a file, read; or an image given whole with SetInputData)
            w = Watcher()
            f = w.watch(aperture.vtkApertureSkyVisibility())
            w.watch(f.GetExecutive())
            if isinstance(path, vtkImageData):
                f.SetInputData(path)
            else:
                reader = w.watch(aperture.vtkApertureDEMReader())
                w.watch(reader.GetExecutive())
                reader.SetFileName(path)
                f.SetInputConnection(reader.GetOutputPort())
            f.SetMaximumDistance(distance)
            f.SetFloatEdgeTruncated(floats)
            f.ComputeHorizonAnglesOn()
            f.UpdateInformation()
            f.UpdateExtent(extent)
            data = {name: vtk_to_numpy(f.GetOutput().GetPointData().GetArray(name)).copy()
                    for name in names} if not w.errors else None
            return data, f.GetInputAllNodata(), w.errors

        with tempfile.TemporaryDirectory() as tmp:
            coast = dem(z, os.path.join(tmp, "coast.tif"))
            # (given whole, the image's data outside a piece's halo does not count: until
            # 2026-12-06 InputAllNodata said False there, the products all nodata)
            image = make_image(z, 400000, 5000000, 30, 30, "EPSG:32633")
            for floats, coast in ((False, coast), (True, coast), (False, image)):
                whole, nodata, errors = run(coast, (0, 69, 0, 59, 0, 0), floats=floats)
                self.assertEqual((nodata, errors), (False, []))
                # (rows 30-38: nodata, their halo of 12 rows not: the halo decides)
                for extent, expected in (((0, 69, 0, 20, 0, 0), True),
                                         ((0, 69, 21, 40, 0, 0), False),
                                         ((0, 69, 30, 38, 0, 0), False),
                                         ((5, 30, 3, 15, 0, 0), True)):
                    got, nodata, errors = run(coast, extent, floats=floats)
                    self.assertEqual((nodata, errors), (expected, []), extent)
                    i0, i1, j0, j1 = extent[:4]
                    for name in names:
                        values = whole[name].reshape(60, 70, -1)[j0:j1 + 1, i0:i1 + 1]
                        # every bit, NaN's too (the EXR writer copies them)
                        self.assertEqual(got[name].tobytes(), values.tobytes(), (name, extent))
                edge = got["EdgeTruncated"]
                self.assertTrue(np.isnan(edge).all() if floats else (edge == 0).all())
                self.assertTrue(np.isnan(got["HorizonAngles"]).all())
            # no data at all: a piece with a radius cannot know it (nodata, no error); the
            # whole DEM, or a piece without a radius (its halo: the whole DEM), is an error
            void = dem(np.full((60, 70), np.nan), os.path.join(tmp, "void.tif"))
            _, nodata, errors = run(void, (0, 69, 0, 20, 0, 0))
            self.assertEqual((nodata, errors), (True, []))
            for extent, distance in (((0, 69, 0, 59, 0, 0), 300.0), ((0, 69, 0, 20, 0, 0), 0.0)):
                _, nodata, errors = run(void, extent, distance)
                self.assertFalse(nodata)
                self.assertIn("band 1 is nodata", errors[0])  # (the reader's, reading it all)
        # the sky filter's own refusal of a whole DEM of nodata: testErrors

    def testEmptyRequest(self):
        # An empty update extent (max < min: VTK's request for nothing) gives an empty output
        # and reads nothing; it used to copy a block of negative width (a crash) once the halo
        # had grown the input's request into a real region.
        from aperture.errors import Watcher
        z = np.add.outer(np.arange(50.0), np.arange(60.0)).astype(np.float32)
        image = make_image(z, 400000, 5000000, 30, 30, "EPSG:32633")
        for source in ("reader", image):
            for distance in (2000.0, 0.0):
                reader = aperture.vtkApertureDEMReader()
                reader.SetFileName(aperture.default_dem())
                w = Watcher()
                f = w.watch(aperture.vtkApertureSkyVisibility())
                w.watch(f.GetExecutive())
                if source == "reader":
                    f.SetInputConnection(reader.GetOutputPort())
                else:
                    f.SetInputData(image)
                f.SetMaximumDistance(distance)
                f.UpdateInformation()
                f.UpdateExtent((10, 5, 0, 10, 0, 0))
                self.assertEqual(w.errors, [])
                self.assertEqual(f.GetOutput().GetNumberOfPoints(), 0)
                if source == "reader":
                    self.assertEqual(reader.GetOutput().GetNumberOfPoints(), 0)
                f.UpdateExtent((3, 4, 5, 5, 0, 0))  # and the next request is served
                self.assertEqual(f.GetOutput().GetExtent(), (3, 4, 5, 5, 0, 0))
                self.assertTrue(np.all(np.isfinite(array(f.GetOutput(), "SkyViewFactor"))))

    def testProgressEvents(self):
        # VTK's contract: StartEvent, ProgressEvents rising from 0 to 1, EndEvent.
        z = np.add.outer(np.arange(60.0), np.arange(70.0)).astype(np.float32)
        f = aperture.vtkApertureSkyVisibility()
        f.SetInputData(make_image(z, 400000, 5000000, 30, 30, "EPSG:32633"))
        events = []
        for name in ("StartEvent", "ProgressEvent", "EndEvent"):
            f.AddObserver(name, lambda o, e: events.append((e, o.GetProgress())))
        f.Update()
        self.assertEqual(events[0][0], "StartEvent")
        self.assertEqual(events[-1][0], "EndEvent")
        progress = [p for e, p in events if e == "ProgressEvent"]
        self.assertGreaterEqual(len(progress), 10)
        self.assertEqual(progress, sorted(progress))
        self.assertEqual(progress[-1], 1.0)
        # The serial set-up (seconds on a DEM of 10^8 cells, before the first sector reports)
        # reports progress 0 at three checkpoints and stops at any of them when aborted there:
        # no sector runs, the output stays empty (the update fails, as for any abort).
        from aperture.errors import Watcher
        for stop in range(2, 5):
            w = Watcher()
            g = w.watch(aperture.vtkApertureSkyVisibility())
            w.watch(g.GetExecutive())
            g.SetInputData(make_image(z, 400000, 5000000, 30, 30, "EPSG:32633"))
            seen = []

            def abort_at(o, e, stop=stop, seen=seen):
                seen.append(o.GetProgress())
                if len(seen) == stop:
                    o.SetAbortExecute(1)
            g.AddObserver("ProgressEvent", abort_at)
            g.Update()
            self.assertEqual(seen, [0.0] * stop, stop)  # (the first is the executive's)
            self.assertEqual(g.GetOutput().GetNumberOfPoints(), 0)
            self.assertEqual(len(w.errors), 1, w.errors)  # (the executive's, no error of ours)
            self.assertIn("returned failure for request", w.errors[0])

    def testProgressWithinSectors(self):
        # A DEM of more than 8 Mi cells runs each sector's three phases in slices, reporting
        # progress and checking AbortExecute after each slice but the sector's last: here 2
        # slices, so 5 events inside each of the 4 sectors, 1 at its end ((d + 1) / 5: the
        # sectors take 4 fifths, the end the last fifth), then 2 in the end (after the sums'
        # finish, 0.9, and after the bent normals' rotation, 0.98) before the executive's 1;
        # rising, on 1 thread (the calling one) and on 2. An abort set at the first event
        # inside the first sector, or at the end's first, stops there: no further progress,
        # and no error of the filter's own (the executive reports the aborted update's
        # failure). (A sector of a 10000^2 DEM takes seconds, its end about as long.)
        from aperture.errors import Watcher
        ny, nx = 2050, 4100
        y, x = np.mgrid[0:ny, 0:nx].astype(np.float32)
        z = 300.0 + 40.0 * np.sin(x / 37.0) * np.cos(y / 23.0)
        image = make_image(z, 400000, 5000000, 30, 30, "EPSG:32633")
        del x, y, z
        ends = [(d + 1) / 5 for d in range(4)]
        finish, rotated = (4 + 0.5) / 5, (4 + 0.9) / 5
        for threads in (1, 2):
            for abort in (None, "sector", "end"):
                w = Watcher()
                f = w.watch(aperture.vtkApertureSkyVisibility())
                w.watch(f.GetExecutive())
                f.SetInputData(image)
                f.SetNumberOfThreads(threads)
                f.SetNumberOfDirections(4)
                f.SetMaximumDistance(300.0)
                for name in ("VisibleSolidAngle", "ApertureRadius", "BentNormal",
                             "DiffuseSkyFactor", "PositiveOpenness", "EdgeTruncated"):
                    getattr(f, "SetCompute" + name)(False)
                progress = []

                def note(o, e, abort=abort, progress=progress):
                    progress.append(o.GetProgress())
                    if (abort == "sector" and 0.0 < progress[-1] < ends[0]) or \
                            (abort == "end" and progress[-1] == finish):
                        o.SetAbortExecute(1)
                f.AddObserver("ProgressEvent", note)
                f.Update()
                label = "threads %d, abort %s: %s" % (threads, abort, progress)
                self.assertEqual(progress, sorted(progress), label)
                inside = [p for p in progress if 0.0 < p < ends[-1] and p not in ends]
                if abort:
                    self.assertTrue(w.errors, label)
                    for message in w.errors:
                        self.assertIn("vtkApertureSkyVisibility", message)
                        self.assertIn("returned failure for request", message)
                    if abort == "sector":
                        self.assertEqual(len(inside), 1, label)
                        self.assertEqual(max(progress), inside[0], label)
                    else:
                        self.assertEqual(len(inside), 20, label)
                        self.assertEqual(max(progress), finish, label)
                    continue
                self.assertEqual(w.errors, [], label)
                self.assertEqual(len(inside), 20, label)
                for d in range(4):
                    self.assertEqual(sum(d / 5 < p < (d + 1) / 5 for p in inside), 5, label)
                    self.assertIn(ends[d], progress, label)
                self.assertEqual([p for p in progress if p > ends[-1]], [finish, rotated, 1.0],
                                 label)
                svf = array(f.GetOutput(), "SkyViewFactor")
                self.assertEqual(svf.size, nx * ny)
                if threads == 1:
                    first = svf
                else:
                    self.assertTrue(np.array_equal(first, svf, equal_nan=True))

    def testErrors(self):
        image = make_image(np.ones((10, 10)), 0, 0, 30, 30, "EPSG:32633")
        cases = [(dict(NumberOfDirections=3), "NumberOfDirections must be within 4..360"),
                 (dict(NumberOfDirections=361), "NumberOfDirections must be within 4..360"),
                 (dict(MaximumDistance=-1.0), "MaximumDistance must be"),
                 (dict(RefractionCoefficient=1.0), "RefractionCoefficient must be within")]
        for options, message in cases:
            self.assertIn(message, self.error(image, **options))
        self.assertIn("no metric cell size",
                      self.error(make_image(np.ones((5, 5)), 0, 0, 1, 1, None)))
        self.assertIn("every cell of the DEM is nodata",
                      self.error(make_image(np.full((5, 5), np.nan), 0, 0, 30, 30, "EPSG:32633")))
        self.assertIn("at least 2 x 2",
                      self.error(make_image(np.ones((1, 5)), 0, 0, 30, 30, "EPSG:32633")))

    def testGridWiderThanTheEarth(self):
        # A gridline-registered global grid (361 columns of 1 degree: -180 and 180 both) is
        # refused in RequestUpdateExtent, before its reader reads a cell (a 20 GB ETOPO grid
        # was read whole first until 2026-12-07), and for a sub-extent with why it is refused
        # too; an image without the CRS in the pipeline information, in RequestData. So is a
        # grid beyond a pole (read whole, then refused, until later that day).
        import tempfile
        from osgeo import gdal
        from aperture.errors import Watcher
        z = np.full((181, 361), 100.0, np.float32)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "gridline.tif")
            ds = gdal.GetDriverByName("GTiff").Create(path, 361, 181, 1, gdal.GDT_Float32)
            ds.SetGeoTransform((-180.5, 1, 0, 90.5, 0, -1))
            ds.SetProjection(osr.SRS_WKT_WGS84_LAT_LONG)
            ds.GetRasterBand(1).WriteArray(z)
            ds = None
            # (a whole grid of 0.5-degree cells whose cell centres reach the poles: its
            # outer rows reach a quarter of a degree beyond them)
            polar = os.path.join(tmp, "polar.tif")
            ds = gdal.GetDriverByName("GTiff").Create(polar, 720, 361, 1, gdal.GDT_Float32)
            ds.SetGeoTransform((-180, 0.5, 0, 90.25, 0, -0.5))
            ds.SetProjection(osr.SRS_WKT_WGS84_LAT_LONG)
            ds.GetRasterBand(1).WriteArray(np.full((361, 720), 100.0, np.float32))
            ds = None
            for extent, (dem, words) in itertools.product(
                    (None, (10, 59, 10, 59, 0, 0)),
                    ((path, ["the grid spans 361 degrees of longitude",
                             "(a gridline-registered global grid)"]),
                     (polar, ["the row of cells at y = -90 (grid row 0, counted from the south)"
                              " reaches latitude -90.25, beyond the pole"]))):
                w = Watcher()
                reader = aperture.vtkApertureDEMReader()
                reader.SetFileName(dem)
                f = w.watch(aperture.vtkApertureSkyVisibility())
                w.watch(f.GetExecutive())
                f.SetInputConnection(reader.GetOutputPort())
                f.SetMaximumDistance(300000.0)
                if extent:
                    f.UpdateExtent(extent)
                else:
                    f.Update()
                self.assertTrue(w.errors, extent)
                self.assertTrue(w.errors[0].startswith("no metric cell size: " + words[0]),
                                w.errors[0])
                self.assertIn(words[-1], w.errors[0])
                piece = "; that is the whole grid's: a sub-extent's cells are measured on the " \
                        "whole grid, so that sub-extents tile it"
                self.assertEqual(piece in w.errors[0], extent is not None, w.errors[0])
                self.assertEqual(reader.GetOutput().GetNumberOfPoints(), 0, extent)
                # (planning an update refuses it as well, with the same words)
                self.assertFalse(f.ComputeInputExtent(extent or (0, 359, 0, 180, 0, 0),
                                                      [0] * 6))
                self.assertTrue(w.errors[-1].startswith("no metric cell size: " + words[0]))
            # (a local CRS has no longitudes: not refused, as it was for an hour of 2026-12-07)
            path = os.path.join(tmp, "site.tif")
            ds = gdal.GetDriverByName("GTiff").Create(path, 30, 20, 1, gdal.GDT_Float32)
            ds.SetGeoTransform((1000, 2, 0, 5000, 0, -2))
            ds.SetProjection('LOCAL_CS["grid",UNIT["metre",1]]')
            ds.GetRasterBand(1).WriteArray(z[:20, :30])
            ds = None
            w = Watcher()
            reader = aperture.vtkApertureDEMReader()
            reader.SetFileName(path)
            f = w.watch(aperture.vtkApertureSkyVisibility())
            f.SetInputConnection(reader.GetOutputPort())
            f.UpdateExtent((5, 20, 5, 15, 0, 0))
            self.assertEqual(w.errors, [])
            self.assertTrue((array(f.GetOutput(), "SkyViewFactor") > 0.99).all())
        image = make_image(z, -180.5, -90.5, 1.0, 1.0, "EPSG:4326")
        self.assertIn("(a gridline-registered global grid)", self.error(image))
        self.assertIn("; that is the whole grid's",
                      self.error(image, UpdateExtent=(10, 59, 10, 59, 0, 0)))

    def testNonFiniteAndImplausibleElevations(self):
        # Infinities are nodata, as the reader makes them: the same products bit for bit as
        # with NaN there (NaN at the cell, transparent to its neighbours).
        from aperture.errors import Watcher
        rng = np.random.default_rng(5)
        z = rng.uniform(200.0, 400.0, (30, 40))

        def run(values, cell=30, crs="EPSG:32633"):
            w = Watcher()
            f = w.watch(aperture.vtkApertureSkyVisibility())
            f.SetInputData(make_image(values, 400000, 5000000, cell, cell, crs))
            f.Update()
            self.assertEqual(w.errors, [])
            return {name: array(f.GetOutput(), name) for name in
                    ("SkyViewFactor", "VisibleSolidAngle", "BentNormal")}, w.warnings

        holes = z.copy()
        holes[12, 17] = holes[3, 0] = np.nan
        expected, warnings = run(holes)
        self.assertEqual(warnings, [])
        self.assertTrue(np.isnan(expected["SkyViewFactor"][12 * 40 + 17]))
        for big in (np.inf, -np.inf):
            infinite = z.copy()
            infinite[12, 17], infinite[3, 0] = big, -big
            got, warnings = run(infinite)
            self.assertEqual(warnings, [])
            for name in expected:
                np.testing.assert_array_equal(got[name], expected[name], err_msg=name)
        # Finite but beyond any elevation on Earth: computed, with a warning naming the range
        # (an undeclared nodata value of -32768; 1e30 m).
        for fill, text in ((-32768.0, "elevations range from -32768 to "),
                           (1e30, "elevations range from ")):
            odd = z.copy()
            odd[12, 17] = fill
            got, warnings = run(odd)
            self.assertEqual(len(warnings), 1, warnings)
            self.assertIn(text, warnings[0])
            self.assertIn("beyond any on Earth (-11100 to 9000 m)", warnings[0])
            self.assertFalse(np.isnan(got["SkyViewFactor"][12 * 40 + 17]))
        # the highest and lowest places on Earth are not warned about (on a grid of 40 x 30
        # cells of 100 m, 4 km wide)
        _, warnings = run(np.where(z > 300.0, 8848.9, -10935.0), cell=100)
        self.assertEqual(warnings, [])
        # A relief over ten times the grid's larger side is no terrain: degrees taken for
        # metres (3 arc-second cells in a CRS in metres); 40 x 30 cells of 1 m (a 40 m grid):
        # 400 m of relief passes, 401 m is warned about.
        _, warnings = run(z, cell=1 / 1200.0)
        self.assertEqual(len(warnings), 1, warnings)
        self.assertTrue(warnings[0].startswith("elevations range over "), warnings[0])
        self.assertIn("steeper than any terrain: a CRS whose unit does not fit the grid's "
                      "coordinates (degrees taken for metres?), or heights not in metres? Sky "
                      "products computed from them are meaningless", warnings[0])
        local = 'LOCAL_CS["grid",UNIT["metre",1]]'
        for relief, count in ((400.0, 0), (401.0, 1)):
            _, warnings = run(np.where(z > 300.0, relief, 0.0), cell=1, crs=local)
            self.assertEqual(len(warnings), count, (relief, warnings))
        self.assertEqual(warnings[0], "elevations range over 401 m on a grid of 40 x 30 m "
                         "(cells of 1 x 1 m), steeper than any terrain: a CRS whose unit does "
                         "not fit the grid's coordinates (degrees taken for metres?), or heights "
                         "not in metres? Sky products computed from them are meaningless")
        # Elevations of other array types (a VTK pipeline's, not the reader's float32): the
        # same products as their values as float32; doubles beyond the float range are nodata.
        whole = np.round(z)
        expected, _ = run(whole)
        for dtype in (np.float64, np.int16, np.int32, np.uint16):
            f = sky(make_image(whole, 400000, 5000000, 30, 30, "EPSG:32633", dtype))
            for name in expected:
                np.testing.assert_array_equal(array(f.GetOutput(), name), expected[name],
                                              err_msg="%s %s" % (dtype.__name__, name))
        beyond = z.astype(np.float64)
        beyond[12, 17], beyond[3, 0] = 1e300, -np.inf
        f = sky(make_image(beyond, 400000, 5000000, 30, 30, "EPSG:32633", np.float64))
        expected, _ = run(holes)
        for name in expected:
            np.testing.assert_array_equal(array(f.GetOutput(), name), expected[name],
                                          err_msg="beyond float " + name)

    def testProjectionScaleChangesPerCell(self):
        # A projection's scale changes across a large DEM (7% over north polar stereographic
        # from 60 to 88 N, true scale at 70 N; 1.5% over LAEA Europe from 52 to 72 N, not
        # conformal): each cell's ground distances come from its own scale, not the centre's.
        # Flat ground with one-cell towers 100 m high, 3 cells north of an observer on the
        # projection's central meridian (ground distance: the meridian arc between their
        # latitudes) and 2 cells east of one (straddling the meridian, at one latitude: the
        # parallel's arc N cos(lat) dlon); each observer's horizon towards its tower is
        # atan(100 / distance), read from PositiveOpenness, the mean of 90 degrees less the
        # horizon over the 4 sectors, of which the other 3 are flat: it holds the sector's own
        # ray, where HorizonAngles are interpolated to true azimuths (the convergence
        # changes by 0.02 degree from the meridian to the next column at 60 N, a 2e-4 part of
        # a 90-degree sector). With the centre's cell size for every cell the tangents were
        # off by up to 4.6% (polar, at 60 N); now by the scale's change along the 2-3 km to
        # the tower (7e-5 measured there).
        from aperture.errors import Watcher
        cell, H, nx = 1000.0, 100.0, 9
        wgs84 = osr.SpatialReference()
        wgs84.ImportFromEPSG(4326)
        wgs84.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)

        for epsg, lon0, south, north in ((3413, -45.0, 60.0, 88.0), (3035, 10.0, 52.0, 72.0)):
            crs = osr.SpatialReference()
            crs.ImportFromEPSG(epsg)
            crs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
            to_crs = osr.CoordinateTransformation(wgs84, crs)
            to_geo = osr.CoordinateTransformation(crs, wgs84)
            a, b = to_crs.TransformPoint(lon0, south), to_crs.TransformPoint(lon0, north)
            self.assertLess(abs(a[0] - b[0]), 1e-6)  # (the meridian is a grid column)
            y0 = min(a[1], b[1])
            ny = int(abs(b[1] - a[1]) / cell)
            x0 = a[0] - 4 * cell  # (column 4 on the meridian)
            z = np.zeros((ny, nx))
            to_north = list(range(40, ny - 10, 300))
            to_east = list(range(190, ny - 10, 300))
            for j in to_north:
                z[j + 3, 4] = H
            for j in to_east:
                z[j, 5] = H
            w = Watcher()
            f = w.watch(aperture.vtkApertureSkyVisibility())
            f.SetInputData(make_image(z, x0, y0, cell, cell, "EPSG:%d" % epsg))
            f.SetEarthCurvature(False)
            f.SetNumberOfDirections(4)
            f.SetMaximumDistance(20000.0)
            f.Update()
            self.assertEqual(w.errors, [])
            openness = array(f.GetOutput(), "PositiveOpenness").reshape(ny, nx)
            h = 4 * (math.pi / 2 - openness)  # (the tower's sector)
            lat = lambda i, j: to_geo.TransformPoint(x0 + i * cell, y0 + j * cell)[:2]
            for j in to_north:
                la, lb = math.radians(lat(4, j)[1]), math.radians(lat(4, j + 3)[1])
                err = math.tan(h[j, 4]) * abs(float(meridian_arc(la, lb))) / H - 1
                self.assertLess(abs(err), 1.5e-4, "EPSG:%d row %d: %.2e" % (epsg, j, err))
            for j in to_east:
                (ea, la), (eb, lb) = lat(3, j), lat(5, j)
                self.assertAlmostEqual(la, lb, delta=1e-9)
                distance = radii(math.radians(la))[1] * math.cos(math.radians(la)) * \
                    math.radians(abs(eb - ea))
                err = math.tan(h[j, 3]) * distance / H - 1
                self.assertLess(abs(err), 1.5e-4, "EPSG:%d row %d: %.2e" % (epsg, j, err))
            self.assertEqual(w.warnings, [])
            if epsg == 3413:
                continue
            # LAEA is not conformal: it turns directions by up to 0.67 degree over the
            # filter's lattice (33 nodes up the meridian), here from the local radii and
            # PROJ's coordinates of each node's cell: the ground steps' lengths sx, sy relative
            # to the centre row's turn a direction by asin(|sx - sy| / (sx + sy)). The sectors
            # follow that (their weights and azimuths), so it is not warned about (it was,
            # before they did); on the central meridian the axis sectors keep their weight.
            def steps(j):
                out = []
                for di, dj in ((0.5, 0.0), (0.0, 0.5)):
                    (e0, n0), (e1, n1) = lat(4 - di, j - dj), lat(4 + di, j + dj)
                    m, n = radii(math.radians(0.5 * (n0 + n1)))
                    out.append(math.hypot(n * math.cos(math.radians(0.5 * (n0 + n1))) *
                                          math.radians(e1 - e0), m * math.radians(n1 - n0)))
                return np.array(out)

            centre = steps(ny // 2)
            turn = max(math.degrees(math.asin(abs(s[0] - s[1]) / (s[0] + s[1])))
                       for s in (steps((ny - 1) * k / 32.0) / centre for k in range(33)))
            self.assertAlmostEqual(turn, 0.671, delta=0.001)

    def testHorizonAnglesAtTrueAzimuths(self):
        # A projected DEM's sweep runs at the centre's grid azimuths, so at a cell where the
        # meridian convergence differs by dg its sector d looks at true azimuth phi_d + dg:
        # 9 degrees at the ends of a strip 700 km long across 70 N in polar stereographic
        # (EPSG:3413, the convergence is the longitude's difference). HorizonAngles hold the
        # horizon at phi_d itself, linear between the two sectors either side. The terrain is
        # a ground plane rising S to the north (z = tan S * meridian arc), whose horizon in
        # true azimuth a is atan(tan S cos a) everywhere (flat Earth): the interpolation
        # leaves 0.003 degree of it (tan S (pi/16)^2 / 8), the rays' crossing of curved
        # parallels 0.001; without it the ends' horizons were 0.11 degree off.
        S, D, cell, nx, ny = math.radians(0.7), 32, 1000.0, 701, 21
        expected = np.arctan(np.tan(S) * np.cos(2 * np.pi * np.arange(D) / D))
        wgs84 = osr.SpatialReference()
        wgs84.ImportFromEPSG(4326)
        wgs84.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
        polar = osr.SpatialReference()
        polar.ImportFromEPSG(3413)
        polar.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
        to_polar = osr.CoordinateTransformation(wgs84, polar)
        to_geo = osr.CoordinateTransformation(polar, wgs84)
        x0, y0 = to_polar.TransformPoint(-45.0, 70.0)[:2]
        x0 -= cell * (nx // 2)
        y0 -= cell * (ny // 2)
        lat = np.radians([[to_geo.TransformPoint(x0 + i * cell, y0 + j * cell)[1]
                           for i in range(nx)] for j in range(ny)])
        z = np.tan(S) * meridian_arc(math.radians(65), lat)
        out = flat_earth_products(self, z, x0, y0, cell, "EPSG:3413", D)
        h = array(out, "HorizonAngles").reshape(ny, nx, D)
        for i in (10, nx // 2, nx - 11):
            lon = to_geo.TransformPoint(x0 + i * cell, y0 + 10 * cell)[0]
            err = np.degrees(np.abs(h[10, i] - expected)).max()
            self.assertLess(err, 0.006, "at %.1f E: %.4f deg" % (lon, err))
            if i != nx // 2:
                self.assertGreater(abs(lon + 45.0), 8.5)  # (the convergence's change)

    def testNamesInAnyLocale(self):
        # A program whose LC_NUMERIC writes decimal commas (a Qt host, or setlocale in
        # Python) still gets HorizonAngles components "az011.25", which become GeoTIFF band
        # descriptions and EXR channels; until 2026-12-07 printf made them "az011,25", and
        # the solar position's messages "5000,5". The locale is compiled into a folder of
        # the test's own (LOCPATH) from Debian's `locales` sources: no system change.
        import shutil
        import subprocess
        import tempfile
        localedef = shutil.which("localedef")
        if not localedef or not os.path.exists("/usr/share/i18n/locales/de_DE"):
            self.skipTest("no localedef or no de_DE locale source (Debian package locales)")
        with tempfile.TemporaryDirectory() as folder:
            made = subprocess.run([localedef, "-i", "de_DE", "-f", "UTF-8",
                                   os.path.join(folder, "de_DE.UTF-8")],
                                  capture_output=True, text=True)
            self.assertTrue(os.path.isdir(os.path.join(folder, "de_DE.UTF-8")), made.stderr)
            script = """
import locale
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import vtkImageData
import aperture
locale.setlocale(locale.LC_ALL, "")
assert "%.2f" % 1.5 == "1.50" and locale.format_string("%.2f", 1.5) == "1,50"
image = vtkImageData()
image.SetDimensions(4, 3, 1)
image.SetSpacing(30, 30, 1)
values = numpy_to_vtk(np.arange(12, dtype=np.float32), deep=1)
values.SetName("Elevation")
image.GetPointData().SetScalars(values)
geo = aperture.vtkApertureGeoreference()
assert geo.SetCRS("EPSG:32633")
geo.AttachToImage(image)
f = aperture.vtkApertureSkyVisibility()
f.SetInputData(image)
f.SetNumberOfDirections(32)
f.ComputeHorizonAnglesOn()
f.Update()
h = f.GetOutput().GetPointData().GetArray("HorizonAngles")
print(" ".join(h.GetComponentName(d) for d in (0, 1, 31)))
sun = aperture.vtkApertureSolarPosition()
sun.GlobalWarningDisplayOff()
sun.SetTime("2026-06-21T12:00Z")
sun.SetPressure(5000.5)
print(sun.Compute(), sun.GetErrorMessage())
"""
            env = dict(os.environ, LOCPATH=folder, LC_ALL="de_DE.UTF-8")
            p = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                               env=env, timeout=120)
        self.assertEqual(p.returncode, 0, p.stderr[-2000:])
        names, message = p.stdout.splitlines()[:2]
        self.assertEqual(names, "az000.00 az011.25 az348.75")
        self.assertEqual(message, "False the pressure 5000.5 hPa is outside 0..5000 hPa")

    def testSectorsOfProjectionsNotConformal(self):
        # A projection that is not conformal shears the grid: the sweep's sectors, even in
        # grid azimuth, lie unevenly on the ground (sinusoidal at 45 N, 15 E: a cell's steps
        # along the row and the column meet at 79.5 degrees on the ground, and directions turn
        # by up to 5.4 degrees). The sectors' sums are weighted by their share of the ground's
        # directions, the bent normal follows their ground directions and HorizonAngles are
        # interpolated from their ground azimuths. The terrain is a plane rising S to grid
        # azimuth a0 of an azimuthal equidistant projection about the DEM's centre (z linear in
        # its coordinates; flat Earth), so to true azimuth a1 = a0 + that projection's
        # meridian convergence at a cell (0.15 degree at the corners): there its horizon in
        # azimuth a is atan(tan S cos(a - a1)), its SkyViewFactor 1 - S / pi, its visible
        # solid angle 2 pi - 2 S, its bent normal points down the slope (a1 + 180) and its
        # DiffuseSkyFactor is the Dozier-Frew integral over the sky above the plane and the
        # horizontal, by a fine quadrature here. Before, the sectors' uneven shares left
        # SkyViewFactor 0.0026 off, the visible solid angle 0.016 sr, bent normals 7.0
        # degrees and horizons 1.8 degrees (now 2.6e-5, 1.6e-4 sr, 0.03 and 0.011 degree; the
        # bent normal's 0.008 at D = 256).
        S, a0, D, cell, n = math.radians(10.0), math.radians(30.0), 64, 500.0, 61
        sinu = "+proj=sinu +lon_0=0 +datum=WGS84 +units=m +no_defs"
        local = "+proj=aeqd +lat_0=45 +lon_0=15 +datum=WGS84 +units=m +no_defs"
        wgs84 = osr.SpatialReference()
        wgs84.ImportFromEPSG(4326)
        wgs84.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
        crs = osr.SpatialReference()
        crs.SetFromUserInput(sinu)
        ground = osr.SpatialReference()
        ground.SetFromUserInput(local)
        xc, yc = osr.CoordinateTransformation(wgs84, crs).TransformPoint(15.0, 45.0)[:2]
        x0, y0 = xc - cell * (n // 2), yc - cell * (n // 2)
        to_ground = osr.CoordinateTransformation(crs, ground)
        en = np.array([[to_ground.TransformPoint(x0 + i * cell, y0 + j * cell)[:2]
                        for i in range(n)] for j in range(n)])
        # (the steps' ground angle at the centre)
        east, north = en[30, 31] - en[30, 30], en[31, 30] - en[30, 30]
        angle = math.degrees(math.acos(east @ north / np.hypot(*east) / np.hypot(*north)))
        self.assertAlmostEqual(angle, 79.5, delta=0.1)
        t = math.tan(S)
        z = t * (en[..., 0] * math.sin(a0) + en[..., 1] * math.cos(a0))
        inner = (slice(10, n - 10), slice(10, n - 10))  # (every ray finds the plane)
        to_geo = osr.CoordinateTransformation(crs, wgs84)
        to_local = osr.CoordinateTransformation(wgs84, ground)
        a1 = np.empty((n, n))
        for j in range(10, n - 10):
            for i in range(10, n - 10):
                lon, lat = to_geo.TransformPoint(x0 + i * cell, y0 + j * cell)[:2]
                (ea, na), (eb, nb) = (to_local.TransformPoint(lon, lat + k)[:2]
                                      for k in (0.0, 1e-4))
                a1[j, i] = a0 - math.atan2(eb - ea, nb - na)  # (the local grid's bearing)
        a1 = a1[inner]
        self.assertLess(np.degrees(np.abs(a1 - a0)).max(), 0.16)
        out = flat_earth_products(self, z, x0, y0, cell, sinu, D)
        h = array(out, "HorizonAngles").reshape(n, n, D)[inner]
        bn = array(out, "BentNormal").reshape(n, n, 3)[inner]
        svf = array(out, "SkyViewFactor").reshape(n, n)[inner]
        vsa = array(out, "VisibleSolidAngle").reshape(n, n)[inner]
        dsf = array(out, "DiffuseSkyFactor").reshape(n, n)[inner]
        az = 2 * np.pi * np.arange(D) / D
        # the horizons: linear between sectors 5.7 degrees apart leaves tan S (5.7 deg)^2 / 8
        err = np.degrees(np.abs(h - np.arctan(t * np.cos(az - a1[..., None])))).max()
        self.assertLess(err, 0.02, "HorizonAngles off by %.4f deg" % err)
        down = np.degrees(np.arctan2(bn[..., 0], bn[..., 1])) % 360.0
        err = np.abs(down - np.degrees(a1 + np.pi)).max()
        self.assertLess(err, 0.05, "BentNormal's azimuth off by %.4f deg" % err)
        err = np.abs(svf - (1 - S / np.pi)).max()
        self.assertLess(err, 5e-5, "SkyViewFactor off by %.2e" % err)
        err = np.abs(vsa - (2 * np.pi - 2 * S)).max()
        self.assertLess(err, 3e-4, "VisibleSolidAngle off by %.2e" % err)
        # Dozier-Frew: n . B / pi, B = integral of the visible sky's directions times sin h;
        # per azimuth in closed form over h from the horizon he to the zenith
        a = (np.arange(200000) + 0.5) * 2 * np.pi / 200000
        he = np.maximum(np.arctan(t * np.cos(a - a0)), 0.0)
        horizontal = np.pi / 4 - he / 2 - np.sin(2 * he) / 4
        B = np.array([(np.sin(a) * horizontal).mean(), (np.cos(a) * horizontal).mean(),
                      (np.cos(he) ** 2 / 2).mean()]) * 2 * np.pi
        normal = np.array([-t * math.sin(a0), -t * math.cos(a0), 1.0]) / math.hypot(1, t)
        err = np.abs(dsf - normal @ B / np.pi).max()
        self.assertLess(err, 1e-5, "DiffuseSkyFactor off by %.2e" % err)

    def testPoles(self):
        # A DEM around a pole (polar stereographic, the pole on a cell): the meridian
        # convergence takes every value around it, so between the lattice's nodes it is not
        # bilinear (nor continuous: +-180 degrees); there each cell takes its own. A cone 2 km
        # high and 20 km across on the pole: every cell's BentNormal points away from the pole
        # (true south on the north pole, north on the south pole) but for the grid's
        # discretization of the cone, which turns it by up to 1 degree on the same cone in UTM.
        # Before, interpolating the convergence turned bent normals by up to 167 degrees.
        from aperture.errors import Watcher
        n, cell = 101, 1000.0
        y, x = (np.mgrid[0:n, 0:n] - 50) * cell
        r = np.hypot(x, y)
        z = np.maximum(0.0, 2000.0 - 0.1 * r)
        near = (r > 0) & (r <= 12000.0)
        for epsg, away in ((3413, -1.0), (3031, 1.0)):
            w = Watcher()
            f = w.watch(aperture.vtkApertureSkyVisibility())
            f.SetInputData(make_image(z, -50 * cell, -50 * cell, cell, cell, "EPSG:%d" % epsg))
            f.SetMaximumDistance(20000.0)
            f.SetEarthCurvature(False)
            f.Update()
            self.assertEqual((w.errors, w.warnings), ([], []))
            bn = array(f.GetOutput(), "BentNormal").reshape(n, n, 3)
            off = np.degrees(np.abs(np.arctan2(bn[..., 0], away * bn[..., 1])))[near]
            self.assertLess(off.max(), 1.5, "EPSG:%d" % epsg)
            self.assertLess(off.mean(), 0.3, "EPSG:%d" % epsg)

    def testProjectionScaleChangeWithoutLattice(self):
        # Where a part of the DEM has no geographic coordinates (an orthographic view's
        # corners beyond the globe's disc) no lattice of scales can be measured: the sweep
        # takes the centre's cell size for every cell, and a DEM across which the ground cell
        # size changes by more than 0.5% is warned about. The sizes are computed here on the
        # sphere: the orthographic projection's inverse and great-circle distances between
        # the centres of a cell's opposite edges, at the points the filter measures (the
        # centre, the edges' midpoints; the corners have no coordinates).
        from aperture.errors import Watcher
        R = 6371000.0
        ortho = "+proj=ortho +lat_0=0 +lon_0=0 +R=%.0f +units=m +no_defs" % R

        def warnings_of(x0, y0, dx, dy, n):
            w = Watcher()
            f = w.watch(aperture.vtkApertureSkyVisibility())
            image = make_image(np.full((n, n), 100.0), x0, y0, dx, dy, ortho)
            f.SetInputData(image)
            f.SetMaximumDistance(3 * dx)
            f.Update()
            self.assertEqual(w.errors, [])
            return w.warnings

        def lonlat(x, y):  # (radians)
            r = math.hypot(x, y)
            c = math.asin(r / R)
            return math.atan2(x * math.sin(c), r * math.cos(c)), math.asin(y * math.sin(c) / r)

        def distance(p, q):
            (l1, f1), (l2, f2) = lonlat(*p), lonlat(*q)
            h = math.sin((f2 - f1) / 2) ** 2 + \
                math.cos(f1) * math.cos(f2) * math.sin((l2 - l1) / 2) ** 2
            return 2 * R * math.asin(math.sqrt(h))

        # 41 x 41 cells of 30 x 110 km, 4.8 to 6.0 million m east, -2.2 to 2.2 million north
        dx, dy, n, x0, y0 = 30000.0, 110000.0, 41, 4800000.0, -2200000.0
        self.assertGreater(math.hypot(x0 + 40 * dx, y0), R)  # (the east corners)
        sizes = {}
        for i, j in ((20, 20), (0, 20), (40, 20), (20, 0), (20, 40)):
            x, y = x0 + i * dx, y0 + j * dy
            sizes[i, j] = (distance((x - dx / 2, y), (x + dx / 2, y)),
                           distance((x, y - dy / 2), (x, y + dy / 2)))
        centre = sizes[20, 20]
        worst = max(abs(s[c] / centre[c] - 1) for s in sizes.values() for c in (0, 1))
        self.assertGreater(worst, 0.5)
        warnings = warnings_of(x0, y0, dx, dy, n)
        self.assertEqual(len(warnings), 1, warnings)
        # A DEM whose rows reach off the globe's disc on its central column (the top row's
        # centre 100 km beyond it) is refused, as when every row's sizes were measured there;
        # since only the centre row's are used, the first and last rows are measured too.
        w = Watcher()
        f = w.watch(aperture.vtkApertureSkyVisibility())
        w.watch(f.GetExecutive())
        f.SetInputData(make_image(np.full((41, 11), 100.0), -50000.0, R - 300000.0, 10000.0,
                                  10000.0, ortho))
        f.SetMaximumDistance(30000.0)
        f.Update()
        self.assertEqual(len(w.errors), 2, w.errors)  # (ours, then the executive's failure)
        self.assertIn("no metric cell size: the row of cells at y = 6.471e+06 (grid row 40, "
                      "counted from the south) has no geographic coordinates", w.errors[0])
        self.assertIn("the projection's scale changes across this DEM: its cells measure ",
                      warnings[0])
        self.assertIn("against %.0f x %.0f m at its centre, which the sweep uses for every "
                      "cell" % centre, warnings[0])
        got = float(re.search(r"off by up to ([0-9.]+)%", warnings[0]).group(1))
        self.assertAlmostEqual(got, 100 * worst, delta=0.006)
        # 100 km of the same projection, inside the disc: a lattice, so no warning (this near
        # the disc's edge the projection turns directions by 0.7 degrees across it, which
        # the sectors' weights and azimuths follow)
        self.assertEqual(warnings_of(x0, 0.0, 1000.0, 1000.0, 101), [])

    def testMercatorRowsAreExact(self):
        # A Mercator DEM's rows are parallels and its columns meridians, so its cells' ground
        # sizes depend on the row alone and the filter takes them row by row, as for lat/lon:
        # exact over a DEM from 58 to 64 N, where the scale changes by 20%. The terrain is a
        # plane rising S to the north on the ground, z = tan S * (meridian arc from the DEM's
        # south edge): its horizon in azimuth phi is atan(tan S cos phi) everywhere (flat Earth),
        # as on rhumb lines the northing grows by cos phi per metre. With the centre's cell size
        # for every cell, the cells near the edges got horizons 10% too steep or too flat.
        from aperture.errors import Watcher
        S, D, cell, nx = math.radians(0.7), 32, 1000.0, 50
        expected = np.arctan(np.tan(S) * np.cos(2 * np.pi * np.arange(D) / D))
        wgs84 = osr.SpatialReference()
        wgs84.ImportFromEPSG(4326)
        wgs84.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)

        for epsg in (3395, 3857):  # (World Mercator, ellipsoidal; Web Mercator, spherical)
            merc = osr.SpatialReference()
            merc.ImportFromEPSG(epsg)
            merc.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
            to_merc = osr.CoordinateTransformation(wgs84, merc)
            to_geo = osr.CoordinateTransformation(merc, wgs84)
            y0 = to_merc.TransformPoint(10.0, 58.0)[1]
            ny = int((to_merc.TransformPoint(10.0, 64.0)[1] - y0) / cell)
            ys = y0 + cell * np.arange(ny)
            lats = np.radians([to_geo.TransformPoint(1e6, y)[1] for y in ys])
            south = math.radians(to_geo.TransformPoint(1e6, y0 - cell / 2)[1])
            z = np.tile((-4000 + np.tan(S) * meridian_arc(south, lats))[:, None], (1, nx))
            w = Watcher()
            f = w.watch(aperture.vtkApertureSkyVisibility())
            f.SetInputData(make_image(z, 1e6, y0, cell, cell, "EPSG:%d" % epsg))
            f.SetMaximumDistance(5000.0)
            f.SetEarthCurvature(False)
            f.SetNumberOfDirections(D)
            f.SetComputeHorizonAngles(True)
            f.Update()
            self.assertEqual((w.errors, w.warnings), ([], []))  # (no scale-change warning)
            h = array(f.GetOutput(), "HorizonAngles").reshape(ny, nx, D)
            bent = array(f.GetOutput(), "BentNormal").reshape(ny, nx, 3)
            for j in (12, ny // 2, ny - 13):  # 58.1, 61 and 63.9 N
                err = np.degrees(np.abs(h[j, nx // 2] - expected)).max()
                # (6e-5 degree measured: float32 elevations; 0.067 with the centre's cell size)
                self.assertLess(err, 2e-4, "EPSG:%d row %d: %.5f deg" % (epsg, j, err))
                self.assertLess(abs(bent[j, nx // 2, 0]), 1e-6)  # (no convergence to rotate)

    def testLocalCRS(self):
        # A site grid in a local CRS (no place on the Earth): cells of its spacing in its unit,
        # its +y axis north, curvature on a sphere of the mean Earth radius R1.
        from aperture.errors import Watcher
        R1, k = 6371008.8, 0.13
        # A 1000 m peak 100 km east of a cell on flat ground, as in the kernel's test: the
        # peak's top seen over a sphere of effective radius R1 / (1 - k), in metres and in US
        # survey feet (the same grid of 50 m cells).
        z = np.zeros((5, 2001))
        z[2, 2000] = 1000.0
        Re = R1 / (1 - k)
        a = 100000.0 / Re
        exact = math.degrees(math.atan2((Re + 1000.0) * math.cos(a) - Re,
                                        (Re + 1000.0) * math.sin(a)))
        for unit, metres in (("metre", 1.0), ("US survey foot", 1200.0 / 3937.0)):
            w = Watcher()
            f = w.watch(aperture.vtkApertureSkyVisibility())
            f.SetInputData(make_image(z, 0.0, 0.0, 50.0 / metres, 50.0 / metres,
                                      'LOCAL_CS["site",UNIT["%s",%.17g]]' % (unit, metres)))
            f.SetNumberOfDirections(4)
            f.SetComputeHorizonAngles(True)
            f.Update()
            self.assertEqual((w.errors, w.warnings), ([], []))
            east = math.degrees(array(f.GetOutput(), "HorizonAngles").reshape(5, 2001, 4)[2, 0, 1])
            self.assertAlmostEqual(east, exact, delta=0.01, msg=unit)
            # (without curvature atan(H / d) = 0.573 degree; with it about 0.08 lower)
            self.assertGreater(abs(east - math.degrees(math.atan(0.01))), 0.05)
        # Rough terrain: every product as on the same grid laid on that sphere at the equator on
        # the central meridian of a transverse Mercator (cells of 30 m to within 1e-7, north
        # along the columns to within 2e-7 radian: the constant cell size the local grid takes
        # too). Away from the DEM's border: there that tiny convergence turns the sweep's
        # northward rays of the first column off the DEM at once (a horizon of -90 degrees).
        y, x = np.mgrid[0:90, 0:100] * 30.0
        z = (300 * np.sin(x / 900) * np.cos(y / 700) + 120 * np.sin(x / 230 + 1.3) *
             np.sin(y / 310) + 40 * np.cos(x / 70 - y / 90))
        names = ("VisibleSolidAngle", "ApertureRadius", "BentNormal", "SkyViewFactor",
                 "DiffuseSkyFactor", "PositiveOpenness", "HorizonAngles", "EdgeTruncated")
        out = {}
        for crs in ('LOCAL_CS["site",UNIT["metre",1]]', "+proj=tmerc +R=6371008.8 +units=m"):
            f = sky(make_image(z, 0.0, 0.0, 30.0, 30.0, crs), MaximumDistance=2000.0,
                    ComputeHorizonAngles=True)
            out[crs] = [array(f.GetOutput(), name).reshape(90, 100, -1)[1:-1, 1:-1]
                        for name in names]
        for name, local, sphere in zip(names, *out.values()):
            self.assertLess(np.abs(local - sphere).max(), 1e-5, name)

    def testFormatBytes(self):
        # the one formatter of byte counts (the command line's messages use it too)
        V = aperture.vtkApertureSkyVisibility
        for n, text in ((0, "0 bytes"), (512, "512 bytes"), (1023, "1023 bytes"),
                        (1024, "1.000 KiB"), (1536, "1.500 KiB"), (21600, "21.094 KiB"),
                        (828 * 1024 ** 2 * 1.0, "828.000 MiB"), (3.353 * 1024 ** 3, "3.353 GiB"),
                        (2.0 * 1024 ** 6, "2.000 EiB"), (5000.0 * 1024 ** 6, "5000.000 EiB")):
            self.assertEqual(V.FormatBytes(float(n)), text)
        self.assertEqual(V.GetUsableMemoryOwner(), usable_memory()[1])

    def testMemoryLimit(self):
        # Refused before allocating when the estimate exceeds MemoryLimit: bytes per cell of
        # the default products 33 (five floats, BentNormal 12, EdgeTruncated 1), the float
        # copy 4, the sweep's state 17: 54 x 20 x 20 = 21600 bytes = 21.094 KiB.
        image = make_image(np.ones((20, 20)), 400000, 5000000, 30, 30, "EPSG:32633")
        self.assertEqual(self.error(image, MemoryLimit=21599),
                         "a 20 x 20 DEM with these products needs about 21.094 KiB, more "
                         "than the 21.093 KiB MemoryLimit; bake a part of the DEM, a "
                         "decimated one, or fewer products")
        f = sky(image, MemoryLimit=21600)
        self.assertEqual(f.EstimateBytes(400.0), 21600.0)
        # the same check before reading: the update's text without its advice
        self.assertEqual(f.CheckMemory(20, 20, 0.0), "")
        f.SetMemoryLimit(21599)
        self.assertEqual(f.CheckMemory(20, 20, 0.0), "a 20 x 20 DEM with these products needs "
                         "about 21.094 KiB, more than the 21.093 KiB MemoryLimit")
        f.SetMemoryLimit(0)  # the machine's memory (or a control group's) beside the input
        memory, owner = usable_memory()
        self.assertEqual(f.CheckMemory(20, 20, memory - 21600.0), "")
        self.assertIn("needs about 21.094 KiB, more than the 21.092 KiB of memory %s beside the "
                      "DEM's " % owner, f.CheckMemory(20, 20, memory - 21598.0))
        # an input as large as the memory leaves nothing to compare with: the message says so
        units = ("bytes", "KiB", "MiB", "GiB", "TiB")
        u = max(k for k in range(5) if memory >= 1024 ** k)
        self.assertEqual(f.CheckMemory(20, 20, memory), "a 20 x 20 DEM with these products "
                         "needs about 21.094 KiB, and the DEM's %.3f %s alone exceed the "
                         "%.3f %s of memory %s" % ((memory / 1024.0 ** u, units[u]) * 2
                                                   + (owner,)))
        self.assertTrue(np.all(array(f.GetOutput(), "SkyViewFactor") == 1.0))
        # A sub-extent's outputs cover it alone (5 x 5 cells of 33 bytes, not 20 x 20), and the
        # elevations passed on are copied to it (4 bytes a cell): 21600 - 375 x 33 + 25 x 4.
        f = aperture.vtkApertureSkyVisibility()
        f.SetInputData(image)
        f.SetMemoryLimit(9325)
        f.UpdateExtent((0, 4, 0, 4, 0, 0))
        self.assertEqual(f.GetOutput().GetDimensions(), (5, 5, 1))
        region = ("the products of 5 x 5 cells, with the 20 x 20 cells of DEM around them, "
                  "need about 9.106 KiB, more than the 9.105 KiB MemoryLimit")
        self.assertEqual(region + "; bake a part of the DEM, a decimated one, or fewer products",
                         self.error(image, MemoryLimit=9324, UpdateExtent=(0, 4, 0, 4, 0, 0)))
        # the same before reading, for a request whose input extent is known (the bake's
        # --srcwin): the update's text without its advice
        self.assertEqual(f.EstimateBytes(400.0, 25.0), 9325.0)
        self.assertEqual(f.EstimateBytes(400.0, 400.0), 21600.0)
        self.assertEqual(f.CheckMemory(20, 20, 5, 5, 0.0), "")
        f.SetMemoryLimit(9324)
        self.assertEqual(f.CheckMemory(20, 20, 5, 5, 0.0), region)
        self.assertEqual(f.CheckMemory(20, 20, 20, 20, 0.0), f.CheckMemory(20, 20, 0.0))
        # The default limit is the usable memory less the input's size: 360 directions of
        # HorizonAngles (1494 bytes a cell) on a grid of a little more cells than that allows.
        side = int(math.sqrt(memory / 1494.0 * 1.02)) + 1
        if side * side * 4 > 1 << 30:
            self.skipTest("more than 1 GiB of elevations to exceed this machine's memory")
        big = make_image(np.zeros((side, side), dtype=np.float32), 400000, 5000000, 30, 30,
                         "EPSG:32633")
        message = self.error(big, NumberOfDirections=360, ComputeHorizonAngles=True)
        self.assertTrue(message.startswith(
            "a %d x %d DEM with these products needs about " % (side, side)), message)
        self.assertIn("(HorizonAngles take 4 bytes per cell and direction), more than the ",
                      message)
        self.assertIn(" of memory %s beside the DEM's " % owner, message)
        # the elevation array must have a value for every point
        short = make_image(np.ones((4, 5)), 400000, 5000000, 30, 30, "EPSG:32633")
        short.GetPointData().GetArray("Elevation").SetNumberOfTuples(19)
        self.assertEqual(self.error(short), "the point array 'Elevation' has 19 tuples "
                         "for the 5 x 4 points of the input's extent")

    def testOutOfMemory(self):
        # Child processes whose address space leaves some MiB above what they hold once the
        # DEM is built, so that an allocation fails: an error naming the size, not an abort.
        # (With a MemoryLimit of a TiB, past the check that refuses such a job up front, 3.)
        # Bytes per cell named (vtkApertureSkyVisibility.h, ap_horizon_create): each output
        # (4 per float, 12 for BentNormal, 1 for EdgeTruncated, 4 per HorizonAngles sector),
        # the filter's float copy of the elevations (4) and the sweep's state (17, plus 12
        # when DiffuseSkyFactor is wanted without BentNormal).
        # 1. The 360 MiB of HorizonAngles (512 x 512 cells x 360 directions) fail in VTK:
        #    1440 + 33 of the seven derived products + 4 + 17 = 1494 bytes x 262144 cells
        #    = 373.5 MiB.
        self.assertIn("out of memory: a 512 x 512 DEM with these products needs about 374 MiB "
                      "(HorizonAngles take 4 bytes per cell and direction)",
                      self.out_of_memory(512, 256, "f.SetNumberOfDirections(360)\n"
                                         "f.SetComputeHorizonAngles(True)\n"))
        # 2. Only SkyViewFactor on 4096 x 4096 cells: its 64 MiB and the filter's 64 MiB copy
        #    fit in 200 MiB, the sweep's 272 MiB of state do not, and the C kernel's failure
        #    gets the same message: 4 + 4 + 17 = 25 bytes x 16 Mi cells = 400 MiB.
        only_svf = "".join("f.SetCompute%s(False)\n" % name for name in (
            "VisibleSolidAngle", "ApertureRadius", "BentNormal", "DiffuseSkyFactor",
            "PositiveOpenness", "EdgeTruncated"))
        message = self.out_of_memory(4096, 200, only_svf)
        self.assertIn("out of memory: a 4096 x 4096 DEM with these products needs about "
                      "400 MiB", message)
        self.assertNotIn("HorizonAngles", message)
        # 3. Without a MemoryLimit the job is refused before anything is allocated: the memory
        #    the process may use is what the address-space limit leaves (less 128 MiB, at most
        #    half, for threads still to start), since 2026-12-06.
        message = self.out_of_memory(512, 256, "f.SetNumberOfDirections(360)\n"
                                     "f.SetComputeHorizonAngles(True)\n", limit=False)
        self.assertTrue(message.startswith(
            "a 512 x 512 DEM with these products needs about 373.500 MiB (HorizonAngles take 4 "
            "bytes per cell and direction), more than the "), message)
        # (the DEM is mapped already: in what the limit leaves, not subtracted again)
        self.assertTrue(message.endswith(" of memory this process may use under its "
                                         "address-space limit (ulimit -v); bake a part of the "
                                         "DEM, a decimated one, or fewer products\n"), message)
        # 4. Memory the process holds counts once under an address-space limit: a DEM with
        #    400 MiB of other point arrays, under a limit 400 MiB above what the process has
        #    mapped with it, bakes its 512 x 512 cells (about 10 MiB; the usable memory is
        #    272 MiB, 400 less 128 for threads); subtracting the arrays again, as until
        #    2026-12-06, refused it ("the DEM's 401 MiB alone exceed the 272 MiB").
        self.assertEqual(self.out_of_memory(
            512, 400, "", limit=False, extra="extra = numpy_to_vtk(np.zeros((%d, 200), "
            "dtype=np.float64), deep=1)\nextra.SetName('Other')\n"
            "image.GetPointData().AddArray(extra)\n" % (512 * 512)), "no error\n")

    def out_of_memory(self, size, headroom_mib, setup, limit=True, extra=""):
        import subprocess
        script = """
import resource
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import vtkImageData
import aperture
from aperture.errors import Watcher
image = vtkImageData()
image.SetDimensions(%(size)d, %(size)d, 1)
image.SetSpacing(30, 30, 1)
values = numpy_to_vtk(np.zeros(%(size)d * %(size)d, dtype=np.float32), deep=1)
values.SetName("Elevation")
image.GetPointData().SetScalars(values)
%(extra)sgeo = aperture.vtkApertureGeoreference()
assert geo.SetCRS("EPSG:32633")
geo.AttachToImage(image)
w = Watcher()
f = w.watch(aperture.vtkApertureSkyVisibility())
f.SetInputData(image)
%(setup)sf.SetNumberOfThreads(1)
%(limit)s
with open("/proc/self/status") as status:
    vm = next(int(line.split()[1]) for line in status if line.startswith("VmSize:"))
resource.setrlimit(resource.RLIMIT_AS, ((vm + %(headroom)d * 1024) * 1024, resource.RLIM_INFINITY))
f.Update()
print(w.errors[0] if w.errors else "no error")
""" % dict(size=size, headroom=headroom_mib, setup=setup, extra=extra,
           limit="f.SetMemoryLimit(1 << 40)" if limit else "")
        p = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                           timeout=120)
        self.assertEqual(p.returncode, 0, p.stderr[-2000:])
        return p.stdout

    def error(self, image, **options):
        from aperture.errors import Watcher
        w = Watcher()
        f = w.watch(aperture.vtkApertureSkyVisibility())
        w.watch(f.GetExecutive())
        f.SetInputData(image)
        extent = options.pop("UpdateExtent", None)
        for key, value in options.items():
            getattr(f, "Set" + key)(value)
        if extent:
            f.UpdateExtent(extent)
        else:
            f.Update()
        self.assertTrue(w.errors, "expected an error for %r" % (options,))
        return w.errors[0]


if __name__ == "__main__":
    Testing.main([(TestSkyVisibility, "test")])
