/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal (not installed): memory hints shared by the C core and the VTK modules, and
 * the memory and CPUs a process may use. */
#ifndef AP_MEMORY_H
#define AP_MEMORY_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Ask Linux for transparent huge pages over a fresh buffer of `bytes` at `p`, before it is
 * first touched (where THP is enabled for madvise, as on Debian). Each first touch of a 4 KiB
 * page faults, about 10 us on virtual machines: paging in a 50 MB array took longer than
 * reading a DEM into it. Only a hint: no effect on contents, nothing done for buffers under
 * 4 MiB, for NULL, or off Linux. */
void ap_advise_huge_pages(void *p, size_t bytes);

/* Uninitialised memory for `bytes` (free() releases it; NULL when out of memory, never for
 * 0 bytes). From 4 MiB up it starts on a 2 MiB boundary, and its whole 2 MiB are advised as
 * above, so that huge pages cover all of it but the last partial 2 MiB (which would take a
 * whole huge page of memory); smaller sizes come from malloc. */
void *ap_alloc_huge(size_t bytes);

/* The lowest memory limit, in bytes, of the Linux control group a process runs in or of any
 * group above it: cgroup v2's memory.max, v1's memory.limit_in_bytes. `cgroups` is the
 * process's /proc/<pid>/cgroup (lines "0::/path", v2, and "N:memory:/path" or
 * "N:cpu,memory:/path", v1), `root` where the hierarchies are mounted (v2 at root, v1's memory
 * controller at root/memory: "/sys/fs/cgroup" on Debian). Each group's file is looked for at
 * its path under the mount and at every ancestor up to the mount's own root, which in a
 * container (a cgroup namespace) is the container's group even where the file lists the
 * host's path. 0 when no limit applies ("max", v1's "no limit" of 2^63 less a page, no such
 * files: not Linux, or no memory controller). Past this limit the kernel ends the process,
 * as past physical memory, rather than fail an allocation. */
unsigned long long ap_memory_cgroup_limit(const char *cgroups, const char *root);

/* What an address-space limit (RLIMIT_AS, `ulimit -v`) leaves this process to allocate: the
 * limit less the address space mapped already (/proc/self/statm: its data, libraries, thread
 * stacks, allocator arenas), less AP_MEMORY_GROUP_RESERVE (at most half of it) for the
 * stacks and arenas of threads still to start; at least 1. 0 without such a limit (or off
 * Linux). Past it an allocation fails (C++: std::bad_alloc) rather than the kernel ending the
 * process. */
unsigned long long ap_memory_address_limit(void);

/* The bytes of memory this process may use, the lowest of: the physical memory (sysconf);
 * the limit of its control group (ap_memory_cgroup_limit of /proc/self/cgroup under
 * /sys/fs/cgroup) less AP_MEMORY_GROUP_RESERVE (at most half of it), as in a container run
 * with a memory limit; ap_memory_address_limit(). *source (unless NULL) says which: one of
 * AP_MEMORY_MACHINE, AP_MEMORY_GROUP, AP_MEMORY_ADDRESS_SPACE. 0 when the system does not
 * say. (The reserve is what the process itself holds before its data, its interpreter and
 * libraries, which count against the group's limit; against physical memory there is
 * swap and the page cache to give.) */
#define AP_MEMORY_GROUP_RESERVE (128ULL << 20)
enum { AP_MEMORY_MACHINE = 0, AP_MEMORY_GROUP = 1, AP_MEMORY_ADDRESS_SPACE = 2 };
unsigned long long ap_memory_usable(int *source);

/* The CPUs a control group's quota grants a process, its group's and every group above it's
 * (as ap_memory_cgroup_limit finds them): cgroup v2's cpu.max ("quota period"), v1's
 * cpu.cfs_quota_us / cpu.cfs_period_us under root/cpu; the lowest, as a fraction (1.5 for
 * `docker --cpus 1.5`); 0 when no quota applies ("max", -1, no such files). */
double ap_cpu_cgroup_limit(const char *cgroups, const char *root);

/* The CPUs this process may run on at once, at least 1: the online CPUs, or fewer where its
 * affinity mask (taskset, `docker --cpuset-cpus`) or its control group's quota rounded up
 * (`docker --cpus`) allows fewer. */
int ap_cpu_usable(void);

#ifdef __cplusplus
}
#endif

#endif
