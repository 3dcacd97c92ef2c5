// SPDX-License-Identifier: BSD-3-Clause
// vtkApertureLightingMapper, vertex shader declarations (after the normal declarations).
// Per-vertex inputs in the mesh's own frame (East-North-Up metres of vtkApertureTerrainMesh):
// the surface normal, the bent normal (axis of the visible-sky cap) and the aperture radius
// (radians). Shading per pixel, they go to the fragment shader, which interpolates them;
// shading per vertex, the irradiance is computed here (the model follows these lines then).
// (Never write VTK's tag strings in these comments: the superclass expands them anywhere.)
in vec3 apertureNormalMC;
in vec3 apertureBentMC;
in float apertureRadiusMC;
#ifdef AP_PER_VERTEX
out vec3 apertureIrradianceVSOut;
#else
out vec3 apertureNormalVSOut;
out vec3 apertureBentVSOut;
out float apertureRadiusVSOut;
#endif
