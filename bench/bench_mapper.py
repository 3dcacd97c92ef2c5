# SPDX-License-Identifier: BSD-3-Clause
"""Benchmark: frame time of vtkApertureLightingMapper against VTK's default
vtkOpenGLPolyDataMapper with standard lighting, on the same terrain meshes, measured in the
same run (Mesa llvmpipe under Xvfb on these machines: a software rasteriser, so the numbers
are CPU-bound and only their ratios carry over to GPUs).

    xvfb-run -a -s "-screen 0 1920x1080x24" build/bin/aperture-python bench/bench_mapper.py \
        [--sizes 1,4] [--frames 30] [--output bench/results-mapper.md]

Meshes: a synthetic fractal DEM of 30 m cells with (about) 1 and 4 million triangles, baked
(BentNormal, ApertureRadius) and meshed by Aperture. Each contender renders --frames frames of
1920 x 1080 while the sun moves 10 degrees per frame (uniforms only; for VTK's mapper the
light moves), after two warm-up frames, the contenders' frames interleaved so that the
machine's drifts hit them alike; a frame ends when its pixels are read back (one pixel),
which waits for the rasteriser. Reported: median milliseconds per frame and the ratio to
VTK's default mapper (ours shading per pixel, exact and smoothstep, and per vertex); and the
smoothstep intersection's speed-up over the exact one.
"""
import argparse
import math
import os
import statistics
import sys
import time

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import (vtkActor, vtkLight, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

import aperture

HERE = os.path.dirname(os.path.abspath(__file__))


def fractal(n, seed=5):
    rng = np.random.default_rng(seed)
    f = np.fft.fftfreq(n)
    k = np.sqrt(f[:, None] ** 2 + f[None, :] ** 2)
    k[0, 0] = 1.0
    spectrum = (rng.normal(size=(n, n)) + 1j * rng.normal(size=(n, n))) * k ** -1.6
    spectrum[0, 0] = 0
    z = np.fft.ifft2(spectrum).real
    return ((z - z.min()) / (z.max() - z.min()) * 1500.0).astype(np.float32)


def terrain_mesh(million_triangles):
    n = int(round(math.sqrt(million_triangles * 1e6 / 2.0))) + 1
    image = vtkImageData()
    image.SetDimensions(n, n, 1)
    image.SetSpacing(30.0, 30.0, 1.0)
    image.SetOrigin(500000.0, 4000000.0, 0.0)
    z = numpy_to_vtk(fractal(n).ravel(), deep=1)
    z.SetName("Elevation")
    image.GetPointData().SetScalars(z)
    geo = aperture.vtkApertureGeoreference()
    geo.SetCRS("EPSG:32633")
    geo.AttachToImage(image)
    sky = aperture.vtkApertureSkyVisibility()
    sky.SetInputData(image)
    sky.SetMaximumDistance(5000.0)
    for name in ("VisibleSolidAngle", "SkyViewFactor", "DiffuseSkyFactor", "PositiveOpenness",
                 "EdgeTruncated"):
        getattr(sky, "SetCompute" + name)(False)
    mesher = aperture.vtkApertureTerrainMesh()
    mesher.SetInputConnection(sky.GetOutputPort())
    mesher.Update()
    return mesher.GetOutput()


class Contender:
    """One window rendering the mesh with one mapper."""

    def __init__(self, mesh, make_mapper, move_sun, size):
        from vtkmodules.vtkCommonCore import vtkUnsignedCharArray
        self.mapper = make_mapper()
        self.mapper.SetInputData(mesh)
        self.mapper.ScalarVisibilityOff()
        self.move_sun = move_sun
        actor = vtkActor()
        actor.SetMapper(self.mapper)
        actor.GetProperty().SetColor(0.6, 0.58, 0.5)
        renderer = vtkRenderer()
        renderer.AddActor(actor)
        renderer.AutomaticLightCreationOff()
        self.light = vtkLight()
        self.light.SetLightTypeToSceneLight()
        self.light.SetPositional(False)
        renderer.AddLight(self.light)
        self.window = vtkRenderWindow()
        self.window.SetOffScreenRendering(1)
        self.window.SetSize(*size)
        self.window.SetMultiSamples(0)
        self.window.AddRenderer(renderer)
        renderer.ResetCamera()
        renderer.GetActiveCamera().Elevation(-45)
        renderer.ResetCamera()
        self.pixel = vtkUnsignedCharArray()
        self.times = []

    def frame(self, k, record):
        az = math.radians(10.0 * k)
        d = (math.cos(0.6) * math.sin(az), math.cos(0.6) * math.cos(az), math.sin(0.6))
        self.move_sun(self.mapper, self.light, d)
        start = time.perf_counter()
        self.window.Render()
        self.window.GetPixelData(0, 0, 0, 0, 0, self.pixel, 0)  # read back: waits for the frame
        if record:
            self.times.append(time.perf_counter() - start)


def frame_times(contenders, frames):
    """Median ms per frame of each contender; their frames interleave (A, B, C, A, B, C, ...)
    so that the machine's drifts hit all of them alike. Two warm-up rounds."""
    for k in range(frames + 2):
        for c in contenders:
            c.frame(k, record=k >= 2)
    return [1000.0 * statistics.median(c.times) for c in contenders]


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sizes", default="1,4", help="million triangles (default 1,4)")
    parser.add_argument("--frames", type=int, default=30)
    parser.add_argument("--width", type=int, default=1920)
    parser.add_argument("--height", type=int, default=1080)
    parser.add_argument("--output", default=os.path.join(HERE, "results-mapper.md"))
    args = parser.parse_args()
    size = (args.width, args.height)

    def vtk_default():
        return vtkPolyDataMapper()

    def ours(mode, per_vertex=False):
        def make():
            m = aperture.vtkApertureLightingMapper()
            m.SetIntersectionMode(mode)
            m.SetExposure(-7.0)
            if per_vertex:
                m.SetShadingFrequency(m.PER_VERTEX)
            return m
        return make

    def move_light(mapper, light, d):
        light.SetPosition(*d)
        light.SetFocalPoint(0, 0, 0)

    def move_sun(mapper, light, d):
        mapper.SetSunDirection(*d)

    rows = []
    for millions in [float(s) for s in args.sizes.split(",") if s]:
        mesh = terrain_mesh(millions)
        tris = mesh.GetNumberOfPolys()
        contenders = [
            Contender(mesh, vtk_default, move_light, size),
            Contender(mesh, ours(aperture.vtkApertureLightingMapper.EXACT), move_sun, size),
            Contender(mesh, ours(aperture.vtkApertureLightingMapper.SMOOTHSTEP), move_sun, size),
            Contender(mesh, ours(aperture.vtkApertureLightingMapper.EXACT, True), move_sun,
                      size)]
        t_vtk, t_exact, t_smooth, t_vertex = frame_times(contenders, args.frames)
        del contenders
        rows.append((tris, t_vtk, t_exact, t_smooth, t_vertex))
        print("%.2f M triangles: VTK %.1f ms, ours exact %.1f ms (%.2fx), smoothstep %.1f ms, "
              "per vertex %.1f ms (%.2fx)" % (tris / 1e6, t_vtk, t_exact, t_exact / t_vtk,
                                              t_smooth, t_vertex, t_vertex / t_vtk), flush=True)
    lines = ["# vtkApertureLightingMapper vs VTK's default mapper", "",
             "%d x %d, %d frames (median), Mesa llvmpipe under Xvfb; %d cores." % (
                 size[0], size[1], args.frames, os.cpu_count()), "",
             "| triangles | VTK default ms | ours exact ms | ratio | ours smoothstep ms | "
             "smoothstep speed-up over exact | ours per vertex ms | ratio |",
             "|---|---|---|---|---|---|---|---|"]
    for tris, t_vtk, t_exact, t_smooth, t_vertex in rows:
        lines.append("| %.2f M | %.1f | %.1f | %.2f | %.1f | %.1f%% | %.1f | %.2f |" % (
            tris / 1e6, t_vtk, t_exact, t_exact / t_vtk, t_smooth,
            100.0 * (t_exact / t_smooth - 1.0), t_vertex, t_vertex / t_vtk))
    text = "\n".join(lines) + "\n"
    print(text)
    with open(args.output, "w") as f:
        f.write(text)


if __name__ == "__main__":
    sys.exit(main())
