// SPDX-License-Identifier: BSD-3-Clause
// Test helpers for the writers' strips: a source of the sub-extents of an image, a noisy
// georeferenced image, an abort.
#ifndef ApertureStripSource_h
#define ApertureStripSource_h

#include "ApertureTestRasters.h"
#include "vtkApertureGeoreference.h"

#include "vtkExecutive.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageAlgorithm.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTestErrorObserver.h"
#include "vtkWriter.h"

#include <algorithm>
#include <string>
#include <vector>

namespace
{
// A source of the sub-extents of an image (as vtkApertureDEMReader and the sky filter produce
// them), recording each extent asked for, and failing when asked for rows below FailBelow.
class StripSource : public vtkImageAlgorithm
{
public:
  static StripSource* New();
  vtkTypeMacro(StripSource, vtkImageAlgorithm);
  vtkSmartPointer<vtkImageData> Image;
  std::vector<std::vector<int>> Requests;
  int FailBelow = -1;

protected:
  StripSource() { this->SetNumberOfInputPorts(0); }
  int RequestInformation(
    vtkInformation*, vtkInformationVector**, vtkInformationVector* out) override
  {
    vtkInformation* info = out->GetInformationObject(0);
    info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), this->Image->GetExtent(), 6);
    info->Set(vtkDataObject::ORIGIN(), this->Image->GetOrigin(), 3);
    info->Set(vtkDataObject::SPACING(), this->Image->GetSpacing(), 3);
    info->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
    return 1;
  }
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out) override
  {
    vtkInformation* info = out->GetInformationObject(0);
    int ext[6], whole[6];
    info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ext);
    this->Image->GetExtent(whole);
    this->Requests.emplace_back(ext, ext + 6);
    if (this->FailBelow >= 0 && ext[2] < this->FailBelow)
    {
      vtkErrorMacro(<< "asked for row " << ext[2]);
      return 0;
    }
    vtkImageData* output = vtkImageData::GetData(info);
    output->SetExtent(ext);
    output->GetFieldData()->PassData(this->Image->GetFieldData());
    vtkPointData* pd = this->Image->GetPointData();
    for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
    {
      vtkDataArray* src = pd->GetArray(a);
      vtkSmartPointer<vtkDataArray> dst = vtk::TakeSmartPointer(src->NewInstance());
      dst->SetName(src->GetName());
      dst->SetNumberOfComponents(src->GetNumberOfComponents());
      dst->SetNumberOfTuples(output->GetNumberOfPoints());
      vtkIdType k = 0;
      for (int j = ext[2]; j <= ext[3]; ++j)
      {
        for (int i = ext[0]; i <= ext[1]; ++i)
        {
          dst->SetTuple(k++, (j - whole[2]) * (whole[1] - whole[0] + 1) + (i - whole[0]), src);
        }
      }
      output->GetPointData()->AddArray(dst);
    }
    return 1;
  }
};
vtkStandardNewMacro(StripSource);

// The errors of writer->Write() (which must return 0) from `source` failing below row
// `failBelow` (its own error, and the executive's, are caught and not printed).
inline std::string FailingWrite(vtkWriter* writer, StripSource* source, int failBelow)
{
  source->FailBelow = failBelow;
  writer->SetInputConnection(source->GetOutputPort());
  vtkNew<vtkTest::ErrorObserver> errors, sourceErrors, executiveErrors;
  writer->AddObserver(vtkCommand::ErrorEvent, errors);
  source->AddObserver(vtkCommand::ErrorEvent, sourceErrors);
  source->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, executiveErrors);
  AP_CHECK(writer->Write() == 0);
  AP_CHECK_CONTAINS(sourceErrors->GetErrorMessage(), "asked for row");
  source->FailBelow = -1;
  source->RemoveObservers(vtkCommand::ErrorEvent);
  source->GetExecutive()->RemoveObservers(vtkCommand::ErrorEvent);
  return errors->GetErrorMessage();
}

// An nx x ny image (point array `name`, the active scalars) of values that do not compress to
// nothing: aptest::NoisyRamp(nx, ny, seed, noise); cells of 30 m from (300015, 5000015) in
// EPSG:32633.
inline vtkSmartPointer<vtkImageData> NoisyImage(
  int nx, int ny, unsigned seed, float noise, const char* name)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, 1);
  image->SetOrigin(300015.0, 5000015.0, 0.0);
  image->SetSpacing(30.0, 30.0, 1.0);
  vtkNew<vtkFloatArray> z;
  z->SetName(name);
  const std::vector<float> values = aptest::NoisyRamp(nx, ny, seed, noise);
  z->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  std::copy(values.begin(), values.end(), z->GetPointer(0));
  image->GetPointData()->SetScalars(z);
  vtkNew<vtkApertureGeoreference> geo;
  geo->SetCRS("EPSG:32633");
  geo->AttachToImage(image);
  return image;
}

// Make `algorithm` abort at its first progress event.
inline void AbortOnProgress(vtkAlgorithm* algorithm)
{
  vtkNew<vtkCallbackCommand> abort;
  abort->SetCallback([](vtkObject* caller, unsigned long, void*, void*) {
    static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
  });
  algorithm->AddObserver(vtkCommand::ProgressEvent, abort);
}
}

#endif
