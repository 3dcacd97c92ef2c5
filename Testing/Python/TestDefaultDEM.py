# SPDX-License-Identifier: BSD-3-Clause
"""The embedded default DEM: bounds and orientation checked against the npz's own arrays and
against published landmarks (coordinates and elevations from the landmarks' Wikipedia/GNIS
entries, not from this DEM):

- Cross Mountain summit ("The Flag Pole"), 36.19833 N 84.23056 W, 1077 m (3534 ft): the
  highest point of the Cumberland Mountains in Tennessee; it must be the DEM's highest cell.
- Jacksboro, 36.331511 N 84.188793 W, 335 m; LaFollette, 36.375006 N 84.127623 W, 327 m:
  towns on the floor of Powell Valley.

If rows were flipped, or the npz's `ymin` were taken as the northern edge, none of these
would hold (the towns would lie outside the DEM).
"""
import math
import os
import sys
import unittest

import numpy as np

NPZ = "/usr/share/matplotlib/mpl-data/sample_data/jacksboro_fault_dem.npz"
CELL = 1.0 / 1200.0


def skip_unless_default_dem():
    import aperture
    try:
        return aperture.default_dem()
    except FileNotFoundError as e:
        print("skipped: %s" % e)
        sys.exit(125)


class TestDefaultDEM(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        import aperture
        from vtkmodules.util.numpy_support import vtk_to_numpy
        cls.path = skip_unless_default_dem()
        reader = aperture.vtkApertureDEMReader()
        reader.SetFileName(cls.path)
        reader.Update()
        cls.image = reader.GetOutput()
        nx, ny, _ = cls.image.GetDimensions()
        cls.z = vtk_to_numpy(cls.image.GetPointData().GetArray("Elevation")).reshape(ny, nx)
        cls.origin = cls.image.GetOrigin()

    def lonlat_to_index(self, lon, lat):
        """Fractional (column, row) of a point; row 0 south, as in the image."""
        return (lon - self.origin[0]) / CELL, (lat - self.origin[1]) / CELL

    def bilinear(self, lon, lat):
        i, j = self.lonlat_to_index(lon, lat)
        i0, j0 = int(math.floor(i)), int(math.floor(j))
        fi, fj = i - i0, j - j0
        z = self.z
        return ((1 - fi) * (1 - fj) * z[j0, i0] + fi * (1 - fj) * z[j0, i0 + 1]
                + (1 - fi) * fj * z[j0 + 1, i0] + fi * fj * z[j0 + 1, i0 + 1])

    def test_bounds(self):
        import aperture
        geo = aperture.vtkApertureGeoreference()
        self.assertTrue(geo.SetFromImage(self.image))
        self.assertTrue(geo.IsGeographic())
        b = [0.0] * 4
        self.assertTrue(geo.GetBoundsLonLat(b))
        expected = [-84.41375, 36.44625 - 344 * CELL, -84.41375 + 403 * CELL, 36.44625]
        for got, want in zip(b, expected):
            self.assertAlmostEqual(got, want, places=9)
        self.assertAlmostEqual(expected[1], 36.1595833333, places=9)
        self.assertEqual(self.image.GetDimensions(), (403, 344, 1))

    def test_values_match_npz(self):
        # The npz stores the northern row first; the image stores the southern row first.
        if not os.path.exists(NPZ):
            self.skipTest("python-matplotlib-data is not installed")
        with np.load(NPZ) as npz:
            elevation = npz["elevation"].astype(np.float32)
        np.testing.assert_array_equal(self.z, np.flipud(elevation))

    def test_cross_mountain_is_the_summit(self):
        j, i = np.unravel_index(np.nanargmax(self.z), self.z.shape)
        lon = self.origin[0] + i * CELL
        lat = self.origin[1] + j * CELL
        # Published summit position within one cell, published height within 2 m.
        self.assertLess(abs(lon - (-84.23056)), CELL)
        self.assertLess(abs(lat - 36.19833), CELL)
        self.assertLess(abs(self.z[j, i] - 1077.0), 2.0)

    def test_towns_on_the_valley_floor(self):
        for name, lon, lat, height in (("Jacksboro", -84.188793, 36.331511, 335.0),
                                       ("LaFollette", -84.127623, 36.375006, 327.0)):
            with self.subTest(town=name):
                # (332.6 and 334.6 m: Documents/DefaultDEM.md's table, which gave 327 and 325
                # until 2026-12-07; a town is not one point of the valley floor)
                self.assertLess(abs(self.bilinear(lon, lat) - height), 10.0)

    def test_mesh_puts_the_summit_south_of_centre(self):
        # In the ENU mesh, north is +y: Cross Mountain is 11.6 km south and 1.4 km east of the
        # DEM centre (36.302917 N, 84.245833 W); meridian and parallel radii from WGS 84.
        import aperture
        mesher = aperture.vtkApertureTerrainMesh()
        mesher.SetInputData(self.image)
        mesher.Update()
        mesh = mesher.GetOutput()
        from vtkmodules.util.numpy_support import vtk_to_numpy
        z = vtk_to_numpy(mesh.GetPointData().GetArray("Elevation"))
        x, y, _ = mesh.GetPoint(int(np.nanargmax(z)))
        a, f = 6378137.0, 1 / 298.257223563
        e2 = f * (2 - f)
        phi = math.radians(36.302917)
        w = math.sqrt(1 - e2 * math.sin(phi) ** 2)
        north = a * (1 - e2) / w ** 3 * math.radians(36.19833 - 36.302917)
        east = a / w * math.cos(phi) * math.radians(-84.23056 + 84.245833)
        self.assertLess(abs(y - north), 100.0)
        self.assertLess(abs(x - east), 100.0)
        self.assertLess(north, -11000.0)

    def test_maker_beside_the_function(self):
        # The module that makes the DEM does not shadow aperture.default_dem(), the function
        # (until 2026-12-06 it was the module aperture.default_dem: importing it replaced the
        # function on the package, and `aperture info` then failed with "'module' object is
        # not callable")
        import subprocess
        code = ("import aperture, aperture.make_default_dem; print(aperture.default_dem()); "
                "import aperture.cli; aperture.cli.main(['info', '--json'])")
        p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           timeout=120)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual(p.stdout.splitlines()[0], self.path)
        import importlib.util
        self.assertIsNone(importlib.util.find_spec("aperture.default_dem"))

    def test_maker_refuses_bad_input(self):
        from aperture import make_default_dem
        with np.load(NPZ) as npz:
            arrays = dict(npz)
        for key in ("dx", "xmin", "ymax"):
            for bad in (float("nan"), float("inf")):
                changed = dict(arrays, **{key: np.float64(bad)})
                with self.assertRaises(ValueError, msg=(key, bad)):
                    make_default_dem.georeference(changed)
        # a folder that cannot be made: a one-line message and status 1, no traceback
        import contextlib
        import io
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            status = make_default_dem.main([NPZ, "/proc/no/such/folder/dem.tif"])
        self.assertEqual(status, 1)
        self.assertRegex(err.getvalue(), r"^aperture\.make_default_dem: .*'/proc/no'\n$")


if __name__ == "__main__":
    sys.exit(0 if unittest.main(exit=False).result.wasSuccessful() else 1)
