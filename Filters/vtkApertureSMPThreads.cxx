// SPDX-License-Identifier: BSD-3-Clause
#include "vtkApertureSMPThreads.h"

std::recursive_mutex& vtkApertureSMPScopeMutex()
{
  static std::recursive_mutex scopes;
  return scopes;
}
