/* SPDX-License-Identifier: BSD-3-Clause */
/** @file ap_sky.h
 *  @brief Sun and sky radiometry for a physically scaled terrain shader: optical air mass,
 *         clear-sky direct normal irradiance, the sun's colour, sky radiance models, and sky
 *         radiance averaged or cosine-integrated over a spherical cap (the aperture of
 *         ALGORITHMS.md §6.3).
 *
 *  ## Frame, angles, units
 *  Directions are ENU vectors (x east, y north, z up; ALGORITHMS.md conventions) of any
 *  non-zero finite length (they are normalised here); ap_sky_enu_direction() builds one from a
 *  compass azimuth (clockwise from north) and an elevation. Angles are radians. The sun's
 *  zenith angle Z is the *apparent* (refracted) one, as a topocentric ephemeris such as SPA
 *  returns it; its elevation is π/2 − Z. Irradiance is W/m², radiance W/(m²·sr).
 *
 *  Colour is linear RGB with Rec.709 / sRGB primaries and D65 white (IEC 61966-2-1 without the
 *  transfer curve): XYZ → RGB by the matrix derived from the primaries (0.64, 0.33),
 *  (0.30, 0.60), (0.15, 0.06) and white (0.3127, 0.3290). Every RGB value here is radiometric
 *  and scaled so that its Rec.709 luminance 0.2126 R + 0.7152 G + 0.0722 B equals the
 *  broadband quantity it stands for (the sun's DNI, a sky radiance or irradiance): a grey
 *  quantity of q W/m² is (q, q, q). (Exactly: the luminance row (0.2126390, 0.7151687, 0.0721923)
 *  of the derived matrix.) Chromaticities outside the Rec.709 gamut (the deepest sunset reds)
 *  give negative components; they are clamped to 0 and the triple rescaled to keep its
 *  luminance.
 *
 *  ## Sun (ap_sky_air_mass, ap_sky_clear_irradiance, ap_sky_sunlight_compute)
 *  * Relative optical air mass, Kasten & Young (1989), Z in degrees:
 *        m(Z) = 1 / (cos Z + 0.50572 (96.07995 − Z)^−1.6364)
 *    (apparent Z; pvlib documents the same requirement), finite at the horizon:
 *    m(90°) = 37.92. Site height h enters as the barometric pressure ratio of the ESRA model
 *    (Rigollier, Bauer & Wald 2000, after Kasten): m_p = m · p/p0, p/p0 = exp(−h / 8434.5 m).
 *    Below the horizon (Z > 90°) the air mass is +INFINITY and every direct quantity is 0;
 *    the step at Z = 90° is the model's (the partly set disc is the horizon visibility's
 *    business, ALGORITHMS.md §6.2).
 *  * Direct normal irradiance, ESRA clear-sky model (Rigollier, Bauer & Wald, "On the clear sky
 *    model of the ESRA — European Solar Radiation Atlas — with respect to the Heliosat method",
 *    Solar Energy 68(1):33–48, 2000), with Linke turbidity T_L (at air mass 2):
 *        DNI = S0 / R² · exp(−0.8662 · T_L · m_p · δR(m_p))
 *        1/δR(m) = 6.6296 + 1.7513 m − 0.1202 m² + 0.0065 m³ − 0.00013 m⁴   (m ≤ 20)
 *        1/δR(m) = 10.4 + 0.718 m                                           (m > 20)
 *    S0 = 1361 W/m² (the nominal total solar irradiance at 1 AU of IAU 2015 Resolution B3),
 *    R the Earth–Sun distance in AU. δR is evaluated at the pressure-corrected air mass, as
 *    GRASS r.sun does; the paper's finer correction of δR for high sites is not applied.
 *    Diffuse horizontal irradiance of the same model (used to scale the sky, below):
 *        D = S0 / R² · T_rd(T_L) · F_d(γ, T_L),  γ = solar elevation,
 *        T_rd = −1.5843e-2 + 3.0543e-2 T_L + 3.797e-4 T_L²,
 *        F_d = A0 + A1 sin γ + A2 sin² γ,
 *        A0 = 2.6463e-1 − 6.1581e-2 T_L + 3.1408e-3 T_L²  (A0 = 2e-3 / T_rd if A0·T_rd < 2e-3),
 *        A1 = 2.0402 + 1.8945e-2 T_L − 1.1161e-2 T_L²,
 *        A2 = −1.3025 + 3.9231e-2 T_L + 8.5079e-3 T_L²;   D = 0 below the horizon.
 *  * Sun colour: the extraterrestrial solar spectrum of Preetham, Shirley & Smits (1999; their
 *    table, 380–750 nm every 10 nm, from Iqbal 1983; held constant to 780 nm, where the CIE
 *    functions are below 2e-4 of their peak), times the spectral transmittance Preetham et al.
 *    use (after Iqbal, "An Introduction to Solar Radiation", 1983), λ in µm, turbidity T:
 *        τ_R = exp(−m_p · 0.008735 λ^−4.08)                     Rayleigh
 *        τ_A = exp(−m · β λ^−1.3),  β = 0.04608365822050 T − 0.04586025928522   aerosol
 *        τ_O = exp(−m · k_o(λ) · l),  l = ozone column (cm, default 0.35), k_o from Iqbal's
 *              table as reproduced with Preetham's code (Chappuis band)
 *    (Rayleigh with the pressure-corrected air mass, aerosol and ozone with the sea-level one;
 *    Preetham's mixed-gas and water-vapour terms are left out: they absorb mainly at
 *    720–770 nm, where the colour matching functions are below 0.3 % of their peak). The
 *    spectrum is integrated against the CIE 1931 2° colour matching functions at 380–780 nm
 *    every 10 nm (the CIE table, typed in; not a fitted approximation) → XYZ → linear Rec.709
 *    RGB. Normalisation: the chromaticity comes from this spectral model, the magnitude from
 *    the ESRA DNI; RGB is scaled so that its luminance equals the DNI (W/m²). The beam is
 *    warmer than D65 (which includes the blue sky): at the zenith with T = 2 it is
 *    (x, y) = (0.330, 0.341), about 5600 K, R : G : B = 1.15 : 1 : 0.89; it reddens
 *    monotonically as the sun goes down.
 *
 *  ## Sky (ap_sky_prepare, ap_sky_radiance, ap_sky_cap)
 *  θ = zenith angle of the viewing direction, γ = its angle to the sun, Z = sun zenith angle.
 *  Directions below the horizon (z < 0) have zero sky radiance: there is no ground-reflected
 *  light in this module (no ground albedo).
 *  * AP_SKY_UNIFORM: L = E_h / π.
 *  * AP_SKY_CIE_OVERCAST (Moon & Spencer 1942; CIE standard overcast sky):
 *        L = L_z (1 + 2 cos θ) / 3,  E_h = (7π/9) L_z.
 *  * AP_SKY_CIE_CLEAR (CIE 1973 clear sky, Kittler; = CIE general sky with gradation
 *    (a, b) = (−1, −0.32) and indicatrix (c, d, e) = (10, −3, 0.45); the formula of
 *    ALGORITHMS.md §6.5, not re-checked against the CIE text):
 *        L/L_z = f(γ) φ(θ) / (f(Z) φ(0)),  f(γ) = 0.91 + 10 e^{−3γ} + 0.45 cos² γ,
 *        φ(θ) = 1 − e^{−0.32 / cos θ};  L_z from E_h by quadrature of the shape.
 *  * AP_SKY_PREETHAM (Preetham, Shirley & Smits, "A practical analytic model for daylight",
 *    SIGGRAPH 1999): Y, x, y each = (zenith value) · F(θ, γ) / F(0, Z), with the Perez form
 *    F = (1 + A e^{B / cos θ})(1 + C e^{Dγ} + E cos² γ), coefficients linear in T and zenith
 *    values Y_z (kcd/m²), x_z, y_z as in ALGORITHMS.md §6.5 (x_z's first coefficient 0.00166).
 *    Y (cd/m²) becomes radiance by a luminous efficacy K (default 130 lm/W, the clear-sky
 *    diffuse average of Littlefair's 1985 review, which gives ~110 lm/W for overcast skies):
 *    L_Y = 1000 Y / K W/(m²·sr); (x, y, L_Y) → XYZ → RGB. The zenith values are evaluated at
 *    min(Z, 90°); the model has no twilight, so with its native scale the sky is black once
 *    the sun is below the horizon (Z > 90°).
 *  E_h is the sky's (luminance-weighted) irradiance on an unobstructed horizontal surface.
 *  If params.diffuse_horizontal >= 0 it is that value, for every model (the Preetham sky is
 *  then rescaled, keeping its shape and colour). Otherwise (the default) it comes from a model:
 *  UNIFORM and CIE_CLEAR: the ESRA clear-sky diffuse D above; CIE_OVERCAST: Kasten & Czeplak
 *  (Solar Energy 24:177–189, 1980), global irradiance at 8/8 cloud = 0.25 × clear-sky global
 *  (G(N) = G_clear (1 − 0.75 (N/8)^3.4)), all of it diffuse: E_h = 0.25 (DNI cos Z + D);
 *  PREETHAM: its own absolute luminance. The CIE models are achromatic (R = G = B, D65 white).
 *  With a given E_h, a sun below the horizon keeps the sky's shape (CIE clear evaluated with
 *  the actual Z, Preetham with its zenith values at Z = 90°); the default scales are 0 there.
 *
 *  ## Cap quadrature (ap_sky_cap)
 *  The region integrated is the cap (axis a, radius r <= 90°) ∩ the sky above the horizon
 *  [∩ the front of the surface, n·ω >= 0, for the irradiance]: convex, bounded by at most three
 *  circles. It is integrated in polar coordinates (t, ψ) about a pole strictly inside it
 *  (dω = sin t dt dψ): an approximate Chebyshev centre of the region (the cap's axis when that
 *  is deep enough), so that no boundary passes near the pole. Each ray from the pole leaves the
 *  region once; its length is found exactly and the ray is integrated by params.cap_rings-point
 *  Gauss–Legendre in t. In ψ the circle is cut at the region's corners (where two boundary
 *  circles cross), so the ray length is smooth on every piece, and the pieces are covered by
 *  8-point Gauss–Legendre on about params.cap_sectors / 8 sub-intervals in all. The CIE clear
 *  and Preetham skies have a cusp at the sun (e^{Dγ}, γ the angle to the sun), wherever the sun
 *  is: ψ is also cut at the sun's direction from the pole, and a ray that passes the sun is
 *  split at its point nearest to it, each part by cap_rings points. Horizon and surface
 *  clipping are therefore exact, and the cusp sits on the pieces' ends, where the rules are
 *  good. Cost at the defaults (8 × 32): 256 radiance evaluations per integral; for the clear
 *  skies 344 on the mean over random caps and suns (the rays passing the sun count twice).
 *  Accuracy at the defaults, as an absolute error relative to L·π sin² r (irradiance) or to L
 *  (mean radiance), L = the zenith radiance: unclipped caps of a uniform or CIE overcast sky,
 *  exact to rounding (< 1e-10; the integrands are entire functions of t); uniform sky clipped
 *  by horizon and/or surface, r = 5–90°, any tilt, < 1.2e-4 (Snyder 1996 closed form,
 *  ALGORITHMS.md §6.1). Preetham and CIE clear skies, caps of 2–90° anywhere, the sun inside or
 *  outside (1,200 random caps and surfaces for each model and range of the sun's elevation,
 *  against a 64 × 4096 reference that a brute-force midpoint rule confirms to 1e-5): Preetham
 *  below 2e-4 at any sun; CIE clear below 4.5e-4 with the sun above 15°, up to 1.7e-3 with it
 *  0–15° high and up to 2.6e-3 with it below the horizon (a given E_h), where its brightness
 *  peak then lies just outside the region, near a corner (up to 0.1% of the value itself).
 *  16 × 64 points (4 times the cost) give below 5e-5 in all these cases. Slivers thinner than
 *  about r/2000 count as empty. The horizontal irradiance E_h that the sky is scaled to is
 *  computed once in ap_sky_prepare by the same scheme over the hemisphere, about the zenith
 *  with 24 × 96 points: < 2e-5 relative (CIE clear < 1e-6), the sun anywhere.
 *
 *  ## Use and threads
 *      ap_sky_params p; ap_sky_params_init(&p);  ...set fields...
 *      ap_sky_sunlight sun;  ap_sky_sunlight_compute(&p, zenith, &sun);   (direct beam)
 *      ap_sky_state sky;     ap_sky_prepare(&p, sun_enu, &sky);           (once per sun)
 *      ap_sky_radiance(&sky, dir, rgb);  ap_sky_cap(&sky, axis, r, n, mean, irr);  (any number)
 *  Everything is reentrant: no globals except constant tables, no allocation; an
 *  ap_sky_state is read-only after ap_sky_prepare and may be shared by threads.
 *  On failure, every numeric output that is not NULL is set to NaN.
 */
#ifndef AP_SKY_H
#define AP_SKY_H

#include "ap_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Spectral grid of ap_sky_spectrum_to_xyz: 380, 390, …, 780 nm. */
#define AP_SKY_SPECTRUM_SAMPLES 41
#define AP_SKY_SPECTRUM_FIRST_NM 380.0
#define AP_SKY_SPECTRUM_STEP_NM 10.0

/** Largest params.cap_rings (size of the Gauss–Legendre tables kept in ap_sky_state). */
#define AP_SKY_MAX_RINGS 64
/** Gauss–Legendre points per azimuth sub-interval of the cap quadrature. */
#define AP_SKY_PSI_ORDER 8

/** Sky radiance models (see the file comment). */
typedef enum ap_sky_model {
  AP_SKY_UNIFORM = 0,   /**< constant radiance E_h / π */
  AP_SKY_CIE_OVERCAST,  /**< CIE standard overcast sky, L_z (1 + 2 cos θ) / 3 */
  AP_SKY_CIE_CLEAR,     /**< CIE 1973 clear sky */
  AP_SKY_PREETHAM       /**< Preetham, Shirley & Smits 1999, coloured */
} ap_sky_model;

/** Options; always start from ap_sky_params_init(). Ranges are checked by
 *  ap_sky_params_validate() (AP_ERR_INVALID_ARGUMENT outside them, NaN included). */
typedef struct ap_sky_params {
  ap_sky_model model;        /**< sky model (default AP_SKY_PREETHAM) */
  double turbidity;          /**< Preetham turbidity T, [2, 10]: sun colour and the Preetham sky
                                  (default 3) */
  double linke_turbidity;    /**< Linke turbidity T_L at air mass 2, [1, 8]: ESRA DNI and diffuse
                                  (default 3). Both are ratios of the hazy to the clean-air optical
                                  thickness; equal values are a reasonable pairing. */
  double earth_sun_distance; /**< R in AU, [0.9, 1.1] (the real range is 0.983–1.017;
                                  default 1) */
  double site_height;        /**< metres above sea level, [−1000, 10000] (default 0) */
  double solar_constant;     /**< S0, W/m² at 1 AU, (0, 2000] (default 1361) */
  double ozone;              /**< ozone column, cm NTP, [0, 1] (default 0.35, Preetham's value) */
  double diffuse_horizontal; /**< E_h, W/m², finite: >= 0 sets the sky's horizontal irradiance;
                                  < 0 takes it from the model (default −1) */
  double luminous_efficacy;  /**< K, lm/W, [50, 683]: Preetham luminance → radiance
                                  (default 130) */
  int cap_rings;             /**< Gauss–Legendre points along each ray of a cap, 1..64
                                  (default 8) */
  int cap_sectors;           /**< about this many ray directions around a cap's pole, 8..4096
                                  (default 32) */
} ap_sky_params;

/** The direct beam for one sun position (ap_sky_sunlight_compute). */
typedef struct ap_sky_sunlight {
  double air_mass;        /**< pressure-corrected relative air mass m_p; +INFINITY below the
                               horizon */
  double dni;             /**< direct normal irradiance, W/m² (0 below the horizon) */
  double rgb[3];          /**< the same irradiance as linear Rec.709 RGB, W/m² per channel;
                               luminance = dni */
  double chromaticity[2]; /**< CIE 1931 (x, y) of the transmitted beam; NaN below the horizon */
} ap_sky_sunlight;

/** A sky for one sun position, filled by ap_sky_prepare(); read-only afterwards. Only the
 *  first four fields are for reading; the rest are private. */
typedef struct ap_sky_state {
  double sun[3];                /**< unit sun direction, ENU */
  double sun_zenith;            /**< Z, radians, [0, π] */
  double horizontal_irradiance; /**< E_h, W/m²: the sky's luminance-weighted irradiance on an
                                     unobstructed horizontal surface */
  double zenith_radiance[3];    /**< RGB radiance of the zenith, W/(m²·sr) */
  /* private */
  unsigned magic;
  ap_sky_model model;
  double scale;                 /* W/(m²·sr) per unit of the shape function */
  double perez[3][5];           /* Preetham: A..E for Y, x, y */
  double inv_f0[3];             /* Preetham: 1 / F(0, Z) for Y, x, y */
  double zenith_xy[2];          /* Preetham: x_z, y_z */
  double clear_norm;            /* CIE clear: 1 / (f(Z) φ(0)) */
  int rings, sectors;
  double gl_node[AP_SKY_MAX_RINGS], gl_weight[AP_SKY_MAX_RINGS];
  double psi_node[AP_SKY_PSI_ORDER], psi_weight[AP_SKY_PSI_ORDER];
} ap_sky_state;

/** Set the defaults documented on each field. NULL is ignored. */
void ap_sky_params_init(ap_sky_params *p);

/** AP_OK, AP_ERR_NULL_POINTER, or AP_ERR_INVALID_ARGUMENT for a field outside its range. */
ap_status ap_sky_params_validate(const ap_sky_params *p);

/** The first field of p that ap_sky_params_validate refuses, for messages: its name in the
 *  struct ("turbidity", "linke_turbidity", "site_height", "diffuse_horizontal", ... in the
 *  struct's order; "model" for an unknown model), its range in *lo and *hi (either may be
 *  NULL; -inf..inf for diffuse_horizontal, which must be finite; the model's enumerators for
 *  "model"). NULL when every field is valid, or p is NULL. */
const char *ap_sky_params_invalid(const ap_sky_params *p, double *lo, double *hi);

/** Unit ENU direction from a compass azimuth (radians, clockwise from north) and an elevation
 *  (radians): (cos e sin φ, cos e cos φ, sin e). AP_ERR_INVALID_ARGUMENT for non-finite input. */
ap_status ap_sky_enu_direction(double azimuth, double elevation, double v[3]);

/** Pressure-corrected relative optical air mass m_p (Kasten & Young 1989 × exp(−h/8434.5)) for
 *  the apparent sun zenith angle `zenith` in [0, π] (radians) at `site_height` metres in
 *  [−1000, 10000]. +INFINITY when zenith > π/2. AP_ERR_INVALID_ARGUMENT for input out of
 *  range (NaN included). */
ap_status ap_sky_air_mass(double zenith, double site_height, double *air_mass);

/** Preetham's Rayleigh × aerosol transmittance τ_R τ_A at `wavelength_nm` (> 0) through
 *  `air_mass` (>= 0, may be +INFINITY) with turbidity T in [2, 10] (one air mass for both
 *  terms, as in Preetham's code; no ozone). */
ap_status ap_sky_preetham_transmittance(double wavelength_nm, double air_mass, double turbidity,
                                        double *tau);

/** ESRA clear-sky direct normal and diffuse horizontal irradiance (W/m²) for the apparent sun
 *  zenith angle in [0, π]; uses linke_turbidity, earth_sun_distance, site_height and
 *  solar_constant. Either output may be NULL. Both are 0 below the horizon. */
ap_status ap_sky_clear_irradiance(const ap_sky_params *p, double zenith, double *dni,
                                  double *diffuse_horizontal);

/** The direct beam: air mass, ESRA DNI, and its colour from the spectral model (file comment).
 *  zenith: apparent sun zenith angle in [0, π]. */
ap_status ap_sky_sunlight_compute(const ap_sky_params *p, double zenith, ap_sky_sunlight *out);

/** Set up the sky of params.model for the sun in direction `sun` (ENU, any non-zero length;
 *  may point below the horizon). Validates the params. */
ap_status ap_sky_prepare(const ap_sky_params *p, const double sun[3], ap_sky_state *s);

/** Sky radiance (RGB, W/(m²·sr)) arriving from direction `dir` (ENU, non-zero; 0 below the
 *  horizon). AP_ERR_INVALID_ARGUMENT for a NaN, infinite or zero-length direction or a state
 *  that ap_sky_prepare did not fill. */
ap_status ap_sky_radiance(const ap_sky_state *s, const double dir[3], double rgb[3]);

/** Caps of a smaller radius (rad; 21″) are taken as their axis by ap_sky_cap: below it the
 *  quadrature's depths lose digits in 1 − cos r faster than the cap's mean departs from the
 *  axis's radiance (4e-8 relative at this radius, 4e-6 at 1e-5; nothing left below 1e-8).
 *  A cap that close to the horizon (or, for the irradiance, to the surface's plane) counts as
 *  wholly on its axis's side of it. */
#define AP_SKY_POINT_CAP 1e-4

/** Integrals of the sky over the cap of axis `axis` (ENU, any non-zero length) and angular
 *  radius `radius` in [0, π/2] (radians; an aperture is at most a hemisphere, ALGORITHMS.md
 *  §6.3), by the quadrature of the file comment:
 *  - mean_radiance: (1/Ω) ∫_cap L dω, Ω = 4π sin²(r/2) the whole cap's solid angle
 *    (directions below the horizon count as zero radiance); for r < AP_SKY_POINT_CAP (r = 0
 *    included), the radiance at the axis;
 *  - irradiance: ∫_cap L(ω) max(0, n·ω) dω onto a surface of normal `normal` (W/m²); for
 *    r < AP_SKY_POINT_CAP, L(axis) Ω max(0, n·axis).
 *  Either output may be NULL (they must not overlap); `normal` (ENU, non-zero) is needed only
 *  with `irradiance`. AP_ERR_INVALID_ARGUMENT for a radius outside [0, π/2] or NaN, a NaN,
 *  infinite or zero-length axis or normal, or an unprepared state. */
ap_status ap_sky_cap(const ap_sky_state *s, const double axis[3], double radius,
                     const double normal[3], double mean_radiance[3], double irradiance[3]);

/** CIE 1931 XYZ of a spectrum sampled at AP_SKY_SPECTRUM_SAMPLES wavelengths 380..780 nm
 *  every 10 nm: X = Σ S(λ) xbar(λ) Δλ (Δλ = 10 nm), likewise Y, Z; with S in W/(m²·nm),
 *  Y is the ybar-weighted irradiance in W/m² (illuminance = 683 lm/W × Y). */
ap_status ap_sky_spectrum_to_xyz(const double spectrum[AP_SKY_SPECTRUM_SAMPLES], double xyz[3]);

/** Linear Rec.709 RGB (D65 white) of CIE XYZ; no clamping. xyz and rgb may be the same array. */
ap_status ap_sky_xyz_to_rgb(const double xyz[3], double rgb[3]);

#ifdef __cplusplus
}
#endif

#endif /* AP_SKY_H */
