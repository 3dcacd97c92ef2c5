# SPDX-License-Identifier: BSD-3-Clause
"""Benchmark: baking horizon angles / sky-view factor for every DEM cell, against peer tools
measured in the same run.

    build/bin/aperture-python bench/bench_bake.py [--quick] [--output bench/results-bake.md]
        [--ours TEMPLATE] [--no-ours] [--no-peers] [--peers-on-scaling] [--timeout S] ...

Every contender is an external command, timed with `/usr/bin/time -v` (wall seconds and peak
resident memory), one after the other on the same machine, with the same parameters: 32
directions and a 10 km search radius on a DEM in a projected, metric CRS.

Contenders:
- SAGA  `saga_cmd ta_lighting 3` (Sky View Factor), METHOD 0 ("cell size": the sector
  method, stepping one cell size along each of NDIRS directions and reading the nearest cell;
  not the multi-scale approximation; its accuracy: bench_accuracy.py), reading and writing
  GeoTIFF directly. Uses OpenMP (`saga_cmd --cores`).
- GRASS `r.horizon` (all 32 directions, `step=11.25 maxdistance=10000`) in a temporary
  location made from the DEM: `grass --tmp-location DEM --exec sh script` that imports with
  r.in.gdal, sets the region and runs r.horizon under its own `/usr/bin/time`, so the horizon
  computation is also reported alone ("compute s"). Single-threaded in GRASS 8.2. The 32 maps
  stay in GRASS's format (no export).
- ours: a command template (--ours), by default
  `{aperture} bake {dem} {out} --directions {directions} {radius_opt} {threads_opt}`, i.e.
  `aperture bake DEM OUT.tif --directions 32 --radius 10000 --threads N`. A contender whose
  command does not exist (or whose CLI has no `bake`) is recorded as "not available".

DEMs (made once in --workdir, reused by later runs):
- the embedded DEM (EPSG:4326, 3 arc-second) warped bilinearly to UTM 16N (EPSG:32616) at 90 m;
- a synthetic fractal DEM, N x N cells of 30 m in UTM 16N, made by seeded spectral synthesis
  (1-D profile spectrum ~ f^-beta, beta 2.2 by default: 2-D power ~ f^-(beta+1)), scaled to
  0-2000 m of relief plus 0.5 m of white noise; N = 1024 (512 with --quick);
- ../shared/data/dem/bigtujunga_srtm1_utm11n_30m.tif when present (1197 x 643, 30 m);
- any --dem given.

On each of these DEMs the contenders run in the order ours, ours on SAGA's job, SAGA, GRASS,
GRASS, SAGA, ours on SAGA's job, ours (--comparison-repeats 2, the default), so that a drift of
the VM's speed during the comparison weighs on all of them alike; the table gives each
contender's mean and a note every run. "Ours on SAGA's job" is the same command with
`--products DiffuseSkyFactor`: the one band SAGA's run writes (its "Sky View Factor" weighs by
the cell's slope, Haentzschel et al. 2005, as DiffuseSkyFactor does; runs before 2026-12-06
baked SkyViewFactor, which takes the same time), where ours writes nine bands by default;
SAGA's speed-up is given against both.

Missing peers (Debian packages saga, grass-core) and GNU time are installed with apt-get
first (as root, or through sudo) unless --no-install.

Then ours alone (skippable): on ../shared/data/dem/white_mountains_N44W072_srtm3_geo.tif when
present (lat/lon, 1201 x 1201) and on the same elevations relabelled as UTM with the same
metric cell sizes (the cost of the lat/lon code path); on 2048^2 and 4096^2 synthetic DEMs
(scaling with cells), on the 2048^2 one at radius 1 km, 10 km and unlimited (no --radius),
and with --threads 1 vs the default (parallel speed-up; then --thread-pairs more such pairs,
each run right after the other, reported with their median, since this is the number VM noise
moves most). Peers are not run on those large DEMs unless --peers-on-scaling: on 2 cores SAGA
took 381 s and GRASS 428 s on 2048^2, and 4096^2 (4x the cells) would come close to the
default 1800 s timeout.

Writes a Markdown table (stdout and --output) with, per DEM and contender: cells, parameters,
wall seconds, peak RSS in MiB, cell-directions per second (cells x directions / wall), and our
speed-up over each peer on the same DEM (peer wall seconds / our wall seconds; > 1 means ours
is faster); plus the CPU, core count and tool versions. Each run has a --timeout; failures are
recorded and the run goes on.
"""
import argparse
import datetime
import importlib.util
import json
import os
import re
import shlex
import shutil
import signal
import statistics
import subprocess
import sys
import time

import numpy
from osgeo import gdal, osr

gdal.UseExceptions()

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
GNU_TIME = "/usr/bin/time"
DEFAULT_OURS = "{aperture} bake {dem} {out} --directions {directions} {radius_opt} {threads_opt}"
BIGTUJUNGA = os.path.join(REPO, "..", "shared", "data", "dem", "bigtujunga_srtm1_utm11n_30m.tif")
LATLON = os.path.join(REPO, "..", "shared", "data", "dem", "white_mountains_N44W072_srtm3_geo.tif")
UTM16N = 32616
# SAGA's job for ours: the one product SAGA's runs write (SAGA_JOB_LABEL's table rows)
SAGA_JOB = ("--products", "DiffuseSkyFactor")
SAGA_JOB_LABEL = "ours, SAGA's output only"
# messages that mean "this CLI has no such command/option yet", as opposed to a failed run
NOT_AVAILABLE = ("invalid choice", "unrecognized arguments", "No such file or directory",
                 "command not found", "not found")

GRASS_SCRIPT = """\
# run by: grass --tmp-location DEM --exec sh THIS DEM TIMEFILE STEP MAXDISTANCE
set -e
r.in.gdal -o input="$1" output=dem --quiet
g.region raster=dem
{time} -v -o "$2" r.horizon elevation=dem step="$3" maxdistance="$4" output=hz --quiet
echo "HORIZON_MAPS=$(g.list type=raster pattern='hz_*' | wc -l)"
"""


# ---------------------------------------------------------------------------------------------
# tools

# program -> Debian package that provides it
PEER_PACKAGES = {"saga_cmd": "saga", "grass": "grass-core"}


def ensure_packages(programs, install):
    """Install (apt-get, as root or through sudo) the Debian packages of the programs that are
    missing. Returns the programs still missing afterwards."""
    missing = [p for p in programs if shutil.which(p) is None and not os.path.exists(p)]
    if not missing or not install:
        return missing
    packages = sorted({PEER_PACKAGES.get(p, "time" if p == GNU_TIME else p) for p in missing})
    sudo = [] if os.geteuid() == 0 else ["sudo"]
    print("installing Debian packages: %s" % " ".join(packages), flush=True)
    env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
    try:
        subprocess.run(sudo + ["apt-get", "update", "-qq"], check=True, env=env)
        subprocess.run(sudo + ["apt-get", "install", "-y", "-qq", "--no-install-recommends"]
                       + packages, check=True, env=env)
    except (OSError, subprocess.CalledProcessError) as e:
        print("warning: could not install %s: %s" % (" ".join(packages), e), file=sys.stderr)
    return [p for p in programs if shutil.which(p) is None and not os.path.exists(p)]


# ---------------------------------------------------------------------------------------------
# DEMs

def embedded_dem():
    """The embedded DEM of the `aperture` package, found without importing it (and VTK)."""
    spec = importlib.util.find_spec("aperture")
    if spec is None or not spec.submodule_search_locations:
        return None
    path = os.path.join(list(spec.submodule_search_locations)[0], "data",
                        "jacksboro_fault_dem.tif")
    return path if os.path.exists(path) else None


def warp_to_utm(src, dst, epsg, cell):
    """gdalwarp -t_srs EPSG:epsg -tr cell cell -tap -r bilinear -dstnodata -9999 src dst"""
    if not os.path.exists(dst):
        gdal.Warp(dst + ".part.tif", src, format="GTiff", dstSRS="EPSG:%d" % epsg,
                  xRes=cell, yRes=cell, targetAlignedPixels=True, resampleAlg="bilinear",
                  dstNodata=-9999, outputType=gdal.GDT_Float32)
        os.replace(dst + ".part.tif", dst)
    return dst


def same_cells_as_utm(src, dst, aperture):
    """The elevations of a lat/lon DEM relabelled as a UTM DEM (the zone of its centre, placed
    at its centre) whose cells have the lat/lon cells' metric size at the centre (as
    `aperture info` measures it): the same terrain through the projected code path, to price
    the lat/lon one."""
    if os.path.exists(dst):
        return dst
    info = json.loads(subprocess.run([aperture, "info", src, "--json"], stdout=subprocess.PIPE,
                                     text=True, check=True, timeout=120).stdout)
    lon, lat = info["centre_lonlat"]
    dx, dy = info["cell_size_m"]
    ds = gdal.Open(src)
    zone = int((lon + 180) // 6) + 1
    epsg = (32600 if lat >= 0 else 32700) + zone
    utm = osr.SpatialReference()
    utm.ImportFromEPSG(epsg)
    geo = osr.SpatialReference()
    geo.ImportFromEPSG(4326)
    geo.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    utm.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    cx, cy, _ = osr.CoordinateTransformation(geo, utm).TransformPoint(lon, lat)
    band = ds.GetRasterBand(1)
    out = gdal.GetDriverByName("GTiff").Create(dst + ".part.tif", ds.RasterXSize,
                                              ds.RasterYSize, 1, band.DataType)
    out.SetProjection(utm.ExportToWkt())
    out.SetGeoTransform((cx - dx * ds.RasterXSize / 2.0, dx, 0.0,
                         cy + dy * ds.RasterYSize / 2.0, 0.0, -dy))
    if band.GetNoDataValue() is not None:
        out.GetRasterBand(1).SetNoDataValue(band.GetNoDataValue())
    out.GetRasterBand(1).WriteArray(band.ReadAsArray())
    out = None
    ds = None
    os.replace(dst + ".part.tif", dst)
    return dst


def fractal_surface(n, beta, seed, relief, noise):
    """n x n heights (float32, metres) by spectral synthesis: random phases, amplitudes so the
    2-D power spectrum falls as f^-(beta+1) (a 1-D profile's as f^-beta), scaled to
    [0, relief], plus Gaussian noise of `noise` metres."""
    rng = numpy.random.default_rng(seed)
    fy = numpy.fft.fftfreq(n)[:, None]
    fx = numpy.fft.rfftfreq(n)[None, :]
    f = numpy.hypot(fx, fy)
    f[0, 0] = numpy.inf  # no mean term
    amplitude = f ** (-(beta + 1.0) / 2.0)
    spectrum = amplitude * (rng.standard_normal(f.shape) + 1j * rng.standard_normal(f.shape))
    del f, amplitude
    z = numpy.fft.irfft2(spectrum, s=(n, n))
    del spectrum
    z -= z.min()
    z *= relief / z.max()
    z += rng.normal(0.0, noise, z.shape)
    return z.astype(numpy.float32)


def synthetic_dem(workdir, n, beta, seed, cell=30.0):
    path = os.path.join(workdir, "synthetic_%d_b%.2f_s%d.tif" % (n, beta, seed))
    if os.path.exists(path):
        return path
    z = fractal_surface(n, beta, seed + n, relief=2000.0, noise=0.5)
    driver = gdal.GetDriverByName("GTiff")
    ds = driver.Create(path + ".part.tif", n, n, 1, gdal.GDT_Float32, ["TILED=YES"])
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(UTM16N)
    ds.SetProjection(srs.ExportToWkt())
    ds.SetGeoTransform((700000.0, cell, 0.0, 4000000.0 + n * cell, 0.0, -cell))
    band = ds.GetRasterBand(1)
    band.SetNoDataValue(-9999)
    band.WriteArray(z)
    ds.SetMetadataItem("SOURCE", "bench_bake.py spectral synthesis, beta %.2f, seed %d"
                       % (beta, seed + n))
    band = None
    ds = None
    os.replace(path + ".part.tif", path)
    return path


def dem_size(path):
    ds = gdal.Open(path)
    size = ds.RasterXSize, ds.RasterYSize
    srs = ds.GetSpatialRef()
    if srs is None or not srs.IsProjected():
        print("warning: %s is not in a projected CRS; peers will take degrees for metres"
              % path, file=sys.stderr)
    return size


# ---------------------------------------------------------------------------------------------
# running and timing

def parse_gnu_time(path):
    """(wall seconds, peak RSS MiB) from a `/usr/bin/time -v -o path` report."""
    wall = rss = None
    try:
        with open(path) as f:
            text = f.read()
    except OSError:
        return None, None
    m = re.search(r"Elapsed \(wall clock\) time.*: (\S+)", text)
    if m:
        seconds = 0.0
        for part in m.group(1).split(":"):
            seconds = seconds * 60 + float(part)
        wall = seconds
    m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", text)
    if m:
        rss = int(m.group(1)) / 1024.0
    return wall, rss


def parse_saga_seconds(log):
    """SAGA's own timing of the tool ("Execution succeeded (01m 03s)"), 1 s resolution."""
    m = re.search(r"\] Execution succeeded \(([^)]*)\)", log)
    if not m:
        return None
    text = m.group(1)
    if "less than" in text:
        return 0.0
    units = {"h": 3600.0, "m": 60.0, "s": 1.0, "ms": 0.001}
    parts = re.findall(r"(\d+(?:\.\d+)?)\s*(ms|h|m|s)\b", text)
    return sum(float(v) * units[u] for v, u in parts) if parts else None


def run_timed(cmd, log_base, timeout, env=None):
    """Runs cmd under /usr/bin/time -v with a timeout, stdout+stderr to log_base.log.
    Returns dict(rc, wall, rss, log, timed_out)."""
    time_file = log_base + ".time"
    log_file = log_base + ".log"
    if os.path.exists(time_file):
        os.remove(time_file)
    with open(log_file, "w") as log:
        log.write("$ %s\n" % " ".join(shlex.quote(c) for c in cmd))
        log.flush()
        start = time.perf_counter()
        try:
            proc = subprocess.Popen([GNU_TIME, "-v", "-o", time_file] + cmd, stdout=log,
                                    stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                    start_new_session=True, env=env)
        except OSError as e:
            return dict(rc=127, wall=None, rss=None, log=str(e), timed_out=False)
        timed_out = False
        try:
            rc = proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            timed_out = True
            for sig in (signal.SIGTERM, signal.SIGKILL):
                try:
                    os.killpg(proc.pid, sig)
                except ProcessLookupError:
                    break
                try:
                    proc.wait(timeout=10)
                    break
                except subprocess.TimeoutExpired:
                    pass
            rc = proc.returncode
        elapsed = time.perf_counter() - start
    wall, rss = parse_gnu_time(time_file)
    with open(log_file, errors="replace") as f:
        text = f.read()
    return dict(rc=rc, wall=wall if wall is not None else elapsed, rss=rss, log=text,
                timed_out=timed_out)


def tail(text, lines=3):
    kept = [l.strip() for l in text.strip().splitlines() if l.strip() and "%" not in l[:6]]
    return " / ".join(kept[-lines:])[:200]


# ---------------------------------------------------------------------------------------------
# contenders: each returns a result dict (status, wall, rss, compute, params)

def run_saga(dem, tag, args):
    out = os.path.join(args.workdir, "out", "saga_%s.tif" % tag)
    if os.path.exists(out):
        os.remove(out)
    cmd = ["saga_cmd", "--cores=%d" % args.threads, "ta_lighting", "3", "-DEM", dem,
           "-SVF", out, "-RADIUS", "%g" % args.radius, "-NDIRS", str(args.directions),
           "-METHOD", "0"]
    r = run_timed(cmd, os.path.join(args.workdir, "logs", "saga_%s" % tag), args.timeout)
    params = "NDIRS=%d RADIUS=%g METHOD=0, %d cores" % (args.directions, args.radius,
                                                          args.threads)
    res = dict(params=params, wall=r["wall"], rss=r["rss"], compute=None, command=cmd)
    if r["timed_out"]:
        res["status"] = "timeout (%d s)" % args.timeout
    elif r["rc"] != 0:
        res["status"] = "failed (rc %s: %s)" % (r["rc"], tail(r["log"]))
    elif not os.path.exists(out):
        res["status"] = "failed (no output %s)" % out
    else:
        res["status"] = "ok"
        res["compute"] = parse_saga_seconds(r["log"])
    if os.path.exists(out) and not args.keep_outputs:
        os.remove(out)
    return res


def run_grass(dem, tag, args):
    script = os.path.join(args.workdir, "grass_horizon.sh")
    with open(script, "w") as f:
        f.write(GRASS_SCRIPT.format(time=GNU_TIME))
    horizon_time = os.path.join(args.workdir, "logs", "grass_%s.horizon.time" % tag)
    if os.path.exists(horizon_time):
        os.remove(horizon_time)
    step = 360.0 / args.directions
    cmd = ["grass", "--tmp-location", dem, "--exec", "sh", script, dem, horizon_time,
           "%g" % step, "%g" % args.radius]
    # the temporary location goes under TMPDIR: keep it in the workdir, and remove what a
    # killed (timed-out) run leaves behind
    tmp = os.path.join(args.workdir, "grass-tmp")
    shutil.rmtree(tmp, ignore_errors=True)
    os.makedirs(tmp)
    env = dict(os.environ, TMPDIR=tmp)
    r = run_timed(cmd, os.path.join(args.workdir, "logs", "grass_%s" % tag), args.timeout, env)
    shutil.rmtree(tmp, ignore_errors=True)
    params = "step=%g maxdistance=%g, 1 thread" % (step, args.radius)
    res = dict(params=params, wall=r["wall"], rss=r["rss"], compute=None, command=cmd)
    m = re.search(r"HORIZON_MAPS=(\d+)", r["log"])
    maps = int(m.group(1)) if m else 0
    if r["timed_out"]:
        res["status"] = "timeout (%d s)" % args.timeout
    elif r["rc"] != 0 or "ERROR" in r["log"]:
        res["status"] = "failed (rc %s: %s)" % (r["rc"], tail(r["log"]))
    elif maps != args.directions:
        res["status"] = "failed (%d horizon maps, not %d)" % (maps, args.directions)
    else:
        res["status"] = "ok"
        res["compute"], horizon_rss = parse_gnu_time(horizon_time)
        if res["rss"] is None:
            res["rss"] = horizon_rss
    return res


def run_ours(dem, tag, args, radius, threads, extra=()):
    """radius None: unlimited (no --radius); threads None: the tool's default; extra: more
    arguments after the template's (--products)."""
    params = "%d dirs, radius %s, %s%s" % (
        args.directions, "%g m" % radius if radius else "unlimited",
        "%d threads" % threads if threads else "default threads",
        ", " + " ".join(extra) if extra else "")
    if args.ours_unavailable:
        return dict(params=params, wall=None, rss=None, compute=None,
                    status="not available (%s)" % args.ours_unavailable, command=[])
    out = os.path.join(args.workdir, "out", "ours_%s.tif" % tag)
    if os.path.exists(out):
        os.remove(out)
    fields = dict(aperture=shlex.quote(args.aperture), dem=shlex.quote(dem),
                  out=shlex.quote(out), directions=args.directions,
                  radius="%g" % radius if radius else "",
                  radius_opt="--radius %g" % radius if radius else "",
                  threads=threads or "", threads_opt="--threads %d" % threads if threads else "")
    cmd = shlex.split(args.ours.format(**fields)) + list(extra)
    res = dict(params=params, wall=None, rss=None, compute=None, command=cmd)
    if not cmd or shutil.which(cmd[0]) is None:
        args.ours_unavailable = "no program %s" % (cmd[0] if cmd else "''")
        res["status"] = "not available (%s)" % args.ours_unavailable
        return res
    r = run_timed(cmd, os.path.join(args.workdir, "logs", "ours_%s" % tag), args.timeout)
    m = re.search(r"\(sky filter ([0-9.]+) s\)", r["log"])
    res.update(wall=r["wall"], rss=r["rss"], compute=float(m.group(1)) if m else None)
    if r["timed_out"]:
        res["status"] = "timeout (%d s)" % args.timeout
    elif r["rc"] != 0:
        if any(s in r["log"] for s in NOT_AVAILABLE):
            args.ours_unavailable = tail(r["log"], 1)
            res["status"] = "not available (%s)" % args.ours_unavailable
        else:
            res["status"] = "failed (rc %s: %s)" % (r["rc"], tail(r["log"]))
    elif not os.path.exists(out):
        res["status"] = "failed (no output %s)" % out
    else:
        res["status"] = "ok"
    if res["status"] != "ok":
        res.update(wall=None, rss=None, compute=None)
    if os.path.exists(out) and not args.keep_outputs:
        os.remove(out)
    return res


def merge_runs(runs):
    """One result for repeated runs of a contender: the mean wall and compute seconds, the
    largest peak memory, and every run's wall seconds (walls); a failed run's result if any
    failed."""
    failed = [r for r in runs if r["status"] != "ok"]
    if failed or len(runs) == 1:
        return dict(failed[0] if failed else runs[0], walls=[r["wall"] for r in runs])
    computes = [r["compute"] for r in runs]
    return dict(runs[0], wall=statistics.mean(r["wall"] for r in runs),
                compute=statistics.mean(computes) if None not in computes else None,
                rss=max(r["rss"] for r in runs if r["rss"] is not None),
                walls=[r["wall"] for r in runs])


# ---------------------------------------------------------------------------------------------
# machine and versions

def command_output(cmd):
    """stdout and stderr of cmd (grass prints its version on stderr), '' if it cannot run."""
    try:
        return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              timeout=60, stdin=subprocess.DEVNULL).stdout
    except (OSError, subprocess.TimeoutExpired):
        return ""


def versions(args):
    found = {}
    m = re.search(r"SAGA Version: (\S+)", command_output(["saga_cmd", "--version"]))
    found["SAGA"] = m.group(1) if m else "not installed"
    m = re.search(r"GRASS GIS (\S+)", command_output(["grass", "--version"]))
    found["GRASS"] = m.group(1) if m else "not installed"
    m = re.search(r"GDAL (\S+),", command_output(["gdalinfo", "--version"]))
    found["GDAL"] = m.group(1) if m else gdal.__version__
    if shutil.which(args.aperture):
        text = command_output([args.aperture, "--version"]).strip()
        found["aperture"] = text.split()[-1] if text else "?"
    else:
        found["aperture"] = "not found (%s)" % args.aperture
    return found


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown"


# ---------------------------------------------------------------------------------------------
# report

def fmt(value, spec):
    return spec % value if value is not None else "—"


def report(rows, args, header, baseline_rss=None, thread_pairs=()):
    lines = list(header)
    lines.append("| DEM | cells | contender | parameters | wall s | compute s | peak RSS MiB | "
                 "M cell-dirs/s | M cell-dirs/s/core (compute) | our speed-up | status |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|---|")
    # our reference per DEM: the run at the common radius with the default thread count
    ours_ref = {row["dem"]: row for row in rows
                if row["contender"] == "ours" and row.get("reference") and row["wall"]}
    # ours doing SAGA's job (SAGA_JOB) on the same DEM, for SAGA's second speed-up
    same_job = {row["dem"]: row for row in rows
                if row["contender"] == "ours-svf" and row["status"] == "ok" and row["wall"]}
    for row in rows:
        cells = row["nx"] * row["ny"]
        rate = cells * args.directions / row["wall"] / 1e6 if row["wall"] else None
        speedup = "—"
        if not row["contender"].startswith("ours") and row["wall"] and row["status"] == "ok":
            ref = ours_ref.get(row["dem"])
            speedup = "%.2f" % (row["wall"] / ref["wall"]) if ref else "n/a"
            same = same_job.get(row["dem"])
            if row["contender"] == "saga" and same:
                speedup += " (%.2f on its output only)" % (row["wall"] / same["wall"])
        per_core = None
        if row["contender"].startswith("ours") and row["status"] == "ok" and row["compute"]:
            per_core = (cells * args.directions / row["compute"] / 1e6
                        / (row.get("threads") or os.cpu_count() or 1))
        lines.append("| %s | %d x %d = %.2f M | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            row["dem"], row["nx"], row["ny"], cells / 1e6, row["label"], row["params"],
            fmt(row["wall"] if row["status"] == "ok" else None, "%.2f"),
            fmt(row["compute"], "%.2f"), fmt(row["rss"] if row["status"] == "ok" else None,
                                             "%.0f"),
            fmt(rate if row["status"] == "ok" else None, "%.1f"), fmt(per_core, "%.1f"),
            speedup, row["status"]))
    notes = (repeat_notes(rows) + scaling_notes(rows) + pair_notes(thread_pairs, args.threads)
             + memory_notes(rows, baseline_rss))
    if notes:
        lines.append("")
        lines.extend(notes)
    lines.append("")
    lines.append("Commands (first run of each contender):")
    lines.append("")
    seen = set()
    for row in rows:
        if row["contender"] not in seen and row["command"]:
            seen.add(row["contender"])
            lines.append("    " + " ".join(shlex.quote(c) for c in row["command"]))
            if row["contender"] == "grass":
                lines.extend("    | " + l for l in GRASS_SCRIPT.format(time=GNU_TIME)
                             .splitlines()[1:])
    lines.append("")
    lines.append("wall s: whole command under /usr/bin/time -v (GRASS: location creation, "
                 "import and r.horizon; SAGA: read, compute, write GeoTIFF). compute s: GRASS "
                 "r.horizon alone (its own /usr/bin/time), SAGA's own report of the tool "
                 "(1 s resolution), ours: the sky filter alone (as `aperture bake` reports "
                 "it: the sweep and the products, without start-up, reading and writing). "
                 "M cell-dirs/s/core: cells x directions / compute s / threads (ours). "
                 "peak RSS: largest process of the command. "
                 "M cell-dirs/s: cells x %d directions / wall. our speed-up: peer wall / our "
                 "wall on the same DEM (> 1: ours faster; n/a: no successful run of ours on it), "
                 "ours with its default products (nine bands); for SAGA also against %s "
                 "(`%s`: the one band SAGA writes, the same job)."
                 % (args.directions, SAGA_JOB_LABEL, " ".join(SAGA_JOB)))
    return "\n".join(lines) + "\n"


# the default products of `aperture bake` as float32 bands (BentNormal counts 3), + the input
OUR_BANDS = 9


def memory_notes(rows, base):
    """Our peak memory above the process's own baseline (base MiB), against the data it must
    hold."""
    ours = [r for r in rows if r["contender"] == "ours" and r["status"] == "ok" and r["rss"]]
    if not base or not ours:
        return []
    parts = []
    for r in ours:
        data = r["nx"] * r["ny"] * 4.0 * (1 + OUR_BANDS) / 2 ** 20
        parts.append("%s r=%s t=%s: %.0f MiB over %.0f MiB of data = %.2fx" % (
            r["dem"], "%g" % r["radius"] if r["radius"] else "inf", r["threads"],
            r["rss"] - base, data, (r["rss"] - base) / data))
    return ["Ours, peak RSS above the baseline of the process (%.0f MiB: interpreter, VTK and "
            "GDAL loaded, `aperture bake` on a 16 x 16 window of the embedded DEM) against "
            "input + outputs as float32 (1 + %d bands): " % (base, OUR_BANDS)
            + "; ".join(parts) + "."]


def pair_notes(pairs, threads):
    """The extra (one-thread seconds, many-thread seconds) pairs."""
    if not pairs:
        return []
    ratios = [one / many for one, many in pairs]
    return ["Ours, parallel speed-up in %d more interleaved pairs (1 thread, then %d; sky filter "
            "seconds): %s; median %.2f." % (
                len(pairs), threads,
                ", ".join("%.2f/%.2f s = %.2f" % (one, many, one / many) for one, many in pairs),
                statistics.median(ratios))]


def repeat_notes(rows):
    """Every run of the contenders compared more than once (their table rows give the means)."""
    parts = ["%s %s: %s" % (r["dem"], r["contender"], ", ".join(fmt(w, "%.2f") for w in r["walls"]))
             for r in rows if len(r.get("walls") or []) > 1]
    if not parts:
        return []
    svf = any(r["contender"] == "ours-svf" for r in rows)
    order = "ours, ours-svf, peers, peers, ours-svf, ours" if svf else "ours, peers, peers, ours"
    return ["Comparison runs in the order " + order + " on each DEM"
            + (" (ours-svf: %s)" % SAGA_JOB_LABEL if svf else "") + "; the table gives "
            "each contender's mean; wall seconds of each run: " + "; ".join(parts) + "."]


def scaling_notes(rows):
    """Our scaling, on the sky filter's own seconds (compute) when reported, else wall."""
    ours = [r for r in rows if r["contender"] == "ours" and r["status"] == "ok"]
    secs = lambda r: r["compute"] or r["wall"]
    notes = []
    cells = sorted((r["nx"] * r["ny"], secs(r)) for r in ours if "cells" in r["series"])
    if len(cells) > 1:
        notes.append("Ours, scaling with cells (sky filter seconds per M cells): " + ", ".join(
            "%.2f M: %.3f" % (c / 1e6, w / (c / 1e6)) for c, w in cells) + ".")
    radius = sorted((r for r in ours if "radius" in r["series"]),
                    key=lambda r: (r["radius"] is None, r["radius"] or 0))
    if len(radius) > 1:
        notes.append("Ours, scaling with radius on %s (sky filter seconds): " % radius[0]["dem"]
                     + ", ".join("%s: %.2f s" % ("%g m" % r["radius"] if r["radius"]
                                                 else "unlimited", secs(r)) for r in radius)
                     + ".")
    latlon = [r for r in ours if "latlon" in r["series"]]
    if len(latlon) == 2:
        ns = lambda r: secs(r) * r["threads"] / (r["nx"] * r["ny"] * r["directions"]) * 1e9
        notes.append("Ours, lat/lon against projected on the same elevations and cell sizes "
                     "(sky filter ns per cell-direction per core): %s %.1f, %s %.1f." % (
                         latlon[0]["dem"], ns(latlon[0]), latlon[1]["dem"], ns(latlon[1])))
    threads = {r["threads"]: secs(r) for r in ours if "threads" in r["series"]}
    if 1 in threads and len(threads) > 1:
        best = max(threads)
        notes.append("Ours, parallel speed-up of the sky filter, %d threads over 1: %.2f "
                     "(efficiency %.0f%%)." % (best, threads[1] / threads[best],
                                               100 * threads[1] / threads[best] / best))
    return notes


# ---------------------------------------------------------------------------------------------

def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true",
                        help="embedded DEM and a 512^2 synthetic DEM only, no scaling runs")
    parser.add_argument("--dem", action="append", default=[],
                        help="extra DEM in a projected metric CRS (repeatable)")
    parser.add_argument("--size", type=int, default=None,
                        help="synthetic DEM for the peer comparison, cells a side "
                             "(default 1024; 512 with --quick)")
    parser.add_argument("--scaling-sizes", default="2048,4096",
                        help="synthetic sizes for our cell-scaling runs (default 2048,4096)")
    parser.add_argument("--beta", type=float, default=2.2,
                        help="synthetic DEM: 1-D spectral exponent (default 2.2)")
    parser.add_argument("--seed", type=int, default=20240607, help="synthetic DEM seed")
    parser.add_argument("--directions", type=int, default=32)
    parser.add_argument("--radius", type=float, default=10000.0, help="metres (default 10000)")
    parser.add_argument("--scaling-radii", default="1000,10000,0",
                        help="radii for our radius scaling on the first scaling size; "
                             "0 = unlimited, no --radius (default 1000,10000,0)")
    parser.add_argument("--threads", type=int, default=os.cpu_count() or 1,
                        help="threads for ours and SAGA's cores (default: all, %d)"
                             % (os.cpu_count() or 1))
    parser.add_argument("--timeout", type=int, default=1800, help="seconds per run")
    parser.add_argument("--ours", default=DEFAULT_OURS,
                        help="our command template; fields {aperture} {dem} {out} "
                             "{directions} {radius} {radius_opt} {threads} {threads_opt} "
                             "(default: %(default)s)")
    parser.add_argument("--aperture", default=None,
                        help="the aperture program (default: build/bin/aperture, else PATH)")
    parser.add_argument("--no-ours", action="store_true", help="peers only")
    parser.add_argument("--no-peers", action="store_true", help="ours only")
    parser.add_argument("--no-saga", action="store_true")
    parser.add_argument("--no-grass", action="store_true")
    parser.add_argument("--no-cell-scaling", action="store_true",
                        help="skip ours on the --scaling-sizes DEMs")
    parser.add_argument("--no-radius-scaling", action="store_true")
    parser.add_argument("--comparison-repeats", type=int, choices=(1, 2), default=2,
                        help="2 (default): run the comparison's contenders again in the "
                             "mirror order and report their means; 1: once each")
    parser.add_argument("--no-latlon", action="store_true",
                        help="skip ours on the lat/lon DEM and its projected twin")
    parser.add_argument("--no-thread-scaling", action="store_true")
    parser.add_argument("--thread-pairs", type=int, default=5,
                        help="extra interleaved 1-thread / all-threads pairs (default 5: "
                             "one pair on these VMs can say anything from 1.4x to 2.4x)")
    parser.add_argument("--scaling-only", action="store_true",
                        help="skip the comparison DEMs, run only the scaling part")
    parser.add_argument("--peers-on-scaling", action="store_true",
                        help="also run the peers on the --scaling-sizes DEMs (long: SAGA "
                             "and GRASS ~7 min each on 2048^2)")
    parser.add_argument("--workdir", default="/tmp/aperture-bench-bake",
                        help="DEMs, outputs and logs (default %(default)s)")
    parser.add_argument("--keep-outputs", action="store_true")
    parser.add_argument("--no-install", action="store_true",
                        help="do not apt-get install missing peers (saga, grass-core) or time")
    parser.add_argument("--output", default=os.path.join(HERE, "results-bake.md"),
                        help="Markdown report (default bench/results-bake.md)")
    args = parser.parse_args()

    wanted = [GNU_TIME]
    if not args.no_peers:
        wanted += [] if args.no_saga else ["saga_cmd"]
        wanted += [] if args.no_grass else ["grass"]
    still_missing = ensure_packages(wanted, not args.no_install)
    if GNU_TIME in still_missing:
        raise SystemExit("%s is missing: apt-get install -y time" % GNU_TIME)
    for program in still_missing:
        print("warning: %s is missing; its runs are recorded as failed" % program,
              file=sys.stderr)
    if args.aperture is None:
        built = os.path.join(REPO, "build", "bin", "aperture")
        args.aperture = built if os.path.exists(built) else "aperture"
    args.ours_unavailable = "--no-ours" if args.no_ours else None
    for sub in ("", "out", "logs"):
        os.makedirs(os.path.join(args.workdir, sub), exist_ok=True)
    size = args.size or (512 if args.quick else 1024)
    scaling_sizes = [] if args.quick else [int(s) for s in args.scaling_sizes.split(",") if s]
    radii = [float(r) for r in args.scaling_radii.split(",") if r]

    # DEMs for the peer comparison
    dems = []
    embedded = embedded_dem()
    if embedded:
        dems.append(warp_to_utm(embedded, os.path.join(args.workdir, "jacksboro_utm16n_90m.tif"),
                                UTM16N, 90.0))
    else:
        print("warning: embedded DEM not found (is the build on PYTHONPATH?)", file=sys.stderr)
    synthetic = synthetic_dem(args.workdir, size, args.beta, args.seed)
    dems.append(synthetic)
    if not args.quick and os.path.exists(BIGTUJUNGA):
        dems.append(os.path.abspath(BIGTUJUNGA))
    dems.extend(os.path.abspath(d) for d in args.dem)

    peers = []
    if not args.no_peers:
        if not args.no_saga:
            peers.append(("saga", "SAGA ta_lighting 3", run_saga))
        if not args.no_grass:
            peers.append(("grass", "GRASS r.horizon", run_grass))

    rows = []

    def record(dem, contender, label, res, **extra):
        nx, ny = dem_size(dem)
        row = dict(dem=os.path.basename(dem), nx=nx, ny=ny, contender=contender, label=label)
        row.update(res)
        row.update(extra)
        rows.append(row)
        print("  %-22s %-50s %s %s" % (label, res["params"],
                                      fmt(res["wall"], "%.2f s"), res["status"]), flush=True)
        return row

    def tag_of(dem, *more):
        return "_".join([os.path.splitext(os.path.basename(dem))[0]] + [str(m) for m in more])

    done = {}

    def ours_tag(dem, radius, threads, repeat=0):
        return tag_of(dem, "r%g" % (radius or 0), "t%s" % threads,
                      *(["rep%d" % (repeat + 1)] if repeat else []))

    def ours(dem, radius, threads, series=None, runs=None):
        """Our row for (dem, radius, threads): from the given runs (their mean), else a run of
        its own, made once and shared by every series that asks for it."""
        key = (dem, radius, threads)
        if key not in done:
            res = (merge_runs(runs) if runs else
                   run_ours(dem, ours_tag(dem, radius, threads), args, radius, threads))
            done[key] = record(dem, "ours", "ours (aperture bake)", res, threads=threads,
                               radius=radius, series=set(), directions=args.directions,
                               reference=radius == args.radius and threads == args.threads)
        # a run shared by several series (2048^2 at 10 km) is run and listed once
        row = done[key]
        if series:
            row["series"].add(series)

    baseline_rss = None  # MiB: the process with everything loaded, for memory_notes
    thread_pairs = []  # (one-thread s, all-threads s) of the extra interleaved pairs
    if not args.no_ours and embedded:
        # the same command on a 16 x 16 window: every module and library the bake loads
        # (`aperture info` loads numpy, which the bake no longer does), almost no data
        r = run_timed([args.aperture, "bake", embedded,
                       os.path.join(args.workdir, "out", "ours_baseline.tif"),
                       "--srcwin", "0", "0", "16", "16", "--directions", str(args.directions),
                       "--radius", "%g" % args.radius],
                      os.path.join(args.workdir, "logs", "ours_baseline"), args.timeout)
        baseline_rss = r["rss"] if r["rc"] == 0 else None

    print("comparison: %d directions, radius %g m" % (args.directions, args.radius), flush=True)
    for dem in [] if args.scaling_only else dems:
        print(os.path.basename(dem), flush=True)
        # ours, the peers, then (--comparison-repeats 2) the peers and ours again in the mirror
        # order, so that a drift of the machine's speed during the comparison weighs on every
        # contender alike; each is reported with the mean of its runs
        contenders = ([] if args.no_ours else [("ours", None, None)]) + peers
        if not args.no_ours and any(name == "saga" for name, _, _ in peers):
            # SAGA's job: its one output, a slope-weighted sky view (DiffuseSkyFactor), as one
            # band (ours writes nine by default), so the speed-up over SAGA is also measured on
            # the same work
            contenders.insert(1, ("ours-svf", None, None))
        order = contenders + (contenders[::-1] if args.comparison_repeats > 1 else [])
        runs = {}
        for name, label, fn in order:
            n = len(runs.setdefault(name, []))
            if name == "ours":
                res = run_ours(dem, ours_tag(dem, args.radius, args.threads, n), args,
                               args.radius, args.threads)
            elif name == "ours-svf":
                res = run_ours(dem, ours_tag(dem, args.radius, args.threads, n) + "_svf", args,
                               args.radius, args.threads, SAGA_JOB)
            else:
                res = fn(dem, tag_of(dem, *(["rep%d" % (n + 1)] if n else [])), args)
            print("  %-22s run %d: %s %s" % (label or name, n + 1,
                                              fmt(res["wall"], "%.2f s"), res["status"]),
                  flush=True)
            runs[name].append(res)
        for name, label, fn in peers:
            record(dem, name, label, merge_runs(runs[name]))
        if "ours-svf" in runs:
            record(dem, "ours-svf", SAGA_JOB_LABEL, merge_runs(runs["ours-svf"]),
                   threads=args.threads, radius=args.radius, series=set(),
                   directions=args.directions)
        if not args.no_ours:
            ours(dem, args.radius, args.threads,
                 series="cells" if dem == synthetic and scaling_sizes else None,
                 runs=runs["ours"])

    if not args.quick and not args.no_ours and not args.no_latlon and os.path.exists(LATLON):
        print("lat/lon", flush=True)
        latlon = os.path.abspath(LATLON)
        projected = same_cells_as_utm(latlon, os.path.join(
            args.workdir, os.path.splitext(os.path.basename(LATLON))[0] + "_as_utm.tif"),
            args.aperture)
        for dem in (latlon, projected):
            print(os.path.basename(dem), flush=True)
            ours(dem, args.radius, args.threads, "latlon")

    if scaling_sizes and (args.peers_on_scaling or not args.ours_unavailable):
        print("scaling", flush=True)
        big = [synthetic_dem(args.workdir, n, args.beta, args.seed) for n in scaling_sizes]
        for dem in big:
            print(os.path.basename(dem), flush=True)
            if args.peers_on_scaling:
                for name, label, fn in peers:
                    record(dem, name, label, fn(dem, tag_of(dem), args))
            if not args.no_ours and not args.no_cell_scaling:
                ours(dem, args.radius, args.threads, "cells")
        if not args.no_ours and not args.no_radius_scaling:
            for radius in radii:
                ours(big[0], radius or None, args.threads, "radius")
        if not args.no_ours and not args.no_thread_scaling:
            for threads in sorted({1, args.threads}):
                ours(big[0], args.radius, threads, "threads")
            # A single pair says little on a shared VM (one-thread times wandered by 40%):
            # more pairs, each one thread then all, right after each other.
            for k in range(args.thread_pairs if args.threads > 1 else 0):
                t = {}
                for threads in (1, args.threads):
                    res = run_ours(big[0], tag_of(big[0], "pair%d" % k, "t%d" % threads), args,
                                   args.radius, threads)
                    t[threads] = res["compute"]
                print("  thread pair %d: %s" % (k + 1, t), flush=True)
                if t[1] and t[args.threads]:
                    thread_pairs.append((t[1], t[args.threads]))
    elif scaling_sizes:
        print("scaling runs skipped: ours not available (%s)" % args.ours_unavailable,
              flush=True)

    found = versions(args)
    header = [
        "# aperture bake vs peers",
        "",
        "Run %s on %s, %d cores, %.0f GiB; %d directions, radius %g m, timeout %d s."
        % (datetime.datetime.now().strftime("%Y-%m-%d %H:%M"), cpu_model(), os.cpu_count(),
           os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2 ** 30,
           args.directions, args.radius, args.timeout),
        "Versions: " + "; ".join("%s %s" % kv for kv in found.items()) + ".",
        "",
    ]
    text = report(rows, args, header, baseline_rss, thread_pairs)
    print()
    print(text)
    with open(args.output, "w") as f:
        f.write(text)
    print("written to %s" % args.output)


if __name__ == "__main__":
    main()
