// SPDX-License-Identifier: BSD-3-Clause
// Internal (not installed, not wrapped): the thread count for a vtkSMPTools::LocalScope from a
// filter's or writer's NumberOfThreads property.
#ifndef vtkApertureSMPThreads_h
#define vtkApertureSMPThreads_h

#include "vtkSMPTools.h"

#include <algorithm>

/** 0 (the backend's default) stays 0; a larger count than the backend offers is capped at
 *  what it offers: TBB ignores the excess anyway and prints a warning on stderr for it. */
inline int vtkApertureSMPThreads(int requested)
{
  return requested > 0 ? std::min(requested, vtkSMPTools::GetEstimatedNumberOfThreads()) : 0;
}

#endif
