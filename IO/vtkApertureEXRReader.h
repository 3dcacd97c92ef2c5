// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkApertureEXRReader
 * @brief   Read a single-part scanline OpenEXR image as a 2-D vtkImageData of float point arrays.
 *
 * Output: a vtkImageData of the data window's columns x rows (extent starting at 0, one slice).
 * EXR scanline 0 is the top row of the picture and VTK row 0 the southern row of a DEM, so
 * scanline y becomes VTK row rows-1-y (one flip, here; vtkApertureEXRWriter makes the opposite
 * one). The data window's offset is not kept.
 *
 * Geometry: spacing 1 and origin 0, unless the header has the string attribute
 * `aperture:geotransform` (six comma-separated numbers, GDAL's north-up geotransform, as
 * vtkApertureEXRWriter writes it): then origin and spacing follow vtkApertureGeoreference's
 * conventions (origin at the centre of the south-west cell, CRS units). When the header has
 * `aperture:crs` (WKT), the output carries the field-data arrays `CRS` and `GeoTransform` (of
 * the output grid) exactly as vtkApertureGeoreference::AttachToImage leaves them.
 *
 * Arrays (vtkFloatArray, one per array below; HALF and UINT channels are converted to float,
 * UINT values above 2^24 losing precision; NaN stays NaN):
 * - The channels R, G, B, when all three exist, become one array `RGB` with components R, G, B,
 *   or `RGBA` with A as well. It is the active scalars.
 * - Channels that share the prefix before their last '.' (`Vector.E`, `Vector.N`) become one
 *   multi-component array named by the prefix, with the suffixes as component names: a group
 *   whose suffixes are all R, G, B (A), or all r, g, b (a), in a colour's order (a renderer's
 *   `diffuse.R`...), one whose suffixes are all numbers in their order (`v.2` before `v.10`),
 *   any other group in the header's (OpenEXR sorts channels by name: `k.20`, `k.3`, `k.x`).
 * - Every other channel becomes a one-component array named like the channel: a lone `a.b`,
 *   and the members of a group whose prefix is itself a channel name (`V` beside `V.x`, `V.y`
 *   gives three arrays `V`, `V.x`, `V.y`) or the name of the color array. Without RGB, the first
 *   array in header order is the active scalars.
 *
 * Metadata: every string attribute of the header except `type` (OpenEXR's storage kind), in
 * alphabetical order of keys, including `aperture:crs` and `aperture:geotransform`; valid after
 * UpdateInformation().
 *
 * Errors (vtkErrorMacro, failed update, empty output): no file name, a missing file, a named
 * pipe or socket (its open would wait for a writer), a file the process may not read (the
 * system's reason: "Permission denied"), a file that is not OpenEXR (or whose
 * header is damaged), a multi-part, tiled, deep scanline or deep tiled file (the message says
 * which), no channels or an empty data window, a channel that is subsampled (x or y sampling
 * other than 1), a data window larger than the machine's memory as float (a huge image or a
 * damaged header), an `aperture:geotransform` that is not a north-up
 * geotransform, an `aperture:crs` GDAL cannot parse, OpenEXR failing to decode the pixels (its
 * own message is included), and pixels the process cannot allocate (a huge or corrupt data
 * window; out of memory, with the size).
 *
 * Example:
 * @code
 * vtkNew<vtkApertureEXRReader> reader;
 * reader->SetFileName("slope.exr");
 * reader->Update();
 * vtkDataArray* slope = reader->GetOutput()->GetPointData()->GetArray("Slope");
 * const char* software = reader->GetMetadataValue("aperture:software");
 * @endcode
 *
 * @warning Uses only the OpenEXR C library (OpenEXRCore); one reader per thread. The whole
 * image is read on every update, whatever the requested extent.
 * @sa vtkApertureEXRWriter vtkApertureDEMReader vtkApertureGeoreference
 */
#ifndef vtkApertureEXRReader_h
#define vtkApertureEXRReader_h

#include "ApertureIOModule.h" // for export macro
#include "vtkImageAlgorithm.h"

class APERTUREIO_EXPORT vtkApertureEXRReader : public vtkImageAlgorithm
{
public:
  static vtkApertureEXRReader* New();
  vtkTypeMacro(vtkApertureEXRReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The OpenEXR file to read. */
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

  ///@{
  /** String attributes of the header (see above), valid after UpdateInformation(): their
   *  number, the key of attribute i (nullptr when i is out of range), and the value of a key
   *  (nullptr when the header has no such string attribute). */
  int GetNumberOfMetadata();
  const char* GetMetadataKey(int i);
  const char* GetMetadataValue(const char* key);
  ///@}

protected:
  vtkApertureEXRReader();
  ~vtkApertureEXRReader() override;

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

private:
  vtkApertureEXRReader(const vtkApertureEXRReader&) = delete;
  void operator=(const vtkApertureEXRReader&) = delete;

  struct Internals;
  Internals* Impl;
};

#endif
