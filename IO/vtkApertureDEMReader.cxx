// SPDX-License-Identifier: BSD-3-Clause
#include "vtkApertureDEMReader.h"

#include "vtkApertureGDALErrorTrap.h"
#include "vtkApertureGeoreference.h"
#include "vtkApertureMemory.h"
#include "vtkApertureOutputFile.h"
#include "vtkApertureEmptyOutput.h"

#include "vtkDataObject.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "ap_grid.h"

#include <cpl_conv.h>
#include <cpl_string.h>
#include <cpl_vsi.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <new>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkApertureDEMReader);

namespace
{
// Owns a GDAL dataset handle.
struct DatasetHandle
{
  GDALDatasetH H = nullptr;
  DatasetHandle() = default;
  DatasetHandle(const DatasetHandle&) = delete;
  DatasetHandle& operator=(const DatasetHandle&) = delete;
  ~DatasetHandle()
  {
    if (this->H)
    {
      GDALClose(this->H);
    }
  }
};

// Metres per unit of a band's vertical unit string; 0 when unknown.
double MetresPerUnit(const char* unitType)
{
  std::string u(unitType ? unitType : "");
  std::transform(u.begin(), u.end(), u.begin(), [](unsigned char c) { return std::tolower(c); });
  if (u == "m" || u == "metre" || u == "meter" || u == "metres" || u == "meters")
  {
    return 1.0;
  }
  // the metre's multiples that DEMs of integers use (centimetres, decimetres) and their kin
  const struct
  {
    const char* Symbol;
    const char* Prefix;
    double Metres;
  } multiples[] = { { "mm", "milli", 1e-3 }, { "cm", "centi", 1e-2 }, { "dm", "deci", 1e-1 },
    { "km", "kilo", 1e3 } };
  for (const auto& m : multiples)
  {
    const std::string p(m.Prefix);
    if (u == m.Symbol || u == p + "metre" || u == p + "meter" || u == p + "metres" ||
      u == p + "meters")
    {
      return m.Metres;
    }
  }
  if (u == "ft" || u == "foot" || u == "feet" || u == "international foot" ||
    u == "ft (international)")
  {
    return 0.3048;
  }
  if (u == "us survey foot" || u == "us-ft" || u == "ftus" || u == "us_survey_foot" ||
    u == "foot_us" || u == "us survey feet")
  {
    return 1200.0 / 3937.0;
  }
  return 0.0;
}

// Whether a file begins with OpenEXR's magic number (0x762f3101, little-endian).
bool IsOpenEXR(const char* fileName)
{
  unsigned char magic[4] = { 0, 0, 0, 0 };
  FILE* f = std::fopen(fileName, "rb");
  if (!f)
  {
    return false;
  }
  const size_t got = std::fread(magic, 1, 4, f);
  std::fclose(f);
  return got == 4 && magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 && magic[3] == 0x01;
}

// Why a window (x offset, y offset, columns, rows; 0 columns or rows: to the edge) of full-
// resolution pixels is not inside a raster of `size`, or "" when it is.
std::string WindowProblem(const char* what, const int w[4], const int size[2])
{
  if (w[0] < 0 || w[1] < 0 || w[2] < 0 || w[3] < 0 || w[0] >= size[0] || w[1] >= size[1] ||
    w[0] + static_cast<vtkTypeInt64>(w[2]) > size[0] ||
    w[1] + static_cast<vtkTypeInt64>(w[3]) > size[1])
  {
    std::ostringstream s;
    s << what << " (" << w[0] << ", " << w[1] << ", " << w[2] << ", " << w[3]
      << ") is not inside the " << size[0] << " x " << size[1] << " raster";
    return s.str();
  }
  return std::string();
}

// The pixels [first, first + count) of a level of `level` pixels that cover the pixels
// [w, w + size) (size 0: to the edge) of the full resolution's `full` (along one axis).
void LevelSpan(int w, int size, int full, int level, int& first, int& count)
{
  const double scale = static_cast<double>(full) / level;
  const int end = size ? w + size : full;
  first = static_cast<int>(std::floor(w / scale));
  count = std::min(level, static_cast<int>(std::ceil(end / scale))) - first;
}

// The decimation factors nearest `f` that divide `n`, within lowest..highest, as the
// decimation warnings name them: "4 or 6", "4", "6", or "" when none is.
std::string NearestDivisors(int n, int f, int lowest, int highest)
{
  int below = f - 1, above = f + 1;
  while (below >= lowest && n % below)
  {
    --below;
  }
  while (above <= highest && n % above)
  {
    ++above;
  }
  const bool hasBelow = below >= lowest, hasAbove = above <= highest;
  return (hasBelow ? std::to_string(below) : std::string()) +
    (hasBelow && hasAbove ? " or " : "") + (hasAbove ? std::to_string(above) : std::string());
}
} // namespace

// What RequestInformation resolved from the file and the options; RequestData reuses it.
struct vtkApertureDEMReader::Internals
{
  std::string Driver;
  std::vector<std::string> Files; // GDALGetFileList's, once asked for
  bool FilesListed = false;
  int Band = 1;
  int Level = -1;               // -1: full resolution, else overview index
  int Window[4] = { 0, 0, 0, 0 }; // x0, y0, columns, rows in pixels of the level
  int LevelSize[2] = { 0, 0 };  // columns, rows of the level read
  int Block[2] = { 0, 0 };      // columns, rows of the level's blocks (BlockBytes: their bytes)
  int Factor = 1;               // decimation
  int Out[2] = { 0, 0 };        // output columns, rows
  bool SouthUp = false;         // the file's first row is its southern row
  double Origin[2] = { 0, 0 };  // CRS coordinates of the south-west output cell centre
  double Spacing[2] = { 1, 1 }; // output cell size, CRS units
  std::string CRS;              // WKT
  bool HasNoData = false;
  double NoData = 0.0;
  bool NoDataNear = false; // float bands: ap_sample_params.nodata_near
  double Scale = 1.0, Offset = 0.0; // includes the unit conversion to metres
  double FileScale = 1.0, FileOffset = 0.0; // the band's own (for messages)
  bool SignedByte = false;          // GDAL 3.6's Int8: a Byte band of PIXELTYPE=SIGNEDBYTE
  std::string UnitSource;           // where the elevation unit came from (for messages)
  bool UseMask = false;
  bool Valid = false;
  int Reading[2] = { 0, 0 }; // columns, rows of the request being read (for messages)

  // The files a GDAL name that is no file names (between colons, the rest after each colon,
  // and between quotes: a path may hold colons): `any` whether one exists; false, with
  // `error`, where one is a pipe or a socket (GDAL's open of one would wait for a writer).
  static bool NamedFiles(const std::string& name, bool& any, std::string& error)
  {
    std::vector<std::string> parts;
    for (size_t a = 0; a <= name.size();)
    {
      const size_t colon = name.find(':', a);
      const size_t b = colon == std::string::npos ? name.size() : colon;
      parts.push_back(name.substr(a, b - a));
      parts.push_back(name.substr(a));
      a = b + 1;
    }
    for (size_t q = name.find('"'); q != std::string::npos;)
    {
      const size_t end = name.find('"', q + 1);
      if (end == std::string::npos)
      {
        break;
      }
      parts.push_back(name.substr(q + 1, end - q - 1));
      q = name.find('"', end + 1);
    }
    any = false;
    for (const std::string& part : parts)
    {
      struct stat ps = {};
      if (!part.empty() && stat(part.c_str(), &ps) == 0)
      {
        any = true;
        if (vtkApertureUnreadableStream(ps))
        {
          error = "'" + name + "' names " + vtkApertureFileKind(ps) + " ('" + part +
            "'), not a file: GDAL reads a DEM by seeking in it; save it to a file first";
          return false;
        }
      }
    }
    return true;
  }

  // Open the file with a clear message on failure; *warning (when given) gets GDAL's last
  // warning while opening, if any (a GeoTIFF's unreadable keys, for instance).
  static bool Open(
    const char* fileName, DatasetHandle& ds, std::string& error, std::string* warning = nullptr)
  {
    if (!fileName || !*fileName)
    {
      error = "no file name was set";
      return false;
    }
    const std::string name(fileName);
    const bool virtualPath = name.compare(0, 4, "/vsi") == 0; // (GDAL's own: /vsizip/, ...)
    struct stat sb = {};
    // A name of GDAL's own that is no file: a subdataset (NETCDF:"f.nc":z, GTIFF_DIR:2:f.tif,
    // HDF5:...), refused as a missing file until 2026-12-07; opened below like a file, the
    // files it names checked first (namesFile: one exists, so GDAL's reason if it fails).
    bool gdalName = false, namesFile = false;
    int statErrno = 0;
    if (!virtualPath && stat(fileName, &sb) != 0)
    {
      const size_t scheme = name.find("://");
      if (scheme != std::string::npos && scheme > 0 &&
        name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789+.-") == scheme)
      {
        // (a URL: GDAL reads it through its network file systems, not as a name)
        error = "'" + name + "' is a URL, not a file: GDAL reads one through /vsicurl/ ('" +
          "/vsicurl/" + name + "'), where this machine can reach it";
        return false;
      }
      gdalName = name.find(':') != std::string::npos;
      if (!gdalName)
      {
        error = vtkApertureMissingFileMessage(name);
        return false;
      }
      statErrno = errno;
      if (!NamedFiles(name, namesFile, error))
      {
        return false;
      }
    }
    if (!virtualPath && !gdalName && vtkApertureUnreadableStream(sb))
    {
      // (GDAL also opens a file more than once: one writer to a pipe would not do)
      error = "'" + name + "' is " + vtkApertureFileKind(sb) +
        ", not a file: GDAL reads a DEM by seeking in it; save the DEM to a file first";
      return false;
    }
    GDALAllRegister();
    vtkApertureGDALErrorTrap trap;
    ds.H = GDALOpenEx(fileName, GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
    if (!ds.H)
    {
      VSIStatBufL vsb;
      if (virtualPath && VSIStatL(fileName, &vsb) != 0)
      {
        // (said once GDAL has tried; over the network it may also not be reachable)
        bool network = false;
        for (const char* prefix :
          { "/vsicurl/", "/vsis3/", "/vsigs/", "/vsiaz/", "/vsiadls/", "/vsiswift/", "/vsioss/" })
        {
          network = network || name.rfind(prefix, 0) == 0;
        }
        const std::string why = trap.Message("");
        error = network ? "nothing can be read at '" + name +
            "' (no such file there, or the server cannot be reached from this machine" +
            (why.empty() ? std::string() : ": " + why) + ")"
                        : "file '" + name + "' does not exist";
        return false;
      }
      if (gdalName && !namesFile)
      {
        errno = statErrno; // (no file of that name, nor one it names)
        error = vtkApertureMissingFileMessage(name);
        return false;
      }
      // (a file without read permission was "not a raster format GDAL recognises")
      const std::string unreadable =
        virtualPath || gdalName ? "" : vtkApertureUnreadableReason(fileName);
      if (!unreadable.empty())
      {
        error = "cannot read '" + name + "': " + unreadable;
        return false;
      }
      error = "GDAL cannot open '" + name + "' as a raster: " +
        trap.Message("not a raster format GDAL recognises");
      if (!virtualPath && S_ISDIR(sb.st_mode))
      {
        error += " (it is a folder, and not one GDAL reads as a raster, such as an ArcInfo "
                 "grid's)";
      }
      if (IsOpenEXR(fileName))
      {
        // (as `aperture bake --exr` writes them; Debian's GDAL has no EXR driver)
        error += " (it is an OpenEXR file, which this GDAL does not read: the products of "
                 "'aperture bake --exr' are read by vtkApertureEXRReader; bake from the DEM "
                 "or its GeoTIFF)";
      }
      return false;
    }
    if (warning)
    {
      *warning = trap.Message();
    }
    return true;
  }
};

//------------------------------------------------------------------------------
vtkApertureDEMReader::vtkApertureDEMReader()
  : FileName(nullptr)
  , BandIndex(0)
  , OverviewLevel(-1)
  , Decimation(1)
  , PartialBlockWarning(true)
  , OverrideCRS(nullptr)
  , MemoryLimit(0)
  , MetresPerElevationUnit(0.0)
  , NumberOfBands(0)
  , BandRead(0)
  , HasNoDataValue(false)
  , NoDataValue(0.0)
  , SouthUp(false)
  , ElevationUnitRead(0.0)
  , Impl(new Internals)
{
  this->SetNumberOfInputPorts(0);
  this->SubWindow[0] = this->SubWindow[1] = this->SubWindow[2] = this->SubWindow[3] = 0;
  this->RasterSize[0] = this->RasterSize[1] = 0;
}

//------------------------------------------------------------------------------
vtkApertureDEMReader::~vtkApertureDEMReader()
{
  this->SetFileName(nullptr);
  this->SetOverrideCRS(nullptr);
  delete this->Impl;
}

//------------------------------------------------------------------------------
const char* vtkApertureDEMReader::GetDriverName()
{
  return this->Impl->Driver.c_str();
}

//------------------------------------------------------------------------------
int vtkApertureDEMReader::GetNumberOfFiles()
{
  Internals& d = *this->Impl;
  if (!d.FilesListed && !d.Driver.empty())
  {
    // Listed when asked, not on every update: GDAL looks up each source of a VRT (over the
    // network for /vsicurl/ ones).
    d.FilesListed = true;
    std::string error;
    DatasetHandle ds;
    if (Internals::Open(this->FileName, ds, error))
    {
      vtkApertureGDALErrorTrap trap;
      if (char** files = GDALGetFileList(ds.H))
      {
        for (char** f = files; *f; ++f)
        {
          d.Files.emplace_back(*f);
        }
        CSLDestroy(files);
      }
    }
  }
  return static_cast<int>(d.Files.size());
}

//------------------------------------------------------------------------------
const char* vtkApertureDEMReader::GetFile(int index)
{
  this->GetNumberOfFiles();
  const std::vector<std::string>& files = this->Impl->Files;
  return index >= 0 && static_cast<size_t>(index) < files.size() ? files[index].c_str()
                                                                 : nullptr;
}

//------------------------------------------------------------------------------
const char* vtkApertureDEMReader::GetElevationUnitSource()
{
  return this->Impl->UnitSource.c_str();
}

//------------------------------------------------------------------------------
double vtkApertureDEMReader::GetMetresPerUnit(const char* name)
{
  return MetresPerUnit(name);
}

//------------------------------------------------------------------------------
int vtkApertureDEMReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  return vtkApertureEmptyOutputUnless(this->ReadInformation(outputVector), outputVector);
}

//------------------------------------------------------------------------------
int vtkApertureDEMReader::ReadInformation(vtkInformationVector* outputVector)
{
  Internals& d = *this->Impl;
  d.Valid = false;
  d.UnitSource.clear();
  // (the facts of a file that fails to open are not the previous file's)
  d.Driver.clear();
  d.Files.clear();
  d.FilesListed = false;
  this->ElevationUnitRead = 0.0;
  this->RasterSize[0] = this->RasterSize[1] = 0;
  this->NumberOfBands = this->BandRead = 0;
  this->HasNoDataValue = false;
  this->NoDataValue = 0.0;
  this->SouthUp = false;
  this->BlockBytes = 0.0;
  std::string error, openWarning;
  DatasetHandle ds;
  if (!Internals::Open(this->FileName, ds, error, &openWarning))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  const std::string name(this->FileName);
  d.Driver = GDALGetDriverShortName(GDALGetDatasetDriver(ds.H));
  this->RasterSize[0] = GDALGetRasterXSize(ds.H);
  this->RasterSize[1] = GDALGetRasterYSize(ds.H);
  this->NumberOfBands = GDALGetRasterCount(ds.H);

  // Band.
  if (this->NumberOfBands < 1)
  {
    // (a container of several grids, a netCDF or HDF file: each is read by its own name)
    char** subdatasets = GDALGetMetadata(ds.H, "SUBDATASETS");
    std::ostringstream names;
    int count = 0;
    for (int k = 1; subdatasets; ++k)
    {
      const char* sub =
        CSLFetchNameValue(subdatasets, ("SUBDATASET_" + std::to_string(k) + "_NAME").c_str());
      if (!sub)
      {
        break;
      }
      if (++count <= 4)
      {
        names << (count > 1 ? ", " : "") << sub;
      }
    }
    if (count > 4)
    {
      names << ", ...";
    }
    vtkErrorMacro(<< "'" << name << "' has no raster bands"
                  << (count ? "; it holds " + std::to_string(count) + " subdataset" +
                        (count > 1 ? "s" : "") + ", each read by its name: " + names.str()
                            : std::string()));
    return 0;
  }
  d.Band = this->BandIndex == 0 ? 1 : this->BandIndex;
  if (d.Band > this->NumberOfBands)
  {
    vtkErrorMacro(<< "'" << name << "' has " << this->NumberOfBands << " band"
                  << (this->NumberOfBands == 1 ? "" : "s") << "; band " << d.Band
                  << " does not exist");
    return 0;
  }
  GDALRasterBandH base = GDALGetRasterBand(ds.H, d.Band);
  // An alpha band (gdalwarp -dstalpha) is GDAL's mask of the others where it is the last of 2
  // bands, or of 4 for the first 3, with Byte or UInt16 samples, and the band read has no
  // nodata value (which wins) nor a mask of its own: no band to choose then. Otherwise, with
  // nothing else to mask the band, the cells it makes transparent (a warp's collar: 0 m) were
  // read as heights with only "2 bands; reading band 1" said, until 2026-12-07: said why.
  int alpha = 0; // (the last alpha band, where GDAL looks for one)
  for (int b = this->NumberOfBands; b >= 1 && !alpha; --b)
  {
    alpha = GDALGetRasterColorInterpretation(GDALGetRasterBand(ds.H, b)) == GCI_AlphaBand ? b : 0;
  }
  const int maskFlags = GDALGetMaskFlags(base);
  std::ostringstream bands;
  if (this->BandIndex == 0 && this->NumberOfBands > 1 &&
    !(alpha == 2 && this->NumberOfBands == 2))
  {
    bands << "'" << name << "' has " << this->NumberOfBands
          << " bands; reading band 1 as elevation (set BandIndex to choose)";
  }
  const bool placed = alpha == this->NumberOfBands &&
    (this->NumberOfBands == 2 || (this->NumberOfBands == 4 && d.Band <= 3));
  const GDALDataType alphaType =
    alpha ? GDALGetRasterDataType(GDALGetRasterBand(ds.H, alpha)) : GDT_Unknown;
  const bool typed = alphaType == GDT_Byte || alphaType == GDT_UInt16;
  if (alpha && alpha != d.Band && maskFlags == GMF_ALL_VALID && !(placed && typed))
  {
    std::string why = placed ? "" : " as the last of 2 bands, or of 4 for the first 3";
    if (!typed)
    {
      why += std::string(placed ? "" : ",") + " with Byte or UInt16 samples, not " +
        GDALGetDataTypeName(alphaType);
    }
    bands << (bands.tellp() > 0 ? "; its" : "'" + name + "'") << " band " << alpha
          << " is an alpha band, which GDAL takes as a mask only" << why
          << ": the cells it makes transparent are read as heights; give the DEM a nodata value "
          << "instead (gdalwarp -dstnodata nan)";
  }
  if (bands.tellp() > 0)
  {
    vtkWarningMacro(<< bands.str());
  }
  this->BandRead = d.Band;
  const GDALDataType type = GDALGetRasterDataType(base);
  if (GDALDataTypeIsComplex(type))
  {
    // GDAL would hand over the real parts alone.
    vtkErrorMacro(<< "'" << name << "' band " << d.Band << " holds complex numbers ("
                  << GDALGetDataTypeName(type) << "), not elevations");
    return 0;
  }
  // A band of colour indices (a palette: a land-cover map, a scanned map) or a picture's
  // channel is read all the same, but said: its values are not heights.
  const GDALColorInterp interp = GDALGetRasterColorInterpretation(base);
  if (interp == GCI_PaletteIndex || GDALGetRasterColorTable(base))
  {
    vtkWarningMacro(<< "'" << name << "' band " << d.Band << " has a colour table: its values "
                    << "are colour or class indices, not elevations; read as heights all the "
                    << "same");
  }
  else if (interp != GCI_Undefined && interp != GCI_GrayIndex)
  {
    vtkWarningMacro(<< "'" << name << "' band " << d.Band << " is the "
                    << GDALGetColorInterpretationName(interp) << " channel of a picture, not "
                    << "elevations; read as heights all the same");
  }
  // (GDAL 3.6 has no Int8 type: such a band is Byte with this flag, and reads as 0..255)
  const char* pixelType = GDALGetMetadataItem(base, "PIXELTYPE", "IMAGE_STRUCTURE");
  d.SignedByte = type == GDT_Byte && pixelType && EQUAL(pixelType, "SIGNEDBYTE");

  // Georeference: a north-up or south-up geotransform and a CRS. (A damaged GeoTIFF's
  // unreadable keys are a GDAL warning while it opens or its georeference loads: named in the
  // no-CRS error below.)
  vtkApertureGDALErrorTrap trap;
  double gt[6];
  if (GDALGetGeoTransform(ds.H, gt) != CE_None)
  {
    const int gcps = GDALGetGCPCount(ds.H);
    if (gcps >= 3)
    {
      vtkErrorMacro(<< "'" << name << "' is georeferenced only by " << gcps
                    << " ground control points; warp it to a grid first (gdalwarp)");
    }
    else if (gcps > 0)
    {
      // (what GDAL reads from a GeoTIFF tie point without a pixel size, as a geotransform
      // with a pixel size of 0 is written; too few for gdalwarp, which needs 3)
      vtkErrorMacro(<< "'" << name << "' is georeferenced only by " << gcps
                    << " ground control point" << (gcps == 1 ? "" : "s")
                    << ", too few to place a grid; set its corners first (gdal_edit.py -a_ullr)");
    }
    else
    {
      // (a heightmap from a picture or a game engine: gdal_translate writes a GeoTIFF of it
      // with a grid, where gdal_edit.py cannot update a PNG)
      vtkErrorMacro(<< "'" << name << "' has no georeference (no geotransform); give it a "
                    << "grid first (gdal_translate -a_ullr ULX ULY LRX LRY, with -a_srs CRS, "
                    << "to a GeoTIFF)");
    }
    return 0;
  }
  // (first: a NaN pixel size made every test below true, and was called a rotation)
  if (!std::isfinite(gt[1]) || !std::isfinite(gt[5]) || !std::isfinite(gt[2]) ||
    !std::isfinite(gt[4]))
  {
    vtkErrorMacro(<< "'" << name << "' has a geotransform whose pixel size is not a finite "
                  << "number (width " << gt[1] << ", height " << gt[5] << ", rotation terms "
                  << gt[2] << ", " << gt[4] << "); set its corners first (gdal_edit.py -a_ullr)");
    return 0;
  }
  // Rotation terms that move the grid's far edges by under a thousandth of a cell are a
  // writer's rounding (1e-15 on a grid of 0.0008 degree cells was refused until 2026-12-06),
  // read as north-up; the outputs' geotransforms have none.
  if (!(std::fabs(gt[2]) * this->RasterSize[1] <= 1e-3 * std::fabs(gt[1])) ||
    !(std::fabs(gt[4]) * this->RasterSize[0] <= 1e-3 * std::fabs(gt[5])))
  {
    vtkErrorMacro(<< "'" << name << "' has a rotated geotransform (rotation terms " << gt[2]
                  << ", " << gt[4] << "); warp it north-up first (gdalwarp)");
    return 0;
  }
  if (gt[1] == 0 || gt[5] == 0)
  {
    vtkErrorMacro(<< "'" << name << "' has a pixel size of 0 in its geotransform (width " << gt[1]
                  << ", height " << gt[5] << "); set its corners first (gdal_edit.py -a_ullr)");
    return 0;
  }
  if (!std::isfinite(gt[0]) || !std::isfinite(gt[3]))
  {
    // (was "an unsupported geotransform (pixel width 30, ...)": the size was not the problem)
    vtkErrorMacro(<< "'" << name << "' has a geotransform whose origin is not finite ("
                  << gt[0] << ", " << gt[3]
                  << "); set its corners first (gdal_edit.py -a_ullr)");
    return 0;
  }
  if (!(gt[1] > 0))
  {
    vtkErrorMacro(<< "'" << name << "' has an unsupported geotransform (pixel width " << gt[1]
                  << ", pixel height " << gt[5] << "); warp it north-up first (gdalwarp)");
    return 0;
  }
  const double farX = gt[0] + this->RasterSize[0] * gt[1];
  const double farY = gt[3] + this->RasterSize[1] * gt[5];
  if (!std::isfinite(farX) || !std::isfinite(farY))
  {
    vtkErrorMacro(<< "'" << name << "' has a geotransform (origin " << gt[0] << ", " << gt[3]
                  << ", pixel size " << gt[1] << " x " << gt[5]
                  << ") whose grid reaches beyond the range of numbers; set its corners first "
                     "(gdal_edit.py -a_ullr)");
    return 0;
  }
  d.SouthUp = gt[5] > 0;
  this->SouthUp = d.SouthUp;

  vtkNew<vtkApertureGeoreference> geo;
  if (this->OverrideCRS && *this->OverrideCRS)
  {
    if (!geo->SetCRS(this->OverrideCRS))
    {
      vtkErrorMacro(<< "OverrideCRS: " << geo->GetErrorMessage());
      return 0;
    }
  }
  else
  {
    OGRSpatialReferenceH srs = GDALGetSpatialRef(ds.H);
    char* wkt = nullptr;
    const char* options[] = { "FORMAT=WKT2_2019", "MULTILINE=NO", nullptr };
    if (!srs || OSRExportToWktEx(srs, &wkt, options) != OGRERR_NONE || !wkt || !*wkt)
    {
      CPLFree(wkt);
      const std::string why = trap.Message(openWarning.c_str());
      vtkErrorMacro(<< "'" << name << "' has no coordinate reference system"
                    << (why.empty() ? std::string()
                                    : " (GDAL: " + why + "; is the file damaged?)")
                    << "; set OverrideCRS (aperture: --srs EPSG:xxxx; a site grid with no "
                       "place on the Earth: --srs 'LOCAL_CS[\"grid\",UNIT[\"metre\",1]]')");
      return 0;
    }
    const bool ok = geo->SetCRS(wkt);
    CPLFree(wkt);
    if (!ok)
    {
      vtkErrorMacro(<< "'" << name << "': " << geo->GetErrorMessage());
      return 0;
    }
  }
  d.CRS = geo->GetCRS();

  // Resolution level and window.
  GDALRasterBandH level = base;
  d.Level = this->OverviewLevel;
  if (d.Level >= 0)
  {
    const int count = GDALGetOverviewCount(base);
    if (d.Level >= count)
    {
      vtkErrorMacro(<< "'" << name << "' band " << d.Band << " has " << count
                    << " overview levels; level " << d.Level << " does not exist");
      return 0;
    }
    level = GDALGetOverview(base, d.Level);
  }
  GDALGetBlockSize(level, &d.Block[0], &d.Block[1]);
  this->BlockBytes = static_cast<double>(d.Block[0]) * d.Block[1] *
    GDALGetDataTypeSizeBytes(GDALGetRasterDataType(level));
  const int levelX = GDALGetRasterBandXSize(level), levelY = GDALGetRasterBandYSize(level);
  const double sx = static_cast<double>(this->RasterSize[0]) / levelX;
  const double sy = static_cast<double>(this->RasterSize[1]) / levelY;
  const int* w = this->SubWindow;
  const std::string outside = WindowProblem("SubWindow", w, this->RasterSize);
  if (!outside.empty())
  {
    vtkErrorMacro(<< outside);
    return 0;
  }
  // Window in level pixels: the level pixels that cover the full-resolution window.
  LevelSpan(w[0], w[2], this->RasterSize[0], levelX, d.Window[0], d.Window[2]);
  LevelSpan(w[1], w[3], this->RasterSize[1], levelY, d.Window[1], d.Window[3]);
  d.LevelSize[0] = levelX;
  d.LevelSize[1] = levelY;
  d.Factor = this->Decimation;
  // Decimation's blocks align to the level's top-left corner, not the window's, so that every
  // window of a raster reads cells of one grid: the window grows to the blocks it touches, less
  // a partial block at the level's east or south edge.
  vtkTypeInt64 lost[2] = { 0, 0 }; // the window's columns and rows in such a partial block
  for (int a = 0; a < 2; ++a)
  {
    const vtkTypeInt64 f = d.Factor, size = a ? levelY : levelX;
    const vtkTypeInt64 reach = d.Window[a] + d.Window[a + 2], kept = size / f * f;
    lost[a] = reach > kept ? reach - std::max<vtkTypeInt64>(kept, d.Window[a]) : 0;
    const vtkTypeInt64 first = d.Window[a] / f;
    const vtkTypeInt64 end = std::min((d.Window[a] + d.Window[a + 2] + f - 1) / f, size / f);
    d.Window[a] = static_cast<int>(first * f);
    d.Window[a + 2] = static_cast<int>(std::max<vtkTypeInt64>(0, end - first) * f);
  }
  d.Out[0] = d.Window[2] / d.Factor;
  d.Out[1] = d.Window[3] / d.Factor;
  if (d.Out[0] < 2 || d.Out[1] < 2)
  {
    // (the steps taken named, only those: a 1 x 1 raster read whole was "a 1 x 1 grid (after
    // subwindow, overview and decimation)")
    std::vector<std::string> steps;
    if (w[0] || w[1] || w[2] || w[3])
    {
      steps.emplace_back("subwindow");
    }
    if (d.Level >= 0)
    {
      steps.emplace_back("overview");
    }
    if (d.Factor > 1)
    {
      steps.emplace_back("decimation");
    }
    std::string after;
    for (size_t k = 0; k < steps.size(); ++k)
    {
      after += (k == 0 ? " (after " : k + 1 == steps.size() ? " and " : ", ") + steps[k];
    }
    vtkErrorMacro(<< "'" << name << "' " << (steps.empty() ? "is a " : "gives a ") << d.Out[0]
                  << " x " << d.Out[1] << (steps.empty() ? " raster" : " grid" + after + ")")
                  << "; at least 2 x 2 cells are needed");
    return 0;
  }

  // Output grid geometry (pixel-is-area: geotransforms give cell edges).
  const double levelDx = gt[1] * sx, levelDy = gt[5] * sy; // levelDy < 0 for north-up
  d.Spacing[0] = d.Factor * levelDx;
  d.Spacing[1] = d.Factor * std::fabs(levelDy);
  const double west = gt[0] + d.Window[0] * levelDx;
  const double firstRowEdge = gt[3] + d.Window[1] * levelDy;
  const double south =
    d.SouthUp ? firstRowEdge : firstRowEdge + static_cast<double>(d.Out[1]) * d.Factor * levelDy;
  d.Origin[0] = west + 0.5 * d.Spacing[0];
  d.Origin[1] = south + 0.5 * d.Spacing[1];
  const int dropped = levelX % d.Factor;
  bool told = false;
  if (dropped && d.Window[0] == 0 && d.Window[2] == levelX - dropped)
  {
    // A global DEM's east and west edges join (vtkApertureGeoreference::WrapsAround); a
    // partial block dropped at its east edge leaves a grid that no longer spans 360 degrees.
    geo->SetGrid(gt[0] + 0.5 * levelDx, 0.0, levelDx, 1.0, levelX, 2);
    if (geo->WrapsAround())
    {
      // (1 divides any: a factor below is always named)
      vtkWarningMacro(<< "'" << name << "' spans 360 degrees of longitude, but decimation by "
                      << d.Factor << " drops its last " << dropped << " of " << levelX
                      << " columns (a partial block): the grid read does not, so its east and "
                         "west edges do not join; a factor dividing "
                      << levelX << " keeps them joined ("
                      << NearestDivisors(levelX, d.Factor, 1, levelX - 1) << ")");
      told = true;
    }
  }
  if (this->PartialBlockWarning && (lost[0] || lost[1]))
  {
    // (dropped silently until 2026-12-06: cells with data at the edge a user asked for)
    std::ostringstream what;
    if (lost[0] && !told) // (a global DEM's columns are said above)
    {
      what << "its last " << (lost[0] == 1 ? "column" : std::to_string(lost[0]) + " columns")
           << " (east)";
    }
    if (lost[1])
    {
      what << (what.tellp() > 0 ? " and " : "") << "its last "
           << (lost[1] == 1 ? "row" : std::to_string(lost[1]) + " rows")
           << (d.SouthUp ? " (north)" : " (south)");
    }
    // the factors nearest that keep every cell: those dividing the sizes of the axes with
    // cells left out (at most half of each, for 2 x 2 cells)
    const int g = std::gcd(lost[0] ? levelX : 0, lost[1] ? levelY : 0);
    const int most = std::min(
      { g, lost[0] ? levelX / 2 : VTK_INT_MAX, lost[1] ? levelY / 2 : VTK_INT_MAX });
    const std::string sizes = lost[0] && lost[1]
      ? std::to_string(levelX) + " and " + std::to_string(levelY)
      : std::to_string(g);
    const std::string factors = NearestDivisors(g, d.Factor, 2, most);
    if (what.tellp() > 0)
    {
      vtkWarningMacro(<< "'" << name << "': decimation by " << d.Factor << " leaves out "
                      << what.str() << (d.Level >= 0 ? " of the overview" : "") << ", partial "
                      << d.Factor << " x " << d.Factor << " blocks"
                      << (factors.empty() ? " (no factor above 1 divides " + sizes + ")"
                                          : "; a factor dividing " + sizes +
                              " keeps every cell (" + factors + ")"));
    }
  }

  // Sample conversion: nodata, scale/offset and vertical unit, from the base band.
  int has = 0;
  const double scale = GDALGetRasterScale(base, &has);
  d.Scale = has ? scale : 1.0;
  const double offset = GDALGetRasterOffset(base, &has);
  d.Offset = has ? offset : 0.0;
  if (!std::isfinite(d.Scale) || d.Scale == 0.0 || !std::isfinite(d.Offset))
  {
    vtkErrorMacro(<< "'" << name << "' band " << d.Band << " has a scale of " << d.Scale
                  << " and an offset of " << d.Offset << ": elevations (samples x scale + "
                  << "offset) would be "
                  << (d.Scale == 0.0 && std::isfinite(d.Offset) ? "the offset everywhere"
                                                                : "no numbers")
                  << "; correct them (gdal_edit.py -scale, -offset)");
    return 0;
  }
  d.FileScale = d.Scale;
  d.FileOffset = d.Offset;
  // The elevation unit: MetresPerElevationUnit, else the band's unit, else the height unit of
  // a compound CRS (the file's, or OverrideCRS), else metres. A projected CRS in feet that
  // says nothing of heights (a state-plane DEM's, often in feet too) gets a warning: read as
  // metres, horizon tangents would be 3.28 times too steep.
  const char* unit = GDALGetRasterUnitType(base);
  const std::string bandUnit = unit ? unit : "";
  const double vertical = geo->GetVerticalUnitMetres();
  const double given = this->MetresPerElevationUnit;
  double metres = 1.0;
  if (given != 0.0)
  {
    if (!(given > 0.0) || !(given <= 1e4))
    {
      // (beyond a unit of 10 km, elevations would overflow floats, as nodata, before they are
      // anything a DEM holds)
      vtkErrorMacro(<< "MetresPerElevationUnit must be a positive number of metres up to 10000 "
                       "(0: the file's unit), not "
                    << given);
      return 0;
    }
    metres = given;
    d.UnitSource = "MetresPerElevationUnit";
  }
  else if (!bandUnit.empty())
  {
    metres = MetresPerUnit(unit); // (not empty here)
    d.UnitSource = "the band's unit '" + bandUnit + "'";
    if (metres == 0.0)
    {
      vtkWarningMacro(<< "'" << name << "' band " << d.Band << " has the unknown unit '"
                      << bandUnit << "'; treating elevations as metres (another unit: give "
                      << "its metres with MetresPerElevationUnit)");
      metres = 1.0;
      d.UnitSource += ", unknown: read as metres";
    }
    else if (vertical > 0.0 && std::fabs(vertical - metres) > 1e-9 * metres)
    {
      vtkWarningMacro(<< "'" << name << "' band " << d.Band << " has the unit '" << bandUnit
                      << "' but the CRS's heights are in " << geo->GetVerticalUnitName()
                      << "; the band's unit is used (another: MetresPerElevationUnit)");
    }
  }
  else if (vertical > 0.0)
  {
    metres = vertical;
    d.UnitSource = std::string("the CRS's height unit '") + geo->GetVerticalUnitName() + "'";
  }
  else
  {
    d.UnitSource = "none in the file: metres";
    // (a foot of any kind: international, US survey, Clarke's, Indian, ... within 0.1%)
    const double horizontal = geo->GetCRSUnitMetres();
    if (std::fabs(horizontal / 0.3048 - 1.0) < 1e-3)
    {
      vtkWarningMacro(<< "'" << name << "' band " << d.Band << " has no elevation unit and its "
                      << "CRS is in " << geo->GetCRSUnitName() << "; elevations are read as "
                      << "metres: if they are in feet, say so with MetresPerElevationUnit "
                      << "0.3048006096 (US survey feet) or 0.3048 (feet); 1 keeps metres "
                      << "without this warning");
    }
  }
  this->ElevationUnitRead = metres;
  d.Scale *= metres;
  d.Offset *= metres;
  const double nodata = GDALGetRasterNoDataValue(level, &has);
  d.HasNoData = has != 0;
  d.NoData = nodata;
  if (d.HasNoData && type == GDT_Float32 && std::fabs(nodata) <= FLT_MAX)
  {
    // As GDAL's nodata mask compares: a float band's samples with the value rounded to float
    // (a VRT's or an ENVI header's -9999.9 is no float; its samples are -9999.900390625).
    d.NoData = static_cast<double>(static_cast<float>(nodata));
  }
  // and with a relative width of a few float32 ulps (ap_sample_params.nodata_near)
  d.NoDataNear = type == GDT_Float32 || type == GDT_Float64;
  this->HasNoDataValue = d.HasNoData;
  this->NoDataValue = nodata;
  const int flags = GDALGetMaskFlags(level);
  d.UseMask = !(flags & (GMF_ALL_VALID | GMF_NODATA));

  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int whole[6] = { 0, d.Out[0] - 1, 0, d.Out[1] - 1, 0, 0 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole, 6);
  outInfo->Set(vtkDataObject::SPACING(), d.Spacing[0], d.Spacing[1], 1.0);
  outInfo->Set(vtkDataObject::ORIGIN(), d.Origin[0], d.Origin[1], 0.0);
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
  outInfo->Set(vtkApertureGeoreference::CRS_KEY(), d.CRS.c_str());
  d.Valid = true;
  return 1;
}

//------------------------------------------------------------------------------
bool vtkApertureDEMReader::GetWindowExtent(
  int xoff, int yoff, int xsize, int ysize, int extent[6])
{
  const Internals& d = *this->Impl;
  if (!d.Valid)
  {
    vtkErrorMacro(<< "no valid raster information (call UpdateInformation first, or see the "
                     "previous error)");
    return false;
  }
  const int w[4] = { xoff, yoff, xsize, ysize };
  const std::string outside = WindowProblem("the window", w, this->RasterSize);
  if (!outside.empty())
  {
    vtkErrorMacro(<< outside);
    return false;
  }
  // level pixels covering the window, then the grid's blocks covering those (in the file's
  // row order), clipped to the grid
  int first[2], count[2], lo[2], hi[2];
  LevelSpan(xoff, xsize, this->RasterSize[0], d.LevelSize[0], first[0], count[0]);
  LevelSpan(yoff, ysize, this->RasterSize[1], d.LevelSize[1], first[1], count[1]);
  for (int a = 0; a < 2; ++a)
  {
    const double f = d.Factor;
    lo[a] = std::max(0, static_cast<int>(std::floor((first[a] - d.Window[a]) / f)));
    hi[a] = std::min(
      d.Out[a] - 1, static_cast<int>(std::ceil((first[a] + count[a] - d.Window[a]) / f)) - 1);
    if (hi[a] < lo[a])
    {
      const int* sub = this->SubWindow;
      const bool cropped = sub[0] || sub[1] || sub[2] || sub[3];
      vtkErrorMacro(<< "the window (" << xoff << ", " << yoff << ", " << xsize << ", " << ysize
                    << ") covers no cell of the " << d.Out[0] << " x " << d.Out[1]
                    << " grid read"
                    << (cropped ? " (it is outside the SubWindow)"
                                : " (decimation drops the partial blocks at the east and "
                                  "south edges)"));
      return false;
    }
  }
  // output rows run south to north
  extent[0] = lo[0];
  extent[1] = hi[0];
  extent[2] = d.SouthUp ? lo[1] : d.Out[1] - 1 - hi[1];
  extent[3] = d.SouthUp ? hi[1] : d.Out[1] - 1 - lo[1];
  extent[4] = extent[5] = 0;
  return true;
}

//------------------------------------------------------------------------------
int vtkApertureDEMReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  this->Impl->Reading[0] = this->Impl->Reading[1] = 0;
  int ok = 0;
  try
  {
    ok = this->RunRequestData(outputVector);
  }
  catch (const std::bad_alloc&)
  {
    // The size check below compares with the machine's memory; a process limit (ulimit -v),
    // other allocations or fragmentation can still make VTK's array or a strip fail.
    const Internals& d = *this->Impl;
    vtkErrorMacro(<< "out of memory reading " << d.Reading[0] << " x " << d.Reading[1]
                  << " cells of '" << this->FileName << "' (the elevations alone take "
                  << vtkApertureHumanBytes(4.0 * d.Reading[0] * d.Reading[1])
                  << " as float32); read a SubWindow, or use Decimation or an OverviewLevel");
  }
  return vtkApertureEmptyOutputUnless(ok, outputVector);
}

//------------------------------------------------------------------------------
int vtkApertureDEMReader::RunRequestData(vtkInformationVector* outputVector)
{
  Internals& d = *this->Impl;
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  if (!d.Valid)
  {
    vtkErrorMacro(<< "no valid raster information (see the previous error)");
    return 0;
  }
  int ext[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ext);
  ext[0] = std::max(ext[0], 0);
  ext[2] = std::max(ext[2], 0);
  ext[1] = std::min(ext[1], d.Out[0] - 1);
  ext[3] = std::min(ext[3], d.Out[1] - 1);
  ext[4] = ext[5] = 0;
  if (ext[1] < ext[0] || ext[3] < ext[2])
  {
    return 1; // empty request
  }
  const size_t ncols = static_cast<size_t>(ext[1] - ext[0] + 1);
  const size_t nrows = static_cast<size_t>(ext[3] - ext[2] + 1);
  const size_t f = static_cast<size_t>(d.Factor);
  d.Reading[0] = static_cast<int>(ncols);
  d.Reading[1] = static_cast<int>(nrows);

  // Memory: refuse before allocating anything large.
  size_t cells = 0, bytes = 0;
  int source = AP_MEMORY_MACHINE;
  const vtkTypeInt64 limit =
    this->MemoryLimit > 0 ? this->MemoryLimit : vtkApertureUsableMemory(&source);
  // ("the 1.000 GiB MemoryLimit", "... of memory on this machine")
  std::string allowed = vtkApertureHumanBytes(static_cast<double>(limit));
  if (this->MemoryLimit > 0)
  {
    allowed += " MemoryLimit";
  }
  else
  {
    allowed += source != AP_MEMORY_MACHINE
      ? std::string(" of memory ") + vtkApertureUsableMemoryOwner(source)
      : std::string(" of memory on this machine");
  }
  if (ap_size_mul(ncols, nrows, &cells) != AP_OK ||
    ap_size_mul(cells, sizeof(float), &bytes) != AP_OK ||
    bytes > static_cast<size_t>(limit))
  {
    vtkErrorMacro(<< "reading " << ncols << " x " << nrows << " cells of '" << this->FileName
                  << "' needs "
                  << vtkApertureHumanBytes(static_cast<double>(ncols) * nrows * 4.0)
                  << " as float32, more than the " << allowed
                  << "; read a SubWindow, or use Decimation or an OverviewLevel");
    return 0;
  }

  std::string error;
  DatasetHandle ds;
  if (!Internals::Open(this->FileName, ds, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  if (GDALGetRasterCount(ds.H) < d.Band)
  {
    vtkErrorMacro(<< "'" << this->FileName << "' changed since its information was read");
    return 0;
  }
  GDALRasterBandH band = GDALGetRasterBand(ds.H, d.Band);
  if (d.Level >= 0)
  {
    band = GDALGetOverview(band, d.Level);
  }
  GDALRasterBandH mask = d.UseMask ? GDALGetMaskBand(band) : nullptr;
  // GDAL decompresses a block whole, whatever part of it is read: a compressed raster stored
  // as one strip (as Pillow writes them) held 800 MB for a 100 x 100 window of a 20000^2 one,
  // past MemoryLimit, until 2026-12-07 (an uncompressed strip GDAL splits into rows itself)
  // (the block RequestInformation found)
  if (static_cast<double>(bytes) + this->BlockBytes > static_cast<double>(limit))
  {
    // (a file in tiles already was told to be written in tiles, until 2026-12-07; a strip is
    // as wide as the raster, a tile of a narrow one wider)
    const bool tiled = d.Block[0] != GDALGetRasterBandXSize(band);
    // (the limit named in both: a file in tiles as wide as the raster looks like strips)
    std::ostringstream advice;
    advice << "allow at least " << vtkApertureHumanBytes(bytes + this->BlockBytes, true);
    if (!tiled)
    {
      advice << ", or write it in tiles first (gdal_translate -co TILED=YES -co "
                "COMPRESS=DEFLATE)";
    }
    else if (d.Block[0] > 128 || d.Block[1] > 128)
    {
      advice << ", or write it in smaller tiles first (gdal_translate -co TILED=YES -co "
                "BLOCKXSIZE=128 -co BLOCKYSIZE=128 -co COMPRESS=DEFLATE)";
    }
    vtkErrorMacro(<< "reading " << ncols << " x " << nrows << " cells of '" << this->FileName
                  << "' needs " << vtkApertureHumanBytes(static_cast<double>(bytes))
                  << " as float32 and " << vtkApertureHumanBytes(this->BlockBytes)
                  << " for one of its blocks of " << d.Block[0] << " x " << d.Block[1]
                  << " cells, which GDAL reads whole, more than the " << allowed << "; "
                  << advice.str());
    return 0;
  }

  vtkNew<vtkFloatArray> elevation;
  vtkApertureAllocate(elevation, "Elevation", 1, static_cast<vtkIdType>(cells));
  float* out = elevation->GetPointer(0);

  // Read strips of whole output rows, top (file order) to bottom, each at most ~2 MiB of
  // double samples; convert, mask, block-average, and place each output row. (Small strips:
  // the buffers are zeroed and paged in once and stay in the cache; with strips of 32 MiB,
  // zeroing and first-touch page faults took two thirds of the reader's time.) Where one strip
  // of `f` source rows would exceed 16 MiB of doubles (a decimated raster millions of columns
  // wide: its buffers, not the output, would have needed gigabytes), the strip is read in
  // pieces of whole blocks of columns instead.
  const size_t srcCols = ncols * f;
  const size_t budget = 2u << 20;
  const size_t pieceCols = srcCols * f * sizeof(double) <= 8 * budget
    ? srcCols
    : f * std::max<size_t>(1, budget / (f * f * sizeof(double)));
  const size_t rowsPerStrip =
    std::max<size_t>(1, budget / std::max<size_t>(1, pieceCols * f * sizeof(double)));
  std::vector<double> raw;
  std::vector<float> conv;
  std::vector<unsigned char> valid;
  ap_sample_params sp;
  ap_sample_params_init(&sp);
  sp.has_nodata = d.HasNoData;
  sp.nodata = d.NoData;
  sp.nodata_near = d.NoDataNear;
  sp.scale = d.Scale;
  sp.offset = d.Offset;
  sp.signed_byte = d.SignedByte;
  // Output rows from the file's first row: r = 0 .. nrows-1 of the request, in file order.
  // North-up: request row r (file order) is output row ext[3] - r; south-up: ext[2] + r.
  const int firstFileRow = d.SouthUp ? ext[2] : (d.Out[1] - 1 - ext[3]);
  vtkApertureGDALErrorTrap trap;
  // GDAL's warnings while reading samples (a truncated JPEG's "Premature end of JPEG file",
  // whose missing rows it fills with grey) say the values read are damaged: the first is
  // passed on as a warning (silenced until 2026-12-07: garbage elevations without a word).
  std::string damaged;
  // Without a declared nodata value, cells of -9999 (ESRI's and gdaldem's nodata, within the
  // Earth's range of heights, so that no other check names it) are looked for, for a warning:
  // a margin of them read as a 10 km cliff without a word until 2026-12-07.
  size_t sentinels = 0;
  size_t infinite = 0; // (undeclared infinities, nodata all the same: said in a warning)
  // (and finite samples beyond the float range, -1.79e308 as an undeclared nodata value, which
  // a Float64 band can hold: nodata too, silently until 2026-12-07)
  size_t huge = 0;
  const auto noteWarning = [&damaged]() {
    if (CPLGetLastErrorType() == CE_Warning && damaged.empty())
    {
      damaged = vtkApertureGDALErrorTrap::Message("a warning without a message");
    }
    CPLErrorReset();
  };
  for (size_t r0 = 0; r0 < nrows; r0 += rowsPerStrip)
  {
    const size_t k = std::min(rowsPerStrip, nrows - r0);
    const size_t srcRows = k * f;
    const int yoff = d.Window[1] + (firstFileRow + static_cast<int>(r0)) * d.Factor;
    for (size_t c0 = 0; c0 < srcCols; c0 += pieceCols) // (c0, cols: whole blocks)
    {
      const size_t cols = std::min(pieceCols, srcCols - c0);
      raw.resize(srcRows * cols);
      conv.resize(srcRows * cols);
      const int xoff = d.Window[0] + ext[0] * d.Factor + static_cast<int>(c0);
      if (GDALRasterIO(band, GF_Read, xoff, yoff, static_cast<int>(cols),
            static_cast<int>(srcRows), raw.data(), static_cast<int>(cols),
            static_cast<int>(srcRows), GDT_Float64, 0, 0) != CE_None)
      {
        vtkErrorMacro(<< "GDAL failed reading '" << this->FileName
                      << "': " << trap.Message("unknown error"));
        return 0;
      }
      noteWarning();
      size_t beyond = 0;
      const ap_status st =
        ap_samples_to_elevation(raw.data(), raw.size(), &sp, conv.data(), &beyond);
      if (st != AP_OK)
      {
        vtkErrorMacro(<< "converting samples: " << ap_status_string(st));
        return 0;
      }
      if (beyond)
      {
        vtkErrorMacro(<< "'" << this->FileName << "' band " << d.Band << ": its scale of "
                      << d.FileScale << " and offset of " << d.FileOffset
                      << " take samples beyond the range of float32 elevations (3.4e38): a "
                         "wrong scale or offset? (gdal_edit.py -scale, -offset)");
        return 0;
      }
      if (mask)
      {
        valid.resize(srcRows * cols);
        if (GDALRasterIO(mask, GF_Read, xoff, yoff, static_cast<int>(cols),
              static_cast<int>(srcRows), valid.data(), static_cast<int>(cols),
              static_cast<int>(srcRows), GDT_Byte, 0, 0) != CE_None)
        {
          vtkErrorMacro(<< "GDAL failed reading the mask of '" << this->FileName
                        << "': " << trap.Message("unknown error"));
          return 0;
        }
        noteWarning();
        for (size_t q = 0; q < valid.size(); ++q)
        {
          if (!valid[q])
          {
            conv[q] = NAN;
          }
        }
      }
      for (size_t q = 0; q < raw.size(); ++q)
      {
        const bool data = !mask || valid[q]; // (a masked cell is nodata)
        sentinels += !d.HasNoData && raw[q] == -9999.0 && data;
        const bool undeclared = data && !ap_sample_declared_nodata(&sp, raw[q]);
        infinite += undeclared && std::isinf(raw[q]);
        huge += undeclared && std::isfinite(raw[q]) && std::fabs(raw[q]) > FLT_MAX &&
          std::isnan(conv[q]);
      }
      for (size_t r = 0; r < k; ++r)
      {
        const size_t fileRow = r0 + r;
        const size_t outRow =
          d.SouthUp ? fileRow : (nrows - 1 - fileRow); // relative to ext[2]
        float* dst = out + outRow * ncols + c0 / f;
        const float* src = conv.data() + r * f * cols;
        if (f == 1)
        {
          std::copy(src, src + cols, dst);
        }
        else
        {
          ap_block_mean(src, cols, static_cast<ptrdiff_t>(cols), f, dst);
        }
      }
    }
    this->UpdateProgress(static_cast<double>(r0 + k) / static_cast<double>(nrows));
    if (this->GetAbortExecute())
    {
      return 0;
    }
  }

  if (sentinels > 0 && d.FileScale == 1.0 && d.FileOffset == 0.0)
  {
    // (no count: a read in strips or windows sees a part of them)
    vtkWarningMacro(<< "'" << this->FileName << "' band " << d.Band << " has cells of -9999, "
                    << "a common nodata value the file does not declare: read as heights of "
                    << "-9999 (declare it: gdal_edit.py -a_nodata -9999)");
  }
  if (infinite > 0)
  {
    vtkWarningMacro(<< "'" << this->FileName << "' band " << d.Band << " has infinite cells "
                    << "(+inf or -inf), which its nodata value does not declare: read as "
                    << "nodata");
  }
  if (huge > 0)
  {
    vtkWarningMacro(<< "'" << this->FileName << "' band " << d.Band << " has cells beyond the "
                    << "range of float32 elevations (3.4e38), which its nodata value does not "
                    << "declare (-1.79e308, say: an undeclared nodata value?): read as "
                    << "nodata");
  }
  if (!damaged.empty())
  {
    vtkWarningMacro(<< "GDAL warned while reading '" << this->FileName << "' band " << d.Band
                    << ": " << damaged << " (the elevations read may be damaged: a truncated "
                    << "or corrupt file?)");
  }
  // A whole raster of nodata is an error; a piece of one may legitimately be empty.
  const bool whole =
    ext[0] == 0 && ext[2] == 0 && ext[1] == d.Out[0] - 1 && ext[3] == d.Out[1] - 1;
  if (whole)
  {
    const ap_grid_view g = ap_grid_view_make(out, ncols, nrows);
    ap_grid_stats stats;
    if (ap_grid_stats_compute(&g, &stats) == AP_OK && stats.valid == 0)
    {
      // (a window's nodata says nothing of the rest of the file: named so)
      const int* w = this->SubWindow;
      std::ostringstream window;
      if (w[0] || w[1] || w[2] || w[3])
      {
        window << "the window (" << w[0] << ", " << w[1] << ", " << w[2] << ", " << w[3]
               << ") of ";
      }
      vtkErrorMacro(<< "every cell of " << window.str() << "'" << this->FileName << "' band "
                    << d.Band << " is nodata");
      return 0;
    }
  }

  output->SetExtent(ext);
  output->SetOrigin(d.Origin[0], d.Origin[1], 0.0);
  output->SetSpacing(d.Spacing[0], d.Spacing[1], 1.0);
  output->GetPointData()->SetScalars(elevation);
  vtkNew<vtkApertureGeoreference> geo;
  geo->SetCRS(d.CRS.c_str());
  geo->AttachToImage(output);
  return 1;
}

//------------------------------------------------------------------------------
void vtkApertureDEMReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "BandIndex: " << this->BandIndex << "\n";
  os << indent << "SubWindow: " << this->SubWindow[0] << ", " << this->SubWindow[1] << ", "
     << this->SubWindow[2] << ", " << this->SubWindow[3] << "\n";
  os << indent << "OverviewLevel: " << this->OverviewLevel << "\n";
  os << indent << "Decimation: " << this->Decimation << "\n";
  os << indent << "PartialBlockWarning: " << this->PartialBlockWarning << "\n";
  os << indent << "OverrideCRS: " << (this->OverrideCRS ? this->OverrideCRS : "(none)") << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << "\n";
  os << indent << "MetresPerElevationUnit: " << this->MetresPerElevationUnit << "\n";
  os << indent << "DriverName: " << this->Impl->Driver << "\n";
  os << indent << "RasterSize: " << this->RasterSize[0] << ", " << this->RasterSize[1] << "\n";
  os << indent << "NumberOfBands: " << this->NumberOfBands << "\n";
  os << indent << "BandRead: " << this->BandRead << "\n";
  os << indent << "HasNoDataValue: " << this->HasNoDataValue << "\n";
  os << indent << "NoDataValue: " << this->NoDataValue << "\n";
  os << indent << "SouthUp: " << this->SouthUp << "\n";
  os << indent << "BlockBytes: " << this->BlockBytes << "\n";
  os << indent << "ElevationUnitRead: " << this->ElevationUnitRead << " ("
     << this->Impl->UnitSource << ")\n";
}
