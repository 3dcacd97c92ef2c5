// SPDX-License-Identifier: BSD-3-Clause
// vtkApertureLightingMapper, fragment shader declarations (the lighting model itself,
// vtkApertureLightingModel.glsl, follows them when shading per pixel).
// (Never write VTK's tag strings in these comments: the superclass expands them anywhere.)
uniform float apertureExposureScale; // 2^EV
uniform int apertureToneMap;         // 1: 1 - exp(-x) then sRGB encoding; 0: none (linear)
#ifdef AP_PER_VERTEX
const float AP_PI = 3.14159265358979;
in vec3 apertureIrradianceVSOut;     // W/m2 RGB, computed per vertex and interpolated
#else
in vec3 apertureNormalVSOut;
in vec3 apertureBentVSOut;
in float apertureRadiusVSOut;
#endif
