// SPDX-License-Identifier: BSD-3-Clause
#include "vtkApertureTerrainMesh.h"

#include "vtkApertureGeoreference.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "ap_grid.h"
#include "ap_mesh.h"

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/LocalCartesian.hpp>

#include <cmath>
#include <limits>
#include <vector>

vtkStandardNewMacro(vtkApertureTerrainMesh);

static_assert(sizeof(vtkIdType) == sizeof(int64_t), "the C core writes 64-bit vertex ids");

//------------------------------------------------------------------------------
vtkApertureTerrainMesh::vtkApertureTerrainMesh()
  : ElevationArrayName(nullptr)
  , VerticalExaggeration(1.0)
  , OutputPointsPrecision(SINGLE_PRECISION)
  , ComputeNormals(true)
  , GenerateTextureCoordinates(true)
{
  this->SetElevationArrayName("Elevation");
}

//------------------------------------------------------------------------------
vtkApertureTerrainMesh::~vtkApertureTerrainMesh()
{
  this->SetElevationArrayName(nullptr);
}

//------------------------------------------------------------------------------
int vtkApertureTerrainMesh::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

//------------------------------------------------------------------------------
int vtkApertureTerrainMesh::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!input || input->GetNumberOfPoints() == 0)
  {
    return 1; // empty in, empty out
  }

  // 1. Validate the grid and its elevation array.
  int ext[6];
  input->GetExtent(ext);
  if (ext[4] != ext[5])
  {
    vtkErrorMacro(<< "the DEM must be a 2-D image (one slice); this one has "
                  << (ext[5] - ext[4] + 1) << " slices");
    return 0;
  }
  const size_t nx = static_cast<size_t>(ext[1] - ext[0] + 1);
  const size_t ny = static_cast<size_t>(ext[3] - ext[2] + 1);
  if (nx < 2 || ny < 2)
  {
    vtkErrorMacro(<< "the DEM has " << nx << " x " << ny
                  << " points; a mesh needs at least 2 x 2");
    return 0;
  }
  const char* name = this->ElevationArrayName ? this->ElevationArrayName : "";
  vtkDataArray* elevation = input->GetPointData()->GetArray(name);
  if (!elevation)
  {
    vtkErrorMacro(<< "the input has no point array named '" << name << "'");
    return 0;
  }
  if (elevation->GetNumberOfComponents() != 1 ||
    (elevation->GetDataType() != VTK_FLOAT && elevation->GetDataType() != VTK_DOUBLE))
  {
    vtkErrorMacro(<< "the elevation array '" << name
                  << "' must have one float or double component");
    return 0;
  }
  const vtkIdType n = static_cast<vtkIdType>(nx * ny);

  vtkNew<vtkApertureGeoreference> geo;
  if (!geo->SetFromImage(input))
  {
    vtkErrorMacro(<< geo->GetErrorMessage());
    return 0;
  }

  // 2. Frame origin: the centre of the whole extent (shared by every piece of a streamed DEM).
  int whole[6];
  std::copy(ext, ext + 6, whole);
  if (inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  }
  double origin[3], spacing[3];
  input->GetOrigin(origin);
  input->GetSpacing(spacing);
  const double centre[2] = { origin[0] + 0.5 * (whole[0] + whole[1]) * spacing[0],
    origin[1] + 0.5 * (whole[2] + whole[3]) * spacing[1] };
  double lonlat0[2], ellipsoid[2];
  if (!geo->CRSToLonLat(centre[0], centre[1], lonlat0) || !geo->GetEllipsoid(ellipsoid))
  {
    vtkErrorMacro(<< geo->GetErrorMessage());
    return 0;
  }

  // 3. Elevations as float with NaN for nodata (copy: the input may be double or SOA).
  std::vector<float> z(static_cast<size_t>(n));
  for (vtkIdType k = 0; k < n; ++k)
  {
    z[static_cast<size_t>(k)] = static_cast<float>(elevation->GetComponent(k, 0));
  }
  const ap_grid_view grid = ap_grid_view_make(z.data(), nx, ny);
  ap_grid_stats stats;
  ap_status st = ap_grid_stats_compute(&grid, &stats);
  if (st != AP_OK)
  {
    vtkErrorMacro(<< "elevation statistics: " << ap_status_string(st));
    return 0;
  }
  if (stats.valid == 0)
  {
    vtkErrorMacro(<< "every point of the DEM is nodata; there is no terrain to mesh");
    return 0;
  }
  this->UpdateProgress(0.1);

  // 4. Geographic coordinates of every point.
  std::vector<double> xy(2 * static_cast<size_t>(n)), ll(2 * static_cast<size_t>(n));
  for (size_t j = 0; j < ny; ++j)
  {
    for (size_t i = 0; i < nx; ++i)
    {
      const size_t k = j * nx + i;
      xy[2 * k] = origin[0] + (ext[0] + static_cast<double>(i)) * spacing[0];
      xy[2 * k + 1] = origin[1] + (ext[2] + static_cast<double>(j)) * spacing[1];
    }
  }
  if (!geo->CRSToLonLatPoints(n, xy.data(), ll.data()))
  {
    vtkErrorMacro(<< geo->GetErrorMessage());
    return 0;
  }
  xy.clear();
  xy.shrink_to_fit();
  vtkIdType unprojectable = 0;
  for (vtkIdType k = 0; k < n; ++k)
  {
    if (std::isnan(ll[2 * k]) && !std::isnan(z[static_cast<size_t>(k)]))
    {
      z[static_cast<size_t>(k)] = std::numeric_limits<float>::quiet_NaN();
      ++unprojectable;
    }
  }
  if (unprojectable)
  {
    vtkWarningMacro(<< unprojectable << " points lie outside the domain of the CRS '"
                    << geo->GetCRSName() << "' and are treated as nodata");
  }
  if (this->GetAbortExecute())
  {
    return 0;
  }
  this->UpdateProgress(0.4);

  // 5. East-North-Up positions (GeographicLib LocalCartesian; Forward is const, so threads
  //    can share it). Nodata points get NaN here, which the normals kernel skips.
  const double exaggeration = this->VerticalExaggeration;
  const double parkHeight = exaggeration * stats.min;
  std::vector<double> enu(3 * static_cast<size_t>(n));
  try
  {
    const GeographicLib::Geocentric earth(ellipsoid[0], ellipsoid[1]);
    const GeographicLib::LocalCartesian frame(lonlat0[1], lonlat0[0], 0.0, earth);
    vtkSMPTools::For(0, n, [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType k = begin; k < end; ++k)
      {
        double* p = &enu[3 * static_cast<size_t>(k)];
        const float h = z[static_cast<size_t>(k)];
        if (std::isnan(h))
        {
          p[0] = p[1] = p[2] = std::numeric_limits<double>::quiet_NaN();
          continue;
        }
        frame.Forward(ll[2 * k + 1], ll[2 * k], exaggeration * h, p[0], p[1], p[2]);
      }
    });
    // Keep nodata vertices at finite places (on the grid, at the lowest valid height) so
    // bounds and pickers stay sane; no triangle uses them.
    vtkNew<vtkPoints> points;
    points->SetDataType(
      this->OutputPointsPrecision == DOUBLE_PRECISION ? VTK_DOUBLE : VTK_FLOAT);
    points->SetNumberOfPoints(n);
    for (vtkIdType k = 0; k < n; ++k)
    {
      const double* p = &enu[3 * static_cast<size_t>(k)];
      if (!std::isnan(p[0]))
      {
        points->SetPoint(k, p);
        continue;
      }
      double q[3] = { 0.0, 0.0, parkHeight };
      if (!std::isnan(ll[2 * k]))
      {
        frame.Forward(ll[2 * k + 1], ll[2 * k], parkHeight, q[0], q[1], q[2]);
      }
      points->SetPoint(k, q);
    }
    output->SetPoints(points);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "GeographicLib: " << e.what());
    return 0;
  }
  this->UpdateProgress(0.7);

  // 6. Triangles, with holes at nodata.
  size_t maxTri = 0;
  st = ap_mesh_max_triangles(nx, ny, &maxTri);
  if (st != AP_OK)
  {
    vtkErrorMacro(<< "triangle count: " << ap_status_string(st));
    return 0;
  }
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfValues(static_cast<vtkIdType>(3 * maxTri));
  size_t ntri = 0;
  st = ap_mesh_triangulate(&grid, reinterpret_cast<int64_t*>(connectivity->GetPointer(0)),
    maxTri, &ntri);
  if (st != AP_OK)
  {
    vtkErrorMacro(<< "triangulation: " << ap_status_string(st));
    return 0;
  }
  connectivity->Resize(static_cast<vtkIdType>(3 * ntri));
  connectivity->SetNumberOfValues(static_cast<vtkIdType>(3 * ntri));
  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfValues(static_cast<vtkIdType>(ntri + 1));
  for (size_t t = 0; t <= ntri; ++t)
  {
    offsets->SetValue(static_cast<vtkIdType>(t), static_cast<vtkIdType>(3 * t));
  }
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);
  output->SetPolys(polys);

  // 7. Point data: the DEM's arrays unchanged (vertex id = point id), then ours.
  vtkPointData* outPD = output->GetPointData();
  outPD->PassData(input->GetPointData());
  if (this->ComputeNormals)
  {
    vtkNew<vtkFloatArray> normals;
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(n);
    float* nptr = normals->GetPointer(0);
    st = ap_mesh_normals_validate(enu.data(), nx, ny, nptr);
    if (st != AP_OK)
    {
      vtkErrorMacro(<< "normals: " << ap_status_string(st));
      return 0;
    }
    vtkSMPTools::For(0, static_cast<vtkIdType>(ny), [&](vtkIdType j0, vtkIdType j1) {
      ap_mesh_normals_rows(
        enu.data(), nx, ny, static_cast<size_t>(j0), static_cast<size_t>(j1), nptr);
    });
    outPD->SetNormals(normals);
  }
  if (this->GenerateTextureCoordinates)
  {
    vtkNew<vtkFloatArray> tcoords;
    tcoords->SetName("TextureCoordinates");
    tcoords->SetNumberOfComponents(2);
    tcoords->SetNumberOfTuples(n);
    const double wnx = whole[1] - whole[0] + 1, wny = whole[3] - whole[2] + 1;
    for (size_t j = 0; j < ny; ++j)
    {
      const double v = (ext[2] + static_cast<double>(j) - whole[2] + 0.5) / wny;
      for (size_t i = 0; i < nx; ++i)
      {
        const double u = (ext[0] + static_cast<double>(i) - whole[0] + 0.5) / wnx;
        const vtkIdType k = static_cast<vtkIdType>(j * nx + i);
        tcoords->SetTypedComponent(k, 0, static_cast<float>(u));
        tcoords->SetTypedComponent(k, 1, static_cast<float>(v));
      }
    }
    outPD->SetTCoords(tcoords);
  }

  // 8. Field data: georeference passed through, frame recorded.
  output->GetFieldData()->PassData(input->GetFieldData());
  vtkNew<vtkDoubleArray> frameOrigin;
  frameOrigin->SetName("FrameOrigin");
  frameOrigin->SetNumberOfValues(3);
  frameOrigin->SetValue(0, lonlat0[1]);
  frameOrigin->SetValue(1, lonlat0[0]);
  frameOrigin->SetValue(2, 0.0);
  vtkNew<vtkDoubleArray> frameEllipsoid;
  frameEllipsoid->SetName("FrameEllipsoid");
  frameEllipsoid->SetNumberOfValues(2);
  frameEllipsoid->SetValue(0, ellipsoid[0]);
  frameEllipsoid->SetValue(1, ellipsoid[1]);
  vtkNew<vtkDoubleArray> exaggerationArray;
  exaggerationArray->SetName("VerticalExaggeration");
  exaggerationArray->SetNumberOfValues(1);
  exaggerationArray->SetValue(0, exaggeration);
  vtkFieldData* fd = output->GetFieldData();
  fd->AddArray(frameOrigin);
  fd->AddArray(frameEllipsoid);
  fd->AddArray(exaggerationArray);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkApertureTerrainMesh::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ElevationArrayName: "
     << (this->ElevationArrayName ? this->ElevationArrayName : "(none)") << "\n";
  os << indent << "VerticalExaggeration: " << this->VerticalExaggeration << "\n";
  os << indent << "OutputPointsPrecision: " << this->OutputPointsPrecision << "\n";
  os << indent << "ComputeNormals: " << this->ComputeNormals << "\n";
  os << indent << "GenerateTextureCoordinates: " << this->GenerateTextureCoordinates << "\n";
}
