/* SPDX-License-Identifier: BSD-3-Clause */
/* Unit tests of ap_memory: the huge-page hint leaves every byte as it was, ignores what it
 * should (NULL, small buffers), and, where Linux offers transparent huge pages on request,
 * reaches the kernel (the advised buffer is a THP-eligible mapping in /proc/self/smaps);
 * ap_alloc_huge gives large buffers on 2 MiB boundaries, advised, and small ones as malloc;
 * control groups' memory limits and CPU quotas are found as cgroup v1 and v2 lay them out (a
 * made-up /proc/self/cgroup and /sys/fs/cgroup in a temporary folder). */
#define _DEFAULT_SOURCE 1 /* (mkdtemp, mkdir, rmdir: POSIX) */

#include "ap_memory.h"
#include "aptest.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

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
  if (thp_on_request() != 1) {
    /* ([always] makes every large mapping eligible, hinted or not: nothing to tell apart) */
    printf("transparent huge pages are %s here: the hint's effect is not checked\n",
           thp_on_request() ? "always on" : "off");
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
      if (thp_on_request() == 1) { /* (under [always] any mapping is eligible) */
        AP_CHECK_EQ_INT(thp_eligible((uintptr_t)p), 1);
        AP_CHECK_EQ_INT(thp_eligible((uintptr_t)(p + sizes[s] / huge * huge - 1)), 1);
        if (sizes[s] % huge > 4096) {
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

/* The made-up tree: files written (made with their folders) and removed in reverse order. */
static char tree[64];
static char made[32][256];
static int nmade = 0;

/* Write `text` to tree/rel, making its folders. */
static void put(const char *rel, const char *text)
{
  char path[256];
  size_t i;
  FILE *f;
  snprintf(path, sizeof path, "%s/%s", tree, rel);
  for (i = strlen(tree) + 1; path[i]; ++i) {
    if (path[i] == '/') {
      path[i] = '\0';
      if (mkdir(path, 0700) == 0 && nmade < 32) {
        snprintf(made[nmade++], sizeof made[0], "%s", path);
      }
      path[i] = '/';
    }
  }
  f = fopen(path, "w");
  AP_CHECK(f != NULL);
  if (f) {
    fputs(text, f);
    fclose(f);
    if (nmade < 32) {
      snprintf(made[nmade++], sizeof made[0], "%s", path);
    }
  }
}

/* ap_memory_cgroup_limit of tree/cgroup under tree/sys. */
static unsigned long long limit_here(void)
{
  char cgroups[128], root[128];
  snprintf(cgroups, sizeof cgroups, "%s/cgroup", tree);
  snprintf(root, sizeof root, "%s/sys", tree);
  return ap_memory_cgroup_limit(cgroups, root);
}

/* Remove every file and folder made. */
static void clear_tree(void)
{
  while (nmade > 0) {
    const char *p = made[--nmade];
    if (remove(p) != 0) {
      rmdir(p);
    }
  }
}

static void test_cgroup_limits(void)
{
  const unsigned long long GiB = 1ULL << 30;
  int grouped = -1;
  unsigned long long usable;
  snprintf(tree, sizeof tree, "/tmp/ap-cgroup-XXXXXX");
  AP_CHECK(mkdtemp(tree) != NULL);
  /* no such files (not Linux): no limit */
  AP_CHECK_EQ_INT(limit_here(), 0);
  /* v2: the group's own "max", its parent's 1 GiB applies; the root has no file */
  put("cgroup", "0::/user.slice/app.scope\n");
  put("sys/user.slice/app.scope/memory.max", "max\n");
  put("sys/user.slice/memory.max", "1073741824\n");
  AP_CHECK_EQ_INT(limit_here(), GiB);
  /* the lower of two (the group's own 768 MiB) */
  put("sys/user.slice/app.scope/memory.max", "805306368\n");
  AP_CHECK_EQ_INT(limit_here(), 768ULL << 20);
  clear_tree();
  /* v2 in a container: the host's path listed, the container's group at the mount's root */
  put("cgroup", "0::/system.slice/docker-0123abcd.scope\n");
  put("sys/memory.max", "536870912\n");
  AP_CHECK_EQ_INT(limit_here(), 512ULL << 20);
  clear_tree();
  /* v1 (and other hierarchies beside it): the memory controller's mount; "no limit" is
   * 2^63 less a page, the parent's 2 GiB applies */
  put("cgroup", "9:name=systemd:/\n8:pids:/a/b\n4:memory:/a/b\n0::/\n");
  put("sys/memory/a/b/memory.limit_in_bytes", "9223372036854771712\n");
  put("sys/memory/a/memory.limit_in_bytes", "2147483648\n");
  put("sys/memory/memory.limit_in_bytes", "9223372036854771712\n");
  put("sys/pids/a/b/memory.limit_in_bytes", "1024\n"); /* (not the memory controller's) */
  AP_CHECK_EQ_INT(limit_here(), 2 * GiB);
  clear_tree();
  /* v1 with controllers mounted together ("cpu,memory"), and v2 beside it: the lower */
  put("cgroup", "3:cpu,memory:/z\n0::/z\n");
  put("sys/memory/z/memory.limit_in_bytes", "3221225472\n");
  put("sys/z/memory.max", "4294967296\n");
  AP_CHECK_EQ_INT(limit_here(), 3 * GiB);
  clear_tree();
  /* what is not a limit: empty, malformed, negative, "max" everywhere */
  put("cgroup", "0::/q\n");
  put("sys/q/memory.max", "12abc\n");
  put("sys/memory.max", "-5\n");
  AP_CHECK_EQ_INT(limit_here(), 0);
  put("sys/q/memory.max", "");
  AP_CHECK_EQ_INT(limit_here(), 0);
  clear_tree();
  rmdir(tree);
  /* this machine: at most its physical memory, and said what set it */
  usable = ap_memory_usable(&grouped);
  AP_CHECK(grouped == AP_MEMORY_MACHINE || grouped == AP_MEMORY_GROUP ||
           grouped == AP_MEMORY_ADDRESS_SPACE);
#if defined(__linux__)
  AP_CHECK(usable > 0);
  AP_CHECK(usable <= (unsigned long long)sysconf(_SC_PHYS_PAGES) *
                       (unsigned long long)sysconf(_SC_PAGE_SIZE));
#endif
  AP_CHECK_EQ_INT(ap_memory_usable(NULL), usable);
}

/* ap_cpu_cgroup_limit of tree/cgroup under tree/sys. */
static double cpus_here(void)
{
  char cgroups[128], root[128];
  snprintf(cgroups, sizeof cgroups, "%s/cgroup", tree);
  snprintf(root, sizeof root, "%s/sys", tree);
  return ap_cpu_cgroup_limit(cgroups, root);
}

static void test_cgroup_cpus(void)
{
  int usable;
  snprintf(tree, sizeof tree, "/tmp/ap-cgroup-XXXXXX");
  AP_CHECK(mkdtemp(tree) != NULL);
  AP_CHECK_EQ_INT(cpus_here() == 0.0, 1);
  /* v2: 1.5 CPUs in the group; "max" at the root */
  put("cgroup", "0::/a\n");
  put("sys/a/cpu.max", "150000 100000\n");
  put("sys/cpu.max", "max 100000\n");
  AP_CHECK_NEAR(cpus_here(), 1.5, 1e-12);
  clear_tree();
  /* v1 ("cpu,cpuacct" mounted at cpu): the group's -1 (none), its parent's 2 CPUs; a line of
   * cpuacct alone is not the cpu controller's */
  put("cgroup", "5:cpuacct:/k8s/pod\n2:cpu,cpuacct:/k8s/pod\n");
  put("sys/cpu/k8s/pod/cpu.cfs_quota_us", "-1\n");
  put("sys/cpu/k8s/pod/cpu.cfs_period_us", "100000\n");
  put("sys/cpu/k8s/cpu.cfs_quota_us", "200000\n");
  put("sys/cpu/k8s/cpu.cfs_period_us", "100000\n");
  put("sys/cpuacct/k8s/pod/cpu.cfs_quota_us", "1000\n");
  put("sys/cpuacct/k8s/pod/cpu.cfs_period_us", "100000\n");
  AP_CHECK_NEAR(cpus_here(), 2.0, 1e-12);
  clear_tree();
  /* malformed: nothing */
  put("cgroup", "0::/b\n");
  put("sys/b/cpu.max", "100000\n"); /* (no period) */
  AP_CHECK_EQ_INT(cpus_here() == 0.0, 1);
  clear_tree();
  rmdir(tree);
  usable = ap_cpu_usable();
  AP_CHECK(usable >= 1);
#if defined(__linux__)
  AP_CHECK(usable <= sysconf(_SC_NPROCESSORS_ONLN));
#endif
}

/* An address-space limit (ulimit -v) 512 MiB above the address space mapped (statm read here
 * too): what it leaves is those 512 MiB less the 128 MiB reserve, and it is the usable
 * memory's lowest bound, said so. Without one, 0. (The soft limit is set and then
 * restored in this process: a soft limit may be raised back up to the hard one.) */
static void test_address_limit(void)
{
#if defined(__linux__)
  struct rlimit saved, limit;
  unsigned long long size = 0, resident = 0, left, usable;
  const unsigned long long expected = (512ULL - 128ULL) << 20;
  const unsigned long long page = (unsigned long long)sysconf(_SC_PAGE_SIZE);
  int source = -1;
  FILE *f;
  AP_CHECK(getrlimit(RLIMIT_AS, &saved) == 0);
  if (saved.rlim_cur != RLIM_INFINITY) {
    printf("test_address_limit: skipped (already under ulimit -v)\n");
    return;
  }
  AP_CHECK_EQ_INT(ap_memory_address_limit(), 0);
  f = fopen("/proc/self/statm", "r");
  AP_CHECK(f && fscanf(f, "%llu %llu", &size, &resident) == 2);
  if (f) {
    fclose(f);
  }
  limit = saved;
  limit.rlim_cur = (rlim_t)(size * page + (512ULL << 20));
  AP_CHECK(setrlimit(RLIMIT_AS, &limit) == 0);
  left = ap_memory_address_limit();
  usable = ap_memory_usable(&source);
  AP_CHECK(setrlimit(RLIMIT_AS, &saved) == 0);
  /* (the pages mapped may change a little between the reads of statm) */
  AP_CHECK(left > expected - (16ULL << 20) && left < expected + (16ULL << 20));
  AP_CHECK_EQ_INT(source, AP_MEMORY_ADDRESS_SPACE);
  AP_CHECK(usable + (16ULL << 20) > left && usable < left + (16ULL << 20));
  AP_CHECK_EQ_INT(ap_memory_address_limit(), 0);
#endif
}

int main(void)
{
  AP_TEST_RUN(test_contents_and_no_ops);
  AP_TEST_RUN(test_reaches_the_kernel);
  AP_TEST_RUN(test_alloc_huge);
  AP_TEST_RUN(test_cgroup_limits);
  AP_TEST_RUN(test_cgroup_cpus);
  AP_TEST_RUN(test_address_limit);
  AP_TEST_MAIN_END();
}
