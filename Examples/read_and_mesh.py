# SPDX-License-Identifier: BSD-3-Clause
"""Read a DEM, look at its georeference, and build the terrain mesh in a local
East-North-Up frame (metres), as a VTK pipeline.

    build/bin/aperture-python Examples/read_and_mesh.py [DEM] [--exaggeration X] [-o mesh.vtp]
    (installed, /usr/bin/python3 in place of build/bin/aperture-python)

Shows: vtkApertureDEMReader -> vtkApertureTerrainMesh, the georeference in the field data,
cell size in metres, and the mesh frame."""
import argparse

from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

import aperture


def get_program_parameters():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("dem", nargs="?", help="DEM raster (default: the embedded DEM)")
    parser.add_argument("--exaggeration", type=float, default=1.0)
    parser.add_argument("-o", "--output", help="write the mesh as a .vtp file")
    return parser.parse_args()


def main():
    args = get_program_parameters()

    # 1. read: any single-band raster GDAL opens
    reader = aperture.vtkApertureDEMReader()
    reader.SetFileName(args.dem or aperture.default_dem())
    reader.Update()
    dem = reader.GetOutput()
    if dem.GetNumberOfPoints() == 0:  # (VTK printed the reader's error)
        raise SystemExit("read_and_mesh: no DEM read from %s" % (args.dem or "the embedded DEM"))

    # 2. georeference: CRS and grid, in metres at the centre
    geo = aperture.vtkApertureGeoreference()
    if not geo.SetFromImage(dem):
        raise SystemExit(geo.GetErrorMessage())
    size = [0.0, 0.0]
    geo.GetCellSizeMetres(size)
    print("%s: %d x %d cells of %.1f m x %.1f m, CRS %s"
          % (reader.GetFileName(), *geo.GetGridSize(), size[0], size[1], geo.GetCRSName()))

    # 3. mesh: ENU metres about the DEM centre, holes at nodata, normals, texture coordinates
    mesher = aperture.vtkApertureTerrainMesh()
    mesher.SetInputConnection(reader.GetOutputPort())
    mesher.SetVerticalExaggeration(args.exaggeration)
    mesher.Update()
    mesh = mesher.GetOutput()
    lat, lon, h = (mesh.GetFieldData().GetArray("FrameOrigin").GetValue(k) for k in range(3))
    b = mesh.GetBounds()
    print("mesh: %d triangles, frame origin %.6f N %.6f E %.0f m, extent %.1f km east x "
          "%.1f km north, z %.0f .. %.0f m"
          % (mesh.GetNumberOfCells(), lat, lon, h, (b[1] - b[0]) / 1000, (b[3] - b[2]) / 1000,
             b[4], b[5]))

    # 4. write (optional)
    if args.output:
        writer = vtkXMLPolyDataWriter()
        writer.SetFileName(args.output)
        writer.SetInputData(mesh)
        writer.Write()
        print("wrote", args.output)


if __name__ == "__main__":
    main()
