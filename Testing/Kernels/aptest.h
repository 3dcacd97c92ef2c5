/* SPDX-License-Identifier: BSD-3-Clause */
/* Minimal assertions for the C core's unit tests: each failure prints file:line and the values,
 * and the test's exit status is the number of failures (0 = pass). */
#ifndef APTEST_H
#define APTEST_H

#include <math.h>
#include <stdio.h>

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

#define AP_TEST_MAIN_END()                                                                        \
  do {                                                                                            \
    if (aptest_failures) {                                                                        \
      fprintf(stderr, "%d check(s) failed\n", aptest_failures);                                   \
    }                                                                                             \
    return aptest_failures ? 1 : 0;                                                               \
  } while (0)

#endif
