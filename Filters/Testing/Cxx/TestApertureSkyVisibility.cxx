// SPDX-License-Identifier: BSD-3-Clause
// vtkApertureSkyVisibility, the C++ shim around the horizon kernel, run from C++ so that the
// sanitizer build (AddressSanitizer, UndefinedBehaviorSanitizer: the `unit` tests) covers it;
// TestSkyVisibility.py checks it in depth. Closed forms: planes in a projected, a lat/lon, a
// non-conformal and a local CRS, and a wall seen from flat ground (with and without curvature),
// in each search mode (rays marched, far-marched, hull sweep); sub-extents through a streaming
// source and other thread counts bit for bit against the whole run; a global DEM's joined
// edges; nodata (a piece of it),
// other array types, degrees, abort, and the documented errors.
#include "aptest.hxx"
#include "aptest_dem.hxx"
#include "aptest_source.hxx"

#include "vtkApertureSkyVisibility.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkShortArray.h"
#include "vtkSmartPointer.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace
{
const double kPi = 3.14159265358979323846;
const char* const kProducts[] = { "VisibleSolidAngle", "ApertureRadius", "BentNormal",
  "SkyViewFactor", "DiffuseSkyFactor", "PositiveOpenness", "EdgeTruncated", "HorizonAngles" };
const char* const kLocal = "LOCAL_CS[\"site grid\",UNIT[\"metre\",1]]";

using Setup = std::function<void(vtkApertureSkyVisibility*)>;

// A DEM's grid: its CRS, the centre of its south-west cell and its cell size in CRS units.
struct Grid
{
  const char* crs;
  double x0, y0, dx, dy;
};

// The sky filter's output for `dem` (every product, HorizonAngles too), set up by `setup`.
vtkSmartPointer<vtkImageData> Sky(vtkImageData* dem, const Setup& setup)
{
  vtkNew<vtkApertureSkyVisibility> sky;
  sky->SetInputData(dem);
  sky->SetComputeHorizonAngles(true);
  setup(sky);
  sky->Update();
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->ShallowCopy(sky->GetOutput());
  return out;
}

// The sky filter (every product, set up by `setup`) behind a source of any sub-extent of `dem`
// that publishes its CRS, so that an update of a sub-extent reads it and its halo alone, as
// behind vtkApertureDEMReader.
struct Streamed
{
  vtkNew<StripSource> Source;
  vtkNew<vtkApertureSkyVisibility> Sky;
  Streamed(vtkImageData* dem, const Setup& setup)
  {
    this->Source->Image = dem;
    this->Source->PublishCRS = true;
    this->Sky->SetInputConnection(this->Source->GetOutputPort());
    this->Sky->SetComputeHorizonAngles(true);
    setup(this->Sky);
  }
};

// Component c of product `name` at grid point (i, j) of `image` (of any extent).
double At(vtkImageData* image, const char* name, int i, int j, int c = 0)
{
  vtkDataArray* a = image->GetPointData()->GetArray(name);
  int ext[6];
  image->GetExtent(ext);
  if (!a || i < ext[0] || i > ext[1] || j < ext[2] || j > ext[3])
  {
    std::fprintf(stderr, "no %s at (%d, %d)\n", name, i, j);
    ++aptest::Failures();
    return std::numeric_limits<double>::quiet_NaN();
  }
  return a->GetComponent((j - ext[2]) * (ext[1] - ext[0] + 1) + (i - ext[0]), c);
}

// Every product of `got` (over its extent) equals `whole`'s there, bit for bit (NaN too).
void CheckSameBits(vtkImageData* got, vtkImageData* whole, const char* what)
{
  int ext[6];
  got->GetExtent(ext);
  for (const char* name : kProducts)
  {
    vtkDataArray* a = got->GetPointData()->GetArray(name);
    vtkDataArray* b = whole->GetPointData()->GetArray(name);
    if (!a || !b || a->GetNumberOfComponents() != b->GetNumberOfComponents() ||
      a->GetDataType() != b->GetDataType())
    {
      std::fprintf(stderr, "%s: %s missing or of another layout\n", what, name);
      ++aptest::Failures();
      continue;
    }
    int differ = 0;
    for (int j = ext[2]; j <= ext[3]; ++j)
    {
      for (int i = ext[0]; i <= ext[1]; ++i)
      {
        for (int c = 0; c < a->GetNumberOfComponents(); ++c)
        {
          const float x = static_cast<float>(At(got, name, i, j, c));
          const float y = static_cast<float>(At(whole, name, i, j, c));
          differ += std::memcmp(&x, &y, sizeof(float)) != 0;
        }
      }
    }
    if (differ)
    {
      std::fprintf(stderr, "%s: %d values of %s differ from the whole run's\n", what, differ,
        name);
      ++aptest::Failures();
    }
  }
}

// Rough terrain (sums of sines and a hash's noise, 0..~900 m), the same in every CRS.
float Rough(int i, int j)
{
  unsigned h = static_cast<unsigned>(i) * 73856093u ^ static_cast<unsigned>(j) * 19349663u;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return static_cast<float>(400.0 + 200.0 * std::sin(0.21 * i) * std::cos(0.17 * j) +
    150.0 * std::sin(0.05 * (i + 2 * j)) + 40.0 * ((h & 0xffff) / 65535.0));
}

// A flat plane, curvature off: the whole sky is visible from every cell (A = 2 pi, rp = 90
// degrees, B = up, both sky-view factors 1), and at the centre, whose search stays inside the
// DEM in every sector, each horizon is 0 and the openness 90 degrees. In each CRS kind and
// search mode.
void TestPlanes()
{
  const Grid grids[] = { { "EPSG:32633", 400000, 5000000, 30, 30 },
    { "EPSG:4326", 15.0, 60.0, 1.0 / 1200, 1.0 / 1200 }, // (15.5 x 30.9 m cells)
    { "EPSG:3035", 4800000, 2800000, 30, 30 },           // (not conformal: the ground lattice)
    { kLocal, 1000, 2000, 30, 30 } };
  // marched (at most 64 steps), far-marched (at most 1024), swept (no limit)
  const double distances[] = { 200.0, 2500.0, 0.0 };
  for (const Grid& g : grids)
  {
    auto dem = MakeDEM(g.crs, g.x0, g.y0, g.dx, g.dy, 41, 31, [](int, int) { return 250.0f; });
    for (double distance : distances)
    {
      auto out = Sky(dem, [&](vtkApertureSkyVisibility* s) {
        s->SetEarthCurvature(false);
        s->SetMaximumDistance(distance);
        s->SetNumberOfDirections(16);
      });
      if (!out->GetPointData()->GetArray("VisibleSolidAngle"))
      {
        std::fprintf(stderr, "no output on the plane in %s at %g m\n", g.crs, distance);
        ++aptest::Failures();
        continue;
      }
      for (int j = 0; j < 31; j += 5)
      {
        for (int i = 0; i < 41; i += 4)
        {
          AP_CHECK_NEAR(At(out, "VisibleSolidAngle", i, j), 2.0 * kPi, 2e-6);
          AP_CHECK_NEAR(At(out, "ApertureRadius", i, j), 0.5 * kPi, 1e-5);
          AP_CHECK_NEAR(At(out, "BentNormal", i, j, 0), 0.0, 1e-6);
          AP_CHECK_NEAR(At(out, "BentNormal", i, j, 1), 0.0, 1e-6);
          AP_CHECK_NEAR(At(out, "BentNormal", i, j, 2), 1.0, 1e-6);
          AP_CHECK_NEAR(At(out, "SkyViewFactor", i, j), 1.0, 1e-6);
          AP_CHECK_NEAR(At(out, "DiffuseSkyFactor", i, j), 1.0, 1e-6);
        }
      }
      for (int d = 0; d < 16; ++d)
      {
        AP_CHECK_NEAR(At(out, "HorizonAngles", 20, 15, d), 0.0, 1e-6);
      }
      AP_CHECK_NEAR(At(out, "PositiveOpenness", 20, 15), 0.5 * kPi, 1e-6);
      // the DEM goes on for 200 m around the centre, not for 2.5 km; without a limit (and
      // without curvature) terrain beyond the edge could always matter; a corner's search
      // always leaves it
      AP_CHECK(At(out, "EdgeTruncated", 20, 15) == (distance == 200.0 ? 0.0 : 1.0));
      AP_CHECK(At(out, "EdgeTruncated", 0, 0) == 1.0);
    }
  }
}

// Flat ground at 0 m with a wall 100 m high from grid row 40 north: from a cell n rows south
// of it the horizon towards the north is where the bilinear surface reaches the wall's top,
// atan(100 / (n dy)); with curvature and refraction k the wall's top drops by
// (1 - k) d^2 / 2R at ground distance d: atan(100 / d - (1 - k) d / 2R). In a local CRS (R the
// Earth's mean radius) and on a lat/lon DEM at the equator (dy the meridian arc of 3
// arc-seconds there, R the meridian radius of curvature a (1 - e^2)), in each search mode.
// Their slopes tan h match to float rounding (1e-6), except on the lat/lon grid in the near
// field (NearField 1) and where the rays are marched: on grids with per-row cell sizes the
// steps of those rays are rounded to 1e-4 in log(length), so that pieces share their patterns
// (ap_horizon.c, "Near-field patterns"): within 6e-5 there (5e-5 of the step at most). The
// local grid's cells are all of one size, and exact.
void TestWall()
{
  const double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2.0 - f);
  const double meridian = a * (1.0 - e2); // (at the equator)
  struct WallGrid
  {
    Grid grid;
    double metresNorth, radius; // (a row's ground step; the radius of curvature northwards)
  };
  const double arc = 1.0 / 1200.0;
  const WallGrid grids[] = { { { kLocal, 1000, 2000, 30, 30 }, 30, 6371008.8 },
    { { "EPSG:4326", 10.0, -20 * arc, arc, arc }, meridian * arc * kPi / 180.0, meridian } };
  for (const WallGrid& w : grids)
  {
    const Grid& g = w.grid;
    auto dem = MakeDEM(g.crs, g.x0, g.y0, g.dx, g.dy, 41, 60,
      [](int, int j) { return j >= 40 ? 100.0f : 0.0f; });
    for (double distance : { 25.0 * w.metresNorth, 80.0 * w.metresNorth, 0.0 })
    {
      for (bool curvature : { false, true })
      {
        for (int nearField : { 1, 0 })
        {
          auto out = Sky(dem, [&](vtkApertureSkyVisibility* s) {
            s->SetEarthCurvature(curvature);
            s->SetMaximumDistance(distance);
            s->SetNumberOfDirections(8);
            s->SetNearField(nearField);
          });
          for (int n : { 3, 20 })
          {
            const double d = n * w.metresNorth;
            const double drop = curvature ? (1.0 - 0.13) * d / (2.0 * w.radius) : 0.0;
            const double expected = 100.0 / d - drop;
            const double got = std::tan(At(out, "HorizonAngles", 20, 40 - n, 0));
            const bool patterns = g.crs != kLocal &&
              (nearField != 1 || distance == 25.0 * w.metresNorth);
            if (!(std::fabs(got / expected - 1.0) <= (patterns ? 6e-5 : 1e-6)))
            {
              std::fprintf(stderr,
                "wall in %s, %g m, curvature %d, near field %d, %d rows: slope %.9g, "
                "expected %.9g\n",
                g.crs, distance, curvature, nearField, n, got, expected);
              ++aptest::Failures();
            }
          }
        }
      }
    }
  }
}

// Sub-extents through a streaming source that publishes the CRS (so the filter reads the
// region and its halo, as behind vtkApertureDEMReader) and one thread instead of two: the
// whole run's values bit for bit, on a projected and a lat/lon DEM, marched, far-marched and
// swept.
void TestPiecesAndThreads()
{
  const Grid grids[] = { { "EPSG:32633", 400000, 5000000, 30, 30 },
    { "EPSG:4326", 15.0, 60.0, 1.0 / 1200, 1.0 / 1200 } };
  for (const Grid& g : grids)
  {
    auto dem = MakeDEM(g.crs, g.x0, g.y0, g.dx, g.dy, 90, 70, Rough);
    for (double distance : { 900.0, 2400.0, 0.0 })
    {
      const Setup setup = [distance](vtkApertureSkyVisibility* s) {
        s->SetMaximumDistance(distance);
        s->SetNumberOfDirections(12);
        s->SetNumberOfThreads(2);
      };
      auto whole = Sky(dem, setup);
      auto oneThread = Sky(dem, [&](vtkApertureSkyVisibility* s) {
        setup(s);
        s->SetNumberOfThreads(1);
      });
      CheckSameBits(oneThread, whole, "one thread");

      Streamed streamed(dem, setup);
      vtkApertureSkyVisibility* sky = streamed.Sky;
      const int pieces[][6] = { { 10, 49, 20, 44, 0, 0 }, { 0, 89, 60, 69, 0, 0 },
        { 70, 89, 0, 5, 0, 0 } };
      for (const auto& piece : pieces)
      {
        sky->UpdateExtent(piece);
        CheckSameBits(sky->GetOutput(), whole, "piece");
        int got[6];
        sky->GetOutput()->GetExtent(got);
        AP_CHECK(std::equal(got, got + 6, piece));
        // without a limit the source is asked for all of it; at 900 m on the UTM grid (30
        // cells and 2), for the region and its halo
        const std::vector<int>& asked = streamed.Source->Requests.back();
        const bool all = asked[0] == 0 && asked[1] == 89 && asked[2] == 0 && asked[3] == 69;
        AP_CHECK(distance != 0.0 || all);
        AP_CHECK(distance != 900.0 || g.dx != 30 || !all);
      }
    }
  }
}

// A global lat/lon DEM (240 columns of 1.5 degrees) has no east and west edges: a mountain just
// east of the antimeridian raises the horizon west of a cell just west of it; no cell at
// either side is EdgeTruncated; the products equal, bit for bit, those of the same DEM with
// its seam 100 columns further on (rolled, its columns' longitudes with them); and a piece
// beside the seam reads every column (its halo the other side's), one inside its own halo
// alone, each the whole run's values. At 400 km and unlimited. The same on Web Mercator (cells
// of 1.5 degrees of longitude by as many metres, from 41 S to 41 N; its edges did not join
// until 2026-12-07), `crs` with columns from x0, `cell` wide and high, rows from y0.
void TestAntimeridian(const char* crs, double x0, double y0, double cell)
{
  const int nx = 240, ny = 60, roll = 100;
  const auto terrain = [](int i, int j) {
    const double lon = -180.0 + 1.5 * (i + 0.5), lat = -45.0 + 1.5 * (j + 0.5);
    return static_cast<float>(
      3000.0 * std::exp(-((lon - 178.5) * (lon - 178.5) + lat * lat) / 4.0) + Rough(i, j) / 2);
  };
  auto dem = MakeDEM(crs, x0, y0, cell, cell, nx, ny, terrain);
  auto rolled = MakeDEM(crs, x0 + cell * roll, y0, cell, cell, nx, ny,
    [&](int i, int j) { return terrain((i + roll) % nx, j); });
  for (double distance : { 400000.0, 0.0 })
  {
    const Setup setup = [distance](vtkApertureSkyVisibility* s) {
      s->SetMaximumDistance(distance);
      s->SetNumberOfDirections(16);
    };
    auto whole = Sky(dem, setup);
    auto other = Sky(rolled, setup);
    int differ = 0;
    for (const char* name : kProducts)
    {
      const int components = whole->GetPointData()->GetArray(name)->GetNumberOfComponents();
      for (int j = 0; j < ny; ++j)
      {
        for (int i = 0; i < nx; ++i)
        {
          for (int c = 0; c < components; ++c)
          {
            differ += At(whole, name, i, j, c) != At(other, name, (i - roll + nx) % nx, j, c);
          }
        }
      }
    }
    AP_CHECK(differ == 0);
    for (int j = 5; j < ny - 5; ++j)
    {
      AP_CHECK(At(whole, "EdgeTruncated", 0, j) == 0.0);
      AP_CHECK(At(whole, "EdgeTruncated", nx - 1, j) == 0.0);
    }
    // west (sector 12 of 16) of the westernmost cell at the equator: the mountain 2.5 deg away
    AP_CHECK(At(whole, "HorizonAngles", 0, 30, 12) > 0.005);

    Streamed streamed(dem, setup);
    // the columns joined on each side: the halo of 400 km at the widest row's smallest cells
    // (1.5 degrees of the parallel at 44.25 degrees, 119.8 km: 4 and 2 more), half the DEM's
    // without a distance; none for an input without every column
    streamed.Sky->UpdateInformation();
    const int all[6] = { 0, nx - 1, 0, ny - 1, 0, 0 }, some[6] = { 0, nx - 2, 0, ny - 1, 0, 0 };
    AP_CHECK(streamed.Sky->GetWrapColumns(all) == (distance == 0.0 ? nx / 2 : 6));
    AP_CHECK(streamed.Sky->GetWrapColumns(some) == 0);
    const int pieces[][6] = { { 0, 9, 25, 34, 0, 0 }, { 100, 139, 20, 39, 0, 0 } };
    for (const auto& piece : pieces)
    {
      streamed.Sky->UpdateExtent(piece);
      CheckSameBits(streamed.Sky->GetOutput(), whole, "a piece of a global DEM");
      const std::vector<int>& asked = streamed.Source->Requests.back();
      const bool everyColumn = asked[0] == 0 && asked[1] == nx - 1;
      AP_CHECK(everyColumn == (distance == 0.0 || piece[0] == 0));
    }
  }
}

// Nodata: NaN products at the nodata cells, finite ones around; a piece whose input (with its
// halo) is all nodata gives nodata products (EdgeTruncated 0) and says so; a DEM of nodata
// alone is an error (TestErrors).
void TestNodata()
{
  const float nan = std::numeric_limits<float>::quiet_NaN();
  auto dem = MakeDEM("EPSG:32633", 400000, 5000000, 30, 30, 40, 30, [nan](int i, int j) {
    return i >= 2 && i < 28 && j >= 2 && j < 28 ? nan : Rough(i, j);
  });
  const Setup setup = [](vtkApertureSkyVisibility* s) { s->SetMaximumDistance(60.0); };
  auto whole = Sky(dem, setup);
  AP_CHECK(std::isnan(At(whole, "SkyViewFactor", 10, 10)));
  AP_CHECK(std::isnan(At(whole, "HorizonAngles", 10, 10, 3)));
  AP_CHECK(At(whole, "EdgeTruncated", 10, 10) == 0.0);
  AP_CHECK(std::isfinite(At(whole, "SkyViewFactor", 35, 10)));
  AP_CHECK(std::isfinite(At(whole, "SkyViewFactor", 10, 29)));

  Streamed streamed(dem, setup);
  vtkApertureSkyVisibility* sky = streamed.Sky;
  const int sea[6] = { 12, 17, 12, 17, 0, 0 };
  AP_CHECK(sky->UpdateExtent(sea) == 1);
  AP_CHECK(sky->GetInputAllNodata());
  CheckSameBits(sky->GetOutput(), whole, "a piece of nodata");
  const int coast[6] = { 24, 33, 12, 17, 0, 0 };
  AP_CHECK(sky->UpdateExtent(coast) == 1);
  AP_CHECK(!sky->GetInputAllNodata());
  CheckSameBits(sky->GetOutput(), whole, "a piece of the coast");
}

// Elevations as doubles and as 16-bit integers: the float run's values; a double beyond the
// float range is nodata. AnglesInDegrees and FloatEdgeTruncated change units and types only.
void TestArrayTypesAndUnits()
{
  auto rounded = [](int i, int j) { return std::round(Rough(i, j)); };
  auto dem = MakeDEM("EPSG:32633", 400000, 5000000, 30, 30, 30, 20, rounded);
  const Setup setup = [](vtkApertureSkyVisibility* s) { s->SetMaximumDistance(300.0); };
  auto expected = Sky(dem, setup);
  vtkNew<vtkDoubleArray> doubles;
  vtkNew<vtkShortArray> shorts;
  for (vtkDataArray* values : { static_cast<vtkDataArray*>(doubles), // (a braced list's type)
         static_cast<vtkDataArray*>(shorts) })
  {
    auto typed = MakeDEM("EPSG:32633", 400000, 5000000, 30, 30, 30, 20, rounded);
    values->SetName("Elevation");
    values->SetNumberOfTuples(600);
    for (vtkIdType k = 0; k < 600; ++k)
    {
      values->SetComponent(k, 0, rounded(static_cast<int>(k % 30), static_cast<int>(k / 30)));
    }
    typed->GetPointData()->SetScalars(values);
    CheckSameBits(Sky(typed, setup), expected, values->GetClassName());
  }
  // an image without an "Elevation" array (made by hand, VTK's way): its active scalars
  auto unnamed = MakeDEM("EPSG:32633", 400000, 5000000, 30, 30, 30, 20, rounded);
  vtkNew<vtkShortArray> dem16;
  dem16->DeepCopy(shorts);
  dem16->SetName("band1");
  unnamed->GetPointData()->RemoveArray("Elevation");
  unnamed->GetPointData()->SetScalars(dem16);
  CheckSameBits(Sky(unnamed, setup), expected, "the active scalars 'band1'");
  // ... which come out as the point array Elevation too (their memory shared), beside band1,
  // and in place of unnamed scalars, as the terrain mesh's do (until 2026-12-06 unnamed ones
  // stayed unnamed, and a writer, which writes named arrays, left the heights out)
  {
    auto named = Sky(unnamed, setup);
    vtkPointData* pd = named->GetPointData();
    AP_CHECK(pd->GetArray("band1") && pd->GetArray("Elevation") &&
      pd->GetArray("Elevation")->GetVoidPointer(0) == pd->GetArray("band1")->GetVoidPointer(0));
    dem16->SetName(nullptr);
    unnamed->Modified();
    auto renamed = Sky(unnamed, setup);
    pd = renamed->GetPointData();
    AP_CHECK(pd->GetScalars() && pd->GetScalars()->GetName() &&
      std::string(pd->GetScalars()->GetName()) == "Elevation");
    AP_CHECK(unnamed->GetPointData()->GetScalars()->GetName() == nullptr); // (the input's kept)
    AP_CHECK(pd->GetArray("Elevation") &&
      pd->GetArray("Elevation")->GetTuple1(5 * 30 + 7) == rounded(7, 5));
    CheckSameBits(renamed, expected, "unnamed active scalars");
  }
  // doubles beyond the float range (and infinities) are nodata, as NaN is
  auto holes = MakeDEM("EPSG:32633", 400000, 5000000, 30, 30, 30, 20, [&](int i, int j) {
    return i == 7 && j == 5 ? std::numeric_limits<float>::quiet_NaN() : rounded(i, j);
  });
  auto expectedHoles = Sky(holes, setup);
  auto beyond = MakeDEM("EPSG:32633", 400000, 5000000, 30, 30, 30, 20, rounded);
  vtkNew<vtkDoubleArray> big;
  big->DeepCopy(doubles);
  big->SetValue(5 * 30 + 7, 1e300);
  beyond->GetPointData()->SetScalars(big);
  CheckSameBits(Sky(beyond, setup), expectedHoles, "a double beyond the float range");

  auto degrees = Sky(dem, [&](vtkApertureSkyVisibility* s) {
    setup(s);
    s->SetAnglesInDegrees(true);
    s->SetFloatEdgeTruncated(true);
  });
  AP_CHECK(vtkFloatArray::SafeDownCast(degrees->GetPointData()->GetArray("EdgeTruncated")));
  AP_CHECK(
    vtkUnsignedCharArray::SafeDownCast(expected->GetPointData()->GetArray("EdgeTruncated")));
  for (int j = 0; j < 20; j += 3)
  {
    for (int i = 0; i < 30; i += 3)
    {
      AP_CHECK(At(degrees, "EdgeTruncated", i, j) == At(expected, "EdgeTruncated", i, j));
      AP_CHECK(At(degrees, "SkyViewFactor", i, j) == At(expected, "SkyViewFactor", i, j));
      for (const char* angle : { "ApertureRadius", "PositiveOpenness" })
      {
        AP_CHECK_NEAR(At(degrees, angle, i, j), At(expected, angle, i, j) * 180.0 / kPi, 3e-5);
      }
      AP_CHECK_NEAR(At(degrees, "HorizonAngles", i, j, 5),
        At(expected, "HorizonAngles", i, j, 5) * 180.0 / kPi, 3e-5);
    }
  }
}

// SetInputArrayToProcess(0, ...) selects the elevations as VTK's filters take theirs (it was
// ignored until 2026-12-06): a point array by name, or the point scalars by attribute type,
// once called (vtkImageAlgorithm's own default selection of the scalars leaves the
// ElevationArrayName in force); cell data or another attribute is an error. A flat array
// selected gives a sky-view factor of 1 everywhere.
void ExpectError(vtkImageData* dem, const Setup& setup, const std::string& expected);

void TestInputArraySelection()
{
  const Setup setup = [](vtkApertureSkyVisibility* s) { s->SetMaximumDistance(300.0); };
  auto dem = MakeDEM("EPSG:32633", 400000, 5000000, 30, 30, 20, 20, Rough);
  auto expected = Sky(dem, setup);
  vtkNew<vtkFloatArray> flat;
  flat->SetName("flat");
  flat->SetNumberOfTuples(400);
  flat->Fill(250.0);
  dem->GetPointData()->AddArray(flat);
  auto allFlat = [](vtkImageData* out, const char* what) {
    vtkDataArray* svf = out->GetPointData()->GetArray("SkyViewFactor");
    AP_CHECK(svf != nullptr);
    for (vtkIdType k = 0; svf && k < svf->GetNumberOfTuples(); ++k)
    {
      if (std::fabs(svf->GetTuple1(k) - 1.0) > 1e-6)
      {
        std::printf("%s: SkyViewFactor %g at %lld\n", what, svf->GetTuple1(k),
          static_cast<long long>(k));
        AP_CHECK(false);
        break;
      }
    }
  };
  allFlat(Sky(dem, [&](vtkApertureSkyVisibility* s) {
    setup(s);
    s->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "flat");
  }),
    "by name");
  // the scalars: 'flat' made active; without the call, Elevation is still read
  dem->GetPointData()->SetActiveScalars("flat");
  CheckSameBits(Sky(dem, setup), expected, "the default selection, flat scalars beside");
  allFlat(Sky(dem, [&](vtkApertureSkyVisibility* s) {
    setup(s);
    s->SetInputArrayToProcess(
      0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
  }),
    "the point scalars");
  // so does a null or empty ElevationArrayName, as VTK's filters take unnamed input (both were
  // "no point array named ''" until 2026-12-07)
  for (const char* name : { static_cast<const char*>(nullptr), "" })
  {
    allFlat(Sky(dem, [&](vtkApertureSkyVisibility* s) {
      setup(s);
      s->SetElevationArrayName(name);
    }),
      "no name: the point scalars");
  }
  // ... and the Elevation array selected by name, whatever the scalars
  CheckSameBits(Sky(dem,
                  [&](vtkApertureSkyVisibility* s) {
                    setup(s);
                    s->SetInputArrayToProcess(
                      0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Elevation");
                  }),
    expected, "Elevation by name");
  // The scalars chosen are the scalars, unnamed ones too, beside a flat array named Elevation
  // (until review they were looked up as 'Elevation', which found it: SkyViewFactor 1
  // everywhere); the output's Elevation stays that array.
  {
    auto mixed = MakeDEM("EPSG:32633", 400000, 5000000, 30, 30, 20, 20, Rough);
    vtkNew<vtkFloatArray> unnamed;
    unnamed->DeepCopy(mixed->GetPointData()->GetArray("Elevation"));
    unnamed->SetName(nullptr);
    mixed->GetPointData()->RemoveArray("Elevation");
    mixed->GetPointData()->SetScalars(unnamed);
    vtkNew<vtkFloatArray> level;
    level->DeepCopy(flat);
    level->SetName("Elevation");
    mixed->GetPointData()->AddArray(level);
    for (const Setup& choose : { Setup([](vtkApertureSkyVisibility* s) {
           s->SetElevationArrayName(nullptr);
         }),
           Setup([](vtkApertureSkyVisibility* s) {
             s->SetInputArrayToProcess(
               0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
           }) })
    {
      auto out = Sky(mixed, [&](vtkApertureSkyVisibility* s) {
        setup(s);
        choose(s);
      });
      CheckSameBits(out, expected, "unnamed scalars beside a flat Elevation");
      AP_CHECK(out->GetPointData()->GetArray("Elevation") &&
        out->GetPointData()->GetArray("Elevation")->GetRange()[1] == 250.0);
    }
  }
  // Of ElevationArrayName and a selection, the one made last holds (until 2026-12-07 a name
  // set after any selection was kept, and ignored): one filter, updated after each.
  {
    vtkNew<vtkApertureSkyVisibility> s;
    setup(s);
    s->SetInputData(dem);
    s->SetComputeHorizonAngles(true); // (as Sky's)
    s->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "flat");
    s->Update();
    allFlat(s->GetOutput(), "selected");
    s->SetElevationArrayName("Elevation"); // (the name it had: the selection replaced)
    s->Update();
    CheckSameBits(s->GetOutput(), expected, "the name after a selection");
    s->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "flat");
    s->Update();
    allFlat(s->GetOutput(), "selected again");
  }
  ExpectError(dem,
    [](vtkApertureSkyVisibility* s) {
      s->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "flat");
    },
    "SetInputArrayToProcess selects an array that is not point data");
  ExpectError(dem,
    [](vtkApertureSkyVisibility* s) {
      s->SetInputArrayToProcess(
        0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::VECTORS);
    },
    "SetInputArrayToProcess selects the point Vectors, not the scalars");
  ExpectError(dem,
    [](vtkApertureSkyVisibility* s) {
      s->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Height");
    },
    "the input has no point array named 'Height'");
}

// An observer aborting at the first progress event (the executive's own, at 0, before the
// filter runs): the filter stops at its first checkpoint (its progress 0 after the copy of the
// elevations), before any sector, and the update fails with no products.
void TestAbort()
{
  auto dem = MakeDEM("EPSG:32633", 400000, 5000000, 30, 30, 50, 40, Rough);
  vtkNew<vtkApertureSkyVisibility> sky;
  sky->SetInputData(dem);
  std::vector<double> progress;
  vtkNew<vtkCallbackCommand> abort;
  abort->SetClientData(&progress);
  abort->SetCallback([](vtkObject* caller, unsigned long, void* client, void*) {
    auto* algorithm = static_cast<vtkAlgorithm*>(caller);
    static_cast<std::vector<double>*>(client)->push_back(algorithm->GetProgress());
    algorithm->SetAbortExecute(1);
  });
  sky->AddObserver(vtkCommand::ProgressEvent, abort);
  vtkNew<vtkTest::ErrorObserver> errors, executiveErrors; // (an aborted update fails)
  sky->AddObserver(vtkCommand::ErrorEvent, errors);
  sky->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, executiveErrors);
  sky->Update();
  AP_CHECK(progress == std::vector<double>({ 0.0, 0.0 }));
  AP_CHECK(sky->GetOutput()->GetPointData()->GetArray("SkyViewFactor") == nullptr);
}

// Two updates on two threads whose parallel work overlaps, X's ending within Y's: VTK's
// vtkSMPTools::LocalScope restores the configuration it found, so Y's end put back X's
// (Sequential, one thread) for every later VTK filter of the process, until 2026-12-06. Now
// the process's configuration is afterwards what it was, and both results the lone update's.
void TestOverlappingScopes()
{
  auto dem = MakeDEM("EPSG:32633", 400000, 5000000, 30, 30, 50, 40, Rough);
  const Setup setup = [](vtkApertureSkyVisibility* s) {
    s->SetNumberOfDirections(8);
    s->ComputeHorizonAnglesOn();
  };
  auto alone = Sky(dem, setup);
  const std::string backend = vtkSMPTools::GetBackend();
  const int threads = vtkSMPTools::GetEstimatedNumberOfThreads();

  struct Meeting
  {
    std::mutex Mutex;
    std::condition_variable Changed;
    bool XInside = false, Go = false, XWaited = false, YMet = false;
    std::thread X;
  } meet;
  // X waits in its first progress event within its parallel work (0 < p < 1) until Y is
  // within its own; Y lets X go and waits for X to finish.
  const auto prepare = [&](vtkApertureSkyVisibility* s, int threadCount) {
    setup(s);
    s->SetInputData(dem);
    s->SetNumberOfThreads(threadCount);
  };
  // the process's configuration as before, and both results the lone update's
  const auto restoredAndSame = [&](vtkApertureSkyVisibility* a, const char* aWhat,
                                 vtkApertureSkyVisibility* b, const char* bWhat) {
    AP_CHECK(vtkSMPTools::GetBackend() == backend);
    AP_CHECK(vtkSMPTools::GetEstimatedNumberOfThreads() == threads);
    CheckSameBits(a->GetOutput(), alone, aWhat);
    CheckSameBits(b->GetOutput(), alone, bWhat);
  };
  vtkNew<vtkApertureSkyVisibility> x, y;
  prepare(x, 1);
  prepare(y, 2);
  vtkNew<vtkCallbackCommand> xWaits, yMeets;
  xWaits->SetClientData(&meet);
  xWaits->SetCallback([](vtkObject* caller, unsigned long, void* client, void*) {
    auto& m = *static_cast<Meeting*>(client);
    const double p = static_cast<vtkAlgorithm*>(caller)->GetProgress();
    if (p > 0.0 && p < 1.0 && !m.XWaited)
    {
      m.XWaited = true;
      std::unique_lock<std::mutex> lock(m.Mutex);
      m.XInside = true;
      m.Changed.notify_all();
      // (a minute at most: were Y never to reach an event, the test fails below, not hangs)
      m.Changed.wait_for(lock, std::chrono::minutes(1), [&m]() { return m.Go; });
    }
  });
  yMeets->SetClientData(&meet);
  yMeets->SetCallback([](vtkObject* caller, unsigned long, void* client, void*) {
    auto& m = *static_cast<Meeting*>(client);
    const double p = static_cast<vtkAlgorithm*>(caller)->GetProgress();
    if (p > 0.0 && p < 1.0 && !m.YMet)
    {
      m.YMet = true;
      {
        const std::lock_guard<std::mutex> lock(m.Mutex);
        m.Go = true;
      }
      m.Changed.notify_all();
      m.X.join();
    }
  });
  x->AddObserver(vtkCommand::ProgressEvent, xWaits);
  y->AddObserver(vtkCommand::ProgressEvent, yMeets);
  meet.X = std::thread([&x]() { x->Update(); });
  {
    std::unique_lock<std::mutex> lock(meet.Mutex);
    AP_CHECK(meet.Changed.wait_for(
      lock, std::chrono::minutes(1), [&meet]() { return meet.XInside; }));
  }
  y->Update();
  if (meet.X.joinable())
  {
    meet.X.join(); // (Y's work had no event within it: the test did not overlap them)
  }
  AP_CHECK(meet.YMet);
  restoredAndSame(x, "the update on one thread", y, "the update on two threads");

  // An update within another's progress event, on the same thread: its scope nests and is
  // undone first, as LocalScope's own nesting is.
  vtkNew<vtkApertureSkyVisibility> outer, inner;
  prepare(outer, 2);
  prepare(inner, 1);
  vtkNew<vtkCallbackCommand> nests;
  nests->SetClientData(inner.GetPointer());
  nests->SetCallback([](vtkObject* caller, unsigned long, void* client, void*) {
    const double p = static_cast<vtkAlgorithm*>(caller)->GetProgress();
    auto* in = static_cast<vtkApertureSkyVisibility*>(client);
    if (p > 0.0 && p < 1.0 && in->GetNumberOfThreadsUsed() == 0)
    {
      in->Update();
    }
  });
  outer->AddObserver(vtkCommand::ProgressEvent, nests);
  // The inner update runs in its own scope, on the Sequential backend of its one thread, not
  // in the outer's (STDThread on two: with a plain mutex its try_lock said busy, and the
  // update ran in the outer's scope; GetNumberOfThreadsUsed, capped at 1, hid it).
  std::string innerBackend;
  vtkNew<vtkCallbackCommand> innerSees;
  innerSees->SetClientData(&innerBackend);
  innerSees->SetCallback([](vtkObject* caller, unsigned long, void* client, void*) {
    const double p = static_cast<vtkAlgorithm*>(caller)->GetProgress();
    auto& seen = *static_cast<std::string*>(client);
    if (p > 0.0 && p < 1.0 && seen.empty())
    {
      seen = vtkSMPTools::GetBackend();
    }
  });
  inner->AddObserver(vtkCommand::ProgressEvent, innerSees);
  outer->Update();
  AP_CHECK(inner->GetNumberOfThreadsUsed() == 1);
  AP_CHECK(innerBackend == "Sequential");
  restoredAndSame(outer, "the outer update", inner, "the update nested in its progress event");
}

// Each documented error: a failed update with a message naming the problem.
void ExpectError(vtkImageData* dem, const Setup& setup, const std::string& expected)
{
  vtkNew<vtkApertureSkyVisibility> sky;
  setup(sky);
  vtkNew<vtkTest::ErrorObserver> errors, executiveErrors;
  sky->AddObserver(vtkCommand::ErrorEvent, errors);
  sky->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, executiveErrors);
  sky->SetInputData(dem);
  AP_CHECK(sky->GetExecutive()->Update() == 0);
  if (errors->GetErrorMessage().find(expected) == std::string::npos)
  {
    std::fprintf(stderr, "expected an error containing '%s', got '%s'\n", expected.c_str(),
      errors->GetErrorMessage().c_str());
    ++aptest::Failures();
  }
}

void TestErrors()
{
  auto dem = MakeDEM("EPSG:32633", 400000, 5000000, 30, 30, 10, 10, Rough);
  const Setup none = [](vtkApertureSkyVisibility*) {};
  ExpectError(dem, [](vtkApertureSkyVisibility* s) { s->SetNumberOfDirections(3); },
    "NumberOfDirections must be within 4..360, not 3");
  ExpectError(dem, [](vtkApertureSkyVisibility* s) { s->SetNumberOfDirections(361); },
    "NumberOfDirections must be within 4..360, not 361");
  ExpectError(dem, [](vtkApertureSkyVisibility* s) { s->SetMaximumDistance(-1.0); },
    "MaximumDistance must be a distance in metres >= 0");
  ExpectError(dem,
    [](vtkApertureSkyVisibility* s) {
      s->SetMaximumDistance(std::numeric_limits<double>::infinity());
    },
    "MaximumDistance must be a distance in metres >= 0");
  ExpectError(dem, [](vtkApertureSkyVisibility* s) { s->SetRefractionCoefficient(1.0); },
    "RefractionCoefficient must be within [0, 1)");
  ExpectError(dem, [](vtkApertureSkyVisibility* s) { s->SetRefractionCoefficient(-0.1); },
    "RefractionCoefficient must be within [0, 1)");
  ExpectError(dem, [](vtkApertureSkyVisibility* s) { s->SetElevationArrayName("Height"); },
    "the input has no point array named 'Height' (its point arrays: 'Elevation'); "
    "SetElevationArrayName names the one holding elevations in metres");
  auto vectors = MakeDEM("EPSG:32633", 400000, 5000000, 30, 30, 10, 10, Rough);
  vtkNew<vtkFloatArray> v3;
  v3->SetName("Elevation");
  v3->SetNumberOfComponents(3);
  v3->SetNumberOfTuples(100);
  v3->Fill(0.0);
  vectors->GetPointData()->AddArray(v3); // (replaces the scalars of that name)
  ExpectError(
    vectors, none, "the elevation array 'Elevation' has 3 components; elevations need one");
  auto bare = MakeDEM("EPSG:32633", 400000, 5000000, 30, 30, 10, 10, Rough);
  bare->GetPointData()->RemoveArray("Elevation");
  ExpectError(bare, none,
    "the input has no point array named 'Elevation' and no point scalars: it has no point "
    "arrays");
  // an image that disagrees with itself (made by hand; too few heights: TestSkyVisibility.py):
  // another array, passed on or copied over a requested extent
  auto more = MakeDEM("EPSG:32633", 400000, 5000000, 30, 30, 10, 10, Rough);
  vtkNew<vtkFloatArray> extra;
  extra->SetName("Class");
  extra->SetNumberOfTuples(101);
  extra->Fill(1.0f);
  more->GetPointData()->AddArray(extra);
  ExpectError(more, none, "the point array 'Class' has 101 tuples for the 10 x 10 points");
  ExpectError(dem, [](vtkApertureSkyVisibility* s) { s->SetMemoryLimit(1000); },
    "more than the 1000 bytes MemoryLimit");
  // (the advice's local CRS is one SetCRS takes: the sky filter runs on it, below)
  ExpectError(MakeDEM(nullptr, 0, 0, 30, 30, 10, 10, Rough), none,
    "no metric cell size: the image has no CRS (field data array 'CRS'); read DEMs with "
    "vtkApertureDEMReader or attach one with vtkApertureGeoreference (SetCRS, such as "
    "'EPSG:32633', or for a grid in metres that is nowhere in particular "
    "'LOCAL_CS[\"grid\",UNIT[\"metre\",1]]'; then AttachToImage)");
  AP_CHECK(Sky(MakeDEM("LOCAL_CS[\"grid\",UNIT[\"metre\",1]]", 0, 0, 30, 30, 10, 10, Rough), none)
             ->GetPointData()
             ->GetArray("SkyViewFactor") != nullptr);
  ExpectError(MakeDEM("EPSG:32633", 400000, 5000000, 30, 30, 1, 5, Rough), none,
    "at least 2 x 2");
  ExpectError(MakeDEM("EPSG:32633", 400000, 5000000, 30, 30, 10, 10,
                [](int, int) { return std::numeric_limits<float>::quiet_NaN(); }),
    none, "every cell of the DEM is nodata");
  auto volume = vtkSmartPointer<vtkImageData>::New();
  volume->DeepCopy(dem);
  volume->SetDimensions(10, 5, 2);
  ExpectError(volume, none, "the DEM must be a 2-D image");
}
} // namespace

int TestApertureSkyVisibility(int, char*[])
{
  TestPlanes();
  TestWall();
  TestPiecesAndThreads();
  TestAntimeridian("EPSG:4326", -179.25, -44.25, 1.5);
  const double mercatorCell = 2.0 * 20037508.342789244 / 240; // (1.5 degrees of longitude)
  TestAntimeridian("EPSG:3857", -20037508.342789244 + 0.5 * mercatorCell,
    -29.5 * mercatorCell, mercatorCell);
  TestNodata();
  TestArrayTypesAndUnits();
  TestInputArraySelection();
  TestAbort();
  TestOverlappingScopes();
  TestErrors();
  return aptest::Result();
}
