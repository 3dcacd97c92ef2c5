// SPDX-License-Identifier: BSD-3-Clause
// Internal (not installed, not wrapped): sizing arrays so that a failed allocation can be
// reported (with huge pages asked for large ones), the size of the input behind a failed
// update, the memory this process may use (the readers' and the sky filter's default size
// limit: physical memory, or a control group's limit) and byte counts for messages.
#ifndef vtkApertureMemory_h
#define vtkApertureMemory_h

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformationVector.h"
#include "vtkType.h"

#include "ap_memory.h"

#include <cmath>
#include <new>
#include <sstream>
#include <string>

// Name (unless name is null) and size an array, its values uninitialised, in memory from
// ap_alloc_huge (which huge pages cover from 4 MiB up: first touched faster).
// std::bad_alloc when the memory could not be had (VTK reports that and leaves the array
// short), for RequestData to turn into an error naming the size needed.
inline void vtkApertureAllocate(
  vtkDataArray* a, const char* name, int components, vtkIdType tuples)
{
  if (name)
  {
    a->SetName(name);
  }
  a->SetNumberOfComponents(components);
  const double bytes = static_cast<double>(tuples) * components * a->GetDataTypeSize();
  if (a->HasStandardMemoryLayout() && bytes < 1e18)
  {
    void* values = ap_alloc_huge(static_cast<size_t>(bytes));
    if (!values)
    {
      throw std::bad_alloc();
    }
    a->SetVoidArray(values, tuples * components, 0, vtkAbstractArray::VTK_DATA_ARRAY_FREE);
  }
  else
  {
    a->SetNumberOfTuples(tuples);
  }
  if (a->GetNumberOfTuples() != tuples)
  {
    throw std::bad_alloc();
  }
}

// Dimensions of the input image of a failed update, for RequestData's out-of-memory message;
// 0 x 0 x 0 when there is none.
inline void vtkApertureInputDimensions(vtkInformationVector* inputs, int dims[3])
{
  dims[0] = dims[1] = dims[2] = 0;
  if (vtkImageData* input = vtkImageData::GetData(inputs))
  {
    input->GetDimensions(dims);
  }
}

// Bytes of memory this process may use (ap_memory_usable): the physical memory, or its
// control group's limit or what its address-space limit leaves where lower; *source (unless
// null) says which (AP_MEMORY_MACHINE, _GROUP, _ADDRESS_SPACE). VTK_TYPE_INT64_MAX when the
// system does not say.
inline vtkTypeInt64 vtkApertureUsableMemory(int* source = nullptr)
{
  const unsigned long long bytes = ap_memory_usable(source);
  return bytes == 0 || bytes > static_cast<unsigned long long>(VTK_TYPE_INT64_MAX)
    ? VTK_TYPE_INT64_MAX
    : static_cast<vtkTypeInt64>(bytes);
}

// What messages call that memory: "the 3.2 GiB of memory " + this.
inline const char* vtkApertureUsableMemoryOwner(int source)
{
  return source == AP_MEMORY_GROUP ? "this process may use under its control group's limit"
    : source == AP_MEMORY_ADDRESS_SPACE
    ? "this process may use under its address-space limit (ulimit -v)"
    : "this machine has";
}

// A byte count for messages: "512 bytes", "1.500 KiB", ... "3.353 GiB"; rounded up to the
// digits shown with `up` (a limit to ask for: 1,048,976 bytes are "1.001 MiB", not "1.000").
inline std::string vtkApertureHumanBytes(double bytes, bool up = false)
{
  const char* units[] = { "bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB" };
  int u = 0;
  while (bytes >= 1024.0 && u < 6)
  {
    bytes /= 1024.0;
    ++u;
  }
  if (up)
  {
    const double digits = u == 0 ? 1.0 : 1000.0;
    bytes = std::ceil(bytes * digits) / digits;
  }
  std::ostringstream s;
  s.precision(u == 0 ? 0 : 3);
  s << std::fixed << bytes << " " << units[u];
  return s.str();
}

// `bytes` this process has allocated already (an update's input), as vtkApertureBeyondMemory's
// `held` counts them: against physical memory or a control group's limit, all of them; under
// an address-space limit none, since the usable memory there is what the limit leaves beside
// everything mapped, these bytes among it (counted twice, they refused updates that fit).
inline double vtkApertureHeldNow(double bytes)
{
  int source = AP_MEMORY_MACHINE;
  vtkApertureUsableMemory(&source);
  return source == AP_MEMORY_ADDRESS_SPACE ? 0.0 : bytes;
}

// "" when `need` bytes fit within `limit` (> 0: a MemoryLimit property), or (limit 0) within
// the memory this process may use less `held` bytes (what its input occupies, or will once read;
// vtkApertureHeldNow of the bytes of an input held already); else `needs`
// (what needs the bytes, with their count) and the memory they exceed.
inline std::string vtkApertureBeyondMemory(
  double need, double held, vtkTypeInt64 limit, const std::string& needs)
{
  int source = AP_MEMORY_MACHINE; // (the usable memory is read only when no limit is set)
  const double usable = limit > 0 ? 0.0 : static_cast<double>(vtkApertureUsableMemory(&source));
  const double allowed = limit > 0 ? static_cast<double>(limit) : usable - held;
  if (need <= allowed)
  {
    return std::string();
  }
  if (limit > 0)
  {
    return needs + ", more than the " + vtkApertureHumanBytes(allowed) + " MemoryLimit";
  }
  if (allowed <= 0.0) // (nothing left to compare with: say what does not fit)
  {
    return needs + ", and the DEM's " + vtkApertureHumanBytes(held) + " alone exceed the " +
      vtkApertureHumanBytes(usable) + " of memory " + vtkApertureUsableMemoryOwner(source);
  }
  return needs + ", more than the " + vtkApertureHumanBytes(allowed) + " of memory " +
    vtkApertureUsableMemoryOwner(source) +
    (held > 0.0 ? " beside the DEM's " + vtkApertureHumanBytes(held) : std::string());
}

#endif
