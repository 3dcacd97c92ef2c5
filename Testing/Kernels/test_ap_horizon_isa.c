/* SPDX-License-Identifier: BSD-3-Clause */
/* Prints one line per configuration: a hash of every bit of every sky product (horizon angles
 * included) of ap_horizon_run on rough synthetic terrain with nodata holes. Built twice: once
 * against the kernel library (whose hot loops are compiled for x86-64-v4, AVX2 and the baseline,
 * the CPU picking at run time) and once from the kernel's sources with
 * AP_HORIZON_NO_MULTIVERSION (the baseline alone). The test Kernels-isa-equality
 * (isa_equality.cmake) runs both and requires the same lines: the clones make the same IEEE
 * operations in the same order, so the results must not depend on the CPU. The configurations
 * cover every search path: the exact march (short radius), the far march (4 km; projected and
 * lat/lon rows), the sweep (unlimited), x-major and y-major sectors, D not a multiple of 4.
 * Built a third time with AP_HORIZON_NO_VOID_SKIP too (every stretch of the crossings beside
 * nodata tested, none ruled out for lying in rows or columns without nodata), for the test
 * Kernels-void-skip-equality: the same lines again. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ap_horizon.h"

static double rough(double x, double y)
{
  /* (through int64_t: a double beyond unsigned's range does not convert to it) */
  unsigned h = (unsigned)(int64_t)(x * 73856093.0) ^ (unsigned)(int64_t)(y * 19349663.0);
  h = (h ^ (h >> 13)) * 1274126177u;
  return 300 * sin(x / 900) * cos(y / 700) + 120 * sin(x / 230 + 1.3) * sin(y / 310) +
         40 * cos(x / 70 - y / 90) + 6.0 * ((double)(h & 1023u) / 1023.0 - 0.5);
}

static uint64_t fnv(uint64_t h, const void *data, size_t bytes)
{
  const unsigned char *b = (const unsigned char *)data;
  size_t i;
  for (i = 0; i < bytes; ++i) {
    h = (h ^ b[i]) * 1099511628211ull;
  }
  return h;
}

/* Hash of every product of one run; 0 with the status on failure. */
static uint64_t run(const ap_horizon_grid *g, const ap_horizon_params *p, ap_status *status)
{
  const size_t n = g->z.nx * g->z.ny, D = (size_t)p->directions;
  float *f = (float *)malloc(n * (9 + D) * sizeof(float));
  unsigned char *edge = (unsigned char *)malloc(n);
  uint64_t h = 1469598103934665603ull;
  ap_sky_products o;
  if (!f || !edge) {
    free(f);
    free(edge);
    *status = AP_ERR_OUT_OF_MEMORY;
    return 0;
  }
  o.visible_solid_angle = f;
  o.aperture_radius = f + n;
  o.bent_normal = f + 2 * n;
  o.sky_view_factor = f + 5 * n;
  o.diffuse_sky_factor = f + 6 * n;
  o.positive_openness = f + 7 * n;
  o.edge_truncated = edge;
  o.horizon_angles = f + 9 * n;
  memset(f + 8 * n, 0, n * sizeof(float)); /* (unused slot) */
  *status = ap_horizon_run(g, p, &o);
  if (*status == AP_OK) {
    h = fnv(fnv(h, f, n * (9 + D) * sizeof(float)), edge, n);
  }
  free(f);
  free(edge);
  return *status == AP_OK ? h : 0;
}

int main(void)
{
  enum { NX = 181, NY = 157 };
  static float z[NX * NY];
  static double dx[NY], dy[NY];
  ap_horizon_grid g;
  ap_horizon_params p;
  int i, j, c, failed = 0;
  for (j = 0; j < NY; ++j) {
    for (i = 0; i < NX; ++i) {
      const int hole = (i - 120) * (i - 120) + (j - 40) * (j - 40) < 30 || (i == 7 && j > 100);
      z[j * NX + i] = hole ? NAN : (float)rough(i * 30.0, j * 30.0);
    }
    /* 1 arc-second rows from 44 N (one row is about 30.9 m) */
    dx[j] = 30.87 * cos((44.0 + j / 3600.0) * 3.14159265358979 / 180.0);
    dy[j] = 30.87;
  }
  for (c = 0; c < 7; ++c) {
    static const char *const what[7] = {
      "projected, 32 sectors, 1500 m (exact march)",
      "projected, 32 sectors, 4000 m (far march)",
      "projected, 29 sectors, 4000 m (far march)",
      "projected, 32 sectors, unlimited (sweep)",
      "lat/lon rows, 32 sectors, unlimited (sweep)",
      "lat/lon rows, 29 sectors, 1500 m (exact march)",
      "lat/lon rows, 32 sectors, 4000 m (far march)"};
    ap_status status;
    uint64_t h;
    memset(&g, 0, sizeof g);
    g.z = ap_grid_view_make(z, NX, NY);
    g.dx0 = 30.0;
    g.dy0 = 30.0;
    if (c >= 4) {
      g.dx = dx;
      g.dy = dy;
    }
    ap_horizon_params_init(&p);
    p.directions = (c == 2 || c == 5) ? 29 : 32;
    p.max_distance = (c == 0 || c == 5) ? 1500.0 : ((c <= 2 || c == 6) ? 4000.0 : INFINITY);
    p.azimuth_offset = c == 1 ? 0.0123 : 0.0;
    h = run(&g, &p, &status);
    if (status != AP_OK) {
      fprintf(stderr, "%s: %s\n", what[c], ap_status_string(status));
      failed = 1;
    }
    printf("%-48s %016llx\n", what[c], (unsigned long long)h);
  }
  return failed;
}
