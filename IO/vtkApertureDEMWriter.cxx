// SPDX-License-Identifier: BSD-3-Clause
#include "vtkApertureDEMWriter.h"

#include "vtkApertureGDALErrorTrap.h"
#include "vtkApertureGeoreference.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
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
#include <cmath>
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
};

//------------------------------------------------------------------------------
vtkApertureDEMWriter::vtkApertureDEMWriter()
  : FileName(nullptr)
  , Compression(nullptr)
  , CompressionLevel(1)
  , NumberOfThreads(0)
  , Impl(new Internals)
{
  this->SetCompression("DEFLATE");
}

//------------------------------------------------------------------------------
vtkApertureDEMWriter::~vtkApertureDEMWriter()
{
  this->SetFileName(nullptr);
  this->SetCompression(nullptr);
  delete this->Impl;
}

//------------------------------------------------------------------------------
void vtkApertureDEMWriter::AddArrayName(const char* name)
{
  if (name && *name)
  {
    this->Impl->ArrayNames.emplace_back(name);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkApertureDEMWriter::ClearArrayNames()
{
  this->Impl->ArrayNames.clear();
  this->Modified();
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
    this->Impl->Metadata.emplace_back(key, value ? value : "");
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkApertureDEMWriter::AddBandMetadata(const char* arrayName, const char* key, const char* value)
{
  if (arrayName && *arrayName && key && *key)
  {
    this->Impl->BandMetadata.push_back({ arrayName, key, value ? value : "" });
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkApertureDEMWriter::ClearMetadata()
{
  this->Impl->Metadata.clear();
  this->Impl->BandMetadata.clear();
  this->Modified();
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
// The level's creation option and range for the GeoTIFF codecs that have one (GDAL 3.6).
struct CompressionLevelOption
{
  const char *Codec, *Option;
  int Lowest, Highest;
};
const CompressionLevelOption levelOptions[] = { { "DEFLATE", "ZLEVEL", 1, 12 },
  { "ZSTD", "ZSTD_LEVEL", 1, 22 }, { "LZMA", "LZMA_PRESET", 0, 9 } };

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
void* vtkApertureDEMWriter::CheckCompression(std::string& codec, const char*& levelOption)
{
  GDALAllRegister();
  GDALDriverH driver = GDALGetDriverByName("GTiff");
  if (!driver)
  {
    vtkErrorMacro(<< "GDAL has no GeoTIFF driver");
    return nullptr;
  }
  codec = this->Compression && *this->Compression ? this->Compression : "NONE";
  for (char& ch : codec)
  {
    ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  }
  const std::vector<std::string> codecs = GeoTIFFCodecs(driver);
  if (std::find(codecs.begin(), codecs.end(), codec) == codecs.end())
  {
    std::string known;
    for (const std::string& c : codecs)
    {
      known += (known.empty() ? "" : ", ") + c;
    }
    vtkErrorMacro(<< "unknown GeoTIFF compression '" << (this->Compression ? this->Compression : "")
                  << "' (GDAL offers " << known << ")");
    return nullptr;
  }
  const CompressionLevelOption* level = nullptr;
  for (const CompressionLevelOption& lo : levelOptions)
  {
    level = codec == lo.Codec ? &lo : level;
  }
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
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro(<< "no file name was set");
    return;
  }
  const std::string path(this->FileName);
  if (!input || input->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro(<< "no input image to write to '" << path << "'");
    return;
  }
  int ext[6];
  input->GetExtent(ext);
  if (ext[4] != ext[5])
  {
    vtkErrorMacro(<< "only 2-D images can be written as GeoTIFF; this one has "
                  << (ext[5] - ext[4] + 1) << " slices");
    return;
  }
  const int nx = ext[1] - ext[0] + 1, ny = ext[3] - ext[2] + 1;

  // 1. The arrays, as (array, component, band description) in band order.
  vtkPointData* pd = input->GetPointData();
  std::vector<std::string> names = this->Impl->ArrayNames;
  if (names.empty())
  {
    for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
    {
      if (pd->GetArrayName(a))
      {
        names.emplace_back(pd->GetArrayName(a));
      }
    }
  }
  if (names.empty())
  {
    vtkErrorMacro(<< "the image has no named point arrays to write to '" << path << "'");
    return;
  }
  struct Band
  {
    vtkDataArray* Array;
    int Component;
    std::string ArrayName, Description;
  };
  std::vector<Band> bands;
  bool anyDouble = false;
  for (const std::string& name : names)
  {
    vtkAbstractArray* abstract = pd->GetAbstractArray(name.c_str());
    if (!abstract)
    {
      vtkErrorMacro(<< "the image has no point array named '" << name << "'");
      return;
    }
    vtkDataArray* array = vtkDataArray::SafeDownCast(abstract);
    if (!array)
    {
      vtkErrorMacro(<< "the point array '" << name << "' is not numeric");
      return;
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
      bands.push_back({ array, c, name, description });
    }
  }

  // 2. Georeference.
  vtkNew<vtkApertureGeoreference> geo;
  const bool hasCRS = geo->SetFromImage(input);
  double gt[6];
  if (hasCRS)
  {
    geo->GetGeoTransform(gt);
  }
  else
  {
    vtkWarningMacro(<< "writing '" << path << "' without a CRS: " << geo->GetErrorMessage());
    double origin[3], spacing[3];
    input->GetOrigin(origin);
    input->GetSpacing(spacing);
    gt[0] = origin[0] + (ext[0] - 0.5) * spacing[0];
    gt[1] = spacing[0];
    gt[2] = 0.0;
    gt[3] = origin[1] + (ext[3] + 0.5) * spacing[1];
    gt[4] = 0.0;
    gt[5] = -spacing[1];
  }

  // 3. Create the file.
  vtkApertureGDALErrorTrap trap;
  std::string compression;
  const char* levelOption = nullptr;
  GDALDriverH driver = static_cast<GDALDriverH>(this->CheckCompression(compression, levelOption));
  if (!driver)
  {
    return; // (reported)
  }
  char** options = nullptr;
  options = CSLSetNameValue(options, "TILED", "YES");
  options = CSLSetNameValue(options, "BLOCKXSIZE", "256");
  options = CSLSetNameValue(options, "BLOCKYSIZE", "256");
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
    const std::string threads =
      this->NumberOfThreads > 0 ? std::to_string(this->NumberOfThreads) : "ALL_CPUS";
    options = CSLSetNameValue(options, "NUM_THREADS", threads.c_str());
  }
  const GDALDataType type = anyDouble ? GDT_Float64 : GDT_Float32;
  GDALDatasetH ds =
    GDALCreate(driver, path.c_str(), nx, ny, static_cast<int>(bands.size()), type, options);
  CSLDestroy(options);
  if (!ds)
  {
    vtkErrorMacro(<< "GDAL cannot create '" << path
                  << "': " << trap.Message("unknown error"));
    return;
  }
  bool ok = GDALSetGeoTransform(ds, gt) == CE_None;
  if (ok && hasCRS)
  {
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    ok = OSRSetFromUserInput(srs, geo->GetCRS()) == OGRERR_NONE &&
      GDALSetSpatialRef(ds, srs) == CE_None;
    OSRRelease(srs);
  }
  for (const auto& kv : this->Impl->Metadata)
  {
    ok = ok && GDALSetMetadataItem(ds, kv.first.c_str(), kv.second.c_str(), nullptr) == CE_None;
  }

  // 4. Bands, written in strips of one tile row in file order (north first), converting on
  //    the fly into a buffer of the file's sample type, and each strip's tiles flushed at once
  //    (compressed on the worker threads): GDAL's block cache never holds more than a strip.
  const int stripRows = 256;
  std::vector<float> stripF;
  std::vector<double> stripD;
  for (size_t b = 0; ok && b < bands.size(); ++b)
  {
    const Band& band = bands[b];
    GDALRasterBandH hb = GDALGetRasterBand(ds, static_cast<int>(b) + 1);
    GDALSetDescription(hb, band.Description.c_str());
    ok = GDALSetRasterNoDataValue(hb, std::numeric_limits<double>::quiet_NaN()) == CE_None;
    for (const auto& item : this->Impl->BandMetadata)
    {
      if (item.Array == band.ArrayName)
      {
        ok = ok && GDALSetMetadataItem(hb, item.Key.c_str(), item.Value.c_str(), nullptr) == CE_None;
      }
    }
    const int nc = band.Array->GetNumberOfComponents();
    // Rows r0 .. r0 + k - 1 of the file (image rows counted from the south) into dst.
    auto fill = [&](auto* dst, int r0, int k) {
      using T = typename std::remove_pointer<decltype(dst)>::type;
      for (int r = 0; r < k; ++r)
      {
        const vtkIdType row = ny - 1 - (r0 + r); // file row r0 + r is image row ny-1-(r0+r)
        T* out = dst + static_cast<size_t>(r) * static_cast<size_t>(nx);
        const vtkIdType first = row * nx;
        if (auto* fa = vtkFloatArray::SafeDownCast(band.Array))
        {
          const float* src = fa->GetPointer(0) + first * nc + band.Component;
          for (int i = 0; i < nx; ++i)
          {
            out[i] = static_cast<T>(src[static_cast<size_t>(i) * nc]);
          }
        }
        else if (auto* da = vtkDoubleArray::SafeDownCast(band.Array))
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
            out[i] = static_cast<T>(band.Array->GetComponent(first + i, band.Component));
          }
        }
      }
    };
    // One strip through a buffer whose element type is the file's sample type.
    auto writeStrip = [&](auto& strip, int r0, int k) {
      strip.resize(static_cast<size_t>(k) * static_cast<size_t>(nx));
      fill(strip.data(), r0, k);
      return GDALRasterIO(hb, GF_Write, 0, r0, nx, k, strip.data(), nx, k, type, 0, 0) == CE_None;
    };
    for (int r0 = 0; ok && r0 < ny; r0 += stripRows)
    {
      const int k = std::min(stripRows, ny - r0);
      ok = (type == GDT_Float32 ? writeStrip(stripF, r0, k) : writeStrip(stripD, r0, k)) &&
        GDALFlushRasterCache(hb) == CE_None;
    }
    this->UpdateProgress(static_cast<double>(b + 1) / static_cast<double>(bands.size()));
  }
  GDALFlushCache(ds);
  const std::string reason = trap.Message("unknown error");
  GDALClose(ds);
  if (!ok || CPLGetLastErrorType() >= CE_Failure)
  {
    VSIUnlink(path.c_str());
    vtkErrorMacro(<< "GDAL failed writing '" << path << "': " << reason);
  }
}

//------------------------------------------------------------------------------
void vtkApertureDEMWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "Compression: " << (this->Compression ? this->Compression : "(none)") << "\n";
  os << indent << "CompressionLevel: " << this->CompressionLevel << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "ArrayNames:";
  for (const auto& n : this->Impl->ArrayNames)
  {
    os << " " << n;
  }
  os << "\n";
  os << indent << "Metadata items: " << this->Impl->Metadata.size() << "\n";
  os << indent << "Band metadata items: " << this->Impl->BandMetadata.size() << "\n";
}
