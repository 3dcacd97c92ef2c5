// SPDX-License-Identifier: BSD-3-Clause
#include "vtkApertureEXRReader.h"

#include "vtkApertureEXRErrorTrap.h"
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
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <openexr.h>

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <locale>
#include <map>
#include <new>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkApertureEXRReader);

namespace
{
const char* const CRSAttribute = "aperture:crs";
const char* const GeoTransformAttribute = "aperture:geotransform";

// Owns a read context.
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

// Six comma-separated numbers of a north-up geotransform (gt[1] > 0, gt[5] < 0, no rotation).
// Parsed in the classic locale, as the writer prints them, whatever the program's locale.
// Returns nullptr, or what is wrong with the text.
const char* ParseGeoTransform(const std::string& text, double gt[6])
{
  std::istringstream in(text);
  in.imbue(std::locale::classic());
  for (int k = 0; k < 6; ++k)
  {
    char comma = 0;
    if (!(in >> gt[k]) || !std::isfinite(gt[k]) || (k < 5 && (!(in >> comma) || comma != ',')))
    {
      return "is not six comma-separated finite numbers";
    }
  }
  in >> std::ws;
  if (!in.eof())
  {
    return "is not six comma-separated finite numbers";
  }
  if (gt[2] != 0 || gt[4] != 0)
  {
    return "is rotated or sheared (its third and fifth numbers are not 0)";
  }
  if (!(gt[1] > 0 && gt[5] < 0))
  {
    return "is not north-up (its pixel width, the second number, must be positive and its "
           "pixel height, the sixth, negative)";
  }
  return nullptr;
}

const char* StorageName(exr_storage_t storage)
{
  switch (storage)
  {
    case EXR_STORAGE_SCANLINE:
      return "scanline";
    case EXR_STORAGE_TILED:
      return "tiled";
    case EXR_STORAGE_DEEP_SCANLINE:
      return "deep scanline";
    case EXR_STORAGE_DEEP_TILED:
      return "deep tiled";
    default:
      return "unknown";
  }
}

// A dotted group's channels (`prefix.suffix`, all of one prefix) in their components' order:
// a colour's R, G, B (A) as a colour has them (`diffuse.R`...: OpenEXR's sorted header gives
// A, B, G, R), numbered ones by number (`v.2` before `v.10`), any other group as the header has
// them (sorted by name).
void OrderComponents(std::vector<std::string>& members, size_t prefixLength)
{
  std::vector<std::string> suffixes;
  for (const std::string& m : members)
  {
    suffixes.push_back(m.substr(prefixLength + 1));
  }
  std::sort(suffixes.begin(), suffixes.end());
  using Names = std::vector<std::string>;
  const bool colour = suffixes == Names{ "B", "G", "R" } ||
    suffixes == Names{ "A", "B", "G", "R" } || suffixes == Names{ "b", "g", "r" } ||
    suffixes == Names{ "a", "b", "g", "r" };
  const bool numbered = std::all_of(suffixes.begin(), suffixes.end(), [](const std::string& x) {
    return x.find_first_not_of("0123456789") == std::string::npos;
  });
  // the key a suffix sorts by: a colour's place, or a number's digits without leading zeros
  // after a character of their count (shorter is smaller), or nothing (the header's order)
  const auto key = [&](const std::string& member) {
    const std::string x = member.substr(prefixLength + 1);
    if (colour)
    {
      return std::string(1, static_cast<char>('0' + std::string("RGBArgba").find(x[0]) % 4));
    }
    if (numbered)
    {
      const size_t first = std::min(x.find_first_not_of('0'), x.size());
      return std::string(1, static_cast<char>(x.size() - first)) + x.substr(first);
    }
    return std::string();
  };
  std::stable_sort(members.begin(), members.end(),
    [&](const std::string& a, const std::string& b) { return key(a) < key(b); });
}
} // namespace

// What RequestInformation found in the header; RequestData reuses it.
struct vtkApertureEXRReader::Internals
{
  struct ArraySpec
  {
    std::string Name;
    std::vector<std::string> Channels;       // channel names, one per component
    std::vector<std::string> ComponentNames; // empty for a one-component array
  };
  std::vector<std::pair<std::string, std::string>> Metadata; // sorted by key
  int Size[2] = { 0, 0 };                                    // columns, rows
  int Channels = 0;                                          // all of them, each read
  std::vector<ArraySpec> Arrays;
  size_t Scalars = 0; // index of the active scalars in Arrays
  double Origin[2] = { 0.0, 0.0 };
  double Spacing[2] = { 1.0, 1.0 };
  std::string CRS; // WKT; empty = none
  bool Valid = false;

  // Bytes of every channel as float, and the header's size in words for messages.
  double FloatBytes() const { return 4.0 * this->Size[0] * this->Size[1] * this->Channels; }
  std::string SizeText() const
  {
    std::ostringstream s;
    s << this->Size[0] << " x " << this->Size[1] << " pixels of " << this->Channels
      << " channels, " << std::ceil(this->FloatBytes() / 1048576.0) << " MiB as float";
    return s.str();
  }

  // Open the file for reading with a clear message on failure.
  static bool Open(
    const char* fileName, ContextHandle& ctx, vtkApertureEXRErrorTrap& trap, std::string& error)
  {
    if (!fileName || !*fileName)
    {
      error = "no file name was set";
      return false;
    }
    const std::string name(fileName);
    struct stat sb;
    if (stat(fileName, &sb) != 0)
    {
      error = vtkApertureMissingFileMessage(name);
      return false;
    }
    if (vtkApertureUnreadableStream(sb))
    {
      // (the magic number's read below and OpenEXR's own open each open it: on a named pipe
      // the first waits for a writer, the second for another)
      error = "'" + name + "' is " + vtkApertureFileKind(sb) +
        ", not a file: OpenEXR reads a file by seeking in it";
      return false;
    }
    // Every OpenEXR file starts with the magic number 20000630 (little-endian).
    unsigned char magic[4] = { 0, 0, 0, 0 };
    FILE* f = std::fopen(fileName, "rb");
    if (!f) // (was "not an OpenEXR file (it cannot be opened)" for a file without permission)
    {
      error = "cannot read '" + name + "': " + std::strerror(errno);
      return false;
    }
    const size_t got = std::fread(magic, 1, 4, f);
    std::fclose(f);
    if (got != 4 || magic[0] != 0x76 || magic[1] != 0x2f || magic[2] != 0x31 || magic[3] != 0x01)
    {
      error = "'" + name + "' is not an OpenEXR file";
      return false;
    }
    const exr_context_initializer_t init = vtkApertureEXRErrorTrap::Initializer();
    const exr_result_t rv = exr_start_read(&ctx.H, fileName, &init);
    if (rv != EXR_ERR_SUCCESS)
    {
      error = "OpenEXR cannot read the header of '" + name + "': " + trap.Message(rv);
      return false;
    }
    return true;
  }
};

//------------------------------------------------------------------------------
vtkApertureEXRReader::vtkApertureEXRReader()
  : FileName(nullptr)
  , Impl(new Internals)
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
vtkApertureEXRReader::~vtkApertureEXRReader()
{
  this->SetFileName(nullptr);
  delete this->Impl;
}

//------------------------------------------------------------------------------
int vtkApertureEXRReader::GetNumberOfMetadata()
{
  return static_cast<int>(this->Impl->Metadata.size());
}

//------------------------------------------------------------------------------
const char* vtkApertureEXRReader::GetMetadataKey(int i)
{
  if (i < 0 || i >= this->GetNumberOfMetadata())
  {
    return nullptr;
  }
  return this->Impl->Metadata[static_cast<size_t>(i)].first.c_str();
}

//------------------------------------------------------------------------------
const char* vtkApertureEXRReader::GetMetadataValue(const char* key)
{
  if (!key)
  {
    return nullptr;
  }
  for (const auto& kv : this->Impl->Metadata)
  {
    if (kv.first == key)
    {
      return kv.second.c_str();
    }
  }
  return nullptr;
}

//------------------------------------------------------------------------------
int vtkApertureEXRReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  return vtkApertureEmptyOutputUnless(this->ReadInformation(outputVector), outputVector);
}

//------------------------------------------------------------------------------
int vtkApertureEXRReader::ReadInformation(vtkInformationVector* outputVector)
{
  Internals& d = *this->Impl;
  d.Valid = false;
  d.Metadata.clear();
  d.Arrays.clear();
  d.CRS.clear();
  std::string error;
  vtkApertureEXRErrorTrap trap;
  ContextHandle ctx;
  if (!Internals::Open(this->FileName, ctx, trap, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  const std::string name(this->FileName);

  // 1. Kind of file: one scanline part.
  int parts = 0;
  exr_result_t rv = exr_get_count(ctx.H, &parts);
  if (rv == EXR_ERR_SUCCESS && parts != 1)
  {
    vtkErrorMacro(<< "'" << name << "' is a multi-part OpenEXR file (" << parts
                  << " parts); only single-part scanline images can be read");
    return 0;
  }
  exr_storage_t storage = EXR_STORAGE_LAST_TYPE;
  if (rv == EXR_ERR_SUCCESS)
  {
    rv = exr_get_storage(ctx.H, 0, &storage);
  }
  if (rv == EXR_ERR_SUCCESS && storage != EXR_STORAGE_SCANLINE)
  {
    vtkErrorMacro(<< "'" << name << "' is a " << StorageName(storage)
                  << " OpenEXR image; only scanline images can be read");
    return 0;
  }
  exr_attr_box2i_t window;
  const exr_attr_chlist_t* channels = nullptr;
  if (rv == EXR_ERR_SUCCESS)
  {
    rv = exr_get_data_window(ctx.H, 0, &window);
  }
  if (rv == EXR_ERR_SUCCESS)
  {
    rv = exr_get_channels(ctx.H, 0, &channels);
  }
  if (rv != EXR_ERR_SUCCESS || !channels)
  {
    vtkErrorMacro(<< "OpenEXR cannot read the header of '" << name << "': " << trap.Message(rv));
    return 0;
  }
  // The library checked the window against its image size limits; sizes fit an int.
  d.Size[0] = window.max.x - window.min.x + 1;
  d.Size[1] = window.max.y - window.min.y + 1;
  if (d.Size[0] < 1 || d.Size[1] < 1 || channels->num_channels < 1)
  {
    vtkErrorMacro(<< "'" << name << "' has no pixels (" << channels->num_channels
                  << " channels, data window " << d.Size[0] << " x " << d.Size[1] << ")");
    return 0;
  }
  // Every channel is read as float: refuse a window no machine of this size can hold (a huge
  // image, or a damaged header) before allocating anything.
  d.Channels = channels->num_channels;
  int source = AP_MEMORY_MACHINE;
  if (d.FloatBytes() > static_cast<double>(vtkApertureUsableMemory(&source)) ||
    static_cast<double>(d.Size[0]) * d.Size[1] > static_cast<double>(VTK_ID_MAX))
  {
    vtkErrorMacro(<< "'" << name << "' has a data window of " << d.SizeText()
                  << ": more than "
                  << (source != AP_MEMORY_MACHINE
                         ? std::string("the memory ") + vtkApertureUsableMemoryOwner(source)
                         : std::string("this machine's memory"))
                  << " (or a damaged header)");
    return 0;
  }

  // 2. Channels -> arrays. Every channel must have a sample at every pixel.
  std::set<std::string> byName;
  std::vector<std::string> order; // channel names in header order
  for (int c = 0; c < channels->num_channels; ++c)
  {
    const exr_attr_chlist_entry_t& e = channels->entries[c];
    const std::string channel(e.name.str, static_cast<size_t>(e.name.length));
    if (e.x_sampling != 1 || e.y_sampling != 1)
    {
      vtkErrorMacro(<< "'" << name << "' channel '" << channel << "' is sampled every "
                    << e.x_sampling << " x " << e.y_sampling
                    << " pixels; only channels sampled at every pixel (1 x 1) can be read");
      return 0;
    }
    byName.insert(channel);
    order.push_back(channel);
  }
  const bool rgb = byName.count("R") && byName.count("G") && byName.count("B");
  const bool rgba = rgb && byName.count("A");
  if (rgb)
  {
    Internals::ArraySpec color;
    color.Name = rgba ? "RGBA" : "RGB";
    color.Channels = { "R", "G", "B" };
    if (rgba)
    {
      color.Channels.emplace_back("A");
    }
    color.ComponentNames = color.Channels;
    d.Arrays.push_back(color);
  }
  // Group dotted channels by the prefix before the last '.', in header order of first
  // appearance. A group whose prefix is also the name of a channel (`V` beside `V.x`, `V.y`) or
  // of the color array stays apart as one-component arrays: two arrays of one name would make
  // vtkFieldData drop one of them.
  struct Group
  {
    std::string Prefix;
    std::vector<std::string> Members;
    bool Dotted;
  };
  std::vector<Group> groups;
  std::map<std::string, size_t> dotted; // prefix -> index in groups
  for (const std::string& channel : order)
  {
    const bool isColor =
      rgb && (channel == "R" || channel == "G" || channel == "B" || (rgba && channel == "A"));
    if (isColor)
    {
      continue;
    }
    const size_t dot = channel.rfind('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == channel.size())
    {
      groups.push_back({ channel, { channel }, false });
      continue;
    }
    const std::string prefix = channel.substr(0, dot);
    const auto found = dotted.find(prefix);
    if (found == dotted.end())
    {
      dotted[prefix] = groups.size();
      groups.push_back({ prefix, { channel }, true });
    }
    else
    {
      groups[found->second].Members.push_back(channel);
    }
  }
  for (const Group& g : groups)
  {
    const bool clash =
      byName.count(g.Prefix) || (rgb && !d.Arrays.empty() && g.Prefix == d.Arrays[0].Name);
    if (g.Dotted && g.Members.size() > 1 && !clash)
    {
      Internals::ArraySpec spec;
      spec.Name = g.Prefix;
      spec.Channels = g.Members;
      OrderComponents(spec.Channels, g.Prefix.size());
      for (const std::string& channel : spec.Channels)
      {
        spec.ComponentNames.push_back(channel.substr(g.Prefix.size() + 1));
      }
      d.Arrays.push_back(spec);
      continue;
    }
    for (const std::string& channel : g.Members)
    {
      Internals::ArraySpec spec; // a lone channel keeps its full name, dots included
      spec.Name = channel;
      spec.Channels = { channel };
      d.Arrays.push_back(spec);
    }
  }
  d.Scalars = 0; // RGB(A) when present, else the first array in header order

  // 3. String attributes, sorted by key; the georeference among them.
  int32_t count = 0;
  rv = exr_get_attribute_list(ctx.H, 0, EXR_ATTR_LIST_SORTED_ORDER, &count, nullptr);
  std::vector<const exr_attribute_t*> attributes(static_cast<size_t>(std::max(count, 0)));
  if (rv == EXR_ERR_SUCCESS && count > 0)
  {
    rv = exr_get_attribute_list(ctx.H, 0, EXR_ATTR_LIST_SORTED_ORDER, &count, attributes.data());
  }
  if (rv != EXR_ERR_SUCCESS)
  {
    vtkErrorMacro(<< "OpenEXR cannot list the attributes of '" << name
                  << "': " << trap.Message(rv));
    return 0;
  }
  for (const exr_attribute_t* a : attributes)
  {
    if (a && a->type == EXR_ATTR_STRING && a->string && std::strcmp(a->name, "type") != 0)
    {
      const exr_attr_string_t* s = a->string;
      d.Metadata.emplace_back(a->name,
        s->str ? std::string(s->str, static_cast<size_t>(std::max(s->length, 0))) : std::string());
    }
  }
  d.Origin[0] = d.Origin[1] = 0.0;
  d.Spacing[0] = d.Spacing[1] = 1.0;
  if (const char* text = this->GetMetadataValue(GeoTransformAttribute))
  {
    double gt[6];
    if (const char* problem = ParseGeoTransform(text, gt))
    {
      vtkErrorMacro(<< "'" << name << "' has an " << GeoTransformAttribute << " attribute '" << text
                    << "' that " << problem);
      return 0;
    }
    if (!std::isfinite(gt[0] + d.Size[0] * gt[1]) || !std::isfinite(gt[3] + d.Size[1] * gt[5]))
    {
      vtkErrorMacro(<< "'" << name << "' has an " << GeoTransformAttribute << " attribute '"
                    << text << "' whose grid of " << d.Size[0] << " x " << d.Size[1]
                    << " pixels reaches beyond the range of numbers");
      return 0;
    }
    d.Spacing[0] = gt[1];
    d.Spacing[1] = -gt[5];
    d.Origin[0] = gt[0] + 0.5 * gt[1];
    d.Origin[1] = gt[3] + (d.Size[1] - 0.5) * gt[5];
  }
  if (const char* wkt = this->GetMetadataValue(CRSAttribute))
  {
    vtkNew<vtkApertureGeoreference> geo;
    if (!geo->SetCRS(wkt) || !geo->HasCRS())
    {
      vtkErrorMacro(<< "'" << name << "' has an " << CRSAttribute
                    << " attribute that is not a CRS: " << geo->GetErrorMessage());
      return 0;
    }
    d.CRS = geo->GetCRS();
  }

  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int whole[6] = { 0, d.Size[0] - 1, 0, d.Size[1] - 1, 0, 0 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole, 6);
  outInfo->Set(vtkDataObject::SPACING(), d.Spacing[0], d.Spacing[1], 1.0);
  outInfo->Set(vtkDataObject::ORIGIN(), d.Origin[0], d.Origin[1], 0.0);
  vtkDataObject::SetPointDataActiveScalarInfo(
    outInfo, VTK_FLOAT, static_cast<int>(d.Arrays[d.Scalars].Channels.size()));
  d.Valid = true;
  return 1;
}

//------------------------------------------------------------------------------
int vtkApertureEXRReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  int ok = 0;
  try
  {
    ok = this->RunRequestData(outputVector);
  }
  catch (const std::bad_alloc&)
  {
    // (a header may promise more pixels than memory holds: a huge image, or a corrupt one)
    vtkErrorMacro(<< "out of memory reading '" << (this->FileName ? this->FileName : "")
                  << "': its header gives " << this->Impl->SizeText());
  }
  return vtkApertureEmptyOutputUnless(ok, outputVector);
}

//------------------------------------------------------------------------------
int vtkApertureEXRReader::RunRequestData(vtkInformationVector* outputVector)
{
  Internals& d = *this->Impl;
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  if (!d.Valid)
  {
    vtkErrorMacro(<< "no valid OpenEXR header information (see the previous error)");
    return 0;
  }
  std::string error;
  vtkApertureEXRErrorTrap trap;
  ContextHandle ctx;
  if (!Internals::Open(this->FileName, ctx, trap, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  const std::string name(this->FileName);
  const int nx = d.Size[0], ny = d.Size[1];
  exr_attr_box2i_t window;
  exr_result_t rv = exr_get_data_window(ctx.H, 0, &window);
  if (rv != EXR_ERR_SUCCESS || window.max.x - window.min.x + 1 != nx ||
    window.max.y - window.min.y + 1 != ny)
  {
    vtkErrorMacro(<< "'" << name << "' changed since its header was read");
    return 0;
  }

  // 1. The output arrays, and where each channel goes.
  struct Target
  {
    float* Base; // first value of the array
    int Components;
    int Component;
  };
  std::map<std::string, size_t> channelIndex;
  std::vector<Target> targets;
  std::vector<vtkSmartPointer<vtkFloatArray>> arrays;
  const vtkIdType points = static_cast<vtkIdType>(nx) * ny;
  for (const Internals::ArraySpec& spec : d.Arrays)
  {
    auto array = vtkSmartPointer<vtkFloatArray>::New();
    const int nc = static_cast<int>(spec.Channels.size());
    vtkApertureAllocate(array, spec.Name.c_str(), nc, points);
    for (size_t c = 0; c < spec.ComponentNames.size(); ++c)
    {
      array->SetComponentName(static_cast<vtkIdType>(c), spec.ComponentNames[c].c_str());
    }
    for (int c = 0; c < nc; ++c)
    {
      channelIndex[spec.Channels[static_cast<size_t>(c)]] = targets.size();
      targets.push_back({ array->GetPointer(0), nc, c });
    }
    arrays.push_back(array);
  }

  // 2. Decode chunk by chunk (top scanlines first) into float scratch rows, converting HALF and
  // UINT in the decoder, then place scanline y at VTK row ny-1-y.
  int linesPerChunk = 1;
  rv = exr_get_scanlines_per_chunk(ctx.H, 0, &linesPerChunk);
  if (rv != EXR_ERR_SUCCESS || linesPerChunk < 1)
  {
    vtkErrorMacro(<< "OpenEXR cannot read '" << name << "': " << trap.Message(rv));
    return 0;
  }
  const size_t chunkValues = static_cast<size_t>(linesPerChunk) * static_cast<size_t>(nx);
  std::vector<float> scratch(chunkValues * targets.size());
  exr_decode_pipeline_t decoder = EXR_DECODE_PIPELINE_INITIALIZER;
  bool initialized = false, routinesChosen = false;
  for (int y = window.min.y; rv == EXR_ERR_SUCCESS && y <= window.max.y; y += linesPerChunk)
  {
    exr_chunk_info_t chunk;
    rv = exr_read_scanline_chunk_info(ctx.H, 0, y, &chunk);
    if (rv == EXR_ERR_SUCCESS)
    {
      rv = initialized ? exr_decoding_update(ctx.H, 0, &chunk, &decoder)
                       : exr_decoding_initialize(ctx.H, 0, &chunk, &decoder);
      initialized = initialized || rv == EXR_ERR_SUCCESS;
    }
    for (int c = 0; rv == EXR_ERR_SUCCESS && c < decoder.channel_count; ++c)
    {
      exr_coding_channel_info_t& in = decoder.channels[c];
      const auto found = channelIndex.find(in.channel_name ? in.channel_name : "");
      if (found == channelIndex.end() || in.width != nx || in.height > linesPerChunk)
      {
        rv = EXR_ERR_INCORRECT_CHUNK; // the header read before does not describe this chunk
        break;
      }
      in.decode_to_ptr = reinterpret_cast<uint8_t*>(scratch.data() + found->second * chunkValues);
      in.user_pixel_stride = static_cast<int32_t>(sizeof(float));
      in.user_line_stride = static_cast<int32_t>(sizeof(float)) * nx;
      in.user_bytes_per_element = static_cast<int16_t>(sizeof(float));
      in.user_data_type = EXR_PIXEL_FLOAT;
    }
    if (rv == EXR_ERR_SUCCESS && !routinesChosen)
    {
      rv = exr_decoding_choose_default_routines(ctx.H, 0, &decoder);
      routinesChosen = rv == EXR_ERR_SUCCESS;
    }
    if (rv == EXR_ERR_SUCCESS)
    {
      rv = exr_decoding_run(ctx.H, 0, &decoder);
    }
    if (rv != EXR_ERR_SUCCESS)
    {
      break;
    }
    for (const auto& entry : channelIndex)
    {
      const Target& t = targets[entry.second];
      const float* src = scratch.data() + entry.second * chunkValues;
      for (int r = 0; r < chunk.height; ++r)
      {
        const int scanline = chunk.start_y - window.min.y + r;
        const vtkIdType row = ny - 1 - scanline;
        float* dst = t.Base + (row * nx) * t.Components + t.Component;
        const float* line = src + static_cast<size_t>(r) * static_cast<size_t>(nx);
        for (int i = 0; i < nx; ++i)
        {
          dst[static_cast<size_t>(i) * t.Components] = line[i];
        }
      }
    }
    this->UpdateProgress(static_cast<double>(y - window.min.y + chunk.height) / ny);
    if (this->GetAbortExecute())
    {
      break;
    }
  }
  if (initialized)
  {
    exr_decoding_destroy(ctx.H, &decoder);
  }
  if (rv != EXR_ERR_SUCCESS)
  {
    vtkErrorMacro(<< "OpenEXR failed reading the pixels of '" << name << "': " << trap.Message(rv));
    return 0;
  }
  if (this->GetAbortExecute())
  {
    return 0;
  }

  // 3. The image.
  output->SetExtent(0, nx - 1, 0, ny - 1, 0, 0);
  output->SetOrigin(d.Origin[0], d.Origin[1], 0.0);
  output->SetSpacing(d.Spacing[0], d.Spacing[1], 1.0);
  vtkPointData* pd = output->GetPointData();
  for (size_t a = 0; a < arrays.size(); ++a)
  {
    if (a == d.Scalars)
    {
      pd->SetScalars(arrays[a]);
    }
    else
    {
      pd->AddArray(arrays[a]);
    }
  }
  if (!d.CRS.empty())
  {
    vtkNew<vtkApertureGeoreference> geo;
    geo->SetCRS(d.CRS.c_str());
    geo->AttachToImage(output);
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkApertureEXRReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "Metadata: " << this->Impl->Metadata.size() << " items\n";
  for (const auto& kv : this->Impl->Metadata)
  {
    os << indent.GetNextIndent() << kv.first << " = " << kv.second << "\n";
  }
}
