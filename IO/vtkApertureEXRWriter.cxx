// SPDX-License-Identifier: BSD-3-Clause
#include "vtkApertureEXRWriter.h"

#include "vtkApertureEXRErrorTrap.h"
#include "vtkApertureGeoreference.h"
#include "vtkApertureOutputFile.h"
#include "vtkApertureSMPThreads.h"
#include "vtkApertureStripDriver.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"

#include <libdeflate.h>
#include <openexr.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <limits>
#include <locale>
#include <map>
#include <memory>
#include <new>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkApertureEXRWriter);

// The public enum mirrors exr_compression_t so the value passes straight to OpenEXR.
static_assert(static_cast<int>(vtkApertureEXRWriter::NONE) == EXR_COMPRESSION_NONE &&
    static_cast<int>(vtkApertureEXRWriter::RLE) == EXR_COMPRESSION_RLE &&
    static_cast<int>(vtkApertureEXRWriter::ZIPS) == EXR_COMPRESSION_ZIPS &&
    static_cast<int>(vtkApertureEXRWriter::ZIP) == EXR_COMPRESSION_ZIP &&
    static_cast<int>(vtkApertureEXRWriter::PIZ) == EXR_COMPRESSION_PIZ,
  "vtkApertureEXRWriter::CompressionTypes must match exr_compression_t");

namespace
{
const char* const CompressionNames[] = { "NONE", "RLE", "ZIPS", "ZIP", "PIZ" };
const char* const CRSAttribute = "aperture:crs";
const char* const GeoTransformAttribute = "aperture:geotransform";
// OpenEXR's limit for channel and attribute names without long-name support (EXR_SHORTNAME_MAXLEN).
const size_t ShortNameLength = 31;

// Owns a write context and the temporary file it writes (OpenEXR writing it directly), which
// replaces FileName once complete (Finish). A discard closes the context and removes the
// temporary file: nothing is left behind, an earlier file as it was. The temporary file's name
// is short whatever FileName's length (OpenEXR's own, "tmp.<pid>" + the file's name, failed on
// names near the folder's limit): ".aperture-<pid>-<n>.tmp" in FileName's folder. Through a
// symbolic link FileName's target is replaced (the link stays), keeping its permissions.
struct ContextHandle
{
  exr_context_t H = nullptr;
  std::string Temporary; // the file H writes, until Finish renames it
  std::string Target;    // the file it replaces: FileName, or the target of its links
  int Mode = -1;         // the permissions of the file it replaces, -1 for none
  ContextHandle() = default;
  ContextHandle(const ContextHandle&) = delete;
  ContextHandle& operator=(const ContextHandle&) = delete;
  ~ContextHandle() { this->Discard(); }
  void Name(const std::string& path)
  {
    this->Target = vtkApertureOutputTarget(path);
    this->Mode = vtkApertureExistingMode(this->Target);
    this->Temporary = vtkApertureTemporaryName(this->Target);
  }
  void Discard()
  {
    if (this->H)
    {
      vtkApertureEXRErrorTrap trap; // (its complaints, missing chunks, expected)
      exr_finish(&this->H);
      this->H = nullptr;
    }
    if (!this->Temporary.empty())
    {
      unlink(this->Temporary.c_str());
    }
    this->Temporary.clear();
  }
  // Complete the file and put it in place of `path`; "" or what failed.
  std::string Finish(const std::string& path)
  {
    vtkApertureEXRErrorTrap trap;
    const exr_result_t rv = exr_finish(&this->H);
    this->H = nullptr;
    std::string problem;
    if (rv != EXR_ERR_SUCCESS)
    {
      problem = "OpenEXR failed finishing '" + path + "': " + trap.Message(rv);
    }
    else if (!vtkAperturePutInPlace(this->Temporary, this->Target, this->Mode))
    {
      problem = "cannot put the temporary file '" + this->Temporary + "' in place of '" + path +
        "': " + std::strerror(errno);
    }
    else
    {
      this->Temporary.clear();
    }
    this->Discard(); // (the temporary file, when anything failed)
    return problem;
  }
};

// One output channel: a component of a point array (Array: of the strip being written).
struct Channel
{
  std::string Name;
  std::string ArrayName;
  int Component;
  int Components;
  exr_perceptual_treatment_t Perception;
  vtkDataArray* Array;
};

// Where a strip's rows are: scanline y (0 = the file's top) is image row Top - y, which
// starts at tuple (Top - y - Bottom) * Width + Column of the strip's arrays. The one
// orientation flip of the writer.
struct StripLayout
{
  int Top, Bottom;
  vtkIdType Width, Column;
  vtkIdType First(int y) const
  {
    return (this->Top - y - this->Bottom) * this->Width + this->Column;
  }
};

// Fill `rows` scanlines starting at scanline y0 of one channel (float, nx per row). Returns
// how many finite samples (doubles, or integers as doubles) were beyond the floats: infinite.
uint64_t FillScanlines(
  const Channel& ch, const StripLayout& at, int nx, int y0, int rows, float* dst)
{
  uint64_t overflow = 0;
  const int nc = ch.Array->GetNumberOfComponents();
  auto* fa = vtkFloatArray::SafeDownCast(ch.Array);
  auto* da = vtkDoubleArray::SafeDownCast(ch.Array);
  for (int r = 0; r < rows; ++r)
  {
    const vtkIdType first = at.First(y0 + r);
    float* out = dst + static_cast<size_t>(r) * static_cast<size_t>(nx);
    if (fa)
    {
      const float* src = fa->GetPointer(0) + first * nc + ch.Component;
      for (int i = 0; i < nx; ++i)
      {
        out[i] = src[static_cast<size_t>(i) * nc];
      }
    }
    else if (da)
    {
      const double* src = da->GetPointer(0) + first * nc + ch.Component;
      for (int i = 0; i < nx; ++i)
      {
        const double value = src[static_cast<size_t>(i) * nc];
        out[i] = static_cast<float>(value);
        overflow += std::isinf(out[i]) && std::isfinite(value);
      }
    }
    else
    {
      for (int i = 0; i < nx; ++i)
      {
        const double value = ch.Array->GetComponent(first + i, ch.Component);
        out[i] = static_cast<float>(value);
        overflow += std::isinf(out[i]) && std::isfinite(value);
      }
    }
  }
  return overflow;
}

// The smallest magnitude OpenEXR's float-to-half conversion (round to nearest even) turns
// into an infinity: halfway between the largest half, 65504, and 2^16.
constexpr float HalfOverflow = 65520.0f;

// Values that are written whole before they are read: no zero fill, as std::vector's resize
// would do (on large chunks, zeroing fresh pages cost a third of a ZIP write), and the
// allocation kept for a later request no larger. Throws std::bad_alloc.
template <typename T>
struct Buffer
{
  std::unique_ptr<T[]> Data;
  size_t Size = 0, Capacity = 0;
  T* Resize(size_t n)
  {
    if (n > this->Capacity)
    {
      this->Data.reset(new T[n]);
      this->Capacity = n;
    }
    this->Size = n;
    return this->Data.get();
  }
};

// One chunk of scanlines to encode on a worker thread: its place, its compressed bytes, and
// the outcome (with OpenEXR's message on failure). A batch's jobs are reused by the next
// batch, buffers and all.
struct ChunkJob
{
  exr_chunk_info_t Info;
  int ZipLevel = 0; // ZIP or ZIPS: libdeflate's level; 0: OpenEXR's own compression
  Buffer<uint8_t> Bytes;
  exr_result_t Result = EXR_ERR_SUCCESS;
  std::string Message;
  std::vector<uint64_t> Overflow; // per channel: finite samples written as infinities
};

// The encoding pipeline's last step, instead of writing: keep the compressed bytes (or the
// packed ones, without compression) for the writing thread.
exr_result_t KeepChunk(exr_encode_pipeline_t* encoder)
{
  auto* job = static_cast<ChunkJob*>(encoder->encoding_user_data);
  const auto* bytes = static_cast<const uint8_t*>(encoder->compressed_buffer);
  if (bytes == job->Bytes.Data.get())
  {
    return EXR_ERR_SUCCESS; // (DeflateChunk compressed into them)
  }
  try
  {
    std::memcpy(job->Bytes.Resize(encoder->compressed_bytes), bytes, encoder->compressed_bytes);
  }
  catch (const std::bad_alloc&)
  {
    return EXR_ERR_OUT_OF_MEMORY;
  }
  return EXR_ERR_SUCCESS;
}

// ZIP and ZIPS as OpenEXR defines them, compressed by libdeflate instead of OpenEXR 3.1's zlib
// (2 to 3 times as fast, files 0.2-0.5% larger at level 1): the chunk's bytes are split into
// the even-numbered ones followed by the odd-numbered ones, each byte but the first then
// replaced by its difference from the one before plus 128 (mod 256), and the result compressed
// as one zlib stream; a chunk that does not shrink is stored as it is (its size then equals
// the uncompressed size, which is how readers tell). Any OpenEXR reader decodes it.
exr_result_t DeflateChunk(exr_encode_pipeline_t* encoder)
{
  auto* job = static_cast<ChunkJob*>(encoder->encoding_user_data);
  const auto* packed = static_cast<const uint8_t*>(encoder->packed_buffer);
  const size_t n = encoder->packed_bytes;
  // (the compressor and scratch are made per chunk on purpose, as is EncodeChunk's: kept in
  // each job instead, ZIP writes of a 1024^2 DEM's nine channels took 1.3-1.9 times as long,
  // the same bytes; freed per chunk, malloc hands the memory back still in the cache)
  struct Free
  {
    void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
  };
  std::unique_ptr<libdeflate_compressor, Free> compressor(
    libdeflate_alloc_compressor(job->ZipLevel));
  if (!compressor)
  {
    return EXR_ERR_OUT_OF_MEMORY; // (the level is checked by the writer's property)
  }
  try
  {
    Buffer<uint8_t> scratch;
    uint8_t* const t = scratch.Resize(n);
    uint8_t* even = t;
    uint8_t* odd = t + (n + 1) / 2;
    for (size_t k = 0; k < n; ++k)
    {
      *((k & 1) ? odd++ : even++) = packed[k];
    }
    for (size_t k = n - 1; k > 0; --k) // (back to front: each takes the original before it)
    {
      t[k] = static_cast<uint8_t>(t[k] - t[k - 1] + 128);
    }
    const size_t bound = libdeflate_zlib_compress_bound(compressor.get(), n);
    uint8_t* const out = job->Bytes.Resize(bound);
    const size_t m = libdeflate_zlib_compress(compressor.get(), t, n, out, bound);
    if (m == 0 || m >= n)
    {
      std::memcpy(out, packed, n);
      job->Bytes.Size = n;
    }
    else
    {
      job->Bytes.Size = m;
    }
  }
  catch (const std::bad_alloc&)
  {
    return EXR_ERR_OUT_OF_MEMORY;
  }
  // (ours: a compressed_alloc_size of 0 keeps OpenEXR from freeing it)
  encoder->compressed_buffer = job->Bytes.Data.get();
  encoder->compressed_bytes = job->Bytes.Size;
  encoder->compressed_alloc_size = 0;
  return EXR_ERR_SUCCESS;
}

// Convert and compress one chunk (any thread: after the header is written, OpenEXR's encoding
// calls take no lock and only read the context).
void EncodeChunk(exr_context_t ctx, int part, const std::vector<Channel>& channels,
  const std::map<std::string, size_t>& byName, const StripLayout& at, int nx, ChunkJob& job)
{
  vtkApertureEXRErrorTrap trap; // this thread's messages
  exr_encode_pipeline_t encoder = EXR_ENCODE_PIPELINE_INITIALIZER;
  exr_result_t rv = exr_encoding_initialize(ctx, part, &job.Info, &encoder);
  const bool initialized = rv == EXR_ERR_SUCCESS;
  Buffer<float> scratch; // (every value written by FillScanlines)
  if (initialized)
  {
    try
    {
      scratch.Resize(static_cast<size_t>(job.Info.height) * static_cast<size_t>(nx) *
        channels.size());
    }
    catch (const std::bad_alloc&)
    {
      rv = EXR_ERR_OUT_OF_MEMORY;
    }
  }
  const size_t chunkValues = static_cast<size_t>(job.Info.height) * static_cast<size_t>(nx);
  job.Overflow.assign(channels.size(), 0);
  for (int c = 0; rv == EXR_ERR_SUCCESS && c < encoder.channel_count; ++c)
  {
    exr_coding_channel_info_t& out = encoder.channels[c];
    const auto found = byName.find(out.channel_name ? out.channel_name : "");
    if (found == byName.end())
    {
      rv = EXR_ERR_INCORRECT_CHUNK; // cannot happen: the header holds only our channels
      break;
    }
    float* dst = scratch.Data.get() + found->second * chunkValues;
    uint64_t& overflow = job.Overflow[found->second];
    overflow =
      FillScanlines(channels[found->second], at, nx, job.Info.start_y, job.Info.height, dst);
    if (out.data_type == EXR_PIXEL_HALF)
    {
      for (size_t k = 0; k < chunkValues; ++k)
      {
        overflow += std::fabs(dst[k]) >= HalfOverflow && std::isfinite(dst[k]);
      }
    }
    out.encode_from_ptr = reinterpret_cast<const uint8_t*>(dst);
    out.user_pixel_stride = static_cast<int32_t>(sizeof(float));
    out.user_line_stride = static_cast<int32_t>(sizeof(float)) * nx;
    out.user_bytes_per_element = static_cast<int16_t>(sizeof(float));
    out.user_data_type = EXR_PIXEL_FLOAT;
  }
  if (rv == EXR_ERR_SUCCESS)
  {
    rv = exr_encoding_choose_default_routines(ctx, part, &encoder);
  }
  if (rv == EXR_ERR_SUCCESS)
  {
    encoder.yield_until_ready_fn = nullptr; // (the writing thread keeps the order)
    if (encoder.compress_fn && job.ZipLevel > 0)
    {
      encoder.compress_fn = &DeflateChunk;
    }
    encoder.write_fn = &KeepChunk;
    encoder.encoding_user_data = &job;
    rv = exr_encoding_run(ctx, part, &encoder);
  }
  if (initialized)
  {
    exr_encoding_destroy(ctx, &encoder);
  }
  job.Result = rv;
  if (rv != EXR_ERR_SUCCESS)
  {
    job.Message = trap.Message(rv);
  }
}
} // namespace

struct vtkApertureEXRWriter::Internals
{
  std::vector<std::string> ArrayNames;
  std::vector<std::pair<std::string, std::string>> Metadata;

  // The file being written, from BeginStrips to EndStrips.
  ContextHandle Context;
  std::string Path;
  std::vector<Channel> Channels;
  std::map<std::string, size_t> ByName;
  int Part = 0;
  int LinesPerChunk = 1;
  int ZipLevel = 0; // CompressionLevel for ZIP and ZIPS, else 0 (ChunkJob::ZipLevel)
  int Whole[6] = { 0, -1, 0, -1, 0, 0 };
  int NextRow = -1;    // the next image row to write (north first)
  std::vector<uint64_t> Overflow; // per channel: finite samples written as infinities
  bool Failed = false;  // a strip failed (reported)
  bool Written = false; // the last WriteData wrote its file
};

//------------------------------------------------------------------------------
vtkApertureEXRWriter::vtkApertureEXRWriter()
  : FileName(nullptr)
  , ColorArrayName(nullptr)
  , PixelType(FLOAT)
  , Compression(ZIP)
  , CompressionLevel(1)
  , NumberOfThreads(0)
  , NumberOfThreadsUsed(0)
  , StripRows(0)
  , Impl(new Internals)
{
}

//------------------------------------------------------------------------------
vtkApertureEXRWriter::~vtkApertureEXRWriter()
{
  this->SetFileName(nullptr);
  this->SetColorArrayName(nullptr);
  delete this->Impl;
}

//------------------------------------------------------------------------------
void vtkApertureEXRWriter::AddArrayName(const char* name)
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
void vtkApertureEXRWriter::ClearArrayNames()
{
  if (!this->Impl->ArrayNames.empty())
  {
    this->Impl->ArrayNames.clear();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
int vtkApertureEXRWriter::GetNumberOfArrayNames()
{
  return static_cast<int>(this->Impl->ArrayNames.size());
}

//------------------------------------------------------------------------------
const char* vtkApertureEXRWriter::GetArrayName(int i)
{
  if (i < 0 || i >= this->GetNumberOfArrayNames())
  {
    return nullptr;
  }
  return this->Impl->ArrayNames[static_cast<size_t>(i)].c_str();
}

//------------------------------------------------------------------------------
const char* vtkApertureEXRWriter::GetPixelTypeAsString()
{
  return this->PixelType == HALF ? "HALF" : "FLOAT";
}

//------------------------------------------------------------------------------
void vtkApertureEXRWriter::SetCompression(const char* name)
{
  std::string upper(name ? name : "");
  std::transform(upper.begin(), upper.end(), upper.begin(),
    [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  for (int k = NONE; k <= PIZ; ++k)
  {
    if (upper == CompressionNames[k])
    {
      this->SetCompression(k);
      return;
    }
  }
  vtkErrorMacro(<< "unknown OpenEXR compression '" << (name ? name : "")
                << "'; use NONE, RLE, ZIPS, ZIP or PIZ (keeping " << this->GetCompressionAsString()
                << ")");
}

//------------------------------------------------------------------------------
const char* vtkApertureEXRWriter::GetCompressionAsString()
{
  return CompressionNames[std::min(std::max(this->Compression, 0), static_cast<int>(PIZ))];
}

//------------------------------------------------------------------------------
void vtkApertureEXRWriter::AddMetadata(const char* key, const char* value)
{
  const size_t length = key ? std::strlen(key) : 0;
  if (length == 0 || length > 255)
  {
    // (said here rather than dropped, or refused by OpenEXR at the Write)
    vtkErrorMacro(<< "AddMetadata: a key has 1 to 255 characters, not " << length
                  << "; the item is not added");
    return;
  }
  vtkApertureReplaceOrAppend(this->Impl->Metadata, { key, value ? value : "" },
    [key](const std::pair<std::string, std::string>& kv) { return kv.first == key; });
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkApertureEXRWriter::ClearMetadata()
{
  if (!this->Impl->Metadata.empty())
  {
    this->Impl->Metadata.clear();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkImageData* vtkApertureEXRWriter::GetInput()
{
  return vtkImageData::SafeDownCast(this->Superclass::GetInput());
}

//------------------------------------------------------------------------------
int vtkApertureEXRWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

//------------------------------------------------------------------------------
void vtkApertureEXRWriter::WriteData()
{
  vtkImageData* input = this->GetInput();
  int ext[6];
  vtkApertureWrittenExtent(input, this->GetInputInformation(), ext);
  if (this->BeginStrips(input, ext) && this->WriteStrip(input))
  {
    this->Impl->Written = this->EndStrips() != 0;
  }
  else
  {
    this->AbandonStrips();
  }
}

//------------------------------------------------------------------------------
int vtkApertureEXRWriter::Write()
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
  // whole EXR chunks (1, 16 or 32 scanlines) in every strip
  const int ok =
    vtkApertureWriteInStrips(this, this->StripRows, 32, this->FileName);
  this->SetErrorCode(vtkApertureWriteErrorCode(ok, this->GetErrorCode()));
  return ok;
}

//------------------------------------------------------------------------------
void vtkApertureEXRWriter::AbandonStrips()
{
  for (Channel& ch : this->Impl->Channels)
  {
    ch.Array = nullptr;
  }
  this->Impl->Context.Discard();
}

//------------------------------------------------------------------------------
int vtkApertureEXRWriter::GetNextStripRow()
{
  return this->Impl->NextRow;
}

//------------------------------------------------------------------------------
bool vtkApertureEXRWriter::ResolveChannels(vtkImageData* input, const std::string& path)
{
  Internals& d = *this->Impl;
  vtkPointData* pd = input->GetPointData();
  const vtkIdType points = input->GetNumberOfPoints();
  auto fetch = [&](const std::string& name, const char* role) -> vtkDataArray* {
    vtkAbstractArray* abstract = pd->GetAbstractArray(name.c_str());
    if (!abstract)
    {
      vtkErrorMacro(<< "the image has no point array named '" << name << "'" << role
                    << " to write to '" << path << "'");
      return nullptr;
    }
    vtkDataArray* array = vtkDataArray::SafeDownCast(abstract);
    if (!array)
    {
      vtkErrorMacro(<< "the point array '" << name << "'" << role << " is not numeric; it "
                    << "cannot be written to '" << path << "'");
      return nullptr;
    }
    if (array->GetNumberOfTuples() != points)
    {
      vtkErrorMacro(<< "the point array '" << name << "' has " << array->GetNumberOfTuples()
                    << " tuples but the image has " << points << " points; '" << path
                    << "' not written");
      return nullptr;
    }
    return array;
  };
  if (!d.Channels.empty())
  {
    // a later strip: the arrays the first one gave, with as many components
    for (Channel& ch : d.Channels)
    {
      ch.Array = fetch(ch.ArrayName, "");
      if (!ch.Array)
      {
        return false;
      }
      if (ch.Array->GetNumberOfComponents() != ch.Components)
      {
        vtkErrorMacro(<< "the point array '" << ch.ArrayName << "' has "
                      << ch.Array->GetNumberOfComponents() << " components in this strip and "
                      << ch.Components << " in the first; '" << path << "' not written");
        return false;
      }
    }
    return true;
  }

  // The first strip: the color array as R, G, B (, A), then the other arrays.
  std::vector<Channel>& channels = d.Channels;
  const std::string colorName = this->ColorArrayName ? this->ColorArrayName : "";
  if (!colorName.empty())
  {
    vtkDataArray* color = fetch(colorName, " (ColorArrayName)");
    if (!color)
    {
      return false;
    }
    const int nc = color->GetNumberOfComponents();
    if (nc != 3 && nc != 4)
    {
      vtkErrorMacro(<< "the color array '" << colorName << "' has " << nc << " component"
                    << (nc == 1 ? "" : "s") << "; it needs 3 (RGB) or 4 (RGBA) to be written to '"
                    << path << "'");
      return false;
    }
    const char* rgba[4] = { "R", "G", "B", "A" };
    for (int c = 0; c < nc; ++c)
    {
      channels.push_back({ rgba[c], colorName, c, nc, EXR_PERCEPTUALLY_LOGARITHMIC, color });
    }
  }
  std::vector<std::string> names = d.ArrayNames;
  if (names.empty())
  {
    for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
    {
      // GetArray() returns only numeric arrays: the others are skipped here.
      vtkDataArray* array = pd->GetArray(a);
      if (array && array->GetName() && *array->GetName())
      {
        names.emplace_back(array->GetName());
      }
    }
  }
  for (const std::string& name : names)
  {
    if (name == colorName)
    {
      continue; // written as R, G, B (, A) above
    }
    vtkDataArray* array = fetch(name, "");
    if (!array)
    {
      return false;
    }
    const int nc = array->GetNumberOfComponents();
    for (int c = 0; c < nc; ++c)
    {
      std::string channel = name;
      if (nc > 1)
      {
        const char* cname = array->GetComponentName(c);
        std::string component = (cname && *cname) ? std::string(cname) : std::to_string(c);
        std::replace(component.begin(), component.end(), '.', '_'); // (the layer is the array)
        channel += "." + component;
      }
      channels.push_back({ channel, name, c, nc, EXR_PERCEPTUALLY_LINEAR, array });
    }
  }
  if (channels.empty())
  {
    bool unnamed = false; // numeric arrays, all without a name
    for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
    {
      unnamed = unnamed || pd->GetArray(a) != nullptr;
    }
    vtkErrorMacro(<< "the image has no " << (unnamed ? "named " : "")
                  << "numeric point arrays to write to '" << path << "'"
                  << (unnamed ? " (a channel is named by its array: name the array, such as "
                                "'Elevation')"
                              : ""));
    return false;
  }
  for (size_t k = 0; k < channels.size(); ++k)
  {
    if (!d.ByName.emplace(channels[k].Name, k).second)
    {
      vtkErrorMacro(<< "two arrays give the channel name '" << channels[k].Name << "' (array '"
                    << channels[k].ArrayName << "'); rename one before writing '" << path
                    << "'");
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
int vtkApertureEXRWriter::BeginStrips(vtkImageData* input, const int whole[6])
{
  Internals& d = *this->Impl;
  this->NumberOfThreadsUsed = 0;
  d.Context.Discard(); // (a file begun and never ended)
  d.Channels.clear();
  d.ByName.clear();
  d.Overflow.clear();
  d.Failed = false;
  d.NextRow = whole[2] - 1;
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro(<< "no file name was set");
    return 0;
  }
  const std::string path(this->FileName);
  std::string what;
  if (!vtkApertureOutputReplaceable(path, what))
  {
    vtkErrorMacro(<< "'" << path << "' is " << what << ", not a file an EXR can be written to");
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
    return 0;
  }
  if (vtkApertureOutputReadOnly(path))
  {
    vtkErrorMacro(<< "cannot write '" << path << "': the file exists and is read-only");
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
    return 0;
  }
  if (!input || input->GetNumberOfPoints() == 0 || whole[1] < whole[0] || whole[3] < whole[2])
  {
    vtkErrorMacro(<< "no input image to write to '" << path << "'");
    return 0;
  }
  if (whole[4] != whole[5])
  {
    vtkErrorMacro(<< "only 2-D images can be written to '" << path << "'; this one has "
                  << (whole[5] - whole[4] + 1) << " slices");
    return 0;
  }
  const int nx = whole[1] - whole[0] + 1, ny = whole[3] - whole[2] + 1;
  // The encoder takes the row stride in bytes as a 32-bit int.
  if (nx > std::numeric_limits<int32_t>::max() / static_cast<int>(sizeof(float)))
  {
    vtkErrorMacro(<< "the image is " << nx << " columns wide, too wide for '" << path << "'");
    return 0;
  }

  // 1. Channels.
  if (!this->ResolveChannels(input, path))
  {
    d.Channels.clear();
    return 0;
  }
  size_t longest = 0;
  for (const Channel& ch : d.Channels)
  {
    longest = std::max(longest, ch.Name.size());
  }

  // 2. Header attributes: metadata, then the georeference (which wins on equal keys).
  std::vector<std::pair<std::string, std::string>> attributes = d.Metadata;
  if (vtkApertureGeoreference::GetAttachedCRS(input))
  {
    // (the image's geometry is written: one by hand never set was written without a word,
    // until 2026-12-07)
    vtkApertureGeoreference::WarnOfDefaultGeometry(this, input);
    vtkNew<vtkApertureGeoreference> geo;
    if (!geo->SetFromImage(input) || !*geo->GetHorizontalCRS())
    {
      vtkErrorMacro(<< "the image has a CRS but its georeference cannot be written to '" << path
                    << "': " << geo->GetErrorMessage());
      return 0;
    }
    // the grid of `whole`, which a strip is part of
    double origin[3], spacing[3], gt[6];
    input->GetOrigin(origin);
    input->GetSpacing(spacing);
    geo->SetGrid(origin[0] + whole[0] * spacing[0], origin[1] + whole[2] * spacing[1],
      spacing[0], spacing[1], nx, ny);
    geo->GetGeoTransform(gt);
    // (of the whole extent, which a strip is part of)
    const std::string edges = vtkApertureGeoTransformProblem(path, gt, nx, ny, origin, spacing);
    if (!edges.empty())
    {
      vtkErrorMacro(<< edges);
      return 0;
    }
    // %.17g (round-trips every double), in the classic locale so that a program locale with
    // a decimal comma cannot merge the numbers.
    std::ostringstream text;
    text.imbue(std::locale::classic());
    text.precision(17);
    for (int k = 0; k < 6; ++k)
    {
      text << (k ? "," : "") << gt[k];
    }
    // (the horizontal part of a compound CRS, as the GeoTIFF writer's: the values are no
    // heights in its height unit)
    attributes.emplace_back(CRSAttribute, geo->GetHorizontalCRS());
    attributes.emplace_back(GeoTransformAttribute, text.str());
  }
  for (const auto& kv : attributes)
  {
    longest = std::max(longest, kv.first.size());
  }

  // 3. Create the file (a temporary one, put in place when complete) and its header.
  vtkApertureEXRErrorTrap trap;
  const exr_context_initializer_t init = vtkApertureEXRErrorTrap::Initializer();
  d.Context.Name(path);
  exr_result_t rv = exr_start_write(
    &d.Context.H, d.Context.Temporary.c_str(), EXR_WRITE_FILE_DIRECTLY, &init);
  if (rv != EXR_ERR_SUCCESS)
  {
    d.Context.H = nullptr;
    vtkErrorMacro(<< "OpenEXR cannot create '" << path << "' (as its temporary file '"
                  << d.Context.Temporary << "' first): " << trap.Message(rv));
    d.Context.Discard();
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
    return 0;
  }
  exr_context_t ctx = d.Context.H;
  const exr_pixel_type_t type = this->PixelType == HALF ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT;
  rv = exr_add_part(ctx, "", EXR_STORAGE_SCANLINE, &d.Part);
  if (rv == EXR_ERR_SUCCESS)
  {
    // Data and display window (0, 0) - (nx-1, ny-1), increasing-y line order, aspect 1.
    rv = exr_initialize_required_attr_simple(
      ctx, d.Part, nx, ny, static_cast<exr_compression_t>(this->Compression));
  }
  if (rv == EXR_ERR_SUCCESS && longest > ShortNameLength)
  {
    rv = exr_set_longname_support(ctx, 1);
  }
  for (size_t k = 0; rv == EXR_ERR_SUCCESS && k < d.Channels.size(); ++k)
  {
    rv = exr_add_channel(ctx, d.Part, d.Channels[k].Name.c_str(), type, d.Channels[k].Perception,
      1, 1);
  }
  for (size_t k = 0; rv == EXR_ERR_SUCCESS && k < attributes.size(); ++k)
  {
    rv = exr_attr_set_string(
      ctx, d.Part, attributes[k].first.c_str(), attributes[k].second.c_str());
  }
  if (rv == EXR_ERR_SUCCESS)
  {
    rv = exr_write_header(ctx);
  }
  if (rv == EXR_ERR_SUCCESS)
  {
    rv = exr_get_scanlines_per_chunk(ctx, d.Part, &d.LinesPerChunk);
  }
  if (rv != EXR_ERR_SUCCESS)
  {
    vtkErrorMacro(<< "OpenEXR failed writing the header of '" << path << "': " << trap.Message(rv));
    d.Context.Discard();
    return 0;
  }
  d.Path = path;
  std::copy(whole, whole + 6, d.Whole);
  d.NextRow = whole[3];
  d.ZipLevel = this->Compression == ZIP || this->Compression == ZIPS ? this->CompressionLevel : 0;
  this->UpdateProgress(0.0); // (progress starts at 0, as a whole write's does)
  return 1;
}

//------------------------------------------------------------------------------
int vtkApertureEXRWriter::WriteStrip(vtkImageData* strip)
{
  Internals& d = *this->Impl;
  if (!d.Context.H || d.Failed)
  {
    vtkErrorMacro(<< (d.Failed ? "a strip failed; EndStrips() removes the file"
                               : "no file begun: call BeginStrips() first"));
    return 0;
  }
  const int* whole = d.Whole;
  const std::string& path = d.Path;
  d.Failed = true; // until written
  int j0 = 0;
  if (!vtkApertureStripRows(this, strip, whole, d.NextRow, d.LinesPerChunk, "a chunk", path, j0))
  {
    return 0;
  }
  // Scanlines y0 .. y1 - 1: image rows NextRow down to j0.
  const int nx = whole[1] - whole[0] + 1, ny = whole[3] - whole[2] + 1;
  const int lines = d.LinesPerChunk;
  const int y0 = whole[3] - d.NextRow, y1 = whole[3] - j0 + 1;
  int ext[6];
  strip->GetExtent(ext);
  if (!this->ResolveChannels(strip, path))
  {
    return 0;
  }
  const StripLayout at{ whole[3], ext[2], static_cast<vtkIdType>(ext[1]) - ext[0] + 1,
    static_cast<vtkIdType>(whole[0]) - ext[0] };

  // Scanlines in batches of chunks, top (north) first: the worker threads convert each
  // chunk's channels to float in their own scratch (the encoder converts to HALF when asked)
  // and compress it into the chunk's buffer; this thread then writes the batch in order.
  // Compression is per chunk and deterministic, so the bytes do not depend on the threads.
  vtkApertureEXRErrorTrap trap;
  exr_context_t ctx = d.Context.H;
  const int chunkCount = (ny + lines - 1) / lines;
  const int firstChunk = y0 / lines, endChunk = (y1 + lines - 1) / lines;
  const size_t chunkValues = static_cast<size_t>(lines) * static_cast<size_t>(nx);
  const size_t chunkBytes = chunkValues * d.Channels.size() * sizeof(float);
  const size_t batchBytes = size_t(64) << 20; // of scratch and compressed chunks together
  const int batch =
    static_cast<int>(std::max<size_t>(1, std::min<size_t>(256, batchBytes / (2 * chunkBytes))));
  std::vector<ChunkJob> jobs;
  std::string chunkMessage; // a worker's OpenEXR message for a failed chunk
  exr_result_t rv = EXR_ERR_SUCCESS;
  bool aborted = false;
  vtkApertureThreadTally tally;
  const vtkSMPTools::Config threads = vtkApertureSMPConfig(this->NumberOfThreads);
  try
  {
    vtkApertureSMPScope(threads, [&]() {
      for (int first = firstChunk; rv == EXR_ERR_SUCCESS && first < endChunk; first += batch)
      {
        const int count = std::min(batch, endChunk - first);
        jobs.resize(std::max(jobs.size(), static_cast<size_t>(count)));
        for (int k = 0; rv == EXR_ERR_SUCCESS && k < count; ++k)
        {
          ChunkJob& job = jobs[static_cast<size_t>(k)];
          job.ZipLevel = d.ZipLevel;
          job.Result = EXR_ERR_SUCCESS;
          job.Message.clear();
          rv = exr_write_scanline_chunk_info(ctx, d.Part, (first + k) * lines, &job.Info);
        }
        if (rv != EXR_ERR_SUCCESS)
        {
          break;
        }
        vtkSMPTools::For(0, count, [&](vtkIdType begin, vtkIdType end) {
          tally.Note();
          for (vtkIdType k = begin; k < end; ++k)
          {
            EncodeChunk(ctx, d.Part, d.Channels, d.ByName, at, nx, jobs[static_cast<size_t>(k)]);
          }
        });
        if (this->GetAbortExecute())
        {
          aborted = true; // (before writing: an aborted file never holds every chunk)
          break;
        }
        for (int k = 0; rv == EXR_ERR_SUCCESS && k < count; ++k)
        {
          ChunkJob& job = jobs[static_cast<size_t>(k)];
          rv = job.Result;
          if (rv == EXR_ERR_SUCCESS)
          {
            d.Overflow.resize(job.Overflow.size());
            for (size_t c = 0; c < job.Overflow.size(); ++c)
            {
              d.Overflow[c] += job.Overflow[c];
            }
            rv = exr_write_scanline_chunk(
              ctx, d.Part, job.Info.start_y, job.Bytes.Data.get(), job.Bytes.Size);
          }
          else
          {
            chunkMessage = job.Message;
          }
        }
        this->UpdateProgress(static_cast<double>(first + count) / chunkCount);
        if (rv == EXR_ERR_SUCCESS && this->GetAbortExecute())
        {
          aborted = true; // (asked at this event, the last one too: as the GeoTIFF writer)
          break;
        }
      }
    });
  }
  catch (const std::system_error& e)
  {
    // (the STDThread backend's std::thread, when the system refuses a thread)
    vtkErrorMacro(<< "writing '" << path
                  << "': " << vtkApertureThreadsRefused(threads.MaxNumberOfThreads, e));
    return 0;
  }
  this->NumberOfThreadsUsed = std::max(this->NumberOfThreadsUsed, tally.Count());
  jobs.clear();
  if (aborted)
  {
    vtkErrorMacro(<< "writing '" << path << "' was aborted");
    return 0;
  }
  if (rv != EXR_ERR_SUCCESS)
  {
    vtkErrorMacro(<< "OpenEXR failed writing '" << path
                  << "': " << (chunkMessage.empty() ? trap.Message(rv) : chunkMessage));
    return 0;
  }
  d.NextRow = whole[3] - y1;
  d.Failed = false;
  return 1;
}

//------------------------------------------------------------------------------
int vtkApertureEXRWriter::EndStrips()
{
  Internals& d = *this->Impl;
  for (Channel& ch : d.Channels)
  {
    ch.Array = nullptr; // (the last strip's arrays are not kept)
  }
  if (!d.Context.H)
  {
    return 0; // (nothing begun, or BeginStrips failed: reported)
  }
  if (!vtkApertureStripsComplete(this, d.Failed, d.NextRow, d.Whole, d.Path))
  {
    d.Context.Discard();
    return 0;
  }
  // Offsets table, close, and put the temporary file in place of FileName.
  const std::string problem = d.Context.Finish(d.Path);
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return 0;
  }
  const std::string stale = vtkApertureRemoveStaleSidecars(d.Path, d.Context.Target);
  if (!stale.empty())
  {
    vtkWarningMacro(<< "wrote '" << d.Path << "', but " << stale);
  }
  std::ostringstream overflow; // "1 in channel 'A', 3 in 'B'"
  for (size_t c = 0; c < d.Overflow.size() && c < d.Channels.size(); ++c)
  {
    if (d.Overflow[c] > 0)
    {
      const bool first = overflow.tellp() == 0;
      overflow << (first ? "" : ", ") << d.Overflow[c] << (first ? " in channel '" : " in '")
               << d.Channels[c].Name << "'";
    }
  }
  if (overflow.tellp() > 0)
  {
    const bool half = this->PixelType == HALF;
    vtkWarningMacro(<< "wrote '" << d.Path << "' with infinities for finite samples beyond "
                    << (half ? "HALF's largest number, 65504" : "the largest float, 3.4e38")
                    << ": " << overflow.str() << (half ? "; PixelType FLOAT keeps them" : ""));
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkApertureEXRWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "ArrayNames:";
  for (const auto& n : this->Impl->ArrayNames)
  {
    os << " " << n;
  }
  os << (this->Impl->ArrayNames.empty() ? " (all)\n" : "\n");
  os << indent << "ColorArrayName: " << (this->ColorArrayName ? this->ColorArrayName : "(none)")
     << "\n";
  os << indent << "PixelType: " << this->GetPixelTypeAsString() << "\n";
  os << indent << "Compression: " << this->GetCompressionAsString() << "\n";
  os << indent << "CompressionLevel: " << this->CompressionLevel << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "StripRows: " << this->StripRows << "\n";
  os << indent << "NumberOfThreadsUsed: " << this->NumberOfThreadsUsed << "\n";
  os << indent << "Metadata: " << this->Impl->Metadata.size() << " items\n";
  for (const auto& kv : this->Impl->Metadata)
  {
    os << indent.GetNextIndent() << kv.first << " = " << kv.second << "\n";
  }
}
