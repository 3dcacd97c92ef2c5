// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkApertureLinearCapture
 * @brief   Render a scene into a 32-bit float framebuffer and read the linear colour back, so
 *          that radiances above 1 (and below 1/255) survive: the input of OpenEXR output.
 *
 * Capture() renders `renderer`'s window once through a vtkFramebufferPass with a Float32 colour
 * texture (VTK's usual render steps inside), downloads that texture and returns it as a
 * vtkImageData of the renderer's viewport size with one 4-component float point array
 * "Radiance" (R, G, B, A; row 0 at the bottom, as VTK images). The renderer's own pass is
 * restored afterwards. Whatever the fragment shaders write is captured unclamped: with
 * vtkApertureLightingMapper, switch ToneMapping off (and set the exposure, EV 0 for radiance
 * in W/m²/sr) to capture linear radiance. The background colour is captured too (black gives
 * zero radiance there).
 *
 * Errors (vtkErrorMacro, nullptr): no renderer or window, not an OpenGL renderer, a viewport
 * of no pixels (an empty or inverted Viewport) or too large to read back (GetMaximumBytes), or
 * the float texture could not be read back.
 */
#ifndef vtkApertureLinearCapture_h
#define vtkApertureLinearCapture_h

#include "ApertureRenderingModule.h" // for export macro
#include "vtkObject.h"

class vtkImageData;
class vtkRenderer;

class APERTURERENDERING_EXPORT vtkApertureLinearCapture : public vtkObject
{
public:
  static vtkApertureLinearCapture* New();
  vtkTypeMacro(vtkApertureLinearCapture, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** Render and read back; the caller owns the returned image (nullptr on failure). */
  VTK_NEWINSTANCE vtkImageData* Capture(vtkRenderer* renderer);

  /** Bytes of float RGBA a capture can read back, exclusive (2^32: VTK's pixel buffers count
   *  bytes in 32 bits): a viewport of width x height x 16 bytes or more is an error, so
   *  16384 x 16384 is refused and 16384 x 16383 read. */
  static double GetMaximumBytes() { return 4294967296.0; }

protected:
  vtkApertureLinearCapture() = default;
  ~vtkApertureLinearCapture() override = default;

private:
  vtkApertureLinearCapture(const vtkApertureLinearCapture&) = delete;
  void operator=(const vtkApertureLinearCapture&) = delete;
};

#endif
