// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkApertureEXRWriter
 * @brief   Write point arrays of a 2-D image to a single-part scanline OpenEXR file, one channel
 *          per component.
 *
 * Input: a 2-D vtkImageData (one slice). Output: a single-part scanline OpenEXR image of the
 * image's columns x rows, data window and display window both (0, 0) - (columns-1, rows-1),
 * pixel aspect ratio 1.
 *
 * Orientation: VTK row 0 is the southern row of a DEM (STYLE.md, vtkApertureGeoreference);
 * EXR scanline 0 is the top row of the picture. Rows are flipped once, here: scanline y holds
 * VTK row rows-1-y, so the picture is north-up. vtkApertureEXRReader flips them back.
 *
 * Channels:
 * - The point arrays named with AddArrayName, in any order (all numeric point arrays when none
 *   is named; arrays that are not numeric or have no name are then skipped). A one-component
 *   array gives one channel named like the array; an array of c > 1 components gives c channels
 *   `<name>.<component name>`, or `<name>.<k>` (k = 0 .. c-1) where the component has no name.
 *   A '.' in a component name becomes '_': OpenEXR tools take the text before a channel's last
 *   '.' as its layer, so `HorizonAngles.az011.25` would be a channel `25` of a layer of its own,
 *   where `HorizonAngles.az011_25` is one of the layer `HorizonAngles` (and vtkApertureEXRReader
 *   reads the layer back as one array). OpenEXR stores channels sorted by name, whatever the
 *   order here.
 * - ColorArrayName: a 3- or 4-component array written as the standard channels R, G, B (and A),
 *   so image tools and renderers see an RGB(A) picture. It is not written again under its own
 *   name, even when it is also named with AddArrayName.
 * Samples are converted to 32-bit float (PixelType FLOAT, the default) or 16-bit half (HALF) in
 * every channel: doubles and integers above 2^24 lose precision in FLOAT; HALF keeps 11
 * significant bits (relative error <= 2^-11; below its smallest normal number, 6.1e-5, absolute
 * error <= 2^-25, 3e-8), rounds magnitudes below 65520 to its largest, 65504, and turns
 * larger ones into infinities. Finite samples written as infinities (beyond HALF's range, or
 * doubles beyond the floats') are counted per channel in a warning once the file is written.
 * NaN (Aperture's nodata) is written as NaN in both.
 *
 * Compression: lossless only, ZIP (default; 16 scanlines per block), ZIPS (1), RLE (1),
 * PIZ (32) or NONE; set it with the enum or its name. ZIP and ZIPS blocks are deflated by
 * libdeflate at CompressionLevel (OpenEXR's own format, which every OpenEXR reader decodes;
 * 2 to 3 times as fast as OpenEXR 3.1's zlib, files 0.2-0.5% larger at level 1). Blocks
 * are converted and compressed on NumberOfThreads threads and written in order (the file's
 * bytes do not depend on it).
 *
 * Header attributes (all of OpenEXR type string):
 * - AddMetadata(key, value): provenance and other free text, written as given (a later value
 *   for the same key replaces an earlier one).
 * - Georeference: when the image has a non-empty field-data array `CRS` (a vtkStringArray, as
 *   vtkApertureDEMReader and vtkApertureGeoreference::AttachToImage leave it), the writer takes
 *   the georeference with vtkApertureGeoreference::SetFromImage and writes
 *   `aperture:crs` (the CRS as WKT; of a compound CRS its horizontal part, as
 *   vtkApertureDEMWriter writes it: the values are no heights in its height unit) and
 *   `aperture:geotransform` (GDAL's geotransform of the
 *   written grid: west edge, cell width, 0, north edge, 0, minus the cell height; six numbers
 *   printed with %.17g and separated by commas, e.g. "300000,30,0,5000120,0,-30").
 *   These two are written after the metadata and replace metadata with the same keys.
 *   vtkApertureEXRReader restores the grid and the CRS from them. The grid written is the
 *   image's origin and spacing: when they are VTK's defaults while the field data's
 *   GeoTransform describes another grid (an image made by hand whose geometry was never set) a
 *   warning says so (vtkApertureGeoreference::GetDefaultGeometryWarning). Without a `CRS` array
 *   neither is written and the file is a plain picture.
 * Names longer than 31 characters (channels or keys) switch on OpenEXR's long-name support,
 * which readers older than OpenEXR 2.0 reject.
 *
 * The file is written through a temporary file in the same folder that replaces FileName only
 * when everything was written, so a failed write leaves neither a partial file nor a damaged
 * earlier version behind. The earlier file's GDAL sidecars (.aux.xml, .ovr, .msk) are then
 * removed, as GDAL's own Create does: GDAL would read them with the new file (a warning names
 * one that cannot be).
 *
 * Errors (vtkErrorMacro naming the file and the problem; nothing written): no file name, a file
 * name that names something other than a file (a folder, a device such as /dev/null, a pipe:
 * left as it is), a file this process may not write (read-only: left as it is), no input or an
 * input that is not 2-D, a named array that does not exist, is not numeric or does not have
 * one tuple per point, a color array that does not exist or has
 * neither 3 nor 4 components, two arrays giving the same channel name, nothing to write, a
 * `CRS` array with an unusable georeference (rotated direction matrix, non-positive spacing,
 * edges beyond the range of doubles, CRS GDAL cannot parse), and OpenEXR failing to create or
 * write the file (its own message is included). An unknown compression name is an error of
 * SetCompression(const char*), which then keeps the previous setting.
 *
 * Example:
 * @code
 * vtkNew<vtkApertureEXRWriter> writer;
 * writer->SetInputConnection(slope->GetOutputPort());
 * writer->SetFileName("slope.exr");
 * writer->AddArrayName("Slope");
 * writer->AddMetadata("aperture:software", "aperture 0.1");
 * writer->Write();
 * @endcode
 *
 * @warning Uses only the OpenEXR C library (OpenEXRCore); one writer per thread.
 * @sa vtkApertureEXRReader vtkApertureDEMWriter vtkApertureGeoreference
 */
#ifndef vtkApertureEXRWriter_h
#define vtkApertureEXRWriter_h

#include "ApertureIOModule.h" // for export macro
#include "vtkWriter.h"

#include <string> // for std::string

class vtkImageData;

class APERTUREIO_EXPORT vtkApertureEXRWriter : public vtkWriter
{
public:
  static vtkApertureEXRWriter* New();
  vtkTypeMacro(vtkApertureEXRWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** Sample types of the channels. */
  enum PixelTypes
  {
    FLOAT = 0, ///< 32-bit IEEE float
    HALF = 1   ///< 16-bit IEEE half
  };

  /** Lossless OpenEXR compressions (same values as OpenEXR's exr_compression_t). */
  enum CompressionTypes
  {
    NONE = 0,
    RLE = 1,
    ZIPS = 2,
    ZIP = 3,
    PIZ = 4
  };

  ///@{
  /** The OpenEXR file to write (replaced if it exists, keeping its permissions; a symbolic
   *  link is written through: its target replaced, the link kept). */
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

  ///@{
  /** Point arrays to write as channels, in any order (a name added again is ignored); empty
   *  (default) = every numeric point array. */
  void AddArrayName(const char* name);
  void ClearArrayNames();
  int GetNumberOfArrayNames();
  const char* GetArrayName(int i);
  ///@}

  ///@{
  /** A 3- or 4-component point array written as the channels R, G, B (, A); empty or nullptr
   *  (default) = none. */
  vtkSetStringMacro(ColorArrayName);
  vtkGetStringMacro(ColorArrayName);
  ///@}

  ///@{
  /** Sample type of every channel: FLOAT (default, 32 bit) or HALF (16 bit). */
  vtkSetClampMacro(PixelType, int, FLOAT, HALF);
  vtkGetMacro(PixelType, int);
  void SetPixelTypeToFloat() { this->SetPixelType(FLOAT); }
  void SetPixelTypeToHalf() { this->SetPixelType(HALF); }
  const char* GetPixelTypeAsString();
  ///@}

  ///@{
  /** Compression: NONE, RLE, ZIPS, ZIP (default) or PIZ, by enum or by name (any case). */
  vtkSetClampMacro(Compression, int, NONE, PIZ);
  vtkGetMacro(Compression, int);
  void SetCompression(const char* name);
  void SetCompressionToNone() { this->SetCompression(NONE); }
  void SetCompressionToRLE() { this->SetCompression(RLE); }
  void SetCompressionToZIPS() { this->SetCompression(ZIPS); }
  void SetCompressionToZIP() { this->SetCompression(ZIP); }
  void SetCompressionToPIZ() { this->SetCompression(PIZ); }
  const char* GetCompressionAsString();
  ///@}

  ///@{
  /** Deflate level of ZIP and ZIPS, 1 (default: the fastest) to 12 (the smallest files; the
   *  same format at every level, libdeflate's). Ignored by the other compressions. */
  vtkSetClampMacro(CompressionLevel, int, 1, 12);
  vtkGetMacro(CompressionLevel, int);
  ///@}

  ///@{
  /** Threads converting and compressing chunks of scanlines (vtkSMPTools' STDThread backend,
   *  as in vtkApertureSkyVisibility; one runs in the calling thread, and threads the system
   *  refuses to start are an error): 0 (default) = all the cores the process may use
   *  (vtkApertureSkyVisibility::GetUsableCores; they also cap larger values). The file's
   *  bytes do not depend on it. */
  vtkSetClampMacro(NumberOfThreads, int, 0, VTK_INT_MAX);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  /** Threads that converted and compressed the last write's chunks (0 before any). */
  vtkGetMacro(NumberOfThreadsUsed, int);

  ///@{
  /** Rows per update when > 0: Write() asks its input for strips of this many rows (rounded
   * up to a multiple of 32, so whole chunks of scanlines), north first, and writes each into
   * the file before asking for the next, so that a pipeline whose stages produce sub-extents
   * holds one strip at a time. The file has the same bytes as with 0 (default: the whole image
   * in one update); a strip the input fails to produce is an error, and no file is left. When
   * the input's producer has its ReleaseDataFlag on, each strip is released once written. */
  vtkSetClampMacro(StripRows, int, 0, VTK_INT_MAX);
  vtkGetMacro(StripRows, int);
  ///@}

  /** Write the file (in strips when StripRows > 0); 1 on success, 0 after an error, which
   *  also sets GetErrorCode() (vtkErrorCode: NoFileNameError, CannotOpenFileError for a
   *  path that cannot be created or replaced, else UnknownError; NoError after success). */
  int Write() override;

  ///@{
  /**
   * Writing strips the caller produces itself (one pass of a pipeline feeding this writer and
   * a vtkApertureDEMWriter, say); Write() takes the same steps.
   * - BeginStrips(image, whole) creates the file (a temporary one until EndStrips) for the
   *   image rows and columns of `whole` (an extent in image indices): its channels from
   *   `image`'s point arrays, its georeference from `image`'s origin, spacing and `CRS` (any
   *   strip of the image will do), and the metadata; the header is written.
   * - WriteStrip(strip) writes the rows of `strip` that come next, north first: from row
   *   GetNextStripRow() (whole[3] at first) down to the strip's southern row, in whole chunks
   *   of scanlines (1, 16 or 32 rows, by Compression) unless that reaches whole[2] (rows
   *   beyond the last whole chunk are left for the next strip). The strip must hold every
   *   column of `whole`, the next row, and the arrays the first strip had.
   * - EndStrips() completes the file and gives it its name when every row was written
   *   without an error; otherwise it leaves no file (and an earlier one of that name as it
   *   was), with an error naming the rows missing unless writing was aborted or an error was
   *   reported already.
   * - AbandonStrips() removes a file begun, quietly (for a caller that stops early).
   * Each returns 1 on success and 0 after reporting the problem (vtkErrorMacro); after a
   * failure only EndStrips() or AbandonStrips() is useful. Progress events run over the
   * chunks of `whole`, and AbortExecute is checked after every batch of chunks is compressed
   * and after each progress event, the last one too (an abort then discards the whole file).
   */
  int BeginStrips(vtkImageData* image, const int whole[6]);
  int WriteStrip(vtkImageData* strip);
  int EndStrips();
  void AbandonStrips();
  /** The next image row WriteStrip() writes (whole[2] - 1 once all are written). */
  int GetNextStripRow();
  ///@}

  ///@{
  /** String attributes of the header (key = value), written with the file. Keys are non-empty
   *  and at most 255 characters (another is an error here, and not added), and must not name
   *  one of OpenEXR's own attributes (channels, compression, dataWindow, ...: the Write fails,
   *  saying so). */
  void AddMetadata(const char* key, const char* value);
  void ClearMetadata();
  ///@}

  vtkImageData* GetInput();

protected:
  vtkApertureEXRWriter();
  ~vtkApertureEXRWriter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

  char* FileName;
  char* ColorArrayName;
  int PixelType;
  int Compression;
  int CompressionLevel;
  int NumberOfThreads;
  int NumberOfThreadsUsed;
  int StripRows;

private:
  vtkApertureEXRWriter(const vtkApertureEXRWriter&) = delete;
  void operator=(const vtkApertureEXRWriter&) = delete;

  struct Internals;
  Internals* Impl;

  // The channels of the first strip, or the same arrays of a later one; false, reported, when
  // the image lacks them.
  bool ResolveChannels(vtkImageData* input, const std::string& path);
};

#endif
