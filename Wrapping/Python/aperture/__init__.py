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
from .ApertureRendering import *  # noqa: F401,F403


def default_dem():
    """Path of the embedded default DEM GeoTIFF (built with the package)."""
    path = _os.path.join(_os.path.dirname(_os.path.abspath(__file__)), "data",
                         "jacksboro_fault_dem.tif")
    if not _os.path.exists(path):
        raise FileNotFoundError(
            "the embedded default DEM is missing (%s); it is built from Debian's "
            "python-matplotlib-data package, which was not installed at build time" % path)
    return path
