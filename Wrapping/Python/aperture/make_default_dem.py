# SPDX-License-Identifier: BSD-3-Clause
"""Make the embedded default DEM: matplotlib's `jacksboro_fault_dem.npz` (USGS 3 arc-second
elevations of the Jacksboro fault area, Tennessee; shipped by Debian's python-matplotlib-data)
as a georeferenced GeoTIFF in EPSG:4326, written with Aperture's own writer.

    python3 -m aperture.make_default_dem NPZ OUT.tif

(Named apart from the function aperture.default_dem(), the path of the result: a submodule of
that name would replace the function on the package once imported.)

How the npz maps to the ground (Documents/DefaultDEM.md has the evidence):
- `elevation` is rows x columns, int16 metres; row 0 is the northern row, column 0 the western.
- `dx`, `dy` are the cell size in degrees (3 arc-seconds); `xmin`, `xmax` are the western and
  eastern cell edges (xmax - xmin = columns * dx exactly).
- `ymax` (36.44625) is the northern edge. The npz's `ymin` (36.7329) is ymax + rows * dy, a
  point north of `ymax`, not the southern edge: the southern edge is ymax - rows * dy
  (36.159583). Taking `ymin` as the northern edge would move the DEM 32 km north, away from
  every landmark in it (Cross Mountain, Jacksboro, LaFollette, Norris Lake).
"""
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import vtkImageData

from aperture import vtkApertureDEMWriter, vtkApertureGeoreference
from aperture.errors import ApertureError, Watcher

ARC_SECOND = 1.0 / 3600.0


def georeference(npz):
    """Check the arrays of the npz against each other and return
    (elevation rows north to south, west edge, south edge, cell size) in degrees."""
    z = np.asarray(npz["elevation"])
    if z.ndim != 2 or z.shape[0] < 2 or z.shape[1] < 2:
        raise ValueError("elevation must be a 2-D array of at least 2 x 2, got %r" % (z.shape,))
    rows, cols = z.shape
    dx, dy = float(npz["dx"]), float(npz["dy"])
    xmin, xmax = float(npz["xmin"]), float(npz["xmax"])
    ymin, ymax = float(npz["ymin"]), float(npz["ymax"])
    # (each test written so that NaN fails it)
    if not (abs(dx - dy) <= 1e-12 and abs(dx - 3 * ARC_SECOND) <= 1e-12):
        raise ValueError("expected square 3 arc-second cells, got dx=%r dy=%r" % (dx, dy))
    # The x bounds are cell edges: their span is exactly columns * dx.
    if not (abs(xmin) <= 180.0 and abs((xmax - xmin) - cols * dx) <= 1e-9):
        raise ValueError("xmax - xmin = %r is not columns * dx = %r (or xmin %r is not a "
                         "longitude)" % (xmax - xmin, cols * dx, xmin))
    # |ymin - ymax| spans exactly rows * dy too, but ymin lies north of ymax; ymax is the
    # northern edge (see the module docstring), so the southern edge is ymax - rows * dy.
    if not (abs(ymax) <= 90.0 and abs(ymax - rows * dy) <= 90.0 and
            abs(abs(ymin - ymax) - rows * dy) <= 1e-9):
        raise ValueError("|ymin - ymax| = %r is not rows * dy = %r" % (abs(ymin - ymax), rows * dy))
    north = ymax
    south = north - rows * dy
    return z, xmin, south, dx


def make_image(npz):
    """The DEM as an Aperture DEM image (row 0 south, CRS in the field data)."""
    z, west, south, cell = georeference(npz)
    rows, cols = z.shape
    image = vtkImageData()
    image.SetDimensions(cols, rows, 1)
    image.SetSpacing(cell, cell, 1.0)
    image.SetOrigin(west + 0.5 * cell, south + 0.5 * cell, 0.0)
    # VTK images store the southern row first; the npz stores the northern row first.
    values = np.ascontiguousarray(np.flipud(z).astype(np.float32).ravel())
    elevation = numpy_to_vtk(values, deep=1)
    elevation.SetName("Elevation")
    image.GetPointData().SetScalars(elevation)
    geo = vtkApertureGeoreference()
    if not geo.SetCRS("EPSG:4326"):
        raise RuntimeError(geo.GetErrorMessage())
    geo.AttachToImage(image)
    return image


def write(npz_path, out_path):
    with np.load(npz_path) as npz:
        image = make_image(npz)
    watcher = Watcher()
    writer = watcher.watch(vtkApertureDEMWriter())
    writer.SetInputData(image)
    writer.SetFileName(out_path)
    writer.AddMetadata("SOURCE", "USGS 3 arc-second DEM, Jacksboro fault area, Tennessee; "
                       "matplotlib sample_data/jacksboro_fault_dem.npz (Debian "
                       "python-matplotlib-data)")
    writer.AddMetadata("LICENSE", "USGS elevation data: public domain")
    writer.AddMetadata("GEOREFERENCE", "north edge = npz ymax, west edge = npz xmin, "
                       "3 arc-second cells, WGS 84; see Documents/DefaultDEM.md")
    watcher.write(writer, "writing %s" % out_path)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 2:
        print("usage: python3 -m aperture.make_default_dem NPZ OUT.tif", file=sys.stderr)
        return 2
    import os
    try:
        os.makedirs(os.path.dirname(os.path.abspath(argv[1])), exist_ok=True)
        write(argv[0], argv[1])
    except (OSError, ValueError, ApertureError, RuntimeError, KeyError) as e:
        print("aperture.make_default_dem: %s" % e, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
