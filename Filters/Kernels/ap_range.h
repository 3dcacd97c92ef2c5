/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal to the kernels (not installed): the range check behind ap_sky_params_invalid and
 * ap_sun_params_invalid, which name the first field of a parameter struct outside its
 * documented range. */
#ifndef AP_RANGE_H
#define AP_RANGE_H

#include <stddef.h>

/** One field: its name in its struct, its value, its range, each end included unless open. */
typedef struct ap_range_field {
  const char *name;
  double value, lo, hi;
  int lo_open, hi_open;
} ap_range_field;

/** The name of the first of the n fields outside its range (NaN is outside every range), with
 *  that range in *lo and *hi (either may be NULL); NULL when all are within. */
static inline const char *ap_range_first_outside(const ap_range_field *f, size_t n, double *lo,
                                                 double *hi)
{
  size_t i;
  for (i = 0; i < n; ++i) {
    const double v = f[i].value;
    const int low_ok = f[i].lo_open ? v > f[i].lo : v >= f[i].lo;
    const int high_ok = f[i].hi_open ? v < f[i].hi : v <= f[i].hi;
    if (!low_ok || !high_ok) {
      if (lo) {
        *lo = f[i].lo;
      }
      if (hi) {
        *hi = f[i].hi;
      }
      return f[i].name;
    }
  }
  return NULL;
}

#endif /* AP_RANGE_H */
