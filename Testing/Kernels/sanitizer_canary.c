/* SPDX-License-Identifier: BSD-3-Clause */
/* Built only with APERTURE_SANITIZE: a deliberate heap overflow through the C core. The test
 * that runs it passes only when AddressSanitizer reports the overflow, so the sanitizer build
 * proves AddressSanitizer is really active (a build that silently lost -fsanitize fails it). */
#include "ap_grid.h"

#include <stdlib.h>

int main(void)
{
  float *z = (float *)malloc(3 * sizeof(float));
  ap_grid_stats s;
  /* A view that claims 2 x 2 cells over a 3-cell buffer: reads one float past the end. */
  ap_grid_view g = ap_grid_view_make(z, 2, 2);
  int status;
  z[0] = z[1] = z[2] = 1.0f;
  status = (int)ap_grid_stats_compute(&g, &s);
  free(z);
  return status == 0 && s.valid == 4 ? 0 : 2;
}
