/* SPDX-License-Identifier: BSD-3-Clause */
/** @file ap_sun.h
 *  @brief Position of the sun seen from a point on the Earth, and the day's sunrise, transit
 *         and sunset: the NREL Solar Position Algorithm (SPA).
 *
 *  Method: Reda I., Andreas A., "Solar Position Algorithm for Solar Radiation Applications",
 *  NREL/TP-560-34302 (rev. 2008; Solar Energy 76(5):577–589, 2004), written from the report's
 *  equations and its published tables (truncated VSOP87 Earth series, IAU 1980 nutation with
 *  63 terms; Meeus, Astronomical Algorithms). Stated uncertainty ±0.0003° in zenith and azimuth
 *  for the years −2000..6000 given the right ΔT. ALGORITHMS.md §4.
 *
 *  ## Time
 *  An instant is a `double` of POSIX seconds: UTC seconds since 1970-01-01T00:00:00Z without
 *  leap seconds, on the proleptic Gregorian calendar (also before 1582-10-15; the report
 *  switches to the Julian calendar there, this API does not). Its resolution is better than
 *  0.03 ms over the supported years −2000..6000 (astronomical numbering: year 0 = 1 BC).
 *  Universal time UT1 = UTC + delta_ut1; terrestrial time TT = UT1 + delta_t.
 *
 *  ## Frames and units
 *  Angles in degrees. Latitude north-positive (geodetic, on the report's ellipsoid: equatorial
 *  radius 6378140 m, polar/equatorial axis ratio 0.99664719),
 *  longitude east-positive, height in metres above the ellipsoid (the report's "elevation").
 *  Azimuth clockwise from true north in [0, 360) (the report's observers' azimuth Φ); right
 *  ascension and hour angles in [0, 360) unless noted; positions are apparent (nutation,
 *  aberration) and, where named topocentric, include parallax for the observer's place.
 *
 *  ## Threads and errors
 *  Every function is reentrant (no globals, no allocation, no lazy initialisation). Bad
 *  arguments give AP_ERR_NULL_POINTER or AP_ERR_OUT_OF_RANGE and leave outputs untouched.
 */
#ifndef AP_SUN_H
#define AP_SUN_H

#include "ap_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Limits of the supported calendar years (inclusive), as the report's. */
#define AP_SUN_YEAR_MIN (-2000)
#define AP_SUN_YEAR_MAX 6000

/** Options; always start from ap_sun_params_init(). */
typedef struct ap_sun_params {
  double delta_t;       /**< ΔT = TT − UT1 (s), |ΔT| <= 100000; NaN (default): estimated from
                             the instant's year and month with the Espenak & Meeus (2006)
                             polynomials, see ap_sun_delta_t_estimate() */
  double delta_ut1;     /**< UT1 − UTC (s), −1 < delta_ut1 < 1 (default 0; IERS Bulletin A) */
  double pressure;      /**< mean local air pressure (hPa = mbar), 0..5000 (default 1013.25) */
  double temperature;   /**< mean local air temperature (°C), −100..100 (default 15; SPA's
                         *   −273..6000 let the refraction lift the sun past the zenith) */
  double atmos_refract; /**< refraction at the horizon (deg), 0..4 (default 0.5667): sets the
                             lowest sun elevation −(0.26667 + atmos_refract) at which
                             refraction is still applied, and the rise/set altitude */
  int refraction;       /**< nonzero: refract the elevation (default 1); 0: elevation and
                             zenith equal their geometric (true) values */
} ap_sun_params;

/** Everything ap_sun_position() computes for one instant and place. */
typedef struct ap_sun_position_result {
  /* Time */
  double jd;                /**< Julian day of the instant in UT1 */
  double jde;               /**< Julian ephemeris day (TT) = jd + delta_t / 86400 */
  double delta_t;           /**< ΔT used (s): the parameter, or its estimate */
  /* Heliocentric and geocentric (apparent, equinox of date) */
  double helio_longitude;   /**< L, Earth heliocentric longitude (deg, [0, 360)) */
  double helio_latitude;    /**< B, Earth heliocentric latitude (deg) */
  double distance;          /**< R, Earth–Sun distance (AU) */
  double nutation_longitude; /**< Δψ (deg) */
  double nutation_obliquity; /**< Δε (deg) */
  double obliquity;         /**< ε, true obliquity of the ecliptic (deg) */
  double apparent_longitude; /**< λ, apparent sun longitude (deg, [0, 360)) */
  double sidereal_time;     /**< ν, apparent sidereal time at Greenwich (deg, [0, 360)) */
  double right_ascension;   /**< α, geocentric right ascension (deg, [0, 360)) */
  double declination;       /**< δ, geocentric declination (deg) */
  double hour_angle;        /**< H = ν + longitude − α, observer local hour angle (deg, [0, 360)) */
  /* Topocentric (parallax for the observer's place and height) */
  double topo_right_ascension; /**< α' (deg, [0, 360)) */
  double topo_declination;  /**< δ' (deg) */
  double topo_hour_angle;   /**< H' (deg, [0, 360)) */
  double elevation_true;    /**< e0, geometric elevation, no refraction (deg, −90..90) */
  double refraction;        /**< Δe added by refraction (deg); 0 below the cut-off or when off */
  double elevation;         /**< e = e0 + Δe, apparent elevation (deg) */
  double zenith;            /**< θ = 90 − e, apparent zenith angle (deg) */
  double zenith_true;       /**< 90 − e0 (deg) */
  double azimuth;           /**< Φ, clockwise from true north (deg, [0, 360)) */
  double azimuth_astro;     /**< Γ = Φ − 180, astronomers' azimuth, westward from south
                                 (deg, [0, 360)) */
  /* Derived */
  double equation_of_time;  /**< apparent − mean solar time (minutes, in [−20, 20]) */
  double angular_radius;    /**< apparent radius of the sun's disc = 959.63″ / R (deg) */
} ap_sun_position_result;

/** Set the defaults documented on each field. NULL is ignored. */
void ap_sun_params_init(ap_sun_params *p);

/** Check options: AP_ERR_NULL_POINTER, AP_ERR_OUT_OF_RANGE (a field outside its documented
 *  range or not finite; delta_t may be NaN) or AP_OK. */
ap_status ap_sun_params_validate(const ap_sun_params *p);

/** The first field of p that ap_sun_params_validate refuses, for messages: its name in the
 *  struct ("delta_t", "delta_ut1", "pressure", "temperature", "atmos_refract"), its range in
 *  *lo and *hi (either may be NULL; delta_ut1's ends excluded).
 *  NULL when every field is valid, or p is NULL. */
const char *ap_sun_params_invalid(const ap_sun_params *p, double *lo, double *hi);

/** POSIX seconds of the UTC civil time year-month-day hour:minute:second (proleptic Gregorian).
 *  Requires AP_SUN_YEAR_MIN <= year <= AP_SUN_YEAR_MAX, 1 <= month <= 12, 1 <= day <= days in
 *  that month, 0 <= hour <= 23, 0 <= minute <= 59, 0 <= second < 61 (a leap second 23:59:60
 *  maps to the next midnight); otherwise AP_ERR_OUT_OF_RANGE. */
ap_status ap_sun_unix_time(int year, int month, int day, int hour, int minute, double second,
                           double *unix_seconds);

/** Julian day of a POSIX instant, unix_seconds / 86400 + 2440587.5 (no range check). */
double ap_sun_julian_day(double unix_seconds);

/** ΔT = TT − UT (s) estimated for a decimal year y = year + (month − 0.5) / 12 with the
 *  polynomials of Espenak & Meeus, "Five Millennium Canon of Solar Eclipses" (NASA TP-2006-
 *  214141; −20 + 32 u², u = (y − 1820) / 100 outside −500..2150). The 2005–2050 branch is an
 *  extrapolation that runs a few seconds above the measured ΔT in the 2020s; at −2000 the
 *  estimate (~47000 s) is uncertain by hours. A ΔT error of 1 s moves the sun by only
 *  ~0.00001° (UT, not TT, drives the Earth's rotation). NaN for a non-finite y. */
double ap_sun_delta_t_estimate(double decimal_year);

/** Sun position at instant t (POSIX seconds, UTC) seen from latitude lat_deg ∈ [−90, 90],
 *  longitude lon_deg ∈ [−180, 180] and height height_m ∈ [−6.5e6, 1e8] m.
 *  Errors: NULL p or out → AP_ERR_NULL_POINTER; bad params (see ap_sun_params_validate),
 *  non-finite inputs, or an instant outside the years −2000..6000 → AP_ERR_OUT_OF_RANGE. */
ap_status ap_sun_position(const ap_sun_params *p, double t, double lat_deg, double lon_deg,
                          double height_m, ap_sun_position_result *out);

/** The refraction (deg) ap_sun_position adds to a geometric elevation (deg) with p's
 *  atmosphere: Sæmundsson's formula scaled by pressure and temperature, 0 with refraction off
 *  and below the report's cut-off −(0.26667 + atmos_refract) (where the apparent elevation
 *  therefore jumps by about 0.6°). p is assumed valid (ap_sun_params_validate). */
double ap_sun_refraction(const ap_sun_params *p, double elevation_true_deg);

/** Angle of incidence (deg, [0, 180]) of sunlight on a plane surface, from the apparent
 *  (refracted) zenith and azimuth of `sun`: cos I = cos θ cos s + sin s sin θ cos(Φ − a),
 *  s = slope_deg ∈ [0, 180] from the horizontal, a = aspect_deg (any finite value) the azimuth,
 *  clockwise from north, toward which the surface faces (the horizontal projection of its
 *  normal). The report's azm_rotation γ (from south, east negative) is a = 180 + γ.
 *  Errors: NULL → AP_ERR_NULL_POINTER; bad angles → AP_ERR_OUT_OF_RANGE. */
ap_status ap_sun_incidence(const ap_sun_position_result *sun, double slope_deg,
                           double aspect_deg, double *incidence_deg);

/** What happens to the sun on a day, relative to the rise/set altitude. */
typedef enum ap_sun_day_kind {
  AP_SUN_DAY_NORMAL = 0,  /**< the sun rises or sets (both, but next to polar day or night) */
  AP_SUN_DAY_POLAR_DAY,   /**< the sun stays above the rise/set altitude (never sets) */
  AP_SUN_DAY_POLAR_NIGHT  /**< the sun stays below the rise/set altitude (never rises) */
} ap_sun_day_kind;

/** Sunrise, transit and sunset of one day. */
typedef struct ap_sun_rts_result {
  ap_sun_day_kind kind;
  double sunrise;        /**< POSIX seconds (UTC); NaN unless kind is AP_SUN_DAY_NORMAL, and */
  double transit;        /**< on a day on which the sun only sets (sunrise NaN) or only rises */
  double sunset;         /**< (sunset NaN), next to polar day or night; transit (sun on the
                              local meridian) NaN only on a day without one (below) */
  double sunrise_hour;   /**< time of day of each event at the given UTC offset (hours, */
  double transit_hour;   /**< [0, 24)), as the report prints them; NaN where the */
  double sunset_hour;    /**< instant is NaN */
  double transit_elevation; /**< geocentric elevation at transit, no refraction (deg) */
  double rise_set_altitude; /**< h0' used (deg): −(0.26667 + atmos_refract), i.e. the
                                 report's −0.8333 by default; −0.26667 with refraction off */
} ap_sun_rts_result;

/** Sunrise, sun transit and sunset for the day year-month-day starting at local midnight at
 *  UTC offset utc_offset_hours ∈ [−18, 18], on the report's Appendix A.2 model: the apparent
 *  sidereal time and the sun's geocentric right ascension and declination at that midnight and
 *  ±1 day, interpolated to any instant of the day. The transit is the report's (its
 *  approximate transit corrected by the hour angle there). Sunrise and sunset are where that
 *  model's altitude crosses the rise/set altitude h0' upwards and downwards within the day
 *  (sampled every 5 minutes and at the transit and anti-transit, then bisected to 1e-4 s),
 *  not the report's single correction of events placed by the declination at midnight,
 *  which near the start and end of polar day and night gave days of the wrong kind, events
 *  hours off, and a sunrise after the sunset. Every event lies in the day; with offset 0 the
 *  day is the report's UT day, whose events it prints in local time (its sunset of the
 *  example, 00:20 UT, is that of the evening before in local time); with the local offset these are
 *  the events of the local day. Transits fall 24 hours give or take half a minute apart: where two
 *  more than 24 hours apart straddle a day (a few days a year at places whose midnight is within a
 *  minute of solar noon, as at ±180° of longitude at UTC), that day has none (NaN), and its sunrise
 *  and sunset are chosen about the nearest. Where a day has two crossings of one kind, sunrise is
 *  the last before the transit (else the first) and sunset the first after it (else the last).
 *  Parallax is neglected, as in the report; params as for ap_sun_position (delta_ut1 shifts the
 *  results from UT1 to UTC; pressure and temperature are unused). The date is proleptic Gregorian,
 *  year in −2000..6000. Errors: NULL → AP_ERR_NULL_POINTER; bad date, place or params →
 *  AP_ERR_OUT_OF_RANGE. Polar day and night (no crossing in the day) are results (kind), not
 *  errors.
 *  Accuracy: rise and set within 3 s and transit within 0.1 s of PyEphem (sun centre at
 *  −0.8333°, 1950–2050) for |latitude| <= 65°; the example's events within 1 s of the
 *  report's; beyond, the kind agrees with the full algorithm's elevation through the day
 *  wherever its extremes clear h0' by 0.01°, and the events are where the full algorithm puts
 *  the sun at h0' within 0.01° (a minute of time at 89°, where the sun's altitude changes by
 *  0.004° a minute: parallax is 0.002°). About 40 µs (300 evaluations of the interpolation). */
ap_status ap_sun_rise_transit_set(const ap_sun_params *p, int year, int month, int day,
                                  double utc_offset_hours, double lat_deg, double lon_deg,
                                  ap_sun_rts_result *out);

#ifdef __cplusplus
}
#endif

#endif /* AP_SUN_H */
