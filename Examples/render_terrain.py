# SPDX-License-Identifier: BSD-3-Clause
"""Render a DEM with a hand-built VTK pipeline: reader -> terrain mesh -> Aperture's mapper
(its STANDARD model: VTK's lighting plus exposure; lit_terrain.py shows the aperture model)
-> actor -> renderer, lit by one directional "sun".

    xvfb-run -a build/bin/aperture-python Examples/render_terrain.py [DEM] [-o terrain.png]
    (installed, /usr/bin/python3 in place of build/bin/aperture-python)
"""
import argparse
import math

from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (
    vtkActor,
    vtkColorTransferFunction,
    vtkLight,
    vtkRenderer,
    vtkRenderWindow,
    vtkWindowToImageFilter,
)
# Registers the OpenGL implementations of the rendering classes.
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

import aperture


def get_program_parameters():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("dem", nargs="?", help="DEM raster (default: the embedded DEM)")
    parser.add_argument("-o", "--output", default="terrain.png")
    parser.add_argument("--sun-az", type=float, default=315.0, help="degrees from north")
    parser.add_argument("--sun-el", type=float, default=35.0, help="degrees above the horizon")
    return parser.parse_args()


def main():
    args = get_program_parameters()

    # 1. read and mesh (ENU metres, x east, y north, z up), heights exaggerated twice
    reader = aperture.vtkApertureDEMReader()
    reader.SetFileName(args.dem or aperture.default_dem())
    mesher = aperture.vtkApertureTerrainMesh()
    mesher.SetInputConnection(reader.GetOutputPort())
    mesher.SetVerticalExaggeration(2.0)
    mesher.Update()
    if mesher.GetOutput().GetNumberOfPoints() == 0:  # (VTK printed the reader's error)
        raise SystemExit("render_terrain: no terrain to render from %s"
                         % (args.dem or "the embedded DEM"))
    lo, hi = mesher.GetOutput().GetPointData().GetArray("Elevation").GetRange()

    # 2. colour by elevation through Aperture's mapper
    colors = vtkColorTransferFunction()
    colors.AddRGBPoint(lo, 0.25, 0.45, 0.25)
    colors.AddRGBPoint(hi, 0.90, 0.88, 0.85)
    mapper = aperture.vtkApertureLightingMapper()
    mapper.SetInputConnection(mesher.GetOutputPort())
    mapper.SetLookupTable(colors)
    mapper.SetScalarRange(lo, hi)
    mapper.SetLightingModel(mapper.STANDARD)  # (APERTURE, the default, needs a bake's arrays)
    mapper.SetExposure(0.3)
    actor = vtkActor()
    actor.SetMapper(mapper)

    # 3. a directional light from the sun's azimuth and elevation, in the mesh's ENU frame
    az, el = math.radians(args.sun_az), math.radians(args.sun_el)
    sun = vtkLight()
    sun.SetLightTypeToSceneLight()
    sun.SetPositional(False)
    sun.SetFocalPoint(0, 0, 0)
    sun.SetPosition(math.cos(el) * math.sin(az), math.cos(el) * math.cos(az), math.sin(el))
    renderer = vtkRenderer()
    renderer.AutomaticLightCreationOff()
    renderer.AddLight(sun)
    renderer.AddActor(actor)
    renderer.SetBackground(0.55, 0.65, 0.80)

    # 4. look north from the south, render off screen, save
    camera = renderer.GetActiveCamera()
    camera.SetPosition(0, -60000, 35000)
    camera.SetFocalPoint(0, 0, 0)
    camera.SetViewUp(0, 0, 1)
    renderer.ResetCamera()
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(800, 500)
    window.AddRenderer(renderer)
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    writer = vtkPNGWriter()
    writer.SetFileName(args.output)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    print("wrote", args.output)


if __name__ == "__main__":
    main()
