// SPDX-License-Identifier: BSD-3-Clause
// vtkApertureGeoreference: CRS parsing, geographic coordinates (projected, geographic, grads
// from Paris), bounds, metric cell size against closed forms, ellipsoids, field-data round
// trip and errors.
#include "aptest.hxx"

#include "vtkApertureGeoreference.h"

#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <GeographicLib/TransverseMercator.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace
{
const double kDeg = 3.14159265358979323846 / 180.0;

void TestProjected()
{
  vtkNew<vtkApertureGeoreference> geo;
  AP_CHECK(geo->SetCRS("EPSG:32611"));
  AP_CHECK(geo->HasCRS() && !geo->IsGeographic());
  AP_CHECK(std::string(geo->GetCRSName()) == "WGS 84 / UTM zone 11N");
  AP_CHECK(std::string(geo->GetCRSUnitName()) == "metre");
  AP_CHECK(geo->GetCRSUnitMetres() == 1.0);
  AP_CHECK(geo->GetVerticalUnitMetres() == 0.0 && !*geo->GetVerticalUnitName());
  // Units in feet: a state plane (US survey feet, 1200/3937 m), with NAVD88 heights in the same
  // unit as a compound CRS; the horizontal unit is the projected part's.
  vtkNew<vtkApertureGeoreference> feet;
  AP_CHECK(feet->SetCRS("EPSG:2263"));
  AP_CHECK_NEAR(feet->GetCRSUnitMetres(), 1200.0 / 3937.0, 1e-15);
  AP_CHECK(feet->GetVerticalUnitMetres() == 0.0);
  AP_CHECK(feet->SetCRS("EPSG:2263+6360"));
  AP_CHECK_NEAR(feet->GetCRSUnitMetres(), 1200.0 / 3937.0, 1e-15);
  AP_CHECK_NEAR(feet->GetVerticalUnitMetres(), 1200.0 / 3937.0, 1e-15);
  AP_CHECK(std::string(feet->GetVerticalUnitName()) == "US survey foot");
  AP_CHECK(feet->SetCRS("EPSG:32611+5703")); // (UTM 11N + NAVD88 height in metres)
  AP_CHECK(feet->GetCRSUnitMetres() == 1.0 && feet->GetVerticalUnitMetres() == 1.0);
  AP_CHECK(feet->SetCRS("EPSG:32611")); // (a new CRS forgets the vertical part)
  AP_CHECK(feet->GetVerticalUnitMetres() == 0.0 && !*feet->GetVerticalUnitName());
  // The false origin of UTM zone 11N: the equator on the central meridian, 117 W.
  double ll[2];
  AP_CHECK(geo->CRSToLonLat(500000.0, 0.0, ll));
  AP_CHECK_NEAR(ll[0], -117.0, 1e-12);
  AP_CHECK_NEAR(ll[1], 0.0, 1e-12);
  double xy[2];
  AP_CHECK(geo->LonLatToCRS(-118.25, 34.05, xy));
  AP_CHECK(geo->CRSToLonLat(xy[0], xy[1], ll));
  AP_CHECK_NEAR(ll[0], -118.25, 1e-9);
  AP_CHECK_NEAR(ll[1], 34.05, 1e-9);
  // A 101 x 101 grid of 30 m cells centred on the central meridian: ground cell size 30 / k0.
  geo->SetGrid(500000.0 - 50 * 30.0, 4000000.0, 30.0, 30.0, 101, 101);
  double size[2];
  AP_CHECK(geo->GetCellSizeMetres(size));
  AP_CHECK_NEAR(size[0], 30.0 / 0.9996, 1e-6);
  AP_CHECK_NEAR(size[1], 30.0 / 0.9996, 1e-6);
  // Elsewhere the scale factor k of GeographicLib's exact transverse Mercator (zone 11: 117 W)
  // gives 30 / k: 300 km east of the central meridian k is 1.0007 (not 0.9996); the grid
  // centre through GetCellSizeMetresAt is GetCellSizeMetres.
  {
    double at[2], p[2];
    AP_CHECK(geo->GetCellSizeMetresAt(500000.0, 4001500.0, at));
    AP_CHECK(at[0] == size[0] && at[1] == size[1]);
    AP_CHECK(geo->CRSToLonLat(800000.0, 4001500.0, p));
    double x, y, gamma, k;
    GeographicLib::TransverseMercator::UTM().Forward(-117.0, p[1], p[0], x, y, gamma, k);
    AP_CHECK(k > 1.0005);
    AP_CHECK(geo->GetCellSizeMetresAt(800000.0, 4001500.0, at));
    AP_CHECK_NEAR(at[0], 30.0 / k, 1e-5);
    AP_CHECK_NEAR(at[1], 30.0 / k, 1e-5);
  }
  // Bounds: symmetric about 117 W; they enclose the transformed corners.
  double b[4], centre[2];
  AP_CHECK(geo->GetBoundsLonLat(b));
  AP_CHECK(geo->GetCentreLonLat(centre));
  AP_CHECK_NEAR(centre[0], -117.0, 1e-9);
  AP_CHECK_NEAR(-117.0 - b[0], b[2] + 117.0, 1e-9);
  double gt[6];
  geo->GetGeoTransform(gt);
  AP_CHECK_NEAR(gt[0], 500000.0 - 50 * 30.0 - 15.0, 1e-9);
  AP_CHECK_NEAR(gt[3], 4000000.0 + 100 * 30.0 + 15.0, 1e-9);
  AP_CHECK_NEAR(gt[5], -30.0, 0.0);
  const double corners[4][2] = { { gt[0], gt[3] }, { gt[0] + 101 * 30.0, gt[3] },
    { gt[0], gt[3] - 101 * 30.0 }, { gt[0] + 101 * 30.0, gt[3] - 101 * 30.0 } };
  for (const auto& c : corners)
  {
    AP_CHECK(geo->CRSToLonLat(c[0], c[1], ll));
    AP_CHECK(ll[0] >= b[0] - 1e-12 && ll[0] <= b[2] + 1e-12);
    AP_CHECK(ll[1] >= b[1] - 1e-12 && ll[1] <= b[3] + 1e-12);
  }
  double ellipsoid[2];
  AP_CHECK(geo->GetEllipsoid(ellipsoid));
  AP_CHECK_NEAR(ellipsoid[0], 6378137.0, 0.0);
  AP_CHECK_NEAR(1.0 / ellipsoid[1], 298.257223563, 1e-9);
}

void TestGeographic()
{
  vtkNew<vtkApertureGeoreference> geo;
  AP_CHECK(geo->SetCRS("EPSG:4326"));
  AP_CHECK(geo->IsGeographic());
  AP_CHECK(std::string(geo->GetCRSUnitName()) == "degree");
  AP_CHECK(geo->GetCRSUnitMetres() == 0.0);
  // 3 arc-second cells at 36.3 N: east-west N cos(lat) dlon, north-south M dlat (closed forms
  // of the prime vertical and meridian radii; the geodesic over 90 m differs by < 1e-9).
  const double cell = 1.0 / 1200.0, lat = 36.3;
  geo->SetGrid(-84.4, lat - 100 * cell, cell, cell, 201, 201);
  double size[2];
  AP_CHECK(geo->GetCellSizeMetres(size));
  const double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2 - f);
  const double s = std::sin(lat * kDeg), w = std::sqrt(1 - e2 * s * s);
  AP_CHECK_NEAR(size[0], a / w * std::cos(lat * kDeg) * cell * kDeg, 1e-6);
  AP_CHECK_NEAR(size[1], a * (1 - e2) / (w * w * w) * cell * kDeg, 1e-6);
  double b[4];
  AP_CHECK(geo->GetBoundsLonLat(b));
  AP_CHECK_NEAR(b[0], -84.4 - 0.5 * cell, 1e-12);
  AP_CHECK_NEAR(b[1], lat - 100.5 * cell, 1e-12);
  AP_CHECK_NEAR(b[2], -84.4 + 200.5 * cell, 1e-12);
  AP_CHECK_NEAR(b[3], lat + 100.5 * cell, 1e-12);
}

// A geographic CRS in grads counted from Paris (NTF (Paris), EPSG:4807) reports degrees from
// Greenwich: 50 grad north is 45 degrees; 0 grad east of Paris is 2.33722917 degrees east.
void TestGradsFromParis()
{
  vtkNew<vtkApertureGeoreference> geo;
  AP_CHECK(geo->SetCRS("EPSG:4807"));
  double ll[2];
  AP_CHECK(geo->CRSToLonLat(0.0, 50.0, ll));
  AP_CHECK_NEAR(ll[0], 2.33722917, 1e-8);
  AP_CHECK_NEAR(ll[1], 45.0, 1e-9);
  double ellipsoid[2];
  AP_CHECK(geo->GetEllipsoid(ellipsoid));
  AP_CHECK_NEAR(ellipsoid[0], 6378249.2, 1e-6); // Clarke 1880 (IGN)
}

void TestErrors()
{
  vtkNew<vtkApertureGeoreference> geo;
  AP_CHECK(!geo->SetCRS("not a CRS at all"));
  AP_CHECK(std::string(geo->GetErrorMessage()).find("cannot parse") != std::string::npos);
  AP_CHECK(!geo->HasCRS());
  double ll[2];
  AP_CHECK(!geo->CRSToLonLat(0, 0, ll));
  AP_CHECK(std::string(geo->GetErrorMessage()).find("no coordinate reference system") !=
    std::string::npos);
  AP_CHECK(geo->SetCRS("LOCAL_CS[\"mine site\",UNIT[\"metre\",1]]"));
  AP_CHECK(!geo->CRSToLonLat(0, 0, ll));
  AP_CHECK(std::string(geo->GetErrorMessage()).find("no geographic coordinates") !=
    std::string::npos);
  // a success in between does not take the reason from the next failure (the geographic
  // form is tried once: until 2026-12-07 the later failures said nothing)
  {
    double cell[2];
    geo->SetGrid(0.0, 0.0, 10.0, 10.0, 10, 10);
    AP_CHECK(geo->GetCellSizeMetres(cell) && std::string(geo->GetErrorMessage()).empty());
    AP_CHECK(!geo->GetCentreLonLat(ll));
    AP_CHECK_CONTAINS(geo->GetErrorMessage(), "no geographic coordinates");
    AP_CHECK(geo->GetCellSizeMetres(cell));
    AP_CHECK(std::isnan(geo->ComputeMeridianConvergence(5.0, 5.0)));
    AP_CHECK_CONTAINS(geo->GetErrorMessage(), "no geographic coordinates");
  }
  // Geographic CRSs whose x and y are not longitude east and latitude north are refused (the
  // previous CRS kept): until 2026-12-07 a rotated pole's grid near its own equator was read
  // as if on the Earth's, and a west/south axis as east/north, silently 20-30 degrees off.
  AP_CHECK(geo->SetCRS("EPSG:4326"));
  const std::string wgs84 = geo->GetCRS();
  AP_CHECK(!geo->SetCRS("+proj=ob_tran +o_proj=longlat +o_lat_p=30 +o_lon_p=0 +lon_0=10 "
                        "+ellps=WGS84"));
  AP_CHECK_CONTAINS(geo->GetErrorMessage(),
    "is a rotated-pole (derived geographic) CRS, whose coordinates are not the Earth's "
    "longitudes and latitudes; warp the DEM to a geographic or projected CRS first");
  // (and as the horizontal part of a compound CRS, which GDAL calls geographic, not derived)
  AP_CHECK(!geo->SetCRS("+proj=ob_tran +o_proj=longlat +o_lat_p=30 +o_lon_p=0 +lon_0=10 "
                        "+ellps=WGS84 +geoidgrids=egm96_15.gtx +vunits=m"));
  AP_CHECK_CONTAINS(geo->GetErrorMessage(), "is a rotated-pole (derived geographic) CRS");
  AP_CHECK(!geo->SetCRS("+proj=longlat +ellps=WGS84 +axis=wsu"));
  AP_CHECK_CONTAINS(geo->GetErrorMessage(), "has its first axis pointing west");
  AP_CHECK(!geo->SetCRS("+proj=longlat +ellps=WGS84 +axis=esu"));
  AP_CHECK_CONTAINS(geo->GetErrorMessage(), "has its second axis pointing south");
  AP_CHECK(geo->GetCRS() == wgs84);
  // (latitude first, as EPSG:4326 itself declares, is read in GIS order: x the longitude)
  AP_CHECK(geo->SetCRS("+proj=longlat +ellps=WGS84 +axis=neu"));
  AP_CHECK(geo->CRSToLonLat(-84.3, 36.3, ll) && ll[0] == -84.3 && ll[1] == 36.3);
  // a projected CRS with westing and southing axes goes through PROJ, which honours them:
  // EPSG:2053 (Hartebeesthoek94 / Lo29, South Africa), the point 30 km west, 3000 km south of
  // its origin (29 E on the equator) lies west of 29 E
  AP_CHECK(geo->SetCRS("EPSG:2053"));
  AP_CHECK(geo->CRSToLonLat(30000.0, 3000000.0, ll) && ll[0] < 29.0 && ll[1] < -27.0);
  AP_CHECK(geo->SetCRS("EPSG:4978")); // WGS 84 geocentric
  AP_CHECK(!geo->CRSToLonLat(4e6, 4e6, ll));
  AP_CHECK(std::string(geo->GetErrorMessage()).find("is geocentric") != std::string::npos);
  double size[2];
  geo->SetGrid(4e6, 4e6, 30.0, 30.0, 3, 3);
  AP_CHECK(!geo->GetCellSizeMetres(size));
  AP_CHECK(std::string(geo->GetErrorMessage()).find("is geocentric") != std::string::npos);
  AP_CHECK(geo->SetCRS(nullptr) && !geo->HasCRS());

  vtkNew<vtkImageData> image;
  image->SetDimensions(3, 3, 1);
  AP_CHECK(!geo->SetFromImage(image));
  AP_CHECK(std::string(geo->GetErrorMessage()).find("has no CRS") != std::string::npos);
  AP_CHECK(!geo->AttachToImage(image));
  AP_CHECK(!vtkApertureGeoreference::GetAttachedCRS(image));
  AP_CHECK(!vtkApertureGeoreference::GetAttachedCRS(nullptr));
  AP_CHECK(geo->SetCRS("EPSG:4326") && geo->AttachToImage(image));
  AP_CHECK(vtkApertureGeoreference::GetAttachedCRS(image) &&
    std::string(vtkApertureGeoreference::GetAttachedCRS(image)) == geo->GetCRS());
  AP_CHECK(geo->SetFromImage(image));
  image->SetSpacing(0.0, 1.0, 1.0);
  AP_CHECK(!geo->SetFromImage(image));
  image->SetSpacing(1.0, 1.0, 1.0);
  vtkNew<vtkMatrix3x3> rotation;
  rotation->SetElement(0, 0, 0.0);
  rotation->SetElement(0, 1, -1.0);
  rotation->SetElement(1, 0, 1.0);
  rotation->SetElement(1, 1, 0.0);
  image->SetDirectionMatrix(rotation);
  AP_CHECK(!geo->SetFromImage(image));
  AP_CHECK(std::string(geo->GetErrorMessage()).find("north-up") != std::string::npos);
  // a mirror is refused as a rotation is; a z flip alone turns neither x nor y of a one-slice
  // DEM (refused as "rotated" until 2026-12-07). (The image holds `rotation` itself: the
  // values below are written into a matrix of its own.)
  image->SetDirectionMatrix(vtkNew<vtkMatrix3x3>());
  const double mirrorX[9] = { -1, 0, 0, 0, 1, 0, 0, 0, 1 }, flipZ[9] = { 1, 0, 0, 0, 1, 0, 0, 0,
    -1 };
  image->SetDirectionMatrix(mirrorX);
  AP_CHECK(!geo->SetFromImage(image) && !vtkApertureGeoreference::HasNorthUpAxes(image));
  AP_CHECK_CONTAINS(geo->GetErrorMessage(), "rotates or mirrors its x and y axes");
  image->SetDirectionMatrix(flipZ);
  AP_CHECK(geo->SetFromImage(image) && vtkApertureGeoreference::HasNorthUpAxes(image));
  image->SetDirectionMatrix(rotation);
  // nor attached to one: a GeoTransform of its origin and spacing would place it elsewhere
  // (it did until 2026-12-07: a south-up direction put its north edge beyond its points)
  image->GetFieldData()->Initialize();
  AP_CHECK(!geo->AttachToImage(image));
  AP_CHECK(std::string(geo->GetErrorMessage()).find("north-up") != std::string::npos);
  AP_CHECK(!vtkApertureGeoreference::GetAttachedCRS(image));
  // nor a spacing that is not positive and finite (attached until 2026-12-07: a y spacing of
  // -10, numpy's north-up rows, gave a GeoTransform of a south-up grid, and a NaN one a NaN
  // origin; the filters refused them only at their updates); as SetFromImage refuses them
  image->SetDirectionMatrix(vtkNew<vtkMatrix3x3>());
  const double spacings[][2] = { { 10.0, -10.0 }, { NAN, 10.0 }, { 10.0, 0.0 },
    { -10.0, 10.0 } };
  for (const auto& s : spacings)
  {
    image->SetSpacing(s[0], s[1], 1.0);
    AP_CHECK(!geo->AttachToImage(image));
    AP_CHECK_CONTAINS(geo->GetErrorMessage(), "the image spacing must be positive");
    AP_CHECK(!vtkApertureGeoreference::GetAttachedCRS(image));
    AP_CHECK(!geo->SetFromImage(image));
    AP_CHECK_CONTAINS(geo->GetErrorMessage(), "the image spacing must be positive");
  }
  image->SetSpacing(10.0, -10.0, 1.0); // (what to do, said)
  AP_CHECK(!geo->AttachToImage(image));
  AP_CHECK_CONTAINS(geo->GetErrorMessage(), "(its y spacing is negative): VTK's rows run from "
                                            "south to north; give them in that order");
  image->SetSpacing(1e308, 1.0, 1.0);
  AP_CHECK(!geo->AttachToImage(image));
  AP_CHECK_CONTAINS(geo->GetErrorMessage(), "the image's west and east edges are not finite");
  image->SetSpacing(10.0, 10.0, 1.0);
  AP_CHECK(geo->AttachToImage(image) && geo->SetFromImage(image));

  // A grid of no cells given to SetGrid: its queries fail saying so (they answered with cells
  // of 0 m and bounds west of east, as successes, until 2026-12-06); cells lost to rounding
  // (1e-300 degrees) have no size on the ground.
  AP_CHECK(geo->SetCRS("EPSG:4326"));
  double bounds[4];
  const struct
  {
    double dx, dy;
    int nx, ny;
  } none[] = { { 0.0, 1.0, 10, 10 }, { -1.0, 1.0, 10, 10 }, { 1.0, NAN, 10, 10 },
    { 1.0, 1.0, -5, 10 }, { 1.0, 1.0, 10, 0 } };
  for (const auto& g : none)
  {
    geo->SetGrid(0.0, 0.0, g.dx, g.dy, g.nx, g.ny);
    AP_CHECK(!geo->GetCellSizeMetres(size));
    AP_CHECK_CONTAINS(geo->GetErrorMessage(), "the grid describes no cells: origin 0, 0, ");
    AP_CHECK(!geo->GetBoundsLonLat(bounds));
    AP_CHECK_CONTAINS(geo->GetErrorMessage(), "the grid describes no cells");
    double centre[2]; // (a centre until 2026-12-06)
    AP_CHECK(!geo->GetCentreLonLat(centre));
    AP_CHECK_CONTAINS(geo->GetErrorMessage(), "the grid describes no cells");
  }
  // edges beyond the doubles: said so
  geo->SetGrid(0.0, 0.0, 1e308, 1.0, 10, 10);
  AP_CHECK(!geo->GetBoundsLonLat(bounds));
  AP_CHECK_CONTAINS(geo->GetErrorMessage(), "the grid's far edges are not finite numbers: "
                                            "origin 0, 0, cell size 1e+308 x 1, 10 x 10 cells");
  geo->SetGrid(0.0, 0.0, 1e-300, 1e-300, 10, 10);
  AP_CHECK(!geo->GetCellSizeMetres(size));
  AP_CHECK_CONTAINS(geo->GetErrorMessage(), "the grid's cells have no positive size on the "
                                            "ground (0 x 0 m): a wrong origin or spacing?");
  geo->SetGrid(0.0, 0.0, 1.0, 1.0, 10, 10);
  AP_CHECK(geo->GetCellSizeMetres(size) && geo->GetBoundsLonLat(bounds));
}

// Field data written by AttachToImage is what SetFromImage and the GeoTransform report.
void TestFieldData()
{
  vtkNew<vtkImageData> image;
  image->SetExtent(2, 5, 1, 3, 0, 0);
  image->SetOrigin(10.0, 20.0, 0.0);
  image->SetSpacing(0.5, 0.25, 1.0);
  vtkNew<vtkApertureGeoreference> geo;
  AP_CHECK(geo->SetCRS("EPSG:3857") && geo->AttachToImage(image));
  auto* gt = vtkDoubleArray::SafeDownCast(image->GetFieldData()->GetArray("GeoTransform"));
  AP_CHECK(gt != nullptr);
  if (gt)
  {
    AP_CHECK_NEAR(gt->GetValue(0), 10.0 + 2 * 0.5 - 0.25, 1e-12);
    AP_CHECK_NEAR(gt->GetValue(3), 20.0 + 3 * 0.25 + 0.125, 1e-12);
    AP_CHECK_NEAR(gt->GetValue(5), -0.25, 0.0);
  }
  vtkNew<vtkApertureGeoreference> back;
  AP_CHECK(back->SetFromImage(image));
  int size[2];
  back->GetGridSize(size);
  AP_CHECK(size[0] == 4 && size[1] == 3);
  double g2[6];
  back->GetGeoTransform(g2);
  for (int k = 0; gt && k < 6; ++k)
  {
    AP_CHECK_NEAR(g2[k], gt->GetValue(k), 1e-12);
  }
  AP_CHECK(std::string(back->GetCRSName()) == "WGS 84 / Pseudo-Mercator");
}
// Meridian convergence against GeographicLib's exact transverse Mercator (ALGORITHMS.md 5):
// on a UTM zone edge (3 degrees from the central meridian) at 45 N: 2.1223 deg; Zurich in
// zone 32: -0.3372; Sydney in zone 56 (south): +0.9982; zero on the central meridian and for
// geographic CRSs. The grid bearing of true north is then -gamma.
void TestConvergence()
{
  vtkNew<vtkApertureGeoreference> geo;
  AP_CHECK(geo->SetCRS("EPSG:32632"));
  AP_CHECK_NEAR(geo->ComputeMeridianConvergence(12.0, 45.0), 2.1223, 1e-4);
  AP_CHECK_NEAR(geo->ComputeMeridianConvergence(6.0, 45.0), -2.1223, 1e-4);
  AP_CHECK_NEAR(geo->ComputeMeridianConvergence(9.0, 45.0), 0.0, 1e-9);
  AP_CHECK_NEAR(geo->ComputeMeridianConvergence(8.5417, 47.3769), -0.3372, 1e-4);
  AP_CHECK(geo->SetCRS("EPSG:32756"));
  AP_CHECK_NEAR(geo->ComputeMeridianConvergence(151.2093, -33.8688), 0.9982, 1e-4);
  AP_CHECK(geo->SetCRS("EPSG:4326"));
  AP_CHECK_NEAR(geo->ComputeMeridianConvergence(151.2093, -33.8688), 0.0, 0.0);
}

// Per-row cell sizes of a lat/lon grid follow the parallel radius N cos(lat) (closed form).
void TestRowSizes()
{
  vtkNew<vtkApertureGeoreference> geo;
  AP_CHECK(geo->SetCRS("EPSG:4326"));
  const double cell = 0.01;
  geo->SetGrid(10.0, 40.0, cell, cell, 5, 101); // rows from 40 N to 41 N
  double dx[101], dy[101];
  AP_CHECK(geo->GetRowCellSizesMetres(dx, dy));
  const double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2 - f);
  for (int j = 0; j < 101; j += 25)
  {
    const double lat = (40.0 + j * cell) * kDeg, s = std::sin(lat), w = std::sqrt(1 - e2 * s * s);
    AP_CHECK_NEAR(dx[j], a / w * std::cos(lat) * cell * kDeg, 1e-5);
    AP_CHECK_NEAR(dy[j], a * (1 - e2) / (w * w * w) * cell * kDeg, 1e-5);
  }
  AP_CHECK(dx[100] < dx[0]);
  // Rows from a given one: the same values, bit for bit (chunks of 4096 rows inside), also on a
  // grid of 10000 rows; rows outside the grid are refused.
  geo->SetGrid(10.0, -40.0, cell, cell, 5, 10000);
  std::vector<double> wdx(10000), wdy(10000), sdx(5000), sdy(5000);
  AP_CHECK(geo->GetRowCellSizesMetres(wdx.data(), wdy.data()));
  AP_CHECK(geo->GetRowCellSizesMetres(4321, 5000, sdx.data(), sdy.data()));
  AP_CHECK(std::equal(sdx.begin(), sdx.end(), wdx.begin() + 4321) &&
    std::equal(sdy.begin(), sdy.end(), wdy.begin() + 4321));
  AP_CHECK(geo->GetRowCellSizesMetres(9999, 1, sdx.data(), sdy.data()) && sdx[0] == wdx[9999]);
  AP_CHECK(!geo->GetRowCellSizesMetres(9999, 2, sdx.data(), sdy.data()));
  AP_CHECK_CONTAINS(
    std::string(geo->GetErrorMessage()), "rows 9999 to 10000 are not rows of the grid's 10000");
  AP_CHECK(!geo->GetRowCellSizesMetres(-1, 1, sdx.data(), sdy.data()));
}

// A grid whose last row's north edge is the pole (90.00000000000001 after rounding): sizes from
// the closed forms; a grid reaching beyond the pole is refused, naming the row.
void TestRowSizesAtPole()
{
  vtkNew<vtkApertureGeoreference> geo;
  AP_CHECK(geo->SetCRS("EPSG:4326"));
  const double cell = 0.05;
  geo->SetGrid(-175.5, 88.025, 9.0, cell, 40, 40); // rows from 88 N to the pole, all longitudes
  double dx[40], dy[40];
  AP_CHECK(geo->GetRowCellSizesMetres(dx, dy));
  const double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2 - f);
  const double lat = 89.975 * kDeg, s = std::sin(lat), w = std::sqrt(1 - e2 * s * s);
  // meridian arc over the top row (M is stationary at the pole: the midpoint value holds)
  AP_CHECK_NEAR(dy[39] / (a * (1 - e2) / (w * w * w) * cell * kDeg), 1.0, 1e-6);
  // the geodesic across 9 degrees of that parallel is a little shorter than the parallel arc
  const double arc = a / w * std::cos(lat) * 9.0 * kDeg;
  AP_CHECK(dx[39] < arc && dx[39] > 0.995 * arc);
  geo->SetGrid(-175.5, 88.075, 9.0, cell, 40, 40); // the last row's centre at 90.025 N
  AP_CHECK(!geo->GetRowCellSizesMetres(dx, dy));
  AP_CHECK_CONTAINS(std::string(geo->GetErrorMessage()),
    "the row of cells at y = 90.025 (grid row 39, counted from the south) reaches latitude "
    "90.025, beyond the pole");
  // Its bounds in degrees are no bounds on the Earth either (PROJ passes 90.05 through), while
  // the grid that ends on the pole, its edge a rounding error beyond it, has bounds.
  double bounds[4];
  AP_CHECK(!geo->GetBoundsLonLat(bounds));
  AP_CHECK_CONTAINS(std::string(geo->GetErrorMessage()),
    "the grid's north edge is at latitude 90.05, beyond the north pole");
  // (and no bounds left behind: they were the degrees beyond the pole until 2026-12-06)
  AP_CHECK(std::isnan(bounds[0]) && std::isnan(bounds[1]) && std::isnan(bounds[2]) &&
    std::isnan(bounds[3]));
  geo->SetGrid(-175.5, 88.025, 9.0, cell, 40, 40);
  AP_CHECK(geo->GetBoundsLonLat(bounds));
  AP_CHECK_NEAR(bounds[3], 90.0, 1e-9);
  geo->SetGrid(-175.5, -90.025, 9.0, cell, 40, 40); // the first row's centre on the south pole
  AP_CHECK(!geo->GetBoundsLonLat(bounds));
  AP_CHECK_CONTAINS(std::string(geo->GetErrorMessage()),
    "the grid's south edge is at latitude -90.05, beyond the south pole");
  geo->SetGrid(-175.5, 90.125, 9.0, cell, 40, 2); // wholly beyond the north pole
  AP_CHECK(!geo->GetBoundsLonLat(bounds));
  AP_CHECK_CONTAINS(std::string(geo->GetErrorMessage()),
    "the grid's south edge is at latitude 90.1, beyond the north pole");
  // its centre and its cells' sizes neither (they were true, with NaN sizes and latitude 90.2)
  double lonlat[2], size[2], metric[3];
  AP_CHECK(!geo->GetCentreLonLat(lonlat));
  AP_CHECK_CONTAINS(std::string(geo->GetErrorMessage()),
    "the grid centre is at latitude 90.15, beyond the pole");
  AP_CHECK(!geo->GetCellSizeMetres(size));
  AP_CHECK_CONTAINS(
    std::string(geo->GetErrorMessage()), "the cell reaches latitude 90.15, beyond the pole");
  AP_CHECK(!geo->GetCellMetricAt(0.0, 90.15, metric));
  // the top row's cell, whose north edge is the pole (a rounding error beyond it): sizes
  geo->SetGrid(-175.5, 88.025, 9.0, cell, 40, 40);
  AP_CHECK(geo->GetCellSizeMetresAt(0.0, 89.975, size) && size[0] > 0.0 && size[1] > 0.0);
  AP_CHECK_NEAR(size[1], dy[39], 1e-6 * dy[39]);
}

// A geographic grid may go once around the Earth (360 degrees plus rounding), not more: 40
// columns of 20 degrees would put every cell on the ground of another. The span is counted in
// degrees whatever the CRS's unit (400 grads are 360 degrees); a cylindrical projection's grid
// (columns on meridians) by its columns' longitude step; other projected grids are not limited.
void TestLongitudeSpan()
{
  vtkNew<vtkApertureGeoreference> geo;
  AP_CHECK(geo->SetCRS("EPSG:4326"));
  double dx[20], dy[20], bounds[4];
  geo->SetGrid(-179.975, -9.975, 0.05, 0.05, 7200, 20); // the whole globe, 0.05 degree cells
  AP_CHECK(geo->CheckLongitudeSpan() && geo->GetRowCellSizesMetres(dx, dy));
  geo->SetGrid(-179.8333333333, -9.5, 0.3333333334, 1.0, 1080, 20); // (360 + 7.2e-8)
  AP_CHECK(geo->CheckLongitudeSpan());
  geo->SetGrid(-179.8, -9.5, 0.3337, 1.0, 1080, 20);
  AP_CHECK(!geo->CheckLongitudeSpan());
  AP_CHECK_CONTAINS(std::string(geo->GetErrorMessage()),
    "the grid spans 360.396 degrees of longitude (1080 columns of 0.3337 degrees)");
  geo->SetGrid(-170.0, -9.5, 20.0, 1.0, 40, 20);
  AP_CHECK(!geo->CheckLongitudeSpan());
  AP_CHECK_CONTAINS(std::string(geo->GetErrorMessage()),
    "the grid spans 800 degrees of longitude (40 columns of 20 degrees), more than the 360");
  AP_CHECK(!geo->GetRowCellSizesMetres(dx, dy) && !geo->GetBoundsLonLat(bounds));
  // a gridline-registered global grid (GMT, ETOPO: columns centred on -180 and on 180, rows
  // on the poles when it reaches them) is named as such, with the way out
  geo->SetGrid(-180.0, -90.0, 1.0, 1.0, 361, 181);
  AP_CHECK(!geo->CheckLongitudeSpan());
  AP_CHECK_CONTAINS(std::string(geo->GetErrorMessage()),
    "spans 361 degrees of longitude (361 columns of 1 degrees), more than the 360 around the "
    "Earth: its first and last columns are one meridian (a gridline-registered global grid); "
    "drop the last column and the rows centred on a pole first (gdal_translate -srcwin 0 1 "
    "360 179; with -of VRT it copies nothing)");
  geo->SetGrid(-180.0, -60.0, 1.0, 1.0, 361, 121); // 60 S to 60 N
  AP_CHECK(!geo->CheckLongitudeSpan());
  AP_CHECK_CONTAINS(std::string(geo->GetErrorMessage()),
    "drop the last column first (gdal_translate -srcwin 0 0 360 121; with -of VRT it copies "
    "nothing)");
  AP_CHECK(geo->SetCRS("EPSG:4807")); // NTF (Paris), grads
  geo->SetGrid(-199.5, 0.5, 1.0, 1.0, 400, 20);
  AP_CHECK(geo->CheckLongitudeSpan());
  geo->SetGrid(-199.5, 0.5, 1.0, 1.0, 401, 20);
  AP_CHECK(!geo->CheckLongitudeSpan());
  AP_CHECK_CONTAINS(std::string(geo->GetErrorMessage()), "spans 360.9 degrees");
  AP_CHECK(geo->SetCRS("EPSG:32616"));
  geo->SetGrid(0.0, 0.0, 1e6, 1e6, 400, 2); // 400 000 km: nonsense, but not a longitude span
  AP_CHECK(geo->CheckLongitudeSpan());
  // Web Mercator and equirectangular: one degree of longitude per column, 360 columns once
  // around (east and west edges joined), 361 the same meridian twice (PROJ gives longitudes
  // within +-180: 361 columns were "from -180 to -179" and baked as a strip, until 2026-12-07)
  const double e = 20037508.342789244, c = e / 180.0;
  AP_CHECK(geo->SetCRS("EPSG:3857"));
  geo->SetGrid(-e + 0.5 * c, 2e6, c, c, 360, 20);
  AP_CHECK(geo->CheckLongitudeSpan() && geo->WrapsAround() && geo->GetRowCellSizesMetres(dx, dy));
  geo->SetGrid(-e + 0.5 * c, 2e6, c, c, 361, 20);
  AP_CHECK(!geo->CheckLongitudeSpan());
  AP_CHECK_CONTAINS(std::string(geo->GetErrorMessage()),
    "spans 361 degrees of longitude (361 columns of 1 degrees), more than the 360 around the "
    "Earth: its first and last columns are one meridian (a gridline-registered global grid); "
    "drop the last column first (gdal_translate -srcwin 0 0 360 20;");
  AP_CHECK(!geo->WrapsAround());
  AP_CHECK(!geo->GetRowCellSizesMetres(dx, dy) && !geo->GetBoundsLonLat(bounds));
  AP_CHECK_CONTAINS(std::string(geo->GetErrorMessage()), "spans 361 degrees of longitude");
  geo->SetGrid(-e + 100.0 * c, 2e6, 200.0 * c, c, 2, 20); // (two columns of 200 degrees)
  AP_CHECK(!geo->CheckLongitudeSpan());
  AP_CHECK_CONTAINS(
    std::string(geo->GetErrorMessage()), "spans 400 degrees of longitude (2 columns");
  geo->SetGrid(-e + 0.5 * c, 2e6, 2.0 * c, c, 200, 20);
  AP_CHECK(!geo->CheckLongitudeSpan());
  AP_CHECK_CONTAINS(std::string(geo->GetErrorMessage()),
    "spans 400 degrees of longitude (200 columns of 2 degrees), more than the 360 around the "
    "Earth: a wrong cell size or unit?");
  // gridline-registered equirectangular, rows centred on the poles too (PROJ gives the edges
  // half a row beyond them as latitudes beyond 90)
  AP_CHECK(geo->SetCRS("EPSG:4087"));
  geo->SetGrid(-e, -0.5 * e, c, c, 361, 181);
  AP_CHECK(!geo->CheckLongitudeSpan());
  AP_CHECK_CONTAINS(std::string(geo->GetErrorMessage()),
    "drop the last column and the rows centred on a pole first (gdal_translate -srcwin 0 1 "
    "360 179;");
  geo->SetGrid(-e + 0.5 * c, -0.5 * e + 0.5 * c, c, c, 360, 180);
  AP_CHECK(geo->CheckLongitudeSpan() && geo->WrapsAround());
}
} // namespace

// Columns are meridians and rows parallels on lat/lon grids and the cylindrical projections
// (also across the antimeridian, and around the globe), not on transverse Mercator (even a 2 x 2
// grid beside its central meridian), polar stereographic, sinusoidal or Albers.
void TestMeridianColumns()
{
  struct Case
  {
    const char* CRS;
    double X0, Y0, Cell;
    int N;
    bool Expected;
  };
  const Case cases[] = { { "EPSG:4326", -120.0, 40.0, 0.001, 100, true },
    { "EPSG:3857", 1e6, 8.5e6, 1000.0, 100, true },
    { "EPSG:3857", 20037508.34 - 50000.0, 8.5e6, 1000.0, 100, true },
    // (more than 180 degrees of longitude, around the globe: false until 2026-12-07)
    { "EPSG:3857", -20037508.34 + 50000.0, -5e6, 100000.0, 300, true },
    { "EPSG:3857", -20037508.342789244 + 55659.74539663679, -5e6, 111319.49079327357, 360,
      true },
    { "EPSG:4087", -20037508.342789244 + 0.5e5, -5e6, 1e5, 400, true },
    { "EPSG:3395", 1e6, 8.5e6, 1000.0, 100, true }, { "EPSG:4087", 1e6, 6e6, 1000.0, 100, true },
    { "EPSG:6933", 1e6, 5e6, 1000.0, 100, true }, { "EPSG:32611", 5e5, 4e6, 30.0, 100, false },
    { "EPSG:32611", 499985.0, 4e6, 30.0, 2, false }, { "EPSG:3031", 5e5, 5e5, 1000.0, 100, false },
    { "ESRI:54008", 1e6, 5e6, 1000.0, 100, false }, { "EPSG:5070", 1e6, 2e6, 30.0, 100, false } };
  for (const Case& c : cases)
  {
    vtkNew<vtkApertureGeoreference> geo;
    AP_CHECK(geo->SetCRS(c.CRS));
    geo->SetGrid(c.X0, c.Y0, c.Cell, c.Cell, c.N, c.N + 20);
    if (geo->HasMeridianColumns() != c.Expected)
    {
      std::printf("HasMeridianColumns of %s at (%g, %g): %d\n", c.CRS, c.X0, c.Y0, !c.Expected);
      AP_CHECK(false);
    }
  }
  vtkNew<vtkApertureGeoreference> none;
  AP_CHECK(!none->HasMeridianColumns());
  AP_CHECK(std::string(none->GetErrorMessage()) == "no coordinate reference system is set");
  AP_CHECK(none->SetCRS("EPSG:3857"));
  none->SetGrid(1e6, 8.5e6, 1000.0, 1000.0, 1, 5);
  AP_CHECK(!none->HasMeridianColumns());
}

// SetFromInformation: the whole grid of pipeline information as an image of the whole extent
// gives it to SetFromImage (extent starting at 10: its first cell, not the origin), the CRS
// from CRS_KEY; without the key the grid is set and the CRS cleared; without a grid nothing.
void TestFromInformation()
{
  vtkNew<vtkInformation> info;
  vtkNew<vtkApertureGeoreference> geo;
  AP_CHECK(!geo->SetFromInformation(info));
  AP_CHECK_CONTAINS(geo->GetErrorMessage(), "no grid in the pipeline information");
  const int whole[6] = { 10, 19, 0, 4, 0, 0 };
  info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole, 6);
  info->Set(vtkDataObject::ORIGIN(), 500000.0, 4000000.0, 0.0);
  info->Set(vtkDataObject::SPACING(), 30.0, 20.0, 1.0);
  geo->SetCRS("EPSG:4326");
  AP_CHECK(!geo->SetFromInformation(info));
  AP_CHECK(!geo->HasCRS());
  AP_CHECK_CONTAINS(geo->GetErrorMessage(), "no CRS in the pipeline information");
  double origin[2], spacing[2];
  int size[2];
  geo->GetGridOrigin(origin);
  geo->GetGridSpacing(spacing);
  geo->GetGridSize(size);
  AP_CHECK_NEAR(origin[0], 500000.0 + 10 * 30.0, 0.0);
  AP_CHECK_NEAR(origin[1], 4000000.0, 0.0);
  AP_CHECK_NEAR(spacing[0], 30.0, 0.0);
  AP_CHECK_NEAR(spacing[1], 20.0, 0.0);
  AP_CHECK(size[0] == 10 && size[1] == 5);
  info->Set(vtkApertureGeoreference::CRS_KEY(), "EPSG:32611");
  AP_CHECK(geo->SetFromInformation(info));
  AP_CHECK(std::string(geo->GetCRSName()) == "WGS 84 / UTM zone 11N");
  info->Set(vtkApertureGeoreference::CRS_KEY(), "EPSG:999999999");
  AP_CHECK(!geo->SetFromInformation(info));
}

// WrapsAround: a lat/lon grid whose columns span 360 degrees (in degrees or in grads, whose
// unit the CRS names), wherever it starts; not one column fewer, nor a projected world grid.
void TestWrapsAround()
{
  struct Case
  {
    const char* CRS;
    double X0, Cell;
    int N;
    bool Expected;
  };
  const char* grads = "GEOGCS[\"WGS 84 in grads\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\","
                      "6378137,298.257223563]],PRIMEM[\"Greenwich\",0],UNIT[\"grad\","
                      "0.015707963267949]]";
  const Case cases[] = { { "EPSG:4326", -179.875, 0.25, 1440, true },
    { "EPSG:4326", 0.125, 0.25, 1440, true }, { "EPSG:4326", -179.875, 0.25, 1439, false },
    { "EPSG:4326", -179.9, 0.2, 1800, true }, { grads, -199.75, 0.5, 800, true },
    { grads, -199.75, 0.5, 720, false }, { "EPSG:3857", -20037508.34 + 5000.0, 10000.0, 4008,
                                            false },
    // cylindrical projections' columns of 360 / 4000 degrees (lat/lon only until 2026-12-07);
    // not transverse Mercator's or a local CRS's, however wide
    { "EPSG:3857", -20037508.342789244 + 5009.377085697311, 10018.754171394622, 4000, true },
    { "EPSG:3857", -20037508.342789244 + 5009.377085697311, 10018.754171394622, 3999, false },
    { "EPSG:4087", -20037508.342789244 + 5009.377085697311, 10018.754171394622, 4000, true },
    { "EPSG:32633", -20037508.342789244 + 5009.377085697311, 10018.754171394622, 4000, false },
    { "LOCAL_CS[\"site\",UNIT[\"metre\",1]]", 0.0, 10018.754171394622, 4000, false },
    // cell sizes of 9 and 10 digits (1/3 degree: 3.6e-7 short of 360, 7.2e-8 over), not
    // 1/1000 of a cell more (0.36 degree over 1080 columns)
    { "EPSG:4326", -179.8333333335, 0.333333333, 1080, true },
    { "EPSG:4326", -179.8333333333, 0.3333333334, 1080, true },
    { "EPSG:4326", -179.83, 0.3336666, 1080, false } };
  for (const Case& c : cases)
  {
    vtkNew<vtkApertureGeoreference> geo;
    AP_CHECK(geo->SetCRS(c.CRS));
    geo->SetGrid(c.X0, -50.0, c.Cell, c.Cell, c.N, 40);
    if (geo->WrapsAround() != c.Expected)
    {
      std::printf("WrapsAround of %d columns of %g from %g: %d\n", c.N, c.Cell, c.X0,
        !c.Expected);
      AP_CHECK(false);
    }
  }
  vtkNew<vtkApertureGeoreference> none;
  AP_CHECK(!none->WrapsAround());
}

// GetCellMetricAt: on UTM (conformal) the steps along the row and the column are as long as
// GetCellSizeMetresAt says and at right angles; on the sinusoidal projection of a sphere
// (x = R lon cos lat, y = R lat: not conformal) a step of d along the row runs d along the
// parallel, and one of d along the column moves lat by d / R and lon by lon tan(lat) d / R,
// so E = d (1, 0) and N = d (lon sin(lat), 1) in east-north metres: E.N = d^2 lon sin(lat),
// |N|^2 = d^2 (1 + lon^2 sin^2(lat)) (a 1 km cell: chords against these curves differ by
// 1e-9 of them).
void TestCellMetric()
{
  vtkNew<vtkApertureGeoreference> geo;
  AP_CHECK(geo->SetCRS("EPSG:32611"));
  geo->SetGrid(500000.0 - 50 * 30.0, 4000000.0, 30.0, 30.0, 101, 101);
  double size[2], m[3];
  AP_CHECK(geo->GetCellSizeMetresAt(800000.0, 4001500.0, size));
  AP_CHECK(geo->GetCellMetricAt(800000.0, 4001500.0, m));
  AP_CHECK(m[0] == size[0] * size[0] && m[2] == size[1] * size[1]);
  AP_CHECK(std::fabs(m[1]) < 1e-6 * m[0]);
  const double R = 6371000.0, d = 1000.0, lon = 30.0 * kDeg, lat = 45.0 * kDeg;
  AP_CHECK(geo->SetCRS("+proj=sinu +R=6371000 +units=m +no_defs"));
  geo->SetGrid(0.0, 0.0, d, d, 10, 10);
  AP_CHECK(geo->GetCellMetricAt(R * lon * std::cos(lat), R * lat, m));
  const double s = lon * std::sin(lat);
  AP_CHECK_NEAR(m[0] / (d * d), 1.0, 1e-6);
  AP_CHECK_NEAR(m[1] / (d * d), s, 1e-6);
  AP_CHECK_NEAR(m[2] / (d * d), 1.0 + s * s, 1e-6);
  // on and beside a pole (polar stereographic, conformal): square cells, at right angles, where
  // azimuths change fast or are undefined (from the cells' chords, not their azimuths)
  AP_CHECK(geo->SetCRS("EPSG:3413"));
  geo->SetGrid(-5000.0, -5000.0, d, d, 11, 11);
  for (const double x : { 0.0, 1000.0, 3000.0 })
  {
    AP_CHECK(geo->GetCellMetricAt(x, 0.5 * x, m));
    AP_CHECK_NEAR(m[2] / m[0], 1.0, 1e-9);
    AP_CHECK(std::fabs(m[1]) < 1e-9 * m[0]);
  }
  // off the projection's domain (beyond an orthographic view's disc): no metric, and why
  AP_CHECK(geo->SetCRS("+proj=ortho +lat_0=0 +lon_0=0 +R=6371000 +units=m +no_defs"));
  geo->SetGrid(0.0, 0.0, d, d, 10, 10);
  AP_CHECK(geo->GetCellMetricAt(0.5 * R, 0.0, m));
  AP_CHECK(!geo->GetCellMetricAt(1.01 * R, 0.0, m));
  AP_CHECK(std::string(geo->GetErrorMessage()) == "the cell has no geographic coordinates");
}

// A local (site) CRS: metric cells from its unit, nothing geographic.
void TestLocal()
{
  vtkNew<vtkApertureGeoreference> geo;
  AP_CHECK(geo->SetCRS("LOCAL_CS[\"mine grid\",UNIT[\"US survey foot\",0.304800609601219]]"));
  AP_CHECK(geo->IsLocal() && !geo->IsGeographic());
  geo->SetGrid(1000.0, 2000.0, 10.0, 20.0, 4, 3);
  double size[2], metric[3], ll[2], ellipsoid[2], bounds[4];
  AP_CHECK(geo->GetCellSizeMetres(size));
  AP_CHECK_NEAR(size[0], 10.0 * 1200.0 / 3937.0, 1e-12);
  AP_CHECK_NEAR(size[1], 20.0 * 1200.0 / 3937.0, 1e-12);
  AP_CHECK(geo->GetCellSizeMetresAt(-5e6, 7e6, size)); // the same everywhere
  AP_CHECK_NEAR(size[0], 10.0 * 1200.0 / 3937.0, 1e-12);
  AP_CHECK(geo->GetCellMetricAt(1000.0, 2000.0, metric));
  AP_CHECK_NEAR(metric[0], size[0] * size[0], 1e-9);
  AP_CHECK(metric[1] == 0.0);
  AP_CHECK_NEAR(metric[2], size[1] * size[1], 1e-9);
  double dx[3] = { 0, 0, 0 }, dy[3] = { 0, 0, 0 };
  AP_CHECK(geo->GetRowCellSizesMetres(dx, dy));
  for (int j = 0; j < 3; ++j)
  {
    AP_CHECK(dx[j] == size[0] && dy[j] == size[1]);
  }
  AP_CHECK(geo->HasMeridianColumns());
  AP_CHECK(!geo->CRSToLonLat(1000.0, 2000.0, ll));
  AP_CHECK(!geo->GetCentreLonLat(ll));
  AP_CHECK(!geo->GetBoundsLonLat(bounds));
  AP_CHECK(!geo->GetEllipsoid(ellipsoid));
  AP_CHECK(std::string(geo->GetErrorMessage()).find("no geographic coordinates") !=
    std::string::npos);
  AP_CHECK(std::isnan(geo->ComputeMeridianConvergence(0.0, 0.0)));
  AP_CHECK(geo->SetCRS("EPSG:32633") && !geo->IsLocal());
  AP_CHECK(geo->SetCRS("EPSG:4326") && !geo->IsLocal());
}

int TestApertureGeoreference(int, char*[])
{
  TestLocal();
  TestProjected();
  TestGeographic();
  TestGradsFromParis();
  TestErrors();
  TestFieldData();
  TestConvergence();
  TestRowSizes();
  TestRowSizesAtPole();
  TestLongitudeSpan();
  TestMeridianColumns();
  TestWrapsAround();
  TestFromInformation();
  TestCellMetric();
  return aptest::Result();
}
