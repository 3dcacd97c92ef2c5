/* SPDX-License-Identifier: BSD-3-Clause */
/** @file ap_mesh.h
 *  @brief Triangle connectivity and vertex normals of a terrain mesh whose vertices are the
 *         nodes of a regular grid.
 *
 *  Node (i, j) (column i west to east, row j south to north) is vertex j * nx + i. A node is
 *  valid when its elevation (for ap_mesh_triangulate) or its position (for ap_mesh_normals) is
 *  not NaN. Triangles are counter-clockwise seen from above (+z of a frame whose x points east
 *  and y north), so their geometric normals point up.
 */
#ifndef AP_MESH_H
#define AP_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "ap_grid.h"
#include "ap_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Upper bound on the triangles of an nx x ny grid, 2 (nx - 1)(ny - 1), in *out;
 *  AP_ERR_SIZE_OVERFLOW if it (or 3 ids per triangle) does not fit in size_t. */
ap_status ap_mesh_max_triangles(size_t nx, size_t ny, size_t *out);

/** Triangulate the grid cells (each the quad of four neighbouring nodes; no seam).
 *
 *  A quad with four valid nodes is split along its south-west/north-east diagonal into
 *  (SW, SE, NE) and (SW, NE, NW). A quad with one nodata node keeps the one triangle of its
 *  three valid nodes (splitting along the diagonal that avoids the nodata node); quads with two
 *  or more nodata nodes are dropped. So nodata leaves holes exactly where the data are missing.
 *
 *  @param g        grid of elevations (only NaN-ness is used), at least 2 x 2
 *  @param tri      output, 3 vertex ids per triangle (caller-allocated, capacity max_tri)
 *  @param max_tri  capacity of `tri` in triangles; ap_mesh_max_triangles() is always enough
 *  @param ntri     output, number of triangles written; row-major order of quads
 *  @return AP_OK, or AP_ERR_NULL_POINTER / AP_ERR_GRID_TOO_SMALL / AP_ERR_BAD_STRIDE /
 *          AP_ERR_SIZE_OVERFLOW / AP_ERR_BUFFER_TOO_SMALL (nothing useful is written then).
 */
ap_status ap_mesh_triangulate(const ap_grid_view *g, int64_t *tri, size_t max_tri, size_t *ntri);

/** Row-range form of ap_mesh_triangulate, for callers that split the work across threads:
 *  count each range's triangles, place the ranges by a prefix sum, then fill them; the result
 *  is identical to ap_mesh_triangulate for any split.
 *
 *  seam (0 or 1): whether the grid's east and west edges meet (a DEM spanning 360 degrees of
 *  longitude). With a seam, quad row j ends with the quad from column nx - 1 to column 0,
 *  triangulated as the others with column 0's nodes (and their validity) as its east nodes,
 *  but with the vertex ids nx * ny + j and nx * ny + j + 1: one vertex per row after the
 *  grid's, a copy of the row's node in column 0, so that the caller can give it the texture
 *  coordinate past the east edge (u = 1 + u0) that the seam's quads need.
 *
 *  ap_mesh_triangulate_validate() checks the grid once (as ap_mesh_triangulate does) and
 *  reports whether vertex ids (the seam's too) fit in int32 (*ids_fit_i32, may be NULL). Quad
 *  row j spans node rows j and j + 1, so quad rows run over [0, ny - 1). The other functions
 *  must only be called after a successful validate; they are reentrant and never allocate. */
ap_status ap_mesh_triangulate_validate(const ap_grid_view *g, int seam, int *ids_fit_i32);
/** Number of triangles of quad rows [j0, j1). */
size_t ap_mesh_count_rows(const ap_grid_view *g, int seam, size_t j0, size_t j1);
/** Write the triangles of quad rows [j0, j1) to tri (exactly ap_mesh_count_rows of them). */
void ap_mesh_triangulate_rows(const ap_grid_view *g, int seam, size_t j0, size_t j1,
                              int64_t *tri);
/** The same with 32-bit ids; only when validate reported that ids fit in int32. */
void ap_mesh_triangulate_rows_i32(const ap_grid_view *g, int seam, size_t j0, size_t j1,
                                  int32_t *tri);

/** Close the hole that the first (row 0) or last (row ny - 1) node row of a grid with a seam
 *  encircles: a DEM whose edge there is at latitude +-90 degrees, around whose pole that row's
 *  nodes lie on a small circle. The ring of nodes (0, row) ... (nx - 1, row) is triangulated
 *  as a fan from its node 0, nx - 2 triangles oriented as the quads are (for row ny - 1,
 *  counter-clockwise seen from the side the grid's triangles face; row 0 the reverse, being
 *  the other end). Only when nx >= 3 and every node of the row is valid: nodata beside a pole
 *  leaves the hole open, as it leaves holes elsewhere. Writes the triangles to tri (may be
 *  NULL to count them) and returns their number, 0 or nx - 2; 0 for any other row. Call after
 *  a successful ap_mesh_triangulate_validate; reentrant. */
size_t ap_mesh_cap(const ap_grid_view *g, size_t row, int64_t *tri);

/** Check the arguments of ap_mesh_normals_rows once: non-NULL, at least 2 x 2 (3 x 2 with
 *  wrap), sizes addressable. */
ap_status ap_mesh_normals_validate(const double *xyz, size_t nx, size_t ny, int wrap,
                                   const float *normals);

/** Unit vertex normals for rows [j0, j1) of a grid of vertex positions.
 *
 *  xyz holds 3 doubles per node (node order as above, positions in any Cartesian frame whose
 *  x, y follow the grid's east and north directions); a node whose x is NaN is invalid.
 *  The normal of a node is the normalised sum, over its four quadrants (NE, NW, SW, SE), of
 *  the cross product of the two edges to its neighbours in that quadrant:
 *  (E - P) x (N - P) for NE, and so on counter-clockwise. With all four neighbours valid this
 *  equals the central-difference normal (E - W) x (N - S). Where an axis neighbour is missing,
 *  the quadrant uses the diagonal neighbour instead, so every triangle that
 *  ap_mesh_triangulate can emit contributes to each of its vertices. Nodes with no
 *  contribution (nodata, isolated) get NaN normals. With wrap (the seam of
 *  ap_mesh_triangulate_rows), the east neighbour of column nx - 1 is column 0 and the west
 *  neighbour of column 0 is column nx - 1, so the normals of the seam's nodes are those of
 *  any other column.
 *
 *  Call only after ap_mesh_normals_validate() succeeded. Reentrant; disjoint row ranges may run
 *  on different threads and the result does not depend on the split. Never allocates.
 */
void ap_mesh_normals_rows(const double *xyz, size_t nx, size_t ny, int wrap, size_t j0,
                          size_t j1, float *normals);

#ifdef __cplusplus
}
#endif

#endif /* AP_MESH_H */
