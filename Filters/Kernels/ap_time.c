/* SPDX-License-Identifier: BSD-3-Clause */
/* Instants, civil dates, Julian days, ISO 8601 and TZif time zones. See ap_time.h.
 *
 * References:
 *  - H. Hinnant, "chrono-Compatible Low-Level Date Algorithms" (days_from_civil,
 *    civil_from_days), http://howardhinnant.github.io/date_algorithms.html
 *  - RFC 8536, "The Time Zone Information Format (TZif)", and POSIX.1-2017 section 8.3 (TZ),
 *    with RFC 8536's extension of rule times to -167..167 hours.
 *  - ISO 8601-1:2019 and RFC 3339 section 5.6 (date-time syntax).
 */
#include "ap_time.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SECONDS_PER_DAY 86400
/* Julian day of 1970-01-01T00:00:00Z. */
#define JD_UNIX_EPOCH 2440587.5
/* Largest TZif file read; real files are under 4 KiB. */
#define TZIF_MAX_BYTES (1024 * 1024)
/* UTC offsets allowed in a zone (RFC 8536 section 3.2: [-89999, 93599] s, i.e. within 26 h). */
#define TZ_OFFSET_MIN (-89999)
#define TZ_OFFSET_MAX 93599
/* Half-width of the window searched for a clock change around a local time: more than the
 * largest |offset| (26 h). */
#define TZ_SEARCH_WINDOW (2 * SECONDS_PER_DAY)

/* ----------------------------------------------------------------------------------------------
 * Calendar
 * -------------------------------------------------------------------------------------------- */

/* floor(a / b) and the matching non-negative remainder, for b > 0. */
static int64_t floor_div(int64_t a, int64_t b)
{
  int64_t q = a / b;
  if ((a % b) < 0) {
    --q;
  }
  return q;
}

static int64_t floor_mod(int64_t a, int64_t b)
{
  int64_t r = a % b;
  return r < 0 ? r + b : r;
}

int64_t ap_time_days_from_civil(int64_t year, int month, int day)
{
  /* Hinnant: shift the year to start on March 1 so the leap day is the last day of the year. */
  const int64_t y = year - (month <= 2);
  const int64_t era = (y >= 0 ? y : y - 399) / 400;
  const int64_t yoe = y - era * 400;                                     /* [0, 399] */
  const int64_t mp = month > 2 ? month - 3 : month + 9;                  /* March = 0 */
  const int64_t doy = (153 * mp + 2) / 5 + day - 1;                      /* [0, 365] */
  const int64_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;             /* [0, 146096] */
  return era * 146097 + doe - 719468;
}

void ap_time_civil_from_days(int64_t days, int64_t *year, int *month, int *day)
{
  const int64_t z = days + 719468;
  const int64_t era = (z >= 0 ? z : z - 146096) / 146097;
  const int64_t doe = z - era * 146097;                                          /* [0, 146096] */
  const int64_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;    /* [0, 399] */
  const int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);                   /* [0, 365] */
  const int64_t mp = (5 * doy + 2) / 153;                                        /* [0, 11] */
  const int d = (int)(doy - (153 * mp + 2) / 5 + 1);
  const int m = (int)(mp < 10 ? mp + 3 : mp - 9);
  *year = yoe + era * 400 + (m <= 2);
  *month = m;
  *day = d;
}

int ap_time_is_leap_year(int64_t year)
{
  return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
}

int ap_time_days_in_month(int64_t year, int month)
{
  static const unsigned char days[12] = { 31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31 };
  if (month == 2 && ap_time_is_leap_year(year)) {
    return 29;
  }
  return days[month - 1];
}

/* Fields of a civil time, without the year range: 1 if valid. */
static int civil_fields_valid(int64_t year, int month, int day, int hour, int minute, int second)
{
  return month >= 1 && month <= 12 && day >= 1 && day <= ap_time_days_in_month(year, month) &&
         hour >= 0 && hour <= 23 && minute >= 0 && minute <= 59 && second >= 0 && second <= 59;
}

static int fraction_valid(double f)
{
  return f >= 0.0 && f < 1.0; /* false for NaN */
}

static int year_in_range(int64_t year)
{
  return year >= AP_TIME_YEAR_MIN && year <= AP_TIME_YEAR_MAX;
}

static ap_status instant_check(ap_instant t)
{
  if (!fraction_valid(t.fraction)) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  if (t.unix_seconds < AP_TIME_UNIX_MIN || t.unix_seconds > AP_TIME_UNIX_MAX) {
    return AP_ERR_OUT_OF_RANGE;
  }
  return AP_OK;
}

/* Seconds since the epoch of a civil time's whole seconds (no checks; fields valid). */
static int64_t civil_seconds(const ap_civil_time *c)
{
  return ap_time_days_from_civil(c->year, c->month, c->day) * SECONDS_PER_DAY +
         (int64_t)c->hour * 3600 + (int64_t)c->minute * 60 + c->second;
}

ap_status ap_civil_validate(const ap_civil_time *c)
{
  if (!c) {
    return AP_ERR_NULL_POINTER;
  }
  if (!civil_fields_valid(c->year, c->month, c->day, c->hour, c->minute, c->second) ||
      !fraction_valid(c->fraction)) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  if (!year_in_range(c->year)) {
    return AP_ERR_OUT_OF_RANGE;
  }
  return AP_OK;
}

ap_status ap_instant_from_civil(const ap_civil_time *utc, ap_instant *out)
{
  ap_status st;
  if (!utc || !out) {
    return AP_ERR_NULL_POINTER;
  }
  st = ap_civil_validate(utc);
  if (st != AP_OK) {
    return st;
  }
  out->unix_seconds = civil_seconds(utc);
  out->fraction = utc->fraction;
  return AP_OK;
}

/* Civil fields of whole seconds since the epoch (any |s| < 2^62). */
static void civil_from_seconds(int64_t s, double fraction, ap_civil_time *out)
{
  const int64_t days = floor_div(s, SECONDS_PER_DAY);
  const int64_t sod = s - days * SECONDS_PER_DAY;
  int64_t year;
  ap_time_civil_from_days(days, &year, &out->month, &out->day);
  out->year = (int)year;
  out->hour = (int)(sod / 3600);
  out->minute = (int)(sod / 60 % 60);
  out->second = (int)(sod % 60);
  out->fraction = fraction;
}

ap_status ap_instant_to_civil(ap_instant t, ap_civil_time *out)
{
  ap_status st;
  if (!out) {
    return AP_ERR_NULL_POINTER;
  }
  st = instant_check(t);
  if (st != AP_OK) {
    return st;
  }
  civil_from_seconds(t.unix_seconds, t.fraction, out);
  return AP_OK;
}

ap_status ap_instant_add_seconds(ap_instant t, double seconds, ap_instant *out)
{
  ap_status st;
  double whole, part, f;
  int64_t s;
  if (!out) {
    return AP_ERR_NULL_POINTER;
  }
  st = instant_check(t);
  if (st != AP_OK) {
    return st;
  }
  if (!isfinite(seconds)) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  if (!(fabs(seconds) <= 1e12)) { /* far beyond the 2.5e11 s of the range; keeps int64 exact */
    return AP_ERR_OUT_OF_RANGE;
  }
  whole = floor(seconds);
  part = seconds - whole; /* [0, 1], exact; 1 only by rounding of a tiny negative value */
  s = t.unix_seconds + (int64_t)whole;
  if (part >= 1.0) {
    part = 0.0;
    ++s;
  }
  f = t.fraction + part;
  if (f >= 1.0) {
    f -= 1.0; /* exact: f is in [1, 2) */
    ++s;
  }
  if (s < AP_TIME_UNIX_MIN || s > AP_TIME_UNIX_MAX) {
    return AP_ERR_OUT_OF_RANGE;
  }
  out->unix_seconds = s;
  out->fraction = f;
  return AP_OK;
}

ap_status ap_instant_to_julian_day(ap_instant t, ap_julian_day *out)
{
  ap_status st;
  int64_t days, sod;
  if (!out) {
    return AP_ERR_NULL_POINTER;
  }
  st = instant_check(t);
  if (st != AP_OK) {
    return st;
  }
  days = floor_div(t.unix_seconds, SECONDS_PER_DAY);
  sod = t.unix_seconds - days * SECONDS_PER_DAY;
  /* |days| < 2^21 and JD < 2^22: both sums are exact in double. */
  out->midnight = JD_UNIX_EPOCH + (double)days;
  out->day_fraction = ((double)sod + t.fraction) / SECONDS_PER_DAY;
  if (out->day_fraction >= 1.0) { /* 86399 + (1 - 2^-53) can round up to 86400 */
    out->day_fraction = 0x1.fffffffffffffp-1;
  }
  return AP_OK;
}

/* ----------------------------------------------------------------------------------------------
 * ISO 8601 output
 * -------------------------------------------------------------------------------------------- */

static ap_status format_iso8601(ap_instant t, int with_offset, int32_t utc_offset,
                                int fraction_digits, char *buf, size_t size)
{
  static const int64_t pow10[10] = { 1,      10,      100,      1000,      10000,
                                     100000, 1000000, 10000000, 100000000, 1000000000 };
  char tmp[80];
  ap_civil_time c;
  ap_status st;
  int64_t s, units;
  double rounded;
  int n, pos;
  if (!buf) {
    return AP_ERR_NULL_POINTER;
  }
  if (size > 0) {
    buf[0] = '\0';
  }
  if (fraction_digits < 0 || fraction_digits > 9 ||
      (with_offset && (utc_offset <= -93600 || utc_offset >= 93600))) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  st = instant_check(t);
  if (st != AP_OK) {
    return st;
  }
  s = t.unix_seconds + utc_offset;
  /* Round the fraction to the digits shown; a carry moves to the seconds, except beyond the
   * range's last second, where the digits are truncated (text the parser reads back). */
  rounded = floor(t.fraction * (double)pow10[fraction_digits] + 0.5);
  units = (int64_t)rounded;
  if (units >= pow10[fraction_digits]) {
    if (t.unix_seconds < AP_TIME_UNIX_MAX) {
      units -= pow10[fraction_digits];
      ++s;
    } else {
      units = pow10[fraction_digits] - 1;
    }
  }
  civil_from_seconds(s, 0.0, &c);
  if (c.year < AP_TIME_YEAR_MIN || c.year > AP_TIME_YEAR_MAX) {
    return AP_ERR_OUT_OF_RANGE; /* a local time at the range's ends, in the year beyond */
  }
  if (c.year < 0) {
    n = snprintf(tmp, sizeof tmp, "-%04d", -c.year);
  } else {
    n = snprintf(tmp, sizeof tmp, "%04d", c.year);
  }
  pos = n;
  n = snprintf(tmp + pos, sizeof tmp - (size_t)pos, "-%02d-%02dT%02d:%02d:%02d", c.month, c.day,
               c.hour, c.minute, c.second);
  pos += n;
  if (fraction_digits > 0) {
    n = snprintf(tmp + pos, sizeof tmp - (size_t)pos, ".%0*lld", fraction_digits,
                 (long long)units);
    pos += n;
  }
  if (!with_offset) {
    n = snprintf(tmp + pos, sizeof tmp - (size_t)pos, "Z");
  } else {
    const int32_t a = utc_offset < 0 ? -utc_offset : utc_offset;
    const char sign = utc_offset < 0 ? '-' : '+';
    if (a % 60) {
      n = snprintf(tmp + pos, sizeof tmp - (size_t)pos, "%c%02d:%02d:%02d", sign, (int)(a / 3600),
                   (int)(a / 60 % 60), (int)(a % 60));
    } else {
      n = snprintf(tmp + pos, sizeof tmp - (size_t)pos, "%c%02d:%02d", sign, (int)(a / 3600),
                   (int)(a / 60 % 60));
    }
  }
  pos += n;
  if ((size_t)pos + 1 > size) {
    return AP_ERR_BUFFER_TOO_SMALL;
  }
  memcpy(buf, tmp, (size_t)pos + 1);
  return AP_OK;
}

ap_status ap_instant_format_iso8601(ap_instant t, int fraction_digits, char *buf, size_t size)
{
  return format_iso8601(t, 0, 0, fraction_digits, buf, size);
}

ap_status ap_instant_format_iso8601_local(ap_instant t, int32_t utc_offset, int fraction_digits,
                                          char *buf, size_t size)
{
  return format_iso8601(t, 1, utc_offset, fraction_digits, buf, size);
}

/* ----------------------------------------------------------------------------------------------
 * ISO 8601 input
 * -------------------------------------------------------------------------------------------- */

static int is_digit(char c)
{
  return c >= '0' && c <= '9';
}

/* Read exactly n digits (n <= 9) at *p; 1 on success, advancing *p. */
static int read_digits(const char **p, int n, int *value)
{
  int v = 0, k;
  for (k = 0; k < n; ++k) {
    if (!is_digit((*p)[k])) {
      return 0;
    }
    v = v * 10 + ((*p)[k] - '0');
  }
  *value = v;
  *p += n;
  return 1;
}

ap_status ap_time_parse_iso8601(const char *text, ap_parsed_time *out)
{
  ap_parsed_time r;
  const char *p = text;
  int64_t year = 0;
  int n, hh, mm;
  if (!text || !out) {
    return AP_ERR_NULL_POINTER;
  }
  memset(&r, 0, sizeof r);

  /* Year: exactly 4 digits, or a sign and 4..6 digits (ISO 8601 expanded representation). */
  if (*p == '+' || *p == '-') {
    const int negative = *p == '-';
    ++p;
    for (n = 0; is_digit(p[n]); ++n) {
      if (n < 6) {
        year = year * 10 + (p[n] - '0');
      }
    }
    if (n < 4 || n > 6) {
      return AP_ERR_PARSE;
    }
    p += n;
    if (negative) {
      year = -year;
    }
  } else {
    int y4;
    if (!read_digits(&p, 4, &y4)) {
      return AP_ERR_PARSE;
    }
    year = y4;
  }
  if (*p++ != '-' || !read_digits(&p, 2, &r.local.month) || *p++ != '-' ||
      !read_digits(&p, 2, &r.local.day)) {
    return AP_ERR_PARSE;
  }

  if (*p != '\0') {
    if (*p != 'T' && *p != 't' && *p != ' ') {
      return AP_ERR_PARSE;
    }
    ++p;
    r.has_time = 1;
    if (!read_digits(&p, 2, &r.local.hour) || *p++ != ':' || !read_digits(&p, 2, &r.local.minute)) {
      return AP_ERR_PARSE;
    }
    if (*p == ':') {
      ++p;
      if (!read_digits(&p, 2, &r.local.second)) {
        return AP_ERR_PARSE;
      }
      if (*p == '.' || *p == ',') {
        static const double scale[10] = { 1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9 };
        int32_t units = 0;
        ++p;
        for (n = 0; is_digit(p[n]); ++n) {
          if (n >= 9) {
            return AP_ERR_PARSE; /* more than nanoseconds */
          }
          units = units * 10 + (p[n] - '0');
        }
        if (n == 0) {
          return AP_ERR_PARSE;
        }
        p += n;
        r.local.fraction = (double)units / scale[n]; /* correctly rounded; < 1 */
      }
    }
    /* Offset. */
    if (*p == 'Z' || *p == 'z') {
      ++p;
      r.has_offset = 1;
    } else if (*p == '+' || *p == '-') {
      const int negative = *p == '-';
      ++p;
      if (!read_digits(&p, 2, &hh)) {
        return AP_ERR_PARSE;
      }
      mm = 0;
      if (*p == ':') {
        ++p;
        if (!read_digits(&p, 2, &mm)) {
          return AP_ERR_PARSE;
        }
      } else if (is_digit(*p)) {
        if (!read_digits(&p, 2, &mm)) {
          return AP_ERR_PARSE;
        }
      }
      if (hh > 18 || mm > 59 || hh * 60 + mm > 18 * 60) {
        return AP_ERR_PARSE;
      }
      r.has_offset = 1;
      r.utc_offset = (int32_t)((hh * 60 + mm) * 60);
      if (negative) {
        r.utc_offset = -r.utc_offset;
      }
    }
  }
  if (*p != '\0') {
    return AP_ERR_PARSE; /* trailing characters */
  }
  if (!civil_fields_valid(year, r.local.month, r.local.day, r.local.hour, r.local.minute,
                          r.local.second)) {
    return AP_ERR_PARSE;
  }
  if (!year_in_range(year)) {
    return AP_ERR_OUT_OF_RANGE;
  }
  r.local.year = (int)year;
  *out = r;
  return AP_OK;
}

/* ----------------------------------------------------------------------------------------------
 * Time zones: data
 * -------------------------------------------------------------------------------------------- */

/* One local time type (a TZif ttinfo, or one half of a POSIX TZ rule). */
typedef struct tz_type {
  int32_t utoff; /* seconds east of UTC */
  int is_dst;
  char abbr[AP_TZ_ABBR_SIZE];
} tz_type;

/* A POSIX TZ rule date: Jn (1..365, no Feb 29), n (0..365) or Mm.w.d; time in seconds of local
 * time then in effect (-167 h .. 167 h, RFC 8536). */
typedef struct tz_rule_date {
  char kind; /* 'J', 'N' (zero-based day) or 'M' */
  int n, m, w, d;
  int32_t time;
} tz_rule_date;

typedef struct tz_rule {
  int has_dst;
  tz_type std, dst;
  tz_rule_date start, end; /* start of DST (in standard time), end (in DST) */
} tz_rule;

struct ap_tz {
  char name[AP_TZ_NAME_MAX + 1];
  size_t timecnt;    /* transitions */
  size_t typecnt;    /* 1..256 */
  int64_t *at;       /* transition instants, strictly increasing */
  unsigned char *idx; /* type after each transition, < typecnt */
  tz_type types[256];
  int has_rule;      /* footer rule present (otherwise the last type continues) */
  tz_rule rule;
};

/* ----------------------------------------------------------------------------------------------
 * POSIX TZ rules (the TZif footer)
 * -------------------------------------------------------------------------------------------- */

static int is_alpha(char c)
{
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
}

/* Zone abbreviation: 3+ letters, or <...> of letters, digits, '+' and '-'. */
static int parse_tz_name(const char **s, char abbr[AP_TZ_ABBR_SIZE])
{
  const char *p = *s, *b;
  size_t len;
  if (*p == '<') {
    b = ++p;
    while (is_alpha(*p) || is_digit(*p) || *p == '+' || *p == '-') {
      ++p;
    }
    if (*p != '>') {
      return 0;
    }
    len = (size_t)(p - b);
    ++p;
  } else {
    b = p;
    while (is_alpha(*p)) {
      ++p;
    }
    len = (size_t)(p - b);
  }
  if (len < 3) {
    return 0;
  }
  if (len > AP_TZ_ABBR_SIZE - 1) {
    len = AP_TZ_ABBR_SIZE - 1;
  }
  memcpy(abbr, b, len);
  abbr[len] = '\0';
  *s = p;
  return 1;
}

/* 1..max_digits digits, value <= max; 1 on success. */
static int parse_number(const char **s, int max_digits, int max, int *value)
{
  const char *p = *s;
  int v = 0, n = 0;
  while (is_digit(*p)) {
    if (++n > max_digits) {
      return 0;
    }
    v = v * 10 + (*p++ - '0');
  }
  if (n == 0 || v > max) {
    return 0;
  }
  *value = v;
  *s = p;
  return 1;
}

/* [+-]hh[:mm[:ss]] with hh <= max_hours; seconds, sign applied. */
static int parse_hms(const char **s, int max_hours, int32_t *seconds)
{
  const char *p = *s;
  int sign = 1, h, m = 0, sec = 0;
  if (*p == '+' || *p == '-') {
    sign = *p == '-' ? -1 : 1;
    ++p;
  }
  if (!parse_number(&p, 3, max_hours, &h)) {
    return 0;
  }
  if (*p == ':') {
    ++p;
    if (!parse_number(&p, 2, 59, &m)) {
      return 0;
    }
    if (*p == ':') {
      ++p;
      if (!parse_number(&p, 2, 59, &sec)) {
        return 0;
      }
    }
  }
  *seconds = (int32_t)(sign * (h * 3600 + m * 60 + sec));
  *s = p;
  return 1;
}

static int parse_rule_date(const char **s, tz_rule_date *d)
{
  const char *p = *s;
  memset(d, 0, sizeof *d);
  if (*p == 'J') {
    ++p;
    d->kind = 'J';
    if (!parse_number(&p, 3, 365, &d->n) || d->n < 1) {
      return 0;
    }
  } else if (*p == 'M') {
    ++p;
    d->kind = 'M';
    if (!parse_number(&p, 2, 12, &d->m) || d->m < 1 || *p++ != '.' ||
        !parse_number(&p, 1, 5, &d->w) || d->w < 1 || *p++ != '.' ||
        !parse_number(&p, 1, 6, &d->d)) {
      return 0;
    }
  } else {
    d->kind = 'N';
    if (!parse_number(&p, 3, 365, &d->n)) {
      return 0;
    }
  }
  d->time = 2 * 3600; /* POSIX default 02:00:00 */
  if (*p == '/') {
    ++p;
    if (!parse_hms(&p, 167, &d->time)) {
      return 0;
    }
  }
  *s = p;
  return 1;
}

/* Parse a POSIX TZ string ("CET-1CEST,M3.5.0,M10.5.0/3"); 1 on success. */
static int parse_posix_tz(const char *s, tz_rule *r)
{
  int32_t off;
  memset(r, 0, sizeof *r);
  if (!parse_tz_name(&s, r->std.abbr) || !parse_hms(&s, 24, &off)) {
    return 0;
  }
  r->std.utoff = -off; /* POSIX offsets are positive west of Greenwich */
  r->std.is_dst = 0;
  if (*s == '\0') {
    return 1;
  }
  r->has_dst = 1;
  if (!parse_tz_name(&s, r->dst.abbr)) {
    return 0;
  }
  r->dst.is_dst = 1;
  r->dst.utoff = r->std.utoff + 3600;
  if (*s == '+' || *s == '-' || is_digit(*s)) {
    if (!parse_hms(&s, 24, &off)) {
      return 0;
    }
    r->dst.utoff = -off;
  }
  if (*s == '\0') {
    /* No rule: the default of tzcode (US rules since 2007). */
    const char *def = "M3.2.0,M11.1.0";
    return parse_rule_date(&def, &r->start) && *def++ == ',' && parse_rule_date(&def, &r->end);
  }
  if (*s++ != ',' || !parse_rule_date(&s, &r->start) || *s++ != ',' ||
      !parse_rule_date(&s, &r->end)) {
    return 0;
  }
  return *s == '\0';
}

/* UTC year of an instant. */
static int64_t year_of(int64_t t)
{
  int64_t y;
  int m, d;
  ap_time_civil_from_days(floor_div(t, SECONDS_PER_DAY), &y, &m, &d);
  return y;
}

/* UTC instant of a rule date in `year`, whose time is in local time at offset utoff_before. */
static int64_t rule_transition(const tz_rule_date *d, int64_t year, int32_t utoff_before)
{
  const int64_t jan1 = ap_time_days_from_civil(year, 1, 1);
  int64_t day;
  if (d->kind == 'J') {
    day = jan1 + d->n - 1 + (ap_time_is_leap_year(year) && d->n >= 60);
  } else if (d->kind == 'N') {
    day = jan1 + d->n;
  } else {
    const int64_t first = ap_time_days_from_civil(year, d->m, 1);
    const int64_t wd_first = floor_mod(first + 4, 7); /* 1970-01-01 was a Thursday (4) */
    const int64_t dim = ap_time_days_in_month(year, d->m);
    day = first + floor_mod(d->d - wd_first, 7) + 7 * (int64_t)(d->w - 1);
    while (day >= first + dim) { /* w = 5: the last such weekday */
      day -= 7;
    }
  }
  return day * SECONDS_PER_DAY + d->time - utoff_before;
}

/* Type of the footer rule at instant t: the latest rule transition <= t among the years around
 * t; on equal instants the later one in (year, start, end) order wins, so DST all year ("starts
 * Jan 1 00:00, ends Dec 31 24:00 + save", RFC 8536 section 3.3.1) stays DST. */
static const tz_type *rule_type_at(const tz_rule *r, int64_t t)
{
  int64_t y, yy, best = 0;
  const tz_type *type = &r->std;
  int found = 0;
  if (!r->has_dst) {
    return &r->std;
  }
  y = year_of(t);
  for (yy = y - 2; yy <= y + 1; ++yy) {
    const int64_t s = rule_transition(&r->start, yy, r->std.utoff);
    const int64_t e = rule_transition(&r->end, yy, r->dst.utoff);
    if (s <= t && (!found || s >= best)) {
      best = s;
      type = &r->dst;
      found = 1;
    }
    if (e <= t && (!found || e >= best)) {
      best = e;
      type = &r->std;
      found = 1;
    }
  }
  return type;
}

/* ----------------------------------------------------------------------------------------------
 * Time zones: lookup
 * -------------------------------------------------------------------------------------------- */

/* Type in effect at instant t (any t with |t| < 2^62). */
static const tz_type *zone_type_at(const ap_tz *z, int64_t t)
{
  size_t lo, hi;
  const size_t n = z->timecnt;
  if (n == 0 || t >= z->at[n - 1]) {
    if (z->has_rule) {
      return rule_type_at(&z->rule, t);
    }
    return n == 0 ? &z->types[0] : &z->types[z->idx[n - 1]];
  }
  if (t < z->at[0]) {
    return &z->types[0];
  }
  /* at[lo] <= t < at[hi] */
  lo = 0;
  hi = n - 1;
  while (hi - lo > 1) {
    const size_t mid = lo + (hi - lo) / 2;
    if (z->at[mid] <= t) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return &z->types[z->idx[lo]];
}

static void info_from_type(const tz_type *type, ap_tz_info *info)
{
  info->utc_offset = type->utoff;
  info->is_dst = type->is_dst;
  memcpy(info->abbreviation, type->abbr, sizeof info->abbreviation);
}

const char *ap_tz_name(const ap_tz *tz)
{
  return tz ? tz->name : "";
}

ap_status ap_tz_lookup(const ap_tz *tz, ap_instant t, ap_tz_info *out)
{
  ap_status st;
  if (!tz || !out) {
    return AP_ERR_NULL_POINTER;
  }
  st = instant_check(t);
  if (st != AP_OK) {
    return st;
  }
  info_from_type(zone_type_at(tz, t.unix_seconds), out);
  return AP_OK;
}

/* Is local time L inside the gap (want_gap) or the overlap of a change at T from b to a? */
static int change_matches(int64_t T, const tz_type *b, const tz_type *a, int64_t L, int want_gap)
{
  if (want_gap) {
    return b->utoff < a->utoff && T + b->utoff <= L && L < T + a->utoff;
  }
  return b->utoff > a->utoff && T + a->utoff <= L && L < T + b->utoff;
}

/* Find the clock change whose gap (or overlap) contains local time L; 1 if found. Every change
 * that can contain L lies within TZ_SEARCH_WINDOW of L. */
static int find_change(const ap_tz *z, int64_t L, int want_gap, int64_t *T, const tz_type **before,
                       const tz_type **after)
{
  const int64_t lo = L - TZ_SEARCH_WINDOW, hi = L + TZ_SEARCH_WINDOW;
  const size_t n = z->timecnt;
  size_t i = 0, a = 0, b = n;
  int64_t yy;
  /* Table: first index with at[i] >= lo. */
  while (a < b) {
    const size_t mid = a + (b - a) / 2;
    if (z->at[mid] < lo) {
      a = mid + 1;
    } else {
      b = mid;
    }
  }
  for (i = a; i < n && z->at[i] <= hi; ++i) {
    const tz_type *tb = i ? &z->types[z->idx[i - 1]] : &z->types[0];
    const tz_type *ta = &z->types[z->idx[i]];
    if (change_matches(z->at[i], tb, ta, L, want_gap)) {
      *T = z->at[i];
      *before = tb;
      *after = ta;
      return 1;
    }
  }
  /* Footer rule, after the table. */
  if (!z->has_rule || !z->rule.has_dst || (n > 0 && hi <= z->at[n - 1])) {
    return 0;
  }
  for (yy = year_of(lo) - 1; yy <= year_of(hi) + 1; ++yy) {
    const tz_rule *r = &z->rule;
    const int64_t s = rule_transition(&r->start, yy, r->std.utoff);
    const int64_t e = rule_transition(&r->end, yy, r->dst.utoff);
    if ((n == 0 || s > z->at[n - 1]) && s >= lo && s <= hi &&
        change_matches(s, &r->std, &r->dst, L, want_gap)) {
      *T = s;
      *before = &r->std;
      *after = &r->dst;
      return 1;
    }
    if ((n == 0 || e > z->at[n - 1]) && e >= lo && e <= hi &&
        change_matches(e, &r->dst, &r->std, L, want_gap)) {
      *T = e;
      *before = &r->dst;
      *after = &r->std;
      return 1;
    }
  }
  return 0;
}

static ap_status choose(const ap_tz_local_result *r, ap_tz_choice choice, ap_status if_error,
                        ap_instant *out)
{
  ap_instant t;
  if (choice == AP_TZ_CHOOSE_ERROR) {
    return if_error;
  }
  t = choice == AP_TZ_CHOOSE_EARLIER ? r->earlier : r->later;
  if (t.unix_seconds < AP_TIME_UNIX_MIN || t.unix_seconds > AP_TIME_UNIX_MAX) {
    return AP_ERR_OUT_OF_RANGE;
  }
  *out = t;
  return AP_OK;
}

static int choice_valid(ap_tz_choice c)
{
  return c == AP_TZ_CHOOSE_ERROR || c == AP_TZ_CHOOSE_EARLIER || c == AP_TZ_CHOOSE_LATER;
}

ap_status ap_tz_local_to_instant(const ap_tz *tz, const ap_civil_time *local,
                                 ap_tz_choice if_nonexistent, ap_tz_choice if_ambiguous,
                                 ap_instant *out, ap_tz_local_result *result)
{
  int32_t offsets[258];
  size_t noff = 0, i, j;
  int count = 0;
  int64_t L, first = 0, last = 0, T = 0;
  const tz_type *first_type = NULL, *last_type = NULL, *before = NULL, *after = NULL;
  ap_tz_local_result r;
  ap_status st;
  if (!tz || !local || !out) {
    return AP_ERR_NULL_POINTER;
  }
  if (!choice_valid(if_nonexistent) || !choice_valid(if_ambiguous)) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  st = ap_civil_validate(local);
  if (st != AP_OK) {
    return st;
  }
  L = civil_seconds(local);

  /* Every instant showing local time L is L - o for an offset o the zone can have, with
   * utoff(L - o) == o. Try each distinct offset: complete and exact. */
  for (i = 0; i < tz->typecnt + 2; ++i) {
    int32_t o;
    if (i < tz->typecnt) {
      o = tz->types[i].utoff;
    } else if (tz->has_rule && (i == tz->typecnt || tz->rule.has_dst)) {
      o = i == tz->typecnt ? tz->rule.std.utoff : tz->rule.dst.utoff;
    } else {
      continue;
    }
    for (j = 0; j < noff && offsets[j] != o; ++j) {
    }
    if (j == noff) {
      offsets[noff++] = o;
    }
  }
  for (i = 0; i < noff; ++i) {
    const int64_t t = L - offsets[i];
    const tz_type *type = zone_type_at(tz, t);
    if (type->utoff == offsets[i]) {
      if (count == 0 || t < first) {
        first = t;
        first_type = type;
      }
      if (count == 0 || t > last) {
        last = t;
        last_type = type;
      }
      ++count;
    }
  }

  memset(&r, 0, sizeof r);
  r.count = count;
  r.earlier.fraction = local->fraction;
  r.later.fraction = local->fraction;
  if (count == 1) {
    r.earlier.unix_seconds = r.later.unix_seconds = first;
    info_from_type(first_type, &r.before);
    r.after = r.before;
  } else if (count == 0) {
    if (find_change(tz, L, 1, &T, &before, &after)) {
      r.has_transition = 1;
      r.earlier.unix_seconds = L - after->utoff;
      r.later.unix_seconds = L - before->utoff;
    } else { /* only for an inconsistent file: report the zone at L read as UTC */
      before = after = zone_type_at(tz, L);
      r.earlier.unix_seconds = r.later.unix_seconds = L - before->utoff;
    }
  } else {
    r.earlier.unix_seconds = first;
    r.later.unix_seconds = last;
    if (find_change(tz, L, 0, &T, &before, &after)) {
      r.has_transition = 1;
    } else {
      before = first_type;
      after = last_type;
    }
  }
  if (count != 1) {
    r.transition.unix_seconds = r.has_transition ? T : 0;
    info_from_type(before, &r.before);
    info_from_type(after, &r.after);
  }
  if (result) {
    *result = r;
  }
  if (count == 1) {
    if (first < AP_TIME_UNIX_MIN || first > AP_TIME_UNIX_MAX) {
      return AP_ERR_OUT_OF_RANGE;
    }
    *out = r.earlier;
    return AP_OK;
  }
  if (count == 0) {
    return choose(&r, if_nonexistent, AP_ERR_TIME_NONEXISTENT, out);
  }
  return choose(&r, if_ambiguous, AP_ERR_TIME_AMBIGUOUS, out);
}

ap_status ap_parsed_time_to_instant(const ap_parsed_time *p, const ap_tz *tz,
                                    ap_tz_choice if_nonexistent, ap_tz_choice if_ambiguous,
                                    ap_instant *out, ap_tz_local_result *result)
{
  ap_status st;
  int64_t s;
  if (!p || !out) {
    return AP_ERR_NULL_POINTER;
  }
  if (!p->has_offset) {
    if (!tz) {
      return AP_ERR_INVALID_ARGUMENT;
    }
    return ap_tz_local_to_instant(tz, &p->local, if_nonexistent, if_ambiguous, out, result);
  }
  if (p->utc_offset < -18 * 3600 || p->utc_offset > 18 * 3600) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  st = ap_civil_validate(&p->local);
  if (st != AP_OK) {
    return st;
  }
  s = civil_seconds(&p->local) - p->utc_offset;
  if (result) {
    memset(result, 0, sizeof *result);
    result->count = 1;
    result->earlier.unix_seconds = result->later.unix_seconds = s;
    result->earlier.fraction = result->later.fraction = p->local.fraction;
    result->before.utc_offset = result->after.utc_offset = p->utc_offset;
  }
  if (s < AP_TIME_UNIX_MIN || s > AP_TIME_UNIX_MAX) {
    return AP_ERR_OUT_OF_RANGE;
  }
  out->unix_seconds = s;
  out->fraction = p->local.fraction;
  return AP_OK;
}

/* ----------------------------------------------------------------------------------------------
 * Time zones: loading TZif files
 * -------------------------------------------------------------------------------------------- */

/* Zone names: [A-Za-z0-9_+-] components separated by single '/'. */
static int tz_name_valid(const char *name)
{
  size_t k, len = strlen(name);
  if (len == 0 || len > AP_TZ_NAME_MAX || name[0] == '/' || name[len - 1] == '/') {
    return 0;
  }
  for (k = 0; k < len; ++k) {
    const char c = name[k];
    if (c == '/') {
      if (name[k + 1] == '/') {
        return 0;
      }
    } else if (!is_alpha(c) && !is_digit(c) && c != '_' && c != '+' && c != '-') {
      return 0;
    }
  }
  return 1;
}

/* Read a whole file of at most TZIF_MAX_BYTES. */
static ap_status read_file(const char *path, unsigned char **data, size_t *len)
{
  size_t cap = 8192, n = 0;
  unsigned char *buf;
  FILE *f = fopen(path, "rb");
  *data = NULL;
  *len = 0;
  if (!f) {
    return AP_ERR_NOT_FOUND;
  }
  buf = (unsigned char *)malloc(cap);
  if (!buf) {
    fclose(f);
    return AP_ERR_OUT_OF_MEMORY;
  }
  for (;;) {
    n += fread(buf + n, 1, cap - n, f);
    if (n < cap) {
      break;
    }
    if (cap > TZIF_MAX_BYTES) {
      free(buf);
      fclose(f);
      return AP_ERR_BAD_FILE;
    }
    {
      unsigned char *bigger = (unsigned char *)realloc(buf, cap * 2);
      if (!bigger) {
        free(buf);
        fclose(f);
        return AP_ERR_OUT_OF_MEMORY;
      }
      buf = bigger;
      cap *= 2;
    }
  }
  if (ferror(f)) { /* e.g. a directory */
    free(buf);
    fclose(f);
    return AP_ERR_NOT_FOUND;
  }
  fclose(f);
  if (n > TZIF_MAX_BYTES) {
    free(buf);
    return AP_ERR_BAD_FILE;
  }
  *data = buf;
  *len = n;
  return AP_OK;
}

static uint32_t be32(const unsigned char *p)
{
  return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | (uint32_t)p[3];
}

static int64_t be64(const unsigned char *p)
{
  const uint64_t u = (uint64_t)be32(p) << 32 | be32(p + 4);
  /* Two's complement without implementation-defined conversion. */
  return u <= (uint64_t)INT64_MAX ? (int64_t)u : -(int64_t)(~u) - 1;
}

static int32_t be32s(const unsigned char *p)
{
  const uint32_t u = be32(p);
  return u <= (uint32_t)INT32_MAX ? (int32_t)u : -(int32_t)(~u) - 1;
}

typedef struct tzif_header {
  int version; /* 0 for version 1, else the version byte */
  uint64_t isutcnt, isstdcnt, leapcnt, timecnt, typecnt, charcnt;
} tzif_header;

/* Header at data[pos]; 1 if it is one and fits. */
static int read_header(const unsigned char *data, size_t len, size_t pos, tzif_header *h)
{
  const unsigned char *p = data + pos;
  if (len - pos < 44 || memcmp(p, "TZif", 4) != 0) {
    return 0;
  }
  h->version = p[4];
  h->isutcnt = be32(p + 20);
  h->isstdcnt = be32(p + 24);
  h->leapcnt = be32(p + 28);
  h->timecnt = be32(p + 32);
  h->typecnt = be32(p + 36);
  h->charcnt = be32(p + 40);
  return 1;
}

/* Size of the data block after a header, with time values of tsize bytes (no overflow: each
 * count < 2^32). */
static uint64_t block_size(const tzif_header *h, uint64_t tsize)
{
  return h->timecnt * tsize + h->timecnt + h->typecnt * 6 + h->charcnt + h->leapcnt * (tsize + 4) +
         h->isstdcnt + h->isutcnt;
}

/* Parse the data block at data[pos] into z; 1 if valid. */
static int read_block(const unsigned char *data, const tzif_header *h, size_t pos, size_t tsize,
                      ap_tz *z)
{
  const unsigned char *times = data + pos;
  const unsigned char *idx = times + h->timecnt * tsize;
  const unsigned char *types = idx + h->timecnt;
  const unsigned char *chars = types + h->typecnt * 6;
  size_t i;
  /* RFC 8536 section 3.1: typecnt and charcnt nonzero, indicator counts 0 or typecnt. We do
   * not apply leap seconds, so a leap-second table is not accepted. */
  if (h->typecnt == 0 || h->typecnt > 256 || h->charcnt == 0 || h->leapcnt != 0 ||
      (h->isstdcnt != 0 && h->isstdcnt != h->typecnt) ||
      (h->isutcnt != 0 && h->isutcnt != h->typecnt)) {
    return 0;
  }
  z->timecnt = (size_t)h->timecnt;
  z->typecnt = (size_t)h->typecnt;
  if (z->timecnt > 0) {
    z->at = (int64_t *)malloc(z->timecnt * sizeof *z->at);
    z->idx = (unsigned char *)malloc(z->timecnt);
    if (!z->at || !z->idx) {
      return -1;
    }
  }
  for (i = 0; i < z->timecnt; ++i) {
    z->at[i] = tsize == 8 ? be64(times + 8 * i) : (int64_t)be32s(times + 4 * i);
    if (i > 0 && z->at[i] <= z->at[i - 1]) {
      return 0;
    }
    z->idx[i] = idx[i];
    if (idx[i] >= z->typecnt) {
      return 0;
    }
  }
  for (i = 0; i < z->typecnt; ++i) {
    const unsigned char *t = types + 6 * i;
    const int32_t utoff = be32s(t);
    const size_t ai = t[5];
    size_t k;
    if (utoff < TZ_OFFSET_MIN || utoff > TZ_OFFSET_MAX || t[4] > 1 || ai >= h->charcnt) {
      return 0;
    }
    for (k = ai; k < h->charcnt && chars[k] != '\0'; ++k) {
    }
    if (k == h->charcnt) {
      return 0; /* abbreviation not terminated inside the table */
    }
    z->types[i].utoff = utoff;
    z->types[i].is_dst = t[4];
    k -= ai;
    if (k > AP_TZ_ABBR_SIZE - 1) {
      k = AP_TZ_ABBR_SIZE - 1;
    }
    memcpy(z->types[i].abbr, chars + ai, k);
    z->types[i].abbr[k] = '\0';
  }
  return 1;
}

/* Parse a whole TZif file into z: AP_OK, AP_ERR_BAD_FILE or AP_ERR_OUT_OF_MEMORY. */
static ap_status parse_tzif(const unsigned char *data, size_t len, ap_tz *z)
{
  tzif_header h;
  uint64_t size;
  size_t pos = 0, end, k;
  int ok;
  if (!read_header(data, len, 0, &h)) {
    return AP_ERR_BAD_FILE;
  }
  size = block_size(&h, 4);
  if (size > len - 44) {
    return AP_ERR_BAD_FILE;
  }
  if (h.version == 0) { /* version 1: 32-bit block only, no footer */
    ok = read_block(data, &h, 44, 4, z);
    return ok < 0 ? AP_ERR_OUT_OF_MEMORY : ok ? AP_OK : AP_ERR_BAD_FILE;
  }
  /* Version 2+: skip the 32-bit block; read the 64-bit one and the footer. */
  pos = 44 + (size_t)size;
  if (!read_header(data, len, pos, &h) || h.version == 0) {
    return AP_ERR_BAD_FILE;
  }
  pos += 44;
  size = block_size(&h, 8);
  if (size > len - pos) {
    return AP_ERR_BAD_FILE;
  }
  ok = read_block(data, &h, pos, 8, z);
  if (ok <= 0) {
    return ok < 0 ? AP_ERR_OUT_OF_MEMORY : AP_ERR_BAD_FILE;
  }
  pos += (size_t)size;
  /* Footer: "\n" TZ-string "\n". */
  if (pos >= len || data[pos] != '\n') {
    return AP_ERR_BAD_FILE;
  }
  ++pos;
  for (end = pos; end < len && data[end] != '\n'; ++end) {
    if (data[end] == '\0') {
      return AP_ERR_BAD_FILE;
    }
  }
  if (end == len || end - pos > 255) {
    return AP_ERR_BAD_FILE;
  }
  if (end > pos) {
    char tzstr[256];
    memcpy(tzstr, data + pos, end - pos);
    tzstr[end - pos] = '\0';
    if (!parse_posix_tz(tzstr, &z->rule)) {
      return AP_ERR_BAD_FILE;
    }
    for (k = 0; k < 2; ++k) {
      const int32_t o = k ? z->rule.dst.utoff : z->rule.std.utoff;
      if (o < TZ_OFFSET_MIN || o > TZ_OFFSET_MAX) {
        return AP_ERR_BAD_FILE;
      }
    }
    z->has_rule = 1;
  }
  return AP_OK;
}

void ap_tz_free(ap_tz *tz)
{
  if (tz) {
    free(tz->at);
    free(tz->idx);
    free(tz);
  }
}

ap_status ap_tz_load(const char *name, const char *zoneinfo_dir, ap_tz **out)
{
  ap_tz *z;
  ap_status st;
  unsigned char *data = NULL;
  size_t len = 0, dlen, nlen;
  char *path;
  if (out) {
    *out = NULL;
  }
  if (!name || !out) {
    return AP_ERR_NULL_POINTER;
  }
  if (!tz_name_valid(name)) {
    return AP_ERR_NOT_FOUND;
  }
  z = (ap_tz *)calloc(1, sizeof *z);
  if (!z) {
    return AP_ERR_OUT_OF_MEMORY;
  }
  nlen = strlen(name);
  memcpy(z->name, name, nlen + 1);
  if (strcmp(name, "UTC") == 0 || strcmp(name, "Etc/UTC") == 0) {
    z->typecnt = 1;
    memcpy(z->types[0].abbr, "UTC", 4);
    *out = z;
    return AP_OK;
  }
  if (!zoneinfo_dir || !*zoneinfo_dir) {
    zoneinfo_dir = getenv("TZDIR");
    if (!zoneinfo_dir || !*zoneinfo_dir) {
      zoneinfo_dir = "/usr/share/zoneinfo";
    }
  }
  dlen = strlen(zoneinfo_dir);
  path = (char *)malloc(dlen + nlen + 2);
  if (!path) {
    ap_tz_free(z);
    return AP_ERR_OUT_OF_MEMORY;
  }
  memcpy(path, zoneinfo_dir, dlen);
  path[dlen] = '/';
  memcpy(path + dlen + 1, name, nlen + 1);
  st = read_file(path, &data, &len);
  free(path);
  if (st == AP_OK) {
    st = parse_tzif(data, len, z);
  }
  free(data);
  if (st != AP_OK) {
    ap_tz_free(z);
    return st;
  }
  *out = z;
  return AP_OK;
}
