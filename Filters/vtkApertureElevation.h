// SPDX-License-Identifier: BSD-3-Clause
// Internal (not installed, not wrapped): elevations as the filters take them from their input.
// Nodata is NaN, and so is every elevation that is not finite (as vtkApertureDEMReader makes
// them, for an image built by hand); finite ones beyond any on the Earth are kept, and named
// in a warning (an undeclared nodata value such as -32768, or heights not in metres).
#ifndef vtkApertureElevation_h
#define vtkApertureElevation_h

#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
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

// The elevation array of point data `pd`: the array named `name`, or, when there is none so
// named and `name` is the filters' default "Elevation", the active scalars (an image made by
// hand, as VTK's imaging filters take it). Any numeric type, one component. nullptr when there
// is none, with *problem naming what the point data hold instead.
inline vtkDataArray* vtkApertureElevationArray(
  vtkDataSetAttributes* pd, const char* name, std::string* problem)
{
  name = name ? name : "";
  vtkDataArray* a = pd ? pd->GetArray(name) : nullptr;
  const bool scalars = !a && pd && std::string(name) == "Elevation";
  if (scalars)
  {
    a = pd->GetScalars();
  }
  std::ostringstream msg;
  if (a && a->GetNumberOfComponents() == 1)
  {
    return a;
  }
  if (a)
  {
    msg << (scalars ? "the input has no point array named 'Elevation', and its active scalars '"
                    : "the elevation array '")
        << (a->GetName() ? a->GetName() : "") << (scalars ? "' have " : "' has ")
        << a->GetNumberOfComponents() << " components; elevations need one";
  }
  else
  {
    msg << "the input has no point array named '" << name << "'";
    const int n = pd ? pd->GetNumberOfArrays() : 0;
    msg << (n ? " (its point arrays: " : " and no point scalars: it has no point arrays");
    for (int k = 0; k < n; ++k)
    {
      vtkAbstractArray* other = pd->GetAbstractArray(k);
      const char* o = other && other->GetName() ? other->GetName() : "";
      msg << (k ? ", '" : "'") << o << "'";
    }
    msg << (n ? "); SetElevationArrayName names the one holding elevations in metres" : "");
  }
  *problem = msg.str();
  return nullptr;
}

// "" when every point array of `pd` (elevations, and what the filters pass on) holds one
// tuple per point of an nx x ny image, else the problem, naming the first that does not: an
// image assembled by hand can disagree with itself, and copies of a short array read past it.
inline std::string vtkApertureCheckPointArrays(
  vtkDataSetAttributes* pd, vtkIdType nx, vtkIdType ny)
{
  const int n = pd ? pd->GetNumberOfArrays() : 0;
  for (int k = 0; k < n; ++k)
  {
    vtkAbstractArray* a = pd->GetAbstractArray(k);
    if (a && a->GetNumberOfTuples() != nx * ny)
    {
      std::ostringstream msg;
      msg << "the point array '" << (a->GetName() ? a->GetName() : "") << "' has "
          << a->GetNumberOfTuples() << " tuples for the " << nx << " x " << ny
          << " points of the input's extent";
      return msg.str();
    }
  }
  return std::string();
}

// The warning for valid elevations from min to max (m) on a grid of nx x ny cells of cell[0] x
// cell[1] m (nullptr: unknown), "" when they could be terrain: heights beyond any on the Earth
// (an undeclared nodata value, or heights not in metres), else a relief more than ten times
// the grid's larger side, which no terrain has (a mean slope beyond 84 degrees across the
// grid) while coordinates in degrees taken for metres (a projected CRS given to a lat/lon DEM)
// make cells of a millimetre and such a relief. `what` names what is made of them ("Sky
// products computed from them").
inline std::string vtkApertureElevationWarning(
  double min, double max, int nx, int ny, const double* cell, const char* what)
{
  std::ostringstream msg;
  if (min < vtkApertureEarthLowest || max > vtkApertureEarthHighest)
  {
    msg << "elevations range from " << min << " to " << max << " m, beyond any on Earth ("
        << vtkApertureEarthLowest << " to " << vtkApertureEarthHighest
        << " m): a nodata value the DEM does not declare, or heights not in metres? ";
  }
  else if (cell && max - min > 10.0 * std::max(nx * cell[0], ny * cell[1]))
  {
    msg << "elevations range over " << max - min << " m on a grid of " << nx * cell[0] << " x "
        << ny * cell[1] << " m (cells of " << cell[0] << " x " << cell[1]
        << " m), steeper than any terrain: a CRS whose unit does not fit the grid's "
           "coordinates (degrees taken for metres?), or heights not in metres? ";
  }
  else
  {
    return std::string();
  }
  msg << what << " are meaningless";
  return msg.str();
}

#endif
