// SPDX-License-Identifier: BSD-3-Clause
// Private to Aperture::IO: the strip loop of the writers' StripRows (vtkApertureDEMWriter,
// vtkApertureEXRWriter).
#ifndef vtkApertureStripDriver_h
#define vtkApertureStripDriver_h

#include "vtkApertureElevation.h" // (vtkApertureExtentInside)

#include "vtkAlgorithm.h"
#include "vtkAlgorithmOutput.h"
#include "vtkCommand.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkType.h"

#include <algorithm>
#include <string>

/**
 * The extent a writer writes of its `input` at once (not in strips): its pipeline's whole
 * extent (`info`, the input's information; may be null) where the data holds that and more,
 * as VTK's writers write (vtkImageClip with ClipData off passes all of its input on, beyond
 * the clip), else the data's own extent.
 */
inline void vtkApertureWrittenExtent(vtkImageData* input, vtkInformation* info, int ext[6])
{
  const int none[6] = { 0, -1, 0, -1, 0, -1 };
  std::copy(none, none + 6, ext);
  if (!input)
  {
    return;
  }
  input->GetExtent(ext);
  int whole[6];
  if (info && info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
    if (vtkApertureExtentInside(whole, ext))
    {
      std::copy(whole, whole + 6, ext);
    }
  }
}

/**
 * The rows a writer's WriteStrip(strip) writes, from `next` (the next row of `whole` not yet
 * written, north first) down to `first` (set here): down to the strip's southern row, in
 * whole multiples of `multiple` rows unless that reaches whole[2]. False after reporting
 * (on `writer`, naming `path` and `unit`, what `multiple` rows are of the file) a strip that
 * does not hold the next row and every column of `whole`, one that holds fewer than
 * `multiple` rows short of the last, or a file whose rows are all written.
 */
inline bool vtkApertureStripRows(vtkObject* writer, vtkImageData* strip, const int whole[6],
  int next, int multiple, const char* unit, const std::string& path, int& first)
{
  int ext[6] = { 0, -1, 0, -1, 0, -1 };
  if (strip)
  {
    strip->GetExtent(ext);
  }
  if (next < whole[2])
  {
    vtkErrorWithObjectMacro(writer, << "every row of '" << path << "' is written already");
    return false;
  }
  if (ext[0] > whole[0] || ext[1] < whole[1] || ext[2] > next || ext[3] < next)
  {
    vtkErrorWithObjectMacro(writer, << "the strip's extent (" << ext[0] << ".." << ext[1] << ", "
                                    << ext[2] << ".." << ext[3] << ") does not hold row " << next
                                    << " of columns " << whole[0] << " to " << whole[1]
                                    << ", the next of '" << path << "'");
    return false;
  }
  first = std::max(ext[2], whole[2]);
  if (first > whole[2])
  {
    first = next + 1 - (next - first + 1) / multiple * multiple;
    if (first > next)
    {
      vtkErrorWithObjectMacro(writer, << "a strip must hold " << multiple << " rows (" << unit
                                      << " of '" << path << "') or reach the last row "
                                      << whole[2] << "; this one holds rows " << ext[2] << " to "
                                      << next);
      return false;
    }
  }
  return true;
}

/**
 * Whether a file written in strips is complete: no strip failed and every row of `whole` was
 * written (`next`, the next row, below whole[2]). Otherwise false, after reporting (on
 * `writer`, naming `path`) the rows never written, unless a strip failed (reported then) or
 * `writer` was aborted.
 */
inline bool vtkApertureStripsComplete(
  vtkAlgorithm* writer, bool failed, int next, const int whole[6], const std::string& path)
{
  if (failed)
  {
    return false;
  }
  if (next < whole[2])
  {
    return true;
  }
  if (!writer->GetAbortExecute())
  {
    vtkErrorWithObjectMacro(writer, << "rows " << whole[2] << " to " << next << " of '" << path
                                    << "' were not written; the file is removed");
  }
  return false;
}

/**
 * Update the producer of `writer`'s input for strips of `rows` image rows (rounded up to a
 * multiple of `multiple`) of its whole extent, north (the files' first rows) first, and hand
 * each to the writer: `writer.BeginStrips(strip, whole)` with the first, then
 * `writer.WriteStrip(strip)` with every one, and `writer.EndStrips()` after the last, or
 * `writer.AbandonStrips()` after a failure. Strips are asked for from the writer's next row
 * (`writer.GetNextStripRow()`), so a producer giving more rows than asked (an image set as
 * input data) is written as it comes.
 *
 * The producer is driven directly (an Update with an UPDATE_EXTENT per strip) instead of
 * through CONTINUE_EXECUTING: with that, an upstream failing mid-way leaves VTK 9.1's executive
 * looping forever. A producer whose ReleaseDataFlag is on gets each strip released once
 * written. Returns 1 when every strip was written; 0 after reporting the failure. `path`, the
 * writer's file name, is not empty: the writers' Write() refuses a missing one first.
 */
template <class Writer>
int vtkApertureWriteInStrips(Writer* writer, int rows, int multiple, const char* path)
{
  if (writer->GetNumberOfInputConnections(0) < 1)
  {
    vtkErrorWithObjectMacro(writer, << "no input to write");
    return 0;
  }
  vtkAlgorithmOutput* connection = writer->GetInputConnection(0, 0);
  vtkAlgorithm* producer = connection->GetProducer();
  const int port = connection->GetIndex();
  writer->SetAbortExecute(0);
  producer->UpdateInformation();
  int whole[6];
  vtkInformation* info = producer->GetOutputInformation(port);
  if (!info || !info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    vtkErrorWithObjectMacro(writer, << "the input has no whole extent to write in strips (see "
                                    << "its error)");
    return 0;
  }
  info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  if (whole[1] < whole[0] || whole[3] < whole[2])
  {
    vtkErrorWithObjectMacro(writer, << "no input image to write to '" << path << "'");
    return 0;
  }
  const vtkTypeInt64 step =
    std::max<vtkTypeInt64>(1, (static_cast<vtkTypeInt64>(rows) + multiple - 1) / multiple) *
    multiple;
  writer->InvokeEvent(vtkCommand::StartEvent, nullptr);
  bool ok = true, begun = false;
  for (int next = whole[3]; ok && next >= whole[2]; next = writer->GetNextStripRow())
  {
    const int j0 = static_cast<int>(std::max<vtkTypeInt64>(whole[2], next - step + 1));
    const int ext[6] = { whole[0], whole[1], j0, next, whole[4], whole[5] };
    vtkNew<vtkInformationVector> requests;
    requests->SetNumberOfInformationObjects(producer->GetNumberOfOutputPorts());
    requests->GetInformationObject(port)->Set(
      vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ext, 6);
    // (a failed update has reported its error; rows j0..next are image rows, south up)
    vtkImageData* strip = producer->Update(port, requests)
      ? vtkImageData::SafeDownCast(producer->GetOutputDataObject(port))
      : nullptr;
    if (!strip)
    {
      vtkErrorWithObjectMacro(writer, << "the input did not produce rows " << j0 << " to " << next
                                      << " of " << whole[2] << " to " << whole[3] << " for '"
                                      << path << "'");
      ok = false;
      break;
    }
    if (!begun)
    {
      ok = begun = writer->BeginStrips(strip, whole) != 0;
    }
    ok = ok && writer->WriteStrip(strip) != 0;
    // a producer whose data is to be released once used (its ReleaseDataFlag) holds no strip
    // while the next is computed (a shallow copy would keep the arrays of its input alive)
    auto* executive = vtkDemandDrivenPipeline::SafeDownCast(producer->GetExecutive());
    if (executive && executive->GetReleaseDataFlag(port))
    {
      strip->ReleaseData();
    }
  }
  if (begun && ok)
  {
    ok = writer->EndStrips() != 0;
  }
  else if (begun)
  {
    writer->AbandonStrips(); // (the failure is reported)
  }
  writer->InvokeEvent(vtkCommand::EndEvent, nullptr);
  return ok ? 1 : 0;
}

#endif
// VTK-HeaderTest-Exclude: vtkApertureStripDriver.h
