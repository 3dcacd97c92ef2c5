/* SPDX-License-Identifier: BSD-3-Clause */
/* madvise and sched_getaffinity are not C11: ask for the system's declarations (this file
 * only). */
#define _GNU_SOURCE 1

#include "ap_memory.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__linux__)
#include <sched.h>
#include <sys/mman.h>
#include <sys/resource.h>
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

/* A group's limit read from its folder `dir` (0 for none). */
typedef double (*group_reader)(const char *dir);

/* CPUs of a quota of `quota` us in every `period` us; 0 for none (a quota of -1, "max"). */
static double cpu_share(const char *quota, const char *period)
{
  char *end = NULL;
  const double q = strtod(quota, &end), p = end != quota ? strtod(period, NULL) : 0.0;
  return end != quota && q > 0.0 && p > 0.0 ? q / p : 0.0;
}

/* The first line of dir/file into text (at most size bytes, "" when the file cannot be
 * read); 0 when it cannot be opened. */
static int first_line(const char *dir, const char *file, char *text, size_t size)
{
  char at[4200];
  FILE *f;
  text[0] = '\0';
  if (snprintf(at, sizeof at, "%s/%s", dir, file) >= (int)sizeof at || !(f = fopen(at, "r"))) {
    return 0;
  }
  if (!fgets(text, (int)size, f)) {
    text[0] = '\0';
  }
  fclose(f);
  return 1;
}

/* The limit dir/file holds: bytes, or 0 for none ("max"; v1's "no limit", 2^63 less a page,
 * and anything as large; an unreadable or malformed file). */
static double limit_file(const char *dir, const char *file)
{
  char text[64];
  char *end = NULL;
  unsigned long long v;
  if (!first_line(dir, file, text, sizeof text) || text[0] < '0' || text[0] > '9') {
    return 0.0; /* ("max", or nothing) */
  }
  v = strtoull(text, &end, 10);
  return end == text || (*end != '\0' && *end != '\n') || v >= (1ULL << 62) ? 0.0 : (double)v;
}

static double memory_v2(const char *dir)
{
  return limit_file(dir, "memory.max");
}

static double memory_v1(const char *dir)
{
  return limit_file(dir, "memory.limit_in_bytes");
}

static double cpu_v2(const char *dir)
{
  char text[128];
  const char *space = first_line(dir, "cpu.max", text, sizeof text) ? strchr(text, ' ') : NULL;
  /* "quota period", or "max period" */
  return space && text[0] >= '0' && text[0] <= '9' ? cpu_share(text, space + 1) : 0.0;
}

static double cpu_v1(const char *dir)
{
  char quota[64], period[64];
  if (!first_line(dir, "cpu.cfs_quota_us", quota, sizeof quota) ||
      !first_line(dir, "cpu.cfs_period_us", period, sizeof period)) {
    return 0.0;
  }
  return quota[0] >= '0' && quota[0] <= '9' ? cpu_share(quota, period) : 0.0;
}

/* The lowest limit `read` finds for the group at `path` (from "/") under `mount` and for its
 * ancestors up to the mount's root; 0 for none. */
static double group_limit(const char *mount, const char *path, group_reader read)
{
  char at[4096];
  double lowest = 0.0;
  size_t n = strlen(path);
  while (n > 0 && path[n - 1] == '/') {
    --n;
  }
  for (;;) {
    if (snprintf(at, sizeof at, "%s%.*s", mount, (int)n, path) < (int)sizeof at) {
      const double v = read(at);
      lowest = v > 0.0 && (lowest == 0.0 || v < lowest) ? v : lowest;
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

/* The lowest limit over the groups `cgroups` lists: v2 ones read by `v2` under root, v1 ones
 * of the controller `controller` by `v1` under root/controller. */
static double cgroup_limit(const char *cgroups, const char *root, const char *controller,
                           group_reader v2, group_reader v1)
{
  char line[4096], mount[4096];
  const size_t clen = strlen(controller);
  double lowest = 0.0;
  FILE *f = fopen(cgroups, "r");
  if (!f) {
    return 0.0;
  }
  while (fgets(line, sizeof line, f)) {
    /* "id:controllers:path" */
    char *a = strchr(line, ':'), *b = a ? strchr(a + 1, ':') : NULL, *nl;
    double v = 0.0;
    if (!b || b[1] != '/') {
      continue;
    }
    nl = strchr(b, '\n');
    if (nl) {
      *nl = '\0';
    }
    *b = '\0';
    if (a + 1 == b) { /* v2: no controllers named */
      v = group_limit(root, b + 1, v2);
    } else {
      const char *c = a + 1;
      int named = 0;
      while (*c) { /* the controllers, comma-separated */
        const size_t len = strcspn(c, ",");
        named |= len == clen && strncmp(c, controller, clen) == 0;
        c += len + (c[len] == ',');
      }
      if (named && snprintf(mount, sizeof mount, "%s/%s", root, controller) < (int)sizeof mount) {
        v = group_limit(mount, b + 1, v1);
      }
    }
    lowest = v > 0.0 && (lowest == 0.0 || v < lowest) ? v : lowest;
  }
  fclose(f);
  return lowest;
}

unsigned long long ap_memory_cgroup_limit(const char *cgroups, const char *root)
{
  return (unsigned long long)cgroup_limit(cgroups, root, "memory", memory_v2, memory_v1);
}

double ap_cpu_cgroup_limit(const char *cgroups, const char *root)
{
  return cgroup_limit(cgroups, root, "cpu", cpu_v2, cpu_v1);
}

int ap_cpu_usable(void)
{
  long n = 1;
#if defined(__linux__)
  cpu_set_t set;
  double quota;
  n = sysconf(_SC_NPROCESSORS_ONLN);
  n = n < 1 ? 1 : n;
  if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) >= 1 &&
      CPU_COUNT(&set) < n) {
    n = CPU_COUNT(&set);
  }
  quota = ap_cpu_cgroup_limit("/proc/self/cgroup", "/sys/fs/cgroup");
  if (quota > 0.0 && ceil(quota) < (double)n) {
    n = (long)ceil(quota);
  }
#endif
  return n > 65536 ? 65536 : (int)n;
}

unsigned long long ap_memory_address_limit(void)
{
#if defined(__linux__)
  struct rlimit limit;
  unsigned long long size = 0, resident = 0, mapped, left;
  const long page_size = sysconf(_SC_PAGE_SIZE);
  FILE *f;
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY || page_size <= 0) {
    return 0;
  }
  f = fopen("/proc/self/statm", "r"); /* pages: the address space, then those resident */
  if (f) {
    if (fscanf(f, "%llu %llu", &size, &resident) != 2) {
      size = resident = 0;
    }
    fclose(f);
  }
  mapped = size * (unsigned long long)page_size;
  left = (unsigned long long)limit.rlim_cur > mapped ? (unsigned long long)limit.rlim_cur - mapped
                                                     : 0;
  left -= left / 2 < AP_MEMORY_GROUP_RESERVE ? left / 2 : AP_MEMORY_GROUP_RESERVE;
  return left > 0 ? left : 1;
#else
  return 0;
#endif
}

unsigned long long ap_memory_usable(int *source)
{
  unsigned long long usable = 0, group, address;
  int from = AP_MEMORY_MACHINE;
#if defined(__linux__)
  const long pages = sysconf(_SC_PHYS_PAGES), page_size = sysconf(_SC_PAGE_SIZE);
  if (pages > 0 && page_size > 0) {
    usable = (unsigned long long)pages * (unsigned long long)page_size;
  }
  group = ap_memory_cgroup_limit("/proc/self/cgroup", "/sys/fs/cgroup");
  group -= group / 2 < AP_MEMORY_GROUP_RESERVE ? group / 2 : AP_MEMORY_GROUP_RESERVE;
#else
  group = 0;
#endif
  if (group && (!usable || group < usable)) {
    usable = group;
    from = AP_MEMORY_GROUP;
  }
  address = ap_memory_address_limit();
  if (address && (!usable || address < usable)) {
    usable = address;
    from = AP_MEMORY_ADDRESS_SPACE;
  }
  if (source) {
    *source = from;
  }
  return usable;
}
