// SPDX-License-Identifier: BSD-3-Clause
// Checks for the C++ module tests: each failure prints file:line and the values and is
// counted; a test returns aptest::Result() (0 = pass).
#ifndef aptest_hxx
#define aptest_hxx

#include <cmath>
#include <cstdio>
#include <string>

namespace aptest
{
inline int& Failures()
{
  static int failures = 0;
  return failures;
}

/** 0 when every check passed, else 1 (after saying how many failed). */
inline int Result()
{
  if (Failures())
  {
    std::fprintf(stderr, "%d check(s) failed\n", Failures());
  }
  return Failures() ? 1 : 0;
}
} // namespace aptest

#define AP_CHECK(cond)                                                                           \
  do                                                                                             \
  {                                                                                              \
    if (!(cond))                                                                                 \
    {                                                                                            \
      std::fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond);              \
      ++aptest::Failures();                                                                      \
    }                                                                                            \
  } while (0)

// |a - b| <= tol; NaN never passes.
#define AP_CHECK_NEAR(a, b, tol)                                                                 \
  do                                                                                             \
  {                                                                                              \
    const double va_ = (a), vb_ = (b);                                                           \
    if (!(std::fabs(va_ - vb_) <= (tol)))                                                        \
    {                                                                                            \
      std::fprintf(stderr, "%s:%d: |%s - %s| <= %g failed: %.15g vs %.15g\n", __FILE__,          \
        __LINE__, #a, #b, static_cast<double>(tol), va_, vb_);                                   \
      ++aptest::Failures();                                                                      \
    }                                                                                            \
  } while (0)

#define AP_CHECK_CONTAINS(text, part)                                                            \
  do                                                                                             \
  {                                                                                              \
    const std::string t_(text), p_(part);                                                        \
    if (t_.find(p_) == std::string::npos)                                                        \
    {                                                                                            \
      std::fprintf(stderr, "%s:%d: expected '%s' in '%s'\n", __FILE__, __LINE__, p_.c_str(),     \
        t_.c_str());                                                                             \
      ++aptest::Failures();                                                                      \
    }                                                                                            \
  } while (0)

#endif
