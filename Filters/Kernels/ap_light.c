/* SPDX-License-Identifier: BSD-3-Clause */
/* Sun-and-sky lighting of a terrain point from its aperture; the model, its formulas and
 * sources are in ap_light.h. The "shader core" section is the code the GLSL port mirrors. */
#include "ap_light.h"
#include "ap_vec.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#define PI 3.14159265358979323846
#define HALF_PI 1.57079632679489661923
#define SUN_RADIUS_DEG 0.26667 /* SPA's SUN_RADIUS; ALGORITHMS.md conventions */

/* ---------------------------------------------------------------------------------------------
 * Shader core: double here, float in GLSL, same operations. No domain checks (callers do them).
 * ------------------------------------------------------------------------------------------- */

/* Ω(r) = 2π(1 − cos r) = 4π sin²(r/2). */
static double cap_area(double r)
{
  double h = sin(0.5 * r);
  return 4.0 * PI * h * h;
}

/* Case of §1.1 for radii r1, r2 and axis distance d (in this order of tests). */
static int overlap_case(double r1, double r2, double d)
{
  if (d <= fabs(r1 - r2)) {
    return AP_LIGHT_CONTAINED;
  }
  if (d >= r1 + r2) {
    return AP_LIGHT_DISJOINT;
  }
  if (d >= 2.0 * PI - r1 - r2) {
    return AP_LIGHT_COVERS_SPHERE;
  }
  return AP_LIGHT_PARTIAL;
}

/* Partial overlap only: angles α1, α2 of the lens at the two axes (half-angle formulas) and the
 * spherical excess E of the triangle axis 1 – axis 2 – crossing point (L'Huilier). */
static void lens_angles(double r1, double r2, double d, double *a1, double *a2, double *excess)
{
  double s = 0.5 * (r1 + r2 + d);
  double k = sqrt(fmax(0.0, sin(s - r1) * sin(s - r2) * sin(s - d) / sin(s)));
  *a1 = 2.0 * atan2(k, sin(s - r2));
  *a2 = 2.0 * atan2(k, sin(s - r1));
  *excess = 4.0 * atan(sqrt(fmax(0.0, tan(0.5 * s) * tan(0.5 * (s - r1)) *
                                        tan(0.5 * (s - r2)) * tan(0.5 * (s - d)))));
}

/* ALGORITHMS.md (1.2): exact area, all four cases. */
static double intersection_exact(double r1, double r2, double d)
{
  int c = overlap_case(r1, r2, d);
  if (c == AP_LIGHT_CONTAINED) {
    return cap_area(fmin(r1, r2));
  }
  if (c == AP_LIGHT_DISJOINT) {
    return 0.0;
  }
  if (c == AP_LIGHT_COVERS_SPHERE) {
    return cap_area(r1) + cap_area(r2) - 4.0 * PI;
  }
  double a1, a2, e;
  lens_angles(r1, r2, d, &a1, &a2, &e);
  double h1 = sin(0.5 * r1), h2 = sin(0.5 * r2);
  return fmax(0.0, 4.0 * a1 * h1 * h1 + 4.0 * a2 * h2 * h2 - 2.0 * e);
}

/* Oat & Sander 2007 §3.2 smoothstep approximation (ALGORITHMS.md §1.4). */
static double intersection_smoothstep(double r1, double r2, double d)
{
  double rmin = fmin(r1, r2), diff = fabs(r1 - r2);
  double amin = cap_area(rmin);
  if (d <= diff) {
    return amin;
  }
  if (d >= r1 + r2) {
    return 0.0;
  }
  double x = 1.0 - (d - diff) / (r1 + r2 - diff);
  return amin * x * x * (3.0 - 2.0 * x);
}

/* a − sin a for a lens angle a in [0, π] with its sine: below 0.5, where the difference
 * cancels, the series a³/6 (1 − a²/(4·5) (1 − a²/(6·7) (...))) to double precision (the
 * shader's apAngleLessSine stops three terms earlier, at float's). */
static double angle_less_sine(double a, double sin_a)
{
  if (a >= 0.5) {
    return a - sin_a;
  }
  double q = a * a, sum = 1.0;
  for (int k = 8; k >= 2; --k) {
    sum = 1.0 - q / ((2.0 * k) * (2.0 * k + 1.0)) * sum;
  }
  return a * q / 6.0 * sum;
}

/* ALGORITHMS.md (1.4): first moment of the lens (partial overlap, sin d > 0), from the lens
 * angles a1, a2 of lens_angles; cd = cos d, sd = sin d, d of the unit axes c1, c2. Taken about
 * the smaller cap's axis (ap_light.h, 3), so that no term is larger than the lens. */
static void lens_moment_partial(double r1, double r2, double a1, double a2, const double c1[3],
                                const double c2[3], double cd, double sd, double d, double B[3])
{
  int one = r1 <= r2; /* cap 1 is the smaller: the moment about c1 */
  double rs = one ? r1 : r2, ro = one ? r2 : r1, as = one ? a1 : a2, ao = one ? a2 : a1;
  const double *cs = one ? c1 : c2, *co = one ? c2 : c1;
  double hs = sin(0.5 * rs), srs = sin(rs), sro = sin(ro), sao = sin(ao);
  double dif = sin(0.5 * (ro - d)), sum = sin(0.5 * (ro + d)), cos_sum = cos(0.5 * (ro + d));
  double ks = srs * as * srs, kt = 2.0 * srs * hs * hs * sin(as);
  double ko = sro * (angle_less_sine(ao, sao) * sro + 2.0 * sao * cos_sum * dif);
  double kto = sro * 2.0 * sao * sum * dif;
  for (int i = 0; i < 3; ++i) {
    double ts = (co[i] - cd * cs[i]) / sd; /* tangent at cs toward co */
    double to = (cs[i] - cd * co[i]) / sd; /* tangent at co toward cs */
    B[i] = ks * cs[i] + kt * ts + ko * co[i] + kto * to;
  }
}

/* ALGORITHMS.md §6.1 (Snyder 1996; Lagarde & de Rousiers 2014): ∫_cap max(0, n·ω) dω for a cap
 * of radius σ <= π/2, cos_t = n·axis in [−1, 1], sin2s = sin²σ. */
static double cap_cosine_integral(double cos_t, double sin2s)
{
  if (cos_t * cos_t >= sin2s) {
    return PI * sin2s * fmax(cos_t, 0.0); /* the cap lies wholly on one side of the plane */
  }
  double sin_t = sqrt(fmax(0.0, 1.0 - cos_t * cos_t));
  double x = sqrt(fmax(0.0, 1.0 / sin2s - 1.0)); /* cot σ; 0 for a hemisphere */
  double y = clamp1(-x * cos_t / sin_t);
  double sy = sin_t * sqrt(fmax(0.0, 1.0 - y * y));
  double t = (x > 0.0) ? atan(sy / x) : HALF_PI; /* guard x = 0 (GLSL has no infinity) */
  return fmax(0.0, (cos_t * acos(y) - x * sy) * sin2s + t);
}

/* What the shader receives as uniforms. */
typedef struct light_setup {
  double s[3];           /* unit sun direction */
  double rl;             /* sun cap radius */
  double sin2_rl;        /* sin² rl */
  double omega_l;        /* Ω_l = 4π sin²(rl/2) */
  double l_sun[3];       /* L_sun = Esun / (π sin² rl) */
  double l_sky[3];       /* Lsky */
  int intersection;      /* ap_light_intersection */
  int lambert;           /* ap_light_lambert */
  double exposure_scale; /* 2^EV */
  const ap_light_params *params; /* for the sky table, when there is one */
} light_setup;

/* Cosine-weighted visible sun S (sr) and aperture cosine integral C_sky for unit n, b. */
static void light_terms(const light_setup *u, const double n[3], const double b[3], double rp,
                        double *S_out, double *C_sky)
{
  const double *s = u->s;
  double rl = u->rl;
  rp = fmin(rp, HALF_PI);

  /* 2. Axis distance and visible sun area. */
  double bxs[3];
  cross3(b, s, bxs);
  double sd = sqrt(dot3(bxs, bxs)); /* sin d */
  double cd = dot3(b, s);           /* cos d */
  double d = atan2(sd, cd);
  int ov = overlap_case(rp, rl, d);
  double area = 0.0;
  if (rp > 0.0) {
    area = (u->intersection == AP_LIGHT_EXACT) ? intersection_exact(rp, rl, d)
                                               : intersection_smoothstep(rp, rl, d);
  }

  /* 3. Lambert term. */
  double S = 0.0;
  if (area > 0.0) {
    if (u->lambert == AP_LIGHT_CENTROID) {
      double c[3] = { 0.0, 0.0, 0.0 };
      if (ov == AP_LIGHT_CONTAINED || sd <= 0.0) {
        /* Concentric or nested: the centroid is the smaller cap's axis. */
        const double *axis = (rp <= rl) ? b : s;
        c[0] = axis[0];
        c[1] = axis[1];
        c[2] = axis[2];
      } else if (ov == AP_LIGHT_PARTIAL) {
        double a_p, a_l, e, B[3];
        lens_angles(rp, rl, d, &a_p, &a_l, &e);
        lens_moment_partial(rp, rl, a_p, a_l, b, s, cd, sd, d, B);
        double len = sqrt(dot3(B, B));
        if (len > 0.0) {
          c[0] = B[0] / len;
          c[1] = B[1] / len;
          c[2] = B[2] / len;
        }
      }
      S = area * fmax(0.0, dot3(n, c));
    } else {
      S = cap_cosine_integral(clamp1(dot3(n, s)), u->sin2_rl) * area / u->omega_l;
    }
  }

  /* 4. The aperture's cosine integral (the sky takes it less S). */
  double sp = sin(rp);
  *S_out = S;
  *C_sky = cap_cosine_integral(clamp1(dot3(n, b)), sp * sp);
}

/* 5. Irradiance components and outgoing radiance of a point with unit n, b. */
static void light_point_core(const light_setup *u, const double n[3], const double b[3],
                             double rp, const double albedo[3], double lo[3], double e_sun[3],
                             double e_sky[3])
{
  double S, C;
  light_terms(u, n, b, rp, &S, &C);
  double sky = fmax(0.0, C - S);
  double l_sky[3] = { u->l_sky[0], u->l_sky[1], u->l_sky[2] };
  if (u->params && u->params->sky_table) {
    ap_light_sky_lookup(u->params, b, rp, l_sky); /* the sky over this aperture */
  }
  for (int i = 0; i < 3; ++i) {
    e_sun[i] = u->l_sun[i] * S;
    e_sky[i] = l_sky[i] * sky;
    lo[i] = albedo[i] / PI * (e_sun[i] + e_sky[i]);
  }
}

static double tonemap(double x)
{
  return 1.0 - exp(-x);
}

static double srgb_encode(double t)
{
  if (t < 0.0) {
    t = 0.0;
  }
  if (t > 1.0) {
    t = 1.0;
  }
  return (t <= 0.0031308) ? 12.92 * t : 1.055 * pow(t, 1.0 / 2.4) - 0.055;
}

static unsigned char display8(double lo, double exposure_scale)
{
  double v = srgb_encode(tonemap(lo * exposure_scale));
  if (!(v >= 0.0)) {
    return 0; /* NaN (nodata) */
  }
  return (unsigned char)round(255.0 * fmin(v, 1.0));
}

/* ---------------------------------------------------------------------------------------------
 * Checks and setup
 * ------------------------------------------------------------------------------------------- */

/* Copy v / |v| into u when v is finite and unit within AP_LIGHT_UNIT_TOLERANCE; else 0. */
static int unit_vector(const double v[3], double u[3])
{
  if (!isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2])) {
    return 0;
  }
  double q = dot3(v, v);
  if (!(fabs(q - 1.0) <= AP_LIGHT_UNIT_TOLERANCE)) {
    return 0;
  }
  double len = sqrt(q);
  u[0] = v[0] / len;
  u[1] = v[1] / len;
  u[2] = v[2] / len;
  return 1;
}

static int finite_nonnegative3(const double v[3])
{
  for (int i = 0; i < 3; ++i) {
    if (!(isfinite(v[i]) && v[i] >= 0.0)) {
      return 0;
    }
  }
  return 1;
}

static int in_domain(double r1, double r2, double d)
{
  return r1 >= 0.0 && r1 <= PI && r2 >= 0.0 && r2 <= PI && d >= 0.0 && d <= PI;
}

static void set_nan(double *v, int count)
{
  for (int i = 0; i < count; ++i) {
    v[i] = NAN;
  }
}

void ap_light_params_init(ap_light_params *p)
{
  if (!p) {
    return;
  }
  p->sun[0] = -0.5;
  p->sun[1] = 0.5;
  p->sun[2] = sqrt(0.5);
  p->sun_radius = SUN_RADIUS_DEG * PI / 180.0;
  for (int i = 0; i < 3; ++i) {
    p->sun_irradiance[i] = 1000.0;
    p->sky_radiance[i] = 30.0;
  }
  p->intersection = AP_LIGHT_EXACT;
  p->lambert = AP_LIGHT_EXACTCAP;
  p->exposure = -6.0;
  p->sky_table = NULL;
  p->sky_table_size[0] = p->sky_table_size[1] = p->sky_table_size[2] = 0;
}

/* The sky table's sizes within their ranges (ap_light_params.sky_table_size). */
static int sky_table_sizes_ok(const ap_light_params *p)
{
  const int na = p->sky_table_size[0], ne = p->sky_table_size[1], nr = p->sky_table_size[2];
  return na >= 4 && na <= 256 && ne >= 2 && ne <= 256 && nr >= 2 && nr <= 256;
}

void ap_light_sky_lookup(const ap_light_params *p, const double b[3], double rp, double rgb[3])
{
  if (!p || !b || !rgb) {
    return;
  }
  if (!p->sky_table) {
    rgb[0] = p->sky_radiance[0];
    rgb[1] = p->sky_radiance[1];
    rgb[2] = p->sky_radiance[2];
    return;
  }
  const int na = p->sky_table_size[0], ne = p->sky_table_size[1], nr = p->sky_table_size[2];
  if (!isfinite(b[0]) || !isfinite(b[1]) || !isfinite(b[2]) || isnan(rp) ||
      !sky_table_sizes_ok(p)) {
    set_nan(rgb, 3);
    return;
  }
  double az = atan2(b[0], b[1]);
  if (az < 0.0) {
    az += 2.0 * PI;
  }
  double el = asin(fmin(1.0, fmax(-1.0, b[2] / sqrt(dot3(b, b)))));
  el = fmin(HALF_PI, fmax(0.0, el));
  const double r = fmin(HALF_PI, fmax(0.0, rp));
  /* azimuth: cell-centred nodes, wrapping; elevation and radius: nodes at both ends */
  const double fa = az / (2.0 * PI) * na - 0.5;
  const double fe = el / HALF_PI * (ne - 1), fr = r / HALF_PI * (nr - 1);
  const double a0f = floor(fa);
  const int e0 = (int)fmin(floor(fe), (double)(ne - 2));
  const int r0 = (int)fmin(floor(fr), (double)(nr - 2));
  const double wa = fa - a0f, we = fe - e0, wr = fr - r0;
  const int a0 = (((int)a0f % na) + na) % na, a1 = (a0 + 1) % na;
  for (int c = 0; c < 3; ++c) {
    double v = 0.0;
    for (int k = 0; k < 2; ++k) {
      for (int j = 0; j < 2; ++j) {
        const size_t row = ((size_t)(r0 + k) * (size_t)ne + (size_t)(e0 + j)) * (size_t)na;
        const double lo = p->sky_table[(row + (size_t)a0) * 3 + (size_t)c];
        const double hi = p->sky_table[(row + (size_t)a1) * 3 + (size_t)c];
        v += (k ? wr : 1.0 - wr) * (j ? we : 1.0 - we) * ((1.0 - wa) * lo + wa * hi);
      }
    }
    rgb[c] = v;
  }
}

ap_status ap_light_params_validate(const ap_light_params *p)
{
  if (!p) {
    return AP_ERR_NULL_POINTER;
  }
  double s[3];
  if (!unit_vector(p->sun, s)) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  if (!(p->sun_radius >= AP_LIGHT_MIN_SUN_RADIUS && p->sun_radius <= HALF_PI)) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  if (!finite_nonnegative3(p->sun_irradiance) || !finite_nonnegative3(p->sky_radiance)) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  if (p->intersection != AP_LIGHT_EXACT && p->intersection != AP_LIGHT_SMOOTHSTEP) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  if (p->lambert != AP_LIGHT_CENTROID && p->lambert != AP_LIGHT_EXACTCAP) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  if (!(fabs(p->exposure) <= AP_LIGHT_MAX_EXPOSURE)) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  if (p->sky_table) {
    if (!sky_table_sizes_ok(p)) {
      return AP_ERR_INVALID_ARGUMENT;
    }
    const size_t n = (size_t)p->sky_table_size[0] * (size_t)p->sky_table_size[1] *
                     (size_t)p->sky_table_size[2] * 3;
    for (size_t i = 0; i < n; ++i) {
      if (!(isfinite(p->sky_table[i]) && p->sky_table[i] >= 0.0f)) {
        return AP_ERR_INVALID_ARGUMENT;
      }
    }
  }
  return AP_OK;
}

/* Only after a successful ap_light_params_validate. */
static void setup_from_params(const ap_light_params *p, light_setup *u)
{
  (void)unit_vector(p->sun, u->s);
  u->rl = p->sun_radius;
  double sl = sin(u->rl), hl = sin(0.5 * u->rl);
  u->sin2_rl = sl * sl;
  u->omega_l = 4.0 * PI * hl * hl;
  for (int i = 0; i < 3; ++i) {
    u->l_sun[i] = p->sun_irradiance[i] / (PI * u->sin2_rl);
    u->l_sky[i] = p->sky_radiance[i];
  }
  u->intersection = (int)p->intersection;
  u->lambert = (int)p->lambert;
  u->exposure_scale = exp2(p->exposure);
  u->params = p;
}

/* One point with the nodata checks of ap_light.h; returns 0 (outputs NaN) for nodata. */
static int light_point(const light_setup *u, const double n_in[3], const double b_in[3],
                       double rp, const double albedo[3], double lo[3], double e_sun[3],
                       double e_sky[3])
{
  double n[3], b[3];
  int ok = unit_vector(n_in, n) && unit_vector(b_in, b) && rp >= 0.0;
  for (int i = 0; i < 3; ++i) {
    ok = ok && albedo[i] >= 0.0 && albedo[i] <= 1.0;
  }
  if (!ok) {
    set_nan(lo, 3);
    set_nan(e_sun, 3);
    set_nan(e_sky, 3);
    return 0;
  }
  light_point_core(u, n, b, rp, albedo, lo, e_sun, e_sky);
  return 1;
}

/* ---------------------------------------------------------------------------------------------
 * Public building blocks
 * ------------------------------------------------------------------------------------------- */

double ap_light_cap_area(double r)
{
  return (r >= 0.0 && r <= PI) ? cap_area(r) : NAN;
}

int ap_light_cap_overlap(double r1, double r2, double d)
{
  return in_domain(r1, r2, d) ? overlap_case(r1, r2, d) : -1;
}

double ap_light_cap_intersection_exact(double r1, double r2, double d)
{
  return in_domain(r1, r2, d) ? intersection_exact(r1, r2, d) : NAN;
}

double ap_light_cap_intersection_smoothstep(double r1, double r2, double d)
{
  return in_domain(r1, r2, d) ? intersection_smoothstep(r1, r2, d) : NAN;
}

int ap_light_lens_moment(double r1, double r2, const double c1[3], const double c2[3],
                         double B[3])
{
  if (!B) {
    return -1;
  }
  if (!c1 || !c2 || !(r1 >= 0.0 && r1 <= PI && r2 >= 0.0 && r2 <= PI) ||
      !isfinite(dot3(c1, c1)) || !isfinite(dot3(c2, c2))) {
    set_nan(B, 3);
    return -1;
  }
  double x[3];
  cross3(c1, c2, x);
  double sd = sqrt(dot3(x, x)), cd = dot3(c1, c2);
  double d = atan2(sd, cd);
  int c = overlap_case(r1, r2, d);
  if (c == AP_LIGHT_PARTIAL && sd > 0.0) {
    double a1, a2, e;
    lens_angles(r1, r2, d, &a1, &a2, &e);
    lens_moment_partial(r1, r2, a1, a2, c1, c2, cd, sd, d, B);
    return c;
  }
  /* Cap moments π sin² r · c: the smaller cap (contained, or concentric), both (union). */
  double s1 = sin(r1), s2 = sin(r2);
  double k1 = PI * s1 * s1, k2 = PI * s2 * s2;
  if (c == AP_LIGHT_DISJOINT) {
    k1 = k2 = 0.0;
  } else if (c != AP_LIGHT_COVERS_SPHERE) {
    c = AP_LIGHT_CONTAINED;
    if (r1 <= r2) {
      k2 = 0.0;
    } else {
      k1 = 0.0;
    }
  }
  for (int i = 0; i < 3; ++i) {
    B[i] = k1 * c1[i] + k2 * c2[i];
  }
  return c;
}

int ap_light_lens_centroid(double r1, double r2, const double c1[3], const double c2[3],
                           double dir[3])
{
  if (!dir) {
    return -1;
  }
  double B[3];
  int c = ap_light_lens_moment(r1, r2, c1, c2, B);
  if (c < 0) {
    set_nan(dir, 3);
    return -1;
  }
  dir[0] = dir[1] = dir[2] = 0.0;
  if (c == AP_LIGHT_CONTAINED) {
    const double *axis = (r1 <= r2) ? c1 : c2; /* also for r = 0, where B = 0 */
    B[0] = axis[0];
    B[1] = axis[1];
    B[2] = axis[2];
  }
  double len = sqrt(dot3(B, B));
  if (!(len > 0.0)) {
    return 0;
  }
  for (int i = 0; i < 3; ++i) {
    dir[i] = B[i] / len;
  }
  return 1;
}

double ap_light_cap_cosine_integral(double cos_t, double sin2s)
{
  if (isnan(cos_t) || !(sin2s >= 0.0 && sin2s <= 1.0)) {
    return NAN;
  }
  return cap_cosine_integral(clamp1(cos_t), sin2s);
}

/* ---------------------------------------------------------------------------------------------
 * Public model
 * ------------------------------------------------------------------------------------------- */

ap_status ap_light_point(const ap_light_params *p, const double n[3], const double b[3],
                         double rp, const double albedo[3], double Lo[3], double E_sun[3],
                         double E_sky[3])
{
  double tmp_sun[3], tmp_sky[3];
  double *es = E_sun ? E_sun : tmp_sun;
  double *ek = E_sky ? E_sky : tmp_sky;
  ap_status st = (!n || !b || !albedo || !Lo) ? AP_ERR_NULL_POINTER : ap_light_params_validate(p);
  if (st != AP_OK) {
    if (Lo) {
      set_nan(Lo, 3);
    }
    set_nan(es, 3);
    set_nan(ek, 3);
    return st;
  }
  light_setup u;
  setup_from_params(p, &u);
  (void)light_point(&u, n, b, rp, albedo, Lo, es, ek);
  return AP_OK;
}

static int overlaps(const void *a, size_t na, const void *b, size_t nb)
{
  uintptr_t pa = (uintptr_t)a, pb = (uintptr_t)b;
  return a && b && na > 0 && nb > 0 && pa < pb + nb && pb < pa + na;
}

ap_status ap_light_points(const ap_light_params *p, size_t n, const float *normals,
                          const float *bent, const float *aperture_radius, const float *albedo,
                          size_t albedo_stride, float *radiance, unsigned char *rgb8)
{
  if (!p) {
    return AP_ERR_NULL_POINTER;
  }
  ap_status st = ap_light_params_validate(p);
  if (st != AP_OK) {
    return st;
  }
  if (albedo_stride == 1 || albedo_stride == 2) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  if (n == 0) {
    return AP_OK;
  }
  if (!normals || !bent || !aperture_radius || !albedo) {
    return AP_ERR_NULL_POINTER;
  }
  if (n > SIZE_MAX / (3 * sizeof(float)) ||
      (albedo_stride > 0 && n - 1 > (SIZE_MAX / sizeof(float) - 3) / albedo_stride)) {
    return AP_ERR_SIZE_OVERFLOW;
  }
  size_t vec_bytes = 3 * n * sizeof(float);
  size_t rp_bytes = n * sizeof(float);
  size_t albedo_bytes = ((n - 1) * albedo_stride + 3) * sizeof(float);
  size_t rgb_bytes = 3 * n;
  const void *in[4] = { normals, bent, aperture_radius, albedo };
  size_t in_bytes[4] = { vec_bytes, vec_bytes, rp_bytes, albedo_bytes };
  for (int i = 0; i < 4; ++i) {
    if (overlaps(radiance, vec_bytes, in[i], in_bytes[i]) ||
        overlaps(rgb8, rgb_bytes, in[i], in_bytes[i])) {
      return AP_ERR_OVERLAP;
    }
  }
  if (overlaps(radiance, vec_bytes, rgb8, rgb_bytes)) {
    return AP_ERR_OVERLAP;
  }

  light_setup u;
  setup_from_params(p, &u);
  for (size_t k = 0; k < n; ++k) {
    double nv[3], bv[3], a[3], lo[3], es[3], ek[3];
    const float *ak = albedo + k * albedo_stride;
    for (int i = 0; i < 3; ++i) {
      nv[i] = normals[3 * k + (size_t)i];
      bv[i] = bent[3 * k + (size_t)i];
      a[i] = ak[i];
    }
    (void)light_point(&u, nv, bv, aperture_radius[k], a, lo, es, ek);
    for (int i = 0; i < 3; ++i) {
      if (radiance) {
        radiance[3 * k + (size_t)i] = (float)lo[i];
      }
      if (rgb8) {
        rgb8[3 * k + (size_t)i] = display8(lo[i], u.exposure_scale);
      }
    }
  }
  return AP_OK;
}

/* ---------------------------------------------------------------------------------------------
 * Display
 * ------------------------------------------------------------------------------------------- */

double ap_light_tonemap(double x)
{
  return tonemap(x);
}

double ap_light_srgb_encode(double t)
{
  return isnan(t) ? t : srgb_encode(t);
}

unsigned char ap_light_display8(double Lo, double exposure)
{
  return display8(Lo, exp2(exposure));
}
