# SPDX-License-Identifier: BSD-3-Clause
"""Compute what every cell of a DEM sees of the sky, and save the two sky-view factors side by
side as a grey-scale PNG (left: SkyViewFactor, right: DiffuseSkyFactor).

    build/bin/aperture-python Examples/sky_products.py [DEM] [--radius METRES] [-o sky.png]
    (installed, /usr/bin/python3 in place of build/bin/aperture-python)

Shows: vtkApertureDEMReader -> vtkApertureSkyVisibility, its point arrays as numpy arrays,
and the difference between the two sky-view definitions: SkyViewFactor (horizontal plane,
Zaksek et al. 2011) is about the sky above the horizon only, so every open cell is white;
DiffuseSkyFactor (Dozier & Frew 1990) is the diffuse light a sloping cell receives, so steep
slopes are grey even when nothing blocks their view."""
import argparse

import numpy as np
from osgeo import gdal
from vtkmodules.util.numpy_support import vtk_to_numpy

import aperture

gdal.UseExceptions()


def get_program_parameters():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("dem", nargs="?", help="DEM raster (default: the embedded DEM)")
    parser.add_argument("--radius", type=float, default=0.0,
                        help="search distance in metres (default 0: unlimited)")
    parser.add_argument("-o", "--output", default="sky.png", help="PNG to write")
    return parser.parse_args()


def grey(values, low, high):
    """values in [low, high] -> 0..255 (all white where low = high: a flat DEM's open cells, or
    a mostly flat one's); nodata (NaN) -> 0."""
    span = high - low
    with np.errstate(invalid="ignore"):  # (NaN compares false: nodata, black below)
        scaled = (np.clip((values - low) / span, 0.0, 1.0) if span > 0 else
                  (values >= high).astype(float)) * 255.0
    return np.where(np.isnan(values), 0, np.rint(scaled)).astype(np.uint8)


def main():
    args = get_program_parameters()

    reader = aperture.vtkApertureDEMReader()
    reader.SetFileName(args.dem or aperture.default_dem())

    sky = aperture.vtkApertureSkyVisibility()
    sky.SetInputConnection(reader.GetOutputPort())
    sky.SetNumberOfDirections(32)
    sky.SetMaximumDistance(args.radius)          # 0: unlimited
    sky.Update()
    image = sky.GetOutput()
    if image.GetNumberOfPoints() == 0:  # (VTK printed the filters' error)
        raise SystemExit("sky_products: no sky products from %s" % (args.dem or "the embedded DEM"))
    nx, ny, _ = image.GetDimensions()

    def product(name):
        # point arrays are row-major with row 0 south; flip so that north is up in the PNG
        return vtk_to_numpy(image.GetPointData().GetArray(name)).reshape(ny, nx)[::-1]

    svf, dsf = product("SkyViewFactor"), product("DiffuseSkyFactor")
    print("SkyViewFactor    %.3f .. %.3f, mean %.3f" % (np.nanmin(svf), np.nanmax(svf),
                                                     np.nanmean(svf)))
    print("DiffuseSkyFactor %.3f .. %.3f, mean %.3f" % (np.nanmin(dsf), np.nanmax(dsf),
                                                     np.nanmean(dsf)))

    # each stretched from its own 0.5th percentile (black) to 1 (white); 4 white pixels between
    lows = [float(np.nanpercentile(v, 0.5)) for v in (svf, dsf)]
    gap = np.full((ny, 4), 255, np.uint8)
    picture = np.hstack([grey(svf, lows[0], 1.0), gap, grey(dsf, lows[1], 1.0)])
    mem = gdal.GetDriverByName("MEM").Create("", picture.shape[1], picture.shape[0], 1,
                                             gdal.GDT_Byte)
    mem.GetRasterBand(1).WriteArray(picture)
    gdal.GetDriverByName("PNG").CreateCopy(args.output, mem)
    print("black at %.3f (left), %.3f (right), white at 1; wrote %s"
          % (lows[0], lows[1], args.output))


if __name__ == "__main__":
    main()
