// SPDX-License-Identifier: BSD-3-Clause
// Test helpers: write small rasters with GDAL's C API (independently of the reader under test),
// and check results with failure counting.
#ifndef ApertureTestRasters_h
#define ApertureTestRasters_h

#include "aptest.hxx"
#include "vtkType.h"

#include <cpl_string.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace aptest
{
/** What to put in a test raster. */
struct RasterSpec
{
  int nx = 4, ny = 3, bands = 1;
  GDALDataType type = GDT_Float32;
  bool hasGeoTransform = true;
  double gt[6] = { 500000.0, 30.0, 0.0, 4000000.0, 0.0, -30.0 };
  std::string crs = "EPSG:32611"; // empty: none
  bool hasNoData = false;
  double noData = -32768.0;
  double scale = 1.0, offset = 0.0;
  std::string unit;
  int gcps = 0; // > 0: add this many ground control points (and no geotransform)
  std::vector<std::string> options; // GTiff creation options, such as PIXELTYPE=SIGNEDBYTE
  // raw(band, column, row) with row 0 the file's first row
  std::function<double(int, int, int)> raw = [](int, int c, int r) { return 10.0 * r + c; };
};

/** Write a GeoTIFF following spec; returns false on any GDAL failure. */
inline bool WriteRaster(const std::string& path, const RasterSpec& s)
{
  GDALAllRegister();
  GDALDriverH drv = GDALGetDriverByName("GTiff");
  std::vector<const char*> options;
  for (const std::string& o : s.options)
  {
    options.push_back(o.c_str());
  }
  options.push_back(nullptr);
  GDALDatasetH ds = GDALCreate(drv, path.c_str(), s.nx, s.ny, s.bands, s.type,
    const_cast<char**>(options.data()));
  if (!ds)
  {
    return false;
  }
  bool ok = true;
  if (s.hasGeoTransform)
  {
    double gt[6];
    std::copy(s.gt, s.gt + 6, gt);
    ok = ok && GDALSetGeoTransform(ds, gt) == CE_None;
  }
  OGRSpatialReferenceH srs = nullptr;
  if (!s.crs.empty())
  {
    srs = OSRNewSpatialReference(nullptr);
    ok = ok && OSRSetFromUserInput(srs, s.crs.c_str()) == OGRERR_NONE;
    ok = ok && GDALSetSpatialRef(ds, srs) == CE_None;
  }
  if (s.gcps > 0)
  {
    GDAL_GCP gcps[4];
    GDALInitGCPs(4, gcps);
    const double px[4] = { 0, double(s.nx), 0, double(s.nx) };
    const double py[4] = { 0, 0, double(s.ny), double(s.ny) };
    for (int k = 0; k < 4 && k < s.gcps; ++k)
    {
      gcps[k].dfGCPPixel = px[k];
      gcps[k].dfGCPLine = py[k];
      gcps[k].dfGCPX = 10.0 + 0.01 * px[k] + 0.001 * py[k];
      gcps[k].dfGCPY = 45.0 - 0.01 * py[k];
    }
    ok = ok && GDALSetGCPs2(ds, s.gcps < 4 ? s.gcps : 4, gcps, srs) == CE_None;
    GDALDeinitGCPs(4, gcps);
  }
  if (srs)
  {
    OSRRelease(srs);
  }
  std::vector<double> row(static_cast<size_t>(s.nx));
  for (int b = 1; ok && b <= s.bands; ++b)
  {
    GDALRasterBandH band = GDALGetRasterBand(ds, b);
    if (s.hasNoData)
    {
      ok = ok && GDALSetRasterNoDataValue(band, s.noData) == CE_None;
    }
    if (s.scale != 1.0 || s.offset != 0.0)
    {
      ok = ok && GDALSetRasterScale(band, s.scale) == CE_None &&
        GDALSetRasterOffset(band, s.offset) == CE_None;
    }
    if (!s.unit.empty())
    {
      ok = ok && GDALSetRasterUnitType(band, s.unit.c_str()) == CE_None;
    }
    for (int r = 0; ok && r < s.ny; ++r)
    {
      for (int c = 0; c < s.nx; ++c)
      {
        row[static_cast<size_t>(c)] = s.raw(b, c, r);
      }
      ok = GDALRasterIO(band, GF_Write, 0, r, s.nx, 1, row.data(), s.nx, 1, GDT_Float64, 0, 0) ==
        CE_None;
    }
  }
  GDALClose(ds);
  return ok;
}

/** The folder after "-T" on the test's command line (VTK's test output directory). */
inline std::string TempDir(int argc, char* argv[])
{
  for (int k = 1; k + 1 < argc; ++k)
  {
    if (std::string(argv[k]) == "-T")
    {
      return argv[k + 1];
    }
  }
  return ".";
}

/** Write text to a file. */
inline bool WriteText(const std::string& path, const std::string& text)
{
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f)
  {
    return false;
  }
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  return std::fclose(f) == 0 && ok;
}
/** Samples of an nx-wide grid, row by row, that compress but not to nothing: the column index
 * plus noise in [0, 2^24 scale) from Numerical Recipes' LCG started at seed. */
inline std::vector<float> NoisyRamp(int nx, int ny, unsigned seed, float scale)
{
  std::vector<float> values(static_cast<size_t>(nx) * static_cast<size_t>(ny));
  unsigned state = seed;
  for (size_t k = 0; k < values.size(); ++k)
  {
    state = state * 1664525u + 1013904223u;
    values[k] = static_cast<float>(k % static_cast<size_t>(nx)) +
      static_cast<float>(state >> 8) * scale;
  }
  return values;
}

/** The whole content of a file ("" when it cannot be read): for byte-for-byte comparisons. */
inline std::string ReadFileBytes(const std::string& path)
{
  std::string bytes;
  if (FILE* f = std::fopen(path.c_str(), "rb"))
  {
    char buf[65536];
    size_t n;
    while ((n = std::fread(buf, 1, sizeof(buf), f)) > 0)
    {
      bytes.append(buf, n);
    }
    std::fclose(f);
  }
  return bytes;
}

/** Remove what SpecialFiles made (or an earlier run left). */
inline void RemoveSpecialFiles(const std::vector<std::pair<std::string, std::string>>& made)
{
  for (const auto& m : made)
  {
    if (unlink(m.first.c_str()) != 0)
    {
      rmdir(m.first.c_str());
    }
  }
}

/** Paths `dir`/`prefix`-... that name no regular file, as (path, kind), made here (anew): a
 *  pipe, a folder, and when run as root a null device (a copy of /dev/null's node, so that a
 *  writer that removed it would remove the copy). A writer must refuse each and leave it as it
 *  was (SameKind); RemoveSpecialFiles afterwards. */
inline std::vector<std::pair<std::string, std::string>> SpecialFiles(
  const std::string& dir, const std::string& prefix)
{
  const std::string base = dir + "/" + prefix;
  RemoveSpecialFiles({ { base + "-pipe", "" }, { base + "-folder", "" }, { base + "-null", "" } });
  std::vector<std::pair<std::string, std::string>> made;
  if (mkfifo((base + "-pipe").c_str(), 0644) == 0)
  {
    made.emplace_back(base + "-pipe", "a pipe");
  }
  if (mkdir((base + "-folder").c_str(), 0755) == 0)
  {
    made.emplace_back(base + "-folder", "a folder");
  }
  if (geteuid() == 0 && mknod((base + "-null").c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0)
  {
    made.emplace_back(base + "-null", "a device");
  }
  return made;
}

/** Whether `path` is still what SpecialFiles made as `kind`. */
inline bool SameKind(const std::string& path, const std::string& kind)
{
  struct stat st;
  if (stat(path.c_str(), &st) != 0)
  {
    return false;
  }
  return kind == "a pipe" ? S_ISFIFO(st.st_mode)
    : kind == "a folder"  ? S_ISDIR(st.st_mode)
                          : S_ISCHR(st.st_mode) && st.st_rdev == makedev(1, 3);
}

/** A writer's Add* and Clear* lists change its modification time only when they change the
 * list: a Clear of an empty list, as VTK's setters of an unchanged value, does not (a pipeline
 * would write again for nothing). */
template <typename Writer>
void CheckClearsModifyOnlyOnChange(Writer* w)
{
  vtkMTimeType m = w->GetMTime();
  w->ClearArrayNames();
  w->ClearMetadata();
  AP_CHECK(w->GetMTime() == m);
  w->AddArrayName("A");
  AP_CHECK(w->GetMTime() > m);
  m = w->GetMTime();
  w->ClearArrayNames();
  AP_CHECK(w->GetMTime() > m && w->GetNumberOfArrayNames() == 0);
  m = w->GetMTime();
  w->ClearArrayNames();
  AP_CHECK(w->GetMTime() == m);
  w->AddMetadata("key", "value");
  AP_CHECK(w->GetMTime() > m);
  m = w->GetMTime();
  w->ClearMetadata();
  AP_CHECK(w->GetMTime() > m);
  m = w->GetMTime();
  w->ClearMetadata();
  AP_CHECK(w->GetMTime() == m);
}

} // namespace aptest

#endif
