// SPDX-License-Identifier: BSD-3-Clause
#include "vtkApertureDEMWriter.h"

#include "vtkApertureGDALErrorTrap.h"
#include "vtkApertureGeoreference.h"
#include "vtkApertureOutputFile.h"
#include "vtkApertureSMPThreads.h"
#include "vtkApertureStripDriver.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"

#include <cpl_conv.h>
#include <cpl_string.h>
#include <cpl_vsi.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkApertureDEMWriter);

struct vtkApertureDEMWriter::Internals
{
  std::vector<std::string> ArrayNames;
  std::vector<std::pair<std::string, std::string>> Metadata;
  struct BandItem
  {
    std::string Array, Key, Value;
  };
  std::vector<BandItem> BandMetadata;

  // The file being written, from BeginFile to EndFile, and what BeginFile resolved.
  struct Band
  {
    std::string ArrayName, Description;
    int Component, Components;
  };
  GDALDatasetH Dataset = nullptr;
  std::string Path;      // the output: FileName, or the target of its symbolic links
  std::string Temporary; // the file GDAL writes, renamed to Path when complete
  int Mode = -1;         // the permissions of the file it replaces, kept; -1 for none
  std::vector<Band> Bands;
  GDALDataType Type = GDT_Float32;
  double NoData = 0.0; // NaN cells are written as this (the NoDataValue of BeginFile)
  int Whole[6] = { 0, -1, 0, -1, 0, 0 }; // the extent the file covers
  int NextRow = -1;                      // the next image row to write (north first)
  bool Failed = false;                   // a strip failed (reported)
  bool Written = false;                  // the last WriteData wrote its file
  std::string Error;                     // GDAL's message of a failed write
};

//------------------------------------------------------------------------------
vtkApertureDEMWriter::vtkApertureDEMWriter()
  : FileName(nullptr)
  , Compression(nullptr)
  , CompressionLevel(1)
  , NoDataValue(std::numeric_limits<double>::quiet_NaN())
  , NumberOfThreads(0)
  , StripRows(0)
  , Impl(new Internals)
{
  this->SetCompression("DEFLATE");
}

//------------------------------------------------------------------------------
vtkApertureDEMWriter::~vtkApertureDEMWriter()
{
  this->EndFile(false); // (only after an exception between BeginFile and EndFile)
  this->SetFileName(nullptr);
  this->SetCompression(nullptr);
  delete this->Impl;
}

//------------------------------------------------------------------------------
void vtkApertureDEMWriter::AddArrayName(const char* name)
{
  // (a name listed already is not listed again: a script adding its arrays in a loop of
  // writes gave the GeoTIFF one more band a write, and the EXR a clash of channel names)
  auto& names = this->Impl->ArrayNames;
  if (name && *name && std::find(names.begin(), names.end(), name) == names.end())
  {
    names.emplace_back(name);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkApertureDEMWriter::ClearArrayNames()
{
  if (!this->Impl->ArrayNames.empty())
  {
    this->Impl->ArrayNames.clear();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
int vtkApertureDEMWriter::GetNumberOfArrayNames()
{
  return static_cast<int>(this->Impl->ArrayNames.size());
}

//------------------------------------------------------------------------------
const char* vtkApertureDEMWriter::GetArrayName(int i)
{
  if (i < 0 || i >= this->GetNumberOfArrayNames())
  {
    return nullptr;
  }
  return this->Impl->ArrayNames[static_cast<size_t>(i)].c_str();
}

//------------------------------------------------------------------------------
void vtkApertureDEMWriter::AddMetadata(const char* key, const char* value)
{
  if (key && *key)
  {
    // (GDAL's keys are alike whatever their case)
    vtkApertureReplaceOrAppend(this->Impl->Metadata, { key, value ? value : "" },
      [key](const std::pair<std::string, std::string>& kv) {
        return EQUAL(kv.first.c_str(), key);
      });
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkApertureDEMWriter::AddBandMetadata(
  const char* arrayName, const char* key, const char* value)
{
  if (arrayName && *arrayName && key && *key)
  {
    vtkApertureReplaceOrAppend(this->Impl->BandMetadata, { arrayName, key, value ? value : "" },
      [&](const Internals::BandItem& item) {
        return item.Array == arrayName && EQUAL(item.Key.c_str(), key);
      });
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkApertureDEMWriter::ClearMetadata()
{
  if (!this->Impl->Metadata.empty() || !this->Impl->BandMetadata.empty())
  {
    this->Impl->Metadata.clear();
    this->Impl->BandMetadata.clear();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkImageData* vtkApertureDEMWriter::GetInput()
{
  return vtkImageData::SafeDownCast(this->Superclass::GetInput());
}

//------------------------------------------------------------------------------
int vtkApertureDEMWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

//------------------------------------------------------------------------------
namespace
{
// The level's creation option and range for the GeoTIFF codecs that have one (GDAL 3.6). (LZMA's
// presets 6 to 9 differ in their dictionaries alone, larger than a tile: they compress alike;
// GDAL 3.6 passes on presets above 0 only, so 0 would write 6's: refused.)
struct CompressionLevelOption
{
  const char *Codec, *Option;
  int Lowest, Highest;
};
const CompressionLevelOption levelOptions[] = { { "DEFLATE", "ZLEVEL", 1, 12 },
  { "ZSTD", "ZSTD_LEVEL", 1, 22 }, { "LZMA", "LZMA_PRESET", 1, 9 } };

// A codec's name as GDAL lists it: upper case ("" for null).
std::string CodecName(const char* codec)
{
  std::string name = codec ? codec : "";
  for (char& ch : name)
  {
    ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  }
  return name;
}

// The level option of a codec named as GDAL lists it, or null for a codec without levels.
const CompressionLevelOption* LevelOption(const std::string& codec)
{
  const auto it = std::find_if(std::begin(levelOptions), std::end(levelOptions),
    [&codec](const CompressionLevelOption& lo) { return codec == lo.Codec; });
  return it == std::end(levelOptions) ? nullptr : it;
}

// The file's square tiles (cells a side): the strips written at a time are whole tile rows.
constexpr int Tile = 256;

// The values GDAL's GeoTIFF driver accepts for COMPRESS, from its creation option list.
std::vector<std::string> GeoTIFFCodecs(GDALDriverH driver)
{
  std::vector<std::string> codecs;
  const char* list = GDALGetMetadataItem(driver, GDAL_DMD_CREATIONOPTIONLIST, nullptr);
  const std::string xml = list ? list : "";
  size_t begin = xml.find("name='COMPRESS'"); // (GDAL 3.6 quotes so; others may not)
  begin = begin == std::string::npos ? xml.find("name=\"COMPRESS\"") : begin;
  const size_t end = begin == std::string::npos ? begin : xml.find("</Option>", begin);
  for (size_t at = begin; end != std::string::npos;)
  {
    at = xml.find("<Value>", at);
    if (at == std::string::npos || at > end)
    {
      break;
    }
    at += 7;
    const size_t stop = xml.find("</Value>", at);
    if (stop == std::string::npos)
    {
      break;
    }
    codecs.push_back(xml.substr(at, stop - at));
  }
  return codecs;
}
}

//------------------------------------------------------------------------------
bool vtkApertureDEMWriter::CheckCompression()
{
  std::string codec;
  const char* levelOption = nullptr;
  return this->CheckCompression(codec, levelOption) != nullptr;
}

//------------------------------------------------------------------------------
bool vtkApertureDEMWriter::HasCompressionLevel(const char* codec)
{
  return LevelOption(CodecName(codec)) != nullptr;
}

//------------------------------------------------------------------------------
void* vtkApertureDEMWriter::CheckCompression(std::string& codec, const char*& levelOption)
{
  GDALAllRegister();
  GDALDriverH driver = GDALGetDriverByName("GTiff");
  if (!driver)
  {
    vtkErrorMacro(<< "GDAL has no GeoTIFF driver");
    return nullptr;
  }
  codec = CodecName(this->Compression && *this->Compression ? this->Compression : "NONE");
  // The codecs that keep floating-point samples exactly. JPEG and WEBP take 8- or 12-bit
  // samples, the CCITT ones 1-bit: GDAL refuses them for every tile, and on its compression
  // threads, where no caller sees the error, leaves the tiles out of a file that looks whole.
  static const char* const lossless[] = { "NONE", "LZW", "PACKBITS", "DEFLATE", "ZSTD", "LZMA",
    "LERC", "LERC_DEFLATE", "LERC_ZSTD" };
  auto exact = [](const std::string& c) {
    return std::find(std::begin(lossless), std::end(lossless), c) != std::end(lossless);
  };
  const std::vector<std::string> offered = GeoTIFFCodecs(driver);
  std::string usable;
  for (const std::string& c : offered)
  {
    usable += exact(c) ? (usable.empty() ? "" : ", ") + c : std::string();
  }
  const char* name = this->Compression ? this->Compression : "";
  if (std::find(offered.begin(), offered.end(), codec) == offered.end())
  {
    vtkErrorMacro(<< "unknown GeoTIFF compression '" << name << "' (GDAL offers " << usable
                  << " for floating-point bands)");
    return nullptr;
  }
  if (!exact(codec))
  {
    vtkErrorMacro(<< "GeoTIFF compression '" << name
                  << "' cannot store floating-point bands; choose one of " << usable);
    return nullptr;
  }
  const CompressionLevelOption* level = LevelOption(codec);
  if (level && this->CompressionLevel != -1 &&
    (this->CompressionLevel < level->Lowest || this->CompressionLevel > level->Highest))
  {
    vtkErrorMacro(<< "compression level " << this->CompressionLevel << " is outside "
                  << level->Codec << "'s range " << level->Lowest << "-" << level->Highest
                  << " (-1: GDAL's default)");
    return nullptr;
  }
  levelOption = level && this->CompressionLevel != -1 ? level->Option : nullptr;
  return driver;
}

//------------------------------------------------------------------------------
void vtkApertureDEMWriter::WriteData()
{
  vtkImageData* input = this->GetInput();
  int ext[6];
  vtkApertureWrittenExtent(input, this->GetInputInformation(), ext);
  if (!this->BeginFile(input, ext))
  {
    return; // (reported)
  }
  this->Impl->Written = this->EndFile(this->WriteRows(input, ext[2], ext[3]));
}

//------------------------------------------------------------------------------
int vtkApertureDEMWriter::Write()
{
  this->SetErrorCode(vtkErrorCode::NoError);
  if (!this->FileName || !*this->FileName)
  {
    // (first, in either path: the code named the name for any failure without one, such as
    // no input, until review)
    vtkErrorMacro(<< "no file name was set");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return 0;
  }
  if (this->StripRows <= 0)
  {
    this->Impl->Written = false;
    const int ok = this->Superclass::Write() && this->Impl->Written;
    this->SetErrorCode(vtkApertureWriteErrorCode(ok, this->GetErrorCode()));
    return ok;
  }
  const int ok =
    vtkApertureWriteInStrips(this, this->StripRows, Tile, this->FileName);
  this->SetErrorCode(vtkApertureWriteErrorCode(ok, this->GetErrorCode()));
  return ok;
}

//------------------------------------------------------------------------------
int vtkApertureDEMWriter::GetTileSize()
{
  return Tile;
}

//------------------------------------------------------------------------------
int vtkApertureDEMWriter::BeginStrips(vtkImageData* image, const int whole[6])
{
  if (!this->BeginFile(image, whole))
  {
    return 0;
  }
  this->Impl->NextRow = whole[3];
  this->Impl->Failed = false;
  this->UpdateProgress(0.0); // (progress starts at 0, as a whole write's does)
  return 1;
}

//------------------------------------------------------------------------------
int vtkApertureDEMWriter::WriteStrip(vtkImageData* strip)
{
  Internals& d = *this->Impl;
  if (!d.Dataset || d.Failed)
  {
    vtkErrorMacro(<< (d.Failed ? "a strip failed; EndStrips() removes the file"
                               : "no file begun: call BeginStrips() first"));
    return 0;
  }
  int j0 = 0;
  if (!vtkApertureStripRows(this, strip, d.Whole, d.NextRow, Tile, "a tile row", d.Path, j0))
  {
    d.Failed = true;
    return 0;
  }
  if (!this->WriteRows(strip, j0, d.NextRow))
  {
    d.Failed = true;
    return 0;
  }
  d.NextRow = j0 - 1;
  return 1;
}

//------------------------------------------------------------------------------
int vtkApertureDEMWriter::EndStrips()
{
  Internals& d = *this->Impl;
  if (!d.Dataset)
  {
    return 0; // (nothing begun, or BeginStrips failed: reported)
  }
  // (metadata added while the strips were written, such as a digest of them, with the rest)
  vtkApertureGDALErrorTrap trap;
  for (const auto& kv : d.Metadata)
  {
    if (!d.Failed &&
      GDALSetMetadataItem(d.Dataset, kv.first.c_str(), kv.second.c_str(), nullptr) != CE_None)
    {
      d.Error = trap.Message("unknown error");
      d.Failed = true;
    }
  }
  return this->EndFile(vtkApertureStripsComplete(this, d.Failed, d.NextRow, d.Whole, d.Path))
    ? 1
    : 0;
}

//------------------------------------------------------------------------------
void vtkApertureDEMWriter::AbandonStrips()
{
  this->EndFile(false);
}

//------------------------------------------------------------------------------
int vtkApertureDEMWriter::GetNextStripRow()
{
  return this->Impl->NextRow;
}

//------------------------------------------------------------------------------
bool vtkApertureDEMWriter::BeginFile(vtkImageData* input, const int whole[6])
{
  Internals& d = *this->Impl;
  this->EndFile(false); // (a file begun by BeginStrips and never ended: removed)
  d.Bands.clear();
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro(<< "no file name was set");
    return false;
  }
  const std::string path(this->FileName);
  std::string what;
  if (!vtkApertureOutputReplaceable(path, what))
  {
    vtkErrorMacro(<< "'" << path << "' is " << what << ", not a file a GeoTIFF can be written to");
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
    return false;
  }
  if (vtkApertureOutputReadOnly(path))
  {
    vtkErrorMacro(<< "cannot write '" << path << "': the file exists and is read-only");
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
    return false;
  }
  if (!input || input->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro(<< "no input image to write to '" << path << "'");
    return false;
  }
  if (whole[4] != whole[5])
  {
    vtkErrorMacro(<< "only 2-D images can be written as GeoTIFF; this one has "
                  << (whole[5] - whole[4] + 1) << " slices");
    return false;
  }
  const int nx = whole[1] - whole[0] + 1, ny = whole[3] - whole[2] + 1;

  // 1. The arrays, as (array, component, band description) in band order.
  vtkPointData* pd = input->GetPointData();
  std::vector<std::string> names = d.ArrayNames;
  if (names.empty())
  {
    for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
    {
      // (numeric ones: a label array of strings beside them is skipped, as the EXR writer
      // skips it, not an error that only naming every other array avoided)
      if (pd->GetArrayName(a) && pd->GetArray(a))
      {
        names.emplace_back(pd->GetArrayName(a));
      }
    }
  }
  if (names.empty())
  {
    bool unnamed = false; // numeric arrays, all without a name (a hand-made image's scalars)
    for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
    {
      unnamed = unnamed || pd->GetArray(a) != nullptr;
    }
    vtkErrorMacro(<< "the image has no named point arrays to write to '" << path << "'"
                  << (unnamed ? " (a band is described by its array's name: name the array, "
                                "such as 'Elevation')"
                              : ""));
    return false;
  }
  bool anyDouble = false;
  for (const std::string& name : names)
  {
    vtkAbstractArray* abstract = pd->GetAbstractArray(name.c_str());
    if (!abstract)
    {
      vtkErrorMacro(<< "the image has no point array named '" << name << "'");
      return false;
    }
    vtkDataArray* array = vtkDataArray::SafeDownCast(abstract);
    if (!array)
    {
      vtkErrorMacro(<< "the point array '" << name << "' is not numeric");
      return false;
    }
    anyDouble = anyDouble || array->GetDataType() == VTK_DOUBLE;
    const int nc = array->GetNumberOfComponents();
    for (int c = 0; c < nc; ++c)
    {
      std::string description = name;
      if (nc > 1)
      {
        const char* cname = array->GetComponentName(c);
        description += "_" + ((cname && *cname) ? std::string(cname) : std::to_string(c));
      }
      d.Bands.push_back({ name, description, c, nc });
    }
  }

  // 2. Georeference of the whole extent (CRS from the image's field data). (An image made by
  // hand with the reader's field data but VTK's default geometry was written at the CRS's
  // origin in cells of one unit, without a word, until 2026-12-07.)
  vtkApertureGeoreference::WarnOfDefaultGeometry(this, input);
  vtkNew<vtkApertureGeoreference> geo;
  const bool hasCRS = geo->SetFromImage(input);
  double origin[3], spacing[3], gt[6];
  input->GetOrigin(origin);
  input->GetSpacing(spacing);
  if (!hasCRS && vtkApertureGeoreference::GetAttachedCRS(input))
  {
    // (as the EXR writer: a NaN origin or a negative spacing made a geotransform of NaN, or a
    // mirrored one that no reader takes, with only a warning)
    vtkErrorMacro(<< "the image has a CRS but its georeference cannot be written to '" << path
                  << "': " << geo->GetErrorMessage());
    return false;
  }
  if (!hasCRS && !(spacing[0] > 0.0 && spacing[1] > 0.0 && std::isfinite(spacing[0]) &&
                   std::isfinite(spacing[1]) && std::isfinite(origin[0]) &&
                   std::isfinite(origin[1])))
  {
    vtkErrorMacro(<< "cannot write '" << path << "': the image's spacing must be positive and "
                  << "finite and its origin finite to make a geotransform (spacing "
                  << spacing[0] << ", " << spacing[1] << "; origin " << origin[0] << ", "
                  << origin[1] << ")");
    return false;
  }
  if (!hasCRS && !vtkApertureGeoreference::HasNorthUpAxes(input))
  {
    // (with a CRS SetFromImage refuses it; without one the file was written upside down, or
    // rotated, with only the warning below, until 2026-12-07)
    vtkErrorMacro(<< "cannot write '" << path << "': the image has a rotated or mirrored "
                  << "direction matrix, which no geotransform of its origin and spacing "
                  << "describes");
    return false;
  }
  if (hasCRS && !*geo->GetHorizontalCRS())
  {
    vtkErrorMacro(<< "cannot write the CRS to '" << path << "': " << geo->GetErrorMessage());
    return false;
  }
  if (hasCRS)
  {
    geo->SetGrid(origin[0] + whole[0] * spacing[0], origin[1] + whole[2] * spacing[1],
      spacing[0], spacing[1], nx, ny);
    geo->GetGeoTransform(gt);
  }
  else
  {
    gt[0] = origin[0] + (whole[0] - 0.5) * spacing[0];
    gt[1] = spacing[0];
    gt[2] = 0.0;
    gt[3] = origin[1] + (whole[3] + 0.5) * spacing[1];
    gt[4] = 0.0;
    gt[5] = -spacing[1];
  }
  // (of the whole extent, which a strip is part of)
  const std::string edges = vtkApertureGeoTransformProblem(path, gt, nx, ny, origin, spacing);
  if (!edges.empty())
  {
    vtkErrorMacro(<< edges);
    return false;
  }
  if (!hasCRS)
  {
    vtkWarningMacro(<< "writing '" << path << "' without a CRS: " << geo->GetErrorMessage());
  }

  // 3. Create the file (its nodata value checked first: nothing of GDAL's made yet). Float32
  // bands take any value that rounds to a finite float (-3.4028235e38, numpy's and ESRI's
  // spelling of -FLT_MAX, lies a hair beyond it), and declare that float, the cells' value.
  const double floatLimit = 3.4028235677973366e38; // 2^128 - 2^103: rounds to infinity
  if (!std::isnan(this->NoDataValue) &&
    !(anyDouble ? std::fabs(this->NoDataValue) <= std::numeric_limits<double>::max()
                : std::fabs(this->NoDataValue) < floatLimit))
  {
    char text[32];
    std::snprintf(text, sizeof(text), "%.9g", this->NoDataValue);
    vtkErrorMacro(<< "the NoDataValue " << text << " is not a finite "
                  << (anyDouble ? "Float64" : "Float32") << " value (nor NaN)");
    return false;
  }
  vtkApertureGDALErrorTrap trap;
  std::string compression;
  const char* levelOption = nullptr;
  GDALDriverH driver = static_cast<GDALDriverH>(this->CheckCompression(compression, levelOption));
  if (!driver)
  {
    return false; // (reported)
  }
  char** options = nullptr;
  if (nx < Tile)
  {
    // (a raster narrower than a tile is stored in strips of a tile's rows, as wide as the
    // raster: tiles are multiples of 16 wide, and a 2-column DEM in 16-column tiles compressed
    // 8 times its size into a file 2.6 times as large)
    options = CSLSetNameValue(options, "TILED", "NO");
    options = CSLSetNameValue(options, "BLOCKYSIZE", std::to_string(Tile).c_str());
  }
  else
  {
    // (a raster of fewer rows gets tiles of its rows rounded up to 16, GeoTIFF's unit: a 2-row
    // DEM in 256-row tiles would compress 128 times its size)
    const int tileRows = std::min(Tile, (ny + 15) / 16 * 16);
    options = CSLSetNameValue(options, "TILED", "YES");
    options = CSLSetNameValue(options, "BLOCKXSIZE", std::to_string(Tile).c_str());
    options = CSLSetNameValue(options, "BLOCKYSIZE", std::to_string(tileRows).c_str());
  }
  options = CSLSetNameValue(options, "INTERLEAVE", "BAND");
  options = CSLSetNameValue(options, "BIGTIFF", "IF_SAFER");
  options = CSLSetNameValue(options, "COMPRESS", compression.c_str());
  if (compression == "DEFLATE" || compression == "LZW" || compression == "ZSTD")
  {
    options = CSLSetNameValue(options, "PREDICTOR", "3"); // floating-point predictor
  }
  if (levelOption)
  {
    options =
      CSLSetNameValue(options, levelOption, std::to_string(this->CompressionLevel).c_str());
  }
  if (compression != "NONE")
  {
    // GDAL compresses whole tiles on worker threads and writes them in order: same bytes.
    // (0: the cores this process may use, which GDAL's ALL_CPUS does not know in a container
    // with a CPU quota; they cap larger counts, which GDAL's pool would start and keep)
    // LZMA on two at least: GDAL 3.6 compresses nothing on the writing thread alone (its tiles
    // are stored at full size in LZMA's framing), so a file written with one thread, or on a
    // machine of one core, had other and 30% larger bytes than with two, until 2026-12-07
    const int cores = vtkApertureCores();
    const int asked = this->NumberOfThreads > 0 ? std::min(this->NumberOfThreads, cores) : cores;
    const std::string threads = std::to_string(compression == "LZMA" ? std::max(asked, 2) : asked);
    options = CSLSetNameValue(options, "NUM_THREADS", threads.c_str());
  }
  d.Type = anyDouble ? GDT_Float64 : GDT_Float32;
  d.NoData = anyDouble || std::isnan(this->NoDataValue)
    ? this->NoDataValue
    : static_cast<double>(static_cast<float>(
        std::copysign(std::min(std::fabs(this->NoDataValue),
                        static_cast<double>(std::numeric_limits<float>::max())),
          this->NoDataValue)));
  // Written to a temporary file renamed into place when complete (EndFile): a failed or
  // aborted write leaves an earlier file as it was (GDAL deleted it before creating its own).
  // Through a symbolic link its target is replaced, the link kept, with its permissions.
  const std::string target = vtkApertureOutputTarget(path);
  const int mode = vtkApertureExistingMode(target);
  const std::string temporary = vtkApertureTemporaryName(target);
  GDALDatasetH ds = GDALCreate(
    driver, temporary.c_str(), nx, ny, static_cast<int>(d.Bands.size()), d.Type, options);
  CSLDestroy(options);
  if (!ds)
  {
    vtkErrorMacro(<< "GDAL cannot create '" << path << "': " << trap.Message("unknown error"));
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
    return false;
  }
  d.Dataset = ds;
  d.Path = target;
  d.Temporary = temporary;
  d.Mode = mode;
  std::copy(whole, whole + 6, d.Whole);
  bool ok = GDALSetGeoTransform(ds, gt) == CE_None;
  if (ok && hasCRS)
  {
    // (a compound CRS's vertical part would give every band its height unit: products and
    // elevations in metres read back as feet; the horizontal part places the grid)
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    ok = OSRSetFromUserInput(srs, geo->GetHorizontalCRS()) == OGRERR_NONE &&
      GDALSetSpatialRef(ds, srs) == CE_None;
    OSRRelease(srs);
  }
  for (const auto& kv : d.Metadata)
  {
    ok = ok && GDALSetMetadataItem(ds, kv.first.c_str(), kv.second.c_str(), nullptr) == CE_None;
  }
  for (size_t b = 0; ok && b < d.Bands.size(); ++b)
  {
    GDALRasterBandH hb = GDALGetRasterBand(ds, static_cast<int>(b) + 1);
    GDALSetDescription(hb, d.Bands[b].Description.c_str());
    ok = GDALSetRasterNoDataValue(hb, d.NoData) == CE_None;
    if (ok && d.Bands[b].ArrayName == "Elevation")
    {
      // (heights in metres, as the reader gives them: without the unit a DEM in a CRS in feet
      // read back warned that its heights might be feet, until 2026-12-07)
      ok = GDALSetRasterUnitType(hb, "metre") == CE_None;
    }
    for (const auto& item : d.BandMetadata)
    {
      if (item.Array == d.Bands[b].ArrayName)
      {
        ok = ok &&
          GDALSetMetadataItem(hb, item.Key.c_str(), item.Value.c_str(), nullptr) == CE_None;
        if (ok && EQUAL(item.Key.c_str(), "UNITS") && item.Value != "1")
        {
          // (the unit gdalinfo and QGIS show: the products' degrees and steradians were only
          // in the metadata until 2026-12-07; a ratio, "1", has none there)
          ok = GDALSetRasterUnitType(hb, item.Value.c_str()) == CE_None;
        }
      }
    }
  }
  if (!ok)
  {
    d.Error = trap.Message("unknown error");
    this->EndFile(false);
  }
  return ok;
}

//------------------------------------------------------------------------------
bool vtkApertureDEMWriter::WriteRows(vtkImageData* input, int j0, int j1)
{
  Internals& d = *this->Impl;
  const int* whole = d.Whole;
  const int nx = whole[1] - whole[0] + 1;
  int ext[6];
  input->GetExtent(ext);
  if (ext[0] > whole[0] || ext[1] < whole[1] || ext[2] > j0 || ext[3] < j1)
  {
    vtkErrorMacro(<< "the input's extent (" << ext[0] << ".." << ext[1] << ", " << ext[2]
                  << ".." << ext[3] << ") does not hold rows " << j0 << " to " << j1
                  << " of columns " << whole[0] << " to " << whole[1]);
    return false;
  }
  const vtkIdType width = ext[1] - ext[0] + 1;
  vtkApertureGDALErrorTrap trap;
  // Rows in strips of one tile row in file order (north first), converted on the fly into a
  // buffer of the file's sample type, and each strip's tiles flushed at once (compressed on
  // the worker threads): GDAL's block cache never holds more than a strip. The file's row r
  // is image row whole[3] - r.
  const int fileFirst = whole[3] - j1, fileEnd = whole[3] - j0 + 1;
  std::vector<float> stripF;
  std::vector<double> stripD;
  bool ok = true;
  for (size_t b = 0; ok && b < d.Bands.size(); ++b)
  {
    const Internals::Band& band = d.Bands[b];
    vtkDataArray* array = input->GetPointData()->GetArray(band.ArrayName.c_str());
    if (!array || array->GetNumberOfComponents() != band.Components)
    {
      vtkErrorMacro(<< "the input of rows " << j0 << " to " << j1 << " has no point array '"
                    << band.ArrayName << "' of " << band.Components
                    << " components (as the first rows had)");
      return false;
    }
    if (array->GetNumberOfTuples() != input->GetNumberOfPoints())
    {
      vtkErrorMacro(<< "the point array '" << band.ArrayName << "' has "
                    << array->GetNumberOfTuples() << " tuples for the " << width << " x "
                    << (ext[3] - ext[2] + 1) << " points of the input's extent");
      return false;
    }
    const int nc = band.Components;
    GDALRasterBandH hb = GDALGetRasterBand(d.Dataset, static_cast<int>(b) + 1);
    // File rows r0 .. r0 + k - 1 into dst, NaN as the nodata value.
    auto fill = [&](auto* dst, int r0, int k) {
      using T = typename std::remove_pointer<decltype(dst)>::type;
      const T nodata = static_cast<T>(d.NoData);
      const bool replace = !std::isnan(d.NoData);
      auto replaceNaN = [&](T* row) {
        for (int i = 0; replace && i < nx; ++i)
        {
          row[i] = std::isnan(row[i]) ? nodata : row[i];
        }
      };
      for (int r = 0; r < k; ++r)
      {
        const vtkIdType row = whole[3] - (r0 + r) - ext[2];
        T* out = dst + static_cast<size_t>(r) * static_cast<size_t>(nx);
        const vtkIdType first = row * width + (whole[0] - ext[0]);
        if (auto* fa = vtkFloatArray::SafeDownCast(array))
        {
          const float* src = fa->GetPointer(0) + first * nc + band.Component;
          for (int i = 0; i < nx; ++i)
          {
            out[i] = static_cast<T>(src[static_cast<size_t>(i) * nc]);
          }
        }
        else if (auto* da = vtkDoubleArray::SafeDownCast(array))
        {
          const double* src = da->GetPointer(0) + first * nc + band.Component;
          for (int i = 0; i < nx; ++i)
          {
            out[i] = static_cast<T>(src[static_cast<size_t>(i) * nc]);
          }
        }
        else
        {
          for (int i = 0; i < nx; ++i)
          {
            out[i] = static_cast<T>(array->GetComponent(first + i, band.Component));
          }
        }
        replaceNaN(out);
      }
    };
    // One strip through a buffer whose element type is the file's sample type.
    auto writeStrip = [&](auto& strip, int r0, int k) {
      strip.resize(static_cast<size_t>(k) * static_cast<size_t>(nx));
      fill(strip.data(), r0, k);
      return GDALRasterIO(hb, GF_Write, 0, r0, nx, k, strip.data(), nx, k, d.Type, 0, 0) ==
        CE_None;
    };
    // (progress over the file's rows: those above this strip, then this strip's band by band,
    // each tile row by tile row; a large band is a long write)
    const double rows = static_cast<double>(whole[3]) - whole[2] + 1;
    for (int r0 = fileFirst; ok && r0 < fileEnd; r0 += Tile)
    {
      const int k = std::min(Tile, fileEnd - r0);
      ok = (d.Type == GDT_Float32 ? writeStrip(stripF, r0, k) : writeStrip(stripD, r0, k)) &&
        GDALFlushRasterCache(hb) == CE_None;
      const double done = (static_cast<double>(b) +
                            static_cast<double>(r0 + k - fileFirst) / (fileEnd - fileFirst)) /
        static_cast<double>(d.Bands.size());
      this->UpdateProgress((static_cast<double>(fileFirst) + (j1 - j0 + 1.0) * done) / rows);
      if (ok && this->GetAbortExecute())
      {
        vtkErrorMacro(<< "writing '" << d.Path << "' was aborted");
        return false;
      }
    }
  }
  if (!ok)
  {
    d.Error = trap.Message("unknown error");
  }
  return ok;
}

//------------------------------------------------------------------------------
bool vtkApertureDEMWriter::EndFile(bool ok)
{
  Internals& d = *this->Impl;
  if (!d.Dataset)
  {
    return false;
  }
  vtkApertureGDALErrorTrap trap;
  GDALFlushCache(d.Dataset);
  const std::string reason = trap.Message(d.Error.empty() ? "unknown error" : d.Error.c_str());
  GDALClose(d.Dataset);
  d.Dataset = nullptr;
  const bool failed = CPLGetLastErrorType() >= CE_Failure || !d.Error.empty();
  if (!ok || failed)
  {
    // GDAL's message for a full disk names a scanline only ("TIFFAppendToStrip: Write error"):
    // say it, while the partial file still holds the space
    const GIntBig left = failed ? VSIGetDiskFreeSpace(CPLGetDirname(d.Path.c_str())) : -1;
    VSIUnlink(d.Temporary.c_str());
    if (failed)
    {
      vtkErrorMacro(<< "GDAL failed writing '" << d.Path << "': " << reason
                    << (left >= 0 && left < (1 << 20) ? " (the disk is full)" : ""));
    }
    d.Error.clear();
    return false;
  }
  if (!vtkAperturePutInPlace(d.Temporary, d.Path, d.Mode))
  {
    vtkErrorMacro(<< "cannot put the temporary file '" << d.Temporary << "' in place of '"
                  << d.Path << "': " << std::strerror(errno));
    VSIUnlink(d.Temporary.c_str());
    return false;
  }
  d.Error.clear();
  const std::string stale =
    vtkApertureRemoveStaleSidecars(this->FileName ? this->FileName : d.Path, d.Path);
  if (!stale.empty())
  {
    vtkWarningMacro(<< "wrote '" << d.Path << "', but " << stale);
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkApertureDEMWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "Compression: " << (this->Compression ? this->Compression : "(none)") << "\n";
  os << indent << "CompressionLevel: " << this->CompressionLevel << "\n";
  os << indent << "NoDataValue: " << this->NoDataValue << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "StripRows: " << this->StripRows << "\n";
  os << indent << "ArrayNames:";
  for (const auto& n : this->Impl->ArrayNames)
  {
    os << " " << n;
  }
  os << "\n";
  os << indent << "Metadata items: " << this->Impl->Metadata.size() << "\n";
  os << indent << "Band metadata items: " << this->Impl->BandMetadata.size() << "\n";
}
