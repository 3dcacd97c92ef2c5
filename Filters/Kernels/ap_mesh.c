/* SPDX-License-Identifier: BSD-3-Clause */
#include "ap_mesh.h"

#include <math.h>

ap_status ap_mesh_max_triangles(size_t nx, size_t ny, size_t *out)
{
  size_t quads, tris, ids;
  if (!out) {
    return AP_ERR_NULL_POINTER;
  }
  if (nx < 2 || ny < 2) {
    *out = 0;
    return AP_OK;
  }
  if (ap_size_mul(nx - 1, ny - 1, &quads) != AP_OK || ap_size_mul(quads, 2, &tris) != AP_OK ||
      ap_size_mul(tris, 3 * sizeof(int64_t), &ids) != AP_OK) {
    return AP_ERR_SIZE_OVERFLOW;
  }
  *out = tris;
  return AP_OK;
}

ap_status ap_mesh_triangulate(const ap_grid_view *g, int64_t *restrict tri, size_t max_tri,
                              size_t *restrict ntri)
{
  size_t i, j, n = 0, cap;
  ap_status st;
  if (!tri || !ntri) {
    return AP_ERR_NULL_POINTER;
  }
  *ntri = 0;
  st = ap_grid_validate(g, 2, 2);
  if (st != AP_OK) {
    return st;
  }
  st = ap_mesh_max_triangles(g->nx, g->ny, &cap);
  if (st != AP_OK) {
    return st;
  }
  if ((size_t)INT64_MAX / g->ny < g->nx) {
    return AP_ERR_SIZE_OVERFLOW; /* vertex ids must fit in int64 */
  }
  for (j = 0; j + 1 < g->ny; ++j) {
    const float *s = g->z + (ptrdiff_t)j * g->row_stride;
    const float *nrow = s + g->row_stride;
    for (i = 0; i + 1 < g->nx; ++i) {
      const int64_t a = (int64_t)(j * g->nx + i); /* SW */
      const int64_t b = a + 1;                     /* SE */
      const int64_t d = a + (int64_t)g->nx;        /* NW */
      const int64_t c = d + 1;                     /* NE */
      const int va = !isnan(s[i]), vb = !isnan(s[i + 1]);
      const int vd = !isnan(nrow[i]), vc = !isnan(nrow[i + 1]);
      int64_t t[6];
      size_t k = 0, m;
      if (va && vb && vc) { /* (SW, SE, NE) */
        t[k++] = a; t[k++] = b; t[k++] = c;
      }
      if (va && vc && vd) { /* (SW, NE, NW) */
        t[k++] = a; t[k++] = c; t[k++] = d;
      }
      if (k == 0) {
        /* The SW-NE diagonal has a nodata end: try the other diagonal, which keeps the
         * triangle of the three valid nodes when exactly one of SW, NE is missing. */
        if (va && vb && vd) { /* (SW, SE, NW) */
          t[k++] = a; t[k++] = b; t[k++] = d;
        } else if (vb && vc && vd) { /* (SE, NE, NW) */
          t[k++] = b; t[k++] = c; t[k++] = d;
        }
      }
      if (n + k / 3 > max_tri) {
        *ntri = 0;
        return AP_ERR_BUFFER_TOO_SMALL;
      }
      for (m = 0; m < k; ++m) {
        tri[3 * n + m] = t[m];
      }
      n += k / 3;
    }
  }
  *ntri = n;
  return AP_OK;
}

ap_status ap_mesh_normals_validate(const double *xyz, size_t nx, size_t ny, const float *normals)
{
  size_t nodes, values;
  if (!xyz || !normals) {
    return AP_ERR_NULL_POINTER;
  }
  if (nx < 2 || ny < 2) {
    return AP_ERR_GRID_TOO_SMALL;
  }
  if (ap_size_mul(nx, ny, &nodes) != AP_OK || ap_size_mul(nodes, 3 * sizeof(double), &values) != AP_OK) {
    return AP_ERR_SIZE_OVERFLOW;
  }
  return AP_OK;
}

/* Neighbour offsets counter-clockwise from east: E, NE, N, NW, W, SW, S, SE. */
static const int ring_di[8] = { 1, 1, 0, -1, -1, -1, 0, 1 };
static const int ring_dj[8] = { 0, 1, 1, 1, 0, -1, -1, -1 };

static void cross_acc(const double u[3], const double v[3], double acc[3])
{
  acc[0] += u[1] * v[2] - u[2] * v[1];
  acc[1] += u[2] * v[0] - u[0] * v[2];
  acc[2] += u[0] * v[1] - u[1] * v[0];
}

void ap_mesh_normals_rows(const double *restrict xyz, size_t nx, size_t ny, size_t j0, size_t j1,
                          float *restrict normals)
{
  size_t i, j;
  for (j = j0; j < j1 && j < ny; ++j) {
    for (i = 0; i < nx; ++i) {
      const size_t id = j * nx + i;
      const double *p = xyz + 3 * id;
      float *out = normals + 3 * id;
      double edge[8][3];
      int valid[8];
      double acc[3] = { 0.0, 0.0, 0.0 };
      int q, k, any = 0;
      if (isnan(p[0])) {
        out[0] = out[1] = out[2] = NAN;
        continue;
      }
      for (k = 0; k < 8; ++k) {
        const ptrdiff_t ii = (ptrdiff_t)i + ring_di[k], jj = (ptrdiff_t)j + ring_dj[k];
        valid[k] = 0;
        if (ii >= 0 && jj >= 0 && (size_t)ii < nx && (size_t)jj < ny) {
          const double *o = xyz + 3 * ((size_t)jj * nx + (size_t)ii);
          if (!isnan(o[0])) {
            valid[k] = 1;
            edge[k][0] = o[0] - p[0];
            edge[k][1] = o[1] - p[1];
            edge[k][2] = o[2] - p[2];
          }
        }
      }
      /* Quadrant q spans ring entries 2q (axis), 2q + 1 (diagonal), 2q + 2 (next axis). */
      for (q = 0; q < 4; ++q) {
        const int a = 2 * q, d = 2 * q + 1, b = (2 * q + 2) % 8;
        if (valid[a] && valid[b]) {
          cross_acc(edge[a], edge[b], acc);
        } else if (valid[a] && valid[d]) {
          cross_acc(edge[a], edge[d], acc);
        } else if (valid[d] && valid[b]) {
          cross_acc(edge[d], edge[b], acc);
        } else {
          continue;
        }
        any = 1;
      }
      {
        const double len = sqrt(acc[0] * acc[0] + acc[1] * acc[1] + acc[2] * acc[2]);
        if (!any || !(len > 0.0)) {
          out[0] = out[1] = out[2] = NAN;
        } else {
          out[0] = (float)(acc[0] / len);
          out[1] = (float)(acc[1] / len);
          out[2] = (float)(acc[2] / len);
        }
      }
    }
  }
}
