// SPDX-License-Identifier: BSD-3-Clause
// vtkApertureLightingMapper, vertex shader: pass the lighting inputs through.
  apertureNormalVSOut = apertureNormalMC;
  apertureBentVSOut = apertureBentMC;
  apertureRadiusVSOut = apertureRadiusMC;
