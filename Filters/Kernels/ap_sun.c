/* SPDX-License-Identifier: BSD-3-Clause */
/* The NREL Solar Position Algorithm (Reda & Andreas, NREL/TP-560-34302, rev. 2008), written
 * from the report's equations; the step numbers below are those of the report's section 3 and
 * Appendix A. The periodic-term tables are the report's published data, checked term by term
 * against the full VSOP87D Earth series and Meeus' Table 22.A. */
#include "ap_sun.h"

#include "ap_range.h"
#include "ap_time.h" /* the calendar: days <-> civil dates */
#include "ap_vec.h"

#include <math.h>
#include <stddef.h>

#define PI 3.14159265358979323846

/* POSIX seconds of J2000.0 taken as a UT instant, 2000-01-01T12:00:00 (JD 2451545.0). */
#define UNIX_J2000 946728000.0
#define SECONDS_PER_DAY 86400.0
/* Radius of the sun's disc used by the report for the refraction cut-off and rise/set (deg). */
#define SUN_RADIUS_DEG 0.26667

/* Earth periodic terms, the report's table (truncated VSOP87D, Meeus Appendix III): rows of
 * {A, B, C}; term = A cos(B + C·JME), A in 1e-8 rad (L, B) or 1e-8 AU (R), B in rad,
 * C in rad per Julian millennium. */
typedef struct term {
  double a, b, c;
} term;

static const term L0_TERMS[] = {
  { 175347046.0, 0.0, 0.0 },        { 3341656.0, 4.6692568, 6283.07585 },
  { 34894.0, 4.6261, 12566.1517 },  { 3497.0, 2.7441, 5753.3849 },
  { 3418.0, 2.8289, 3.5231 },       { 3136.0, 3.6277, 77713.7715 },
  { 2676.0, 4.4181, 7860.4194 },    { 2343.0, 6.1352, 3930.2097 },
  { 1324.0, 0.7425, 11506.7698 },   { 1273.0, 2.0371, 529.691 },
  { 1199.0, 1.1096, 1577.3435 },    { 990.0, 5.233, 5884.927 },
  { 902.0, 2.045, 26.298 },         { 857.0, 3.508, 398.149 },
  { 780.0, 1.179, 5223.694 },       { 753.0, 2.533, 5507.553 },
  { 505.0, 4.583, 18849.228 },      { 492.0, 4.205, 775.523 },
  { 357.0, 2.92, 0.067 },           { 317.0, 5.849, 11790.629 },
  { 284.0, 1.899, 796.298 },        { 271.0, 0.315, 10977.079 },
  { 243.0, 0.345, 5486.778 },       { 206.0, 4.806, 2544.314 },
  { 205.0, 1.869, 5573.143 },       { 202.0, 2.458, 6069.777 },
  { 156.0, 0.833, 213.299 },        { 132.0, 3.411, 2942.463 },
  { 126.0, 1.083, 20.775 },         { 115.0, 0.645, 0.98 },
  { 103.0, 0.636, 4694.003 },       { 102.0, 0.976, 15720.839 },
  { 102.0, 4.267, 7.114 },          { 99.0, 6.21, 2146.17 },
  { 98.0, 0.68, 155.42 },           { 86.0, 5.98, 161000.69 },
  { 85.0, 1.3, 6275.96 },           { 85.0, 3.67, 71430.7 },
  { 80.0, 1.81, 17260.15 },         { 79.0, 3.04, 12036.46 },
  { 75.0, 1.76, 5088.63 },          { 74.0, 3.5, 3154.69 },
  { 74.0, 4.68, 801.82 },           { 70.0, 0.83, 9437.76 },
  { 62.0, 3.98, 8827.39 },          { 61.0, 1.82, 7084.9 },
  { 57.0, 2.78, 6286.6 },           { 56.0, 4.39, 14143.5 },
  { 56.0, 3.47, 6279.55 },          { 52.0, 0.19, 12139.55 },
  { 52.0, 1.33, 1748.02 },          { 51.0, 0.28, 5856.48 },
  { 49.0, 0.49, 1194.45 },          { 41.0, 5.37, 8429.24 },
  { 41.0, 2.4, 19651.05 },          { 39.0, 6.17, 10447.39 },
  { 37.0, 6.04, 10213.29 },         { 37.0, 2.57, 1059.38 },
  { 36.0, 1.71, 2352.87 },          { 36.0, 1.78, 6812.77 },
  { 33.0, 0.59, 17789.85 },         { 30.0, 0.44, 83996.85 },
  { 30.0, 2.74, 1349.87 },          { 25.0, 3.16, 4690.48 },
};

static const term L1_TERMS[] = {
  { 628331966747.0, 0.0, 0.0 },     { 206059.0, 2.678235, 6283.07585 },
  { 4303.0, 2.6351, 12566.1517 },   { 425.0, 1.59, 3.523 },
  { 119.0, 5.796, 26.298 },         { 109.0, 2.966, 1577.344 },
  { 93.0, 2.59, 18849.23 },         { 72.0, 1.14, 529.69 },
  { 68.0, 1.87, 398.15 },           { 67.0, 4.41, 5507.55 },
  { 59.0, 2.89, 5223.69 },          { 56.0, 2.17, 155.42 },
  { 45.0, 0.4, 796.3 },             { 36.0, 0.47, 775.52 },
  { 29.0, 2.65, 7.11 },             { 21.0, 5.34, 0.98 },
  { 19.0, 1.85, 5486.78 },          { 19.0, 4.97, 213.3 },
  { 17.0, 2.99, 6275.96 },          { 16.0, 0.03, 2544.31 },
  { 16.0, 1.43, 2146.17 },          { 15.0, 1.21, 10977.08 },
  { 12.0, 2.83, 1748.02 },          { 12.0, 3.26, 5088.63 },
  { 12.0, 5.27, 1194.45 },          { 12.0, 2.08, 4694.0 },
  { 11.0, 0.77, 553.57 },           { 10.0, 1.3, 6286.6 },
  { 10.0, 4.24, 1349.87 },          { 9.0, 2.7, 242.73 },
  { 9.0, 5.64, 951.72 },            { 8.0, 5.3, 2352.87 },
  { 6.0, 2.65, 9437.76 },           { 6.0, 4.67, 4690.48 },
};

static const term L2_TERMS[] = {
  { 52919.0, 0.0, 0.0 },            { 8720.0, 1.0721, 6283.0758 },
  { 309.0, 0.867, 12566.152 },      { 27.0, 0.05, 3.52 },
  { 16.0, 5.19, 26.3 },             { 16.0, 3.68, 155.42 },
  { 10.0, 0.76, 18849.23 },         { 9.0, 2.06, 77713.77 },
  { 7.0, 0.83, 775.52 },            { 5.0, 4.66, 1577.34 },
  { 4.0, 1.03, 7.11 },              { 4.0, 3.44, 5573.14 },
  { 3.0, 5.14, 796.3 },             { 3.0, 6.05, 5507.55 },
  { 3.0, 1.19, 242.73 },            { 3.0, 6.12, 529.69 },
  { 3.0, 0.31, 398.15 },            { 3.0, 2.28, 553.57 },
  { 2.0, 4.38, 5223.69 },           { 2.0, 3.75, 0.98 },
};

static const term L3_TERMS[] = {
  { 289.0, 5.844, 6283.076 },       { 35.0, 0.0, 0.0 },
  { 17.0, 5.49, 12566.15 },         { 3.0, 5.2, 155.42 },
  { 1.0, 4.72, 3.52 },              { 1.0, 5.3, 18849.23 },
  { 1.0, 5.97, 242.73 },
};

static const term L4_TERMS[] = {
  { 114.0, 3.142, 0.0 }, { 8.0, 4.13, 6283.08 }, { 1.0, 3.84, 12566.15 },
};

static const term L5_TERMS[] = {
  { 1.0, 3.14, 0.0 },
};

static const term B0_TERMS[] = {
  { 280.0, 3.199, 84334.662 }, { 102.0, 5.422, 5507.553 }, { 80.0, 3.88, 5223.69 },
  { 44.0, 3.7, 2352.87 },      { 32.0, 4.0, 1577.34 },
};

static const term B1_TERMS[] = {
  { 9.0, 3.9, 5507.55 }, { 6.0, 1.73, 5223.69 },
};

static const term R0_TERMS[] = {
  { 100013989.0, 0.0, 0.0 },        { 1670700.0, 3.0984635, 6283.07585 },
  { 13956.0, 3.05525, 12566.1517 }, { 3084.0, 5.1985, 77713.7715 },
  { 1628.0, 1.1739, 5753.3849 },    { 1576.0, 2.8469, 7860.4194 },
  { 925.0, 5.453, 11506.77 },       { 542.0, 4.564, 3930.21 },
  { 472.0, 3.661, 5884.927 },       { 346.0, 0.964, 5507.553 },
  { 329.0, 5.9, 5223.694 },         { 307.0, 0.299, 5573.143 },
  { 243.0, 4.273, 11790.629 },      { 212.0, 5.847, 1577.344 },
  { 186.0, 5.022, 10977.079 },      { 175.0, 3.012, 18849.228 },
  { 110.0, 5.055, 5486.778 },       { 98.0, 0.89, 6069.78 },
  { 86.0, 5.69, 15720.84 },         { 86.0, 1.27, 161000.69 },
  { 65.0, 0.27, 17260.15 },         { 63.0, 0.92, 529.69 },
  { 57.0, 2.01, 83996.85 },         { 56.0, 5.24, 71430.7 },
  { 49.0, 3.25, 2544.31 },          { 47.0, 2.58, 775.52 },
  { 45.0, 5.54, 9437.76 },          { 43.0, 6.01, 6275.96 },
  { 39.0, 5.36, 4694.0 },           { 38.0, 2.39, 8827.39 },
  { 37.0, 0.83, 19651.05 },         { 37.0, 4.9, 12139.55 },
  { 36.0, 1.67, 12036.46 },         { 35.0, 1.84, 2942.46 },
  { 33.0, 0.24, 7084.9 },           { 32.0, 0.18, 5088.63 },
  { 32.0, 1.78, 398.15 },           { 28.0, 1.21, 6286.6 },
  { 28.0, 1.9, 6279.55 },           { 26.0, 4.59, 10447.39 },
};

static const term R1_TERMS[] = {
  { 103019.0, 1.10749, 6283.07585 }, { 1721.0, 1.0644, 12566.1517 },
  { 702.0, 3.142, 0.0 },             { 32.0, 1.02, 18849.23 },
  { 31.0, 2.84, 5507.55 },           { 25.0, 1.32, 5223.69 },
  { 18.0, 1.42, 1577.34 },           { 10.0, 5.91, 10977.08 },
  { 9.0, 1.42, 6275.96 },            { 9.0, 0.27, 5486.78 },
};

static const term R2_TERMS[] = {
  { 4359.0, 5.7846, 6283.0758 }, { 124.0, 5.579, 12566.152 }, { 12.0, 3.14, 0.0 },
  { 9.0, 3.63, 77713.77 },       { 6.0, 1.87, 5573.14 },      { 3.0, 5.47, 18849.23 },
};

static const term R3_TERMS[] = {
  { 145.0, 4.273, 6283.076 }, { 7.0, 3.92, 12566.15 },
};

static const term R4_TERMS[] = {
  { 4.0, 2.56, 6283.08 },
};

/* Nutation in longitude and obliquity, the report's 63-row table (IAU 1980 theory, Meeus 22.A):
 * multiples of the arguments X0..X4 = D, M, M', F, Ω, and the coefficients a, b (Δψ) and
 * c, d (Δε) in units of 0.0001″: Δψ = Σ (a + b·JCE) sin(Σ Xj·Yj), Δε = Σ (c + d·JCE) cos(...). */
typedef struct nutation_term {
  signed char y[5];
  double a, b, c, d;
} nutation_term;

static const nutation_term NUTATION_TERMS[] = {
  { { 0, 0, 0, 0, 1 }, -171996.0, -174.2, 92025.0, 8.9 },
  { { -2, 0, 0, 2, 2 }, -13187.0, -1.6, 5736.0, -3.1 },
  { { 0, 0, 0, 2, 2 }, -2274.0, -0.2, 977.0, -0.5 },
  { { 0, 0, 0, 0, 2 }, 2062.0, 0.2, -895.0, 0.5 },
  { { 0, 1, 0, 0, 0 }, 1426.0, -3.4, 54.0, -0.1 },
  { { 0, 0, 1, 0, 0 }, 712.0, 0.1, -7.0, 0.0 },
  { { -2, 1, 0, 2, 2 }, -517.0, 1.2, 224.0, -0.6 },
  { { 0, 0, 0, 2, 1 }, -386.0, -0.4, 200.0, 0.0 },
  { { 0, 0, 1, 2, 2 }, -301.0, 0.0, 129.0, -0.1 },
  { { -2, -1, 0, 2, 2 }, 217.0, -0.5, -95.0, 0.3 },
  { { -2, 0, 1, 0, 0 }, -158.0, 0.0, 0.0, 0.0 },
  { { -2, 0, 0, 2, 1 }, 129.0, 0.1, -70.0, 0.0 },
  { { 0, 0, -1, 2, 2 }, 123.0, 0.0, -53.0, 0.0 },
  { { 2, 0, 0, 0, 0 }, 63.0, 0.0, 0.0, 0.0 },
  { { 0, 0, 1, 0, 1 }, 63.0, 0.1, -33.0, 0.0 },
  { { 2, 0, -1, 2, 2 }, -59.0, 0.0, 26.0, 0.0 },
  { { 0, 0, -1, 0, 1 }, -58.0, -0.1, 32.0, 0.0 },
  { { 0, 0, 1, 2, 1 }, -51.0, 0.0, 27.0, 0.0 },
  { { -2, 0, 2, 0, 0 }, 48.0, 0.0, 0.0, 0.0 },
  { { 0, 0, -2, 2, 1 }, 46.0, 0.0, -24.0, 0.0 },
  { { 2, 0, 0, 2, 2 }, -38.0, 0.0, 16.0, 0.0 },
  { { 0, 0, 2, 2, 2 }, -31.0, 0.0, 13.0, 0.0 },
  { { 0, 0, 2, 0, 0 }, 29.0, 0.0, 0.0, 0.0 },
  { { -2, 0, 1, 2, 2 }, 29.0, 0.0, -12.0, 0.0 },
  { { 0, 0, 0, 2, 0 }, 26.0, 0.0, 0.0, 0.0 },
  { { -2, 0, 0, 2, 0 }, -22.0, 0.0, 0.0, 0.0 },
  { { 0, 0, -1, 2, 1 }, 21.0, 0.0, -10.0, 0.0 },
  { { 0, 2, 0, 0, 0 }, 17.0, -0.1, 0.0, 0.0 },
  { { 2, 0, -1, 0, 1 }, 16.0, 0.0, -8.0, 0.0 },
  { { -2, 2, 0, 2, 2 }, -16.0, 0.1, 7.0, 0.0 },
  { { 0, 1, 0, 0, 1 }, -15.0, 0.0, 9.0, 0.0 },
  { { -2, 0, 1, 0, 1 }, -13.0, 0.0, 7.0, 0.0 },
  { { 0, -1, 0, 0, 1 }, -12.0, 0.0, 6.0, 0.0 },
  { { 0, 0, 2, -2, 0 }, 11.0, 0.0, 0.0, 0.0 },
  { { 2, 0, -1, 2, 1 }, -10.0, 0.0, 5.0, 0.0 },
  { { 2, 0, 1, 2, 2 }, -8.0, 0.0, 3.0, 0.0 },
  { { 0, 1, 0, 2, 2 }, 7.0, 0.0, -3.0, 0.0 },
  { { -2, 1, 1, 0, 0 }, -7.0, 0.0, 0.0, 0.0 },
  { { 0, -1, 0, 2, 2 }, -7.0, 0.0, 3.0, 0.0 },
  { { 2, 0, 0, 2, 1 }, -7.0, 0.0, 3.0, 0.0 },
  { { 2, 0, 1, 0, 0 }, 6.0, 0.0, 0.0, 0.0 },
  { { -2, 0, 2, 2, 2 }, 6.0, 0.0, -3.0, 0.0 },
  { { -2, 0, 1, 2, 1 }, 6.0, 0.0, -3.0, 0.0 },
  { { 2, 0, -2, 0, 1 }, -6.0, 0.0, 3.0, 0.0 },
  { { 2, 0, 0, 0, 1 }, -6.0, 0.0, 3.0, 0.0 },
  { { 0, -1, 1, 0, 0 }, 5.0, 0.0, 0.0, 0.0 },
  { { -2, -1, 0, 2, 1 }, -5.0, 0.0, 3.0, 0.0 },
  { { -2, 0, 0, 0, 1 }, -5.0, 0.0, 3.0, 0.0 },
  { { 0, 0, 2, 2, 1 }, -5.0, 0.0, 3.0, 0.0 },
  { { -2, 0, 2, 0, 1 }, 4.0, 0.0, 0.0, 0.0 },
  { { -2, 1, 0, 2, 1 }, 4.0, 0.0, 0.0, 0.0 },
  { { 0, 0, 1, -2, 0 }, 4.0, 0.0, 0.0, 0.0 },
  { { -1, 0, 1, 0, 0 }, -4.0, 0.0, 0.0, 0.0 },
  { { -2, 1, 0, 0, 0 }, -4.0, 0.0, 0.0, 0.0 },
  { { 1, 0, 0, 0, 0 }, -4.0, 0.0, 0.0, 0.0 },
  { { 0, 0, 1, 2, 0 }, 3.0, 0.0, 0.0, 0.0 },
  { { 0, 0, -2, 2, 2 }, -3.0, 0.0, 0.0, 0.0 },
  { { -1, -1, 1, 0, 0 }, -3.0, 0.0, 0.0, 0.0 },
  { { 0, 1, 1, 0, 0 }, -3.0, 0.0, 0.0, 0.0 },
  { { 0, -1, 1, 2, 2 }, -3.0, 0.0, 0.0, 0.0 },
  { { 2, -1, -1, 2, 2 }, -3.0, 0.0, 0.0, 0.0 },
  { { 0, 0, 3, 2, 2 }, -3.0, 0.0, 0.0, 0.0 },
  { { 2, -1, 0, 2, 2 }, -3.0, 0.0, 0.0, 0.0 },
};

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

/* ------------------------------------------------------------------------------------------ */
/* Small helpers                                                                              */

static double rad(double d) { return d * (PI / 180.0); }
static double deg(double r) { return r * (180.0 / PI); }

/* d reduced to [0, 360). */
static double wrap360(double d)
{
  double r = fmod(d, 360.0);
  if (r < 0.0) {
    r += 360.0;
  }
  return r >= 360.0 ? 0.0 : r;
}

/* d reduced to [-180, 180). */
static double wrap180(double d) { return wrap360(d + 180.0) - 180.0; }

/* x reduced to [0, 1). */
static double frac01(double x)
{
  double r = x - floor(x);
  return r >= 1.0 ? 0.0 : r;
}

static int in_range(double x, double lo, double hi) { return x >= lo && x <= hi; }

/* Is t (POSIX seconds) within the years AP_SUN_YEAR_MIN..AP_SUN_YEAR_MAX? If so, give its
 * decimal year y = year + (month - 0.5) / 12 as Espenak & Meeus define it for ΔT. */
static int instant_ok(double t, double *decimal_year)
{
  const double t_min = (double)ap_time_days_from_civil(AP_SUN_YEAR_MIN, 1, 1) * SECONDS_PER_DAY;
  const double t_end = (double)ap_time_days_from_civil(AP_SUN_YEAR_MAX + 1, 1, 1) * SECONDS_PER_DAY;
  if (!(t >= t_min && t < t_end)) { /* also rejects NaN */
    return 0;
  }
  int64_t year;
  int month, day;
  ap_time_civil_from_days((int64_t)floor(t / SECONDS_PER_DAY), &year, &month, &day);
  *decimal_year = (double)year + ((double)month - 0.5) / 12.0;
  return 1;
}

/* ------------------------------------------------------------------------------------------ */
/* Geocentric position (report steps 3.1-3.8)                                                 */

typedef struct geo {
  double jc, jce, jme;      /* Julian century (UT), ephemeris century and millennium (TT) */
  double l, b, r;           /* heliocentric longitude, latitude (deg), radius (AU) */
  double dpsi, deps, eps;   /* nutation in longitude, obliquity; true obliquity (deg) */
  double lambda;            /* apparent sun longitude (deg) */
  double nu;                /* apparent sidereal time at Greenwich (deg, [0, 360)) */
  double alpha, delta;      /* geocentric right ascension [0, 360), declination (deg) */
} geo;

/* Σ A cos(B + C·x) over a table. */
static double series(const term *t, size_t n, double x)
{
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) {
    s += t[i].a * cos(t[i].b + t[i].c * x);
  }
  return s;
}
#define SERIES(T, x) series(T, COUNT(T), x)

/* d_ut = JD - 2451545 (UT1 days), d_tt = JDE - 2451545 (TT days). */
static void geocentric(double d_ut, double d_tt, geo *g)
{
  g->jc = d_ut / 36525.0;
  g->jce = d_tt / 36525.0;
  g->jme = g->jce / 10.0;
  const double x = g->jme;

  /* 3.2 Earth heliocentric longitude, latitude and radius. */
  const double l_rad =
    (SERIES(L0_TERMS, x) +
     x * (SERIES(L1_TERMS, x) +
          x * (SERIES(L2_TERMS, x) +
               x * (SERIES(L3_TERMS, x) + x * (SERIES(L4_TERMS, x) + x * SERIES(L5_TERMS, x)))))) /
    1e8;
  g->l = wrap360(deg(l_rad));
  g->b = deg((SERIES(B0_TERMS, x) + x * SERIES(B1_TERMS, x)) / 1e8);
  g->r = (SERIES(R0_TERMS, x) +
          x * (SERIES(R1_TERMS, x) +
               x * (SERIES(R2_TERMS, x) + x * (SERIES(R3_TERMS, x) + x * SERIES(R4_TERMS, x))))) /
         1e8;

  /* 3.3 Geocentric longitude and latitude. */
  const double theta = wrap360(g->l + 180.0);
  const double beta = -g->b;

  /* 3.4 Nutation: X0..X4 = D, M, M', F, Ω in degrees. */
  const double t = g->jce;
  double xs[5];
  xs[0] = wrap360(297.85036 + t * (445267.111480 + t * (-0.0019142 + t / 189474.0)));
  xs[1] = wrap360(357.52772 + t * (35999.050340 + t * (-0.0001603 - t / 300000.0)));
  xs[2] = wrap360(134.96298 + t * (477198.867398 + t * (0.0086972 + t / 56250.0)));
  xs[3] = wrap360(93.27191 + t * (483202.017538 + t * (-0.0036825 + t / 327270.0)));
  xs[4] = wrap360(125.04452 + t * (-1934.136261 + t * (0.0020708 + t / 450000.0)));
  double dpsi = 0.0, deps = 0.0;
  for (size_t i = 0; i < COUNT(NUTATION_TERMS); ++i) {
    const nutation_term *n = &NUTATION_TERMS[i];
    double arg = 0.0;
    for (int j = 0; j < 5; ++j) {
      arg += n->y[j] * xs[j];
    }
    arg = rad(arg);
    dpsi += (n->a + n->b * t) * sin(arg);
    deps += (n->c + n->d * t) * cos(arg);
  }
  g->dpsi = dpsi / 36000000.0; /* 0.0001″ -> deg */
  g->deps = deps / 36000000.0;

  /* 3.5 True obliquity (Laskar's polynomial in U = JME / 10, arcsec). */
  const double u = g->jme / 10.0;
  const double eps0 =
    84381.448 +
    u * (-4680.93 +
         u * (-1.55 +
              u * (1999.25 +
                   u * (-51.38 +
                        u * (-249.67 +
                             u * (-39.05 + u * (7.12 + u * (27.87 + u * (5.79 + u * 2.45)))))))));
  g->eps = eps0 / 3600.0 + g->deps;

  /* 3.6-3.7 Aberration and apparent sun longitude. */
  const double dtau = -20.4898 / (3600.0 * g->r);
  g->lambda = wrap360(theta + g->dpsi + dtau);

  /* 3.8 Apparent sidereal time at Greenwich. */
  const double nu0 = wrap360(280.46061837 + 360.98564736629 * d_ut +
                             g->jc * g->jc * (0.000387933 - g->jc / 38710000.0));
  const double eps_r = rad(g->eps);
  g->nu = wrap360(nu0 + g->dpsi * cos(eps_r));

  /* 3.9-3.10 Geocentric right ascension and declination. */
  const double lam = rad(g->lambda), bet = rad(beta);
  g->alpha = wrap360(
    deg(atan2(sin(lam) * cos(eps_r) - tan(bet) * sin(eps_r), cos(lam))));
  g->delta = deg(asin(clamp1(sin(bet) * cos(eps_r) + cos(bet) * sin(eps_r) * sin(lam))));
}

/* ------------------------------------------------------------------------------------------ */
/* Public API                                                                                 */

void ap_sun_params_init(ap_sun_params *p)
{
  if (!p) {
    return;
  }
  p->delta_t = NAN;
  p->delta_ut1 = 0.0;
  p->pressure = 1013.25;
  p->temperature = 15.0;
  p->atmos_refract = 0.5667;
  p->refraction = 1;
}

ap_status ap_sun_params_validate(const ap_sun_params *p)
{
  if (!p) {
    return AP_ERR_NULL_POINTER;
  }
  return ap_sun_params_invalid(p, NULL, NULL) ? AP_ERR_OUT_OF_RANGE : AP_OK;
}

const char *ap_sun_params_invalid(const ap_sun_params *p, double *lo, double *hi)
{
  if (!p) {
    return NULL;
  }
  /* each field's range, its ends included unless open; delta_t NaN: estimated */
  const ap_range_field fields[] = {
    { "delta_t", isnan(p->delta_t) ? 0.0 : p->delta_t, -100000.0, 100000.0, 0, 0 },
    { "delta_ut1", p->delta_ut1, -1.0, 1.0, 1, 1 },
    { "pressure", p->pressure, 0.0, 5000.0, 0, 0 },
    /* (not SPA's -273..6000: near -273 the refraction's factor 283 / (273 + T) lifted the
     * sun by tens of degrees, past the zenith; the air at the ground stays within these) */
    { "temperature", p->temperature, -100.0, 100.0, 0, 0 },
    { "atmos_refract", p->atmos_refract, 0.0, 4.0, 0, 0 },
  };
  return ap_range_first_outside(fields, sizeof fields / sizeof fields[0], lo, hi);
}

ap_status ap_sun_unix_time(int year, int month, int day, int hour, int minute, double second,
                           double *unix_seconds)
{
  if (!unix_seconds) {
    return AP_ERR_NULL_POINTER;
  }
  if (year < AP_SUN_YEAR_MIN || year > AP_SUN_YEAR_MAX || month < 1 || month > 12 || day < 1 ||
      day > ap_time_days_in_month(year, month) || hour < 0 || hour > 23 || minute < 0 ||
      minute > 59 || !(second >= 0.0 && second < 61.0)) {
    return AP_ERR_OUT_OF_RANGE;
  }
  *unix_seconds = (double)(ap_time_days_from_civil(year, month, day) * 86400LL + hour * 3600LL +
                           minute * 60LL) +
                  second;
  return AP_OK;
}

double ap_sun_julian_day(double unix_seconds)
{
  return unix_seconds / SECONDS_PER_DAY + 2440587.5;
}

double ap_sun_delta_t_estimate(double y)
{
  if (!isfinite(y)) {
    return NAN;
  }
  double t, u;
  if (y < -500.0 || y >= 2150.0) {
    u = (y - 1820.0) / 100.0;
    return -20.0 + 32.0 * u * u;
  }
  if (y < 500.0) {
    u = y / 100.0;
    return 10583.6 +
           u * (-1014.41 +
                u * (33.78311 +
                     u * (-5.952053 + u * (-0.1798452 + u * (0.022174192 + u * 0.0090316521)))));
  }
  if (y < 1600.0) {
    u = (y - 1000.0) / 100.0;
    return 1574.2 +
           u * (-556.01 +
                u * (71.23472 +
                     u * (0.319781 + u * (-0.8503463 + u * (-0.005050998 + u * 0.0083572073)))));
  }
  if (y < 1700.0) {
    t = y - 1600.0;
    return 120.0 + t * (-0.9808 + t * (-0.01532 + t / 7129.0));
  }
  if (y < 1800.0) {
    t = y - 1700.0;
    return 8.83 + t * (0.1603 + t * (-0.0059285 + t * (0.00013336 - t / 1174000.0)));
  }
  if (y < 1860.0) {
    t = y - 1800.0;
    return 13.72 +
           t * (-0.332447 +
                t * (0.0068612 +
                     t * (0.0041116 +
                          t * (-0.00037436 +
                               t * (0.0000121272 + t * (-0.0000001699 + t * 0.000000000875))))));
  }
  if (y < 1900.0) {
    t = y - 1860.0;
    return 7.62 +
           t * (0.5737 + t * (-0.251754 + t * (0.01680668 + t * (-0.0004473624 + t / 233174.0))));
  }
  if (y < 1920.0) {
    t = y - 1900.0;
    return -2.79 + t * (1.494119 + t * (-0.0598939 + t * (0.0061966 - t * 0.000197)));
  }
  if (y < 1941.0) {
    t = y - 1920.0;
    return 21.20 + t * (0.84493 + t * (-0.076100 + t * 0.0020936));
  }
  if (y < 1961.0) {
    t = y - 1950.0;
    return 29.07 + t * (0.407 + t * (-1.0 / 233.0 + t / 2547.0));
  }
  if (y < 1986.0) {
    t = y - 1975.0;
    return 45.45 + t * (1.067 + t * (-1.0 / 260.0 - t / 718.0));
  }
  if (y < 2005.0) {
    t = y - 2000.0;
    return 63.86 +
           t * (0.3345 + t * (-0.060374 + t * (0.0017275 + t * (0.000651814 + t * 0.00002373599))));
  }
  if (y < 2050.0) {
    t = y - 2000.0;
    return 62.92 + t * (0.32217 + t * 0.005589);
  }
  u = (y - 1820.0) / 100.0; /* 2050..2150 */
  return -20.0 + 32.0 * u * u - 0.5628 * (2150.0 - y);
}

double ap_sun_refraction(const ap_sun_params *p, double elevation_true_deg)
{
  if (!p->refraction || !(elevation_true_deg >= -(SUN_RADIUS_DEG + p->atmos_refract))) {
    return 0.0;
  }
  /* Sæmundsson's formula scaled by pressure and temperature, degrees. */
  const double e0 = elevation_true_deg;
  return (p->pressure / 1010.0) * (283.0 / (273.0 + p->temperature)) * 1.02 /
         (60.0 * tan(rad(e0 + 10.3 / (e0 + 5.11))));
}

ap_status ap_sun_position(const ap_sun_params *p, double t, double lat_deg, double lon_deg,
                          double height_m, ap_sun_position_result *out)
{
  if (!p || !out) {
    return AP_ERR_NULL_POINTER;
  }
  ap_status st = ap_sun_params_validate(p);
  if (st != AP_OK) {
    return st;
  }
  double year;
  if (!in_range(lat_deg, -90.0, 90.0) || !in_range(lon_deg, -180.0, 180.0) ||
      !in_range(height_m, -6.5e6, 1e8) || !instant_ok(t, &year)) {
    return AP_ERR_OUT_OF_RANGE;
  }
  ap_sun_position_result r;
  r.delta_t = isnan(p->delta_t) ? ap_sun_delta_t_estimate(year) : p->delta_t;

  /* 3.1 Julian day (UT1) and ephemeris day (TT), kept as days since J2000.0 for precision. */
  const double d_ut = (t + p->delta_ut1 - UNIX_J2000) / SECONDS_PER_DAY;
  const double d_tt = d_ut + r.delta_t / SECONDS_PER_DAY;
  r.jd = 2451545.0 + d_ut;
  r.jde = 2451545.0 + d_tt;

  geo g;
  geocentric(d_ut, d_tt, &g);
  r.helio_longitude = g.l;
  r.helio_latitude = g.b;
  r.distance = g.r;
  r.nutation_longitude = g.dpsi;
  r.nutation_obliquity = g.deps;
  r.obliquity = g.eps;
  r.apparent_longitude = g.lambda;
  r.sidereal_time = g.nu;
  r.right_ascension = g.alpha;
  r.declination = g.delta;

  /* 3.11 Observer local hour angle. */
  r.hour_angle = wrap360(g.nu + lon_deg - g.alpha);

  /* 3.12 Topocentric right ascension: equatorial horizontal parallax ξ, the
   * observer's geocentric position terms u, x, y, and the parallax in right ascension. */
  const double phi = rad(lat_deg);
  const double xi = rad(8.794 / (3600.0 * g.r));
  const double uu = atan(0.99664719 * tan(phi));
  const double x = cos(uu) + height_m / 6378140.0 * cos(phi);
  const double y = 0.99664719 * sin(uu) + height_m / 6378140.0 * sin(phi);
  const double h = rad(r.hour_angle), dec = rad(g.delta);
  const double den = cos(dec) - x * sin(xi) * cos(h);
  const double dalpha = atan2(-x * sin(xi) * sin(h), den);
  r.topo_right_ascension = wrap360(g.alpha + deg(dalpha));
  const double dec_t = atan2((sin(dec) - y * sin(xi)) * cos(dalpha), den);
  r.topo_declination = deg(dec_t);
  /* 3.13 Topocentric local hour angle. */
  r.topo_hour_angle = wrap360(r.hour_angle - deg(dalpha));
  const double h_t = rad(r.topo_hour_angle);

  /* 3.14 Topocentric zenith angle. */
  r.elevation_true =
    deg(asin(clamp1(sin(phi) * sin(dec_t) + cos(phi) * cos(dec_t) * cos(h_t))));
  r.refraction = ap_sun_refraction(p, r.elevation_true);
  r.elevation = r.elevation_true + r.refraction;
  r.zenith = 90.0 - r.elevation;
  r.zenith_true = 90.0 - r.elevation_true;

  /* 3.15 Topocentric azimuth. */
  r.azimuth_astro =
    wrap360(deg(atan2(sin(h_t), cos(h_t) * sin(phi) - tan(dec_t) * cos(phi))));
  r.azimuth = wrap360(r.azimuth_astro + 180.0);

  /* A.1 Equation of time: sun's mean longitude M, then minutes in [-20, 20]. */
  const double jme = g.jme;
  const double m =
    wrap360(280.4664567 +
            jme * (360007.6982779 +
                   jme * (0.03032028 + jme * (1.0 / 49931.0 +
                                              jme * (-1.0 / 15300.0 - jme / 2000000.0)))));
  double eot = 4.0 * (m - 0.0057183 - g.alpha + g.dpsi * cos(rad(g.eps)));
  if (eot > 20.0) {
    eot -= 1440.0;
  } else if (eot < -20.0) {
    eot += 1440.0;
  }
  r.equation_of_time = eot;

  /* ALGORITHMS.md §4.4: semidiameter 959.63″ at 1 AU. */
  r.angular_radius = 959.63 / 3600.0 / g.r;

  *out = r;
  return AP_OK;
}

ap_status ap_sun_incidence(const ap_sun_position_result *sun, double slope_deg,
                           double aspect_deg, double *incidence_deg)
{
  if (!sun || !incidence_deg) {
    return AP_ERR_NULL_POINTER;
  }
  if (!in_range(slope_deg, 0.0, 180.0) || !isfinite(aspect_deg) ||
      !in_range(sun->zenith, -1.0, 181.0) || !isfinite(sun->azimuth)) {
    return AP_ERR_OUT_OF_RANGE;
  }
  /* 3.16 Incidence, with Γ − γ = Φ − aspect (both measured from the same origin). */
  const double th = rad(sun->zenith), w = rad(slope_deg);
  const double c =
    cos(th) * cos(w) + sin(w) * sin(th) * cos(rad(sun->azimuth - aspect_deg));
  *incidence_deg = deg(acos(clamp1(c)));
  return AP_OK;
}

/* The report's Appendix A.2 interpolation over one day: the apparent sidereal time at its
 * midnight, the geocentric right ascension and declination at midnight (alpha0, delta0, deg)
 * and their differences to the day before (a, ad) and after (b, bd); n0 = ΔT in days. */
typedef struct rts_day {
  double nu, lon, sin_phi, cos_phi, n0, alpha0, delta0, a, b, ad, bd;
} rts_day;

/* Samples of the day's altitude for its rise and set: every 5 minutes. */
#define RTS_SAMPLES 288

/* Geocentric altitude (deg, no refraction, no parallax) at fraction f of the day from its
 * midnight (the report's steps 6-10 at one instant); the local hour angle into *ha (deg,
 * [-180, 180)) when ha is not NULL. */
static double rts_altitude(const rts_day *d, double f, double *ha)
{
  const double nu_f = d->nu + 360.985647 * f;
  const double n = f + d->n0;
  const double alpha = d->alpha0 + n * (d->a + d->b + (d->b - d->a) * n) / 2.0;
  const double dec = rad(d->delta0 + n * (d->ad + d->bd + (d->bd - d->ad) * n) / 2.0);
  const double h = wrap180(nu_f + d->lon - alpha);
  if (ha) {
    *ha = h;
  }
  return deg(asin(clamp1(d->sin_phi * sin(dec) + d->cos_phi * cos(dec) * cos(rad(h)))));
}

ap_status ap_sun_rise_transit_set(const ap_sun_params *p, int year, int month, int day,
                                  double utc_offset_hours, double lat_deg, double lon_deg,
                                  ap_sun_rts_result *out)
{
  if (!p || !out) {
    return AP_ERR_NULL_POINTER;
  }
  ap_status st = ap_sun_params_validate(p);
  if (st != AP_OK) {
    return st;
  }
  if (year < AP_SUN_YEAR_MIN || year > AP_SUN_YEAR_MAX || month < 1 || month > 12 || day < 1 ||
      day > ap_time_days_in_month(year, month) || !in_range(utc_offset_hours, -18.0, 18.0) ||
      !in_range(lat_deg, -90.0, 90.0) || !in_range(lon_deg, -180.0, 180.0)) {
    return AP_ERR_OUT_OF_RANGE;
  }
  const double dt = isnan(p->delta_t)
                      ? ap_sun_delta_t_estimate((double)year + ((double)month - 0.5) / 12.0)
                      : p->delta_t;

  /* A.2 step 1-2: local midnight as a UT instant (0 UT when the offset is 0); the apparent
   * sidereal time there and the geocentric α, δ at that midnight and ±1 day, with ΔT = 0. */
  const double t0 = (double)ap_time_days_from_civil(year, month, day) * SECONDS_PER_DAY -
                    utc_offset_hours * 3600.0;
  const double d0 = (t0 - UNIX_J2000) / SECONDS_PER_DAY;
  geo g[3];
  for (int k = 0; k < 3; ++k) {
    geocentric(d0 + (k - 1), d0 + (k - 1), &g[k]);
  }
  const double nu = g[1].nu;
  const double alpha0 = g[1].alpha, delta0 = g[1].delta;
  const double phi = rad(lat_deg);
  const double h0p = -(SUN_RADIUS_DEG + (p->refraction ? p->atmos_refract : 0.0));

  ap_sun_rts_result r;
  r.rise_set_altitude = h0p;

  /* Step 3, 6-10 and 11 for the transit: approximate transit m0, corrected by its hour angle
   * at the interpolated sidereal time and right ascension. The report's α difference above 2°
   * reduced to its fractional part undoes the 360° wrap; wrapping it to [-180, 180) does that
   * for every case. */
  rts_day rd;
  rd.nu = nu;
  rd.lon = lon_deg;
  rd.sin_phi = sin(phi);
  rd.cos_phi = cos(phi);
  rd.n0 = dt / SECONDS_PER_DAY;
  rd.alpha0 = alpha0;
  rd.delta0 = delta0;
  rd.a = wrap180(alpha0 - g[0].alpha);
  rd.b = wrap180(g[2].alpha - alpha0);
  rd.ad = delta0 - g[0].delta;
  rd.bd = g[2].delta - delta0;
  const double m0 = frac01((alpha0 - lon_deg - nu) / 360.0);
  double ha0;
  r.transit_elevation = rts_altitude(&rd, m0, &ha0);
  double f[3] = { m0 - ha0 / 360.0, NAN, NAN };
  /* The correction can take the transit out of the day, when it falls within a minute of a
   * midnight: then the day's transit is the next cycle's (or the previous one's), if that one
   * lies in the day; transits 24 h plus some seconds apart leave one day of the year with none
   * (NaN; transit_elevation then stays the nearest transit's, about which, f0, the events are
   * chosen below). */
  const double utc = p->delta_ut1 / SECONDS_PER_DAY; /* (the day is UTC's; f are UT1's) */
  double f0 = f[0];
  if (f0 - utc < 0.0 || f0 - utc >= 1.0) {
    const double m1 = m0 + (f0 - utc < 0.0 ? 1.0 : -1.0);
    double ha1;
    const double e1 = rts_altitude(&rd, m1, &ha1);
    const double f1 = m1 - ha1 / 360.0;
    f[0] = NAN;
    if (f1 - utc >= 0.0 && f1 - utc < 1.0) {
      f[0] = f0 = f1;
      r.transit_elevation = e1;
    }
  }

  /* Sunrise and sunset: where the interpolated altitude crosses h0' upwards and downwards in the
   * day ([utc, 1 + utc] in UT1's fractions: UTC's day, as the transit's) (the report's step 4-5
   * and 12-13 instead take the hour angle H0 from the declination at midnight and correct each
   * event once, which near the start and end of polar day and night gave days of the wrong kind
   * and events hours off, even in the wrong order). Sampled every 5 minutes, and at the transit
   * and the anti-transit, the altitude's highest and lowest points, so that a graze above or below
   * h0' between samples is not lost; each crossing found by bisection to 1e-9 day. Where the day
   * has several of a kind, sunrise is the last before the transit (else the first) and sunset the
   * first after it (else the last). No crossing: polar day or night by the altitude's sign, the
   * same all day. */
  double xs[RTS_SAMPLES + 4], ys[RTS_SAMPLES + 4];
  int nx = 0;
  {
    const double fixed[3] = { f0 - 0.5, f0, f0 + 0.5 }; /* (ascending) */
    double extra[3];
    int ne = 0;
    for (int k = 0; k < 3; ++k) {
      if (fixed[k] > utc && fixed[k] < 1.0 + utc) {
        extra[ne++] = fixed[k];
      }
    }
    for (int k = 0, e = 0; k <= RTS_SAMPLES; ++k) {
      const double x = utc + (double)k / RTS_SAMPLES;
      while (e < ne && extra[e] < x) {
        xs[nx++] = extra[e++];
      }
      xs[nx++] = x;
    }
  }
  for (int k = 0; k < nx; ++k) {
    ys[k] = rts_altitude(&rd, xs[k], NULL) - h0p;
  }
  double rise_before = NAN, rise_after = NAN, set_before = NAN, set_after = NAN;
  for (int k = 0; k + 1 < nx; ++k) {
    const int up = ys[k] < 0.0 && ys[k + 1] >= 0.0, down = ys[k] >= 0.0 && ys[k + 1] < 0.0;
    if (!up && !down) {
      continue;
    }
    double lo = xs[k], hi = xs[k + 1];
    while (hi - lo > 1e-9) {
      const double mid = 0.5 * (lo + hi);
      if ((rts_altitude(&rd, mid, NULL) - h0p < 0.0) == up) {
        lo = mid;
      } else {
        hi = mid;
      }
    }
    const double x = 0.5 * (lo + hi);
    if (up && x <= f0) {
      rise_before = x; /* (the last) */
    } else if (up && isnan(rise_after)) {
      rise_after = x;
    } else if (down && x < f0) {
      set_before = x; /* (the last) */
    } else if (down && isnan(set_after)) {
      set_after = x;
    }
  }
  const double rise = isnan(rise_before) ? rise_after : rise_before;
  const double set = isnan(set_after) ? set_before : set_after;
  if (!isnan(rise) || !isnan(set)) {
    r.kind = AP_SUN_DAY_NORMAL;
  } else {
    r.kind = ys[0] >= 0.0 ? AP_SUN_DAY_POLAR_DAY : AP_SUN_DAY_POLAR_NIGHT;
  }
  f[1] = rise;
  f[2] = set;
  double inst[3], hour[3];
  for (int i = 0; i < 3; ++i) {
    /* Events are in UT1; UTC = UT1 - delta_ut1. */
    inst[i] = t0 + f[i] * SECONDS_PER_DAY - p->delta_ut1;
    hour[i] = 24.0 * frac01((inst[i] - t0) / SECONDS_PER_DAY);
  }
  r.transit = inst[0];
  r.sunrise = inst[1];
  r.sunset = inst[2];
  r.transit_hour = hour[0];
  r.sunrise_hour = hour[1];
  r.sunset_hour = hour[2];
  *out = r;
  return AP_OK;
}
