// SPDX-License-Identifier: BSD-3-Clause
// Internal (not installed, not wrapped): silence GDAL's stderr messages inside a scope and keep
// the last one, so the calling filter can report it once through vtkErrorMacro.
#ifndef vtkApertureGDALErrorTrap_h
#define vtkApertureGDALErrorTrap_h

#include <cpl_error.h>

#include <string>

class vtkApertureGDALErrorTrap
{
public:
  vtkApertureGDALErrorTrap()
  {
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
  }
  ~vtkApertureGDALErrorTrap() { CPLPopErrorHandler(); }
  vtkApertureGDALErrorTrap(const vtkApertureGDALErrorTrap&) = delete;
  vtkApertureGDALErrorTrap& operator=(const vtkApertureGDALErrorTrap&) = delete;

  /** The last GDAL error message in this scope, or `fallback` when GDAL gave none. */
  static std::string Message(const char* fallback = "")
  {
    const char* m = CPLGetLastErrorMsg();
    return (m && *m) ? std::string(m) : std::string(fallback);
  }
};

#endif
