/* SPDX-License-Identifier: BSD-3-Clause */
/* Minimal assertions for the C core's unit tests: each failure prints file:line and the values,
 * and the test's exit status is the number of failures (0 = pass). */
#ifndef APTEST_H
#define APTEST_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static int aptest_failures = 0;

#define AP_CHECK(cond)                                                                            \
  do {                                                                                            \
    if (!(cond)) {                                                                                \
      fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond);                    \
      ++aptest_failures;                                                                          \
    }                                                                                             \
  } while (0)

#define AP_CHECK_EQ_INT(a, b)                                                                     \
  do {                                                                                            \
    long long aptest_a = (long long)(a), aptest_b = (long long)(b);                               \
    if (aptest_a != aptest_b) {                                                                   \
      fprintf(stderr, "%s:%d: %s == %s failed: %lld != %lld\n", __FILE__, __LINE__, #a, #b,       \
              aptest_a, aptest_b);                                                                \
      ++aptest_failures;                                                                          \
    }                                                                                             \
  } while (0)

/* |a - b| <= tol; NaN never passes. */
#define AP_CHECK_NEAR(a, b, tol)                                                                  \
  do {                                                                                            \
    double aptest_a = (double)(a), aptest_b = (double)(b);                                        \
    if (!(fabs(aptest_a - aptest_b) <= (tol))) {                                                  \
      fprintf(stderr, "%s:%d: |%s - %s| <= %g failed: %.17g vs %.17g\n", __FILE__, __LINE__, #a,  \
              #b, (double)(tol), aptest_a, aptest_b);                                             \
      ++aptest_failures;                                                                          \
    }                                                                                             \
  } while (0)

#define AP_CHECK_NAN(a) AP_CHECK(isnan((double)(a)))

/* Running a selection of a program's test functions (AP_TEST_RUN): the environment's
 * AP_TEST_ONLY (comma-separated names: run only these; unset or empty: all) or AP_TEST_SKIP
 * (run all but these), so that one slow program can be split into ctest entries that together
 * run every function (the Valgrind run of test_ap_horizon). A name in either list that no
 * AP_TEST_RUN met is a failure (AP_TEST_MAIN_END), so a renamed function cannot silently drop
 * out of both halves. AP_TEST_TIMES=1 prints each function's seconds to stderr, for balancing
 * the split. */
#define APTEST_MAX_RUNS 128
static const char *aptest_run_names[APTEST_MAX_RUNS];
static int aptest_run_count = 0;

/* Whether `name` is an item of the comma-separated `list`. */
static int aptest_listed(const char *list, const char *name)
{
  const size_t n = strlen(name);
  while (list && *list) {
    const char *end = strchr(list, ',');
    const size_t len = end ? (size_t)(end - list) : strlen(list);
    if (len == n && strncmp(list, name, n) == 0) {
      return 1;
    }
    list = end ? end + 1 : NULL;
  }
  return 0;
}

/* The environment's `name`, NULL when unset or empty. */
static const char *aptest_env(const char *name)
{
  const char *v = getenv(name);
  return v && *v ? v : NULL;
}

static double aptest_seconds(void)
{
  struct timespec ts;
  return timespec_get(&ts, TIME_UTC) ? (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec : 0.0;
}

static void aptest_run(const char *name, void (*fn)(void))
{
  const char *only = aptest_env("AP_TEST_ONLY"), *skip = aptest_env("AP_TEST_SKIP");
  const char *times = aptest_env("AP_TEST_TIMES");
  double t0;
  if (aptest_run_count < APTEST_MAX_RUNS) {
    aptest_run_names[aptest_run_count++] = name;
  }
  if ((only && !aptest_listed(only, name)) || (skip && aptest_listed(skip, name))) {
    return;
  }
  t0 = aptest_seconds();
  fn();
  if (times) {
    fprintf(stderr, "%s: %.2f s\n", name, aptest_seconds() - t0);
  }
}

#define AP_TEST_RUN(fn) aptest_run(#fn, fn)

/* Counts as failures the names of AP_TEST_ONLY and AP_TEST_SKIP that no AP_TEST_RUN met. */
static void aptest_check_selection(void)
{
  const char *lists[2];
  int l;
  lists[0] = aptest_env("AP_TEST_ONLY");
  lists[1] = aptest_env("AP_TEST_SKIP");
  for (l = 0; l < 2; ++l) {
    const char *item = lists[l];
    while (item && *item) {
      const char *end = strchr(item, ',');
      const int len = end ? (int)(end - item) : (int)strlen(item);
      int k, found = 0;
      for (k = 0; k < aptest_run_count && !found; ++k) {
        found = (int)strlen(aptest_run_names[k]) == len &&
                strncmp(aptest_run_names[k], item, (size_t)len) == 0;
      }
      if (!found) {
        fprintf(stderr, "%s names no test function of this program: %.*s\n",
                l == 0 ? "AP_TEST_ONLY" : "AP_TEST_SKIP", len, item);
        ++aptest_failures;
      }
      item = end ? end + 1 : NULL;
    }
  }
}

#define AP_TEST_MAIN_END()                                                                        \
  do {                                                                                            \
    aptest_check_selection();                                                                     \
    if (aptest_failures) {                                                                        \
      fprintf(stderr, "%d check(s) failed\n", aptest_failures);                                   \
    }                                                                                             \
    return aptest_failures ? 1 : 0;                                                               \
  } while (0)

#endif
