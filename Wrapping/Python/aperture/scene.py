# SPDX-License-Identifier: BSD-3-Clause
"""Terrain scenes for pictures: a DEM mesh coloured by elevation, lit either by the sun and
the sky through each point's aperture (vtkApertureLightingMapper, `build_aperture`) or by one
directional light with VTK's standard lighting (`build`), framed top-down (north up) or
obliquely from the south. Used by `aperture render` and the rendering regression tests.

Frames: the mesh is in the local East-North-Up frame of vtkApertureTerrainMesh (x east,
y north, z up, metres). Light azimuth is clockwise from north in that frame, elevation above
the horizontal, both in degrees (gdaldem's hillshade default is azimuth 315, elevation 45).
"""
import math
import os
import stat

from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (
    vtkActor,
    vtkColorTransferFunction,
    vtkLight,
    vtkRenderer,
    vtkRenderWindow,
    vtkWindowToImageFilter,
)
# Registers the OpenGL implementations behind vtkRenderWindow and friends.
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

from aperture import vtkApertureLightingMapper

VIEWS = ("top", "oblique")
SKY_MODES = ("constant", "model")


def _number(name, value, low=-math.inf, high=math.inf, above=False):
    """`value` as a float: TypeError unless a number (a str or a bool is not one), ValueError
    unless finite and within [low, high] (above: > low), both naming `name`."""
    if isinstance(value, (str, bytes, bool)):
        raise TypeError("%s must be a number, not %r" % (name, value))
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise TypeError("%s must be a number, not %r" % (name, value)) from None
    if not math.isfinite(v):
        raise ValueError("%s must be finite, not %r" % (name, value))
    if v < low or (above and v == low) or v > high:
        bound = ("within [%g, %g]" % (low, high) if high < math.inf else
                 "%s %g" % ("above" if above else "at least", low))
        raise ValueError("%s must be %s, not %r" % (name, bound, value))
    return v


def _numbers(name, values, count, **limits):
    """`count` numbers as _number checks them (a sequence of that length, not a str, else
    TypeError)."""
    return [_number(name, v, **limits) for v in _sequence(name, values, (count,),
                                                         "%d numbers" % count)]


def _sequence(name, values, lengths, what):
    """`values` as a list whose length is one of `lengths` (a tuple, list, numpy array...; not
    a str or bytes); TypeError naming `name` and `what` it must be otherwise."""
    if isinstance(values, (str, bytes)):
        raise TypeError("%s must be %s, not %r" % (name, what, values))
    try:
        values = list(values)
    except TypeError:
        raise TypeError("%s must be %s, not %r" % (name, what, values)) from None
    if len(values) not in lengths:
        raise TypeError("%s must be %s, not %r" % (name, what, values))
    return values


def _check_size(size):
    """(width, height) in pixels, each a whole number of at least 1; ValueError otherwise."""
    w, h = _numbers("size", size, 2, low=1.0)
    if w != int(w) or h != int(h):
        raise ValueError("size must be whole pixels, not %r" % (size,))
    return int(w), int(h)


def _check_camera(camera):
    """None, or (azimuth, elevation[, zoom]) for frame(): finite degrees, the elevation within
    [-90, 90], the zoom within [0.001, 10000] (beyond, the camera's clipping range loses the
    terrain: a blank picture)."""
    if camera is None:
        return None
    camera = _sequence("camera", camera, (2, 3),
                       "(azimuth, elevation) or (azimuth, elevation, zoom)")
    checked = [_number("camera azimuth", camera[0]),
               _number("camera elevation", camera[1], -90.0, 90.0)]
    if len(camera) == 3:
        checked.append(_number("camera zoom", camera[2], 1e-3, 1e4))
    return tuple(checked)


def _quietly(obj, method, *args):
    """obj.method(*args), an error it reports taken by an observer instead of printed by VTK
    (the caller raises it, from obj.GetErrorMessage())."""
    tag = obj.AddObserver("ErrorEvent", lambda caller, event: None)
    try:
        return getattr(obj, method)(*args)
    finally:
        obj.RemoveObserver(tag)


def direction_enu(azimuth_deg, elevation_deg):
    """Unit vector (east, north, up) towards azimuth (clockwise from north) and elevation."""
    az, el = math.radians(azimuth_deg), math.radians(elevation_deg)
    return (math.cos(el) * math.sin(az), math.cos(el) * math.cos(az), math.sin(el))


def hypsometric_colors(zmin, zmax):
    """Elevation colours: lowland greens, upland tans and browns, light grey summits, from zmin
    to zmax (finite, zmin <= zmax; ValueError otherwise)."""
    zmin, zmax = _number("zmin", zmin), _number("zmax", zmax)
    if zmin > zmax:
        raise ValueError("zmin %g is above zmax %g" % (zmin, zmax))
    ctf = vtkColorTransferFunction()
    span = max(zmax - zmin, 1e-6)
    stops = [(0.00, (0.20, 0.42, 0.25)), (0.25, (0.45, 0.60, 0.32)), (0.50, (0.78, 0.74, 0.50)),
             (0.75, (0.62, 0.48, 0.33)), (1.00, (0.93, 0.92, 0.90))]
    for t, rgb in stops:
        ctf.AddRGBPoint(zmin + t * span, *rgb)
    ctf.SetNanColor(0.0, 0.0, 0.0)
    return ctf


def elevation_range(mesh, name="Elevation"):
    """(lowest, highest) value of the mesh's point array `name` (metres for the Elevation of
    vtkApertureTerrainMesh; NaN nodata skipped); ValueError when the mesh has no such array
    or it holds no finite value (no points, or all nodata)."""
    array = mesh.GetPointData().GetArray(name)
    if array is None:
        raise ValueError("the mesh has no point array '%s'" % name)
    lo, hi = array.GetRange()
    if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
        raise ValueError("the mesh's point array '%s' has no finite value (%s)" % (
            name, "no points" if array.GetNumberOfTuples() == 0 else "all nodata"))
    return lo, hi


def color_by_elevation(mapper, mesh):
    """Colour the mesh by its Elevation point array with the hypsometric colours."""
    zmin, zmax = elevation_range(mesh)
    mapper.SetLookupTable(hypsometric_colors(zmin, zmax))
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray("Elevation")
    mapper.SetScalarRange(zmin, zmax)
    mapper.ScalarVisibilityOn()


def build(mesh, size=(1200, 900), view="oblique", light_azimuth=315.0, light_elevation=45.0,
          exposure=0.0, multisamples=8, background=(1.0, 1.0, 1.0), camera=None):
    """A render window showing the mesh with VTK's own lighting from light_azimuth and
    light_elevation (degrees; from true north, above the horizon), scaled by 2^exposure (EV);
    a light below the horizon lights nothing, as the sun there in build_aperture (the mesh is
    black, no ambient term either: no slope facing it is lit from below the Earth);
    returns (render_window, renderer). The window renders off screen (an X display, e.g. Xvfb,
    is still needed by Debian's VTK). ValueError for an unknown view, a light elevation outside
    -90..90, a value that is not finite, a size or camera that frames nothing, or a mesh
    without an Elevation array (TypeError for a value that is not a number)."""
    if view not in VIEWS:
        raise ValueError("view must be one of %s, not %r" % (", ".join(VIEWS), view))
    # (aim_light and offscreen_window say it too: before any work)
    _number("light azimuth", light_azimuth)
    _number("light elevation", light_elevation, -90.0, 90.0)
    exposure = _number("exposure", exposure)
    _check_window_options(size, multisamples, background, camera)
    mapper = vtkApertureLightingMapper()
    mapper.SetLightingModel(vtkApertureLightingMapper.STANDARD)  # VTK lighting + exposure
    mapper.SetInputData(mesh)
    color_by_elevation(mapper, mesh)
    mapper.SetExposure(exposure)

    actor = vtkActor()
    actor.SetMapper(mapper)
    prop = actor.GetProperty()
    prop.SetDiffuse(0.85)
    prop.SetSpecular(0.0)

    renderer = vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(*background)
    renderer.AutomaticLightCreationOff()
    light = vtkLight()
    light.SetLightTypeToSceneLight()
    light.SetPositional(False)
    light.SetFocalPoint(0.0, 0.0, 0.0)
    renderer.AddLight(light)
    aim_light(renderer, light_azimuth, light_elevation)

    return offscreen_window(renderer, mesh, view, size, multisamples, camera), renderer


def aim_light(renderer, light_azimuth, light_elevation):
    """Move the light of a `build` renderer to light_azimuth, light_elevation (degrees), as
    `build` places it: below the horizon it lights nothing, and the mesh's ambient term is off
    with it. ValueError for an elevation outside -90..90 or an azimuth that is not finite, and
    for a renderer that `build` did not make (no light of its own, as build_aperture's)."""
    light_azimuth = _number("light azimuth", light_azimuth)
    light_elevation = _number("light elevation", light_elevation, -90.0, 90.0)
    light = renderer.GetLights().GetItemAsObject(0)
    actor = renderer.GetActors().GetLastActor()
    mapper = actor.GetMapper() if actor is not None else None
    # (an aperture renderer has a light too once drawn: VTK makes one; its mapper tells)
    if (light is None or not isinstance(mapper, vtkApertureLightingMapper) or
            mapper.GetLightingModel() != vtkApertureLightingMapper.STANDARD):
        raise ValueError("aim_light moves the light of a renderer made by build(); this one "
                         "is not (an aperture's sun moves with set_sun)")
    lit = light_elevation >= 0.0
    actor.GetProperty().SetAmbient(0.25 if lit else 0.0)
    light.SetPosition(*direction_enu(light_azimuth, light_elevation))
    # (off by its intensity, not SwitchOff: with no light on, VTK draws the colours unlit)
    light.SetIntensity(1.0 if lit else 0.0)


def _check_window_options(size, multisamples, background, camera):
    """The checks of offscreen_window's and the builders' window options (background None:
    the renderer's own, not checked); returns the camera as a tuple of floats, or None."""
    _check_size(size)
    m = _number("multisamples", multisamples, 0.0, 16.0)
    if m != int(m):
        raise ValueError("multisamples must be a whole number within [0, 16], not %r"
                         % (multisamples,))
    if background is not None:
        _numbers("background", background, 3, low=0.0, high=1.0)
    return _check_camera(camera)


def offscreen_window(renderer, mesh, view, size, multisamples, camera=None):
    """An off-screen render window of `size` (width, height: whole pixels, at least 1) showing
    `renderer`, framed for `view`; multisamples 0..16; camera: None or (azimuth, elevation[,
    zoom]) for frame(). ValueError (TypeError) for values outside those."""
    camera = _check_window_options(size, multisamples, None, camera)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(int(size[0]), int(size[1]))
    window.SetMultiSamples(int(multisamples))
    window.AddRenderer(renderer)
    frame(renderer, mesh, view, size, *(camera or ()))
    return window


def luminance(rgb):
    """Rec.709 luminance of linear RGB."""
    return 0.2126390059 * rgb[0] + 0.7151686788 * rgb[1] + 0.0721923154 * rgb[2]


def sky_radiance(sun):
    """The uniform sky radiance (W/m2/sr, RGB) that gives the sun's sky model's irradiance on a
    horizontal surface: the model's cosine-weighted hemisphere integral divided by pi.
    ValueError when the sun has not been computed."""
    mean, irradiance = [0.0] * 3, [0.0] * 3
    if not _quietly(sun, "GetSkyCap", [0.0, 0.0, 1.0], 90.0, [0.0, 0.0, 1.0], mean, irradiance):
        raise ValueError("the sun: %s" % sun.GetErrorMessage())
    return [v / math.pi for v in irradiance]


def auto_exposure(sun_rgb, sun_elevation, sky_rgb):
    """EV that maps a flat, open, white (albedo 0.8) surface to x = 1 before tone mapping (0.63,
    about 208 of 255 on screen): 2^EV = 1 / L, L = 0.8 (E_sun sin e + pi L_sky) / pi, with the
    sun's elevation counted at 12 degrees at least so that low suns are not over-exposed (L at
    least 1e-6). No light at all (a sun below the horizon): 0, the picture black at any EV."""
    e = math.radians(max(sun_elevation, 12.0))
    radiance = 0.8 * (luminance(sun_rgb) * math.sin(e) + math.pi * luminance(sky_rgb)) / math.pi
    if not radiance > 0.0:
        return 0.0
    return -math.log2(max(radiance, 1e-6))


def build_aperture(mesh, sun, size=(1200, 900), view="oblique", sun_scale=1.0,
                   intersection="exact", lambert="centroid", exposure=None, texture=None,
                   multisamples=8, background=(1.0, 1.0, 1.0), sky=None, camera=None,
                   sky_mode="constant", shading="pixel"):
    """A render window showing the mesh lit by the sun and sky of `sun` (a computed
    vtkApertureSolarPosition) through each point's aperture. The mesh needs the Normals,
    BentNormal and ApertureRadius point arrays (bake, then mesh). Albedo: the elevation colours, or
    `texture` (a vtkTexture draped by the mesh's TextureCoordinates). Exposure in EV, None:
    auto_exposure. sky_mode "constant": one sky radiance everywhere (`sky`, or the uniform radiance
    giving the model's irradiance on level ground, sky_radiance); "model": each aperture filled with
    the sun's sky model over that aperture (a table of the caps' radiances, cosine-weighted about
    their axes: vtkApertureSolarPosition.ComputeSkyTable). shading "pixel" (default) or "vertex":
    where the lighting model runs. intersection "exact" or "smoothstep", lambert "centroid" or
    "exactcap" (the mapper's modes).
    Returns (render_window, renderer, mapper). ValueError for an unknown view, sky_mode,
    intersection, lambert or shading, a mesh without the Elevation, Normals, BentNormal or
    ApertureRadius arrays, a sun that has not been computed, a sun_scale that is not positive,
    an exposure or sky that is not finite (or a negative sky), a size or camera that frames
    nothing (TypeError for a value that is not a number)."""
    if view not in VIEWS:
        raise ValueError("view must be one of %s, not %r" % (", ".join(VIEWS), view))
    for name, value, choices in (("sky_mode", sky_mode, SKY_MODES),
                                 ("intersection", intersection, ("exact", "smoothstep")),
                                 ("lambert", lambert, ("centroid", "exactcap")),
                                 ("shading", shading, ("pixel", "vertex"))):
        if value not in choices:
            raise ValueError("%s must be %s, not %r" % (name, " or ".join(choices), value))
    # (before any work: the elevation colours and the lighting need these arrays)
    elevation_range(mesh)
    for name in ("Normals", "BentNormal", "ApertureRadius"):
        if mesh.GetPointData().GetArray(name) is None:
            raise ValueError("the mesh has no point array '%s': mesh a DEM baked with "
                             "vtkApertureSkyVisibility (BentNormal, ApertureRadius) by "
                             "vtkApertureTerrainMesh" % name)
    sun_scale = _number("sun_scale", sun_scale, 0.0, above=True)
    if exposure is not None:
        exposure = _number("exposure", exposure)
    _check_window_options(size, multisamples, background, camera)

    mapper = vtkApertureLightingMapper()
    mapper.SetInputData(mesh)
    sun_rgb, sky_rgb = set_sun(mapper, sun, sky_mode, sky)
    mapper.SetSunScale(sun_scale)
    mapper.SetShadingFrequency(mapper.PER_VERTEX if shading == "vertex" else mapper.PER_FRAGMENT)
    mapper.SetIntersectionMode(mapper.SMOOTHSTEP if intersection == "smoothstep" else mapper.EXACT)
    mapper.SetLambertMode(mapper.EXACT_CAP if lambert == "exactcap" else mapper.CENTROID)
    if exposure is None:
        exposure = auto_exposure(sun_rgb, sun.GetElevation(), sky_rgb)
    mapper.SetExposure(exposure)
    actor = vtkActor()
    actor.SetMapper(mapper)
    if texture is not None:
        mapper.ScalarVisibilityOff()
        actor.SetTexture(texture)
        actor.GetProperty().SetColor(1.0, 1.0, 1.0)
    else:
        color_by_elevation(mapper, mesh)

    renderer = vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(*background)
    return offscreen_window(renderer, mesh, view, size, multisamples, camera), renderer, mapper


def set_sun(mapper, sun, sky_mode="constant", sky=None):
    """Light an aperture mapper by `sun` (a computed vtkApertureSolarPosition): its direction,
    angular radius and colour, and the sky as `build_aperture` takes it (sky_mode "constant":
    `sky` or sky_radiance(sun); "model": the sky model's table). Uniforms and the sky's small
    texture only: moving the sun of a drawn scene (a time-lapse) uploads no geometry; "constant"
    takes away a model's table set before. Returns (sun_rgb, sky_rgb), the sun's irradiance and
    the uniform sky radiance. ValueError, the mapper unchanged, for a sky_mode other than those
    two, a sun that has not been computed, or a `sky` that is not three finite radiances of 0
    or more (TypeError for values that are not numbers)."""
    if sky_mode not in SKY_MODES:
        raise ValueError("sky_mode must be %s, not %r" % (" or ".join(SKY_MODES), sky_mode))
    model_sky = sky_radiance(sun)  # (ValueError for a sun not computed, `sky` given or not)
    sky_rgb = _numbers("sky", sky, 3, low=0.0) if sky is not None else model_sky
    table = None
    if sky_mode == "model":
        from vtkmodules.vtkCommonCore import vtkFloatArray
        table = vtkFloatArray()
        if not _quietly(sun, "ComputeSkyTable", table, 32, 9, 9):
            raise ValueError(sun.GetErrorMessage())
    direction, sun_rgb = [0.0] * 3, [0.0] * 3
    sun.GetDirection(direction)
    sun.GetSunColor(sun_rgb)
    mapper.SetSunDirection(direction)
    mapper.SetSunAngularRadius(sun.GetAngularRadius())
    mapper.SetSunIrradiance(*sun_rgb)
    mapper.SetSkyRadiance(*sky_rgb)
    mapper.SetSkyTable(table, 32, 9, 9)
    return sun_rgb, sky_rgb


def frame(renderer, mesh, view, size, camera_azimuth=180.0, camera_elevation=35.0, zoom=1.0):
    """Place the camera: "top" looks straight down with north up (orthographic); "oblique"
    looks from camera_azimuth (degrees clockwise from north; default 180: from the south,
    looking north) down at camera_elevation degrees, perspective, at the distance where the
    whole mesh fits, divided by zoom. ValueError (TypeError) for a view other than those, a
    size of less than a pixel, an azimuth that is not finite, an elevation outside [-90, 90]
    or a zoom outside [0.001, 10000]."""
    if view not in VIEWS:
        raise ValueError("view must be one of %s, not %r" % (", ".join(VIEWS), view))
    size = _check_size(size)
    camera_azimuth, camera_elevation, zoom = _check_camera(
        (camera_azimuth, camera_elevation, zoom))
    b = mesh.GetBounds()
    cx, cy, cz = (b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2
    width, height, depth = b[1] - b[0], b[3] - b[2], b[5] - b[4]
    camera = renderer.GetActiveCamera()
    aspect = size[0] / float(size[1])
    if view == "top":
        camera.ParallelProjectionOn()
        camera.SetFocalPoint(cx, cy, cz)
        camera.SetPosition(cx, cy, b[5] + 10.0 * max(width, height, 1.0))
        camera.SetViewUp(0.0, 1.0, 0.0)
        camera.SetParallelScale(0.5 * max(height, width / aspect) * 1.02 / zoom)
        renderer.ResetCameraClippingRange()
        return
    camera.ParallelProjectionOff()
    view_angle = 30.0
    camera.SetViewAngle(view_angle)
    # Look north, down at 35 degrees, from the distance at which all eight corners of the
    # bounding box fit: a corner at q (relative to the focal point) is at depth D + q.d and must
    # satisfy |q.up| <= depth tan(angle/2) and |q.right| <= depth aspect tan(angle/2).
    elevation = math.radians(camera_elevation)
    az = math.radians(camera_azimuth)
    # the horizontal direction the camera looks in: away from its azimuth
    hx, hy = -math.sin(az), -math.cos(az)
    d = (hx * math.cos(elevation), hy * math.cos(elevation), -math.sin(elevation))
    up = (hx * math.sin(elevation), hy * math.sin(elevation), math.cos(elevation))
    right = (d[1] * up[2] - d[2] * up[1], d[2] * up[0] - d[0] * up[2], d[0] * up[1] - d[1] * up[0])
    t = math.tan(math.radians(view_angle) / 2.0)
    distance = 0.0
    for x in (b[0], b[1]):
        for y in (b[2], b[3]):
            for z in (b[4], b[5]):
                q = (x - cx, y - cy, z - cz)
                along = sum(a * c for a, c in zip(q, d))
                need_up = abs(sum(a * c for a, c in zip(q, up))) / t - along
                need_right = abs(sum(a * c for a, c in zip(q, right))) / (aspect * t) - along
                distance = max(distance, need_up, need_right)
    distance *= 1.03 / zoom
    camera.SetFocalPoint(cx, cy, cz)
    camera.SetPosition(cx - distance * d[0], cy - distance * d[1], cz - distance * d[2])
    camera.SetViewUp(*up)
    renderer.ResetCameraClippingRange()


def _render_pixels(window):
    window.Render()
    grabber = vtkWindowToImageFilter()
    grabber.SetInput(window)
    grabber.SetInputBufferTypeToRGB()
    grabber.ReadFrontBufferOff()
    grabber.Update()
    return grabber.GetOutput()


def _blank(window, image):
    """Every byte of the picture 0 over a background that is not black: nothing was drawn."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    renderer = window.GetRenderers().GetFirstRenderer()
    if renderer is None or max(renderer.GetBackground()) < 0.5 / 255:
        return False
    scalars = image.GetPointData().GetScalars()
    return scalars is not None and not vtk_to_numpy(scalars).any()


def _background_drawn(window):
    """Whether the driver draws the renderers' backgrounds at this size: the window rendered
    once with every prop hidden (a picture all black over a background that is not may be
    terrain unlit at night filling the view, or nothing drawn at all)."""
    hidden = []
    renderers = window.GetRenderers()
    renderers.InitTraversal()
    for _ in range(renderers.GetNumberOfItems()):
        props = renderers.GetNextItem().GetViewProps()
        props.InitTraversal()
        for _ in range(props.GetNumberOfItems()):
            prop = props.GetNextProp()
            if prop.GetVisibility():
                prop.VisibilityOff()
                hidden.append(prop)
    try:
        return not _blank(window, _render_pixels(window))
    finally:
        for prop in hidden:
            prop.VisibilityOn()


def grab(window, on_warning=None):
    """Render the window and return its RGB pixels as a vtkImageData (row 0 at the bottom).
    A multisampled picture that comes back blank (the OpenGL driver could not make a
    multisampled framebuffer that large, and said nothing: Mesa's llvmpipe beyond 2 GiB, from
    some 11600 x 11600 pixels at the default 8 samples, which VTK lowers to 4) is rendered
    again without multisampling, which the window keeps, and on_warning(message) is told.
    A blank picture whose background the driver draws alone is what was drawn (unlit terrain
    filling the view). RuntimeError when nothing is drawn even without multisampling, and
    for a picture of 2 GiB or more (VTK's vtkWindowToImageFilter counts its bytes in 32 bits:
    27000 x 27000 pixels aborted the process, std::bad_alloc, until 2026-12-07)."""
    width, height = window.GetSize()
    if 3 * width * height >= 2 ** 31:
        raise RuntimeError("a picture of %d x %d pixels is 2 GiB or more of RGB, which VTK "
                           "cannot read back: render a smaller one" % (width, height))
    image = _render_pixels(window)
    if not _blank(window, image) or _background_drawn(window):
        return image
    samples = window.GetMultiSamples()
    if samples > 0:
        window.SetMultiSamples(0)
        image = _render_pixels(window)
    if samples == 0 or (_blank(window, image) and not _background_drawn(window)):
        raise RuntimeError("the OpenGL driver drew nothing into a picture of %d x %d pixels "
                           "(beyond its framebuffer's limits?)" % (width, height))
    if on_warning:
        on_warning("the OpenGL driver drew nothing with %d samples per pixel at %d x %d "
                   "(its multisampled framebuffer's limit); the picture is rendered "
                   "without antialiasing, as with --multisamples 0 (a smaller --size keeps "
                   "it)" % (samples, width, height))
    return image


def rgb_pixels(window, on_warning=None):
    """Render the window and return its pixels as a (height, width, 3) uint8 numpy array, row 0
    at the bottom (VTK's order); on_warning as for grab."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    image = grab(window, on_warning)
    width, height, _ = image.GetDimensions()
    return vtk_to_numpy(image.GetPointData().GetScalars()).reshape(height, width, 3)


def write_png(window, path, on_warning=None, text=()):
    """Render and write the window's pixels to a PNG; returns the absolute path. `text`: (key,
    value) pairs of str written as the PNG's tEXt chunks: keys of 1 to 79 printable Latin-1
    characters (no leading, trailing or double space), values of Latin-1 characters without
    NUL; TypeError or ValueError for others, before anything is drawn or written. The PNG is
    written aside and renamed into place, as the GeoTIFF and EXR writers do: a failed write
    leaves an earlier file of that name as it was; a file replaced keeps its permissions, and
    a symbolic link stays a link, its target written. OSError when the file cannot be
    written (a read-only file, a full disk); on_warning and RuntimeError as for grab."""
    from aperture.errors import native_path
    chunks = [_png_text_chunk(pair) for pair in text]
    folder = os.path.dirname(os.path.abspath(path))
    if os.path.isdir(path) or not os.path.isdir(folder):
        # (said before VTK's writer tries: it would print "Ran out of disk space")
        raise OSError("cannot write the PNG %s: %s" % (path, "it is a folder" if os.path.isdir(
            path) else "%s is not a folder" % folder if os.path.exists(folder) else
            "the folder %s does not exist" % folder))
    target = os.path.realpath(path)  # (through symbolic links: a link stays one)
    try:
        existing = os.stat(target)
    except OSError:
        existing = None  # (a new file)
    if existing is not None and not stat.S_ISREG(existing.st_mode):
        # (a pipe, a device: renamed over, /dev/null would have become a PNG, as root)
        raise OSError("cannot write the PNG %s: it is not a file" % path)
    if existing is not None and not os.access(target, os.W_OK):
        raise OSError("cannot write the PNG %s: it is read-only" % path)
    image = grab(window, on_warning)
    temporary = _temporary_beside(target, path)
    try:
        writer = vtkPNGWriter()
        writer.SetFileName(native_path(temporary))
        for key, value in chunks:
            writer.AddText(key, value)
        writer.SetInputData(image)
        # (VTK's own message, "Ran out of disk space", said in ours instead of printed)
        writer.AddObserver("ErrorEvent", lambda caller, event: None)
        writer.Write()
        if writer.GetErrorCode():
            # (VTK says no more than that a write failed: libpng's own lines say "Write Error")
            try:
                fs = os.statvfs(os.path.dirname(target))
                full = fs.f_bavail * fs.f_frsize < (1 << 20)
            except OSError:
                full = False
            raise OSError("cannot write the PNG %s: %s" % (
                path, "the disk is full" if full else "the write failed (out of space, or over "
                "a limit on file sizes)"))
        if existing is not None:
            os.chmod(temporary, stat.S_IMODE(existing.st_mode))
        os.replace(temporary, target)
    finally:
        if os.path.exists(temporary):
            os.remove(temporary)
    return os.path.abspath(path)


def _temporary_beside(target, path):
    """A new hidden file in the folder of `target` for writing it aside, made as open() makes
    a file (0666 less the umask, which mkstemp's 0600 is not); OSError naming `path`."""
    folder = os.path.dirname(target)
    for _ in range(100):
        name = os.path.join(folder, ".aperture-%d-%s.tmp" % (os.getpid(), os.urandom(4).hex()))
        try:
            os.close(os.open(name, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666))
            return name
        except FileExistsError:
            continue
        except OSError as e:
            raise OSError("cannot write the PNG %s: %s" % (path, e.strerror)) from None
    raise OSError("cannot write the PNG %s: no temporary file could be made beside it" % path)


def _png_text_chunk(pair):
    """A (key, value) pair of str as the Latin-1 bytes of a PNG tEXt chunk (the PNG
    specification's rules for keywords); TypeError or ValueError naming what is wrong."""
    try:
        key, value = pair
    except (TypeError, ValueError):
        raise TypeError("text must hold (key, value) pairs, not %r" % (pair,)) from None
    if not isinstance(key, str) or not isinstance(value, str):
        raise TypeError("a PNG text chunk's key and value must be str, not %r" % (pair,))
    try:
        k, v = key.encode("latin-1"), value.encode("latin-1")
    except UnicodeEncodeError:
        raise ValueError("a PNG text chunk holds Latin-1 characters only: %r" % (pair,)) from None
    if not (1 <= len(k) <= 79 and all(32 <= c <= 126 or c >= 161 for c in k)
            and key == key.strip(" ") and "  " not in key):
        raise ValueError("a PNG text chunk's key is 1 to 79 printable Latin-1 characters, "
                         "without leading, trailing or double spaces: %r" % key)
    if b"\0" in v:
        raise ValueError("a PNG text chunk's value holds no NUL character: %r" % value)
    return k, v
