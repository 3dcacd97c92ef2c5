/* SPDX-License-Identifier: BSD-3-Clause */
/* Sun and sky radiometry; formulas and sources are in ap_sky.h. */
#include "ap_sky.h"

#include "ap_range.h"
#include "ap_vec.h"

#include <math.h>
#include <stddef.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)
#define SKY_MAGIC 0x41534b59u /* "ASKY": set by ap_sky_prepare */

/* Order of the quadrature about the zenith that normalises the sky to E_h (ap_sky_prepare). */
#define NORM_RINGS 24
#define NORM_SECTORS 96

/* ---------------------------------------------------------------------------------------------
 * Tables (380..780 nm every 10 nm)
 * ------------------------------------------------------------------------------------------- */

/* CIE 1931 2° standard observer x̄, ȳ, z̄ (CIE 15; the 1 nm table sampled every 10 nm). */
static const double cmf[AP_SKY_SPECTRUM_SAMPLES][3] = {
  { 0.001368, 0.000039, 0.006450 }, /* 380 */
  { 0.004243, 0.000120, 0.020050 }, /* 390 */
  { 0.014310, 0.000396, 0.067850 }, /* 400 */
  { 0.043510, 0.001210, 0.207400 }, /* 410 */
  { 0.134380, 0.004000, 0.645600 }, /* 420 */
  { 0.283900, 0.011600, 1.385600 }, /* 430 */
  { 0.348280, 0.023000, 1.747060 }, /* 440 */
  { 0.336200, 0.038000, 1.772110 }, /* 450 */
  { 0.290800, 0.060000, 1.669200 }, /* 460 */
  { 0.195360, 0.090980, 1.287640 }, /* 470 */
  { 0.095640, 0.139020, 0.812950 }, /* 480 */
  { 0.032010, 0.208020, 0.465180 }, /* 490 */
  { 0.004900, 0.323000, 0.272000 }, /* 500 */
  { 0.009300, 0.503000, 0.158200 }, /* 510 */
  { 0.063270, 0.710000, 0.078250 }, /* 520 */
  { 0.165500, 0.862000, 0.042160 }, /* 530 */
  { 0.290400, 0.954000, 0.020300 }, /* 540 */
  { 0.433450, 0.994950, 0.008750 }, /* 550 */
  { 0.594500, 0.995000, 0.003900 }, /* 560 */
  { 0.762100, 0.952000, 0.002100 }, /* 570 */
  { 0.916300, 0.870000, 0.001650 }, /* 580 */
  { 1.026300, 0.757000, 0.001100 }, /* 590 */
  { 1.062200, 0.631000, 0.000800 }, /* 600 */
  { 1.002600, 0.503000, 0.000340 }, /* 610 */
  { 0.854450, 0.381000, 0.000190 }, /* 620 */
  { 0.642400, 0.265000, 0.000050 }, /* 630 */
  { 0.447900, 0.175000, 0.000020 }, /* 640 */
  { 0.283500, 0.107000, 0.000000 }, /* 650 */
  { 0.164900, 0.061000, 0.000000 }, /* 660 */
  { 0.087400, 0.032000, 0.000000 }, /* 670 */
  { 0.046770, 0.017000, 0.000000 }, /* 680 */
  { 0.022700, 0.008210, 0.000000 }, /* 690 */
  { 0.011359, 0.004102, 0.000000 }, /* 700 */
  { 0.005790, 0.002091, 0.000000 }, /* 710 */
  { 0.002899, 0.001047, 0.000000 }, /* 720 */
  { 0.001440, 0.000520, 0.000000 }, /* 730 */
  { 0.000690, 0.000249, 0.000000 }, /* 740 */
  { 0.000332, 0.000120, 0.000000 }, /* 750 */
  { 0.000166, 0.000060, 0.000000 }, /* 760 */
  { 0.000083, 0.000030, 0.000000 }, /* 770 */
  { 0.000042, 0.000015, 0.000000 }, /* 780 */
};

/* Extraterrestrial solar spectrum of Preetham et al. 1999 (their code's solAmplitudes, from
 * Iqbal 1983), 380..750 nm, arbitrary units (only its shape is used); 760..780 nm hold the
 * 750 nm value. */
static const double sun_spectrum[AP_SKY_SPECTRUM_SAMPLES] = {
  165.5, 162.3, 211.2, 258.8, 258.2, 242.3, 267.6, 296.6, 305.4, 300.6, /* 380..470 */
  306.6, 288.3, 287.1, 278.2, 271.0, 272.3, 263.6, 255.0, 250.6, 253.1, /* 480..570 */
  253.5, 251.3, 246.3, 241.7, 236.8, 232.1, 228.2, 223.4, 219.7, 215.3, /* 580..670 */
  211.0, 207.3, 202.4, 198.7, 194.3, 190.7, 186.3, 182.6,               /* 680..750 */
  182.6, 182.6, 182.6                                                   /* 760..780 */
};

/* Ozone absorption coefficient k_o (1/cm), Iqbal 1983 as in Preetham's code: the tabulated
 * values at 450..780 nm; 380..440 nm interpolated linearly between the table's 355 nm (0) and
 * 445 nm (0.003) entries, as that code's table lookup does. */
static const double ozone_k[AP_SKY_SPECTRUM_SAMPLES] = {
  0.003 * 25.0 / 90.0, 0.003 * 35.0 / 90.0, 0.003 * 45.0 / 90.0, 0.003 * 55.0 / 90.0,
  0.003 * 65.0 / 90.0, 0.003 * 75.0 / 90.0, 0.003 * 85.0 / 90.0,           /* 380..440 */
  0.003, 0.006, 0.009, 0.014, 0.021, 0.030, 0.040, 0.048, 0.063, 0.075, /* 450..540 */
  0.085, 0.103, 0.120, 0.120, 0.115, 0.125, 0.120, 0.105, 0.090, 0.079, /* 550..640 */
  0.067, 0.057, 0.048, 0.036, 0.028, 0.023, 0.018, 0.014, 0.011, 0.010, /* 650..740 */
  0.009, 0.007, 0.004, 0.000                                             /* 750..780 */
};

/* XYZ → linear Rec.709 (D65), derived exactly from the primaries and white chromaticities
 * (ap_sky.h); its inverse's middle row is the luminance (0.2126390, 0.7151687, 0.0721923). */
static const double xyz_to_rgb[3][3] = {
  { 3.2409699419, -1.5373831776, -0.4986107603 },
  { -0.9692436363, 1.8759675015, 0.0415550574 },
  { 0.0556300797, -0.2039769589, 1.0569715142 },
};

/* Preetham 1999 Perez coefficients: A..E = c[k][0] T + c[k][1], for Y, x, y. */
static const double perez_coef[3][5][2] = {
  { { 0.1787, -1.4630 }, { -0.3554, 0.4275 }, { -0.0227, 5.3251 }, { 0.1206, -2.5771 },
    { -0.0670, 0.3703 } },
  { { -0.0193, -0.2592 }, { -0.0665, 0.0008 }, { -0.0004, 0.2125 }, { -0.0641, -0.8989 },
    { -0.0033, 0.0452 } },
  { { -0.0167, -0.2608 }, { -0.0950, 0.0092 }, { -0.0079, 0.2102 }, { -0.0441, -1.6537 },
    { -0.0109, 0.0529 } },
};

/* ---------------------------------------------------------------------------------------------
 * Small helpers
 * ------------------------------------------------------------------------------------------- */

static void set_nan(double *v, int n)
{
  if (v) {
    for (int i = 0; i < n; ++i) {
      v[i] = NAN;
    }
  }
}

/* v normalised into u; 0 if v is not finite or has zero length. */
static int unit_vector(const double v[3], double u[3])
{
  if (!isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2])) {
    return 0;
  }
  /* scale first so that tiny and huge vectors neither underflow nor overflow */
  double s = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
  if (!(s > 0.0)) {
    return 0;
  }
  double x = v[0] / s, y = v[1] / s, z = v[2] / s;
  double len = sqrt(x * x + y * y + z * z);
  u[0] = x / len;
  u[1] = y / len;
  u[2] = z / len;
  return 1;
}

static void xyz_rgb(const double xyz[3], double rgb[3])
{
  double x = xyz[0], y = xyz[1], z = xyz[2];
  for (int i = 0; i < 3; ++i) {
    rgb[i] = xyz_to_rgb[i][0] * x + xyz_to_rgb[i][1] * y + xyz_to_rgb[i][2] * z;
  }
}

/* Luminance of linear Rec.709 RGB: the Y row of the inverse of xyz_to_rgb. */
static const double luminance_row[3] = { 0.2126390059, 0.7151686788, 0.0721923154 };

/* Clamp negative components to 0, then rescale so that the luminance is `lum` again. */
static void clamp_rgb(double rgb[3], double lum)
{
  if (rgb[0] >= 0.0 && rgb[1] >= 0.0 && rgb[2] >= 0.0) {
    return;
  }
  for (int i = 0; i < 3; ++i) {
    rgb[i] = fmax(0.0, rgb[i]);
  }
  double l = luminance_row[0] * rgb[0] + luminance_row[1] * rgb[1] + luminance_row[2] * rgb[2];
  if (l > 0.0) {
    double k = lum / l;
    for (int i = 0; i < 3; ++i) {
      rgb[i] *= k;
    }
  }
}

static int in_range(double v, double lo, double hi)
{
  return v >= lo && v <= hi; /* false for NaN */
}

static int zenith_ok(double zenith)
{
  return in_range(zenith, 0.0, PI);
}

/* P_n(z) and P_{n−1}(z) by Bonnet's recurrence. */
static void legendre_pair(int n, double z, double *pn, double *pn1)
{
  double p0 = 1.0, p1 = 0.0;
  for (int k = 1; k <= n; ++k) {
    const double p2 = p1;
    p1 = p0;
    p0 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p2) / k;
  }
  *pn = p0;
  *pn1 = p1;
}

static double legendre(int n, double z)
{
  double pn, pn1;
  legendre_pair(n, z, &pn, &pn1);
  return pn;
}

/* P_n'(z) = n (z P_n − P_{n−1}) / (z² − 1), |z| < 1. */
static double legendre_derivative(int n, double z)
{
  double pn, pn1;
  legendre_pair(n, z, &pn, &pn1);
  return n * (z * pn - pn1) / (z * z - 1.0);
}

/* Gauss–Legendre nodes and weights on [−1, 1], n >= 1 (Newton on P_n from Chebyshev-like
 * starting points; converges to rounding in a few steps). */
static void gauss_legendre(int n, double *x, double *w)
{
  for (int i = 0; i < n; ++i) {
    double z = cos(PI * (i + 0.75) / (n + 0.5));
    double dp = legendre_derivative(n, z);
    for (int it = 0; it < 100; ++it) {
      const double dz = legendre(n, z) / dp;
      z -= dz;
      dp = legendre_derivative(n, z); /* at the new node: the weight needs it converged */
      if (fabs(dz) < 1e-16) {
        break;
      }
    }
    x[i] = z;
    w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
  }
}

/* ---------------------------------------------------------------------------------------------
 * Parameters
 * ------------------------------------------------------------------------------------------- */

void ap_sky_params_init(ap_sky_params *p)
{
  if (!p) {
    return;
  }
  p->model = AP_SKY_PREETHAM;
  p->turbidity = 3.0;
  p->linke_turbidity = 3.0;
  p->earth_sun_distance = 1.0;
  p->site_height = 0.0;
  p->solar_constant = 1361.0;
  p->ozone = 0.35;
  p->diffuse_horizontal = -1.0;
  p->luminous_efficacy = 130.0;
  p->cap_rings = 8;
  p->cap_sectors = 32;
}

ap_status ap_sky_params_validate(const ap_sky_params *p)
{
  if (!p) {
    return AP_ERR_NULL_POINTER;
  }
  return ap_sky_params_invalid(p, NULL, NULL) ? AP_ERR_INVALID_ARGUMENT : AP_OK;
}

const char *ap_sky_params_invalid(const ap_sky_params *p, double *lo, double *hi)
{
  if (!p) {
    return NULL;
  }
  /* each field's range, its ends included unless open (solar_constant's lower end; both of
   * diffuse_horizontal's, which must be finite); the model one of the enumerators, which run
   * from UNIFORM to PREETHAM */
  const ap_range_field fields[] = {
    { "model", (double)p->model, (double)AP_SKY_UNIFORM, (double)AP_SKY_PREETHAM, 0, 0 },
    { "turbidity", p->turbidity, 2.0, 10.0, 0, 0 },
    { "linke_turbidity", p->linke_turbidity, 1.0, 8.0, 0, 0 },
    { "earth_sun_distance", p->earth_sun_distance, 0.9, 1.1, 0, 0 },
    { "site_height", p->site_height, -1000.0, 10000.0, 0, 0 },
    { "solar_constant", p->solar_constant, 0.0, 2000.0, 1, 0 },
    { "ozone", p->ozone, 0.0, 1.0, 0, 0 },
    { "diffuse_horizontal", p->diffuse_horizontal, -INFINITY, INFINITY, 1, 1 },
    { "luminous_efficacy", p->luminous_efficacy, 50.0, 683.0, 0, 0 },
    { "cap_rings", (double)p->cap_rings, 1.0, (double)AP_SKY_MAX_RINGS, 0, 0 },
    { "cap_sectors", (double)p->cap_sectors, (double)AP_SKY_PSI_ORDER, 4096.0, 0, 0 },
  };
  return ap_range_first_outside(fields, sizeof fields / sizeof fields[0], lo, hi);
}

ap_status ap_sky_enu_direction(double azimuth, double elevation, double v[3])
{
  if (!v) {
    return AP_ERR_NULL_POINTER;
  }
  if (!isfinite(azimuth) || !isfinite(elevation)) {
    set_nan(v, 3);
    return AP_ERR_INVALID_ARGUMENT;
  }
  double ce = cos(elevation);
  v[0] = ce * sin(azimuth);
  v[1] = ce * cos(azimuth);
  v[2] = sin(elevation);
  return AP_OK;
}

/* ---------------------------------------------------------------------------------------------
 * Sun
 * ------------------------------------------------------------------------------------------- */

/* Kasten & Young 1989 at sea level; zenith in [0, π/2] radians. */
static double kasten_young(double zenith)
{
  double zd = zenith / DEG;
  return 1.0 / (cos(zenith) + 0.50572 * pow(96.07995 - zd, -1.6364));
}

static double pressure_ratio(double site_height)
{
  return exp(-site_height / 8434.5);
}

ap_status ap_sky_air_mass(double zenith, double site_height, double *air_mass)
{
  if (!air_mass) {
    return AP_ERR_NULL_POINTER;
  }
  if (!zenith_ok(zenith) || !in_range(site_height, -1000.0, 10000.0)) {
    *air_mass = NAN;
    return AP_ERR_INVALID_ARGUMENT;
  }
  *air_mass = zenith > 0.5 * PI ? INFINITY : kasten_young(zenith) * pressure_ratio(site_height);
  return AP_OK;
}

/* Preetham's transmittance exponent coefficients at λ (µm): Rayleigh and aerosol optical
 * thickness per unit air mass. */
static double rayleigh_thickness(double lambda_um)
{
  return 0.008735 * pow(lambda_um, -4.08);
}

static double aerosol_thickness(double lambda_um, double turbidity)
{
  double beta = 0.04608365822050 * turbidity - 0.04586025928522;
  return beta * pow(lambda_um, -1.3);
}

ap_status ap_sky_preetham_transmittance(double wavelength_nm, double air_mass, double turbidity,
                                        double *tau)
{
  if (!tau) {
    return AP_ERR_NULL_POINTER;
  }
  if (!(wavelength_nm > 0.0 && isfinite(wavelength_nm)) || !(air_mass >= 0.0) ||
      !in_range(turbidity, 2.0, 10.0)) {
    *tau = NAN;
    return AP_ERR_INVALID_ARGUMENT;
  }
  double l = wavelength_nm * 1e-3;
  double k = rayleigh_thickness(l) + aerosol_thickness(l, turbidity);
  *tau = isinf(air_mass) ? 0.0 : exp(-air_mass * k);
  return AP_OK;
}

/* ESRA Rayleigh optical thickness δR(m) (Kasten 1996 fit as given by Rigollier et al. 2000). */
static double rayleigh_delta(double m)
{
  if (m <= 20.0) {
    return 1.0 / (6.6296 + m * (1.7513 + m * (-0.1202 + m * (0.0065 - m * 0.00013))));
  }
  return 1.0 / (10.4 + 0.718 * m);
}

/* ESRA beam and diffuse for valid params and zenith; fills what is non-NULL. */
static void esra(const ap_sky_params *p, double zenith, double *dni, double *dhi)
{
  double i0 = p->solar_constant / (p->earth_sun_distance * p->earth_sun_distance);
  double tl = p->linke_turbidity;
  if (zenith > 0.5 * PI) {
    if (dni) {
      *dni = 0.0;
    }
    if (dhi) {
      *dhi = 0.0;
    }
    return;
  }
  if (dni) {
    double m = kasten_young(zenith) * pressure_ratio(p->site_height);
    *dni = i0 * exp(-0.8662 * tl * m * rayleigh_delta(m));
  }
  if (dhi) {
    double sh = cos(zenith); /* sin of the elevation */
    double trd = -1.5843e-2 + 3.0543e-2 * tl + 3.797e-4 * tl * tl;
    double a0 = 2.6463e-1 - 6.1581e-2 * tl + 3.1408e-3 * tl * tl;
    double a1 = 2.0402 + 1.8945e-2 * tl - 1.1161e-2 * tl * tl;
    double a2 = -1.3025 + 3.9231e-2 * tl + 8.5079e-3 * tl * tl;
    if (a0 * trd < 2e-3) {
      a0 = 2e-3 / trd;
    }
    double fd = a0 + a1 * sh + a2 * sh * sh;
    *dhi = fmax(0.0, i0 * trd * fd);
  }
}

ap_status ap_sky_clear_irradiance(const ap_sky_params *p, double zenith, double *dni,
                                  double *diffuse_horizontal)
{
  ap_status st = ap_sky_params_validate(p);
  if (st == AP_OK && !zenith_ok(zenith)) {
    st = AP_ERR_INVALID_ARGUMENT;
  }
  if (st != AP_OK) {
    set_nan(dni, 1);
    set_nan(diffuse_horizontal, 1);
    return st;
  }
  esra(p, zenith, dni, diffuse_horizontal);
  return AP_OK;
}

ap_status ap_sky_sunlight_compute(const ap_sky_params *p, double zenith, ap_sky_sunlight *out)
{
  if (!out) {
    return AP_ERR_NULL_POINTER;
  }
  ap_status st = ap_sky_params_validate(p);
  if (st == AP_OK && !zenith_ok(zenith)) {
    st = AP_ERR_INVALID_ARGUMENT;
  }
  if (st != AP_OK) {
    out->air_mass = out->dni = NAN;
    set_nan(out->rgb, 3);
    set_nan(out->chromaticity, 2);
    return st;
  }
  if (zenith > 0.5 * PI) {
    out->air_mass = INFINITY;
    out->dni = 0.0;
    out->rgb[0] = out->rgb[1] = out->rgb[2] = 0.0;
    out->chromaticity[0] = out->chromaticity[1] = NAN;
    return AP_OK;
  }
  double m = kasten_young(zenith);
  double mp = m * pressure_ratio(p->site_height);
  double spd[AP_SKY_SPECTRUM_SAMPLES];
  for (int i = 0; i < AP_SKY_SPECTRUM_SAMPLES; ++i) {
    double l = (AP_SKY_SPECTRUM_FIRST_NM + AP_SKY_SPECTRUM_STEP_NM * i) * 1e-3;
    double k = mp * rayleigh_thickness(l) + m * aerosol_thickness(l, p->turbidity) +
               m * ozone_k[i] * p->ozone;
    spd[i] = sun_spectrum[i] * exp(-k);
  }
  double xyz[3];
  (void)ap_sky_spectrum_to_xyz(spd, xyz);
  double sum = xyz[0] + xyz[1] + xyz[2];
  double dni;
  esra(p, zenith, &dni, NULL);
  out->air_mass = mp;
  out->dni = dni;
  out->chromaticity[0] = xyz[0] / sum;
  out->chromaticity[1] = xyz[1] / sum;
  double k = dni / xyz[1]; /* luminance := DNI */
  xyz[0] *= k;
  xyz[1] = dni;
  xyz[2] *= k;
  xyz_rgb(xyz, out->rgb);
  clamp_rgb(out->rgb, dni);
  return AP_OK;
}

/* ---------------------------------------------------------------------------------------------
 * Sky models
 * ------------------------------------------------------------------------------------------- */

/* Perez function (1 + A e^{B / cos θ})(1 + C e^{Dγ} + E cos² γ). cos θ > 0. */
static double perez(const double c[5], double cos_theta, double gamma, double cos_gamma)
{
  return (1.0 + c[0] * exp(c[1] / cos_theta)) *
         (1.0 + c[2] * exp(c[3] * gamma) + c[4] * cos_gamma * cos_gamma);
}

static double cie_clear_indicatrix(double gamma, double cos_gamma)
{
  return 0.91 + 10.0 * exp(-3.0 * gamma) + 0.45 * cos_gamma * cos_gamma;
}

/* The smallest cos θ used in the gradation terms: e^{B / cos θ} with B < 0 is 0 there. */
#define COS_MIN 1e-6

/* Luminance shape (Preetham: relative to the zenith; CIE: L / L_z) of a unit direction at or
 * above the horizon; 0 below it. */
static double sky_shape(const ap_sky_state *s, const double w[3])
{
  double ct = w[2];
  if (ct < 0.0) {
    return 0.0;
  }
  ct = fmax(ct, COS_MIN);
  switch (s->model) {
    case AP_SKY_UNIFORM:
      return 1.0;
    case AP_SKY_CIE_OVERCAST:
      return (1.0 + 2.0 * w[2]) / 3.0;
    case AP_SKY_CIE_CLEAR: {
      double cg = clamp1(dot3(w, s->sun));
      double g = acos(cg);
      return cie_clear_indicatrix(g, cg) * (1.0 - exp(-0.32 / ct)) * s->clear_norm;
    }
    case AP_SKY_PREETHAM: {
      double cg = clamp1(dot3(w, s->sun));
      double g = acos(cg);
      return perez(s->perez[0], ct, g, cg) * s->inv_f0[0];
    }
  }
  return 0.0;
}

/* RGB radiance of a unit direction. */
static void sky_rgb(const ap_sky_state *s, const double w[3], double rgb[3])
{
  if (w[2] < 0.0 || s->scale == 0.0) {
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    return;
  }
  if (s->model != AP_SKY_PREETHAM) {
    double l = s->scale * sky_shape(s, w);
    rgb[0] = rgb[1] = rgb[2] = l;
    return;
  }
  double ct = fmax(w[2], COS_MIN);
  double cg = clamp1(dot3(w, s->sun));
  double g = acos(cg);
  double lum = s->scale * perez(s->perez[0], ct, g, cg) * s->inv_f0[0];
  double x = s->zenith_xy[0] * perez(s->perez[1], ct, g, cg) * s->inv_f0[1];
  double y = s->zenith_xy[1] * perez(s->perez[2], ct, g, cg) * s->inv_f0[2];
  double xyz[3] = { x / y * lum, lum, (1.0 - x - y) / y * lum };
  xyz_rgb(xyz, rgb);
  clamp_rgb(rgb, lum);
}

/* Shape function as a 3-channel integrand (channel 0 only), for the normalisation. */
static void shape_fn(const ap_sky_state *s, const double w[3], double out[3])
{
  out[0] = sky_shape(s, w);
  out[1] = out[2] = 0.0;
}

typedef void (*dir_fn)(const ap_sky_state *s, const double w[3], double out[3]);

/* Orthonormal e1, e2 completing unit a (Duff et al., "Building an orthonormal basis,
 * revisited", JCGT 6(1), 2017). */
static void frame(const double a[3], double e1[3], double e2[3])
{
  double sign = copysign(1.0, a[2]);
  double aa = -1.0 / (sign + a[2]);
  double b = a[0] * a[1] * aa;
  e1[0] = 1.0 + sign * a[0] * a[0] * aa;
  e1[1] = sign * b;
  e1[2] = -sign * a[0];
  e2[0] = b;
  e2[1] = sign + a[1] * a[1] * aa;
  e2[2] = -a[1];
}

/* Intersect [*lo, *hi] ⊂ [0, π] with {t : A cos t + B sin t >= c}, 0 <= c < 1; returns 0 if
 * the result is empty. With R = hypot(A, B) the set is the arc |t − φ0| <= δ (mod 2π),
 * φ0 = atan2(B, A), δ = acos(c / R) <= π/2 (empty if R <= c). An arc of length 2δ <= π
 * meets an interval of length <= π in one interval (two only if together they covered the
 * circle), and the copies k = 0, 1 of the arc are the only ones that can reach t in [0, π]. */
static int clip_arc(double a, double b, double c, double *lo, double *hi)
{
  double r = hypot(a, b);
  if (r == 0.0 && c == 0.0) {
    return *hi > *lo; /* the value is 0 along the whole great circle: keep it */
  }
  if (!(r > c)) {
    return 0;
  }
  double phi0 = atan2(b, a);
  double delta = c == 0.0 ? 0.5 * PI : acos(fmin(1.0, c / r));
  double best_lo = 0.0, best_hi = -1.0;
  for (int k = 0; k <= 1; ++k) {
    double l = fmax(*lo, phi0 - delta + 2.0 * PI * k);
    double h = fmin(*hi, phi0 + delta + 2.0 * PI * k);
    if (h - l > best_hi - best_lo) {
      best_lo = l;
      best_hi = h;
    }
  }
  *lo = best_lo;
  *hi = best_hi;
  return best_hi > best_lo;
}

/* A region of the sphere: the intersection of up to three caps {ω : u_i·ω >= c_i},
 * 0 <= c_i < 1 (the aperture cap, the sky above the horizon, the front of the surface),
 * integrated in polar coordinates (t, ψ) about a pole strictly inside it. Every region here is
 * convex (caps of radius <= π/2), so each ray from the pole leaves it once, at
 * t_exit(ψ) = the first boundary crossing, a smooth function of ψ between the ψ of the
 * region's corners. */
typedef struct region {
  const double *pole;
  int count;
  const double *u[3];
  double c[3];
  const double *n; /* cosine weight max(0, n·ω), or NULL */
  const double *cusp; /* the sun's circumsolar cusp away from the pole, or NULL */
} region;

/* Sorted ψ in [0, 2π) (about the pole, frame e1, e2) of the region's corners: the points where
 * two boundary circles cross and every constraint holds. At most 6. */
static int region_corners(const region *g, const double e1[3], const double e2[3], double psi[6])
{
  int m = 0;
  for (int i = 0; i < g->count; ++i) {
    for (int j = i + 1; j < g->count; ++j) {
      const double *ui = g->u[i], *uj = g->u[j];
      double w[3];
      cross3(ui, uj, w);
      double w2 = dot3(w, w); /* = 1 − (ui·uj)² */
      if (w2 < 1e-20) {
        continue; /* parallel circles: no transversal crossing */
      }
      double k = dot3(ui, uj);
      double al = (g->c[i] - g->c[j] * k) / w2, be = (g->c[j] - g->c[i] * k) / w2;
      double p[3] = { al * ui[0] + be * uj[0], al * ui[1] + be * uj[1], al * ui[2] + be * uj[2] };
      double p2 = dot3(p, p);
      if (p2 >= 1.0) {
        continue;
      }
      double lam = sqrt((1.0 - p2) / w2);
      for (int sg = -1; sg <= 1; sg += 2) {
        double q[3] = { p[0] + sg * lam * w[0], p[1] + sg * lam * w[1], p[2] + sg * lam * w[2] };
        int inside = 1;
        for (int l = 0; l < g->count; ++l) {
          if (l != i && l != j && dot3(g->u[l], q) < g->c[l] - 1e-12) {
            inside = 0;
          }
        }
        if (inside) {
          double a = atan2(dot3(q, e2), dot3(q, e1));
          psi[m++] = a < 0.0 ? a + 2.0 * PI : a;
        }
      }
    }
  }
  for (int i = 1; i < m; ++i) { /* insertion sort */
    double v = psi[i];
    int j = i - 1;
    for (; j >= 0 && psi[j] > v; --j) {
      psi[j + 1] = psi[j];
    }
    psi[j + 1] = v;
  }
  return m;
}

/* ∫ over the ray of azimuth ψ: t in [0, t_exit] by `rings`-point Gauss–Legendre. */
static void ray_integrate(const ap_sky_state *s, dir_fn f, const region *g, const double d[3],
                          int rings, const double *node, const double *weight, double out[3])
{
  const double *c = g->pole;
  double lo = 0.0, hi = PI;
  out[0] = out[1] = out[2] = 0.0;
  for (int i = 0; i < g->count; ++i) {
    if (!clip_arc(dot3(g->u[i], c), dot3(g->u[i], d), g->c[i], &lo, &hi)) {
      return;
    }
  }
  double cut[3] = { lo, hi, hi };
  int pieces = 1;
  if (g->cusp) {
    double ts = atan2(dot3(d, g->cusp), dot3(c, g->cusp)); /* the ray's nearest to the sun */
    if (ts > lo && ts < hi) {
      cut[1] = ts;
      pieces = 2;
    }
  }
  for (int p = 0; p < pieces; ++p) {
    double half = 0.5 * (cut[p + 1] - cut[p]), mid = 0.5 * (cut[p + 1] + cut[p]);
    for (int k = 0; k < rings; ++k) {
      double t = mid + half * node[k];
      double ct = cos(t), st = sin(t);
      double w[3] = { ct * c[0] + st * d[0], ct * c[1] + st * d[1], ct * c[2] + st * d[2] };
      double v[3];
      f(s, w, v);
      double wt = half * weight[k] * st;
      if (g->n) {
        wt *= fmax(0.0, dot3(g->n, w));
      }
      out[0] += wt * v[0];
      out[1] += wt * v[1];
      out[2] += wt * v[2];
    }
  }
}

/* ∫_region f(ω) [max(0, n·ω)] dω. ψ: the circle is cut at the region's corners and each
 * piece is split into about sectors·width/(2π·AP_SKY_PSI_ORDER) equal sub-intervals (at least
 * one), each integrated by AP_SKY_PSI_ORDER-point Gauss–Legendre; t: ray_integrate. */
static void region_integrate(const ap_sky_state *s, dir_fn f, const region *g, int rings,
                             const double *node, const double *weight, int sectors, double out[3])
{
  double e1[3], e2[3];
  frame(g->pole, e1, e2);
  double b[8];
  int m = region_corners(g, e1, e2, b);
  if (g->cusp) { /* the sun's direction about the pole: its cusp on a piece's end */
    double a = atan2(dot3(g->cusp, e2), dot3(g->cusp, e1));
    a = a < 0.0 ? a + 2.0 * PI : a;
    int j = m++;
    for (; j > 0 && b[j - 1] > a; --j) {
      b[j] = b[j - 1];
    }
    b[j] = a;
  }
  if (m == 0) {
    b[0] = 0.0;
    m = 1;
  }
  b[m] = b[0] + 2.0 * PI;
  double acc[3] = { 0.0, 0.0, 0.0 };
  for (int k = 0; k < m; ++k) {
    double width = b[k + 1] - b[k];
    if (!(width > 0.0)) {
      continue;
    }
    long sub = lround((double)sectors / AP_SKY_PSI_ORDER * width / (2.0 * PI));
    if (sub < 1) {
      sub = 1;
    }
    double h = width / (double)sub;
    for (long q = 0; q < sub; ++q) {
      double mid = b[k] + h * ((double)q + 0.5);
      for (int i = 0; i < AP_SKY_PSI_ORDER; ++i) {
        double psi = mid + 0.5 * h * s->psi_node[i];
        double cp = cos(psi), sp = sin(psi);
        double d[3] = { cp * e1[0] + sp * e2[0], cp * e1[1] + sp * e2[1],
                        cp * e1[2] + sp * e2[2] };
        double v[3];
        ray_integrate(s, f, g, d, rings, node, weight, v);
        double wt = 0.5 * h * s->psi_weight[i];
        acc[0] += wt * v[0];
        acc[1] += wt * v[1];
        acc[2] += wt * v[2];
      }
    }
  }
  out[0] = acc[0];
  out[1] = acc[1];
  out[2] = acc[2];
}

/* Angular depth of p inside the region: the smallest angle from p to a boundary, negative
 * outside. */
static double depth(const region *g, const double p[3])
{
  double d = INFINITY;
  for (int i = 0; i < g->count; ++i) {
    d = fmin(d, acos(g->c[i]) - acos(clamp1(dot3(g->u[i], p))));
  }
  return d;
}

static void try_pole(const region *g, const double q[3], double p[3], double *best)
{
  double d = depth(g, q);
  if (d > *best) {
    *best = d;
    p[0] = q[0];
    p[1] = q[1];
    p[2] = q[2];
  }
}

/* A point deep inside the region (an approximate Chebyshev centre of the intersection of its
 * caps); returns its depth (<= 0: no interior found). Candidates: each cap's centre, and for
 * each pair of caps the point on the arc between their centres that is equally deep in both
 * (the deepest point of that pair's intersection); then a deterministic pattern search from the
 * best, in 16 directions with halving steps from r/2 down to r/2000. */
static double deep_point(const region *g, double r, double p[3])
{
  double best = -INFINITY;
  for (int i = 0; i < g->count; ++i) {
    try_pole(g, g->u[i], p, &best);
  }
  for (int i = 0; i < g->count; ++i) {
    for (int j = i + 1; j < g->count; ++j) {
      double d = acos(clamp1(dot3(g->u[i], g->u[j])));
      double x = 0.5 * (acos(g->c[i]) - acos(g->c[j]) + d);
      if (d > 1e-9 && d < PI - 1e-9 && x > 0.0 && x < d) {
        double wi = sin(d - x) / sin(d), wj = sin(x) / sin(d), q[3];
        for (int k = 0; k < 3; ++k) {
          q[k] = wi * g->u[i][k] + wj * g->u[j][k];
        }
        try_pole(g, q, p, &best);
      }
    }
  }
  double h0 = 0.5 * r, h = h0;
  for (int it = 0; it < 200 && h > 1e-3 * h0; ++it) {
    double e1[3], e2[3];
    frame(p, e1, e2);
    double before = best, ch = cos(h), sh = sin(h), q[3];
    for (int k = 0; k < 16 && best == before; ++k) {
      double ca = cos(0.125 * PI * k), sa = sin(0.125 * PI * k);
      for (int i = 0; i < 3; ++i) {
        q[i] = ch * p[i] + sh * (ca * e1[i] + sa * e2[i]);
      }
      try_pole(g, q, p, &best);
    }
    if (best == before) {
      h *= 0.5;
    }
  }
  return best;
}

static const double up_dir[3] = { 0.0, 0.0, 1.0 };

/* The cusp of a sky with a circumsolar peak (CIE clear, Preetham: the callers check) for a
 * region about `pole`: the sun, unless it is the pole itself, where the polar rule is smooth. */
static const double *cusp_of(const ap_sky_state *s, const double pole[3])
{
  return dot3(s->sun, pole) < 1.0 - 1e-12 ? s->sun : NULL;
}

/* The cap (unit axis a, radius r in (0, π/2]) ∩ sky [∩ front of n] as a region, with its pole
 * strictly inside, a deep interior point, so that no boundary passes near the pole; the sun's
 * cusp, if the sky has one, is cut out (region_integrate, ray_integrate). Returns 0 if the
 * region has no interior. */
static int cap_region(const ap_sky_state *s, const double a[3], double r, const double *n,
                      double pole[3], region *g)
{
  g->count = 0;
  g->u[g->count] = a;
  g->c[g->count++] = cos(r);
  g->u[g->count] = up_dir;
  g->c[g->count++] = 0.0;
  if (n) {
    g->u[g->count] = n;
    g->c[g->count++] = 0.0;
  }
  g->n = n;
  g->pole = pole;
  g->cusp = NULL;
  double dp;
  if (depth(g, a) >= 0.5 * r) { /* the axis is deep enough: no search */
    pole[0] = a[0];
    pole[1] = a[1];
    pole[2] = a[2];
    dp = depth(g, a);
  } else {
    dp = deep_point(g, r, pole);
  }
  if (!(dp > 0.0)) {
    return 0;
  }
  if (s->model == AP_SKY_CIE_CLEAR || s->model == AP_SKY_PREETHAM) {
    g->cusp = cusp_of(s, pole);
  }
  return 1;
}

ap_status ap_sky_prepare(const ap_sky_params *p, const double sun[3], ap_sky_state *s)
{
  if (!s) {
    return AP_ERR_NULL_POINTER;
  }
  s->magic = 0;
  ap_status st = ap_sky_params_validate(p);
  if (st == AP_OK && !sun) {
    st = AP_ERR_NULL_POINTER;
  }
  if (st == AP_OK && !unit_vector(sun, s->sun)) {
    st = AP_ERR_INVALID_ARGUMENT;
  }
  if (st != AP_OK) {
    set_nan(s->sun, 3);
    s->sun_zenith = s->horizontal_irradiance = NAN;
    set_nan(s->zenith_radiance, 3);
    return st;
  }

  double zs = acos(clamp1(s->sun[2]));
  int below = zs > 0.5 * PI;
  s->sun_zenith = zs;
  s->model = p->model;
  s->rings = p->cap_rings;
  s->sectors = p->cap_sectors;
  gauss_legendre(s->rings, s->gl_node, s->gl_weight);
  gauss_legendre(AP_SKY_PSI_ORDER, s->psi_node, s->psi_weight);
  s->clear_norm = 0.0;
  for (int c = 0; c < 3; ++c) {
    s->inv_f0[c] = 0.0;
    for (int k = 0; k < 5; ++k) {
      s->perez[c][k] = 0.0;
    }
  }
  s->zenith_xy[0] = s->zenith_xy[1] = 0.0;

  /* E_h from the params or the models of ap_sky.h */
  double eh = p->diffuse_horizontal;
  if (eh < 0.0 && p->model != AP_SKY_PREETHAM) {
    double dni, dhi;
    esra(p, zs, &dni, &dhi);
    eh = p->model == AP_SKY_CIE_OVERCAST ? 0.25 * (dni * cos(zs) + dhi) : dhi; /* dni = 0 below */
  }

  /* shape-specific set-up; `integral` = ∫_hemisphere shape · cos θ dω */
  double integral = 0.0;
  if (p->model == AP_SKY_UNIFORM) {
    integral = PI;
  } else if (p->model == AP_SKY_CIE_OVERCAST) {
    integral = 7.0 * PI / 9.0;
  } else {
    if (p->model == AP_SKY_CIE_CLEAR) {
      double cz = cos(zs);
      s->clear_norm = 1.0 / (cie_clear_indicatrix(zs, cz) * (1.0 - exp(-0.32)));
    } else {
      double t = p->turbidity;
      double th = fmin(zs, 0.5 * PI); /* zenith formulas at the sun's zenith, <= 90° */
      for (int c = 0; c < 3; ++c) {
        for (int k = 0; k < 5; ++k) {
          s->perez[c][k] = perez_coef[c][k][0] * t + perez_coef[c][k][1];
        }
        /* F(0, Z): the zenith direction, γ = Z (the true sun angle, also below the horizon) */
        s->inv_f0[c] = 1.0 / perez(s->perez[c], 1.0, zs, cos(zs));
      }
      double th2 = th * th, th3 = th2 * th;
      s->zenith_xy[0] = t * t * (0.00166 * th3 - 0.00375 * th2 + 0.00209 * th) +
                        t * (-0.02903 * th3 + 0.06377 * th2 - 0.03202 * th + 0.00394) +
                        (0.11693 * th3 - 0.21196 * th2 + 0.06052 * th + 0.25886);
      s->zenith_xy[1] = t * t * (0.00275 * th3 - 0.00610 * th2 + 0.00317 * th) +
                        t * (-0.04214 * th3 + 0.08970 * th2 - 0.04153 * th + 0.00516) +
                        (0.15346 * th3 - 0.26756 * th2 + 0.06670 * th + 0.26688);
    }
    /* over the sky (z >= 0), cosine to up, about the zenith with the sun's cusp cut out */
    double node[NORM_RINGS], weight[NORM_RINGS], v[3];
    gauss_legendre(NORM_RINGS, node, weight);
    region g = { up_dir, 1, { up_dir, NULL, NULL }, { 0.0, 0.0, 0.0 }, up_dir,
                 cusp_of(s, up_dir) };
    region_integrate(s, shape_fn, &g, NORM_RINGS, node, weight, NORM_SECTORS, v);
    integral = v[0];
  }

  if (p->model == AP_SKY_PREETHAM && eh < 0.0) {
    double t = p->turbidity;
    double chi = (4.0 / 9.0 - t / 120.0) * (PI - 2.0 * zs);
    double yz = (4.0453 * t - 4.9710) * tan(chi) - 0.2155 * t + 2.4192; /* kcd/m² */
    s->scale = below ? 0.0 : fmax(0.0, 1000.0 * yz / p->luminous_efficacy);
    eh = s->scale * integral;
  } else {
    s->scale = integral > 0.0 ? eh / integral : 0.0;
  }
  s->horizontal_irradiance = eh;
  s->magic = SKY_MAGIC;
  sky_rgb(s, up_dir, s->zenith_radiance);
  return AP_OK;
}

static int state_ok(const ap_sky_state *s)
{
  return s->magic == SKY_MAGIC;
}

ap_status ap_sky_radiance(const ap_sky_state *s, const double dir[3], double rgb[3])
{
  if (!rgb) {
    return AP_ERR_NULL_POINTER;
  }
  if (!s || !dir) {
    set_nan(rgb, 3);
    return AP_ERR_NULL_POINTER;
  }
  double w[3];
  if (!state_ok(s) || !unit_vector(dir, w)) {
    set_nan(rgb, 3);
    return AP_ERR_INVALID_ARGUMENT;
  }
  sky_rgb(s, w, rgb);
  return AP_OK;
}

ap_status ap_sky_cap(const ap_sky_state *s, const double axis[3], double radius,
                     const double normal[3], double mean_radiance[3], double irradiance[3])
{
  ap_status st = AP_OK;
  double a[3], n[3];
  if (!s || !axis || (irradiance && !normal)) {
    st = AP_ERR_NULL_POINTER;
  } else if (!state_ok(s) || !unit_vector(axis, a) || !in_range(radius, 0.0, 0.5 * PI) ||
             (irradiance && !unit_vector(normal, n))) {
    st = AP_ERR_INVALID_ARGUMENT;
  }
  if (st != AP_OK) {
    set_nan(mean_radiance, 3);
    set_nan(irradiance, 3);
    return st;
  }
  if (radius < AP_SKY_POINT_CAP) {
    /* cos r = 1 - r²/2 keeps too few digits for the regions' depths (none at all below 1e-8):
     * the cap is its axis */
    double l[3];
    sky_rgb(s, a, l);
    const double sh = sin(0.5 * radius), omega = 4.0 * PI * sh * sh;
    const double facing = irradiance ? fmax(0.0, dot3(n, a)) : 0.0;
    for (int i = 0; i < 3; ++i) {
      if (mean_radiance) {
        mean_radiance[i] = l[i];
      }
      if (irradiance) {
        irradiance[i] = l[i] * omega * facing;
      }
    }
    return AP_OK;
  }
  if (mean_radiance) {
    double sh = sin(0.5 * radius);
    double omega = 4.0 * PI * sh * sh;
    double v[3];
    double pole[3];
    region g;
    v[0] = v[1] = v[2] = 0.0;
    if (cap_region(s, a, radius, NULL, pole, &g)) {
      region_integrate(s, sky_rgb, &g, s->rings, s->gl_node, s->gl_weight, s->sectors, v);
    }
    for (int i = 0; i < 3; ++i) {
      mean_radiance[i] = v[i] / omega;
    }
  }
  if (irradiance) {
    double pole[3];
    region g;
    irradiance[0] = irradiance[1] = irradiance[2] = 0.0;
    if (cap_region(s, a, radius, n, pole, &g)) {
      region_integrate(s, sky_rgb, &g, s->rings, s->gl_node, s->gl_weight, s->sectors,
                       irradiance);
    }
  }
  return AP_OK;
}

/* ---------------------------------------------------------------------------------------------
 * Colour
 * ------------------------------------------------------------------------------------------- */

ap_status ap_sky_spectrum_to_xyz(const double spectrum[AP_SKY_SPECTRUM_SAMPLES], double xyz[3])
{
  if (!xyz) {
    return AP_ERR_NULL_POINTER;
  }
  if (!spectrum) {
    set_nan(xyz, 3);
    return AP_ERR_NULL_POINTER;
  }
  double x = 0.0, y = 0.0, z = 0.0;
  for (int i = 0; i < AP_SKY_SPECTRUM_SAMPLES; ++i) {
    x += spectrum[i] * cmf[i][0];
    y += spectrum[i] * cmf[i][1];
    z += spectrum[i] * cmf[i][2];
  }
  xyz[0] = x * AP_SKY_SPECTRUM_STEP_NM;
  xyz[1] = y * AP_SKY_SPECTRUM_STEP_NM;
  xyz[2] = z * AP_SKY_SPECTRUM_STEP_NM;
  return AP_OK;
}

ap_status ap_sky_xyz_to_rgb(const double xyz[3], double rgb[3])
{
  if (!rgb) {
    return AP_ERR_NULL_POINTER;
  }
  if (!xyz) {
    set_nan(rgb, 3);
    return AP_ERR_NULL_POINTER;
  }
  double v[3] = { xyz[0], xyz[1], xyz[2] };
  xyz_rgb(v, rgb);
  return AP_OK;
}
