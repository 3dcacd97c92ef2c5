/* SPDX-License-Identifier: BSD-3-Clause */
/* Unit tests of ap_memory: the huge-page hint leaves every byte as it was, ignores what it
 * should (NULL, small buffers), and, where Linux offers transparent huge pages on request,
 * reaches the kernel (the advised buffer is a THP-eligible mapping in /proc/self/smaps);
 * ap_alloc_huge gives large buffers on 2 MiB boundaries, advised, and small ones as malloc. */
#include "ap_memory.h"
#include "aptest.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Whether /sys says THP can be asked for with madvise: 1 for "[madvise]" (only then), 2 for
 * "[always]", 0 otherwise. */
static int thp_on_request(void)
{
  char line[256] = "";
  FILE *f = fopen("/sys/kernel/mm/transparent_hugepage/enabled", "r");
  if (!f) {
    return 0;
  }
  if (!fgets(line, sizeof line, f)) {
    line[0] = '\0';
  }
  fclose(f);
  return strstr(line, "[madvise]") != NULL ? 1 : strstr(line, "[always]") != NULL ? 2 : 0;
}

/* The THPeligible value of the mapping holding address a in /proc/self/smaps; -1 when the
 * mapping or the field is not found. */
static int thp_eligible(uintptr_t a)
{
  char line[512];
  int inside = 0, value = -1;
  FILE *f = fopen("/proc/self/smaps", "r");
  if (!f) {
    return -1;
  }
  while (value < 0 && fgets(line, sizeof line, f)) {
    unsigned long lo, hi;
    int v;
    if (sscanf(line, "%lx-%lx ", &lo, &hi) == 2 && strchr(line, '-') < strchr(line, ' ')) {
      inside = a >= (uintptr_t)lo && a < (uintptr_t)hi;
    } else if (inside && sscanf(line, "THPeligible: %d", &v) == 1) {
      value = v;
    }
  }
  fclose(f);
  return value;
}

static void test_contents_and_no_ops(void)
{
  const size_t big = (size_t)24 << 20;
  unsigned char small[100];
  unsigned char *p = (unsigned char *)malloc(big);
  size_t i, bad = 0;
  AP_CHECK(p != NULL);
  if (!p) {
    return;
  }
  memset(small, 0x5a, sizeof small);
  ap_advise_huge_pages(NULL, big);                   /* nothing to do */
  ap_advise_huge_pages(small + 1, sizeof small - 1); /* too small: left alone */
  for (i = 0; i < sizeof small; ++i) {
    bad += small[i] != 0x5a;
  }
  /* bytes written before the hint (given an unaligned start) stay, later ones land */
  for (i = 0; i < big / 2; ++i) {
    p[i] = (unsigned char)(i * 7u + (i >> 12));
  }
  ap_advise_huge_pages(p + 3, big - 3);
  for (i = big / 2; i < big; ++i) {
    p[i] = (unsigned char)(i * 7u + (i >> 12));
  }
  for (i = 0; i < big; ++i) {
    bad += p[i] != (unsigned char)(i * 7u + (i >> 12));
  }
  AP_CHECK_EQ_INT((int)bad, 0);
  free(p);
}

static void test_reaches_the_kernel(void)
{
  const size_t big = (size_t)32 << 20;
  unsigned char *p;
  if (!thp_on_request()) {
    printf("transparent huge pages are off here: the hint's effect is not checked\n");
    return;
  }
  p = (unsigned char *)malloc(big);
  AP_CHECK(p != NULL);
  if (!p) {
    return;
  }
  ap_advise_huge_pages(p, big);
  memset(p, 1, big);
  /* the middle of the buffer lies in an advised mapping */
  AP_CHECK_EQ_INT(thp_eligible((uintptr_t)(p + big / 2)), 1);
  free(p);
}

static void test_alloc_huge(void)
{
  const size_t huge = (size_t)2 << 20;
  const size_t sizes[] = { 0, 1, 100, 4 * huge - 1, 4 * huge, 5 * huge + 12345 };
  size_t s;
  for (s = 0; s < sizeof sizes / sizeof sizes[0]; ++s) {
    unsigned char *p = (unsigned char *)ap_alloc_huge(sizes[s]);
    size_t i, bad = 0;
    AP_CHECK(p != NULL);
    if (!p) {
      continue;
    }
    if (sizes[s] >= 2 * huge) {
      AP_CHECK_EQ_INT((int)((uintptr_t)p % huge), 0);
      if (thp_on_request()) {
        AP_CHECK_EQ_INT(thp_eligible((uintptr_t)p), 1);
        AP_CHECK_EQ_INT(thp_eligible((uintptr_t)(p + sizes[s] / huge * huge - 1)), 1);
        if (sizes[s] % huge > 4096 && thp_on_request() == 1) {
          /* (a partial last 2 MiB stays on small pages) */
          AP_CHECK_EQ_INT(thp_eligible((uintptr_t)(p + sizes[s] - 1)), 0);
        }
      }
    }
    for (i = 0; i < sizes[s]; ++i) {
      p[i] = (unsigned char)(i * 13u);
    }
    for (i = 0; i < sizes[s]; ++i) {
      bad += p[i] != (unsigned char)(i * 13u);
    }
    AP_CHECK_EQ_INT((int)bad, 0);
    free(p);
  }
}

int main(void)
{
  test_contents_and_no_ops();
  test_reaches_the_kernel();
  test_alloc_huge();
  AP_TEST_MAIN_END();
}
