// SPDX-License-Identifier: BSD-3-Clause
// Private to Aperture::IO: the readers' (vtkApertureDEMReader, vtkApertureEXRReader) output
// after a failed RequestInformation or RequestData.
#ifndef vtkApertureReaderOutput_h
#define vtkApertureReaderOutput_h

#include "vtkImageData.h"
#include "vtkInformationVector.h"

/** `ok`, the result of a reader's RequestInformation or RequestData work; when it failed, the
 *  output image is emptied first. Otherwise the last file's image stayed in the output of an
 *  update that said it failed: whole after RequestInformation (VTK then runs no RequestData),
 *  its elevations after RequestData (vtkImageData::PrepareForNewData keeps the scalars). */
inline int vtkApertureEmptyOutputUnless(int ok, vtkInformationVector* outputVector)
{
  vtkImageData* output = ok ? nullptr : vtkImageData::GetData(outputVector);
  if (output)
  {
    output->Initialize();
  }
  return ok;
}

#endif
