// SPDX-License-Identifier: BSD-3-Clause
// vtkApertureLightingMapper, vertex shader: pass the lighting inputs through, or light the
// vertex.
#ifdef AP_PER_VERTEX
  apertureIrradianceVSOut = apIrradiance(apertureNormalMC, apertureBentMC, apertureRadiusMC);
#else
  apertureNormalVSOut = apertureNormalMC;
  apertureBentVSOut = apertureBentMC;
  // (kept within a cap's [0, pi] (-1 for a negative, nodata) before it is interpolated: +inf,
  // which the model takes as pi/2, interpolated to NaN, nodata, until 2026-12-07; radii of a
  // cap interpolate as they are; NaN stays NaN)
  apertureRadiusVSOut =
    isnan(apertureRadiusMC) ? apertureRadiusMC : clamp(apertureRadiusMC, -1.0, 3.141592653589793);
#endif
