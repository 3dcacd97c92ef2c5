// SPDX-License-Identifier: BSD-3-Clause
// vtkApertureLightingMapper: the lighting model, compiled into the fragment shader (per-pixel
// shading, the default) or into the vertex shader (per-vertex shading). The ambient aperture
// lighting of Oat & Sander (2007, "Ambient aperture lighting", seed 000) with the exact
// spherical-cap intersection and Lambert terms of ALGORITHMS.md; the CPU reference in
// Filters/Kernels/ap_light.c (double precision, the formulas as ALGORITHMS.md writes them) step
// by step, in single precision, with the trigonometry shared between the steps (identities
// noted where they are used); the two must stay identical in meaning, and the regression test
// compares them pixel by pixel.
// (Never write VTK's tag strings in these comments: the superclass expands them anywhere.)

uniform vec3 apertureSunDirection;   // unit vector to the sun's centre, mesh frame
uniform float apertureSunRadius;     // rl: angular radius of the sun cap (rad), (0, pi/2]
uniform float apertureSunSin;        // sin rl
uniform float apertureSunCos;        // cos rl
uniform vec2 apertureSunHalf;        // sin(rl/2), cos(rl/2)
uniform float apertureSunArea;       // 4 pi sin^2(rl/2): the sun cap's solid angle (sr)
uniform vec3 apertureSunRadiance;    // Esun / (pi sin^2 rl), W/m2/sr, RGB; Esun normal to the beam
uniform vec3 apertureSkyRadiance;    // Lsky: W/m2/sr, uniform over the aperture, RGB
// The modes are compiled variants, not uniform branches (llvmpipe pays for untaken branches):
// AP_SMOOTHSTEP (defined: Oat & Sander's intersection, 1.4; else the exact one, 1.2),
// AP_EXACT_CAP (defined: the exact-cap Lambert term, 6.1; else the lens centroid, 1.6) and
// AP_SKY_TABLE (defined: the sky model over each aperture, cosine-weighted, from a table).
#ifdef AP_SKY_TABLE
uniform sampler2D apertureSkyTable;  // caps' sky radiance, RGB float, (azimuth, elev + radius)
uniform int apertureSkyTableSize[3]; // azimuths, elevations, radii
#endif

const float AP_PI = 3.14159265358979;

// Cost note: a software rasteriser (llvmpipe) runs every side of a branch whose condition
// differs between pixels, masked, so the functions below share their trigonometry. Each cap
// and the distance d between the axes arrive as the sine and cosine of their half-angles
// (the sun's computed once per draw, the aperture's from one sine, d's from the dot and cross
// products of the unit axes); 1 - cos r = 2 sin^2(r/2) and sin r = 2 sin(r/2) cos(r/2).

// atan2(y, x) in [-pi, pi], within 2.5e-7 relative of the exact angle at every size (float
// roundings): the built-in atan's precision is the implementation's, and Mesa's (a polynomial,
// 2e-5 relative near 0) makes the lens's small angles, whose terms cancel by factors of 50 and
// more near tangency, off by a percent. |y| / |x| or its inverse is brought within tan(pi/8)
// (atan q = pi/4 + atan((q - 1) / (q + 1))), then u + u^3 P(u^2): P minimax in relative error.
float apAtan2(float y, float x)
{
  float ax = abs(x), ay = abs(y), big = max(ax, ay);
  float q = big > 0.0 ? min(ax, ay) / big : 0.0;
  bool far = q > 0.41421356;
  float u = far ? (q - 1.0) / (q + 1.0) : q, z = u * u;
  float r = u + u * z * (((0.08053719 * z - 0.13877678) * z + 0.19977710) * z - 0.33332949);
  r = far ? 0.78539816 + r : r;
  r = ay > ax ? 1.5707963 - r : r;
  r = x < 0.0 ? 3.1415927 - r : r;
  return y < 0.0 ? -r : r;
}

// The half-angle sine and cosine of d, from cos d = b.s and sin d = |b x s| (d in [0, pi]):
// the square root where it does not cancel, the other from sin d = 2 sin(d/2) cos(d/2).
vec2 apHalfAngle(float cosD, float sinD)
{
  float c = sqrt(max(0.0, 0.5 * (1.0 + cosD))), sn = sqrt(max(0.0, 0.5 * (1.0 - cosD)));
  return cosD >= 0.0 ? vec2(0.5 * sinD / max(c, 1e-30), c) : vec2(sn, 0.5 * sinD / max(sn, 1e-30));
}

// The four sines of L'Huilier's half-perimeter s = (r1 + r2 + d) / 2 (ALGORITHMS.md 1.2):
// (sin s, sin(s - r1), sin(s - r2), sin(s - d)), by angle addition from the half-angles h1, h2,
// hd (each (sin, cos) of half the angle) with P = (r1 + r2)/2 and M = (r1 - r2)/2:
// s = P + d/2, s - r1 = d/2 - M, s - r2 = d/2 + M, s - d = P - d/2. A sum or difference of
// products carries the same absolute rounding (~1e-7) as the float angles s - r it replaces,
// so near tangency the lens is as exact as with the sines of those angles.
vec4 apLensSines(vec2 h1, vec2 h2, vec2 hd)
{
  float sinP = h1.x * h2.y + h1.y * h2.x, cosP = h1.y * h2.y - h1.x * h2.x;
  float sinM = h1.x * h2.y - h1.y * h2.x, cosM = h1.y * h2.y + h1.x * h2.x;
  return vec4(sinP * hd.y + cosP * hd.x, cosM * hd.x - sinM * hd.y,
    sinM * hd.y + cosM * hd.x, sinP * hd.y - cosP * hd.x);
}

// The lens of two caps (r1, r2) in partial overlap, from the four sines sn of apLensSines:
// the half-angles a1, a2 at the axes with their sines, and the excess e of the triangle
// (axis 1, axis 2, a rim crossing).
// k = sqrt(sin(s - r1) sin(s - r2) sin(s - d) / sin s); a1 = 2 atan2(k, sin(s - r2)),
// a2 = 2 atan2(k, sin(s - r1)), so sin a = 2 k t / (k^2 + t^2) with t the atan2's second term.
// e = 2 atan2(2 k sin s, 1 + cos r1 + cos r2 + cos d): the quotient of Cagnoli's
//   sin(e/2) = k sin s / (2 cos(r1/2) cos(r2/2) cos(d/2)) and of
//   cos(e/2) = (1 + cos r1 + cos r2 + cos d) / (4 cos(r1/2) cos(r2/2) cos(d/2)), equal to
//   L'Huilier's 4 atan sqrt(tan(s/2) tan((s-r1)/2) tan((s-r2)/2) tan((s-d)/2)) (to 2e-9 in
//   double over random lenses) and as safe in float (atan2 has no pole).
void apCapLens(vec4 sn, float cosR1, float cosR2, float cosD,
  out float a1, out float a2, out float sinA1, out float sinA2, out float e)
{
  float k = sqrt(max(0.0, sn.y * sn.z * sn.w / max(sn.x, 1e-30)));
  a1 = 2.0 * apAtan2(k, sn.z);
  a2 = 2.0 * apAtan2(k, sn.y);
  sinA1 = 2.0 * k * sn.z / max(k * k + sn.z * sn.z, 1e-30);
  sinA2 = 2.0 * k * sn.y / max(k * k + sn.y * sn.y, 1e-30);
  e = 2.0 * apAtan2(2.0 * k * sn.x, 1.0 + cosR1 + cosR2 + cosD);
}

// a - sin a for a lens angle a in [0, pi] with its sine: the series below 0.5 (to 1e-9
// relative), where the difference would lose its digits.
float apAngleLessSine(float a, float sinA)
{
  float q = a * a;
  float series = a * q / 6.0 * (1.0 - q / 20.0 * (1.0 - q / 42.0 * (1.0 - q / 72.0)));
  return a < 0.5 ? series : a - sinA;
}

// The lens's first moment B (ap_light.h, 3) about the axis cS of the smaller cap: the rim
// arc of that cap (half-angle aS about the tangent tS towards the other axis) and the other
// cap's (aO about tO towards cS), from half-angle pairs (sin, cos) of rS, rO and d. Every term
// is of the lens's size; about the sphere's centre the big cap's rim gives two terms of
// ~ aO sin rO that cancel to the lens's ~ rl^2, turning a float centroid by several rl.
vec3 apLensMoment(vec3 cS, vec3 tS, float aS, float sinAS, vec2 halfS, vec3 cO, vec3 tO,
  float aO, float sinAO, vec2 halfO, vec2 halfD)
{
  float sinRS = 2.0 * halfS.x * halfS.y, sinRO = 2.0 * halfO.x * halfO.y;
  // sin((rO - d)/2), sin((rO + d)/2), cos((rO + d)/2)
  float dif = halfO.x * halfD.y - halfO.y * halfD.x;
  float sum = halfO.x * halfD.y + halfO.y * halfD.x;
  float cosSum = halfO.y * halfD.y - halfO.x * halfD.x;
  return sinRS * (aS * sinRS * cS + 2.0 * halfS.x * halfS.x * sinAS * tS) +
    sinRO * ((apAngleLessSine(aO, sinAO) * sinRO + 2.0 * sinAO * cosSum * dif) * cO +
              2.0 * sinAO * sum * dif * tO);
}

// Intersection area (sr) of caps whose lens sines are sn (apLensSines), ALGORITHMS.md 1.1/1.2:
// contained (d <= |r1 - r2|: sin(s - r1) or sin(s - r2) not positive) the smaller cap,
// disjoint (d >= r1 + r2: sin(s - d) not positive) nothing, else the sector form
// 4 a1 h1 + 4 a2 h2 - 2 e of the lens (h = sin^2(r/2): no cancellation of nearly equal
// cosines; the acos form is off by thousands of percent for the sun in float). The fourth case
// of 1.1, d >= 2 pi - r1 - r2, needs r1 + r2 > pi: not with radii of at most pi/2.
// partial: whether the caps overlap partially.
float apCapIntersectionExact(vec4 sn, float h1, float h2, float a1, float a2, float e,
  out bool partial)
{
  partial = false;
  if (sn.y <= 0.0 || sn.z <= 0.0) { return 4.0 * AP_PI * min(h1, h2); }
  if (sn.w <= 0.0) { return 0.0; }
  partial = true;
  return max(0.0, 4.0 * a1 * h1 + 4.0 * a2 * h2 - 2.0 * e);
}

// Oat & Sander's approximation, ALGORITHMS.md 1.4: the smaller cap's area times a smoothstep
// of the normalised axis distance (h = sin^2(r/2)).
float apCapIntersectionSmoothstep(float r1, float r2, float d, float h1, float h2)
{
  float amin = 4.0 * AP_PI * min(h1, h2), diff = abs(r1 - r2);
  if (d <= diff) { return amin; }
  if (d >= r1 + r2) { return 0.0; }
  float x = 1.0 - (d - diff) / (r1 + r2 - diff);
  return amin * x * x * (3.0 - 2.0 * x);
}

// Integral of max(0, n.w) over a cap of half-angle sigma <= pi/2 whose axis makes cosT with n:
// Snyder (1996) in Frostbite's form, ALGORITHMS.md 6.1, with x = sqrt(1/sin^2 sigma - 1)
// = cos sigma / sin sigma and atan(sy / x) = atan2(sy sin sigma, cos sigma).
float apCapCosineIntegral(float cosT, float sinS, float cosS)
{
  float sin2s = sinS * sinS;
  if (cosT * cosT >= sin2s) { return AP_PI * sin2s * max(cosT, 0.0); }
  float sinT = sqrt(max(0.0, 1.0 - cosT * cosT));
  float y = -cosS * cosT / (sinS * sinT);
  float w = sqrt(max(0.0, (1.0 - y) * (1.0 + y))), sy = sinT * w; // (w = sin acos y)
  float t = apAtan2(sy * sinS, cosS);
  return max(0.0, cosT * apAtan2(w, y) * sin2s - cosS * sinS * sy + t);
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
  float az = apAtan2(b.x, b.y);
  if (az < 0.0) { az += 2.0 * AP_PI; }
  float el = clamp(apAtan2(b.z, length(b.xy)), 0.0, 0.5 * AP_PI);
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

// Nodata: NaN, a negative radius, vectors whose largest component (in magnitude) is below
// 2^-100 or 2^62 and above (their squares would overflow), as ComputeReference takes them (a
// black point). The others are scaled by that component before normalize(), so that their
// squares neither underflow nor overflow; a component a GPU flushes to 0 (subnormal: below
// 2^-126) is then under 2^-26 of the largest, no matter.
float apLargest(vec3 apV)
{
  vec3 apA = abs(apV);
  return max(apA.x, max(apA.y, apA.z));
}
bool apUsable(vec3 apV)
{
  float apM = apLargest(apV);
  return !any(isnan(apV)) && apM >= 7.8886091e-31 && apM < 4.611686e18;
}
bool apValid(vec3 apN, vec3 apB, float apRp)
{
  return !(isnan(apRp) || isnan(apN.x) || isnan(apB.x)) && apRp >= 0.0 && apUsable(apN) &&
    apUsable(apB);
}

// The aperture's half-angle sine and cosine: (sin(rp/2), cos(rp/2)), rp in [0, pi/2].
vec2 apApertureHalf(float apRp)
{
  float apSh = sin(0.5 * apRp);
  return vec2(apSh, sqrt(max(0.0, 1.0 - apSh * apSh)));
}

// The irradiance of a point (W/m2, RGB): sun through the aperture plus the sky filling the rest
// of it (ap_light.c, step by step). apN: normal, apB: bent normal, apRp: aperture radius (rad).
// Nodata (NaN, zero vectors) gives 0: a black point.
vec3 apIrradiance(vec3 apN, vec3 apB, float apRp)
{
  vec3 apE = vec3(0.0);
  if (apValid(apN, apB, apRp))
  {
    apN = normalize(apN / apLargest(apN));
    apB = normalize(apB / apLargest(apB));
    apRp = clamp(apRp, 0.0, 0.5 * AP_PI);
    vec3 apS = apertureSunDirection;
    float apRl = apertureSunRadius;
    // the aperture's half-angle (sine, cosine), h = sin^2(rp/2), sin rp and cos rp = 1 - 2h
    vec2 apHalf = apApertureHalf(apRp);
    float apHp = apHalf.x * apHalf.x;
    float apSinRp = 2.0 * apHalf.x * apHalf.y, apCosRp = 1.0 - 2.0 * apHp;
    float apHl = apertureSunHalf.x * apertureSunHalf.x;
    // 1. the sun's radiance, so that a fully visible sun facing the surface gives Esun:
    //    Esun / (pi sin^2 rl), computed once on the CPU
    vec3 apLsun = apertureSunRadiance;
    // 2. the visible part of the sun: aperture cap (b, rp) against the sun cap (s, rl), axes
    //    d apart: cos d = b.s, sin d = |b x s|
    float apCd = dot(apB, apS), apSd = length(cross(apB, apS));
    vec2 apHd = apHalfAngle(apCd, apSd);
    vec4 apSn = apLensSines(apHalf, apertureSunHalf, apHd);
    float apA1, apA2, apSinA1, apSinA2, apE3;
    apCapLens(apSn, apCosRp, apertureSunCos, apCd, apA1, apA2, apSinA1, apSinA2, apE3);
    bool apPartial;
    float apVis = apCapIntersectionExact(apSn, apHp, apHl, apA1, apA2, apE3, apPartial);
#ifdef AP_SMOOTHSTEP
    apVis = apCapIntersectionSmoothstep(apRp, apRl, apAtan2(apSd, apCd), apHp, apHl);
#endif
    if (apRp <= 0.0)
    {
      apVis = 0.0;
    }
    // 3. the Lambert term S (sr): cosine-weighted visible sun
    float apS_ = 0.0;
#ifdef AP_EXACT_CAP
    // exact cap: the sun cap's clipped cosine integral times its visible fraction
    apS_ = apCapCosineIntegral(dot(apN, apS), apertureSunSin, apertureSunCos) * apVis /
      apertureSunArea;
#else
    {
      // centroid: area times the cosine of the lens centroid (first moment, 1.6); in
      // containment the smaller cap's axis, else the lens's moment about the smaller cap's
      // axis, with the tangents t1 = (s - cos d b) / sin d at b and t2 = (b - cos d s) / sin d
      // at s
      vec3 apC = apRp < apRl ? apB : apS;
      if (apPartial)
      {
        vec3 apT1 = (apS - apCd * apB) / apSd, apT2 = (apB - apCd * apS) / apSd;
        apC = normalize(apRp <= apRl
            ? apLensMoment(apB, apT1, apA1, apSinA1, apHalf, apS, apT2, apA2, apSinA2,
                apertureSunHalf, apHd)
            : apLensMoment(apS, apT2, apA2, apSinA2, apertureSunHalf, apB, apT1, apA1, apSinA1,
                apHalf, apHd));
      }
      apS_ = apVis * max(0.0, dot(apN, apC));
    }
#endif
    // 4. the sky: the aperture's cosine-weighted solid angle less the sun's share
    float apSky = max(0.0, apCapCosineIntegral(dot(apN, apB), apSinRp, apCosRp) - apS_);
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
