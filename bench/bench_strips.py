# SPDX-License-Identifier: BSD-3-Clause
"""Benchmark: `aperture bake` in strips (a bake that does not fit in memory) against at once.

    build/bin/aperture-python bench/bench_strips.py [--size 2048] [--repeat 3]
        [--radii 3000,20000,unlimited] [--workdir /tmp/aperture-bench-bake]

A bake whose products and sweep do not fit in memory (or in --max-memory) is written in strips
of 256-row tiles, each reading its rows plus the DEM within the radius around them. For each
radius the script runs the whole command at once and with a --max-memory that allows strips of
256 rows only (the largest budget below two tile rows' need, from the byte counts the
documentation gives), interleaved, under /usr/bin/time -v, and reports the median seconds,
the median peak resident memory and their ratios (strips / at once), and checks that the two
GeoTIFFs hold the same values. The DEM is bench_bake.py's synthetic fractal one (N x N cells
of 30 m), made in --workdir when missing.
"""
import argparse
import math
import os
import re
import statistics
import subprocess
import sys
import time

import numpy as np
from osgeo import gdal

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_bake import synthetic_dem  # noqa: E402  (the same DEM as the bake benchmark)

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
APERTURE = os.path.join(REPO, "build", "bin", "aperture")


def bake(dem, out, radius, max_memory=None):
    """(seconds, peak resident bytes, stdout) of one bake."""
    # (no -q: its summary line on stdout says whether it ran in strips; stderr is not a
    # terminal, so there is no progress display)
    command = ["/usr/bin/time", "-v", APERTURE, "bake", dem, out]
    if radius:
        command += ["--radius", str(radius)]
    if max_memory:
        command += ["--max-memory", "%dK" % (max_memory // 1024)]
    t = time.perf_counter()
    p = subprocess.run(command, capture_output=True, text=True)
    elapsed = time.perf_counter() - t
    if p.returncode:
        raise SystemExit("bake failed: %s" % p.stderr)
    peak = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", p.stderr).group(1))
    return elapsed, peak * 1024, p.stdout


def same_values(a, b):
    da, db = gdal.Open(a), gdal.Open(b)
    same = da.RasterCount == db.RasterCount and all(
        np.array_equal(da.GetRasterBand(k).ReadAsArray(), db.GetRasterBand(k).ReadAsArray(),
                       equal_nan=True) for k in range(1, da.RasterCount + 1))
    da = db = None
    return same


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--size", type=int, default=2048)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--radii", default="3000,20000,unlimited",
                        help="metres, or 'unlimited' (no --radius)")
    parser.add_argument("--workdir", default="/tmp/aperture-bench-bake")
    args = parser.parse_args()
    if not os.path.exists(APERTURE):
        raise SystemExit("%s is not built (run with build/bin/aperture-python)" % APERTURE)
    os.makedirs(args.workdir, exist_ok=True)
    dem = synthetic_dem(args.workdir, args.size, 2.2, 20240607)
    n = args.size
    print("%s, the default products, 32 directions, all cores; median of %d interleaved runs"
          % (os.path.basename(dem), args.repeat))
    print("| radius | at once | strips of 256 rows | time ratio | peak memory at once | "
          "in strips | ratio |")
    print("|---|---|---|---|---|---|---|")
    for radius in (None if r == "unlimited" else float(r) for r in args.radii.split(",")):
        # The sky filter's need (vtkApertureSkyVisibility.h): 21 bytes a cell it reads (its
        # float copy of the elevations and the sweep's state) and 41 a cell it computes (the
        # seven default products, EdgeTruncated as float beside its byte flags, and the
        # strip's copy of the elevations). A strip of r rows reads r + 2 halo rows, the halo
        # the radius over the 30 m cells and 2 more; a budget just below 512 rows' need leaves
        # 256-row strips.
        halo = math.ceil(radius / 30.0) + 2 if radius else n  # (unlimited: all of the DEM)
        need = lambda rows: 21.0 * n * min(n, rows + 2 * halo) + 41.0 * n * rows
        budget = int(need(512)) - 1024
        once, strips = [], []
        out_once = os.path.join(args.workdir, "strips-once.tif")
        out_strips = os.path.join(args.workdir, "strips-strips.tif")
        for _ in range(args.repeat):
            once.append(bake(dem, out_once, radius)[:2])
            result = bake(dem, out_strips, radius, budget)
            if "strips of 256 rows" not in result[2]:
                raise SystemExit("not baked in 256-row strips: %s" % result[2])
            strips.append(result[:2])
        if not same_values(out_once, out_strips):
            raise SystemExit("the strips' GeoTIFF differs from the one at once")
        t1, t2 = (statistics.median(s for s, _ in runs) for runs in (once, strips))
        m1, m2 = (statistics.median(m for _, m in runs) for runs in (once, strips))
        print("| %s | %.2f s | %.2f s | %.2f | %.0f MB | %.0f MB | %.2f |"
              % ("%g km" % (radius / 1000) if radius else "unlimited", t1, t2, t2 / t1,
                 m1 / 1e6, m2 / 1e6, m2 / m1))


if __name__ == "__main__":
    main()
