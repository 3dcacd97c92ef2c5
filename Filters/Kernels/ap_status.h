/* SPDX-License-Identifier: BSD-3-Clause */
/** @file ap_status.h
 *  @brief Status codes of the Aperture C core and their messages.
 *
 *  Every fallible `ap_` function returns an `ap_status`. The core never prints, exits or aborts
 *  on bad input; the VTK shims turn a failure into `vtkErrorMacro` plus a failed update, adding
 *  the context (file, array, parameter) the core does not know.
 */
#ifndef AP_STATUS_H
#define AP_STATUS_H

#ifdef __cplusplus
extern "C" {
#endif

/** Result of a core call. `AP_OK` is zero; every other value is an error. */
typedef enum ap_status {
  AP_OK = 0,                   /**< success */
  AP_ERR_NULL_POINTER,         /**< a required pointer argument was NULL */
  AP_ERR_INVALID_ARGUMENT,     /**< a parameter is outside its documented range */
  AP_ERR_GRID_TOO_SMALL,       /**< the grid has fewer rows or columns than the operation needs */
  AP_ERR_BAD_STRIDE,           /**< a row stride is smaller than the row length */
  AP_ERR_SIZE_OVERFLOW,        /**< a size computation overflows size_t */
  AP_ERR_ALL_NODATA,           /**< every cell of the grid is nodata (NaN) */
  AP_ERR_BUFFER_TOO_SMALL,     /**< a caller-provided output buffer is too small */
  AP_ERR_OVERLAP,              /**< an output buffer overlaps an input buffer */
  AP_ERR_OUT_OF_MEMORY,        /**< the core could not allocate its working memory */
  AP_ERR_OUT_OF_RANGE,         /**< an input (date, latitude, ...) is outside the valid range */
  AP_ERR_PARSE,                /**< a text input (time, zone rule) cannot be parsed */
  AP_ERR_NOT_FOUND,            /**< a named resource (time zone) does not exist */
  AP_ERR_BAD_FILE,             /**< a file (TZif zone file) is corrupt or of an unknown format */
  AP_ERR_TIME_NONEXISTENT,     /**< a local time skipped by a clock change (daylight saving) */
  AP_ERR_TIME_AMBIGUOUS,       /**< a local time that occurs twice (clock set back) */
  AP_STATUS_LAST = AP_ERR_TIME_AMBIGUOUS /**< the last status (for tests; keep it last) */
} ap_status;

/** Static English text for a status; never NULL (unknown codes give "unknown status"). */
const char *ap_status_string(ap_status status);

#ifdef __cplusplus
}
#endif

#endif /* AP_STATUS_H */
