# SPDX-License-Identifier: BSD-3-Clause
"""Benchmark: the sky filter streamed in pieces against the whole run, measured in the same run.

    build/bin/aperture-python bench/bench_pieces.py [--size 1024] [--pieces 4] [--repeat 3]
        [--radii 10000,0] [--threads 2] [--workdir /tmp/aperture-bench-bake]

A streaming consumer (UpdatePiece, ParaView's ranks) asks vtkApertureSkyVisibility for pieces;
each reads its extent plus a halo of the search distance (the whole DEM without one) and should
compute its own cells only, so N pieces should cost about one whole run. For each radius the
script times the whole update and the N piece updates (each piece in a fresh pipeline behind
the DEM reader, reading included on both sides), interleaved, and reports the medians and
their ratio (pieces / whole: 1.0 is ideal; a filter that computed its halo too would take
about N times as long without a radius). The DEM is bench_bake.py's synthetic fractal one
(N x N cells of 30 m), made in --workdir when missing.
"""
import argparse
import os
import statistics
import sys
import time

import aperture

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_bake import synthetic_dem  # noqa: E402  (the same DEM as the bake benchmark)


def sky_update(path, radius, threads, piece=None, pieces=1):
    reader = aperture.vtkApertureDEMReader()
    reader.SetFileName(path)
    sky = aperture.vtkApertureSkyVisibility()
    sky.SetInputConnection(reader.GetOutputPort())
    sky.SetMaximumDistance(radius)
    sky.SetNumberOfThreads(threads)
    t = time.perf_counter()
    if piece is None:
        sky.Update()
    else:
        sky.UpdatePiece(piece, pieces, 0)
    elapsed = time.perf_counter() - t
    if sky.GetErrorCode() or sky.GetOutput().GetNumberOfPoints() == 0:
        raise SystemExit("the sky filter failed on %s" % path)
    return elapsed


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--size", type=int, default=1024)
    parser.add_argument("--pieces", type=int, default=4)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--radii", default="10000,0", help="metres, 0 = unlimited")
    parser.add_argument("--threads", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--workdir", default="/tmp/aperture-bench-bake")
    args = parser.parse_args()
    os.makedirs(args.workdir, exist_ok=True)
    path = synthetic_dem(args.workdir, args.size, 2.2, 20240607)
    print("%s, %d pieces, %d threads, median of %d interleaved runs"
          % (os.path.basename(path), args.pieces, args.threads, args.repeat))
    for radius in (float(r) for r in args.radii.split(",")):
        whole, streamed = [], []
        for _ in range(args.repeat):
            whole.append(sky_update(path, radius, args.threads))
            streamed.append(sum(sky_update(path, radius, args.threads, k, args.pieces)
                                for k in range(args.pieces)))
        w, s = statistics.median(whole), statistics.median(streamed)
        print("radius %s: whole %.2f s, %d pieces %.2f s, pieces / whole %.2f"
              % ("unlimited" if radius <= 0 else "%g m" % radius, w, args.pieces, s, s / w))


if __name__ == "__main__":
    main()
