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

/* The triangles of quad (i, j) as vertex ids, counter-clockwise; returns how many (0, 1, 2).
 * Nodes: a = SW, b = SE, c = NE, d = NW. With seam, the quad of column nx - 1 takes column 0's
 * nodes as its east ones, with the ids of their copies after the grid's (ap_mesh.h). */
static int quad_triangles(const ap_grid_view *g, int seam, size_t i, size_t j, int64_t t[6])
{
  const float *s = g->z + (ptrdiff_t)j * g->row_stride;
  const float *nrow = s + g->row_stride;
  const int east_is_seam = seam && i + 1 == g->nx;
  const size_t ie = east_is_seam ? 0 : i + 1;
  const int64_t a = (int64_t)(j * g->nx + i);
  const int64_t d = a + (int64_t)g->nx;
  const int64_t b = east_is_seam ? (int64_t)(g->nx * g->ny + j) : a + 1;
  const int64_t c = b + (east_is_seam ? 1 : (int64_t)g->nx);
  const int va = !isnan(s[i]), vb = !isnan(s[ie]);
  const int vd = !isnan(nrow[i]), vc = !isnan(nrow[ie]);
  int k = 0;
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
  return k / 3;
}

ap_status ap_mesh_triangulate_validate(const ap_grid_view *g, int seam, int *ids_fit_i32)
{
  size_t cap, nodes;
  ap_status st = ap_grid_validate(g, seam ? 3 : 2, 2);
  if (st != AP_OK) {
    return st;
  }
  st = ap_mesh_max_triangles(g->nx + (seam ? 1 : 0), g->ny, &cap);
  if (st != AP_OK) {
    return st;
  }
  /* vertex ids, the seam's copies included, must fit in int64 */
  if (ap_size_mul(g->nx + (seam ? 1 : 0), g->ny, &nodes) != AP_OK || nodes > (size_t)INT64_MAX) {
    return AP_ERR_SIZE_OVERFLOW;
  }
  if (ids_fit_i32) {
    *ids_fit_i32 = nodes <= (size_t)INT32_MAX;
  }
  return AP_OK;
}

/* Quads per row: nx - 1, and the seam's. */
static size_t row_quads(const ap_grid_view *g, int seam)
{
  return g->nx - (seam ? 0 : 1);
}

size_t ap_mesh_count_rows(const ap_grid_view *g, int seam, size_t j0, size_t j1)
{
  size_t i, j, n = 0;
  int64_t t[6];
  for (j = j0; j < j1 && j + 1 < g->ny; ++j) {
    for (i = 0; i < row_quads(g, seam); ++i) {
      n += (size_t)quad_triangles(g, seam, i, j, t);
    }
  }
  return n;
}

/* Write triangles (3 ids each, m of them from t) as 64-bit (wide) or 32-bit ids. */
static void put(const int64_t *t, int m, int64_t **wide, int32_t **narrow)
{
  int k;
  for (k = 0; k < 3 * m; ++k) {
    if (*wide) {
      *(*wide)++ = t[k];
    } else {
      *(*narrow)++ = (int32_t)t[k];
    }
  }
}

/* Write the triangles of quad rows [j0, j1) as 64-bit (wide) or 32-bit ids. */
static void emit_rows(const ap_grid_view *g, int seam, size_t j0, size_t j1, int64_t *wide,
                      int32_t *narrow)
{
  size_t i, j;
  int64_t t[6];
  for (j = j0; j < j1 && j + 1 < g->ny; ++j) {
    for (i = 0; i < row_quads(g, seam); ++i) {
      put(t, quad_triangles(g, seam, i, j, t), &wide, &narrow);
    }
  }
}

void ap_mesh_triangulate_rows(const ap_grid_view *g, int seam, size_t j0, size_t j1,
                              int64_t *tri)
{
  emit_rows(g, seam, j0, j1, tri, NULL);
}

void ap_mesh_triangulate_rows_i32(const ap_grid_view *g, int seam, size_t j0, size_t j1,
                                  int32_t *tri)
{
  emit_rows(g, seam, j0, j1, NULL, tri);
}

size_t ap_mesh_cap(const ap_grid_view *g, size_t row, int64_t *tri)
{
  const float *s;
  const int64_t first = (int64_t)(row * g->nx);
  const int last = row + 1 == g->ny;
  size_t i;
  if ((row != 0 && !last) || g->nx < 3) {
    return 0;
  }
  s = g->z + (ptrdiff_t)row * g->row_stride;
  for (i = 0; i < g->nx; ++i) {
    if (isnan(s[i])) {
      return 0;
    }
  }
  if (tri) {
    /* The last row's ring runs counter-clockwise seen from beyond that end (columns east,
     * rows north: the east direction turns left around the end); the first row's clockwise. */
    for (i = 1; i + 1 < g->nx; ++i) {
      int64_t *t = tri + 3 * (i - 1);
      t[0] = first;
      t[1] = first + (int64_t)(last ? i : i + 1);
      t[2] = first + (int64_t)(last ? i + 1 : i);
    }
  }
  return g->nx - 2;
}

ap_status ap_mesh_triangulate(const ap_grid_view *g, int64_t *restrict tri, size_t max_tri,
                              size_t *restrict ntri)
{
  size_t n;
  ap_status st;
  if (!tri || !ntri) {
    return AP_ERR_NULL_POINTER;
  }
  *ntri = 0;
  st = ap_mesh_triangulate_validate(g, 0, NULL);
  if (st != AP_OK) {
    return st;
  }
  n = ap_mesh_count_rows(g, 0, 0, g->ny - 1);
  if (n > max_tri) {
    return AP_ERR_BUFFER_TOO_SMALL;
  }
  ap_mesh_triangulate_rows(g, 0, 0, g->ny - 1, tri);
  *ntri = n;
  return AP_OK;
}

ap_status ap_mesh_normals_validate(const double *xyz, size_t nx, size_t ny, int wrap,
                                   const float *normals)
{
  size_t nodes, values;
  if (!xyz || !normals) {
    return AP_ERR_NULL_POINTER;
  }
  if (nx < (wrap ? 3u : 2u) || ny < 2) {
    return AP_ERR_GRID_TOO_SMALL;
  }
  if (ap_size_mul(nx, ny, &nodes) != AP_OK ||
      ap_size_mul(nodes, 3 * sizeof(double), &values) != AP_OK) {
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

void ap_mesh_normals_rows(const double *restrict xyz, size_t nx, size_t ny, int wrap, size_t j0,
                          size_t j1, float *restrict normals)
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
        ptrdiff_t ii = (ptrdiff_t)i + ring_di[k];
        const ptrdiff_t jj = (ptrdiff_t)j + ring_dj[k];
        if (wrap) { /* the seam's neighbours: column nx - 1 beside column 0 */
          ii = ii < 0 ? (ptrdiff_t)nx - 1 : ((size_t)ii == nx ? 0 : ii);
        }
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
