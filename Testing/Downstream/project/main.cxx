// SPDX-License-Identifier: BSD-3-Clause
// Uses the installed Aperture: a 3 x 3 lat/lon DEM meshed into 8 triangles, and the C core.
#include "vtkApertureGeoreference.h"
#include "vtkApertureTerrainMesh.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include "ap_status.h"

#include <cstdio>
#include <cstring>

int main()
{
  vtkNew<vtkImageData> dem;
  dem->SetDimensions(3, 3, 1);
  dem->SetSpacing(0.01, 0.01, 1);
  dem->SetOrigin(7.0, 46.0, 0);
  vtkNew<vtkFloatArray> z;
  z->SetName("Elevation");
  z->SetNumberOfTuples(9);
  for (vtkIdType k = 0; k < 9; ++k)
  {
    z->SetValue(k, 500.0f + 10.0f * static_cast<float>(k));
  }
  dem->GetPointData()->SetScalars(z);
  vtkNew<vtkApertureGeoreference> geo;
  if (!geo->SetCRS("EPSG:4326") || !geo->AttachToImage(dem))
  {
    std::fprintf(stderr, "georeference: %s\n", geo->GetErrorMessage());
    return 1;
  }
  vtkNew<vtkApertureTerrainMesh> mesh;
  mesh->SetInputData(dem);
  mesh->Update();
  const vtkIdType cells = mesh->GetOutput()->GetNumberOfCells();
  if (cells != 8 || std::strcmp(ap_status_string(AP_OK), "success") != 0)
  {
    std::fprintf(stderr, "expected 8 triangles, got %lld\n", static_cast<long long>(cells));
    return 1;
  }
  std::printf("downstream OK: %lld triangles\n", static_cast<long long>(cells));
  return 0;
}
