/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal to the kernels (not installed): arctan in single precision without a library call,
 * so that the per-sector loops of ap_horizon.c vectorise (eight cells per AVX2 instruction).
 * Moshier's Cephes atanf: reduction to |r| <= tan(pi/8) by atan x = pi/4 + atan((x-1)/(x+1))
 * and atan x = pi/2 - atan(1/x), then an odd polynomial of degree 9, written with selects
 * instead of branches. Within 2.1e-7 relative of atan for every positive float from 1e-30 up
 * (checked exhaustively when written; test_ap_horizon checks 2^20 floats spread over the whole
 * range and the reduction's boundaries); atan(+-inf) = +-pi/2, atan(+-0) = +-0, NaN gives NaN.
 * The per-sector terms need no more: each is an addend of a float sum. */
#ifndef AP_ATANF_H
#define AP_ATANF_H

#include <math.h>

#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline float ap_atanf(float x)
{
  const float ax = fabsf(x);
  const int big = ax > 2.414213562373095f, mid = ax > 0.4142135623730950f; /* tan(3pi/8, pi/8) */
  const float num = big ? -1.0f : (mid ? ax - 1.0f : ax);
  const float den = big ? ax : (mid ? ax + 1.0f : 1.0f);
  const float r = num / den, z = r * r;
  const float base = big ? 1.5707963267948966f : (mid ? 0.7853981633974483f : 0.0f);
  const float poly =
    (((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z -
     3.33329491539e-1f) * z * r + r;
  return copysignf(base + poly, x);
}

#endif
