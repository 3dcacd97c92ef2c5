// SPDX-License-Identifier: BSD-3-Clause
#include "vtkApertureLinearCapture.h"

#include "vtkFloatArray.h"
#include "vtkFramebufferPass.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPixelBufferObject.h"
#include "vtkPointData.h"
#include "vtkRenderStepsPass.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"

vtkStandardNewMacro(vtkApertureLinearCapture);

namespace
{
// The error for a viewport of w x h pixels, `bytes` of float RGBA: VTK 9.1's pixel buffers count
// their bytes in 32 bits, and a larger download overran its buffer (a segmentation fault).
void TooLarge(vtkApertureLinearCapture* self, int w, int h, double bytes)
{
  vtkErrorWithObjectMacro(self, << "cannot read back " << w << " x " << h
                                << " pixels of float RGBA (" << bytes / 1073741824.0
                                << " GiB): VTK's pixel buffers hold less than 4 GiB; capture a "
                                   "smaller viewport");
}

// Whether the window's OpenGL driver takes textures of w x h pixels (its largest, on a side,
// into `largest`; the window's context made first if it has none yet); true when it cannot be
// asked. A larger viewport was captured as zeros, with VTK's 40 lines on an incomplete
// framebuffer, until 2026-12-07.
bool TextureFits(vtkOpenGLRenderWindow* window, int w, int h, int& largest)
{
  window->MakeCurrent();
  if (!window->IsCurrent())
  {
    window->Initialize(); // (as its first Render would)
    window->MakeCurrent();
  }
  largest = window->IsCurrent() ? vtkTextureObject::GetMaximumTextureSize(window) : -1;
  return largest <= 0 || (w <= largest && h <= largest);
}
}

//------------------------------------------------------------------------------
vtkImageData* vtkApertureLinearCapture::Capture(vtkRenderer* renderer)
{
  auto* gl = vtkOpenGLRenderer::SafeDownCast(renderer);
  auto* window = renderer ? vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow())
                          : nullptr;
  if (!gl || !window)
  {
    vtkErrorMacro(<< "Capture needs an OpenGL renderer in an OpenGL render window");
    return nullptr;
  }
  const int* viewport = renderer->GetSize(); // (pixels: the texture's size below)
  if (viewport[0] < 1 || viewport[1] < 1)
  {
    // (VTK's framebuffer pass printed its diagnosis of an incomplete framebuffer, 40 lines,
    // and this only "could not read the float framebuffer back", until 2026-12-06)
    const double* v = renderer->GetViewport();
    vtkErrorMacro(<< "the renderer's viewport is " << viewport[0] << " x " << viewport[1]
                  << " pixels (Viewport " << v[0] << ", " << v[1] << ", " << v[2] << ", " << v[3]
                  << " of the window): nothing to capture");
    return nullptr;
  }
  const double asked = 4.0 * sizeof(float) * viewport[0] * static_cast<double>(viewport[1]);
  if (asked >= GetMaximumBytes())
  {
    TooLarge(this, viewport[0], viewport[1], asked);
    return nullptr; // (before rendering at that size)
  }
  int largest = 0;
  if (!TextureFits(window, viewport[0], viewport[1], largest))
  {
    vtkErrorMacro(<< "the renderer's viewport is " << viewport[0] << " x " << viewport[1]
                  << " pixels, beyond the " << largest << " pixels on a side of the OpenGL "
                  << "driver's textures: capture a smaller viewport");
    return nullptr;
  }
  vtkSmartPointer<vtkRenderPass> previous = gl->GetPass();
  vtkNew<vtkRenderStepsPass> steps;
  vtkNew<vtkFramebufferPass> framebuffer;
  framebuffer->SetDelegatePass(steps);
  framebuffer->SetColorFormat(vtkTextureObject::Float32);
  gl->SetPass(framebuffer);
  window->Render();

  vtkImageData* image = nullptr;
  vtkTextureObject* texture = framebuffer->GetColorTexture();
  const double bytes = texture
    ? 4.0 * sizeof(float) * texture->GetWidth() * static_cast<double>(texture->GetHeight())
    : 0.0;
  if (bytes >= GetMaximumBytes())
  {
    TooLarge(this, texture->GetWidth(), texture->GetHeight(), bytes);
    texture = nullptr;
  }
  if (texture && texture->GetWidth() > 0 && texture->GetHeight() > 0)
  {
    window->MakeCurrent();
    const unsigned int w = texture->GetWidth(), h = texture->GetHeight();
    vtkPixelBufferObject* pbo = texture->Download();
    if (pbo && texture->GetComponents() == 4) // vtkFramebufferPass's colour is RGBA
    {
      vtkNew<vtkFloatArray> rgba;
      rgba->SetName("Radiance");
      rgba->SetNumberOfComponents(4);
      rgba->SetNumberOfTuples(static_cast<vtkIdType>(w) * h);
      const char* names[4] = { "R", "G", "B", "A" };
      for (int c = 0; c < 4; ++c)
      {
        rgba->SetComponentName(c, names[c]);
      }
      unsigned int dims[2] = { w, h };
      vtkIdType increments[2] = { 0, 0 };
      if (pbo->Download2D(VTK_FLOAT, rgba->GetPointer(0), dims, 4, increments))
      {
        image = vtkImageData::New();
        image->SetDimensions(static_cast<int>(w), static_cast<int>(h), 1);
        image->GetPointData()->AddArray(rgba);
        image->GetPointData()->SetActiveScalars("Radiance");
      }
    }
    if (pbo)
    {
      pbo->Delete();
    }
  }
  gl->SetPass(previous);
  framebuffer->ReleaseGraphicsResources(window); // its FBO and textures, while the context lives
  if (!image && bytes < GetMaximumBytes())
  {
    vtkErrorMacro(<< "could not read the float framebuffer back");
  }
  return image;
}

//------------------------------------------------------------------------------
void vtkApertureLinearCapture::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
