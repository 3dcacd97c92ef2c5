/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal (not installed): memory hints shared by the C core and the VTK modules. */
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

#ifdef __cplusplus
}
#endif

#endif
