// SPDX-License-Identifier: BSD-3-Clause
// vtkApertureDEMReader on rasters written here with GDAL's C API: orientation (north-up and
// south-up), georeference, nodata, scale/offset and units, subwindow, decimation, overviews,
// update extents, band choice, and every documented bad input.
#include "ApertureTestRasters.h"

#include "vtkApertureDEMReader.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkTestErrorObserver.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <string>

namespace
{
std::string tmp;

struct Read
{
  vtkNew<vtkApertureDEMReader> Reader;
  vtkNew<vtkTest::ErrorObserver> Errors, ExecutiveErrors, Warnings;
  int Ok = 0;
  explicit Read(const std::string& path)
  {
    this->Reader->SetFileName(path.c_str());
    this->Reader->AddObserver(vtkCommand::ErrorEvent, this->Errors);
    this->Reader->AddObserver(vtkCommand::WarningEvent, this->Warnings);
    this->Reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, this->ExecutiveErrors);
  }
  vtkImageData* Update()
  {
    this->Ok = this->Reader->GetExecutive()->Update();
    return this->Reader->GetOutput();
  }
  double Z(int i, int j)
  {
    return this->Reader->GetOutput()->GetPointData()->GetScalars()->GetTuple1(this->Index(i, j));
  }
  vtkIdType Index(int i, int j)
  {
    int ext[6];
    this->Reader->GetOutput()->GetExtent(ext);
    return static_cast<vtkIdType>(j - ext[2]) * (ext[1] - ext[0] + 1) + (i - ext[0]);
  }
};

// Check fix for flipped rows: a north-up Int16 raster with nodata, scale/offset. VTK row j is
// file row ny-1-j; elevation = raw * scale + offset; the nodata cell is NaN; geometry and
// georeference follow the geotransform.
void TestNorthUp()
{
  aptest::RasterSpec s;
  s.nx = 5;
  s.ny = 4;
  s.type = GDT_Int16;
  s.hasNoData = true;
  s.noData = -32768;
  s.scale = 0.5;
  s.offset = 100.0;
  s.raw = [](int, int c, int r) { return (c == 2 && r == 1) ? -32768.0 : 10.0 * r + c; };
  const std::string path = tmp + "/northup.tif";
  AP_CHECK(aptest::WriteRaster(path, s));
  Read rd(path);
  vtkImageData* img = rd.Update();
  AP_CHECK(rd.Ok == 1 && !rd.Errors->GetError());
  int dims[3];
  img->GetDimensions(dims);
  AP_CHECK(dims[0] == 5 && dims[1] == 4 && dims[2] == 1);
  double spacing[3], origin[3];
  img->GetSpacing(spacing);
  img->GetOrigin(origin);
  AP_CHECK_NEAR(spacing[0], 30.0, 0.0);
  AP_CHECK_NEAR(spacing[1], 30.0, 0.0);
  AP_CHECK_NEAR(origin[0], 500015.0, 1e-9);            // west edge + half a cell
  AP_CHECK_NEAR(origin[1], 4000000.0 - 120.0 + 15.0, 1e-9); // south edge + half a cell
  for (int j = 0; j < 4; ++j)
  {
    for (int i = 0; i < 5; ++i)
    {
      const int fileRow = 3 - j;
      if (i == 2 && fileRow == 1)
      {
        AP_CHECK(std::isnan(rd.Z(i, j)));
      }
      else
      {
        AP_CHECK_NEAR(rd.Z(i, j), (10.0 * fileRow + i) * 0.5 + 100.0, 0.0);
      }
    }
  }
  AP_CHECK(std::string(img->GetPointData()->GetScalars()->GetName()) == "Elevation");
  AP_CHECK(img->GetPointData()->GetScalars()->GetDataType() == VTK_FLOAT);
  auto* crs = vtkStringArray::SafeDownCast(img->GetFieldData()->GetAbstractArray("CRS"));
  AP_CHECK(crs && crs->GetValue(0).find("UTM zone 11N") != std::string::npos);
  auto* gt = vtkDoubleArray::SafeDownCast(img->GetFieldData()->GetArray("GeoTransform"));
  AP_CHECK(gt && gt->GetNumberOfValues() == 6);
  if (gt)
  {
    const double expected[6] = { 500000.0, 30.0, 0.0, 4000000.0, 0.0, -30.0 };
    for (int k = 0; k < 6; ++k)
    {
      AP_CHECK_NEAR(gt->GetValue(k), expected[k], 1e-9);
    }
  }
  AP_CHECK(rd.Reader->GetHasNoDataValue() && rd.Reader->GetNoDataValue() == -32768.0);
  AP_CHECK(std::string(rd.Reader->GetDriverName()) == "GTiff");
}

// A south-up raster (positive pixel height): file row r is VTK row r, and the grid comes out
// north-up with the same ground positions.
void TestSouthUp()
{
  aptest::RasterSpec s;
  s.gt[3] = 3999880.0; // south edge
  s.gt[5] = 30.0;
  const std::string path = tmp + "/southup.tif";
  AP_CHECK(aptest::WriteRaster(path, s));
  Read rd(path);
  vtkImageData* img = rd.Update();
  AP_CHECK(rd.Ok == 1);
  double origin[3];
  img->GetOrigin(origin);
  AP_CHECK_NEAR(origin[1], 3999880.0 + 15.0, 1e-9);
  for (int j = 0; j < 3; ++j)
  {
    for (int i = 0; i < 4; ++i)
    {
      AP_CHECK_NEAR(rd.Z(i, j), 10.0 * j + i, 0.0);
    }
  }
  auto* gt = vtkDoubleArray::SafeDownCast(img->GetFieldData()->GetArray("GeoTransform"));
  AP_CHECK(gt && std::fabs(gt->GetValue(3) - (3999880.0 + 90.0)) < 1e-9 && gt->GetValue(5) < 0);
}

// NaN samples are nodata even without a declared nodata value.
void TestNaNSamples()
{
  aptest::RasterSpec s;
  s.raw = [](int, int c, int r) { return (c == 1 && r == 0) ? NAN : 5.0; };
  AP_CHECK(aptest::WriteRaster(tmp + "/nan.tif", s));
  Read rd(tmp + "/nan.tif");
  rd.Update();
  AP_CHECK(rd.Ok == 1 && !rd.Reader->GetHasNoDataValue());
  AP_CHECK(std::isnan(rd.Z(1, 2))); // file row 0 is the northern row, VTK row 2
  AP_CHECK_NEAR(rd.Z(0, 2), 5.0, 0.0);
}

// Feet become metres; an unknown unit warns and is taken as metres.
void TestUnits()
{
  // the table of unit names, as the command line's --zfactor also reads it
  const struct
  {
    const char* name;
    double metres;
  } names[] = { { "m", 1.0 }, { "Metres", 1.0 }, { "FEET", 0.3048 }, { "ft", 0.3048 },
    { "international foot", 0.3048 }, { "us-ft", 1200.0 / 3937.0 },
    { "US survey foot", 1200.0 / 3937.0 }, { "ftUS", 1200.0 / 3937.0 }, { "cm", 0.01 },
    { "Centimetres", 0.01 }, { "millimeter", 0.001 }, { "dm", 0.1 }, { "decimetre", 0.1 },
    { "KM", 1000.0 }, { "kilometers", 1000.0 }, { "cubits", 0.0 }, { "centimetre s", 0.0 },
    { "", 0.0 }, { nullptr, 0.0 } };
  for (const auto& n : names)
  {
    AP_CHECK(vtkApertureDEMReader::GetMetresPerUnit(n.name) == n.metres);
  }
  aptest::RasterSpec s;
  s.unit = "ft";
  s.raw = [](int, int, int) { return 1000.0; };
  AP_CHECK(aptest::WriteRaster(tmp + "/feet.tif", s));
  Read rd(tmp + "/feet.tif");
  rd.Update();
  AP_CHECK_NEAR(rd.Z(0, 0), 304.8, 1e-4);
  AP_CHECK(rd.Reader->GetElevationUnitRead() == 0.3048);
  AP_CHECK(std::string(rd.Reader->GetElevationUnitSource()) == "the band's unit 'ft'");
  s.unit = "US survey foot";
  AP_CHECK(aptest::WriteRaster(tmp + "/usfeet.tif", s));
  Read us(tmp + "/usfeet.tif");
  us.Update();
  AP_CHECK_NEAR(us.Z(0, 0), 1000.0 * 1200.0 / 3937.0, 1e-4);
  s.unit = "cm"; // (integer DEMs in centimetres)
  AP_CHECK(aptest::WriteRaster(tmp + "/centimetres.tif", s));
  Read cm(tmp + "/centimetres.tif");
  cm.Update();
  AP_CHECK(cm.Ok == 1 && !cm.Warnings->GetWarning());
  AP_CHECK_NEAR(cm.Z(0, 0), 10.0, 1e-6);
  AP_CHECK(std::string(cm.Reader->GetElevationUnitSource()) == "the band's unit 'cm'");
  s.unit = "cubits";
  AP_CHECK(aptest::WriteRaster(tmp + "/cubits.tif", s));
  Read cu(tmp + "/cubits.tif");
  cu.Update();
  AP_CHECK(cu.Ok == 1 && cu.Warnings->GetWarning());
  AP_CHECK_CONTAINS(cu.Warnings->GetWarningMessage(), "unknown unit 'cubits'");
  AP_CHECK_NEAR(cu.Z(0, 0), 1000.0, 0.0);
  AP_CHECK(cu.Reader->GetElevationUnitRead() == 1.0);

  // MetresPerElevationUnit overrides the band's unit (cubits: 0.4572 m), silently.
  Read cubits(tmp + "/cubits.tif");
  cubits.Reader->SetMetresPerElevationUnit(0.4572);
  cubits.Update();
  AP_CHECK(cubits.Ok == 1 && !cubits.Warnings->GetWarning());
  AP_CHECK_NEAR(cubits.Z(0, 0), 457.2, 1e-4);
  AP_CHECK(std::string(cubits.Reader->GetElevationUnitSource()) == "MetresPerElevationUnit");
  Read metres(tmp + "/feet.tif");
  metres.Reader->SetMetresPerElevationUnit(1.0);
  metres.Update();
  AP_CHECK_NEAR(metres.Z(0, 0), 1000.0, 0.0);
  // (1e300: the elevations overflowed to infinity, as nodata: "every cell is nodata")
  for (double bad : { -0.3048, std::nan(""), HUGE_VAL, 1e300, 10000.001 })
  {
    Read b(tmp + "/feet.tif");
    b.Reader->SetMetresPerElevationUnit(bad);
    b.Update();
    AP_CHECK(b.Ok == 0 && b.Errors->GetError());
    AP_CHECK_CONTAINS(
      b.Errors->GetErrorMessage(), "MetresPerElevationUnit must be a positive number of metres");
  }
  {
    Read km(tmp + "/feet.tif");
    km.Reader->SetMetresPerElevationUnit(10000.0); // (the largest unit taken)
    km.Update();
    AP_CHECK(km.Ok == 1);
  }

  // No unit in the band: metres, silently in a metric CRS or a geographic one...
  s.unit.clear();
  AP_CHECK(aptest::WriteRaster(tmp + "/nounit.tif", s));
  Read plain(tmp + "/nounit.tif");
  plain.Update();
  AP_CHECK(plain.Ok == 1 && !plain.Warnings->GetWarning());
  AP_CHECK_NEAR(plain.Z(0, 0), 1000.0, 0.0);
  AP_CHECK(std::string(plain.Reader->GetElevationUnitSource()) == "none in the file: metres");
  aptest::RasterSpec ll = s;
  ll.crs = "EPSG:4326";
  ll.gt[0] = -84.0;
  ll.gt[1] = 1.0 / 1200;
  ll.gt[5] = -1.0 / 1200;
  ll.gt[3] = 36.0;
  AP_CHECK(aptest::WriteRaster(tmp + "/nounit-ll.tif", ll));
  Read geographic(tmp + "/nounit-ll.tif");
  geographic.Update();
  AP_CHECK(geographic.Ok == 1 && !geographic.Warnings->GetWarning());
  // ...but a warning in a projected CRS in feet, whose DEMs' heights are often feet too.
  aptest::RasterSpec sp = s;
  sp.crs = "EPSG:2263"; // (NAD83 / New York Long Island (ftUS))
  sp.gt[0] = 1000000.0;
  sp.gt[3] = 200000.0;
  AP_CHECK(aptest::WriteRaster(tmp + "/stateplane.tif", sp));
  Read feetCRS(tmp + "/stateplane.tif");
  feetCRS.Update();
  AP_CHECK(feetCRS.Ok == 1 && feetCRS.Warnings->GetWarning());
  AP_CHECK_CONTAINS(feetCRS.Warnings->GetWarningMessage(),
    "has no elevation unit and its CRS is in US survey foot; elevations are read as metres");
  AP_CHECK_NEAR(feetCRS.Z(0, 0), 1000.0, 0.0);
  Read feetSaid(tmp + "/stateplane.tif");
  feetSaid.Reader->SetMetresPerElevationUnit(1200.0 / 3937.0);
  feetSaid.Update();
  AP_CHECK(feetSaid.Ok == 1 && !feetSaid.Warnings->GetWarning());
  AP_CHECK_NEAR(feetSaid.Z(0, 0), 1000.0 * 1200.0 / 3937.0, 1e-4);
  // (a CRS in kilometres says nothing of feet: no warning)
  Read kilometres(tmp + "/nounit.tif");
  kilometres.Reader->SetOverrideCRS("+proj=utm +zone=11 +datum=WGS84 +units=km +type=crs");
  kilometres.Update();
  AP_CHECK(kilometres.Ok == 1 && !kilometres.Warnings->GetWarning());

  // A compound CRS's height unit (here through OverrideCRS: NAVD88 height in US survey feet)
  // when the band has none; the band's own unit wins over it, with a warning.
  Read compound(tmp + "/nounit.tif");
  compound.Reader->SetOverrideCRS("EPSG:32611+6360");
  compound.Update();
  AP_CHECK(compound.Ok == 1 && !compound.Warnings->GetWarning());
  AP_CHECK_NEAR(compound.Z(0, 0), 1000.0 * 1200.0 / 3937.0, 1e-4);
  AP_CHECK(std::string(compound.Reader->GetElevationUnitSource()) ==
    "the CRS's height unit 'US survey foot'");
  s.unit = "metre";
  AP_CHECK(aptest::WriteRaster(tmp + "/metre.tif", s));
  Read disagree(tmp + "/metre.tif");
  disagree.Reader->SetOverrideCRS("EPSG:32611+6360");
  disagree.Update();
  AP_CHECK(disagree.Ok == 1 && disagree.Warnings->GetWarning());
  AP_CHECK_CONTAINS(disagree.Warnings->GetWarningMessage(),
    "has the unit 'metre' but the CRS's heights are in US survey foot; the band's unit is used");
  AP_CHECK_NEAR(disagree.Z(0, 0), 1000.0, 0.0);
}

// Subwindow, decimation (block means ignoring nodata), overviews and update extents.
void TestWindowsAndLevels()
{
  aptest::RasterSpec s;
  s.nx = 7;
  s.ny = 5;
  s.hasNoData = true;
  s.noData = -9999.0;
  s.raw = [](int, int c, int r) { return (c == 0 && r == 0) ? -9999.0 : 10.0 * r + c; };
  const std::string path = tmp + "/windows.tif";
  AP_CHECK(aptest::WriteRaster(path, s));

  // Subwindow x 1..3, y 1..2 (file rows 1, 2): VTK row 0 = file row 2.
  Read sub(path);
  sub.Reader->SetSubWindow(1, 1, 3, 2);
  vtkImageData* img = sub.Update();
  int dims[3];
  img->GetDimensions(dims);
  AP_CHECK(dims[0] == 3 && dims[1] == 2);
  AP_CHECK_NEAR(sub.Z(0, 0), 21.0, 0.0);
  AP_CHECK_NEAR(sub.Z(2, 1), 13.0, 0.0);
  double origin[3];
  img->GetOrigin(origin);
  AP_CHECK_NEAR(origin[0], 500000.0 + 30.0 + 15.0, 1e-9);
  AP_CHECK_NEAR(origin[1], 4000000.0 - 3 * 30.0 + 15.0, 1e-9);

  // Decimation 2: 7 x 5 -> 3 x 2 blocks over file rows 0-3, columns 0-5.
  // Block (0,0) = {NaN, 1, 10, 11} -> 22/3; block (2,1) = {24, 25, 34, 35} -> 29.5.
  Read dec(path);
  dec.Reader->SetDecimation(2);
  img = dec.Update();
  img->GetDimensions(dims);
  AP_CHECK(dims[0] == 3 && dims[1] == 2);
  double spacing[3];
  img->GetSpacing(spacing);
  AP_CHECK_NEAR(spacing[0], 60.0, 0.0);
  img->GetOrigin(origin);
  AP_CHECK_NEAR(origin[0], 500030.0, 1e-9);
  AP_CHECK_NEAR(origin[1], 4000000.0 - 120.0 + 30.0, 1e-9);
  AP_CHECK_NEAR(dec.Z(0, 1), 22.0 / 3.0, 1e-5); // VTK row 1 = first block row (north)
  AP_CHECK_NEAR(dec.Z(2, 0), 29.5, 1e-5);
  // the partial blocks left out (column 6, row 4) are said (silently until 2026-12-06); a
  // window that does not reach them, or a factor that divides the raster, says nothing
  AP_CHECK_CONTAINS(dec.Warnings->GetWarningMessage(), "windows.tif': decimation by 2 leaves "
    "out its last column (east) and its last row (south), partial 2 x 2 blocks (no factor "
    "above 1 divides 7 and 5)");
  const struct
  {
    int window[4], factor;
    const char* said; // nullptr: nothing
  } partial[] = { { { 0, 0, 6, 4 }, 2, nullptr }, { { 0, 0, 0, 0 }, 1, nullptr },
    { { 3, 0, 0, 4 }, 2, "leaves out its last column (east), partial 2 x 2 blocks (no factor "
                         "above 1 divides 7)" },
    { { 0, 0, 6, 0 }, 2, "leaves out its last row (south), partial 2 x 2" }, { { 0 }, 1, "" } };
  for (const auto& u : partial)
  {
    Read part(path);
    if (u.said && !*u.said) // (off: nothing said where it would be)
    {
      part.Reader->PartialBlockWarningOff();
      part.Reader->SetDecimation(2);
      part.Update();
      AP_CHECK(part.Ok == 1 && !part.Warnings->GetWarning());
      continue;
    }
    part.Reader->SetSubWindow(u.window[0], u.window[1], u.window[2], u.window[3]);
    part.Reader->SetDecimation(u.factor);
    part.Update();
    AP_CHECK(part.Ok == 1);
    if (u.said)
    {
      AP_CHECK_CONTAINS(part.Warnings->GetWarningMessage(), u.said);
    }
    else
    {
      AP_CHECK(!part.Warnings->GetWarning());
    }
  }

  // Overviews built by GDAL (2x average): level 0 is 4 x 3, cells 60 m.
  {
    GDALDatasetH ds = GDALOpen(path.c_str(), GA_Update);
    int levels[1] = { 2 };
    AP_CHECK(ds && GDALBuildOverviews(ds, "NEAREST", 1, levels, 0, nullptr, nullptr, nullptr) ==
        CE_None);
    GDALClose(ds);
  }
  Read ov(path);
  ov.Reader->SetOverviewLevel(0);
  img = ov.Update();
  img->GetDimensions(dims);
  AP_CHECK(ov.Ok == 1 && dims[0] == 4 && dims[1] == 3);
  img->GetSpacing(spacing);
  AP_CHECK_NEAR(spacing[0], 30.0 * 7.0 / 4.0, 1e-9);
  Read noLevel(path);
  noLevel.Reader->SetOverviewLevel(3);
  noLevel.Update();
  AP_CHECK(noLevel.Ok == 0);
  AP_CHECK_CONTAINS(noLevel.Errors->GetErrorMessage(), "level 3 does not exist");

  // An update extent reads only that piece, with the same values as a full read.
  Read piece(path);
  piece.Reader->UpdateInformation();
  int ext[6] = { 2, 4, 1, 3, 0, 0 };
  piece.Reader->UpdateExtent(ext);
  img = piece.Reader->GetOutput();
  int got[6];
  img->GetExtent(got);
  AP_CHECK(got[0] == 2 && got[1] == 4 && got[2] == 1 && got[3] == 3);
  for (int j = 1; j <= 3; ++j)
  {
    for (int i = 2; i <= 4; ++i)
    {
      AP_CHECK_NEAR(piece.Z(i, j), 10.0 * (4 - j) + i, 0.0);
    }
  }
}

// A global DEM (36 x 18 cells of 10 degrees) decimated by a factor that does not divide 36 loses
// its last partial block and with it the join of its east and west edges: a warning says so
// and names the dividing factors around it. Dividing factors, a window short of the width and
// a DEM short of 360 degrees are quiet. (The rows read are a multiple of the factor: a partial
// block of rows has a warning of its own.)
void TestGlobalDecimation()
{
  aptest::RasterSpec s;
  s.nx = 36;
  s.ny = 18;
  s.crs = "EPSG:4326";
  const double gt[6] = { -180.0, 10.0, 0.0, 90.0, 0.0, -10.0 };
  std::copy(gt, gt + 6, s.gt);
  const std::string path = tmp + "/global.tif";
  AP_CHECK(aptest::WriteRaster(path, s));
  s.nx = 35;
  const std::string shortPath = tmp + "/almost-global.tif";
  AP_CHECK(aptest::WriteRaster(shortPath, s));
  struct Case
  {
    const std::string* file;
    int factor, window;
    const char* warning;
  };
  const Case cases[] = {
    { &path, 5, 0, "global.tif' spans 360 degrees of longitude, but decimation by 5 drops its "
                   "last 1 of 36 columns (a partial block): the grid read does not, so its east "
                   "and west edges do not join; a factor dividing 36 keeps them joined (4 or 6)" },
    { &path, 7, 36, "decimation by 7 drops its last 1 of 36 columns" },
    { &path, 4, 0, nullptr }, { &path, 5, 20, nullptr }, { &shortPath, 5, 0, nullptr },
    // (its rows too: one warning of them, naming the factors that keep the rows and columns)
    { &path, -5, 0, "global.tif': decimation by 5 leaves out its last 3 rows (south), partial "
                    "5 x 5 blocks; a factor dividing 36 and 18 keeps every cell (3 or 6)" } };
  for (const Case& c : cases)
  {
    Read r(*c.file);
    const int f = std::abs(c.factor); // (negative: all 18 rows)
    r.Reader->SetDecimation(f);
    r.Reader->SetSubWindow(0, 0, c.window, c.factor < 0 ? 0 : 18 / f * f); // (0: to the edge)
    r.Update();
    AP_CHECK(r.Ok == 1);
    AP_CHECK(!!r.Warnings->GetWarning() == (c.warning != nullptr));
    if (c.warning)
    {
      AP_CHECK_CONTAINS(r.Warnings->GetWarningMessage(), c.warning);
    }
  }
}

// A multi-band raster reads band 1 and says so; BandIndex picks another quietly.
void TestBands()
{
  aptest::RasterSpec s;
  s.bands = 3;
  s.raw = [](int b, int c, int r) { return 1000.0 * b + 10.0 * r + c; };
  const std::string path = tmp + "/bands.tif";
  AP_CHECK(aptest::WriteRaster(path, s));
  Read first(path);
  first.Update();
  AP_CHECK(first.Ok == 1 && first.Warnings->GetWarning());
  AP_CHECK_CONTAINS(first.Warnings->GetWarningMessage(), "has 3 bands; reading band 1");
  AP_CHECK_NEAR(first.Z(0, 2), 1000.0, 0.0);
  Read second(path);
  second.Reader->SetBandIndex(2);
  second.Update();
  AP_CHECK(second.Ok == 1 && !second.Warnings->GetWarning());
  AP_CHECK_NEAR(second.Z(0, 2), 2000.0, 0.0);
  AP_CHECK(second.Reader->GetBandRead() == 2 && second.Reader->GetNumberOfBands() == 3);
  Read missing(path);
  missing.Reader->SetBandIndex(4);
  missing.Update();
  AP_CHECK(missing.Ok == 0);
  AP_CHECK_CONTAINS(missing.Errors->GetErrorMessage(), "has 3 bands; band 4 does not exist");

  // A picture's channel, or a band of colour indices, is read as heights all the same, with a
  // warning (until 2026-12-06 a palette band was read without a word).
  aptest::RasterSpec rgb;
  rgb.bands = 3;
  rgb.type = GDT_Byte;
  rgb.options = { "PHOTOMETRIC=RGB" };
  AP_CHECK(aptest::WriteRaster(tmp + "/rgb.tif", rgb));
  Read picture(tmp + "/rgb.tif");
  picture.Reader->SetBandIndex(2);
  picture.Update();
  AP_CHECK(picture.Ok == 1);
  AP_CHECK_CONTAINS(picture.Warnings->GetWarningMessage(),
    "band 2 is the Green channel of a picture, not elevations; read as heights all the same");
  aptest::RasterSpec classes;
  classes.type = GDT_Byte;
  AP_CHECK(aptest::WriteRaster(tmp + "/classes.tif", classes));
  {
    GDALDatasetH ds = GDALOpen((tmp + "/classes.tif").c_str(), GA_Update);
    GDALColorTableH table = GDALCreateColorTable(GPI_RGB);
    const GDALColorEntry red = { 255, 0, 0, 255 };
    GDALSetColorEntry(table, 0, &red);
    AP_CHECK(ds && GDALSetRasterColorTable(GDALGetRasterBand(ds, 1), table) == CE_None);
    GDALDestroyColorTable(table);
    GDALClose(ds);
  }
  Read palette(tmp + "/classes.tif");
  palette.Update();
  AP_CHECK(palette.Ok == 1);
  AP_CHECK_CONTAINS(palette.Warnings->GetWarningMessage(),
    "band 1 has a colour table: its values are colour or class indices, not elevations");
  AP_CHECK_NEAR(palette.Z(0, 2), 0.0, 0.0); // (raw 10 r + c: the file's first row, column 0)
  // an elevation band (grey, or no interpretation) is read quietly, as before
  Read plain(path);
  plain.Reader->SetBandIndex(3);
  plain.Update();
  AP_CHECK(plain.Ok == 1 && !plain.Warnings->GetWarning());

  // An alpha band: GDAL's mask with UInt16 samples (its 0 cells nodata, read quietly: no band
  // to choose); with Float32 ones, as gdalwarp -dstalpha makes for a Float32 DEM, no mask to
  // GDAL, so its transparent cells are heights: said (only "2 bands" until 2026-12-07). Not
  // GDAL's mask either: a Byte alpha as band 2 of 3 (GDAL looks at the last of 2 or 4); and no
  // warning where a nodata value masks the band (it wins over the alpha): a Byte alpha (its 0
  // cells not nodata then, as GDAL reads them) and gdalwarp -dstalpha's Float32 one. Band 1 is
  // 100 + column, 100 the nodata value where there is one; the alpha makes column 1 transparent.
  struct AlphaCase
  {
    int Bands;
    GDALDataType Type;
    bool NoData, AlphaMasks;
    const char* Warning;
  };
  for (const AlphaCase& c : { AlphaCase{ 2, GDT_UInt16, false, true, nullptr },
         AlphaCase{ 2, GDT_Float32, false, false,
           "' band 2 is an alpha band, which GDAL takes as a mask only with Byte or UInt16 "
           "samples, not Float32: the cells it makes transparent are read as heights; give the "
           "DEM a nodata value instead (gdalwarp -dstnodata nan)" },
         AlphaCase{ 3, GDT_Byte, false, false,
           "has 3 bands; reading band 1 as elevation (set BandIndex to choose); its band 2 is an "
           "alpha band, which GDAL takes as a mask only as the last of 2 bands, or of 4 for the "
           "first 3: the cells it makes transparent are read as heights" },
         AlphaCase{ 2, GDT_Byte, true, false, nullptr },
         AlphaCase{ 2, GDT_Float32, true, false, nullptr } })
  {
    aptest::RasterSpec alpha;
    alpha.bands = c.Bands;
    alpha.type = c.Type;
    alpha.hasNoData = c.NoData;
    alpha.noData = 100.0;
    alpha.options = { "ALPHA=YES", "PHOTOMETRIC=MINISBLACK" }; // (3 Byte bands: not RGB)
    alpha.raw = [](int b, int col, int) { return b == 1 ? 100.0 + col : (col == 1 ? 0 : 255); };
    const std::string file = tmp + "/alpha-" + std::to_string(c.Bands) +
      GDALGetDataTypeName(c.Type) + (c.NoData ? "-nodata" : "") + ".tif";
    AP_CHECK(aptest::WriteRaster(file, alpha));
    Read r(file);
    r.Update();
    AP_CHECK(r.Ok == 1);
    AP_CHECK(std::isnan(r.Z(0, 1)) == c.NoData);
    if (c.AlphaMasks)
    {
      AP_CHECK(std::isnan(r.Z(1, 1)));
    }
    else
    {
      AP_CHECK_NEAR(r.Z(1, 1), 101.0, 0.0); // (transparent, read all the same)
    }
    AP_CHECK(!!r.Warnings->GetWarning() == (c.Warning != nullptr));
    if (c.Warning)
    {
      AP_CHECK_CONTAINS(r.Warnings->GetWarningMessage(), c.Warning);
      AP_CHECK(c.Bands > 2 || r.Warnings->GetWarningMessage().find("2 bands") == std::string::npos);
    }
  }
  // beside other bands, both said in one warning (GTiff's ALPHA=YES makes the first extra
  // band the alpha)
  aptest::RasterSpec four;
  four.bands = 4;
  four.options = { "ALPHA=YES" };
  AP_CHECK(aptest::WriteRaster(tmp + "/four.tif", four));
  Read fourBands(tmp + "/four.tif");
  fourBands.Update();
  AP_CHECK(fourBands.Ok == 1);
  AP_CHECK_CONTAINS(fourBands.Warnings->GetWarningMessage(),
    "has 4 bands; reading band 1 as elevation (set BandIndex to choose); its band 2 is an alpha "
    "band, which GDAL takes as a mask only as the last of 2 bands, or of 4 for the first 3, with "
    "Byte or UInt16 samples, not Float32: the cells"); // (both reasons: either alone misleads)
}

// Each bad input gives a clear error and a failed update.
void ExpectError(const std::string& path, const std::string& expected,
  const std::function<void(vtkApertureDEMReader*)>& setup = nullptr)
{
  Read rd(path);
  if (setup)
  {
    setup(rd.Reader);
  }
  vtkImageData* img = rd.Update();
  AP_CHECK(rd.Ok == 0);
  AP_CHECK(rd.Errors->GetError());
  AP_CHECK_CONTAINS(rd.Errors->GetErrorMessage(), expected);
  AP_CHECK(img->GetNumberOfPoints() == 0);
}

// GetWindowExtent against a brute force: the cells of the grid read whose ground overlaps the
// ground of the window's file pixels (from the geotransform), for every window of an 11 x 8
// raster (north-up and south-up) read whole, decimated by 2 and 3 (partial blocks dropped),
// at an overview of 6 x 4 (11/6 file pixels a level pixel), and through a SubWindow.
void TestWindowExtent()
{
  for (bool southUp : { false, true })
  {
    aptest::RasterSpec s;
    s.nx = 11;
    s.ny = 8;
    if (southUp)
    {
      s.gt[3] = 4000000.0 - 8 * 30.0; // south edge
      s.gt[5] = 30.0;
    }
    const std::string path = tmp + (southUp ? "/extent-south.tif" : "/extent.tif");
    AP_CHECK(aptest::WriteRaster(path, s));
    GDALDatasetH ds = GDALOpen(path.c_str(), GA_Update);
    int levels[1] = { 2 };
    AP_CHECK(ds && GDALBuildOverviews(ds, "AVERAGE", 1, levels, 0, nullptr, nullptr, nullptr) ==
        CE_None);
    GDALClose(ds);
    struct Setup
    {
      int level, factor, sub[4];
      bool misses; // some windows cover no cell: dropped partial blocks, or the SubWindow
    };
    const Setup setups[] = { { -1, 1, { 0, 0, 0, 0 }, false }, { -1, 2, { 0, 0, 0, 0 }, true },
      { -1, 3, { 0, 0, 0, 0 }, true }, { 0, 1, { 0, 0, 0, 0 }, false },
      { 0, 2, { 0, 0, 0, 0 }, false }, { -1, 1, { 2, 1, 6, 5 }, true },
      { -1, 2, { 1, 2, 0, 0 }, true } };
    for (const Setup& u : setups)
    {
      Read rd(path);
      rd.Reader->SetOverviewLevel(u.level);
      rd.Reader->SetDecimation(u.factor);
      rd.Reader->SetSubWindow(const_cast<int*>(u.sub));
      vtkImageData* img = rd.Update();
      AP_CHECK(rd.Ok == 1);
      int dims[3];
      double origin[3], spacing[3];
      img->GetDimensions(dims);
      img->GetOrigin(origin);
      img->GetSpacing(spacing);
      int checked = 0, empty = 0, compared = 0;
      for (int x0 = 0; x0 < s.nx; ++x0)
      {
        for (int w = 0; x0 + w <= s.nx; ++w)
        {
          for (int y0 = 0; y0 < s.ny; ++y0)
          {
            for (int h = 0; y0 + h <= s.ny; ++h)
            {
              // the window's ground, and the grid's cells overlapping it
              const double wx0 = s.gt[0] + x0 * s.gt[1];
              const double wx1 = s.gt[0] + (w ? x0 + w : s.nx) * s.gt[1];
              const double ya = s.gt[3] + y0 * s.gt[5];
              const double yb = s.gt[3] + (h ? y0 + h : s.ny) * s.gt[5];
              const double wy0 = std::min(ya, yb), wy1 = std::max(ya, yb);
              int want[6] = { dims[0], -1, dims[1], -1, 0, 0 };
              for (int j = 0; j < dims[1]; ++j)
              {
                for (int i = 0; i < dims[0]; ++i)
                {
                  const double cx = origin[0] + i * spacing[0], cy = origin[1] + j * spacing[1];
                  const double ox = std::min(wx1, cx + 0.5 * spacing[0]) -
                    std::max(wx0, cx - 0.5 * spacing[0]);
                  const double oy = std::min(wy1, cy + 0.5 * spacing[1]) -
                    std::max(wy0, cy - 0.5 * spacing[1]);
                  if (ox > 1e-6 * spacing[0] && oy > 1e-6 * spacing[1])
                  {
                    want[0] = std::min(want[0], i);
                    want[1] = std::max(want[1], i);
                    want[2] = std::min(want[2], j);
                    want[3] = std::max(want[3], j);
                  }
                }
              }
              int got[6] = { -7, -7, -7, -7, -7, -7 };
              rd.Errors->Clear();
              const bool ok = rd.Reader->GetWindowExtent(x0, y0, w, h, got);
              if (want[1] < 0)
              {
                ++empty;
                AP_CHECK(!ok);
                AP_CHECK_CONTAINS(rd.Errors->GetErrorMessage(), "covers no cell of the");
              }
              else
              {
                ++checked;
                AP_CHECK(ok && !rd.Errors->GetError());
                AP_CHECK(std::equal(want, want + 6, got));
              }
              // A SubWindow of the same window reads those cells of the same grid (a sample
              // of the windows of the setups without a SubWindow of their own).
              if (u.sub[2] || u.sub[1] || u.sub[0] || (x0 + 3 * y0 + 5 * w + 7 * h) % 29 != 0)
              {
                continue;
              }
              Read part(path);
              part.Reader->SetOverviewLevel(u.level);
              part.Reader->SetDecimation(u.factor);
              part.Reader->SetSubWindow(x0, y0, w, h);
              vtkImageData* window = part.Update();
              if (want[1] - want[0] < 1 || want[3] - want[2] < 1)
              {
                AP_CHECK(part.Ok == 0); // fewer than 2 x 2 cells
                continue;
              }
              ++compared;
              int pdims[3];
              double porigin[3];
              window->GetDimensions(pdims);
              window->GetOrigin(porigin);
              AP_CHECK(part.Ok == 1 && pdims[0] == want[1] - want[0] + 1 &&
                pdims[1] == want[3] - want[2] + 1);
              AP_CHECK_NEAR(porigin[0], origin[0] + want[0] * spacing[0], 1e-6);
              AP_CHECK_NEAR(porigin[1], origin[1] + want[2] * spacing[1], 1e-6);
              for (int j = 0; part.Ok && j < pdims[1]; ++j)
              {
                for (int i = 0; i < pdims[0]; ++i)
                {
                  AP_CHECK_NEAR(part.Z(i, j), rd.Z(want[0] + i, want[2] + j), 0.0);
                }
              }
            }
          }
        }
      }
      AP_CHECK(checked > 1000);
      AP_CHECK(compared > 10 || u.sub[0] || u.sub[1] || u.sub[2]);
      AP_CHECK((empty > 0) == u.misses);
    }
  }
  // a window outside the raster, and a reader without raster information
  Read rd(tmp + "/extent.tif");
  rd.Update();
  int ext[6];
  AP_CHECK(!rd.Reader->GetWindowExtent(10, 0, 2, 0, ext));
  AP_CHECK_CONTAINS(
    rd.Errors->GetErrorMessage(), "the window (10, 0, 2, 0) is not inside the 11 x 8 raster");
  Read none(tmp + "/no-such-file.tif");
  none.Update();
  AP_CHECK(!none.Reader->GetWindowExtent(0, 0, 0, 0, ext));
  AP_CHECK_CONTAINS(none.Errors->GetErrorMessage(), "no valid raster information");
}

void TestBadInput()
{
  ExpectError(tmp + "/no-such-file.tif", "does not exist");
  // a URL, and a network path that leads nowhere, are said so (both were "file ... does not
  // exist" until 2026-12-06; nothing listens on port 1 of this machine)
  ExpectError("https://example.com/dem.tif", "'https://example.com/dem.tif' is a URL, not a "
    "file: GDAL reads one through /vsicurl/ ('/vsicurl/https://example.com/dem.tif')");
  ExpectError("/vsicurl/http://127.0.0.1:1/dem.tif", "nothing can be read at "
    "'/vsicurl/http://127.0.0.1:1/dem.tif' (no such file there, or the server cannot be "
    "reached from this machine");
  AP_CHECK(aptest::WriteText(tmp + "/notes.tif", "this is not a raster\n"));
  ExpectError(tmp + "/notes.tif", "GDAL cannot open");
  // GDAL's own paths are said to be missing once GDAL has tried them; a folder is named
  ExpectError("/vsimem/no-such-file.tif", "file '/vsimem/no-such-file.tif' does not exist");
  ExpectError("/vsizip/" + tmp + "/no-such.zip/dem.tif", "does not exist");
  ExpectError(tmp, "GDAL cannot open '" + tmp + "' as a raster: ");
  ExpectError(tmp, " (it is a folder, and not one GDAL reads as a raster, such as an ArcInfo "
                   "grid's)");
  // a named pipe: GDAL's open waited for a writer, for ever (and one writer is not enough: GDAL
  // opens a file more than once); refused by name
  const std::string pipe = tmp + "/pipe.tif";
  unlink(pipe.c_str());
  AP_CHECK(mkfifo(pipe.c_str(), 0644) == 0);
  ExpectError(pipe, "'" + pipe + "' is a pipe, not a file: GDAL reads a DEM by seeking in it");
  unlink(pipe.c_str());

  aptest::RasterSpec tiny;
  tiny.nx = 1;
  tiny.ny = 1;
  AP_CHECK(aptest::WriteRaster(tmp + "/tiny.tif", tiny));
  ExpectError(tmp + "/tiny.tif", "/tiny.tif' is a 1 x 1 raster; at least 2 x 2 cells are needed");
  // A grid too small names the steps that made it so, only those taken (4 x 3 cells, an
  // overview of 2 x 2)
  const std::string narrow = tmp + "/narrow.tif";
  AP_CHECK(aptest::WriteRaster(narrow, aptest::RasterSpec()));
  {
    GDALDatasetH ds = GDALOpen(narrow.c_str(), GA_Update);
    int levels[1] = { 2 };
    AP_CHECK(ds && GDALBuildOverviews(ds, "NEAREST", 1, levels, 0, nullptr, nullptr, nullptr) ==
        CE_None);
    GDALClose(ds);
  }
  ExpectError(narrow, "' gives a 1 x 3 grid (after subwindow); at least 2 x 2",
    [](vtkApertureDEMReader* r) { r->SetSubWindow(2, 0, 1, 0); });
  ExpectError(narrow, "' gives a 2 x 1 grid (after decimation); at least 2 x 2",
    [](vtkApertureDEMReader* r) { r->SetDecimation(2); });
  ExpectError(narrow, "' gives a 1 x 1 grid (after overview and decimation); at least 2 x 2",
    [](vtkApertureDEMReader* r) {
      r->SetOverviewLevel(0);
      r->SetDecimation(2);
    });
  ExpectError(narrow, "' gives a 1 x 1 grid (after subwindow, overview and decimation); at",
    [](vtkApertureDEMReader* r) {
      r->SetSubWindow(0, 0, 4, 2);
      r->SetOverviewLevel(0);
      r->SetDecimation(2);
    });

  aptest::RasterSpec rotated;
  rotated.gt[2] = 0.5;
  AP_CHECK(aptest::WriteRaster(tmp + "/rotated.tif", rotated));
  ExpectError(tmp + "/rotated.tif", "rotated geotransform");
  // Rotation terms moving the far edges by over a thousandth of a cell (30 m cells, 3 rows:
  // 0.02 m a row is 0.06 m) are a rotation; a writer's rounding error (1e-9) is none.
  for (const double rotation : { 0.02, 1e-9 })
  {
    for (const int term : { 2, 4 })
    {
      aptest::RasterSpec nearly;
      nearly.gt[term] = rotation;
      std::remove((tmp + "/nearly.tif").c_str());
      AP_CHECK(aptest::WriteRaster(tmp + "/nearly.tif", nearly));
      if (rotation > 1e-3)
      {
        ExpectError(tmp + "/nearly.tif", "rotated geotransform");
        continue;
      }
      Read rd(tmp + "/nearly.tif");
      vtkImageData* img = rd.Update();
      AP_CHECK(rd.Ok == 1 && !rd.Errors->GetError());
      double origin[3], spacing[3];
      img->GetOrigin(origin);
      img->GetSpacing(spacing);
      AP_CHECK_NEAR(origin[0], 500015.0, 0.0);
      AP_CHECK_NEAR(origin[1], 4000000.0 - 75.0, 0.0);
      AP_CHECK_NEAR(spacing[0], 30.0, 0.0);
      AP_CHECK_NEAR(spacing[1], 30.0, 0.0);
    }
  }

  aptest::RasterSpec bare;
  bare.hasGeoTransform = false;
  bare.crs = "";
  AP_CHECK(aptest::WriteRaster(tmp + "/bare.tif", bare));
  ExpectError(tmp + "/bare.tif", "has no georeference");

  aptest::RasterSpec gcps;
  gcps.hasGeoTransform = false;
  gcps.crs = "EPSG:4326";
  gcps.gcps = 4;
  AP_CHECK(aptest::WriteRaster(tmp + "/gcps.tif", gcps));
  ExpectError(tmp + "/gcps.tif", "only by 4 ground control points; warp it");
  // A GeoTIFF tie point without a pixel size (GDAL's GTiff writes a geotransform whose pixel
  // size is 0 so) reads as one ground control point, which no warp can use.
  gcps.gcps = 1;
  AP_CHECK(aptest::WriteRaster(tmp + "/gcp.tif", gcps));
  ExpectError(tmp + "/gcp.tif", "only by 1 ground control point, too few to place a grid; set "
                                "its corners first (gdal_edit.py -a_ullr)");

  aptest::RasterSpec nocrs;
  nocrs.crs = "";
  AP_CHECK(aptest::WriteRaster(tmp + "/nocrs.tif", nocrs));
  ExpectError(tmp + "/nocrs.tif", "has no coordinate reference system");
  {
    // ... which OverrideCRS fixes.
    Read fixed(tmp + "/nocrs.tif");
    fixed.Reader->SetOverrideCRS("EPSG:32611");
    fixed.Update();
    AP_CHECK(fixed.Ok == 1);
  }
  ExpectError(tmp + "/nocrs.tif", "GDAL cannot parse the CRS",
    [](vtkApertureDEMReader* r) { r->SetOverrideCRS("EPSG:999999999"); });
  {
    // A GeoTIFF cut short where its GeoKeyDirectory's values begin (the first IFD, little
    // endian, read here by hand): GDAL opens it but cannot read the keys, and says so in a
    // warning that the message carries instead of printing it on its own.
    aptest::RasterSpec whole;
    std::remove((tmp + "/damaged.tif").c_str()); // (GDAL's Create would open the last one)
    AP_CHECK(aptest::WriteRaster(tmp + "/damaged.tif", whole));
    std::string bytes;
    if (FILE* f = std::fopen((tmp + "/damaged.tif").c_str(), "rb"))
    {
      char buf[4096];
      size_t got;
      while ((got = std::fread(buf, 1, sizeof buf, f)) > 0)
      {
        bytes.append(buf, got);
      }
      std::fclose(f);
    }
    auto u16 = [&](size_t at) { return static_cast<unsigned>(static_cast<unsigned char>(bytes[at]) |
                                  static_cast<unsigned char>(bytes[at + 1]) << 8); };
    auto u32 = [&](size_t at) { return u16(at) | u16(at + 2) << 16; };
    size_t cut = 0;
    if (bytes.size() > 8 && bytes.compare(0, 2, "II") == 0)
    {
      const size_t ifd = u32(4);
      for (unsigned e = 0; ifd + 2 + 12 * (e + 1) <= bytes.size() && e < u16(ifd); ++e)
      {
        const size_t entry = ifd + 2 + 12 * e;
        if (u16(entry) == 34735 && u32(entry + 4) > 2) // GeoKeyDirectoryTag, SHORT values
        {
          cut = u32(entry + 8);
        }
      }
    }
    AP_CHECK(cut > 8 && cut < bytes.size());
    AP_CHECK(aptest::WriteText(tmp + "/damaged.tif", bytes.substr(0, cut)));
    ExpectError(tmp + "/damaged.tif", "has no coordinate reference system (GDAL: ");
    ExpectError(tmp + "/damaged.tif", "TIFFFetchNormalTag:IO error during reading of \"Geo");
    ExpectError(tmp + "/damaged.tif", "tag ignored; is the file damaged?); set OverrideCRS");
  }

  aptest::RasterSpec empty;
  empty.hasNoData = true;
  empty.noData = -1.0;
  empty.raw = [](int, int, int) { return -1.0; };
  AP_CHECK(aptest::WriteRaster(tmp + "/allnodata.tif", empty));
  ExpectError(tmp + "/allnodata.tif", "is nodata");
  {
    // a window of nodata in a raster with data: the window's message (until 2026-12-06 the
    // whole file's, "every cell of 'coast.tif' band 1 is nodata")
    aptest::RasterSpec coast;
    coast.nx = 8;
    coast.hasNoData = true;
    coast.noData = -1.0;
    coast.raw = [](int, int c, int) { return c < 4 ? -1.0 : 25.0; };
    AP_CHECK(aptest::WriteRaster(tmp + "/coast.tif", coast));
    ExpectError(tmp + "/coast.tif",
      "every cell of the window (0, 0, 3, 3) of '" + tmp + "/coast.tif' band 1 is nodata",
      [](vtkApertureDEMReader* r) { r->SetSubWindow(0, 0, 3, 3); });
  }
  {
    // A piece of an all-nodata raster is not an error by itself (streaming).
    Read piece(tmp + "/allnodata.tif");
    piece.Reader->UpdateInformation();
    int ext[6] = { 0, 1, 0, 1, 0, 0 };
    piece.Reader->UpdateExtent(ext);
    AP_CHECK(!piece.Errors->GetError());
  }

  // A VRT declaring 10^6 x 10^6 cells: refused before anything is allocated.
  AP_CHECK(aptest::WriteRaster(tmp + "/small.tif", aptest::RasterSpec()));
  // (a VRT of nx x ny cells over small.tif)
  auto smallVrt = [](const char* nx, const char* ny) {
    return std::string("<VRTDataset rasterXSize=\"") + nx + "\" rasterYSize=\"" + ny +
      "\">\n"
      "  <SRS>EPSG:32611</SRS>\n"
      "  <GeoTransform>500000, 1, 0, 4000000, 0, -1</GeoTransform>\n"
      "  <VRTRasterBand dataType=\"Float32\" band=\"1\">\n"
      "    <SimpleSource><SourceFilename relativeToVRT=\"1\">small.tif</SourceFilename>\n"
      "      <SourceBand>1</SourceBand></SimpleSource>\n"
      "  </VRTRasterBand>\n"
      "</VRTDataset>\n";
  };
  AP_CHECK(aptest::WriteText(tmp + "/huge.vrt", smallVrt("1000000", "1000000")));
  ExpectError(tmp + "/huge.vrt", "1000000 x 1000000 cells");
  ExpectError(tmp + "/huge.vrt", "3.638 TiB");
  ExpectError(tmp + "/small.tif", "more than the 16 bytes MemoryLimit",
    [](vtkApertureDEMReader* r) { r->SetMemoryLimit(16); });
  {
    // GDAL decompresses a block whole: a window of a compressed raster stored as one strip
    // (2000 x 1000 Int16 cells, 3.8 MiB) counts it (it held the whole strip past MemoryLimit
    // until 2026-12-07); stored in 256 x 256 tiles it is read under the same limit
    aptest::RasterSpec spec;
    spec.nx = 2000;
    spec.ny = 1000;
    spec.type = GDT_Int16;
    spec.options = { "COMPRESS=DEFLATE", "BLOCKYSIZE=1000" };
    AP_CHECK(aptest::WriteRaster(tmp + "/one-strip.tif", spec));
    // (a 10 x 10 window under a memory limit)
    const auto windowUnder = [](vtkTypeInt64 limit) {
      return [limit](vtkApertureDEMReader* r) {
        r->SetSubWindow(0, 0, 10, 10);
        r->SetMemoryLimit(limit);
      };
    };
    const auto window = windowUnder(3 << 20);
    ExpectError(tmp + "/one-strip.tif",
      "reading 10 x 10 cells of '" + tmp + "/one-strip.tif' needs 400 bytes as float32 and "
        "3.815 MiB for one of its blocks of 2000 x 1000 cells, which GDAL reads whole, more "
        "than the 3.000 MiB MemoryLimit; allow at least 3.816 MiB, or write it in tiles first",
      window);
    spec.options = { "COMPRESS=DEFLATE", "TILED=YES" };
    AP_CHECK(aptest::WriteRaster(tmp + "/tiled.tif", spec));
    Read rd(tmp + "/tiled.tif");
    window(rd.Reader);
    AP_CHECK(rd.Update()->GetNumberOfPoints() == 100 && rd.Ok == 1);
    AP_CHECK(rd.Reader->GetBlockBytes() == 256.0 * 256.0 * 2.0); // (what a caller leaves room for)
    // a tiled file whose tile does not fit is not told to be written in tiles (it was, until
    // 2026-12-07): the limit that reads it (400 + 131072 bytes), or smaller tiles
    ExpectError(tmp + "/tiled.tif",
      "reading 10 x 10 cells of '" + tmp + "/tiled.tif' needs 400 bytes as float32 and "
        "128.000 KiB for one of its blocks of 256 x 256 cells, which GDAL reads whole, more "
        "than the 100.000 KiB MemoryLimit; allow at least 128.391 KiB, or write it in smaller "
        "tiles first (gdal_translate -co TILED=YES -co BLOCKXSIZE=128 -co BLOCKYSIZE=128 -co "
        "COMPRESS=DEFLATE)",
      windowUnder(100 << 10));
    // tiles wider than the raster are tiles too (told to be written in tiles until review), and
    // the limit named is rounded up: 1 MiB + 400 bytes is 1.001 MiB (1.000 until review, which
    // refused again)
    spec.nx = 200;
    spec.options = { "COMPRESS=DEFLATE", "TILED=YES", "BLOCKXSIZE=512", "BLOCKYSIZE=1024" };
    AP_CHECK(aptest::WriteRaster(tmp + "/wide-tiles.tif", spec));
    ExpectError(tmp + "/wide-tiles.tif",
      "needs 400 bytes as float32 and 1.000 MiB for one of its blocks of 512 x 1024 cells, which "
      "GDAL reads whole, more than the 1.000 MiB MemoryLimit; allow at least 1.001 MiB, or write "
      "it in smaller tiles first",
      windowUnder(1 << 20));
    rd.Reader->SetFileName((tmp + "/one-strip.tif").c_str());
    rd.Reader->UpdateInformation();
    AP_CHECK(rd.Reader->GetBlockBytes() == 2000.0 * 1000.0 * 2.0);
  }
  ExpectError(tmp + "/small.tif", "is not inside the 4 x 3 raster",
    [](vtkApertureDEMReader* r) { r->SetSubWindow(3, 0, 2, 1); });
  ExpectError("", "no file name was set");
  {
    // The files GDAL reads: a VRT, then its source (which a caller must not write over).
    AP_CHECK(aptest::WriteText(tmp + "/small.vrt", smallVrt("4", "3")));
    Read vrt(tmp + "/small.vrt");
    AP_CHECK(vrt.Reader->GetNumberOfFiles() == 0 && !vrt.Reader->GetFile(0)); // (not yet)
    vrt.Reader->UpdateInformation();
    AP_CHECK(vrt.Reader->GetNumberOfFiles() == 2);
    AP_CHECK(vrt.Reader->GetFile(0) && vrt.Reader->GetFile(0) == tmp + "/small.vrt");
    AP_CHECK(vrt.Reader->GetFile(1) && vrt.Reader->GetFile(1) == tmp + "/small.tif");
    AP_CHECK(!vrt.Reader->GetFile(2) && !vrt.Reader->GetFile(-1));
  }
  {
    // a file that cannot be opened leaves no facts of the one read before
    Read rd(tmp + "/small.tif");
    AP_CHECK(rd.Update() && rd.Ok == 1 && std::string(rd.Reader->GetDriverName()) == "GTiff");
    AP_CHECK(rd.Reader->GetRasterSize()[0] == 4 && rd.Reader->GetNumberOfBands() == 1);
    AP_CHECK(rd.Reader->GetNumberOfFiles() == 1 && rd.Reader->GetFile(0) == tmp + "/small.tif");
    rd.Reader->SetFileName((tmp + "/nothing-here.tif").c_str());
    rd.Update();
    AP_CHECK(rd.Ok == 0 && std::string(rd.Reader->GetDriverName()).empty());
    AP_CHECK(rd.Reader->GetRasterSize()[0] == 0 && rd.Reader->GetNumberOfBands() == 0);
    AP_CHECK(rd.Reader->GetBandRead() == 0 && !rd.Reader->GetHasNoDataValue());
    AP_CHECK(rd.Reader->GetNumberOfFiles() == 0 && !rd.Reader->GetFile(0));
    AP_CHECK(rd.Reader->GetOutput()->GetNumberOfPoints() == 0); // (the last file's stayed)
  }
  {
    // nor does a file that fails once read (every cell nodata): until 2026-12-07 the last
    // file's elevations stayed in the output of no points (vtkImageData keeps its scalars)
    Read rd(tmp + "/small.tif");
    AP_CHECK(rd.Update()->GetPointData()->GetNumberOfArrays() == 1 && rd.Ok == 1);
    rd.Reader->SetFileName((tmp + "/allnodata.tif").c_str());
    vtkImageData* out = rd.Update();
    AP_CHECK_CONTAINS(rd.Errors->GetErrorMessage(), "is nodata");
    AP_CHECK(rd.Ok == 0 && out->GetNumberOfPoints() == 0);
    AP_CHECK(out->GetPointData()->GetNumberOfArrays() == 0);
  }
}
// How samples become elevations where the file's declarations are not what they seem: GDAL
// 3.6's Int8 (a Byte band flagged PIXELTYPE=SIGNEDBYTE), a float band's nodata value that is
// no float (a VRT's or an ENVI header's), and scales and offsets that make no elevations.
void TestSampleEncodings()
{
  // Int8: bytes 206..254 and 255 hold -50..-2 and the nodata -1, below sea level.
  aptest::RasterSpec int8;
  int8.type = GDT_Byte;
  int8.options = { "PIXELTYPE=SIGNEDBYTE" };
  int8.hasNoData = true;
  int8.noData = -1.0;
  int8.raw = [](int, int c, int r) { return (c == 3 && r == 0) ? 255.0 : 206.0 + 2 * (c + r); };
  AP_CHECK(aptest::WriteRaster(tmp + "/int8.tif", int8));
  {
    Read rd(tmp + "/int8.tif");
    rd.Update();
    AP_CHECK(rd.Ok == 1);
    for (int fileRow = 0; fileRow < 3; ++fileRow)
    {
      for (int c = 0; c < 4; ++c)
      {
        const double z = rd.Z(c, 2 - fileRow);
        if (c == 3 && fileRow == 0)
        {
          AP_CHECK(std::isnan(z));
        }
        else
        {
          AP_CHECK_NEAR(z, -50.0 + 2 * (c + fileRow), 0.0);
        }
      }
    }
  }

  // A Float32 band whose VRT declares the nodata -9999.9, which no float is: its samples are
  // -9999.900390625, and GDAL's own mask takes them as nodata.
  aptest::RasterSpec plain;
  plain.raw = [](int, int c, int r) { return (c < 2 && r == 1) ? -9999.9 : 100.0 + c; };
  AP_CHECK(aptest::WriteRaster(tmp + "/plain.tif", plain));
  AP_CHECK(aptest::WriteText(tmp + "/nodata.vrt",
    "<VRTDataset rasterXSize=\"4\" rasterYSize=\"3\"><SRS>EPSG:32611</SRS>\n"
    "<GeoTransform>500000, 30, 0, 4000000, 0, -30</GeoTransform>\n"
    "<VRTRasterBand dataType=\"Float32\" band=\"1\"><NoDataValue>-9999.9</NoDataValue>\n"
    "<SimpleSource><SourceFilename relativeToVRT=\"1\">plain.tif</SourceFilename>\n"
    "<SourceBand>1</SourceBand></SimpleSource></VRTRasterBand></VRTDataset>\n"));
  {
    Read rd(tmp + "/nodata.vrt");
    rd.Update();
    AP_CHECK(rd.Ok == 1);
    AP_CHECK(std::isnan(rd.Z(0, 1)) && std::isnan(rd.Z(1, 1)));
    AP_CHECK_NEAR(rd.Z(2, 1), 102.0, 0.0);
    AP_CHECK(rd.Reader->GetNoDataValue() == -9999.9); // (as the file says)
  }

  // Scales and offsets that give no elevations: refused, named.
  const struct
  {
    double scale, offset;
    const char* expected;
  } bad[] = {
    { NAN, 0.0, "band 1 has a scale of nan and an offset of 0: elevations (samples x scale + "
                "offset) would be no numbers" },
    { 1.0, INFINITY, "has a scale of 1 and an offset of inf" },
    { 0.0, 5.0, "has a scale of 0 and an offset of 5: elevations (samples x scale + offset) "
                "would be the offset everywhere; correct them (gdal_edit.py -scale, -offset)" },
    { 1e37, 0.0, "band 1: its scale of 1e+37 and offset of 0 take samples beyond the range of "
                 "float32 elevations" },
  };
  for (const auto& b : bad)
  {
    aptest::RasterSpec scaled;
    scaled.scale = b.scale;
    scaled.offset = b.offset;
    scaled.raw = [](int, int c, int r) { return 100.0 + c + r; };
    std::remove((tmp + "/scaled.tif").c_str());
    AP_CHECK(aptest::WriteRaster(tmp + "/scaled.tif", scaled));
    ExpectError(tmp + "/scaled.tif", b.expected);
  }

  // A geotransform of finite numbers whose grid reaches beyond them (4 x 1e308 m).
  aptest::RasterSpec vast;
  vast.gt[1] = 1e308;
  vast.gt[5] = -1e308;
  vast.gt[0] = vast.gt[3] = 0.0;
  AP_CHECK(aptest::WriteRaster(tmp + "/vast.tif", vast));
  ExpectError(tmp + "/vast.tif", "whose grid reaches beyond the range of numbers");
}

// Which float samples are nodata: those GDAL's own mask band says are (GDAL compares floats
// with a relative width of about two float32 ulps). ArcGIS declares -3.4028230607370965e38
// for cells of -FLT_MAX, two ulps apart: they were read as heights of -3.4e38 m until
// 2026-12-06. An integer band compares exactly (the width would span whole integers).
void TestNoDataAsGDALMasks()
{
  const struct
  {
    GDALDataType type;
    double nodata;
    double values[4]; // row 1 of a 4 x 3 raster; the rest are heights
    int masked;       // how many of them GDAL masks (not vacuous)
  } cases[] = {
    { GDT_Float32, -3.4028230607370965e38,
      { -FLT_MAX, -3.4028230607370965e38, 5.0, -FLT_MAX }, 3 },
    { GDT_Float32, -9999.0, { -9999.0009765625, -9999.00390625, -9999.005859375, -9999.0 }, 3 },
    { GDT_Float64, -9999.0, { -9999.001, -9999.004, -9999.006, 7.0 }, 2 },
    { GDT_Float32, 0.0, { 1e-30, -1e-30, 0.0, 3.0 }, 1 },
    { GDT_Float64, 1e30, { 1.0000001e30, 1.000001e30, 2.0, 1e30 }, 2 },
    { GDT_UInt32, 4294967295.0, { 4294967294.0, 4294967295.0, 4294967293.0, 9.0 }, 1 },
  };
  for (const auto& c : cases)
  {
    aptest::RasterSpec spec;
    spec.type = c.type;
    spec.hasNoData = true;
    spec.noData = c.nodata;
    const double* values = c.values;
    spec.raw = [values](int, int col, int r) { return r == 1 ? values[col] : 100.0 + col; };
    const std::string path = tmp + "/nodata-near.tif";
    std::remove(path.c_str());
    AP_CHECK(aptest::WriteRaster(path, spec));
    GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
    AP_CHECK(ds != nullptr);
    if (!ds)
    {
      continue;
    }
    unsigned char mask[4] = { 1, 1, 1, 1 };
    AP_CHECK(GDALRasterIO(GDALGetMaskBand(GDALGetRasterBand(ds, 1)), GF_Read, 0, 1, 4, 1, mask,
               4, 1, GDT_Byte, 0, 0) == CE_None);
    GDALClose(ds);
    Read rd(path);
    rd.Update();
    AP_CHECK(rd.Ok == 1);
    int masked = 0;
    for (int col = 0; col < 4; ++col)
    {
      masked += mask[col] == 0;
      if (std::isnan(rd.Z(col, 1)) != (mask[col] == 0))
      {
        std::fprintf(stderr, "type %d, nodata %.17g, sample %.17g: GDAL's mask %d, read %.17g\n",
          static_cast<int>(c.type), c.nodata, c.values[col], mask[col], rd.Z(col, 1));
        AP_CHECK(false);
      }
    }
    AP_CHECK(masked == c.masked);
  }
}

// A decimated raster 2 million columns wide: its strips of source rows are read in pieces of
// whole blocks (each strip of two rows would have taken 32 MiB of doubles), and the blocks on
// either side of a piece's edge land where they belong. The VRT puts small.tif's 4 x 3 cells at
// column 262142, across the first edge (at 262144: 2 MiB of doubles in two rows).
void TestWideDecimation()
{
  AP_CHECK(aptest::WriteRaster(tmp + "/small.tif", aptest::RasterSpec()));
  AP_CHECK(aptest::WriteText(tmp + "/wide.vrt",
    "<VRTDataset rasterXSize=\"2000000\" rasterYSize=\"4\"><SRS>EPSG:32611</SRS>\n"
    "<GeoTransform>0, 1, 0, 4000000, 0, -1</GeoTransform>\n"
    "<VRTRasterBand dataType=\"Float32\" band=\"1\">\n"
    "<SimpleSource><SourceFilename relativeToVRT=\"1\">small.tif</SourceFilename>\n"
    "<SourceBand>1</SourceBand><SrcRect xOff=\"0\" yOff=\"0\" xSize=\"4\" ySize=\"3\"/>\n"
    "<DstRect xOff=\"262142\" yOff=\"0\" xSize=\"4\" ySize=\"3\"/></SimpleSource>\n"
    "</VRTRasterBand></VRTDataset>\n"));
  Read rd(tmp + "/wide.vrt");
  rd.Reader->SetDecimation(2);
  vtkImageData* img = rd.Update();
  AP_CHECK(rd.Ok == 1);
  int dims[3];
  img->GetDimensions(dims);
  AP_CHECK(dims[0] == 1000000 && dims[1] == 2);
  // small.tif's cells are 10 r + c (file row r); around them the VRT gives 0. Output row 1 is
  // file rows 0-1, row 0 file rows 2-3 (row 3 of the VRT: 0).
  AP_CHECK_NEAR(rd.Z(131070, 1), 0.0, 0.0);
  AP_CHECK_NEAR(rd.Z(131071, 1), (0 + 1 + 10 + 11) / 4.0, 0.0);
  AP_CHECK_NEAR(rd.Z(131072, 1), (2 + 3 + 12 + 13) / 4.0, 0.0);
  AP_CHECK_NEAR(rd.Z(131071, 0), (20 + 21) / 4.0, 0.0);
  AP_CHECK_NEAR(rd.Z(131072, 0), (22 + 23) / 4.0, 0.0);
  AP_CHECK_NEAR(rd.Z(131073, 1), 0.0, 0.0);
  AP_CHECK_NEAR(rd.Z(999999, 0), 0.0, 0.0);
}
} // namespace

int TestApertureDEMReader(int argc, char* argv[])
{
  tmp = aptest::TempDir(argc, argv);
  TestNorthUp();
  TestSouthUp();
  TestNaNSamples();
  TestUnits();
  TestWindowsAndLevels();
  TestGlobalDecimation();
  TestBands();
  TestWindowExtent();
  TestBadInput();
  TestSampleEncodings();
  TestNoDataAsGDALMasks();
  TestWideDecimation();
  return aptest::Result();
}
