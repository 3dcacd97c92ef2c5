/* SPDX-License-Identifier: BSD-3-Clause */
/* Unit tests of ap_mesh: triangulation with nodata holes and vertex normals, against
 * hand-counted topologies and the exact normal of a plane. */
#include "ap_mesh.h"
#include "aptest.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* z component of (b - a) x (c - a) for grid nodes laid out at unit spacing. */
static double tri_up(size_t nx, const int64_t *t)
{
  const double ax = (double)(t[0] % (int64_t)nx), ay = (double)(t[0] / (int64_t)nx);
  const double bx = (double)(t[1] % (int64_t)nx), by = (double)(t[1] / (int64_t)nx);
  const double cx = (double)(t[2] % (int64_t)nx), cy = (double)(t[2] / (int64_t)nx);
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

/* A full grid gives 2 (nx-1)(ny-1) counter-clockwise triangles covering each quad. */
/* The two triangles of a quad with four valid nodes at t: (SW, SE, NE) and (SW, NE, NW). */
static void check_quad(const int64_t *t, int64_t sw, int64_t se, int64_t ne, int64_t nw)
{
  AP_CHECK_EQ_INT(t[0], sw);
  AP_CHECK_EQ_INT(t[1], se);
  AP_CHECK_EQ_INT(t[2], ne);
  AP_CHECK_EQ_INT(t[3], sw);
  AP_CHECK_EQ_INT(t[4], ne);
  AP_CHECK_EQ_INT(t[5], nw);
}

static void test_full_grid(void)
{
  float z[5 * 4] = { 0 };
  int64_t tri[3 * 2 * 4 * 3];
  size_t n = 0, k, maxt;
  ap_grid_view g = ap_grid_view_make(z, 5, 4);
  for (k = 0; k < 20; ++k) {
    z[k] = (float)k;
  }
  AP_CHECK_EQ_INT(ap_mesh_max_triangles(5, 4, &maxt), AP_OK);
  AP_CHECK_EQ_INT(maxt, 24);
  AP_CHECK_EQ_INT(ap_mesh_triangulate(&g, tri, maxt, &n), AP_OK);
  AP_CHECK_EQ_INT(n, 24);
  for (k = 0; k < n; ++k) {
    AP_CHECK_NEAR(tri_up(5, tri + 3 * k), 1.0, 0.0); /* area 1/2, CCW */
  }
  /* The first quad: (SW, SE, NE) = (0, 1, 6) and (SW, NE, NW) = (0, 6, 5). */
  check_quad(tri, 0, 1, 6, 5);
  /* Too small a buffer is an error, not an overflow. */
  AP_CHECK_EQ_INT(ap_mesh_triangulate(&g, tri, 23, &n), AP_ERR_BUFFER_TOO_SMALL);
  AP_CHECK_EQ_INT(n, 0);
  /* A view of 2^60 cells (addressable as floats) has 2^61 triangles, whose ids would take
   * 2^65.6 bytes: refused before a row is read. */
  g = ap_grid_view_make(z, (size_t)1 << 40, (size_t)1 << 20);
  AP_CHECK_EQ_INT(ap_mesh_triangulate(&g, tri, maxt, &n), AP_ERR_SIZE_OVERFLOW);
  AP_CHECK_EQ_INT(n, 0);
}

static int uses(const int64_t *tri, size_t n, int64_t v)
{
  size_t k;
  for (k = 0; k < 3 * n; ++k) {
    if (tri[k] == v) {
      return 1;
    }
  }
  return 0;
}

/* One nodata node in a 2 x 2 grid (a single quad), in each of the four corners: the triangle
 * of the three valid nodes survives and never uses the nodata node. */
static void test_one_nodata_corner(void)
{
  int corner;
  for (corner = 0; corner < 4; ++corner) {
    float z[4] = { 1, 2, 3, 4 };
    int64_t tri[6];
    size_t n = 0;
    ap_grid_view g = ap_grid_view_make(z, 2, 2);
    z[corner] = NAN;
    AP_CHECK_EQ_INT(ap_mesh_triangulate(&g, tri, 2, &n), AP_OK);
    AP_CHECK_EQ_INT(n, 1);
    AP_CHECK(!uses(tri, n, corner));
    AP_CHECK_NEAR(tri_up(2, tri), 1.0, 0.0);
  }
}

/* Holes: a nodata node in the interior of a 5 x 5 grid removes exactly the triangles that
 * touch it. Its four quads each keep one triangle: 32 - 4 = 28. Two nodata nodes side by
 * side drop the two quads they share entirely. */
static void test_holes(void)
{
  float z[25] = { 0 };
  int64_t tri[3 * 32];
  size_t n = 0, k;
  ap_grid_view g = ap_grid_view_make(z, 5, 5);
  for (k = 0; k < 25; ++k) {
    z[k] = 0.0f;
  }
  z[12] = NAN; /* centre */
  AP_CHECK_EQ_INT(ap_mesh_triangulate(&g, tri, 32, &n), AP_OK);
  AP_CHECK_EQ_INT(n, 28);
  AP_CHECK(!uses(tri, n, 12));
  z[13] = NAN; /* and its east neighbour: quads (2,1),(2,2) lose both triangles,
                  (1,1),(1,2),(3,1),(3,2) keep one each -> 32 - 2*2 - 4 = 24 */
  AP_CHECK_EQ_INT(ap_mesh_triangulate(&g, tri, 32, &n), AP_OK);
  AP_CHECK_EQ_INT(n, 24);
  AP_CHECK(!uses(tri, n, 12) && !uses(tri, n, 13));
  for (k = 0; k < 25; ++k) {
    z[k] = NAN;
  }
  AP_CHECK_EQ_INT(ap_mesh_triangulate(&g, tri, 32, &n), AP_OK);
  AP_CHECK_EQ_INT(n, 0);
}

/* Row ranges: counts add up, fills concatenate to the whole-grid result for any split, and
 * the 32-bit form writes the same ids. */
static void test_row_ranges(void)
{
  enum { NX = 9, NY = 7 };
  float z[NX * NY] = { 0 };
  int64_t whole[3 * 2 * (NX - 1) * (NY - 1)], parts[3 * 2 * (NX - 1) * (NY - 1)];
  int32_t narrow[3 * 2 * (NX - 1) * (NY - 1)];
  size_t k, n = 0, total = 0, j;
  int fits = 0;
  ap_grid_view g = ap_grid_view_make(z, NX, NY);
  for (k = 0; k < NX * NY; ++k) {
    z[k] = (k % 7 == 3 || k % 11 == 5) ? NAN : (float)k;
  }
  AP_CHECK_EQ_INT(ap_mesh_triangulate_validate(&g, 0, &fits), AP_OK);
  AP_CHECK(fits);
  AP_CHECK_EQ_INT(ap_mesh_triangulate(&g, whole, 2 * (NX - 1) * (NY - 1), &n), AP_OK);
  AP_CHECK(n > 0 && n < 2 * (NX - 1) * (NY - 1));
  for (j = 0; j + 1 < NY; j += 2) { /* ranges of two quad rows, the last one partial */
    const size_t j1 = j + 2 < NY - 1 ? j + 2 : NY - 1;
    const size_t c = ap_mesh_count_rows(&g, 0, j, j1);
    ap_mesh_triangulate_rows(&g, 0, j, j1, parts + 3 * total);
    ap_mesh_triangulate_rows_i32(&g, 0, j, j1, narrow + 3 * total);
    total += c;
  }
  AP_CHECK_EQ_INT(total, n);
  AP_CHECK(memcmp(whole, parts, 3 * n * sizeof(int64_t)) == 0);
  for (k = 0; k < 3 * n; ++k) {
    AP_CHECK_EQ_INT(narrow[k], whole[k]);
  }
  AP_CHECK_EQ_INT(ap_mesh_count_rows(&g, 0, NY - 1, NY + 5), 0); /* past the last quad row */
  {
    /* 50000 x 50000 nodes do not fit 32-bit ids (the view is never read by validate). */
    ap_grid_view big = ap_grid_view_make(z, 50000, 50000);
    AP_CHECK_EQ_INT(ap_mesh_triangulate_validate(&big, 0, &fits), AP_OK);
    AP_CHECK(!fits);
  }
}

/* A seam's triangles with their copies' ids mapped back to column 0, each rotated to start at
 * its smallest id (which keeps its orientation), columns rolled by `roll`, sorted. */
static int compare_tri(const void *a, const void *b)
{
  const int64_t *x = (const int64_t *)a, *y = (const int64_t *)b;
  int k;
  for (k = 0; k < 3; ++k) {
    if (x[k] != y[k]) {
      return x[k] < y[k] ? -1 : 1;
    }
  }
  return 0;
}

static void canonical(int64_t *tri, size_t n, size_t nx, size_t ny, size_t roll)
{
  size_t t;
  int k;
  for (t = 0; t < n; ++t) {
    int64_t *v = tri + 3 * t, r[3];
    int first = 0;
    for (k = 0; k < 3; ++k) {
      size_t id = (size_t)v[k], i, j;
      if (id >= nx * ny) {
        id = (id - nx * ny) * nx; /* the copy of row j's column 0 */
      }
      i = (id % nx + roll) % nx;
      j = id / nx;
      v[k] = (int64_t)(j * nx + i);
    }
    for (k = 1; k < 3; ++k) {
      if (v[k] < v[first]) {
        first = k;
      }
    }
    for (k = 0; k < 3; ++k) {
      r[k] = v[(first + k) % 3];
    }
    memcpy(v, r, sizeof r);
  }
  qsort(tri, n, 3 * sizeof(int64_t), compare_tri);
}

/* Count how often the directed edge (u, v) occurs in the triangles. */
static int directed(const int64_t *tri, size_t n, int64_t u, int64_t v)
{
  size_t t;
  int k, c = 0;
  for (t = 0; t < n; ++t) {
    for (k = 0; k < 3; ++k) {
      c += tri[3 * t + k] == u && tri[3 * t + (k + 1) % 3] == v;
    }
  }
  return c;
}

/* A grid whose east and west edges meet: its row j ends with the quad from column nx - 1 to
 * the copies nx * ny + j, nx * ny + j + 1 of column 0; mapped back to column 0, the triangles
 * of a grid are those of the same grid with its columns rolled, whatever its nodata (no column
 * is special any more); with both caps a full grid is a closed surface: every directed edge
 * once, its reverse once, V - E + F = 2. */
static void test_seam_and_caps(void)
{
  enum { NX = 6, NY = 5, MAXT = 2 * NX * (NY - 1) + 2 * (NX - 2) };
  float z[NX * NY] = { 0 }, rolled[NX * NY] = { 0 };
  int64_t tri[3 * MAXT], other[3 * MAXT];
  int32_t narrow[3 * MAXT];
  size_t n, m, k, r, i, j;
  int fits = 0;
  ap_grid_view g = ap_grid_view_make(z, NX, NY), h = ap_grid_view_make(rolled, NX, NY);
  for (k = 0; k < NX * NY; ++k) {
    z[k] = 1.0f;
  }
  AP_CHECK_EQ_INT(ap_mesh_triangulate_validate(&g, 1, &fits), AP_OK);
  AP_CHECK(fits);
  n = ap_mesh_count_rows(&g, 1, 0, NY - 1);
  AP_CHECK_EQ_INT(n, 2 * NX * (NY - 1));
  ap_mesh_triangulate_rows(&g, 1, 0, NY - 1, tri);
  /* row 0's seam quad: SW = 5, SE = copy 30, NE = copy 31, NW = 11 */
  check_quad(tri + 30, 5, 30, 31, 11);
  AP_CHECK_EQ_INT(ap_mesh_cap(&g, 0, NULL), NX - 2);
  AP_CHECK_EQ_INT(ap_mesh_cap(&g, 0, tri + 3 * n), NX - 2);
  AP_CHECK_EQ_INT(ap_mesh_cap(&g, NY - 1, tri + 3 * (n + NX - 2)), NX - 2);
  AP_CHECK_EQ_INT(ap_mesh_cap(&g, 1, NULL), 0); /* not an end row */
  n += 2 * (NX - 2);
  canonical(tri, n, NX, NY, 0);
  for (k = 0; k < n; ++k) {
    int e;
    for (e = 0; e < 3; ++e) {
      const int64_t u = tri[3 * k + e], v = tri[3 * k + (e + 1) % 3];
      AP_CHECK_EQ_INT(directed(tri, n, u, v), 1);
      AP_CHECK_EQ_INT(directed(tri, n, v, u), 1);
    }
  }
  AP_CHECK_EQ_INT((long)(NX * NY) - (long)(3 * n / 2) + (long)n, 2); /* V - E + F */
  /* nodata: rolling the columns relabels the same triangles */
  for (k = 0; k < NX * NY; ++k) {
    z[k] = (k % 7 == 3 || k % 11 == 5) ? NAN : (float)k;
  }
  z[0] = NAN;
  z[2 * NX + NX - 1] = NAN;
  n = ap_mesh_count_rows(&g, 1, 0, NY - 1);
  ap_mesh_triangulate_rows(&g, 1, 0, NY - 1, tri);
  ap_mesh_triangulate_rows_i32(&g, 1, 0, NY - 1, narrow);
  for (k = 0; k < 3 * n; ++k) {
    AP_CHECK_EQ_INT(narrow[k], tri[k]);
  }
  AP_CHECK(n > 0 && n < 2 * NX * (NY - 1));
  canonical(tri, n, NX, NY, 0);
  for (r = 1; r < NX; ++r) {
    for (j = 0; j < NY; ++j) {
      for (i = 0; i < NX; ++i) {
        rolled[j * NX + (i + r) % NX] = z[j * NX + i];
      }
    }
    m = ap_mesh_count_rows(&h, 1, 0, NY - 1);
    AP_CHECK_EQ_INT(m, n);
    if (m == n) {
      ap_mesh_triangulate_rows(&h, 1, 0, NY - 1, other);
      canonical(tri, n, NX, NY, r); /* the original's, rolled by r */
      canonical(other, m, NX, NY, 0);
      AP_CHECK(memcmp(tri, other, 3 * n * sizeof(int64_t)) == 0);
      canonical(tri, n, NX, NY, NX - r); /* back */
    }
  }
  /* a ring with nodata stays open; too narrow a grid has no seam or cap */
  AP_CHECK_EQ_INT(ap_mesh_cap(&g, 0, NULL), 0);
  g = ap_grid_view_make(z, 2, 3);
  AP_CHECK_EQ_INT(ap_mesh_triangulate_validate(&g, 1, &fits), AP_ERR_GRID_TOO_SMALL);
  AP_CHECK_EQ_INT(ap_mesh_triangulate_validate(&g, 0, &fits), AP_OK);
  for (k = 0; k < 6; ++k) {
    z[k] = 0.0f;
  }
  AP_CHECK_EQ_INT(ap_mesh_cap(&g, 0, NULL), 0);
  {
    /* the seam's copies count: 46341 x 46340 nodes fit 32-bit ids, one more column does not */
    ap_grid_view big = ap_grid_view_make(z, 46340, 46341);
    AP_CHECK_EQ_INT(ap_mesh_triangulate_validate(&big, 0, &fits), AP_OK);
    AP_CHECK(fits);
    AP_CHECK_EQ_INT(ap_mesh_triangulate_validate(&big, 1, &fits), AP_OK);
    AP_CHECK(!fits);
  }
}

static void test_triangulate_errors(void)
{
  float z[4] = { 0, 0, 0, 0 };
  int64_t tri[6];
  size_t n = 99, m;
  ap_grid_view g = ap_grid_view_make(z, 1, 4);
  AP_CHECK_EQ_INT(ap_mesh_triangulate(&g, tri, 2, &n), AP_ERR_GRID_TOO_SMALL);
  AP_CHECK_EQ_INT(n, 0);
  g = ap_grid_view_make(z, 2, 2);
  AP_CHECK_EQ_INT(ap_mesh_triangulate(&g, NULL, 2, &n), AP_ERR_NULL_POINTER);
  AP_CHECK_EQ_INT(ap_mesh_triangulate(&g, tri, 2, NULL), AP_ERR_NULL_POINTER);
  AP_CHECK_EQ_INT(ap_mesh_max_triangles(SIZE_MAX / 2, 4, &m), AP_ERR_SIZE_OVERFLOW);
  AP_CHECK_EQ_INT(ap_mesh_max_triangles(1, 9, &m), AP_OK);
  AP_CHECK_EQ_INT(m, 0);
}

/* Positions of a plane z = a x + b y on a grid with cell sizes dx, dy. */
static double *plane(size_t nx, size_t ny, double dx, double dy, double a, double b)
{
  double *xyz = (double *)malloc(3 * nx * ny * sizeof(double));
  size_t i, j;
  for (j = 0; j < ny; ++j) {
    for (i = 0; i < nx; ++i) {
      double *p = xyz + 3 * (j * nx + i);
      p[0] = (double)i * dx;
      p[1] = (double)j * dy;
      p[2] = a * p[0] + b * p[1];
    }
  }
  return xyz;
}

/* On a plane every node, edges and corners included, gets the exact normal
 * (-a, -b, 1) / sqrt(1 + a^2 + b^2); next to holes too. */
static void test_normals_plane(void)
{
  const size_t nx = 7, ny = 5;
  const double a = 0.3, b = -1.2, len = sqrt(1.0 + a * a + b * b);
  double *xyz = plane(nx, ny, 30.0, 20.0, a, b);
  float *nrm = (float *)calloc(3 * nx * ny, sizeof(float));
  size_t k;
  AP_CHECK_EQ_INT(ap_mesh_normals_validate(xyz, nx, ny, 0, nrm), AP_OK);
  ap_mesh_normals_rows(xyz, nx, ny, 0, 0, ny, nrm);
  for (k = 0; k < nx * ny; ++k) {
    AP_CHECK_NEAR(nrm[3 * k + 0], -a / len, 1e-6);
    AP_CHECK_NEAR(nrm[3 * k + 1], -b / len, 1e-6);
    AP_CHECK_NEAR(nrm[3 * k + 2], 1.0 / len, 1e-6);
  }
  /* Punch holes: node (3,2) and the whole column 5 of row 1. */
  xyz[3 * (2 * nx + 3)] = NAN;
  xyz[3 * (1 * nx + 5)] = NAN;
  ap_mesh_normals_rows(xyz, nx, ny, 0, 0, ny, nrm);
  for (k = 0; k < nx * ny; ++k) {
    if (k == 2 * nx + 3 || k == 1 * nx + 5) {
      AP_CHECK_NAN(nrm[3 * k]);
      continue;
    }
    AP_CHECK_NEAR(nrm[3 * k + 2], 1.0 / len, 1e-6);
  }
  free(nrm);
  free(xyz);
}

/* A node whose neighbours are all nodata has no normal; a node with only an east and a
 * north-east neighbour (the one triangle it can be in) gets that triangle's normal. */
static void test_normals_sparse(void)
{
  double *xyz = plane(3, 3, 1.0, 1.0, 0.0, 0.0);
  float nrm[27];
  size_t k;
  for (k = 0; k < 9; ++k) {
    if (k != 4) {
      xyz[3 * k] = NAN; /* only the centre is valid */
    }
  }
  ap_mesh_normals_rows(xyz, 3, 3, 0, 0, 3, nrm);
  AP_CHECK_NAN(nrm[3 * 4]);
  /* Valid: centre (4), east (5), north-east (8), tilted so the triangle normal is known:
   * points (1,1,0), (2,1,1), (2,2,1) -> edges (1,0,1), (1,1,1) -> cross (-1, 0, 1)/sqrt 2 */
  xyz[3 * 5] = 2.0;
  xyz[3 * 5 + 2] = 1.0;
  xyz[3 * 8] = 2.0;
  xyz[3 * 8 + 2] = 1.0;
  ap_mesh_normals_rows(xyz, 3, 3, 0, 0, 3, nrm);
  AP_CHECK_NEAR(nrm[3 * 4 + 0], -1.0 / sqrt(2.0), 1e-6);
  AP_CHECK_NEAR(nrm[3 * 4 + 1], 0.0, 1e-6);
  AP_CHECK_NEAR(nrm[3 * 4 + 2], 1.0 / sqrt(2.0), 1e-6);
  free(xyz);
}

/* Normals of a rough surface are bitwise the same whether rows run in one call or one at a
 * time (how vtkSMPTools splits them must not matter). */
static void test_normals_split_invariance(void)
{
  const size_t nx = 9, ny = 8;
  double *xyz = plane(nx, ny, 1.0, 1.0, 0.0, 0.0);
  float *once = (float *)malloc(3 * nx * ny * sizeof(float));
  float *rows = (float *)malloc(3 * nx * ny * sizeof(float));
  size_t k, j;
  unsigned s = 12345u;
  for (k = 0; k < nx * ny; ++k) {
    s = s * 1103515245u + 12345u;
    xyz[3 * k + 2] = (double)(s >> 16) / 65536.0;
  }
  xyz[3 * 20] = NAN;
  ap_mesh_normals_rows(xyz, nx, ny, 0, 0, ny, once);
  for (j = 0; j < ny; ++j) {
    ap_mesh_normals_rows(xyz, nx, ny, 0, j, j + 1, rows);
  }
  AP_CHECK(memcmp(once, rows, 3 * nx * ny * sizeof(float)) == 0);
  AP_CHECK_EQ_INT(ap_mesh_normals_validate(xyz, 1, ny, 0, once), AP_ERR_GRID_TOO_SMALL);
  AP_CHECK_EQ_INT(ap_mesh_normals_validate(NULL, nx, ny, 0, once), AP_ERR_NULL_POINTER);
  AP_CHECK_EQ_INT(ap_mesh_normals_validate(xyz, SIZE_MAX / 4, 8, 0, once), AP_ERR_SIZE_OVERFLOW);
  free(once);
  free(rows);
  free(xyz);
}

/* With wrap, a tube closed around its axis (node (i, j) at angle 2 pi i / nx around the y
 * axis, y = j) gets the radial normal at every node, the seam's columns included: the
 * neighbours across the seam are the right ones. Without wrap the edge columns tilt. */
static void test_normals_wrap(void)
{
  const size_t nx = 12, ny = 4;
  const double pi = 3.14159265358979323846, radius = 3.0;
  double *xyz = (double *)malloc(3 * nx * ny * sizeof(double));
  float *nrm = (float *)calloc(3 * nx * ny, sizeof(float));
  size_t i, j;
  double worst = 0.0;
  for (j = 0; j < ny; ++j) {
    for (i = 0; i < nx; ++i) {
      const double a = 2.0 * pi * (double)i / (double)nx;
      double *p = xyz + 3 * (j * nx + i);
      p[0] = radius * sin(a);
      p[1] = (double)j;
      p[2] = radius * cos(a);
    }
  }
  AP_CHECK_EQ_INT(ap_mesh_normals_validate(xyz, nx, ny, 1, nrm), AP_OK);
  AP_CHECK_EQ_INT(ap_mesh_normals_validate(xyz, 2, ny, 1, nrm), AP_ERR_GRID_TOO_SMALL);
  ap_mesh_normals_rows(xyz, nx, ny, 1, 0, ny, nrm);
  for (j = 0; j < ny; ++j) {
    for (i = 0; i < nx; ++i) {
      const double a = 2.0 * pi * (double)i / (double)nx;
      const float *v = nrm + 3 * (j * nx + i);
      AP_CHECK_NEAR(v[0], sin(a), 1e-6);
      AP_CHECK_NEAR(v[1], 0.0, 1e-6);
      AP_CHECK_NEAR(v[2], cos(a), 1e-6);
    }
  }
  ap_mesh_normals_rows(xyz, nx, ny, 0, 0, ny, nrm);
  for (j = 0; j < ny; ++j) {
    const double d = fabs(nrm[3 * j * nx] - 0.0) + fabs(nrm[3 * j * nx + 2] - 1.0);
    worst = d > worst ? d : worst;
  }
  AP_CHECK(worst > 0.01);
  free(nrm);
  free(xyz);
}

int main(void)
{
  AP_TEST_RUN(test_full_grid);
  AP_TEST_RUN(test_one_nodata_corner);
  AP_TEST_RUN(test_holes);
  AP_TEST_RUN(test_row_ranges);
  AP_TEST_RUN(test_seam_and_caps);
  AP_TEST_RUN(test_triangulate_errors);
  AP_TEST_RUN(test_normals_plane);
  AP_TEST_RUN(test_normals_sparse);
  AP_TEST_RUN(test_normals_split_invariance);
  AP_TEST_RUN(test_normals_wrap);
  AP_TEST_MAIN_END();
}
