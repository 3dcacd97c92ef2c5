// SPDX-License-Identifier: BSD-3-Clause
// Internal (not installed, not wrapped): elevations as the filters take them from their input,
// and the input image itself when it was given with SetInputData.
// Nodata is NaN, and so is every elevation that is not finite (as vtkApertureDEMReader makes
// them, for an image built by hand); finite ones beyond any on the Earth are kept, and named
// in a warning (vtkApertureGeoreference::GetElevationWarning).
#ifndef vtkApertureElevation_h
#define vtkApertureElevation_h

#include "vtkAlgorithm.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkCellData.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationExecutivePortKey.h"
#include "vtkPointData.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

// The image of an input (its pipeline information inInfo) given with SetInputData, whose
// producer is a vtkTrivialProducer: there, whole, before any request, so that its own CRS and
// grid can plan one; nullptr for an input from a filter (whose image held is whatever was
// computed last) or without an image.
inline vtkImageData* vtkApertureGivenImage(vtkInformation* inInfo)
{
  vtkExecutive* producer = nullptr;
  int port = 0;
  vtkExecutive::PRODUCER()->Get(inInfo, producer, port);
  vtkAlgorithm* algorithm = producer ? producer->GetAlgorithm() : nullptr;
  return algorithm && algorithm->IsA("vtkTrivialProducer") ? vtkImageData::GetData(inInfo)
                                                           : nullptr;
}

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

// The name of the elevation array a filter `self` reads from point data `pd`: the one its
// SetInputArrayToProcess(0, ...) selected, as VTK's filters and ParaView select theirs, when
// that selection changed after `made` (its MTime when the ElevationArrayName was last set:
// vtkApertureDropElevationSelection, which the constructors' setting calls too, takes a
// selection made before away, vtkImageAlgorithm's default one of the point scalars
// included): a point array by name, or the point scalars (""). Else `fallback` (the filter's
// ElevationArrayName; null, "": the point scalars, an error until 2026-12-07). "" with
// *problem set when the selection is not of point data, or an attribute other than the
// scalars. (Until 2026-12-06 the selection was ignored; until review the scalars were looked
// up by their name, or "Elevation" for unnamed ones, which found another array so named.)
inline std::string vtkApertureSelectedElevationName(
  vtkAlgorithm* self, vtkMTimeType made, const char* fallback, std::string* problem)
{
  vtkInformation* info = self->GetInputArrayInformation(0);
  if (!info || info->GetMTime() <= made ||
    !(info->Has(vtkDataObject::FIELD_NAME()) || info->Has(vtkDataObject::FIELD_ATTRIBUTE_TYPE())))
  {
    return fallback ? fallback : "";
  }
  const int association = info->Has(vtkDataObject::FIELD_ASSOCIATION())
    ? info->Get(vtkDataObject::FIELD_ASSOCIATION())
    : vtkDataObject::FIELD_ASSOCIATION_POINTS;
  if (association != vtkDataObject::FIELD_ASSOCIATION_POINTS &&
    association != vtkDataObject::FIELD_ASSOCIATION_POINTS_THEN_CELLS)
  {
    *problem = "SetInputArrayToProcess selects an array that is not point data; the elevations "
               "are a point array (ElevationArrayName)";
    return "";
  }
  if (info->Has(vtkDataObject::FIELD_NAME()))
  {
    return info->Get(vtkDataObject::FIELD_NAME());
  }
  const int attribute = info->Get(vtkDataObject::FIELD_ATTRIBUTE_TYPE());
  if (attribute != vtkDataSetAttributes::SCALARS)
  {
    *problem = std::string("SetInputArrayToProcess selects the point ") +
      vtkDataSetAttributes::GetAttributeTypeAsString(attribute) +
      ", not the scalars or an array by name; the elevations are one value a point";
  }
  return ""; // (the point scalars, or nothing with *problem set)
}

// The first step of a filter's SetElevationArrayName (VTK's string setter the second): of it
// and SetInputArrayToProcess(0, ...) the later holds, so a selection made before (its info
// changed after `made`) is taken away, and the same selection made again counts anew (until
// 2026-12-07 a name set after any selection was kept, and ignored). True when one was taken
// away: the filter is then modified, even if its name stays.
inline bool vtkApertureDropElevationSelection(vtkAlgorithm* self, vtkMTimeType& made)
{
  vtkInformation* info = self->GetInputArrayInformation(0);
  const bool selected = info->GetMTime() > made &&
    (info->Has(vtkDataObject::FIELD_NAME()) || info->Has(vtkDataObject::FIELD_ATTRIBUTE_TYPE()));
  if (selected)
  {
    // (VTK's SetInputArrayToProcess leaves an unchanged selection's time as it is)
    info->Remove(vtkDataObject::FIELD_NAME());
    info->Remove(vtkDataObject::FIELD_ATTRIBUTE_TYPE());
  }
  made = info->GetMTime();
  return selected;
}

// After a filter carried its input's point data `in` to `out`: heights it took from the active
// scalars, asked for (`name` "") or for want of an array named `name` (the default
// "Elevation": an image made by hand), come out as the point array Elevation too, as from the
// reader (the same values, their memory shared): in place of unnamed scalars, beside named
// ones; not in place of another array named Elevation.
inline void vtkApertureNameElevation(
  vtkDataSetAttributes* in, vtkDataSetAttributes* out, const char* name)
{
  vtkDataArray* carried = out->GetScalars();
  if (!carried || !name || (*name && std::string(name) != "Elevation") ||
    in->GetArray("Elevation") || out->GetArray("Elevation"))
  {
    return;
  }
  vtkDataArray* named = carried->NewInstance();
  named->ShallowCopy(carried);
  named->SetName("Elevation");
  if (carried->GetName() && *carried->GetName())
  {
    out->AddArray(named);
  }
  else
  {
    out->SetScalars(named);
  }
  named->Delete();
}

// The elevation array of point data `pd`: the array named `name`; the active scalars for a
// null or empty name, and when there is none so named and `name` is the filters' default
// "Elevation" (an image made by hand, as VTK's imaging filters take it). Any numeric type, one
// component. nullptr when there is none, with *problem (if given) naming what the point data
// hold instead.
inline vtkDataArray* vtkApertureElevationArray(
  vtkDataSetAttributes* pd, const char* name, std::string* problem)
{
  name = name ? name : "";
  const bool unnamed = !*name; // (the scalars themselves)
  vtkDataArray* a = pd && !unnamed ? pd->GetArray(name) : nullptr;
  const bool scalars = !a && pd && (unnamed || std::string(name) == "Elevation");
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
    msg << (!scalars ? "the elevation array '"
                     : unnamed ? "the active point scalars '"
                               : "the input has no point array named 'Elevation', and its active "
                                 "scalars '")
        << (a->GetName() ? a->GetName() : "") << (scalars ? "' have " : "' has ")
        << a->GetNumberOfComponents() << " components; elevations need one";
  }
  else if (vtkAbstractArray* other = pd && !unnamed ? pd->GetAbstractArray(name) : nullptr)
  {
    // (not "no point array named 'Elevation' (its point arrays: 'Elevation')")
    msg << "the point array '" << name << "' is not numeric (a " << other->GetClassName()
        << "); elevations are numbers";
  }
  else
  {
    if (unnamed)
    {
      msg << "the point scalars are asked for (by a null or empty ElevationArrayName, or by "
             "SetInputArrayToProcess of the scalars), but the input has none";
    }
    else
    {
      msg << "the input has no point array named '" << name << "'";
    }
    const int n = pd ? pd->GetNumberOfArrays() : 0;
    msg << (n ? " (its point arrays: "
              : unnamed ? ": it has no point arrays"
                        : " and no point scalars: it has no point arrays");
    for (int k = 0; k < n; ++k)
    {
      vtkAbstractArray* other = pd->GetAbstractArray(k);
      msg << (k ? ", " : "");
      if (other && other->GetName() && *other->GetName())
      {
        msg << "'" << other->GetName() << "'";
      }
      else // (not '')
      {
        msg << "an unnamed " << (other ? other->GetClassName() : "array");
      }
    }
    msg << (n ? "); SetElevationArrayName names the one holding elevations in metres" : "");
  }
  if (problem)
  {
    *problem = msg.str();
  }
  return nullptr;
}

// The elevation array a filter `self` reads from point data `pd`, and its name in `name`:
// vtkApertureSelectedElevationName's choice (the selection, else `fallback`), looked up as
// vtkApertureElevationArray does. nullptr with *problem set when there is none.
inline vtkDataArray* vtkApertureSelectedElevation(vtkAlgorithm* self, vtkMTimeType made,
  vtkDataSetAttributes* pd, const char* fallback, std::string& name, std::string* problem)
{
  name = vtkApertureSelectedElevationName(self, made, fallback, problem);
  return problem->empty() ? vtkApertureElevationArray(pd, name.c_str(), problem) : nullptr;
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

// Whether extent `inner` is not empty and lies inside `outer` (both VTK extents).
inline bool vtkApertureExtentInside(const int inner[6], const int outer[6])
{
  bool inside = true;
  for (int a = 0; a < 6; a += 2)
  {
    inside = inside && inner[a] <= inner[a + 1] && inner[a] >= outer[a] &&
      inner[a + 1] <= outer[a + 1];
  }
  return inside;
}

// `image` cropped to `want` where it holds more than that and `want` lies inside its extent: `copy`
// gets its structure and point arrays (and its cell arrays if `cells`) cropped, and is returned;
// else `image` itself (also a 3-D image, which the filters refuse). The filters read only what
// their update asked for, as VTK's do: an input may hold more (a reader updated whole before, an
// image given with SetInputData, vtkImageClip passing all of its input on with ClipData off). The
// crop reads every point array by the image's extent, so one that disagrees with it is refused
// first: nullptr, and `problem` says which.
inline vtkImageData* vtkApertureCropTo(vtkImageData* image, const int want[6], vtkImageData* copy,
  bool cells, std::string& problem)
{
  int have[6];
  image->GetExtent(have);
  if (have[4] != have[5] || !vtkApertureExtentInside(want, have) ||
    std::equal(want, want + 6, have))
  {
    return image;
  }
  problem = vtkApertureCheckPointArrays(image->GetPointData(),
    static_cast<vtkIdType>(have[1]) - have[0] + 1, static_cast<vtkIdType>(have[3]) - have[2] + 1);
  if (!problem.empty())
  {
    return nullptr;
  }
  copy->ShallowCopy(image);
  if (!cells)
  {
    copy->GetCellData()->Initialize();
  }
  copy->Crop(want);
  return copy;
}

#endif
