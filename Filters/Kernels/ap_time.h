/* SPDX-License-Identifier: BSD-3-Clause */
/** @file ap_time.h
 *  @brief Instants, civil dates, Julian days, ISO 8601 text and IANA time zones (TZif) for the
 *         solar position code.
 *
 *  Time scale: UTC without leap seconds (POSIX time): every day has 86400 s, a leap second
 *  (hh:mm:60) cannot be written, and UTC is used as UT (|UT1 - UTC| < 0.9 s is ignored).
 *  Calendar: proleptic Gregorian with astronomical year numbering (year 0 = 1 BC, -1 = 2 BC).
 *  Supported range: the years AP_TIME_YEAR_MIN..AP_TIME_YEAR_MAX (-2000..6000) of NREL SPA,
 *  i.e. the instants -2000-01-01T00:00:00Z .. 6000-12-31T23:59:59.999...Z. Civil times (UTC or
 *  local) and instants outside it give AP_ERR_OUT_OF_RANGE; a local time whose UTC instant
 *  falls outside it does too.
 *  Everything is reentrant: no global state; a loaded ap_tz is immutable and may be shared by
 *  threads. Nothing here prints, exits or keeps a pointer to an argument.
 */
#ifndef AP_TIME_H
#define AP_TIME_H

#include <stddef.h>
#include <stdint.h>

#include "ap_status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define AP_TIME_YEAR_MIN (-2000) /**< first supported year */
#define AP_TIME_YEAR_MAX 6000    /**< last supported year */
/** Unix seconds of -2000-01-01T00:00:00Z, the first supported instant. */
#define AP_TIME_UNIX_MIN (-INT64_C(125281123200))
/** Unix seconds of 6000-12-31T23:59:59Z, the last whole second of the supported range. */
#define AP_TIME_UNIX_MAX INT64_C(127206115199)

/** A UTC instant: unix_seconds + fraction seconds after 1970-01-01T00:00:00Z (no leap seconds).
 *  Exact to the second over any range; `fraction` in [0, 1) carries sub-second time with a
 *  resolution of about 1e-16 s. Functions taking an instant return AP_ERR_INVALID_ARGUMENT
 *  for a fraction outside [0, 1) or NaN, AP_ERR_OUT_OF_RANGE outside the supported range. */
typedef struct ap_instant {
  int64_t unix_seconds; /**< whole seconds since the Unix epoch (floor; negative before 1970) */
  double fraction;      /**< seconds after unix_seconds, in [0, 1) */
} ap_instant;

/** Broken-down civil time (proleptic Gregorian, astronomical years). Whether it is UTC or a
 *  zone's local wall-clock time depends on the function. */
typedef struct ap_civil_time {
  int year;        /**< astronomical year, AP_TIME_YEAR_MIN..AP_TIME_YEAR_MAX */
  int month;       /**< 1..12 */
  int day;         /**< 1..28/29/30/31 */
  int hour;        /**< 0..23 (24:00 is not accepted) */
  int minute;      /**< 0..59 */
  int second;      /**< 0..59 (no leap second 60) */
  double fraction; /**< fraction of the second, [0, 1) */
} ap_civil_time;

/** Days from 1970-01-01 to year-month-day (H. Hinnant's days_from_civil; proleptic Gregorian).
 *  Exact for |year| <= 1e9; month 1..12 and day 1..31 are assumed, not checked (use
 *  ap_civil_validate). Example: (2000, 1, 1) -> 10957. */
int64_t ap_time_days_from_civil(int64_t year, int month, int day);

/** Inverse of ap_time_days_from_civil (Hinnant's civil_from_days) for |days| <= 3e11.
 *  Every output pointer must be non-NULL. */
void ap_time_civil_from_days(int64_t days, int64_t *year, int *month, int *day);

/** 1 if `year` is a Gregorian leap year, else 0. */
int ap_time_is_leap_year(int64_t year);

/** Days in `month` (1..12, not checked) of `year` on the proleptic Gregorian calendar. */
int ap_time_days_in_month(int64_t year, int month);

/** Check a civil time: AP_ERR_NULL_POINTER, AP_ERR_INVALID_ARGUMENT (a field outside the ranges
 *  documented on ap_civil_time, e.g. 2026-02-29 or second 60), AP_ERR_OUT_OF_RANGE (year outside
 *  the supported range), else AP_OK. */
ap_status ap_civil_validate(const ap_civil_time *c);

/** UTC civil time -> instant. Errors as ap_civil_validate; *out is untouched on error. */
ap_status ap_instant_from_civil(const ap_civil_time *utc, ap_instant *out);

/** Instant -> UTC civil time. Errors: NULL_POINTER, INVALID_ARGUMENT, OUT_OF_RANGE. */
ap_status ap_instant_to_civil(ap_instant t, ap_civil_time *out);

/** t + seconds (any finite value, e.g. a time step); the result must be in range
 *  (AP_ERR_OUT_OF_RANGE) and seconds finite (AP_ERR_INVALID_ARGUMENT). Exact when `seconds` is a
 *  whole number; otherwise the only rounding is that of the new fraction (<= 1.2e-16 s). */
ap_status ap_instant_add_seconds(ap_instant t, double seconds, ap_instant *out);

/** A Julian day (UT) split in two doubles: JD = midnight + day_fraction. */
typedef struct ap_julian_day {
  double midnight;     /**< JD of 0h UTC of the UTC date: an integer + 0.5, exact (990574.5 for
                            -2000-01-01, 2451544.5 for 2000-01-01) */
  double day_fraction; /**< (seconds since 0h UTC) / 86400 in [0, 1); error < 1e-16 day */
} ap_julian_day;

/** Instant -> Julian day. Keep the two parts apart for full precision: their sum as one double
 *  has a resolution of at most 2^-31 day (40 us) over the supported range (JD < 2^22).
 *  Example: 2000-01-01T12:00:00Z -> {2451544.5, 0.5}. Errors: NULL_POINTER, INVALID_ARGUMENT,
 *  OUT_OF_RANGE. */
ap_status ap_instant_to_julian_day(ap_instant t, ap_julian_day *out);

/** Write t as ISO 8601 UTC, "YYYY-MM-DDTHH:MM:SSZ" or with `fraction_digits` (0..9) digits after
 *  a '.', rounded to nearest (a carry may advance the seconds, and so the date; in the range's
 *  last second the digits are truncated instead, so that the text stays in range). Years 0..9999
 *  have 4 digits, negative years are written "-YYYY" (e.g. "-0044-03-15T12:00:00Z"). `size`
 *  counts the terminating NUL (21 + fraction digits + (1 if any) + (1 if year < 0) suffices).
 *  Errors: NULL_POINTER; INVALID_ARGUMENT (fraction_digits or t.fraction bad); OUT_OF_RANGE;
 *  BUFFER_TOO_SMALL (then buf is "" if size > 0). */
ap_status ap_instant_format_iso8601(ap_instant t, int fraction_digits, char *buf, size_t size);

/** As ap_instant_format_iso8601 but as the local time at `utc_offset` seconds east of UTC
 *  (|utc_offset| < 26 h), with the offset as "+HH:MM"/"-HH:MM" ("+00:00" for 0), or
 *  "+HH:MM:SS" when the offset has seconds (historical local mean time; not ISO 8601, and not
 *  read back by ap_time_parse_iso8601). Needs up to 6 (or 9) more bytes than the UTC form.
 *  AP_ERR_OUT_OF_RANGE also for a local time in the year before or after the supported range
 *  (an instant in its first or last hours), which ap_time_parse_iso8601 would not read. */
ap_status ap_instant_format_iso8601_local(ap_instant t, int32_t utc_offset, int fraction_digits,
                                          char *buf, size_t size);

/* --------------------------------------------------------------------------------------------
 * ISO 8601 text
 * ------------------------------------------------------------------------------------------ */

/** Result of ap_time_parse_iso8601. */
typedef struct ap_parsed_time {
  ap_civil_time local; /**< the fields as written (wall-clock time at utc_offset, or in an
                            unspecified zone when has_offset is 0); midnight for a date alone */
  int has_time;        /**< 1 if a time of day was given, 0 for a date alone */
  int has_offset;      /**< 1 if "Z" or a numeric offset was given; 0 = local time, needs a zone */
  int32_t utc_offset;  /**< seconds east of UTC (local = UTC + offset); 0 for "Z" or no offset */
} ap_parsed_time;

/** Parse an ISO 8601 / RFC 3339 date-time. Accepted, in full and nothing else (no surrounding
 *  space):
 *    date:   YYYY-MM-DD; or a signed year of 4..6 digits, "-YYYY-MM-DD" / "+YYYYY-MM-DD"
 *    time:   after 'T', 't' or one space: HH:MM, HH:MM:SS, HH:MM:SS.f (1..9 digits, '.' or ',')
 *    offset: after a time only: 'Z'/'z', +HH:MM, +HHMM, +HH or the same with '-'; at most 18:00;
 *            "-00:00" is read as UTC
 *  A date alone means midnight (has_time = 0). Not accepted: hour 24 (write the next day's
 *  00:00), second 60 (no leap seconds), a fraction on minutes, week or ordinal dates, the basic
 *  format (20260621T1200). Errors: AP_ERR_NULL_POINTER; AP_ERR_PARSE for any syntax error or
 *  impossible field (month 13, day 0, 2026-02-29, minute 60, an offset beyond 18:00, more than 9
 *  fraction digits, trailing characters); AP_ERR_OUT_OF_RANGE for a well-formed date whose year
 *  is outside -2000..6000. *out is written only on success. */
ap_status ap_time_parse_iso8601(const char *text, ap_parsed_time *out);

/* --------------------------------------------------------------------------------------------
 * IANA time zones
 * ------------------------------------------------------------------------------------------ */

/** A time zone loaded from a TZif file (RFC 8536, versions 1..4): transition table plus the
 *  footer's POSIX TZ rule for instants after the last transition. Opaque, immutable. */
typedef struct ap_tz ap_tz;

#define AP_TZ_NAME_MAX 255  /**< longest accepted zone name, in bytes */
#define AP_TZ_ABBR_SIZE 16  /**< size of an abbreviation buffer, NUL included; longer ones
                                 are cut */

/** Load the zone `name` ("Europe/Zurich", "Etc/GMT-14", ...) from `zoneinfo_dir`/`name`.
 *  zoneinfo_dir NULL or "" means $TZDIR when set and not empty (read once, here), else
 *  "/usr/share/zoneinfo". "UTC" and "Etc/UTC" are built in and need no file.
 *  Names: 1..AP_TZ_NAME_MAX bytes of [A-Za-z0-9_+-/], components separated by single '/', no
 *  leading or trailing '/' (so no absolute path, no "." or ".."); anything else gives
 *  AP_ERR_NOT_FOUND, as does a missing or unreadable file (or a directory).
 *  AP_ERR_BAD_FILE: not TZif, truncated, inconsistent (every count, index, abbreviation and the
 *  footer are checked), larger than 1 MiB, UTC offsets beyond [-89999, 93599] s, or a leap-second
 *  table ("right/" zones; leap seconds are not supported). AP_ERR_OUT_OF_MEMORY,
 *  AP_ERR_NULL_POINTER (name or out). On success *out owns the zone (free with ap_tz_free);
 *  on error *out is set to NULL. */
ap_status ap_tz_load(const char *name, const char *zoneinfo_dir, ap_tz **out);

/** Free a zone from ap_tz_load; NULL is allowed. */
void ap_tz_free(ap_tz *tz);

/** The name given to ap_tz_load (owned by tz); "" for NULL. */
const char *ap_tz_name(const ap_tz *tz);

/** The state of a zone at one instant. */
typedef struct ap_tz_info {
  int32_t utc_offset;                  /**< seconds east of UTC: local = UTC + utc_offset */
  int is_dst;                          /**< 1 during daylight saving time, else 0 */
  char abbreviation[AP_TZ_ABBR_SIZE];  /**< e.g. "CEST", "+0530"; NUL-terminated */
} ap_tz_info;

/** UTC offset, DST flag and abbreviation of `tz` at instant t. Before the first transition the
 *  file's first time type applies; after the last one, the footer rule (or, without one, the
 *  last type). Errors: NULL_POINTER, INVALID_ARGUMENT, OUT_OF_RANGE. */
ap_status ap_tz_lookup(const ap_tz *tz, ap_instant t, ap_tz_info *out);

/** What to do with a local time that a clock change skips or repeats. */
typedef enum ap_tz_choice {
  AP_TZ_CHOOSE_ERROR = 0, /**< fail with AP_ERR_TIME_NONEXISTENT / AP_ERR_TIME_AMBIGUOUS */
  AP_TZ_CHOOSE_EARLIER,   /**< take the earlier candidate instant (see ap_tz_local_result) */
  AP_TZ_CHOOSE_LATER      /**< take the later candidate instant */
} ap_tz_choice;

/** Details of a local -> UTC conversion, for choosing or for an error message. */
typedef struct ap_tz_local_result {
  int count;             /**< instants that show this local time: 1, 0 (skipped: in a gap)
                              or 2 (repeated: in an overlap; more only in odd zone files) */
  ap_instant earlier;    /**< count 1: the instant; count 2: the first one; count 0: the local
                              time read with the offset after the change (e.g. 02:30 at +02:00
                              = 00:30Z, before the change) */
  ap_instant later;      /**< count 1: the instant; count 2: the last one; count 0: the local
                              time read with the offset before the change (02:30 at +01:00 =
                              01:30Z, which clocks show as 03:30) */
  int has_transition;    /**< 1 when count != 1 and the clock change was found (always, for a
                              valid zone file) */
  ap_instant transition; /**< instant of that clock change (e.g. 2026-03-29T01:00:00Z) */
  ap_tz_info before;     /**< zone state just before the change (count 1: at the instant) */
  ap_tz_info after;      /**< zone state from the change on (count 1: at the instant); clocks
                              jump from transition + before.utc_offset to
                              transition + after.utc_offset */
} ap_tz_local_result;

/** Local wall-clock time in `tz` -> UTC instant. With exactly one match, *out is it. In a gap
 *  (spring forward) `if_nonexistent` and in an overlap (fall back) `if_ambiguous` decide:
 *  AP_TZ_CHOOSE_ERROR returns AP_ERR_TIME_NONEXISTENT / AP_ERR_TIME_AMBIGUOUS (out untouched),
 *  EARLIER / LATER return AP_OK with result->earlier / result->later. For a gap, LATER moves the
 *  time forward by the gap (02:30 -> 03:30 CEST, like java.time) and EARLIER back (-> 01:30 CET).
 *  `result` is optional (NULL) and is filled whenever the arguments are valid, errors included.
 *  Other errors: NULL_POINTER, INVALID_ARGUMENT (bad fields or choice), OUT_OF_RANGE. */
ap_status ap_tz_local_to_instant(const ap_tz *tz, const ap_civil_time *local,
                                 ap_tz_choice if_nonexistent, ap_tz_choice if_ambiguous,
                                 ap_instant *out, ap_tz_local_result *result);

/** Instant of a parsed time: with an offset, local - utc_offset (tz is ignored and may be NULL;
 *  result, if given, gets count 1 and before = after = {utc_offset, 0, ""}); without one,
 *  ap_tz_local_to_instant in `tz` (AP_ERR_INVALID_ARGUMENT if tz is NULL). */
ap_status ap_parsed_time_to_instant(const ap_parsed_time *p, const ap_tz *tz,
                                    ap_tz_choice if_nonexistent, ap_tz_choice if_ambiguous,
                                    ap_instant *out, ap_tz_local_result *result);

#ifdef __cplusplus
}
#endif

#endif /* AP_TIME_H */
