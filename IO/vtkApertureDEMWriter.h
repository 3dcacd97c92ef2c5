// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkApertureDEMWriter
 * @brief   Write point arrays of a DEM image to a georeferenced GeoTIFF, one band per component.
 *
 * Input: a 2-D vtkImageData following vtkApertureGeoreference's conventions (origin and
 * spacing in CRS units, `CRS` in the field data). The GeoTIFF gets the same georeference
 * (geotransform from the image geometry, north-up; the CRS from the field data; without a CRS
 * the file is written without one and a warning says so, while a CRS that cannot be used, or a
 * grid it cannot place, is an error; an image whose origin and spacing are VTK's defaults while
 * its field data's GeoTransform describes another grid, an image made by hand whose geometry
 * was never set, is written as it is with a warning:
 * vtkApertureGeoreference::GetDefaultGeometryWarning). Of a compound CRS (horizontal +
 * vertical) the horizontal part is written: GDAL would give every band the vertical part's
 * height unit, so that a sky-view factor read as feet, and elevations, which
 * vtkApertureDEMReader gives in metres, were converted again on reading.
 *
 * Bands: every point array named in ArrayNames, in that order (all numeric point arrays, in the
 * image's order, when the list is empty; arrays that are not numeric or have no name, which a
 * band's description needs, are then skipped). A one-component array is one band described by
 * its name; an array of c > 1 components gives c bands described `<name>_<component name>`,
 * or `<name>_<k>` where the component has no name.
 * Band metadata added with AddBandMetadata is attached to the bands whose description starts
 * with the given array name; an item UNITS also sets GDAL's band unit (what gdalinfo and QGIS
 * show), unless it is "1" (a ratio). The array named Elevation (heights in metres, as the
 * reader gives them and the filters take them) gets GDAL's band unit "metre".
 *
 * Samples: Float32 bands, or Float64 when any written array is double. NaN cells are nodata:
 * written as NoDataValue (default NaN), which every band declares as its nodata value.
 * Compression: DEFLATE with the floating-point predictor, tiled 256 x 256 (a raster of fewer
 * rows: its rows rounded up to 16; one of fewer columns is stored in strips of 256 rows
 * instead), BigTIFF when needed;
 * Compression may name another GeoTIFF codec that keeps floating-point samples exactly (NONE,
 * LZW, PACKBITS, ZSTD, LZMA, LERC, LERC_DEFLATE, LERC_ZSTD, where GDAL offers them),
 * CompressionLevel sets its level (default 1, the fastest). Tiles are compressed on
 * NumberOfThreads threads (GDAL's NUM_THREADS; the file's bytes do not depend on it), LZMA on
 * two at least (GDAL 3.6 stores its tiles uncompressed on one).
 *
 * The file is written aside (a hidden temporary file in the same folder) and renamed into
 * place when complete, so a failed or aborted write leaves neither a partial file nor a damaged
 * earlier version behind, as the EXR writer's. The earlier file's GDAL sidecars (.aux.xml with
 * its statistics, .ovr with its overviews, .msk) are then removed, as GDAL's own Create does:
 * GDAL would read them with the new file (a warning names one that cannot be).
 *
 * Errors (vtkErrorMacro, nothing left behind): no file name, a file name that names something
 * other than a file (a folder, a device such as /dev/null, a pipe: left as it is), a file this
 * process may not write (read-only: left as it is, though its folder would take the rename), an
 * input that is not 2-D, a grid no geotransform can say (a non-finite origin, a spacing that is
 * not positive and finite, edges beyond the range of doubles, a rotated or mirrored direction
 * matrix), a named array that does not exist or is not numeric, a codec GDAL does not offer
 * or one that cannot store floating-point samples (JPEG, WEBP, the CCITT ones), a compression
 * level outside the codec's range, or GDAL failing to create or write (with "the disk is full"
 * added when under 1 MiB is left beside the partial file, which GDAL does not say).
 * @sa vtkApertureDEMReader vtkApertureGeoreference
 */
#ifndef vtkApertureDEMWriter_h
#define vtkApertureDEMWriter_h

#include "ApertureIOModule.h" // for export macro
#include "vtkWriter.h"

#include <string> // for std::string

class vtkImageData;

class APERTUREIO_EXPORT vtkApertureDEMWriter : public vtkWriter
{
public:
  static vtkApertureDEMWriter* New();
  vtkTypeMacro(vtkApertureDEMWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The GeoTIFF to write (replaced if it exists, keeping its permissions; a symbolic link
   *  is written through: its target replaced, the link kept). */
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

  ///@{
  /** Point arrays to write, in order (a name added again is ignored); empty (default) =
   *  every numeric point array. */
  void AddArrayName(const char* name);
  void ClearArrayNames();
  int GetNumberOfArrayNames();
  const char* GetArrayName(int i);
  ///@}

  ///@{
  /** GeoTIFF COMPRESS option (case-insensitive), one of the lossless codecs above. Default
   * "DEFLATE". */
  vtkSetStringMacro(Compression);
  vtkGetStringMacro(Compression);
  ///@}

  ///@{
  /** Compression level: DEFLATE's ZLEVEL (1-12), ZSTD's ZSTD_LEVEL (1-22) or LZMA's
   * LZMA_PRESET (1-9; 6 to 9 compress alike); -1 = GDAL's default for the codec (6, 9, 6).
   * Default 1, the fastest: with the floating-point predictor, DEFLATE level 6 makes float
   * files under 1% smaller than level 1 and takes 1.2 to 1.6 times as long. Ignored by codecs
   * without levels (LZW, NONE, ...); a level outside the codec's range is an error when
   * writing. */
  vtkSetMacro(CompressionLevel, int);
  vtkGetMacro(CompressionLevel, int);
  ///@}

  /** Whether GDAL's GeoTIFF driver offers Compression, it keeps floating-point samples, and
   * CompressionLevel is within its range; otherwise false, with an error naming the problem.
   * Writing checks the same first; callers with long pipelines ahead of the writer call this
   * to fail early. */
  bool CheckCompression();

  /** Whether a GeoTIFF codec (case ignored) has levels that CompressionLevel sets: DEFLATE,
   *  ZSTD and LZMA; false for the others and for null. */
  static bool HasCompressionLevel(const char* codec);

  ///@{
  /** The nodata value the bands declare, and NaN cells are written as: NaN (default), or a
   * finite number for tools that take no NaN (an ASCII grid: gdaldem's float outputs use
   * -9999). A value a product may take (0 for an EdgeTruncated band) makes such cells read as
   * nodata too: the caller's choice. Float32 bands declare the value rounded to float, which
   * their cells hold (0.1 as 0.100000001490116; -3.4028235e38 as -FLT_MAX). A value that does
   * not round to a finite Float32 (nor, double arrays, is a finite Float64): an error when
   * writing. */
  vtkSetMacro(NoDataValue, double);
  vtkGetMacro(NoDataValue, double);
  ///@}

  ///@{
  /** Threads compressing tiles (GDAL's NUM_THREADS): 0 (default) = all the cores this
   *  process may use (vtkApertureSkyVisibility::GetUsableCores), which also cap larger
   *  values; 1 = on the writing thread alone. Negative values are clamped to 0. Has no effect
   *  without compression. */
  vtkSetClampMacro(NumberOfThreads, int, 0, VTK_INT_MAX);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /** Rows per update when > 0: Write() asks its input for strips of this many rows (rounded
   * up to whole 256-row tiles), north first, and writes each into the file before asking for
   * the next, so that a pipeline whose stages produce sub-extents (vtkApertureDEMReader,
   * vtkApertureSkyVisibility with its halo) holds one strip at a time. The file has the same
   * bands, values, georeference and metadata as with 0 (default: the whole image in one
   * update); a strip the input fails to produce is an error, and the file is discarded. When
   * the input's producer has its ReleaseDataFlag on, each strip is released once written. */
  vtkSetClampMacro(StripRows, int, 0, VTK_INT_MAX);
  vtkGetMacro(StripRows, int);
  ///@}

  /** Rows and columns of the file's square tiles (256; a raster of fewer rows has one row of
   * tiles, its rows rounded up to 16 high, and one of fewer columns strips of 256 rows instead
   * of tiles): strips of whole tile rows are written without rewriting a tile. */
  static int GetTileSize();

  /** Write the file (in strips when StripRows > 0); 1 on success, 0 after an error, which
   *  also sets GetErrorCode() (vtkErrorCode: NoFileNameError, CannotOpenFileError for a
   *  path that cannot be created or replaced, else UnknownError; NoError after success). */
  int Write() override;

  ///@{
  /**
   * Writing strips the caller produces itself (one pass of a pipeline feeding this writer and
   * a vtkApertureEXRWriter, say); Write() with StripRows takes the same steps.
   * - BeginStrips(image, whole) creates the file for the image rows and columns of `whole`
   *   (an extent in image indices), its bands and their types from `image`'s point arrays,
   *   its georeference from `image`'s origin, spacing and `CRS` (any strip of the image will
   *   do), and the metadata.
   * - WriteStrip(strip) writes the rows of `strip` that come next, north first: from row
   *   GetNextStripRow() (whole[3] at first) down to the strip's southern row, in whole 256-row
   *   tile rows unless that reaches whole[2] (rows beyond the last whole tile row are left for
   *   the next strip). The strip must hold every column of `whole` and the next row.
   * - EndStrips() closes the file. It is put in place only when every row was written without
   *   an error; otherwise it is discarded (with an error naming the rows missing, unless
   *   writing was aborted or an error was reported already).
   * - AbandonStrips() discards a file begun, quietly (for a caller that stops early).
   * Each returns 1 on success and 0 after reporting the problem (vtkErrorMacro), except that
   * WriteStrip keeps GDAL's reason for a failed write (a full disk: known only once GDAL gives
   * up) for EndStrips to report; after a failure only EndStrips() or AbandonStrips() is
   * useful. Progress events run over the rows of `whole`, and AbortExecute is checked, after
   * every tile row (256 rows) of every band.
   */
  int BeginStrips(vtkImageData* image, const int whole[6]);
  int WriteStrip(vtkImageData* strip);
  int EndStrips();
  void AbandonStrips();
  /** The next image row WriteStrip() writes (whole[2] - 1 once all are written). */
  int GetNextStripRow();
  ///@}

  ///@{
  /** Dataset metadata (key = value, the GeoTIFF's GDAL metadata domain), written with the file;
   *  a key added again replaces its value. What is added between BeginStrips and EndStrips is
   *  written by EndStrips (band metadata is not: it is written by BeginStrips). */
  void AddMetadata(const char* key, const char* value);
  /** Metadata for the bands of one array (all its components); the same array and key added
   *  again replaces the value. */
  void AddBandMetadata(const char* arrayName, const char* key, const char* value);
  void ClearMetadata();
  ///@}

  vtkImageData* GetInput();

protected:
  vtkApertureDEMWriter();
  ~vtkApertureDEMWriter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

  /** CheckCompression, returning GDAL's GTiff driver (a GDALDriverH; nullptr on failure,
   * reported) with the codec in upper case and the creation option of its level (nullptr: none
   * to set). */
  void* CheckCompression(std::string& codec, const char*& levelOption);

  /** Create the file for the image rows and columns of `whole` (bands, georeference and
   * metadata from `input`); false, reported, on failure (nothing left behind). */
  bool BeginFile(vtkImageData* input, const int whole[6]);
  /** Write image rows j0..j1 of every band from `input`, whose extent holds them; progress
   * runs over the rows of the file. False, reported by EndFile or here, on failure. */
  bool WriteRows(vtkImageData* input, int j0, int j1);
  /** Close the file; remove it unless ok and GDAL reported no failure. True when kept. */
  bool EndFile(bool ok);

  char* FileName;
  char* Compression;
  int CompressionLevel;
  double NoDataValue;
  int NumberOfThreads;
  int StripRows;

private:
  vtkApertureDEMWriter(const vtkApertureDEMWriter&) = delete;
  void operator=(const vtkApertureDEMWriter&) = delete;

  struct Internals;
  Internals* Impl;
};

#endif
