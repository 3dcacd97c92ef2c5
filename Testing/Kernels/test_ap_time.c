/* SPDX-License-Identifier: BSD-3-Clause */
/* Unit tests of ap_time: calendar, Julian days, ISO 8601 text, TZif zones and POSIX TZ rules.
 *
 * Expected values come from outside this code: Unix seconds from GNU `date -u -d ... +%s`,
 * Julian days from Meeus ("Astronomical Algorithms", ch. 7) and the NREL SPA report (Reda &
 * Andreas 2008, table A4.1), zone offsets from the rules themselves (EU: last Sunday of March /
 * October at 01:00 UTC; US: second Sunday of March / first Sunday of November at 02:00 local;
 * New South Wales: first Sunday of October / April) and were cross-checked with Python's
 * zoneinfo. Zone tests that need the system's tzdata print a skip message when it is missing;
 * the synthetic TZif files written to a temporary directory always run. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp, setenv, unsetenv, rmdir (test only) */

#include "ap_time.h"
#include "aptest.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef SYSTEM_ZONEINFO
#define SYSTEM_ZONEINFO "/usr/share/zoneinfo"
#endif

static char tmpdir[64];

/* ---------------------------------------------------------------------------------------------
 * Helpers
 * ------------------------------------------------------------------------------------------- */

static ap_civil_time civil(int y, int mo, int d, int h, int mi, int s)
{
  ap_civil_time c;
  c.year = y;
  c.month = mo;
  c.day = d;
  c.hour = h;
  c.minute = mi;
  c.second = s;
  c.fraction = 0.0;
  return c;
}

static ap_instant instant(int64_t s)
{
  ap_instant t;
  t.unix_seconds = s;
  t.fraction = 0.0;
  return t;
}

static int file_exists(const char *path)
{
  FILE *f = fopen(path, "rb");
  if (f) {
    fclose(f);
    return 1;
  }
  return 0;
}

static void tmp_path(char *buf, size_t size, const char *name)
{
  snprintf(buf, size, "%s/%s", tmpdir, name);
}

static int write_file(const char *name, const void *data, size_t n)
{
  char path[128];
  FILE *f;
  tmp_path(path, sizeof path, name);
  f = fopen(path, "wb");
  if (!f) {
    return 0;
  }
  if (n > 0 && fwrite(data, 1, n, f) != n) {
    fclose(f);
    return 0;
  }
  return fclose(f) == 0;
}

static void remove_file(const char *name)
{
  char path[128];
  tmp_path(path, sizeof path, name);
  remove(path);
}

/* Read a whole (small) file; returns its size or 0. */
static size_t read_whole(const char *path, unsigned char *buf, size_t cap)
{
  size_t n;
  FILE *f = fopen(path, "rb");
  if (!f) {
    return 0;
  }
  n = fread(buf, 1, cap, f);
  fclose(f);
  return n;
}

static void put32(unsigned char **p, uint32_t v)
{
  (*p)[0] = (unsigned char)(v >> 24);
  (*p)[1] = (unsigned char)(v >> 16);
  (*p)[2] = (unsigned char)(v >> 8);
  (*p)[3] = (unsigned char)v;
  *p += 4;
}

static void put64(unsigned char **p, int64_t v)
{
  const uint64_t u = (uint64_t)v;
  put32(p, (uint32_t)(u >> 32));
  put32(p, (uint32_t)u);
}

/* A TZif description for build_tzif (RFC 8536 layout). */
typedef struct tzif_spec {
  int version;           /* 0 (version 1: 32-bit data only, no footer) or '2'..'4' */
  size_t timecnt;
  const int64_t *at;
  const unsigned char *idx;
  size_t typecnt;
  const int32_t *utoff;
  const unsigned char *isdst;
  const unsigned char *abbrind;
  const char *chars; /* charcnt bytes, NULs included */
  size_t charcnt;
  const char *footer; /* TZ string without the newlines (version 2+) */
  size_t leapcnt;     /* zero-filled leap-second records to add */
} tzif_spec;

static unsigned char *header(unsigned char *p, int version, const tzif_spec *s)
{
  memcpy(p, "TZif", 4);
  p[4] = (unsigned char)version;
  memset(p + 5, 0, 15);
  p += 20;
  put32(&p, 0);                    /* isutcnt */
  put32(&p, 0);                    /* isstdcnt */
  put32(&p, (uint32_t)s->leapcnt); /* leapcnt */
  put32(&p, (uint32_t)s->timecnt); /* timecnt */
  put32(&p, (uint32_t)s->typecnt); /* typecnt */
  put32(&p, (uint32_t)s->charcnt); /* charcnt */
  return p;
}

static unsigned char *block(unsigned char *p, const tzif_spec *s, int tsize)
{
  size_t i;
  for (i = 0; i < s->timecnt; ++i) {
    if (tsize == 8) {
      put64(&p, s->at[i]);
    } else {
      put32(&p, (uint32_t)(int32_t)s->at[i]);
    }
  }
  for (i = 0; i < s->timecnt; ++i) {
    *p++ = s->idx[i];
  }
  for (i = 0; i < s->typecnt; ++i) {
    put32(&p, (uint32_t)s->utoff[i]);
    *p++ = s->isdst[i];
    *p++ = s->abbrind[i];
  }
  memcpy(p, s->chars, s->charcnt);
  p += s->charcnt;
  memset(p, 0, s->leapcnt * (size_t)(tsize + 4));
  return p + s->leapcnt * (size_t)(tsize + 4);
}

/* Serialize a spec; returns the size. The 32-bit block repeats the data (times must fit). */
static size_t build_tzif(unsigned char *buf, const tzif_spec *s)
{
  unsigned char *p = header(buf, s->version, s);
  p = block(p, s, 4);
  if (s->version != 0) {
    const size_t n = strlen(s->footer);
    p = header(p, s->version, s);
    p = block(p, s, 8);
    *p++ = '\n';
    memcpy(p, s->footer, n);
    p += n;
    *p++ = '\n';
  }
  return (size_t)(p - buf);
}

/* A zone with no transitions, one standard type and a footer rule. */
static size_t build_footer_only(unsigned char *buf, const char *abbr, int32_t utoff,
                                const char *footer)
{
  char chars[16];
  const int32_t off[1] = { utoff };
  const unsigned char dst[1] = { 0 }, ai[1] = { 0 };
  tzif_spec s;
  memset(&s, 0, sizeof s);
  memset(chars, 0, sizeof chars);
  memcpy(chars, abbr, strlen(abbr));
  s.version = '2';
  s.typecnt = 1;
  s.utoff = off;
  s.isdst = dst;
  s.abbrind = ai;
  s.chars = chars;
  s.charcnt = strlen(abbr) + 1;
  s.footer = footer;
  return build_tzif(buf, &s);
}

static ap_tz *load_footer_zone(const char *name, const char *abbr, int32_t utoff,
                               const char *footer)
{
  unsigned char buf[512];
  ap_tz *tz = NULL;
  const size_t n = build_footer_only(buf, abbr, utoff, footer);
  AP_CHECK(write_file(name, buf, n));
  AP_CHECK_EQ_INT(ap_tz_load(name, tmpdir, &tz), AP_OK);
  return tz;
}

/* UTC offset of tz at unix second s (INT32_MIN on error). */
static int32_t offset_at(const ap_tz *tz, int64_t s)
{
  ap_tz_info info;
  if (ap_tz_lookup(tz, instant(s), &info) != AP_OK) {
    return INT32_MIN;
  }
  return info.utc_offset;
}

/* Local civil time -> unix seconds with the default (error) policy; status returned. */
static ap_status local_to(const ap_tz *tz, ap_civil_time c, int64_t *s, ap_tz_local_result *r)
{
  ap_instant t = instant(0);
  const ap_status st =
      ap_tz_local_to_instant(tz, &c, AP_TZ_CHOOSE_ERROR, AP_TZ_CHOOSE_ERROR, &t, r);
  *s = t.unix_seconds;
  return st;
}

/* ---------------------------------------------------------------------------------------------
 * Calendar and instants
 * ------------------------------------------------------------------------------------------- */

static void test_calendar(void)
{
  int64_t y, d;
  int m, dd, mprev, dprev;
  int64_t yprev;
  /* Day numbers: 1970-01-01 = 0; 2000-01-01 = 10957 (30 years with 7 leap days); a 400-year
   * Gregorian cycle has 146097 days, so -2000-01-01 = 10957 - 10 * 146097 and 6000-01-01 =
   * 10957 + 10 * 146097; 6000 is a leap year (divisible by 400). */
  AP_CHECK_EQ_INT(ap_time_days_from_civil(1970, 1, 1), 0);
  AP_CHECK_EQ_INT(ap_time_days_from_civil(1969, 12, 31), -1);
  AP_CHECK_EQ_INT(ap_time_days_from_civil(2000, 1, 1), 10957);
  AP_CHECK_EQ_INT(ap_time_days_from_civil(2000, 3, 1), 10957 + 31 + 29);
  AP_CHECK_EQ_INT(ap_time_days_from_civil(-2000, 1, 1), 10957 - 1460970);
  AP_CHECK_EQ_INT(ap_time_days_from_civil(6000, 1, 1), 10957 + 1460970);
  AP_CHECK_EQ_INT(ap_time_days_from_civil(6001, 1, 1), 10957 + 1460970 + 366);
  AP_CHECK_EQ_INT(AP_TIME_UNIX_MIN, (int64_t)(10957 - 1460970) * 86400);
  AP_CHECK_EQ_INT(AP_TIME_UNIX_MAX, (int64_t)(10957 + 1460970 + 366) * 86400 - 1);
  ap_time_civil_from_days(-1, &y, &m, &dd);
  AP_CHECK(y == 1969 && m == 12 && dd == 31);
  ap_time_civil_from_days(10957 - 1460970, &y, &m, &dd);
  AP_CHECK(y == -2000 && m == 1 && dd == 1);
  AP_CHECK(ap_time_is_leap_year(2000) && ap_time_is_leap_year(2024) && ap_time_is_leap_year(0) &&
           ap_time_is_leap_year(-2000) && ap_time_is_leap_year(-4) && ap_time_is_leap_year(6000));
  AP_CHECK(!ap_time_is_leap_year(1900) && !ap_time_is_leap_year(2100) &&
           !ap_time_is_leap_year(2026) && !ap_time_is_leap_year(-1) &&
           !ap_time_is_leap_year(-100));
  /* Every day of the supported range (and a year on each side): consecutive day numbers are
   * consecutive calendar dates, and the round trip is exact. */
  ap_time_civil_from_days(ap_time_days_from_civil(-2001, 1, 1) - 1, &yprev, &mprev, &dprev);
  for (d = ap_time_days_from_civil(-2001, 1, 1); d <= ap_time_days_from_civil(6002, 1, 1); ++d) {
    int ok;
    ap_time_civil_from_days(d, &y, &m, &dd);
    if (dd == 1) {
      ok = (m == 1) ? (y == yprev + 1 && mprev == 12 && dprev == 31)
                    : (y == yprev && m == mprev + 1 && dprev >= 28);
    } else {
      ok = y == yprev && m == mprev && dd == dprev + 1;
    }
    ok = ok && ap_time_days_from_civil(y, m, dd) == d;
    if (!ok) {
      AP_CHECK(ok);
      fprintf(stderr, "  day %lld -> %lld-%d-%d\n", (long long)d, (long long)y, m, dd);
      break;
    }
    yprev = y;
    mprev = m;
    dprev = dd;
  }
}

static void test_instants(void)
{
  ap_civil_time c;
  ap_instant t;
  /* The epoch. */
  c = civil(1970, 1, 1, 0, 0, 0);
  AP_CHECK_EQ_INT(ap_instant_from_civil(&c, &t), AP_OK);
  AP_CHECK_EQ_INT(t.unix_seconds, 0);
  AP_CHECK_EQ_INT(t.fraction == 0.0, 1);
  /* GNU date: 2026-06-21T12:00:00Z = 1782043200, 2003-10-17T19:30:30Z = 1066419030. */
  c = civil(2026, 6, 21, 12, 0, 0);
  AP_CHECK_EQ_INT(ap_instant_from_civil(&c, &t), AP_OK);
  AP_CHECK_EQ_INT(t.unix_seconds, 1782043200);
  c = civil(2003, 10, 17, 19, 30, 30);
  AP_CHECK_EQ_INT(ap_instant_from_civil(&c, &t), AP_OK);
  AP_CHECK_EQ_INT(t.unix_seconds, 1066419030);
  /* Before the epoch: 1969-12-31T23:59:59.25Z. */
  c = civil(1969, 12, 31, 23, 59, 59);
  c.fraction = 0.25;
  AP_CHECK_EQ_INT(ap_instant_from_civil(&c, &t), AP_OK);
  AP_CHECK_EQ_INT(t.unix_seconds, -1);
  AP_CHECK_NEAR(t.fraction, 0.25, 0.0);
  AP_CHECK_EQ_INT(ap_instant_to_civil(t, &c), AP_OK);
  AP_CHECK(c.year == 1969 && c.month == 12 && c.day == 31 && c.hour == 23 && c.minute == 59 &&
           c.second == 59 && c.fraction == 0.25);

  /* The ends of the range round-trip exactly. */
  c = civil(-2000, 1, 1, 0, 0, 0);
  AP_CHECK_EQ_INT(ap_instant_from_civil(&c, &t), AP_OK);
  AP_CHECK_EQ_INT(t.unix_seconds, AP_TIME_UNIX_MIN);
  c = civil(-2000, 2, 29, 6, 7, 8); /* -2000 is a leap year */
  c.fraction = 0.5;
  AP_CHECK_EQ_INT(ap_instant_from_civil(&c, &t), AP_OK);
  memset(&c, 0, sizeof c);
  AP_CHECK_EQ_INT(ap_instant_to_civil(t, &c), AP_OK);
  AP_CHECK(c.year == -2000 && c.month == 2 && c.day == 29 && c.hour == 6 && c.minute == 7 &&
           c.second == 8 && c.fraction == 0.5);
  c = civil(6000, 12, 31, 23, 59, 59);
  c.fraction = 0.999;
  AP_CHECK_EQ_INT(ap_instant_from_civil(&c, &t), AP_OK);
  AP_CHECK_EQ_INT(t.unix_seconds, AP_TIME_UNIX_MAX);
  AP_CHECK_EQ_INT(ap_instant_to_civil(t, &c), AP_OK);
  AP_CHECK(c.year == 6000 && c.month == 12 && c.day == 31 && c.second == 59 && c.fraction == 0.999);

  /* Errors. */
  c = civil(-2001, 12, 31, 23, 59, 59);
  AP_CHECK_EQ_INT(ap_instant_from_civil(&c, &t), AP_ERR_OUT_OF_RANGE);
  c = civil(6001, 1, 1, 0, 0, 0);
  AP_CHECK_EQ_INT(ap_instant_from_civil(&c, &t), AP_ERR_OUT_OF_RANGE);
  c = civil(2026, 2, 29, 0, 0, 0);
  AP_CHECK_EQ_INT(ap_instant_from_civil(&c, &t), AP_ERR_INVALID_ARGUMENT);
  c = civil(2026, 1, 1, 0, 0, 60);
  AP_CHECK_EQ_INT(ap_civil_validate(&c), AP_ERR_INVALID_ARGUMENT);
  c = civil(2026, 1, 1, 24, 0, 0);
  AP_CHECK_EQ_INT(ap_civil_validate(&c), AP_ERR_INVALID_ARGUMENT);
  c = civil(2026, 1, 1, 0, 0, 0);
  c.fraction = 1.0;
  AP_CHECK_EQ_INT(ap_civil_validate(&c), AP_ERR_INVALID_ARGUMENT);
  c.fraction = NAN;
  AP_CHECK_EQ_INT(ap_civil_validate(&c), AP_ERR_INVALID_ARGUMENT);
  AP_CHECK_EQ_INT(ap_civil_validate(NULL), AP_ERR_NULL_POINTER);
  AP_CHECK_EQ_INT(ap_instant_from_civil(NULL, &t), AP_ERR_NULL_POINTER);
  AP_CHECK_EQ_INT(ap_instant_to_civil(instant(0), NULL), AP_ERR_NULL_POINTER);
  AP_CHECK_EQ_INT(ap_instant_to_civil(instant(AP_TIME_UNIX_MIN - 1), &c), AP_ERR_OUT_OF_RANGE);
  AP_CHECK_EQ_INT(ap_instant_to_civil(instant(AP_TIME_UNIX_MAX + 1), &c), AP_ERR_OUT_OF_RANGE);
  t = instant(0);
  t.fraction = -0.1;
  AP_CHECK_EQ_INT(ap_instant_to_civil(t, &c), AP_ERR_INVALID_ARGUMENT);

  /* Adding seconds: whole steps are exact, fractions carry. */
  t = instant(0);
  t.fraction = 0.75;
  AP_CHECK_EQ_INT(ap_instant_add_seconds(t, 0.5, &t), AP_OK);
  AP_CHECK_EQ_INT(t.unix_seconds, 1);
  AP_CHECK_NEAR(t.fraction, 0.25, 0.0);
  AP_CHECK_EQ_INT(ap_instant_add_seconds(t, -1.5, &t), AP_OK);
  AP_CHECK_EQ_INT(t.unix_seconds, -1);
  AP_CHECK_NEAR(t.fraction, 0.75, 0.0);
  AP_CHECK_EQ_INT(ap_instant_add_seconds(instant(0), -1e-20, &t), AP_OK); /* rounds to 0 */
  AP_CHECK(t.unix_seconds == 0 && t.fraction == 0.0);
  AP_CHECK_EQ_INT(ap_instant_add_seconds(instant(0), 900.0 * 96 * 365, &t), AP_OK);
  AP_CHECK_EQ_INT(t.unix_seconds, 900 * 96 * 365);
  AP_CHECK_EQ_INT(ap_instant_add_seconds(instant(AP_TIME_UNIX_MAX), 1.0, &t), AP_ERR_OUT_OF_RANGE);
  AP_CHECK_EQ_INT(ap_instant_add_seconds(instant(0), 1e300, &t), AP_ERR_OUT_OF_RANGE);
  AP_CHECK_EQ_INT(ap_instant_add_seconds(instant(0), NAN, &t), AP_ERR_INVALID_ARGUMENT);
  AP_CHECK_EQ_INT(ap_instant_add_seconds(instant(0), INFINITY, &t), AP_ERR_INVALID_ARGUMENT);
}

static void test_julian_day(void)
{
  ap_julian_day jd;
  ap_parsed_time p;
  ap_instant t;
  ap_civil_time c;
  /* 1970-01-01T00:00Z = JD 2440587.5; J2000.0 = 2000-01-01T12:00Z = JD 2451545.0. */
  AP_CHECK_EQ_INT(ap_instant_to_julian_day(instant(0), &jd), AP_OK);
  AP_CHECK_NEAR(jd.midnight, 2440587.5, 0.0);
  AP_CHECK_NEAR(jd.day_fraction, 0.0, 0.0);
  AP_CHECK_EQ_INT(ap_instant_to_julian_day(instant(946728000), &jd), AP_OK);
  AP_CHECK_NEAR(jd.midnight, 2451544.5, 0.0);
  AP_CHECK_NEAR(jd.day_fraction, 0.5, 0.0);
  AP_CHECK_NEAR(jd.midnight + jd.day_fraction, 2451545.0, 0.0);
  /* NREL SPA test case: 2003-10-17 12:30:30 at UTC-7 = JD 2452930.312847 (report table A4.1). */
  AP_CHECK_EQ_INT(ap_time_parse_iso8601("2003-10-17T12:30:30-07:00", &p), AP_OK);
  AP_CHECK_EQ_INT(ap_parsed_time_to_instant(&p, NULL, AP_TZ_CHOOSE_ERROR, AP_TZ_CHOOSE_ERROR, &t,
                                            NULL),
                  AP_OK);
  AP_CHECK_EQ_INT(t.unix_seconds, 1066419030);
  AP_CHECK_EQ_INT(ap_instant_to_julian_day(t, &jd), AP_OK);
  AP_CHECK_NEAR(jd.midnight + jd.day_fraction, 2452930.312847, 5e-7);
  AP_CHECK_NEAR(jd.midnight, 2452929.5, 0.0);
  AP_CHECK_NEAR(jd.day_fraction, 70230.0 / 86400.0, 1e-16);
  /* Meeus' algorithm (Gregorian, floor): -2000-01-01 0h = JD 990574.5; 6000-12-31 0h = JD
   * 3912879.5 (= 2440587.5 + 1471927 + 365). */
  c = civil(-2000, 1, 1, 0, 0, 0);
  AP_CHECK_EQ_INT(ap_instant_from_civil(&c, &t), AP_OK);
  AP_CHECK_EQ_INT(ap_instant_to_julian_day(t, &jd), AP_OK);
  AP_CHECK_NEAR(jd.midnight, 990574.5, 0.0);
  c = civil(6000, 12, 31, 18, 0, 0);
  AP_CHECK_EQ_INT(ap_instant_from_civil(&c, &t), AP_OK);
  AP_CHECK_EQ_INT(ap_instant_to_julian_day(t, &jd), AP_OK);
  AP_CHECK_NEAR(jd.midnight, 3912879.5, 0.0);
  AP_CHECK_NEAR(jd.day_fraction, 0.75, 0.0);
  /* Sub-millisecond precision is kept in the fraction part (1 us here). */
  t = instant(1066419030);
  t.fraction = 1e-6;
  AP_CHECK_EQ_INT(ap_instant_to_julian_day(t, &jd), AP_OK);
  AP_CHECK_NEAR(jd.day_fraction * 86400.0 - 70230.0, 1e-6, 1e-10);
  /* The last representable fraction of a day stays below 1. */
  t = instant(86399);
  t.fraction = 0.99999999999999989;
  AP_CHECK_EQ_INT(ap_instant_to_julian_day(t, &jd), AP_OK);
  AP_CHECK(jd.day_fraction < 1.0);
  AP_CHECK_EQ_INT(ap_instant_to_julian_day(instant(0), NULL), AP_ERR_NULL_POINTER);
  AP_CHECK_EQ_INT(ap_instant_to_julian_day(instant(AP_TIME_UNIX_MAX + 1), &jd),
                  AP_ERR_OUT_OF_RANGE);
}

static void test_format(void)
{
  char buf[64];
  ap_instant t;
  ap_civil_time c;
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(instant(0), 0, buf, sizeof buf), AP_OK);
  AP_CHECK(strcmp(buf, "1970-01-01T00:00:00Z") == 0);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(instant(1782043200), 0, buf, sizeof buf), AP_OK);
  AP_CHECK(strcmp(buf, "2026-06-21T12:00:00Z") == 0);
  /* 0.123 is not exact in binary; rounding still prints it. */
  t = instant(1782043200);
  t.fraction = 0.123;
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(t, 3, buf, sizeof buf), AP_OK);
  AP_CHECK(strcmp(buf, "2026-06-21T12:00:00.123Z") == 0);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(t, 9, buf, sizeof buf), AP_OK);
  AP_CHECK(strcmp(buf, "2026-06-21T12:00:00.123000000Z") == 0);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(t, 1, buf, sizeof buf), AP_OK);
  AP_CHECK(strcmp(buf, "2026-06-21T12:00:00.1Z") == 0);
  /* A rounding carry crosses into the next year. GNU date: 2026-12-31T23:59:59Z = 1798761599. */
  t = instant(1798761599);
  t.fraction = 0.9996;
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(t, 3, buf, sizeof buf), AP_OK);
  AP_CHECK(strcmp(buf, "2027-01-01T00:00:00.000Z") == 0);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(t, 4, buf, sizeof buf), AP_OK);
  AP_CHECK(strcmp(buf, "2026-12-31T23:59:59.9996Z") == 0);
  /* Negative years: -2000-01-01 and -0044-03-15 (astronomical year -44 = 45 BC). */
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(instant(AP_TIME_UNIX_MIN), 0, buf, sizeof buf), AP_OK);
  AP_CHECK(strcmp(buf, "-2000-01-01T00:00:00Z") == 0);
  c = civil(-44, 3, 15, 12, 0, 0);
  AP_CHECK_EQ_INT(ap_instant_from_civil(&c, &t), AP_OK);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(t, 0, buf, sizeof buf), AP_OK);
  AP_CHECK(strcmp(buf, "-0044-03-15T12:00:00Z") == 0);
  c = civil(6000, 12, 31, 23, 59, 59);
  AP_CHECK_EQ_INT(ap_instant_from_civil(&c, &t), AP_OK);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(t, 0, buf, sizeof buf), AP_OK);
  AP_CHECK(strcmp(buf, "6000-12-31T23:59:59Z") == 0);
  /* In the range's last second the digits are truncated, not carried into the year 6001,
   * which the parser refuses (until 2026-12-07: "6001-01-01T00:00:00Z"); every text parses. */
  t.fraction = 0.99999999999;
  for (int digits = 0; digits <= 9; ++digits) {
    ap_parsed_time parsed;
    AP_CHECK_EQ_INT(ap_instant_format_iso8601(t, digits, buf, sizeof buf), AP_OK);
    AP_CHECK(strncmp(buf, "6000-12-31T23:59:59", 19) == 0);
    AP_CHECK(digits == 0 || strncmp(buf + 19, ".999999999", (size_t)digits + 1) == 0);
    AP_CHECK_EQ_INT(ap_time_parse_iso8601(buf, &parsed), AP_OK);
  }
  t.unix_seconds = AP_TIME_UNIX_MAX - 1; /* (a second before it carries as always) */
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(t, 3, buf, sizeof buf), AP_OK);
  AP_CHECK(strcmp(buf, "6000-12-31T23:59:59.000Z") == 0);
  /* A local time in the year beyond either end is out of range (the parser would refuse it);
   * the same instants on the other side of UTC are written. */
  AP_CHECK_EQ_INT(ap_instant_format_iso8601_local(instant(AP_TIME_UNIX_MAX), 3600, 0, buf,
                                                  sizeof buf),
                  AP_ERR_OUT_OF_RANGE);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601_local(instant(AP_TIME_UNIX_MAX), -3600, 0, buf,
                                                  sizeof buf),
                  AP_OK);
  AP_CHECK(strcmp(buf, "6000-12-31T22:59:59-01:00") == 0);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601_local(instant(AP_TIME_UNIX_MIN), -60, 0, buf,
                                                  sizeof buf),
                  AP_ERR_OUT_OF_RANGE);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601_local(instant(AP_TIME_UNIX_MIN), 60, 0, buf,
                                                  sizeof buf),
                  AP_OK);
  AP_CHECK(strcmp(buf, "-2000-01-01T00:01:00+00:01") == 0);
  /* Local forms. */
  AP_CHECK_EQ_INT(ap_instant_format_iso8601_local(instant(1782043200), 7200, 0, buf, sizeof buf),
                  AP_OK);
  AP_CHECK(strcmp(buf, "2026-06-21T14:00:00+02:00") == 0);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601_local(instant(1066419030), -7 * 3600, 0, buf,
                                                  sizeof buf),
                  AP_OK);
  AP_CHECK(strcmp(buf, "2003-10-17T12:30:30-07:00") == 0);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601_local(instant(1782023400), 19800, 0, buf, sizeof buf),
                  AP_OK);
  AP_CHECK(strcmp(buf, "2026-06-21T12:00:00+05:30") == 0);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601_local(instant(0), 0, 0, buf, sizeof buf), AP_OK);
  AP_CHECK(strcmp(buf, "1970-01-01T00:00:00+00:00") == 0);
  /* Bern mean time, +00:29:46: 1890-01-01T11:30:14Z (GNU date: -2524480186). */
  AP_CHECK_EQ_INT(ap_instant_format_iso8601_local(instant(-2524480186), 1786, 0, buf, sizeof buf),
                  AP_OK);
  AP_CHECK(strcmp(buf, "1890-01-01T12:00:00+00:29:46") == 0);
  /* Buffer sizes: 20 characters + NUL. */
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(instant(0), 0, buf, 21), AP_OK);
  buf[0] = 'x';
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(instant(0), 0, buf, 20), AP_ERR_BUFFER_TOO_SMALL);
  AP_CHECK(buf[0] == '\0');
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(instant(0), 3, buf, 24), AP_ERR_BUFFER_TOO_SMALL);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(instant(0), 3, buf, 25), AP_OK);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(instant(0), 0, buf, 0), AP_ERR_BUFFER_TOO_SMALL);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(instant(AP_TIME_UNIX_MIN), 9, buf, 32), AP_OK);
  AP_CHECK_EQ_INT((int)strlen(buf), 31);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(instant(0), 0, NULL, 10), AP_ERR_NULL_POINTER);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(instant(0), 10, buf, sizeof buf),
                  AP_ERR_INVALID_ARGUMENT);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(instant(0), -1, buf, sizeof buf),
                  AP_ERR_INVALID_ARGUMENT);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601_local(instant(0), 26 * 3600, 0, buf, sizeof buf),
                  AP_ERR_INVALID_ARGUMENT);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601(instant(AP_TIME_UNIX_MIN - 1), 0, buf, sizeof buf),
                  AP_ERR_OUT_OF_RANGE);
}

/* ---------------------------------------------------------------------------------------------
 * ISO 8601 parsing
 * ------------------------------------------------------------------------------------------- */

static void check_parse(const char *text, int y, int mo, int d, int h, int mi, int s, double frac,
                        int has_time, int has_offset, int32_t offset, int line)
{
  ap_parsed_time p;
  const ap_status st = ap_time_parse_iso8601(text, &p);
  if (st != AP_OK) {
    fprintf(stderr, "line %d: \"%s\": %s\n", line, text, ap_status_string(st));
    AP_CHECK_EQ_INT(st, AP_OK);
    return;
  }
  if (!(p.local.year == y && p.local.month == mo && p.local.day == d && p.local.hour == h &&
        p.local.minute == mi && p.local.second == s && p.local.fraction == frac &&
        p.has_time == has_time && p.has_offset == has_offset && p.utc_offset == offset)) {
    fprintf(stderr, "line %d: \"%s\" parsed as %d-%d-%d %d:%d:%d+%.17g time %d offset %d %d\n",
            line, text, p.local.year, p.local.month, p.local.day, p.local.hour, p.local.minute,
            p.local.second, p.local.fraction, p.has_time, p.has_offset, (int)p.utc_offset);
    AP_CHECK(0);
  }
}

#define CHECK_PARSE(text, y, mo, d, h, mi, s, frac, ht, ho, off)                                   \
  check_parse(text, y, mo, d, h, mi, s, frac, ht, ho, off, __LINE__)

static void test_parse_accept(void)
{
  CHECK_PARSE("2026-06-21T12:00:00Z", 2026, 6, 21, 12, 0, 0, 0.0, 1, 1, 0);
  CHECK_PARSE("2026-06-21T12:00Z", 2026, 6, 21, 12, 0, 0, 0.0, 1, 1, 0);
  CHECK_PARSE("2026-06-21t12:00z", 2026, 6, 21, 12, 0, 0, 0.0, 1, 1, 0);
  CHECK_PARSE("2026-06-21 12:00", 2026, 6, 21, 12, 0, 0, 0.0, 1, 0, 0);
  CHECK_PARSE("2026-06-21T14:00", 2026, 6, 21, 14, 0, 0, 0.0, 1, 0, 0);
  CHECK_PARSE("2026-06-21", 2026, 6, 21, 0, 0, 0, 0.0, 0, 0, 0);
  CHECK_PARSE("2026-06-21T12:00:00.5Z", 2026, 6, 21, 12, 0, 0, 0.5, 1, 1, 0);
  CHECK_PARSE("2026-06-21T12:00:00,25+01:00", 2026, 6, 21, 12, 0, 0, 0.25, 1, 1, 3600);
  CHECK_PARSE("2026-06-21T12:00:00.123456789Z", 2026, 6, 21, 12, 0, 0, 0.123456789, 1, 1, 0);
  CHECK_PARSE("2003-10-17T12:30:30-07:00", 2003, 10, 17, 12, 30, 30, 0.0, 1, 1, -25200);
  CHECK_PARSE("2026-06-21T12:00+0530", 2026, 6, 21, 12, 0, 0, 0.0, 1, 1, 19800);
  CHECK_PARSE("2026-06-21T12:00:59-03", 2026, 6, 21, 12, 0, 59, 0.0, 1, 1, -10800);
  CHECK_PARSE("2026-06-21T12:00+18:00", 2026, 6, 21, 12, 0, 0, 0.0, 1, 1, 64800);
  CHECK_PARSE("2026-06-21T12:00-1800", 2026, 6, 21, 12, 0, 0, 0.0, 1, 1, -64800);
  CHECK_PARSE("2026-06-21T12:00-00:00", 2026, 6, 21, 12, 0, 0, 0.0, 1, 1, 0);
  CHECK_PARSE("2026-06-21T23:59:59.999999999Z", 2026, 6, 21, 23, 59, 59, 0.999999999, 1, 1, 0);
  CHECK_PARSE("2024-02-29", 2024, 2, 29, 0, 0, 0, 0.0, 0, 0, 0);
  CHECK_PARSE("2000-02-29T00:00Z", 2000, 2, 29, 0, 0, 0, 0.0, 1, 1, 0);
  CHECK_PARSE("-2000-01-01T00:00Z", -2000, 1, 1, 0, 0, 0, 0.0, 1, 1, 0);
  CHECK_PARSE("-0044-03-15", -44, 3, 15, 0, 0, 0, 0.0, 0, 0, 0);
  CHECK_PARSE("-0000-01-01", 0, 1, 1, 0, 0, 0, 0.0, 0, 0, 0);
  CHECK_PARSE("+2026-06-21", 2026, 6, 21, 0, 0, 0, 0.0, 0, 0, 0);
  CHECK_PARSE("+006000-12-31T23:59:59Z", 6000, 12, 31, 23, 59, 59, 0.0, 1, 1, 0);
  CHECK_PARSE("0000-01-01", 0, 1, 1, 0, 0, 0, 0.0, 0, 0, 0);
}

static void check_reject(const char *text, ap_status expected, int line)
{
  ap_parsed_time p;
  ap_status st;
  memset(&p, 0x5a, sizeof p);
  st = ap_time_parse_iso8601(text, &p);
  if (st != expected) {
    fprintf(stderr, "line %d: \"%s\" gave %s\n", line, text ? text : "(null)",
            ap_status_string(st));
    AP_CHECK_EQ_INT(st, expected);
  }
  AP_CHECK(p.local.year == 0x5a5a5a5a); /* untouched */
}

#define CHECK_REJECT(text, st) check_reject(text, st, __LINE__)

static void test_parse_reject(void)
{
  ap_parsed_time p;
  char longbuf[600];
  AP_CHECK_EQ_INT(ap_time_parse_iso8601(NULL, &p), AP_ERR_NULL_POINTER);
  AP_CHECK_EQ_INT(ap_time_parse_iso8601("2026-06-21", NULL), AP_ERR_NULL_POINTER);
  CHECK_REJECT("", AP_ERR_PARSE);
  CHECK_REJECT(" ", AP_ERR_PARSE);
  CHECK_REJECT("T", AP_ERR_PARSE);
  /* trailing or leading garbage */
  CHECK_REJECT("2026-06-21T12:00:00Zjunk", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12:00:00Z ", AP_ERR_PARSE);
  CHECK_REJECT(" 2026-06-21T12:00:00Z", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21x", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12:00:00+05:30:00", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12:00:00ZZ", AP_ERR_PARSE);
  /* field ranges */
  CHECK_REJECT("2026-13-01", AP_ERR_PARSE);
  CHECK_REJECT("2026-00-10", AP_ERR_PARSE);
  CHECK_REJECT("2026-01-00", AP_ERR_PARSE);
  CHECK_REJECT("2026-01-32", AP_ERR_PARSE);
  CHECK_REJECT("2026-02-29", AP_ERR_PARSE);
  CHECK_REJECT("2026-02-30", AP_ERR_PARSE);
  CHECK_REJECT("2026-04-31T00:00Z", AP_ERR_PARSE);
  CHECK_REJECT("1900-02-29", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T24:00", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T24:00:00Z", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T25:00Z", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12:60Z", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12:00:60Z", AP_ERR_PARSE);
  CHECK_REJECT("2026-12-31T23:59:60Z", AP_ERR_PARSE);
  /* offsets */
  CHECK_REJECT("2026-06-21T12:00+18:01", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12:00-19:00", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12:00+19", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12:00+05:60", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12:00+5:30", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12:00+05:3", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12:00+053", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12:00+", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12:00UTC", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21Z", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21+01:00", AP_ERR_PARSE);
  /* shapes */
  CHECK_REJECT("2026-6-21", AP_ERR_PARSE);
  CHECK_REJECT("26-06-21", AP_ERR_PARSE);
  CHECK_REJECT("20260621", AP_ERR_PARSE);
  CHECK_REJECT("20260621T120000Z", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12Z", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12:0", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T1200", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12:00:0", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12:00:00.", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12:00:00.Z", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12:00.5", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21  12:00", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21_12:00", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T-1:00", AP_ERR_PARSE);
  CHECK_REJECT("--2026-06-21", AP_ERR_PARSE);
  CHECK_REJECT("+-2026-06-21", AP_ERR_PARSE);
  CHECK_REJECT("-026-06-21", AP_ERR_PARSE);
  /* long digit strings: no overflow, just a parse error */
  CHECK_REJECT("2026-06-21T12:00:00.1234567890Z", AP_ERR_PARSE);
  CHECK_REJECT("99999999999999999999999999-01-01", AP_ERR_PARSE);
  CHECK_REJECT("+99999999999999999999999999-01-01", AP_ERR_PARSE);
  CHECK_REJECT("-99999999999999999999999999-01-01", AP_ERR_PARSE);
  CHECK_REJECT("+0000002026-01-01", AP_ERR_PARSE);
  CHECK_REJECT("2026-0000000000000000000006-21", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T000000000000000000012:00", AP_ERR_PARSE);
  CHECK_REJECT("2026-06-21T12:00+0000000000000000000001", AP_ERR_PARSE);
  memset(longbuf, '9', sizeof longbuf - 1);
  longbuf[sizeof longbuf - 1] = '\0';
  CHECK_REJECT(longbuf, AP_ERR_PARSE);
  memcpy(longbuf, "2026-06-21T12:00:00.", 20);
  CHECK_REJECT(longbuf, AP_ERR_PARSE);
  /* well-formed but outside the SPA range */
  CHECK_REJECT("-2001-12-31T23:59:59Z", AP_ERR_OUT_OF_RANGE);
  CHECK_REJECT("6001-01-01", AP_ERR_OUT_OF_RANGE);
  CHECK_REJECT("9999-12-31T23:59Z", AP_ERR_OUT_OF_RANGE);
  CHECK_REJECT("+10000-01-01", AP_ERR_OUT_OF_RANGE);
  CHECK_REJECT("-999999-01-01", AP_ERR_OUT_OF_RANGE);
  /* a bad field wins over the range */
  CHECK_REJECT("+10000-13-01", AP_ERR_PARSE);
}

/* Random strings over the date-time alphabet: only defined results, and accepted ones are
 * valid civil times. */
static void test_parse_fuzz(void)
{
  static const char alphabet[] = "0123456789-+:.,TZ tz9012-:";
  uint32_t state = 12345u;
  char text[48];
  int k, bad = 0;
  for (k = 0; k < 200000; ++k) {
    ap_parsed_time p;
    ap_status st;
    int n, i;
    state = state * 1664525u + 1013904223u;
    n = (int)(state >> 27) + 4; /* 4..35 */
    if (k % 3 == 0) { /* start from a valid prefix to reach deeper */
      memcpy(text, "2026-06-21T12:00:00", 19);
      i = n < 19 ? n : 19;
    } else {
      i = 0;
    }
    for (; i < n; ++i) {
      state = state * 1664525u + 1013904223u;
      text[i] = alphabet[(state >> 24) % (sizeof alphabet - 1)];
    }
    text[n] = '\0';
    st = ap_time_parse_iso8601(text, &p);
    if (st == AP_OK) {
      if (ap_civil_validate(&p.local) != AP_OK || p.utc_offset < -64800 || p.utc_offset > 64800) {
        ++bad;
      }
    } else if (st != AP_ERR_PARSE && st != AP_ERR_OUT_OF_RANGE) {
      ++bad;
    }
  }
  AP_CHECK_EQ_INT(bad, 0);
}

static void test_parsed_to_instant(void)
{
  ap_parsed_time p;
  ap_instant t;
  ap_tz_local_result r;
  AP_CHECK_EQ_INT(ap_time_parse_iso8601("2026-06-21T14:00:00.25+02:00", &p), AP_OK);
  AP_CHECK_EQ_INT(ap_parsed_time_to_instant(&p, NULL, AP_TZ_CHOOSE_ERROR, AP_TZ_CHOOSE_ERROR, &t,
                                            &r),
                  AP_OK);
  AP_CHECK_EQ_INT(t.unix_seconds, 1782043200);
  AP_CHECK_NEAR(t.fraction, 0.25, 0.0);
  AP_CHECK_EQ_INT(r.count, 1);
  AP_CHECK_EQ_INT(r.before.utc_offset, 7200);
  /* A local time needs a zone. */
  AP_CHECK_EQ_INT(ap_time_parse_iso8601("2026-06-21T14:00", &p), AP_OK);
  AP_CHECK_EQ_INT(ap_parsed_time_to_instant(&p, NULL, AP_TZ_CHOOSE_ERROR, AP_TZ_CHOOSE_ERROR, &t,
                                            NULL),
                  AP_ERR_INVALID_ARGUMENT);
  /* The offset can push a valid local date outside the range. */
  AP_CHECK_EQ_INT(ap_time_parse_iso8601("6000-12-31T23:00-05:00", &p), AP_OK);
  AP_CHECK_EQ_INT(ap_parsed_time_to_instant(&p, NULL, AP_TZ_CHOOSE_ERROR, AP_TZ_CHOOSE_ERROR, &t,
                                            NULL),
                  AP_ERR_OUT_OF_RANGE);
  AP_CHECK_EQ_INT(ap_time_parse_iso8601("-2000-01-01T00:30+01:00", &p), AP_OK);
  AP_CHECK_EQ_INT(ap_parsed_time_to_instant(&p, NULL, AP_TZ_CHOOSE_ERROR, AP_TZ_CHOOSE_ERROR, &t,
                                            NULL),
                  AP_ERR_OUT_OF_RANGE);
  AP_CHECK_EQ_INT(ap_parsed_time_to_instant(NULL, NULL, AP_TZ_CHOOSE_ERROR, AP_TZ_CHOOSE_ERROR, &t,
                                            NULL),
                  AP_ERR_NULL_POINTER);
}

/* ---------------------------------------------------------------------------------------------
 * Zones: names, UTC, errors
 * ------------------------------------------------------------------------------------------- */

static void test_zone_names(void)
{
  static const char *bad[] = { "",
                               "Nowhere/Atlantis",
                               "../../etc/passwd",
                               "/etc/passwd",
                               "Europe/../Europe/Zurich",
                               "./Europe/Zurich",
                               "Europe//Zurich",
                               "Europe/Zurich/",
                               "Europe/Z\xc3\xbcrich",
                               "Europe\\Zurich",
                               "Europe/Zurich ",
                               "zone.tab",
                               "Europe" /* a directory */ };
  char longname[400];
  ap_tz *tz = (ap_tz *)&tz;
  size_t k;
  for (k = 0; k < sizeof bad / sizeof bad[0]; ++k) {
    const ap_status st = ap_tz_load(bad[k], NULL, &tz);
    if (st != AP_ERR_NOT_FOUND) {
      fprintf(stderr, "zone name \"%s\": %s\n", bad[k], ap_status_string(st));
    }
    AP_CHECK_EQ_INT(st, AP_ERR_NOT_FOUND);
    AP_CHECK(tz == NULL);
  }
  memset(longname, 'A', sizeof longname - 1);
  longname[sizeof longname - 1] = '\0';
  AP_CHECK_EQ_INT(ap_tz_load(longname, NULL, &tz), AP_ERR_NOT_FOUND);
  AP_CHECK_EQ_INT(ap_tz_load("Europe/Zurich", "/nonexistent/zoneinfo", &tz), AP_ERR_NOT_FOUND);
  AP_CHECK_EQ_INT(ap_tz_load(NULL, NULL, &tz), AP_ERR_NULL_POINTER);
  AP_CHECK_EQ_INT(ap_tz_load("UTC", NULL, NULL), AP_ERR_NULL_POINTER);
  ap_tz_free(NULL);
  AP_CHECK(strcmp(ap_tz_name(NULL), "") == 0);
}

static void test_zone_utc(void)
{
  const char *names[2] = { "UTC", "Etc/UTC" };
  int k;
  for (k = 0; k < 2; ++k) {
    ap_tz *tz = NULL;
    ap_tz_info info;
    ap_civil_time c = civil(2026, 6, 21, 12, 0, 0);
    ap_instant t;
    ap_tz_local_result r;
    /* Built in: works without any zoneinfo directory. */
    AP_CHECK_EQ_INT(ap_tz_load(names[k], "/nonexistent/zoneinfo", &tz), AP_OK);
    if (!tz) {
      continue;
    }
    AP_CHECK(strcmp(ap_tz_name(tz), names[k]) == 0);
    AP_CHECK_EQ_INT(ap_tz_lookup(tz, instant(1782043200), &info), AP_OK);
    AP_CHECK_EQ_INT(info.utc_offset, 0);
    AP_CHECK_EQ_INT(info.is_dst, 0);
    AP_CHECK(strcmp(info.abbreviation, "UTC") == 0);
    AP_CHECK_EQ_INT(ap_tz_local_to_instant(tz, &c, AP_TZ_CHOOSE_ERROR, AP_TZ_CHOOSE_ERROR, &t, &r),
                    AP_OK);
    AP_CHECK_EQ_INT(t.unix_seconds, 1782043200);
    AP_CHECK_EQ_INT(r.count, 1);
    AP_CHECK_EQ_INT(r.has_transition, 0);
    /* Argument errors. */
    AP_CHECK_EQ_INT(ap_tz_lookup(tz, instant(AP_TIME_UNIX_MAX + 1), &info), AP_ERR_OUT_OF_RANGE);
    AP_CHECK_EQ_INT(ap_tz_lookup(NULL, instant(0), &info), AP_ERR_NULL_POINTER);
    AP_CHECK_EQ_INT(ap_tz_local_to_instant(tz, &c, (ap_tz_choice)7, AP_TZ_CHOOSE_ERROR, &t, &r),
                    AP_ERR_INVALID_ARGUMENT);
    c.month = 13;
    AP_CHECK_EQ_INT(ap_tz_local_to_instant(tz, &c, AP_TZ_CHOOSE_ERROR, AP_TZ_CHOOSE_ERROR, &t, &r),
                    AP_ERR_INVALID_ARGUMENT);
    c = civil(6001, 1, 1, 0, 0, 0);
    AP_CHECK_EQ_INT(ap_tz_local_to_instant(tz, &c, AP_TZ_CHOOSE_ERROR, AP_TZ_CHOOSE_ERROR, &t, &r),
                    AP_ERR_OUT_OF_RANGE);
    ap_tz_free(tz);
  }
}

/* ---------------------------------------------------------------------------------------------
 * Zones: European rules, from a synthetic footer-only file and from the system's tzdata
 * ------------------------------------------------------------------------------------------- */

/* Europe/Zurich (or the same rule in a synthetic file). Facts: CET = +1, CEST = +2; in 2026
 * DST runs from Sun 2026-03-29 01:00Z (1774746000) to Sun 2026-10-25 01:00Z (1792890000); in
 * 2100 from Sun 03-28 01:00Z (4109878800) to Sun 10-31 01:00Z (4128627600). */
static void check_central_europe(const ap_tz *tz, const char *what)
{
  ap_tz_info info;
  ap_tz_local_result r;
  ap_instant t;
  ap_civil_time c;
  int64_t s;
  char msg[160], a[40], b[40];
  fprintf(stderr, "  central European rules: %s\n", what);

  AP_CHECK_EQ_INT(ap_tz_lookup(tz, instant(1782043200), &info), AP_OK);
  AP_CHECK_EQ_INT(info.utc_offset, 7200);
  AP_CHECK_EQ_INT(info.is_dst, 1);
  AP_CHECK(strcmp(info.abbreviation, "CEST") == 0);
  AP_CHECK_EQ_INT(ap_tz_lookup(tz, instant(1768482000), &info), AP_OK);
  AP_CHECK_EQ_INT(info.utc_offset, 3600);
  AP_CHECK_EQ_INT(info.is_dst, 0);
  AP_CHECK(strcmp(info.abbreviation, "CET") == 0);
  AP_CHECK_EQ_INT(offset_at(tz, 1774746000 - 1), 3600);
  AP_CHECK_EQ_INT(offset_at(tz, 1774746000), 7200);
  AP_CHECK_EQ_INT(offset_at(tz, 1792890000 - 1), 7200);
  AP_CHECK_EQ_INT(offset_at(tz, 1792890000), 3600);

  /* 2026-06-21T14:00 local = 12:00Z (CEST); 2026-01-15T14:00 local = 13:00Z (CET). */
  AP_CHECK_EQ_INT(local_to(tz, civil(2026, 6, 21, 14, 0, 0), &s, &r), AP_OK);
  AP_CHECK_EQ_INT(s, 1782043200);
  AP_CHECK_EQ_INT(r.count, 1);
  AP_CHECK(strcmp(r.before.abbreviation, "CEST") == 0);
  AP_CHECK_EQ_INT(local_to(tz, civil(2026, 1, 15, 14, 0, 0), &s, &r), AP_OK);
  AP_CHECK_EQ_INT(s, 1768482000);

  /* Spring forward: 02:00 -> 03:00, so 02:30 does not exist. Candidates: 02:30 at +02:00 =
   * 00:30Z and 02:30 at +01:00 = 01:30Z. */
  c = civil(2026, 3, 29, 2, 30, 0);
  s = 42;
  AP_CHECK_EQ_INT(local_to(tz, c, &s, &r), AP_ERR_TIME_NONEXISTENT);
  AP_CHECK_EQ_INT(s, 0); /* out untouched (local_to starts it at 0) */
  AP_CHECK_EQ_INT(r.count, 0);
  AP_CHECK_EQ_INT(r.has_transition, 1);
  AP_CHECK_EQ_INT(r.transition.unix_seconds, 1774746000);
  AP_CHECK_EQ_INT(r.earlier.unix_seconds, 1774746000 - 1800);
  AP_CHECK_EQ_INT(r.later.unix_seconds, 1774746000 + 1800);
  AP_CHECK_EQ_INT(r.before.utc_offset, 3600);
  AP_CHECK_EQ_INT(r.after.utc_offset, 7200);
  AP_CHECK(strcmp(r.before.abbreviation, "CET") == 0 && strcmp(r.after.abbreviation, "CEST") == 0);
  /* The caller's message, built from the result. */
  AP_CHECK_EQ_INT(ap_instant_format_iso8601_local(r.transition, r.before.utc_offset, 0, a,
                                                  sizeof a),
                  AP_OK);
  AP_CHECK_EQ_INT(ap_instant_format_iso8601_local(r.transition, r.after.utc_offset, 0, b, sizeof b),
                  AP_OK);
  snprintf(msg, sizeof msg, "clocks jump from %.5s to %.5s", a + 11, b + 11);
  AP_CHECK(strcmp(msg, "clocks jump from 02:00 to 03:00") == 0);
  /* Policies: LATER moves forward (03:30 CEST = 01:30Z), EARLIER back (01:30 CET = 00:30Z). */
  AP_CHECK_EQ_INT(ap_tz_local_to_instant(tz, &c, AP_TZ_CHOOSE_LATER, AP_TZ_CHOOSE_ERROR, &t, NULL),
                  AP_OK);
  AP_CHECK_EQ_INT(t.unix_seconds, 1774746000 + 1800);
  AP_CHECK_EQ_INT(ap_tz_local_to_instant(tz, &c, AP_TZ_CHOOSE_EARLIER, AP_TZ_CHOOSE_ERROR, &t,
                                         NULL),
                  AP_OK);
  AP_CHECK_EQ_INT(t.unix_seconds, 1774746000 - 1800);
  /* The gap edges: 01:59:59 and 03:00:00 exist, 02:00:00 and 02:59:59 do not. */
  AP_CHECK_EQ_INT(local_to(tz, civil(2026, 3, 29, 1, 59, 59), &s, NULL), AP_OK);
  AP_CHECK_EQ_INT(s, 1774746000 - 1);
  AP_CHECK_EQ_INT(local_to(tz, civil(2026, 3, 29, 2, 0, 0), &s, NULL), AP_ERR_TIME_NONEXISTENT);
  AP_CHECK_EQ_INT(local_to(tz, civil(2026, 3, 29, 2, 59, 59), &s, NULL), AP_ERR_TIME_NONEXISTENT);
  AP_CHECK_EQ_INT(local_to(tz, civil(2026, 3, 29, 3, 0, 0), &s, NULL), AP_OK);
  AP_CHECK_EQ_INT(s, 1774746000);

  /* Fall back: 03:00 -> 02:00, so 02:30 happens at 00:30Z (CEST) and 01:30Z (CET). */
  c = civil(2026, 10, 25, 2, 30, 0);
  c.fraction = 0.5;
  AP_CHECK_EQ_INT(local_to(tz, c, &s, &r), AP_ERR_TIME_AMBIGUOUS);
  AP_CHECK_EQ_INT(r.count, 2);
  AP_CHECK_EQ_INT(r.has_transition, 1);
  AP_CHECK_EQ_INT(r.transition.unix_seconds, 1792890000);
  AP_CHECK_EQ_INT(r.earlier.unix_seconds, 1792890000 - 1800);
  AP_CHECK_EQ_INT(r.later.unix_seconds, 1792890000 + 1800);
  AP_CHECK_NEAR(r.earlier.fraction, 0.5, 0.0);
  AP_CHECK_EQ_INT(r.before.utc_offset, 7200);
  AP_CHECK_EQ_INT(r.after.utc_offset, 3600);
  AP_CHECK_EQ_INT(ap_tz_local_to_instant(tz, &c, AP_TZ_CHOOSE_ERROR, AP_TZ_CHOOSE_EARLIER, &t,
                                         NULL),
                  AP_OK);
  AP_CHECK_EQ_INT(t.unix_seconds, 1792890000 - 1800);
  AP_CHECK_NEAR(t.fraction, 0.5, 0.0);
  AP_CHECK_EQ_INT(ap_tz_local_to_instant(tz, &c, AP_TZ_CHOOSE_ERROR, AP_TZ_CHOOSE_LATER, &t, NULL),
                  AP_OK);
  AP_CHECK_EQ_INT(t.unix_seconds, 1792890000 + 1800);
  /* The overlap edges: 01:59:59 and 03:00:00 are unique, 02:00:00 and 02:59:59 are not. */
  AP_CHECK_EQ_INT(local_to(tz, civil(2026, 10, 25, 1, 59, 59), &s, NULL), AP_OK);
  AP_CHECK_EQ_INT(local_to(tz, civil(2026, 10, 25, 2, 0, 0), &s, NULL), AP_ERR_TIME_AMBIGUOUS);
  AP_CHECK_EQ_INT(local_to(tz, civil(2026, 10, 25, 2, 59, 59), &s, NULL), AP_ERR_TIME_AMBIGUOUS);
  AP_CHECK_EQ_INT(local_to(tz, civil(2026, 10, 25, 3, 0, 0), &s, NULL), AP_OK);
  AP_CHECK_EQ_INT(s, 1792890000 + 3600);

  /* 2100, beyond any transition table: the footer rule. */
  AP_CHECK_EQ_INT(offset_at(tz, 4109878800 - 1), 3600);
  AP_CHECK_EQ_INT(offset_at(tz, 4109878800), 7200);
  AP_CHECK_EQ_INT(offset_at(tz, 4128627600 - 1), 7200);
  AP_CHECK_EQ_INT(offset_at(tz, 4128627600), 3600);
  AP_CHECK_EQ_INT(local_to(tz, civil(2100, 7, 1, 12, 0, 0), &s, NULL), AP_OK);
  AP_CHECK_EQ_INT(s, 4118119200); /* 2100-07-01T10:00Z */
  AP_CHECK_EQ_INT(local_to(tz, civil(2100, 3, 28, 2, 30, 0), &s, &r), AP_ERR_TIME_NONEXISTENT);
  AP_CHECK_EQ_INT(r.transition.unix_seconds, 4109878800);
  AP_CHECK_EQ_INT(local_to(tz, civil(2100, 10, 31, 2, 30, 0), &s, &r), AP_ERR_TIME_AMBIGUOUS);
  AP_CHECK_EQ_INT(r.transition.unix_seconds, 4128627600);
  AP_CHECK_EQ_INT(r.earlier.unix_seconds, 4128627600 - 1800);
  AP_CHECK_EQ_INT(r.later.unix_seconds, 4128627600 + 1800);
  /* Year 6000 still follows the rule: 6000-07-01T12:00 local is CEST. */
  AP_CHECK_EQ_INT(local_to(tz, civil(6000, 7, 1, 12, 0, 0), &s, &r), AP_OK);
  AP_CHECK_EQ_INT(r.before.utc_offset, 7200);
}

/* Round trips over a long span: every UTC instant maps to a local time that maps back to it
 * (as the unique answer, or one of the two in an overlap); local times in gaps are skipped. */
static void check_round_trips(const ap_tz *tz, int64_t from, int64_t to, int64_t step)
{
  int64_t s;
  int bad = 0, ambiguous = 0;
  for (s = from; s < to && bad < 5; s += step) {
    ap_tz_info info;
    ap_civil_time c;
    ap_instant t = instant(0);
    ap_tz_local_result r;
    ap_status st;
    AP_CHECK_EQ_INT(ap_tz_lookup(tz, instant(s), &info), AP_OK);
    AP_CHECK_EQ_INT(ap_instant_to_civil(instant(s + info.utc_offset), &c), AP_OK);
    st = ap_tz_local_to_instant(tz, &c, AP_TZ_CHOOSE_ERROR, AP_TZ_CHOOSE_ERROR, &t, &r);
    if (st == AP_OK) {
      bad += t.unix_seconds != s;
    } else if (st == AP_ERR_TIME_AMBIGUOUS) {
      ++ambiguous;
      bad += (r.earlier.unix_seconds != s && r.later.unix_seconds != s) || !r.has_transition;
    } else {
      ++bad;
    }
    if (bad) {
      fprintf(stderr, "  round trip failed at %lld in %s (%s)\n", (long long)s, ap_tz_name(tz),
              ap_status_string(st));
    }
  }
  AP_CHECK_EQ_INT(bad, 0);
  AP_CHECK(ambiguous > 0 || to - from < 400LL * 86400);
}

static void test_zone_synthetic_europe(void)
{
  ap_tz *tz = load_footer_zone("Synthetic_CET", "CET", 3600, "CET-1CEST,M3.5.0,M10.5.0/3");
  if (tz) {
    check_central_europe(tz, "footer-only TZif file");
    check_round_trips(tz, 0, 4200000000LL, 7 * 3600 + 13 * 60);
    ap_tz_free(tz);
  }
}

static void test_zone_system(void)
{
  ap_tz *tz = NULL;
  ap_tz_info info;
  ap_tz_local_result r;
  int64_t s;
  if (!file_exists(SYSTEM_ZONEINFO "/Europe/Zurich")) {
    fprintf(stderr, "SKIP: " SYSTEM_ZONEINFO "/Europe/Zurich not found (package tzdata); "
                    "system zone tests skipped\n");
    return;
  }
  /* Europe/Zurich: the transition table up to 2037, the footer after. */
  AP_CHECK_EQ_INT(ap_tz_load("Europe/Zurich", SYSTEM_ZONEINFO, &tz), AP_OK);
  if (tz) {
    AP_CHECK(strcmp(ap_tz_name(tz), "Europe/Zurich") == 0);
    check_central_europe(tz, SYSTEM_ZONEINFO "/Europe/Zurich");
    /* 1900-01-01T12:00 local = 11:00Z (CET since 1894); 1890: Bern mean time +00:29:46. */
    AP_CHECK_EQ_INT(local_to(tz, civil(1900, 1, 1, 12, 0, 0), &s, NULL), AP_OK);
    AP_CHECK_EQ_INT(s, -2208949200);
    AP_CHECK_EQ_INT(local_to(tz, civil(1890, 1, 1, 12, 0, 0), &s, &r), AP_OK);
    AP_CHECK_EQ_INT(s, -2524480186);
    AP_CHECK_EQ_INT(r.before.utc_offset, 1786);
    AP_CHECK(strcmp(r.before.abbreviation, "BMT") == 0);
    /* Before the first transition: local mean time (+00:34:08) of the first type. */
    AP_CHECK_EQ_INT(offset_at(tz, AP_TIME_UNIX_MIN), 34 * 60 + 8);
    check_round_trips(tz, -2500000000LL, 4300000000LL, 5 * 3600 + 17 * 60);
    ap_tz_free(tz);
  }
  /* The same zone found through TZDIR. */
  if (setenv("TZDIR", SYSTEM_ZONEINFO, 1) == 0) {
    AP_CHECK_EQ_INT(ap_tz_load("Europe/Zurich", NULL, &tz), AP_OK);
    ap_tz_free(tz);
    unsetenv("TZDIR");
  }

  /* America/New_York: EST -5, EDT -4. 2026: DST from Sun 03-08 02:00 EST to Sun 11-01 02:00
   * EDT. */
  if (ap_tz_load("America/New_York", SYSTEM_ZONEINFO, &tz) == AP_OK) {
    AP_CHECK_EQ_INT(local_to(tz, civil(2026, 7, 4, 12, 0, 0), &s, &r), AP_OK);
    AP_CHECK_EQ_INT(s, 1783180800); /* 2026-07-04T16:00Z */
    AP_CHECK(strcmp(r.before.abbreviation, "EDT") == 0);
    AP_CHECK_EQ_INT(local_to(tz, civil(2026, 1, 4, 12, 0, 0), &s, NULL), AP_OK);
    AP_CHECK_EQ_INT(s, 1767546000); /* 2026-01-04T17:00Z */
    AP_CHECK_EQ_INT(local_to(tz, civil(2026, 3, 8, 2, 30, 0), &s, &r), AP_ERR_TIME_NONEXISTENT);
    AP_CHECK_EQ_INT(r.transition.unix_seconds, 1772953200); /* 2026-03-08T07:00Z */
    AP_CHECK_EQ_INT(r.later.unix_seconds, 1772955000);      /* 02:30 EST = 07:30Z */
    AP_CHECK_EQ_INT(local_to(tz, civil(2026, 11, 1, 1, 30, 0), &s, &r), AP_ERR_TIME_AMBIGUOUS);
    AP_CHECK_EQ_INT(r.earlier.unix_seconds, 1793511000); /* 05:30Z, EDT */
    AP_CHECK_EQ_INT(r.later.unix_seconds, 1793514600);   /* 06:30Z, EST */
    AP_CHECK_EQ_INT(local_to(tz, civil(1900, 1, 1, 12, 0, 0), &s, NULL), AP_OK);
    AP_CHECK_EQ_INT(s, -2208927600); /* EST: 17:00Z */
    AP_CHECK_EQ_INT(local_to(tz, civil(2100, 7, 1, 12, 0, 0), &s, NULL), AP_OK);
    AP_CHECK_EQ_INT(s, 4118140800); /* footer, EDT: 16:00Z */
    /* 2100: second Sunday of March = 03-14, first Sunday of November = 11-07. */
    AP_CHECK_EQ_INT(offset_at(tz, 4108690800 - 1), -18000); /* 2100-03-14T07:00Z */
    AP_CHECK_EQ_INT(offset_at(tz, 4108690800), -14400);
    AP_CHECK_EQ_INT(offset_at(tz, 4129250400 - 1), -14400); /* 2100-11-07T06:00Z */
    AP_CHECK_EQ_INT(offset_at(tz, 4129250400), -18000);
    check_round_trips(tz, -2500000000LL, 4300000000LL, 5 * 3600 + 17 * 60);
    ap_tz_free(tz);
  } else {
    AP_CHECK(0);
  }

  /* Australia/Sydney, southern DST: AEDT +11 from the first Sunday of October to the first
   * Sunday of April (03:00 AEDT -> 02:00 AEST). */
  if (ap_tz_load("Australia/Sydney", SYSTEM_ZONEINFO, &tz) == AP_OK) {
    AP_CHECK_EQ_INT(local_to(tz, civil(2026, 1, 15, 12, 0, 0), &s, &r), AP_OK);
    AP_CHECK_EQ_INT(s, 1768438800); /* 01:00Z */
    AP_CHECK_EQ_INT(r.before.is_dst, 1);
    AP_CHECK_EQ_INT(local_to(tz, civil(2026, 7, 15, 12, 0, 0), &s, &r), AP_OK);
    AP_CHECK_EQ_INT(s, 1784080800); /* 02:00Z */
    AP_CHECK_EQ_INT(r.before.is_dst, 0);
    AP_CHECK_EQ_INT(local_to(tz, civil(2026, 10, 4, 2, 30, 0), &s, &r), AP_ERR_TIME_NONEXISTENT);
    AP_CHECK_EQ_INT(r.transition.unix_seconds, 1791043200); /* 2026-10-03T16:00Z */
    AP_CHECK_EQ_INT(local_to(tz, civil(2026, 4, 5, 2, 30, 0), &s, &r), AP_ERR_TIME_AMBIGUOUS);
    AP_CHECK_EQ_INT(r.earlier.unix_seconds, 1775316600); /* 2026-04-04T15:30Z */
    AP_CHECK_EQ_INT(r.later.unix_seconds, 1775320200);   /* 2026-04-04T16:30Z */
    /* 2100 (footer): 2100-01-15T12:00 AEDT = 01:00Z; the April change on 2100-04-04 (a
     * Sunday) at 2100-04-03T16:00Z makes 02:30 ambiguous. */
    AP_CHECK_EQ_INT(local_to(tz, civil(2100, 1, 15, 12, 0, 0), &s, NULL), AP_OK);
    AP_CHECK_EQ_INT(s, 4103658000);
    AP_CHECK_EQ_INT(local_to(tz, civil(2100, 4, 4, 2, 30, 0), &s, &r), AP_ERR_TIME_AMBIGUOUS);
    AP_CHECK_EQ_INT(r.transition.unix_seconds, 4110451200);
    check_round_trips(tz, -2500000000LL, 4300000000LL, 5 * 3600 + 17 * 60);
    ap_tz_free(tz);
  } else {
    AP_CHECK(0);
  }

  /* Asia/Kolkata: IST +05:30 without DST. */
  if (ap_tz_load("Asia/Kolkata", SYSTEM_ZONEINFO, &tz) == AP_OK) {
    AP_CHECK_EQ_INT(ap_tz_lookup(tz, instant(1782043200), &info), AP_OK);
    AP_CHECK_EQ_INT(info.utc_offset, 19800);
    AP_CHECK_EQ_INT(info.is_dst, 0);
    AP_CHECK(strcmp(info.abbreviation, "IST") == 0);
    AP_CHECK_EQ_INT(local_to(tz, civil(2026, 6, 21, 12, 0, 0), &s, NULL), AP_OK);
    AP_CHECK_EQ_INT(s, 1782023400); /* 06:30Z */
    AP_CHECK_EQ_INT(offset_at(tz, 4118119200), 19800); /* 2100 */
    ap_tz_free(tz);
  } else {
    AP_CHECK(0);
  }

  /* Europe/Dublin: "negative DST" footer (IST-1GMT0,M10.5.0,M3.5.0/1): summer +1, winter 0,
   * in 2100 too. */
  if (ap_tz_load("Europe/Dublin", SYSTEM_ZONEINFO, &tz) == AP_OK) {
    AP_CHECK_EQ_INT(offset_at(tz, 1782903600), 3600); /* 2026-07-01T11:00Z */
    AP_CHECK_EQ_INT(offset_at(tz, 1767268800), 0);    /* 2026-01-01T12:00Z */
    AP_CHECK_EQ_INT(offset_at(tz, 4118122800), 3600); /* 2100-07-01T11:00Z */
    AP_CHECK_EQ_INT(offset_at(tz, 4102488000), 0);    /* 2100-01-01T12:00Z */
    AP_CHECK_EQ_INT(offset_at(tz, 4109878800 - 1), 0); /* EU change, 2100-03-28T01:00Z */
    AP_CHECK_EQ_INT(offset_at(tz, 4109878800), 3600);
    ap_tz_free(tz);
  } else {
    AP_CHECK(0);
  }

  /* Leap-second ("right/") zones are refused rather than misread. */
  if (file_exists(SYSTEM_ZONEINFO "/right/Europe/Zurich")) {
    AP_CHECK_EQ_INT(ap_tz_load("right/Europe/Zurich", SYSTEM_ZONEINFO, &tz), AP_ERR_BAD_FILE);
  }
}

/* ---------------------------------------------------------------------------------------------
 * POSIX TZ rule forms (synthetic files; expectations worked out by hand)
 * ------------------------------------------------------------------------------------------- */

static void test_posix_rules(void)
{
  ap_tz *tz;
  int64_t s;
  ap_tz_local_result r;

  /* Jn and zero-based n forms, a time over 24 h: DST (+2) from March 1 (J60 never counts Feb 29)
   * at 02:00 local standard (+1) = 01:00Z, to zero-based day 300 at 26:00 local DST, i.e. the
   * next day 02:00 +2 = 00:00Z. 2026: day 300 = Oct 28 -> Oct 29 00:00Z (1793232000); March 1
   * 01:00Z = 1772326800. Leap year 2028: day 300 = Oct 27 -> Oct 28 00:00Z (1856304000); March 1
   * 01:00Z = 1835485200. */
  tz = load_footer_zone("Synthetic_J", "AAA", 3600, "AAA-1BBB,J60/2,300/26");
  if (tz) {
    AP_CHECK_EQ_INT(offset_at(tz, 1772326800 - 1), 3600);
    AP_CHECK_EQ_INT(offset_at(tz, 1772326800), 7200);
    AP_CHECK_EQ_INT(offset_at(tz, 1793232000 - 1), 7200);
    AP_CHECK_EQ_INT(offset_at(tz, 1793232000), 3600);
    AP_CHECK_EQ_INT(offset_at(tz, 1835485200 - 1), 3600);
    AP_CHECK_EQ_INT(offset_at(tz, 1835485200), 7200);
    AP_CHECK_EQ_INT(offset_at(tz, 1856304000 - 1), 7200);
    AP_CHECK_EQ_INT(offset_at(tz, 1856304000), 3600);
    check_round_trips(tz, 1700000000, 1900000000, 3 * 3600 + 7 * 60);
    ap_tz_free(tz);
  }

  /* Negative transition time and quoted names (America/Nuuk since 2023): DST starts on the last
   * Sunday of March at -1:00 local (-02) = 01:00Z and ends on the last Sunday of October at
   * 0:00 local (-01) = 01:00Z, the EU instants. */
  tz = load_footer_zone("Synthetic_Nuuk", "-02", -7200, "<-02>2<-01>,M3.5.0/-1,M10.5.0/0");
  if (tz) {
    ap_tz_info info;
    AP_CHECK_EQ_INT(offset_at(tz, 1774746000 - 1), -7200);
    AP_CHECK_EQ_INT(ap_tz_lookup(tz, instant(1774746000), &info), AP_OK);
    AP_CHECK_EQ_INT(info.utc_offset, -3600);
    AP_CHECK(strcmp(info.abbreviation, "-01") == 0);
    AP_CHECK_EQ_INT(offset_at(tz, 1792890000 - 1), -3600);
    AP_CHECK_EQ_INT(offset_at(tz, 1792890000), -7200);
    /* The gap is Saturday 2026-03-28 23:00 -> Sunday 00:00 local. */
    AP_CHECK_EQ_INT(local_to(tz, civil(2026, 3, 28, 23, 30, 0), &s, &r), AP_ERR_TIME_NONEXISTENT);
    AP_CHECK_EQ_INT(r.transition.unix_seconds, 1774746000);
    check_round_trips(tz, 1700000000, 1900000000, 3 * 3600 + 7 * 60);
    ap_tz_free(tz);
  }

  /* DST all year (RFC 8536 section 3.3.1): starts Jan 1 00:00, ends Dec 31 at 24:00 + 1 h. */
  tz = load_footer_zone("Synthetic_AllYear", "EST", -18000, "EST5EDT,0/0,J365/25");
  if (tz) {
    int64_t t;
    int bad = 0;
    for (t = 1767225600 - 86400 * 3; t < 1767225600 + 86400 * 400; t += 1800) {
      bad += offset_at(tz, t) != -14400;
    }
    AP_CHECK_EQ_INT(bad, 0);
    AP_CHECK_EQ_INT(local_to(tz, civil(2026, 12, 31, 23, 30, 0), &s, NULL), AP_OK);
    AP_CHECK_EQ_INT(local_to(tz, civil(2027, 1, 1, 0, 30, 0), &s, NULL), AP_OK);
    AP_CHECK_EQ_INT(s, 1798777800); /* EDT: 2027-01-01T04:30Z */
    ap_tz_free(tz);
  }

  /* No rule after the DST name: tzcode's default, US rules (2026: 03-08 07:00Z). */
  tz = load_footer_zone("Synthetic_Default", "EST", -18000, "EST5EDT");
  if (tz) {
    AP_CHECK_EQ_INT(offset_at(tz, 1772953200 - 1), -18000);
    AP_CHECK_EQ_INT(offset_at(tz, 1772953200), -14400);
    ap_tz_free(tz);
  }

  /* Standard time only, with minutes: "IST-5:30". */
  tz = load_footer_zone("Synthetic_IST", "IST", 19800, "IST-5:30");
  if (tz) {
    AP_CHECK_EQ_INT(offset_at(tz, 4118119200), 19800);
    AP_CHECK_EQ_INT(local_to(tz, civil(2026, 6, 21, 12, 0, 0), &s, NULL), AP_OK);
    AP_CHECK_EQ_INT(s, 1782023400);
    ap_tz_free(tz);
  }
  remove_file("Synthetic_J");
  remove_file("Synthetic_Nuuk");
  remove_file("Synthetic_AllYear");
  remove_file("Synthetic_Default");
  remove_file("Synthetic_IST");
}

/* A version-1 file (32-bit data, no footer) and a v2 file with a table and no footer rule. */
static void test_tzif_versions(void)
{
  static const int64_t at[2] = { 0, 86400 };
  static const unsigned char idx[2] = { 1, 0 };
  static const int32_t off[2] = { 0, 3600 };
  static const unsigned char dst[2] = { 0, 1 }, ai[2] = { 0, 4 };
  static const char chars[8] = "AAA\0BBB";
  unsigned char buf[512];
  tzif_spec spec;
  ap_tz *tz = NULL;
  int64_t s;
  ap_tz_local_result r;
  int v;
  for (v = 0; v < 2; ++v) {
    memset(&spec, 0, sizeof spec);
    spec.version = v ? '3' : 0;
    spec.timecnt = 2;
    spec.at = at;
    spec.idx = idx;
    spec.typecnt = 2;
    spec.utoff = off;
    spec.isdst = dst;
    spec.abbrind = ai;
    spec.chars = chars;
    spec.charcnt = 8;
    spec.footer = ""; /* empty: the last type continues */
    AP_CHECK(write_file("Synthetic_V", buf, build_tzif(buf, &spec)));
    AP_CHECK_EQ_INT(ap_tz_load("Synthetic_V", tmpdir, &tz), AP_OK);
    if (!tz) {
      continue;
    }
    /* Type 0 before the first transition, BBB (+1, DST) for one day, then AAA for ever. */
    AP_CHECK_EQ_INT(offset_at(tz, -1), 0);
    AP_CHECK_EQ_INT(offset_at(tz, 0), 3600);
    AP_CHECK_EQ_INT(offset_at(tz, 86399), 3600);
    AP_CHECK_EQ_INT(offset_at(tz, 86400), 0);
    AP_CHECK_EQ_INT(offset_at(tz, AP_TIME_UNIX_MAX), 0);
    AP_CHECK_EQ_INT(offset_at(tz, AP_TIME_UNIX_MIN), 0);
    AP_CHECK_EQ_INT(local_to(tz, civil(1970, 1, 1, 0, 30, 0), &s, &r), AP_ERR_TIME_NONEXISTENT);
    AP_CHECK_EQ_INT(r.transition.unix_seconds, 0);
    AP_CHECK_EQ_INT(local_to(tz, civil(1970, 1, 2, 0, 30, 0), &s, &r), AP_ERR_TIME_AMBIGUOUS);
    AP_CHECK_EQ_INT(r.earlier.unix_seconds, 86400 - 1800);
    AP_CHECK_EQ_INT(r.later.unix_seconds, 86400 + 1800);
    ap_tz_free(tz);
    tz = NULL;
  }
  remove_file("Synthetic_V");
}

/* ---------------------------------------------------------------------------------------------
 * Corrupt files
 * ------------------------------------------------------------------------------------------- */

static ap_status load_bytes(const void *data, size_t n)
{
  ap_tz *tz = NULL;
  ap_status st;
  if (!write_file("Bad", data, n)) {
    return AP_ERR_NOT_FOUND;
  }
  st = ap_tz_load("Bad", tmpdir, &tz);
  if (st == AP_OK) { /* exercise the loaded zone; must not crash */
    int64_t s;
    ap_tz_local_result r;
    ap_instant t;
    ap_civil_time c = civil(2026, 3, 29, 2, 30, 0);
    for (s = AP_TIME_UNIX_MIN; s < AP_TIME_UNIX_MAX - 20000000000LL; s += 20000000000LL) {
      offset_at(tz, s);
      ap_instant_to_civil(instant(s), &c);
      c.second = 0;
      ap_tz_local_to_instant(tz, &c, AP_TZ_CHOOSE_LATER, AP_TZ_CHOOSE_EARLIER, &t, &r);
    }
    c = civil(2026, 3, 29, 2, 30, 0);
    ap_tz_local_to_instant(tz, &c, AP_TZ_CHOOSE_ERROR, AP_TZ_CHOOSE_ERROR, &t, &r);
    offset_at(tz, 1774746000);
    ap_tz_free(tz);
  }
  AP_CHECK(tz == NULL || st == AP_OK);
  return st;
}

static void test_bad_files(void)
{
  static const int64_t at[2] = { 100, 50 }; /* not ascending */
  static const unsigned char idx_ok[2] = { 0, 0 }, idx_bad[2] = { 0, 2 };
  static const int32_t off[1] = { 3600 }, off_bad[1] = { 200000 };
  static const unsigned char dst[1] = { 0 }, dst_bad[1] = { 2 };
  static const unsigned char ai[1] = { 0 }, ai_bad[1] = { 4 };
  static const char chars[4] = "CET", chars_unterminated[4] = { 'C', 'E', 'T', 'X' };
  static const char *bad_footers[] = { "CET-1CEST,M13.5.0,M10.5.0/3", "CET-1CEST,M3.5.0",
                                       "CET-1CEST,M3.5.0,M10.5.0/168", "CE-1", "CET",
                                       "CET-1CEST,M3.6.0,M10.5.0", "CET-1CEST,J0,J365",
                                       "CET-25", "<CET-1", "CET-1CEST,M3.5.0,M10.5.0/3x" };
  unsigned char buf[8192], good[8192];
  tzif_spec spec;
  size_t n, k, cut;
  uint32_t state = 777u;
  int fuzz_ok = 0, fuzz_bad = 0, other = 0;

  /* Not TZif at all, empty, header only. */
  AP_CHECK_EQ_INT(load_bytes("hello world, this is not a zone file\n", 37), AP_ERR_BAD_FILE);
  AP_CHECK_EQ_INT(load_bytes("", 0), AP_ERR_BAD_FILE);
  AP_CHECK_EQ_INT(load_bytes("TZif2", 5), AP_ERR_BAD_FILE);

  /* Field-level corruption of a small valid file. */
  memset(&spec, 0, sizeof spec);
  spec.version = '2';
  spec.timecnt = 1;
  spec.at = at;
  spec.idx = idx_ok;
  spec.typecnt = 1;
  spec.utoff = off;
  spec.isdst = dst;
  spec.abbrind = ai;
  spec.chars = chars;
  spec.charcnt = 4;
  spec.footer = "CET-1CEST,M3.5.0,M10.5.0/3";
  n = build_tzif(good, &spec);
  AP_CHECK_EQ_INT(load_bytes(good, n), AP_OK);
  spec.timecnt = 2;
  spec.idx = idx_ok;
  AP_CHECK_EQ_INT(load_bytes(buf, build_tzif(buf, &spec)), AP_ERR_BAD_FILE); /* order */
  spec.timecnt = 1;
  spec.idx = idx_bad + 1;
  AP_CHECK_EQ_INT(load_bytes(buf, build_tzif(buf, &spec)), AP_ERR_BAD_FILE); /* type index */
  spec.idx = idx_ok;
  spec.utoff = off_bad;
  AP_CHECK_EQ_INT(load_bytes(buf, build_tzif(buf, &spec)), AP_ERR_BAD_FILE); /* offset */
  spec.utoff = off;
  spec.isdst = dst_bad;
  AP_CHECK_EQ_INT(load_bytes(buf, build_tzif(buf, &spec)), AP_ERR_BAD_FILE); /* isdst */
  spec.isdst = dst;
  spec.abbrind = ai_bad;
  AP_CHECK_EQ_INT(load_bytes(buf, build_tzif(buf, &spec)), AP_ERR_BAD_FILE); /* abbr index */
  spec.abbrind = ai;
  spec.chars = chars_unterminated;
  AP_CHECK_EQ_INT(load_bytes(buf, build_tzif(buf, &spec)), AP_ERR_BAD_FILE); /* no NUL */
  spec.chars = chars;
  spec.typecnt = 0;
  spec.timecnt = 0;
  AP_CHECK_EQ_INT(load_bytes(buf, build_tzif(buf, &spec)), AP_ERR_BAD_FILE); /* no types */
  spec.typecnt = 1;
  spec.timecnt = 1;
  for (k = 0; k < sizeof bad_footers / sizeof bad_footers[0]; ++k) {
    spec.footer = bad_footers[k];
    n = build_tzif(buf, &spec);
    if (load_bytes(buf, n) != AP_ERR_BAD_FILE) {
      fprintf(stderr, "footer \"%s\" accepted\n", bad_footers[k]);
      AP_CHECK(0);
    }
  }
  spec.footer = "CET-1CEST,M3.5.0,M10.5.0/3";
  n = build_tzif(buf, &spec);
  /* Footer without its final newline, with a NUL inside, or missing entirely. */
  AP_CHECK_EQ_INT(load_bytes(buf, n - 1), AP_ERR_BAD_FILE);
  buf[n - 3] = '\0';
  AP_CHECK_EQ_INT(load_bytes(buf, n), AP_ERR_BAD_FILE);
  n = build_tzif(buf, &spec);
  AP_CHECK_EQ_INT(load_bytes(buf, n - strlen(spec.footer) - 2), AP_ERR_BAD_FILE);
  /* Huge counts (timecnt = 0xffffffff in the v2 header) must not allocate or read past the end.
   * The v2 header starts after the v1 header (44) and v1 block (4+1+6+4 = 15). */
  memcpy(buf, good, 59 + 44);
  buf[59 + 32] = buf[59 + 33] = buf[59 + 34] = buf[59 + 35] = 0xff;
  AP_CHECK_EQ_INT(load_bytes(buf, n), AP_ERR_BAD_FILE);
  memcpy(buf, good, 44);
  buf[40] = buf[41] = buf[42] = buf[43] = 0xff; /* v1 charcnt */
  AP_CHECK_EQ_INT(load_bytes(buf, 44), AP_ERR_BAD_FILE);
  /* A leap-second table is refused. */
  spec.leapcnt = 1;
  AP_CHECK_EQ_INT(load_bytes(buf, build_tzif(buf, &spec)), AP_ERR_BAD_FILE);
  spec.leapcnt = 0;

  /* Every truncation of a real file (or of the synthetic one) is refused; byte flips never
   * crash. */
  n = read_whole(SYSTEM_ZONEINFO "/Europe/Zurich", good, sizeof good);
  if (n == 0 || n == sizeof good) {
    spec.footer = "CET-1CEST,M3.5.0,M10.5.0/3";
    n = build_tzif(good, &spec);
  }
  AP_CHECK_EQ_INT(load_bytes(good, n), AP_OK);
  for (cut = 0; cut < n; ++cut) {
    if (load_bytes(good, cut) != AP_ERR_BAD_FILE) {
      fprintf(stderr, "truncation to %zu bytes accepted\n", cut);
      AP_CHECK(0);
      break;
    }
  }
  for (k = 0; k < 1500; ++k) {
    int flips, f;
    ap_status st;
    memcpy(buf, good, n);
    state = state * 1664525u + 1013904223u;
    flips = 1 + (int)(state >> 30);
    for (f = 0; f < flips; ++f) {
      state = state * 1664525u + 1013904223u;
      /* Bias towards the headers and counts, where corruption matters most. */
      const size_t pos = (state >> 8) % (k % 2 ? n : (n < 200 ? n : 200));
      state = state * 1664525u + 1013904223u;
      buf[pos] = (unsigned char)(state >> 24);
    }
    st = load_bytes(buf, n);
    if (st == AP_OK) {
      ++fuzz_ok;
    } else if (st == AP_ERR_BAD_FILE) {
      ++fuzz_bad;
    } else {
      ++other;
    }
  }
  AP_CHECK_EQ_INT(other, 0);
  AP_CHECK(fuzz_bad > 0);
  fprintf(stderr, "  fuzzed zone files: %d loaded, %d refused\n", fuzz_ok, fuzz_bad);
  remove_file("Bad");
}

int main(void)
{
  memcpy(tmpdir, "/tmp/ap_time_test_XXXXXX", 25);
  if (!mkdtemp(tmpdir)) {
    fprintf(stderr, "cannot create a temporary directory\n");
    return 1;
  }
  AP_TEST_RUN(test_calendar);
  AP_TEST_RUN(test_instants);
  AP_TEST_RUN(test_julian_day);
  AP_TEST_RUN(test_format);
  AP_TEST_RUN(test_parse_accept);
  AP_TEST_RUN(test_parse_reject);
  AP_TEST_RUN(test_parse_fuzz);
  AP_TEST_RUN(test_parsed_to_instant);
  AP_TEST_RUN(test_zone_names);
  AP_TEST_RUN(test_zone_utc);
  AP_TEST_RUN(test_zone_synthetic_europe);
  AP_TEST_RUN(test_zone_system);
  AP_TEST_RUN(test_posix_rules);
  AP_TEST_RUN(test_tzif_versions);
  AP_TEST_RUN(test_bad_files);
  remove_file("Synthetic_CET");
  rmdir(tmpdir);
  AP_TEST_MAIN_END();
}
