/* SPDX-License-Identifier: BSD-3-Clause */
/* Unit tests of ap_horizon: horizon angles and sky products on terrains with closed forms,
 * against an independent brute-force ray marcher, curvature against spherical geometry, the
 * distance limit, lat/lon-like grids, split invariance and argument errors; and the sums'
 * single-precision arctangent.
 *
 * Where possible the test terrain is one whose piecewise-linear grid surface *is* the analytic
 * terrain (planes, a V-valley with its floor on a grid line, a wall whose top edge is a grid
 * row), so the sweep must match the closed form to float precision; the remaining tolerance
 * is stated where the grid cannot represent the shape (the pit's circular rim). */
#include "ap_horizon.h"
#include "ap_atanf.h"
#include "ap_zenith.h"
#include "aptest.h"

#include <float.h>
#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

typedef struct terrain {
  size_t nx, ny;
  float *z;
  double *dx, *dy; /* per row, NULL: constant */
  double dx0, dy0;
} terrain;

static terrain make(size_t nx, size_t ny, double cell)
{
  terrain t;
  t.nx = nx;
  t.ny = ny;
  t.z = (float *)calloc(nx * ny, sizeof(float));
  t.dx = t.dy = NULL;
  t.dx0 = t.dy0 = cell;
  return t;
}

static void drop(terrain *t)
{
  free(t->z);
  free(t->dx);
  free(t->dy);
}

/* Per-row cell sizes of a lat/lon grid on a sphere of radius R: rows from lat0 (radians)
 * northwards, dlat by dlon radians. */
static void latlon_rows(terrain *t, double R, double lat0, double dlat, double dlon)
{
  size_t j;
  t->dx = (double *)malloc(t->ny * sizeof(double));
  t->dy = (double *)malloc(t->ny * sizeof(double));
  for (j = 0; j < t->ny; ++j) {
    t->dx[j] = R * cos(lat0 + (double)j * dlat) * dlon;
    t->dy[j] = R * dlat;
  }
  t->dx0 = t->dx[0];
  t->dy0 = t->dy[0];
}

static ap_horizon_grid grid_of(const terrain *t)
{
  ap_horizon_grid g;
  g.z = ap_grid_view_make(t->z, t->nx, t->ny);
  g.dx = t->dx;
  g.dy = t->dy;
  g.dx0 = t->dx0;
  g.dy0 = t->dy0;
  return g;
}

typedef struct results {
  float *A, *rp, *bn, *svf, *vd, *open, *h;
  unsigned char *edge;
} results;

/* Every product of the grid, or of p's region (region_nx * region_ny cells) when it has one. */
static results compute(const terrain *t, const ap_horizon_params *p)
{
  const size_t n = p->region_nx ? p->region_nx * p->region_ny : t->nx * t->ny;
  ap_horizon_grid g = grid_of(t);
  ap_sky_products o;
  results r;
  r.A = (float *)malloc(n * sizeof(float));
  r.rp = (float *)malloc(n * sizeof(float));
  r.bn = (float *)malloc(3 * n * sizeof(float));
  r.svf = (float *)malloc(n * sizeof(float));
  r.vd = (float *)malloc(n * sizeof(float));
  r.open = (float *)malloc(n * sizeof(float));
  r.h = (float *)malloc(n * (size_t)p->directions * sizeof(float));
  r.edge = (unsigned char *)malloc(n);
  o.visible_solid_angle = r.A;
  o.aperture_radius = r.rp;
  o.bent_normal = r.bn;
  o.sky_view_factor = r.svf;
  o.diffuse_sky_factor = r.vd;
  o.positive_openness = r.open;
  o.edge_truncated = r.edge;
  o.horizon_angles = r.h;
  AP_CHECK_EQ_INT(ap_horizon_run(&g, p, &o), AP_OK);
  return r;
}

static void release(results *r)
{
  free(r->A);
  free(r->rp);
  free(r->bn);
  free(r->svf);
  free(r->vd);
  free(r->open);
  free(r->h);
  free(r->edge);
}

static ap_horizon_params params(int directions, int curvature)
{
  ap_horizon_params p;
  ap_horizon_params_init(&p);
  p.directions = directions;
  p.curvature = curvature;
  return p;
}

/* How a search distance of a few dozen columns is searched: every ray marched on the bilinear
 * surface (up to march_columns), every ray marched across the view columns (the far march, up
 * to far_march_columns; with per-row cell sizes only in row-major sectors), or swept through
 * the hulls. */
enum { MARCHED, FAR_MARCHED, SWEPT, SEARCH_MODES };
static const char *const mode_name[SEARCH_MODES] = {"marched", "far-marched", "swept"};

static void set_mode(ap_horizon_params *p, int mode, int march_columns)
{
  p->march_columns = mode == MARCHED ? march_columns : 0;
  p->far_march_columns = mode == SWEPT ? 0 : 1024;
  /* The swept mode is there to exercise the hulls: 8 exact columns, not the automatic 32,
   * which would search these distances of a few dozen columns nearly alone. */
  p->near_field = mode == SWEPT ? 8 : 0;
}

/* The sector sums of ap_horizon.h for a horizon h_t(phi) and a tangent-plane elevation
 * h_s(phi) given per sector (a direct transcription, independent of the kernel's loops). */
typedef struct sector_sums {
  double A, bx, by, bz, svf, open;
} sector_sums;

static sector_sums sums(int D, const double *ht, const double *hs)
{
  sector_sums s;
  int d;
  const double delta = 2 * PI / D;
  memset(&s, 0, sizeof(s));
  for (d = 0; d < D; ++d) {
    const double phi = d * delta;
    double h = ht[d];
    double q;
    if (hs[d] > h) h = hs[d];
    if (h < 0) h = 0;
    q = 0.5 * ((PI / 2 - h) - sin(h) * cos(h));
    s.A += delta * (1 - sin(h));
    s.bx += 2 * sin(delta / 2) * sin(phi) * q;
    s.by += 2 * sin(delta / 2) * cos(phi) * q;
    s.bz += delta / 2 * cos(h) * cos(h);
    s.svf += ht[d] > 0 ? sin(ht[d]) : 0;
    s.open += PI / 2 - ht[d];
  }
  s.svf = 1 - s.svf / D;
  s.open /= D;
  return s;
}

/* Cells from cell (i, j) to the nearest edge of the grid along a row or column. */
static size_t cells_from_edge(const terrain *t, size_t i, size_t j)
{
  const size_t ei = i < t->nx - 1 - i ? i : t->nx - 1 - i;
  const size_t ej = j < t->ny - 1 - j ? j : t->ny - 1 - j;
  return ei < ej ? ei : ej;
}

/* Check fix for nothing in particular: a flat plane without curvature sees the whole upper
 * hemisphere from every interior cell (A = 2 pi, rp = 90 deg, SVF = V_d = 1, zenith bent
 * normal, horizon 0 and openness 90 deg). */
static void test_flat(void)
{
  terrain t = make(40, 30, 10.0);
  ap_horizon_params p = params(32, 0);
  results r = compute(&t, &p);
  size_t i, j;
  int d, mode;
  for (j = 2; j + 2 < t.ny; ++j) {
    for (i = 2; i + 2 < t.nx; ++i) {
      const size_t k = j * t.nx + i;
      AP_CHECK_NEAR(r.A[k], 2 * PI, 1e-5);
      AP_CHECK_NEAR(r.rp[k], PI / 2, 1e-5);
      AP_CHECK_NEAR(r.svf[k], 1.0, 1e-6);
      AP_CHECK_NEAR(r.vd[k], 1.0, 1e-6);
      AP_CHECK_NEAR(r.bn[3 * k + 2], 1.0, 1e-6);
      AP_CHECK_NEAR(r.open[k], PI / 2, 1e-6);
      for (d = 0; d < 32; ++d) {
        AP_CHECK_NEAR(r.h[k * 32 + (size_t)d], 0.0, 1e-7);
      }
    }
  }
  /* On the west edge nothing lies to the west: horizon -90 deg there, and EdgeTruncated. */
  AP_CHECK_NEAR(r.h[(10 * t.nx + 0) * 32 + 24], -PI / 2, 1e-6);
  AP_CHECK_EQ_INT(r.edge[10 * t.nx], 1);
  release(&r);
  /* With curvature, a plain continued beyond the edge would stay below every cell's
   * horizontal: no cell is flagged, and the products clipped at the horizontal are those of
   * the endless plain on the edges too. PositiveOpenness is not clipped (ap_horizon.h): on the
   * west edge the 15 sectors pointing west of north-south (azimuths 191.25..348.75 deg) leave
   * the DEM at once and count a zenith angle of 180 deg, the other 17 about 90 deg, so the
   * edge's openness is (15 x 180 + 17 x 90) / 32 = 132.19 deg where the plain gives 90. */
  p = params(32, 1);
  r = compute(&t, &p);
  {
    const size_t k = 10 * t.nx; /* west edge, mid-height */
    AP_CHECK_EQ_INT(r.edge[k], 0);
    AP_CHECK_NEAR(r.A[k], 2 * PI, 1e-5);
    AP_CHECK_NEAR(r.svf[k], 1.0, 1e-6);
    AP_CHECK_NEAR(r.h[k * 32 + 24], -PI / 2, 1e-6);
    AP_CHECK_NEAR(r.open[k], (15 * PI + 17 * PI / 2) / 32, 1e-4);
  }
  release(&r);
  /* With a search distance the flag is the distance's alone, as without curvature
   * (test_edge_flags; a piece of a DEM would not know the DEM's highest cell): on the plain,
   * cells within 55 m (5.5 columns) of an edge are flagged, the others not, in every mode. */
  p.max_distance = 55.0;
  for (mode = 0; mode < SEARCH_MODES; ++mode) {
    size_t wrong = 0;
    set_mode(&p, mode, 64);
    r = compute(&t, &p);
    for (j = 0; j < t.ny; ++j) {
      for (i = 0; i < t.nx; ++i) {
        wrong += r.edge[j * t.nx + i] != (cells_from_edge(&t, i, j) * 10 < 55);
      }
    }
    AP_CHECK_EQ_INT((int)wrong, 0);
    release(&r);
  }
  drop(&t);
}

/* An inclined plane z = tan(S) y (S = 30 deg, facing south): the horizon is the plane itself,
 * h(phi) = atan(tan S cos phi), exactly on the grid; products equal the sector sums of that
 * horizon to float precision at D = 32, and with D = 360 the continuous closed forms
 * (ALGORITHMS.md table 2.4 (d2): A = 2 pi - 2S, SVF = 1 - S/pi, V_d = (1 + cos S)/2,
 * rp = acos(S/pi), bent normal tilted S/2 south) within the O(1/D^2) sector error. */
static void test_inclined_plane(void)
{
  const double S = 30 * DEG, cell = 25.0;
  const int D = 32;
  terrain t = make(60, 60, cell);
  ap_horizon_params p = params(D, 0);
  results r;
  size_t i, j;
  double ht[32], hs[32];
  int d;
  sector_sums e;
  for (j = 0; j < t.ny; ++j) {
    for (i = 0; i < t.nx; ++i) {
      t.z[j * t.nx + i] = (float)(tan(S) * (double)j * cell);
    }
  }
  r = compute(&t, &p);
  for (d = 0; d < D; ++d) {
    ht[d] = atan(tan(S) * cos(2 * PI * d / D));
    hs[d] = ht[d];
  }
  e = sums(D, ht, hs);
  {
    const size_t k = 30 * t.nx + 30;
    const double len = sqrt(e.bx * e.bx + e.by * e.by + e.bz * e.bz);
    for (d = 0; d < D; ++d) {
      AP_CHECK_NEAR(r.h[k * (size_t)D + (size_t)d], ht[d], 2e-6);
    }
    AP_CHECK_NEAR(r.A[k], e.A, 2e-5);
    AP_CHECK_NEAR(r.svf[k], e.svf, 2e-6);
    AP_CHECK_NEAR(r.vd[k], (-0.0 * e.bx - tan(S) * e.by + e.bz) / sqrt(1 + tan(S) * tan(S)) / PI,
                  2e-6);
    AP_CHECK_NEAR(r.bn[3 * k + 1], e.by / len, 2e-6);
    AP_CHECK(r.bn[3 * k + 1] < 0 && fabs(r.bn[3 * k]) < 1e-6); /* tilted toward the south */
  }
  release(&r);
  /* With 360 sectors the sums are within ~1e-5 of the continuous closed forms. */
  p.directions = 360;
  r = compute(&t, &p);
  {
    const size_t k = 30 * t.nx + 30;
    AP_CHECK_NEAR(r.svf[k], 1 - S / PI, 2e-5);
    AP_CHECK_NEAR(r.vd[k], (1 + cos(S)) / 2, 2e-5);
    AP_CHECK_NEAR(r.A[k], 2 * PI - 2 * S, 1e-4);
    AP_CHECK_NEAR(acos(r.bn[3 * k + 2]) / DEG, 15.0, 0.01); /* tilt S/2 */
    AP_CHECK_NEAR(r.rp[k], acos(S / PI), 2e-5);
  }
  release(&r);
  drop(&t);
}

/* A V-valley along the north-south axis, sides rising at alpha = 30 deg from a floor on grid
 * column 30: from the floor h(phi) = atan(tan(alpha) |sin phi|) exactly; products equal the
 * sector sums; with D = 360, SVF = 1 - 2 alpha/pi, V_d = cos alpha (ALGORITHMS.md 2.4 (c)),
 * A = 2(pi - 2 alpha); zenith bent normal. Along the axis (sectors 0 and D/2) the floor ends
 * at the DEM edge, which costs the 360-sector sums a little (2 of 360 sectors). */
static void test_valley(void)
{
  const double alpha = 30 * DEG, cell = 20.0;
  const int D = 32;
  terrain t = make(61, 80, cell);
  ap_horizon_params p = params(D, 0);
  results r;
  size_t i, j;
  double ht[32], hs[32];
  int d;
  sector_sums e;
  for (j = 0; j < t.ny; ++j) {
    for (i = 0; i < t.nx; ++i) {
      t.z[j * t.nx + i] = (float)(tan(alpha) * fabs((double)i - 30.0) * cell);
    }
  }
  r = compute(&t, &p);
  for (d = 0; d < D; ++d) {
    ht[d] = atan(tan(alpha) * fabs(sin(2 * PI * d / D)));
    hs[d] = 0.0; /* Horn's gradient on the floor of a symmetric V is zero */
  }
  e = sums(D, ht, hs);
  for (j = 20; j < 60; j += 13) {
    const size_t k = j * t.nx + 30;
    for (d = 0; d < D; ++d) {
      if (d == 0 || d == D / 2) {
        continue; /* along the floor the horizon is the floor's end, not a closed form */
      }
      AP_CHECK_NEAR(r.h[k * (size_t)D + (size_t)d], ht[d], 2e-6);
    }
    AP_CHECK_NEAR(r.svf[k], e.svf, 2e-6);
    AP_CHECK_NEAR(r.vd[k], e.bz / PI, 2e-6);
    AP_CHECK_NEAR(r.vd[k], cos(alpha), 1e-5); /* exact for any even D here */
    AP_CHECK_NEAR(r.bn[3 * k + 2], 1.0, 1e-6);
  }
  release(&r);
  p.directions = 360;
  r = compute(&t, &p);
  {
    const size_t k = 40 * t.nx + 30;
    AP_CHECK_NEAR(r.svf[k], 1 - 2 * alpha / PI, 2e-4); /* the two axis sectors end at the DEM */
    AP_CHECK_NEAR(r.A[k], 2 * (PI - 2 * alpha), 1e-3);
    AP_CHECK_NEAR(r.vd[k], cos(alpha), 2e-5);
  }
  release(&r);
  drop(&t);
}

/* Flat ground and, north of it, a plateau of height H whose edge is the grid row 50 (a wall
 * sloping over one cell, which the grid represents exactly). From a point x = 40 cells south
 * of the edge, for sectors facing the wall (cos phi > 0): h = atan(H cos(phi) / x) while the
 * ray meets the wall inside the DEM; 0 elsewhere (flat ground, no curvature). */
static void test_wall(void)
{
  const double cell = 10.0, H = 400.0;
  const int D = 32;
  terrain t = make(401, 90, cell);
  ap_horizon_params p = params(D, 0);
  results r;
  size_t i, j, k;
  int d;
  for (j = 50; j < t.ny; ++j) {
    for (i = 0; i < t.nx; ++i) {
      t.z[j * t.nx + i] = (float)H;
    }
  }
  r = compute(&t, &p);
  k = 10 * t.nx + 200;
  for (d = 0; d < D; ++d) {
    const double phi = 2 * PI * d / D, x = 40 * cell;
    /* rows north of the observer where the ray leaves the DEM through its east/west edge */
    const double exit_rows = fabs(sin(phi)) > 1e-9 ? 200.0 / fabs(tan(phi)) : INFINITY;
    double expected = 0.0;
    if (cos(phi) <= 1e-9 || exit_rows < 39.0) {
      expected = 0.0; /* the ray never meets the wall */
    } else if (exit_rows >= 40.0) {
      expected = atan(H * cos(phi) / x); /* it passes over the wall's top edge */
    } else {
      continue; /* it leaves the DEM on the wall's one-cell ramp: no simple closed form */
    }
    /* Rays crossing columns (|sin phi| large) sample the wall's top edge between rows. The
     * cell's ray is evaluated at the columns of its two bracketing lines' tangent points, the
     * first samples of each line on the wall; the line below the ray, up to a row away,
     * meets the edge up to one row later, |tan phi| columns (cell / |cos phi| along the ray),
     * and its first sample on the wall is at most one column (cell / |sin phi|) past that. */
    {
      const double along = x / fmax(cos(phi), 1e-9);
      const double late = cell / fabs(sin(phi)) + cell / fmax(fabs(cos(phi)), 1e-9);
      const double slack = fabs(sin(phi)) > fabs(cos(phi)) && expected > 0
                             ? fabs(atan(H / along) - atan(H / (along + late)))
                             : 0.0;
      AP_CHECK_NEAR(r.h[k * (size_t)D + (size_t)d], expected, 2e-6 + slack);
    }
  }
  release(&r);
  drop(&t);
}

/* The bottom centre of a cylindrical pit of radius R = 60 cells and depth D = 30 cells: the
 * horizon is atan(D / R) in every direction, SVF = 1 - sin h, V_d = cos^2 h, rp = pi/2 - h
 * (ALGORITHMS.md 2.4 (b)). The grid cannot draw a circle: along each ray the rim's top is
 * first sampled between R and R + sqrt(2) cells, so the tolerance is the change of each
 * quantity over that range. */
static void test_pit(void)
{
  const double cell = 5.0, R = 60.0, Dp = 30.0;
  const int D = 32;
  terrain t = make(161, 161, cell);
  ap_horizon_params p = params(D, 0);
  results r;
  size_t i, j, k = 80 * 161 + 80;
  const double h_in = atan(Dp / R), h_out = atan(Dp / (R + sqrt(2.0)));
  int d;
  for (j = 0; j < t.ny; ++j) {
    for (i = 0; i < t.nx; ++i) {
      const double rr = hypot((double)i - 80.0, (double)j - 80.0);
      t.z[j * t.nx + i] = rr < R ? (float)(-Dp * cell) : 0.0f;
    }
  }
  r = compute(&t, &p);
  for (d = 0; d < D; ++d) {
    const double h = r.h[k * (size_t)D + (size_t)d];
    AP_CHECK(h <= h_in + 1e-6 && h >= h_out - 1e-6);
  }
  AP_CHECK(r.svf[k] >= 1 - sin(h_in) - 1e-6 && r.svf[k] <= 1 - sin(h_out) + 1e-6);
  AP_CHECK(r.vd[k] >= cos(h_in) * cos(h_in) - 1e-6 && r.vd[k] <= cos(h_out) * cos(h_out) + 1e-6);
  AP_CHECK(r.rp[k] >= PI / 2 - h_in - 1e-5 && r.rp[k] <= PI / 2 - h_out + 1e-5);
  AP_CHECK_NEAR(r.svf[k], 0.552786, 0.02); /* R = 2D: sin h = 1/sqrt 5 */
  AP_CHECK_NEAR(r.bn[3 * k + 2], 1.0, 1e-4);
  release(&r);
  drop(&t);
}

/* The bottom of a shaft one cell wide (1 m cells, the cell H below its neighbours, which are
 * level): along a ray at azimuth phi the bilinear patch rises by H t (|sin phi| + |cos phi|
 * - t |sin phi cos phi|), so the horizon is its limit at t -> 0, atan(H (|sin phi| +
 * |cos phi|)), and the products are the sector sums of those horizons (flat normal). With H
 * of kilometres every horizon lies within 1e-4 rad of the zenith: the sums' terms 1 - sin h
 * and Q(h) must not cancel in single precision (a 9 km shaft's bent normal came out 52
 * degrees off the zenith its symmetry gives, its visible solid angle 0). */
static void test_deep_shaft(void)
{
  static const double depths[3] = { 10.0, 1e3, 9e3 };
  static const int sectors[2] = { 32, 33 };
  int a, b, mode;
  for (a = 0; a < 3; ++a) {
    for (b = 0; b < 2; ++b) {
      for (mode = 0; mode < 2; ++mode) {
        const double H = depths[a];
        const int D = sectors[b];
        terrain t = make(9, 9, 1.0);
        ap_horizon_params p = params(D, 0);
        double *ht = (double *)malloc((size_t)D * sizeof(double));
        double *hs = (double *)malloc((size_t)D * sizeof(double));
        const size_t k = 4 * 9 + 4;
        sector_sums want;
        double len;
        results r;
        int d;
        t.z[k] = (float)-H;
        if (mode == 1) {
          p.max_distance = 4.0;
          set_mode(&p, MARCHED, 64);
        }
        for (d = 0; d < D; ++d) {
          const double phi = 2 * PI * d / D;
          ht[d] = atan(H * (fabs(sin(phi)) + fabs(cos(phi))));
          hs[d] = 0.0;
        }
        want = sums(D, ht, hs);
        r = compute(&t, &p);
        for (d = 0; d < D; ++d) {
          AP_CHECK_NEAR(r.h[k * (size_t)D + (size_t)d], ht[d], 2e-7);
        }
        len = sqrt(want.bx * want.bx + want.by * want.by + want.bz * want.bz);
        AP_CHECK_NEAR(r.A[k] / want.A, 1.0, 1e-5);
        AP_CHECK_NEAR(r.rp[k] / acos(1 - want.A / (2 * PI)), 1.0, 1e-5);
        AP_CHECK_NEAR(r.vd[k] / (want.bz / PI), 1.0, 1e-5);
        AP_CHECK_NEAR(r.bn[3 * k], want.bx / len, 1e-5);
        AP_CHECK_NEAR(r.bn[3 * k + 1], want.by / len, 1e-5);
        AP_CHECK_NEAR(r.bn[3 * k + 2], want.bz / len, 1e-6);
        release(&r);
        drop(&t);
        free(ht);
        free(hs);
      }
    }
  }
}

/* Steep planes (slopes of 60, 80 and 88 degrees, falling toward azimuth 37, D = 33): the
 * sectors' horizons run from the slope down to the horizontal, so their zenith distances take
 * every value the sums' terms meet, both sides of where Q(h) changes from its series to its
 * direct form; every product must equal the sector sums of the closed-form horizons (a
 * symmetric shaft leaves B's horizontal 0 whatever Q is: a Q 5% off passed it). */
static void test_steep_planes(void)
{
  static const double slopes[3] = { 60 * DEG, 80 * DEG, 88 * DEG };
  const double A = 37 * DEG, cell = 10.0;
  const int D = 33;
  int a, d;
  for (a = 0; a < 3; ++a) {
    const double t = tan(slopes[a]), gx = -t * sin(A), gy = -t * cos(A);
    terrain ter = make(61, 61, cell);
    ap_horizon_params p = params(D, 0);
    double ht[33], hs[33], len, n;
    const size_t k = 30 * 61 + 30;
    sector_sums e;
    results r;
    size_t i, j;
    for (j = 0; j < ter.ny; ++j) {
      for (i = 0; i < ter.nx; ++i) {
        ter.z[j * ter.nx + i] =
          (float)(gx * ((double)i - 30) * cell + gy * ((double)j - 30) * cell);
      }
    }
    for (d = 0; d < D; ++d) {
      const double phi = 2 * PI * d / D;
      ht[d] = hs[d] = atan(gx * sin(phi) + gy * cos(phi));
    }
    e = sums(D, ht, hs);
    r = compute(&ter, &p);
    len = sqrt(e.bx * e.bx + e.by * e.by + e.bz * e.bz);
    n = sqrt(1 + gx * gx + gy * gy);
    for (d = 0; d < D; ++d) {
      AP_CHECK_NEAR(r.h[k * (size_t)D + (size_t)d], ht[d], 2e-6); /* (as the gentle plane's) */
    }
    AP_CHECK_NEAR(r.A[k] / e.A, 1.0, 2e-6);
    AP_CHECK_NEAR(r.vd[k], (-gx * e.bx - gy * e.by + e.bz) / n / PI, 2e-6);
    AP_CHECK_NEAR(r.bn[3 * k], e.bx / len, 2e-6);
    AP_CHECK_NEAR(r.bn[3 * k + 1], e.by / len, 2e-6);
    AP_CHECK_NEAR(r.bn[3 * k + 2], e.bz / len, 2e-6);
    release(&r);
    drop(&ter);
  }
}

/* Curvature: a 1000 m peak 100 km east of an observer on flat ground. The exact elevation of
 * the peak's top from a sphere of effective radius R / (1 - k) (the standard refraction
 * model) is atan2((Re + H) cos a - Re, (Re + H) sin a), a = d / Re; the sweep's parabolic drop
 * agrees with it to ~3e-4 deg here. Without curvature: atan(H / d). */
static void test_curvature(void)
{
  const double cell = 50.0, H = 1000.0, R = 6371000.0, k = 0.13;
  terrain t = make(2001, 5, cell);
  ap_horizon_params p = params(4, 1);
  results r;
  size_t obs = 2 * t.nx + 0;
  double Re = R / (1 - k), a = 2000 * cell / Re;
  double exact = atan2((Re + H) * cos(a) - Re, (Re + H) * sin(a));
  t.z[2 * t.nx + 2000] = (float)H;
  p.refraction = k;
  p.radius_meridian = p.radius_normal = R;
  r = compute(&t, &p);
  AP_CHECK_NEAR(r.h[obs * 4 + 1] / DEG, exact / DEG, 0.01); /* sector 1 = east */
  AP_CHECK(fabs(r.h[obs * 4 + 1] / DEG - atan(H / (2000 * cell)) / DEG) > 0.3);
  release(&r);
  p.curvature = 0;
  r = compute(&t, &p);
  AP_CHECK_NEAR(r.h[obs * 4 + 1], atan(H / (2000 * cell)), 1e-6);
  release(&r);
  drop(&t);
}

/* Rough synthetic terrain for brute-force comparisons: a few octaves of sinusoids plus hash
 * noise, heights in metres. */
static double rough(double x, double y)
{
  /* (through int64_t: a double beyond unsigned's range does not convert to it) */
  unsigned h = (unsigned)(int64_t)(x * 73856093.0) ^ (unsigned)(int64_t)(y * 19349663.0);
  h = (h ^ (h >> 13)) * 1274126177u;
  return 300 * sin(x / 900) * cos(y / 700) + 120 * sin(x / 230 + 1.3) * sin(y / 310) +
         40 * cos(x / 70 - y / 90) + 6.0 * ((double)(h & 1023u) / 1023.0 - 0.5);
}

/* Independent reference: march the cell's own ray in ground metres, bilinear heights. Steps
 * are 1/16 of the smallest cell, and near the observer also geometrically shorter (down to
 * 1e-6 of a cell): on a bilinear patch the elevation angle is often largest as t -> 0 (the
 * surface's own slope along the ray), which fixed steps would miss by up to a degree on rough
 * terrain. For the same reason it also takes the points where the ray crosses a grid line
 * (kinks of the surface, often peaks along the ray) and its last point, at the grid's edge or
 * the search distance: without them it read up to 0.4 deg low. Positions come from
 * geographic-like coordinates when the grid has per-row cell sizes (constant azimuth: north
 * step ds cos phi over the row's dy, east step ds sin phi over the row's dx). */
static double height_at(const terrain *t, double ci, double cj)
{
  size_t a = (size_t)ci, b = (size_t)cj;
  double fi, fj, lo, hi;
  if (a + 1 >= t->nx) a = t->nx - 2;
  if (b + 1 >= t->ny) b = t->ny - 2;
  fi = ci - (double)a;
  fj = cj - (double)b;
  /* A point within 1e-9 of a grid line lies on it: a corner of zero weight is not read, so a
   * point on the line between two cells with data has their height whatever lies beside it
   * (nodata: a NaN corner of nonzero weight voids the point). */
  if (fi < 1e-9) fi = 0.0;
  if (fj < 1e-9) fj = 0.0;
  if (fi > 1.0 - 1e-9) fi = 1.0;
  if (fj > 1.0 - 1e-9) fj = 1.0;
#define ROW(r) (fi == 0.0   ? t->z[(r) * t->nx + a]                                           \
                : fi == 1.0 ? t->z[(r) * t->nx + a + 1]                                       \
                            : (1 - fi) * t->z[(r) * t->nx + a] + fi * t->z[(r) * t->nx + a + 1])
  lo = fj == 1.0 ? 0.0 : ROW(b);
  hi = fj == 0.0 ? 0.0 : ROW(b + 1);
#undef ROW
  return fj == 0.0 ? lo : (fj == 1.0 ? hi : (1 - fj) * lo + fj * hi);
}

static int inside(const terrain *t, double ci, double cj)
{
  return ci >= 0 && cj >= 0 && ci <= (double)(t->nx - 1) && cj <= (double)(t->ny - 1);
}

static double brute_force(const terrain *t, size_t i0, size_t j0, double phi, double c,
                          double maxd)
{
  const double z0 = t->z[j0 * t->nx + i0];
  const double cell = fmin(t->dx0, t->dy0), ds = cell / 16.0;
  /* (a ray along an axis keeps to its row or column: sin and cos of the axes' azimuths are
   * rounding noise, which took a ray along the grid's first row or column off the grid) */
  const double sphi = fabs(sin(phi)) > 1e-12 ? sin(phi) : 0.0;
  const double cphi = fabs(cos(phi)) > 1e-12 ? cos(phi) : 0.0;
  double ci = (double)i0, cj = (double)j0, dist = 0.0, best = -INFINITY, tiny;
  /* near the observer: geometric distances, positions from the cell's own row sizes */
  for (tiny = 1e-6 * cell; tiny < ds; tiny *= 1.5) {
    const double dxr = t->dx ? t->dx[j0] : t->dx0, dyr = t->dy ? t->dy[j0] : t->dy0;
    const double ti = ci + tiny * sphi / dxr, tj = cj + tiny * cphi / dyr;
    if (inside(t, ti, tj)) { /* (not beyond an edge cell) */
      const double s = (height_at(t, ti, tj) - z0) / tiny - c * tiny;
      if (s > best) best = s;
    }
  }
  for (;;) {
    const size_t jr = cj < 0 ? 0 : (cj > (double)(t->ny - 1) ? t->ny - 1 : (size_t)cj);
    const double dxr = t->dx ? t->dx[jr] : t->dx0, dyr = t->dy ? t->dy[jr] : t->dy0;
    const double di = ds * sphi / dxr, dj = ds * cphi / dyr;
    double s, lo = 0.0, hi = 1.0, f[2];
    int k;
    /* Where the step crosses a grid line the bilinear surface has a kink, often a peak along
     * the ray that fixed steps would miss: take those points too. */
    f[0] = di > 0 ? (floor(ci) + 1 - ci) / di : (di < 0 ? (ceil(ci) - 1 - ci) / di : 2.0);
    f[1] = dj > 0 ? (floor(cj) + 1 - cj) / dj : (dj < 0 ? (ceil(cj) - 1 - cj) / dj : 2.0);
    for (k = 0; k < 2; ++k) {
      const double end = dist + f[k] * ds;
      if (f[k] <= 1.0 && inside(t, ci + f[k] * di, cj + f[k] * dj) && end <= maxd) {
        s = (height_at(t, ci + f[k] * di, cj + f[k] * dj) - z0) / end - c * end;
        if (s > best) best = s;
      }
    }
    if (inside(t, ci + di, cj + dj) && dist + ds <= maxd) {
      ci += di;
      cj += dj;
      dist += ds;
      s = (height_at(t, ci, cj) - z0) / dist - c * dist;
      if (s > best) best = s;
      continue;
    }
    /* The last piece of the ray, to the grid's edge or the search distance, whichever comes
     * first: terrain often rises to it, so find that end point by bisection and take it too. */
    for (k = 0; k < 50; ++k) {
      const double mid = 0.5 * (lo + hi);
      if (inside(t, ci + mid * di, cj + mid * dj) && dist + mid * ds <= maxd) {
        lo = mid;
      } else {
        hi = mid;
      }
    }
    if (lo > 1e-9) { /* (less is the bisection's rounding where the ray leaves at once) */
      const double end = dist + lo * ds;
      s = (height_at(t, ci + lo * di, cj + lo * dj) - z0) / end - c * end;
      if (s > best) best = s;
    }
    break;
  }
  return best == -INFINITY ? -PI / 2 : atan(best);
}

static int cmp_double(const void *a, const void *b)
{
  const double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

/* Every how many cells (along rows and columns) the brute force checks: 1, or the environment's
 * AP_TEST_REFERENCE_STRIDE (the Valgrind run sets 4: the kernel still computes every cell, so
 * memcheck sees all of its paths, but the reference, slow under Valgrind and not what it
 * checks, runs on a sixteenth of the cells). */
static size_t reference_stride(void)
{
  static size_t stride = 0;
  if (stride == 0) {
    const char *v = getenv("AP_TEST_REFERENCE_STRIDE");
    const long n = v ? strtol(v, NULL, 10) : 1;
    stride = n >= 1 && n <= 64 ? (size_t)n : 1;
  }
  return stride;
}

/* Horizons of every cell at least 6 cells from the edges, in every sector, against the brute
 * force: mean absolute error <= 0.05 deg and 99th percentile <= 0.5 deg (the issue's targets;
 * the sweep samples the piecewise-linear surface along grid lines, the reference bilinear
 * patches, which differ by a fraction of the local relief inside one cell). */
static double compare_brute_force(const terrain *t, const ap_horizon_params *p, const char *what)
{
  results r = compute(t, p);
  const int D = p->directions;
  size_t i, j, n = 0, cap = t->nx * t->ny * (size_t)D;
  double *err = (double *)malloc(cap * sizeof(double)), sum = 0.0, p99, worst;
  const double c = p->curvature ? (1 - p->refraction) / (2 * p->radius_normal) : 0.0;
  int d;
  for (j = 6; j + 6 < t->ny; j += 3 * reference_stride()) {
    for (i = 6; i + 6 < t->nx; i += 3 * reference_stride()) {
      for (d = 0; d < D; ++d) {
        const double phi = 2 * PI * d / D;
        const double ref = brute_force(t, i, j, phi, c, p->max_distance);
        const double got = r.h[(j * t->nx + i) * (size_t)D + (size_t)d];
        err[n] = fabs(got - ref) / DEG;
        sum += err[n++];
      }
    }
  }
  qsort(err, n, sizeof(double), cmp_double);
  p99 = err[(size_t)(0.99 * (double)(n - 1))];
  worst = err[n - 1];
  fprintf(stderr, "%s: %zu cell-directions, MAE %.4f deg, p99 %.4f deg, max %.3f deg\n", what, n,
          sum / (double)n, p99, worst);
  AP_CHECK(sum / (double)n <= 0.05);
  AP_CHECK(p99 <= 0.5);
  free(err);
  release(&r);
  return p99;
}

/* nx x ny cells of 30 m of the rough terrain */
static terrain rough_terrain(size_t nx, size_t ny)
{
  terrain t = make(nx, ny, 30.0);
  size_t i, j;
  for (j = 0; j < t.ny; ++j) {
    for (i = 0; i < t.nx; ++i) {
      t.z[j * t.nx + i] = (float)rough((double)i * 30.0, (double)j * 30.0);
    }
  }
  return t;
}

static void test_brute_force(void)
{
  terrain t = rough_terrain(120, 100);
  ap_horizon_params p = params(32, 1);
  p.radius_meridian = p.radius_normal = 6371000.0;
  {
    /* The automatic near field (0: 32 columns exact where the hulls search) against 8: the
     * hulls miss most near the cell, so the longer exact stretch must cut the p99 at least in
     * half (measured: 0.022 against 0.115 deg). */
    const double automatic = compare_brute_force(&t, &p, "rough, unlimited");
    p.near_field = 8;
    AP_CHECK(automatic < 0.5 * compare_brute_force(&t, &p, "rough, unlimited, near field 8"));
  }
  /* The search modes at one near field, K = 8 (p.near_field stays 8 until below).
   * 900 m is 30 columns: the rays are marched exactly to the distance (march_columns), on the
   * reference's own bilinear surface, so they must match it to its step (p99 0.0008 deg, max
   * 0.007 measured); the same radius through the far march (samples where each ray crosses the
   * view columns, as the hulls hold them: p99 0.13 deg) and through the hulls (0.13-0.21 deg),
   * and 2500 m (83 columns, beyond march_columns) both ways, must meet the issue's bounds. */
  p.max_distance = 900.0;
  {
    double p99[SEARCH_MODES];
    int mode;
    char what[64];
    for (mode = 0; mode < SEARCH_MODES; ++mode) {
      set_mode(&p, mode, 64);
      snprintf(what, sizeof what, "rough, 900 m radius, %s", mode_name[mode]);
      p99[mode] = compare_brute_force(&t, &p, what);
    }
    AP_CHECK(p99[MARCHED] <= 0.005);
    AP_CHECK(p99[MARCHED] < p99[FAR_MARCHED]);
    AP_CHECK(p99[MARCHED] < p99[SWEPT]);
    AP_CHECK(p99[FAR_MARCHED] <= p99[SWEPT]);
    p.max_distance = 2500.0;
    for (mode = FAR_MARCHED; mode <= SWEPT; ++mode) {
      set_mode(&p, mode, 64);
      snprintf(what, sizeof what, "rough, 2500 m radius, %s", mode_name[mode]);
      p99[mode] = compare_brute_force(&t, &p, what);
    }
    AP_CHECK(p99[FAR_MARCHED] <= p99[SWEPT]); /* (0.082 and 0.115 deg measured) */
    set_mode(&p, MARCHED, 64);
  }
  p.near_field = 0;
  p.max_distance = INFINITY;
  p.directions = 7 * 4 + 1; /* odd sector counts: azimuths off every grid diagonal */
  compare_brute_force(&t, &p, "rough, 29 sectors");
  drop(&t);
}

/* Long, narrow grids, either way round: each band of sweep lines crosses the grid within a few
 * columns, and the sweep starts and stops it there (band_columns) instead of walking every
 * column (a 40000 x 2 DEM took 13 s, not 0.3). Every cell must still get the brute force's
 * horizons, unlimited and through the windows of a limited sweep. */
static void test_long_narrow(void)
{
  const size_t sizes[2][2] = { { 600, 14 }, { 14, 600 } };
  int k;
  for (k = 0; k < 2; ++k) {
    terrain t = rough_terrain(sizes[k][0], sizes[k][1]);
    ap_horizon_params p = params(32, 1);
    p.radius_meridian = p.radius_normal = 6371000.0;
    compare_brute_force(&t, &p, k ? "14 x 600, unlimited" : "600 x 14, unlimited");
    p.max_distance = 4000.0;
    set_mode(&p, SWEPT, 64);
    compare_brute_force(&t, &p, k ? "14 x 600, 4000 m, swept" : "600 x 14, 4000 m, swept");
    drop(&t);
  }
  /* The same on lat/lon rows (about 29 x 33 m cells at 50 N): the x-major sectors' lines bend,
   * and each band starts where its first line nears the grid (band_columns on lattice_row),
   * its lines' distances in closed form until they reach it. */
  for (k = 0; k < 2; ++k) {
    terrain t = rough_terrain(sizes[k][0], sizes[k][1]);
    ap_horizon_params p = params(32, 1);
    latlon_rows(&t, 6371000.0, 50.0 * DEG, 0.0003 * DEG, 0.0004 * DEG);
    p.radius_meridian = p.radius_normal = 6371000.0;
    compare_brute_force(&t, &p, k ? "lat/lon 14 x 600, unlimited" : "lat/lon 600 x 14, unlimited");
    p.max_distance = 4000.0;
    set_mode(&p, SWEPT, 64);
    compare_brute_force(&t, &p,
                        k ? "lat/lon 14 x 600, 4000 m, swept" : "lat/lon 600 x 14, 4000 m, swept");
    drop(&t);
  }
}

/* A lat/lon-like grid over 40..60 N: the east-west cell size shrinks by a third from south to
 * north, so sweep lines bend; horizons must still match the constant-azimuth brute force. */
static void test_latlon_rows(void)
{
  terrain t = make(90, 100, 0.0);
  ap_horizon_params p = params(32, 1);
  const double R = 6371000.0, dlat = 0.2 * DEG, dlon = 0.3 * DEG;
  size_t i, j;
  latlon_rows(&t, R, 40 * DEG, dlat, dlon);
  for (j = 0; j < t.ny; ++j) {
    const double lat = 40 * DEG + (double)j * dlat;
    for (i = 0; i < t.nx; ++i) {
      /* terrain on the sphere: heights from ground coordinates (km-scale relief) */
      const double east = (double)i * dlon * R * cos(lat), north = (double)j * dlat * R;
      t.z[j * t.nx + i] = (float)(3000 * sin(east / 90000) * cos(north / 70000) +
                                  1500 * sin(east / 23000 + north / 31000));
    }
  }
  p.radius_meridian = p.radius_normal = R;
  compare_brute_force(&t, &p, "lat/lon 40-60 N");
  /* 8 to 9 columns: marched along straight index-space lines, which the rhumb lines of these
   * 0.2-degree rows leave by up to a twentieth of a cell: no more exact than the sweep here
   * (p99 0.033 deg both), but within the same bounds */
  p.max_distance = 200000.0;
  compare_brute_force(&t, &p, "lat/lon 40-60 N, 200 km, marched");
  p.march_columns = 0;
  compare_brute_force(&t, &p, "lat/lon 40-60 N, 200 km, far-marched");
  p.far_march_columns = 0;
  compare_brute_force(&t, &p, "lat/lon 40-60 N, 200 km, swept");
  drop(&t);
  /* Rough terrain on rows of 0.0004 x 0.0006 degrees from 50 N (about 44 x 43 m), 3 km: 68 to
   * 70 steps, beyond march_columns, so every ray far-marches along its rhumb line (steps from
   * the cell's row on: p99 0.0096 deg, max 0.18 measured); then the sweep with the same 8
   * exact columns (p99 0.034, max 1.1). Both within the bounds, the far march no less
   * accurate than the sweep. */
  {
    terrain u = make(130, 120, 0.0);
    const double dlat2 = 0.0004 * DEG, dlon2 = 0.0006 * DEG;
    double p99_far, p99_swept;
    latlon_rows(&u, R, 50 * DEG, dlat2, dlon2);
    for (j = 0; j < u.ny; ++j) {
      const double lat = 50 * DEG + (double)j * dlat2;
      for (i = 0; i < u.nx; ++i) {
        const double east = (double)i * dlon2 * R * cos(lat), north = (double)j * dlat2 * R;
        u.z[j * u.nx + i] = (float)rough(east, north);
      }
    }
    p = params(32, 1);
    p.radius_meridian = p.radius_normal = R;
    p.max_distance = 3000.0;
    p99_far = compare_brute_force(&u, &p, "lat/lon rough 50 N, 3 km, far-marched");
    p.far_march_columns = 0;
    p.near_field = 8; /* the hulls beyond the far march's 8 columns, not the automatic 32 */
    p99_swept = compare_brute_force(&u, &p, "lat/lon rough 50 N, 3 km, swept");
    AP_CHECK(p99_far <= p99_swept + 0.01);
    drop(&u);
  }
}

/* The largest error (degrees) of the horizons against a reference over the cells from `from`
 * to `band` - 1 cells of the grid's edges, every sector: the far march's (ref: the same samples
 * of each cell's own ray, all of them) or else the brute force's (bilinear). */
static double edge_band_error(const terrain *t, const ap_horizon_params *p, const results *ref,
                              size_t from, size_t band, const char *what)
{
  results r = compute(t, p);
  const int D = p->directions;
  double worst = 0.0, sum = 0.0;
  size_t i, j, n = 0, wi = 0, wj = 0;
  int d, wd = 0;
  for (j = 0; j < t->ny; ++j) {
    for (i = 0; i < t->nx; ++i) {
      const size_t e_cells = cells_from_edge(t, i, j);
      if (e_cells < from || e_cells >= band || (!ref && (i + j) % reference_stride() != 0)) {
        continue;
      }
      for (d = 0; d < D; ++d) {
        const double phi = 2 * PI * d / D;
        const size_t k = (j * t->nx + i) * (size_t)D + (size_t)d;
        double e;
        e = fabs(r.h[k] - (ref ? ref->h[k] : brute_force(t, i, j, phi, 0.0, p->max_distance))) /
            DEG;
        sum += e;
        ++n;
        if (e > worst) {
          worst = e;
          wi = i;
          wj = j;
          wd = d;
        }
      }
    }
  }
  fprintf(stderr, "%s: %zu cell-directions %zu to %zu cells from an edge, MAE %.4f deg, max %.3f "
          "deg (cell %zu, %zu, sector %d)\n", what, n, from, band - 1, sum / (double)n, worst, wi,
          wj, wd);
  release(&r);
  return worst;
}

/* A bowl whose rim is the DEM's edge, seen along the sides: rays that leave the grid sideways
 * run, over their last stretch, where one of the two lines bracketing them has already left
 * and the other's hull is tangent beyond the ray's end. The sweep used to lose that stretch
 * (33 degrees low on an edge row, 4.5 twenty cells in, on a 1024^2 bowl); its cells now sample
 * their own rays there. And the samples where rays cross view columns stop up to a column
 * short of where a ray leaves through a side, where this bowl is highest: the sweep and the
 * far march used to be up to 3.1 degrees low against the brute force (MAE 0.05 to 0.11), the
 * lat/lon sweep 0.97; both now take the point where the ray leaves. Against the far march,
 * which takes every sample of every ray (no curvature: a distance beyond the grid is
 * unlimited), and against the brute force (the 48 x 40 bowl, every cell up to 29 cells from an
 * edge, the edge cells included: both find no terrain in the directions leaving at once), at
 * unlimited and limited distance, D = 32 (sectors along the axes, whose lines used to lie a
 * rounding error off the edge) and D = 29. The brute force keeps an axis ray on its row or
 * column; it had left the edge cells out, its own rays along an edge leaving the grid by a
 * rounding error. On lat/lon rows the sweep's lines of the first and last columns lay a
 * rounding error off the grid, and those of the first and last rows a fraction of a row off,
 * lines being spaced evenly in Psi: those cells were up to 17 and 27 deg low along their
 * edge. The bowl is smooth, its horizons everywhere the edge: measured within 0.003 deg of
 * the brute force; 0.02 allowed (the piecewise-linear samples against the bilinear surface),
 * and 0.25 against the far march on the 1024^2 bowl's edge band. */
static void test_side_edges(void)
{
  const int Ds[2] = {32, 29};
  int latlon, k, limited;
  for (latlon = 0; latlon < 2; ++latlon) {
    terrain t = make(48, 40, 30.0);
    size_t i, j;
    if (latlon) {
      latlon_rows(&t, 6371000.0, 45 * DEG, 1.0 / 1200 * DEG, 1.0 / 1200 * DEG);
    }
    for (j = 0; j < t.ny; ++j) {
      for (i = 0; i < t.nx; ++i) {
        const double x = (double)i - 0.5 * (double)(t.nx - 1), y = (double)j - 0.4 * (double)t.ny;
        t.z[j * t.nx + i] = (float)(0.9 * (x * x + y * y) + 20.0 * sin(0.3 * x) * cos(0.2 * y));
      }
    }
    for (k = 0; k < 2; ++k) {
      for (limited = 0; limited < 2; ++limited) {
        ap_horizon_params p = params(Ds[k], 0);
        char what[96];
        const char *frame = latlon ? "lat/lon" : "projected";
        /* 8 exact columns (the far march's own): the automatic 32 would cover most of this
         * 48 x 40 bowl exactly and leave the sweep's side handling untested */
        p.near_field = 8;
        snprintf(what, sizeof what, "%s bowl, D = %d, %s, swept", frame, Ds[k],
                 limited ? "700 m" : "unlimited");
        p.max_distance = limited ? 700.0 : INFINITY;
        p.march_columns = 0;
        p.far_march_columns = 0;
        AP_CHECK(edge_band_error(&t, &p, NULL, 0, 30, what) <= 0.02);
        if (latlon) {
          p.far_march_columns = 1024;
          snprintf(what, sizeof what, "%s bowl, D = %d, %s, far march", frame, Ds[k],
                   limited ? "700 m" : "100 km");
          p.max_distance = limited ? 700.0 : 1e5;
          AP_CHECK(edge_band_error(&t, &p, NULL, 0, 30, what) <= 0.02);
        } else {
          results ref;
          p.max_distance = limited ? 700.0 : 1e6;
          p.far_march_columns = 65536;
          snprintf(what, sizeof what, "%s bowl, D = %d, %s, far march", frame, Ds[k],
                   limited ? "700 m" : "unlimited");
          AP_CHECK(edge_band_error(&t, &p, NULL, 0, 30, what) <= 0.02);
          ref = compute(&t, &p);
          p.max_distance = limited ? 700.0 : INFINITY;
          p.far_march_columns = 0;
          snprintf(what, sizeof what, "%s bowl, D = %d, %s, swept against far march", frame,
                   Ds[k], limited ? "700 m" : "unlimited");
          AP_CHECK(edge_band_error(&t, &p, &ref, 0, 12, what) <= 0.25);
          release(&ref);
        }
      }
    }
    drop(&t);
  }
}

/* The far march takes the point where a ray leaves through a side of the DEM, k view columns
 * on. On the diagonals of a DEM of square cells the view is x-major where sin(phi) / dx and
 * cos(phi) / dx round to one number (20 m cells; not 30 m), and its slope is then
 * cos / sin = 1 + 2e-16: the rays of the cells on the diagonal through a corner leave
 * k = n (1 - 2e-16) columns on, n the columns left. It read the columns at p + k rounded, the
 * last one, and the one after it, past the grid's columns (a crash, or garbage weighted by 0;
 * found by a probe of the filter at the default 32 directions; AddressSanitizer's run of this
 * test names the read). Those cells' horizons in the diagonal sectors must match the brute
 * force, for cells of 20 and 30 m, on DEMs wider and taller than long. */
static void test_far_march_corner_diagonals(void)
{
  const size_t dims[2][2] = {{100, 90}, {90, 100}};
  const double cells[2] = {20.0, 30.0};
  int shape, size, d;
  for (shape = 0; shape < 2; ++shape) {
    for (size = 0; size < 2; ++size) {
      terrain t = make(dims[shape][0], dims[shape][1], cells[size]);
      ap_horizon_params p = params(32, 0);
      results r;
      size_t i, j, k, n = 0;
      double worst = 0.0;
      for (j = 0; j < t.ny; ++j) {
        for (i = 0; i < t.nx; ++i) {
          t.z[j * t.nx + i] = (float)rough((double)i * 30.0, (double)j * 30.0);
        }
      }
      p.max_distance = 150 * cells[size]; /* (150 columns: far-marched) */
      r = compute(&t, &p);
      for (d = 4; d < 32; d += 8) { /* NE, SE, SW, NW */
        const double phi = 2 * PI * d / 32;
        const int east = d < 16, north = d < 8 || d > 24;
        for (k = 1; k < t.nx && k < t.ny; ++k) {
          /* the cell k cells (diagonally) from the corner the sector looks at */
          i = east ? t.nx - 1 - k : k;
          j = north ? t.ny - 1 - k : k;
          worst = fmax(worst, fabs(r.h[(j * t.nx + i) * 32 + (size_t)d] -
                                   brute_force(&t, i, j, phi, 0.0, p.max_distance)) /
                                DEG);
          ++n;
        }
      }
      fprintf(stderr, "far march, %zu x %zu cells of %.0f m, rays into the corners: %zu cells, "
              "max %.3f deg\n", t.nx, t.ny, cells[size], n, worst);
      AP_CHECK(worst <= 0.5);
      release(&r);
      drop(&t);
    }
  }
}

/* A tower one cell wide (ap_horizon.h, "Features a cell wide"): on flat ground with 10 m
 * cells, a 300 m tower 36 rows ahead and 1.5 degrees off a cell's 30-degree sector lies inside
 * a bilinear patch the ray crosses between two columns. Far-marched with the automatic near
 * field (8 columns) it is missed at 800 m and 2 km; the documented remedy, near_field 64, must
 * find it there as the brute force does (3.83 degrees), as the exact march (640 m) and the
 * sweep (unlimited, 32 exact columns) do with the automatic one. */
static void test_one_cell_tower(void)
{
  const double dists[4] = {640.0, 800.0, 2000.0, INFINITY};
  terrain t = make(80, 70, 10.0);
  size_t k;
  int m;
  for (k = 0; k < t.nx * t.ny; ++k) {
    t.z[k] = 50.0f;
  }
  t.z[40 * t.nx + 48] = 300.0f;
  for (m = 0; m < 4; ++m) {
    ap_horizon_params p = params(12, 1);
    results r;
    double ref, got;
    p.radius_meridian = p.radius_normal = 6371008.8;
    p.max_distance = dists[m];
    p.near_field = m == 1 || m == 2 ? 64 : 0;
    r = compute(&t, &p);
    got = r.h[(9 * t.nx + 29) * 12 + 1];
    ref = brute_force(&t, 29, 9, PI / 6, (1 - p.refraction) / (2 * 6371008.8), p.max_distance);
    fprintf(stderr, "one-cell tower, %.0f m, near field %d: %.4f deg (brute force %.4f)\n",
            p.max_distance, p.near_field, got / DEG, ref / DEG);
    /* (this brute force's steps of 1/16 cell pass 0.013 degree below the peak that steps of
     * 1/64 find, 3.833 degrees) */
    AP_CHECK(ref > 3.8 * DEG && fabs(got - ref) <= 0.03 * DEG);
    release(&r);
  }
  drop(&t);
}

/* Results are bitwise the same however the brackets and rows are split (threads), through the
 * hulls and with marched rays (on the bilinear surface, and across the view columns), with
 * constant and with per-row (lat/lon) cell sizes, whose x-major sectors split the near field by
 * rows. */
static void test_split_invariance_mode(int mode, int latlon)
{
  terrain t = make(70, 50, 30.0);
  ap_horizon_params p = params(16, 1);
  const size_t n = t.nx * t.ny;
  float *a[2][3];
  ap_horizon *hz[2];
  int run, d;
  size_t i, j;
  for (j = 0; j < t.ny; ++j) {
    for (i = 0; i < t.nx; ++i) {
      t.z[j * t.nx + i] = (float)rough((double)i * 30.0, (double)j * 30.0);
    }
  }
  t.z[5 * t.nx + 7] = NAN;
  if (latlon) {
    /* about 23 x 33 m cells at 60 N; rows 0.0003 degrees (the per-row patterns change every
     * few rows) */
    latlon_rows(&t, 6371000.0, 60.0 * DEG, 0.0003 * DEG, 0.0004 * DEG);
  }
  p.max_distance = 600.0;
  set_mode(&p, mode, 64);
  for (run = 0; run < 2; ++run) {
    ap_horizon_grid g = grid_of(&t);
    ap_sky_products o;
    memset(&o, 0, sizeof(o));
    a[run][0] = (float *)malloc(n * sizeof(float));
    a[run][1] = (float *)malloc(3 * n * sizeof(float));
    a[run][2] = (float *)malloc(n * 16 * sizeof(float));
    o.sky_view_factor = a[run][0];
    o.bent_normal = a[run][1];
    o.horizon_angles = a[run][2];
    AP_CHECK_EQ_INT(ap_horizon_create(&g, &p, &o, &hz[run]), AP_OK);
    for (d = 0; d < 16; ++d) {
      const size_t nb = (ap_horizon_prepare(hz[run], d), ap_horizon_bracket_count(hz[run]));
      const size_t nc = ap_horizon_near_field_count(hz[run]);
      if (run == 0) {
        AP_CHECK_EQ_INT(ap_horizon_near_field(hz[run], 0, nc), AP_OK);
        AP_CHECK_EQ_INT(ap_horizon_sweep(hz[run], 0, nb), AP_OK);
        AP_CHECK_EQ_INT(ap_horizon_accumulate(hz[run], 0, t.ny), AP_OK);
      } else {
        size_t b, r0;
        for (b = 0; b < nc; b += 5) {
          AP_CHECK_EQ_INT(ap_horizon_near_field(hz[run], b, b + 5 < nc ? b + 5 : nc), AP_OK);
        }
        for (b = 0; b < nb; b += 7) {
          AP_CHECK_EQ_INT(ap_horizon_sweep(hz[run], b, b + 7 < nb ? b + 7 : nb), AP_OK);
        }
        for (r0 = 0; r0 < t.ny; r0 += 3) {
          AP_CHECK_EQ_INT(ap_horizon_accumulate(hz[run], r0, r0 + 3), AP_OK);
        }
      }
    }
    ap_horizon_finish(hz[run], 0, t.ny);
    ap_horizon_destroy(hz[run]);
  }
  AP_CHECK(memcmp(a[0][0], a[1][0], n * sizeof(float)) == 0);
  AP_CHECK(memcmp(a[0][1], a[1][1], 3 * n * sizeof(float)) == 0);
  AP_CHECK(memcmp(a[0][2], a[1][2], 16 * n * sizeof(float)) == 0);
  AP_CHECK(isnan(a[0][0][5 * t.nx + 7])); /* nodata stays nodata */
  for (run = 0; run < 2; ++run) {
    for (d = 0; d < 3; ++d) {
      free(a[run][d]);
    }
  }
  drop(&t);
}

static void test_split_invariance(void)
{
  test_split_invariance_mode(SWEPT, 0);
  test_split_invariance_mode(MARCHED, 0);
  test_split_invariance_mode(FAR_MARCHED, 0);
  test_split_invariance_mode(SWEPT, 1);
  test_split_invariance_mode(MARCHED, 1);
  test_split_invariance_mode(FAR_MARCHED, 1);
}

/* The edge flag, closed form on a flat grid without curvature in the four axis sectors: a cell
 * is flagged when it lies within the search distance of an edge, whether the search runs
 * through the hulls or marches the rays (600 m = 20 columns of 30 m); horizons are 0 where the
 * ray stays on the grid. (march_columns 20: the distance is exactly at the limit.) */
static void test_edge_flags(void)
{
  terrain t = make(60, 45, 30.0);
  ap_horizon_params p = params(4, 0);
  int mode;
  size_t i, j;
  for (j = 0; j < t.ny; ++j) {
    for (i = 0; i < t.nx; ++i) {
      t.z[j * t.nx + i] = 250.0f;
    }
  }
  p.max_distance = 600.0;
  for (mode = 0; mode < SEARCH_MODES; ++mode) {
    results r;
    size_t wrong = 0, wrong_h = 0;
    set_mode(&p, mode, 20);
    r = compute(&t, &p);
    for (j = 0; j < t.ny; ++j) {
      for (i = 0; i < t.nx; ++i) {
        const int d = (int)(j * t.nx + i);
        int k;
        wrong += r.edge[d] != (cells_from_edge(&t, i, j) * 30 < 600);
        /* north, east, south, west: a ray leaving the grid at once sees nothing (-pi/2); any
         * other stays on the grid, if only along its boundary row or column, and sees the
         * horizontal */
        for (k = 0; k < 4; ++k) {
          const int leaves =
            k == 0 ? j == t.ny - 1 : k == 1 ? i == t.nx - 1 : k == 2 ? j == 0 : i == 0;
          wrong_h += fabs(r.h[(size_t)d * 4 + (size_t)k] - (leaves ? -PI / 2 : 0.0)) > 1e-6;
        }
      }
    }
    fprintf(stderr, "edge flags, %s: %zu wrong flags, %zu wrong horizons\n", mode_name[mode],
            wrong, wrong_h);
    AP_CHECK_EQ_INT((int)wrong, 0);
    AP_CHECK_EQ_INT((int)wrong_h, 0);
    release(&r);
  }
  drop(&t);
}

/* The edge flag in oblique sectors, closed form on a flat grid of 30 x 20 m cells: a cell is
 * flagged when, in some sector, its own ray leaves the grid (the rectangle of the cell centres)
 * closer than the search limit: the distance L (no curvature; marched, far-marched or swept),
 * or without one (swept), with curvature c, sqrt((zmax - z) / c) (one cell raised: 6 mm, 300 m for
 * the others; by 15 micrometres, 15 m, less than a cell; 0 for it). The sweep took a cell's
 * reach from the nearer of the two lines bracketing it, which beside a side of the DEM can
 * leave the grid at once: the second ring of cells was flagged where the limit was less than a
 * cell, 164 of these 1,920 (a probe of 2026-12-07 found it on a UTM DEM's 100 m cells). */
static void test_edge_flags_oblique(void)
{
  terrain t = make(48, 40, 30.0);
  int scenario;
  t.dy0 = 20.0;
  for (scenario = 0; scenario < 3; ++scenario) {
    const int limited = scenario == 0;
    ap_horizon_params p = params(16, !limited);
    const size_t top = 7 * t.nx + 30; /* (the raised cell) */
    double c = 0.0, closest = INFINITY; /* (how near an exit comes to the limit: no ties) */
    int mode;
    size_t i, j;
    for (j = 0; j < t.ny * t.nx; ++j) {
      t.z[j] = 0.0f;
    }
    if (limited) {
      p.max_distance = 437.0;
    } else {
      t.z[top] = scenario == 1 ? 0.006f : 1.5e-5f;
      c = (1.0 - p.refraction) / (2.0 * p.radius_meridian); /* (M = N: every azimuth's) */
    }
    for (mode = 0; mode < SEARCH_MODES; ++mode) {
      results r;
      size_t wrong = 0;
      set_mode(&p, mode, 32);
      r = compute(&t, &p);
      for (j = 0; j < t.ny; ++j) {
        for (i = 0; i < t.nx; ++i) {
          const double rise = (double)t.z[top] - (double)t.z[j * t.nx + i];
          int d, flagged = 0;
          for (d = 0; d < p.directions; ++d) {
            /* (grid azimuth from +y, clockwise: the ray's steps east and north per metre) */
            const double phi = 2.0 * PI * d / p.directions;
            const double ex = fabs(sin(phi)) < 1e-12 ? 0.0 : sin(phi);
            const double ey = fabs(cos(phi)) < 1e-12 ? 0.0 : cos(phi);
            double exit = INFINITY;
            if (ex != 0.0) {
              exit = fmin(exit, (ex > 0 ? (double)(t.nx - 1 - i) : (double)i) * t.dx0 / fabs(ex));
            }
            if (ey != 0.0) {
              exit = fmin(exit, (ey > 0 ? (double)(t.ny - 1 - j) : (double)j) * t.dy0 / fabs(ey));
            }
            if (limited) {
              flagged |= exit < p.max_distance;
              closest = fmin(closest, fabs(exit - p.max_distance));
            } else if (rise > 0.0) {
              flagged |= exit * exit * c < rise;
              closest = fmin(closest, fabs(exit - sqrt(rise / c)));
            }
          }
          wrong += r.edge[j * t.nx + i] != flagged;
        }
      }
      fprintf(stderr, "oblique edge flags, %s, %s: %zu wrong flags\n",
              limited ? "437 m" : scenario == 1 ? "curvature, 300 m" : "curvature, 15 m",
              mode_name[mode], wrong);
      AP_CHECK_EQ_INT((int)wrong, 0);
      release(&r);
    }
    AP_CHECK(closest > 1e-3);
  }
  drop(&t);
}

/* Extreme terrain keeps every product in its documented range: cells of +-3e37 m at random
 * (walls at the float range's end) gave 134 cells a DiffuseSkyFactor near -1e-26 before it was
 * clamped, and the top of a single 1e30 m spike, whose every horizon is -pi/2 in single
 * precision, a PositiveOpenness of pi + 5e-7 (180.00003 degrees) from the sum's rounding. */
static void test_extreme_ranges(void)
{
  terrain t = make(30, 30, 30.0);
  ap_horizon_params p = params(32, 1);
  int pass;
  /* without a distance (swept), then 600 m (20 columns) in every mode */
  for (pass = 0; pass < 2 * (1 + SEARCH_MODES); ++pass) {
    results r;
    size_t k, bad = 0;
    p.max_distance = pass < 2 ? INFINITY : 600.0;
    set_mode(&p, pass < 2 ? SWEPT : pass / 2 - 1, 64);
    for (k = 0; k < t.nx * t.ny; ++k) {
      unsigned h = (unsigned)k * 2654435761u;
      h ^= h >> 15;
      t.z[k] = pass % 2 == 0 ? ((h & 4u) ? 3e37f : -3e37f) : (k == 15 * t.nx + 15 ? 1e30f : 0.0f);
    }
    r = compute(&t, &p);
    for (k = 0; k < t.nx * t.ny; ++k) {
      bad += !(r.vd[k] >= 0.0f && r.vd[k] <= 1.0f) || !(r.svf[k] >= 0.0f && r.svf[k] <= 1.0f) ||
             !(r.A[k] >= 0.0f && r.A[k] <= (float)(2 * PI)) ||
             !(r.rp[k] >= 0.0f && r.rp[k] <= (float)(PI / 2)) ||
             !(r.open[k] >= 0.0f && r.open[k] <= (float)PI);
    }
    if (pass % 2 == 1) {
      AP_CHECK_NEAR(r.open[15 * t.nx + 15], PI, 1e-6);
      AP_CHECK_NEAR(r.svf[15 * t.nx + 15], 1.0, 1e-6);
    }
    AP_CHECK_EQ_INT((int)bad, 0);
    release(&r);
  }
  drop(&t);
}

/* Nodata never occludes: a NaN wall between the observer and a peak leaves the peak visible. */
static void test_nodata_transparent(void)
{
  terrain t = make(50, 5, 10.0);
  ap_horizon_params p = params(4, 0);
  results r;
  size_t j;
  int mode;
  for (j = 0; j < t.ny; ++j) {
    t.z[j * t.nx + 10] = NAN;
    t.z[j * t.nx + 11] = NAN;
  }
  t.z[2 * t.nx + 40] = 300.0f;
  r = compute(&t, &p);
  AP_CHECK_NEAR(r.h[(2 * t.nx + 0) * 4 + 1], atan(300.0 / 400.0), 1e-6);
  AP_CHECK(isnan(r.svf[2 * t.nx + 10]));
  release(&r);
  /* the same with a search distance (45 and 35 columns) in every mode: the peak 400 m away is
   * seen past the nodata, and not beyond the search distance */
  for (mode = 0; mode < SEARCH_MODES; ++mode) {
    set_mode(&p, mode, 64);
    p.max_distance = 450.0;
    r = compute(&t, &p);
    AP_CHECK_NEAR(r.h[(2 * t.nx + 0) * 4 + 1], atan(300.0 / 400.0), 1e-6);
    AP_CHECK(isnan(r.svf[2 * t.nx + 10]));
    release(&r);
    p.max_distance = 350.0;
    r = compute(&t, &p);
    AP_CHECK_NEAR(r.h[(2 * t.nx + 0) * 4 + 1], 0.0, 1e-6);
    release(&r);
  }
  drop(&t);
}

/* Each view column's search runs over its cells with data only (hz->data_span). Flat ground
 * of 10 m cells, nodata before and after a span of each row (transposed: of each column) that
 * starts and ends at varying cells, and a 100 m wall across every row at column 30: the first
 * and the last cell with data of every row see the wall at the closed-form angle
 * atan(100 / x), x their distance to it, in every search mode (a span one cell short at either
 * end would leave that cell with no horizon at all: -90 degrees). */
static void test_nodata_spans(void)
{
  int transposed, mode;
  for (transposed = 0; transposed < 2; ++transposed) {
    const size_t N = 60, M = 40;
    terrain t = transposed ? make(M, N, 10.0) : make(N, M, 10.0);
    ap_horizon_params p = params(4, 0);
    size_t i, j;
    /* (along a row: i across, j the row; transposed the same along a column) */
#define AT(i, j) t.z[transposed ? (i) * t.nx + (j) : (j) * t.nx + (i)]
    for (j = 0; j < M; ++j) {
      for (i = 0; i < N; ++i) {
        const size_t first = 5 + j % 7, last = 50 - j % 5;
        AT(i, j) = i < first || i > last ? NAN : (i == 30 ? 100.0f : 0.0f);
      }
    }
    for (mode = 0; mode < SEARCH_MODES; ++mode) {
      results r;
      double worst = 0.0;
      set_mode(&p, mode, 64);
      p.max_distance = 450.0;
      r = compute(&t, &p);
      for (j = 0; j < M; ++j) {
        const size_t first = 5 + j % 7, last = 50 - j % 5;
        /* sectors 1 (east) and 3 (west); transposed 0 (north) and 2 (south) */
        const size_t k0 = transposed ? first * t.nx + j : j * t.nx + first;
        const size_t k1 = transposed ? last * t.nx + j : j * t.nx + last;
        const double h0 = r.h[k0 * 4 + (transposed ? 0 : 1)];
        const double h1 = r.h[k1 * 4 + (transposed ? 2 : 3)];
        worst = fmax(worst, fabs(h0 - atan(100.0 / (10.0 * (double)(30 - first)))));
        worst = fmax(worst, fabs(h1 - atan(100.0 / (10.0 * (double)(last - 30)))));
      }
      fprintf(stderr, "nodata spans%s, %s: largest difference %.3g deg\n",
              transposed ? ", transposed" : "", mode_name[mode], worst / DEG);
      AP_CHECK(worst <= 1e-5);
      release(&r);
    }
#undef AT
    drop(&t);
  }
}

/* The coast of test_nodata_coast: the rough terrain, 90 x 70, a sea of nodata along the west
 * and north edges with a wavy shore, a nodata row (23) and column (61); with thin, a pier
 * along row 40 and a causeway along column 45 out into the sea, 150 m high; with latlon, on
 * lat/lon rows at 50 N. */
static terrain coast_terrain(int thin, int latlon)
{
  terrain t = rough_terrain(90, 70);
  size_t i, j;
  for (j = 0; j < t.ny; ++j) {
    for (i = 0; i < t.nx; ++i) {
      const int sea = (double)i < 20.0 + 8.0 * sin((double)j / 7.0) ||
                      (double)j > 58.0 - 5.0 * sin((double)i / 9.0);
      const int pier = thin && ((j == 40 && i >= 6) || (i == 45 && j >= 50));
      if ((sea && !pier) || i == 61 || j == 23) {
        t.z[j * t.nx + i] = NAN;
      } else if (sea) {
        t.z[j * t.nx + i] += 150.0f;
      }
    }
  }
  if (latlon) {
    latlon_rows(&t, 6371000.0, 50.0 * DEG, 0.0003 * DEG, 0.0004 * DEG);
  }
  return t;
}

/* A coast: a sea of nodata along the west and north edges with a wavy shore, a nodata row and
 * a nodata column across the land, on the rough terrain; with (thin) and without a
 * one-cell-wide pier out into the sea along a row and a causeway along a column, standing
 * 150 m high. Every land cell at least 6 cells from the DEM's edges, in 16 sectors (on the
 * grid's axes and diagonals, and turned 0.05 rad off them), against the brute force, which
 * reads nodata's terrain as the kernel does: bilinear patches whose four corners have data,
 * and the grid lines between two cells with data (a point within 1e-9 of a grid line reads no
 * corner beyond it). Searched exactly (marched) the kernel must find the same, thin features
 * and all: a ray along a row or column beside nodata runs on patches with a nodata corner
 * only (measured before the near field took their exit edges: MAE 0.70 deg, p99 4.3, max 139
 * on the axes, 108 turned). The far field samples the rays where they cross the view's
 * columns; where one of a column sample's two cells is nodata, the far march also takes the
 * points where the ray crosses a view row next to it (far_shore_column), up to the search
 * distance (the last, partial step): so it must keep the issue's bounds here too (measured:
 * MAE 0.0025-0.0039 deg, p99 0.08-0.10, max 0.36-0.51 on the shore; without the crossings MAE
 * 0.013-0.021, p99 0.20-0.57, max 14-20; without the last step max 3.1-4.8). With the pier
 * and the causeway, whose 150 m cells make the bilinear patches beside them peak between two
 * columns, the far field's column samples miss up to 7 deg there, as they would without
 * nodata (before the crossings: about 100 deg, the strips lost). The sweep's hulls hold the
 * column samples alone; it marches the rays whose tangents fell on nodata, and
 * ap_horizon_accumulate adds the same crossings beside nodata (shore_sweep_rows) to its
 * horizons (measured: MAE 0.0034-0.0049, p99 0.10-0.14, max 0.75-0.97, the same with the
 * pier and the causeway but on lat/lon rows on the axes, where the far march too misses 7.2
 * deg of the pier's patches; without the crossings MAE 0.025-0.035, p99 0.44-0.91, max 14-26;
 * before the marches, MAE 0.26-0.28 on the axes and lost horizons). The diagonals' lines and
 * rays run through cells up to rounding, so a nodata neighbour of a weight of 1e-13 voided
 * them (interp_snap: up to 11 deg, 36 along the pier), a line's samples lost beside nodata
 * leave a ray between it and the next line without a bracket (ghost_push: up to 7 deg, 3.7
 * past the pier), and on lat/lon rows the lines along the rows lay between rows, both void
 * beside the pier (row_lines: 20 deg). Each also on lat/lon rows (about 29 x 33 m
 * at 50 N), whose x-major sectors run the near field and the far march row by row (near_row,
 * far_march_row) and sweep along bending lines. */
static void test_nodata_coast(void)
{
  int variant, k, mode, d;
  for (variant = 0; variant < 4; ++variant) {
    /* 0: the shore, 1: the same on lat/lon rows, 2 and 3: with the pier and the causeway */
    const int thin = variant >= 2, latlon = variant % 2;
    terrain t = coast_terrain(thin, latlon);
    ap_horizon_params p = params(16, 1);
    const double c = (1 - p.refraction) / (2 * 6371000.0);
    size_t i, j, n, land = 0;
    double *err = (double *)malloc(t.nx * t.ny * 16 * sizeof(double));
    p.radius_meridian = p.radius_normal = 6371000.0;
    p.max_distance = 900.0;
    for (k = 0; k < 2; ++k) {
      p.azimuth_offset = k ? 0.05 : 0.0;
      for (mode = 0; mode < SEARCH_MODES; ++mode) {
        results r;
        double sum = 0.0, mae, p99, worst;
        set_mode(&p, mode, 64);
        r = compute(&t, &p);
        n = land = 0;
        for (j = 6; j + 6 < t.ny; j += reference_stride()) {
          for (i = 6; i + 6 < t.nx; i += reference_stride()) {
            if (isnan(t.z[j * t.nx + i])) {
              AP_CHECK(isnan(r.svf[j * t.nx + i]));
              continue;
            }
            ++land;
            for (d = 0; d < 16; ++d) {
              const double ref =
                brute_force(&t, i, j, 2 * PI * d / 16 - p.azimuth_offset, c, p.max_distance);
              const double got = r.h[(j * t.nx + i) * 16 + (size_t)d];
              err[n] = fabs(got - ref) / DEG;
              sum += err[n++];
            }
          }
        }
        qsort(err, n, sizeof(double), cmp_double);
        mae = sum / (double)n;
        p99 = err[(size_t)(0.99 * (double)(n - 1))];
        worst = err[n - 1];
        fprintf(stderr,
                "nodata coast%s%s, %s, azimuths %s: %zu land cells, MAE %.4f deg, "
                "p99 %.4f deg, max %.3f deg\n",
                thin ? " with a pier and a causeway" : "", latlon ? ", lat/lon" : "",
                mode_name[mode], k ? "turned" : "on the axes", land, mae, p99, worst);
        if (mode == MARCHED) {
          /* (the largest: the reference's steps, on a 150 m pier's flank) */
          AP_CHECK(mae <= 0.001 && p99 <= 0.005 && worst <= 0.1);
        } else if (mode == FAR_MARCHED) {
          AP_CHECK(mae <= 0.05 && p99 <= 0.5 && worst <= (thin && latlon ? 10.0 : 1.0));
        } else {
          /* (the sweep lost whole horizons along the shore, up to 74 deg, 37 on lat/lon rows,
           * before it marched the rays of cells whose hulls' tangents fell on nodata; then up
           * to 12 deg, 36 with the pier, before interp_snap, the ghosts and the row lines of
           * lat/lon grids' axes) */
          AP_CHECK(mae <= 0.05 && p99 <= 0.5 && worst <= (thin && latlon ? 10.0 : 1.5));
        }
        release(&r);
      }
    }
    AP_CHECK(land * reference_stride() * reference_stride() > 2000);
    free(err);
    drop(&t);
  }
}

/* The searches skip what cannot rise above a slope found, bounded by the DEM's highest cell:
 * the sweep's marches beside nodata (march_done) and near the sides. A cell 5 km high on the
 * west edge, in the coast's sea, lies behind every eastward ray of the other columns, so it
 * must change none of their horizons, bit for bit, while it makes every such bound useless.
 * The coast with the pier and a nodata row every 9 rows and column every 13, 16 sectors, the
 * east-facing ones compared, far-marched and swept, at 900 m and unlimited, projected and on
 * lat/lon rows. (Mutations of march_done that test_nodata_coast's statistics do not see fail
 * here: a top 40 m too low, or a bound 1.5 times the slope found.) */
static void test_top_bounds_exact(void)
{
  int latlon, mode, lim, d;
  for (latlon = 0; latlon < 2; ++latlon) {
    terrain t = coast_terrain(1, latlon);
    terrain u = coast_terrain(1, latlon);
    ap_horizon_params p = params(16, 1);
    size_t x, y;
    for (y = 0; y < t.ny; ++y) {
      for (x = 0; x < t.nx; ++x) {
        if (y % 9 == 4 || x % 13 == 6) { /* (more rays for the sweep to march) */
          t.z[y * t.nx + x] = u.z[y * t.nx + x] = NAN;
        }
      }
    }
    u.z[35 * u.nx + 0] = 5000.0f;
    p.radius_meridian = p.radius_normal = 6371000.0;
    for (lim = 0; lim < 2; ++lim) {
      p.max_distance = lim ? 900.0 : INFINITY;
      for (mode = FAR_MARCHED; mode < SEARCH_MODES; ++mode) { /* (marched: no such bound) */
        results a, b;
        size_t i, j, differ = 0, compared = 0;
        set_mode(&p, mode, 64);
        a = compute(&t, &p);
        b = compute(&u, &p);
        for (j = 0; j < t.ny; ++j) {
          for (i = 1; i < t.nx; ++i) {
            for (d = 1; d < 8; ++d) { /* (azimuths 22.5 to 157.5 deg) */
              const size_t k = (j * t.nx + i) * 16 + (size_t)d;
              compared += !isnan(a.h[k]);
              differ += memcmp(&a.h[k], &b.h[k], sizeof(float)) != 0;
            }
          }
        }
        fprintf(stderr, "top bounds%s, %s, %s: %zu of %zu horizons differ\n",
                latlon ? ", lat/lon" : "", mode_name[mode], lim ? "900 m" : "unlimited", differ,
                compared);
        AP_CHECK(compared > 15000);
        AP_CHECK_EQ_INT((int)differ, 0);
        release(&a);
        release(&b);
      }
    }
    drop(&t);
    drop(&u);
  }
}

/* An integer option accepts exactly [lo, hi] (then restored). */
static void check_int_option(const ap_horizon_grid *g, ap_horizon_params *p, int *option, int lo,
                             int hi)
{
  const int keep = *option;
  *option = lo - 1;
  AP_CHECK_EQ_INT(ap_horizon_validate(g, p), AP_ERR_INVALID_ARGUMENT);
  *option = hi + 1;
  AP_CHECK_EQ_INT(ap_horizon_validate(g, p), AP_ERR_INVALID_ARGUMENT);
  *option = lo;
  AP_CHECK_EQ_INT(ap_horizon_validate(g, p), AP_OK);
  *option = hi;
  AP_CHECK_EQ_INT(ap_horizon_validate(g, p), AP_OK);
  *option = keep;
}

static void test_errors(void)
{
  terrain t = make(10, 10, 30.0);
  ap_horizon_grid g = grid_of(&t);
  ap_horizon_params p = params(32, 1);
  ap_sky_products o;
  ap_horizon *hz = (ap_horizon *)&t; /* must be reset to NULL on failure */
  memset(&o, 0, sizeof(o));
  AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_OK);
  check_int_option(&g, &p, &p.directions, 4, 360);
  p.max_distance = -5;
  AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
  p.max_distance = NAN;
  AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
  p.max_distance = INFINITY;
  p.refraction = 1.0;
  AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
  p.refraction = -0.1;
  AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
  p.refraction = 0.13;
  check_int_option(&g, &p, &p.near_field, 0, 64);
  check_int_option(&g, &p, &p.march_columns, 0, 64);
  check_int_option(&g, &p, &p.far_march_columns, 0, 65536);
  p.origin_col = -1000000001L;
  AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
  p.origin_col = 0;
  p.origin_row = 1000000001L;
  AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
  p.origin_row = LONG_MIN; /* (labs(LONG_MIN) overflowed, and passed) */
  AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
  p.origin_row = 0;
  p.origin_col = LONG_MIN;
  AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
  p.origin_col = 0;
  {
    /* sides beyond AP_HORIZON_MAX_ORIGIN + 1 cells (the sweep counts columns in int) and more
     * than SIZE_MAX / 32 cells are refused before any elevation is read (the views below
     * claim far more storage than the terrain's: none of it is touched) */
    ap_horizon_grid big = g;
    big.z.nx = (size_t)AP_HORIZON_MAX_ORIGIN + 2;
    big.z.ny = 2;
    big.z.row_stride = (ptrdiff_t)big.z.nx;
    big.dx = big.dy = NULL;
    AP_CHECK_EQ_INT(ap_horizon_validate(&big, &p), AP_ERR_SIZE_OVERFLOW);
    big.z.nx = 2;
    big.z.ny = (size_t)AP_HORIZON_MAX_ORIGIN + 2;
    big.z.row_stride = 2;
    AP_CHECK_EQ_INT(ap_horizon_validate(&big, &p), AP_ERR_SIZE_OVERFLOW);
    big.z.nx = big.z.ny = 800000000; /* sides within the limit, 6.4e17 > SIZE_MAX / 32 cells */
    big.z.row_stride = (ptrdiff_t)big.z.nx;
    AP_CHECK_EQ_INT(ap_horizon_validate(&big, &p), AP_ERR_SIZE_OVERFLOW);
  }
  ap_horizon_finish(NULL, 0, 10); /* (does nothing) */
  {
    /* the region: inside the 10 x 10 grid, both sizes or neither */
    static const size_t bad[][4] = { { 0, 0, 0, 5 }, { 0, 0, 5, 0 }, { 3, 0, 0, 0 },
                                     { 6, 0, 5, 5 }, { 0, 10, 1, 1 }, { 0, 0, 11, 1 },
                                     { 1, 1, (size_t)-1, 2 } };
    size_t k;
    for (k = 0; k < sizeof(bad) / sizeof(bad[0]); ++k) {
      p.region_i0 = bad[k][0];
      p.region_j0 = bad[k][1];
      p.region_nx = bad[k][2];
      p.region_ny = bad[k][3];
      AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
    }
    p.region_i0 = 5;
    p.region_j0 = 9;
    p.region_nx = 5;
    p.region_ny = 1;
    AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_OK);
    p.region_i0 = p.region_j0 = p.region_nx = p.region_ny = 0;
  }
  {
    /* the larger DEM's rows (per-row sizes): both tables, enough rows below and above the
     * piece, sizes positive and finite; ignored with constant sizes */
    double wdx[14], wdy[14], rdx[10];
    size_t k;
    for (k = 0; k < 14; ++k) {
      wdx[k] = 20.0 + (double)k;
      wdy[k] = 30.0;
    }
    p.whole_dx = wdx;
    p.whole_dy = NULL;
    AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
    p.whole_dy = wdy;
    p.whole_rows = 14;
    p.origin_row = 5; /* rows 5..14: one more than the 14 */
    AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_OK); /* (constant sizes: not read) */
    memcpy(rdx, wdx + 4, sizeof(rdx));
    g.dx = rdx;
    AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
    p.origin_row = -1;
    AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
    p.origin_row = 4;
    AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_OK);
    p.origin_row = 3; /* rows 3..12: not the grid's */
    AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
    p.origin_row = 4;
    p.whole_rows = 9; /* fewer than the grid's */
    AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
    p.whole_rows = 14;
    wdy[13] = NAN;
    AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
    g.dx = NULL;
    p.whole_dx = p.whole_dy = NULL;
    p.whole_rows = 0;
    p.origin_row = 0;
  }
  {
    /* the scale lattice: 2..1025 nodes a side, spans positive and finite, each node a
     * positive definite metric; not with per-row sizes */
    double m[3 * 6] = { 900, 0, 900, 900, 10, 900, 900, 0, 900, 900, 0, 900, 900, 0, 900,
                        900, -899, 900 };
    double rdx[10];
    size_t k;
    p.scale_metric = m;
    p.scale_cols = 3;
    p.scale_rows = 2;
    p.scale_span_cols = p.scale_span_rows = 9.0;
    AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_OK);
    for (k = 0; k < 10; ++k) {
      rdx[k] = 30.0;
    }
    g.dx = rdx;
    AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
    g.dx = NULL;
    p.scale_cols = 1;
    p.scale_rows = 6;
    AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
    p.scale_cols = 3;
    p.scale_rows = 2;
    p.scale_span_rows = 0.0;
    AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
    p.scale_span_rows = INFINITY;
    AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
    p.scale_span_rows = 9.0;
    m[16] = -900.0; /* (E.N)^2 = |E|^2 |N|^2: the steps parallel */
    AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
    m[16] = -899.0;
    m[0] = NAN;
    AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
    m[0] = 0.0;
    AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
    m[0] = 900.0;
    AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_OK);
    p.scale_metric = NULL;
    p.scale_cols = p.scale_rows = 0;
  }
  g.dx0 = 0.0;
  AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_INVALID_ARGUMENT);
  g.dx0 = 30.0;
  t.z[37] = INFINITY; /* an infinity is not an elevation (NaN is nodata) */
  AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_OUT_OF_RANGE);
  t.z[37] = -INFINITY;
  AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_OUT_OF_RANGE);
  t.z[37] = NAN;
  AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_OK);
  {
    size_t k;
    for (k = 0; k < 100; ++k) t.z[k] = NAN;
  }
  AP_CHECK_EQ_INT(ap_horizon_create(&g, &p, &o, &hz), AP_ERR_ALL_NODATA);
  AP_CHECK(hz == NULL);
  g.z.nx = 1;
  AP_CHECK_EQ_INT(ap_horizon_validate(&g, &p), AP_ERR_GRID_TOO_SMALL);
  AP_CHECK_EQ_INT(ap_horizon_validate(NULL, &p), AP_ERR_NULL_POINTER);
  drop(&t);
}

/* A piece cut from a larger DEM with a margin of the search distance around a region, told
 * its origin in that DEM (and with per-row sizes that DEM's rows), gets the DEM's results in
 * the region: the near field is each cell's own ray either way, and the sweep's lines lie on
 * the DEM's lattice, so every hull holds the same samples within the distance. Only rounding
 * differs (distances along the lines are measured from the piece's middle). Without the
 * origin the lines fall elsewhere: that is the difference the test must see shrink. The piece
 * is region (i0, i1, j0, j1) grown by mi columns and mj rows, cut at the DEM's edges; returns
 * the largest difference of A, SVF and the horizons there. */
static double piece_difference(const terrain *whole, const results *w, const ap_horizon_params *p,
                               const size_t region[4], size_t mi, size_t mj, int with_origin)
{
  const size_t i0 = region[0] > mi ? region[0] - mi : 0, j0 = region[2] > mj ? region[2] - mj : 0;
  const size_t i1 = region[1] + mi < whole->nx ? region[1] + mi : whole->nx - 1;
  const size_t j1 = region[3] + mj < whole->ny ? region[3] + mj : whole->ny - 1;
  const size_t nx = i1 - i0 + 1, ny = j1 - j0 + 1;
  terrain t = make(nx, ny, whole->dx0);
  ap_horizon_params q = *p;
  t.dy0 = whole->dy0;
  results r;
  size_t i, j;
  int d;
  double worst = 0.0;
  for (j = 0; j < ny; ++j) {
    memcpy(t.z + j * nx, whole->z + (j + j0) * whole->nx + i0, nx * sizeof(float));
  }
  if (whole->dx) {
    t.dx = (double *)malloc(ny * sizeof(double));
    t.dy = (double *)malloc(ny * sizeof(double));
    memcpy(t.dx, whole->dx + j0, ny * sizeof(double));
    memcpy(t.dy, whole->dy + j0, ny * sizeof(double));
  }
  q.origin_col = with_origin ? (long)i0 : 0;
  q.origin_row = with_origin ? (long)j0 : 0;
  if (whole->dx && with_origin) {
    /* per-row sizes: the lattice comes from the larger DEM's rows */
    q.whole_dx = whole->dx;
    q.whole_dy = whole->dy;
    q.whole_rows = whole->ny;
  }
  r = compute(&t, &q);
  for (j = region[2]; j <= region[3]; ++j) {
    for (i = region[0]; i <= region[1]; ++i) {
      const size_t a = j * whole->nx + i, b = (j - j0) * nx + (i - i0);
      AP_CHECK_EQ_INT(r.edge[b], w->edge[a]);
      worst = fmax(worst, fabs((double)r.svf[b] - (double)w->svf[a]));
      worst = fmax(worst, fabs((double)r.A[b] - (double)w->A[a]));
      for (d = 0; d < p->directions; ++d) {
        worst = fmax(worst, fabs((double)r.h[b * (size_t)p->directions + (size_t)d] -
                                 (double)w->h[a * (size_t)p->directions + (size_t)d]));
      }
    }
  }
  release(&r);
  drop(&t);
  return worst;
}

/* Rough terrain, swept and far-marched (2500 m: 83 columns), curvature on; then per-row sizes,
 * marched and swept. */
static void test_pieces(void)
{
  terrain t = make(250, 230, 30.0);
  ap_horizon_params p = params(32, 1);
  const size_t region[4] = { 110, 129, 100, 119 }; /* i0, i1, j0, j1 */
  const size_t margin = 2500 / 30 + 3;
  size_t i, j, k;
  for (j = 0; j < t.ny; ++j) {
    for (i = 0; i < t.nx; ++i) {
      t.z[j * t.nx + i] = (float)rough((double)i * 30.0, (double)j * 30.0);
    }
  }
  p.max_distance = 2500.0;
  for (k = 0; k < 4; ++k) {
    /* swept: the lines lie on the whole DEM's lattice only where the piece says where it
     * starts; far-marched: every ray is the cell's own, wherever the piece starts */
    const int mode = k < 2 ? SWEPT : FAR_MARCHED;
    results w;
    double aligned, unaligned;
    p.directions = k % 2 == 0 ? 32 : 29;
    set_mode(&p, mode, 64);
    w = compute(&t, &p);
    aligned = piece_difference(&t, &w, &p, region, margin, margin, 1);
    unaligned = piece_difference(&t, &w, &p, region, margin, margin, 0);
    printf("piece of a %zu x %zu DEM, %s, D = %d: largest difference %.3g aligned, %.3g not\n",
           t.nx, t.ny, mode_name[mode], p.directions, aligned, unaligned);
    if (mode == SWEPT) {
      AP_CHECK(aligned <= 1e-5);
      AP_CHECK(unaligned > 1e-3);
    } else {
      AP_CHECK(aligned == 0.0);
      AP_CHECK(unaligned == 0.0);
    }
    release(&w);
  }
  drop(&t);
  /* Per-row cell sizes (0.002 x 0.003 degree rows from 50 N), 5 km (marched, 23 to 26
   * columns): each row's ray pattern depends on its own sizes only, so the piece's rays are
   * the whole DEM's. */
  {
    terrain u = make(200, 180, 0.0);
    const double R = 6371000.0, dlat = 0.002 * DEG, dlon = 0.003 * DEG;
    const size_t piece[4] = { 80, 99, 70, 89 };
    size_t mi, mj;
    results w;
    double aligned;
    latlon_rows(&u, R, 50 * DEG, dlat, dlon);
    for (j = 0; j < u.ny; ++j) {
      for (i = 0; i < u.nx; ++i) {
        u.z[j * u.nx + i] = (float)rough((double)i * 214.0, (double)j * 222.0);
      }
    }
    p = params(32, 1);
    p.max_distance = 5000.0;
    w = compute(&u, &p);
    mi = (size_t)ceil(5000.0 / u.dx[u.ny - 1]) + 3;
    mj = (size_t)ceil(5000.0 / u.dy[0]) + 3;
    aligned = piece_difference(&u, &w, &p, piece, mi, mj, 1);
    printf("piece of a %zu x %zu lat/lon-like DEM, marched: largest difference %.3g\n", u.nx,
           u.ny, aligned);
    AP_CHECK(aligned == 0.0);
    release(&w);
    /* Swept (march_columns and far_march_columns 0), with curvature: the bending lines lie on
     * the whole DEM's lattice of rhumb lines when the piece has the DEM's rows; without them
     * the piece is a DEM of its own, its lines elsewhere. In D = 29 no sector is row- or
     * column-aligned. Far-marched (march_columns 0): every ray is the cell's own, its steps
     * taken from the cell's row on, so the piece with the DEM's rows gets the same bits, and
     * without them (Psi counted from its own first row) the same up to rounding. A near field
     * of 8 columns (1.7 km) leaves most of the 5 km to the hulls (the automatic 32 would
     * search it all exactly, the same bits either way). */
    p.near_field = 8;
    for (k = 0; k < 4; ++k) {
      double unaligned;
      p.directions = k % 2 == 0 ? 32 : 29;
      p.march_columns = 0;
      p.far_march_columns = k < 2 ? 0 : 1024;
      w = compute(&u, &p);
      aligned = piece_difference(&u, &w, &p, piece, mi, mj, 1);
      unaligned = piece_difference(&u, &w, &p, piece, mi, mj, 0);
      printf("piece of a %zu x %zu lat/lon-like DEM, %s, D = %d: largest difference %.3g "
             "aligned, %.3g not\n", u.nx, u.ny, k < 2 ? "swept" : "far-marched", p.directions,
             aligned, unaligned);
      AP_CHECK(k < 2 ? aligned <= 1e-5 : aligned == 0.0);
      AP_CHECK(k < 2 ? unaligned > 1e-3 : unaligned <= 1e-5);
      release(&w);
    }
    drop(&u);
  }
}

/* The largest difference between two runs' horizons and products over every cell. */
static double results_difference(const terrain *t, int D, const results *a, const results *b)
{
  const size_t n = t->nx * t->ny;
  double worst = 0.0;
  size_t k;
  for (k = 0; k < n * (size_t)D; ++k) {
    worst = fmax(worst, fabs((double)a->h[k] - (double)b->h[k]));
  }
  for (k = 0; k < n; ++k) {
    const float x[6] = { a->A[k], a->rp[k], a->svf[k], a->vd[k], a->open[k], a->bn[3 * k] };
    const float y[6] = { b->A[k], b->rp[k], b->svf[k], b->vd[k], b->open[k], b->bn[3 * k] };
    int c;
    for (c = 0; c < 6; ++c) {
      worst = fmax(worst, fabs((double)x[c] - (double)y[c]));
    }
    worst = fmax(worst, fabs((double)a->bn[3 * k + 1] - (double)b->bn[3 * k + 1]));
    worst = fmax(worst, fabs((double)a->bn[3 * k + 2] - (double)b->bn[3 * k + 2]));
    AP_CHECK_EQ_INT(a->edge[k], b->edge[k]);
  }
  return worst;
}

/* scale_metric, a projection's scale changing across the DEM. With every node's cell s times
 * as large as dx0 x dy0 (isotropic), a run is the run with cells s dx0 x s dy0, flat Earth and
 * no distance limit (where the search does not depend on the cell size): the same horizons and
 * products up to float rounding, DiffuseSkyFactor's gradient included. With steps a dx0 along
 * the rows and b dy0 along the columns (a != b), likewise in the four sectors along the axes
 * (D = 4), the only directions that are not turned. (The two runs' distances round
 * differently, which moves a horizon by up to 3e-6 rad.) A lattice that changes from node to node
 * (turning directions too) gives a piece of the DEM its cells' values bit for bit: the
 * interpolation uses the larger DEM's indices. */
static void test_scale_metric(void)
{
  terrain t = make(90, 70, 30.0), big = make(90, 70, 30.0);
  ap_horizon_params p = params(16, 0), q;
  const double s = 1.03, a = 1.02, b = 0.97;
  double metric[3 * 5 * 4], worst;
  results r0, r1;
  size_t i, j, k;
  for (j = 0; j < t.ny; ++j) {
    for (i = 0; i < t.nx; ++i) {
      t.z[j * t.nx + i] = big.z[j * t.nx + i] = (float)rough((double)i * 30.0, (double)j * 30.0);
    }
  }
  /* isotropic */
  for (k = 0; k < 4; ++k) {
    metric[3 * k] = metric[3 * k + 2] = 900.0 * s * s;
    metric[3 * k + 1] = 0.0;
  }
  big.dx0 = big.dy0 = 30.0 * s;
  r0 = compute(&big, &p);
  q = p;
  q.scale_metric = metric;
  q.scale_cols = q.scale_rows = 2;
  q.scale_span_cols = (double)t.nx - 1.0;
  q.scale_span_rows = (double)t.ny - 1.0;
  r1 = compute(&t, &q);
  worst = results_difference(&t, p.directions, &r0, &r1);
  printf("scale metric, isotropic %.2f: largest difference %.3g\n", s, worst);
  AP_CHECK(worst < 1e-5); /* (the distances' rounding differs: 3e-6 rad measured) */
  release(&r0);
  release(&r1);
  /* anisotropic, four sectors */
  for (k = 0; k < 4; ++k) {
    metric[3 * k] = 900.0 * a * a;
    metric[3 * k + 2] = 900.0 * b * b;
  }
  big.dx0 = 30.0 * a;
  big.dy0 = 30.0 * b;
  p.directions = q.directions = 4;
  r0 = compute(&big, &p);
  r1 = compute(&t, &q);
  worst = results_difference(&t, p.directions, &r0, &r1);
  printf("scale metric, %.2f x %.2f: largest difference %.3g\n", a, b, worst);
  AP_CHECK(worst < 2e-6);
  release(&r0);
  release(&r1);
  /* and without the lattice, the same terrain differs (the test can fail) */
  r0 = compute(&t, &p);
  r1 = compute(&t, &q);
  AP_CHECK(results_difference(&t, p.directions, &r0, &r1) > 1e-3);
  release(&r0);
  release(&r1);
  /* a changing lattice, 5 x 4 nodes, with shear: pieces, swept and far-marched */
  for (k = 0; k < 20; ++k) {
    const double u = 0.9 + 0.01 * (double)k, v = 1.1 - 0.008 * (double)k;
    metric[3 * k] = 900.0 * u * u;
    metric[3 * k + 1] = 900.0 * 0.02 * (double)(k % 3) * u * v;
    metric[3 * k + 2] = 900.0 * v * v;
  }
  q.scale_cols = 5;
  q.scale_rows = 4;
  q.curvature = 1;
  q.directions = 29;
  for (k = 0; k < 2; ++k) {
    const size_t region[4] = { 40, 55, 30, 41 };
    results w;
    double aligned;
    set_mode(&q, k == 0 ? SWEPT : FAR_MARCHED, 64);
    q.max_distance = 900.0;
    w = compute(&t, &q);
    aligned = piece_difference(&t, &w, &q, region, 900 / 27 + 3, 900 / 27 + 3, 1);
    printf("scale metric, changing, piece %s: largest difference %.3g\n",
           mode_name[k == 0 ? SWEPT : FAR_MARCHED], aligned);
    AP_CHECK(k == 0 ? aligned <= 1e-5 : aligned == 0.0);
    release(&w);
  }
  drop(&t);
  drop(&big);
}

/* Ground elevation of the sheared-lattice test: a valley along a bearing of 35 degrees and a
 * hill beside it (m, ground metres). */
static double sheared_ground(double x, double y)
{
  const double across = x * cos(35.0 * PI / 180.0) - y * sin(35.0 * PI / 180.0);
  const double hx = x - 700.0, hy = y + 400.0;
  return 250.0 * (1.0 - exp(-across * across / (2.0 * 500.0 * 500.0))) +
         180.0 * exp(-(hx * hx + hy * hy) / (2.0 * 400.0 * 400.0));
}

/* A projection that is not conformal shears the grid: the ground vector of a step w (in the
 * metres of dx0, dy0) is Q S w with S the metric's square root, so the sweep's sectors, evenly
 * spaced in grid azimuth, lie unevenly on the ground. The same ground terrain on a sheared
 * lattice and on a square grid, each cell of the first at a node of the second, must give the
 * same products (BentNormal in S's frame, which is the ground's here: Q = I), up to where the
 * two grids' rays cross their columns, between which they interpolate (halving both grids'
 * cells took the first cell's differences down 8-fold; D = 180). Sectors weighted evenly, as
 * before the sweep weighted them by their share of the ground's directions, left each
 * product's worst difference 7 to 16 times these bounds (S's singular values are 1.094 and
 * 0.906: sectors 20% wider or narrower on the ground; SkyViewFactor 0.0062-0.0075 off,
 * BentNormal 0.005-0.011 rad). */
static void test_scale_metric_sheared(void)
{
  const double S[3] = { 1.05, 0.08, 0.95 }, cell = 30.0; /* xx, xy, yy */
  const size_t n = 161, c = 80;
  terrain t = make(n, n, cell), sq = make(n, n, cell);
  ap_horizon_params p = params(180, 0), q;
  double metric[3 * 4], worst[5] = { 0 };
  const size_t cells[3][2] = { { 80, 80 }, { 70, 88 }, { 91, 75 } };
  size_t i, j, k;
  /* the metric of one grid step (m^2): S^2 times the cells' squared sizes */
  for (k = 0; k < 4; ++k) {
    metric[3 * k] = cell * cell * (S[0] * S[0] + S[1] * S[1]);
    metric[3 * k + 1] = cell * cell * (S[0] * S[1] + S[1] * S[2]);
    metric[3 * k + 2] = cell * cell * (S[1] * S[1] + S[2] * S[2]);
  }
  for (j = 0; j < n; ++j) {
    for (i = 0; i < n; ++i) {
      const double wx = cell * ((double)i - (double)c), wy = cell * ((double)j - (double)c);
      t.z[j * n + i] = (float)sheared_ground(S[0] * wx + S[1] * wy, S[1] * wx + S[2] * wy);
    }
  }
  p.max_distance = 2500.0;
  q = p;
  q.scale_metric = metric;
  q.scale_cols = q.scale_rows = 2;
  q.scale_span_cols = q.scale_span_rows = (double)n - 1.0;
  {
    results r = compute(&t, &q);
    for (k = 0; k < 3; ++k) {
      const size_t ci = cells[k][0], cj = cells[k][1], kb = cj * n + ci;
      const double wx = cell * ((double)ci - (double)c), wy = cell * ((double)cj - (double)c);
      const double gx = S[0] * wx + S[1] * wy, gy = S[1] * wx + S[2] * wy;
      results r0;
      double e[5];
      /* the square grid with the cell's ground point at its node (c, c) */
      for (j = 0; j < n; ++j) {
        for (i = 0; i < n; ++i) {
          sq.z[j * n + i] = (float)sheared_ground(gx + cell * ((double)i - (double)c),
                                                  gy + cell * ((double)j - (double)c));
        }
      }
      r0 = compute(&sq, &p);
      e[0] = fabs(r.A[kb] - r0.A[c * n + c]);
      e[1] = fabs(r.svf[kb] - r0.svf[c * n + c]);
      e[2] = fabs(r.vd[kb] - r0.vd[c * n + c]);
      e[3] = fabs(r.open[kb] - r0.open[c * n + c]);
      e[4] = acos(fmin(1.0, r.bn[3 * kb] * r0.bn[3 * (c * n + c)] +
                            r.bn[3 * kb + 1] * r0.bn[3 * (c * n + c) + 1] +
                            r.bn[3 * kb + 2] * r0.bn[3 * (c * n + c) + 2]));
      printf("sheared lattice, cell (%zu, %zu): A %.2g sr, SkyViewFactor %.2g, "
             "DiffuseSkyFactor %.2g, PositiveOpenness %.2g rad, BentNormal %.2g rad "
             "(SkyViewFactor %.4f on the square grid)\n",
             ci, cj, e[0], e[1], e[2], e[3], e[4], r0.svf[c * n + c]);
      for (i = 0; i < 5; ++i) {
        worst[i] = fmax(worst[i], e[i]);
      }
      release(&r0);
    }
    release(&r);
  }
  AP_CHECK(worst[0] < 3e-3 && worst[1] < 5e-4 && worst[2] < 2e-4 && worst[3] < 6e-4 &&
           worst[4] < 1.5e-3);
  /* flat ground: the sectors' weights sum to D, so a full sky and a level horizon */
  memset(t.z, 0, n * n * sizeof(float));
  {
    results r = compute(&t, &q);
    const size_t kc = c * n + c;
    printf("sheared lattice, flat: A - 2 pi %.2g, PositiveOpenness - pi/2 %.2g, BentNormal "
           "(%.2g, %.2g, %.7f)\n", r.A[kc] - 2 * PI, r.open[kc] - PI / 2, r.bn[3 * kc],
           r.bn[3 * kc + 1], r.bn[3 * kc + 2]);
    AP_CHECK(fabs(r.A[kc] - 2 * PI) < 2e-5 && fabs(r.open[kc] - PI / 2) < 2e-6);
    AP_CHECK(fabs(r.bn[3 * kc]) < 1e-6 && fabs(r.bn[3 * kc + 1]) < 1e-6 && r.svf[kc] == 1.0f);
    release(&r);
  }
  drop(&t);
  drop(&sq);
}

/* A uniform number in [0, 1) from a xorshift state (deterministic, the same on every
 * platform). */
static double next_uniform(unsigned long long *state)
{
  *state ^= *state << 13;
  *state ^= *state >> 7;
  *state ^= *state << 17;
  return (double)(*state >> 11) / 9007199254740992.0;
}

/* Cell-directions of t whose far-marched horizon (3000 m, curvature on, D = 29) lies below the
 * samples' reference by more than the float rounding; prints the count checked. */
static size_t far_march_below_mode(const terrain *t, size_t stride, const char *what, int mode)
{
  ap_horizon_params p = params(29, 1);
  const double L = 3000.0, c = (1 - p.refraction) / (2 * 6371000.0);
  const int crossings_only = mode == SWEPT; /* (the hulls' own samples are not these) */
  results r;
  size_t i, j, checked = 0, below = 0;
  double worst = 0.0;
  int d;
  p.max_distance = L;
  set_mode(&p, mode, 64);
  r = compute(t, &p);
  for (j = 0; j < t->ny; j += stride) {
    for (i = 0; i < t->nx; i += stride) {
      const double zq = t->z[j * t->nx + i];
      if (isnan(zq)) {
        continue;
      }
      for (d = 0; d < p.directions; ++d) {
        const double phi = 2 * PI * d / p.directions, sx = sin(phi), cy = cos(phi);
        const int xmajor = fabs(sx) >= fabs(cy); /* (square cells) */
        const double m = xmajor ? cy / fabs(sx) : sx / fabs(cy);
        const double len = 30.0 / (xmajor ? fabs(sx) : fabs(cy));
        const long si = sx > 0 ? 1 : -1, sj = cy > 0 ? 1 : -1;
        double best = -INFINITY, got, qp = -1.0;
        int void_p = 0;
        long step;
        for (step = p.near_field ? p.near_field : AP_HORIZON_NEAR_FIELD_MARCHED;; ++step) {
          /* the point at distance t = step len, or at L on the last partial step (whose
           * stretch's crossings below take the void flag of the full step's column sample) */
          const double tt = fmin((double)step * len, L), q = tt / len;
          const double qv = (double)step, lv = m * qv; /* (the full step's column sample) */
          const double xv = xmajor ? (double)i + (double)si * qv : (double)i + lv;
          const double yv = xmajor ? (double)j + lv : (double)j + (double)sj * qv;
          const int on = xv > -1e-9 && yv > -1e-9 && xv < (double)(t->nx - 1) + 1e-9 &&
                         yv < (double)(t->ny - 1) + 1e-9;
          const int void_q = on && isnan(height_at(t, fmin(fmax(xv, 0.0), (double)(t->nx - 1)),
                                                    fmin(fmax(yv, 0.0), (double)(t->ny - 1))));
          const double lat = m * q; /* rows (x-major) or columns moved sideways */
          double x = xmajor ? (double)i + (double)si * q : (double)i + lat;
          double y = xmajor ? (double)j + lat : (double)j + (double)sj * q;
          double z;
          if (x < -1e-9 || y < -1e-9 || x > (double)(t->nx - 1) + 1e-9 ||
              y > (double)(t->ny - 1) + 1e-9) {
            break;
          }
          if (qp >= 0.0 && on && (void_p || void_q)) {
            /* nodata beside: the points where the ray crosses a row (x-major; a column
             * otherwise) since the last sample, on a grid line between two cells */
            const double la = m * qp, lb = m * qv;
            double r;
            for (r = floor(fmin(la, lb)) + 1.0; r < fmax(la, lb); r += 1.0) {
              const double fr = (r - la) / (lb - la), qc = qp + fr * (qv - qp), tc = qc * len;
              const double xc = xmajor ? (double)i + (double)si * qc : (double)i + r;
              const double yc = xmajor ? (double)j + r : (double)j + (double)sj * qc;
              if (tc <= L && xc >= 0.0 && yc >= 0.0 && xc <= (double)(t->nx - 1) &&
                  yc <= (double)(t->ny - 1)) {
                const double zc = height_at(t, xc, yc);
                if (!isnan(zc)) {
                  best = fmax(best, (zc - zq) / tc - c * tc);
                }
              }
            }
          }
          qp = qv;
          void_p = void_q;
          x = fmin(fmax(x, 0.0), (double)(t->nx - 1));
          y = fmin(fmax(y, 0.0), (double)(t->ny - 1));
          z = height_at(t, x, y);
          if (!isnan(z) && !crossings_only) {
            best = fmax(best, (z - zq) / tt - c * tt);
          }
          if (tt >= L) {
            break;
          }
        }
        if (best == -INFINITY) {
          continue;
        }
        got = r.h[(j * t->nx + i) * (size_t)p.directions + (size_t)d];
        ++checked;
        worst = fmax(worst, atan(best) - got);
        below += atan(best) - got > 2e-6;
      }
    }
  }
  fprintf(stderr, "%s against its samples, %s: %zu cell-directions, %zu below, by at "
          "most %.2g rad\n", crossings_only ? "sweep" : "far march", what, checked, below, worst);
  AP_CHECK(checked > (crossings_only ? 1000 : 100000));
  release(&r);
  return below;
}

static size_t far_march_below(const terrain *t, size_t stride, const char *what)
{
  return far_march_below_mode(t, stride, what, FAR_MARCHED);
}

/* The far march skips stretches of a ray whose tile maxima bound them below the slope found so
 * far; a skip must never lose the maximum. Against an independent march of the same samples in
 * double precision (every crossing of a view column from the K-th (the near field's end) within
 * the distance, linear between the column's two cells, and the point at the distance; beside a
 * column sample on nodata also the crossings of view rows next to it, up to the distance): the
 * kernel's horizon is never below it by more than the float rounding (it may lie above: the
 * near field before those samples). 3000 m is 100 columns, so both tests of the skipping (64
 * and 16 steps) run. On rough terrain with 600 single-cell spikes 150-400 m high (so that tile
 * maxima matter) and nodata cells; and on a plain with spikes on the tiles' first and last
 * rows and columns, which every cell's rays pass at every offset, so that a box one row or
 * column short of the samples it bounds would lose some. */
static void test_far_march_skips(void)
{
  terrain t = make(160, 140, 30.0);
  unsigned long long state = 2463534242ULL;
  size_t i, j;
  int k;
  for (j = 0; j < t.ny; ++j) {
    for (i = 0; i < t.nx; ++i) {
      t.z[j * t.nx + i] = (float)rough((double)i * 30.0, (double)j * 30.0);
    }
  }
  for (k = 0; k < 600; ++k) {
    const size_t at = (size_t)(next_uniform(&state) * (double)(t.nx * t.ny));
    t.z[at] += (float)(150.0 + 250.0 * next_uniform(&state));
  }
  for (k = 0; k < 10; ++k) {
    t.z[(size_t)(next_uniform(&state) * (double)(t.nx * t.ny))] = NAN;
  }
  AP_CHECK_EQ_INT((int)far_march_below(&t, 2, "rough with spikes"), 0);
  drop(&t);
  t = make(112, 100, 30.0);
  for (j = 0; j < t.ny; ++j) {
    for (i = 0; i < t.nx; ++i) {
      const int edge_i = i % 16 == 0 || i % 16 == 15, edge_j = j % 16 == 0 || j % 16 == 15;
      t.z[j * t.nx + i] = (edge_i && edge_j && (i / 16 + j / 16) % 3 == 0) ? 60.0f : 0.0f;
    }
  }
  AP_CHECK_EQ_INT((int)far_march_below(&t, 1, "plain with spikes at tile edges"), 0);
  drop(&t);
  /* nodata: a row, a column, a lake and 3% single cells on the rough terrain with spikes, where
   * the crossings beside nodata (far_shore_column) are marched too, and skipped by their own
   * tiles (fm_shore) */
  t = make(160, 140, 30.0);
  for (j = 0; j < t.ny; ++j) {
    for (i = 0; i < t.nx; ++i) {
      const double di = (double)i - 100.0, dj = (double)j - 40.0;
      const int lake = di * di + 2.0 * dj * dj < 300.0;
      t.z[j * t.nx + i] = lake || i == 57 || j == 90 || next_uniform(&state) < 0.03
                            ? NAN
                            : (float)rough((double)i * 30.0, (double)j * 30.0);
    }
  }
  for (k = 0; k < 400; ++k) {
    const size_t at = (size_t)(next_uniform(&state) * (double)(t.nx * t.ny));
    t.z[at] += (float)(150.0 + 250.0 * next_uniform(&state));
  }
  AP_CHECK_EQ_INT((int)far_march_below(&t, 2, "rough with spikes and nodata"), 0);
  /* the sweep (no far march: far_march_columns 0) takes the same crossings beside nodata after
   * its hulls (shore_sweep_rows): never below them alone */
  AP_CHECK_EQ_INT((int)far_march_below_mode(&t, 2, "crossings beside nodata", SWEPT), 0);
  drop(&t);
}

/* Pieces of random DEMs: shapes from 2 cells to 45, lat/lon rows from 89 S to 89 N or constant
 * cell sizes, 4 to 43 sectors, distances of 2 to 20 cells, swept, marched or far-marched,
 * curvature on or off, a nodata cell now and then, regions anywhere (at the DEM's edges too).
 * Each region of a piece grown by the distance must give the whole run's horizons, products and
 * edge flags; only a last-bit rounding may differ (the sweep measures distances along its lines
 * from the piece's edge; a stress run of 5,500 such pieces found two horizons 4e-8 rad apart).
 * Before the lat/lon lines lay on the whole DEM's lattice, or the edge flag with a distance
 * ignored the DEM's highest cell, such pieces differed by up to 1e-2 and in flags. */
/* Whether r (computed for p's region) holds w's values (a whole run) there, bit for bit. */
static int same_in_region(const terrain *t, const results *w, const results *r,
                          const ap_horizon_params *p)
{
  const size_t D = (size_t)p->directions, rnx = p->region_nx;
  size_t i, j, d;
  int same = 1;
  for (j = 0; j < p->region_ny; ++j) {
    for (i = 0; i < rnx; ++i) {
      const size_t a = (j + p->region_j0) * t->nx + (i + p->region_i0), b = j * rnx + i;
#define SAME(x, y) (memcmp(&(x), &(y), sizeof(x)) == 0)
      same = same && SAME(w->A[a], r->A[b]) && SAME(w->rp[a], r->rp[b]) &&
             SAME(w->svf[a], r->svf[b]) && SAME(w->vd[a], r->vd[b]) &&
             SAME(w->open[a], r->open[b]) && w->edge[a] == r->edge[b];
      for (d = 0; d < 3; ++d) {
        same = same && SAME(w->bn[3 * a + d], r->bn[3 * b + d]);
      }
      for (d = 0; d < D; ++d) {
        same = same && SAME(w->h[a * D + d], r->h[b * D + d]);
      }
#undef SAME
    }
  }
  return same;
}

static void test_random_pieces(void)
{
  unsigned long long state = 88172645463325252ULL;
  double worst = 0.0;
  int it, latlon_runs = 0, regions_differ = 0;
  for (it = 0; it < 120; ++it) {
    const size_t nx = 5 + (size_t)(next_uniform(&state) * 40);
    const size_t ny = 5 + (size_t)(next_uniform(&state) * 40);
    const int latlon = next_uniform(&state) < 0.7;
    const double dlat = (0.0003 + 0.01 * next_uniform(&state)) * DEG;
    const double dlon = (0.0003 + 0.01 * next_uniform(&state)) * DEG;
    double lat0 = (-89.0 + 170.0 * next_uniform(&state)) * DEG, shortest;
    terrain t = make(nx, ny, 30.0);
    ap_horizon_params p = params(4 + (int)(next_uniform(&state) * 40), next_uniform(&state) < 0.5);
    size_t region[4], margin, k;
    results w;
    if (latlon) {
      lat0 = fmin(lat0, 89.9 * DEG - dlat * (double)ny);
      latlon_rows(&t, 6371000.0, lat0, dlat, dlon);
      ++latlon_runs;
    }
    shortest = t.dx0;
    for (k = 0; k < ny; ++k) {
      shortest = fmin(shortest, fmin(t.dx ? t.dx[k] : t.dx0, t.dy ? t.dy[k] : t.dy0));
    }
    for (k = 0; k < nx * ny; ++k) {
      t.z[k] = (float)(300.0 * next_uniform(&state));
    }
    if (next_uniform(&state) < 0.3) {
      t.z[(size_t)(next_uniform(&state) * (double)(nx * ny))] = NAN;
    }
    p.max_distance = (2.0 + 18.0 * next_uniform(&state)) * shortest;
    p.march_columns = next_uniform(&state) < 0.5 ? 0 : 64;
    p.far_march_columns = next_uniform(&state) < 0.5 ? 0 : 1024;
    margin = (size_t)ceil(p.max_distance / shortest) + 2;
    region[0] = (size_t)(next_uniform(&state) * (double)nx);
    region[1] = region[0] + (size_t)(next_uniform(&state) * (double)(nx - region[0]));
    region[2] = (size_t)(next_uniform(&state) * (double)ny);
    region[3] = region[2] + (size_t)(next_uniform(&state) * (double)(ny - region[2]));
    w = compute(&t, &p);
    worst = fmax(worst, piece_difference(&t, &w, &p, region, margin, margin, 1));
    {
      /* the same region computed on the whole grid: the whole run's bits */
      ap_horizon_params q = p;
      results r;
      q.region_i0 = region[0];
      q.region_j0 = region[2];
      q.region_nx = region[1] - region[0] + 1;
      q.region_ny = region[3] - region[2] + 1;
      r = compute(&t, &q);
      regions_differ += !same_in_region(&t, &w, &r, &q);
      release(&r);
    }
    release(&w);
    drop(&t);
  }
  printf("120 random pieces (%d lat/lon): largest difference %.3g; as regions, %d differ\n",
         latlon_runs, worst, regions_differ);
  AP_CHECK(worst <= 1e-6);
  AP_CHECK(regions_differ == 0);
}

/* A region of the grid (ap_horizon_params.region_*) gets the whole run's values bit for bit,
 * in every search mode, projected and lat/lon, unlimited or not: regions at the corners and
 * edges (whose rays leave at once or run across the grid), a single row, a single column, a
 * single cell, the interior, and the whole grid named explicitly; nodata inside and outside;
 * also the diffuse sky factor without the bent normal (the kernel's own accumulators). */
static void test_regions(void)
{
  /* i0, j0, nx, ny on a 61 x 47 grid */
  static const size_t regions[][4] = { { 0, 0, 9, 7 },    { 50, 40, 11, 7 }, { 0, 30, 61, 1 },
                                       { 33, 0, 1, 47 },  { 20, 15, 17, 13 }, { 60, 46, 1, 1 },
                                       { 0, 0, 61, 47 },  { 5, 44, 30, 3 } };
  const size_t nreg = sizeof(regions) / sizeof(regions[0]);
  int latlon, mode, failures = 0, runs = 0;
  for (latlon = 0; latlon < 2; ++latlon) {
    for (mode = 0; mode <= SEARCH_MODES; ++mode) {
      terrain t = make(61, 47, 30.0);
      ap_horizon_params p = params(16, 1);
      results w;
      size_t i, j, k;
      for (j = 0; j < t.ny; ++j) {
        for (i = 0; i < t.nx; ++i) {
          t.z[j * t.nx + i] = (float)rough((double)i * 30.0, (double)j * 30.0);
        }
      }
      t.z[3 * t.nx + 4] = NAN;   /* in the first region */
      t.z[40 * t.nx + 10] = NAN; /* outside every region but the whole */
      if (latlon) {
        latlon_rows(&t, 6371000.0, 60.0 * DEG, 0.0003 * DEG, 0.0004 * DEG);
      }
      if (mode == SEARCH_MODES) {
        p.max_distance = INFINITY; /* the sweep's unlimited hulls, the automatic near field */
      } else {
        p.max_distance = mode == MARCHED ? 500.0 : 1500.0;
        set_mode(&p, mode, 64);
      }
      w = compute(&t, &p);
      for (k = 0; k < nreg; ++k) {
        ap_horizon_params q = p;
        results r;
        q.region_i0 = regions[k][0];
        q.region_j0 = regions[k][1];
        q.region_nx = regions[k][2];
        q.region_ny = regions[k][3];
        r = compute(&t, &q);
        if (!same_in_region(&t, &w, &r, &q)) {
          printf("region %zu,%zu %zux%zu differs (%s, %s)\n", q.region_i0, q.region_j0,
                 q.region_nx, q.region_ny, latlon ? "lat/lon" : "projected",
                 mode == SEARCH_MODES ? "unlimited" : mode_name[mode]);
          ++failures;
        }
        ++runs;
        if (k == 4) {
          /* DiffuseSkyFactor alone: the bent-normal sums in the kernel's own buffer */
          ap_horizon_grid g = grid_of(&t);
          ap_sky_products o;
          float *vd = (float *)malloc(q.region_nx * q.region_ny * sizeof(float));
          size_t a;
          memset(&o, 0, sizeof(o));
          o.diffuse_sky_factor = vd;
          AP_CHECK_EQ_INT(ap_horizon_run(&g, &q, &o), AP_OK);
          for (j = 0; j < q.region_ny; ++j) {
            for (i = 0; i < q.region_nx; ++i) {
              a = (j + q.region_j0) * t.nx + i + q.region_i0;
              AP_CHECK(memcmp(&vd[j * q.region_nx + i], &w.vd[a], sizeof(float)) == 0);
            }
          }
          free(vd);
        }
        release(&r);
      }
      AP_CHECK(isnan(w.svf[3 * t.nx + 4]));
      release(&w);
      drop(&t);
    }
  }
  printf("%d regions, %d differ from the whole run\n", runs, failures);
  AP_CHECK(failures == 0);
}

/* Relative error of ap_atanf at x > 0; infinite for a NaN result (fmax would drop a NaN). */
static double atanf_error(float x)
{
  const float r = ap_atanf(x);
  return isnan(r) ? INFINITY : fabs((double)r - atan((double)x)) / atan((double)x);
}

/* The sums' single-precision arctangent against the double-precision library one: 2^20 floats
 * spread evenly over the bit patterns from 1e-30 to FLT_MAX (every exponent, varied
 * mantissas), the floats next to the reduction's boundaries tan(pi/8), 1 and tan(3pi/8), and
 * the special values. Relative error within 2.1e-7 (the bound found exhaustively when it was
 * written: 1.8 float ulps at most), odd symmetry exact. */
static void test_atanf(void)
{
  const float bounds[3] = { 0.41421356237309503f, 1.0f, 2.4142135623730950f };
  float lo = 1e-30f, hi = FLT_MAX;
  uint32_t blo, bhi, b, step;
  double worst = 0.0;
  int k, off;
  memcpy(&blo, &lo, sizeof(blo));
  memcpy(&bhi, &hi, sizeof(bhi));
  step = (bhi - blo) >> 20 | 1u; /* odd: the mantissas vary */
  for (b = blo; b <= bhi - step; b += step) {
    float x;
    memcpy(&x, &b, sizeof(x));
    worst = fmax(worst, atanf_error(x));
    if (ap_atanf(-x) != -ap_atanf(x)) {
      AP_CHECK(ap_atanf(-x) == -ap_atanf(x));
      break;
    }
  }
  for (k = 0; k < 3; ++k) {
    float x = bounds[k];
    for (off = 0; off < 8; ++off) {
      x = nextafterf(x, 0.0f);
    }
    for (off = -8; off <= 8; ++off, x = nextafterf(x, INFINITY)) {
      worst = fmax(worst, atanf_error(x));
    }
  }
  fprintf(stderr, "ap_atanf: largest relative error %.3g\n", worst);
  AP_CHECK(worst <= 2.1e-7);
  AP_CHECK(ap_atanf(0.0f) == 0.0f && !signbit(ap_atanf(0.0f)));
  AP_CHECK(ap_atanf(-0.0f) == 0.0f && signbit(ap_atanf(-0.0f)));
  AP_CHECK(ap_atanf(INFINITY) == (float)(PI / 2));
  AP_CHECK(ap_atanf(-INFINITY) == -(float)(PI / 2));
  AP_CHECK(isnan(ap_atanf(NAN)));
}

/* The sums' terms that vanish at the zenith (ap_zenith.h), for the float tangents of 2e6
 * horizons from 0 to 90 degrees, against long double from the same tangent: the zenith
 * distance within 2.5e-7 relatively (ap_atanf's bound and 1 / t), Q(h) within 8e-7 (the
 * direct form switched at x = 1, as first written, was 2.5e-6 off; pi/2 - atan(t) lost all of
 * u near the zenith). */
static void test_zenith_terms(void)
{
  double worst_u = 0.0, worst_q = 0.0;
  int k;
  for (k = 1; k <= 2000000; ++k) {
    const long double h = (long double)PI / 2 * k / 2000001;
    const float t = (float)tanl(h);
    const float c = 1.0f / sqrtf(1.0f + t * t), s = t * c;
    const long double u = atanl(1.0L / (long double)t), x = 2 * u;
    /* (x - sin x) / 4 by its series where it cancels in long double too */
    const long double q = x < 0.01L ? x * x * x / 24 * (1 - x * x / 20) : (x - sinl(x)) / 4;
    worst_u = fmax(worst_u, (double)fabsl(ap_zenith_distance(t) / u - 1));
    worst_q = fmax(worst_q, (double)fabsl(ap_zenith_q(ap_zenith_distance(t), s, c) / q - 1));
  }
  fprintf(stderr, "zenith terms: u within %.3g, Q within %.3g, relatively\n", worst_u, worst_q);
  AP_CHECK(worst_u <= 2.5e-7);
  AP_CHECK(worst_q <= 8e-7);
  AP_CHECK(ap_zenith_distance(0.0f) == (float)(PI / 2) && ap_zenith_distance(INFINITY) == 0.0f);
}

int main(void)
{
  AP_TEST_RUN(test_atanf);
  AP_TEST_RUN(test_zenith_terms);
  AP_TEST_RUN(test_flat);
  AP_TEST_RUN(test_inclined_plane);
  AP_TEST_RUN(test_valley);
  AP_TEST_RUN(test_wall);
  AP_TEST_RUN(test_pit);
  AP_TEST_RUN(test_deep_shaft);
  AP_TEST_RUN(test_steep_planes);
  AP_TEST_RUN(test_curvature);
  AP_TEST_RUN(test_brute_force);
  AP_TEST_RUN(test_long_narrow);
  AP_TEST_RUN(test_latlon_rows);
  AP_TEST_RUN(test_side_edges);
  AP_TEST_RUN(test_far_march_corner_diagonals);
  AP_TEST_RUN(test_one_cell_tower);
  AP_TEST_RUN(test_split_invariance);
  AP_TEST_RUN(test_far_march_skips);
  AP_TEST_RUN(test_pieces);
  AP_TEST_RUN(test_scale_metric);
  AP_TEST_RUN(test_scale_metric_sheared);
  AP_TEST_RUN(test_random_pieces);
  AP_TEST_RUN(test_regions);
  AP_TEST_RUN(test_edge_flags);
  AP_TEST_RUN(test_edge_flags_oblique);
  AP_TEST_RUN(test_extreme_ranges);
  AP_TEST_RUN(test_nodata_transparent);
  AP_TEST_RUN(test_nodata_spans);
  AP_TEST_RUN(test_nodata_coast);
  AP_TEST_RUN(test_top_bounds_exact);
  AP_TEST_RUN(test_errors);
  AP_TEST_MAIN_END();
}
