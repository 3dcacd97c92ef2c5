/* SPDX-License-Identifier: BSD-3-Clause */
#include "ap_grid.h"

#include <float.h>
#include <math.h>
#include <stdint.h>

ap_grid_view ap_grid_view_make(const float *z, size_t nx, size_t ny)
{
  ap_grid_view g;
  g.z = z;
  g.nx = nx;
  g.ny = ny;
  g.row_stride = (ptrdiff_t)nx;
  return g;
}

ap_status ap_size_mul(size_t a, size_t b, size_t *out)
{
  if (!out) {
    return AP_ERR_NULL_POINTER;
  }
  if (a != 0 && b > SIZE_MAX / a) {
    return AP_ERR_SIZE_OVERFLOW;
  }
  *out = a * b;
  return AP_OK;
}

static size_t abs_stride(ptrdiff_t s)
{
  /* PTRDIFF_MIN has no positive counterpart; treat it as too large (caught by the caller). */
  return s == PTRDIFF_MIN ? SIZE_MAX : (size_t)(s < 0 ? -s : s);
}

ap_status ap_grid_validate(const ap_grid_view *g, size_t min_nx, size_t min_ny)
{
  size_t cells;
  if (!g || !g->z) {
    return AP_ERR_NULL_POINTER;
  }
  if (g->nx < min_nx || g->ny < min_ny || g->nx == 0 || g->ny == 0) {
    return AP_ERR_GRID_TOO_SMALL;
  }
  if (g->nx > (size_t)PTRDIFF_MAX) { /* (no stride can span such a row) */
    return AP_ERR_SIZE_OVERFLOW;
  }
  if (abs_stride(g->row_stride) < g->nx) {
    return AP_ERR_BAD_STRIDE;
  }
  /* The last row must be addressable: (ny - 1) * |stride| + nx elements, in bytes. */
  if (ap_size_mul(g->ny - 1, abs_stride(g->row_stride), &cells) != AP_OK ||
      cells > SIZE_MAX - g->nx || cells + g->nx > SIZE_MAX / sizeof(float) ||
      cells > (size_t)PTRDIFF_MAX) {
    return AP_ERR_SIZE_OVERFLOW;
  }
  return AP_OK;
}

ap_status ap_grid_stats_compute(const ap_grid_view *g, ap_grid_stats *stats)
{
  ap_status st;
  double lo = INFINITY, hi = -INFINITY, sum = 0.0;
  size_t valid = 0, nodata = 0, i, j;
  if (!stats) {
    return AP_ERR_NULL_POINTER;
  }
  st = ap_grid_validate(g, 1, 1);
  if (st != AP_OK) {
    return st;
  }
  for (j = 0; j < g->ny; ++j) {
    const float *row = g->z + (ptrdiff_t)j * g->row_stride;
    for (i = 0; i < g->nx; ++i) {
      const double v = row[i];
      if (isnan(v)) {
        ++nodata;
        continue;
      }
      ++valid;
      sum += v;
      if (v < lo) {
        lo = v;
      }
      if (v > hi) {
        hi = v;
      }
    }
  }
  stats->valid = valid;
  stats->nodata = nodata;
  if (valid == 0) {
    stats->min = stats->max = stats->mean = NAN;
  } else {
    stats->min = lo;
    stats->max = hi;
    stats->mean = sum / (double)valid;
  }
  return AP_OK;
}

void ap_sample_params_init(ap_sample_params *p)
{
  if (!p) {
    return;
  }
  p->has_nodata = 0;
  p->nodata = NAN;
  p->nodata_near = 0;
  p->scale = 1.0;
  p->offset = 0.0;
  p->signed_byte = 0;
}

static int ranges_overlap(const void *a, size_t abytes, const void *b, size_t bbytes)
{
  const uintptr_t pa = (uintptr_t)a, pb = (uintptr_t)b;
  return pa < pb + bbytes && pb < pa + abytes;
}

int ap_sample_declared_nodata(const ap_sample_params *p, double r)
{
  /* (GDAL sums two float32 samples in float, so beyond +-1.7e38, where the sum overflows, it
   * takes any two of one sign as equal; the sum here is a double's, and no elevation lies
   * there.) */
  return p->has_nodata &&
         (r == p->nodata ||
          (p->nodata_near && fabs(r - p->nodata) < 2.0 * FLT_EPSILON * fabs(r + p->nodata)));
}

ap_status ap_samples_to_elevation(const double *raw, size_t n, const ap_sample_params *p,
                                  float *out, size_t *scaled_out)
{
  size_t k, scaled = 0;
  if (scaled_out) {
    *scaled_out = 0;
  }
  if (!p || (n > 0 && (!raw || !out))) {
    return AP_ERR_NULL_POINTER;
  }
  if (!isfinite(p->scale) || !isfinite(p->offset)) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  if (n > SIZE_MAX / sizeof(double)) {
    return AP_ERR_SIZE_OVERFLOW;
  }
  if (n > 0 && ranges_overlap(raw, n * sizeof(double), out, n * sizeof(float))) {
    return AP_ERR_OVERLAP;
  }
  for (k = 0; k < n; ++k) {
    const double r = p->signed_byte && raw[k] >= 128.0 ? raw[k] - 256.0 : raw[k];
    double v;
    /* Compare with the nodata value before scaling: nodata is defined on raw samples. */
    if (!isfinite(r) || ap_sample_declared_nodata(p, r)) {
      out[k] = NAN;
      continue;
    }
    v = r * p->scale + p->offset;
    if (fabs(v) <= FLT_MAX) {
      out[k] = (float)v;
    } else {
      out[k] = NAN;
      scaled += fabs(r) <= FLT_MAX;
    }
  }
  if (scaled_out) {
    *scaled_out = scaled;
  }
  return AP_OK;
}

ap_status ap_block_mean(const float *src, size_t nx, ptrdiff_t src_row_stride, size_t factor,
                        float *dst)
{
  size_t b, nb, r, c;
  if (!src || !dst) {
    return AP_ERR_NULL_POINTER;
  }
  if (factor == 0) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  if (abs_stride(src_row_stride) < nx) {
    return AP_ERR_BAD_STRIDE;
  }
  nb = nx / factor;
  for (b = 0; b < nb; ++b) {
    double sum = 0.0;
    size_t count = 0;
    for (r = 0; r < factor; ++r) {
      const float *row = src + (ptrdiff_t)r * src_row_stride + b * factor;
      for (c = 0; c < factor; ++c) {
        if (!isnan(row[c])) {
          sum += row[c];
          ++count;
        }
      }
    }
    dst[b] = count ? (float)(sum / (double)count) : NAN;
  }
  return AP_OK;
}
