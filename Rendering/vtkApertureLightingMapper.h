// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkApertureLightingMapper
 * @brief   Terrain mapper of Aperture (scaffold): VTK's standard lighting plus an exposure
 *          control, with its GLSL kept in Rendering/glsl and embedded at build time.
 *
 * This is the base the ambient aperture lighting model grows on. Today it renders exactly
 * like vtkOpenGLPolyDataMapper, then multiplies the lit colour by 2^Exposure (photographic
 * exposure value, EV), which is applied in the fragment shader without re-uploading geometry.
 *
 * @warning Colours above 1 after exposure are clipped by the 8-bit framebuffer.
 */
#ifndef vtkApertureLightingMapper_h
#define vtkApertureLightingMapper_h

#include "ApertureRenderingModule.h" // for export macro
#include "vtkOpenGLPolyDataMapper.h"

class APERTURERENDERING_EXPORT vtkApertureLightingMapper : public vtkOpenGLPolyDataMapper
{
public:
  static vtkApertureLightingMapper* New();
  vtkTypeMacro(vtkApertureLightingMapper, vtkOpenGLPolyDataMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Exposure in EV: the lit colour is scaled by 2^Exposure. Default 0; range [-20, 20]. */
  vtkSetClampMacro(Exposure, double, -20.0, 20.0);
  vtkGetMacro(Exposure, double);
  ///@}

protected:
  vtkApertureLightingMapper();
  ~vtkApertureLightingMapper() override;

  void ReplaceShaderValues(
    std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act) override;
  void SetMapperShaderParameters(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;

  double Exposure;

private:
  vtkApertureLightingMapper(const vtkApertureLightingMapper&) = delete;
  void operator=(const vtkApertureLightingMapper&) = delete;
};

#endif
