// SPDX-License-Identifier: BSD-3-Clause
// vtkApertureTerrainMesh: geometry against the textbook geodetic -> ECEF -> ENU formulas
// (written here independently of GeographicLib), cell sizes of lat/lon and UTM DEMs against
// closed forms, a site grid's on its sphere, nodata holes, carried arrays, exaggeration, and
// every documented error.
#include "aptest.hxx"
#include "aptest_dem.hxx"

#include "vtkApertureGeoreference.h"
#include "vtkApertureTerrainMesh.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkShortArray.h"
#include "vtkStringArray.h"
#include "vtkSmartPointer.h"
#include "vtkTestErrorObserver.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <utility>

namespace
{
const double kPi = 3.14159265358979323846;
const double kDeg = kPi / 180.0;
// WGS 84
const double kA = 6378137.0;
const double kF = 1.0 / 298.257223563;

// Textbook geodetic -> Earth-centred Earth-fixed (e.g. Hofmann-Wellenhof et al., GNSS, 5.6).
void Ecef(double latDeg, double lonDeg, double h, double p[3])
{
  const double e2 = kF * (2.0 - kF);
  const double sl = std::sin(latDeg * kDeg), cl = std::cos(latDeg * kDeg);
  const double n = kA / std::sqrt(1.0 - e2 * sl * sl);
  p[0] = (n + h) * cl * std::cos(lonDeg * kDeg);
  p[1] = (n + h) * cl * std::sin(lonDeg * kDeg);
  p[2] = (n * (1.0 - e2) + h) * sl;
}

// An ECEF vector in East-North-Up components at (lat0, lon0).
void EcefToEnu(double lat0, double lon0, const double d[3], double out[3])
{
  const double sp = std::sin(lat0 * kDeg), cp = std::cos(lat0 * kDeg);
  const double sl = std::sin(lon0 * kDeg), cl = std::cos(lon0 * kDeg);
  out[0] = -sl * d[0] + cl * d[1];
  out[1] = -sp * cl * d[0] - sp * sl * d[1] + cp * d[2];
  out[2] = cp * cl * d[0] + cp * sl * d[1] + sp * d[2];
}

// ECEF difference rotated into East-North-Up at (lat0, lon0, 0).
void Enu(double lat0, double lon0, double lat, double lon, double h, double out[3])
{
  double p0[3], p[3];
  Ecef(lat0, lon0, 0.0, p0);
  Ecef(lat, lon, h, p);
  const double d[3] = { p[0] - p0[0], p[1] - p0[1], p[2] - p0[2] };
  EcefToEnu(lat0, lon0, d, out);
}

double Distance(const double a[3], const double b[3])
{
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
    (a[2] - b[2]) * (a[2] - b[2]));
}

vtkSmartPointer<vtkPolyData> Mesh(vtkImageData* dem, double exaggeration = 1.0)
{
  vtkNew<vtkApertureTerrainMesh> mesher;
  mesher->SetInputData(dem);
  mesher->SetVerticalExaggeration(exaggeration);
  mesher->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  mesher->Update();
  return mesher->GetOutput();
}

// Check fix for "degrees treated as metres": the east-west extent of a 0.1 degree cell is the
// chord 2 N cos(lat) sin(dlon / 2) (about 8.9 km at 36.6 N, 5.6 km at 60 N), and every vertex
// sits where the textbook ENU formulas put it.
void TestLatLonGeometry(double latitude, double expectedKm)
{
  const double lon0 = -84.3, dl = 0.1;
  auto dem = MakeDEM("EPSG:4326", lon0, latitude - dl, dl, dl, 3, 3,
    [](int i, int j) { return static_cast<float>(100.0 * i + 10.0 * j); });
  auto mesh = Mesh(dem);
  AP_CHECK(mesh->GetNumberOfPoints() == 9);
  AP_CHECK(mesh->GetNumberOfCells() == 8);

  // Frame origin: the DEM centre = node (1, 1).
  auto* origin = vtkDoubleArray::SafeDownCast(mesh->GetFieldData()->GetArray("FrameOrigin"));
  AP_CHECK(origin && origin->GetNumberOfValues() == 3);
  if (!origin)
  {
    return;
  }
  AP_CHECK_NEAR(origin->GetValue(0), latitude, 1e-12);
  AP_CHECK_NEAR(origin->GetValue(1), lon0 + dl, 1e-12);
  AP_CHECK_NEAR(origin->GetValue(2), 0.0, 0.0);

  // Every vertex where the independent ENU formulas put it (1 mm over ~10 km).
  for (int j = 0; j < 3; ++j)
  {
    for (int i = 0; i < 3; ++i)
    {
      double expected[3], got[3];
      Enu(latitude, lon0 + dl, latitude - dl + j * dl, lon0 + i * dl, 100.0 * i + 10.0 * j,
        expected);
      mesh->GetPoint(j * 3 + i, got);
      AP_CHECK_NEAR(got[0], expected[0], 1e-3);
      AP_CHECK_NEAR(got[1], expected[1], 1e-3);
      AP_CHECK_NEAR(got[2], expected[2], 1e-3);
    }
  }

  // East-west extent of one cell on the central row at height 0 ... (flatten to compare
  // chords on the ellipsoid).
  auto flat = MakeDEM(
    "EPSG:4326", lon0, latitude - dl, dl, dl, 3, 3, [](int, int) { return 0.0f; });
  auto flatMesh = Mesh(flat);
  double w[3], e[3], s[3], n[3];
  flatMesh->GetPoint(3, w);
  flatMesh->GetPoint(4, e);
  flatMesh->GetPoint(1, s);
  flatMesh->GetPoint(4, n);
  const double e2 = kF * (2.0 - kF), sl = std::sin(latitude * kDeg);
  const double primeVertical = kA / std::sqrt(1.0 - e2 * sl * sl);
  const double chord = 2.0 * primeVertical * std::cos(latitude * kDeg) * std::sin(0.5 * dl * kDeg);
  AP_CHECK_NEAR(Distance(w, e), chord, 1e-3);
  AP_CHECK_NEAR(Distance(w, e) / 1000.0, expectedKm, 0.05);
  // ... and the north-south extent: the chord between two points of one meridian.
  double ps[3], pn[3];
  Ecef(latitude - dl, 0.0, 0.0, ps);
  Ecef(latitude, 0.0, 0.0, pn);
  AP_CHECK_NEAR(Distance(s, n), Distance(ps, pn), 1e-3);
  AP_CHECK(Distance(s, n) > 11000.0 && Distance(s, n) < 11200.0); // ~111 km per degree
  // Earth curvature is in the geometry: the western node at height 0 is below the plane.
  AP_CHECK(w[2] < -1.0);
}

// A projected DEM (UTM 11N, 30 m cells) on the central meridian: neighbouring nodes are
// 30 m / k0 apart on the ground (k0 = 0.9996, the UTM scale on the central meridian), and
// the frame origin is on the central meridian, longitude -117.
void TestUTMGeometry()
{
  auto dem = MakeDEM("EPSG:32611", 500000.0 - 30.0, 4000000.0 - 30.0, 30.0, 30.0, 3, 3,
    [](int, int) { return 0.0f; });
  auto mesh = Mesh(dem);
  double c[3], e[3], n[3];
  mesh->GetPoint(4, c);
  mesh->GetPoint(5, e);
  mesh->GetPoint(7, n);
  AP_CHECK_NEAR(Distance(c, e), 30.0 / 0.9996, 1e-4);
  AP_CHECK_NEAR(Distance(c, n), 30.0 / 0.9996, 1e-4);
  // Grid north is true north on the central meridian: the north neighbour is due north.
  AP_CHECK_NEAR(n[0] - c[0], 0.0, 1e-6);
  AP_CHECK_NEAR(e[1] - c[1], 0.0, 1e-6);
  AP_CHECK_NEAR(c[0], 0.0, 1e-6);
  AP_CHECK_NEAR(c[1], 0.0, 1e-6);
  auto* origin = vtkDoubleArray::SafeDownCast(mesh->GetFieldData()->GetArray("FrameOrigin"));
  AP_CHECK(origin != nullptr);
  if (origin)
  {
    AP_CHECK_NEAR(origin->GetValue(1), -117.0, 1e-9);
  }
  auto* ellipsoid =
    vtkDoubleArray::SafeDownCast(mesh->GetFieldData()->GetArray("FrameEllipsoid"));
  AP_CHECK(ellipsoid && std::fabs(ellipsoid->GetValue(0) - kA) < 1e-6 &&
    std::fabs(ellipsoid->GetValue(1) - kF) < 1e-15);
}

// A site grid in a local CRS (US survey feet) on the sphere of radius R: a point (X, Y) metres
// from the centre, at height h, is at ground distance s = |(X, Y)| in azimuth a = atan2(X, Y),
// the angle t = s / R round the sphere: ((R + h) sin t sin a, (R + h) sin t cos a,
// (R + h) cos t - R) in the tangent frame at the centre. A bent normal pointing up at a point
// is carried as that point's radial direction (sin t sin a, sin t cos a, cos t).
void TestLocalGeometry()
{
  const double R = vtkApertureGeoreference::GetLocalSphereRadius(), foot = 1200.0 / 3937.0;
  const double cell = 10000.0; // feet: the grid spans 12 km, the edges drop ~3 m
  const int nx = 5, ny = 5;
  auto dem = MakeDEM("LOCAL_CS[\"mine grid\",UNIT[\"US survey foot\",0.304800609601219]]",
    20000.0, 50000.0, cell, cell, nx, ny,
    [](int i, int j) { return static_cast<float>(50.0 * i - 20.0 * j); });
  vtkNew<vtkFloatArray> bent;
  bent->SetName("BentNormal");
  bent->SetNumberOfComponents(3);
  bent->SetNumberOfTuples(nx * ny);
  for (vtkIdType k = 0; k < nx * ny; ++k)
  {
    bent->SetTuple3(k, 0.0, 0.0, 1.0);
  }
  dem->GetPointData()->AddArray(bent);
  auto mesh = Mesh(dem);
  AP_CHECK(mesh->GetNumberOfPoints() == nx * ny);
  vtkDataArray* up = mesh->GetPointData()->GetArray("BentNormal");
  AP_CHECK(up != nullptr);
  double lowest = 0.0;
  for (int j = 0; j < ny && up; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      const double X = (i - 2) * cell * foot, Y = (j - 2) * cell * foot;
      const double h = 50.0 * i - 20.0 * j, t = std::hypot(X, Y) / R, a = std::atan2(X, Y);
      const double expected[3] = { (R + h) * std::sin(t) * std::sin(a),
        (R + h) * std::sin(t) * std::cos(a), (R + h) * std::cos(t) - R };
      const double radial[3] = { std::sin(t) * std::sin(a), std::sin(t) * std::cos(a),
        std::cos(t) };
      double got[3], v[3];
      mesh->GetPoint(j * nx + i, got);
      up->GetTuple(j * nx + i, v);
      for (int c = 0; c < 3; ++c)
      {
        AP_CHECK_NEAR(got[c], expected[c], 1e-3);
        AP_CHECK_NEAR(v[c], radial[c], 1e-6);
      }
      lowest = std::min(lowest, got[2] - h);
    }
  }
  AP_CHECK(lowest < -5.0); // the corners, 8.6 km out: curvature drops them by 5.8 m
  auto* origin = vtkDoubleArray::SafeDownCast(mesh->GetFieldData()->GetArray("FrameOrigin"));
  auto* sphere = vtkDoubleArray::SafeDownCast(mesh->GetFieldData()->GetArray("FrameEllipsoid"));
  AP_CHECK(origin && origin->GetValue(0) == 0.0 && origin->GetValue(1) == 0.0);
  AP_CHECK(sphere && sphere->GetValue(0) == R && sphere->GetValue(1) == 0.0);
}

// Elevations that are not finite are nodata, as the reader makes them: +-inf give the mesh
// NaN does, point for point, with no warning; finite ones beyond any on the Earth are meshed,
// with a warning naming their range.
void TestNonFiniteAndImplausible()
{
  const auto mesh = [](float hole, vtkTest::ErrorObserver* warnings) {
    auto dem = MakeDEM("EPSG:32633", 400000.0, 5000000.0, 10.0, 10.0, 5, 4,
      [hole](int i, int j) { return i == 2 && j == 1 ? hole : static_cast<float>(i * j); });
    vtkNew<vtkApertureTerrainMesh> mesher;
    mesher->AddObserver(vtkCommand::WarningEvent, warnings);
    mesher->SetInputData(dem);
    mesher->Update();
    return vtkSmartPointer<vtkPolyData>(mesher->GetOutput());
  };
  vtkNew<vtkTest::ErrorObserver> quiet, loud;
  auto expected = mesh(NAN, quiet);
  for (float hole : { INFINITY, -INFINITY })
  {
    auto got = mesh(hole, quiet);
    AP_CHECK(got->GetNumberOfCells() == expected->GetNumberOfCells());
    for (vtkIdType k = 0; k < expected->GetNumberOfPoints(); ++k)
    {
      double a[3], b[3];
      expected->GetPoint(k, a);
      got->GetPoint(k, b);
      AP_CHECK(a[0] == b[0] && a[1] == b[1] && a[2] == b[2]);
    }
  }
  AP_CHECK(!quiet->GetWarning());
  auto pit = mesh(-32768.0f, loud);
  AP_CHECK(pit->GetNumberOfCells() == 24);
  AP_CHECK(loud->GetWarning());
  AP_CHECK_CONTAINS(loud->GetWarningMessage(), "elevations range from -32768 to 12 m, beyond any");
  // a relief over ten times the grid's side: 3 arc-second cells in a CRS in metres
  vtkNew<vtkApertureTerrainMesh> mesher;
  vtkNew<vtkTest::ErrorObserver> steep;
  mesher->AddObserver(vtkCommand::WarningEvent, steep);
  mesher->SetInputData(MakeDEM("EPSG:32633", 400000.0, 5000000.0, 1 / 1200.0, 1 / 1200.0, 5, 4,
    [](int i, int j) { return static_cast<float>(i * j); }));
  mesher->Update();
  AP_CHECK(mesher->GetOutput()->GetNumberOfCells() == 24);
  AP_CHECK_CONTAINS(steep->GetWarningMessage(), "elevations range over 12 m on a grid of ");
  AP_CHECK_CONTAINS(steep->GetWarningMessage(),
    " steeper than any terrain: a CRS whose unit does not fit the grid's coordinates (degrees "
    "taken for metres?), or heights not in metres? A mesh and pictures made of them are "
    "meaningless");
}

// Nodata leaves holes; arrays are carried vertex for vertex; normals and texture coordinates.
void TestHolesAndArrays()
{
  const int nx = 5, ny = 4;
  auto dem = MakeDEM("EPSG:32633", 400000.0, 5000000.0, 10.0, 10.0, nx, ny,
    [](int i, int j) { return (i == 2 && j == 1) ? NAN : static_cast<float>(i + j); });
  vtkNew<vtkDoubleArray> extra;
  extra->SetName("Extra");
  extra->SetNumberOfComponents(2);
  extra->SetNumberOfTuples(nx * ny);
  for (vtkIdType k = 0; k < nx * ny; ++k)
  {
    extra->SetTuple2(k, static_cast<double>(k), -static_cast<double>(k));
  }
  dem->GetPointData()->AddArray(extra);
  auto mesh = Mesh(dem);
  // 2 * 4 * 3 = 24 triangles; the nodata node touches 4 quads, each keeps one: 20.
  AP_CHECK(mesh->GetNumberOfCells() == 20);
  vtkIdType npts;
  const vtkIdType* pts;
  auto* polys = mesh->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(npts, pts);)
  {
    AP_CHECK(npts == 3);
    for (vtkIdType k = 0; k < npts; ++k)
    {
      AP_CHECK(pts[k] != 1 * nx + 2);
    }
  }
  vtkDataArray* z = mesh->GetPointData()->GetArray("Elevation");
  vtkDataArray* carried = mesh->GetPointData()->GetArray("Extra");
  AP_CHECK(z && carried && carried->GetNumberOfComponents() == 2);
  if (z && carried)
  {
    AP_CHECK(std::isnan(z->GetTuple1(1 * nx + 2)));
    AP_CHECK_NEAR(z->GetTuple1(3 * nx + 4), 7.0, 0.0);
    AP_CHECK_NEAR(carried->GetComponent(13, 1), -13.0, 0.0);
  }
  vtkDataArray* normals = mesh->GetPointData()->GetNormals();
  AP_CHECK(normals && normals->GetNumberOfComponents() == 3);
  if (normals)
  {
    AP_CHECK(std::isnan(normals->GetComponent(1 * nx + 2, 0)));
    // Plane z = x/10 + y/10 on 10 m cells: normal ~ (-0.1, -0.1, 1) / |.|, to within the
    // convergence of UTM grid north (a fraction of a degree) and Earth curvature.
    const double len = std::sqrt(1.02);
    AP_CHECK_NEAR(normals->GetComponent(0, 2), 1.0 / len, 1e-3);
    AP_CHECK_NEAR(normals->GetComponent(0, 0), -0.1 / len, 5e-3);
  }
  vtkDataArray* tc = mesh->GetPointData()->GetTCoords();
  AP_CHECK(tc && tc->GetNumberOfComponents() == 2);
  if (tc)
  {
    AP_CHECK_NEAR(tc->GetComponent(0, 0), 0.5 / nx, 1e-7);
    AP_CHECK_NEAR(tc->GetComponent(0, 1), 0.5 / ny, 1e-7);
    AP_CHECK_NEAR(tc->GetComponent(nx * ny - 1, 0), 1.0 - 0.5 / nx, 1e-7);
    AP_CHECK_NEAR(tc->GetComponent(nx * ny - 1, 1), 1.0 - 0.5 / ny, 1e-7);
  }
  AP_CHECK(mesh->GetFieldData()->GetAbstractArray("CRS") != nullptr);
}

// Elevations as 16-bit integers in the active scalars of an image without an "Elevation"
// array (made by hand, VTK's way): the float DEM's points, normals and triangles exactly.
void TestScalarsOfAnyType()
{
  const int nx = 7, ny = 6;
  auto height = [](int i, int j) { return static_cast<float>(40 * i - 25 * j + (i * j) % 7); };
  auto dem = MakeDEM("EPSG:32633", 400000.0, 5000000.0, 30.0, 30.0, nx, ny, height);
  auto expected = Mesh(dem);
  auto shorts = MakeDEM("EPSG:32633", 400000.0, 5000000.0, 30.0, 30.0, nx, ny, height);
  vtkNew<vtkShortArray> dem16;
  dem16->SetName("band1");
  dem16->SetNumberOfTuples(nx * ny);
  for (vtkIdType k = 0; k < nx * ny; ++k)
  {
    const int i = static_cast<int>(k % nx), j = static_cast<int>(k / nx);
    dem16->SetValue(k, static_cast<short>(height(i, j)));
  }
  shorts->GetPointData()->RemoveArray("Elevation");
  shorts->GetPointData()->SetScalars(dem16);
  auto got = Mesh(shorts);
  AP_CHECK(got->GetNumberOfPoints() == nx * ny &&
    got->GetNumberOfCells() == expected->GetNumberOfCells());
  for (vtkIdType k = 0; k < got->GetNumberOfPoints() && k < nx * ny; ++k)
  {
    double a[3], b[3];
    got->GetPoint(k, a);
    expected->GetPoint(k, b);
    AP_CHECK(a[0] == b[0] && a[1] == b[1] && a[2] == b[2]);
    got->GetPointData()->GetNormals()->GetTuple(k, a);
    expected->GetPointData()->GetNormals()->GetTuple(k, b);
    AP_CHECK(a[0] == b[0] && a[1] == b[1] && a[2] == b[2]);
  }
  // ... and the heights come out as Elevation too, beside band1, as the reader's would (until
  // 2026-12-06 only as band1, which aperture.scene and the README's tour could not find)
  vtkDataArray* band1 = got->GetPointData()->GetArray("band1");
  vtkDataArray* elevation = got->GetPointData()->GetArray("Elevation");
  AP_CHECK(band1 && elevation && elevation->GetDataType() == VTK_SHORT &&
    elevation->GetNumberOfTuples() == nx * ny);
  AP_CHECK(elevation && band1 && elevation->GetVoidPointer(0) == band1->GetVoidPointer(0));
  // unnamed scalars are replaced by it (the active scalars, named)
  dem16->SetName(nullptr);
  shorts->Modified();
  auto unnamed = Mesh(shorts);
  vtkPointData* pd = unnamed->GetPointData();
  AP_CHECK(pd->GetScalars() && pd->GetScalars()->GetName() &&
    std::string(pd->GetScalars()->GetName()) == "Elevation");
  AP_CHECK(pd->GetNumberOfArrays() == 3); // Elevation, Normals, TextureCoordinates
  AP_CHECK(shorts->GetPointData()->GetScalars()->GetName() == nullptr); // (the input's kept)
  AP_CHECK(pd->GetArray("Elevation") && pd->GetArray("Elevation")->GetTuple1(nx + 2) ==
    static_cast<short>(height(2, 1)));
}

// The vertex a global mesh's id stands for: the seam's copies (after the grid's) are column 0.
vtkIdType GridVertex(vtkIdType id, vtkIdType nx, vtkIdType ny)
{
  return id < nx * ny ? id : (id - nx * ny) * nx;
}

// A global DEM (2-degree cells from pole to pole, all 360 degrees of longitude) at height 0 is
// the WGS 84 ellipsoid closed: its east and west edges joined by one copied vertex a row (whose
// texture coordinate continues past u = 1), each pole's ring of vertices closed by a fan. So,
// with the copies mapped to column 0, every directed edge occurs once and its reverse once;
// V - E + F = 2; every triangle faces away from the Earth's centre; the enclosed volume is the
// ellipsoid's 4/3 pi a^2 b less the inscribed polyhedron's deficit (about h^2 / 8 relative per
// direction for chords of h = 2 degrees: 3e-4, so less than 1e-3); every normal, the seam's
// too, is the ellipsoid's (the central-difference normal of a smooth surface, within
// O(h^2): 0.05 degree; the pole rings' one-sided, a degree). (Pieces: TestPipelineBehaviour.)
void TestGlobal()
{
  const int nx = 180, ny = 90;
  auto dem = MakeDEM("EPSG:4326", -179.0, -89.0, 2.0, 2.0, nx, ny, [](int, int) { return 0.0f; });
  auto mesh = Mesh(dem);
  const vtkIdType n = nx * ny;
  AP_CHECK(mesh->GetNumberOfPoints() == n + ny);
  AP_CHECK(mesh->GetNumberOfCells() == 2 * nx * (ny - 1) + 2 * (nx - 2));
  std::map<std::pair<vtkIdType, vtkIdType>, int> edges;
  double volume = 0.0;
  int inward = 0;
  const double centre[3] = { 0.0, 0.0, -kA }; // the frame's origin is at latitude 0, longitude 0
  vtkIdType npts;
  const vtkIdType* pts;
  auto* polys = mesh->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(npts, pts);)
  {
    double p[3][3];
    for (int k = 0; k < 3; ++k)
    {
      mesh->GetPoint(pts[k], p[k]);
      ++edges[{ GridVertex(pts[k], nx, ny), GridVertex(pts[(k + 1) % 3], nx, ny) }];
    }
    const double u[3] = { p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2] };
    const double v[3] = { p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2] };
    const double c[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
      u[0] * v[1] - u[1] * v[0] };
    double out = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      out += c[k] * (p[0][k] - centre[k]);
    }
    inward += out <= 0.0;
    volume += (p[0][0] - centre[0]) * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) / 6.0;
    volume += (p[0][1] - centre[1]) * (p[1][2] * p[2][0] - p[1][0] * p[2][2]) / 6.0;
    volume += (p[0][2] - centre[2]) * (p[1][0] * p[2][1] - p[1][1] * p[2][0]) / 6.0;
  }
  AP_CHECK(inward == 0);
  int unpaired = 0;
  for (const auto& e : edges)
  {
    const auto back = edges.find({ e.first.second, e.first.first });
    unpaired += e.second != 1 || back == edges.end() || back->second != 1;
  }
  AP_CHECK(unpaired == 0);
  const long long faces = mesh->GetNumberOfCells();
  AP_CHECK(n - static_cast<long long>(edges.size()) / 2 + faces == 2);
  const double ellipsoid = 4.0 / 3.0 * kPi * kA * kA * kA * (1.0 - kF);
  std::printf("global mesh: volume %.6e of the ellipsoid's %.6e (%.2e less)\n", volume,
    ellipsoid, 1.0 - volume / ellipsoid);
  AP_CHECK(volume < ellipsoid && volume > ellipsoid * (1.0 - 1e-3));

  // Normals: the ellipsoid's geodetic up at each vertex, in the frame.
  vtkDataArray* normals = mesh->GetPointData()->GetNormals();
  vtkDataArray* tc = mesh->GetPointData()->GetTCoords();
  double worst = 0.0, worstRing = 0.0;
  for (vtkIdType id = 0; normals && id < n + ny; ++id)
  {
    const vtkIdType g = GridVertex(id, nx, ny);
    const double lat = -89.0 + 2.0 * static_cast<double>(g / nx);
    const double lon = -179.0 + 2.0 * static_cast<double>(g % nx);
    const double up[3] = { std::cos(lat * kDeg) * std::cos(lon * kDeg),
      std::cos(lat * kDeg) * std::sin(lon * kDeg), std::sin(lat * kDeg) };
    double want[3], got[3];
    EcefToEnu(0.0, 0.0, up, want);
    normals->GetTuple(id, got);
    const double dot = got[0] * want[0] + got[1] * want[1] + got[2] * want[2];
    const double angle = std::acos(std::min(1.0, dot)) / kDeg;
    double& w = (g / nx == 0 || g / nx == ny - 1) ? worstRing : worst;
    w = std::max(w, std::isnan(angle) ? 180.0 : angle);
  }
  std::printf("global mesh: normals within %.4f degrees, pole rings %.3f\n", worst, worstRing);
  AP_CHECK(worst < 0.05 && worstRing < 1.5);
  vtkDataArray* z = mesh->GetPointData()->GetArray("Elevation");
  AP_CHECK(tc && z && z->GetNumberOfTuples() == n + ny);
  for (int j = 0; tc && j < ny; ++j)
  {
    AP_CHECK_NEAR(tc->GetComponent(n + j, 0), 1.0 + 0.5 / nx, 1e-6);
    AP_CHECK_NEAR(tc->GetComponent(n + j, 1), tc->GetComponent(j * nx, 1), 0.0);
  }

  // Nodata on a pole's ring leaves that pole open; a DEM one column short of the globe, or
  // ending short of the poles, has no seam and no caps.
  auto holed = MakeDEM("EPSG:4326", -179.0, -89.0, 2.0, 2.0, nx, ny,
    [](int i, int j) { return (i == 7 && j == 89) ? NAN : 0.0f; });
  AP_CHECK(Mesh(holed)->GetNumberOfCells() == 2 * nx * (ny - 1) - 2 + (nx - 2));
  const auto sea = [](int, int) { return 0.0f; };
  auto narrow = MakeDEM("EPSG:4326", -179.0, -89.0, 2.0, 2.0, nx - 1, ny, sea);
  AP_CHECK(Mesh(narrow)->GetNumberOfPoints() == (nx - 1) * ny);
  AP_CHECK(Mesh(narrow)->GetNumberOfCells() == 2 * (nx - 2) * (ny - 1));
  auto band = MakeDEM("EPSG:4326", -179.0, -87.0, 2.0, 2.0, nx, ny - 2, sea);
  AP_CHECK(Mesh(band)->GetNumberOfCells() == 2 * nx * (ny - 3));

  // The cylindrical projections' global grids join too (until 2026-12-07 only lat/lon did): a
  // Web Mercator band, open at its ends (Mercator never reaches a pole), and an equirectangular
  // grid from pole to pole, closed by its caps. Columns of 2 degrees of longitude.
  const double e = 20037508.342789244, c = 2.0 * e / nx;
  auto mercator = Mesh(MakeDEM("EPSG:3857", -e + 0.5 * c, -19.5 * c, c, c, nx, 40, sea));
  AP_CHECK(mercator->GetNumberOfPoints() == nx * 40 + 40);
  AP_CHECK(mercator->GetNumberOfCells() == 2 * nx * 39);
  auto plate = Mesh(MakeDEM("EPSG:4087", -e + 0.5 * c, -0.5 * e + 0.5 * c, c, c, nx, ny, sea));
  AP_CHECK(plate->GetNumberOfPoints() == n + ny);
  AP_CHECK(plate->GetNumberOfCells() == 2 * nx * (ny - 1) + 2 * (nx - 2));
}

// Ghost levels (UpdatePiece(p, n, g)): each piece meshed over g more rows and columns, whose
// cells and points are marked in vtkGhostType; the pieces' own cells add up to the whole mesh
// (a global DEM's bands with their seams and caps, a UTM DEM's blocks). The Python test
// (TestPipelineBehaviour) compares the triangles themselves; this one runs under the sanitizers.
void TestGhostLevels()
{
  const auto hills = [](int i, int j) { return static_cast<float>(100 * ((i * 7 + j * 3) % 11)); };
  auto globe = MakeDEM("EPSG:4326", -175.0, -85.0, 10.0, 10.0, 36, 18, hills);
  auto block = MakeDEM("EPSG:32611", 500000.0, 4000000.0, 30.0, 30.0, 23, 17, hills);
  // (25 pieces: more than the globe's 17 rows of quads, bands of one row or none)
  const int runs[][2] = { { 3, 1 }, { 3, 2 }, { 25, 1 }, { 25, 2 } };
  for (vtkImageData* dem : { globe.GetPointer(), block.GetPointer() })
  {
    const vtkIdType whole = Mesh(dem)->GetNumberOfCells();
    for (const auto& run : runs)
    {
      vtkNew<vtkApertureTerrainMesh> mesher;
      mesher->SetInputData(dem);
      vtkIdType own = 0;
      for (int piece = 0; piece < run[0]; ++piece)
      {
        mesher->UpdatePiece(piece, run[0], run[1]);
        vtkPolyData* out = mesher->GetOutput();
        if (out->GetNumberOfPoints() == 0)
        {
          continue; // (a piece left without a row of quads)
        }
        vtkDataArray* cells = out->GetCellData()->GetArray(vtkDataSetAttributes::GhostArrayName());
        vtkDataArray* points =
          out->GetPointData()->GetArray(vtkDataSetAttributes::GhostArrayName());
        AP_CHECK(cells && points && cells->GetNumberOfTuples() == out->GetNumberOfCells() &&
          points->GetNumberOfTuples() == out->GetNumberOfPoints());
        vtkIdType ghosts = 0, ghostPoints = 0;
        for (vtkIdType t = 0; cells && t < cells->GetNumberOfTuples(); ++t)
        {
          ghosts += cells->GetComponent(t, 0) == vtkDataSetAttributes::DUPLICATECELL;
        }
        for (vtkIdType k = 0; points && k < points->GetNumberOfTuples(); ++k)
        {
          ghostPoints += points->GetComponent(k, 0) == vtkDataSetAttributes::DUPLICATEPOINT;
        }
        // (each piece borders another: ghost rows or columns of its cells and points)
        AP_CHECK(ghosts > 0 && ghostPoints > 0);
        own += out->GetNumberOfCells() - ghosts;
      }
      AP_CHECK(own == whole);
    }
  }
}

// Exaggeration scales heights above the ellipsoid, not the curvature drop.
void TestExaggeration()
{
  auto dem = MakeDEM("EPSG:4326", 10.0, 45.0, 0.01, 0.01, 3, 3,
    [](int i, int j) { return static_cast<float>(1000.0 + 50.0 * i - 20.0 * j); });
  auto mesh = Mesh(dem, 3.0);
  for (int k = 0; k < 9; ++k)
  {
    const int i = k % 3, j = k / 3;
    double expected[3], got[3];
    Enu(45.01, 10.01, 45.0 + 0.01 * j, 10.0 + 0.01 * i, 3.0 * (1000.0 + 50.0 * i - 20.0 * j),
      expected);
    mesh->GetPoint(k, got);
    AP_CHECK_NEAR(got[2], expected[2], 1e-3);
  }
}

// A vector given in local East-North-Up at (lat, lon), in the frame East-North-Up at
// (lat0, lon0): through ECEF with the textbook unit vectors.
void RotateToFrame(double lat0, double lon0, double lat, double lon, const double v[3],
  double out[3])
{
  const double sp = std::sin(lat * kDeg), cp = std::cos(lat * kDeg);
  const double sl = std::sin(lon * kDeg), cl = std::cos(lon * kDeg);
  const double east[3] = { -sl, cl, 0.0 }, north[3] = { -sp * cl, -sp * sl, cp },
               up[3] = { cp * cl, cp * sl, sp };
  double d[3];
  for (int c = 0; c < 3; ++c)
  {
    d[c] = v[0] * east[c] + v[1] * north[c] + v[2] * up[c];
  }
  EcefToEnu(lat0, lon0, d, out);
}

// BentNormal comes in each point's local East-North-Up and leaves in the mesh's frame, like
// Normals: on a lat/lon DEM spanning 20 x 15 degrees the local frames differ from the mesh's
// by up to ~12 degrees. Local up at a point of flat ground is then the mesh's normal there.
void TestBentNormalFrame()
{
  const int nx = 5, ny = 4;
  const double lonW = 10.0, latS = 40.0, step = 5.0; // centre (20 E, 47.5 N)
  auto dem = MakeDEM("EPSG:4326", lonW, latS, step, step, nx, ny,
    [](int i, int j) { return (i == 3 && j == 2) ? NAN : 0.0f; });
  vtkNew<vtkFloatArray> bent;
  bent->SetName("BentNormal");
  bent->SetNumberOfComponents(3);
  bent->SetNumberOfTuples(nx * ny);
  for (vtkIdType k = 0; k < nx * ny; ++k)
  {
    // a different unit vector per point; up at point 0
    const double a = 0.05 * static_cast<double>(k), b = 0.5 + 0.02 * static_cast<double>(k);
    const double v[3] = { std::sin(b) * std::cos(a), std::sin(b) * std::sin(a), std::cos(b) };
    bent->SetTuple3(k, k == 0 ? 0.0 : v[0], k == 0 ? 0.0 : v[1], k == 0 ? 1.0 : v[2]);
  }
  dem->GetPointData()->AddArray(bent);
  auto mesh = Mesh(dem);
  vtkDataArray* out = mesh->GetPointData()->GetArray("BentNormal");
  AP_CHECK(out && out->GetNumberOfComponents() == 3 && out->GetNumberOfTuples() == nx * ny);
  if (!out)
  {
    return;
  }
  double largest = 0.0;
  for (vtkIdType k = 0; k < nx * ny; ++k)
  {
    const int i = static_cast<int>(k % nx), j = static_cast<int>(k / nx);
    double v[3], expected[3], got[3];
    bent->GetTuple(k, v);
    out->GetTuple(k, got);
    if (i == 3 && j == 2)
    {
      AP_CHECK(std::isnan(got[0]) && std::isnan(got[1]) && std::isnan(got[2]));
      continue;
    }
    RotateToFrame(latS + 1.5 * step, lonW + 2.0 * step, latS + j * step, lonW + i * step, v,
      expected);
    for (int c = 0; c < 3; ++c)
    {
      AP_CHECK_NEAR(got[c], expected[c], 1e-6); // float output of unit vectors
    }
    largest = std::max(largest, std::acos(std::min(1.0, v[0] * got[0] + v[1] * got[1] +
                                          v[2] * got[2])) / kDeg);
  }
  AP_CHECK(largest > 10.0); // the rotation is not the identity here
  // The corner's local up is the ellipsoid normal there: along the (flat) mesh's own normal.
  double up[3], normal[3];
  out->GetTuple(0, up);
  mesh->GetPointData()->GetNormals()->GetTuple(0, normal);
  AP_CHECK_NEAR(up[0] * normal[0] + up[1] * normal[1] + up[2] * normal[2], 1.0, 2e-3);
}

// Each documented error: a clear message and a failed update, nothing printed.
// A mesher of `dem` whose errors (its own, and its executive's: not printed) are caught.
struct ObservedMesher
{
  vtkNew<vtkApertureTerrainMesh> Mesher;
  vtkNew<vtkTest::ErrorObserver> Errors, ExecutiveErrors;
  explicit ObservedMesher(vtkImageData* dem)
  {
    this->Mesher->AddObserver(vtkCommand::ErrorEvent, this->Errors);
    this->Mesher->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, this->ExecutiveErrors);
    this->Mesher->SetInputData(dem);
  }
};

void ExpectError(vtkImageData* dem, const std::string& expected, const char* arrayName = nullptr,
  double exaggeration = 1.0)
{
  ObservedMesher m(dem);
  vtkApertureTerrainMesh* mesher = m.Mesher;
  if (arrayName)
  {
    mesher->SetElevationArrayName(arrayName);
  }
  mesher->SetVerticalExaggeration(exaggeration);
  const int ok = mesher->GetExecutive()->Update();
  AP_CHECK(ok == 0);
  AP_CHECK(m.Errors->GetError());
  if (m.Errors->GetErrorMessage().find(expected) == std::string::npos)
  {
    std::fprintf(stderr, "expected an error containing '%s', got '%s'\n", expected.c_str(),
      m.Errors->GetErrorMessage().c_str());
    ++aptest::Failures();
  }
  // a failed update leaves an empty mesh, not points without triangles
  AP_CHECK(mesher->GetOutput()->GetNumberOfPoints() == 0);
  AP_CHECK(mesher->GetOutput()->GetNumberOfCells() == 0);
}

// SetInputArrayToProcess(0, ...) selects the elevations, as VTK's filters take theirs (it was
// ignored until 2026-12-06): the mesh of a point array selected by name is the mesh of a DEM
// holding it as Elevation; cell data is an error.
void TestInputArraySelection()
{
  const int nx = 6, ny = 5;
  auto rough = [](int i, int j) { return static_cast<float>(40 * i - 25 * j + (i * j) % 7); };
  auto other = [](int i, int j) { return static_cast<float>(300 - 7 * i + 11 * j); };
  auto dem = MakeDEM("EPSG:32633", 400000.0, 5000000.0, 30.0, 30.0, nx, ny, rough);
  auto expected = Mesh(MakeDEM("EPSG:32633", 400000.0, 5000000.0, 30.0, 30.0, nx, ny, other));
  vtkNew<vtkFloatArray> heights;
  heights->SetName("heights");
  heights->SetNumberOfTuples(nx * ny);
  for (vtkIdType k = 0; k < nx * ny; ++k)
  {
    heights->SetValue(k, other(static_cast<int>(k % nx), static_cast<int>(k / nx)));
  }
  dem->GetPointData()->AddArray(heights);
  ObservedMesher m(dem);
  m.Mesher->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  m.Mesher->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "heights");
  // the mesher's points, bit for bit those of `want`
  const auto samePoints = [&m](vtkPolyData* want) {
    vtkPolyData* got = m.Mesher->GetOutput();
    AP_CHECK(got->GetNumberOfPoints() == want->GetNumberOfPoints());
    for (vtkIdType k = 0; k < got->GetNumberOfPoints() && k < want->GetNumberOfPoints(); ++k)
    {
      double a[3], b[3];
      got->GetPoint(k, a);
      want->GetPoint(k, b);
      AP_CHECK(a[0] == b[0] && a[1] == b[1] && a[2] == b[2]);
    }
  };
  AP_CHECK(m.Mesher->GetExecutive()->Update() == 1 && !m.Errors->GetError());
  samePoints(expected);
  // Of ElevationArrayName and a selection, the one made last holds (until 2026-12-07 a name
  // set after any selection was kept, and ignored): the DEM's own Elevation again.
  m.Mesher->SetElevationArrayName("Elevation");
  AP_CHECK(m.Mesher->GetExecutive()->Update() == 1 && !m.Errors->GetError());
  samePoints(Mesh(MakeDEM("EPSG:32633", 400000.0, 5000000.0, 30.0, 30.0, nx, ny, rough)));
  // a null or empty name takes the active point scalars, as VTK's filters take unnamed input
  // (both were "no point array named ''" until 2026-12-07)
  dem->GetPointData()->SetActiveScalars("heights");
  for (const char* name : { static_cast<const char*>(nullptr), "" })
  {
    m.Mesher->SetElevationArrayName(name);
    AP_CHECK(m.Mesher->GetExecutive()->Update() == 1 && !m.Errors->GetError());
    samePoints(expected);
  }
  // ... the scalars themselves, unnamed ones too (in place of 'heights'), not another array
  // named Elevation (until review unnamed scalars were looked up by the name 'Elevation',
  // which found the DEM's); so does a selection of the scalars by attribute type
  vtkNew<vtkFloatArray> unnamed;
  unnamed->DeepCopy(heights);
  unnamed->SetName(nullptr);
  dem->GetPointData()->SetScalars(unnamed);
  AP_CHECK(dem->GetPointData()->GetArray("Elevation") != nullptr);
  m.Mesher->SetElevationArrayName(nullptr);
  AP_CHECK(m.Mesher->GetExecutive()->Update() == 1 && !m.Errors->GetError());
  samePoints(expected);
  m.Mesher->SetElevationArrayName("Elevation"); // (the name, then the selection: it holds)
  m.Mesher->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
  AP_CHECK(m.Mesher->GetExecutive()->Update() == 1 && !m.Errors->GetError());
  samePoints(expected);
  // and without scalars, an error naming what there is
  dem->GetPointData()->SetActiveScalars(nullptr);
  m.Mesher->SetElevationArrayName("");
  AP_CHECK(m.Mesher->GetExecutive()->Update() == 0);
  AP_CHECK_CONTAINS(m.Errors->GetErrorMessage(), "the point scalars are asked for (by a null or "
                                                 "empty ElevationArrayName, or by "
                                                 "SetInputArrayToProcess of the scalars), but the "
                                                 "input has none (its point arrays: 'Elevation', "
                                                 "an unnamed vtkFloatArray)");
  m.Mesher->SetElevationArrayName("Elevation"); // (asked for by a selection: the same message)
  m.Mesher->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
  AP_CHECK(m.Mesher->GetExecutive()->Update() == 0);
  AP_CHECK_CONTAINS(m.Errors->GetErrorMessage(), "the point scalars are asked for (by a null or "
                                                 "empty ElevationArrayName, or by "
                                                 "SetInputArrayToProcess of the scalars), but the "
                                                 "input has none");
  ObservedMesher cells(dem);
  cells.Mesher->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "heights");
  AP_CHECK(cells.Mesher->GetExecutive()->Update() == 0);
  AP_CHECK(cells.Errors->GetErrorMessage().find(
             "SetInputArrayToProcess selects an array that is not point data") !=
    std::string::npos);
}

// MemoryLimit: a 3 x 3 mesh's estimate, 9 points x (4 + 24 + 12 + 12 + 8) bytes and two
// triangles a point (the mesh has 8) of three ids and an offset of 4 bytes, is 828 bytes, 936
// with a BentNormal to rotate; refused by name one byte short, made at the limit.
void TestMemoryLimit()
{
  for (bool bent : { false, true })
  {
    auto dem = MakeDEM("EPSG:32633", 400000.0, 5000000.0, 10.0, 10.0, 3, 3,
      [](int i, int j) { return static_cast<float>(i + j); });
    if (bent)
    {
      vtkNew<vtkFloatArray> b;
      b->SetName("BentNormal");
      b->SetNumberOfComponents(3);
      b->SetNumberOfTuples(9);
      b->Fill(0.0);
      dem->GetPointData()->AddArray(b);
    }
    const vtkTypeInt64 need = bent ? 936 : 828;
    for (vtkTypeInt64 limit : { need - 1, need })
    {
      ObservedMesher m(dem);
      m.Mesher->SetMemoryLimit(limit);
      const int ok = m.Mesher->GetExecutive()->Update();
      AP_CHECK(ok == (limit == need ? 1 : 0));
      if (limit < need)
      {
        AP_CHECK_CONTAINS(m.Errors->GetErrorMessage(),
          "a mesh of 3 x 3 points needs about " + std::to_string(need) + " bytes, more than the " +
            std::to_string(limit) + " bytes MemoryLimit; decimate the DEM");
      }
    }
  }
  {
    // A streamed half of a 3 x 6 image also holds its crops (the piece with its one-row margin,
    // 3 x 4 points, and the piece, 3 x 3: image copies, at least their elevations 48 and 36
    // bytes) and the margin's normals (40 bytes a margin point, 480): refused at 828 + 480 +
    // 84 bytes, where its own mesh (828) alone would have fitted.
    auto dem = MakeDEM("EPSG:32633", 400000.0, 5000000.0, 10.0, 10.0, 3, 6,
      [](int i, int j) { return static_cast<float>(i * j); });
    const vtkTypeInt64 limit = 828 + 480 + 84;
    ObservedMesher m(dem);
    m.Mesher->SetMemoryLimit(limit);
    m.Mesher->UpdatePiece(0, 2, 0);
    const std::string said = m.Errors->GetErrorMessage();
    AP_CHECK_CONTAINS(said, "a mesh of 3 x 3 points needs about ");
    AP_CHECK_CONTAINS(said, " MemoryLimit; decimate the DEM");
    AP_CHECK(m.Mesher->GetOutput()->GetNumberOfPoints() == 0);
    // and at a limit above the crops (each image's size is counted in whole KiB) it is made
    ObservedMesher roomy(dem);
    roomy.Mesher->SetMemoryLimit(limit + 2 * 8192);
    roomy.Mesher->UpdatePiece(0, 2, 0);
    AP_CHECK(roomy.Errors->GetErrorMessage().empty());
    AP_CHECK(roomy.Mesher->GetOutput()->GetNumberOfPoints() == 9);
  }
}

void TestErrors()
{
  auto ok = [](int, int) { return 1.0f; };
  ExpectError(MakeDEM("EPSG:4326", 0, 0, 1, 1, 3, 3, ok),
    "the input has no point array named 'Height' (its point arrays: 'Elevation'); "
    "SetElevationArrayName names the one holding elevations in metres",
    "Height");
  {
    // an array without a name is named as such (it read "(its point arrays: '')")
    auto anonymous = MakeDEM("EPSG:4326", 0, 0, 1, 1, 3, 3, ok);
    anonymous->GetPointData()->GetArray("Elevation")->SetName(nullptr);
    ExpectError(anonymous, "the input has no point array named 'Height' (its point arrays: an "
                           "unnamed vtkFloatArray); SetElevationArrayName", "Height");
  }
  ExpectError(MakeDEM(nullptr, 0, 0, 1, 1, 3, 3, ok), "has no CRS");
  ExpectError(MakeDEM("EPSG:4326", 0, 0, 1, 1, 1, 5, ok), "at least 2 x 2");
  // a longitude of 1e17 degrees: a cell's 0.001 degree is lost to rounding there, and every
  // column collapsed onto one (until 2026-12-06)
  ExpectError(MakeDEM("EPSG:4326", 1e17, 35.0, 0.001, 0.001, 4, 3, ok),
    "the grid's cells have no positive size on the ground (0 x ");
  ExpectError(MakeDEM("EPSG:4326", 0, 0, 1, 1, 3, 3, [](int, int) { return NAN; }),
    "every point of the DEM is nodata");
  // valid points, each isolated (a checkerboard's blocks have two valid corners at most)
  ExpectError(MakeDEM("EPSG:4326", 0, 0, 1, 1, 4, 3,
                [](int i, int j) { return (i + j) % 2 ? NAN : 1.0f; }),
    "no 2 x 2 block of the DEM's points has three valid corners, which a triangle needs: its "
    "valid points (6) are too few or too scattered among nodata; there is no terrain to mesh");
  // (two side by side are not isolated: "each isolated" said so until 2026-12-07)
  ExpectError(MakeDEM("EPSG:4326", 0, 0, 1, 1, 3, 3,
                [](int i, int j) { return j == 0 && i < 2 ? 1.0f : NAN; }),
    "its valid points (2) are too few or too scattered among nodata");
  auto vec = MakeDEM("EPSG:4326", 0, 0, 1, 1, 3, 3, ok);
  vtkNew<vtkFloatArray> v3;
  v3->SetName("Elevation");
  v3->SetNumberOfComponents(3);
  v3->SetNumberOfTuples(9);
  v3->Fill(0.0);
  vec->GetPointData()->RemoveArray("Elevation");
  vec->GetPointData()->AddArray(v3);
  ExpectError(vec, "the elevation array 'Elevation' has 3 components; elevations need one");
  auto rgb = MakeDEM("EPSG:4326", 0, 0, 1, 1, 3, 3, ok);
  v3->SetName("RGB");
  rgb->GetPointData()->RemoveArray("Elevation");
  rgb->GetPointData()->SetScalars(v3);
  ExpectError(rgb, "the input has no point array named 'Elevation', and its active scalars 'RGB' "
                   "have 3 components; elevations need one");
  // an image that disagrees with itself (made by hand): copies would read past a short array
  auto few = MakeDEM("EPSG:4326", 0, 0, 1, 1, 4, 3, ok);
  few->GetPointData()->GetArray("Elevation")->SetNumberOfTuples(5);
  ExpectError(few, "the point array 'Elevation' has 5 tuples for the 4 x 3 points of the input's "
                   "extent");
  vtkNew<vtkShortArray> extra;
  extra->SetName("Class");
  extra->SetNumberOfTuples(13);
  extra->Fill(1);
  auto more = MakeDEM("EPSG:4326", 0, 0, 1, 1, 4, 3, ok);
  more->GetPointData()->AddArray(extra);
  ExpectError(more, "the point array 'Class' has 13 tuples for the 4 x 3 points");
  extra->SetNumberOfTuples(3); // a global DEM copies its arrays' column 0 to the seam
  auto globe = MakeDEM("EPSG:4326", -175.0, -80.0, 10.0, 10.0, 36, 17, ok);
  globe->GetPointData()->AddArray(extra);
  ExpectError(globe, "the point array 'Class' has 3 tuples for the 36 x 17 points");
  {
    // the same short array in a streamed piece: refused before the piece is cut out of the
    // image (the copy read past the array's end)
    auto shortPiece = MakeDEM("EPSG:4326", 0, 0, 1, 1, 6, 6, ok);
    vtkNew<vtkShortArray> few;
    few->SetName("Class");
    few->SetNumberOfTuples(5);
    few->Fill(1);
    shortPiece->GetPointData()->AddArray(few);
    ObservedMesher m(shortPiece);
    m.Mesher->UpdatePiece(0, 2, 0);
    AP_CHECK_CONTAINS(m.Errors->GetErrorMessage(), "the point array 'Class' has 5 tuples for "
                                                   "the 6 x 6 points");
    AP_CHECK(m.Mesher->GetOutput()->GetNumberOfPoints() == 0);
  }
  // a lat/lon grid beyond a pole, refused as the sky filter refuses it (its points there were
  // NaN, in triangles drawn)
  ExpectError(MakeDEM("EPSG:4326", 10.0, 89.5, 0.05, 0.05, 20, 20, ok),
    "the grid's north edge is at latitude 90.475, beyond the north pole");
  // a string array named as the elevations: said so (not "no point array named 'Elevation'
  // (its point arrays: 'Elevation')")
  auto text = MakeDEM("EPSG:4326", 0, 0, 1, 1, 3, 3, ok);
  vtkNew<vtkStringArray> words;
  words->SetName("Elevation");
  words->SetNumberOfValues(9);
  text->GetPointData()->RemoveArray("Elevation");
  text->GetPointData()->AddArray(words);
  ExpectError(text, "the point array 'Elevation' is not numeric (a vtkStringArray); elevations "
                    "are numbers");
  // a NaN exaggeration passed the clamp: every point NaN, the update a success
  ExpectError(MakeDEM("EPSG:4326", 0, 0, 1, 1, 3, 3, ok), "VerticalExaggeration is NaN", nullptr,
    std::nan(""));
}
} // namespace

int TestApertureTerrainMesh(int, char*[])
{
  TestLatLonGeometry(36.6, 8.95);
  TestLatLonGeometry(60.0, 5.58);
  TestUTMGeometry();
  TestLocalGeometry();
  TestBentNormalFrame();
  TestHolesAndArrays();
  TestScalarsOfAnyType();
  TestInputArraySelection();
  TestGlobal();
  TestGhostLevels();
  TestNonFiniteAndImplausible();
  TestExaggeration();
  TestErrors();
  TestMemoryLimit();
  return aptest::Result();
}
