// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkApertureDEMReader
 * @brief   Read a single-band elevation raster (any format GDAL opens) as a 2-D DEM image.
 *
 * Output: a vtkImageData with one float32 point array `Elevation` in metres: the band's scale
 * and offset are applied, and feet, US survey feet and the metre's multiples (mm, cm, dm, km)
 * are converted (the band's unit, else the height unit of a compound CRS, else metres;
 * MetresPerElevationUnit overrides them). Nodata (the band's nodata value, a GDAL mask, NaN,
 * an infinity, or a value that does not fit a float) becomes NaN; a Float32 band's nodata
 * value is compared rounded to float, and a float band's samples within about two float32
 * ulps of it (relatively) are nodata too, as GDAL's mask takes them (ArcGIS declares
 * -3.4028230607370965e38 for cells of -FLT_MAX); an integer band's compare exactly. A band
 * that declares none, has no scale or offset, and has samples of -9999 outside its mask (a
 * common nodata value, within the Earth's range of heights) is read as it is, with a warning.
 * Infinite samples that the nodata value does not declare are nodata, with a warning (with or
 * without a scale or another nodata value); so are a Float64 band's finite samples beyond the
 * float range (-1.79e308, -DBL_MAX: an undeclared nodata value) that its scale does not bring
 * within it.
 * GDAL 3.6's Int8 (a Byte band with PIXELTYPE=SIGNEDBYTE) is read as signed.
 * The grid follows vtkApertureGeoreference's conventions: origin and
 * spacing in CRS units, origin at the centre of the south-west cell, row 0 south, identity
 * direction. North-up and south-up rasters both come out north-up (rows are flipped once,
 * here). The CRS (WKT) and the GeoTransform of the output grid are in the output's field data.
 *
 * Options:
 * - BandIndex: 1-based band; 0 (default) reads band 1 and warns when the raster has others to
 *   choose from (not for a 2-band raster whose band 2 is an alpha band). An alpha band GDAL
 *   takes as no mask (of other samples than Byte or UInt16, or in another place than the last
 *   of 2 or 4 bands), where nothing else masks the band read, is warned about: its
 *   transparent cells are read as heights.
 *   A band with a colour table (classes, a scanned map) or a picture's colour channel (Red,
 *   Green, ...) is read as heights all the same, with a warning.
 * - SubWindow: (x offset, y offset, columns, rows) in full-resolution pixels of the file,
 *   GDAL's convention (offsets from the top-left corner, like `gdal_translate -srcwin`);
 *   columns or rows of 0 extend to the raster edge.
 * - OverviewLevel: read GDAL overview k instead of the full resolution (0 = the first in the
 *   file's order, usually the finest, as `gdal_translate -ovr 0`); -1 (default) reads full
 *   resolution.
 * - Decimation: an integer factor f >= 1; each output cell is the mean of the valid cells of an
 *   f x f block (nodata ignored; all-nodata blocks stay nodata); a partial block at the end
 *   of the file's columns or rows is dropped (the east or south edge; the north one for a
 *   south-up raster, whose file rows run north), with a warning naming the columns and rows
 *   left out when the SubWindow reaches them. Applied to the overview level; the blocks
 *   align to its top-left corner (its first row and column in the file), not to the
 *   SubWindow's, which gets every block it touches, so that the windows of one raster read
 *   cells of one grid. A global DEM (360 degrees of longitude) read across its
 *   width by a factor that does not divide its columns then spans less, so its east and west
 *   edges no longer join (vtkApertureGeoreference::WrapsAround): a warning says so and names
 *   the dividing factors nearest.
 * - OverrideCRS: a CRS (WKT, "EPSG:xxxx", PROJ string) used instead of the file's.
 * - MemoryLimit: the most bytes one update may allocate for the output and one of the file's
 *   blocks (which GDAL reads whole: a compressed raster stored as one strip is all one block);
 *   0 (default) means the memory the process may use: the machine's physical memory, or its
 *   control group's limit where lower (vtkApertureSkyVisibility::GetUsableMemory).
 * - MetresPerElevationUnit: metres per elevation unit, for a file whose unit is missing or
 *   wrong; 0 (default): the file's. A band without a unit in a projected CRS in feet warns
 *   (such DEMs' heights are often feet: read as metres, their slopes would be 3.28 times too
 *   steep); an unknown unit warns; both are read as metres.
 *
 * The reader honours the pipeline's update extent: a sub-extent request reads only those rows
 * and columns from the file.
 *
 * Errors (vtkErrorMacro, failed update, empty output): a missing file (a URL, which GDAL reads as
 * /vsicurl/URL, is named as such; a network path that leads nowhere too), a named pipe or a socket
 * (GDAL seeks in its files; its open of a pipe would wait for a writer), a file the process may
 * not read (the system's reason: "Permission denied"), a file GDAL cannot open, a
 * band that does not exist or holds complex numbers, no georeference (no geotransform, or ground
 * control points only), a rotated (its far edges moved by more than a thousandth of a cell:
 * less is read as north-up) or mirrored geotransform, one with a pixel size of 0, or one
 * whose grid reaches beyond the range of doubles, no CRS (without OverrideCRS), a band scale of 0,
 * NaN or infinity or an offset of NaN or infinity, a scale and offset that take samples beyond the
 * float range, a negative, NaN or infinite MetresPerElevationUnit, fewer than 2 x 2 output cells, a
 * whole raster of nodata, an output (with a block of the file) larger than MemoryLimit, and an
 * output the process cannot allocate (out of memory, e.g. under `ulimit -v`).
 * A warning GDAL gives while reading the samples (a truncated JPEG's "Premature end of JPEG
 * file", its missing rows filled with grey) says the values are damaged: the first is passed on
 * as a vtkWarning naming the file, and the output is made.
 *
 * @sa vtkApertureDEMWriter vtkApertureGeoreference vtkApertureTerrainMesh
 */
#ifndef vtkApertureDEMReader_h
#define vtkApertureDEMReader_h

#include "ApertureIOModule.h" // for export macro
#include "vtkImageAlgorithm.h"

class APERTUREIO_EXPORT vtkApertureDEMReader : public vtkImageAlgorithm
{
public:
  static vtkApertureDEMReader* New();
  vtkTypeMacro(vtkApertureDEMReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The raster to read: a path, or any GDAL dataset name (/vsizip/..., a subdataset such as
   *  NETCDF:"f.nc":z or GTIFF_DIR:2:f.tif). A file of several grids and no band of its own (a
   *  netCDF or HDF file) is an error naming its subdatasets. */
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

  ///@{
  /** 1-based band index; 0 (default) = band 1, with a warning if the raster has others (see
   *  above). */
  vtkSetClampMacro(BandIndex, int, 0, VTK_INT_MAX);
  vtkGetMacro(BandIndex, int);
  ///@}

  ///@{
  /** Subwindow (x offset, y offset, columns, rows) in full-resolution file pixels from the
   *  top-left corner; columns/rows 0 extend to the edge. Default (0, 0, 0, 0) = everything. */
  vtkSetVector4Macro(SubWindow, int);
  vtkGetVector4Macro(SubWindow, int);
  ///@}

  /** The extent of the output grid's cells that cover a window (x offset, y offset, columns,
   *  rows; 0 columns or rows: to the edge) of full-resolution pixels, as SubWindow gives one,
   *  after UpdateInformation: for asking a filter downstream for a window of a grid read whole
   *  (vtkApertureSkyVisibility then reads the window and its halo and computes the window's
   *  cells): the cells a SubWindow of the same window would read, as Decimation's blocks align
   *  to the raster. False, with an error, when the window is not inside the raster or covers
   *  no cell of the grid (only a dropped partial block, or outside the SubWindow). */
  bool GetWindowExtent(int xoff, int yoff, int xsize, int ysize, int extent[6]);

  ///@{
  /** GDAL overview level to read (0-based); -1 (default) = full resolution. */
  vtkSetClampMacro(OverviewLevel, int, -1, VTK_INT_MAX);
  vtkGetMacro(OverviewLevel, int);
  ///@}

  ///@{
  /** Block-mean decimation factor, >= 1 (default 1 = none). */
  vtkSetClampMacro(Decimation, int, 1, VTK_INT_MAX);
  vtkGetMacro(Decimation, int);
  ///@}

  ///@{
  /** Whether a warning names the cells that decimation's partial blocks leave out where the
   *  SubWindow reaches them (default on). A caller that reads the whole grid for a window of
   *  its own (with a halo around it) turns it off and asks a reader with that window. */
  vtkSetMacro(PartialBlockWarning, bool);
  vtkGetMacro(PartialBlockWarning, bool);
  vtkBooleanMacro(PartialBlockWarning, bool);
  ///@}

  ///@{
  /** CRS to use instead of the file's (WKT, "EPSG:xxxx", PROJ string); empty = the file's. */
  vtkSetStringMacro(OverrideCRS);
  vtkGetStringMacro(OverrideCRS);
  ///@}

  ///@{
  /** Largest output one update may allocate, bytes; 0 (default) = the memory the process may
   *  use (physical, or its control group's limit). */
  vtkSetClampMacro(MemoryLimit, vtkTypeInt64, 0, VTK_TYPE_INT64_MAX);
  vtkGetMacro(MemoryLimit, vtkTypeInt64);
  ///@}

  ///@{
  /** Metres per elevation unit of the file (after the band's scale and offset), overriding its
   *  own unit: 0.3048 for feet, 1200/3937 for US survey feet; 0 (default): the file's unit.
   *  Beyond (0, 10000] the update fails. */
  vtkSetMacro(MetresPerElevationUnit, double);
  vtkGetMacro(MetresPerElevationUnit, double);
  ///@}

  /** Metres per unit of an elevation unit's name as bands carry them (case ignored): 1 for
   *  "m", "metre", "meters", ...; 0.001, 0.01, 0.1 and 1000 for "mm", "cm", "dm", "km" and
   *  their names ("centimetres", "centimeter", ...); 0.3048 for "ft", "foot", "feet",
   *  "international foot"; 1200/3937 for "US survey foot", "us-ft", "ftUS", "foot_us", ...; 0
   *  for a name it does not know, and for "" or null. The reader reads a band's unit with it. */
  static double GetMetresPerUnit(const char* name);

  ///@{
  /** Valid after UpdateInformation(): the metres per elevation unit applied, and where it came
   *  from ("MetresPerElevationUnit", "the band's unit 'ft'", "the CRS's height unit 'US survey
   *  foot'", "none in the file: metres"). */
  vtkGetMacro(ElevationUnitRead, double);
  const char* GetElevationUnitSource();
  ///@}

  ///@{
  /** Facts about the file, valid after UpdateInformation(): GDAL driver short name, raster
   *  size in full-resolution pixels, band count, the band read, its nodata value, and whether
   *  the file is south-up (positive pixel height: its first row is its southern one; the
   *  output is north-up either way) ("", 0 and false while no file has been read, or when the
   *  last one could not be opened). BlockBytes: the bytes of one block of the band (or
   *  overview) read, which GDAL decompresses whole and MemoryLimit counts beside the output
   *  (a caller reading in strips under a limit leaves it that room). */
  const char* GetDriverName();
  vtkGetVector2Macro(RasterSize, int);
  vtkGetMacro(NumberOfBands, int);
  vtkGetMacro(BandRead, int);
  vtkGetMacro(HasNoDataValue, bool);
  vtkGetMacro(NoDataValue, double);
  vtkGetMacro(SouthUp, bool);
  vtkGetMacro(BlockBytes, double);
  ///@}

  ///@{
  /** The files GDAL reads for the DEM (GDALGetFileList), valid after UpdateInformation(): the
   *  file itself first, then a VRT's sources, sidecars (.aux.xml, .ovr, world files), a
   *  format's other parts; names as GDAL gives them (relative names as given). None when no
   *  file is open or GDAL lists none (its /vsimem/ datasets may not); GetFile returns null for
   *  an index out of range. A caller writing next to the DEM checks its outputs against
   *  these, not just FileName: writing over a VRT's source would change the DEM being read.
   *  (Listed when first asked after an update, opening the file again.) */
  int GetNumberOfFiles();
  const char* GetFile(int index);
  ///@}

protected:
  vtkApertureDEMReader();
  ~vtkApertureDEMReader() override;

  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  /** RequestInformation's work; RequestInformation empties the output when it fails (VTK
   *  then runs no RequestData, which would: the last file's image stayed there). */
  int ReadInformation(vtkInformationVector* outputVector);
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  /** RequestData's work; RequestData turns a failed allocation in it into an error. */
  int RunRequestData(vtkInformationVector* outputVector);

  char* FileName;
  int BandIndex;
  int SubWindow[4];
  int OverviewLevel;
  int Decimation;
  bool PartialBlockWarning;
  char* OverrideCRS;
  vtkTypeInt64 MemoryLimit;
  double MetresPerElevationUnit;

  int RasterSize[2];
  int NumberOfBands;
  int BandRead;
  bool HasNoDataValue;
  double NoDataValue;
  bool SouthUp;
  double BlockBytes = 0.0;
  double ElevationUnitRead;

private:
  vtkApertureDEMReader(const vtkApertureDEMReader&) = delete;
  void operator=(const vtkApertureDEMReader&) = delete;

  struct Internals;
  Internals* Impl;
};

#endif
