# SPDX-License-Identifier: BSD-3-Clause
"""Benchmark: writing a bake's products, as a GeoTIFF and as an EXR, per codec and thread count.

    build/bin/aperture-python bench/bench_outputs.py [--size 1024] [--dem PATH] [--repeat 3]
        [--threads 1,2] [--horizons] [--workdir /tmp/aperture-bench-bake]

The sky filter runs once (10 km, 32 directions, the default products: nine float32 bands;
with --horizons also the 32 HorizonAngles), then each writer writes them with every codec in
turn, interleaved over --repeat rounds, and the script reports the median seconds, the
nanoseconds per band-cell and the file's size. The DEM is bench_bake.py's synthetic fractal
one (N x N cells of 30 m, made in --workdir when missing) unless --dem names another.
"""
import argparse
import os
import statistics
import sys
import time

import aperture

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_bake import synthetic_dem  # noqa: E402  (the same DEM as the bake benchmark)

GEOTIFF = [("DEFLATE", 1), ("ZSTD", 1), ("LZW", -1), ("NONE", -1)]
EXR = [("ZIP", 1), ("ZIP", 4), ("ZIPS", 1), ("PIZ", 1), ("RLE", 1), ("NONE", 1)]


def products(path, horizons):
    reader = aperture.vtkApertureDEMReader()
    reader.SetFileName(path)
    sky = aperture.vtkApertureSkyVisibility()
    sky.SetInputConnection(reader.GetOutputPort())
    sky.SetMaximumDistance(10000.0)
    sky.SetAnglesInDegrees(True)
    sky.SetFloatEdgeTruncated(True)
    sky.SetComputeHorizonAngles(horizons)
    sky.Update()
    image = sky.GetOutput()
    if sky.GetErrorCode() or image.GetNumberOfPoints() == 0:
        raise SystemExit("the sky filter failed on %s" % path)
    names = [image.GetPointData().GetArrayName(k)
             for k in range(image.GetPointData().GetNumberOfArrays())]
    names = [n for n in names if n != "Elevation"]
    bands = sum(image.GetPointData().GetArray(n).GetNumberOfComponents() for n in names)
    return image, names, bands


def write(kind, image, names, codec, level, threads, path):
    writer = aperture.vtkApertureDEMWriter() if kind == "GeoTIFF" else \
        aperture.vtkApertureEXRWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.SetCompression(codec)
    writer.SetCompressionLevel(level)
    writer.SetNumberOfThreads(threads)
    for name in names:
        writer.AddArrayName(name)
    t = time.perf_counter()
    ok = writer.Write()
    elapsed = time.perf_counter() - t
    if not ok:
        raise SystemExit("writing %s failed" % path)
    return elapsed, os.path.getsize(path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--size", type=int, default=1024)
    parser.add_argument("--dem", help="a DEM instead of the synthetic one")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--threads", default="1,2")
    parser.add_argument("--horizons", action="store_true", help="also the HorizonAngles")
    parser.add_argument("--workdir", default="/tmp/aperture-bench-bake")
    args = parser.parse_args()
    os.makedirs(args.workdir, exist_ok=True)
    path = args.dem or synthetic_dem(args.workdir, args.size, 2.2, 20240607)
    image, names, bands = products(path, args.horizons)
    cells = image.GetNumberOfPoints()
    print("%s: %d cells, %d bands; median of %d interleaved rounds"
          % (os.path.basename(path), cells, bands, args.repeat))
    runs = [(kind, codec, level, int(threads)) for threads in args.threads.split(",")
            for kind, codecs in (("GeoTIFF", GEOTIFF), ("EXR", EXR)) for codec, level in codecs]
    seconds = {run: [] for run in runs}
    sizes = {}
    out = os.path.join(args.workdir, "outputs")
    for _ in range(args.repeat):
        for run in runs:
            kind, codec, level, threads = run
            elapsed, sizes[run] = write(kind, image, names, codec, level, threads,
                                        out + (".tif" if kind == "GeoTIFF" else ".exr"))
            seconds[run].append(elapsed)
    print("| output | codec | level | threads | seconds | ns per band-cell | MB |")
    print("|---|---|---|---|---|---|---|")
    for run in runs:
        kind, codec, level, threads = run
        median = statistics.median(seconds[run])
        print("| %s | %s | %s | %d | %.3f | %.1f | %.1f |"
              % (kind, codec, level if level > 0 else "default", threads, median,
                 1e9 * median / (cells * bands), sizes[run] / 1e6))
    for suffix in (".tif", ".exr"):
        if os.path.exists(out + suffix):
            os.remove(out + suffix)


if __name__ == "__main__":
    main()
