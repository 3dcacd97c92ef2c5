// SPDX-License-Identifier: BSD-3-Clause
// Internal (not installed, not wrapped): elevations as the filters take them from their input.
// Nodata is NaN, and so is every elevation that is not finite (as vtkApertureDEMReader makes
// them, for an image built by hand); finite ones beyond any on the Earth are kept, and named
// in a warning (an undeclared nodata value such as -32768, or heights not in metres).
#ifndef vtkApertureElevation_h
#define vtkApertureElevation_h

#include "vtkDataArray.h"
#include "vtkFloatArray.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

// The range of the Earth's surface with a margin (m): Challenger Deep about -10,935 m, Everest
// 8,849 m, orthometric or ellipsoidal (the geoid stays within about 110 m of the ellipsoid).
constexpr float vtkApertureEarthLowest = -11100.0f;
constexpr float vtkApertureEarthHighest = 9000.0f;

// Tuples [begin, end) of a one-component elevation array into z[begin, end) as float, NaN
// where not finite (doubles beyond the float range included). A float array (the reader's) is
// read in place, others through GetComponent.
inline void vtkApertureCopyElevations(vtkDataArray* a, vtkIdType begin, vtkIdType end, float* z)
{
  const auto finite = [](float v) {
    return std::isfinite(v) ? v : std::numeric_limits<float>::quiet_NaN();
  };
  if (vtkFloatArray* floats = vtkFloatArray::FastDownCast(a))
  {
    std::transform(floats->GetPointer(begin), floats->GetPointer(end), z + begin, finite);
    return;
  }
  for (vtkIdType k = begin; k < end; ++k)
  {
    z[k] = finite(static_cast<float>(a->GetComponent(k, 0)));
  }
}

// The warning for valid elevations from min to max (m), "" when the Earth has such; `what`
// names what is made of them ("sky products computed from them").
inline std::string vtkApertureElevationWarning(double min, double max, const char* what)
{
  if (!(min < vtkApertureEarthLowest || max > vtkApertureEarthHighest))
  {
    return std::string();
  }
  std::ostringstream msg;
  msg << "elevations range from " << min << " to " << max << " m, beyond any on Earth ("
      << vtkApertureEarthLowest << " to " << vtkApertureEarthHighest
      << " m): a nodata value the DEM does not declare, or heights not in metres? " << what
      << " are meaningless";
  return msg.str();
}

#endif
