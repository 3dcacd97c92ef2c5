// SPDX-License-Identifier: BSD-3-Clause
// vtkApertureLightingMapper, fragment shader: the radiance of this point (ap_light.c, step by
// step). Replaces the colour VTK's lighting just wrote; diffuseColor (the actor's colour,
// scalar colours) is the albedo, and a texture, if any, multiplies the result afterwards.
  {
    vec3 apN = apertureNormalVSOut, apB = apertureBentVSOut;
    float apRp = apertureRadiusVSOut;
    bool apValid = !(isnan(apRp) || isnan(apN.x) || isnan(apB.x)) && dot(apN, apN) > 0.0 &&
      dot(apB, apB) > 0.0;
    vec3 apE = vec3(0.0);
    if (apValid)
    {
      apN = normalize(apN);
      apB = normalize(apB);
      apRp = clamp(apRp, 0.0, 0.5 * AP_PI);
      vec3 apS = apertureSunDirection;
      float apRl = apertureSunRadius;
      float apSinRl = apertureSunSin; // sin rl, computed once on the CPU
      // 1. the sun's radiance, so that a fully visible sun facing the surface gives Esun:
      //    Esun / (pi sin^2 rl), also computed once on the CPU
      vec3 apLsun = apertureSunRadiance;
      // 2. the visible part of the sun: aperture cap (b, rp) against the sun cap (s, rl)
      float apD = atan(length(cross(apB, apS)), dot(apB, apS));
      float apA1 = 0.0, apA2 = 0.0, apVis = 0.0;
      if (apRp > 0.0)
      {
        if (apertureIntersection == 1)
        {
          apVis = apCapIntersectionSmoothstep(apRp, apRl, apD);
          if (apertureLambert == 0 && apVis > 0.0 && apD > abs(apRp - apRl))
          {
            apCapLensAngles(apRp, apRl, apD, apA1, apA2); // the centroid needs the lens' angles
          }
        }
        else
        {
          apVis = apCapIntersectionExact(apRp, apRl, apD, apA1, apA2); // gives the angles too
        }
      }
      // 3. the Lambert term S (sr): cosine-weighted visible sun
      float apS_ = 0.0;
      if (apVis > 0.0)
      {
        if (apertureLambert == 1)
        {
          // exact cap: the sun cap's clipped cosine integral times its visible fraction
          apS_ = apCapCosineIntegral(dot(apN, apS), apSinRl * apSinRl) * apVis / apertureSunArea;
        }
        else
        {
          // centroid: area times the cosine of the lens centroid (first moment, 1.6)
          vec3 apC;
          if (apD <= abs(apRp - apRl))
          {
            apC = apRp < apRl ? apB : apS; // containment: the smaller cap's axis
          }
          else
          {
            float apSd = sin(apD), apCd = cos(apD);
            vec3 apT1 = (apS - apCd * apB) / apSd, apT2 = (apB - apCd * apS) / apSd;
            vec3 apM = sin(apRp) * (apA1 * sin(apRp) * apB - sin(apA1) * cos(apRp) * apT1) +
              apSinRl * (apA2 * apSinRl * apS - sin(apA2) * cos(apRl) * apT2);
            apC = normalize(apM);
          }
          apS_ = apVis * max(0.0, dot(apN, apC));
        }
      }
      // 4. the sky: the aperture's cosine-weighted solid angle less the sun's share
      float apSinRp = sin(apRp);
      float apSky = max(0.0, apCapCosineIntegral(dot(apN, apB), apSinRp * apSinRp) - apS_);
      // 5. irradiance (W/m2)
#ifdef AP_SKY_TABLE
      vec3 apLsky = apSkyLookup(apB, apRp); // the sky averaged over this aperture
#else
      vec3 apLsky = apertureSkyRadiance;
#endif
      apE = apLsun * apS_ + apLsky * apSky;
    }
    // outgoing radiance of a Lambertian surface of albedo diffuseColor, W/m2/sr
    gl_FragData[0].rgb = diffuseColor / AP_PI * apE;
  }
