/* SPDX-License-Identifier: BSD-3-Clause */
/** @file ap_grid.h
 *  @brief Views of regular elevation grids, overflow-checked sizes, statistics and the
 *         conversion of raw raster samples to elevations.
 *
 *  Orientation: row 0 is the southern row and column 0 the western column (VTK's image order);
 *  readers flip north-up rasters once, at I/O. Nodata is NaN everywhere in the core.
 */
#ifndef AP_GRID_H
#define AP_GRID_H

#include <stddef.h>

#include "ap_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Read-only view of a grid of elevations (caller-owned memory; nothing is copied or kept). */
typedef struct ap_grid_view {
  const float *z;       /**< elevation (metres) of cell (i, j) at z[j * row_stride + i];
                             NaN = nodata */
  size_t nx, ny;        /**< columns (west to east), rows (south to north) */
  ptrdiff_t row_stride; /**< elements between the starts of consecutive rows; |row_stride| >= nx */
} ap_grid_view;

/** Make a view of a contiguous grid (row_stride = nx). */
ap_grid_view ap_grid_view_make(const float *z, size_t nx, size_t ny);

/** Product a * b; AP_ERR_SIZE_OVERFLOW if it does not fit in size_t (then *out is untouched). */
ap_status ap_size_mul(size_t a, size_t b, size_t *out);

/** Check a view: non-NULL data, at least min_nx columns and min_ny rows, |row_stride| >= nx,
 *  and an addressable extent. Returns AP_OK or the first problem found. */
ap_status ap_grid_validate(const ap_grid_view *g, size_t min_nx, size_t min_ny);

/** Summary of a grid. With no valid cell, min, max and mean are NaN. */
typedef struct ap_grid_stats {
  double min, max; /**< range of the valid elevations (metres) */
  double mean;     /**< mean of the valid elevations, summed in row order (deterministic) */
  size_t valid;    /**< number of cells that are not NaN */
  size_t nodata;   /**< number of NaN cells */
} ap_grid_stats;

/** Statistics of a validated view (any size >= 1 x 1). Errors only on a NULL argument or an
 *  invalid view. */
ap_status ap_grid_stats_compute(const ap_grid_view *g, ap_grid_stats *stats);

/** How raw raster samples become elevations; always initialise with ap_sample_params_init(). */
typedef struct ap_sample_params {
  int has_nodata; /**< nonzero: samples equal to `nodata` are nodata (default 0) */
  double nodata;  /**< the raster's nodata value, compared before scaling (default NaN) */
  int nodata_near; /**< nonzero (float bands): samples near `nodata` are nodata too, as GDAL's
                        nodata mask compares floats: |raw - nodata| < 2 FLT_EPSILON
                        |raw + nodata|, about 2 float32 ulps (ArcGIS declares
                        -3.4028230607370965e38 for cells of -FLT_MAX, two ulps apart); 0: equal
                        only (integer bands, where such a width spans whole integers)
                        (default 0) */
  double scale;   /**< elevation = raw * scale + offset (default 1); include unit factors here */
  double offset;  /**< (default 0) */
  int signed_byte; /**< nonzero: raw samples 0..255 are bytes holding two's-complement int8
                        (GDAL 3.6's Int8, a Byte band with PIXELTYPE=SIGNEDBYTE): 128..255
                        are read as -128..-1 before the nodata test and scaling (default 0) */
} ap_sample_params;

/** Set the defaults documented on each field. */
void ap_sample_params_init(ap_sample_params *p);

/** Whether raw sample r (after signed_byte's reading) is the declared nodata value as
 *  ap_samples_to_elevation tests it: has_nodata, and equal to it or, with nodata_near, within
 *  its width. 1 or 0. (Samples that are not finite are nodata there as well, but not declared
 *  unless equal; the reader's warnings of undeclared ones ask this.) p must not be NULL. */
int ap_sample_declared_nodata(const ap_sample_params *p, double r);

/** Convert n raw samples to float32 elevations. A sample becomes NaN when it is not finite,
 *  equals the nodata value (or is near it: nodata_near), or scales to a value outside the
 *  float range; otherwise out[k] = (float)(raw[k] * scale + offset). `raw` and `out` must not
 *  overlap. `scaled_out` (may be NULL) gets the number of samples within the float range that scale
 *  and offset took beyond it (NaN too, but a sign of a wrong scale or offset rather than of
 *  an undeclared huge nodata value such as -1.79e308, -DBL_MAX).
 *  Never fails on data; returns AP_ERR_NULL_POINTER / AP_ERR_INVALID_ARGUMENT (non-finite
 *  scale or offset) / AP_ERR_SIZE_OVERFLOW (n doubles exceed the address space) /
 *  AP_ERR_OVERLAP only for bad arguments. */
ap_status ap_samples_to_elevation(const double *raw, size_t n, const ap_sample_params *p,
                                  float *out, size_t *scaled_out);

/** Mean of factor x factor blocks, for decimating a strip of `factor` rows.
 *  `src` holds `factor` rows of `nx` values, rows `src_row_stride` elements apart; `dst`
 *  receives nx / factor values (a partial block at the east end is dropped). NaN cells are
 *  ignored; a block with no valid cell gives NaN. Each block is summed in row order in double
 *  precision, so the result does not depend on how the caller splits the work. Returns AP_OK,
 *  or AP_ERR_NULL_POINTER (src or dst NULL), AP_ERR_INVALID_ARGUMENT (factor 0) or
 *  AP_ERR_BAD_STRIDE (|src_row_stride| < nx), writing nothing. */
ap_status ap_block_mean(const float *src, size_t nx, ptrdiff_t src_row_stride, size_t factor,
                        float *dst);

#ifdef __cplusplus
}
#endif

#endif /* AP_GRID_H */
