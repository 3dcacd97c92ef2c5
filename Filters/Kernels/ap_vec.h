/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal to the kernels (not installed): the small 3-vector helpers that ap_light.c, ap_sky.c
 * and ap_sun.c share. */
#ifndef AP_VEC_H
#define AP_VEC_H

static inline double dot3(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* out = a × b; out must not alias a or b. */
static inline void cross3(const double a[3], const double b[3], double out[3])
{
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

/* x clamped to [-1, 1] before acos/asin; NaN stays NaN. */
static inline double clamp1(double x)
{
  return x > 1.0 ? 1.0 : (x < -1.0 ? -1.0 : x);
}

#endif
