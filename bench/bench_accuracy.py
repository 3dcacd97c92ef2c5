# SPDX-License-Identifier: BSD-3-Clause
"""How accurate are the peers of bench_bake.py? Horizons and sky-view values of ours, GRASS
`r.horizon` and SAGA's Sky View Factor (`saga_cmd ta_lighting 3`, METHOD 0) against a brute
force on the same cells, each in its own Earth model.

    build/bin/aperture-python bench/bench_accuracy.py [--size 1024] [--cells 300]
        [--output bench/results-accuracy.md] [--workdir DIR] [--no-install]

The DEMs: bench_bake.py's synthetic fractal one (30 m cells, UTM 16N, rough down to the cell
with 0.5 m of noise; made in --workdir, or reused from there) at --radius, and Big Tujunga
(../shared/data/dem, when present; SRTM, 30 m) at 5 km, where its 643 rows leave an interior.
The cells are drawn at random (seeded) among those whose whole search radius lies inside the
DEM, so that no tool's edge handling enters. The reference marches each cell's ray at every
sector's centre azimuth (360 d / D clockwise from grid north for the peers; from true north for
ours, turned by the meridian convergence at the DEM's centre as ours does) in steps of 1/500
of a cell on the bilinear surface through the cell centres (and log-spaced steps down to 1e-5 of
a cell next to it: the largest slope is often the surface's own at t -> 0), out to the radius,
and takes the largest (z - z0) / t - c t, where c is the tool's own curvature term:
- ours: (1 - 0.13) / 2R (curvature with refraction, the default; R = 6371 km here, ours takes
  R from the ellipsoid at the DEM's latitude, a difference below 1e-4 degree at 10 km), and 0
  with --no-curvature;
- GRASS r.horizon: 1 / 2R (its curvature correction, without refraction);
- SAGA: 0 (no curvature).
The bilinear surface is the issue's definition of the terrain (its accuracy bounds: horizon
mean absolute error <= 0.05 degree, 99th percentile <= 0.5, SkyViewFactor mean error
<= 0.002). The peers step along their rays about a cell at a time and read the DEM's cells
there (SAGA rounds to the nearest cell, by its source; GRASS's horizons come out the same in
neighbouring directions wherever the first cells decide), and neither sees the surface's own
slope at t -> 0; so part of their difference is their model of the terrain, not a fault.

Compared: horizon angles clamped at 0 (h+, degrees: what the sky-view values use; GRASS's
maps converted from its counter-clockwise-from-east directions), SkyViewFactor 1 - mean sin h+
(ours; GRASS's from its horizons) and SAGA's "Visible Sky" 100 mean (1 - h+ / 90 deg), the
only SAGA output that depends on the horizons alone (its SVF also uses its own slope and
aspect), against the same formula on the reference horizons and on ours without curvature.
Needs Debian's grass-core and saga (installed with apt-get unless --no-install; a missing peer
is skipped).
"""
import argparse
import glob
import math
import os
import shutil
import subprocess
import sys

import numpy as np
from osgeo import gdal, osr

import bench_bake

gdal.UseExceptions()

EARTH_R = 6371000.0
GRASS_SCRIPT = """\
set -e
r.in.gdal -o input="$1" output=dem --quiet
g.region raster=dem
r.horizon elevation=dem step="$3" maxdistance="$4" output=hz --quiet
for m in $(g.list type=raster pattern='hz_*'); do
  r.out.gdal input="$m" output="$2/$m.tif" format=GTiff type=Float64 --quiet
done
"""


def read_bands(path):
    ds = gdal.Open(path)
    out = {}
    for b in range(1, ds.RasterCount + 1):
        band = ds.GetRasterBand(b)
        out[band.GetDescription() or str(b)] = band.ReadAsArray().astype(np.float64)
    ds = None
    return out


def band1(path):
    ds = gdal.Open(path)
    a = ds.GetRasterBand(1).ReadAsArray().astype(np.float64)
    ds = None
    return a


def grid_azimuth_of_north(dem):
    """The grid azimuth (radians, clockwise from grid north) of true north at the DEM's
    centre."""
    ds = gdal.Open(dem)
    gt, nx, ny = ds.GetGeoTransform(), ds.RasterXSize, ds.RasterYSize
    srs = ds.GetSpatialRef()
    ds = None
    x, y = gt[0] + 0.5 * nx * gt[1], gt[3] + 0.5 * ny * gt[5]
    geo = srs.CloneGeogCS()
    geo.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    srs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    lon, lat, _ = osr.CoordinateTransformation(srs, geo).TransformPoint(x, y)
    x1, y1, _ = osr.CoordinateTransformation(geo, srs).TransformPoint(lon, lat + 1e-4)
    return math.atan2(x1 - x, y1 - y)


def brute_force(z, cell, rows, cols, azimuths, radius, curvatures, step=0.002):
    """The horizon angle (degrees) of each cell's ray, per cell and azimuth, for each curvature
    term c of `curvatures`: the largest (z - z0) / t - c t over samples at every `step` cells
    along the ray, and log-spaced ones down to 1e-5 of a cell next to it (on the bilinear
    surface the largest slope is often its limit at t -> 0, the terrain's own slope). Returns
    one array [cells, azimuths] per curvature term."""
    ny, nx = z.shape
    t = np.concatenate((np.geomspace(1e-5, step, 40, endpoint=False),
                        np.arange(1, int(radius / (step * cell)) + 1) * step)) * cell  # metres
    out = [np.empty((len(rows), len(azimuths))) for _ in curvatures]
    for n, (r, c) in enumerate(zip(rows, cols)):
        z0 = z[r, c]
        for k, a in enumerate(azimuths):
            x = c + t * math.sin(a) / cell
            y = r - t * math.cos(a) / cell  # rows run south
            i0 = np.clip(np.floor(x).astype(int), 0, nx - 2)
            j0 = np.clip(np.floor(y).astype(int), 0, ny - 2)
            fx, fy = x - i0, y - j0
            zz = ((1 - fy) * ((1 - fx) * z[j0, i0] + fx * z[j0, i0 + 1]) +
                  fy * ((1 - fx) * z[j0 + 1, i0] + fx * z[j0 + 1, i0 + 1]))
            slope = (zz - z0) / t
            for o, curv in zip(out, curvatures):
                o[n, k] = math.degrees(math.atan((slope - curv * t).max()))
    return out


def stats(err):
    a = np.abs(err).ravel()
    return dict(mae=a.mean(), p99=np.percentile(a, 99), max=a.max(), bias=err.mean())


def svf(hdeg):  # 1 - mean sin h+
    return 1.0 - np.sin(np.radians(np.maximum(hdeg, 0.0))).mean(axis=-1)


def visible_sky(hdeg):  # SAGA's "Visible Sky", percent
    return 100.0 * (1.0 - np.maximum(hdeg, 0.0) / 90.0).mean(axis=-1)


def run(cmd, log, env=None):
    with open(log, "w") as f:
        r = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT, env=env)
    if r.returncode != 0:
        with open(log) as f:
            sys.stderr.write("failed (%d): %s\n%s\n" % (r.returncode, " ".join(cmd),
                                                          f.read()[-2000:]))
    return r.returncode == 0


def compare(args, missing, dem, radius, work):
    """Rows of the report for `dem` at `radius` metres (see the module's docstring)."""
    os.makedirs(work)
    z = band1(dem)
    ds = gdal.Open(dem)
    cell = ds.GetGeoTransform()[1]
    ds = None
    D = args.directions
    azimuths = np.radians(360.0 * np.arange(D) / D)
    margin = int(math.ceil(radius / cell)) + 2
    rng = np.random.default_rng(args.seed)
    rows = rng.integers(margin, z.shape[0] - margin, args.cells)
    cols = rng.integers(margin, z.shape[1] - margin, args.cells)
    print("reference: %d cells x %d directions, %g m" % (args.cells, D, radius), flush=True)
    # the peers look along grid azimuths; ours along true ones (the meridian convergence at
    # the DEM's centre turns them: grid azimuth = true azimuth + beta)
    beta = grid_azimuth_of_north(dem)
    print("grid azimuth of true north at the centre: %.4f degrees" % math.degrees(beta))
    c_ours, c_grass = (1.0 - 0.13) / (2.0 * EARTH_R), 1.0 / (2.0 * EARTH_R)
    ref_flat, ref_grass = brute_force(z, cell, rows, cols, azimuths, radius, (0.0, c_grass))
    ref_ours, ref_ours_flat = brute_force(z, cell, rows, cols, azimuths + beta, radius,
                                          (c_ours, 0.0))

    results = []  # (tool, model, horizon stats, sky-view quantity, its stats)
    # ours, default and flat
    for flat in (False, True):
        out = os.path.join(work, "ours%s.tif" % ("_flat" if flat else ""))
        cmd = [args.aperture, "bake", dem, out, "--directions", str(D), "--radius",
               "%g" % radius, "--products", "HorizonAngles", "-q"]
        if flat:
            cmd.append("--no-curvature")
        if not run(cmd, out + ".log"):
            continue
        bands = read_bands(out)
        names = sorted((n for n in bands if n.startswith("HorizonAngles")),
                       key=lambda n: float(n.split("az")[-1]))
        h = np.stack([bands[n][rows, cols] for n in names], axis=1)
        r = ref_ours_flat if flat else ref_ours
        hp, rp = np.maximum(h, 0), np.maximum(r, 0)
        if flat:
            results.append(("ours, --no-curvature", "flat", stats(hp - rp), "Visible Sky (%)",
                            stats(visible_sky(h) - visible_sky(r))))
        else:
            results.append(("ours", "curvature, k = 0.13", stats(hp - rp), "SkyViewFactor",
                            stats(svf(h) - svf(r))))
    # GRASS
    if "grass" not in missing:
        script = os.path.join(work, "grass.sh")
        with open(script, "w") as f:
            f.write(GRASS_SCRIPT)
        maps = os.path.join(work, "grass")
        os.makedirs(maps)
        tmp = os.path.join(work, "grass-tmp")
        os.makedirs(tmp)
        ok = run(["grass", "--tmp-location", dem, "--exec", "sh", script, dem, maps,
                  "%g" % (360.0 / D), "%g" % radius], os.path.join(work, "grass.log"),
                 dict(os.environ, TMPDIR=tmp))
        files = glob.glob(os.path.join(maps, "hz_*.tif"))
        if ok and len(files) == D:
            h = np.zeros((args.cells, D))
            for path in files:
                # hz_011_25: 11.25 degrees counter-clockwise from east -> azimuth 90 - 11.25
                ccw = float(os.path.basename(path)[3:-4].replace("_", "."))
                d = int(round(((90.0 - ccw) % 360.0) / (360.0 / D))) % D
                h[:, d] = np.degrees(band1(path)[rows, cols])
            hp, rp = np.maximum(h, 0), np.maximum(ref_grass, 0)
            results.append(("GRASS r.horizon", "curvature, no refraction", stats(hp - rp),
                            "SkyViewFactor", stats(svf(h) - svf(ref_grass))))
        else:
            sys.stderr.write("GRASS: %d horizon maps, not %d\n" % (len(files), D))
    # SAGA
    if "saga_cmd" not in missing:
        vis, svf_out = os.path.join(work, "saga_visible.tif"), os.path.join(work, "saga_svf.tif")
        if run(["saga_cmd", "ta_lighting", "3", "-DEM", dem, "-VISIBLE", vis, "-SVF", svf_out,
                "-RADIUS", "%g" % radius, "-NDIRS", str(D), "-METHOD", "0"],
               os.path.join(work, "saga.log")):
            v = band1(vis)[rows, cols]
            results.append(("SAGA Sky View Factor", "flat", None, "Visible Sky (%)",
                            stats(v - visible_sky(ref_flat))))

    return results


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--size", type=int, default=1024, help="synthetic DEM, cells a side")
    p.add_argument("--cells", type=int, default=300, help="cells compared (default 300)")
    p.add_argument("--directions", type=int, default=32)
    p.add_argument("--radius", type=float, default=10000.0, help="metres (default 10000)")
    p.add_argument("--seed", type=int, default=20240607, help="synthetic DEM seed")
    p.add_argument("--workdir", default="/tmp/aperture-bench-bake")
    p.add_argument("--output", default=None, help="also write the Markdown report here")
    p.add_argument("--no-install", action="store_true")
    p.add_argument("--aperture", default=os.path.join(bench_bake.REPO, "build", "bin", "aperture"))
    args = p.parse_args()
    work = os.path.join(args.workdir, "accuracy")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    missing = bench_bake.ensure_packages(["saga_cmd", "grass"], not args.no_install)

    cases = [("the %d^2 synthetic DEM" % args.size,
              bench_bake.synthetic_dem(args.workdir, args.size, 2.2, args.seed), args.radius)]
    if os.path.exists(bench_bake.BIGTUJUNGA):  # (1197 x 643: 5 km leaves an interior)
        cases.append(("Big Tujunga (SRTM, 30 m)", bench_bake.BIGTUJUNGA, 5000.0))
    D = args.directions
    lines = ["Accuracy against a brute force on the bilinear surface (bench/bench_accuracy.py): "
             "%d random cells whose whole search radius lies inside the DEM, %d directions; "
             "horizon errors of h+ = max(h, 0) in degrees over all cell-directions, each tool "
             "against the reference in its own Earth model." % (args.cells, D), "",
             "| DEM, radius | tool | Earth model | horizon MAE | p99 | max | mean bias | "
             "sky-view quantity | its MAE | p99 | max | mean bias |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for k, (name, dem, radius) in enumerate(cases):
        for tool, model, hs, q, qs in compare(args, missing, dem, radius,
                                              os.path.join(work, str(k))):
            h = ("%.4f | %.3f | %.2f | %+.4f" % (hs["mae"], hs["p99"], hs["max"], hs["bias"])
                 if hs else "- | - | - | -")
            lines.append("| %s, %g km | %s | %s | %s | %s | %.5f | %.4f | %.3f | %+.5f |" % (
                name, radius / 1000.0, tool, model, h, q, qs["mae"], qs["p99"], qs["max"],
                qs["bias"]))
    report = "\n".join(lines) + "\n"
    print(report)
    if args.output:
        with open(args.output, "w") as f:
            f.write(report)


if __name__ == "__main__":
    main()
