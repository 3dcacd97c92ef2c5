/* SPDX-License-Identifier: BSD-3-Clause */
/* madvise is not C11: ask for the system's declarations (this file only). */
#define _DEFAULT_SOURCE 1

#include "ap_memory.h"

#include <stdint.h>
#include <stdlib.h>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

/* A huge page (x86-64, arm64 with 4 KiB pages), and the smallest buffer worth advising. */
#define AP_HUGE_PAGE ((size_t)2 << 20)
#define AP_HUGE_MIN (2 * AP_HUGE_PAGE)

void ap_advise_huge_pages(void *p, size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const long page_size = sysconf(_SC_PAGE_SIZE);
  uintptr_t page, begin, end;
  if (!p || page_size <= 0 || bytes < AP_HUGE_MIN) {
    return;
  }
  /* the whole pages inside the buffer (the kernel maps huge pages where 2 MiB fit) */
  page = (uintptr_t)page_size;
  begin = ((uintptr_t)p + page - 1) / page * page;
  end = ((uintptr_t)p + bytes) / page * page;
  if (end > begin) {
    (void)madvise((void *)begin, end - begin, MADV_HUGEPAGE);
  }
#else
  (void)p;
  (void)bytes;
#endif
}

void *ap_alloc_huge(size_t bytes)
{
  const size_t huge = AP_HUGE_PAGE;
  void *p;
  if (bytes < AP_HUGE_MIN || bytes > SIZE_MAX - huge) {
    return malloc(bytes ? bytes : 1);
  }
  /* aligned_alloc wants a multiple of the alignment; huge pages for the whole 2 MiB within
   * `bytes` only, as one over the end would take up to 2 MiB of memory for a few bytes */
  p = aligned_alloc(huge, (bytes + huge - 1) / huge * huge);
  ap_advise_huge_pages(p, bytes / huge * huge);
  return p;
}
