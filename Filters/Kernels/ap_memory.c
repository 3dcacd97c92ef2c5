/* SPDX-License-Identifier: BSD-3-Clause */
/* madvise is not C11: ask for the system's declarations (this file only). */
#define _DEFAULT_SOURCE 1

#include "ap_memory.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

/* A limit file's value: bytes, or 0 for none ("max"; v1's "no limit", 2^63 less a page, and
 * anything as large; an unreadable or malformed file). */
static unsigned long long limit_file(const char *path)
{
  char text[64] = "";
  char *end = NULL;
  unsigned long long v;
  FILE *f = fopen(path, "r");
  if (!f) {
    return 0;
  }
  if (!fgets(text, sizeof text, f)) {
    text[0] = '\0';
  }
  fclose(f);
  if (text[0] < '0' || text[0] > '9') {
    return 0; /* ("max", or nothing) */
  }
  v = strtoull(text, &end, 10);
  if (end == text || (*end != '\0' && *end != '\n') || v >= (1ULL << 62)) {
    return 0;
  }
  return v;
}

/* The lowest limit in `file` of the group at `path` (from "/") under `mount` and of its
 * ancestors up to the mount's root; 0 for none. */
static unsigned long long group_limit(const char *mount, const char *path, const char *file)
{
  char at[4096];
  unsigned long long lowest = 0;
  size_t n = strlen(path);
  while (n > 0 && path[n - 1] == '/') {
    --n;
  }
  for (;;) {
    unsigned long long v;
    if (snprintf(at, sizeof at, "%s%.*s/%s", mount, (int)n, path, file) < (int)sizeof at) {
      v = limit_file(at);
      lowest = v && (!lowest || v < lowest) ? v : lowest;
    }
    if (n == 0) {
      return lowest;
    }
    while (n > 0 && path[n - 1] != '/') { /* up a group */
      --n;
    }
    while (n > 0 && path[n - 1] == '/') {
      --n;
    }
  }
}

unsigned long long ap_memory_cgroup_limit(const char *cgroups, const char *root)
{
  char line[4096], mount[4096];
  unsigned long long lowest = 0;
  FILE *f = fopen(cgroups, "r");
  if (!f) {
    return 0;
  }
  while (fgets(line, sizeof line, f)) {
    /* "id:controllers:path" */
    char *a = strchr(line, ':'), *b = a ? strchr(a + 1, ':') : NULL, *nl;
    unsigned long long v = 0;
    if (!b || b[1] != '/') {
      continue;
    }
    nl = strchr(b, '\n');
    if (nl) {
      *nl = '\0';
    }
    *b = '\0';
    if (a + 1 == b) { /* v2: no controllers named */
      v = group_limit(root, b + 1, "memory.max");
    } else {
      const char *c = a + 1;
      int memory = 0;
      while (*c) { /* the controllers, comma-separated */
        const size_t len = strcspn(c, ",");
        memory |= len == 6 && strncmp(c, "memory", 6) == 0;
        c += len + (c[len] == ',');
      }
      if (memory && snprintf(mount, sizeof mount, "%s/memory", root) < (int)sizeof mount) {
        v = group_limit(mount, b + 1, "memory.limit_in_bytes");
      }
    }
    lowest = v && (!lowest || v < lowest) ? v : lowest;
  }
  fclose(f);
  return lowest;
}

unsigned long long ap_memory_usable(int *grouped)
{
  unsigned long long physical = 0, group;
#if defined(__linux__)
  const long pages = sysconf(_SC_PHYS_PAGES), page_size = sysconf(_SC_PAGE_SIZE);
  if (pages > 0 && page_size > 0) {
    physical = (unsigned long long)pages * (unsigned long long)page_size;
  }
  group = ap_memory_cgroup_limit("/proc/self/cgroup", "/sys/fs/cgroup");
  group -= group / 2 < AP_MEMORY_GROUP_RESERVE ? group / 2 : AP_MEMORY_GROUP_RESERVE;
#else
  group = 0;
#endif
  if (grouped) {
    *grouped = group && (!physical || group < physical);
  }
  return group && (!physical || group < physical) ? group : physical;
}
