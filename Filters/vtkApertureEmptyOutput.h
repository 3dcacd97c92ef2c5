// SPDX-License-Identifier: BSD-3-Clause
// Internal (not installed, not wrapped): an image algorithm's output after a failed request
// (the readers', vtkApertureDEMReader and vtkApertureEXRReader, and the sky filter's).
#ifndef vtkApertureEmptyOutput_h
#define vtkApertureEmptyOutput_h

#include "vtkImageData.h"
#include "vtkInformationVector.h"

/** `ok`, the result of an algorithm's RequestInformation or RequestData work; when it failed,
 *  the output image is emptied first. Otherwise the last run's image stayed in the output of
 *  an update that said it failed: a reader's whole image after RequestInformation (VTK then
 *  runs no RequestData), its elevations (or RGB) after RequestData, and the sky filter's
 *  (vtkImageData::PrepareForNewData keeps the scalars). */
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
