# SPDX-License-Identifier: BSD-3-Clause
"""An interactive viewer of a DEM lit by the sun through the day: a slider sets the local time
of day, the Left/Right keys move it by 15 minutes, Up/Down change the exposure by 1/2 EV.
Moving the sun only changes the mapper's uniforms: no geometry is uploaded again.

    build/bin/aperture-python Examples/time_of_day_viewer.py [DEM] [--date 2026-06-21] [--tz ZONE]
    (installed, /usr/bin/python3 in place of build/bin/aperture-python)

Without a display, or to check it in a script: --frames N -o last.png steps through N times of
day (06:00 to 18:00) off screen and writes the last frame; with a frame number in the name,
-o 'frame-%03d.png', it writes every frame, a time-lapse."""
import argparse
import math

from vtkmodules.vtkInteractionWidgets import vtkSliderRepresentation2D, vtkSliderWidget
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkRenderer, vtkRenderWindow,
                                         vtkRenderWindowInteractor, vtkTextActor,
                                         vtkWindowToImageFilter)
import vtkmodules.vtkInteractionStyle  # noqa: F401
import vtkmodules.vtkRenderingFreeType  # noqa: F401
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

import aperture


class Viewer:
    def __init__(self, args):
        reader = aperture.vtkApertureDEMReader()
        reader.SetFileName(args.dem or aperture.default_dem())
        sky = aperture.vtkApertureSkyVisibility()
        sky.SetInputConnection(reader.GetOutputPort())
        mesher = aperture.vtkApertureTerrainMesh()
        mesher.SetInputConnection(sky.GetOutputPort())
        mesher.SetVerticalExaggeration(2.0)
        mesher.Update()
        if mesher.GetOutput().GetNumberOfPoints() == 0:  # (VTK printed the filters' error)
            raise SystemExit("time_of_day_viewer: no terrain to show from %s"
                             % (args.dem or "the embedded DEM"))
        self.date, self.hour = args.date, 12.0
        self.sun = aperture.vtkApertureSolarPosition()
        # (refused up front: each frame would otherwise say why under the mapper's default sun)
        if not self.sun.SetTimeZone(args.tz) or not self.sun.SetTime(args.date + "T12:00"):
            raise SystemExit("time_of_day_viewer: " + self.sun.GetErrorMessage())
        if not self.sun.SetPlaceFromImage(reader.GetOutput()):
            raise SystemExit("time_of_day_viewer: " + self.sun.GetErrorMessage())
        self.mapper = aperture.vtkApertureLightingMapper()
        self.mapper.SetInputConnection(mesher.GetOutputPort())
        self.mapper.ScalarVisibilityOff()
        self.mapper.SetExposure(-7.5)
        actor = vtkActor()
        actor.SetMapper(self.mapper)
        actor.GetProperty().SetColor(0.55, 0.52, 0.42)
        self.label = vtkTextActor()
        self.label.SetPosition(10, 10)
        self.label.GetTextProperty().SetFontSize(16)
        self.label.GetTextProperty().SetColor(0.1, 0.1, 0.15)
        self.renderer = vtkRenderer()
        self.renderer.AddActor(actor)
        self.renderer.AddActor2D(self.label)
        self.renderer.SetBackground(0.92, 0.94, 0.97)
        self.window = vtkRenderWindow()
        self.window.SetSize(1000, 700)
        self.window.AddRenderer(self.renderer)
        self.renderer.ResetCamera()
        self.renderer.GetActiveCamera().Elevation(-55)
        self.renderer.ResetCamera()

    def set_hour(self, hour):
        """Place the sun at `hour` (local, 0..24) of the date; fills the label."""
        minutes = max(0, min(24 * 60 - 1, int(round(60.0 * hour))))  # (to the nearest minute)
        self.hour = minutes / 60.0
        text = "%sT%02d:%02d" % ((self.date,) + divmod(minutes, 60))
        if not self.sun.SetTime(text):  # e.g. a local time a clock change skips
            self.label.SetInput(self.sun.GetErrorMessage())
            return
        self.sun.Compute()
        d, rgb, mean, irr = [0.0] * 3, [0.0] * 3, [0.0] * 3, [0.0] * 3
        self.sun.GetDirection(d)
        self.sun.GetSunColor(rgb)
        self.sun.GetSkyCap([0, 0, 1], 90.0, [0, 0, 1], mean, irr)
        self.mapper.SetSunDirection(d)
        self.mapper.SetSunIrradiance(*rgb)
        self.mapper.SetSkyRadiance(*[max(v / math.pi, 0.5) for v in irr])
        self.label.SetInput("%s  sun azimuth %.1f, elevation %.1f deg  (%.1f EV)" % (
            text, self.sun.GetAzimuth(), self.sun.GetElevation(), self.mapper.GetExposure()))

    def run(self):
        interactor = vtkRenderWindowInteractor()
        interactor.SetRenderWindow(self.window)
        rep = vtkSliderRepresentation2D()
        rep.SetMinimumValue(0.0)
        rep.SetMaximumValue(23.75)
        rep.SetValue(self.hour)
        rep.SetTitleText("local time (h)")
        rep.GetPoint1Coordinate().SetCoordinateSystemToNormalizedDisplay()
        rep.GetPoint1Coordinate().SetValue(0.1, 0.93)
        rep.GetPoint2Coordinate().SetCoordinateSystemToNormalizedDisplay()
        rep.GetPoint2Coordinate().SetValue(0.9, 0.93)
        slider = vtkSliderWidget()
        slider.SetInteractor(interactor)
        slider.SetRepresentation(rep)
        slider.SetAnimationModeToJump()

        def on_slide(widget, event):
            self.set_hour(widget.GetRepresentation().GetValue())
            self.window.Render()
        slider.AddObserver("InteractionEvent", on_slide)

        def on_key(obj, event):
            key = obj.GetKeySym()
            if key in ("Left", "Right"):
                self.set_hour(self.hour + (0.25 if key == "Right" else -0.25))
                rep.SetValue(self.hour)
            elif key in ("Up", "Down"):
                self.mapper.SetExposure(self.mapper.GetExposure() + (0.5 if key == "Up" else -0.5))
                self.set_hour(self.hour)
            else:
                return
            self.window.Render()
        interactor.AddObserver("KeyPressEvent", on_key)
        slider.EnabledOn()
        self.set_hour(self.hour)
        self.window.Render()
        interactor.Start()

    def frames(self, count, output):
        """Off screen: `count` times evenly from 06:00 to 18:00; writes the last frame to
        `output`, or every frame k to `output % k` when it holds a number format (%03d)."""
        numbered = False
        if "%" in output:
            try:
                try:
                    numbered = output % 0 != output % 1
                except TypeError:  # (no number in it: its %% signs only)
                    output = output % ()
            except (TypeError, ValueError):
                raise SystemExit("time_of_day_viewer: -o %s: a frame number is written %%d or "
                                 "%%03d, and a %% sign itself %%%%" % output)
        self.window.SetOffScreenRendering(1)
        uploads = None
        written = []
        for k in range(count):
            self.set_hour(6.0 + 12.0 * k / max(1, count - 1))
            self.window.Render()
            uploads = uploads or self.mapper.GetGeometryUploads()
            if numbered or k == count - 1:
                written.append(output % k if numbered else output)
                self.write_png(written[-1])
        assert self.mapper.GetGeometryUploads() == uploads, "the sun moved the geometry"
        print("%d frames, geometry uploaded %d time(s); wrote %s" % (
            count, uploads, written[0] if len(written) == 1 else
            "%s to %s" % (written[0], written[-1])))

    def write_png(self, path):
        grab = vtkWindowToImageFilter()
        grab.SetInput(self.window)
        grab.Update()
        writer = vtkPNGWriter()
        writer.SetFileName(path)
        writer.SetInputConnection(grab.GetOutputPort())
        writer.Write()


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("dem", nargs="?", help="DEM raster (default: the embedded DEM)")
    parser.add_argument("--date", default="2026-06-21", help="local date, YYYY-MM-DD")
    parser.add_argument("--tz", default="America/New_York", help="IANA time zone")
    parser.add_argument("--frames", type=int, help="off screen: render this many times of day")
    parser.add_argument("-o", "--output", default="viewer.png",
                        help="with --frames: the last frame's PNG, or every frame's with a "
                             "frame number in the name (frame-%%03d.png)")
    args = parser.parse_args()
    if args.frames is not None and args.frames < 1:  # (0 fell through to the window)
        parser.error("--frames must be at least 1")
    viewer = Viewer(args)
    if args.frames is not None:
        viewer.frames(args.frames, args.output)
    else:
        viewer.run()


if __name__ == "__main__":
    main()
