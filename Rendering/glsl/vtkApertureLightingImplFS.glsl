// SPDX-License-Identifier: BSD-3-Clause
// vtkApertureLightingMapper, fragment shader: replaces the colour VTK's lighting just wrote with
// the outgoing radiance of a Lambertian surface (W/m2/sr): diffuseColor (the actor's colour,
// scalar colours) is the albedo, and a texture, if any, multiplies the result afterwards.
#ifdef AP_PER_VERTEX
  gl_FragData[0].rgb = diffuseColor / AP_PI * apertureIrradianceVSOut;
#else
  gl_FragData[0].rgb = diffuseColor / AP_PI *
    apIrradiance(apertureNormalVSOut, apertureBentVSOut, apertureRadiusVSOut);
#endif
