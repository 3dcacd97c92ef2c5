// SPDX-License-Identifier: BSD-3-Clause
#include "vtkApertureEXRWriter.h"

#include "vtkApertureGeoreference.h"
#include "vtkApertureSMPThreads.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkStringArray.h"

#include <openexr.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <limits>
#include <locale>
#include <map>
#include <new>
#include <sstream>
#include <string>
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

// OpenEXR reports errors through a callback given when a context is created, on the thread
// that made the failing call; its default callback prints to stderr. The callback cannot reach
// this writer through exr_get_user_data(): in write mode that call takes the context lock the
// failing call already holds, and deadlocks. So the calls run under a trap that registers
// itself for the current thread and keeps the last message.
class ErrorTrap
{
public:
  ErrorTrap()
    : Previous(Current)
  {
    Current = this;
  }
  ~ErrorTrap() { Current = this->Previous; }
  ErrorTrap(const ErrorTrap&) = delete;
  ErrorTrap& operator=(const ErrorTrap&) = delete;

  static void Handler(exr_const_context_t, exr_result_t code, const char* message)
  {
    if (Current)
    {
      Current->Last = (message && *message) ? message : exr_get_default_error_message(code);
    }
  }

  // Initializer for every context: our handler instead of the printing default.
  static exr_context_initializer_t Initializer()
  {
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = &ErrorTrap::Handler;
    return init;
  }

  // Text for a failed call: the handler's message, else OpenEXR's text for the code.
  std::string Message(exr_result_t code) const
  {
    return this->Last.empty() ? std::string(exr_get_default_error_message(code)) : this->Last;
  }

private:
  static thread_local ErrorTrap* Current;
  ErrorTrap* Previous;
  std::string Last;
};
thread_local ErrorTrap* ErrorTrap::Current = nullptr;

// Owns a write context. Finishing a context whose image was not completely written makes
// OpenEXR delete its temporary file, so an early return leaves nothing behind.
struct ContextHandle
{
  exr_context_t H = nullptr;
  ContextHandle() = default;
  ContextHandle(const ContextHandle&) = delete;
  ContextHandle& operator=(const ContextHandle&) = delete;
  ~ContextHandle()
  {
    if (this->H)
    {
      exr_finish(&this->H);
    }
  }
};

// One output channel: a component of a point array.
struct Channel
{
  std::string Name;
  vtkDataArray* Array;
  int Component;
  exr_perceptual_treatment_t Perception;
};

// Fill `rows` scanlines starting at scanline y0 of one channel (float, nx per row). Scanline y
// is VTK row ny-1-y: the one orientation flip of the writer.
void FillScanlines(const Channel& ch, int nx, int ny, int y0, int rows, float* dst)
{
  const int nc = ch.Array->GetNumberOfComponents();
  auto* fa = vtkFloatArray::SafeDownCast(ch.Array);
  auto* da = vtkDoubleArray::SafeDownCast(ch.Array);
  for (int r = 0; r < rows; ++r)
  {
    const vtkIdType first = static_cast<vtkIdType>(ny - 1 - (y0 + r)) * nx;
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
        out[i] = static_cast<float>(src[static_cast<size_t>(i) * nc]);
      }
    }
    else
    {
      for (int i = 0; i < nx; ++i)
      {
        out[i] = static_cast<float>(ch.Array->GetComponent(first + i, ch.Component));
      }
    }
  }
}

// One chunk of scanlines to encode on a worker thread: its place, its compressed bytes, and
// the outcome (with OpenEXR's message on failure).
struct ChunkJob
{
  exr_chunk_info_t Info;
  std::vector<uint8_t> Bytes;
  exr_result_t Result = EXR_ERR_SUCCESS;
  std::string Message;
};

// The encoding pipeline's last step, instead of writing: keep the compressed bytes (or the
// packed ones, without compression) for the writing thread.
exr_result_t KeepChunk(exr_encode_pipeline_t* encoder)
{
  auto* job = static_cast<ChunkJob*>(encoder->encoding_user_data);
  const auto* bytes = static_cast<const uint8_t*>(encoder->compressed_buffer);
  try
  {
    job->Bytes.assign(bytes, bytes + encoder->compressed_bytes);
  }
  catch (const std::bad_alloc&)
  {
    return EXR_ERR_OUT_OF_MEMORY;
  }
  return EXR_ERR_SUCCESS;
}

// Convert and compress one chunk (any thread: after the header is written, OpenEXR's encoding
// calls take no lock and only read the context).
void EncodeChunk(exr_context_t ctx, int part, const std::vector<Channel>& channels,
  const std::map<std::string, size_t>& byName, int nx, int ny, ChunkJob& job)
{
  ErrorTrap trap; // this thread's messages
  exr_encode_pipeline_t encoder = EXR_ENCODE_PIPELINE_INITIALIZER;
  exr_result_t rv = exr_encoding_initialize(ctx, part, &job.Info, &encoder);
  const bool initialized = rv == EXR_ERR_SUCCESS;
  std::vector<float> scratch;
  if (initialized)
  {
    try
    {
      scratch.resize(static_cast<size_t>(job.Info.height) * static_cast<size_t>(nx) *
        channels.size());
    }
    catch (const std::bad_alloc&)
    {
      rv = EXR_ERR_OUT_OF_MEMORY;
    }
  }
  const size_t chunkValues = static_cast<size_t>(job.Info.height) * static_cast<size_t>(nx);
  for (int c = 0; rv == EXR_ERR_SUCCESS && c < encoder.channel_count; ++c)
  {
    exr_coding_channel_info_t& out = encoder.channels[c];
    const auto found = byName.find(out.channel_name ? out.channel_name : "");
    if (found == byName.end())
    {
      rv = EXR_ERR_INCORRECT_CHUNK; // cannot happen: the header holds only our channels
      break;
    }
    float* dst = scratch.data() + found->second * chunkValues;
    FillScanlines(channels[found->second], nx, ny, job.Info.start_y, job.Info.height, dst);
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
};

//------------------------------------------------------------------------------
vtkApertureEXRWriter::vtkApertureEXRWriter()
  : FileName(nullptr)
  , ColorArrayName(nullptr)
  , PixelType(FLOAT)
  , Compression(ZIP)
  , NumberOfThreads(0)
  , NumberOfThreadsUsed(0)
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
  if (name && *name)
  {
    this->Impl->ArrayNames.emplace_back(name);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkApertureEXRWriter::ClearArrayNames()
{
  this->Impl->ArrayNames.clear();
  this->Modified();
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
  if (key && *key)
  {
    this->Impl->Metadata.emplace_back(key, value ? value : "");
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkApertureEXRWriter::ClearMetadata()
{
  this->Impl->Metadata.clear();
  this->Modified();
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
  this->NumberOfThreadsUsed = 0;
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
    vtkErrorMacro(<< "only 2-D images can be written to '" << path << "'; this one has "
                  << (ext[5] - ext[4] + 1) << " slices");
    return;
  }
  const int nx = ext[1] - ext[0] + 1, ny = ext[3] - ext[2] + 1;
  // The encoder takes the row stride in bytes as a 32-bit int.
  if (nx > std::numeric_limits<int32_t>::max() / static_cast<int>(sizeof(float)))
  {
    vtkErrorMacro(<< "the image is " << nx << " columns wide, too wide for '" << path << "'");
    return;
  }
  const vtkIdType points = static_cast<vtkIdType>(nx) * ny;

  // 1. Channels: the color array as R, G, B (, A), then the other arrays.
  vtkPointData* pd = input->GetPointData();
  std::vector<Channel> channels;
  const std::string colorName = this->ColorArrayName ? this->ColorArrayName : "";
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
  if (!colorName.empty())
  {
    vtkDataArray* color = fetch(colorName, " (ColorArrayName)");
    if (!color)
    {
      return;
    }
    const int nc = color->GetNumberOfComponents();
    if (nc != 3 && nc != 4)
    {
      vtkErrorMacro(<< "the color array '" << colorName << "' has " << nc << " component"
                    << (nc == 1 ? "" : "s") << "; it needs 3 (RGB) or 4 (RGBA) to be written to '"
                    << path << "'");
      return;
    }
    const char* rgba[4] = { "R", "G", "B", "A" };
    for (int c = 0; c < nc; ++c)
    {
      channels.push_back({ rgba[c], color, c, EXR_PERCEPTUALLY_LOGARITHMIC });
    }
  }
  std::vector<std::string> names = this->Impl->ArrayNames;
  const bool all = names.empty();
  if (all)
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
      return;
    }
    const int nc = array->GetNumberOfComponents();
    for (int c = 0; c < nc; ++c)
    {
      std::string channel = name;
      if (nc > 1)
      {
        const char* cname = array->GetComponentName(c);
        channel += "." + ((cname && *cname) ? std::string(cname) : std::to_string(c));
      }
      channels.push_back({ channel, array, c, EXR_PERCEPTUALLY_LINEAR });
    }
  }
  if (channels.empty())
  {
    vtkErrorMacro(<< "the image has no numeric point arrays to write to '" << path << "'");
    return;
  }
  std::map<std::string, size_t> byName;
  size_t longest = 0;
  for (size_t k = 0; k < channels.size(); ++k)
  {
    if (!byName.emplace(channels[k].Name, k).second)
    {
      vtkErrorMacro(<< "two arrays give the channel name '" << channels[k].Name << "' (array '"
                    << channels[k].Array->GetName() << "'); rename one before writing '" << path
                    << "'");
      return;
    }
    longest = std::max(longest, channels[k].Name.size());
  }

  // 2. Header attributes: metadata, then the georeference (which wins on equal keys).
  std::vector<std::pair<std::string, std::string>> attributes = this->Impl->Metadata;
  vtkStringArray* crsArray = vtkStringArray::SafeDownCast(
    input->GetFieldData()->GetAbstractArray(vtkApertureGeoreference::GetCRSArrayName()));
  if (crsArray && crsArray->GetNumberOfValues() > 0 && !crsArray->GetValue(0).empty())
  {
    vtkNew<vtkApertureGeoreference> geo;
    if (!geo->SetFromImage(input))
    {
      vtkErrorMacro(<< "the image has a CRS but its georeference cannot be written to '" << path
                    << "': " << geo->GetErrorMessage());
      return;
    }
    double gt[6];
    geo->GetGeoTransform(gt);
    // %.17g (round-trips every double), in the classic locale so that a program locale with
    // a decimal comma cannot merge the numbers.
    std::ostringstream text;
    text.imbue(std::locale::classic());
    text.precision(17);
    for (int k = 0; k < 6; ++k)
    {
      text << (k ? "," : "") << gt[k];
    }
    attributes.emplace_back(CRSAttribute, geo->GetCRS());
    attributes.emplace_back(GeoTransformAttribute, text.str());
  }
  for (const auto& kv : attributes)
  {
    longest = std::max(longest, kv.first.size());
  }

  // 3. Create the file (a temporary one, renamed by exr_finish on success) and its header.
  ErrorTrap trap;
  ContextHandle ctx;
  const exr_context_initializer_t init = ErrorTrap::Initializer();
  exr_result_t rv = exr_start_write(&ctx.H, path.c_str(), EXR_INTERMEDIATE_TEMP_FILE, &init);
  if (rv != EXR_ERR_SUCCESS)
  {
    vtkErrorMacro(<< "OpenEXR cannot create '" << path << "': " << trap.Message(rv));
    return;
  }
  int part = 0;
  const exr_pixel_type_t type = this->PixelType == HALF ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT;
  rv = exr_add_part(ctx.H, "", EXR_STORAGE_SCANLINE, &part);
  if (rv == EXR_ERR_SUCCESS)
  {
    // Data and display window (0, 0) - (nx-1, ny-1), increasing-y line order, aspect 1.
    rv = exr_initialize_required_attr_simple(
      ctx.H, part, nx, ny, static_cast<exr_compression_t>(this->Compression));
  }
  if (rv == EXR_ERR_SUCCESS && longest > ShortNameLength)
  {
    rv = exr_set_longname_support(ctx.H, 1);
  }
  for (size_t k = 0; rv == EXR_ERR_SUCCESS && k < channels.size(); ++k)
  {
    rv = exr_add_channel(ctx.H, part, channels[k].Name.c_str(), type, channels[k].Perception, 1, 1);
  }
  for (size_t k = 0; rv == EXR_ERR_SUCCESS && k < attributes.size(); ++k)
  {
    rv =
      exr_attr_set_string(ctx.H, part, attributes[k].first.c_str(), attributes[k].second.c_str());
  }
  if (rv == EXR_ERR_SUCCESS)
  {
    rv = exr_write_header(ctx.H);
  }
  int linesPerChunk = 1;
  if (rv == EXR_ERR_SUCCESS)
  {
    rv = exr_get_scanlines_per_chunk(ctx.H, part, &linesPerChunk);
  }
  if (rv != EXR_ERR_SUCCESS)
  {
    vtkErrorMacro(<< "OpenEXR failed writing the header of '" << path << "': " << trap.Message(rv));
    return;
  }

  // 4. Scanlines in batches of chunks, top (north) first: the worker threads convert each
  // chunk's channels to float in their own scratch (the encoder converts to HALF when asked)
  // and compress it into the chunk's buffer; this thread then writes the batch in order.
  // Compression is per chunk and deterministic, so the bytes do not depend on the threads.
  const int chunkCount = (ny + linesPerChunk - 1) / linesPerChunk;
  const size_t chunkValues = static_cast<size_t>(linesPerChunk) * static_cast<size_t>(nx);
  const size_t chunkBytes = chunkValues * channels.size() * sizeof(float);
  const size_t batchBytes = size_t(64) << 20; // of scratch and compressed chunks together
  const int batch =
    static_cast<int>(std::max<size_t>(1, std::min<size_t>(256, batchBytes / (2 * chunkBytes))));
  std::vector<ChunkJob> jobs;
  std::string chunkMessage; // a worker's OpenEXR message for a failed chunk
  vtkApertureThreadTally tally;
  vtkSMPTools::LocalScope(vtkApertureSMPConfig(this->NumberOfThreads), [&]() {
    for (int first = 0; rv == EXR_ERR_SUCCESS && first < chunkCount; first += batch)
    {
      const int count = std::min(batch, chunkCount - first);
      jobs.assign(static_cast<size_t>(count), ChunkJob());
      for (int k = 0; rv == EXR_ERR_SUCCESS && k < count; ++k)
      {
        rv = exr_write_scanline_chunk_info(
          ctx.H, part, (first + k) * linesPerChunk, &jobs[static_cast<size_t>(k)].Info);
      }
      if (rv != EXR_ERR_SUCCESS)
      {
        break;
      }
      vtkSMPTools::For(0, count, [&](vtkIdType begin, vtkIdType end) {
        tally.Note();
        for (vtkIdType k = begin; k < end; ++k)
        {
          EncodeChunk(ctx.H, part, channels, byName, nx, ny, jobs[static_cast<size_t>(k)]);
        }
      });
      for (int k = 0; rv == EXR_ERR_SUCCESS && k < count; ++k)
      {
        ChunkJob& job = jobs[static_cast<size_t>(k)];
        rv = job.Result;
        if (rv == EXR_ERR_SUCCESS)
        {
          rv = exr_write_scanline_chunk(
            ctx.H, part, job.Info.start_y, job.Bytes.data(), job.Bytes.size());
        }
        else
        {
          chunkMessage = job.Message;
        }
      }
      this->UpdateProgress(static_cast<double>(first + count) / chunkCount);
    }
  });
  this->NumberOfThreadsUsed = tally.Count();
  jobs.clear();
  if (rv != EXR_ERR_SUCCESS)
  {
    vtkErrorMacro(<< "OpenEXR failed writing '" << path
                  << "': " << (chunkMessage.empty() ? trap.Message(rv) : chunkMessage));
    return; // ~ContextHandle discards the temporary file
  }

  // 5. Offsets table, close, and rename the temporary file to FileName.
  rv = exr_finish(&ctx.H);
  if (rv != EXR_ERR_SUCCESS)
  {
    vtkErrorMacro(<< "OpenEXR failed finishing '" << path << "': " << trap.Message(rv));
  }
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
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "NumberOfThreadsUsed: " << this->NumberOfThreadsUsed << "\n";
  os << indent << "Metadata: " << this->Impl->Metadata.size() << " items\n";
  for (const auto& kv : this->Impl->Metadata)
  {
    os << indent.GetNextIndent() << kv.first << " = " << kv.second << "\n";
  }
}
