// SPDX-License-Identifier: BSD-3-Clause
// vtkApertureLightingMapper: the lighting model, compiled into the fragment shader (per-pixel
// shading, the default) or into the vertex shader (per-vertex shading). The ambient aperture
// lighting of Oat & Sander (2007, "Ambient aperture lighting", seed 000) with the exact
// spherical-cap intersection and Lambert terms of ALGORITHMS.md; a line-by-line port, in single
// precision, of the CPU reference in Filters/Kernels/ap_light.c (double precision); the two must
// stay identical in meaning, and the regression test compares them pixel by pixel.
// (Never write VTK's tag strings in these comments: the superclass expands them anywhere.)

uniform vec3 apertureSunDirection;   // unit vector to the sun's centre, mesh frame
uniform float apertureSunRadius;     // rl: angular radius of the sun cap (rad), (0, pi/2]
uniform vec3 apertureSunIrradiance;  // Esun: W/m2 normal to the beam, whole disc, RGB
uniform float apertureSunSin;        // sin rl
uniform float apertureSunArea;       // 4 pi sin^2(rl/2): the sun cap's solid angle (sr)
uniform vec3 apertureSunRadiance;    // Esun / (pi sin^2 rl), W/m2/sr
uniform vec3 apertureSkyRadiance;    // Lsky: W/m2/sr, uniform over the aperture, RGB
uniform int apertureIntersection;    // 0: exact (ALGORITHMS.md 1.2), 1: smoothstep (1.4)
uniform int apertureLambert;         // 0: centroid (1.6), 1: exact cap (6.1)
// With a sky table the mapper compiles this shader with AP_SKY_TABLE defined (a variant, not a
// uniform branch: llvmpipe pays for an untaken branch's texture fetches).
#ifdef AP_SKY_TABLE
uniform sampler2D apertureSkyTable;  // cap-mean sky radiance, RGB float, (azimuth, elev + radius)
uniform int apertureSkyTableSize[3]; // azimuths, elevations, radii
#endif

const float AP_PI = 3.14159265358979;

// Solid angle of a cap of angular radius r: 4 pi sin^2(r/2) (the float-safe form).
float apCapArea(float r)
{
  float h = sin(0.5 * r);
  return 4.0 * AP_PI * h * h;
}

// The half-angles at the two axes of a partial overlap (used by apCapIntersectionExact).
void apCapLensAngles(float r1, float r2, float d, out float a1, out float a2)
{
  float s = 0.5 * (r1 + r2 + d);
  float k = sqrt(max(0.0, sin(s - r1) * sin(s - r2) * sin(s - d) / sin(s)));
  a1 = 2.0 * atan(k, sin(s - r2));
  a2 = 2.0 * atan(k, sin(s - r1));
}

// Intersection of caps (r1, r2) whose axes are d apart, ALGORITHMS.md 1.1/1.2: the four cases,
// and in partial overlap the half-angle angles and L'Huilier's excess (no cancellation of
// nearly equal cosines: the acos form is off by thousands of percent for the sun in float).
// a1, a2 return the half-angles at the two axes (used by the lens moment); 0 outside overlap.
float apCapIntersectionExact(float r1, float r2, float d, out float a1, out float a2)
{
  a1 = 0.0;
  a2 = 0.0;
  if (d <= abs(r1 - r2)) { return apCapArea(min(r1, r2)); }
  if (d >= r1 + r2) { return 0.0; }
  if (d >= 2.0 * AP_PI - r1 - r2) { return apCapArea(r1) + apCapArea(r2) - 4.0 * AP_PI; }
  apCapLensAngles(r1, r2, d, a1, a2);
  float s = 0.5 * (r1 + r2 + d);
  float e = 4.0 * atan(sqrt(max(0.0, tan(0.5 * s) * tan(0.5 * (s - r1)) *
                                       tan(0.5 * (s - r2)) * tan(0.5 * (s - d)))));
  float h1 = sin(0.5 * r1), h2 = sin(0.5 * r2);
  return max(0.0, 4.0 * a1 * h1 * h1 + 4.0 * a2 * h2 * h2 - 2.0 * e);
}

// Oat & Sander's approximation, ALGORITHMS.md 1.4: the smaller cap's area times a smoothstep
// of the normalised axis distance.
float apCapIntersectionSmoothstep(float r1, float r2, float d)
{
  float rmin = min(r1, r2), diff = abs(r1 - r2);
  float amin = apCapArea(rmin);
  if (d <= diff) { return amin; }
  if (d >= r1 + r2) { return 0.0; }
  float x = 1.0 - (d - diff) / (r1 + r2 - diff);
  return amin * x * x * (3.0 - 2.0 * x);
}

// Integral of max(0, n.w) over a cap of half-angle sigma <= pi/2 whose axis makes cosT with n
// (sin2s = sin^2 sigma): Snyder (1996) in Frostbite's form, ALGORITHMS.md 6.1.
float apCapCosineIntegral(float cosT, float sin2s)
{
  if (cosT * cosT >= sin2s) { return AP_PI * sin2s * max(cosT, 0.0); }
  float sinT = sqrt(max(0.0, 1.0 - cosT * cosT));
  float x = sqrt(max(0.0, 1.0 / sin2s - 1.0));
  float y = -x * cosT / sinT;
  float sy = sinT * sqrt(max(0.0, 1.0 - y * y));
  float t = x > 0.0 ? atan(sy / x) : 0.5 * AP_PI;
  return max(0.0, (cosT * acos(clamp(y, -1.0, 1.0)) - x * sy) * sin2s + t);
}

#ifdef AP_SKY_TABLE
// The sky table's lookup, ap_light_sky_lookup (ap_light.h) line by line: azimuth cells
// centred on (i + 1/2) 2 pi / na, wrapping; elevation and radius nodes from 0 to pi/2;
// trilinear with exact weights (texelFetch, no hardware filtering).
vec3 apSkyTexel(int i, int j, int k)
{
  return texelFetch(apertureSkyTable, ivec2(i, k * apertureSkyTableSize[1] + j), 0).rgb;
}

vec3 apSkyLookup(vec3 b, float rp)
{
  int na = apertureSkyTableSize[0], ne = apertureSkyTableSize[1], nr = apertureSkyTableSize[2];
  float az = atan(b.x, b.y);
  if (az < 0.0) { az += 2.0 * AP_PI; }
  float el = clamp(asin(clamp(b.z / length(b), -1.0, 1.0)), 0.0, 0.5 * AP_PI);
  float r = clamp(rp, 0.0, 0.5 * AP_PI);
  float fa = az / (2.0 * AP_PI) * float(na) - 0.5;
  float fe = el / (0.5 * AP_PI) * float(ne - 1), fr = r / (0.5 * AP_PI) * float(nr - 1);
  float a0f = floor(fa);
  int e0 = int(min(floor(fe), float(ne - 2))), r0 = int(min(floor(fr), float(nr - 2)));
  float wa = fa - a0f, we = fe - float(e0), wr = fr - float(r0);
  int a0 = ((int(a0f) % na) + na) % na, a1 = (a0 + 1) % na;
  vec3 v = vec3(0.0);
  for (int k = 0; k < 2; ++k)
  {
    for (int j = 0; j < 2; ++j)
    {
      float w = (k == 1 ? wr : 1.0 - wr) * (j == 1 ? we : 1.0 - we);
      v += w * mix(apSkyTexel(a0, e0 + j, r0 + k), apSkyTexel(a1, e0 + j, r0 + k), wa);
    }
  }
  return v;
}
#endif

// The irradiance of a point (W/m2, RGB): sun through the aperture plus the sky filling the rest
// of it (ap_light.c, step by step). apN: normal, apB: bent normal, apRp: aperture radius (rad).
// Nodata (NaN, zero vectors) gives 0: a black point.
vec3 apIrradiance(vec3 apN, vec3 apB, float apRp)
{
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
  return apE;
}
