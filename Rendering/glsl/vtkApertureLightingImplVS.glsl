// SPDX-License-Identifier: BSD-3-Clause
// vtkApertureLightingMapper, vertex shader: light the vertex, or pass the lighting inputs
// through with the sky's sun-independent share.
#ifdef AP_PER_VERTEX
  apertureIrradianceVSOut = apIrradiance(apertureNormalMC, apertureBentMC, apertureRadiusMC);
#else
  apertureNormalVSOut = apertureNormalMC;
  apertureBentVSOut = apertureBentMC;
  apertureRadiusVSOut = apertureRadiusMC;
  apertureSkyApertureVSOut = apSkyAperture(apertureNormalMC, apertureBentMC, apertureRadiusMC);
#ifdef AP_SKY_TABLE
  apertureSkyLightVSOut = apSkyLight(apertureBentMC, apertureRadiusMC);
#endif
#endif
