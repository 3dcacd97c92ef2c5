// SPDX-License-Identifier: BSD-3-Clause
#include "vtkApertureGeoreference.h"

#include "vtkApertureGDALErrorTrap.h"

#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationStringKey.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/Geodesic.hpp>
#include <cpl_conv.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkApertureGeoreference);
vtkInformationKeyMacro(vtkApertureGeoreference, CRS_KEY, String);

// Whether a latitude (degrees) lies beyond a pole. A cell edge on a pole comes out a rounding
// error beyond it (88.025 + 39 * 0.05 + 0.025 = 90.00000000000001): that much is allowed.
static bool BeyondPole(double latitude)
{
  return std::fabs(latitude) - 90.0 > 1e-9;
}

// `srs` as one-line WKT2:2019; WKT1 for the CRSs that have no WKT2 form (e.g. with unusual
// PROJ-only parameters).
static std::string ExportWKT(OGRSpatialReferenceH srs)
{
  char* wkt = nullptr;
  const char* options[] = { "FORMAT=WKT2_2019", "MULTILINE=NO", nullptr };
  if (OSRExportToWktEx(srs, &wkt, options) != OGRERR_NONE || !wkt)
  {
    CPLFree(wkt);
    wkt = nullptr;
    OSRExportToWkt(srs, &wkt);
  }
  std::string text = wkt ? wkt : "";
  CPLFree(wkt);
  return text;
}

// A compound CRS's horizontal part (a clone without the vertical part, to OSRRelease), or
// nullptr when `srs` is not compound or GDAL cannot separate it.
static OGRSpatialReferenceH HorizontalPart(OGRSpatialReferenceH srs)
{
  OGRSpatialReferenceH horizontal = OSRIsCompound(srs) ? OSRClone(srs) : nullptr;
  if (horizontal && OSRStripVertical(horizontal) != OGRERR_NONE)
  {
    OSRRelease(horizontal);
    horizontal = nullptr;
  }
  return horizontal;
}

// Whether the image's direction matrix turns its x and y axes (`error` then says so): its grid
// is rotated or mirrored, which no GeoTransform of its origin and spacing describes.
static bool Rotated(vtkImageData* image, std::string& error)
{
  if (!vtkApertureGeoreference::HasNorthUpAxes(image))
  {
    error = "the image's direction matrix rotates or mirrors its x and y axes; DEM grids must "
            "be north-up (x east, y north)";
    return true;
  }
  return false;
}

// Whether the image's origin and spacing describe cells with finite edges, their x and y
// axes east and north; else false, with `error` set.
static bool GridOfImage(vtkImageData* image, std::string& error)
{
  double spacing[3], origin[3];
  image->GetSpacing(spacing);
  image->GetOrigin(origin);
  if (spacing[1] < 0.0 && spacing[0] > 0.0 && std::isfinite(spacing[1]))
  {
    // (numpy's north-up rows with a spacing of -dy)
    error = "the image spacing must be positive (its y spacing is negative): VTK's rows run "
            "from south to north; give them in that order (numpy: [::-1]) with a positive "
            "spacing";
    return false;
  }
  if (!(spacing[0] > 0) || !(spacing[1] > 0) || !std::isfinite(spacing[0]) ||
    !std::isfinite(spacing[1]) || !std::isfinite(origin[0]) || !std::isfinite(origin[1]))
  {
    error = "the image spacing must be positive and finite and its origin finite";
    return false;
  }
  int extent[6];
  image->GetExtent(extent);
  // (a spacing of 1e308 on 10 cells: the writers wrote a geotransform of inf, which no reader
  // takes, until 2026-12-06)
  for (int a = 0; a < 2; ++a)
  {
    const double low = origin[a] + (extent[2 * a] - 0.5) * spacing[a];
    const double high = origin[a] + (extent[2 * a + 1] + 0.5) * spacing[a];
    if (!std::isfinite(low) || !std::isfinite(high))
    {
      std::ostringstream msg;
      msg << "the image's " << (a ? "south and north" : "west and east")
          << " edges are not finite numbers (origin " << origin[a] << ", spacing " << spacing[a]
          << ", extent " << extent[2 * a] << ".." << extent[2 * a + 1] << ")";
      error = msg.str();
      return false;
    }
  }
  return true;
}

struct vtkApertureGeoreference::Internals
{
  OGRSpatialReferenceH CRS = nullptr;
  OGRSpatialReferenceH Geographic = nullptr;
  OGRCoordinateTransformationH ToGeographic = nullptr;
  OGRCoordinateTransformationH FromGeographic = nullptr;
  bool GeographicTried = false;
  std::string GeographicError; // (why that try failed: Error may have been cleared since)
  // Geographic output of the CRS's own geographic CRS -> degrees east of Greenwich.
  double UnitToDegrees = 1.0;
  double PrimeMeridianDegrees = 0.0;
  std::string WKT;
  std::string HorizontalWKT; // (GetHorizontalCRS: on first use)
  std::string Name;
  std::string UnitName;
  double UnitMetres = 0.0;         // (projected: metres per horizontal unit; else 0)
  std::string VerticalUnitName;    // (a compound or vertical CRS's height unit, else "")
  double VerticalUnitMetres = 0.0;
  std::string Error;

  void ResetTransforms()
  {
    if (this->ToGeographic)
    {
      OCTDestroyCoordinateTransformation(this->ToGeographic);
      this->ToGeographic = nullptr;
    }
    if (this->FromGeographic)
    {
      OCTDestroyCoordinateTransformation(this->FromGeographic);
      this->FromGeographic = nullptr;
    }
    if (this->Geographic)
    {
      OSRRelease(this->Geographic);
      this->Geographic = nullptr;
    }
    this->GeographicTried = false;
    this->GeographicError.clear();
  }

  void Reset()
  {
    this->ResetTransforms();
    if (this->CRS)
    {
      OSRRelease(this->CRS);
      this->CRS = nullptr;
    }
    this->WKT.clear();
    this->HorizontalWKT.clear();
    this->Name.clear();
    this->UnitName.clear();
    this->UnitMetres = 0.0;
    this->VerticalUnitName.clear();
    this->VerticalUnitMetres = 0.0;
  }

  // Build the transformations to and from the CRS's own geographic CRS once.
  bool EnsureGeographic()
  {
    if (!this->CRS)
    {
      this->Error = "no coordinate reference system is set";
      return false;
    }
    if (this->ToGeographic && this->FromGeographic)
    {
      return true;
    }
    if (this->GeographicTried)
    {
      this->Error = this->GeographicError; // (a success in between cleared Error)
      return false;
    }
    this->GeographicTried = true;
    const bool ok = this->TryGeographic();
    if (!ok)
    {
      this->GeographicError = this->Error;
    }
    return ok;
  }

  // EnsureGeographic's one try: false with Error set when the CRS has no geographic form.
  bool TryGeographic()
  {
    vtkApertureGDALErrorTrap trap;
    if (OSRIsLocal(this->CRS))
    {
      this->Error = "the CRS '" + this->Name +
        "' is a local (engineering) CRS with no geographic coordinates; reproject the DEM "
        "to a geographic or projected CRS";
      return false;
    }
    if (OSRIsGeocentric(this->CRS))
    {
      // PROJ would take a grid's x and y for Earth-centred X and Y at Z = 0: a strip of the
      // equator, silently wrong.
      this->Error = "the CRS '" + this->Name +
        "' is geocentric (Earth-centred X, Y, Z), which no DEM grid is in; reproject the DEM "
        "to a geographic or projected CRS";
      return false;
    }
    this->Geographic = OSRCloneGeogCS(this->CRS);
    if (!this->Geographic)
    {
      this->Error = "the CRS '" + this->Name + "' cannot be converted to geographic coordinates" +
        (trap.Message().empty() ? std::string() : ": " + trap.Message());
      return false;
    }
    OSRSetAxisMappingStrategy(this->Geographic, OAMS_TRADITIONAL_GIS_ORDER);
    this->ToGeographic = OCTNewCoordinateTransformation(this->CRS, this->Geographic);
    this->FromGeographic = OCTNewCoordinateTransformation(this->Geographic, this->CRS);
    if (!this->ToGeographic || !this->FromGeographic)
    {
      this->Error = "no transformation between the CRS '" + this->Name +
        "' and its geographic coordinates: " + trap.Message("PROJ gave no reason");
      this->ResetTransforms();
      this->GeographicTried = true;
      return false;
    }
    // The CRS's geographic CRS may count in grads or from Paris; report degrees from Greenwich.
    const double radiansPerUnit = OSRGetAngularUnits(this->Geographic, nullptr);
    this->UnitToDegrees = radiansPerUnit > 0 ? radiansPerUnit * 180.0 / M_PI : 1.0;
    this->PrimeMeridianDegrees = OSRGetPrimeMeridian(this->Geographic, nullptr);
    return true;
  }

  // A local (engineering) CRS: a site grid with no geographic coordinates.
  bool IsLocal() const { return this->CRS && OSRIsLocal(this->CRS); }

  // The cell size (m) of a local CRS's grid: its spacing in the CRS's linear unit, the same
  // for every cell. False without a usable unit.
  bool LocalCellSize(const double spacing[2], double size[2])
  {
    if (!(this->UnitMetres > 0) || !std::isfinite(this->UnitMetres))
    {
      this->Error = "the local CRS '" + this->Name + "' has no linear unit";
      return false;
    }
    size[0] = spacing[0] * this->UnitMetres;
    size[1] = spacing[1] * this->UnitMetres;
    this->Error.clear();
    return true;
  }

  // Ground lengths (m) of the geodesics across the cell of geo's grid centred at CRS point
  // (xc, yc), from its west edge's centre to its east edge's and from its south edge's to its
  // north edge's, and the cosine of the angle between them (from their chords in Earth-centred
  // coordinates: no azimuths, which change fast near a pole and are undefined on it).
  bool CellVectors(
    vtkApertureGeoreference* geo, double xc, double yc, double size[2], double& cosine);
};

bool vtkApertureGeoreference::Internals::CellVectors(
  vtkApertureGeoreference* geo, double xc, double yc, double size[2], double& cosine)
{
  double ell[2];
  if (!geo->GetEllipsoid(ell))
  {
    return false;
  }
  const double hx = 0.5 * geo->GridSpacing[0], hy = 0.5 * geo->GridSpacing[1];
  const double xy[8] = { xc - hx, yc, xc + hx, yc, xc, yc - hy, xc, yc + hy };
  double ll[8];
  if (!geo->CRSToLonLatPoints(4, xy, ll))
  {
    return false;
  }
  for (double v : ll)
  {
    if (std::isnan(v))
    {
      this->Error = "the cell has no geographic coordinates";
      return false;
    }
  }
  for (int k = 1; k < 8; k += 2)
  {
    // (a lat/lon grid's coordinates pass through as they are: GeographicLib gave NaN sizes)
    if (BeyondPole(ll[k]))
    {
      std::ostringstream msg;
      msg << "the cell reaches latitude " << ll[k] << ", beyond the pole";
      this->Error = msg.str();
      return false;
    }
    ll[k] = std::max(-90.0, std::min(90.0, ll[k]));
  }
  try
  {
    const GeographicLib::Geodesic geod(ell[0], ell[1]);
    const GeographicLib::Geocentric ecef(ell[0], ell[1]);
    double chord[2][3];
    for (int k = 0; k < 2; ++k)
    {
      const double* a = ll + 4 * k;
      double p[2][3];
      geod.Inverse(a[1], a[0], a[3], a[2], size[k]);
      ecef.Forward(a[1], a[0], 0.0, p[0][0], p[0][1], p[0][2]);
      ecef.Forward(a[3], a[2], 0.0, p[1][0], p[1][1], p[1][2]);
      for (int c = 0; c < 3; ++c)
      {
        chord[k][c] = p[1][c] - p[0][c];
      }
    }
    const double dot = chord[0][0] * chord[1][0] + chord[0][1] * chord[1][1] +
      chord[0][2] * chord[1][2];
    const double norms = std::sqrt(chord[0][0] * chord[0][0] + chord[0][1] * chord[0][1] +
                           chord[0][2] * chord[0][2]) *
      std::sqrt(chord[1][0] * chord[1][0] + chord[1][1] * chord[1][1] +
        chord[1][2] * chord[1][2]);
    cosine = norms > 0.0 ? dot / norms : 0.0;
  }
  catch (const std::exception& e)
  {
    this->Error = std::string("GeographicLib: ") + e.what();
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
vtkApertureGeoreference::vtkApertureGeoreference()
  : Impl(new Internals)
{
  this->GridOrigin[0] = this->GridOrigin[1] = 0.0;
  this->GridSpacing[0] = this->GridSpacing[1] = 1.0;
  this->GridSize[0] = this->GridSize[1] = 0;
}

//------------------------------------------------------------------------------
vtkApertureGeoreference::~vtkApertureGeoreference()
{
  this->Impl->Reset();
  delete this->Impl;
}

//------------------------------------------------------------------------------
const char* vtkApertureGeoreference::GetCRSArrayName()
{
  return "CRS";
}

//------------------------------------------------------------------------------
const char* vtkApertureGeoreference::GetAttachedCRS(vtkDataObject* data)
{
  vtkStringArray* crs = data
    ? vtkStringArray::SafeDownCast(data->GetFieldData()->GetAbstractArray(GetCRSArrayName()))
    : nullptr;
  return crs && crs->GetNumberOfValues() > 0 && !crs->GetValue(0).empty()
    ? crs->GetValue(0).c_str()
    : nullptr;
}

//------------------------------------------------------------------------------
const char* vtkApertureGeoreference::GetGeoTransformArrayName()
{
  return "GeoTransform";
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::SetCRS(const char* definition)
{
  Internals& d = *this->Impl;
  if (!definition || !*definition)
  {
    if (d.CRS)
    {
      d.Reset();
      this->Modified();
    }
    d.Error.clear();
    return true;
  }
  vtkApertureGDALErrorTrap trap;
  OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
  if (OSRSetFromUserInput(srs, definition) != OGRERR_NONE)
  {
    std::string shown(definition);
    if (shown.size() > 60)
    {
      shown = shown.substr(0, 57) + "...";
    }
    d.Error = "GDAL cannot parse the CRS '" + shown + "'" +
      (trap.Message().empty() ? std::string() : ": " + trap.Message());
    OSRRelease(srs);
    return false;
  }
  OSRSetAxisMappingStrategy(srs, OAMS_TRADITIONAL_GIS_ORDER);
  // A geographic CRS's x and y are read as longitude east and latitude north (its units and
  // prime meridian converted) without PROJ: refused where they are not, which PROJ would have
  // placed elsewhere on Earth (a rotated pole's grid near its own equator, not the Earth's).
  // (of a compound CRS, its horizontal part: GDAL says a compound CRS over a rotated pole is
  // geographic, but not derived geographic)
  OGRSpatialReferenceH horizontal = HorizontalPart(srs);
  OGRSpatialReferenceH plane = horizontal ? horizontal : srs;
  std::string unusable;
  if (OSRIsGeographic(plane) && OSRIsDerivedGeographic(plane))
  {
    unusable = "is a rotated-pole (derived geographic) CRS, whose coordinates are not the "
               "Earth's longitudes and latitudes";
  }
  for (int axis = 0; unusable.empty() && OSRIsGeographic(plane) && axis < 2; ++axis)
  {
    OGRAxisOrientation orientation = OAO_Other;
    OSRGetAxis(plane, "GEOGCS", axis, &orientation);
    if (orientation == OAO_West || orientation == OAO_South)
    {
      unusable = std::string("has its ") + (axis == 0 ? "first" : "second") + " axis pointing " +
        (orientation == OAO_West ? "west" : "south");
    }
  }
  if (horizontal)
  {
    OSRRelease(horizontal);
  }
  if (!unusable.empty())
  {
    const char* name = OSRGetName(srs);
    d.Error = std::string("the CRS '") + (name ? name : "unnamed") + "' " + unusable +
      "; warp the DEM to a geographic or projected CRS first (gdalwarp -t_srs EPSG:4326)";
    OSRRelease(srs);
    return false;
  }
  d.Reset();
  d.CRS = srs;
  d.WKT = ExportWKT(srs);
  const char* name = OSRGetName(srs);
  d.Name = name ? name : "";
  char* unit = nullptr;
  if (OSRIsGeographic(srs))
  {
    OSRGetAngularUnits(srs, &unit);
  }
  else
  {
    d.UnitMetres = OSRGetLinearUnits(srs, &unit);
  }
  d.UnitName = unit ? unit : "";
  if (OSRIsCompound(srs) || OSRIsVertical(srs))
  {
    char* vertical = nullptr;
    d.VerticalUnitMetres = OSRGetTargetLinearUnits(srs, "VERT_CS", &vertical);
    d.VerticalUnitName = vertical ? vertical : "";
  }
  d.Error.clear();
  this->Modified();
  return true;
}

//------------------------------------------------------------------------------
const char* vtkApertureGeoreference::GetCRS()
{
  return this->Impl->WKT.c_str();
}

//------------------------------------------------------------------------------
const char* vtkApertureGeoreference::GetHorizontalCRS()
{
  Internals& d = *this->Impl;
  if (d.HorizontalWKT.empty() && d.CRS)
  {
    if (!OSRIsCompound(d.CRS))
    {
      d.HorizontalWKT = d.WKT;
    }
    else
    {
      vtkApertureGDALErrorTrap trap;
      OGRSpatialReferenceH horizontal = HorizontalPart(d.CRS);
      if (horizontal)
      {
        d.HorizontalWKT = ExportWKT(horizontal);
        OSRRelease(horizontal);
      }
      else
      {
        d.Error = "GDAL cannot separate the horizontal part of the compound CRS '" + d.Name +
          "'" + (trap.Message().empty() ? std::string() : ": " + trap.Message());
      }
    }
  }
  return d.HorizontalWKT.c_str();
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::HasCRS()
{
  return this->Impl->CRS != nullptr;
}

//------------------------------------------------------------------------------
void vtkApertureGeoreference::SetGrid(double x0, double y0, double dx, double dy, int nx, int ny)
{
  this->GridOrigin[0] = x0;
  this->GridOrigin[1] = y0;
  this->GridSpacing[0] = dx;
  this->GridSpacing[1] = dy;
  this->GridSize[0] = nx;
  this->GridSize[1] = ny;
  this->Modified();
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::CheckGrid()
{
  const double* o = this->GridOrigin;
  const double* s = this->GridSpacing;
  const int* n = this->GridSize;
  const bool cells = std::isfinite(o[0]) && std::isfinite(o[1]) && s[0] > 0.0 && s[1] > 0.0 &&
    std::isfinite(s[0]) && std::isfinite(s[1]) && n[0] >= 1 && n[1] >= 1;
  if (cells && std::isfinite(o[0] + n[0] * s[0]) && std::isfinite(o[1] + n[1] * s[1]))
  {
    return true;
  }
  std::ostringstream msg;
  msg << (cells ? "the grid's far edges are not finite numbers" : "the grid describes no cells")
      << ": origin " << o[0] << ", " << o[1] << ", cell size " << s[0] << " x " << s[1]
      << (cells ? "" : " (each must be positive)") << ", " << n[0] << " x " << n[1] << " cells";
  this->Impl->Error = msg.str();
  return false;
}

//------------------------------------------------------------------------------
void vtkApertureGeoreference::GetGeoTransform(double gt[6])
{
  gt[0] = this->GridOrigin[0] - 0.5 * this->GridSpacing[0];
  gt[1] = this->GridSpacing[0];
  gt[2] = 0.0;
  gt[3] = this->GridOrigin[1] + (this->GridSize[1] - 0.5) * this->GridSpacing[1];
  gt[4] = 0.0;
  gt[5] = -this->GridSpacing[1];
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::SetFromImage(vtkImageData* image)
{
  Internals& d = *this->Impl;
  if (!image)
  {
    d.Error = "no image";
    return false;
  }
  if (Rotated(image, d.Error))
  {
    return false;
  }
  if (!GridOfImage(image, d.Error))
  {
    return false;
  }
  double spacing[3], origin[3];
  image->GetSpacing(spacing);
  image->GetOrigin(origin);
  int extent[6];
  image->GetExtent(extent);
  const char* crs = GetAttachedCRS(image);
  if (!crs)
  {
    d.Error = "the image has no CRS (field data array 'CRS'); read DEMs with "
              "vtkApertureDEMReader or attach one with vtkApertureGeoreference (SetCRS, such as "
              "'EPSG:32633', or for a grid in metres that is nowhere in particular "
              "'LOCAL_CS[\"grid\",UNIT[\"metre\",1]]'; then AttachToImage)";
    return false;
  }
  if (!this->SetCRS(crs))
  {
    return false;
  }
  this->SetGrid(origin[0] + extent[0] * spacing[0], origin[1] + extent[2] * spacing[1],
    spacing[0], spacing[1], extent[1] - extent[0] + 1, extent[3] - extent[2] + 1);
  return true;
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::HasNorthUpAxes(vtkImageData* image)
{
  // (a z flip, diag(1, 1, -1), was refused as a rotation until 2026-12-07)
  const vtkMatrix3x3* dir = image ? image->GetDirectionMatrix() : nullptr;
  if (!dir)
  {
    return true;
  }
  const double* m = dir->GetData(); // (row-major)
  return m[0] == 1.0 && m[1] == 0.0 && m[2] == 0.0 && m[3] == 0.0 && m[4] == 1.0 &&
    m[5] == 0.0 && m[6] == 0.0 && m[7] == 0.0 && (m[8] == 1.0 || m[8] == -1.0);
}

//------------------------------------------------------------------------------
std::string vtkApertureGeoreference::GetDefaultGeometryWarning(vtkImageData* image)
{
  vtkDataArray* gt = image && image->GetFieldData()
    ? image->GetFieldData()->GetArray(GetGeoTransformArrayName())
    : nullptr;
  if (!gt || gt->GetNumberOfTuples() * gt->GetNumberOfComponents() != 6)
  {
    return std::string();
  }
  double origin[3], spacing[3], g[6];
  image->GetOrigin(origin);
  image->GetSpacing(spacing);
  for (int k = 0; k < 6; ++k)
  {
    g[k] = gt->GetComponent(k / gt->GetNumberOfComponents(), k % gt->GetNumberOfComponents());
  }
  const bool defaults =
    origin[0] == 0.0 && origin[1] == 0.0 && spacing[0] == 1.0 && spacing[1] == 1.0;
  // (a GeoTransform of the default geometry: north-up cells of 1, its west and north edges on
  // the half-integers, at or beyond this extent's: a piece's or a crop's field data describes
  // the whole grid, larger)
  int extent[6];
  image->GetExtent(extent);
  const auto onLattice = [](double edge) {
    return std::fabs(edge - 0.5 - std::round(edge - 0.5)) <= 1e-6;
  };
  const bool same = std::fabs(g[1] - 1.0) <= 1e-9 && std::fabs(g[5] + 1.0) <= 1e-9 &&
    g[2] == 0.0 && g[4] == 0.0 && onLattice(g[0]) && onLattice(g[3]) &&
    g[0] <= extent[0] - 0.5 + 1e-6 && g[3] >= extent[3] + 0.5 - 1e-6;
  if (!defaults || same)
  {
    return std::string();
  }
  std::ostringstream msg;
  msg << std::setprecision(12)
      << "the image's origin and spacing are VTK's defaults (0 0 and 1 1), but its field "
         "data's GeoTransform has cells of "
      << g[1] << " x " << -g[5]
      << " from x " << g[0] << ", y " << g[3]
      << ": the image's geometry is used, cells of 1 CRS unit at the CRS's origin; set the "
         "image's origin and spacing (SetOrigin, SetSpacing: a cell centre and the cell size)";
  return msg.str();
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::WarnOfDefaultGeometry(vtkObject* caller, vtkImageData* image)
{
  const std::string warning = GetDefaultGeometryWarning(image);
  if (!warning.empty())
  {
    vtkWarningWithObjectMacro(caller, << warning);
  }
  return !warning.empty();
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::SetFromInformation(vtkInformation* info)
{
  Internals& d = *this->Impl;
  if (!info || !info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()) ||
    !info->Has(vtkDataObject::ORIGIN()) || !info->Has(vtkDataObject::SPACING()))
  {
    d.Error = "no grid in the pipeline information (its whole extent, origin and spacing)";
    return false;
  }
  int whole[6];
  double origin[3], spacing[3];
  info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  info->Get(vtkDataObject::ORIGIN(), origin);
  info->Get(vtkDataObject::SPACING(), spacing);
  this->SetGrid(origin[0] + whole[0] * spacing[0], origin[1] + whole[2] * spacing[1],
    spacing[0], spacing[1], whole[1] - whole[0] + 1, whole[3] - whole[2] + 1);
  const char* crs = info->Get(CRS_KEY());
  if (!crs || !*crs)
  {
    this->SetCRS(nullptr);
    d.Error = "no CRS in the pipeline information (vtkApertureDEMReader publishes it)";
    return false;
  }
  return this->SetCRS(crs);
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::AttachToImage(vtkImageData* image)
{
  Internals& d = *this->Impl;
  if (!image || !d.CRS)
  {
    d.Error = image ? "no coordinate reference system is set" : "no image";
    return false;
  }
  // (a GeoTransform of its origin and spacing would misplace it; a flipped or NaN spacing was
  // attached until 2026-12-07, and refused only by the filters' updates)
  if (Rotated(image, d.Error) || !GridOfImage(image, d.Error))
  {
    return false;
  }
  vtkNew<vtkStringArray> crs;
  crs->SetName(GetCRSArrayName());
  crs->InsertNextValue(d.WKT);
  double origin[3], spacing[3];
  int extent[6];
  image->GetOrigin(origin);
  image->GetSpacing(spacing);
  image->GetExtent(extent);
  // GeoTransform of the extent the image holds: north-west corner of its north-west cell.
  vtkNew<vtkDoubleArray> gt;
  gt->SetName(GetGeoTransformArrayName());
  gt->SetNumberOfValues(6);
  gt->SetValue(0, origin[0] + (extent[0] - 0.5) * spacing[0]);
  gt->SetValue(1, spacing[0]);
  gt->SetValue(2, 0.0);
  gt->SetValue(3, origin[1] + (extent[3] + 0.5) * spacing[1]);
  gt->SetValue(4, 0.0);
  gt->SetValue(5, -spacing[1]);
  vtkFieldData* fd = image->GetFieldData();
  fd->RemoveArray(GetCRSArrayName());
  fd->RemoveArray(GetGeoTransformArrayName());
  fd->AddArray(crs);
  fd->AddArray(gt);
  return true;
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::IsGeographic()
{
  if (!this->Impl->CRS)
  {
    this->Impl->Error = "no coordinate reference system is set";
    return false;
  }
  return OSRIsGeographic(this->Impl->CRS) != 0;
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::IsLocal()
{
  return this->Impl->IsLocal();
}

namespace
{
// The longitude step (degrees) of a column of geo's grid along its first row, first from half
// a cell (columns up to 360 degrees wide: two of 200 were one of 160 until review), then over
// `span` of them, as many as stay within a quarter of the globe: so that columns 180 degrees
// or more apart, which a difference within +-180 cannot tell, are predicted from it (a global
// Web Mercator grid was "not cylindrical" until 2026-12-07). False when a point has no
// geographic coordinates or the step is 0.
bool ColumnLongitudeStep(vtkApertureGeoreference* geo, double& step, int& span)
{
  double origin[2], spacing[2];
  int size[2];
  geo->GetGridOrigin(origin);
  geo->GetGridSpacing(spacing);
  geo->GetGridSize(size);
  double first[2], half[2], across[2];
  if (size[0] < 2 || !geo->CRSToLonLat(origin[0], origin[1], first) ||
    !geo->CRSToLonLat(origin[0] + 0.5 * spacing[0], origin[1], half))
  {
    return false;
  }
  const double step1 = 2.0 * std::remainder(half[0] - first[0], 360.0);
  if (!std::isfinite(step1) || step1 == 0.0)
  {
    return false;
  }
  span = static_cast<int>(
    std::min<double>(size[0] - 1, std::max(1.0, std::floor(90.0 / std::fabs(step1)))));
  if (std::fabs(step1) > 90.0)
  {
    step = step1; // (one column is a quarter of the globe or more)
    return true;
  }
  if (!geo->CRSToLonLat(origin[0] + span * spacing[0], origin[1], across))
  {
    return false;
  }
  step = std::remainder(across[0] - first[0], 360.0) / span;
  return std::isfinite(step) && step != 0.0;
}

// Whether a projected grid's (geo's) columns are meridians and its rows parallels, with
// longitude linear in x, and `step`, the columns' longitude step (degrees): for
// HasMeridianColumns and WrapsAround. False for a grid of fewer than 2 x 2 cells.
bool MeridianColumnStep(vtkApertureGeoreference* geo, double& step)
{
  double origin[2], spacing[2];
  int size[2];
  geo->GetGridOrigin(origin);
  geo->GetGridSpacing(spacing);
  geo->GetGridSize(size);
  const int nx = size[0], ny = size[1];
  if (nx < 2 || ny < 2)
  {
    return false;
  }
  int span;
  if (!ColumnLongitudeStep(geo, step, span))
  {
    return false;
  }
  const int cols[4] = { 0, span, (nx - 1) / 2, nx - 1 }, rows[3] = { 0, (ny - 1) / 2, ny - 1 };
  double xy[24], ll[24];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      xy[2 * (4 * r + c)] = origin[0] + cols[c] * spacing[0];
      xy[2 * (4 * r + c) + 1] = origin[1] + rows[r] * spacing[1];
    }
  }
  if (!geo->CRSToLonLatPoints(12, xy, ll))
  {
    return false;
  }
  for (double v : ll)
  {
    if (!std::isfinite(v))
    {
      return false;
    }
  }
  const auto lon = [&ll](int r, int c) { return ll[2 * (4 * r + c)]; };
  const auto lat = [&ll](int r, int c) { return ll[2 * (4 * r + c) + 1]; };
  const double cellLon = std::fabs(step);
  const double cellLat = std::fabs(lat(2, 0) - lat(0, 0)) / (ny - 1);
  if (!(cellLat > 0.0))
  {
    return false;
  }
  const double tolLon = std::max(1e-6 * cellLon, 1e-12);
  const double tolLat = std::max(1e-6 * cellLat, 1e-12);
  // (longitudes compared modulo 360: a grid across the antimeridian, or around the globe)
  const auto apart = [](double a, double b) { return std::fabs(std::remainder(a - b, 360.0)); };
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      if (std::fabs(lat(r, c) - lat(r, 0)) > tolLat || apart(lon(r, c), lon(0, c)) > tolLon)
      {
        return false; // (a row that is not a parallel, or a column that is not a meridian)
      }
      if (apart(lon(r, c), lon(r, 0) + cols[c] * step) > tolLon)
      {
        return false; // (longitude not linear in x)
      }
    }
  }
  return true;
}
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::HasMeridianColumns()
{
  if (!this->Impl->CRS)
  {
    this->Impl->Error = "no coordinate reference system is set";
    return false;
  }
  if (OSRIsGeographic(this->Impl->CRS) || this->Impl->IsLocal())
  {
    return true;
  }
  const int nx = this->GridSize[0], ny = this->GridSize[1];
  if (nx < 2 || ny < 2)
  {
    this->Impl->Error = "the grid has fewer than 2 x 2 cells";
    return false;
  }
  double step;
  return MeridianColumnStep(this, step);
}

//------------------------------------------------------------------------------
const char* vtkApertureGeoreference::GetCRSName()
{
  return this->Impl->Name.c_str();
}

//------------------------------------------------------------------------------
const char* vtkApertureGeoreference::GetCRSUnitName()
{
  return this->Impl->UnitName.c_str();
}

//------------------------------------------------------------------------------
double vtkApertureGeoreference::GetCRSUnitMetres()
{
  return this->Impl->UnitMetres;
}

//------------------------------------------------------------------------------
const char* vtkApertureGeoreference::GetVerticalUnitName()
{
  return this->Impl->VerticalUnitName.c_str();
}

//------------------------------------------------------------------------------
double vtkApertureGeoreference::GetVerticalUnitMetres()
{
  return this->Impl->VerticalUnitMetres;
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::GetEllipsoid(double ellipsoid[2])
{
  Internals& d = *this->Impl;
  if (!d.EnsureGeographic())
  {
    return false;
  }
  OGRErr err = OGRERR_NONE;
  const double a = OSRGetSemiMajor(d.Geographic, &err);
  const double invf = OSRGetInvFlattening(d.Geographic, &err);
  if (err != OGRERR_NONE || !(a > 0))
  {
    d.Error = "the CRS '" + d.Name + "' has no usable ellipsoid";
    return false;
  }
  ellipsoid[0] = a;
  ellipsoid[1] = invf > 0 ? 1.0 / invf : 0.0; // invf = 0 means a sphere
  return true;
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::CRSToLonLat(double x, double y, double lonlat[2])
{
  const double xy[2] = { x, y };
  if (!this->CRSToLonLatPoints(1, xy, lonlat))
  {
    return false;
  }
  if (std::isnan(lonlat[0]))
  {
    std::ostringstream msg;
    msg.precision(17);
    msg << "the point (" << x << ", " << y << ") of the CRS '" << this->Impl->Name
        << "' has no geographic coordinates";
    this->Impl->Error = msg.str();
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::CRSToLonLatPoints(vtkIdType n, const double* xy, double* lonlat)
{
  Internals& d = *this->Impl;
  if (!d.EnsureGeographic())
  {
    return false;
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (OSRIsGeographic(d.CRS))
  {
    // A geographic CRS to its own geographic form is the identity up to units and prime
    // meridian: no need to go through PROJ for every point.
    for (vtkIdType k = 0; k < n; ++k)
    {
      const double x = xy[2 * k], y = xy[2 * k + 1];
      const bool good = std::isfinite(x) && std::isfinite(y);
      lonlat[2 * k] = good ? x * d.UnitToDegrees + d.PrimeMeridianDegrees : nan;
      lonlat[2 * k + 1] = good ? y * d.UnitToDegrees : nan;
    }
    d.Error.clear();
    return true;
  }
  vtkApertureGDALErrorTrap trap;
  // OCTTransformEx works on separate x and y arrays; do it in blocks to bound the scratch.
  const vtkIdType block = 4096;
  double xs[4096], ys[4096];
  int ok[4096];
  for (vtkIdType start = 0; start < n; start += block)
  {
    const vtkIdType m = (n - start < block) ? n - start : block;
    for (vtkIdType k = 0; k < m; ++k)
    {
      xs[k] = xy[2 * (start + k)];
      ys[k] = xy[2 * (start + k) + 1];
    }
    OCTTransformEx(d.ToGeographic, static_cast<int>(m), xs, ys, nullptr, ok);
    for (vtkIdType k = 0; k < m; ++k)
    {
      const bool good = ok[k] && std::isfinite(xs[k]) && std::isfinite(ys[k]);
      lonlat[2 * (start + k)] = good ? xs[k] * d.UnitToDegrees + d.PrimeMeridianDegrees : nan;
      lonlat[2 * (start + k) + 1] = good ? ys[k] * d.UnitToDegrees : nan;
    }
  }
  d.Error.clear();
  return true;
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::LonLatToCRS(double lon, double lat, double xy[2])
{
  Internals& d = *this->Impl;
  if (!d.EnsureGeographic())
  {
    return false;
  }
  vtkApertureGDALErrorTrap trap;
  double x = (lon - d.PrimeMeridianDegrees) / d.UnitToDegrees;
  double y = lat / d.UnitToDegrees;
  int ok = 0;
  if (!OCTTransformEx(d.FromGeographic, 1, &x, &y, nullptr, &ok) || !ok || !std::isfinite(x) ||
    !std::isfinite(y))
  {
    std::ostringstream msg;
    msg << "the geographic point (" << lon << ", " << lat << ") has no coordinates in the CRS '"
        << d.Name << "'";
    d.Error = msg.str();
    return false;
  }
  xy[0] = x;
  xy[1] = y;
  d.Error.clear();
  return true;
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::GetCentreLonLat(double lonlat[2])
{
  if (!this->CheckGrid()) // (a grid of no cells had a centre until 2026-12-06)
  {
    return false;
  }
  const double xc = this->GridOrigin[0] + 0.5 * (this->GridSize[0] - 1) * this->GridSpacing[0];
  const double yc = this->GridOrigin[1] + 0.5 * (this->GridSize[1] - 1) * this->GridSpacing[1];
  if (!this->CRSToLonLat(xc, yc, lonlat))
  {
    return false;
  }
  if (BeyondPole(lonlat[1]))
  {
    std::ostringstream msg;
    msg << "the grid centre is at latitude " << lonlat[1] << ", beyond the pole";
    this->Impl->Error = msg.str();
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
namespace
{
// How far from 360 degrees the longitudes of a global grid of `cell` degree cells may sum: a
// thousandth of a cell (cell sizes written with 9 or 10 digits, 0.333333333 for 1/3, sum to
// 360 less 3.6e-7 over 1080 columns, and were taken for a grid one seam short until
// 2026-12-06, or, 1e-7 over, refused as wider than the Earth).
double SpanSlack(double cell)
{
  return 1e-3 * std::fabs(cell);
}

// The longitude width (degrees) of a column of geo's grid: a lat/lon grid's spacing as it is
// (its CRS unit `toDegrees` degrees), a cylindrical projection's (Mercator, equirectangular)
// step, its magnitude; false for other projected grids. For WrapsAround and CheckLongitudeSpan.
bool ColumnDegrees(vtkApertureGeoreference* geo, bool geographic, double toDegrees, double& cell)
{
  if (geographic)
  {
    double spacing[2];
    geo->GetGridSpacing(spacing);
    cell = spacing[0] * toDegrees;
    return true;
  }
  if (!MeridianColumnStep(geo, cell))
  {
    return false;
  }
  cell = std::fabs(cell);
  return true;
}
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::WrapsAround()
{
  Internals& d = *this->Impl;
  double cell;
  if (!d.CRS || d.IsLocal() || !d.EnsureGeographic() ||
    !ColumnDegrees(this, OSRIsGeographic(d.CRS), d.UnitToDegrees, cell))
  {
    return false;
  }
  cell = std::fabs(cell);
  return std::fabs(this->GridSize[0] * cell - 360.0) <= SpanSlack(cell);
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::CheckLongitudeSpan()
{
  Internals& d = *this->Impl;
  if (!d.EnsureGeographic())
  {
    return false;
  }
  d.Error.clear();
  const bool geographic = OSRIsGeographic(d.CRS);
  // (a cylindrical projection's columns have a longitude step too: 361 columns of one degree
  // of Web Mercator were baked as a strip with two west edges, the same ground at both ends,
  // until 2026-12-07; other projections' grids are not checked)
  double cell;
  if (!ColumnDegrees(this, geographic, d.UnitToDegrees, cell))
  {
    d.Error.clear();
    return true;
  }
  const double span = this->GridSize[0] * cell;
  if (span > 360.0 + SpanSlack(cell))
  {
    std::ostringstream msg;
    msg << std::setprecision(12) << "the grid spans " << span << " degrees of longitude ("
        << this->GridSize[0] << " columns of " << cell
        << " degrees), more than the 360 around the Earth";
    if (std::fabs(span - cell - 360.0) <= SpanSlack(cell))
    {
      // GMT's and ETOPO's gridline registration: cells centred on both -180 and 180, and on
      // the poles when the grid reaches them (their cells half beyond)
      double south, north;
      if (geographic)
      {
        const double dy = this->GridSpacing[1] * d.UnitToDegrees;
        south = this->GridOrigin[1] * d.UnitToDegrees - 0.5 * dy;
        north = south + this->GridSize[1] * dy;
      }
      else
      {
        // (the latitudes of the grid's south and north edges; PROJ gives an equirectangular
        // grid's beyond a pole as more than 90 degrees)
        const double x0 = this->GridOrigin[0], y0 = this->GridOrigin[1];
        const double dy = this->GridSpacing[1];
        const double xy[4] = { x0, y0 - 0.5 * dy, x0, y0 + (this->GridSize[1] - 0.5) * dy };
        double ll[4];
        south = north = 0.0;
        if (this->CRSToLonLatPoints(2, xy, ll) && std::isfinite(ll[1]) && std::isfinite(ll[3]))
        {
          south = std::min(ll[1], ll[3]);
          north = std::max(ll[1], ll[3]);
        }
      }
      const int dropNorth = north > 90.0 + 1e-9 ? 1 : 0, dropSouth = south < -90.0 - 1e-9 ? 1 : 0;
      msg << ": its first and last columns are one meridian (a gridline-registered global "
             "grid); drop the last column"
          << (dropNorth + dropSouth ? " and the rows centred on a pole" : "")
          << " first (gdal_translate -srcwin 0 " << dropNorth << " " << this->GridSize[0] - 1
          << " " << this->GridSize[1] - dropNorth - dropSouth
          << "; with -of VRT it copies nothing)";
    }
    else
    {
      msg << ": a wrong cell size or unit?";
    }
    d.Error = msg.str();
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::GetBoundsLonLat(double bounds[4])
{
  Internals& d = *this->Impl;
  // (NaN unless they are found: a failure beyond a pole left its degrees there, which read as
  // bounds)
  std::fill(bounds, bounds + 4, std::numeric_limits<double>::quiet_NaN());
  if (!this->CheckGrid() || !this->CheckLongitudeSpan())
  {
    return false;
  }
  double gt[6];
  this->GetGeoTransform(gt);
  const double xmin = gt[0];
  const double xmax = gt[0] + this->GridSize[0] * gt[1];
  const double ymax = gt[3];
  const double ymin = gt[3] + this->GridSize[1] * gt[5];
  vtkApertureGDALErrorTrap trap;
  double w, s, e, n;
  if (!OCTTransformBounds(d.ToGeographic, xmin, ymin, xmax, ymax, &w, &s, &e, &n, 21))
  {
    d.Error = "the grid's bounds have no geographic coordinates in the CRS '" + d.Name +
      "': " + trap.Message("PROJ gave no reason");
    return false;
  }
  bounds[0] = w * d.UnitToDegrees + d.PrimeMeridianDegrees;
  bounds[1] = s * d.UnitToDegrees;
  bounds[2] = e * d.UnitToDegrees + d.PrimeMeridianDegrees;
  bounds[3] = n * d.UnitToDegrees;
  // A geographic grid's coordinates pass through as they are: an edge beyond a pole is no
  // place on the Earth.
  for (int k = 1; k < 4; k += 2)
  {
    if (BeyondPole(bounds[k]))
    {
      std::ostringstream msg;
      msg << "the grid's " << (k == 1 ? "south" : "north") << " edge is at latitude "
          << bounds[k] << ", beyond the " << (bounds[k] < 0.0 ? "south" : "north")
          << " pole: a wrong origin, cell size or unit?";
      d.Error = msg.str();
      std::fill(bounds, bounds + 4, std::numeric_limits<double>::quiet_NaN());
      return false;
    }
  }
  d.Error.clear();
  return true;
}

//------------------------------------------------------------------------------
std::string vtkApertureGeoreference::GetElevationWarning(
  double min, double max, const char* what)
{
  // The range of the Earth's surface with a margin (m): Challenger Deep about -10,935 m,
  // Everest 8,849 m, orthometric or ellipsoidal (the geoid is within about 110 m of it).
  const double lowest = -11100.0, highest = 9000.0;
  std::ostringstream msg;
  double cell[2];
  if (min < lowest || max > highest)
  {
    msg << "elevations range from " << min << " to " << max << " m, beyond any on Earth ("
        << lowest << " to " << highest
        << " m): a nodata value the DEM does not declare, or heights not in metres? ";
  }
  else if (this->GetCellSizeMetres(cell) &&
    max - min > 10.0 * std::max(this->GridSize[0] * cell[0], this->GridSize[1] * cell[1]))
  {
    msg << "elevations range over " << max - min << " m on a grid of "
        << this->GridSize[0] * cell[0] << " x " << this->GridSize[1] * cell[1]
        << " m (cells of " << cell[0] << " x " << cell[1]
        << " m), steeper than any terrain: a CRS whose unit does not fit the grid's "
           "coordinates (degrees taken for metres?), or heights not in metres? ";
  }
  else
  {
    return std::string();
  }
  msg << (what ? what : "Products made of them") << " are meaningless";
  return msg.str();
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::GetCellSizeMetres(double size[2])
{
  const double xc = this->GridOrigin[0] + 0.5 * (this->GridSize[0] - 1) * this->GridSpacing[0];
  const double yc = this->GridOrigin[1] + 0.5 * (this->GridSize[1] - 1) * this->GridSpacing[1];
  if (!this->GetCellSizeMetresAt(xc, yc, size))
  {
    if (this->Impl->Error == "the cell has no geographic coordinates")
    {
      this->Impl->Error = "the grid centre has no geographic coordinates";
    }
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::GetCellSizeMetresAt(double xc, double yc, double size[2])
{
  if (!this->CheckGrid())
  {
    return false;
  }
  double cosine;
  if (this->Impl->IsLocal() ? !this->Impl->LocalCellSize(this->GridSpacing, size)
                            : !this->Impl->CellVectors(this, xc, yc, size, cosine))
  {
    return false;
  }
  if (!(size[0] > 0.0 && size[1] > 0.0 && std::isfinite(size[0] + size[1])))
  {
    // (a cell lost to rounding: 1e-300 degrees, or a longitude of 1e17)
    std::ostringstream msg;
    msg << "the grid's cells have no positive size on the ground (" << size[0] << " x "
        << size[1] << " m): a wrong origin or spacing?";
    this->Impl->Error = msg.str();
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::GetCellMetricAt(double xc, double yc, double metric[3])
{
  double size[2], cosine = 0.0; // (a local grid's axes are perpendicular)
  if (this->Impl->IsLocal() ? !this->Impl->LocalCellSize(this->GridSpacing, size)
                            : !this->Impl->CellVectors(this, xc, yc, size, cosine))
  {
    return false;
  }
  metric[0] = size[0] * size[0];
  metric[1] = size[0] * size[1] * cosine;
  metric[2] = size[1] * size[1];
  return true;
}

//------------------------------------------------------------------------------
double vtkApertureGeoreference::ComputeMeridianConvergence(double lon, double lat)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!this->Impl->EnsureGeographic())
  {
    return nan;
  }
  if (OSRIsGeographic(this->Impl->CRS))
  {
    return 0.0;
  }
  // The grid bearing of a short step north from (lon, lat) is -gamma (ALGORITHMS.md 5).
  const double step = lat < 89.0 ? 1e-5 : -1e-5;
  double a[2], b[2];
  if (!this->LonLatToCRS(lon, lat, a) || !this->LonLatToCRS(lon, lat + step, b))
  {
    return nan;
  }
  double dx = b[0] - a[0], dy = b[1] - a[1];
  if (step < 0)
  {
    dx = -dx;
    dy = -dy;
  }
  return -std::atan2(dx, dy) * 180.0 / M_PI;
}

//------------------------------------------------------------------------------
bool vtkApertureGeoreference::GetRowCellSizesMetres(double* dx, double* dy)
{
  return this->GetRowCellSizesMetres(0, this->GridSize[1], dx, dy);
}

bool vtkApertureGeoreference::GetRowCellSizesMetres(int first, int count, double* dx, double* dy)
{
  if (!this->CheckGrid())
  {
    return false;
  }
  if (first < 0 || count < 0 || first > this->GridSize[1] - count)
  {
    std::ostringstream msg;
    msg << "rows " << first << " to " << static_cast<long long>(first) + count - 1
        << " are not rows of the grid's " << this->GridSize[1];
    this->Impl->Error = msg.str();
    return false;
  }
  if (this->Impl->IsLocal())
  {
    double size[2];
    if (!this->Impl->LocalCellSize(this->GridSpacing, size))
    {
      return false;
    }
    std::fill(dx, dx + count, size[0]);
    std::fill(dy, dy + count, size[1]);
    return true;
  }
  double ell[2];
  if (!this->CheckLongitudeSpan() || !this->GetEllipsoid(ell))
  {
    return false;
  }
  const int nx = this->GridSize[0];
  const double xc = this->GridOrigin[0] + 0.5 * (nx - 1) * this->GridSpacing[0];
  const double hx = 0.5 * this->GridSpacing[0], hy = 0.5 * this->GridSpacing[1];
  // (rows in chunks, so that the points' arrays stay small on a grid of millions of rows)
  const int chunk = std::min(count, 4096);
  std::vector<double> xy(8 * static_cast<size_t>(chunk)), ll(8 * static_cast<size_t>(chunk));
  try
  {
    const GeographicLib::Geodesic geod(ell[0], ell[1]);
    // a row named so that users of north-up files find it: by its y, then its grid index
    const auto row = [this](std::ostringstream& msg, int j) -> std::ostringstream& {
      msg << "the row of cells at y = " << this->GridOrigin[1] + j * this->GridSpacing[1]
          << " (grid row " << j << ", counted from the south)";
      return msg;
    };
    for (int c0 = 0; c0 < count; c0 += chunk)
    {
      const int rows = std::min(chunk, count - c0);
      for (int r = 0; r < rows; ++r)
      {
        const double y = this->GridOrigin[1] + (first + c0 + r) * this->GridSpacing[1];
        const double pts[8] = { xc - hx, y, xc + hx, y, xc, y - hy, xc, y + hy };
        std::copy(pts, pts + 8, xy.begin() + 8 * r);
      }
      if (!this->CRSToLonLatPoints(4 * static_cast<vtkIdType>(rows), xy.data(), ll.data()))
      {
        return false;
      }
      for (int r = 0; r < rows; ++r)
      {
        const int j = first + c0 + r, k0 = c0 + r;
        double* q = &ll[8 * static_cast<size_t>(r)];
        for (int k = 0; k < 8; ++k)
        {
          if (std::isnan(q[k]))
          {
            std::ostringstream msg;
            row(msg, j) << " has no geographic coordinates";
            this->Impl->Error = msg.str();
            return false;
          }
        }
        for (int k = 1; k < 8; k += 2)
        {
          // (GeographicLib gives NaN for an edge a rounding error beyond the pole: clamp that,
          // refuse more)
          if (BeyondPole(q[k]))
          {
            std::ostringstream msg;
            row(msg, j) << " reaches latitude " << q[k] << ", beyond the pole";
            this->Impl->Error = msg.str();
            return false;
          }
          q[k] = std::max(-90.0, std::min(90.0, q[k]));
        }
        geod.Inverse(q[1], q[0], q[3], q[2], dx[k0]);
        geod.Inverse(q[5], q[4], q[7], q[6], dy[k0]);
        if (!(std::isfinite(dx[k0]) && dx[k0] > 0.0 && std::isfinite(dy[k0]) && dy[k0] > 0.0))
        {
          std::ostringstream msg;
          row(msg, j) << " has no positive ground cell size (" << dx[k0] << " m east-west, "
                      << dy[k0] << " m north-south)";
          this->Impl->Error = msg.str();
          return false;
        }
      }
    }
  }
  catch (const std::exception& e)
  {
    this->Impl->Error = std::string("GeographicLib: ") + e.what();
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
const char* vtkApertureGeoreference::GetErrorMessage()
{
  return this->Impl->Error.c_str();
}

//------------------------------------------------------------------------------
void vtkApertureGeoreference::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CRS: " << (this->Impl->Name.empty() ? "(none)" : this->Impl->Name) << "\n";
  os << indent << "GridOrigin: " << this->GridOrigin[0] << ", " << this->GridOrigin[1] << "\n";
  os << indent << "GridSpacing: " << this->GridSpacing[0] << ", " << this->GridSpacing[1] << "\n";
  os << indent << "GridSize: " << this->GridSize[0] << ", " << this->GridSize[1] << "\n";
  os << indent << "ErrorMessage: " << this->Impl->Error << "\n";
}
