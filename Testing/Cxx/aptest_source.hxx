// SPDX-License-Identifier: BSD-3-Clause
// A pipeline source for the module tests: any sub-extent of an image, as vtkApertureDEMReader
// produces them (it records each extent asked for, and can fail below a row).
#ifndef aptest_source_hxx
#define aptest_source_hxx

#include "vtkApertureGeoreference.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageAlgorithm.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include <vector>

namespace
{
// The sub-extents of Image (every point array, the field data); with PublishCRS, the image's
// CRS as pipeline information too (vtkApertureGeoreference::CRS_KEY, as the DEM reader
// publishes it, so that the sky filter can read a halo instead of the whole extent).
class StripSource : public vtkImageAlgorithm
{
public:
  static StripSource* New();
  vtkTypeMacro(StripSource, vtkImageAlgorithm);
  vtkSmartPointer<vtkImageData> Image;
  std::vector<std::vector<int>> Requests;
  int FailBelow = -1;
  bool PublishCRS = false;

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
    auto* crs = vtkStringArray::SafeDownCast(this->Image->GetFieldData()->GetAbstractArray(
      vtkApertureGeoreference::GetCRSArrayName()));
    if (this->PublishCRS && crs && crs->GetNumberOfValues() > 0)
    {
      info->Set(vtkApertureGeoreference::CRS_KEY(), crs->GetValue(0).c_str());
    }
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
}

#endif
