/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal to the kernels (not installed): the per-sector terms of ap_horizon.c's sky sums that
 * vanish at the zenith, in single precision and in forms that keep float's relative precision
 * there (a shaft's every horizon within 1e-4 rad of the zenith: 1 - sin h and Q(h) cancelled
 * to nothing, and its bent normal came out 52 degrees off). Branch-free (selects), inlined, so
 * that the loops calling them vectorise. test_ap_horizon checks them against long double. */
#ifndef AP_ZENITH_H
#define AP_ZENITH_H

#include "ap_atanf.h"

/* The zenith distance u = pi/2 - atan(t) of an elevation of tangent t >= 0 (infinity and 0
 * included), as atan(1 / t) above 45 degrees: within 2.3e-7 of u, relatively, where
 * pi/2 - atan(t) leaves 1e-7 rad of rounding near the zenith. */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline float ap_zenith_distance(float t)
{
  const int steep = t > 1.0f;
  const float a = ap_atanf(steep ? 1.0f / t : t);
  return steep ? a : 1.5707963267948966f - a;
}

/* Q(h) = (pi/2 - h - sin h cos h) / 2 = (x - sin x) / 4 with x = 2u (u the zenith distance,
 * s = sin h, c = cos h): by its Taylor series to x^11 below x = 1.5 (truncated within 6e-8),
 * directly above; within 8e-7 of Q, relatively, for any float tangent (measured on 2e6
 * horizons: the rounding and u's 2e-7; the direct form at x = 1, where it was taken before
 * 2026-12-07, is 2e-6 off). */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline float ap_zenith_q(float u, float s, float c)
{
  const float x = 2.0f * u, x2 = x * x;
  const float tail = 1.0f - (x2 / 42.0f) * (1.0f - (x2 / 72.0f) * (1.0f - x2 / 110.0f));
  const float series = (x * x2 / 24.0f) * (1.0f - (x2 / 20.0f) * tail);
  return x < 1.5f ? series : 0.5f * (u - s * c);
}

#endif
