/* SPDX-License-Identifier: BSD-3-Clause */
#include "ap_status.h"

const char *ap_status_string(ap_status status)
{
  switch (status) {
  case AP_OK: return "success";
  case AP_ERR_NULL_POINTER: return "a required pointer argument is NULL";
  case AP_ERR_INVALID_ARGUMENT: return "a parameter is outside its valid range";
  case AP_ERR_GRID_TOO_SMALL: return "the grid is too small for this operation";
  case AP_ERR_BAD_STRIDE: return "the row stride is smaller than the row length";
  case AP_ERR_SIZE_OVERFLOW: return "the grid size overflows the address space";
  case AP_ERR_ALL_NODATA: return "every cell of the grid is nodata";
  case AP_ERR_BUFFER_TOO_SMALL: return "an output buffer is too small";
  case AP_ERR_OVERLAP: return "an output buffer overlaps an input buffer";
  case AP_ERR_OUT_OF_MEMORY: return "out of memory";
  case AP_ERR_OUT_OF_RANGE: return "an input is outside its valid range";
  case AP_ERR_PARSE: return "the text cannot be parsed";
  case AP_ERR_NOT_FOUND: return "not found";
  case AP_ERR_BAD_FILE: return "the file is corrupt or of an unknown format";
  case AP_ERR_TIME_NONEXISTENT: return "the local time does not exist (skipped by a clock change)";
  case AP_ERR_TIME_AMBIGUOUS:
    return "the local time is ambiguous (it occurs twice at a clock change)";
  }
  return "unknown status";
}
