// SPDX-License-Identifier: BSD-3-Clause
// Private to the IO module: the machine's physical memory, the readers' default size limit.
#ifndef vtkAperturePhysicalMemory_h
#define vtkAperturePhysicalMemory_h

#include "vtkType.h"

#include <unistd.h>

// Bytes of physical memory (sysconf); VTK_TYPE_INT64_MAX when the system does not say.
inline vtkTypeInt64 vtkAperturePhysicalMemory()
{
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long pageSize = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || pageSize <= 0)
  {
    return VTK_TYPE_INT64_MAX;
  }
  return static_cast<vtkTypeInt64>(pages) * static_cast<vtkTypeInt64>(pageSize);
}

#endif
