// SPDX-License-Identifier: BSD-3-Clause
// vtkApertureLightingMapper, last colour step (after any texture has multiplied the radiance):
// exposure x = L * 2^EV, then, with tone mapping on, t = 1 - exp(-x) and the sRGB transfer
// function (IEC 61966-2-1) for an 8-bit display; off, the exposed linear value as it is.
  gl_FragData[0].rgb *= apertureExposureScale;
  if (apertureToneMap != 0)
  {
    vec3 apT = vec3(1.0) - exp(-max(gl_FragData[0].rgb, vec3(0.0)));
    vec3 apLo = 12.92 * apT;
    vec3 apHi = 1.055 * pow(apT, vec3(1.0 / 2.4)) - 0.055;
    gl_FragData[0].rgb = mix(apHi, apLo, vec3(lessThanEqual(apT, vec3(0.0031308))));
  }
