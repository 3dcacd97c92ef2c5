/* SPDX-License-Identifier: BSD-3-Clause */
/* Unit tests of ap_grid: views, overflow-checked sizes, statistics, sample conversion and
 * block-mean decimation. Expected values are computed by hand in the comments. */
#include "ap_grid.h"
#include "aptest.h"

#include <float.h>
#include <stdint.h>
#include <string.h>

/* Check ap_size_mul at and beyond the edge of size_t. */
static void test_size_mul(void)
{
  size_t out = 7;
  AP_CHECK_EQ_INT(ap_size_mul(3, 5, &out), AP_OK);
  AP_CHECK_EQ_INT(out, 15);
  AP_CHECK_EQ_INT(ap_size_mul(0, SIZE_MAX, &out), AP_OK);
  AP_CHECK_EQ_INT(out, 0);
  AP_CHECK_EQ_INT(ap_size_mul(SIZE_MAX / 2, 2, &out), AP_OK);
  out = 42;
  AP_CHECK_EQ_INT(ap_size_mul(SIZE_MAX / 2 + 1, 2, &out), AP_ERR_SIZE_OVERFLOW);
  AP_CHECK_EQ_INT(out, 42); /* untouched on overflow */
  /* A 10^6 x 10^6 grid of floats fits in 64-bit size_t, 10^10 x 10^10 does not. */
  AP_CHECK_EQ_INT(ap_size_mul(1000000, 1000000, &out), AP_OK);
  AP_CHECK_EQ_INT(ap_size_mul((size_t)1e10, (size_t)1e10, &out), AP_ERR_SIZE_OVERFLOW);
  AP_CHECK_EQ_INT(ap_size_mul(1, 1, NULL), AP_ERR_NULL_POINTER);
}

/* Check that validation catches each kind of bad view. */
static void test_validate(void)
{
  float z[12] = { 0 };
  ap_grid_view g = ap_grid_view_make(z, 4, 3);
  AP_CHECK_EQ_INT(ap_grid_validate(&g, 2, 2), AP_OK);
  AP_CHECK_EQ_INT(ap_grid_validate(NULL, 1, 1), AP_ERR_NULL_POINTER);
  g.z = NULL;
  AP_CHECK_EQ_INT(ap_grid_validate(&g, 1, 1), AP_ERR_NULL_POINTER);
  g = ap_grid_view_make(z, 4, 3);
  AP_CHECK_EQ_INT(ap_grid_validate(&g, 5, 1), AP_ERR_GRID_TOO_SMALL);
  AP_CHECK_EQ_INT(ap_grid_validate(&g, 1, 4), AP_ERR_GRID_TOO_SMALL);
  g.nx = 0;
  AP_CHECK_EQ_INT(ap_grid_validate(&g, 0, 0), AP_ERR_GRID_TOO_SMALL);
  g = ap_grid_view_make(z, 4, 3);
  g.row_stride = 3;
  AP_CHECK_EQ_INT(ap_grid_validate(&g, 1, 1), AP_ERR_BAD_STRIDE);
  g.row_stride = -4; /* a flipped view is fine */
  AP_CHECK_EQ_INT(ap_grid_validate(&g, 1, 1), AP_OK);
  g.row_stride = PTRDIFF_MIN;
  AP_CHECK_EQ_INT(ap_grid_validate(&g, 1, 1), AP_ERR_SIZE_OVERFLOW);
  g = ap_grid_view_make(z, SIZE_MAX / 2, 3); /* rows that cannot be addressed */
  AP_CHECK_EQ_INT(ap_grid_validate(&g, 1, 1), AP_ERR_SIZE_OVERFLOW);
  g = ap_grid_view_make(z, SIZE_MAX, 1); /* (its stride wraps to -1: not a stride problem) */
  AP_CHECK_EQ_INT(ap_grid_validate(&g, 1, 1), AP_ERR_SIZE_OVERFLOW);
}

/* Statistics ignore NaN, count it, and report NaN ranges for an all-nodata grid. */
static void test_stats(void)
{
  /* 3 x 2 grid with one nodata cell: valid values 1, -2, 4, 8, 0.5 -> sum 11.5, mean 2.3. */
  const float z[6] = { 1.0f, -2.0f, NAN, 4.0f, 8.0f, 0.5f };
  ap_grid_view g = ap_grid_view_make(z, 3, 2);
  ap_grid_stats s;
  AP_CHECK_EQ_INT(ap_grid_stats_compute(&g, &s), AP_OK);
  AP_CHECK_EQ_INT(s.valid, 5);
  AP_CHECK_EQ_INT(s.nodata, 1);
  AP_CHECK_NEAR(s.min, -2.0, 0.0);
  AP_CHECK_NEAR(s.max, 8.0, 0.0);
  AP_CHECK_NEAR(s.mean, 2.3, 1e-12);

  /* A view of the last column only, through a stride: values NaN, 0.5 */
  g.z = z + 2;
  g.nx = 1;
  g.row_stride = 3;
  AP_CHECK_EQ_INT(ap_grid_stats_compute(&g, &s), AP_OK);
  AP_CHECK_EQ_INT(s.valid, 1);
  AP_CHECK_EQ_INT(s.nodata, 1);
  AP_CHECK_NEAR(s.mean, 0.5, 0.0);

  /* Flipped view (negative stride) of the same grid: same statistics. */
  g.z = z + 3;
  g.nx = 3;
  g.row_stride = -3;
  AP_CHECK_EQ_INT(ap_grid_stats_compute(&g, &s), AP_OK);
  AP_CHECK_EQ_INT(s.valid, 5);
  AP_CHECK_NEAR(s.min, -2.0, 0.0);

  {
    const float allnan[4] = { NAN, NAN, NAN, NAN };
    ap_grid_view h = ap_grid_view_make(allnan, 2, 2);
    AP_CHECK_EQ_INT(ap_grid_stats_compute(&h, &s), AP_OK);
    AP_CHECK_EQ_INT(s.valid, 0);
    AP_CHECK_EQ_INT(s.nodata, 4);
    AP_CHECK_NAN(s.min);
    AP_CHECK_NAN(s.max);
    AP_CHECK_NAN(s.mean);
  }
  AP_CHECK_EQ_INT(ap_grid_stats_compute(&g, NULL), AP_ERR_NULL_POINTER);
}

/* Nodata is compared on raw samples, before scale and offset; non-finite samples and values
 * outside the float range become NaN. */
static void test_samples(void)
{
  const double raw[7] = { -32768.0, 100.0, -32767.0, NAN, INFINITY, 1e300, 0.0 };
  float out[7];
  size_t scaled = 99;
  ap_sample_params p;
  ap_sample_params_init(&p);
  AP_CHECK_EQ_INT(p.has_nodata, 0);
  AP_CHECK_NEAR(p.scale, 1.0, 0.0);
  AP_CHECK_NEAR(p.offset, 0.0, 0.0);
  p.has_nodata = 1;
  p.nodata = -32768.0;
  p.scale = 0.5;
  p.offset = 10.0;
  AP_CHECK_EQ_INT(ap_samples_to_elevation(raw, 7, &p, out, &scaled), AP_OK);
  AP_CHECK(scaled == 0); /* 1e300 is beyond the float range before scaling */
  AP_CHECK_NAN(out[0]);                     /* the nodata value itself */
  AP_CHECK_NEAR(out[1], 60.0, 0.0);         /* 100 * 0.5 + 10 */
  AP_CHECK_NEAR(out[2], -16373.5, 0.0);     /* one above nodata stays valid */
  AP_CHECK_NAN(out[3]);                     /* NaN sample */
  AP_CHECK_NAN(out[4]);                     /* infinite sample */
  AP_CHECK_NAN(out[5]);                     /* 1e300 does not fit a float */
  AP_CHECK_NEAR(out[6], 10.0, 0.0);

  /* A nodata value that equals a scaled value must not hide it: nodata 60, raw 100 -> 60. */
  p.nodata = 60.0;
  AP_CHECK_EQ_INT(ap_samples_to_elevation(raw + 1, 1, &p, out, NULL), AP_OK);
  AP_CHECK_NEAR(out[0], 60.0, 0.0);

  /* Without nodata, -32768 is an ordinary value. */
  p.has_nodata = 0;
  AP_CHECK_EQ_INT(ap_samples_to_elevation(raw, 1, &p, out, NULL), AP_OK);
  AP_CHECK_NEAR(out[0], -16374.0, 0.0);

  /* nodata_near, as GDAL 3.6's nodata mask band took these float32 samples (a GeoTIFF of
   * each, read back through its mask): ArcGIS's nodata -3.4028230607370965e38 masks cells of
   * -FLT_MAX; -9999 masks -9999.00390625 but not -9999.005859375; 0 masks no other number. */
  {
    const struct {
      double nodata, raw;
      int is_nodata;
    } near[] = {
      { -3.4028230607370965e38, -FLT_MAX, 1 },
      { -3.4028230607370965e38, -3.4028230607370965e38, 1 },
      { -9999.0, -9999.0009765625, 1 },
      { -9999.0, -9999.00390625, 1 },
      { -9999.0, -9999.005859375, 0 },
      { -9999.0, -9999.009765625, 0 },
      { 1.0, 1.0000004768371582, 1 },
      { 0.0, 1e-30, 0 },
      { 0.0, -1e-30, 0 },
    };
    size_t k;
    p.has_nodata = 1;
    p.scale = 1.0;
    p.offset = 0.0;
    for (k = 0; k < sizeof near / sizeof near[0]; ++k) {
      p.nodata = near[k].nodata;
      p.nodata_near = 1;
      AP_CHECK_EQ_INT(ap_samples_to_elevation(&near[k].raw, 1, &p, out, NULL), AP_OK);
      AP_CHECK_EQ_INT(isnan(out[0]) != 0, near[k].is_nodata);
      AP_CHECK_EQ_INT(ap_sample_declared_nodata(&p, near[k].raw), near[k].is_nodata);
      /* without it (integer bands), only the value itself */
      p.nodata_near = 0;
      AP_CHECK_EQ_INT(ap_samples_to_elevation(&near[k].raw, 1, &p, out, NULL), AP_OK);
      AP_CHECK_EQ_INT(isnan(out[0]) != 0, near[k].raw == near[k].nodata);
      AP_CHECK_EQ_INT(ap_sample_declared_nodata(&p, near[k].raw), near[k].raw == near[k].nodata);
    }
    /* an integer band's nodata 4294967295 (UInt32) leaves its neighbour a height (within 2
     * FLT_EPSILON of it relatively: nodata_near would take it) */
    p.nodata = 4294967295.0;
    AP_CHECK_EQ_INT(ap_samples_to_elevation(&(double){ 4294967294.0 }, 1, &p, out, NULL), AP_OK);
    AP_CHECK_NEAR(out[0], (float)4294967294.0, 0.0);
    /* infinities are declared only as themselves, and nothing without a nodata value */
    p.nodata_near = 1;
    p.nodata = -INFINITY;
    AP_CHECK_EQ_INT(ap_sample_declared_nodata(&p, -INFINITY), 1);
    AP_CHECK_EQ_INT(ap_sample_declared_nodata(&p, INFINITY), 0);
    AP_CHECK_EQ_INT(ap_sample_declared_nodata(&p, -1.7976931348623157e308), 0);
    p.has_nodata = 0;
    AP_CHECK_EQ_INT(ap_sample_declared_nodata(&p, -INFINITY), 0);
    p.nodata_near = 0;
  }

  /* Argument errors. */
  AP_CHECK_EQ_INT(ap_samples_to_elevation(raw, SIZE_MAX / 4, &p, out, NULL),
                  AP_ERR_SIZE_OVERFLOW);
  p.scale = NAN;
  AP_CHECK_EQ_INT(ap_samples_to_elevation(raw, 1, &p, out, NULL), AP_ERR_INVALID_ARGUMENT);
  p.scale = 1.0;
  AP_CHECK_EQ_INT(ap_samples_to_elevation(NULL, 1, &p, out, NULL), AP_ERR_NULL_POINTER);
  AP_CHECK_EQ_INT(ap_samples_to_elevation(raw, 0, &p, NULL, NULL), AP_OK); /* nothing to do */
  {
    double buf[4] = { 1, 2, 3, 4 };
    AP_CHECK_EQ_INT(ap_samples_to_elevation(buf, 4, &p, (float *)(void *)(buf + 1), NULL),
                    AP_ERR_OVERLAP);
  }

  /* A scale that takes samples within the float range beyond it is counted (a wrong scale);
   * samples beyond it already (an undeclared nodata such as -DBL_MAX) are not. */
  {
    const double big[4] = { 1e30, -1e30, 1.0, -1.7976931348623157e308 };
    p.has_nodata = 0;
    p.scale = 1e10;
    p.offset = 0.0;
    AP_CHECK_EQ_INT(ap_samples_to_elevation(big, 4, &p, out, &scaled), AP_OK);
    AP_CHECK(scaled == 2);
    AP_CHECK_NAN(out[0]);
    AP_CHECK_NAN(out[1]);
    AP_CHECK_NEAR(out[2], 1e10, 0.0);
    AP_CHECK_NAN(out[3]);
    p.scale = 1.0;
    AP_CHECK_EQ_INT(ap_samples_to_elevation(big, 4, &p, out, &scaled), AP_OK);
    AP_CHECK(scaled == 0);
    AP_CHECK_NEAR(out[0], 1e30, 1e23);
  }

  /* GDAL 3.6's Int8: bytes read as 0..255 hold -128..127; nodata -1 is the byte 255. */
  {
    const double bytes[5] = { 0.0, 127.0, 128.0, 254.0, 255.0 };
    AP_CHECK_EQ_INT(p.signed_byte, 0);
    p.signed_byte = 1;
    p.has_nodata = 1;
    p.nodata = -1.0;
    p.scale = 2.0;
    p.offset = 0.5;
    AP_CHECK_EQ_INT(ap_samples_to_elevation(bytes, 5, &p, out, NULL), AP_OK);
    AP_CHECK_NEAR(out[0], 0.5, 0.0);
    AP_CHECK_NEAR(out[1], 254.5, 0.0);   /* 127 * 2 + 0.5 */
    AP_CHECK_NEAR(out[2], -255.5, 0.0);  /* -128 * 2 + 0.5 */
    AP_CHECK_NEAR(out[3], -3.5, 0.0);    /* -2 * 2 + 0.5 */
    AP_CHECK_NAN(out[4]);                /* -1: nodata */
    p.signed_byte = 0;                   /* as unsigned bytes, 255 is no nodata */
    AP_CHECK_EQ_INT(ap_samples_to_elevation(bytes, 5, &p, out, NULL), AP_OK);
    AP_CHECK_NEAR(out[4], 510.5, 0.0);
  }
}

/* Block means of a strip: NaN ignored, all-NaN blocks NaN, the partial block dropped. */
static void test_block_mean(void)
{
  /* Two rows of 7, factor 2 -> 3 blocks (column 6 dropped).
   * block 0: 1 2 / 3 4 -> 2.5; block 1: NaN 6 / 7 NaN -> 6.5; block 2: NaN NaN / NaN NaN -> NaN */
  const float src[14] = { 1, 2, NAN, 6, NAN, NAN, 99, 3, 4, 7, NAN, NAN, NAN, 99 };
  float dst[4] = { -1, -1, -1, -1 };
  AP_CHECK_EQ_INT(ap_block_mean(src, 7, 7, 2, dst), AP_OK);
  AP_CHECK_NEAR(dst[0], 2.5, 0.0);
  AP_CHECK_NEAR(dst[1], 6.5, 0.0);
  AP_CHECK_NAN(dst[2]);
  AP_CHECK_NEAR(dst[3], -1.0, 0.0); /* untouched */
  /* Factor 1 copies. */
  AP_CHECK_EQ_INT(ap_block_mean(src, 2, 7, 1, dst), AP_OK);
  AP_CHECK_NEAR(dst[0], 1.0, 0.0);
  AP_CHECK_NEAR(dst[1], 2.0, 0.0);
  AP_CHECK_EQ_INT(ap_block_mean(src, 7, 7, 0, dst), AP_ERR_INVALID_ARGUMENT);
  AP_CHECK_EQ_INT(ap_block_mean(src, 7, 6, 2, dst), AP_ERR_BAD_STRIDE);
  AP_CHECK_EQ_INT(ap_block_mean(NULL, 7, 7, 2, dst), AP_ERR_NULL_POINTER);
}

/* Every status has its own text, and only the codes past the last are unknown (a status added
 * after AP_STATUS_LAST without moving it has a text past it, which fails here). */
static void test_status_strings(void)
{
  int a, b;
  for (a = AP_OK; a <= AP_STATUS_LAST; ++a) {
    AP_CHECK(ap_status_string((ap_status)a) != NULL);
    AP_CHECK(strcmp(ap_status_string((ap_status)a), "unknown status") != 0);
    for (b = a + 1; b <= AP_STATUS_LAST; ++b) {
      AP_CHECK(strcmp(ap_status_string((ap_status)a), ap_status_string((ap_status)b)) != 0);
    }
  }
  AP_CHECK_EQ_INT(AP_STATUS_LAST, AP_ERR_TIME_AMBIGUOUS);
  AP_CHECK(strcmp(ap_status_string((ap_status)(AP_STATUS_LAST + 1)), "unknown status") == 0);
  AP_CHECK(strcmp(ap_status_string((ap_status)999), "unknown status") == 0);
  AP_CHECK(strcmp(ap_status_string((ap_status)-1), "unknown status") == 0);
}

int main(void)
{
  AP_TEST_RUN(test_size_mul);
  AP_TEST_RUN(test_validate);
  AP_TEST_RUN(test_stats);
  AP_TEST_RUN(test_samples);
  AP_TEST_RUN(test_block_mean);
  AP_TEST_RUN(test_status_strings);
  AP_TEST_MAIN_END();
}
