// SPDX-License-Identifier: BSD-3-Clause
#include "vtkApertureSMPThreads.h"

std::mutex& vtkApertureSMPScopeMutex()
{
  static std::mutex scopes;
  return scopes;
}
