# SPDX-License-Identifier: BSD-3-Clause
"""The whole lighting pipeline by hand, as a VTK script: read a DEM, bake what each cell sees
of the sky, mesh it, place the sun for a time and zone, and shade the mesh with the sun and
the sky through each point's aperture.

    xvfb-run -a build/bin/aperture-python Examples/lit_terrain.py [DEM] [--at ISO] [--tz ZONE]
        [--sun-scale S] [--exposure EV] [-o lit.png]
    (installed, /usr/bin/python3 in place of build/bin/aperture-python)

Shows: vtkApertureDEMReader -> vtkApertureSkyVisibility -> vtkApertureTerrainMesh ->
vtkApertureLightingMapper, with vtkApertureSolarPosition giving the sun's direction in the
mesh frame, its colour and strength, and the sky's radiance."""
import argparse
import math
import re
import sys

from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkRenderer, vtkRenderWindow,
                                         vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (OpenGL implementations)

import aperture


def get_program_parameters():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("dem", nargs="?", help="DEM raster (default: the embedded DEM)")
    parser.add_argument("--at", default="2026-10-15T16:00", help="local time (ISO 8601)")
    parser.add_argument("--tz", default="America/New_York",
                        help="IANA time zone (default: the embedded DEM's; give another DEM's)")
    parser.add_argument("--sun-scale", type=float, default=1.0)
    parser.add_argument("--exposure", type=float,
                        help="EV (default: automatic, aperture.scene.auto_exposure)")
    parser.add_argument("-o", "--output", default="lit.png")
    return parser.parse_args()


def main():
    args = get_program_parameters()

    # 1. read, 2. bake the aperture (only the two arrays the lighting needs), 3. mesh
    reader = aperture.vtkApertureDEMReader()
    reader.SetFileName(args.dem or aperture.default_dem())
    sky = aperture.vtkApertureSkyVisibility()
    sky.SetInputConnection(reader.GetOutputPort())
    for name in ("VisibleSolidAngle", "SkyViewFactor", "DiffuseSkyFactor", "PositiveOpenness",
                 "EdgeTruncated"):
        getattr(sky, "SetCompute" + name)(False)
    mesher = aperture.vtkApertureTerrainMesh()
    mesher.SetInputConnection(sky.GetOutputPort())
    mesher.SetVerticalExaggeration(2.0)
    mesher.Update()
    if mesher.GetOutput().GetNumberOfPoints() == 0:  # (VTK printed the filters' error)
        raise SystemExit("lit_terrain: no terrain to light from %s"
                         % (args.dem or "the embedded DEM"))

    # 4. the sun for the DEM's centre (the origin of the mesh frame)
    sun = aperture.vtkApertureSolarPosition()
    sun.SetTimeZone(args.tz)
    if not sun.SetTime(args.at) or not sun.SetPlaceFromImage(reader.GetOutput()) \
            or not sun.Compute():
        raise SystemExit(sun.GetErrorMessage())
    direction, sun_rgb, mean, sky_irradiance = [0.0] * 3, [0.0] * 3, [0.0] * 3, [0.0] * 3
    sun.GetDirection(direction)
    sun.GetSunColor(sun_rgb)
    # a uniform sky with the model's irradiance on a horizontal surface
    sun.GetSkyCap([0, 0, 1], 90.0, [0, 0, 1], mean, sky_irradiance)
    print("sun: azimuth %.2f, elevation %.2f deg, %.0f W/m2 direct normal"
          % (sun.GetAzimuth(), sun.GetElevation(), sun.GetDirectNormalIrradiance()))
    if sun.GetElevation() < 0.0:  # (the sky models have no twilight: a black terrain)
        offset = re.search(r"(Z|[+-][0-9:]+)$", args.at.split("T")[-1])  # (--tz unused)
        print("warning: the sun is %.2f degrees below the horizon at %s%s: the terrain is "
              "unlit (black); give the DEM's local time and zone with --at and --tz"
              % (-sun.GetElevation(), args.at, "" if offset else " in " + args.tz),
              file=sys.stderr)

    # 5. the mapper: uniforms only, so moving the sun later costs one draw
    mapper = aperture.vtkApertureLightingMapper()
    mapper.SetInputConnection(mesher.GetOutputPort())
    mapper.ScalarVisibilityOff()
    mapper.SetSunDirection(direction)
    mapper.SetSunAngularRadius(sun.GetAngularRadius())
    mapper.SetSunScale(args.sun_scale)
    mapper.SetSunIrradiance(*sun_rgb)
    mapper.SetSkyRadiance(*[v / math.pi for v in sky_irradiance])
    sky_rgb = [v / math.pi for v in sky_irradiance]
    if args.exposure is None:
        from aperture.scene import auto_exposure
        args.exposure = auto_exposure(sun_rgb, sun.GetElevation(), sky_rgb)
    mapper.SetExposure(args.exposure)
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(0.55, 0.52, 0.42)  # albedo

    renderer = vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(0.92, 0.94, 0.97)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(900, 600)
    window.AddRenderer(renderer)
    renderer.ResetCamera()
    renderer.GetActiveCamera().Elevation(-55)
    renderer.ResetCamera()
    renderer.GetActiveCamera().Zoom(1.3)
    window.Render()

    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.Update()
    writer = vtkPNGWriter()
    writer.SetFileName(args.output)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    print("wrote", args.output)


if __name__ == "__main__":
    main()
