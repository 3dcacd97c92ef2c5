// SPDX-License-Identifier: BSD-3-Clause
// vtkApertureLightingMapper: inserted after VTK's lighting code. Photographic exposure, a
// linear scale of the lit colour by 2^EV before display.
  gl_FragData[0].rgb *= apertureExposureScale;
