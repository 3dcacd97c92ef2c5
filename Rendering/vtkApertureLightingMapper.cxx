// SPDX-License-Identifier: BSD-3-Clause
#include "vtkApertureLightingMapper.h"

#include "vtkApertureExposureDecFS.h"
#include "vtkApertureExposureImplFS.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLHelper.h"
#include "vtkShader.h"
#include "vtkShaderProgram.h"

#include <cmath>
#include <string>

vtkStandardNewMacro(vtkApertureLightingMapper);

//------------------------------------------------------------------------------
vtkApertureLightingMapper::vtkApertureLightingMapper()
  : Exposure(0.0)
{
}

//------------------------------------------------------------------------------
vtkApertureLightingMapper::~vtkApertureLightingMapper() = default;

//------------------------------------------------------------------------------
void vtkApertureLightingMapper::ReplaceShaderValues(
  std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act)
{
  // Add our code beside VTK's tags, keeping the tags, so the superclass still expands them
  // (lighting, picking, clipping, depth peeling all keep working).
  std::string fs = shaders[vtkShader::Fragment]->GetSource();
  vtkShaderProgram::Substitute(fs, "//VTK::Light::Dec",
    std::string("//VTK::Light::Dec\n") + vtkApertureExposureDecFS, false);
  vtkShaderProgram::Substitute(fs, "//VTK::Light::Impl",
    std::string("//VTK::Light::Impl\n") + vtkApertureExposureImplFS, false);
  shaders[vtkShader::Fragment]->SetSource(fs);
  this->Superclass::ReplaceShaderValues(shaders, ren, act);
}

//------------------------------------------------------------------------------
void vtkApertureLightingMapper::SetMapperShaderParameters(
  vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act)
{
  vtkShaderProgram* program = cellBO.Program;
  if (program && program->IsUniformUsed("apertureExposureScale"))
  {
    program->SetUniformf("apertureExposureScale", static_cast<float>(std::exp2(this->Exposure)));
  }
  this->Superclass::SetMapperShaderParameters(cellBO, ren, act);
}

//------------------------------------------------------------------------------
void vtkApertureLightingMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Exposure: " << this->Exposure << "\n";
}
