/* SPDX-License-Identifier: BSD-3-Clause */
/* Unit tests of ap_light: cap intersection (exact and Oat & Sander's smoothstep) against the
 * ALGORITHMS.md §1.5 table and a 1-D ring quadrature written here; the lens moment against the
 * §6.4 table and the same quadrature; the clipped cap cosine integral against closed forms and
 * a brute-force 2-D quadrature; the whole model on closed-form scenes; the tone map and sRGB
 * curve against hand values; and the exact area evaluated in float (a copy of the formula with
 * float types) against double, which is what the GLSL port will do.
 * Run with -v to print the measured errors. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "ap_light.h"
#include "aptest.h"

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)
#define RHO (0.26667 * DEG) /* the sun cap of the tests, SPA's SUN_RADIUS */

static int verbose = 0;

/* |a − b| <= rel · |b| + abs */
#define CHECK_REL(a, b, rel, abs_)                                                                \
  AP_CHECK_NEAR((a), (b), (rel)*fabs((double)(b)) + (abs_))

static double dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross(const double a[3], const double b[3], double c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/* ENU unit vector from compass azimuth and elevation (ALGORITHMS.md conventions). */
static void enu(double az, double el, double v[3])
{
  v[0] = cos(el) * sin(az);
  v[1] = cos(el) * cos(az);
  v[2] = sin(el);
}

/* An orthonormal frame (c1, t1, v) in a tilted orientation, and c2 = cos d c1 + sin d t1. */
static void axes(double d, double c1[3], double t1[3], double c2[3])
{
  double a[3], v[3];
  enu(0.7, 0.4, c1);
  a[0] = 0.3;
  a[1] = -0.8;
  a[2] = 0.5;
  cross(c1, a, v);
  double lv = sqrt(dot(v, v));
  for (int i = 0; i < 3; ++i) {
    v[i] /= lv;
  }
  cross(v, c1, t1);
  for (int i = 0; i < 3; ++i) {
    c2[i] = cos(d) * c1[i] + sin(d) * t1[i];
  }
}

/* ---- 1-D ring quadrature of the intersection of cap (c1, r1) and cap (c2, r2), axes d apart:
 * rings of radius θ about c1; the arc of each ring inside cap 2 is |φ| <= β(θ), with
 * cos β = (cos r2 − cos θ cos d)/(sin θ sin d); ∫ over the arc of ω dφ = 2β cos θ c1 +
 * 2 sin β sin θ t1. θ is split at the tangencies and mapped by θ = a + (b − a)(1 − cos u)/2 so
 * that the square-root ends of β become smooth; 5-point Gauss–Legendre on 2000 pieces of u. ---- */
static void ring_quadrature(double r1, double r2, double d, double *area, double *m_c1,
                            double *m_t1)
{
  static const double gx[5] = { -0.9061798459386640, -0.5384693101056831, 0.0,
                                0.5384693101056831, 0.9061798459386640 };
  static const double gw[5] = { 0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                0.4786286704993665, 0.2369268850561891 };
  double br[6] = { 0.0, r1, fabs(r2 - d), d + r2, 2.0 * PI - d - r2, 0.0 };
  int nb = 2;
  for (int i = 2; i < 5; ++i) {
    if (br[i] > 0.0 && br[i] < r1) {
      br[nb++] = br[i];
    }
  }
  for (int i = 0; i < nb; ++i) { /* sort */
    for (int j = i + 1; j < nb; ++j) {
      if (br[j] < br[i]) {
        double t = br[i];
        br[i] = br[j];
        br[j] = t;
      }
    }
  }
  const int m = 2000;
  const double h = PI / m;
  double A = 0.0, Mc = 0.0, Mt = 0.0;
  for (int p = 0; p + 1 < nb; ++p) {
    double a = br[p], b = br[p + 1];
    for (int k = 0; k < m; ++k) {
      for (int g = 0; g < 5; ++g) {
        double u = h * (k + 0.5 + 0.5 * gx[g]);
        double th = a + 0.5 * (b - a) * (1.0 - cos(u));
        double w = gw[g] * 0.5 * h * 0.5 * (b - a) * sin(u) * sin(th);
        double q = (cos(r2) - cos(th) * cos(d)) / (sin(th) * sin(d));
        double beta = acos(fmin(1.0, fmax(-1.0, q)));
        A += w * 2.0 * beta;
        Mc += w * 2.0 * beta * cos(th);
        Mt += w * 2.0 * sin(beta) * sin(th);
      }
    }
  }
  *area = A;
  *m_c1 = Mc;
  *m_t1 = Mt;
}

/* ---- brute-force 2-D midpoint rule of ∫_cap max(0, n·ω) dω, cap radius s, axis θ from n ---- */
static double brute_cap_cosine(double s, double theta)
{
  enum { nt = 1500, np = 3000 };
  static double cphi[np];
  for (int j = 0; j < np; ++j) {
    cphi[j] = cos(PI * (j + 0.5) / np); /* φ in [0, π], doubled */
  }
  double sum = 0.0;
  for (int i = 0; i < nt; ++i) {
    double psi = s * (i + 0.5) / nt;
    double a = cos(theta) * cos(psi), b = sin(theta) * sin(psi), ring = 0.0;
    for (int j = 0; j < np; ++j) {
      double c = a + b * cphi[j];
      if (c > 0.0) {
        ring += c;
      }
    }
    sum += ring * sin(psi);
  }
  return sum * 2.0 * (PI / np) * (s / nt);
}

/* ---- the exact area in float, as the shader computes it (copy of the C code, float types) ---- */
#define PI_F 3.14159265f
static float cap_area_f(float r)
{
  float h = sinf(0.5f * r);
  return 4.0f * PI_F * h * h;
}

static float intersection_exact_f(float r1, float r2, float d)
{
  if (d <= fabsf(r1 - r2)) {
    return cap_area_f(fminf(r1, r2));
  }
  if (d >= r1 + r2) {
    return 0.0f;
  }
  if (d >= 2.0f * PI_F - r1 - r2) {
    return cap_area_f(r1) + cap_area_f(r2) - 4.0f * PI_F;
  }
  float s = 0.5f * (r1 + r2 + d);
  float k = sqrtf(fmaxf(0.0f, sinf(s - r1) * sinf(s - r2) * sinf(s - d) / sinf(s)));
  float a1 = 2.0f * atan2f(k, sinf(s - r2));
  float a2 = 2.0f * atan2f(k, sinf(s - r1));
  float e = 4.0f * atanf(sqrtf(fmaxf(0.0f, tanf(0.5f * s) * tanf(0.5f * (s - r1)) *
                                               tanf(0.5f * (s - r2)) * tanf(0.5f * (s - d)))));
  float h1 = sinf(0.5f * r1), h2 = sinf(0.5f * r2);
  return fmaxf(0.0f, 4.0f * a1 * h1 * h1 + 4.0f * a2 * h2 * h2 - 2.0f * e);
}

/* The lens's moment in float, as the shader computes it (ap_light.c's lens_moment_partial with
 * float types; the lens angles as in intersection_exact_f), caps 1 (r1, axis (0, 0, 1)) and 2
 * (r2 <= r1, axis at d from it in the x–z plane); the centroid direction into dir. */
static float angle_less_sine_f(float a)
{
  float q = a * a;
  return (a < 0.5f) ? a * q / 6.0f * (1.0f - q / 20.0f * (1.0f - q / 42.0f * (1.0f - q / 72.0f)))
                    : a - sinf(a);
}

static void lens_centroid_f(float r1, float r2, float d, double dir[3])
{
  float s = 0.5f * (r1 + r2 + d);
  float k = sqrtf(fmaxf(0.0f, sinf(s - r1) * sinf(s - r2) * sinf(s - d) / sinf(s)));
  float a1 = 2.0f * atan2f(k, sinf(s - r2)), a2 = 2.0f * atan2f(k, sinf(s - r1));
  float cd = cosf(d), sd = sinf(d);
  float c1[3] = { 0.0f, 0.0f, 1.0f }, c2[3] = { sd, 0.0f, cd };
  float hs = sinf(0.5f * r2), srs = sinf(r2), sro = sinf(r1), sao = sinf(a1);
  float dif = sinf(0.5f * (r1 - d)), sum = sinf(0.5f * (r1 + d)), cos_sum = cosf(0.5f * (r1 + d));
  float ks = srs * a2 * srs, kt = 2.0f * srs * hs * hs * sinf(a2);
  float ko = sro * (angle_less_sine_f(a1) * sro + 2.0f * sao * cos_sum * dif);
  float kto = sro * 2.0f * sao * sum * dif;
  double B[3], len = 0.0;
  for (int i = 0; i < 3; ++i) {
    float ts = (c1[i] - cd * c2[i]) / sd, to = (c2[i] - cd * c1[i]) / sd;
    B[i] = (double)(ks * c2[i] + kt * ts + ko * c1[i] + kto * to);
    len += B[i] * B[i];
  }
  for (int i = 0; i < 3; ++i) {
    dir[i] = B[i] / sqrt(len);
  }
}

/* ============================================================================================ */

/* ALGORITHMS.md §1.5: r1, r2, d, exact area as printed, its last printed digit, the closed form
 * where one exists (else < 0), Oat–Sander column. Rows 1–2 use π/4, π/2 and rows 11–13 the sun
 * radius 0.26667° exactly (the printed inputs are rounded). */
typedef struct area_row {
  double r1, r2, d, exact, digit, closed, os;
} area_row;

static void test_area_table(void)
{
  const area_row rows[13] = {
    { PI / 4, PI / 4, PI / 4, 0.760827546367, 1e-12, -1, 0.920151 },
    { PI / 2, PI / 2, PI / 2, 3.14159265359, 1e-11, PI, 3.14159 },
    { PI / 2, 0.3, PI / 2, 0.140314557647, 1e-12, PI * (1 - cos(0.3)), 0.140315 },
    { 1, 0.5, 1.2, 0.178276112551, 1e-12, -1, 0.166141 },
    { 0.8, 1.3, 0.6, 1.83992440654, 1e-11, -1, 1.88425 },
    { 1.5, 0.3, 1, 0.280629115293, 1e-12, 2 * PI * (1 - cos(0.3)), 0.280629 },
    { 0.5, 0.5, 1.1, 0, 0, 0, 0 },
    { 2, 1, 2.5, 0.757011875143, 1e-12, -1, 0.451307 },
    { 3, 2.5, 1, 11.254040103, 1e-9, 2 * PI * (1 - cos(3.0)) + 2 * PI * (1 - cos(2.5)) - 4 * PI,
      11.0 },
    { 1, 0.2, 0.801, 0.125216630991, 1e-12, -1, 0.125243 },
    { RHO, 1, 1, 3.40053026455e-05, 1e-16, -1, 3.40269e-05 },
    { RHO, 1.2, 1.2 + 0.5 * RHO, 1.32961308501e-05, 1e-16, -1, 1.06334e-05 },
    { RHO, 1.2, 1.2 - 0.5 * RHO, 5.47406593296e-05, 1e-16, -1, 5.74204e-05 },
  };
  const int cases[13] = { AP_LIGHT_PARTIAL,   AP_LIGHT_PARTIAL,  AP_LIGHT_PARTIAL,
                          AP_LIGHT_PARTIAL,   AP_LIGHT_PARTIAL,  AP_LIGHT_CONTAINED,
                          AP_LIGHT_DISJOINT,  AP_LIGHT_PARTIAL,  AP_LIGHT_COVERS_SPHERE,
                          AP_LIGHT_PARTIAL,   AP_LIGHT_PARTIAL,  AP_LIGHT_PARTIAL,
                          AP_LIGHT_PARTIAL };
  double worst_quad = 0.0;
  for (int i = 0; i < 13; ++i) {
    const area_row *r = &rows[i];
    double a = ap_light_cap_intersection_exact(r->r1, r->r2, r->d);
    AP_CHECK_EQ_INT(ap_light_cap_overlap(r->r1, r->r2, r->d), cases[i]);
    if (r->closed >= 0) {
      CHECK_REL(a, r->closed, 1e-12, 1e-300);
      CHECK_REL(r->closed, r->exact, 0.0, 0.5 * r->digit); /* the table agrees */
    } else {
      /* 1e-12 relative, or half a unit of the table's last printed digit if that is larger */
      CHECK_REL(a, r->exact, 1e-12, 0.5 * r->digit);
    }
    /* symmetric in the two caps */
    CHECK_REL(ap_light_cap_intersection_exact(r->r2, r->r1, r->d), a, 1e-14, 1e-300);
    /* independent ring quadrature */
    double qa, qc, qt;
    ring_quadrature(r->r1, r->r2, r->d, &qa, &qc, &qt);
    CHECK_REL(a, qa, 1e-12, 1e-300);
    if (a > 0) {
      worst_quad = fmax(worst_quad, fabs(a - qa) / a);
    }
    /* Oat & Sander: printed to 6 digits (row 9 to 3; its value is 11.0000454) */
    double os = ap_light_cap_intersection_smoothstep(r->r1, r->r2, r->d);
    CHECK_REL(os, r->os, 1e-5, 1e-300);
  }
  if (verbose) {
    printf("area: exact vs ring quadrature, max rel %.2e\n", worst_quad);
  }
  /* special values and domain */
  AP_CHECK_NEAR(ap_light_cap_intersection_exact(0.0, 1.0, 0.5), 0.0, 0.0);
  AP_CHECK_NEAR(ap_light_cap_intersection_exact(0.5, 0.5, 0.0), ap_light_cap_area(0.5), 1e-15);
  AP_CHECK_NEAR(ap_light_cap_area(PI), 4 * PI, 1e-14);
  AP_CHECK_NAN(ap_light_cap_intersection_exact(NAN, 1.0, 0.5));
  AP_CHECK_NAN(ap_light_cap_intersection_exact(1.0, -0.1, 0.5));
  AP_CHECK_NAN(ap_light_cap_intersection_smoothstep(1.0, 1.0, 3.5));
  AP_CHECK_NAN(ap_light_cap_area(-1.0));
  AP_CHECK_EQ_INT(ap_light_cap_overlap(1.0, 1.0, NAN), -1);
  /* continuity at tangencies: internal and external */
  double eps = 1e-9;
  CHECK_REL(ap_light_cap_intersection_exact(1.0, 0.2, 0.8 + eps), ap_light_cap_area(0.2), 1e-6,
            0.0);
  AP_CHECK_NEAR(ap_light_cap_intersection_exact(1.0, 0.2, 1.2 - eps), 0.0, 1e-10);
}

/* ---- float32: the sun cap against apertures 0.3 / 1.0 / 1.5 rad, offsets within ±0.9ρ ---- */
static void test_area_float(void)
{
  const double rps[3] = { 0.3, 1.0, 1.5 };
  double worst = 0.0, typical = 0.0;
  int count = 0;
  for (int i = 0; i < 3; ++i) {
    for (int k = -90; k <= 90; ++k) {
      float rpf = (float)rps[i], rlf = (float)RHO;
      float df = (float)(rps[i] + 0.01 * k * RHO);
      double ref = ap_light_cap_intersection_exact((double)rpf, (double)rlf, (double)df);
      double f = (double)intersection_exact_f(rpf, rlf, df);
      double rel = fabs(f - ref) / ref;
      AP_CHECK(rel <= 4e-4);
      worst = fmax(worst, rel);
      typical += rel;
      ++count;
    }
  }
  if (verbose) {
    printf("float32 exact area, sun cap: max rel %.2e, mean %.2e over %d\n", worst,
           typical / count, count);
  }
}

/* ---- float32: the lens centroid of the sun cap straddling apertures' rims ----
 * About the sphere's centre, the larger cap's rim terms (~ sin² rp α_p, 1e-3) cancel to the
 * lens's moment (~ ρ², 1e-5), and the float centroid (atan2f, correctly rounded lens angles
 * included) turns by up to 10ρ; about the sun's axis it stays within 3e-4ρ of double. */
static void test_centroid_float(void)
{
  double worst = 0.0;
  for (int i = 0; i <= 12; ++i) {
    for (int k = -90; k <= 90; k += 5) {
      float rpf = (float)(0.3 + 0.1 * i), rlf = (float)RHO;
      float df = (float)(rpf + 0.01 * k * RHO);
      double c1[3] = { 0.0, 0.0, 1.0 }, c2[3] = { sin((double)df), 0.0, cos((double)df) };
      double ref[3], got[3], x[3];
      AP_CHECK_EQ_INT(ap_light_lens_centroid(rpf, rlf, c1, c2, ref), 1);
      lens_centroid_f(rpf, rlf, df, got);
      cross(ref, got, x);
      double err = atan2(sqrt(dot(x, x)), dot(ref, got)) / RHO;
      AP_CHECK(err <= 1e-3);
      worst = fmax(worst, err);
    }
  }
  if (verbose) {
    printf("float32 lens centroid, sun cap: max error %.2e of the sun's radius\n", worst);
  }
}

/* ---- cap cosine integral ---- */
static void test_cap_cosine(void)
{
  /* hemisphere: (π/2)(1 + cos θ) */
  for (int k = 0; k <= 18; ++k) {
    double th = k * 10.0 * DEG;
    CHECK_REL(ap_light_cap_cosine_integral(cos(th), 1.0), 0.5 * PI * (1 + cos(th)), 1e-14, 1e-15);
  }
  /* unclipped: π sin²σ cos θ; wholly below: 0 */
  double s = 0.4;
  CHECK_REL(ap_light_cap_cosine_integral(cos(1.0), sin(s) * sin(s)),
            PI * sin(s) * sin(s) * cos(1.0), 1e-14, 0.0);
  AP_CHECK_NEAR(ap_light_cap_cosine_integral(cos(2.0), sin(s) * sin(s)), 0.0, 0.0);
  /* axis in the plane: σ − sin σ cos σ (the upper half of the cap, by hand) */
  const double sig[4] = { RHO, 0.1, 0.7, 1.5 };
  for (int i = 0; i < 4; ++i) {
    double sg = sig[i];
    CHECK_REL(ap_light_cap_cosine_integral(0.0, sin(sg) * sin(sg)), sg - sin(sg) * cos(sg),
              1e-9, 1e-300);
  }
  /* clipped: against the brute-force 2-D quadrature */
  const double cs[][2] = { { 10, 85 },  { 10, 95 },  { 30, 70 },     { 45, 60 },
                           { 60, 45 },  { 80, 15 },  { 45, 130 },    { 60, 140 },
                           { 90, 120 }, { 10, 120 }, { 0.26667, 89.9 }, { 0.26667, 90.1 } };
  double worst = 0.0;
  for (size_t i = 0; i < sizeof cs / sizeof cs[0]; ++i) {
    double sg = cs[i][0] * DEG, th = cs[i][1] * DEG;
    double c = ap_light_cap_cosine_integral(cos(th), sin(sg) * sin(sg));
    double q = brute_cap_cosine(sg, th);
    CHECK_REL(c, q, 1e-5, 1e-300);
    if (q > 0) {
      worst = fmax(worst, fabs(c - q) / q);
    } else {
      AP_CHECK_NEAR(c, 0.0, 0.0);
    }
  }
  if (verbose) {
    printf("cap cosine integral vs 2-D quadrature: max rel %.2e\n", worst);
  }
  AP_CHECK_NAN(ap_light_cap_cosine_integral(NAN, 0.5));
  AP_CHECK_NAN(ap_light_cap_cosine_integral(0.5, 1.5));
  /* rounding slightly past ±1 is clamped */
  AP_CHECK_NEAR(ap_light_cap_cosine_integral(1.0 + 1e-15, 1.0), PI, 1e-14);
}

/* ---- lens moment ---- */
static void test_lens_moment(void)
{
  /* §6.4 table; its normals are not printed: they are recovered from the "area × cos" columns
   * as n tilted from b by 10° toward the light, 0°, 20° away from it. */
  const double rows[3][5] = {
    /* rp, rl, d (deg), tilt of n toward the light (deg), n·B */
    { 60, 20, 65, 10, 0.08830 },
    { 60, 30, 50, 0, 0.40402 },
    { 45, 10, 40, -20, 0.03957 },
  };
  for (int i = 0; i < 3; ++i) {
    double rp = rows[i][0] * DEG, rl = rows[i][1] * DEG, d = rows[i][2] * DEG;
    double tilt = rows[i][3] * DEG;
    double b[3], t[3], s[3], n[3], B[3];
    axes(d, b, t, s); /* b = aperture axis, s = light axis at d from b */
    for (int k = 0; k < 3; ++k) {
      n[k] = cos(tilt) * b[k] + sin(tilt) * t[k];
    }
    AP_CHECK_EQ_INT(ap_light_lens_moment(rl, rp, s, b, B), AP_LIGHT_PARTIAL);
    AP_CHECK_NEAR(dot(n, B), rows[i][4], 5e-6);
    /* the model's CENTROID S = A · n·ĉ, with A and B from the ring quadrature */
    double qa, qc, qt, Bq[3], tl[3];
    for (int k = 0; k < 3; ++k) {
      tl[k] = (b[k] - cos(d) * s[k]) / sin(d); /* tangent at s toward b */
    }
    ring_quadrature(rl, rp, d, &qa, &qc, &qt);
    for (int k = 0; k < 3; ++k) {
      Bq[k] = qc * s[k] + qt * tl[k];
    }
    double lb = sqrt(dot(Bq, Bq));
    ap_light_params p;
    ap_light_params_init(&p);
    memcpy(p.sun, s, sizeof p.sun);
    p.sun_radius = rl;
    p.lambert = AP_LIGHT_CENTROID;
    double alb[3] = { 1, 1, 1 }, lo[3], es[3], ek[3];
    AP_CHECK_EQ_INT(ap_light_point(&p, n, b, rp, alb, lo, es, ek), AP_OK);
    double l_sun = 1000.0 / (PI * sin(rl) * sin(rl));
    CHECK_REL(es[0], l_sun * qa * dot(n, Bq) / lb, 1e-9, 0.0);
  }
  /* against the ring quadrature (vector), every non-disjoint configuration of §1.5 */
  const double cfg[][3] = { { PI / 4, PI / 4, PI / 4 }, { 1, 0.5, 1.2 }, { 0.8, 1.3, 0.6 },
                            { 1.5, 0.3, 1 }, { 2, 1, 2.5 }, { 3, 2.5, 1 }, { 1, 0.2, 0.801 },
                            { RHO, 1, 1 }, { RHO, 1.2, 1.2 + 0.5 * RHO }, { 0.5, 0.5, 0.3 } };
  double worst = 0.0;
  for (size_t i = 0; i < sizeof cfg / sizeof cfg[0]; ++i) {
    double r1 = cfg[i][0], r2 = cfg[i][1], d = cfg[i][2];
    double c1[3], t1[3], c2[3], B[3], qa, qc, qt;
    axes(d, c1, t1, c2);
    ap_light_lens_moment(r1, r2, c1, c2, B);
    ring_quadrature(r1, r2, d, &qa, &qc, &qt);
    double err = 0.0, norm = sqrt(qc * qc + qt * qt);
    for (int k = 0; k < 3; ++k) {
      double e = B[k] - (qc * c1[k] + qt * t1[k]);
      err += e * e;
    }
    err = sqrt(err) / norm;
    AP_CHECK(err <= 1e-10);
    worst = fmax(worst, err);
  }
  if (verbose) {
    printf("lens moment vs ring quadrature: max rel %.2e\n", worst);
  }
  /* containment: π sin² r · c of the smaller cap; disjoint: 0; tangency: → 0 */
  double c1[3], t1[3], c2[3], B[3];
  axes(0.3, c1, t1, c2);
  AP_CHECK_EQ_INT(ap_light_lens_moment(0.2, 1.0, c1, c2, B), AP_LIGHT_CONTAINED);
  for (int k = 0; k < 3; ++k) {
    AP_CHECK_NEAR(B[k], PI * sin(0.2) * sin(0.2) * c1[k], 1e-15);
  }
  AP_CHECK_EQ_INT(ap_light_lens_moment(0.1, 0.1, c1, c2, B), AP_LIGHT_DISJOINT);
  AP_CHECK_NEAR(fabs(B[0]) + fabs(B[1]) + fabs(B[2]), 0.0, 0.0);
  axes(0.5 - 1e-9, c1, t1, c2);
  ap_light_lens_moment(0.2, 0.3, c1, c2, B);
  AP_CHECK(sqrt(dot(B, B)) < 1e-12);
  AP_CHECK_EQ_INT(ap_light_lens_moment(NAN, 0.3, c1, c2, B), -1);
  AP_CHECK_NAN(B[0]);

  /* equal caps: the centroid lies on the bisector of the axes */
  const double ds[3] = { 0.1, 0.9, 1.3 };
  for (int i = 0; i < 3; ++i) {
    double dir[3], mid[3], x[3];
    axes(ds[i], c1, t1, c2);
    AP_CHECK_EQ_INT(ap_light_lens_centroid(0.7, 0.7, c1, c2, dir), 1);
    for (int k = 0; k < 3; ++k) {
      mid[k] = c1[k] + c2[k];
    }
    cross(dir, mid, x);
    AP_CHECK(sqrt(dot(x, x)) / sqrt(dot(mid, mid)) < 1e-14);
    AP_CHECK(dot(dir, mid) > 0);
    AP_CHECK_NEAR(dot(dir, dir), 1.0, 1e-15);
  }
  /* centroid of a contained cap is its axis; none when disjoint */
  double dir[3];
  axes(0.3, c1, t1, c2);
  AP_CHECK_EQ_INT(ap_light_lens_centroid(1.0, 0.2, c1, c2, dir), 1);
  AP_CHECK_NEAR(dot(dir, c2), 1.0, 1e-15);
  AP_CHECK_EQ_INT(ap_light_lens_centroid(0.1, 0.1, c1, c2, dir), 0);
}

/* ---- the model on closed-form scenes ---- */
static const double up[3] = { 0, 0, 1 };
static const double white[3] = { 1, 1, 1 };

static void run(const ap_light_params *p, const double n[3], const double b[3], double rp,
                double lo[3], double es[3], double ek[3])
{
  AP_CHECK_EQ_INT(ap_light_point(p, n, b, rp, white, lo, es, ek), AP_OK);
}

static void test_model_scenes(void)
{
  ap_light_params p;
  ap_light_params_init(&p);
  AP_CHECK_EQ_INT(ap_light_params_validate(&p), AP_OK);
  p.sun_irradiance[0] = 1000;
  p.sun_irradiance[1] = 800;
  p.sun_irradiance[2] = 600;
  p.sky_radiance[0] = 20;
  p.sky_radiance[1] = 30;
  p.sky_radiance[2] = 50;
  double lo[3], es[3], ek[3];

  /* flat open ground, sun well above the horizon */
  const double elev[4] = { 5, 30, 60, 90 };
  for (int m = 0; m < 4; ++m) {
    p.intersection = (m & 1) ? AP_LIGHT_SMOOTHSTEP : AP_LIGHT_EXACT;
    p.lambert = (m & 2) ? AP_LIGHT_CENTROID : AP_LIGHT_EXACTCAP;
    for (int i = 0; i < 4; ++i) {
      double e = elev[i] * DEG;
      enu(2.0, e, p.sun);
      run(&p, up, up, PI / 2, lo, es, ek);
      /* EXACTCAP: exactly Esun sin e. CENTROID: area × cos = Ω_l sin e, so Esun sin e /
       * cos²(rl/2) (the spec's "exactly Esun" holds for EXACTCAP only; 5.4e-6 here). */
      double k = (p.lambert == AP_LIGHT_EXACTCAP) ? 1.0 : 1.0 / pow(cos(0.5 * RHO), 2);
      double S = sin(e) * ((p.lambert == AP_LIGHT_EXACTCAP) ? PI * sin(RHO) * sin(RHO)
                                                            : 4 * PI * pow(sin(0.5 * RHO), 2));
      for (int c = 0; c < 3; ++c) {
        CHECK_REL(es[c], p.sun_irradiance[c] * sin(e) * k, 1e-9, 0.0);
        CHECK_REL(es[c], p.sun_irradiance[c] * sin(e), 6e-6, 0.0);
        CHECK_REL(ek[c], p.sky_radiance[c] * (PI - S), 1e-12, 0.0);
        CHECK_REL(lo[c], (es[c] + ek[c]) / PI, 1e-15, 0.0);
      }
    }
  }

  /* pit: the aperture (rp = 0.5) misses the sun (zenith 0.5 + ρ + 0.01) */
  ap_light_params_init(&p);
  p.sky_radiance[0] = 20;
  enu(1.0, PI / 2 - (0.5 + RHO + 0.01), p.sun);
  for (int m = 0; m < 4; ++m) {
    p.intersection = (m & 1) ? AP_LIGHT_SMOOTHSTEP : AP_LIGHT_EXACT;
    p.lambert = (m & 2) ? AP_LIGHT_CENTROID : AP_LIGHT_EXACTCAP;
    run(&p, up, up, 0.5, lo, es, ek);
    AP_CHECK_NEAR(es[0], 0.0, 0.0);
    CHECK_REL(ek[0], 20 * PI * sin(0.5) * sin(0.5), 1e-14, 0.0);
  }
  /* rp = 0: no sun, no sky */
  run(&p, up, up, 0.0, lo, es, ek);
  AP_CHECK_NEAR(es[0] + ek[0] + lo[0], 0.0, 0.0);

  /* widened sun (rl = 5°) crossing the rim of rp = 1 on flat ground: the visible fraction
   * (E_sun over the fully visible E_sun at that elevation) falls from 1 to 0, monotonically */
  ap_light_params_init(&p);
  p.sun_radius = 5 * DEG;
  double rl = p.sun_radius;
  for (int m = 0; m < 2; ++m) {
    p.intersection = m ? AP_LIGHT_SMOOTHSTEP : AP_LIGHT_EXACT;
    double prev = 2.0;
    for (int k = -12; k <= 12; ++k) {
      double z = 1.0 + k * rl / 10.0; /* sun zenith angle */
      enu(0.3, PI / 2 - z, p.sun);
      run(&p, up, up, 1.0, lo, es, ek);
      double full = 1000.0 * ap_light_cap_cosine_integral(cos(z), sin(rl) * sin(rl)) /
                    (PI * sin(rl) * sin(rl));
      double f = es[0] / full;
      if (k <= -10) {
        CHECK_REL(f, 1.0, 1e-12, 0.0);
      } else if (k >= 10) {
        AP_CHECK_NEAR(f, 0.0, 1e-12);
      } else {
        AP_CHECK(f > 0.0 && f < 1.0);
        AP_CHECK(f < prev);
      }
      if (m == 0) {
        CHECK_REL(f, ap_light_cap_intersection_exact(1.0, rl, z) / (4 * PI * pow(sin(0.5 * rl), 2)),
                  1e-12, 1e-15);
      }
      if (k == 0 && m == 0) { /* centred on the rim: a little under half (rim curvature) */
        AP_CHECK(f > 0.4 && f < 0.5);
      }
      prev = f;
    }
  }

  /* sun behind the surface's own plane, though inside the aperture: E_sun = 0 */
  ap_light_params_init(&p);
  p.sky_radiance[0] = 25;
  double n[3];
  enu(PI, 30 * DEG, n); /* slope 60° facing south */
  enu(0.0, 30 * DEG, p.sun); /* sun north, elevation 30°: n·s = −0.5 */
  for (int m = 0; m < 4; ++m) {
    p.intersection = (m & 1) ? AP_LIGHT_SMOOTHSTEP : AP_LIGHT_EXACT;
    p.lambert = (m & 2) ? AP_LIGHT_CENTROID : AP_LIGHT_EXACTCAP;
    run(&p, n, up, 1.2, lo, es, ek);
    AP_CHECK_NEAR(es[0], 0.0, 0.0);
    CHECK_REL(ek[0], 25 * ap_light_cap_cosine_integral(dot(n, up), sin(1.2) * sin(1.2)), 1e-15,
              0.0);
  }
  /* sun centre on the surface's plane: EXACTCAP keeps the upper half-disc, CENTROID nothing */
  enu(0.3, 0.0, p.sun);
  p.lambert = AP_LIGHT_EXACTCAP;
  p.intersection = AP_LIGHT_EXACT;
  run(&p, up, up, PI / 2, lo, es, ek);
  /* half of the sun cap visible (A = Ω_l/2 exactly: the boundary is a great circle) */
  CHECK_REL(es[0], 1000.0 / (PI * sin(RHO) * sin(RHO)) * (RHO - sin(RHO) * cos(RHO)) * 0.5, 1e-6,
            0.0);
  /* CENTROID: the visible lens is the upper half-disc; A = Ω_l/2, n·B = ρ − sin ρ cos ρ (as
   * above), s·B = π sin²ρ / 2 (half the cap's moment), so S = A n·B / |B|. EXACTCAP counts the
   * plane twice here (aperture rim and surface plane coincide) and gives half of n·B. */
  p.lambert = AP_LIGHT_CENTROID;
  run(&p, up, up, PI / 2, lo, es, ek);
  {
    double nb = RHO - sin(RHO) * cos(RHO), sb = 0.5 * PI * sin(RHO) * sin(RHO);
    double area = 2 * PI * pow(sin(0.5 * RHO), 2);
    CHECK_REL(es[0], 1000.0 / (PI * sin(RHO) * sin(RHO)) * area * nb / sqrt(nb * nb + sb * sb),
              1e-8, 0.0);
  }

  /* sun exactly at the zenith over flat ground: sin d = 0, concentric caps */
  p.sun[0] = p.sun[1] = 0.0;
  p.sun[2] = 1.0;
  for (int m = 0; m < 2; ++m) {
    p.lambert = m ? AP_LIGHT_CENTROID : AP_LIGHT_EXACTCAP;
    run(&p, up, up, PI / 2, lo, es, ek);
    CHECK_REL(es[0], m ? 1000.0 / pow(cos(0.5 * RHO), 2) : 1000.0, 1e-12, 0.0);
    run(&p, up, up, 0.5 * RHO, lo, es, ek); /* aperture inside the sun disc */
    double q = sin(0.25 * RHO); /* Ω(ρ/2) = 4π q² */
    CHECK_REL(es[0], m ? 1000.0 * 4 * PI * q * q / (PI * sin(RHO) * sin(RHO))
                       : 1000.0 * q * q / pow(sin(0.5 * RHO), 2),
              1e-12, 0.0);
  }

  /* small sun centred on the rim of rp = 1 (zenith 1 rad), lens above the plane, so n·B is its
   * exact Lambert integral: CENTROID (A n·B/|B|, A/|B| = 1 + O(ρ²)) is within 1e-5 of it;
   * EXACTCAP puts the visible half at the disc's centre, 0.42ρ too low: tan(1) · 0.42ρ = 0.3 %
   * too little */
  ap_light_params_init(&p);
  enu(1.1, PI / 2 - 1.0, p.sun);
  double es2[3], B[3];
  p.lambert = AP_LIGHT_EXACTCAP;
  run(&p, up, up, 1.0, lo, es, ek);
  p.lambert = AP_LIGHT_CENTROID;
  run(&p, up, up, 1.0, lo, es2, ek);
  ap_light_lens_moment(1.0, RHO, up, p.sun, B);
  double exact = 1000.0 / (PI * sin(RHO) * sin(RHO)) * B[2];
  CHECK_REL(es2[0], exact, 1e-5, 0.0);
  CHECK_REL(es[0], exact * (1 - tan(1.0) * 4 * RHO / (3 * PI)), 2e-4, 0.0);

  /* rp beyond π/2 is clamped */
  double lo2[3];
  run(&p, up, up, PI / 2, lo, es, ek);
  run(&p, up, up, 2.5, lo2, es, ek);
  AP_CHECK_NEAR(lo2[0], lo[0], 0.0);
  run(&p, up, up, INFINITY, lo2, es, ek);
  AP_CHECK_NEAR(lo2[0], lo[0], 0.0);

  /* albedo scales Lo; a vector off unit length by 1e-5 is normalised */
  double alb[3] = { 0.2, 0.5, 0.0 }, nn[3] = { 0, 0, 1.00001 };
  AP_CHECK_EQ_INT(ap_light_point(&p, nn, up, 1.0, alb, lo2, es, ek), AP_OK);
  run(&p, up, up, 1.0, lo, es, ek);
  CHECK_REL(lo2[0], 0.2 * lo[0], 1e-15, 0.0);
  CHECK_REL(lo2[1], 0.5 * lo[1], 1e-15, 0.0);
  AP_CHECK_NEAR(lo2[2], 0.0, 0.0);
}

static void test_nodata_and_params(void)
{
  ap_light_params p;
  ap_light_params_init(&p);
  double lo[3], es[3], ek[3];
  const double nanv[3] = { NAN, 0, 1 }, zero[3] = { 0, 0, 0 }, two[3] = { 0, 0, 2 };
  const double badalb[3] = { 0.5, 1.5, 0.5 }, nanalb[3] = { 0.5, NAN, 0.5 };
  struct {
    const double *n, *b, *a;
    double rp;
  } bad[] = {
    { nanv, up, white, 1.0 }, { zero, up, white, 1.0 }, { two, up, white, 1.0 },
    { up, nanv, white, 1.0 }, { up, zero, white, 1.0 }, { up, up, white, NAN },
    { up, up, white, -0.1 },  { up, up, badalb, 1.0 },  { up, up, nanalb, 1.0 },
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
    AP_CHECK_EQ_INT(ap_light_point(&p, bad[i].n, bad[i].b, bad[i].rp, bad[i].a, lo, es, ek),
                    AP_OK);
    for (int c = 0; c < 3; ++c) {
      AP_CHECK_NAN(lo[c]);
      AP_CHECK_NAN(es[c]);
      AP_CHECK_NAN(ek[c]);
    }
  }
  /* optional outputs */
  AP_CHECK_EQ_INT(ap_light_point(&p, up, up, 1.0, white, lo, NULL, NULL), AP_OK);
  AP_CHECK(lo[0] > 0);
  AP_CHECK_EQ_INT(ap_light_point(&p, up, up, 1.0, white, NULL, es, ek), AP_ERR_NULL_POINTER);
  AP_CHECK_NAN(es[0]);
  AP_CHECK_EQ_INT(ap_light_point(NULL, up, up, 1.0, white, lo, es, ek), AP_ERR_NULL_POINTER);

  /* params validation */
  AP_CHECK_EQ_INT(ap_light_params_validate(NULL), AP_ERR_NULL_POINTER);
  struct {
    int field;
    double value;
  } inval[] = { { 0, NAN }, { 0, 0.5 }, { 1, 0.0 }, { 1, -1.0 }, { 1, 1.6 }, { 1, NAN },
                { 1, 1e-7 }, { 2, -1.0 }, { 2, INFINITY }, { 3, -0.1 }, { 3, NAN },
                { 4, 7 }, { 5, -1 }, { 6, NAN }, { 6, INFINITY }, { 6, 100 } };
  for (size_t i = 0; i < sizeof inval / sizeof inval[0]; ++i) {
    ap_light_params_init(&p);
    double v = inval[i].value;
    switch (inval[i].field) {
    case 0: p.sun[2] = v; break;
    case 1: p.sun_radius = v; break;
    case 2: p.sun_irradiance[1] = v; break;
    case 3: p.sky_radiance[2] = v; break;
    case 4: p.intersection = (ap_light_intersection)(int)v; break;
    case 5: p.lambert = (ap_light_lambert)(int)v; break;
    default: p.exposure = v; break;
    }
    AP_CHECK_EQ_INT(ap_light_params_validate(&p), AP_ERR_INVALID_ARGUMENT);
    AP_CHECK_EQ_INT(ap_light_point(&p, up, up, 1.0, white, lo, es, ek), AP_ERR_INVALID_ARGUMENT);
    AP_CHECK_NAN(lo[0]);
  }
  ap_light_params_init(&p);
  p.sun_radius = PI / 2;
  p.exposure = -64;
  p.sun_irradiance[0] = 0;
  AP_CHECK_EQ_INT(ap_light_params_validate(&p), AP_OK);
}

static void test_display(void)
{
  AP_CHECK_NEAR(ap_light_tonemap(0.0), 0.0, 0.0);
  AP_CHECK_NEAR(ap_light_tonemap(1.0), 0.6321205588285577, 1e-16);
  AP_CHECK_NEAR(ap_light_tonemap(INFINITY), 1.0, 0.0);
  AP_CHECK_NAN(ap_light_tonemap(NAN));
  AP_CHECK_NEAR(ap_light_srgb_encode(0.0), 0.0, 0.0);
  AP_CHECK_NEAR(ap_light_srgb_encode(0.001), 0.01292, 1e-17);
  AP_CHECK_NEAR(ap_light_srgb_encode(0.2), 0.48452920448170694, 1e-15);
  AP_CHECK_NEAR(ap_light_srgb_encode(0.5), 0.7353569830524495, 1e-15);
  AP_CHECK_NEAR(ap_light_srgb_encode(1.0), 1.0, 1e-15);
  AP_CHECK_NEAR(ap_light_srgb_encode(2.0), 1.0, 1e-15);
  AP_CHECK_NEAR(ap_light_srgb_encode(-1.0), 0.0, 0.0);
  AP_CHECK_NAN(ap_light_srgb_encode(NAN));
  /* the two branches meet at 0.0031308 (0.040449936 vs 0.0404499075) */
  double lo = ap_light_srgb_encode(0.0031308), hi = ap_light_srgb_encode(nextafter(0.0031308, 1.0));
  AP_CHECK_NEAR(lo, 0.040449936, 1e-17);
  AP_CHECK_NEAR(hi, 0.04044990748269014, 1e-15);
  AP_CHECK_NEAR(lo, hi, 3e-8);
  AP_CHECK_EQ_INT(ap_light_display8(0.0, 0.0), 0);
  AP_CHECK_EQ_INT(ap_light_display8(INFINITY, 0.0), 255);
  AP_CHECK_EQ_INT(ap_light_display8(NAN, 0.0), 0);
  AP_CHECK_EQ_INT(ap_light_display8(1e30, -64.0), 255);
  AP_CHECK_EQ_INT(ap_light_display8(log(2.0), 0.0), 188); /* t = 0.5: 187.516 */
  AP_CHECK_EQ_INT(ap_light_display8(4 * log(2.0), -2.0), 188);
  AP_CHECK_EQ_INT(ap_light_display8(-log(1 - 0.2), 0.0), 124); /* 123.555 */
  /* defaults: albedo 0.3, flat ground, sun at 45°: Lo = 0.3/π (1000 sin 45° + 30 π) */
  ap_light_params p;
  ap_light_params_init(&p);
  const double a3[3] = { 0.3, 0.3, 0.3 };
  double lo3[3];
  ap_light_point(&p, up, up, PI / 2, a3, lo3, NULL, NULL);
  CHECK_REL(lo3[0], 0.3 / PI * (1000 * sqrt(0.5) + 30 * PI), 1e-5, 0.0);
  AP_CHECK_EQ_INT(ap_light_display8(lo3[0], p.exposure), 218);
}

static void test_batch(void)
{
  ap_light_params p;
  ap_light_params_init(&p);
  p.sun_radius = 2 * DEG;
  enu(1.0, 40 * DEG, p.sun);
  enum { N = 7 };
  float normals[3 * N], bent[3 * N], rp[N], albedo[4 * N], lo[3 * N];
  unsigned char rgb[3 * N];
  for (int k = 0; k < N; ++k) {
    double nv[3], bv[3];
    enu(0.5 * k, PI / 2 - 0.1 * k, nv);
    enu(1.0 + 0.2 * k, PI / 2 - 0.05 * k, bv);
    for (int i = 0; i < 3; ++i) {
      normals[3 * k + i] = (float)nv[i];
      bent[3 * k + i] = (float)bv[i];
      albedo[4 * k + i] = 0.1f * (float)(k + i);
    }
    albedo[4 * k + 3] = 1.0f;
    rp[k] = 0.3f + 0.15f * (float)k;
  }
  rp[3] = NAN; /* nodata */
  for (int m = 0; m < 4; ++m) {
    p.intersection = (m & 1) ? AP_LIGHT_SMOOTHSTEP : AP_LIGHT_EXACT;
    p.lambert = (m & 2) ? AP_LIGHT_CENTROID : AP_LIGHT_EXACTCAP;
    for (int stride = 0; stride <= 4; stride += 4) {
      AP_CHECK_EQ_INT(ap_light_points(&p, N, normals, bent, rp, albedo, (size_t)stride, lo, rgb),
                      AP_OK);
      for (int k = 0; k < N; ++k) {
        double nv[3], bv[3], a[3], ref[3];
        for (int i = 0; i < 3; ++i) {
          nv[i] = normals[3 * k + i];
          bv[i] = bent[3 * k + i];
          a[i] = albedo[stride * k + i];
        }
        ap_light_point(&p, nv, bv, rp[k], a, ref, NULL, NULL);
        for (int i = 0; i < 3; ++i) {
          if (k == 3) {
            AP_CHECK_NAN(lo[3 * k + i]);
            AP_CHECK_EQ_INT(rgb[3 * k + i], 0);
          } else {
            AP_CHECK_NEAR(lo[3 * k + i], (float)ref[i], 0.0);
            AP_CHECK_EQ_INT(rgb[3 * k + i], ap_light_display8(ref[i], p.exposure));
          }
        }
      }
    }
  }
  /* a split gives the same bytes */
  unsigned char rgb2[3 * N];
  ap_light_points(&p, 3, normals, bent, rp, albedo, 4, NULL, rgb2);
  ap_light_points(&p, N - 3, normals + 9, bent + 9, rp + 3, albedo + 12, 4, NULL, rgb2 + 9);
  ap_light_points(&p, N, normals, bent, rp, albedo, 4, NULL, rgb);
  AP_CHECK(memcmp(rgb, rgb2, sizeof rgb) == 0);
  /* errors */
  AP_CHECK_EQ_INT(ap_light_points(NULL, N, normals, bent, rp, albedo, 3, lo, rgb),
                  AP_ERR_NULL_POINTER);
  AP_CHECK_EQ_INT(ap_light_points(&p, N, NULL, bent, rp, albedo, 3, lo, rgb), AP_ERR_NULL_POINTER);
  AP_CHECK_EQ_INT(ap_light_points(&p, 0, NULL, NULL, NULL, NULL, 3, NULL, NULL), AP_OK);
  /* sizes whose bytes overflow: refused before anything is read */
  AP_CHECK_EQ_INT(ap_light_points(&p, SIZE_MAX / 8, normals, bent, rp, albedo, 3, lo, rgb),
                  AP_ERR_SIZE_OVERFLOW);
  AP_CHECK_EQ_INT(ap_light_points(&p, 2, normals, bent, rp, albedo, SIZE_MAX / 2, lo, rgb),
                  AP_ERR_SIZE_OVERFLOW);
  AP_CHECK_EQ_INT(ap_light_points(&p, N, normals, bent, rp, albedo, 2, lo, rgb),
                  AP_ERR_INVALID_ARGUMENT);
  AP_CHECK_EQ_INT(ap_light_points(&p, 2, normals, bent, rp, albedo, 3, normals + 3, NULL),
                  AP_ERR_OVERLAP);
  AP_CHECK_EQ_INT(ap_light_points(&p, 2, normals, bent, rp, albedo, 3, lo,
                                  (unsigned char *)(void *)(lo + 2)),
                  AP_ERR_OVERLAP);
  p.sun_radius = 0.0;
  AP_CHECK_EQ_INT(ap_light_points(&p, N, normals, bent, rp, albedo, 3, lo, rgb),
                  AP_ERR_INVALID_ARGUMENT);
}

/* The sky table: a table whose value is a known function of (azimuth index, elevation,
 * radius) gives that function at the nodes, trilinear blends between them, wraps around in
 * azimuth; a constant table reproduces the uniform sky exactly; bad tables are refused. */
static void test_sky_table(void)
{
  enum { NA = 8, NE = 5, NR = 4 };
  static float table[NA * NE * NR * 3];
  for (int k = 0; k < NR; ++k) {
    for (int j = 0; j < NE; ++j) {
      for (int i = 0; i < NA; ++i) {
        float *v = &table[(((size_t)k * NE + (size_t)j) * NA + (size_t)i) * 3];
        v[0] = (float)(10 * i); /* R: azimuth index */
        v[1] = (float)(100 + 20 * j); /* G: linear in elevation */
        v[2] = (float)(50 + 7 * k); /* B: linear in radius */
      }
    }
  }
  ap_light_params p;
  ap_light_params_init(&p);
  p.sky_table = table;
  p.sky_table_size[0] = NA;
  p.sky_table_size[1] = NE;
  p.sky_table_size[2] = NR;
  AP_CHECK_EQ_INT(ap_light_params_validate(&p), AP_OK);
  double rgb[3];
  /* a node: azimuth of cell 2 = (2.5) 45 deg = 112.5 deg, elevation node 3 = 67.5 deg,
   * radius node 2 = 60 deg */
  const double az = 112.5 * PI / 180, el = 67.5 * PI / 180;
  const double b[3] = { cos(el) * sin(az), cos(el) * cos(az), sin(el) };
  ap_light_sky_lookup(&p, b, 60.0 * PI / 180, rgb);
  AP_CHECK_NEAR(rgb[0], 20.0, 1e-9);
  AP_CHECK_NEAR(rgb[1], 160.0, 1e-9);
  AP_CHECK_NEAR(rgb[2], 64.0, 1e-9);
  /* halfway in elevation and radius: linear quantities interpolate exactly */
  const double el2 = 56.25 * PI / 180;
  const double b2[3] = { cos(el2) * sin(az), cos(el2) * cos(az), sin(el2) };
  ap_light_sky_lookup(&p, b2, 45.0 * PI / 180, rgb);
  AP_CHECK_NEAR(rgb[1], 150.0, 1e-9);
  AP_CHECK_NEAR(rgb[2], 60.5, 1e-9);
  /* azimuth 0 lies halfway between the last cell (337.5) and the first (22.5): wraps */
  const double b3[3] = { 0.0, cos(el), sin(el) };
  ap_light_sky_lookup(&p, b3, 0.5, rgb);
  AP_CHECK_NEAR(rgb[0], 0.5 * (70.0 + 0.0), 1e-9);
  /* below the horizon and beyond 90 deg: clamped to the edge nodes */
  const double b4[3] = { 0.0, 1.0, -0.5 };
  ap_light_sky_lookup(&p, b4, 3.0, rgb);
  AP_CHECK_NEAR(rgb[1], 100.0, 1e-9);
  AP_CHECK_NEAR(rgb[2], 71.0, 1e-9);
  /* sizes out of range (the defaults are 0: a division by zero before) give NaN */
  {
    ap_light_params q = p;
    const int sizes[][3] = { { 0, 0, 0 }, { NA, 1, NR }, { NA, NE, 1 }, { 3, NE, NR },
                             { 257, NE, NR } };
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; ++k) {
      memcpy(q.sky_table_size, sizes[k], sizeof q.sky_table_size);
      rgb[0] = rgb[1] = rgb[2] = 1.0;
      ap_light_sky_lookup(&q, b, 0.5, rgb);
      AP_CHECK_NAN(rgb[0]);
      AP_CHECK_NAN(rgb[2]);
      AP_CHECK_EQ_INT(ap_light_params_validate(&q), AP_ERR_INVALID_ARGUMENT);
    }
  }
  /* a constant table gives exactly the uniform sky's light */
  static float flat[NA * NE * NR * 3];
  for (size_t q = 0; q < sizeof(flat) / sizeof(flat[0]); ++q) {
    flat[q] = 30.0f;
  }
  ap_light_params c;
  ap_light_params_init(&c);
  ap_light_params t = c;
  t.sky_table = flat;
  t.sky_table_size[0] = NA;
  t.sky_table_size[1] = NE;
  t.sky_table_size[2] = NR;
  const double n[3] = { 0.2, 0.1, sqrt(1 - 0.05) }, bb[3] = { -0.1, 0.3, sqrt(1 - 0.1) };
  const double albedo[3] = { 0.5, 0.5, 0.5 };
  double lo1[3], lo2[3];
  AP_CHECK_EQ_INT(ap_light_point(&c, n, bb, 0.9, albedo, lo1, NULL, NULL), AP_OK);
  AP_CHECK_EQ_INT(ap_light_point(&t, n, bb, 0.9, albedo, lo2, NULL, NULL), AP_OK);
  AP_CHECK_NEAR(lo2[0], lo1[0], 1e-12 * lo1[0]);
  /* bad tables */
  t.sky_table_size[0] = 3;
  AP_CHECK_EQ_INT(ap_light_params_validate(&t), AP_ERR_INVALID_ARGUMENT);
  t.sky_table_size[0] = NA;
  flat[5] = -1.0f;
  AP_CHECK_EQ_INT(ap_light_params_validate(&t), AP_ERR_INVALID_ARGUMENT);
  flat[5] = NAN;
  AP_CHECK_EQ_INT(ap_light_params_validate(&t), AP_ERR_INVALID_ARGUMENT);
}

int main(int argc, char **argv)
{
  verbose = argc > 1 && strcmp(argv[1], "-v") == 0;
  AP_TEST_RUN(test_area_table);
  AP_TEST_RUN(test_area_float);
  AP_TEST_RUN(test_centroid_float);
  AP_TEST_RUN(test_cap_cosine);
  AP_TEST_RUN(test_lens_moment);
  AP_TEST_RUN(test_model_scenes);
  AP_TEST_RUN(test_nodata_and_params);
  AP_TEST_RUN(test_display);
  AP_TEST_RUN(test_batch);
  AP_TEST_RUN(test_sky_table);
  AP_TEST_MAIN_END();
}
