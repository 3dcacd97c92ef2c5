// SPDX-License-Identifier: BSD-3-Clause
// vtkApertureLightingMapper: declarations, inserted after VTK's light declarations.
// (Never write VTK's tag strings in these comments: the superclass expands them anywhere.)
uniform float apertureExposureScale; // 2^Exposure (EV), dimensionless
