// SPDX-License-Identifier: BSD-3-Clause
// vtkApertureLightingMapper, vertex shader: pass the lighting inputs through, or light the
// vertex.
#ifdef AP_PER_VERTEX
  apertureIrradianceVSOut = apIrradiance(apertureNormalMC, apertureBentMC, apertureRadiusMC);
#else
  apertureNormalVSOut = apertureNormalMC;
  apertureBentVSOut = apertureBentMC;
  // (clamped before it is interpolated: +inf, which the model takes as pi/2, interpolated to
  // NaN, nodata, until 2026-12-07; NaN stays NaN)
  apertureRadiusVSOut =
    isnan(apertureRadiusMC) ? apertureRadiusMC : clamp(apertureRadiusMC, -1.0, 1.5707963267948966);
#endif
