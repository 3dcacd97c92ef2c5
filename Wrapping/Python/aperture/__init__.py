# SPDX-License-Identifier: BSD-3-Clause
"""Aperture: sun-and-sky lighting and visibility analysis for digital elevation models.

The VTK classes (vtkApertureDEMReader, vtkApertureTerrainMesh, ...) are importable from here:

    from aperture import vtkApertureDEMReader, vtkApertureTerrainMesh

`default_dem()` is the path of the embedded example DEM (Jacksboro fault, Tennessee, USGS
3 arc-second, EPSG:4326).
"""
import os as _os

from ._version import __version__  # noqa: F401
from .ApertureFilters import *  # noqa: F401,F403
from .ApertureIO import *  # noqa: F401,F403


# The Rendering module's classes are imported when first asked for (`aperture.vtkAperture...`,
# `from aperture import ...`, `from aperture import *`): that module and the OpenGL libraries
# it loads cost every command that does not render some 30 ms. (TestImport checks this list
# against the module.)
_RENDERING = ("vtkApertureLightingMapper", "vtkApertureLinearCapture")
__all__ = sorted([n for n in dir() if n.startswith("vtk")] + list(_RENDERING)) + ["default_dem"]


def __getattr__(name):
    if name in _RENDERING:
        from . import ApertureRendering
        return getattr(ApertureRendering, name)
    raise AttributeError("module %r has no attribute %r" % (__name__, name))


def __dir__():
    return sorted(set(globals()) | set(_RENDERING))


def default_dem():
    """Path of the embedded default DEM GeoTIFF (built with the package); FileNotFoundError
    when the build had no python-matplotlib-data to make it from."""
    path = _os.path.join(_os.path.dirname(_os.path.abspath(__file__)), "data",
                         "jacksboro_fault_dem.tif")
    if not _os.path.exists(path):
        raise FileNotFoundError(
            "the embedded default DEM is missing (%s); it is built from Debian's "
            "python-matplotlib-data package, which was not installed at build time" % path)
    return path
