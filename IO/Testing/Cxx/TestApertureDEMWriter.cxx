// SPDX-License-Identifier: BSD-3-Clause
// vtkApertureDEMWriter: what GDAL reads back (bands, descriptions, values and orientation,
// geotransform, CRS, nodata, compression, metadata), the round trip through the reader, and
// the documented errors.
#include "ApertureStripSource.h"
#include "ApertureTestRasters.h"

#include "vtkApertureDEMReader.h"
#include "vtkApertureDEMWriter.h"
#include "vtkApertureGeoreference.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkErrorCode.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageAlgorithm.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkObjectFactory.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkTestErrorObserver.h"

#include <cpl_conv.h>
#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace
{
std::string tmp;
void ExpectError(vtkApertureDEMWriter* writer, const std::string& expected, int code = -1);
void ExpectRefused(vtkImageData* image, const std::string& path, const std::string& expected);
const int NX = 6, NY = 4;

// Elevation(i, j) = 100 j + i, NaN at (1, 2); Vector (3 components E, N, U); Count (int).
vtkSmartPointer<vtkImageData> MakeImage(bool withCRS)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(NX, NY, 1);
  image->SetOrigin(300015.0, 5000015.0, 0.0);
  image->SetSpacing(30.0, 30.0, 1.0);
  vtkNew<vtkFloatArray> z;
  z->SetName("Elevation");
  vtkNew<vtkFloatArray> v;
  v->SetName("Vector");
  v->SetNumberOfComponents(3);
  v->SetComponentName(0, "E");
  v->SetComponentName(1, "N");
  v->SetComponentName(2, "U");
  vtkNew<vtkIntArray> count;
  count->SetName("Count");
  for (int j = 0; j < NY; ++j)
  {
    for (int i = 0; i < NX; ++i)
    {
      z->InsertNextValue((i == 1 && j == 2) ? NAN : static_cast<float>(100 * j + i));
      v->InsertNextTuple3(i, j, -1.0);
      count->InsertNextValue(i * j);
    }
  }
  image->GetPointData()->SetScalars(z);
  image->GetPointData()->AddArray(v);
  image->GetPointData()->AddArray(count);
  if (withCRS)
  {
    vtkNew<vtkApertureGeoreference> geo;
    geo->SetCRS("EPSG:32633");
    geo->AttachToImage(image);
  }
  return image;
}

double Value(GDALDatasetH ds, int band, int col, int row)
{
  double v = 0.0;
  if (GDALRasterIO(GDALGetRasterBand(ds, band), GF_Read, col, row, 1, 1, &v, 1, 1, GDT_Float64, 0,
        0) != CE_None)
  {
    return -12345.0;
  }
  return v;
}

void TestWriteAndReadBack()
{
  const std::string path = tmp + "/written.tif";
  vtkNew<vtkApertureDEMWriter> writer;
  writer->SetInputData(MakeImage(true));
  writer->SetFileName(path.c_str());
  writer->AddMetadata("PRODUCT", "first");
  writer->AddMetadata("Product", "test");
  writer->AddBandMetadata("Vector", "UNITS", "foot");
  writer->AddBandMetadata("Vector", "units", "metre");
  // a key added again replaces its value, in any case as GDAL's keys (until 2026-12-07 each
  // was kept, the last written: a loop of writes adding one a frame grew the lists, and every
  // write's time, without end)
  std::ostringstream state;
  writer->Print(state);
  AP_CHECK_CONTAINS(state.str(), "Metadata items: 1\n");
  AP_CHECK_CONTAINS(state.str(), "Band metadata items: 1\n");
  writer->Write();

  GDALAllRegister();
  GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
  AP_CHECK(ds != nullptr);
  if (!ds)
  {
    return;
  }
  AP_CHECK(GDALGetRasterXSize(ds) == NX && GDALGetRasterYSize(ds) == NY);
  AP_CHECK(GDALGetRasterCount(ds) == 5);
  const char* names[5] = { "Elevation", "Vector_E", "Vector_N", "Vector_U", "Count" };
  for (int b = 1; b <= 5; ++b)
  {
    GDALRasterBandH band = GDALGetRasterBand(ds, b);
    AP_CHECK(std::string(GDALGetDescription(band)) == names[b - 1]);
    AP_CHECK(GDALGetRasterDataType(band) == GDT_Float32);
    int bx = 0, by = 0; // 6 x 4: one strip of the whole raster, not a 256 x 256 tile
    GDALGetBlockSize(band, &bx, &by);
    AP_CHECK(bx == NX && by == NY);
    int has = 0;
    AP_CHECK(std::isnan(GDALGetRasterNoDataValue(band, &has)) && has);
  }
  // File row 0 is the northern row (VTK row NY-1).
  AP_CHECK_NEAR(Value(ds, 1, 0, 0), 100.0 * (NY - 1), 0.0);
  AP_CHECK_NEAR(Value(ds, 1, 5, NY - 1), 5.0, 0.0);
  AP_CHECK(std::isnan(Value(ds, 1, 1, NY - 1 - 2)));
  AP_CHECK_NEAR(Value(ds, 2, 4, 0), 4.0, 0.0);            // Vector_E = i
  AP_CHECK_NEAR(Value(ds, 3, 4, 0), NY - 1.0, 0.0);       // Vector_N = j
  AP_CHECK_NEAR(Value(ds, 4, 4, 0), -1.0, 0.0);           // Vector_U
  AP_CHECK_NEAR(Value(ds, 5, 3, 0), 3.0 * (NY - 1), 0.0); // Count = i * j
  double gt[6];
  AP_CHECK(GDALGetGeoTransform(ds, gt) == CE_None);
  const double expected[6] = { 300000.0, 30.0, 0.0, 5000000.0 + NY * 30.0, 0.0, -30.0 };
  for (int k = 0; k < 6; ++k)
  {
    AP_CHECK_NEAR(gt[k], expected[k], 1e-9);
  }
  OGRSpatialReferenceH want = OSRNewSpatialReference(nullptr);
  OSRSetFromUserInput(want, "EPSG:32633");
  OGRSpatialReferenceH got = GDALGetSpatialRef(ds);
  AP_CHECK(got && OSRIsSame(want, got));
  OSRRelease(want);
  const char* compression = GDALGetMetadataItem(ds, "COMPRESSION", "IMAGE_STRUCTURE");
  AP_CHECK(compression && std::string(compression) == "DEFLATE");
  const char* product = GDALGetMetadataItem(ds, "PRODUCT", nullptr);
  AP_CHECK(product && std::string(product) == "test");
  const char* units = GDALGetMetadataItem(GDALGetRasterBand(ds, 3), "UNITS", nullptr);
  AP_CHECK(units && std::string(units) == "metre");
  AP_CHECK(GDALGetMetadataItem(GDALGetRasterBand(ds, 1), "UNITS", nullptr) == nullptr);
  // the UNITS item is the band's unit too, which gdalinfo and QGIS show (until 2026-12-07 it
  // was metadata only)
  for (int b = 1; b <= 5; ++b) // (Elevation, Vector_E, _N, _U in metres; Count has none)
  {
    AP_CHECK(std::string(GDALGetRasterUnitType(GDALGetRasterBand(ds, b))) ==
      (b < 5 ? "metre" : ""));
  }
  GDALClose(ds);

  // Round trip through our reader: same grid, same values, NaN where NaN was.
  vtkNew<vtkApertureDEMReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetBandIndex(1);
  reader->Update();
  vtkImageData* back = reader->GetOutput();
  auto original = MakeImage(true);
  double o1[3], o2[3];
  back->GetOrigin(o1);
  original->GetOrigin(o2);
  AP_CHECK_NEAR(o1[0], o2[0], 1e-9);
  AP_CHECK_NEAR(o1[1], o2[1], 1e-9);
  vtkDataArray* a = back->GetPointData()->GetScalars();
  vtkDataArray* b = original->GetPointData()->GetScalars();
  AP_CHECK(a && a->GetNumberOfTuples() == NX * NY);
  for (vtkIdType k = 0; a && k < NX * NY; ++k)
  {
    const double va = a->GetTuple1(k), vb = b->GetTuple1(k);
    AP_CHECK((std::isnan(va) && std::isnan(vb)) || va == vb);
  }
}

// A finite NoDataValue (for tools without NaN: an ASCII grid) is what NaN cells are written as
// and what every band declares, in one write or in strips; the reader reads those cells as
// NaN again. Until 2026-12-06 NaN was the only nodata value.
void TestNoDataValue()
{
  for (int strips : { 0, 1 })
  {
    const std::string path = tmp + "/nodata-" + std::to_string(strips) + ".tif";
    vtkNew<vtkApertureDEMWriter> writer;
    writer->SetInputData(MakeImage(true));
    writer->SetFileName(path.c_str());
    writer->SetNoDataValue(-9999.0);
    writer->SetStripRows(strips);
    writer->Write();
    GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
    AP_CHECK(ds != nullptr);
    if (!ds)
    {
      return;
    }
    for (int b = 1; b <= 5; ++b)
    {
      int has = 0;
      AP_CHECK(GDALGetRasterNoDataValue(GDALGetRasterBand(ds, b), &has) == -9999.0 && has);
    }
    AP_CHECK(Value(ds, 1, 1, NY - 1 - 2) == -9999.0); // the NaN cell
    AP_CHECK(Value(ds, 1, 2, NY - 1 - 2) == 202.0);   // its neighbour
    AP_CHECK(Value(ds, 2, 1, NY - 1 - 2) == 1.0);     // another band at that cell
    GDALClose(ds);
    vtkNew<vtkApertureDEMReader> reader;
    reader->SetFileName(path.c_str());
    reader->SetBandIndex(1);
    reader->Update();
    vtkDataArray* z = reader->GetOutput()->GetPointData()->GetScalars();
    AP_CHECK(z && std::isnan(z->GetTuple1(2 * NX + 1)) && z->GetTuple1(2 * NX + 2) == 202.0);
  }
  // A Float32 band declares the value as the float its cells hold: 0.1 as 0.1f (a reader
  // comparing in double would have missed every cell), and -3.4028235e38, numpy's and ESRI's
  // spelling of -FLT_MAX a hair beyond it, as -FLT_MAX (refused until 2026-12-07)
  for (const double value : { 0.1, -3.4028235e38, 3.4028235677973362e38 })
  {
    const std::string path = tmp + "/nodata-rounded.tif";
    const double want = value == 0.1 ? static_cast<double>(0.1f)
                                     : std::copysign(static_cast<double>(
                                                       std::numeric_limits<float>::max()),
                                         value);
    vtkNew<vtkApertureDEMWriter> writer;
    writer->SetInputData(MakeImage(true));
    writer->SetFileName(path.c_str());
    writer->SetNoDataValue(value);
    AP_CHECK(writer->Write() == 1);
    GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
    AP_CHECK(ds != nullptr);
    if (!ds)
    {
      return;
    }
    int has = 0;
    AP_CHECK(GDALGetRasterNoDataValue(GDALGetRasterBand(ds, 1), &has) == want && has);
    AP_CHECK(Value(ds, 1, 1, NY - 1 - 2) == want);
    GDALClose(ds);
  }
  vtkNew<vtkApertureDEMWriter> writer;
  writer->SetInputData(MakeImage(true));
  writer->SetFileName((tmp + "/nodata-bad.tif").c_str());
  writer->SetNoDataValue(3.4028235677973366e38); // (2^128 - 2^103: rounds to infinity)
  ExpectError(writer, "the NoDataValue 3.40282357e+38 is not a finite Float32 value (nor NaN)");
  writer->SetNoDataValue(1e300);
  ExpectError(writer, "the NoDataValue 1e+300 is not a finite Float32 value (nor NaN)");
  writer->SetNoDataValue(std::numeric_limits<double>::infinity());
  ExpectError(writer, "the NoDataValue inf is not a finite Float32 value");
  struct stat sb;
  AP_CHECK(stat((tmp + "/nodata-bad.tif").c_str(), &sb) != 0);
}

// A compound CRS is written as its horizontal part: until 2026-12-06 GDAL gave every band
// its height unit (US survey feet here), and the reader converted the metres again.
void TestCompoundCRS()
{
  const std::string path = tmp + "/compound.tif";
  auto image = MakeImage(false);
  vtkNew<vtkApertureGeoreference> geo;
  geo->SetCRS("EPSG:32633+6360");
  geo->AttachToImage(image);
  vtkNew<vtkApertureDEMWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(path.c_str());
  writer->Write();
  GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
  AP_CHECK(ds != nullptr);
  if (!ds)
  {
    return;
  }
  OGRSpatialReferenceH want = OSRNewSpatialReference(nullptr);
  OSRSetFromUserInput(want, "EPSG:32633");
  OGRSpatialReferenceH got = GDALGetSpatialRef(ds);
  AP_CHECK(got && !OSRIsCompound(got) && OSRIsSame(want, got));
  OSRRelease(want);
  for (int b = 1; b <= GDALGetRasterCount(ds); ++b)
  {
    // (not the vertical CRS's US survey foot; the heights, in metres, say so)
    GDALRasterBandH band = GDALGetRasterBand(ds, b);
    AP_CHECK(std::string(GDALGetRasterUnitType(band)) ==
      (std::string(GDALGetDescription(band)) == "Elevation" ? "metre" : ""));
  }
  GDALClose(ds);
  vtkNew<vtkApertureDEMReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetBandIndex(1);
  reader->Update();
  vtkDataArray* a = reader->GetOutput()->GetPointData()->GetScalars();
  AP_CHECK(a && a->GetNumberOfTuples() == NX * NY);
  AP_CHECK(a && a->GetTuple1(NX - 1) == NX - 1.0); // 5 m, not 5 US survey feet
}

// Selected arrays only, in the given order; a double array makes Float64 bands; no CRS warns.
void TestSelectionAndTypes()
{
  auto image = MakeImage(false);
  vtkNew<vtkDoubleArray> d;
  d->SetName("Precise");
  d->SetNumberOfTuples(NX * NY);
  d->Fill(0.1);
  image->GetPointData()->AddArray(d);
  const std::string path = tmp + "/selected.tif";
  vtkNew<vtkApertureDEMWriter> writer;
  vtkNew<vtkTest::ErrorObserver> warnings;
  writer->AddObserver(vtkCommand::WarningEvent, warnings);
  writer->SetInputData(image);
  writer->SetFileName(path.c_str());
  writer->AddArrayName("Precise");
  writer->AddArrayName("Elevation");
  writer->AddArrayName("Precise"); // (again, as a loop of writes adds it: ignored; until
                                   // 2026-12-06 each write got one more band of it)
  writer->SetCompression("LZW");
  writer->Write();
  AP_CHECK(warnings->GetWarning());
  AP_CHECK_CONTAINS(warnings->GetWarningMessage(), "without a CRS");
  GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
  AP_CHECK(ds && GDALGetRasterCount(ds) == 2);
  if (ds)
  {
    AP_CHECK(std::string(GDALGetDescription(GDALGetRasterBand(ds, 1))) == "Precise");
    AP_CHECK(GDALGetRasterDataType(GDALGetRasterBand(ds, 1)) == GDT_Float64);
    AP_CHECK_NEAR(Value(ds, 1, 0, 0), 0.1, 0.0); // exact in Float64
    const char* compression = GDALGetMetadataItem(ds, "COMPRESSION", "IMAGE_STRUCTURE");
    AP_CHECK(compression && std::string(compression) == "LZW");
    GDALClose(ds);
  }

  // A label array of strings is skipped when no list is given, as the EXR writer skips it
  // (until 2026-12-06 it failed the write, unless every other array was named); named, it is
  // an error.
  vtkNew<vtkStringArray> labels;
  labels->SetName("Labels");
  labels->SetNumberOfValues(NX * NY);
  image->GetPointData()->AddArray(labels);
  vtkNew<vtkApertureDEMWriter> all;
  vtkNew<vtkTest::ErrorObserver> errors;
  all->AddObserver(vtkCommand::ErrorEvent, errors);
  all->AddObserver(vtkCommand::WarningEvent, warnings); // (no CRS, said above)
  all->SetInputData(image);
  all->SetFileName((tmp + "/with-labels.tif").c_str());
  all->Write();
  AP_CHECK(!errors->GetError());
  ds = GDALOpen((tmp + "/with-labels.tif").c_str(), GA_ReadOnly);
  AP_CHECK(ds && GDALGetRasterCount(ds) == 6); // Elevation, Vector x 3, Count, Precise
  if (ds)
  {
    GDALClose(ds);
  }
  all->AddArrayName("Labels");
  ExpectError(all, "the point array 'Labels' is not numeric");
}

// Tiles compressed on several threads (NUM_THREADS) give the same file as on one, byte for
// byte.
void TestThreadsSameBytes()
{
  const int nx = 600, ny = 520;
  vtkSmartPointer<vtkImageData> image = NoisyImage(600, 520, 12345u, 1e-6f, "Elevation");
  vtkFloatArray* z = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("Elevation"));
  std::string files[2];
  const int threads[2] = { 1, 3 };
  for (int t = 0; t < 2; ++t)
  {
    files[t] = tmp + "/threads" + std::to_string(threads[t]) + ".tif";
    vtkNew<vtkApertureDEMWriter> writer;
    AP_CHECK(writer->GetNumberOfThreads() == 0); // default: all cores
    writer->SetNumberOfThreads(threads[t]);
    AP_CHECK(writer->GetNumberOfThreads() == threads[t]);
    writer->SetInputData(image);
    writer->SetFileName(files[t].c_str());
    writer->Write();
  }
  const std::string one = aptest::ReadFileBytes(files[0]);
  const std::string three = aptest::ReadFileBytes(files[1]);
  AP_CHECK(one.size() > 100000); // compressed, but not to nothing (~1.2 MB of samples)
  AP_CHECK(one == three);
  // every codec alike: LZMA, which GDAL 3.6 leaves uncompressed on one thread, is compressed
  // on two at least (its file on one thread was 30% larger, other bytes, until 2026-12-07)
  for (const char* codec : { "ZSTD", "LZW", "LZMA", "LERC_ZSTD" })
  {
    std::string bytes[2];
    for (int t = 0; t < 2; ++t)
    {
      const std::string path = tmp + "/threads-" + codec + std::to_string(threads[t]) + ".tif";
      vtkNew<vtkApertureDEMWriter> writer;
      writer->SetCompression(codec);
      writer->SetNumberOfThreads(threads[t]);
      writer->SetInputData(image);
      writer->SetFileName(path.c_str());
      AP_CHECK(writer->Write() == 1);
      bytes[t] = aptest::ReadFileBytes(path);
    }
    AP_CHECK(bytes[0] == bytes[1]);
    // (compressed, as ZSTD compresses these noisy samples: 0.72 of their 1.25 MB, where GDAL's
    // LZMA on one thread stored them whole)
    AP_CHECK(std::string(codec) != "LZMA" || bytes[0].size() < 4u * nx * ny * 8 / 10);
  }
  {
    // Counts beyond the cores are capped at them, as for the sky filter and the EXR writer:
    // until 2026-12-06 GDAL was handed 100000, and its thread pool (which stays for the
    // process) grew to some 140 threads on two cores. Tiles of 2048^2 cells: 64 to compress.
    const auto tasks = []() {
      int n = 0;
      if (DIR* dir = opendir("/proc/self/task"))
      {
        while (const dirent* e = readdir(dir))
        {
          n += e->d_name[0] != '.';
        }
        closedir(dir);
      }
      return n;
    };
    const int before = tasks();
    vtkNew<vtkApertureDEMWriter> writer;
    writer->SetNumberOfThreads(100000);
    writer->SetInputData(NoisyImage(2048, 2048, 7u, 1e-6f, "Elevation"));
    const std::string many = tmp + "/threads-many.tif";
    writer->SetFileName(many.c_str());
    writer->SetCompressionLevel(1);
    AP_CHECK(writer->Write() == 1);
    const int started = tasks() - before;
    AP_CHECK(before == 0 || started <= static_cast<int>(std::thread::hardware_concurrency()));
  }
  GDALDatasetH ds = GDALOpen(files[1].c_str(), GA_ReadOnly);
  AP_CHECK(ds != nullptr);
  if (ds)
  {
    const vtkIdType k = static_cast<vtkIdType>(ny - 1 - 300) * nx + 457; // file row 300
    AP_CHECK_NEAR(Value(ds, 1, 457, 300), z->GetValue(k), 0.0);
    GDALClose(ds);
  }
}

// The compression level reaches GDAL: -1 gives GDAL's default file byte for byte (DEFLATE 6,
// ZSTD 9), other levels other files holding the same values; the codec's name is
// case-insensitive (the predictor still applies); codecs without levels ignore it.
void TestCompressionLevels()
{
  vtkSmartPointer<vtkImageData> image = NoisyImage(600, 520, 12345u, 1e-6f, "Elevation");
  auto write = [&](const char* codec, int level) {
    const std::string path =
      tmp + "/level_" + codec + "_" + std::to_string(level) + ".tif";
    vtkNew<vtkApertureDEMWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName(path.c_str());
    writer->SetCompression(codec);
    writer->SetCompressionLevel(level);
    writer->SetNumberOfThreads(1);
    writer->Write();
    return path;
  };
  vtkNew<vtkApertureDEMWriter> defaults;
  AP_CHECK(defaults->GetCompressionLevel() == 1);
  const std::string d1 = write("DEFLATE", 1), d6 = write("DEFLATE", 6),
                    dgdal = write("DEFLATE", -1), d9 = write("deflate", 9);
  const std::string b1 = aptest::ReadFileBytes(d1), b6 = aptest::ReadFileBytes(d6);
  const std::string bgdal = aptest::ReadFileBytes(dgdal), b9 = aptest::ReadFileBytes(d9);
  AP_CHECK(b1.size() > 100000);
  AP_CHECK(bgdal == b6);
  AP_CHECK(b1 != b6);
  AP_CHECK(b9.size() < b1.size()); // the slowest level packs tighter than the fastest
  const std::string z1 = aptest::ReadFileBytes(write("ZSTD", 1));
  const std::string zgdal = aptest::ReadFileBytes(write("ZSTD", -1));
  const std::string z9 = aptest::ReadFileBytes(write("ZSTD", 9));
  AP_CHECK(z1.size() > 100000);
  AP_CHECK(zgdal == z9);
  AP_CHECK(z1 != z9);
  AP_CHECK(aptest::ReadFileBytes(write("LZW", 50)).size() > 100000); // no levels: ignored
  // LZMA's preset reaches GDAL (it was refused for a day on a measurement of 0 and 9 alone):
  // 1 other bytes than 6, GDAL's default
  const std::string l1 = aptest::ReadFileBytes(write("LZMA", 1));
  const std::string l6 = aptest::ReadFileBytes(write("LZMA", 6));
  AP_CHECK(l1.size() > 100000 && l1 != l6);
  AP_CHECK(aptest::ReadFileBytes(write("LZMA", -1)) == l6);
  vtkFloatArray* z = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("Elevation"));
  for (const std::string& path : { d1, d9 })
  {
    GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
    AP_CHECK(ds != nullptr);
    if (ds)
    {
      const char* predictor = GDALGetMetadataItem(ds, "PREDICTOR", "IMAGE_STRUCTURE");
      AP_CHECK(predictor && std::string(predictor) == "3");
      const vtkIdType k = static_cast<vtkIdType>(519 - 211) * 600 + 33; // file row 211
      AP_CHECK_NEAR(Value(ds, 1, 33, 211), z->GetValue(k), 0.0);
      GDALClose(ds);
    }
  }
}

// Every band of two GeoTIFFs, their geotransforms, CRSs, descriptions and metadata are equal.
bool SameContents(const std::string& a, const std::string& b)
{
  GDALDatasetH da = GDALOpen(a.c_str(), GA_ReadOnly), db = GDALOpen(b.c_str(), GA_ReadOnly);
  bool same = da && db && GDALGetRasterCount(da) == GDALGetRasterCount(db) &&
    GDALGetRasterXSize(da) == GDALGetRasterXSize(db) &&
    GDALGetRasterYSize(da) == GDALGetRasterYSize(db);
  if (same)
  {
    double ga[6], gb[6];
    GDALGetGeoTransform(da, ga);
    GDALGetGeoTransform(db, gb);
    same = std::equal(ga, ga + 6, gb) &&
      std::string(GDALGetProjectionRef(da)) == GDALGetProjectionRef(db) &&
      std::string(GDALGetMetadataItem(da, "SOURCE", nullptr)) ==
        GDALGetMetadataItem(db, "SOURCE", nullptr);
    const int nx = GDALGetRasterXSize(da), ny = GDALGetRasterYSize(da);
    std::vector<double> va(static_cast<size_t>(nx) * ny), vb(va.size());
    for (int band = 1; same && band <= GDALGetRasterCount(da); ++band)
    {
      GDALRasterBandH ba = GDALGetRasterBand(da, band), bb = GDALGetRasterBand(db, band);
      const char* ua = GDALGetMetadataItem(ba, "UNITS", nullptr);
      const char* ub = GDALGetMetadataItem(bb, "UNITS", nullptr);
      same = std::string(GDALGetDescription(ba)) == GDALGetDescription(bb) &&
        std::string(ua ? ua : "") == (ub ? ub : "") &&
        GDALGetRasterDataType(ba) == GDALGetRasterDataType(bb) &&
        GDALRasterIO(ba, GF_Read, 0, 0, nx, ny, va.data(), nx, ny, GDT_Float64, 0, 0) ==
          CE_None &&
        GDALRasterIO(bb, GF_Read, 0, 0, nx, ny, vb.data(), nx, ny, GDT_Float64, 0, 0) ==
          CE_None &&
        std::memcmp(va.data(), vb.data(), va.size() * sizeof(double)) == 0;
    }
  }
  GDALClose(da);
  GDALClose(db);
  return same;
}

// StripRows: the input is asked for strips of whole 256-row tiles, north first, and the file
// holds what a whole write gives (from a source of sub-extents, and from an image given whole);
// a strip the input fails to produce, or an abort, is an error that leaves no file (and no
// endless pipeline loop).
void TestStrips()
{
  vtkSmartPointer<vtkImageData> image = NoisyImage(600, 520, 12345u, 1e-6f, "Elevation");
  vtkNew<vtkDoubleArray> twice;
  twice->SetName("Twice");
  twice->SetNumberOfComponents(2);
  vtkDataArray* z = image->GetPointData()->GetArray("Elevation");
  for (vtkIdType k = 0; k < image->GetNumberOfPoints(); ++k)
  {
    twice->InsertNextTuple2(2.0 * z->GetTuple1(k), -static_cast<double>(k));
  }
  image->GetPointData()->AddArray(twice);
  auto setup = [&](vtkApertureDEMWriter* w, const std::string& path, int rows) {
    w->SetFileName(path.c_str());
    w->SetStripRows(rows);
    w->AddMetadata("SOURCE", "strips test");
    w->AddBandMetadata("Twice", "UNITS", "m");
  };
  const std::string whole = tmp + "/strips-whole.tif";
  {
    vtkNew<vtkApertureDEMWriter> w;
    w->SetInputData(image);
    setup(w, whole, 0);
    AP_CHECK(w->Write() == 1);
  }
  vtkNew<StripSource> source;
  source->Image = image;
  {
    vtkNew<vtkApertureDEMWriter> w;
    w->SetInputConnection(source->GetOutputPort());
    setup(w, tmp + "/strips.tif", 1);
    AP_CHECK(w->GetStripRows() == 1);
    AP_CHECK(vtkApertureDEMWriter::GetTileSize() == 256); // (the strips asked below)
    std::vector<double> progress; // (from 0, as a whole write's; it began after a strip)
    RecordProgress(w, &progress);
    AP_CHECK(w->Write() == 1);
    AP_CHECK(ProgressFromZeroToOne(progress));
    const std::vector<std::vector<int>> asked = { { 0, 599, 264, 519, 0, 0 },
      { 0, 599, 8, 263, 0, 0 }, { 0, 599, 0, 7, 0, 0 } };
    AP_CHECK(source->Requests == asked);
    AP_CHECK(SameContents(whole, tmp + "/strips.tif"));
    {
      GDALDatasetH ds = GDALOpen((tmp + "/strips.tif").c_str(), GA_ReadOnly);
      int bx = 0, by = 0; // (520 rows: square tiles)
      GDALGetBlockSize(GDALGetRasterBand(ds, 1), &bx, &by);
      AP_CHECK(bx == 256 && by == 256);
      GDALClose(ds);
    }
    AP_CHECK(source->GetOutput()->GetNumberOfPoints() == 600 * 8); // the last strip, kept
    // with the producer's ReleaseDataFlag on, each strip is released once written
    source->ReleaseDataFlagOn();
    source->Requests.clear();
    setup(w, tmp + "/strips-released.tif", 256);
    AP_CHECK(w->Write() == 1);
    AP_CHECK(source->Requests == asked);
    AP_CHECK(source->GetOutput()->GetNumberOfPoints() == 0);
    AP_CHECK(SameContents(whole, tmp + "/strips-released.tif"));
    source->ReleaseDataFlagOff();
  }
  {
    // 3 columns: the file's strips of 256 rows, 3 wide; written in strips of 256 rows
    vtkSmartPointer<vtkImageData> narrow = NoisyImage(3, 520, 777u, 1e-6f, "Elevation");
    vtkNew<vtkApertureDEMWriter> w;
    w->SetInputData(narrow);
    setup(w, tmp + "/narrow-whole.tif", 0);
    // progress as each tile row of the band is written (256, 512 and 520 of the 520 rows),
    // not once the band is done: a large one-band write is long
    std::vector<double> progress;
    vtkNew<vtkCallbackCommand> record;
    record->SetClientData(&progress);
    record->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
      static_cast<std::vector<double>*>(client)->push_back(*static_cast<double*>(call));
    });
    const unsigned long tag = w->AddObserver(vtkCommand::ProgressEvent, record);
    AP_CHECK(w->Write() == 1);
    w->RemoveObserver(tag);
    for (const double expected : { 256.0 / 520.0, 512.0 / 520.0, 1.0 })
    {
      AP_CHECK(std::any_of(progress.begin(), progress.end(),
        [&](double v) { return std::fabs(v - expected) < 1e-12; }));
    }
    AP_CHECK(std::is_sorted(progress.begin(), progress.end()));
    setup(w, tmp + "/narrow-strips.tif", 1);
    AP_CHECK(w->Write() == 1);
    AP_CHECK(SameContents(tmp + "/narrow-whole.tif", tmp + "/narrow-strips.tif"));
    GDALDatasetH ds = GDALOpen((tmp + "/narrow-strips.tif").c_str(), GA_ReadOnly);
    int bx = 0, by = 0;
    GDALGetBlockSize(GDALGetRasterBand(ds, 1), &bx, &by);
    AP_CHECK(bx == 3 && by == 256);
    AP_CHECK(GDALGetRasterXSize(ds) == 3 && GDALGetRasterYSize(ds) == 520);
    vtkDataArray* nz = narrow->GetPointData()->GetArray("Elevation");
    for (int j : { 0, 255, 256, 519 }) // (file rows north first: grid row j is file row 519 - j)
    {
      AP_CHECK(Value(ds, 1, 2, 519 - j) == static_cast<float>(nz->GetTuple1(3 * j + 2)));
    }
    GDALClose(ds);
  }
  {
    vtkNew<vtkApertureDEMWriter> w;
    w->SetInputData(image);
    setup(w, tmp + "/strips-given.tif", 300); // 512 rows: 2 strips of the image given whole
    AP_CHECK(w->Write() == 1);
    AP_CHECK(SameContents(whole, tmp + "/strips-given.tif"));
  }
  {
    vtkNew<vtkApertureDEMWriter> w;
    const std::string path = tmp + "/strips-failed.tif";
    setup(w, path, 256);
    const std::string errors = FailingWrite(w, source, 100);
    AP_CHECK_CONTAINS(errors, "the input did not produce rows 8 to 263 of 0 to 519");
    AP_CHECK(errors.find("were not written") == std::string::npos);
    struct stat sb;
    AP_CHECK(stat(path.c_str(), &sb) != 0); // nothing left behind
  }
  {
    vtkNew<vtkApertureDEMWriter> w;
    w->SetInputConnection(source->GetOutputPort());
    const std::string path = tmp + "/strips-aborted.tif";
    setup(w, path, 256);
    AbortOnProgress(w);
    vtkNew<vtkTest::ErrorObserver> errors;
    w->AddObserver(vtkCommand::ErrorEvent, errors);
    AP_CHECK(w->Write() == 0);
    AP_CHECK_CONTAINS(errors->GetErrorMessage(), "strips-aborted.tif' was aborted");
    struct stat sb;
    AP_CHECK(stat(path.c_str(), &sb) != 0);
    // the same when the image is written at once (after its first band)
    vtkNew<vtkApertureDEMWriter> once;
    once->SetInputData(image);
    const std::string oncePath = tmp + "/once-aborted.tif";
    setup(once, oncePath, 0);
    AbortOnProgress(once);
    vtkNew<vtkTest::ErrorObserver> onceErrors;
    once->AddObserver(vtkCommand::ErrorEvent, onceErrors);
    AP_CHECK(once->Write() == 0); // (Write() at once reports the failure too)
    AP_CHECK_CONTAINS(onceErrors->GetErrorMessage(), "once-aborted.tif' was aborted");
    AP_CHECK(stat(oncePath.c_str(), &sb) != 0);
    // An earlier file stays as it was, in strips or at once: the file is written aside and
    // renamed into place when complete (until 2026-12-06 GDAL had deleted it first, while
    // the EXR writer kept its earlier file), and nothing hidden is left beside it.
    for (vtkApertureDEMWriter* writer : { w.GetPointer(), once.GetPointer() })
    {
      const std::string kept = tmp + "/kept.tif";
      {
        FILE* f = std::fopen(kept.c_str(), "wb");
        AP_CHECK(f && std::fputs("an earlier file", f) >= 0 && std::fclose(f) == 0);
      }
      writer->SetFileName(kept.c_str());
      AP_CHECK(writer->Write() == 0);
      AP_CHECK(aptest::ReadFileBytes(kept) == "an earlier file");
    }
    DIR* folder = opendir(tmp.c_str());
    // (this process's: the EXR writer's test runs beside this one in the same folder)
    const std::string own = ".aperture-" + std::to_string(static_cast<long>(getpid())) + "-";
    for (struct dirent* e = folder ? readdir(folder) : nullptr; e; e = readdir(folder))
    {
      AP_CHECK(std::string(e->d_name).compare(0, own.size(), own) != 0);
    }
    if (folder)
    {
      closedir(folder);
    }
  }

  {
    // no file name: said before a strip is computed (which can take long)
    vtkNew<vtkApertureDEMWriter> w;
    source->Modified();
    source->Requests.clear();
    w->SetInputConnection(source->GetOutputPort());
    w->SetStripRows(256);
    vtkNew<vtkTest::ErrorObserver> errors;
    w->AddObserver(vtkCommand::ErrorEvent, errors);
    AP_CHECK(w->Write() == 0);
    AP_CHECK_CONTAINS(errors->GetErrorMessage(), "no file name was set");
    AP_CHECK(source->Requests.empty());
  }

  // BeginStrips / WriteStrip / EndStrips with strips the caller makes: a strip of 300 rows
  // writes 256 (a whole tile row) and leaves the rest to the next, which must hold it; the
  // file equals the whole write. A strip without the next row, one of fewer than 256 rows
  // short of the end, or rows never written: errors, and no file.
  const int all[6] = { 0, 599, 0, 519, 0, 0 };
  auto rows = [&](int j0, int j1) {
    source->Modified(); // (else the executive keeps a larger extent computed before)
    source->UpdateExtent(std::vector<int>{ 0, 599, j0, j1, 0, 0 }.data());
    return source->GetOutput();
  };
  {
    vtkNew<vtkApertureDEMWriter> w;
    const std::string path = tmp + "/strips-caller.tif";
    setup(w, path, 0);
    // (the file's grid is that of `all`, whichever strip describes the arrays)
    AP_CHECK(w->BeginStrips(rows(0, 100), all) == 1);
    AP_CHECK(w->GetNextStripRow() == 519);
    AP_CHECK(w->WriteStrip(rows(220, 519)) == 1);
    AP_CHECK(w->GetNextStripRow() == 263); // rows 519 .. 264
    AP_CHECK(w->WriteStrip(rows(0, 263)) == 1);
    AP_CHECK(w->GetNextStripRow() == -1);
    AP_CHECK(w->EndStrips() == 1);
    AP_CHECK(SameContents(whole, path));
  }
  {
    // a file begun and never ended is removed when the writer writes another
    vtkNew<vtkApertureDEMWriter> w;
    const std::string begun = tmp + "/strips-begun.tif", once = tmp + "/strips-then-once.tif";
    setup(w, begun, 0);
    AP_CHECK(w->BeginStrips(rows(0, 519), all) == 1);
    w->SetFileName(once.c_str());
    w->SetInputData(image);
    AP_CHECK(w->Write() == 1);
    struct stat sb;
    AP_CHECK(stat(begun.c_str(), &sb) != 0);
    AP_CHECK(SameContents(whole, once));
  }
  // strips as { first row, last row, WriteStrip's result }
  auto failing = [&](const std::vector<std::vector<int>>& strips, const std::string& expected) {
    vtkNew<vtkApertureDEMWriter> w;
    const std::string path = tmp + "/strips-caller-failed.tif";
    setup(w, path, 0);
    vtkNew<vtkTest::ErrorObserver> errors;
    w->AddObserver(vtkCommand::ErrorEvent, errors);
    AP_CHECK(w->BeginStrips(rows(0, 519), all) == 1);
    for (const std::vector<int>& strip : strips)
    {
      AP_CHECK(w->WriteStrip(rows(strip[0], strip[1])) == strip[2]);
    }
    AP_CHECK(w->EndStrips() == 0);
    AP_CHECK_CONTAINS(errors->GetErrorMessage(), expected);
    struct stat sb;
    AP_CHECK(stat(path.c_str(), &sb) != 0);
  };
  failing({ { 264, 519, 1 }, { 0, 250, 0 } },
    "extent (0..599, 0..250) does not hold row 263 of columns 0 to 599");
  failing({ { 300, 519, 0 }, { 0, 519, 0 } }, "a strip must hold 256 rows (a tile row of");
  failing({ { 264, 519, 1 } },
    "rows 0 to 263 of '" + tmp + "/strips-caller-failed.tif' were not written");
}

// Writing `image` to `path` (none there before: a stale one removed) fails with `expected`
// and leaves no file there.
void ExpectRefused(vtkImageData* image, const std::string& path, const std::string& expected)
{
  std::remove(path.c_str());
  vtkNew<vtkApertureDEMWriter> w;
  w->SetInputData(image);
  w->SetFileName(path.c_str());
  ExpectError(w, expected);
  struct stat sb;
  AP_CHECK(stat(path.c_str(), &sb) != 0);
}

// (and an ErrorCode, as VTK's writers set one: `code`, or any but NoError for -1)
void ExpectError(vtkApertureDEMWriter* writer, const std::string& expected, int code)
{
  vtkNew<vtkTest::ErrorObserver> errors, executiveErrors;
  writer->AddObserver(vtkCommand::ErrorEvent, errors);
  writer->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, executiveErrors);
  AP_CHECK(writer->Write() == 0);
  AP_CHECK(errors->GetError());
  AP_CHECK_CONTAINS(errors->GetErrorMessage(), expected);
  const unsigned long got = writer->GetErrorCode();
  AP_CHECK(code == -1 ? got != vtkErrorCode::NoError : got == static_cast<unsigned long>(code));
}

// Every codec the writer accepts keeps each value, NaNs included, when tiles are compressed
// on GDAL's threads (where GDAL reports a failing codec to nobody: the file would lack the
// tiles); the codecs that cannot store float samples are refused before any file exists.
void TestCodecs()
{
  vtkSmartPointer<vtkImageData> image = NoisyImage(300, 270, 777u, 1e-3f, "Elevation");
  vtkFloatArray* z = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("Elevation"));
  for (vtkIdType k = 0; k < z->GetNumberOfTuples(); k += 37)
  {
    z->SetValue(k, std::numeric_limits<float>::quiet_NaN());
  }
  int written = 0;
  for (const char* codec :
    { "NONE", "LZW", "PACKBITS", "ZSTD", "LZMA", "LERC", "LERC_DEFLATE", "LERC_ZSTD" })
  {
    vtkNew<vtkApertureDEMWriter> writer;
    writer->SetCompression(codec);
    const std::string path = tmp + "/codec_" + codec + ".tif";
    writer->SetInputData(image);
    writer->SetFileName(path.c_str());
    writer->SetNumberOfThreads(2);
    AP_CHECK(writer->Write() == 1);
    GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
    AP_CHECK(ds != nullptr);
    if (!ds)
    {
      continue;
    }
    std::vector<float> back(300 * 270);
    AP_CHECK(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Read, 0, 0, 300, 270, back.data(), 300,
               270, GDT_Float32, 0, 0) == CE_None);
    int differ = 0;
    for (int row = 0; row < 270; ++row)
    {
      for (int col = 0; col < 300; ++col)
      {
        const float want = z->GetValue(static_cast<vtkIdType>(269 - row) * 300 + col);
        const float got = back[static_cast<size_t>(row) * 300 + col];
        differ += std::isnan(want) ? !std::isnan(got) : !(got == want);
      }
    }
    AP_CHECK(differ == 0);
    GDALClose(ds);
    ++written;
  }
  AP_CHECK(written == 8); // (Debian 12's GDAL offers them all)
  for (const char* codec : { "JPEG", "webp", "CCITTFAX4" })
  {
    vtkNew<vtkApertureDEMWriter> w;
    w->SetInputData(image);
    const std::string path = tmp + "/lossy.tif";
    w->SetFileName(path.c_str());
    w->SetCompression(codec);
    w->SetNumberOfThreads(2);
    ExpectError(w, std::string("GeoTIFF compression '") + codec +
        "' cannot store floating-point bands; choose one of NONE, LZW, PACKBITS, DEFLATE");
    struct stat sb;
    AP_CHECK(stat(path.c_str(), &sb) != 0); // nothing left behind
  }
}


void TestErrors()
{
  {
    vtkNew<vtkApertureDEMWriter> w;
    w->SetInputData(MakeImage(true));
    ExpectError(w, "no file name was set", vtkErrorCode::NoFileNameError);
    w->SetStripRows(2); // (refused by Write() before the strip driver; UnknownError until review)
    ExpectError(w, "no file name was set", vtkErrorCode::NoFileNameError);
  }
  {
    // without an input the name is looked at first; with a name, not NoFileNameError (which
    // any failure without a name was, until review)
    vtkNew<vtkApertureDEMWriter> w;
    ExpectError(w, "no file name was set", vtkErrorCode::NoFileNameError);
    w->SetFileName((tmp + "/no-input.tif").c_str());
    ExpectError(w, "No input provided", vtkErrorCode::UnknownError);
    w->SetStripRows(2);
    ExpectError(w, "no input to write", vtkErrorCode::UnknownError);
  }
  // A grid no geotransform can say: refused (a NaN origin was written as a geotransform of
  // NaN, a negative spacing as a mirrored one, zero as none, each with only a warning).
  for (bool withCRS : { true, false })
  {
    for (int bad = 0; bad < 4; ++bad)
    {
      auto image = MakeImage(withCRS);
      if (bad == 0)
      {
        image->SetOrigin(std::nan(""), 5000015.0, 0.0);
      }
      else if (bad < 3)
      {
        image->SetSpacing(30.0, bad == 1 ? -30.0 : 0.0, 1.0);
      }
      else
      {
        // edges beyond the doubles (written as a geotransform of inf until 2026-12-06)
        image->SetSpacing(30.0, 1e308, 1.0);
      }
      const std::string path = tmp + "/badgrid.tif";
      vtkNew<vtkApertureDEMWriter> w;
      w->SetInputData(image);
      w->SetFileName(path.c_str());
      ExpectError(w, bad == 3
          ? (withCRS ? "georeference cannot be written to '" + path + "': the image's south and "
                       "north edges are not finite numbers (origin "
                     : "cannot write '" + path + "': the grid's edges are not finite numbers")
          : withCRS ? "the image has a CRS but its georeference cannot be written"
                    : "the image's spacing must be positive and finite and its origin "
                      "finite to make a geotransform");
      struct stat sb;
      AP_CHECK(stat(path.c_str(), &sb) != 0);
    }
  }
  {
    vtkNew<vtkApertureDEMWriter> w;
    w->SetInputData(MakeImage(true));
    w->SetFileName((tmp + "/missing.tif").c_str());
    w->AddArrayName("Slope");
    ExpectError(w, "no point array named 'Slope'");
    struct stat sb;
    AP_CHECK(stat((tmp + "/missing.tif").c_str(), &sb) != 0); // nothing left behind
  }
  {
    // a hand-made image's heights as its scalars, without a name (which the filters take as
    // its Elevation): what to do, said (the name is the band's description)
    vtkNew<vtkImageData> image;
    image->SetDimensions(3, 2, 1);
    vtkNew<vtkFloatArray> heights;
    heights->SetNumberOfValues(6);
    heights->Fill(100.0f);
    image->GetPointData()->SetScalars(heights);
    const std::string path = tmp + "/nameless.tif";
    ExpectRefused(image, path, "the image has no named point arrays to write to '" + path +
        "' (a band is described by its array's name: name the array, such as 'Elevation')");
  }
  {
    // without a CRS the grid still needs its geotransform: a mirrored direction matrix (north
    // down) is refused, as with a CRS (it was written upside down, with a warning)
    auto image = MakeImage(false);
    const double flip[9] = { 1, 0, 0, 0, -1, 0, 0, 0, 1 };
    image->SetDirectionMatrix(flip);
    const std::string path = tmp + "/flipped.tif";
    ExpectRefused(image, path, "cannot write '" + path + "': the image has a rotated or "
        "mirrored direction matrix, which no geotransform of its origin and spacing describes");
  }
  {
    vtkNew<vtkApertureDEMWriter> w;
    w->SetInputData(MakeImage(true));
    w->SetFileName("/nonexistent-folder/x.tif");
    ExpectError(w, "GDAL cannot create '/nonexistent-folder/x.tif'",
      vtkErrorCode::CannotOpenFileError);
    // (a success clears it)
    w->SetFileName((tmp + "/after-failure.tif").c_str());
    AP_CHECK(w->Write() == 1 && w->GetErrorCode() == vtkErrorCode::NoError);
  }
  {
    // an image that disagrees with itself (made by hand): a band's array too short
    vtkNew<vtkApertureDEMWriter> w;
    auto image = MakeImage(true);
    image->GetPointData()->GetArray("Count")->SetNumberOfTuples(NX);
    w->SetInputData(image);
    const std::string path = tmp + "/short.tif";
    w->SetFileName(path.c_str());
    std::ostringstream expected;
    expected << "the point array 'Count' has " << NX << " tuples for the " << NX << " x " << NY
             << " points of the input's extent";
    ExpectError(w, expected.str());
    struct stat sb;
    AP_CHECK(stat(path.c_str(), &sb) != 0); // nothing left behind
  }
  const struct
  {
    const char* Codec;
    int Level;
    const char* Message;
  } badLevels[] = { { "DEFLATE", 13, "compression level 13 is outside DEFLATE's range 1-12" },
    { "deflate", 0, "compression level 0 is outside DEFLATE's range 1-12" },
    { "ZSTD", 23, "compression level 23 is outside ZSTD's range 1-22" },
    { "LZMA", 0, "compression level 0 is outside LZMA's range 1-9" } };
  {
    // an unknown codec: GDAL would warn and write the file uncompressed
    vtkNew<vtkApertureDEMWriter> w;
    AP_CHECK(w->CheckCompression());
    w->SetInputData(MakeImage(true));
    const std::string path = tmp + "/badcodec.tif";
    w->SetFileName(path.c_str());
    w->SetCompression("DEFLATE9");
    ExpectError(w, "unknown GeoTIFF compression 'DEFLATE9' (GDAL offers NONE, LZW, ");
    struct stat sb;
    AP_CHECK(stat(path.c_str(), &sb) != 0); // nothing left behind
    vtkNew<vtkTest::ErrorObserver> errors;
    w->AddObserver(vtkCommand::ErrorEvent, errors);
    AP_CHECK(!w->CheckCompression());
    AP_CHECK_CONTAINS(errors->GetErrorMessage(), "ZSTD");
    w->SetCompression("zstd");
    AP_CHECK(w->CheckCompression());
    // the codecs whose level CompressionLevel sets (the others ignore it)
    AP_CHECK(vtkApertureDEMWriter::HasCompressionLevel("DEFLATE"));
    AP_CHECK(vtkApertureDEMWriter::HasCompressionLevel("zstd"));
    AP_CHECK(vtkApertureDEMWriter::HasCompressionLevel("Lzma"));
    AP_CHECK(!vtkApertureDEMWriter::HasCompressionLevel("LZW"));
    AP_CHECK(!vtkApertureDEMWriter::HasCompressionLevel("NONE"));
    AP_CHECK(!vtkApertureDEMWriter::HasCompressionLevel("LERC_DEFLATE"));
    AP_CHECK(!vtkApertureDEMWriter::HasCompressionLevel(""));
    AP_CHECK(!vtkApertureDEMWriter::HasCompressionLevel(nullptr));
  }
  // No file there (a pipe, a folder, a device): GDAL would fail writing it, and the writer then
  // removed what it had tried to write, /dev/null for a root bake to /dev/null. Uncompressed
  // (GDAL streams to a pipe: it waited for a reader) and compressed, on one thread and two
  // (GDAL's compression threads spun forever on the device).
  const auto specials = aptest::SpecialFiles(tmp, "dem-writer");
  AP_CHECK(specials.size() >= 2);
  for (const auto& special : specials)
  {
    for (const char* codec : { "NONE", "DEFLATE" })
    {
      for (int threads : { 1, 2 })
      {
        vtkNew<vtkApertureDEMWriter> w;
        w->SetInputData(MakeImage(true));
        w->SetFileName(special.first.c_str());
        w->SetCompression(codec);
        w->SetNumberOfThreads(threads);
        ExpectError(w, "'" + special.first + "' is " + special.second +
            ", not a file a GeoTIFF can be written to", vtkErrorCode::CannotOpenFileError);
        AP_CHECK(aptest::SameKind(special.first, special.second));
      }
    }
  }
  aptest::RemoveSpecialFiles(specials);
  for (const auto& bad : badLevels)
  {
    vtkNew<vtkApertureDEMWriter> w;
    w->SetInputData(MakeImage(true));
    const std::string path = tmp + "/badlevel.tif";
    w->SetFileName(path.c_str());
    w->SetCompression(bad.Codec);
    w->SetCompressionLevel(bad.Level);
    ExpectError(w, bad.Message);
    struct stat sb;
    AP_CHECK(stat(path.c_str(), &sb) != 0); // nothing left behind
  }
}

//------------------------------------------------------------------------------
void TestClears()
{
  vtkNew<vtkApertureDEMWriter> w;
  aptest::CheckClearsModifyOnlyOnChange(w.Get());
  w->AddBandMetadata("A", "UNITS", "m");
  const vtkMTimeType m = w->GetMTime();
  w->ClearMetadata();
  AP_CHECK(w->GetMTime() > m);
}
} // namespace

//------------------------------------------------------------------------------
int TestApertureDEMWriter(int argc, char* argv[])
{
  tmp = aptest::TempDir(argc, argv);
  TestWriteAndReadBack();
  TestNoDataValue();
  TestCompoundCRS();
  TestSelectionAndTypes();
  TestThreadsSameBytes();
  TestCompressionLevels();
  TestCodecs();
  TestStrips();
  TestErrors();
  TestClears();
  return aptest::Result();
}
