// SPDX-License-Identifier: BSD-3-Clause
// Test helpers for the writers' strips: a source of the sub-extents of an image
// (aptest_source.hxx), a failing write, a noisy georeferenced image, an abort.
#ifndef ApertureStripSource_h
#define ApertureStripSource_h

#include "ApertureTestRasters.h"
#include "aptest_source.hxx"
#include "vtkApertureGeoreference.h"

#include "vtkExecutive.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkTestErrorObserver.h"
#include "vtkWriter.h"

#include <algorithm>
#include <string>
#include <vector>

namespace
{
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

// Append each progress value `algorithm` reports to *values.
inline void RecordProgress(vtkAlgorithm* algorithm, std::vector<double>* values)
{
  vtkNew<vtkCallbackCommand> record;
  record->SetClientData(values);
  record->SetCallback([](vtkObject* caller, unsigned long, void* client, void*) {
    static_cast<std::vector<double>*>(client)->push_back(
      static_cast<vtkAlgorithm*>(caller)->GetProgress());
  });
  algorithm->AddObserver(vtkCommand::ProgressEvent, record);
}

// Whether progress `values` run from 0 to 1 without going back.
inline bool ProgressFromZeroToOne(const std::vector<double>& values)
{
  return !values.empty() && values.front() == 0.0 && values.back() == 1.0 &&
    std::is_sorted(values.begin(), values.end());
}

// Make `algorithm` abort at its first progress event (lastOnly: at its last, progress 1).
inline void AbortOnProgress(vtkAlgorithm* algorithm, bool lastOnly = false)
{
  vtkNew<vtkCallbackCommand> abort;
  abort->SetCallback([](vtkObject* caller, unsigned long, void* last, void*) {
    auto* a = static_cast<vtkAlgorithm*>(caller);
    if (!last || a->GetProgress() >= 1.0)
    {
      a->SetAbortExecute(1);
    }
  });
  abort->SetClientData(lastOnly ? algorithm : nullptr); // (non-null: at the last event only)
  algorithm->AddObserver(vtkCommand::ProgressEvent, abort);
}
}

#endif
