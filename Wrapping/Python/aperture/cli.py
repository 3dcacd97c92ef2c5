# SPDX-License-Identifier: BSD-3-Clause
"""The `aperture` command line.

    aperture info [DEM] [--json]          what a DEM is: size, cell size, CRS, bounds, elevations
    aperture bake DEM OUT.tif             what every cell sees of the sky (horizons, SVF, ...)
    aperture render [DEM] [-o OUT.png]    a picture of the DEM lit by the sun and sky (PNG, EXR)
    aperture sun --at ISO (--lat --lon | --dem DEM)   where the sun is; sunrise, sunset

DEM is any raster GDAL reads (GeoTIFF, .hgt, .asc, .dt0, VRT, ...; band 1, or --band N);
without it, the embedded default DEM is used. Errors print one line on stderr and exit with
status 1; a mistake in the options themselves (a malformed or out-of-range value, options
that do not go together) prints the command's usage too and exits with status 2, as
argparse's own checks do.
"""
import argparse
import json
import math
import os
import re
import sys
import textwrap

from aperture.errors import ApertureError, Watcher, native_path, quiet_vtk_output

PROG = "aperture"


class _UsageError(ApertureError):
    """A mistake in the options themselves (a value out of its range, options that do not go
    together), found from the options alone: reported with the command's usage and exit
    status 2, as argparse reports the mistakes it finds."""


_WARNED = set()  # (the warnings of this run of main)


def _warn(message):
    """A warning on stderr, once: a DEM read in strips gave a warning of its infinite cells
    for each strip that had some, until 2026-12-07."""
    text = _as_options(message)
    if text not in _WARNED:
        _WARNED.add(text)
        print("%s: warning: %s" % (PROG, text), file=sys.stderr)


# ---------------------------------------------------------------------------------------------
# Reading


# The reading options' defaults: each leaves the file as it is (sun checks that none is given
# without --dem).
_READ_DEFAULTS = {"band": None, "srcwin": None, "overview": None, "decimate": 1, "srs": None,
                  "zfactor": 0.0}


def _add_read_options(parser, dem_required=False, srcwin_help=None, dem_option=None):
    """The DEM (a positional argument, or with dem_option, that option with its help) and the
    options that read it."""
    g = parser.add_argument_group("reading the DEM")
    if dem_option:
        g.add_argument("--dem", dest="dem", metavar="DEM", help=dem_option)
    elif dem_required:
        g.add_argument("dem", metavar="DEM", help="elevation raster")
    else:
        g.add_argument("dem", nargs="?", metavar="DEM",
                       help="elevation raster (default: the embedded Jacksboro DEM)")
    g.add_argument("--band", "-b", type=_c_int, metavar="N",
                   help="1-based band to read (default: band 1, with a note if there are more)")
    g.add_argument("--srcwin", type=_c_int, nargs=4, metavar=("XOFF", "YOFF", "XSIZE", "YSIZE"),
                   help=(srcwin_help or "read only this window, in pixels from the top-left "
                                        "corner (as gdal_translate -srcwin)") +
                   "; a size of 0 reaches the raster's edge")
    g.add_argument("--overview", type=_c_int, default=_READ_DEFAULTS["overview"], metavar="K",
                   help="read GDAL overview level K (0-based) instead of full resolution")
    g.add_argument("--decimate", type=_c_int, default=_READ_DEFAULTS["decimate"], metavar="F",
                   help="average F x F blocks of cells (nodata ignored), aligned to the "
                        "raster's top-left corner (a --srcwin gets every whole block it "
                        "touches; a partial block at the east or south edge, north if the "
                        "raster is south-up, is left out, with a warning)")
    g.add_argument("--srs", type=_crs_text, metavar="CRS",
                   help="use this CRS instead of the file's (EPSG:xxxx, WKT or PROJ string)")
    g.add_argument("--zfactor", type=_parse_zfactor, default=_READ_DEFAULTS["zfactor"],
                   metavar="Z",
                   help="metres per elevation unit, for a DEM whose unit is missing or wrong: "
                        "a number, or ft (0.3048), us-ft (1200/3937), m, cm, dm, mm, km, or "
                        "another name bands give those units (foot, US survey foot, metre, "
                        "centimetres, ...) (default: the band's unit, else a compound CRS's "
                        "height unit, else metres)")


def _parse_zfactor(text):
    """--zfactor: metres per elevation unit, or a unit's name as the reader knows band units
    (vtkApertureDEMReader::GetMetresPerUnit: m, cm, ft, us-ft, foot, US survey foot, ...)."""
    from aperture import vtkApertureDEMReader
    value = vtkApertureDEMReader.GetMetresPerUnit(text.strip()) if text.strip() else 0.0
    if value == 0.0:
        try:
            value = float(text)
        except ValueError:
            value = math.nan
    if not (0.0 < value <= 1e4):  # (the reader's range: more overflows floats)
        raise argparse.ArgumentTypeError(
            "must be a positive number of metres per elevation unit up to 10000, or a unit: m, "
            "ft, us-ft, "
            "cm, dm, mm or km (or their names: metre, foot, US survey foot, centimetre, ...), "
            "not %r" % text)
    return value


class _TermProgress:
    """Progress on a terminal as GDAL's tools print it: 0...10...20...30 ... 90...100 - done.
    Call with the fraction done; a dot per 2.5 %, the percentage every 10 %."""

    def __init__(self, stream):
        self._stream = stream
        self._ticks = -1  # steps of 2.5 % printed; -1: none yet

    @property
    def open(self):
        """Started and not finished (an error message then needs a new line first)."""
        return 0 <= self._ticks < 40

    def __call__(self, fraction):
        target = int(40 * min(1.0, max(0.0, fraction)))
        out = []
        while self._ticks < target:
            self._ticks += 1
            out.append(str(self._ticks // 4 * 10) if self._ticks % 4 == 0 else ".")
        if out:
            if self._ticks == 40:
                out.append(" - done.\n")
            self._stream.write("".join(out))
            self._stream.flush()


class _StepsProgress:
    """One progress display over a command's steps, each weighted by its rough cost: a step
    reports its own fraction done (a VTK algorithm's ProgressEvent, through observe()), and
    the display shows the weighted sum. Each step only moves forward."""

    def __init__(self, display, weights):
        self._display = display
        self._weights = {step: float(w) for step, w in weights.items() if w > 0}
        self._done = dict.fromkeys(self._weights, 0.0)
        self._total = sum(self._weights.values())

    def __call__(self, step, fraction):
        if step in self._done:
            self._done[step] = max(self._done[step], min(1.0, fraction))
            self._display(sum(self._weights[k] * d for k, d in self._done.items())
                          / self._total)

    def observe(self, algorithm, step, fraction=None):
        """Report `algorithm`'s progress as `step`'s, through fraction(progress) if given."""
        algorithm.AddObserver("ProgressEvent", lambda obj, _: self(
            step, fraction(obj.GetProgress()) if fraction else obj.GetProgress()))


def _full_name(path):
    """The absolute path of a file, for provenance; GDAL's virtual file names (/vsizip/...,
    /vsicurl/...) and its names of subdatasets that are no file (NETCDF:"f.nc":z) as given,
    since normalising them changes what they name."""
    return path if path.startswith("/vsi") or (":" in path and not os.path.exists(path)) \
        else os.path.abspath(path)


# GDAL's virtual file systems that read a file of the disk: an archive's member, a compressed
# file, a part of a file
_VSI_ARCHIVES = ("/vsizip/", "/vsitar/", "/vsi7z/", "/vsirar/")
_VSI_WHOLE = ("/vsigzip/", "/vsibzip2/", "/vsixz/")


def _host_file(path):
    """The file of the disk a GDAL path reads: the archive of /vsizip/archive.zip/dem.tif (or
    /vsizip/{archive.zip}/dem.tif), the file of /vsigzip/dem.tif.gz or of
    /vsisubfile/offset_size,file, through chains of them; other paths as they are (bytes
    too, names that are not UTF-8)."""
    if isinstance(path, bytes):
        return os.fsencode(_host_file(os.fsdecode(path)))
    for _ in range(8):  # (chains such as /vsizip//vsigzip/...)
        if path.startswith(_VSI_WHOLE):
            path = path[path.index("/", 1) + 1:]
        elif path.startswith("/vsisubfile/"):
            path = path[len("/vsisubfile/"):].split(",", 1)[-1]
        elif path.startswith(_VSI_ARCHIVES):
            rest = path[path.index("/", 1) + 1:]
            if rest.startswith("{") and "}" in rest:
                path = rest[1:rest.index("}")]
                continue
            # the longest leading part that is a file of the disk (or a virtual one again)
            parts = rest.split("/")
            path = rest
            for k in range(len(parts), 0, -1):
                head = "/".join(parts[:k])
                if os.path.isfile(head) or head.startswith("/vsi"):
                    path = head
                    break
        else:
            break
    return path


def _same_file(a, b, real=os.path.realpath):
    a, b = _host_file(a), _host_file(b)
    if os.path.exists(a) and os.path.exists(b):
        return os.path.samefile(a, b)  # hard links too
    return real(a) == real(b)


def _folder_realpath():
    """os.path.realpath for many names in few folders (a time-lapse's frames): each folder
    resolved once, a name's own symbolic link still followed (10,000 frames' checks took 8 s
    of realpath's calls, one a folder of each name, until 2026-12-07)."""
    folders = {}

    def real(path):
        head, tail = os.path.split(path)
        if tail in ("", ".", "..") or os.path.islink(path):
            return os.path.realpath(path)
        if head not in folders:
            folders[head] = os.path.realpath(head or os.curdir)
        return os.path.join(folders[head], tail)
    return real


def _file_kind(mode):
    """What a path of this st_mode is, when it is not a regular file."""
    import stat
    for test, kind in ((stat.S_ISDIR, "a folder"), (stat.S_ISCHR, "a device"),
                       (stat.S_ISBLK, "a device"), (stat.S_ISFIFO, "a pipe"),
                       (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return kind
    return "something else"


def _check_outputs(outputs, inputs, probe=True, real=os.path.realpath):
    """Refuse an output that is not a file (a folder, a device such as /dev/null, a pipe), or
    whose folder does not exist or cannot take a new file (read-only, no permission), or that
    cannot be made by that name (too long, characters a FAT or NTFS stick refuses; the EXR
    writer's temporary file beside it has a short name of its own): found before a bake of hours,
    not after it; one that would overwrite an input, or two outputs in one file (the second
    would silently replace the first). outputs, inputs: (option, path) pairs; empty paths
    skipped. probe=False leaves out what only the folder and the name's form decide (its
    folder, a file made there and by that name), for names checked alike beside it already;
    real resolves names (_folder_realpath for many)."""
    import tempfile
    taken = [(name, path) for name, path in inputs if path]
    for name, path in outputs:
        if not path:
            continue
        # the file the writers write: a symbolic link's target (a link to a missing folder
        # failed only when the bake was written, naming a temporary file, until 2026-12-07)
        target = os.path.realpath(path) if os.path.islink(path) else path
        link = " (%s is a symbolic link to %s)" % (path, target) if target != path else ""
        folder = os.path.dirname(os.path.abspath(target))
        if probe and not os.path.isdir(folder):
            raise ApertureError("the output folder %s does not exist%s" % (folder, link))
        exists = os.path.exists(path)
        if exists and not os.path.isfile(path):
            # (the writers refuse these too: they replace their file, and remove it on failure)
            raise ApertureError("cannot write %s %s: it is %s, not a file"
                                % (name, path, _file_kind(os.stat(path).st_mode)))
        if probe:
            try:
                with tempfile.TemporaryFile(dir=folder):  # (unnamed where the system allows)
                    pass
            except OSError as e:
                raise ApertureError("cannot write %s %s: the folder does not take new files "
                                    "(%s)" % (name, path, e.strerror or e))
        if exists and not os.access(path, os.W_OK):
            raise ApertureError("cannot write %s %s: the file exists and is read-only"
                                % (name, path))
        if probe and not exists:  # (made and removed at once)
            try:
                os.close(os.open(target, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600))
            except FileExistsError:
                pass
            except OSError as e:
                raise ApertureError("cannot write %s %s: %s%s" % (name, path, e.strerror or e,
                                                                  link))
            else:
                os.remove(target)
        for other, other_path in taken:
            if _same_file(path, other_path, real):
                raise ApertureError("%s %s is %s; choose another name" % (
                    name, path, "the same file as " + other if _host_file(other_path) ==
                    other_path else "the file %s (%s) is read from" % (other, other_path)))
        taken.append((name, path))


def _check_frame_outputs(frame_paths, inputs):
    """_check_outputs for render's outputs, each (option, [one name a frame]): the first
    frames against each other and the inputs; every other frame against the inputs, probing
    its folder and name for the last frame, the first in each other folder and a symbolic
    link's only (about 1 ms a name; a dangling link of frame 2 failed the series after frame
    1 until 2026-12-07); and no two frames in one file (frame-%d.png as both -o and --exr, or
    through a symbolic link)."""
    real = _folder_realpath()
    _check_outputs([(option, names[0]) for option, names in frame_paths], inputs, real=real)
    seen, folders = {}, set()
    for option, names in frame_paths:
        for k, name in enumerate(names):
            key = real(name)
            if key in seen:
                raise ApertureError("frame %d of %s and frame %d of %s are one file, %s; choose "
                                    "other names" % (seen[key] + (k, option, name)))
            seen[key] = (k, option)
            folder = os.path.dirname(os.path.abspath(name))
            if k:
                _check_outputs([(option, name)], inputs, probe=k == len(names) - 1 or
                               folder not in folders or os.path.islink(name), real=real)
            folders.add(folder)


def _warn_extension(path, extensions, kind):
    """A warning for an output whose name's extension says another format than it gets."""
    if path and os.path.splitext(path)[1].lower() not in extensions:
        _warn("%s is written as %s" % (path, kind))


def _check_sources(outputs, reader):
    """Refuse an output that is one of the files GDAL reads for the DEM (after the reader's
    UpdateInformation): a VRT's sources, a format's other parts, where _check_outputs saw
    only the DEM's own name (a bake over a VRT's source changed the DEM under its strips).
    And one whose GDAL sidecars, which the writers remove when they put it in place (beside its
    name and beside the target of its links: vtkApertureOutputFile.h), are one of those files
    or another output. outputs: (option, path) pairs; empty paths skipped."""
    sources = [reader.GetFile(i) for i in range(reader.GetNumberOfFiles())]
    real = _folder_realpath()
    taken = {real(path): (name, path) for name, path in outputs if path}
    for name, path in outputs:
        for source in sources if path else ():
            if _same_file(path, source, real):
                raise ApertureError("%s %s is %s; choose another name" % (
                    name, path, "the same file as the DEM" if source == sources[0] else
                    "one of the files the DEM %s reads (%s)" % (sources[0], source)))
        beside = dict.fromkeys([path, real(path)]) if path else ()
        for sidecar in (b + suffix for b in beside for suffix in (".aux.xml", ".ovr", ".msk")):
            other = taken.get(real(sidecar))
            which = [("the DEM" if source == sources[0] else "one of the files the DEM %s "
                      "reads" % sources[0]) for source in sources
                     if _same_file(sidecar, source, real)]
            if which or other:
                raise ApertureError(
                    "%s %s: writing it removes %s (GDAL's sidecar of a file of that name), "
                    "which is %s; choose another name" % (
                        name, path, sidecar, which[0] if which else "%s %s" % other))


def _dem_path(args):
    if args.dem is not None:
        if not args.dem:
            # (not the default DEM: an empty variable in a script is a mistake, not a choice)
            raise _UsageError("the DEM path is empty")
        if native_path(args.dem) is not args.dem and not os.path.exists(args.dem):
            # (a name that is not UTF-8: the reader's own message could not reach us)
            raise ApertureError("file '%s' does not exist" % args.dem)
        return args.dem
    from aperture import default_dem
    try:
        return default_dem()
    except FileNotFoundError as e:
        raise ApertureError(str(e))


_SMALLER_READ = "read a part with --srcwin, or use --decimate or --overview"

# The DEM reader's and the sky filter's messages name their VTK properties; here they are
# options (every error and warning is printed through _as_options).
_READER_PHRASES = (
    (re.compile(r"read a SubWindow, or use Decimation or an OverviewLevel"), _SMALLER_READ),
    (re.compile(r"(?:SubWindow|the window) \((-?\d+), (-?\d+), (-?\d+), (-?\d+)\)"),
     r"--srcwin \1 \2 \3 \4"),
    (re.compile(r"set BandIndex to choose"), "choose one with --band"),
    (re.compile(r"the (\S+ \S+) MemoryLimit"), r"--max-memory \1"),
    (re.compile(r"use fewer threads \(NumberOfThreads; 1 starts none\)"),
     "use fewer --threads (1 starts none)"),
    (re.compile(r"^OverrideCRS: "), "--srs: "),
    (re.compile(r"set OverrideCRS \(aperture: (--srs EPSG:xxxx[^)]*)\)"), r"give one with \1"),
    (re.compile(r"MetresPerElevationUnit"), "--zfactor"),
    # (bake and render measure a window's cells on the whole raster: a gridline-registered
    # grid's duplicate meridian is a window's too, which the advice to cut it with
    # gdal_translate -srcwin did not tell a user of --srcwin, until 2026-12-07)
    (re.compile(r"that is the whole grid's: a sub-extent's cells are measured on the whole "
                r"grid, so that sub-extents tile it"),
     "--srcwin cannot: the cells of a window are measured on the whole raster, so that "
     "windows of it tile it"),
    (re.compile(r"\(after [a-z, ]+\)"),  # (the reader's steps, only those taken)
     lambda m: m.group(0).replace("subwindow", "--srcwin").replace("overview", "--overview")
     .replace("decimation", "--decimate")),
    (re.compile(r"\bLinkeTurbidity must be within"), "--linke-turbidity must be within"),
    (re.compile(r"\bTurbidity must be within"), "--turbidity must be within"),
)


def _as_options(message):
    """A reader, sky filter or sun message in the command line's words (others pass
    unchanged)."""
    for pattern, words in _READER_PHRASES:
        message = pattern.sub(words, message)
    return message


def _dem_reader(args, watcher, subwindow=True):
    """A reader set up with the arguments' options (not run); subwindow=False leaves --srcwin
    to the caller."""
    from aperture import vtkApertureDEMReader
    if args.band is not None and args.band < 1:
        raise _UsageError("--band must be 1 or more (%d given)" % args.band)
    if args.decimate < 1:
        raise _UsageError("--decimate must be 1 or more")
    if args.overview is not None and args.overview < 0:  # (-1 was taken for none until 12-06)
        raise _UsageError("--overview must be 0 or more (%d given)" % args.overview)
    reader = watcher.watch(vtkApertureDEMReader())
    reader.SetFileName(native_path(_dem_path(args)))
    reader.SetBandIndex(args.band or 0)  # 0: the reader's default, band 1 with a note
    if args.srcwin and min(args.srcwin) < 0:
        raise _UsageError("--srcwin values must not be negative")
    if args.srcwin and subwindow:
        reader.SetSubWindow(*args.srcwin)
    reader.SetOverviewLevel(-1 if args.overview is None else args.overview)
    reader.SetDecimation(args.decimate)
    if args.srs:
        reader.SetOverrideCRS(args.srs)
    reader.SetMetresPerElevationUnit(args.zfactor)
    return reader


def _read(watcher, reader, extent=None):
    """Run the reader (over `extent`, else all of it); Ctrl-C stops it, as a large DEM can take
    minutes to read. Returns its image."""
    with _abort_on_interrupt(reader):
        return watcher.update(reader, extent=extent)


def _elevations(image, extent=None):
    """The image's Elevation array as a numpy view (no copy) of `extent` (within the image's;
    default all of it), [row, column], its first row the southern one."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    e = image.GetExtent()
    extent = extent or e
    z = vtk_to_numpy(image.GetPointData().GetArray("Elevation"))
    z = z.reshape(e[3] - e[2] + 1, e[1] - e[0] + 1)
    return z[extent[2] - e[2]:extent[3] - e[2] + 1, extent[0] - e[0]:extent[1] - e[0] + 1]


def _has_heights(image, extent=None):
    """Whether any cell of `extent` (within the image's; default all of it) has an elevation
    (not NaN, the reader's nodata)."""
    import numpy as np
    return bool(np.isfinite(_elevations(image, extent)).any())


# the bake's record of the elevations it read, which render --baked compares with its own
DIGEST_KEY = "SOURCE_ELEVATION_DIGEST"
DIGEST_TEXT = ("%s (BLAKE2b-128 of the elevations read for the cells baked: 32-bit floats, "
               "little-endian, nodata as NaN, rows north first, each west first; 'aperture "
               "render --baked' compares it)")


def _elevation_digest():
    import hashlib
    return hashlib.blake2b(digest_size=16)


def _digest_rows(digest, image, extent=None):
    """Feed the elevations of `extent` of `image` (within its extent; default all of it) into
    `digest` (_elevation_digest's), its northern row first, as DIGEST_TEXT says."""
    import numpy as np
    z = _elevations(image, extent)
    for row in range(len(z) - 1, -1, -1024):  # (blocks of rows: no copy of all of them)
        block = z[max(row - 1023, 0):row + 1][::-1].astype("<f4")
        block[np.isnan(block)] = np.nan  # (one NaN, whatever payload a reader gave)
        digest.update(block.tobytes())


def _has_data(args, watcher, whole, rows):
    """Whether any cell of the grid the arguments read (band, overview, decimation; `whole`,
    its extent) has data, read in strips of `rows` rows."""
    reader = _dem_reader(args, watcher, subwindow=False)
    for top in range(whole[3], whole[2] - 1, -rows):
        image = _read(watcher, reader, [whole[0], whole[1], max(whole[2], top - rows + 1), top,
                                        0, 0])
        if _has_heights(image):
            return True
    return False


def read_dem(args, watcher):
    """Read the DEM the arguments name (--srcwin as a SubWindow); returns (reader, image)."""
    reader = _dem_reader(args, watcher)
    return reader, _read(watcher, reader)


def _read_centre(args, watcher):
    """The cells at the centre of the grid the arguments read: the 2 or 3 cells a side whose
    centre is the grid's (as vtkApertureSolarPosition::SetPlaceFromImage takes it), so that the
    place of a DEM larger than memory is found too; the whole grid when they are all nodata
    (its nearest valid cell gives the height)."""
    from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as sddp
    reader = _dem_reader(args, watcher)
    watcher.update_information(reader)
    whole = reader.GetOutputInformation(0).Get(sddp.WHOLE_EXTENT())
    block = list(whole)
    for a in (0, 2):
        n = whole[a + 1] - whole[a] + 1
        mid = whole[a] + (n - 1) // 2
        block[a:a + 2] = (mid - 1, mid + 1) if n % 2 and n >= 3 else (mid, mid + (n > 1))
    image = _read(watcher, reader, block)
    return image if _has_heights(image) else _read(watcher, reader, list(whole))


# ---------------------------------------------------------------------------------------------
# info


# `aperture info` reads the elevations for their statistics in strips of whole rows of at most
# this many bytes as float32 (else --max-memory's), so that a DEM larger than memory is
# described too; past _INFO_NOTE_BYTES a note says that they are all being read.
_INFO_STRIP_BYTES = 256 * 2 ** 20
_INFO_NOTE_BYTES = 2 ** 30


def _whole_grid(reader):
    """(a vtkApertureGeoreference of the reader's CRS and whole grid, as SetFromImage takes it
    from an image of the whole extent; the whole extent), after the reader's
    UpdateInformation; without a CRS it can take, the georeference has none (HasCRS false) and
    says why (GetErrorMessage)."""
    from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as sddp
    from aperture import vtkApertureGeoreference
    info = reader.GetOutputInformation(0)
    geo = vtkApertureGeoreference()
    geo.SetFromInformation(info)
    return geo, info.Get(sddp.WHOLE_EXTENT())


def _crs_code(definition):
    """AUTHORITY:CODE of a CRS definition, as GDAL identifies it ("EPSG:2263+6360" for a
    compound one of two coded parts, as --srs takes it), or None."""
    from osgeo import gdal, osr
    srs = osr.SpatialReference()
    gdal.PushErrorHandler("CPLQuietErrorHandler")
    try:
        if srs.SetFromUserInput(definition) != 0:
            return None
        name, code = srs.GetAuthorityName(None), srs.GetAuthorityCode(None)
        if not code and srs.IsCompound():
            horizontal = "PROJCS" if srs.IsProjected() else "GEOGCS"
            parts = [(srs.GetAuthorityName(k), srs.GetAuthorityCode(k))
                     for k in (horizontal, "VERT_CS")]
            if all(n == parts[0][0] and c for n, c in parts):
                name, code = parts[0][0], "+".join(c for _, c in parts)
    except RuntimeError:  # (with GDAL's exceptions on)
        return None
    finally:
        gdal.PopErrorHandler()
    return "%s:%s" % (name, code) if name and code else None


def _geotransform(geo):
    """GDAL's six numbers of geo's grid (north up)."""
    gt = [0.0] * 6
    geo.GetGeoTransform(gt)
    return gt


def _wider_than_the_earth(geo):
    """Whether geo's grid spans more than 360 degrees of longitude (a lat/lon one, or a
    projected one whose columns are meridians: Mercator, equirectangular), with
    geo.GetErrorMessage() saying so (the sky filter's WholeGridProblem asks it first)."""
    return (not geo.IsLocal() and geo.HasMeridianColumns() and
            not geo.CheckLongitudeSpan())


def _central_meridian(geo):
    """A projected CRS's central meridian: its x (the false easting, CRS units) and longitude
    (degrees, as the CRS gives it: not folded into +-180), or (0, None) where the CRS names
    neither (then PROJ's longitude at x = 0 serves)."""
    from osgeo import gdal, osr
    srs = osr.SpatialReference()
    gdal.PushErrorHandler("CPLQuietErrorHandler")
    try:
        if geo.IsGeographic() or srs.SetFromUserInput(geo.GetCRS()) != 0:
            return 0.0, None
        lon0 = srs.GetNormProjParm(osr.SRS_PP_CENTRAL_MERIDIAN, math.nan)
        x0 = srs.GetProjParm(osr.SRS_PP_FALSE_EASTING, math.nan)
    except RuntimeError:  # (with GDAL's exceptions on)
        return 0.0, None
    finally:
        gdal.PopErrorHandler()
    return (x0, lon0) if math.isfinite(lon0) and math.isfinite(x0) else (0.0, None)


def describe(reader, watcher):
    """The facts `aperture info` prints, as a dict (the --json object), from the reader's
    information alone (nothing read): elevation_range and nodata_count are None
    (elevation_statistics gives them). Also returns the grid's georeference and whole
    extent."""
    watcher.update_information(reader)
    geo, whole = _whole_grid(reader)
    if not geo.HasCRS():
        raise ApertureError(geo.GetErrorMessage() or "the DEM has no CRS")
    nx, ny = _extent_size(whole)
    cell_m = [0.0, 0.0]
    bounds = [0.0] * 4
    centre = [0.0, 0.0]
    local = geo.IsLocal()  # (a site grid: metric cells, no place on the Earth)
    wide = _wider_than_the_earth(geo)
    if wide:
        # (a lat/lon grid wider than the Earth, a gridline-registered global one: described
        # all the same, the refusal said, as info is where one looks at the grid that message
        # tells to cut; refused here too until 2026-12-07)
        _warn(geo.GetErrorMessage() + "; bake and render refuse it")
        gt = _geotransform(geo)
        corners = [[0.0, 0.0], [0.0, 0.0]]
        x0, lon0 = _central_meridian(geo)
        origin, half = [0.0, 0.0], [0.0, 0.0]
        wide = (geo.CRSToLonLat(gt[0], gt[3] + ny * gt[5], corners[0]) and
                geo.CRSToLonLat(gt[0] + nx * gt[1], gt[3], corners[1]) and
                geo.CRSToLonLat(x0, gt[3], origin) and
                geo.CRSToLonLat(x0 + 0.5 * gt[1], gt[3], half))
        if wide and not geo.IsGeographic():
            # (a projected grid's edges, which PROJ gives within +-180, an east edge west of the
            # west one, turned by whole turns to where longitude linear in x from the central
            # meridian puts them: as a lat/lon grid's own, 10 to 371 for 361 columns of a
            # degree from 10 E; turned about the grid's middle, -350 to 11, until review; the
            # step from half a column, as ColumnLongitudeStep, for columns up to 360 degrees)
            per_unit = 2.0 * math.remainder(half[0] - origin[0], 360.0) / gt[1]
            lon0 = origin[0] if lon0 is None else lon0
            for corner, x in ((corners[0], gt[0]), (corners[1], gt[0] + nx * gt[1])):
                corner[0] += 360.0 * round((lon0 + (x - x0) * per_unit - corner[0]) / 360.0)
        bounds = [corners[0][0], corners[0][1], corners[1][0], corners[1][1]]
        # (and refused beyond a pole as any grid is, the rows centred on one aside, which the
        # warning says to drop: the check of one column of the other rows)
        # (a row is centred on a pole within a millionth of a cell; a grid of one such row is
        # checked as it is, and refused)
        cell = (bounds[3] - bounds[1]) / ny
        south = int(bounds[1] < -90 - 1e-9 and abs(bounds[1] + 0.5 * cell + 90) <= 1e-6 * cell)
        north = int(bounds[3] > 90 + 1e-9 and abs(bounds[3] - 0.5 * cell - 90) <= 1e-6 * cell)
        origin, spacing = geo.GetGridOrigin(), geo.GetGridSpacing()
        geo.SetGrid(origin[0], origin[1] + south * spacing[1], spacing[0], spacing[1], 1,
                    max(1, ny - south - north))
        if not geo.GetBoundsLonLat([0.0] * 4):
            raise ApertureError(geo.GetErrorMessage())
        geo.SetGrid(origin[0], origin[1], spacing[0], spacing[1], nx, ny)
    # (the bounds first: beyond a pole they name the edge, the cell size only its latitude)
    if not ((local or wide or geo.GetBoundsLonLat(bounds)) and geo.GetCellSizeMetres(cell_m) and
            (local or geo.GetCentreLonLat(centre))):
        raise ApertureError(geo.GetErrorMessage())
    return {
        "file": _full_name(os.fsdecode(reader.GetFileName())),
        "driver": reader.GetDriverName(),
        "bands": reader.GetNumberOfBands(),
        "band": reader.GetBandRead(),
        "size": [nx, ny],
        "crs": geo.GetCRSName(),
        # (its authority's code, "EPSG:4326", where the CRS has one, for gdalwarp -t_srs and
        # the like; and GDAL's geotransform of the grid described, north up)
        "crs_code": _crs_code(geo.GetCRS()),
        "geotransform": _geotransform(geo),
        "geographic": bool(geo.IsGeographic()),
        "local": bool(local),
        "crs_unit": geo.GetCRSUnitName(),
        "cell_size": list(geo.GetGridSpacing()),
        "cell_size_m": cell_m,
        "bounds_lonlat": None if local else bounds,
        "centre_lonlat": None if local else centre,
        # all longitudes: the east and west edges join (the bake sees across them)
        "wraps_around": bool(geo.WrapsAround()),
        "elevation_range": None,
        # metres per unit of the file's elevations, and where that came from
        "elevation_unit_m": reader.GetElevationUnitRead(),
        "elevation_unit_source": _as_options(reader.GetElevationUnitSource()),
        "nodata_count": None,
        # JSON has no NaN or infinity: such a nodata value is reported as the string "nan",
        # "inf" or "-inf" (a float32 band's 1e308 is infinity too)
        "nodata_value": (None if not reader.GetHasNoDataValue()
                         else reader.GetNoDataValue() if math.isfinite(reader.GetNoDataValue())
                         else repr(reader.GetNoDataValue())),
    }, geo, whole


def elevation_statistics(reader, watcher, whole, strip_bytes, progress=None):
    """The elevation range [low, high] and the nodata count of the grid's `whole` extent, read
    in strips of whole rows (north first) of at most `strip_bytes` as float32 each, reporting
    the fraction read to `progress` after each. Every cell nodata gives the range None (and
    every cell counted), as gdalinfo describes such a raster."""
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy

    nx, ny = _extent_size(whole)
    low, high, nodata_count = math.inf, -math.inf, 0
    rows = max(1, min(ny, strip_bytes // (4 * nx)))
    for top in range(whole[3], whole[2] - 1, -rows):
        bottom = max(whole[2], top - rows + 1)
        try:
            image = _read(watcher, reader, [whole[0], whole[1], bottom, top, 0, 0])
        except ApertureError as e:
            # (the reader refuses a read of the whole grid that holds no data, so that a
            # pipeline stops by name at its first step; here it is a fact to describe)
            if not ((bottom, top) == (whole[2], whole[3]) and str(e).endswith(" is nodata")):
                raise
            nodata_count = nx * ny
            break
        values = vtk_to_numpy(image.GetPointData().GetArray("Elevation"))
        nodata = int(np.count_nonzero(np.isnan(values)))  # (the reader's nodata)
        if nodata < values.size:
            # (not the array's GetRange, which VTK 9.1 clamps to +-1e38: cells all 2e38 were
            # described as ranging from 1e38, a value no cell has)
            low, high = min(low, float(np.nanmin(values))), max(high, float(np.nanmax(values)))
        nodata_count += nodata
        if progress:
            progress((whole[3] - bottom + 1) / ny)
    return ([low, high] if low <= high else None), nodata_count


def _format_info(d):
    def deg(v):
        return "%.6f" % v
    unit = d["crs_unit"] or "unit"
    nodata = "" if d["nodata_value"] is None else " (nodata value %s)" % d["nodata_value"]
    lines = [
        "File:       %s (%s, band %d of %d)" % (d["file"], d["driver"], d["band"], d["bands"]),
        "Size:       %d x %d cells (columns x rows)" % tuple(d["size"]),
        "CRS:        %s (%s)" % (d["crs"], "geographic" if d["geographic"] else
                                 "local: a site grid" if d["local"] else "projected"),
        "Cell size:  %.9g x %.9g %s (%.2f m east x %.2f m north at the centre)"
        % (d["cell_size"][0], d["cell_size"][1], unit, d["cell_size_m"][0], d["cell_size_m"][1]),
    ] + ([
        "Bounds:     none in degrees (a local CRS has no geographic coordinates)",
    ] if d["local"] else [
        "Bounds:     west %s, south %s, east %s, north %s (degrees)%s"
        % (*(deg(v) for v in d["bounds_lonlat"]),
           "; all longitudes: the east and west edges join" if d["wraps_around"] else ""),
        "Centre:     longitude %s, latitude %s" % tuple(deg(v) for v in d["centre_lonlat"]),
    ]) + ([
        "Elevation:  %.2f .. %.2f m (unit: %.10g m, %s)"
        % (*d["elevation_range"], d["elevation_unit_m"], d["elevation_unit_source"]),
        "Nodata:     %d cells%s" % (d["nodata_count"], nodata),
    ] if d["elevation_range"] is not None else [
        "Elevation:  none: every cell is nodata (unit: %.10g m, %s)"
        % (d["elevation_unit_m"], d["elevation_unit_source"]),
        "Nodata:     %d cells, all%s" % (d["nodata_count"], nodata),
    ] if d["nodata_count"] is not None else [
        "Elevation:  not read (--no-stats) (unit: %.10g m, %s)"
        % (d["elevation_unit_m"], d["elevation_unit_source"]),
        "Nodata:     not counted (--no-stats)%s" % nodata,
    ])
    return "\n".join(lines)


def _bytes_text(n):
    """A byte count for messages, as the C++ side writes them: "512 bytes", "3.353 GiB"."""
    from aperture import vtkApertureSkyVisibility
    return vtkApertureSkyVisibility.FormatBytes(float(n))


def cmd_info(args):
    watcher = Watcher(on_warning=_warn)
    reader = _dem_reader(args, watcher)
    if args.max_memory is not None:
        reader.SetMemoryLimit(args.max_memory)  # (a row larger than it is refused by name)
    facts, geo, whole = describe(reader, watcher)
    if not args.no_stats:
        # (--max-memory holds a strip and a block of the file, which GDAL reads whole: strips
        # of all of it were refused beside a block until the reader counted it)
        strip_bytes = (max(1, int(args.max_memory - reader.GetBlockBytes())) if args.max_memory
                       else _INFO_STRIP_BYTES)
        nx, ny = facts["size"]
        size = 4.0 * nx * ny  # (bytes as float32)
        progress = None
        if size > strip_bytes and not args.quiet:
            if size > _INFO_NOTE_BYTES:  # (minutes, or more: what it does, and the way out)
                print("%s: note: reading the elevations of all %d x %d cells (%s as float32) "
                      "for their range and nodata count, in strips; --no-stats describes the "
                      "DEM without reading them" % (PROG, nx, ny, _bytes_text(size)),
                      file=sys.stderr)
            if sys.stderr.isatty():
                progress = _TermProgress(sys.stderr)
        try:
            facts["elevation_range"], facts["nodata_count"] = elevation_statistics(
                reader, watcher, whole, strip_bytes, progress)
        except ApertureError:
            if progress and progress.open:
                sys.stderr.write("\n")
            raise
        if facts["elevation_range"]:  # (heights beyond the Earth's, a relief no terrain has)
            implausible = geo.GetElevationWarning(*facts["elevation_range"],
                                                  "Sky products and pictures made of them")
            if implausible:
                _warn(implausible)
    if args.json:
        print(json.dumps(facts, indent=2, allow_nan=False))
    else:
        print(_format_info(facts))
    return 0


# ---------------------------------------------------------------------------------------------
# render


def _parse_size(text):
    try:
        w, h = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError("size must look like 1200x900, not %r" % text)
    if not (16 <= w <= 16384 and 16 <= h <= 16384):
        raise argparse.ArgumentTypeError("width and height must be within 16..16384")
    return w, h


def _memory_size(text):
    """Bytes from '512' (MiB), '300K', '1.5G', '2TiB' (powers of 1024), '4096B' (bytes)."""
    m = re.match(r"^\s*(\d+(?:\.\d*)?|\.\d+)\s*(?:([KMGT])(?:I?B)?|(B))?\s*$", text,
                 re.IGNORECASE)
    value = 0.0
    if m:
        unit = (m.group(2) or "").upper() or ("B" if m.group(3) else "M")
        value = float(m.group(1)) * 1024 ** "BKMGT".index(unit)
    if not (1 <= value < 2 ** 62):
        raise argparse.ArgumentTypeError("%r is not a size (512, 300K, 1.5G, 2T, 4096B)" % text)
    return int(value)


def _number_in(lo, hi, unit=""):
    """A float option within lo..hi: outside, or NaN, a usage error naming the range, before
    any file is read (the C core's ranges, which the filters check again for other callers)."""
    def number(text):
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError("invalid float value: %r" % text)
        if not lo <= value <= hi:
            raise argparse.ArgumentTypeError("%s is outside %g..%g%s"
                                             % (text, lo, hi, " " + unit if unit else ""))
        return value
    return number


def _crs_text(text):
    """--srs: a CRS GDAL makes of the text, checked at parsing (the reader reads it again); an
    empty one is left for _refuse_empty to name."""
    if text:
        from osgeo import gdal, osr
        gdal.PushErrorHandler("CPLQuietErrorHandler")
        try:
            made = osr.SpatialReference().SetFromUserInput(text) == 0
        except RuntimeError:  # (with GDAL's exceptions on)
            made = False
        finally:
            gdal.PopErrorHandler()
        if not made:
            raise argparse.ArgumentTypeError("GDAL cannot parse the CRS %r" % text)
    return text


def _nodata_value(text):
    """--nodata: nan, or a number a Float32 band holds: one that rounds to a finite float
    (-3.4028235e38, numpy's and ESRI's spelling of -FLT_MAX, lies a hair beyond it), which the
    writer declares rounded."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError("invalid float value: %r" % text)
    if not (math.isnan(value) or abs(value) < 3.4028235677973366e38):  # 2^128 - 2^103
        raise argparse.ArgumentTypeError("%s is not a Float32 number (nor nan)" % text)
    return value


def _c_int(text):
    """An integer option that the filters take as a C int: beyond one, a usage error naming
    the limit (not an OverflowError from the setter)."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError("invalid int value: %r" % text)
    if not -2 ** 31 <= value < 2 ** 31:
        raise argparse.ArgumentTypeError("%s is out of range (%d..%d)" % (text, -2 ** 31,
                                                                            2 ** 31 - 1))
    return value


def _gt_text(gt):
    return "none" if gt is None else "(%s)" % ", ".join("%.10g" % v for v in gt)


def _is_openexr(path):
    """Whether the file at `path` starts with OpenEXR's magic number (False if unreadable)."""
    try:
        with open(path, "rb") as f:
            return f.read(4) == b"\x76\x2f\x31\x01"
    except OSError:
        return False


def _attach_baked(image, path, reader):
    """Put BentNormal and ApertureRadius (radians) from a GeoTIFF of `aperture bake` onto the
    DEM image (read by `reader`): the bake's grid must be the image's, or hold it (a bake of a
    whole DEM, the image a --srcwin of it read alike: its cells are read), and the bands and
    elevation units must be the same."""
    from osgeo import gdal
    gdal.UseExceptions()
    kind = _file_kind(os.stat(path).st_mode) if os.path.exists(path) else None
    if kind in ("a pipe", "a socket") and not path.startswith("/vsi"):
        # (as the DEM reader: GDAL's open of a named pipe waits for a writer, for ever)
        raise ApertureError("cannot read the baked file %s: it is %s, not a file" % (path, kind))
    if os.path.isfile(path) and _is_openexr(path):  # (GDAL has no driver: "not recognized")
        raise ApertureError("the baked file %s is an OpenEXR file: --baked takes the GeoTIFF "
                            "'aperture bake' writes (OUT.tif; its --exr is for other tools)"
                            % path)
    try:
        ds = gdal.Open(path)
        _attach_baked_bands(image, path, ds, reader)
    except ApertureError:  # (a RuntimeError too: said as it is)
        raise
    except RuntimeError as e:  # (a damaged file: GDAL's message)
        raise ApertureError("cannot read the baked file %s: %s" % (path, e))
    finally:
        ds = None


def _attach_baked_bands(image, path, ds, reader):
    """_attach_baked's checks and copies, from the open dataset `ds`."""
    import numpy as np
    from vtkmodules.util.numpy_support import numpy_to_vtk
    bands = {ds.GetRasterBand(b).GetDescription(): b for b in range(1, ds.RasterCount + 1)}
    need = ["BentNormal_E", "BentNormal_N", "BentNormal_U", "ApertureRadius"]
    missing = [n for n in need if n not in bands]
    if missing:
        raise ApertureError("%s has no band %s: bake it with 'aperture bake' and its default "
                            "products" % (path, ", ".join(missing)))
    from osgeo import gdal
    for name in need:  # (numpy warned casting complex samples and kept their real parts)
        band = ds.GetRasterBand(bands[name])
        if gdal.DataTypeIsComplex(band.DataType):
            raise ApertureError("%s band %s holds complex numbers (%s), not the products "
                                "'aperture bake' writes: bake this DEM"
                                % (path, name, gdal.GetDataTypeName(band.DataType)))
    nx, ny, _ = image.GetDimensions()
    xoff = yoff = 0
    # the same size is not the same grid: a bake of another DEM (or of another --srcwin,
    # --decimate) would light this one with the wrong sky
    from osgeo import osr
    from aperture import vtkApertureGeoreference
    geo = vtkApertureGeoreference()
    if not geo.SetFromImage(image):  # (the reader's images always carry it)
        if (ds.RasterXSize, ds.RasterYSize) != (nx, ny):
            raise ApertureError("%s is %d x %d cells, the DEM %d x %d: bake this DEM"
                                % (path, ds.RasterXSize, ds.RasterYSize, nx, ny))
    else:
        dem_gt = [0.0] * 6
        geo.GetGeoTransform(dem_gt)
        baked_gt = ds.GetGeoTransform(can_return_null=True)
        window = _window_in(baked_gt, (ds.RasterXSize, ds.RasterYSize), dem_gt, (nx, ny))
        if window is None:
            raise ApertureError("%s covers another grid than the DEM (geotransform %s, %d x %d "
                                "cells; the DEM %s, %d x %d): bake this DEM with the same "
                                "reading options (a bake of all of it serves any --srcwin)"
                                % (path, _gt_text(baked_gt), ds.RasterXSize, ds.RasterYSize,
                                   _gt_text(dem_gt), nx, ny))
        xoff, yoff = window
        dem_srs = osr.SpatialReference()
        dem_srs.ImportFromWkt(geo.GetCRS())
        if dem_srs.IsCompound():
            dem_srs.StripVertical()  # (the bake's file has the horizontal part: DEMWriter)
        baked_srs = ds.GetSpatialRef()
        if baked_srs is None or not baked_srs.IsSame(
                dem_srs, ["IGNORE_DATA_AXIS_TO_SRS_AXIS_MAPPING=YES"]):
            raise ApertureError("%s is in another CRS (%s) than the DEM (%s): bake this DEM"
                                % (path, baked_srs.GetName() if baked_srs else "none",
                                   dem_srs.GetName()))
    # nor from another band of the DEM (bakes since SOURCE_BAND was recorded)
    # (a DEM of one band may be another file's band copied out: not compared)
    baked_band = ds.GetMetadataItem("SOURCE_BAND")
    if baked_band and reader.GetNumberOfBands() > 1 and baked_band != str(reader.GetBandRead()):
        raise ApertureError("%s was baked from band %s of its DEM; this DEM is read from band %d: "
                            "render with the bake's --band" % (path, baked_band,
                                                              reader.GetBandRead()))
    # nor are the same cells the same terrain when their heights were read in another unit
    # (bakes since SOURCE_ELEVATION_UNIT was recorded, as _elevation_unit writes it)
    baked_unit = ds.GetMetadataItem("SOURCE_ELEVATION_UNIT") or ""
    try:
        baked_metres = float(baked_unit.split(" ", 1)[0])
    except ValueError:
        baked_metres = None
    metres = reader.GetElevationUnitRead()
    if baked_metres is not None and abs(baked_metres - metres) > 1e-9 * metres:
        raise ApertureError("%s was baked from elevations in units of %s; the DEM is read in "
                            "units of %s: render with the bake's --zfactor"
                            % (path, baked_unit, _elevation_unit(reader)))
    # nor are the same cells in the same unit the same terrain: another DEM of the grid, or
    # this one edited since, drew shadows of hills it no longer has (bakes since 2026-12-07,
    # when the DEM is the bake's grid: a window of it would need the bake's cells read)
    recorded = (ds.GetMetadataItem(DIGEST_KEY) or "").split(" ", 1)[0]
    if recorded and (xoff, yoff) == (0, 0) and (ds.RasterXSize, ds.RasterYSize) == (nx, ny):
        digest = _elevation_digest()
        _digest_rows(digest, image)
        if digest.hexdigest() != recorded:
            raise ApertureError("%s was baked from other elevations than this DEM's on the same "
                                "cells (another DEM of the grid, or this one since changed): "
                                "bake this DEM again" % path)
    # file rows run north to south, image rows south to north
    def read(name):
        band = ds.GetRasterBand(bands[name])
        values = band.ReadAsArray(xoff, yoff, nx, ny).astype(np.float32)[::-1]
        nodata = band.GetNoDataValue()  # (a bake's --nodata: its cells are NaN here)
        if nodata is not None and not math.isnan(nodata):
            values[values == np.float32(nodata)] = np.nan
        return values
    bent = np.stack([read("BentNormal_E"), read("BentNormal_N"), read("BentNormal_U")], -1)
    radius = np.radians(read("ApertureRadius")).astype(np.float32)
    # A bake of this DEM has a unit bent normal and a radius in 0..180 degrees wherever the
    # DEM has a height; a cell without them is drawn black (a bake of the DEM with voids since
    # filled lit half of it black, silently, until 2026-12-06)
    elevation = _elevations(image)
    with np.errstate(invalid="ignore"):
        sky = ((np.abs(np.linalg.norm(bent, axis=-1) - 1.0) <= 1e-3) &
               (radius >= 0.0) & (radius <= np.float32(math.pi)))
    heights = np.isfinite(elevation)
    unlit = int(np.count_nonzero(heights & ~sky))
    if unlit:
        _warn("%d of the DEM's cells with heights (%.1f%%) have no sky in %s (nodata, or no "
              "unit BentNormal and ApertureRadius of 0..180 degrees): they are drawn black; "
              "bake this DEM again" % (unlit, 100.0 * unlit / np.count_nonzero(heights), path))
    for name, values in (("BentNormal", bent.reshape(-1, 3)), ("ApertureRadius", radius.ravel())):
        array = numpy_to_vtk(np.ascontiguousarray(values), deep=1)
        array.SetName(name)
        image.GetPointData().AddArray(array)


def _window_in(outer_gt, outer_size, inner_gt, inner_size):
    """(column, row) of the grid (inner_gt, inner_size) within the grid (outer_gt, outer_size):
    the same cells (to 1e-3 of a cell), the inner corner on an outer cell's, inside it; else
    None. A rotated grid is taken only when the two are the same."""
    if outer_gt is None or not all(math.isfinite(v) for v in outer_gt):
        return None  # (a NaN origin was a traceback: int(round(nan)))
    cell = max(abs(inner_gt[1]), abs(inner_gt[5]))
    if any(abs(outer_gt[k] - inner_gt[k]) > 1e-3 * cell for k in (1, 2, 4, 5)):
        return None
    if outer_gt[2] or outer_gt[4]:
        return (0, 0) if (all(abs(a - b) <= 1e-3 * cell for a, b in zip(outer_gt, inner_gt))
                          and tuple(outer_size) == tuple(inner_size)) else None
    column = (inner_gt[0] - outer_gt[0]) / outer_gt[1]
    row = (inner_gt[3] - outer_gt[3]) / outer_gt[5]
    xoff, yoff = int(round(column)), int(round(row))
    if abs(column - xoff) > 1e-3 or abs(row - yoff) > 1e-3:
        return None
    if not (0 <= xoff and xoff + inner_size[0] <= outer_size[0] and 0 <= yoff
            and yoff + inner_size[1] <= outer_size[1]):
        return None
    return xoff, yoff


def _render_sun(args, image, watcher):
    """A computed vtkApertureSolarPosition for --at/--tz, or for --sun-az/--sun-el."""
    from aperture import vtkApertureSolarPosition
    sun = watcher.watch(vtkApertureSolarPosition())
    if not sun.SetPlaceFromImage(image):
        raise ApertureError(sun.GetErrorMessage())
    sun.SetTurbidity(args.turbidity)
    sun.SetLinkeTurbidity(args.linke_turbidity)
    if args.at:  # (its text, --tz and --sun-az/--sun-el checked by _render_option_checks)
        if math.isnan(sun.GetLatitude()):
            raise ApertureError("the DEM is in a local CRS (a site grid, no place on the Earth), "
                                "where the sun has no position for a time: give its direction "
                                "with --sun-az/--sun-el instead of --at")
        if args.tz and not sun.SetTimeZone(args.tz):
            raise _UsageError(sun.GetErrorMessage())
        if not sun.SetTime(args.at):
            raise _UsageError(sun.GetErrorMessage())
        if not sun.Compute():
            raise ApertureError(sun.GetErrorMessage())
    else:
        az = 225.0 if args.sun_az is None else args.sun_az
        el = 35.0 if args.sun_el is None else args.sun_el
        if not sun.ComputeForDirection(az, el):
            raise ApertureError(sun.GetErrorMessage())
    watcher.clear()
    return sun


# What drawing a mesh costs this process beyond the mesh, measured with Mesa's llvmpipe (peak
# resident memory over that before the first frame, 2,500 to 9 million points, standard and
# aperture lighting alike: 91 MiB to 959 MiB): OpenGL's fixed start, the vertex and index
# buffers and their driver copies per point, and the rasteriser's bins, which grow with the
# triangles up to a bound. Within 60 MiB below the measurements at 0.4-1.4 million points,
# above them elsewhere (by half at 9 million); a real GPU keeps its buffers off this process.
_DRAW_FIXED_BYTES = 100 << 20
_DRAW_BYTES_PER_POINT = 100
_DRAW_BINS_PER_POINT, _DRAW_BINS_MAX = 120, 512 << 20
# What the picture costs, measured the same way (the embedded DEM at 1000^2 to 12000^2 pixels,
# 2026-12-07: 37 bytes a pixel without antialiasing, 58 with 8 samples, 83 with --exr, whose
# float read-back outlasts the samples; in address space 41 a pixel): its framebuffers and
# read-backs per pixel, and per pixel and sample; with --exr at least the float read-back's.
# A 16384^2 picture took 10 GB, and aborted the process (std::bad_alloc) where less was allowed.
_PICTURE_BYTES_PER_PIXEL, _PICTURE_BYTES_PER_SAMPLE, _PICTURE_EXR_BYTES_PER_PIXEL = 44, 3, 48
# Under an address-space limit (ulimit -v), what OpenGL maps beyond what it makes resident (the
# driver's libraries, and its rasteriser threads' stacks and malloc arenas): measured at a
# 1000^2 picture with LP_NUM_THREADS 1, 2, 4, 8 and 16, 475, 623, 917, 1311 and 1442 MiB (the
# same at 6000^2 with 2 threads): a base and an allowance per thread, smaller past 8 (and
# assumed so up to Mesa's 32).
_DRAW_ADDRESS_BYTES, _DRAW_ADDRESS_BYTES_PER_THREAD = 400 << 20, 160 << 20


def _llvmpipe_threads():
    """The rasteriser threads Mesa's llvmpipe starts: LP_NUM_THREADS, else one per CPU this
    process may run on (none on one), at most 32 (Mesa 22's LP_MAX_THREADS)."""
    try:
        threads = int(os.environ["LP_NUM_THREADS"])
    except (KeyError, ValueError):
        cpus = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else 1
        threads = cpus if cpus > 1 else 0
    return max(0, min(threads, 32))


def _opengl_address_bytes():
    """What _DRAW_ADDRESS_BYTES* give for the threads llvmpipe will start."""
    n = _llvmpipe_threads()
    return (_DRAW_ADDRESS_BYTES + _DRAW_ADDRESS_BYTES_PER_THREAD * min(n, 8)
            + (24 << 20) * max(0, n - 8))


def _resident_bytes():
    """This process's resident memory, bytes (0 where /proc does not say)."""
    try:
        with open("/proc/self/statm") as f:
            return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        return 0


def _check_render_memory(args, nx, ny, bent, to_bake, read_cells):
    """Refuse by name, before the DEM is read, a render of nx x ny points whose mesh, drawing
    and picture would not fit in the memory this process may use (past it Linux kills the
    process): the elevations to read (read_cells, 4 bytes each), the mesher's own estimate
    (`bent`: with a BentNormal to carry, 16 bytes a point of --baked products), what drawing
    adds (_DRAW_*), the picture (_PICTURE_*: --size, --multisamples, --exr), what the process
    holds already, and with `to_bake` the aperture's products still to be made (16 bytes a
    point). Suggests a --decimate factor, or a --size, that fits."""
    from aperture import vtkApertureSkyVisibility as sky
    from aperture import vtkApertureTerrainMesh
    estimate = vtkApertureTerrainMesh()  # (render's mesher: the default precision)

    def need(n):  # the mesh, drawing it, the products
        return (estimate.EstimateBytes(float(n), bent, 0.0) + _DRAW_FIXED_BYTES
                + _DRAW_BYTES_PER_POINT * n + min(_DRAW_BINS_PER_POINT * n, _DRAW_BINS_MAX)
                + (16 * n if to_bake or bent else 0))

    def picture(w, h):
        return float(w) * h * (_PICTURE_BYTES_PER_PIXEL + max(
            _PICTURE_BYTES_PER_SAMPLE * args.multisamples,
            _PICTURE_EXR_BYTES_PER_PIXEL if args.exr else 0))

    # (an address-space limit's usable memory is what it leaves beside all that is mapped)
    limited = sky.IsMemoryAddressLimited()
    own, read = _opengl_address_bytes() if limited else _resident_bytes(), 4.0 * read_cells
    held = own + read
    usable = float(sky.GetUsableMemory())
    width, height = args.size
    shown = picture(width, height)
    total = need(nx * ny) + shown
    if held + total <= usable:
        return
    mesh = estimate.EstimateBytes(float(nx * ny), bent, 0.0)
    message = ("rendering a mesh of %d x %d points in a picture of %d x %d pixels needs about "
               "%s (the mesh %s, the picture %s, drawing them and the rest %s), more than the "
               "%s of memory %s%s"
               % (nx, ny, width, height, _bytes_text(total), _bytes_text(mesh),
                  _bytes_text(shown), _bytes_text(total - mesh - shown),
                  _bytes_text(max(0.0, usable - held)), sky.GetUsableMemoryOwner(),
                  " beside the %s that %s and the elevations take" % (
                      _bytes_text(held), "OpenGL maps" if limited else "this process holds")))
    fits = []
    for f in range(2, min(nx, ny) // 2 + 1):  # (a mesh of at least 2 x 2 points)
        if own + read / (f * f) + need((nx // f) * (ny // f)) + shown <= usable:
            fits.append("--decimate %d" % (f * args.decimate))
            break
    for size in range(max(width, height) - 1, 15, -1):  # (the aspect kept, 16 pixels or more)
        w, h = (size, max(16, height * size // width)) if width >= height else (
            max(16, width * size // height), size)
        if held + need(nx * ny) + picture(w, h) <= usable:
            fits.append("--size %dx%d" % (w, h))
            break
    raise ApertureError("%s; %s would fit" % (message, " or ".join(fits)) if fits else message)


def _check_display():
    """Refuse by name a DISPLAY no X server answers (a stale one of an ssh session, a stopped
    Xvfb): VTK would abort the process (SIGABRT) when it opens its window, its message
    silenced with the rest of its console output. Xlib's XOpenDisplay is asked first."""
    import ctypes
    try:
        x11 = ctypes.CDLL("libX11.so.6")
    except OSError:
        return  # (no Xlib to ask: VTK's own try decides)
    x11.XOpenDisplay.restype = ctypes.c_void_p
    x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
    x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
    display = x11.XOpenDisplay(None)
    if not display:
        raise ApertureError("cannot connect to the X display %r (DISPLAY): no X server answers "
                            "there; run under xvfb-run -a" % os.environ.get("DISPLAY"))
    x11.XCloseDisplay(display)


# render's options that only --lighting aperture uses, with their defaults (the parser's are
# None, so that an option given with --lighting standard, which would ignore it, is named)
_APERTURE_LIGHTING_OPTIONS = (
    ("--radius", "radius", None), ("--baked", "baked", None), ("--albedo", "albedo", None),
    ("--intersection", "intersection", "exact"), ("--lambert", "lambert", "centroid"),
    ("--sun-scale", "sun_scale", 1.0), ("--sky", "sky", "constant"),
    ("--shading", "shading", "pixel"), ("--turbidity", "turbidity", 3.0),
    ("--linke-turbidity", "linke_turbidity", 3.0))


_MOST_FRAMES = 10000  # (a year of hourly frames)


def _frame_option_checks(args):
    """Refuse --frames and --step given wrongly; set args.frame_paths, the (option, names)
    of each output, one name a frame (one name without --frames), and args.step."""
    if args.frames is None:
        if args.step is not None:
            raise _UsageError("--step %g needs --frames: it is the time between frames"
                              % args.step)
        args.frame_paths = [(o, [p]) for o, p in (("--output", args.output), ("--exr", args.exr))
                            if p]
        for option, path in args.frame_paths:
            if _frame_numbers(path[0]):  # (written as it is, % and all, without a word before)
                _warn("%s %s holds a frame number, but without --frames one picture is written, "
                      "by that name" % (option, path[0]))
        return
    if not 1 <= args.frames <= _MOST_FRAMES:
        raise _UsageError("--frames must be within 1..%d" % _MOST_FRAMES)
    if not args.at:
        raise _UsageError("--frames needs --at, the time of the first frame (the sun moves "
                          "through time)")
    args.step = 10.0 if args.step is None else args.step
    _check_step(args.step)
    args.frame_paths = [(o, _frame_names(o, p, args.frames))
                        for o, p in (("--output", args.output), ("--exr", args.exr)) if p]


def _check_step(minutes):
    """Refuse a --step (render's and sun's) under a second or not finite: a usage error."""
    if not (minutes >= 1.0 / 60.0 and math.isfinite(minutes)):
        raise _UsageError("--step must be a number of minutes of at least one second's, "
                          "1/60 (0.016666667)")


def _step_seconds(minutes):
    """A --step in seconds, to the microsecond that the times are written to: 0.016666667
    minutes (1/60 as written) is 1.00000002 s, whose drift showed from the 31st time on
    (12:00:30.000001Z), fractions of seconds being written since 2026-12-07. (A step of
    more seconds than a double holds to the microsecond is taken as it is, and one past the
    largest double as that: 1e307 minutes made the first time 0 x inf, NaN.)"""
    seconds = min(minutes * 60.0, sys.float_info.max)
    return round(seconds, 6) if seconds < 1e15 else seconds


_FRAME_NUMBER = re.compile(r"%(?:%|(0?[1-9]?)d)")


def _frame_numbers(pattern):
    """The matches of the frame number's %d, %Nd or %0Nd in `pattern` (not its %% signs)."""
    return [m for m in _FRAME_NUMBER.finditer(pattern) if m.group(0) != "%%"]


def _frame_name(pattern, number):
    """`pattern` with its frame number written: %d as it is, %Nd and %0Nd with N digits (zeros
    before it, as ffmpeg reads both: Python's %4d put spaces there, so ffmpeg -i f-%4d.png
    found none of the frames until 2026-12-07), %% as %."""
    return _FRAME_NUMBER.sub(lambda m: "%" if m.group(0) == "%%" else "%0*d" % (
        int(m.group(1) or 0), number), pattern)


def _frame_names(option, pattern, count):
    """The `count` file names of a time-lapse output given as `pattern`, a name holding the
    frame number as %d, or %Nd / %0Nd (a width N of 1 to 9), and %% for a % sign. A usage error
    for any other % in it, two numbers, or (count > 1) none."""
    numbers = _frame_numbers(pattern)
    bare = _FRAME_NUMBER.sub("", pattern)
    if "%" in bare or len(numbers) > 1:
        raise _UsageError("%s %s: the frame number is written %%d, %%4d or %%04d in the name "
                          "(once), and a %% sign itself %%%%" % (option, pattern))
    names = [_frame_name(pattern, k) for k in range(count)]
    if count > 1 and names[0] == names[1]:
        raise _UsageError("--frames %d writes %d pictures: give %s a name with the frame "
                          "number, such as frame-%%03d%s (%s would be overwritten by each)"
                          % (count, count, option, os.path.splitext(names[0])[1] or ".png",
                             names[0]))
    return names


def _earlier_frames(pattern, count):
    """The files beside a time-lapse's frames that its `pattern` names with a frame number of
    `count` or more: frames of an earlier, longer series, which a video made from the pattern
    (ffmpeg -i frame-%03d.png) would append to this one. Sorted by number."""
    number = _frame_numbers(pattern)
    if not number:
        return []
    head, tail = pattern[:number[0].start()], pattern[number[0].end():]
    folder, head = os.path.split(head.replace("%%", "%"))
    shape = re.compile(re.escape(head) + r"(\d+)" + re.escape(tail.replace("%%", "%")) + "$")
    try:
        names = os.listdir(folder or ".")
    except OSError:
        return []
    found = []
    for name in names:
        m = shape.match(name)
        k = int(m.group(1)) if m else -1
        path = os.path.join(folder, name)
        # (normalised: the pattern's folder may be written ./ or with doubled slashes)
        if k >= count and os.path.normpath(_frame_name(pattern, k)) == os.path.normpath(path):
            found.append((k, path))
    return [path for _, path in sorted(found)]


def _render_option_checks(args):
    """Refuse render options that another one makes meaningless (each would be ignored
    without a word), then fill in the defaults of the aperture's options."""
    if args.lighting == "standard":
        given = [name for name, key, _ in _APERTURE_LIGHTING_OPTIONS
                 if getattr(args, key) is not None]
        if given:
            raise _UsageError("%s %s only with --lighting aperture: VTK's standard lighting "
                              "draws the elevation colours lit by a white light from the sun's "
                              "direction" % (", ".join(given),
                                             "applies" if len(given) == 1 else "apply"))
    for _, key, default in _APERTURE_LIGHTING_OPTIONS:
        if getattr(args, key) is None:
            setattr(args, key, default)
    if args.baked and args.radius is not None:
        raise _UsageError("--radius is the search distance of an aperture baked here; --baked "
                          "reads one baked before (its radius is in its metadata)")
    if args.tz and not args.at:
        raise _UsageError("--tz %s needs --at: it is the time zone of a local --at time"
                          % args.tz)
    if args.exr_type and not args.exr:
        raise _UsageError("--exr-type %s needs --exr OUT.exr" % args.exr_type)
    args.exr_type = args.exr_type or "float"
    if not (0.0 <= args.exaggeration <= 1000.0):
        raise _UsageError("--exaggeration must be within [0, 1000]")
    if not 0 <= args.multisamples <= 16:
        raise _UsageError("--multisamples must be within 0..16")
    if not (args.sun_scale > 0 and math.isfinite(args.sun_scale)):
        raise _UsageError("--sun-scale must be a positive factor")
    if args.exposure is not None and not -30.0 <= args.exposure <= 30.0:
        # (the mapper clamps to this range: 2^30 is already a billion times)
        raise _UsageError("--exposure must be within -30..30 EV")
    if args.at:
        if args.sun_az is not None or args.sun_el is not None:
            raise _UsageError("give either --at or --sun-az/--sun-el, not both")
        # (the time read as the render will read it, before any file or display is looked at)
        from aperture import vtkApertureSolarPosition
        sun = vtkApertureSolarPosition()
        if args.tz and not sun.SetTimeZone(args.tz):
            raise _UsageError(sun.GetErrorMessage())
        if not sun.SetTime(args.at):
            raise _UsageError(sun.GetErrorMessage())
    elif not (-90.0 <= (args.sun_el or 0.0) <= 90.0) or not math.isfinite(args.sun_az or 0.0):
        raise _UsageError("--sun-el must be within [-90, 90] degrees (and --sun-az finite)")
    _frame_option_checks(args)
    if args.frames:  # (--frames needs --at: `sun` holds it)
        _check_frame_years(args, sun)
    from aperture import vtkApertureLinearCapture
    if args.exr and (16.0 * args.size[0] * args.size[1]
                     >= vtkApertureLinearCapture.GetMaximumBytes()):
        raise _UsageError("--exr reads the picture back as float RGBA, 16 bytes a pixel, and "
                          "VTK reads back less than 4 GiB: %dx%d is too large for it; give "
                          "a smaller --size" % tuple(args.size))


def _interruptible_import(name):
    """The module `name`, imported with a Ctrl-C meanwhile reported as one: VTK's module loader
    turns the KeyboardInterrupt into an ImportError of whatever it was loading ("Failed to load
    vtkRenderingOpenGL2: No module named vtkmodules.vtkFiltersGeneral", a traceback and exit 1
    in render's first half second, until 2026-12-06) or swallows it; the signal is noted
    here, as the launcher notes it while it loads, and KeyboardInterrupt follows. A SIGINT
    ignored or handled otherwise is left as it is."""
    import importlib
    import signal
    noted = []

    def on_interrupt(signum, frame):
        noted.append(signum)
        raise KeyboardInterrupt

    previous = signal.getsignal(signal.SIGINT)
    ours = previous is signal.default_int_handler
    if ours:
        try:
            signal.signal(signal.SIGINT, on_interrupt)
        except ValueError:  # (not the main thread: signals are the main thread's)
            ours = False
    try:
        module = importlib.import_module(name)
    except ImportError:
        if noted:
            raise KeyboardInterrupt from None
        raise
    finally:
        if ours:
            signal.signal(signal.SIGINT, previous)
    if noted:
        raise KeyboardInterrupt
    return module


def cmd_render(args):
    from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as sddp
    from aperture import vtkApertureSkyVisibility, vtkApertureTerrainMesh
    scene = _interruptible_import("aperture.scene")  # (VTK's rendering: a few tenths of a s)

    _render_option_checks(args)

    _check_frame_outputs(args.frame_paths, [("the DEM", _dem_path(args)), ("--baked", args.baked),
                                            ("--albedo", args.albedo)])
    outputs = [(option, name) for option, names in args.frame_paths for name in names]
    if not os.environ.get("DISPLAY"):
        raise ApertureError("rendering needs an X display (VTK on Debian renders through GLX); "
                            "run under xvfb-run -a")
    _check_display()
    if args.albedo and not os.path.isfile(args.albedo):
        raise ApertureError("the albedo image %s %s" % (args.albedo, "does not exist" if not
                            os.path.exists(args.albedo) else "is %s, not a file"
                            % _file_kind(os.stat(args.albedo).st_mode)))
    _check_radius(args.radius)
    # (the picture first: a bad one is refused before the bake)
    albedo, albedo_bounds = _read_albedo(args.albedo) if args.albedo else (None, None)
    watcher = Watcher(on_warning=_warn)
    bake_here = args.lighting == "aperture" and not args.baked
    if bake_here:
        sky = watcher.watch(vtkApertureSkyVisibility())
        sky.SetMaximumDistance(args.radius or 0.0)
        for name in DERIVED + ["HorizonAngles"]:
            getattr(sky, "SetCompute" + name)(name in ("BentNormal", "ApertureRadius"))
        # the aperture of a --srcwin window sees the DEM around it, as bake --srcwin's does
        reader, window, read, _ = _window_reading(args, watcher, sky)
        _check_sources(outputs, reader)
        _check_render_memory(args, window[1] - window[0] + 1, window[3] - window[2] + 1,
                             True, True, _cells(read))
        _read(watcher, reader, read)
        early = _render_sun(args, reader.GetOutput(), watcher)  # (before the bake: a DEM
        if args.frames:  # in a local CRS, a --frames series past the algorithm's years)
            _frame_times(args, early)
        with _abort_on_interrupt(sky):
            image = source = watcher.update(sky, "bake", extent=window)
    else:
        reader = _dem_reader(args, watcher)
        watcher.update_information(reader)  # (which files it reads: a VRT's sources)
        geo, whole = _whole_grid(reader)
        if _wider_than_the_earth(geo):
            # (before the DEM is read, which render does itself before the mesher runs: it
            # was read whole, and then refused by the mesher, until 2026-12-07)
            raise ApertureError(geo.GetErrorMessage())
        _check_sources(outputs, reader)
        _check_render_memory(args, *_extent_size(whole), bool(args.baked), False, _cells(whole))
        image = _read(watcher, reader)
        if args.baked:
            _attach_baked(image, args.baked, reader)
        source = image
    # (after the refusals about the outputs: not a warning, then an error, for one mistake)
    for option, names in args.frame_paths:
        _warn_extension(names[0], (".png",) if option == "--output" else (".exr",),
                        "a PNG" if option == "--output" else "an OpenEXR file")
        earlier = _earlier_frames(args.output if option == "--output" else args.exr,
                                  args.frames) if args.frames else []
        if earlier:
            _warn("%s: %s beyond this series' %d frame%s match%s its name, from an earlier "
                  "series: a video made from the name would include %s" % (
                      option, earlier[0] if len(earlier) == 1 else "%d files (%s to %s)" % (
                          len(earlier), earlier[0], earlier[-1]),
                      args.frames, "" if args.frames == 1 else "s",
                      "es" if len(earlier) == 1 else "", "it" if len(earlier) == 1 else
                      "them"))
    misplaced = _albedo_placement_warning(args.albedo, albedo_bounds, image) if args.albedo \
        else None
    if misplaced:
        _warn(misplaced)
    sun = _render_sun(args, image, watcher)
    times, exposure = _time_lapse(args, sun, image) if args.frames else ([None], args.exposure)
    if not args.frames and sun.GetElevation() < 0.0:  # (the models end at the horizon)
        _warn("the sun is %.2f degrees below the horizon%s: the terrain is unlit (%s): black%s"
              % (-sun.GetElevation(), " at that time" if args.at else "", _unlit_why(args),
                 _sun_up_elsewhere(image, sun) if args.at else ""))
    # (the mesher names implausible elevations, beyond the Earth's or steeper than terrain, as
    # the sky filter does: said once is enough)
    named = [w for w in watcher.warnings if w.startswith("elevations range ")]
    mesh_watcher = Watcher(on_warning=lambda m: None if named and m.startswith(
        "elevations range ") else _warn(m))
    mesher = mesh_watcher.watch(vtkApertureTerrainMesh())
    mesher.SetInputData(source)
    mesher.SetVerticalExaggeration(args.exaggeration)
    with _abort_on_interrupt(mesher):  # (half a minute for 10^8 points)
        mesh = mesh_watcher.update(mesher, "meshing")

    texture = None
    if albedo is not None:
        from vtkmodules.vtkRenderingCore import vtkTexture
        texture = vtkTexture()
        texture.SetInputData(albedo)
        texture.InterpolateOn()
    if args.lighting == "aperture":
        window, renderer, mapper = scene.build_aperture(
            mesh, sun, size=args.size, view=args.view, sun_scale=args.sun_scale,
            intersection=args.intersection, lambert=args.lambert, exposure=exposure,
            texture=texture, multisamples=args.multisamples, camera=args.camera,
            sky_mode=args.sky, shading=args.shading)
    else:
        window, renderer = scene.build(mesh, size=args.size, view=args.view,
                                       light_azimuth=sun.GetAzimuth(),
                                       light_elevation=sun.GetElevation(),
                                       exposure=exposure or 0.0,
                                       multisamples=args.multisamples, camera=args.camera)
        mapper = renderer.GetActors().GetLastActor().GetMapper()
    exposure = mapper.GetExposure()
    names = dict(args.frame_paths)
    with _ends_between_frames(args.frames) as between:
        for k, t in enumerate(times):
            try:
                _render_frame(args, k, t, sun, window, renderer, mapper, exposure, names,
                              watcher)
            except ApertureError as e:
                if not (args.frames and k):
                    raise
                # (which frames are whole, as an interrupted time-lapse says)
                raise ApertureError("%s (frame%s %s of %d written)" % (
                    e, "s" if k > 1 else "", _ranges_text(range(k)), args.frames)) from None
            between(k)
    return 0


class _ends_between_frames:
    """Ctrl-C (SIGINT), SIGTERM or SIGHUP during render's drawing and writing: noted, and acted
    on between frames (the call the context gives, after each), so every frame's PNG and EXR
    are whole or not begun (a SIGTERM ended the process in a PNG's write, leaving half of it);
    KeyboardInterrupt follows (exit 130; _Terminated, 143 or 129), and an interrupted
    time-lapse says which frames it wrote."""

    def __init__(self, frames):
        self.frames = frames  # (None: one picture)

    def __enter__(self):
        self.received, self.done = [], []
        self.previous = _handle_ending_signals(
            lambda signum, frame: self.received.append(signum))
        return self._between

    def _between(self, frame):
        self.done.append(frame)
        if self.received:
            if self.frames:
                print("%s: interrupted: frame%s %s of %d written" % (
                    PROG, "s" if len(self.done) > 1 else "", _ranges_text(self.done),
                    self.frames), file=sys.stderr)
            raise _interruption(self.received)

    def __exit__(self, kind, value, traceback):
        _restore_signals(self.previous)
        return False


def _render_frame(args, k, t, sun, window, renderer, mapper, exposure, names, watcher):
    """Draw and write frame k (at POSIX time t; None: the picture of one render)."""
    from aperture import scene
    if t is not None:  # (a frame of a time-lapse: the sun moves, nothing else)
        sun.SetUnixTime(t)
        sun.Compute()  # (each computed before, by _time_lapse)
        if args.lighting == "aperture":
            scene.set_sun(mapper, sun, args.sky)
        else:
            scene.aim_light(renderer, sun.GetAzimuth(), sun.GetElevation())
    try:
        path = scene.write_png(window, names["--output"][k], on_warning=_warn,
                               text=_render_metadata(args, sun, exposure, k))
    except (OSError, RuntimeError) as e:
        raise ApertureError(str(e))
    if not args.quiet:
        when = ""
        if args.frames:  # (the local time too with --tz: a day's frames in its hours)
            local = sun.GetLocalTimeString() if args.tz else None
            when = "%s%s, " % (sun.GetTimeString(), " (local %s)" % local if local else "")
        print("wrote %s (%d x %d, %s view, %ssun azimuth %.2f, elevation %.2f deg, %s)" % (
            path, args.size[0], args.size[1], args.view, when, sun.GetAzimuth(),
            sun.GetElevation(), "exposure %.2f EV" % exposure if args.lighting == "aperture"
            else "VTK lighting"))
    if args.exr:
        exr_path = _write_linear_exr(args, names["--exr"][k], window, mapper, sun, watcher, k)
        if not args.quiet:
            print("wrote %s (linear radiance, %s, %s)" % (
                exr_path, "W/m2/sr" if args.lighting == "aperture" else "VTK lighting",
                args.exr_type))


def _grid_places(image):
    """5 x 5 places spread over the DEM image's grid, as (latitude, longitude) in degrees
    (taken from the grid's own coordinates: a projected DEM's box in longitude and latitude
    reaches beyond it, and across the antimeridian its west edge lies east of its east one);
    [] for a DEM in a local CRS."""
    from aperture import vtkApertureGeoreference
    geo = vtkApertureGeoreference()
    if not geo.SetFromImage(image) or geo.IsLocal():
        return []
    (x0, y0, _), (dx, dy, _) = image.GetOrigin(), image.GetSpacing()
    nx, ny, _ = image.GetDimensions()
    places, lonlat = [], [0.0, 0.0]
    for i in range(5):
        for j in range(5):
            if geo.CRSToLonLat(x0 + dx * (nx - 1) * i / 4.0, y0 + dy * (ny - 1) * j / 4.0,
                               lonlat) and all(map(math.isfinite, lonlat)):
                places.append((lonlat[1], math.remainder(lonlat[0], 360.0)))
    return places


def _highest_sun(places, t):
    """The sun's highest apparent elevation at POSIX time t over `places` (_grid_places):
    (degrees, latitude, longitude), or None."""
    from aperture import vtkApertureSolarPosition
    best = None
    probe = vtkApertureSolarPosition()
    probe.SetUnixTime(t)
    for lat, lon in places:
        probe.SetLatitude(lat)
        probe.SetLongitude(lon)
        if probe.Compute() and (best is None or probe.GetElevation() > best[0]):
            best = (probe.GetElevation(), lat, lon)
    return best


# (the clause of the warnings about a sun below the horizon where it is up over part of the DEM:
# the render takes the light of the centre's sun for all of it, and a continent was black while
# its west coast's sun stood at 9.5 degrees, the warning saying only that the sun was down)
_CENTRE_LIGHT = "the light is the DEM centre's, though over part of the DEM the sun is up"


def _sun_up_elsewhere(image, sun):
    """For a DEM whose centre's sun is below the horizon at `sun`'s time: the warning's clause
    saying where over the DEM it is up, or "" if nowhere."""
    best = _highest_sun(_grid_places(image), sun.GetUnixTime())
    if best is None or best[0] < 0.05:  # (up, to the digit said)
        return ""
    elevation, lat, lon = best
    return ("; %s (%.1f degrees at %.2f %s, %.2f %s): render that part (--srcwin)"
            % (_CENTRE_LIGHT, elevation, abs(lat), "N" if lat >= 0 else "S", abs(lon),
               "E" if lon >= 0 else "W"))


def _unlit_why(args):
    """Why a sun below the horizon leaves the terrain black, for the lighting drawn."""
    # (a frame black while 'aperture sun' said the sun had risen puzzled: its sunrise is the
    # upper limb's, minutes before the centre's, or a whole short polar day before it, until
    # 2026-12-07 not said)
    return ("the sky models have no twilight, and the sun lights nothing until its centre is "
            "up: 'aperture sun' gives sunrise and sunset for its upper limb, earlier and later "
            "(minutes; near the poles, days)" if args.lighting == "aperture" else
            "VTK's light, from the sun's direction, is below it")


def _time_lapse(args, sun, image):
    """The --frames' times (POSIX seconds from the computed `sun`'s, every --step minutes),
    each computed before any frame is drawn (a series past the algorithm's years fails first),
    and their one exposure: --exposure, or (aperture lighting) the automatic one of the frame
    whose sun is highest. Warns once of the frames whose sun is below the horizon (black).
    Leaves `sun` at the first frame."""
    from aperture import scene
    start = sun.GetUnixTime()
    times, elevations = _frame_times(args, sun)
    dark = [k for k, e in enumerate(elevations) if e < 0.0]
    if dark:
        places = _grid_places(image)
        up = [k for k in dark if (_highest_sun(places, times[k]) or (0.0,))[0] >= 0.05]
        _warn("the sun is below the horizon in %d of the %d frames (%s): the terrain is unlit "
              "there (%s): black%s" % (len(dark), args.frames, _ranges_text(dark),
                                       _unlit_why(args), "; in %s %s (render that part: "
                                       "--srcwin)" % (_ranges_text(up), _CENTRE_LIGHT)
                                       if up else ""))
    exposure = args.exposure
    if exposure is None and args.lighting == "aperture":
        sun.SetUnixTime(times[elevations.index(max(elevations))])
        sun.Compute()
        sun_rgb = [0.0] * 3
        sun.GetSunColor(sun_rgb)
        exposure = scene.auto_exposure(sun_rgb, sun.GetElevation(), scene.sky_radiance(sun))
    sun.SetUnixTime(start)
    sun.Compute()
    return times, exposure


def _check_frame_years(args, sun):
    """Refuse a --frames series that runs past the algorithm's years before anything is read
    (found after the DEM was read and every frame's name checked, 10 s for 10,000 frames,
    until 2026-12-07). The years do not depend on the place (the sun is computed at 0 N 0 E
    here), and the times increase: the last frame is the one to check."""
    start = sun.GetUnixTime()
    sun.SetLatitude(0.0)
    sun.SetLongitude(0.0)
    sun.SetUnixTime(start + (args.frames - 1) * _step_seconds(args.step))
    if not sun.Compute():
        sun.SetUnixTime(start)
        _frame_times(args, sun)  # (which names the first frame past them)


def _frame_times(args, sun):
    """The --frames' times (POSIX seconds from the computed `sun`'s, every --step minutes) and
    the sun's elevations at them, each computed: a usage error for a series that runs past the
    algorithm's years (a fact of --at, --step and --frames). Leaves `sun` at the first."""
    start = sun.GetUnixTime()
    step = _step_seconds(args.step)
    times = [start + k * step for k in range(args.frames)]
    elevations = []
    for k, t in enumerate(times):
        sun.SetUnixTime(t)
        if not sun.Compute():
            raise _UsageError("frame %d of --frames %d, %g minutes after --at %s: %s" % (
                k, args.frames, k * args.step, args.at, sun.GetErrorMessage()))
        elevations.append(sun.GetElevation())
    sun.SetUnixTime(start)
    sun.Compute()
    return times, elevations


def _ranges_text(numbers):
    """'0-5, 9, 40-47' for sorted integers; past 7 stretches the first 6 and the last, with
    their count (a year's nights were 4.8 kB of one warning line)."""
    runs = []
    for n in numbers:
        if runs and n == runs[-1][1] + 1:
            runs[-1][1] = n
        else:
            runs.append([n, n])
    texts = ["%d" % a if a == b else "%d-%d" % (a, b) for a, b in runs]
    if len(texts) > 7:
        return "%s, ..., %s: %d stretches" % (", ".join(texts[:6]), texts[-1], len(texts))
    return ", ".join(texts)


ALBEDO_MAX_SIDE = 4096  # texels on the albedo texture's longer side


def _read_albedo(path):
    """The --albedo picture as a VTK image of RGB bytes, row 0 south (as the mesh's texture
    coordinates), read with GDAL: 1 band grey (or a palette), 2 grey (or a palette) and alpha,
    3 RGB, 4 RGBA (alpha is ignored), unsigned 8- or 16-bit samples (16-bit scaled by
    255/65535), at most ALBEDO_MAX_SIDE pixels on its longer side (a larger one averaged down,
    through the file's overviews when it has them); and its bounds in degrees (west, south,
    east, north) when it is georeferenced, else None."""
    import numpy as np
    from osgeo import gdal
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonDataModel import vtkImageData
    gdal.UseExceptions()
    try:
        ds = gdal.Open(path)
    except RuntimeError as e:
        raise ApertureError("cannot read the albedo image %s: %s" % (path, e))
    bands = [ds.GetRasterBand(b) for b in range(1, ds.RasterCount + 1)]
    if not 1 <= len(bands) <= 4:
        raise ApertureError("the albedo image %s has %d bands; --albedo takes 1 (grey), 2 (grey, "
                            "alpha), 3 (RGB) or 4 (RGBA)" % (path, len(bands)))
    kind = gdal.GetDataTypeName(bands[0].DataType)
    if kind not in ("Byte", "UInt16"):
        raise ApertureError("the albedo image %s has %s samples (elevations?); --albedo takes a "
                            "picture of unsigned 8- or 16-bit samples (PNG, JPEG, TIFF)"
                            % (path, kind))
    palette = bands[0].GetColorTable() if len(bands) <= 2 else None  # (with alpha: 2 bands)
    scale = min(1.0, ALBEDO_MAX_SIDE / max(ds.RasterXSize, ds.RasterYSize))
    width = max(1, round(ds.RasterXSize * scale))
    height = max(1, round(ds.RasterYSize * scale))
    channels = 1 if len(bands) <= 2 else 3
    try:
        # (a palette's indices are picked, not averaged)
        pixels = np.stack([b.ReadAsArray(buf_xsize=width, buf_ysize=height, resample_alg=(
            gdal.GRIORA_NearestNeighbour if palette else gdal.GRIORA_Average))
            for b in bands[:channels]], axis=-1)
    except RuntimeError as e:
        raise ApertureError("cannot read the albedo image %s: %s" % (path, e))
    if palette is not None:
        table = np.array([palette.GetColorEntry(k)[:3] for k in range(palette.GetCount())] or
                         [(0, 0, 0)], dtype=np.uint8)
        rgb = table[np.minimum(pixels[:, :, 0], len(table) - 1)]
    else:
        if kind == "UInt16":
            pixels = np.round(pixels * (255.0 / 65535.0))
        rgb = np.broadcast_to(pixels, (height, width, 3)).astype(np.uint8)
    image = vtkImageData()
    image.SetDimensions(width, height, 1)
    values = numpy_to_vtk(np.ascontiguousarray(rgb[::-1]).reshape(-1, 3), deep=1)
    values.SetName("Albedo")
    image.GetPointData().SetScalars(values)
    return image, _raster_bounds_lonlat(ds)


def _raster_bounds_lonlat(ds):
    """A GDAL dataset's bounds in degrees (west, south, east, north; its corners and edge
    midpoints), or None without a geotransform and CRS, or with one PROJ cannot convert."""
    from osgeo import osr
    gt, srs = ds.GetGeoTransform(can_return_null=True), ds.GetSpatialRef()
    if gt is None or srs is None:
        return None
    wgs84 = osr.SpatialReference()
    wgs84.ImportFromEPSG(4326)
    for crs in (srs, wgs84):
        crs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    try:
        to = osr.CoordinateTransformation(srs, wgs84)
        points = [to.TransformPoint(gt[0] + u * gt[1] + v * gt[2], gt[3] + u * gt[4] + v * gt[5])
                  for u in (0, ds.RasterXSize / 2, ds.RasterXSize)
                  for v in (0, ds.RasterYSize / 2, ds.RasterYSize)]
    except RuntimeError:
        return None
    lon, lat = [p[0] for p in points], [p[1] for p in points]
    return min(lon), min(lat), max(lon), max(lat)


def _albedo_placement_warning(path, bounds, image):
    """The warning for a georeferenced --albedo picture whose bounds (degrees) differ from the
    DEM image's by more than 1% of its size (it is stretched over the DEM all the same), else
    None: a plain picture, or a DEM without a place on the Earth or around the globe."""
    from aperture import vtkApertureGeoreference
    geo = vtkApertureGeoreference()
    dem = [0.0] * 4
    if (bounds is None or not geo.SetFromImage(image) or geo.IsLocal() or geo.WrapsAround()
            or not geo.GetBoundsLonLat(dem)):
        return None
    size = (dem[2] - dem[0], dem[3] - dem[1])
    if all(abs(a - b) <= 0.01 * size[k % 2] for k, (a, b) in enumerate(zip(bounds, dem))):
        return None
    return ("the albedo image %s covers longitude %.6f..%.6f, latitude %.6f..%.6f, the DEM "
            "%.6f..%.6f, %.6f..%.6f: the picture is stretched over the whole DEM, not placed by "
            "its georeference (clip it to the DEM's bounds, e.g. with gdalwarp -te)"
            % (path, bounds[0], bounds[2], bounds[1], bounds[3], dem[0], dem[2], dem[1], dem[3]))


def _render_metadata(args, sun, exposure, frame=0):
    """What a render's PNG (tEXt) and EXR (header) record: the tool, the sun, the time (with
    --tz also on the zone's clock, and the zone: a caption of a series across a clock change
    had to work it out again until 2026-12-07) and the display exposure (EV); with --frames,
    the frame's number (as in its file name, from 0) and their count."""
    from aperture import __version__
    return [("aperture:software", "aperture " + __version__),
            ("aperture:sun_azimuth_deg", "%.6f" % sun.GetAzimuth()),
            ("aperture:sun_elevation_deg", "%.6f" % sun.GetElevation()),
            ("aperture:time_utc", sun.GetTimeString() if args.at else "n/a")] + (
        [("aperture:time_local", sun.GetLocalTimeString() or "n/a"),
         ("aperture:time_zone", args.tz)] if args.at and args.tz else []) + [
            ("aperture:display_exposure_ev", "%.9f" % exposure)] + (
        [("aperture:frame", "%d" % frame), ("aperture:frames", "%d" % args.frames)]
        if args.frames else [])


def _write_linear_exr(args, path, window, mapper, sun, watcher, frame=0):
    """The picture's linear radiance (no exposure, no tone mapping; W/m2/sr for the aperture
    lighting) read back from a float framebuffer and written as an RGBA OpenEXR; `mapper` is
    the picture's vtkApertureLightingMapper, of either lighting model (both scale by their
    exposure, which is taken off for the capture and recorded in the header)."""
    from aperture import vtkApertureEXRWriter, vtkApertureLinearCapture
    renderer = window.GetRenderers().GetFirstRenderer()
    background = renderer.GetBackground()
    renderer.SetBackground(0.0, 0.0, 0.0)  # no radiance where there is no terrain
    saved = (mapper.GetExposure(), mapper.GetToneMapping(), window.GetMultiSamples())
    window.SetMultiSamples(0)
    mapper.SetExposure(0.0)
    mapper.SetToneMapping(False)
    image = vtkApertureLinearCapture().Capture(renderer)
    mapper.SetExposure(saved[0])
    mapper.SetToneMapping(saved[1])
    window.SetMultiSamples(saved[2])  # (the next frame's PNG antialiased as the first's)
    renderer.SetBackground(*background)
    if image is None:
        raise ApertureError("could not read the float framebuffer back for %s" % path)
    writer = watcher.watch(vtkApertureEXRWriter())
    writer.SetInputData(image)
    writer.SetFileName(native_path(path))
    writer.SetColorArrayName("Radiance")
    writer.AddArrayName("Radiance")
    if args.exr_type == "half":
        writer.SetPixelTypeToHalf()
    unit = ("W/m^2/sr, linear Rec.709 RGB" if args.lighting == "aperture"
            else "VTK lighting, linear")
    metadata = _render_metadata(args, sun, mapper.GetExposure(), frame)
    metadata.insert(1, ("aperture:quantity", "outgoing radiance of the terrain, " + unit))
    for key, value in metadata:
        writer.AddMetadata(key, value)
    watcher.write(writer, "writing %s" % path)
    return os.path.abspath(path)


# ---------------------------------------------------------------------------------------------
# bake

# Products of vtkApertureSkyVisibility, in band order: (name, unit in the files: the filter's
# AnglesInDegrees makes the angles degrees, definition written into each band's metadata).
PRODUCTS = [
    ("VisibleSolidAngle", "sr",
     "solid angle of the sky visible above the horizontal, the terrain horizon and the cell's "
     "own tangent plane"),
    ("ApertureRadius", "degree",
     "angular radius of the spherical cap with the visible solid angle's area, "
     "acos(1 - A / 2 pi) (Oat & Sander 2007)"),
    ("BentNormal", "1",
     "unit mean direction of the visible sky, East-North-Up at the cell (components E, N, "
     "U: GeoTIFF bands _E, _N, _U, EXR channels .E, .N, .U)"),
    ("SkyViewFactor", "1",
     "Zaksek et al. 2011: 1 - mean sin(max(horizon, 0)); share of the upper hemisphere visible "
     "over a horizontal plane, ignoring the cell's slope"),
    ("DiffuseSkyFactor", "1",
     "Dozier & Frew 1990 (with Dozier 2022 self-shadowing): isotropic sky irradiance on the "
     "tilted cell relative to an unobstructed horizontal surface, cosine-weighted"),
    ("PositiveOpenness", "degree",
     "Yokoyama et al. 2002: mean zenith angle of the terrain horizon"),
    ("EdgeTruncated", "1",
     "1 where in some sector the DEM ends closer than the search limit (the radius; without "
     "one, with curvature, where terrain no higher than the DEM's top could rise above the "
     "horizontal); PositiveOpenness may also differ near the edge on unflagged cells; nodata, "
     "which hides the terrain behind it as the edge does, does not set it"),
    ("HorizonAngles", "degree",
     "terrain horizon elevation per azimuth sector (band name: true azimuth of the sector "
     "centre, clockwise from north)"),
]
DERIVED = [name for name, *_ in PRODUCTS if name != "HorizonAngles"]
# The values each product takes in the files (angles in degrees), as their definitions bound
# them: a --nodata among them makes such cells read as nodata (_nodata_collisions).
_PRODUCT_VALUES = {
    "VisibleSolidAngle": (0.0, 2.0 * math.pi, "0 to 2 pi"),
    "ApertureRadius": (0.0, 90.0, "0 to 90"),
    "BentNormal": (-1.0, 1.0, "-1 to 1"),
    "SkyViewFactor": (0.0, 1.0, "0 to 1"),
    "DiffuseSkyFactor": (0.0, 1.0, "0 to 1"),
    "PositiveOpenness": (0.0, 180.0, "0 to 180"),
    "EdgeTruncated": (0.0, 1.0, "0 or 1"),
    "HorizonAngles": (-90.0, 90.0, "-90 to 90"),
}


def _nodata_collisions(nodata, products):
    """A warning when the number `nodata` (--nodata) is a value some of `products` take, else
    None: their cells of that value would read as nodata (--nodata 0 took every EdgeTruncated
    cell of 0 without a word)."""
    hits = []
    # (a reader of the file, GDAL's mask among them, takes as nodata what lies within about
    # two float32 ulps of it, relatively: ap_sample_params.nodata_near)
    near = 4.0 * 1.1920928955078125e-07 * abs(nodata)
    for name in products:
        lo, hi, text = _PRODUCT_VALUES[name]
        if lo - near <= nodata <= hi + near and (
                name != "EdgeTruncated" or min(abs(nodata), abs(nodata - 1.0)) <= near):
            hits.append("%s (%s)" % (name, text))
    if not hits:
        return None
    return ("--nodata %s is also a value of %s: cells of that value will read as nodata; a "
            "value no product takes, such as -9999, or the default nan, would not" % (
                "%.9g" % nodata, hits[0] if len(hits) == 1 else
                ", ".join(hits[:-1]) + " and " + hits[-1]))


def _parse_products(text):
    if text is None:
        return list(DERIVED)
    names = {name.lower(): name for name, *_ in PRODUCTS}
    chosen = []
    for item in (t.strip() for t in text.split(",")):
        if not item:
            continue
        if item.lower() == "all":
            chosen.extend(name for name, *_ in PRODUCTS)
            continue
        if item.lower() not in names:
            raise _UsageError("unknown product %r; choose from %s, or all"
                              % (item, ", ".join(n for n, *_ in PRODUCTS)))
        chosen.append(names[item.lower()])
    if not chosen:
        raise _UsageError("--products names no product")
    # bands in the list's order, as gdal_translate -b takes them ('all' in the table's order
    # where it stands; a name twice once, where it first stands): the table's order whatever
    # the list's until 2026-12-07, which a script's -b N did not expect
    return list(dict.fromkeys(chosen))


def _provenance(args, products, reader):
    from aperture import __version__, vtkApertureSkyVisibility
    geo, _ = _whole_grid(reader)
    local, global_dem = geo.IsLocal(), geo.WrapsAround()
    return {
        "APERTURE_VERSION": __version__,
        "APERTURE_COMMAND": "aperture bake",
        # (metadata is UTF-8 text: a name that is not UTF-8 with its odd bytes as \xNN)
        "SOURCE_DEM": os.fsencode(_full_name(args.dem)).decode("utf-8", "backslashreplace"),
        "ALGORITHM": "convex-hull line sweep (Timonen & Westerholm 2010) of the terrain horizon "
                     "in every azimuth sector, each cell's own ray exact on the bilinear surface "
                     "for the first %s columns; in sectors where the search distance spans at "
                     "most %d columns, every cell's ray marched exactly to it instead (no hulls); "
                     "where it spans at most %d columns, every cell's ray sampled where it "
                     "crosses the grid's columns (the far march, no hulls; along rhumb lines on "
                     "lat/lon and cylindrical (Mercator) DEMs); on other projected DEMs each "
                     "cell's distances at its own ground scale and its sectors weighted by their "
                     "share of the ground's directions; closed-form sector sums (Filters/Kernels/"
                     "ap_horizon.h, Products)"
                     % ("%d (swept sectors) or %d (far-marched sectors)"
                        % (vtkApertureSkyVisibility.GetSweptNearField(),
                           vtkApertureSkyVisibility.GetMarchedNearField())
                        if not args.near_field else str(args.near_field),
                        vtkApertureSkyVisibility.GetMarchColumns(),
                        vtkApertureSkyVisibility.GetFarMarchColumns()),
        "DIRECTIONS": str(args.directions),
        "SECTORS": ("sector d centred on grid azimuth 360 d / %d degrees, clockwise from the "
                    "grid's +y axis (a local CRS: no true north; BentNormal_E and _N along "
                    "the grid's x and y)" if local else
                    "sector d centred on true azimuth 360 d / %d degrees, clockwise from north")
                   % args.directions,
        "MAX_DISTANCE_M": "unlimited" if not args.radius else repr(args.radius),
        "EARTH_CURVATURE": "off" if args.no_curvature else
                           "on, a sphere of the mean Earth radius 6371008.8 m (a local CRS has "
                           "no ellipsoid)" if local else "on",
        "REFRACTION_COEFFICIENT": "n/a" if args.no_curvature else repr(args.refraction),
        "ANGLE_UNIT": "degree",
        "EDGES": ("the DEM spans 360 degrees of longitude: its east and west edges join (the "
                  "cells beside the antimeridian see across it); terrain beyond its north and "
                  "south edges is treated as invisible; see EdgeTruncated" if global_dem else
                  "terrain beyond the DEM edge is treated as invisible; see EdgeTruncated"),
        "PRODUCTS": ",".join(products),
        # what of the DEM was read: a product of a window or a decimated grid says so
        **_read_provenance(args, reader),
    }


def _read_provenance(args, reader):
    """What of the DEM was read (the reader's band and elevation unit, after its update)."""
    record = {"SOURCE_BAND": str(reader.GetBandRead())}
    if args.srcwin:
        # (a size of 0, to the edge, as the cells it reached: 0 was written as given until
        # 2026-12-07)
        xoff, yoff, xsize, ysize = args.srcwin
        width, height = reader.GetRasterSize()
        record["SOURCE_WINDOW"] = ("%d %d %d %d (xoff yoff xsize ysize; its horizons see the "
                                   "DEM around it)" % (xoff, yoff, xsize or width - xoff,
                                                       ysize or height - yoff))
    if args.overview is not None:
        record["SOURCE_OVERVIEW"] = str(args.overview)
    if args.decimate > 1:
        record["SOURCE_DECIMATION"] = "%d x %d blocks averaged" % (args.decimate, args.decimate)
    if args.srs:
        record["SOURCE_CRS_OVERRIDE"] = args.srs
    record["SOURCE_ELEVATION_UNIT"] = _elevation_unit(reader)
    return record


def _elevation_unit(reader):
    """The reader's elevation unit (after its update) as bakes record it and render --baked
    compares it: "<metres per unit> m (<where that came from>)"."""
    return "%.10g m (%s)" % (reader.GetElevationUnitRead(),
                             _as_options(reader.GetElevationUnitSource()))


def _product_image(sky, products):
    """An image sharing the filter's arrays of the chosen products (no copies; the filter ran
    with AnglesInDegrees and FloatEdgeTruncated: angles in degrees, EdgeTruncated as float,
    NaN on nodata; HorizonAngles' components named by azimuth). No numpy: its import alone
    took 0.09 s of a 1.5 s bake."""
    from vtkmodules.vtkCommonDataModel import vtkImageData

    image = vtkImageData()
    image.CopyStructure(sky)
    image.GetFieldData().PassData(sky.GetFieldData())
    for name in products:
        array = sky.GetPointData().GetArray(name)
        if array is None or array.GetDataTypeAsString() != "float":
            raise ApertureError("internal: %s is not a float array" % name)
        image.GetPointData().AddArray(array)
    return image


class _Terminated(KeyboardInterrupt):
    """SIGTERM or SIGHUP during a step that _abort_on_interrupt guards: the step stopped as for
    Ctrl-C, and the command exits 128 + the signal's number (143, 129), as the signal's default
    action would have."""

    def __init__(self, signum):
        super().__init__()
        self.signum = signum


def _interruption(received):
    """The exception ending a command that caught the signals `received` (numbers, at least
    one): _Terminated for SIGTERM or SIGHUP (exit 143, 129), else KeyboardInterrupt (130)."""
    import signal
    ended = [n for n in (signal.SIGTERM, signal.SIGHUP) if n in received]
    return _Terminated(ended[0]) if ended else KeyboardInterrupt()


def _handle_ending_signals(handler):
    """Installs `handler` for SIGINT, SIGTERM and SIGHUP, except those ignored now: a shell's
    background job inherits SIGINT ignored and `nohup` SIGHUP, and the command keeps that, as
    the launcher does while it loads (a bake under nohup ended when its terminal closed, until
    2026-12-06). Returns the handlers it replaced, for _restore_signals."""
    import signal
    return {number: signal.signal(number, handler)
            for number in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)
            if signal.getsignal(number) != signal.SIG_IGN}


def _restore_signals(previous):
    import signal
    for number, handler in previous.items():
        signal.signal(number, handler)


class _abort_on_interrupt:
    """Ctrl-C (SIGINT), SIGTERM (`timeout`, a batch system's time limit) or SIGHUP (the
    terminal or ssh session of a long bake closed) during long filters and writers: Python runs
    its signal handler only when it gets control, which a VTK update gives it only through
    observers. Observers of the algorithms' progress (every azimuth sector for the sky filter,
    or slice of one on large DEMs, every band for the GeoTIFF writer) let the handler run; it
    sets AbortExecute on all of them, the one running stops (a writer removing its file), and
    KeyboardInterrupt follows (exit 130; _Terminated, exit 143 or 129, for SIGTERM and SIGHUP)
    instead of the whole computation first. Without it those signals would end the process at
    once, leaving the writers' temporary files behind (and, until they wrote aside, the GeoTIFF
    partly written under its own name)."""

    def __init__(self, *algorithms):
        self.algorithms = algorithms
        self.received = set()  # the signals handled

    @property
    def interrupted(self):
        return bool(self.received)

    def _handler(self, signum, frame):
        self.received.add(signum)
        for algorithm in self.algorithms:
            algorithm.SetAbortExecute(1)

    def _progress(self, algorithm, event):
        # The handler runs here, once Python checks for signals. It does so by itself only for
        # a signal the main thread took: one that a worker thread took (the kernel's choice
        # when the main thread blocks signals, as it does while it starts a thread) is noted
        # but left for a main thread that retakes the GIL, which a VTK update holds to its
        # end. pthread_kill with signal 0 sends nothing and checks (CPython's own comment: the
        # signal may have been sent to this thread).
        import signal
        import threading
        signal.pthread_kill(threading.main_thread().ident, 0)
        # (and again after an abort VTK has undone: a handler that ran in a StartEvent
        # observer lost its abort when the executive reset AbortExecute next)
        if self.interrupted:
            algorithm.SetAbortExecute(1)

    def __enter__(self):
        self.observers = [a.AddObserver("ProgressEvent", self._progress)
                          for a in self.algorithms]
        self.previous = _handle_ending_signals(self._handler)
        return self

    def __exit__(self, kind, value, traceback):
        _restore_signals(self.previous)
        for algorithm, observer in zip(self.algorithms, self.observers):
            algorithm.RemoveObserver(observer)
        if self.interrupted:
            raise _interruption(self.received)
        return False


def _window_reading(args, watcher, sky):
    """Connect a reader of the whole grid to the sky filter: returns (reader, the extent of the
    grid to compute (--srcwin's cells, else all), the extent the sky filter reads for it (with
    its halo), the grid's whole extent). Nothing is read."""
    from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as sddp
    reader = _dem_reader(args, watcher, subwindow=False)
    if args.srcwin and args.decimate > 1:
        # (the partial blocks at the edges said only when --srcwin reaches them, as a reader
        # of the window says them: the whole grid's reader warned for any window until
        # 2026-12-06; that reader's errors are not this reading's: a window under 2 x 2
        # cells is baked all the same)
        reader.PartialBlockWarningOff()
        _dem_reader(args, Watcher(on_warning=_warn)).UpdateInformation()
    sky.SetInputConnection(reader.GetOutputPort())
    watcher.update_information(sky)
    whole = reader.GetOutputInformation(0).Get(sddp.WHOLE_EXTENT())
    window = list(whole)
    if args.srcwin and not reader.GetWindowExtent(*args.srcwin, window):
        watcher.check()
        raise ApertureError("--srcwin %d %d %d %d: no cells" % tuple(args.srcwin))
    return reader, window, _input_extent(watcher, sky, window), whole


def _input_extent(watcher, sky, extent):
    """The extent of its input the sky filter reads for `extent` of its output (with its
    halo), asked before anything runs."""
    read = [0] * 6
    if not sky.ComputeInputExtent(extent, read):
        watcher.check()
    return read


def _extent_size(e):
    """Columns and rows of a VTK extent."""
    return e[1] - e[0] + 1, e[3] - e[2] + 1


def _cells(e):
    """Cells of a 2-D VTK extent."""
    nx, ny = _extent_size(e)
    return nx * ny


def _plan_bake(args, watcher, sky):
    """Set up the reader for the sky filter and plan the bake before anything is read:
    returns (reader, the extent of the grid to bake (--srcwin's cells, else all), the extent
    the sky filter reads for it (with its halo), rows per strip or 0 for all at once, the
    grid's whole extent).

    --srcwin bakes the window's cells with horizons from the DEM around it (so that windows
    tile a DEM), reading the DEM within the radius around it (without one, all of it). When the
    sky filter cannot hold it all (beside the elevations, 4 bytes a cell: past physical memory,
    or its control group's limit, Linux kills the process instead of failing an allocation),
    the outputs are baked in strips of whole 256-row tiles, each reading its own halo, as many
    rows as fit; refused when not even one tile row fits."""
    reader, window, read, whole = _window_reading(args, watcher, sky)
    # a global DEM's sweep adds columns of the other side to each of its own (its edges join):
    # as many as the widest halo of the window's rows needs (0 unless the DEM wraps around and
    # `read` spans every column, as each strip's read then does too), for the whole and every
    # strip
    wrap = sky.GetWrapColumns(read)

    def problem(read, nx, ny):  # the sky filter's refusal of an update, or ""
        rx, ry = _extent_size(read)
        return sky.CheckMemory(rx + 2 * wrap, ry, nx, ny, 4.0 * rx * ry)

    nx, ny = _extent_size(window)
    whole_problem = problem(read, nx, ny)
    if not whole_problem:
        return reader, window, read, 0, whole
    advice = ("bake a window with --srcwin and a --radius (only the DEM within the radius "
              "around it is read), use --decimate or --overview, or bake fewer --products")
    from aperture import vtkApertureDEMWriter
    tile = vtkApertureDEMWriter.GetTileSize()  # (the strips are whole tile rows of the GeoTIFF)
    if ny <= tile:  # (one tile row: strips would be the same request)
        raise ApertureError("%s; %s" % (whole_problem, advice))
    # the halo of a strip inside the grid. The sky filter's comes from the smallest cell sizes
    # of the rows near what it computes (on a lat/lon DEM a strip near a pole reads more
    # columns than one in the middle): every strip reads at most the columns the whole window
    # does (`read`), and its rows at most the widest row halo of the window's end and middle
    # rows (on a lat/lon DEM the north-south cell size changes by under 1% from equator to pole)
    rows_asked = (window[2], (window[2] + window[3]) // 2, window[3])
    halo = max(max(e[3] - r, r - e[2]) for e, r in (
        (_input_extent(watcher, sky, [window[0], window[1], r, r, 0, 0]), r) for r in rows_asked))
    whole_rows = _extent_size(whole)[1]

    def strip_problem(tiles):  # for strips of this many tile rows
        rows = min(tile * tiles, ny)
        inner = [read[0], read[1], 0, min(rows + 2 * halo, whole_rows) - 1, 0, 0]
        return problem(inner, nx, rows)

    memory = sky.GetUsableMemory()  # (physical, or the control group's or ulimit -v's limit)
    columns = _extent_size(read)[0]
    if not args.max_memory and 4.0 * columns * min(tile + 2 * halo, whole_rows) >= memory:
        raise ApertureError("%s; %s" % (whole_problem, advice))  # (a strip's DEM alone)
    fits, tiles = 0, -(-ny // tile)
    while fits + 1 < tiles:  # the most tiles that fit: 'fits' fit, 'tiles' do not
        mid = (fits + tiles) // 2
        fits, tiles = (mid, tiles) if not strip_problem(mid) else (fits, mid)
    if fits == 0 or strip_problem(fits):
        raise ApertureError("%s, and strips of %d rows (the GeoTIFF's tiles) would not "
                            "fit either: %s; %s" % (whole_problem, tile, strip_problem(1),
                                                    advice))
    return reader, window, read, tile * fits, whole


def _write_strips(watcher, clip, window, extents, outputs, guard, computed=None, finished=None):
    """Update `clip` for each extent of `window` in turn, north first, and write it into every
    (writer, path) of `outputs` (their BeginStrips with the first, EndStrips after the last);
    on an error or an interrupt (`guard`) the files begun are abandoned (an earlier file of the
    name stays as it was), the interrupt left to `guard`, and an error's message names the
    other outputs it leaves whole or removes.
    computed(k), if given, runs after strip k is computed, before it is written; `finished`
    (a list) gets the paths written in full."""
    begun = []
    finished = [] if finished is None else finished  # the paths written in full
    writing = None  # the path being written, if an output's step fails
    try:
        for k, extent in enumerate(extents):
            strip = watcher.update(clip, "bake", extent=extent)
            if guard.interrupted:
                return  # (an aborted sky filter's strip is incomplete)
            if computed:
                computed(k)
            for output, writing in outputs:
                if output not in begun and output.BeginStrips(strip, window):
                    begun.append(output)
                if not output.WriteStrip(strip) and not guard.interrupted:
                    # a writer may keep a failure's reason (GDAL's: a full disk) for EndStrips,
                    # which reports it and removes the file
                    begun.remove(output)
                    output.EndStrips()
                    watcher.check("writing %s" % writing)
                    raise ApertureError("writing %s failed" % writing)  # (no reason given)
                if guard.interrupted:
                    return
                watcher.check("writing %s" % writing)
            writing = None
            strip.ReleaseData()  # (one strip at a time)
        for output, writing in outputs:
            begun.remove(output)
            output.EndStrips()
            watcher.check("writing %s" % writing)
            finished.append(writing)
    except ApertureError as e:
        # (the failed writer discards its own file; the others begun are unfinished)
        raise _outputs_left(e, written=finished, removed=[
            path for output, path in outputs if output in begun and path != writing]) from None
    finally:
        for output in begun:
            output.AbandonStrips()


def _outputs_left(error, written=(), removed=()):
    """`error` (an ApertureError) with what a failed bake leaves of its other outputs: the
    user need not guess whether a file there is this bake's, whole."""
    notes = (["%s was written in full" % path for path in written]
             + ["the unfinished %s was discarded" % path for path in removed])
    return ApertureError("%s (%s)" % (error, "; ".join(notes))) if notes else error


def _check_radius(radius):
    """--radius: a positive, finite distance; leaving it out is the unlimited search."""
    if radius is not None and not (radius > 0 and math.isfinite(radius)):
        raise _UsageError("--radius must be a positive distance in metres (%g given; leave "
                          "--radius out for an unlimited search)" % radius)


def cmd_bake(args):
    products = _parse_products(args.products)
    if not 4 <= args.directions <= 360:
        raise _UsageError("--directions must be within 4..360")
    _check_radius(args.radius)
    if args.refraction is not None and args.no_curvature:
        # (taken without a word, and the files said n/a)
        raise _UsageError("--refraction bends rays over the curved Earth; --no-curvature has "
                          "none")
    args.refraction = 0.13 if args.refraction is None else args.refraction
    if not (0 <= args.refraction < 1):
        raise _UsageError("--refraction must be within [0, 1)")
    if args.threads < 0:
        raise _UsageError("--threads must be 0 (all cores) or more")
    if not 0 <= args.near_field <= 64:
        raise _UsageError("--near-field must be within 1..64, or 0 (automatic)")
    if args.exr_type and not args.exr:
        raise _UsageError("--exr-type %s needs --exr OUT.exr" % args.exr_type)
    _check_outputs([("OUT.tif", args.output), ("--exr", args.exr)], [("the DEM", _dem_path(args))])
    ext = os.path.splitext(args.output)[1].lower()
    if ext == ".exr":
        raise _UsageError("OUT.tif %s is written as a GeoTIFF; name it .tif and give --exr %s "
                          "for the EXR" % (args.output, args.output))

    progress = None if args.quiet or not sys.stderr.isatty() else _TermProgress(sys.stderr)
    try:
        return _bake(args, products, progress)
    except ApertureError:
        if progress and progress.open:
            sys.stderr.write("\n")
        raise


def _bake_steps(progress, window, read, args, products):
    """The bake's progress over its steps, weighted by their rough costs on two cores
    (nanoseconds, measured 2026-12-05 on 1024^2 to 3601^2 DEMs): reading about 20 a cell of
    the extent read (`read`; None: reading is not a step of its own), the sky filter 25 a cell
    and direction, writing 20 a cell and GeoTIFF band (7 uncompressed) and 25 a cell and EXR
    channel. So the display moves while a large output is written, which can take as long as
    the sweep (every HorizonAngles band of a 3601^2 DEM: 13 s against 12)."""
    size = lambda e: math.prod(_extent_size(e))
    cells = size(window)
    bands = sum(3 if p == "BentNormal" else args.directions if p == "HorizonAngles" else 1
                for p in products)
    return _StepsProgress(progress, {
        "read": 20.0 * size(read) if read else 0.0,
        "sky": 25.0 * cells * args.directions,
        "tif": (7.0 if args.compress.upper() == "NONE" else 20.0) * cells * bands,
        "exr": 25.0 * cells * bands if args.exr else 0.0})


def _bake(args, products, progress):
    import time
    from aperture import vtkApertureDEMWriter, vtkApertureEXRWriter, vtkApertureSkyVisibility

    start = time.perf_counter()
    # one line per kind of warning: in strips each strip would repeat it with its own numbers
    kinds = set()

    def warn_once(message):
        kind = re.sub(r"-?\d[\w.+-]*", "#", message)
        if kind not in kinds:
            kinds.add(kind)
            _warn(message)

    watcher = Watcher(on_warning=warn_once)
    writer = watcher.watch(vtkApertureDEMWriter())
    writer.SetCompression(args.compress)
    writer.SetNoDataValue(args.nodata)
    writer.SetCompressionLevel(1 if args.compress_level is None else args.compress_level)
    writer.CheckCompression()  # before the sweep, not after it (an unknown codec named first)
    # (the level named only when given: a JPEG refused said '--compress-level 1' unasked)
    try:
        watcher.check("--compress %s" % args.compress + (
            "" if args.compress_level is None else " --compress-level %d" % args.compress_level))
    except ApertureError as e:
        raise _UsageError(str(e))
    if args.compress_level is not None and not vtkApertureDEMWriter.HasCompressionLevel(
            args.compress):
        raise _UsageError("--compress-level applies to DEFLATE, ZSTD and LZMA, which have "
                          "levels, not to --compress %s" % args.compress)
    sky = watcher.watch(vtkApertureSkyVisibility())
    sky.SetNumberOfDirections(args.directions)
    sky.SetMaximumDistance(args.radius or 0.0)
    sky.SetEarthCurvature(not args.no_curvature)
    sky.SetRefractionCoefficient(args.refraction)
    sky.SetNumberOfThreads(args.threads)
    sky.SetNearField(args.near_field)
    for name in DERIVED + ["HorizonAngles"]:
        getattr(sky, "SetCompute" + name)(name in products)
    sky.SetAnglesInDegrees(True)  # the files' unit
    sky.SetFloatEdgeTruncated(True)  # one sample type for every band, NaN on nodata

    if args.max_memory is not None:
        sky.SetMemoryLimit(args.max_memory)
    reader, window, read, rows, whole = _plan_bake(args, watcher, sky)
    _check_sources([("OUT.tif", args.output), ("--exr", args.exr)], reader)
    # (after every refusal: a warning and then an error would be two lines for one mistake)
    _warn_extension(args.output, (".tif", ".tiff", ".gtiff"), "a GeoTIFF")
    _warn_extension(args.exr, (".exr",), "an OpenEXR file")
    collisions = _nodata_collisions(args.nodata, products)
    if collisions:
        _warn(collisions)
    if reader.GetSouthUp() and not args.quiet:
        print("%s: note: the DEM is south-up (its first row is its southern one); %s is "
              "written north-up: the same cells and CRS, its rows in the reverse order"
              % (PROG, args.output), file=sys.stderr)
    # whether each update of the sky filter (one, or a strip's) read nodata alone: a part of
    # the DEM may (a window or a strip out at sea); all of it is an error
    nodata = []
    sky.AddObserver("EndEvent", lambda obj, _: nodata.append(obj.GetInputAllNodata()))

    heights = []  # whether each strip of the window (or all of it) has a cell with a height

    def after_strip(k):
        # A first strip of nodata, reading the whole DEM's rows in strips: the rest is read
        # for a cell with data, so that a DEM without one is refused now, the reader's way,
        # not after baking and writing it all (a 60000^2 DEM of nodata: 50 s instead of 450).
        if k == 0 and nodata[-1] and list(read) == list(whole) and \
                not _has_data(args, watcher, whole, rows):
            raise ApertureError("every cell of '%s' band %d is nodata"
                                % (_dem_path(args), args.band or 1))
        heights.append(_has_heights(clip.GetOutput(), extents[k]))
        _digest_rows(digest, clip.GetOutput(), extents[k])
        if k == len(extents) - 1:  # (written by EndStrips)
            writer.AddMetadata(DIGEST_KEY, DIGEST_TEXT % digest.hexdigest())
    digest = _elevation_digest()  # (of the elevations read, for render --baked)
    provenance = _provenance(args, products, reader)
    definitions = {name: (unit, text) for name, unit, text in PRODUCTS}
    writer.SetFileName(native_path(args.output))
    writer.SetNumberOfThreads(args.threads)  # tiles compressed in parallel; same bytes
    for key, value in provenance.items():
        writer.AddMetadata(key, value)
    for name in products:
        writer.AddBandMetadata(name, "UNITS", definitions[name][0])
        writer.AddBandMetadata(name, "DEFINITION", definitions[name][1])
    strips = 0
    exr = None
    if args.exr:
        exr = watcher.watch(vtkApertureEXRWriter())
        exr.SetFileName(native_path(args.exr))
        exr.SetNumberOfThreads(args.threads)  # chunks compressed in parallel; same bytes
        if args.exr_type == "half":
            exr.SetPixelTypeToHalf()
        for key, value in provenance.items():
            exr.AddMetadata("aperture:" + key.lower(), value)
        for name in products:  # (which sky-view definition each channel is, as in the GeoTIFF)
            exr.AddMetadata("aperture:unit:" + name, definitions[name][0])
            exr.AddMetadata("aperture:definition:" + name, definitions[name][1])
    outputs = [(writer, args.output)] + ([(exr, args.exr)] if exr else [])
    writers = [output for output, _ in outputs]
    # An interrupt leaves each output whole: the new file when its writer had finished, else
    # the earlier file of that name as it was (the writers write aside and rename; this removed
    # the outputs begun, so an interrupted rewrite deleted the earlier files it had not yet
    # replaced, until 2026-12-07), and a note names which were finished and which not (a new
    # GeoTIFF beside the EXR of before, or beside none)
    finished = []  # the outputs written in full
    existed = {path: os.path.lexists(path) for _, path in outputs}  # (for the note)
    try:
        if rows:
            # In strips, north first: the sky filter computes each (reading it and its halo)
            # and every output writes it before the next; a clip makes the window the whole
            # extent.
            from vtkmodules.vtkImagingCore import vtkImageClip
            clip = vtkImageClip()
            clip.SetInputConnection(sky.GetOutputPort())
            clip.SetOutputWholeExtent(window)
            clip.ClipDataOff()
            for output in writers:
                for name in products:
                    output.AddArrayName(name)
            extents = [[window[0], window[1], max(window[2], top - rows + 1), top, 0, 0]
                       for top in range(window[3], window[2] - 1, -rows)]
            strips = len(extents)
            done = [-1]  # strips started
            sky.AddObserver("StartEvent", lambda obj, _: done.__setitem__(0, done[0] + 1))
            if progress:  # (the writers' progress runs over the rows of the window)
                steps = _bake_steps(progress, window, None, args, products)
                steps.observe(sky, "sky", lambda p: (done[0] + p) / strips)
                steps.observe(writer, "tif")
                if exr:
                    steps.observe(exr, "exr")
                progress(0.0)
            sweep_start = time.perf_counter()
            with _abort_on_interrupt(sky, *writers) as guard:
                _write_strips(watcher, clip, window, extents, outputs, guard,
                              computed=after_strip, finished=finished)
            sweep_seconds = time.perf_counter() - sweep_start
            nx, ny = _extent_size(window)
        else:
            if progress:
                steps = _bake_steps(progress, window, read, args, products)
                for algorithm, step in ((reader, "read"), (sky, "sky"), (writer, "tif"),
                                        (exr, "exr")):
                    if algorithm:
                        steps.observe(algorithm, step)
                progress(0.0)
            _read(watcher, reader, read)
            with _abort_on_interrupt(sky, *writers):
                sweep_start = time.perf_counter()
                # (the reader has run: the sky filter alone)
                result = watcher.update(sky, "bake", extent=window)
                sweep_seconds = time.perf_counter() - sweep_start
                heights.append(_has_heights(result, window))
                _digest_rows(digest, result, window)
                writer.AddMetadata(DIGEST_KEY, DIGEST_TEXT % digest.hexdigest())
                image = _product_image(result, products)
                nx, ny, _ = image.GetDimensions()
                for output, path in outputs:
                    output.SetInputData(image)
                    try:
                        watcher.write(output, "writing %s" % path)
                    except ApertureError as e:
                        # (the writer removed its file; the ones before it are whole)
                        raise _outputs_left(e, written=finished) from None
                    finished.append(path)
    except KeyboardInterrupt:
        left = [path for _, path in outputs if path not in finished]
        if finished and left:
            print("%s: note: interrupted: %s written in full; %s" % (
                PROG, " and ".join(finished), "; ".join(
                    "%s %s" % (path, "left as it was" if existed[path] else "not written")
                    for path in left)), file=sys.stderr)
        raise
    if nodata and all(nodata):  # (a part of the DEM: a window with a radius; after_strip)
        _warn("every cell of the DEM read for --srcwin %s (the window and %s around it) is "
              "nodata, and so is every product" % (" ".join(map(str, args.srcwin or ())),
                                                   "%g m" % (args.radius or 0)))
    elif heights and not any(heights):
        # (a window at sea beside land, whose search reads the land: written silently until
        # 2026-12-06, where a radius that read only the sea had this warning)
        _warn("every cell of --srcwin %s is nodata (the DEM around it has data), and so is "
              "every product" % " ".join(map(str, args.srcwin or ())))
    written = [os.path.abspath(path) for _, path in outputs]
    if progress:
        progress(1.0)
    if args.quiet:
        return 0
    print("wrote %s: %s for %d x %d cells, %d directions, in %.1f s (sky filter %.2f s%s)"
          % (" and ".join(written), ", ".join(products), nx, ny, args.directions,
             time.perf_counter() - start, sweep_seconds,
             "" if not strips else ", with the write, in %d strips of %d rows: the whole "
             "did not fit in %s" % (strips, rows, "--max-memory" if args.max_memory else
                                    "memory")))
    return 0


# ---------------------------------------------------------------------------------------------
# sun

DAY_KINDS = {0: "normal", 1: "polar_day", 2: "polar_night"}
SKY_MODELS = {"preetham": 3, "cie-clear": 2, "cie-overcast": 1, "uniform": 0}
SKY_MODELS_BY_ID = {v: k for k, v in SKY_MODELS.items()}


def _rgb(getter):
    rgb = [0.0, 0.0, 0.0]
    getter(rgb)
    return rgb


def _offset_text(seconds):
    """+HH:MM, or +HH:MM:SS for an offset with seconds (historical local mean time), as
    Python's isoformat() writes them."""
    sign = "-" if seconds < 0 else "+"
    seconds = abs(int(seconds))
    text = "%s%02d:%02d" % (sign, seconds // 3600, seconds // 60 % 60)
    return text + (":%02d" % (seconds % 60) if seconds % 60 else "")


def _sun_record(sun, with_dem):
    """One --json object: the keys the documentation lists."""
    finite = lambda v: v if v is not None and math.isfinite(v) else None
    record = {
        "time_utc": sun.GetTimeString(),
        "time_local": sun.GetLocalTimeString() or None,
        "utc_offset": _offset_text(sun.GetLocalOffset()),
        "time_zone": sun.GetTimeZone() or None,
        "latitude_deg": sun.GetLatitude(),
        "longitude_deg": sun.GetLongitude(),
        "height_m": sun.GetHeight(),
        "azimuth_deg": sun.GetAzimuth(),
        "elevation_deg": sun.GetElevation(),
        "zenith_deg": sun.GetZenith(),
        "elevation_true_deg": sun.GetElevationTrue(),
        "zenith_true_deg": sun.GetZenithTrue(),
        "angular_radius_deg": sun.GetAngularRadius(),
        "distance_au": sun.GetDistance(),
        "equation_of_time_min": sun.GetEquationOfTime(),
        "declination_deg": sun.GetDeclination(),
        "hour_angle_deg": sun.GetHourAngle(),
        "delta_t_s": sun.GetDeltaTUsed(),
        "day_kind": DAY_KINDS.get(sun.GetDayKind()),  # (None: the day beyond the years)
        "sunrise": sun.GetSunriseString() or None,
        "transit": sun.GetTransitString() or None,
        "sunset": sun.GetSunsetString() or None,
        "sunrise_local": sun.GetSunriseLocalString() or None,
        "transit_local": sun.GetTransitLocalString() or None,
        "sunset_local": sun.GetSunsetLocalString() or None,
        "sky_model": SKY_MODELS_BY_ID[sun.GetSkyModel()],
        "air_mass": finite(sun.GetAirMass()),
        "direct_normal_irradiance_w_m2": sun.GetDirectNormalIrradiance(),
        "sun_rgb_w_m2": _rgb(sun.GetSunColor),
        "sky_horizontal_irradiance_w_m2": sun.GetSkyHorizontalIrradiance(),
        "sky_zenith_radiance_rgb_w_m2_sr": _rgb(lambda v: sun.GetSkyRadiance([0, 0, 1], v)),
    }
    if with_dem:
        direction = [0.0, 0.0, 0.0]
        sun.GetDirection(direction)
        record["meridian_convergence_deg"] = sun.GetGridConvergence()
        record["grid_azimuth_deg"] = sun.GetGridAzimuth()
        record["direction_enu"] = direction
    return record


def _day_order_note(sun, record):
    """A note for a day whose events are not in the order sunrise, transit, sunset: the day is
    the clock's (the UTC day, for --at ...Z) and the place's solar time is hours from it."""
    events = (sun.GetSunrise(), sun.GetTransit(), sun.GetSunset())
    if record["day_kind"] != "normal" or any(map(math.isnan, events)) or \
            events[0] < events[1] < events[2]:
        return None  # (a day next to polar day or night may have one event: no order to judge)
    hours = sun.GetLocalOffset() / 3600.0 - record["longitude_deg"] / 15.0
    # (with --tz the zone names the day, whatever offset --at is written with)
    advice = ("give --tz the place's own time zone" if sun.GetTimeZone()
              else "give --tz with its time zone, or its UTC offset in --at")
    return ("the day of the clock at %s is %.1f h %s of the solar time at longitude %.4f, so "
            "its events are not in the order sunrise, transit, sunset; for the place's own day "
            "%s" % (record["utc_offset"], abs(hours), "ahead" if hours > 0 else "behind",
                    record["longitude_deg"], advice))


def _print_sun(record, dem, note=None, refraction=True):
    # (an instant given in UTC without --tz has UTC's clock and day: not labelled "local", as
    # if it were the place's, until 2026-12-07)
    utc = not record["time_zone"] and record["utc_offset"] == "+00:00"
    rows = [
        ("Time", "%s (%s)" % (record["time_utc"],
                              "UTC's clock and day: --tz ZONE gives the place's" if utc else
                              "local %s" % (record["time_local"] or "n/a"))),
        ("Place", "latitude %.6f, longitude %.6f, height %.1f m%s"
         % (record["latitude_deg"], record["longitude_deg"], record["height_m"],
            " (centre of %s)" % dem if dem else "")),
        ("Azimuth", "%.4f deg from true north%s" % (
            record["azimuth_deg"],
            "; %.4f deg from grid north (convergence %.4f deg)"
            % (record["grid_azimuth_deg"], record["meridian_convergence_deg"])
            if "grid_azimuth_deg" in record else "")),
    ] + ([
        ("Elevation", "%.4f deg apparent (refracted), %.4f deg geometric"
         % (record["elevation_deg"], record["elevation_true_deg"])),
        ("Zenith", "%.4f deg apparent, %.4f deg geometric"
         % (record["zenith_deg"], record["zenith_true_deg"])),
    ] if refraction else [  # (said "apparent (refracted)" of geometric angles until 2026-12-07)
        ("Elevation", "%.4f deg geometric (--no-refraction)" % record["elevation_true_deg"]),
        ("Zenith", "%.4f deg geometric" % record["zenith_true_deg"]),
    ])
    if "direction_enu" in record:
        rows.append(("Direction", "(%.6f, %.6f, %.6f) East-North-Up in the mesh frame"
                     % tuple(record["direction_enu"])))
    rows += [
        ("Sun disc", "radius %.5f deg; distance %.6f AU" % (record["angular_radius_deg"],
                                                           record["distance_au"])),
        ("Sunlight", "%.1f W/m2 direct normal (air mass %s), RGB %.1f %.1f %.1f" % (
            record["direct_normal_irradiance_w_m2"],
            "%.3f" % record["air_mass"] if record["air_mass"] is not None else "inf",
            *record["sun_rgb_w_m2"])),
        ("Sky", "%s, %.1f W/m2 on a horizontal surface" % (
            record["sky_model"], record["sky_horizontal_irradiance_w_m2"])),
        ("Eq. of time", "%+.2f min" % record["equation_of_time_min"]),
    ]
    if record["day_kind"] is None:
        rows.append(("Day", "n/a: the local day reaches beyond the years -2000..6000 the "
                            "algorithm covers"))
    elif record["day_kind"] == "normal":
        # (next to polar day or night the sun may only rise, or only set, that day)
        rows.append(("Day", "sunrise %s, transit %s, sunset %s (%s)" % (
            *(record[k] or "n/a (none that day)" for k in ("sunrise", "transit", "sunset")),
            "the UTC day" if utc else "local " + record["utc_offset"])))
        # each event on the clock of its own moment; its offset shown when a clock change
        # (the day of one) gives it another than the instant's
        # (the clock time after the date's T: a year -0001 is a character longer)
        clock = lambda text: text.split("T", 1)[1]
        rows += [] if utc else [("", "local: sunrise %s, transit %s, sunset %s" % tuple(
            "n/a" if not record[k] else clock(record[k])[:8] if clock(record[k])[8:] ==
            record["utc_offset"] else clock(record[k]) for k in ("sunrise_local",
                                                                 "transit_local",
                                                                 "sunset_local")))]
    else:
        rows.append(("Day", "%s: the sun does not %s; transit %s" % (
            record["day_kind"].replace("_", " "),
            "set" if record["day_kind"] == "polar_day" else "rise", record["transit"])))
    for label, text in rows:
        print("%-13s%s" % (label + (":" if label else ""), text))
    if note:
        print(textwrap.fill(note, width=100, initial_indent="%-13s" % "Note:",
                            subsequent_indent=" " * 13))


def _local_instant(sun, wall):
    """The POSIX time at which --tz's clocks (sun.GetLocalOffsetAt) show `wall` (POSIX seconds
    of the local date and time), as Python's zoneinfo resolves it (fold 0): of two such times
    (the clocks going back) the first; where the clocks skip it, `wall` read with the offset
    before the jump (midnight skipped: the moment of the jump). An offset change is at most
    a day here (Samoa skipped 2011-12-30), so the times that can show `wall` lie between 15
    hours before it and 13 after, and the offsets before and after any change in that span
    give them. (The end of the series was start + N days corrected by the change of offset
    between the two, which a change of a whole day cancelled: a single row for Samoa's
    2011-12-29, and one hour short from a midnight the clocks skip, until 2026-12-06.)"""
    before = sun.GetLocalOffsetAt(wall - 15 * 3600.0)
    offsets = {before, sun.GetLocalOffsetAt(wall + 13 * 3600.0)}
    offsets |= {sun.GetLocalOffsetAt(wall - o) for o in offsets}
    shown = [wall - o for o in offsets if sun.GetLocalOffsetAt(wall - o) == o]
    # (skipped: the offset before the jump is the one in force before the earliest candidate)
    return min(shown) if shown else wall - before


def cmd_sun(args):
    from aperture import vtkApertureSolarPosition

    if args.dem is None and (args.lat is None or args.lon is None):
        raise _UsageError("give the place: --lat DEG --lon DEG, or --dem DEM")
    if args.dem is not None and (args.lat is not None or args.lon is not None):
        raise _UsageError("give either --lat/--lon or --dem, not both")
    reading = ["--" + name for name, default in _READ_DEFAULTS.items()
               if getattr(args, name) != default]
    if args.dem is None and reading:
        raise _UsageError("%s read%s the DEM: give one with --dem" % (
            ", ".join(reading), "s" if len(reading) == 1 else ""))
    if args.days is not None and args.days < 1:
        raise _UsageError("--days must be 1 or more")
    if args.step is not None:
        _check_step(args.step)
    watcher = Watcher(on_warning=_warn)
    sun = watcher.watch(vtkApertureSolarPosition())
    if args.tz and not sun.SetTimeZone(args.tz):
        raise _UsageError(sun.GetErrorMessage())
    if not sun.SetTime(args.at):
        raise _UsageError(sun.GetErrorMessage())
    if args.height is not None and not -1000.0 <= args.height <= 10000.0:
        # (one limit, said first: the position took up to 100000 km, then the light refused
        # more than 10 km, and a NaN was "outside -6500..100000 km")
        raise _UsageError("--height must be within -1000..10000 m, the range of the sunlight "
                          "and sky models (%s given)" % args.height)
    if args.dem is not None:
        image = _read_centre(args, watcher)
        if not sun.SetPlaceFromImage(image):
            raise ApertureError(sun.GetErrorMessage())
        if math.isnan(sun.GetLatitude()):
            raise ApertureError("the DEM %s is in a local CRS (a site grid, no place on the "
                                "Earth); give the site's place with --lat/--lon instead of "
                                "--dem (a site grid's +y axis is north: its grid azimuths are "
                                "the sun's)" % args.dem)
        if args.height is not None:
            sun.SetHeight(args.height)
    else:
        sun.SetLatitude(args.lat)
        sun.SetLongitude(args.lon)
        sun.SetHeight(args.height or 0.0)
    sun.SetPressure(args.pressure)
    sun.SetTemperature(args.temperature)
    sun.SetRefraction(not args.no_refraction)
    sun.SetSkyModel(SKY_MODELS[args.sky])
    sun.SetTurbidity(args.turbidity)
    sun.SetLinkeTurbidity(args.linke_turbidity)
    if args.delta_t is not None:  # (a number: NaN, the estimate's value in the filter, and
        sun.SetDeltaT(args.delta_t)  # the range are refused at parsing)
    watcher.clear()

    def compute():
        if not sun.Compute():
            raise ApertureError(sun.GetErrorMessage())
        return _sun_record(sun, args.dem is not None)

    if args.days is None and args.step is None:
        record = compute()
        if args.json:
            print(json.dumps(record, indent=2))
        else:
            # (the place is the centre of what is read: of a --srcwin, not of the file, which
            # the label named until 2026-12-07)
            dem = args.dem and ("--srcwin %d %d %d %d of %s" % (*args.srcwin, args.dem)
                                if args.srcwin else args.dem)
            _print_sun(record, dem, _day_order_note(sun, record), not args.no_refraction)
        return 0

    # A time series from --at: every --step minutes before --days days have passed (at least
    # the start): local days, to the same clock time N days later (_local_instant), 23 or 25
    # hours for a day the clocks change by an hour in --tz (24 from local midnight missed 23:00
    # on the autumn's, until 2026-12-06). The last time is computed first, so that a series running
    # past the algorithm's years fails before it prints, and JSON is streamed, as the text is.
    days = args.days or 1
    step = args.step or 60.0
    start = sun.GetUnixTime()
    end = _local_instant(sun, start + sun.GetLocalOffsetAt(start) + days * 86400.0)
    step = _step_seconds(step)
    count = max(1, int(math.ceil((end - start) / step - 1e-9)))
    compute()  # (the start: any other problem is named as for one time)
    sun.SetUnixTime(start + (count - 1) * step)
    if not sun.Compute():
        raise _UsageError("the series over %d day%s from %s ends too late: %s" % (
            days, "" if days == 1 else "s", args.at, sun.GetErrorMessage()))
    if args.json:
        print("[")
    else:
        header = ["time_utc", "time_local", "azimuth", "elevation", "elev_true"]
        if args.dem is not None:
            header.append("grid_azimuth")
        print("\t".join(header))
    for k in range(count):
        sun.SetUnixTime(start + k * step)
        if args.json:
            text = json.dumps(compute(), indent=1).replace("\n", "\n ")
            print(" " + text + ("," if k + 1 < count else ""))
            continue
        # (the table's columns alone: the sky, which the JSON's light keys need, is prepared
        # only when asked for, and would take 17 times the position's time)
        if not sun.Compute():
            raise ApertureError(sun.GetErrorMessage())
        row = [sun.GetTimeString(), sun.GetLocalTimeString() or "n/a",
               "%.4f" % sun.GetAzimuth(), "%.4f" % sun.GetElevation(),
               "%.4f" % sun.GetElevationTrue()]
        if args.dem is not None:
            row.append("%.4f" % sun.GetGridAzimuth())
        print("\t".join(row))
    if args.json:
        print("]")
    return 0


# ---------------------------------------------------------------------------------------------


def _parse_camera(text):
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        values = []
    if len(values) not in (2, 3) or not all(math.isfinite(v) for v in values):
        raise argparse.ArgumentTypeError("expected AZ,EL or AZ,EL,ZOOM (degrees, degrees, factor)")
    if not 5.0 <= values[1] <= 90.0:
        raise argparse.ArgumentTypeError("the camera elevation must be within 5..90 degrees")
    if len(values) == 3 and not values[2] > 0:
        raise argparse.ArgumentTypeError("the zoom must be positive")
    if len(values) == 3 and not 1e-3 <= values[2] <= 1e4:
        # (beyond, the camera's clipping range loses the terrain: a blank picture)
        raise argparse.ArgumentTypeError("the zoom must be within 0.001..10000")
    return tuple(values) if len(values) == 3 else (values[0], values[1], 1.0)


def _add_atmosphere_options(p):
    p.add_argument("--turbidity", type=_number_in(2, 10), default=3.0, metavar="T",
                   help="Preetham turbidity for the sun's colour and the Preetham sky, 2..10 "
                        "(default 3)")
    p.add_argument("--linke-turbidity", type=_number_in(1, 8), default=3.0, metavar="TL",
                   help="Linke turbidity for the direct beam's strength (ESRA), 1..8 "
                        "(default 3)")


def build_parser():
    from aperture import __version__
    # (no abbreviated long options, as GDAL's tools take none: '--no' was --no-curvature in
    # bake and --no-stats in info, and a new option beginning alike would change a script)
    parser = argparse.ArgumentParser(
        prog=PROG, allow_abbrev=False,
        description="Aperture: sun-and-sky lighting and visibility analysis for DEMs.",
        epilog="Run '%s COMMAND --help' for the options of a command. Angles are in degrees "
               "and lengths in metres at this interface." % PROG)
    parser.add_argument("--version", action="version", version="%(prog)s " + __version__)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    parser.commands = sub.choices

    def add_command(name, **options):  # (each command's parser too takes no abbreviations)
        return sub.add_parser(name, allow_abbrev=False, **options)

    p = add_command("info", help="describe a DEM: size, cell size, CRS, bounds, elevations",
                    description="Describe a DEM: size, cell size (CRS units and metres), CRS, "
                                "lat/lon bounds, elevation range and nodata count.")
    _add_read_options(p)
    p.add_argument("--json", action="store_true",
                   help="print one JSON object (keys size, cell_size_m, crs, crs_code, "
                        "geotransform, bounds_lonlat, elevation_range, nodata_count, "
                        "centre_lonlat, ...; elevation_range is null when every cell is "
                        "nodata; the geotransform is the grid's read, north up)")
    p.add_argument("--no-stats", action="store_true",
                   help="describe the DEM from its header alone, without reading the "
                        "elevations for their range and nodata count (null in --json): at "
                        "once on any size")
    p.add_argument("--max-memory", type=_memory_size, metavar="SIZE",
                   help="most memory for the elevations read at once and a block of the file "
                        "(which GDAL reads whole: a compressed file stored as one strip is one "
                        "block): a number of MiB, or with K, M, G, T or B (bytes) (default 256 "
                        "MiB); they are read in strips of rows that fit, so a DEM larger than "
                        "memory is described too")
    p.add_argument("--quiet", "-q", action="store_true",
                   help="no progress display or note while the elevations are read (shown "
                        "when stderr is a terminal); the description is printed all the same")
    p.set_defaults(func=cmd_info)

    p = add_command("bake", help="horizons, sky-view factors, bent normals -> GeoTIFF/EXR",
                    description="Compute what every cell sees of the sky (one horizon sweep "
                                "in D azimuth sectors) and write the products as GeoTIFF "
                                "bands named after them (angles in degrees), optionally also "
                                "as one multi-channel float EXR.")
    _add_read_options(p, dem_required=True, srcwin_help=(
        "bake only this window's cells, in pixels from the top-left corner (as gdal_translate "
        "-srcwin); their horizons still see the DEM around the window (within --radius; "
        "without one all of it is read), so the windows of a DEM tile its whole bake exactly"))
    p.add_argument("output", metavar="OUT.tif", help="GeoTIFF to write")
    p.add_argument("--directions", "-d", type=_c_int, default=32, metavar="D",
                   help="azimuth sectors, 4..360 (default 32)")
    p.add_argument("--radius", type=float, metavar="METRES",
                   help="search distance in metres (default: unlimited); up to 64 cells "
                        "(1.9 km on a 30 m grid) every cell's ray is marched exactly, up to "
                        "1024 cells (30 km) sampled at every grid column it crosses, beyond "
                        "that the horizon sweep takes over")
    p.add_argument("--no-curvature", action="store_true",
                   help="flat Earth (default: curvature with refraction)")
    p.add_argument("--refraction", type=float, metavar="K",
                   help="refraction coefficient (default 0.13; not with --no-curvature)")
    p.add_argument("--threads", type=_c_int, default=0, metavar="N",
                   help="threads for the sweep and for compressing the GeoTIFF and EXR "
                        "(default 0: all cores, or those a CPU affinity or a container's CPU "
                        "quota allows, which also cap larger values; --compress LZMA on 2 "
                        "at least); results and file contents do not depend on it")
    p.add_argument("--products", metavar="LIST",
                   help="comma-separated products, written as bands in that order: %s; 'all' "
                        "adds HorizonAngles (default: all but HorizonAngles)"
                        % ", ".join(n for n, *_ in PRODUCTS))
    p.add_argument("--exr", metavar="OUT.exr", help="also write the products to this EXR")
    p.add_argument("--exr-type", choices=("float", "half"), metavar="float|half",
                   help="the EXR's sample type: float (default; the GeoTIFF's values exactly) or "
                        "half (16-bit, half the size, as GPUs and game engines take textures; "
                        "within 2^-11 of each value, relatively, 0.04 degree at 90; within 3e-8 "
                        "below 6.1e-5, half's smallest normal number)")
    p.add_argument("--compress", default="DEFLATE", metavar="CODEC",
                   help="GeoTIFF compression, lossless: DEFLATE (default), ZSTD, LZW, LZMA, "
                        "PACKBITS, LERC, LERC_DEFLATE, LERC_ZSTD, NONE")
    p.add_argument("--compress-level", type=_c_int, metavar="N",
                   help="compression level: DEFLATE 1-12, ZSTD 1-22, LZMA 1-9; -1: GDAL's "
                        "default (default 1, the fastest: DEFLATE's float bands shrink under "
                        "1%% more at "
                        "6); an error with the codecs that have no levels")
    p.add_argument("--nodata", type=_nodata_value, default=math.nan, metavar="VALUE",
                   help="the GeoTIFF's nodata value, which its nodata cells hold: nan "
                        "(default), or a number for tools that take no NaN, such as an ASCII "
                        "grid (-9999, as gdaldem's float outputs); the EXR keeps NaN")
    p.add_argument("--max-memory", type=_memory_size, metavar="SIZE",
                   help="most memory for the products and the sweep's state, beside the DEM's "
                        "elevations (4 bytes a cell): a number of MiB, or with K, M, G, T or "
                        "B (bytes) (default: the machine's physical memory, or a control "
                        "group's memory limit less 128 MiB where lower, as in a container, "
                        "or what an address-space limit (ulimit -v) leaves, less the "
                        "elevations); a bake that needs more is written in strips of "
                        "rows that fit, with the same results")
    p.add_argument("--near-field", type=_c_int, default=0, metavar="K",
                   help="columns of each cell's ray evaluated exactly, 1..64 (default 0: 32 "
                        "where the horizon sweep runs, 8 where rays are sampled at every "
                        "column); beyond them rays see the terrain where they cross grid "
                        "lines, and can miss a feature one cell wide (a mast in a DSM): 64 "
                        "finds those within 64 cells, for 10-20%% more time")
    p.add_argument("--quiet", "-q", action="store_true",
                   help="no progress display (shown, as by gdaldem, when stderr is a "
                        "terminal) and no summary line on stdout; warnings and errors still "
                        "go to stderr")
    p.set_defaults(func=cmd_bake)

    p = add_command("sun", help="where the sun is for a time and place; sunrise and sunset",
                    description="Sun position (NREL SPA: azimuth from true north, refracted "
                                "and geometric elevation), apparent disc radius, Earth-Sun "
                                "distance, equation of time, and the local day's sunrise, "
                                "transit and sunset (ISO 8601 UTC). With --dem, the place is "
                                "the DEM's centre, and the azimuth from the DEM's grid north "
                                "and the direction in its terrain-mesh frame are added.")
    p.add_argument("--at", required=True, metavar="ISO",
                   help="the time: ISO 8601 with an offset (2026-06-21T14:00+02:00, "
                        "2026-06-21T12:00Z), or a local time with --tz")
    p.add_argument("--tz", metavar="ZONE",
                   help="IANA time zone (Europe/Zurich) for a local --at and the local day; "
                        "clock changes are handled, and skipped or repeated times reported")
    p.add_argument("--lat", type=_number_in(-90, 90, "degrees"), metavar="DEG",
                   help="latitude, degrees north (-90..90)")
    p.add_argument("--lon", type=_number_in(-180, 180, "degrees"), metavar="DEG",
                   help="longitude, degrees east (-180..180)")
    p.add_argument("--height", type=float, metavar="M",
                   help="height above the ellipsoid, metres, -1000..10000 (default 0; with "
                        "--dem: the DEM's height at its centre)")
    p.add_argument("--pressure", type=_number_in(0, 5000, "hPa"), default=1013.25, metavar="HPA",
                   help="air pressure for refraction, hPa, 0..5000 (default 1013.25)")
    p.add_argument("--temperature", type=_number_in(-100, 100, "C"), default=15.0,
                   metavar="C", help="air temperature for refraction, degrees C, -100..100 "
                                     "(default 15)")
    p.add_argument("--no-refraction", action="store_true",
                   help="report geometric elevations as the apparent ones, and sunrise and "
                        "sunset where the sun's upper limb meets the geometric horizon (its "
                        "centre at -0.2667 deg, not at the -0.8333 deg that the standard "
                        "refraction gives; --pressure and --temperature do not move them)")
    p.add_argument("--sky", choices=sorted(SKY_MODELS), default="preetham",
                   help="sky radiance model (default preetham); the direct beam is the "
                        "clear-sky one whatever the sky: under cie-overcast, whose sky holds "
                        "the whole overcast day's light, leave the beam out")
    _add_atmosphere_options(p)
    p.add_argument("--delta-t", type=_number_in(-100000, 100000, "s"), metavar="S",
                   help="TT - UT1 in seconds, -100000..100000 (default: estimated for the "
                        "date)")
    p.add_argument("--days", type=_c_int, metavar="N",
                   help="a time series from --at over N days (default 1 with --step): local "
                        "days with --tz, to the same clock time N days on (23 or 25 hours on "
                        "a day the clocks change by an hour)")
    p.add_argument("--step", type=float, metavar="MIN",
                   help="time-series step in minutes, at least one second's, 1/60 "
                        "(0.016666667; default 60 with --days); "
                        "the series has every step before --days days have passed")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object (a list for a time series) of the text's "
                        "values, units in the key names: among them azimuth_deg, "
                        "elevation_deg, zenith_deg, elevation_true_deg, angular_radius_deg, "
                        "distance_au, equation_of_time_min, sunrise, transit, sunset (and "
                        "*_local), the light (air_mass, direct_normal_irradiance_w_m2, "
                        "sun_rgb_w_m2, sky_*) and, with --dem, grid_azimuth_deg, "
                        "direction_enu")
    _add_read_options(p, dem_option="take the place (and frame) from this DEM's centre (of "
                                    "the window read, with --srcwin)")
    p.set_defaults(func=cmd_sun)

    p = add_command("render", help="render the DEM lit by the sun and sky, to a PNG",
                    description="Render the DEM as a terrain mesh coloured by elevation and "
                                "lit by the sun and the sky through each point's aperture "
                                "(baked here, or read from 'aperture bake' output with "
                                "--baked), to a PNG. The sun is placed by time (--at, --tz: "
                                "its position, colour and strength for the DEM's centre) or "
                                "by --sun-az/--sun-el. Needs an X display (xvfb-run -a "
                                "aperture render ...).")
    _add_read_options(p)
    p.add_argument("-o", "--output", default="aperture.png", metavar="OUT.png",
                   help="PNG to write (default: aperture.png); with --frames, a name with "
                        "the frame number")
    p.add_argument("--radius", type=float, metavar="METRES",
                   help="search distance of the aperture baked here, in metres (default: "
                        "unlimited); with --srcwin the DEM within it around the window is read "
                        "(without it, all of the DEM), so that terrain outside the window casts "
                        "horizons as in 'aperture bake --srcwin'")
    p.add_argument("--baked", metavar="BAKED.tif",
                   help="reuse the BentNormal and ApertureRadius bands of 'aperture bake' "
                        "output for this DEM (the same grid, CRS and elevations; a bake of the "
                        "whole DEM serves any --srcwin of it) instead of baking")
    p.add_argument("--at", metavar="ISO", help="time of the sun, as for 'aperture sun' (with "
                                               "--frames: of the first frame)")
    p.add_argument("--tz", metavar="ZONE", help="IANA time zone for a local --at")
    p.add_argument("--frames", type=_c_int, metavar="N",
                   help="a time-lapse: N pictures from --at, every --step minutes, of one bake "
                        "and one mesh (the sun moves, nothing else); -o (and --exr) hold the "
                        "frame number, frame-%%03d.png (or %%3d) for frame-000.png, ... (%%%% "
                        "for a %% sign); one exposure for all (--exposure, or the automatic one "
                        "of the frame whose sun is highest), so the light's changes show")
    p.add_argument("--step", type=float, metavar="MIN",
                   help="with --frames: minutes between frames, at least one second's, 1/60 "
                        "(0.016666667; default 10)")
    p.add_argument("--sun-az", "--light-az", dest="sun_az", type=float, metavar="DEG",
                   help="sun azimuth, clockwise from true north (default 225 without --at)")
    p.add_argument("--sun-el", "--light-el", dest="sun_el", type=float, metavar="DEG",
                   help="sun elevation (default 35 without --at)")
    p.add_argument("--size", type=_parse_size, default=(1200, 900), metavar="WxH",
                   help="image size in pixels (default 1200x900)")
    p.add_argument("--view", choices=("oblique", "top"), default="oblique",
                   help="oblique from the south (default) or top-down with north up")
    p.add_argument("--exaggeration", type=float, default=1.0, metavar="X",
                   help="vertical exaggeration (default 1)")
    p.add_argument("--camera", type=_parse_camera, metavar="AZ,EL[,ZOOM]",
                   help="oblique view: look from azimuth AZ (degrees from north; default 180, "
                        "from the south) down at EL degrees (default 35), zoomed ZOOM times "
                        "(default 1: the whole DEM fits); top view: only ZOOM is used")
    p.add_argument("--intersection", choices=("exact", "smoothstep"),
                   help="sun-aperture cap intersection: exact closed form (default) or Oat & "
                        "Sander's smoothstep")
    p.add_argument("--lambert", choices=("centroid", "exactcap"),
                   help="Lambert term: intersection centroid (default) or the exact sun cap")
    p.add_argument("--sun-scale", type=float, metavar="S",
                   help="widen the sun's disc S times: softer, broader penumbrae (default 1)")
    p.add_argument("--sky", choices=("constant", "model"),
                   help="constant: one sky radiance (the uniform one giving the Preetham "
                        "sky's irradiance on level ground; default); model: each aperture "
                        "filled with the Preetham sky over that aperture, cosine-weighted "
                        "(brighter towards the sun)")
    p.add_argument("--exposure", type=float, metavar="EV",
                   help="exposure in EV, -30..30 (default: automatic, a flat open white "
                        "surface in the sun at about 80%% grey)")
    _add_atmosphere_options(p)
    p.add_argument("--albedo", metavar="IMAGE",
                   help="a picture (e.g. an orthophoto: grey, RGB, RGBA or a palette, 8- or "
                        "16-bit, in any format GDAL reads) draped over the whole DEM, its top "
                        "edge north, as its albedo instead of the elevation colours")
    p.add_argument("--shading", choices=("pixel", "vertex"),
                   help="evaluate the lighting at every pixel (default) or at the vertices, "
                        "interpolated (faster for meshes of about pixel-sized triangles)")
    p.add_argument("--exr", metavar="OUT.exr",
                   help="also write the linear radiance (W/m2/sr, before exposure and tone "
                        "mapping) as an RGBA OpenEXR read back from a float framebuffer (of "
                        "fewer than 2^28 pixels, 16 bytes each: VTK reads back less than 4 GiB)")
    p.add_argument("--exr-type", choices=("float", "half"), metavar="float|half",
                   help="EXR sample type (default float)")
    p.add_argument("--multisamples", type=_c_int, default=8, metavar="N",
                   help="antialiasing samples per pixel of the PNG, 0..16 (default 8; the EXR "
                        "is always one sample per pixel)")
    p.add_argument("--lighting", choices=("aperture", "standard"), default="aperture",
                   help="aperture: sun and sky through the aperture (default); standard: VTK's "
                        "lighting with a white light from the sun's direction, on the "
                        "elevation colours (the aperture's, the sky's and the albedo's options "
                        "do not apply)")
    p.add_argument("--quiet", "-q", action="store_true",
                   help="no 'wrote' lines on stdout; warnings and errors still go to stderr")
    # (the aperture's options, and here the atmosphere's shared ones, are None when not given:
    # _render_option_checks fills in _APERTURE_LIGHTING_OPTIONS' defaults, which the help gives)
    p.set_defaults(func=cmd_render, turbidity=None, linke_turbidity=None)
    return parser


def main(argv=None):
    """Run the command line on `argv` (default sys.argv[1:]) and return its exit status (usage
    errors and --help end in SystemExit, as argparse does). While it runs, VTK's own console
    output is kept off the terminal (errors.quiet_vtk_output); VTK's output window and its
    logger's stderr verbosity are put back when it returns, so a script that calls it still
    sees VTK's messages afterwards. (VTK has no getter of the stderr verbosity: the one put
    back is VTK's cutoff over all its log outputs, at most INFO, VTK's default, so that a
    script logging to a file in detail does not get that detail on stderr too.)"""
    # file names that are not UTF-8 (held with surrogates) print as the bytes they are
    for stream in (sys.stdout, sys.stderr):
        if hasattr(stream, "reconfigure"):
            stream.reconfigure(errors="surrogateescape")
    from vtkmodules.vtkCommonCore import vtkLogger, vtkOutputWindow
    window = vtkOutputWindow.GetInstance()
    verbosity = min(vtkLogger.GetCurrentVerbosityCutoff(), vtkLogger.VERBOSITY_INFO)
    # (no stdout at all under `python3 -m aperture ... >&-`: nothing to guard, or to write)
    stdout = sys.stdout
    if stdout is not None:
        sys.stdout = _GuardedStdout(stdout)
    _WARNED.clear()
    try:
        try:
            status = _main(sys.argv[1:] if argv is None else argv)
        except SystemExit as e:  # (argparse's --help and usage errors: their text flushed too)
            status = e
        # what is still buffered (all of it, unless PYTHONUNBUFFERED is set) written here, so
        # that a reader gone is a BrokenPipeError below, not one at the interpreter's exit
        if stdout is not None:
            sys.stdout.flush()
        if isinstance(status, SystemExit):
            raise status
        return status
    except BrokenPipeError:
        # stdout closed before the report was written (`aperture info --json x | head -1`):
        # end quietly, as a tool that SIGPIPE ends does (the report comes after the outputs,
        # which are whole), with its status
        _stdout_to_devnull(stdout)
        import signal
        return 128 + signal.SIGPIPE
    except _StdoutUnwritable as e:  # (a full disk, /dev/full)
        print("%s: error: cannot write the standard output: %s" % (PROG, e), file=sys.stderr)
        _stdout_to_devnull(stdout)
        return 1
    finally:
        sys.stdout = stdout
        vtkOutputWindow.SetInstance(window)
        vtkLogger.SetStderrVerbosity(verbosity)


class _StdoutUnwritable(Exception):
    """stdout refused what was written to it, for another reason than a reader gone."""


class _GuardedStdout:
    """sys.stdout while main runs: a failure to write it other than a closed pipe is
    _StdoutUnwritable, told apart from the OSErrors of the files a command works on."""

    def __init__(self, stream):
        self._stream = stream

    def _guarded(self, call, *args):
        try:
            return call(*args)
        except BrokenPipeError:
            raise
        except OSError as e:
            raise _StdoutUnwritable(e.strerror or str(e)) from None

    def write(self, text):
        return self._guarded(self._stream.write, text)

    def flush(self):
        return self._guarded(self._stream.flush)

    def __getattr__(self, name):
        return getattr(self._stream, name)


def _stdout_to_devnull(stdout):
    """`stdout` onto /dev/null, what is left in its buffer dropped: the interpreter's final
    flush would fail again, with a message."""
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, stdout.fileno())
    os.close(devnull)


def _negative_values(parser, argv):
    """argv with a value that starts with '-' and a digit joined to its option (`--at
    -2000-01-01T12:00Z`, `--camera -30,20` become `--at=...`, `--camera=...`): argparse takes
    such a value, not a plain negative number, for an option of its own and stops."""
    takes_value = set()
    pending = [parser]
    while pending:
        p = pending.pop()
        for action in p._actions:
            if isinstance(action, argparse._SubParsersAction):
                pending.extend(action.choices.values())
            elif action.option_strings and action.nargs is None:
                takes_value.update(o for o in action.option_strings if o.startswith("--"))
    out = []
    for arg in argv:
        # (-inf, -nan: argparse said "expected one argument", not the option's range)
        if out and out[-1] in takes_value and re.match(r"-([0-9.]|inf|nan)", arg, re.I):
            out[-1] = out[-1] + "=" + arg
        else:
            out.append(arg)
    return out


# string options whose empty value is a mistake (an unset variable in a script), not "none":
# each was taken as not given (--compress "" wrote an uncompressed file)
_NOT_EMPTY = (("output", None), ("exr", "--exr"), ("srs", "--srs"), ("compress", "--compress"),
              ("albedo", "--albedo"), ("baked", "--baked"), ("at", "--at"), ("tz", "--tz"),
              ("products", "--products"))


def _refuse_empty(args):
    for dest, name in _NOT_EMPTY:
        if getattr(args, dest, None) == "":
            raise _UsageError("%s is empty" % (name or (
                "the output name OUT.tif" if args.func is cmd_bake else "--output")))


# gdaldem's and GDAL's options, which a GIS analyst tries first: how many values each takes
# after it, at most (up to an option; none when written -co=VALUE), and what to give instead
# (each was "unrecognized arguments" alone until 2026-12-07), by command (None: any other)
_GDAL_HABITS = {
    "-co": (1, {"bake": "GDAL's creation options are not taken: --compress CODEC and "
                        "--compress-level N choose the compression (the GeoTIFF is tiled, with "
                        "the floating-point predictor, BigTIFF when it needs to be)",
                None: "only 'aperture bake' writes a GeoTIFF"}),
    "-of": (1, {"bake": "bake writes a GeoTIFF (and an OpenEXR file with --exr), whatever the "
                        "name",
                "render": "render writes a PNG (and an OpenEXR file with --exr)",
                None: "only bake and render write files"}),
    "-s": (1, {None: "cell sizes come in metres from the DEM's CRS, lat/lon included; "
                     "--zfactor Z gives the metres of an elevation unit"}),
    "-z": (1, {"render": "--exaggeration stretches the heights drawn; --zfactor Z gives the "
                         "metres of an elevation unit",
               None: "--zfactor Z gives the metres of an elevation unit"}),
    "-compute_edges": (0, {None: "every cell is computed, next to the DEM's edge too (terrain "
                                 "beyond it is invisible: bake's EdgeTruncated flags the cells "
                                 "it could hide)"}),
    "--config": (2, {None: "GDAL's configuration options are read from the environment: "
                           "GDAL_CACHEMAX=512 aperture ..."}),
}
_GDAL_HABITS["--co"], _GDAL_HABITS["--of"] = _GDAL_HABITS["-co"], _GDAL_HABITS["-of"]  # (3.11's)


def _habit_refusal(parser, argv):
    """The usage error for gdaldem's options in `argv`, with what to give instead (once for
    each option), or None. Looked for before argparse reads them, which read render's -of as
    -o f and bake's -co COMPRESS=ZSTD's value as the DEM, so that their hints never showed."""
    # (the command's name first: a mistyped one is argparse's to name; values are taken up to
    # an option, so that -z --exaggeration 2 does not name --exaggeration, and --config's
    # KEY=VALUE form takes one)
    command = argv[0] if argv and argv[0] in parser.commands else None
    options = argv[:argv.index("--")] if "--" in argv else argv
    if not command or "-h" in options or "--help" in options:
        return None  # (--help is argparse's to give, as beside any other unknown argument)
    found, hints = [], {}  # (hints: the options that share each text, -co and --co alike)
    k = 1
    while k < len(argv) and argv[k] != "--":
        key = argv[k].split("=", 1)[0]
        if key not in _GDAL_HABITS:
            k += 1
            continue
        values, hint = _GDAL_HABITS[key]
        n = 1
        wanted = 0 if "=" in argv[k] else values
        while n <= wanted and k + n < len(argv) and not (
                argv[k + n].startswith("-") and not re.match(r"-[0-9.]", argv[k + n])):
            n += 1
            if key == "--config" and "=" in argv[k + n - 1]:
                break
        found.append(" ".join(argv[k:k + n]))
        keys = hints.setdefault(hint.get(command, hint[None]), [])
        keys += [] if key in keys else [key]
        k += n
    if not found:
        return None
    return parser.commands.get(command, parser), "unrecognized arguments: %s. %s" % (
        " ".join(found), "; ".join("%s: %s" % (", ".join(keys), text)
                                   for text, keys in hints.items()))


def _main(argv):
    parser = build_parser()
    if not argv:
        parser.print_help()
        return 0
    habits = _habit_refusal(parser, argv)
    if habits:
        habits[0].error(habits[1])
    args, unknown = parser.parse_known_args(_negative_values(parser, argv))
    if unknown:
        # (in the command's usage: parse_args said them in the top level's, naming no option
        # of the command)
        command = parser.commands.get(getattr(args, "command", None), parser)
        command.error("unrecognized arguments: %s" % " ".join(unknown))
    if not getattr(args, "func", None):
        parser.print_help()
        return 0
    quiet_vtk_output()
    try:
        _refuse_empty(args)
        return args.func(args)
    except _UsageError as e:
        # (in the command's usage, exit status 2: parser.error ends the process as it does for
        # argparse's own checks)
        parser.commands.get(args.command, parser).error(_as_options(str(e)))
    except ApertureError as e:
        print("%s: error: %s" % (PROG, _as_options(str(e))), file=sys.stderr)
        return 1
    except MemoryError:
        # numpy's conversions of the products: the filters name their own sizes
        print("%s: error: out of memory; %s" % (PROG, _SMALLER_READ), file=sys.stderr)
        return 1
    except KeyboardInterrupt as e:
        return 128 + e.signum if isinstance(e, _Terminated) else 130


if __name__ == "__main__":
    sys.exit(main())
