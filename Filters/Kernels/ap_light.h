/* SPDX-License-Identifier: BSD-3-Clause */
/** @file ap_light.h
 *  @brief Sun-and-sky lighting of a terrain point from its aperture (Oat & Sander 2007): the
 *         CPU reference that the GLSL terrain shader mirrors formula for formula.
 *
 *  ## Frame, units
 *  Vectors are unit-length ENU (x east, y north, z up); angles are radians; irradiance E is
 *  W/m², radiance L is W/(m²·sr); colours are linear RGB triples, each channel computed alike.
 *  Ω(r) = 2π(1 − cos r) = 4π sin²(r/2) is the solid angle of a cap of angular radius r (the
 *  sin² form keeps its digits in float for the sun's 4.65e-3 rad).
 *
 *  ## Inputs
 *  Per point: surface normal n; bent normal b, the axis of the aperture cap (the visible sky as
 *  one spherical cap); aperture radius rp in [0, π/2] (larger values are clamped to π/2, e.g.
 *  +INFINITY); albedo a[3] in [0, 1]. A point is *nodata* (every output NaN) when n or b is
 *  not finite or not unit within | |v|² − 1 | <= AP_LIGHT_UNIT_TOLERANCE (a zero vector
 *  included), rp is NaN or negative, or an albedo is NaN or outside [0, 1]. Vectors within the
 *  tolerance are normalised before use (GLSL: normalize()).
 *  Global (ap_light_params): sun direction s, sun cap radius rl in [AP_LIGHT_MIN_SUN_RADIUS,
 *  π/2] (the sun's apparent angular radius times a user scale), sun irradiance Esun (normal to
 *  the beam, whole disc), sky radiance Lsky (uniform over the aperture), the intersection and
 *  Lambert modes, and the exposure EV.
 *
 *  ## The model (per point; ALGORITHMS.md §1, §6)
 *  1. Sun radiance L_sun = Esun / (π sin² rl): a fully visible sun on a surface facing it
 *     receives ∫_cap cos = π sin² rl times L_sun, exactly Esun. Ω_l = 4π sin²(rl/2).
 *  2. d = angle between b and s = atan2(|b × s|, b · s) (not acos: acos loses the small angles).
 *     A_vis = |aperture cap ∩ sun cap| = A(rp, rl, d) by the intersection mode; 0 if rp == 0.
 *     * AP_LIGHT_EXACT (ALGORITHMS.md (1.1)/(1.2); Tovchigrechko & Vakser 2001): with
 *       r1, r2 in [0, π] and four cases:
 *           d <= |r1 − r2|          contained:  A = Ω(min(r1, r2))
 *           d >= r1 + r2            disjoint:   A = 0
 *           d >= 2π − r1 − r2       union covers the sphere: A = Ω(r1) + Ω(r2) − 4π
 *           otherwise (partial), half-angle / L'Huilier form:
 *           σ  = (r1 + r2 + d)/2,   k = sqrt( sin(σ−r1) sin(σ−r2) sin(σ−d) / sin σ )
 *           α1 = 2 atan2(k, sin(σ−r2)),   α2 = 2 atan2(k, sin(σ−r1))   (angles at the axes)
 *           E  = 4 atan( sqrt( tan(σ/2) tan((σ−r1)/2) tan((σ−r2)/2) tan((σ−d)/2) ) )
 *           A  = 4 α1 sin²(r1/2) + 4 α2 sin²(r2/2) − 2E
 *       Every sine and tangent takes a sum or difference of angles, so nothing cancels: in
 *       float, the sun cap against apertures of 0.3–1.5 rad, centre within ±0.9 rl of the rim,
 *       is within 3.6e-4 relative of double at the same (float) inputs (tested; 4.1e-4 against
 *       unrounded inputs), where the acos form of (1.1) is wrong by factors.
 *     * AP_LIGHT_SMOOTHSTEP (Oat & Sander 2007 §3.2, as in Filament's
 *       sphericalCapsIntersection): same contained / disjoint cases, otherwise
 *           A = Ω(min(r1, r2)) · x²(3 − 2x),  x = 1 − (d − |r1 − r2|) / (r1 + r2 − |r1 − r2|).
 *  3. Lambert term S (sr): the cosine-weighted visible part of the sun.
 *     * AP_LIGHT_CENTROID (Oat & Sander 2007 §3.3, with the exact centroid):
 *           S = A_vis · max(0, n · ĉ),
 *       ĉ = B_lens / |B_lens| for a partial overlap, B_lens = ∫_lens ω dω the lens's first
 *       moment (ALGORITHMS.md (1.4), from ∫_R ω dω = ½ ∮ ω × dω), taken about the axis c_s of
 *       the smaller cap, ½ ∮ (ω − c_s) × dω (the same vector: ∮ dω = 0), with c_o, r_o, α_o
 *       the other cap's and α_i as in 2:
 *           t_s = (c_o − cos d · c_s)/sin d,   t_o = (c_s − cos d · c_o)/sin d
 *           B_lens = sin r_s (α_s sin r_s · c_s + 2 sin²(r_s/2) sin α_s · t_s)
 *                  + sin r_o ([(α_o − sin α_o) sin r_o + 2 sin α_o cos u sin v] · c_o
 *                             + 2 sin α_o sin u sin v · t_o)
 *       with u = (r_o + d)/2, v = (r_o − d)/2 (sin r_o − sin d = 2 cos u sin v, cos d − cos r_o
 *       = 2 sin u sin v), and α − sin α by its series below α = 0.5. Every term is of the
 *       lens's size: about the sphere's centre, Σ_i sin r_i (α_i sin r_i · c_i − sin α_i cos r_i
 *       · t_i), the larger cap's rim gives two terms of ~ sin r_o α_o that cancel to the lens's
 *       ~ rl², and a float centroid of the sun straddling an aperture's rim turns by several
 *       rl. Contained: ĉ = the axis of the smaller cap (also when sin d = 0: the caps
 *       are concentric); disjoint: S = 0. Note: a fully visible sun gives S = Ω_l cos θ, so a
 *       facing surface receives Esun / cos²(rl/2), not Esun (1 + 5.4e-6 for the real sun,
 *       1 + 1.9e-3 for rl = 5°): area × cosine overestimates the cosine integral of a cap.
 *     * AP_LIGHT_EXACTCAP: S = C(n · s, sin² rl) · A_vis / Ω_l, the sun cap's exact Lambert
 *       integral clipped at the surface's plane, times the visible fraction of the disc.
 *       Both factors treat the two clippings as independent and the visible part as spread
 *       like the whole disc: with the sun half behind the aperture rim at zenith angle z the
 *       visible half is ~0.42 rl higher than the disc centre, so S is low by ~tan z · 0.42 rl
 *       (0.3 % at z = 1 rad for the real sun; CENTROID gets this right); where the rim lies in
 *       the surface's own plane (flat open ground) a grazing sun is clipped twice (half of
 *       the true value, within ±rl of grazing only).
 *     C(cos θ, sin² σ) = ∫_cap(σ) max(0, n · ω) dω for a cap of radius σ <= π/2 whose axis is at
 *     θ from n (Snyder 1996, "Area light sources for real-time graphics", MSR-TR-96-11, in the
 *     form of Lagarde & de Rousiers 2014, "Moving Frostbite to PBR", §4.7.2
 *     `illuminanceSphereOrDisk`; ALGORITHMS.md §6.1):
 *         cos²θ >= sin²σ (cap wholly on one side):  C = π sin²σ · max(cos θ, 0)
 *         otherwise:  x = sqrt(1/sin²σ − 1) = cot σ,  y = −x cos θ / sin θ,
 *                     sy = sin θ sqrt(1 − y²),  t = atan(sy / x)  (π/2 when x = 0),
 *                     C = max(0, (cos θ acos y − x sy) sin²σ + t).
 *     Check: C(cos θ, 1) = (π/2)(1 + cos θ) (the hemisphere).
 *  4. Sky (ALGORITHMS.md §6.3, Oat & Sander's "ambient" fill of the uncovered aperture):
 *         E_sky = Lsky · max(0, C(n · b, sin² rp) − S).
 *  5. E_sun = L_sun · S;  E = E_sun + E_sky;  outgoing radiance Lo = a/π · E (Lambertian).
 *  Display: x = Lo · 2^EV; tone map t = 1 − exp(−x); sRGB transfer (IEC 61966-2-1):
 *  v = 12.92 t for t <= 0.0031308, else 1.055 t^(1/2.4) − 0.055; 8 bits: round(255 v).
 *
 *  ## GLSL port
 *  The static functions of ap_light.c marked "shader core" use only what GLSL ES 3 / 3.30 has
 *  (sin, cos, tan, atan(y, x) for atan2, atan, acos, sqrt, exp, exp2, pow, min, max, clamp,
 *  round, dot, cross, length, normalize); the public wrappers add the domain checks, which
 *  the shader does by construction. A float port must keep the half-angle forms above, the
 *  sin² forms of Ω and 1 − cos r, atan2 for d, and the moment about the smaller cap's axis;
 *  and its atan2 must be good to a few float roundings at every size (the shader has its own,
 *  for acos too: GLSL leaves the built-in's precision to the implementation, and Mesa's, 2e-5
 *  relative near 0, costs the lens's cancelling terms a percent near the rim and C its
 *  grazing sliver). (C itself cancels in float when a small cap grazes the plane: cot σ ·
 *  sin²σ against σ; measured for the sun within ±rl of grazing, an absolute error <= 1.2e-5
 *  of the full-sun π sin² rl, invisible.) The uniforms of the
 *  port are what ap_light.c calls the setup: normalised s, rl, sin² rl, Ω_l, L_sun, Lsky, 2^EV,
 *  the modes.
 *
 *  ## Threads
 *  Everything is reentrant (no globals, no allocation, no threads). ap_light_points treats
 *  each point on its own, so the caller may split [0, n) among threads by offsetting the
 *  pointers; the results do not depend on the split.
 */
#ifndef AP_LIGHT_H
#define AP_LIGHT_H

#include <stddef.h>

#include "ap_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A vector v is unit when | |v|² − 1 | <= this (float-normalised vectors pass easily). */
#define AP_LIGHT_UNIT_TOLERANCE 1e-4

/** Smallest sun_radius (rad, 0.2″): keeps sin² rl a normal float and L_sun finite. */
#define AP_LIGHT_MIN_SUN_RADIUS 1e-6

/** |EV| <= this, so that 2^EV and Lo · 2^EV stay finite (and 0 · 2^EV is 0) in float. */
#define AP_LIGHT_MAX_EXPOSURE 64.0

/** How A_vis, the area of aperture cap ∩ sun cap, is computed. */
typedef enum ap_light_intersection {
  AP_LIGHT_EXACT = 0,     /**< exact area, half-angle / L'Huilier form (1.2) */
  AP_LIGHT_SMOOTHSTEP = 1 /**< Oat & Sander's smoothstep approximation (1.4 of ALGORITHMS.md) */
} ap_light_intersection;

/** How the cosine-weighted visible sun S is computed. */
typedef enum ap_light_lambert {
  AP_LIGHT_CENTROID = 0, /**< A_vis · cos(n, exact centroid of the lens) (Oat & Sander) */
  AP_LIGHT_EXACTCAP = 1  /**< clipped cap cosine integral × visible fraction A_vis / Ω_l */
} ap_light_lambert;

/** Relative position of two caps (ALGORITHMS.md §1.1). */
typedef enum ap_light_overlap {
  AP_LIGHT_DISJOINT = 0,     /**< d >= r1 + r2: no intersection */
  AP_LIGHT_CONTAINED = 1,    /**< d <= |r1 − r2|: the smaller cap lies in the larger */
  AP_LIGHT_PARTIAL = 2,      /**< the boundary circles cross: a lens */
  AP_LIGHT_COVERS_SPHERE = 3 /**< d >= 2π − r1 − r2: together they cover the sphere */
} ap_light_overlap;

/** Global lighting options; always start from ap_light_params_init(). Ranges are checked by
 *  ap_light_params_validate() (AP_ERR_INVALID_ARGUMENT outside them, NaN included). */
typedef struct ap_light_params {
  double sun[3];               /**< unit ENU direction to the sun's centre (default azimuth
                                    315°, elevation 45°: (−0.5, 0.5, √½), the cartographic
                                    north-west light) */
  double sun_radius;           /**< rl (rad), in [AP_LIGHT_MIN_SUN_RADIUS, π/2]: apparent
                                    radius × user scale (default 0.26667° = 4.6543e-3,
                                    SPA's SUN_RADIUS) */
  double sun_irradiance[3];    /**< Esun (W/m²), >= 0, normal to the beam, whole disc
                                    (default 1000 each) */
  double sky_radiance[3];      /**< Lsky (W/(m²·sr)), >= 0, uniform over the aperture
                                    (default 30 each: 94 W/m² on open flat ground) */
  ap_light_intersection intersection; /**< default AP_LIGHT_EXACT */
  ap_light_lambert lambert;           /**< default AP_LIGHT_EXACTCAP */
  double exposure;             /**< EV, |EV| <= AP_LIGHT_MAX_EXPOSURE; display x = Lo · 2^EV
                                    (default −6: albedo 0.3 in full sun at 45° shows 218/255) */
  const float *sky_table;      /**< optional (default NULL: the uniform sky_radiance): the sky
                                    radiance of caps, W/(m²·sr) RGB (cosine-weighted about
                                    their axes, as ComputeSkyTable tabulates it), that replaces
                                    sky_radiance for each point's own aperture; see
                                    ap_light_sky_lookup. Caller-owned, read only. */
  int sky_table_size[3];       /**< its azimuths, elevations and radii: 4..256, 2..256, 2..256 */
} ap_light_params;

/** Set the defaults documented on each field (NULL is ignored). */
void ap_light_params_init(ap_light_params *p);

/** The sky table's lookup, which the shader repeats exactly: for a cap of unit axis b and
 *  radius rp, with az = atan2(b_E, b_N) in [0, 2π) (clockwise from north), el = asin(b_U)
 *  clamped to [0, π/2] and r = rp clamped to [0, π/2], the table (na azimuths, ne elevations,
 *  nr radii; RGB triples, index ((k · ne + j) · na + i) · 3) holds the radiance of the cap
 *  with azimuth (i + ½) 2π / na (cell-centred, wrapping around), elevation j (π/2) / (ne − 1)
 *  and radius k (π/2) / (nr − 1) (nodes at both ends), and the value is the trilinear
 *  interpolation between the eight nodes around (az, el, r). Writes rgb; NaN for a b that is
 *  not finite, a NaN rp, or table sizes out of range (see sky_table_size). Without a table
 *  (NULL), rgb = p->sky_radiance. */
void ap_light_sky_lookup(const ap_light_params *p, const double b[3], double rp, double rgb[3]);

/** AP_OK, AP_ERR_NULL_POINTER, or AP_ERR_INVALID_ARGUMENT when a field is out of range: sun
 *  not finite or not unit (AP_LIGHT_UNIT_TOLERANCE), sun_radius not in
 *  [AP_LIGHT_MIN_SUN_RADIUS, π/2], a negative or non-finite irradiance or radiance (also any
 *  value of a sky table, or its sizes out of range), an
 *  unknown mode, EV not finite or beyond ±AP_LIGHT_MAX_EXPOSURE. */
ap_status ap_light_params_validate(const ap_light_params *p);

/* ---- Building blocks. Outside their domain (NaN included) they return NaN. ---- */

/** Ω(r) = 4π sin²(r/2) (sr), r in [0, π]. */
double ap_light_cap_area(double r);

/** Which case of §1.1 applies to caps of radii r1, r2 in [0, π] whose axes are d in [0, π]
 *  apart; -1 outside the domain. */
int ap_light_cap_overlap(double r1, double r2, double d);

/** Exact intersection area (sr) of two caps, all four cases (formula 2 above, EXACT). */
double ap_light_cap_intersection_exact(double r1, double r2, double d);

/** Oat & Sander's smoothstep approximation of the same area (SMOOTHSTEP). */
double ap_light_cap_intersection_smoothstep(double r1, double r2, double d);

/** First moment B = ∫ ω dω over the intersection of the cap (c1, r1) and the cap (c2, r2),
 *  c1 and c2 unit vectors (not checked), r1, r2 in [0, π]: (1.4) for a partial overlap,
 *  π sin² r · c for containment (smaller cap), 0 when disjoint, B1 + B2 when the caps cover
 *  the sphere. For any normal n with the region above n's plane, n · B is the region's exact
 *  Lambert integral. Returns the ap_light_overlap case, or -1 (B = NaN) outside the domain. */
int ap_light_lens_moment(double r1, double r2, const double c1[3], const double c2[3],
                         double B[3]);

/** Direction ĉ of the intersection's centroid as the CENTROID mode uses it: B / |B| for a
 *  partial overlap (or union), the smaller cap's axis for containment. Returns 1 and sets dir,
 *  or 0 with dir = (0, 0, 0) when there is no direction (disjoint, or |B| = 0 at tangency);
 *  -1 with dir = NaN outside the domain. */
int ap_light_lens_centroid(double r1, double r2, const double c1[3], const double c2[3],
                           double dir[3]);

/** C(cos θ, sin² σ) = ∫ over the cap of max(0, n · ω) dω (sr), formula in 3 above, for a cap
 *  of radius σ <= π/2: sin2s = sin² σ in [0, 1]; cos_t is clamped to [−1, 1]. */
double ap_light_cap_cosine_integral(double cos_t, double sin2s);

/* ---- The model ---- */

/** Lighting of one point: Lo[3] = outgoing radiance (W/(m²·sr)); E_sun[3] and E_sky[3] (W/m²,
 *  may be NULL) = the two irradiance components, E = E_sun + E_sky. A nodata point (see Inputs)
 *  sets every output to NaN and still returns AP_OK. Returns AP_ERR_NULL_POINTER (p, n, b,
 *  albedo or Lo NULL) or AP_ERR_INVALID_ARGUMENT (params invalid); outputs are then NaN. */
ap_status ap_light_point(const ap_light_params *p, const double n[3], const double b[3],
                         double rp, const double albedo[3], double Lo[3], double E_sun[3],
                         double E_sky[3]);

/** The model over n points (float in, double inside). normals and bent: 3 n values, xyz per
 *  point; aperture_radius: n values; albedo: an RGB triple per point, albedo_stride floats
 *  apart (3 for packed triples, 4 for RGBA, 0 for one triple shared by every point).
 *  Outputs (either may be NULL): radiance = 3 n floats, Lo per point (NaN for nodata);
 *  rgb8 = 3 n bytes, ap_light_display8 of each channel (0, 0, 0 for nodata).
 *  Returns AP_ERR_NULL_POINTER (p, or an input when n > 0), AP_ERR_INVALID_ARGUMENT (params, or
 *  albedo_stride 1 or 2), AP_ERR_SIZE_OVERFLOW, or AP_ERR_OVERLAP (an output overlaps an input
 *  or the other output); nothing is written then. */
ap_status ap_light_points(const ap_light_params *p, size_t n, const float *normals,
                          const float *bent, const float *aperture_radius, const float *albedo,
                          size_t albedo_stride, float *radiance, unsigned char *rgb8);

/** Tone map t = 1 − exp(−x) for x >= 0 (x = Lo · 2^EV); +INFINITY gives 1; NaN stays NaN. */
double ap_light_tonemap(double x);

/** sRGB transfer function (IEC 61966-2-1) of t in [0, 1]: 12.92 t for t <= 0.0031308, else
 *  1.055 t^(1/2.4) − 0.055. Values outside [0, 1] are clamped first; NaN stays NaN. */
double ap_light_srgb_encode(double t);

/** One display channel: round(255 · srgb_encode(tonemap(Lo · 2^EV))), 0 for NaN. */
unsigned char ap_light_display8(double Lo, double exposure);

#ifdef __cplusplus
}
#endif

#endif /* AP_LIGHT_H */
