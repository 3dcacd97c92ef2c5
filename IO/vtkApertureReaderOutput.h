// SPDX-License-Identifier: BSD-3-Clause
// Private to Aperture::IO: the readers' (vtkApertureDEMReader, vtkApertureEXRReader) output
// after a failed RequestInformation.
#ifndef vtkApertureReaderOutput_h
#define vtkApertureReaderOutput_h

#include "vtkImageData.h"
#include "vtkInformationVector.h"

/** `ok`, the result of a reader's RequestInformation work; when it failed, the output image is
 *  emptied first: VTK then runs no RequestData (which would), and the last file's image stayed
 *  in the output of an update that said it failed. */
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
