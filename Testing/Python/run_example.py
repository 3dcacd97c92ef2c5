# SPDX-License-Identifier: BSD-3-Clause
"""Run one of Examples/ as a user would and check what it wrote, so that an example which
writes an empty mesh or a blank picture fails (its exit status alone would not):

    run_example.py EXAMPLE.py OUTPUT [--flat | --night | --unusable] [ARGUMENTS...]
        (runs EXAMPLE.py ARGUMENTS -o OUTPUT; --flat: sky_products.py on a flat DEM it writes;
        --night: a rendering example whose sun is below the horizon; --unusable: on a DEM of
        one cell it writes, which must end in the example's one-line error, status 1, and
        nothing written: render_terrain.py and sky_products.py ended in a traceback there,
        time_of_day_viewer.py wrote an empty picture, until 2026-12-07)

- read_and_mesh.py: the embedded DEM's mesh: 403 x 344 points, two triangles per cell, its
  arrays, about 30 x 32 km (cells of 74.85 m x 92.47 m at the centre) and its 840 m of relief
  (the Earth's curvature lowers the edges by up to 18 m more);
- sky_products.py: SkyViewFactor and DiffuseSkyFactor side by side, 403 x 344 each, with the 4
  white columns between them, each stretched from black (its 0.5th percentile) to white (1);
  with --flat, on a flat 60 x 50 DEM with a 2 x 2 hole: white but for the hole (the stretch
  from 1 to 1 divided by 0 until 2026-12-06: a black picture);
- the rendering examples: a picture of the documented size in which the terrain covers a
  tenth or more and is shaded (not uniform, not black); with --night, black terrain and a
  warning that says why (lit_terrain.py wrote it silently until 2026-12-06).
Every example must also print no error on its way (VTK's or its own) and no numpy warning.
"""
import os
import subprocess
import sys

import numpy as np

NX, NY = 403, 344  # the embedded Jacksboro DEM
PICTURES = {"render_terrain.py": (800, 500), "lit_terrain.py": (900, 600),
            "time_of_day_viewer.py": (1000, 700)}


def fail(message):
    print("run_example: " + message, file=sys.stderr)
    sys.exit(1)


def check_mesh(path):
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    mesh = reader.GetOutput()
    if mesh.GetNumberOfPoints() != NX * NY or mesh.GetNumberOfCells() != 2 * (NX - 1) * (NY - 1):
        fail("%s: %d points and %d triangles, not %d and %d" % (
            path, mesh.GetNumberOfPoints(), mesh.GetNumberOfCells(), NX * NY,
            2 * (NX - 1) * (NY - 1)))
    for name in ("Elevation", "Normals", "TextureCoordinates"):
        if not mesh.GetPointData().GetArray(name):
            fail("%s has no point array %s" % (path, name))
    b = mesh.GetBounds()
    east, north, relief = b[1] - b[0], b[3] - b[2], b[5] - b[4]
    if not (abs(east / ((NX - 1) * 74.85) - 1) < 0.02 and abs(north / ((NY - 1) * 92.47) - 1) < 0.02
            and 838.0 <= relief <= 860.0):
        fail("%s spans %.0f m east, %.0f m north, %.1f m of relief" % (path, east, north, relief))


def read_picture(path):
    from osgeo import gdal
    ds = gdal.Open(path)
    if ds is None:
        fail("cannot read the picture " + path)
    pixels = ds.ReadAsArray().astype(float)
    return pixels[None] if pixels.ndim == 2 else pixels[:3]  # bands, rows, columns


def check_sky(path):
    grey = read_picture(path)[0]
    if grey.shape != (NY, 2 * NX + 4):
        fail("%s is %d x %d pixels, not %d x %d" % (path, grey.shape[1], grey.shape[0],
                                                  2 * NX + 4, NY))
    if not (grey[:, NX:NX + 4] == 255).all():
        fail("%s: the 4 columns between the two products are not white" % path)
    for name, half in (("SkyViewFactor", grey[:, :NX]), ("DiffuseSkyFactor", grey[:, NX + 4:])):
        black = (half == 0).mean()
        if not (0.002 <= black <= 0.02 and half.max() >= 250 and half.std() > 10):
            fail("%s: %s has %.2f%% black pixels, its brightest %d, spread %.1f" % (
                path, name, 100 * black, half.max(), half.std()))


def write_flat_dem(path):
    """A flat 60 x 50 GeoTIFF at 500 m, cells 2 x 2 of rows 10-11, columns 20-21 nodata."""
    from osgeo import gdal
    z = np.full((50, 60), 500.0, np.float32)
    z[10:12, 20:22] = -9999.0
    ds = gdal.GetDriverByName("GTiff").Create(path, 60, 50, 1, gdal.GDT_Float32)
    ds.SetGeoTransform((500000.0, 30.0, 0.0, 4000000.0, 0.0, -30.0))
    ds.SetProjection("EPSG:32633")
    ds.GetRasterBand(1).SetNoDataValue(-9999.0)
    ds.GetRasterBand(1).WriteArray(z)
    ds = None


def write_one_cell_dem(path):
    """A GeoTIFF of one cell, which no example can use (the reader wants 2 x 2)."""
    from osgeo import gdal
    ds = gdal.GetDriverByName("GTiff").Create(path, 1, 1, 1, gdal.GDT_Float32)
    ds.SetGeoTransform((500000.0, 30.0, 0.0, 4000000.0, 0.0, -30.0))
    ds.SetProjection("EPSG:32633")
    ds.GetRasterBand(1).Fill(500.0)
    ds = None


def check_flat_sky(path):
    grey = read_picture(path)[0]
    expected = np.full((50, 124), 255)
    for left in (0, 64):
        expected[10:12, left + 20:left + 22] = 0
    if grey.shape != expected.shape or (grey != expected).any():
        fail("%s: the flat DEM's picture is not white but for its hole (%s pixels, %d black)"
             % (path, grey.shape, (grey == 0).sum()))


def check_render(path, size, night=False):
    rgb = read_picture(path)
    if rgb.shape[0] != 3 or rgb.shape[1:] != (size[1], size[0]):
        fail("%s is not a %d x %d RGB picture: %s" % (path, size[0], size[1], rgb.shape))
    background = rgb[:, 0, 0]  # (a corner: the sky behind the terrain)
    terrain = np.abs(rgb - background[:, None, None]).max(axis=0) > 3
    luminance = rgb.mean(axis=0)[terrain]
    if night:
        # (its edges blend into the background)
        lit = not (terrain.mean() >= 0.1 and np.percentile(luminance, 98) <= 3)
    else:
        lit = terrain.mean() >= 0.1 and luminance.std() > 10 and luminance.mean() > 20
    if lit == night:
        fail("%s: terrain on %.0f%% of the picture, luminance %.1f +- %.1f" % (
            path, 100 * terrain.mean(), luminance.mean() if terrain.any() else 0,
            luminance.std() if terrain.any() else 0))


def main(argv):
    example, output, arguments = argv[0], argv[1], argv[2:]
    flat, night = arguments[:1] == ["--flat"], arguments[:1] == ["--night"]
    unusable = arguments[:1] == ["--unusable"]
    if flat:
        arguments = [os.path.splitext(output)[0] + "-dem.tif"] + arguments[1:]
        write_flat_dem(arguments[0])
    elif unusable:
        arguments = [os.path.splitext(output)[0] + "-dem.tif"] + arguments[1:]
        write_one_cell_dem(arguments[0])
    elif night:
        arguments = arguments[1:]
    if os.path.exists(output):
        os.remove(output)  # (the check reads what this run wrote)
    p = subprocess.run([sys.executable, example] + arguments + ["-o", output],
                       stderr=subprocess.PIPE, text=True)
    sys.stderr.write(p.stderr)
    name = os.path.basename(example)
    if unusable:
        last = p.stderr.strip().splitlines()[-1] if p.stderr.strip() else ""
        if p.returncode != 1 or "Traceback" in p.stderr or os.path.exists(output) or \
                not (last.startswith(name[:-3] + ": ") and arguments[0] in last):
            fail("%s on a DEM of one cell: status %d, %s, its last line %r" % (
                example, p.returncode, "wrote %s" % output if os.path.exists(output) else
                "nothing written", last))
        print("run_example: %s refused a DEM of one cell: %s" % (name, last))
        return
    if p.returncode != 0:
        fail("%s exited with status %d" % (example, p.returncode))
    # (an error VTK printed, though the example went on: render_terrain.py asked its mapper
    # for the aperture model without the arrays it needs until 2026-12-06)
    if any(mark in p.stderr for mark in ("ERR|", "ERROR", "Error")):  # (VTK's logger: ERR|)
        fail("%s printed an error:\n%s" % (example, p.stderr))
    if "RuntimeWarning" in p.stderr:  # (numpy's: a division by 0, a NaN cast)
        fail("%s printed a warning:\n%s" % (example, p.stderr))
    if name == "read_and_mesh.py":
        check_mesh(output)
    elif name == "sky_products.py":
        (check_flat_sky if flat else check_sky)(output)
    elif name in PICTURES:
        if night and "below the horizon" not in p.stderr:
            fail("%s said nothing of the sun below the horizon" % example)
        check_render(output, PICTURES[name], night)
    else:
        fail("no check for the example " + name)
    print("run_example: %s wrote %s, checked" % (name, output))


if __name__ == "__main__":
    main(sys.argv[1:])
