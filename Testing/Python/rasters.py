# SPDX-License-Identifier: BSD-3-Clause
"""Small rasters the command-line tests write."""
from osgeo import gdal, osr


def make_dem(path, z, gt, epsg):
    """A one-band float32 GeoTIFF of the elevations z (row 0 north) with geotransform gt in
    EPSG:epsg, nodata -9999; returns path."""
    ds = gdal.GetDriverByName("GTiff").Create(path, z.shape[1], z.shape[0], 1, gdal.GDT_Float32)
    ds.SetGeoTransform(gt)
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(epsg)
    ds.SetSpatialRef(srs)
    ds.GetRasterBand(1).WriteArray(z)
    ds.GetRasterBand(1).SetNoDataValue(-9999)
    ds = None
    return path
