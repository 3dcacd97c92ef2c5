// SPDX-License-Identifier: BSD-3-Clause
// DEM images for the filters' tests: float elevations from a function of the grid indices,
// with a CRS attached as vtkApertureDEMReader attaches it.
#ifndef aptest_dem_hxx
#define aptest_dem_hxx

#include "aptest.hxx"

#include "vtkApertureGeoreference.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <cstdio>

namespace
{
// A DEM image: nx x ny points, CRS, origin/spacing in CRS units, elevation f(i, j).
template <typename F>
vtkSmartPointer<vtkImageData> MakeDEM(const char* crs, double x0, double y0, double dx, double dy,
  int nx, int ny, F elevation)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, 1);
  image->SetOrigin(x0, y0, 0.0);
  image->SetSpacing(dx, dy, 1.0);
  vtkNew<vtkFloatArray> z;
  z->SetName("Elevation");
  z->SetNumberOfTuples(static_cast<vtkIdType>(nx) * ny);
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      z->SetValue(static_cast<vtkIdType>(j) * nx + i, elevation(i, j));
    }
  }
  image->GetPointData()->SetScalars(z);
  if (crs)
  {
    vtkNew<vtkApertureGeoreference> geo;
    if (!geo->SetCRS(crs) || !geo->AttachToImage(image))
    {
      std::fprintf(stderr, "cannot attach CRS %s: %s\n", crs, geo->GetErrorMessage());
      ++aptest::Failures();
    }
  }
  return image;
}

}

#endif
