// SPDX-License-Identifier: BSD-3-Clause
// vtkApertureLightingMapper, vertex shader: pass the lighting inputs through, or light the
// vertex.
#ifdef AP_PER_VERTEX
  apertureIrradianceVSOut = apIrradiance(apertureNormalMC, apertureBentMC, apertureRadiusMC);
#else
  apertureNormalVSOut = apertureNormalMC;
  apertureBentVSOut = apertureBentMC;
  apertureRadiusVSOut = apertureRadiusMC;
#endif
