# SPDX-License-Identifier: BSD-3-Clause
"""Benchmark: reading a DEM and meshing it, against peers measured in the same run.

    build/bin/aperture-python bench/bench_read_mesh.py [DEM ...] [--repeat N] [--threads N]

Peers:
- read: GDAL's own Python read of the band into float32 (`ReadAsArray`), the floor for any
  GDAL-based reader; ours also applies nodata/scale/unit, flips rows and attaches the
  georeference.
- mesh: VTK's stock image-to-surface pipeline (vtkImageDataGeometryFilter ->
  vtkTriangleFilter -> vtkPolyDataNormals), which is what a VTK user would otherwise write. It
  is not a correct terrain mesh (no geodesy: a lat/lon DEM comes out in degrees, no holes at
  nodata), only a speed reference. Ours converts every cell to ENU metres with GeographicLib,
  leaves holes at nodata and adds normals and texture coordinates.

Reports the median of N runs (default 3) in seconds and our time divided by the peer's
(lower is better). Default DEMs: ../shared/data/dem/*.tif when present, else the embedded DEM.
"""
import argparse
import glob
import os
import statistics
import sys
import time

from osgeo import gdal
from vtkmodules.vtkCommonCore import vtkSMPTools
from vtkmodules.vtkFiltersCore import vtkPolyDataNormals, vtkTriangleFilter
from vtkmodules.vtkFiltersGeometry import vtkImageDataGeometryFilter

import aperture

gdal.UseExceptions()


def median_time(fn, repeat):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def gdal_read(path):
    ds = gdal.Open(path)
    band = ds.GetRasterBand(1)
    band.ReadAsArray(buf_type=gdal.GDT_Float32)
    band = None
    ds = None


def our_read(path):
    reader = aperture.vtkApertureDEMReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def vtk_mesh(image):
    geometry = vtkImageDataGeometryFilter()
    geometry.SetInputData(image)
    triangles = vtkTriangleFilter()
    triangles.SetInputConnection(geometry.GetOutputPort())
    normals = vtkPolyDataNormals()
    normals.SetInputConnection(triangles.GetOutputPort())
    normals.SplittingOff()
    normals.Update()


def our_mesh(image):
    mesher = aperture.vtkApertureTerrainMesh()
    mesher.SetInputData(image)
    mesher.Update()
    return mesher.GetOutput().GetNumberOfCells()


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("dems", nargs="*")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--threads", type=int, default=0, help="vtkSMPTools threads (0: all)")
    args = parser.parse_args()
    if args.threads:
        vtkSMPTools.Initialize(args.threads)
    here = os.path.dirname(os.path.abspath(__file__))
    dems = args.dems or sorted(glob.glob(os.path.join(here, "..", "..", "shared", "data", "dem",
                                                      "*.tif")))
    if not dems:
        dems = [aperture.default_dem()]
    print("SMP backend %s, %d threads; median of %d runs; seconds"
          % (vtkSMPTools.GetBackend(), vtkSMPTools.GetEstimatedNumberOfThreads(), args.repeat))
    print("| DEM | cells | GDAL read | our read | ratio | VTK mesh | our mesh | ratio | "
          "our Mcells/s |")
    print("|---|---|---|---|---|---|---|---|---|")
    for path in dems:
        image = our_read(path)
        nx, ny, _ = image.GetDimensions()
        gdal_read(path)  # warm the file cache for both readers
        t_gdal = median_time(lambda: gdal_read(path), args.repeat)
        t_read = median_time(lambda: our_read(path), args.repeat)
        t_vtk = median_time(lambda: vtk_mesh(image), args.repeat)
        t_mesh = median_time(lambda: our_mesh(image), args.repeat)
        print("| %s | %d x %d | %.3f | %.3f | %.2f | %.3f | %.3f | %.2f | %.1f |"
              % (os.path.basename(path), nx, ny, t_gdal, t_read, t_read / t_gdal, t_vtk,
                 t_mesh, t_mesh / t_vtk, nx * ny / t_mesh / 1e6))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
