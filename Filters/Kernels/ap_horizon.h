/* SPDX-License-Identifier: BSD-3-Clause */
/** @file ap_horizon.h
 *  @brief Horizon angles of every cell of a DEM in D azimuth sectors, and the sky-visibility
 *         products derived from them in the same pass: visible solid angle, aperture radius,
 *         bent normal, sky-view factor (Zakšek), diffuse sky factor (Dozier & Frew),
 *         positive openness, edge truncation.
 *
 *  ## Horizons
 *  For cell q and azimuth φ the terrain horizon is
 *      h(q, φ) = max over terrain points P along the ray from q in azimuth φ of
 *                atan((z_P − z_q − c·t²) / t),   t = ground distance from q to P,
 *  with c = (1 − k) / (2 R(φ)) the Earth-curvature drop with refraction coefficient k (c = 0
 *  without curvature) and R(φ) = 1 / (cos²φ / M + sin²φ / N) the ellipsoid's radius of
 *  curvature in that azimuth (Euler), from the meridional and prime-vertical radii M, N given
 *  for the DEM centre. It is computed with the convex-hull line sweep of Timonen & Westerholm
 *  (2010; Stewart 1998): per azimuth, lines of constant ground azimuth cross the grid; each
 *  keeps the upper convex hull of the terrain it has passed in u = z − c·x² (x = distance along
 *  the line, which makes curvature exact, ALGORITHMS.md §3.5), so the cost is amortised O(1)
 *  per cell and direction and does not grow with the search distance. Each cell queries the
 *  hulls of the two lines that bracket it *with its own height* (a galloping search for the
 *  tangent vertex from the line's previous answer; the cell's own ray is then evaluated at
 *  both tangent columns and the higher slope kept) and marches its own ray exactly for the
 *  first K − 1 samples (the near field); querying with interpolated line samples instead is
 *  wrong by tens of degrees at peaks and ridges (ALGORITHMS.md §3.4). Terrain is sampled by
 *  linear interpolation across the grid lines the rays cross. A search distance of at most
 *  march_columns steps of a sector (64 by default: 1.9 km on a 30 m grid) is instead marched
 *  exactly along every cell's own ray on the bilinear surface, without hulls: cost O(distance)
 *  per cell, below the sweep's up to there, and more accurate (the edge flag is then whether
 *  that ray leaves the grid before the limit). Like the near field, the march follows a line
 *  straight in index space with the direction of the cell's row: on lat/lon grids the rhumb
 *  line bends away from it as the east-west cell size changes, by about tan(lat) x (latitude
 *  span) x (columns) / 2 columns at the limit (0.05 of a cell at 60 N over 64 diagonal steps
 *  of a 3-arc-second grid). With per-row cell sizes those rays' steps are rounded to a lattice
 *  of 1e-4 in log(length) (their drift to one of rows), and the rows (or columns) that round
 *  alike share one pattern, so that a piece of a DEM takes the whole DEM's patterns: the near
 *  field's and the march's distances are exact to 5e-5 of themselves, a slope of 1 to 5e-5
 *  (TestApertureSkyVisibility's wall measures it).
 *  A search distance of at most far_march_columns steps (1024 by
 *  default: 30 km on a 30 m grid) is searched by the far march instead of the hulls (with
 *  per-row cell sizes along each ray's rhumb line, the same for every cell of a grid row:
 *  shifted and measured from that row on, as the sweep's lines lie): beyond the near field,
 *  every cell's own ray is sampled where it
 *  crosses each view column up to the distance, linearly between the column's two cells (the
 *  samples the hulls hold), and the largest slope taken; stretches whose elevations, bounded
 *  by tile maxima, cannot beat the slope found so far are skipped without changing a bit.
 *  O(distance) per cell and direction at worst (a bowl rising all the way out), yet faster
 *  than the sweep's sliding windows up to that limit on every DEM measured, and exact on the
 *  cell's own ray where the sweep evaluates it only at its lines' tangent columns (the rough
 *  DEM of the tests at 2500 m: p99 0.082 against 0.115 degree from the brute force).
 *
 *  Features a cell wide: beyond the near field, the far march and the sweep see the terrain
 *  only where a ray crosses a view column (linear between that column's two cells), not inside
 *  the bilinear patches between two crossings. Natural terrain, rough down to the cell, loses
 *  little there (the figures above); a lone spike does: a tower one cell wide (a mast, a
 *  chimney, a tree in a DSM) that a ray passes between two crossings is missed. A probe
 *  (2026-12-06): on flat ground with 10 m cells, a 300 m tower 36 rows ahead, 1.5 degrees off
 *  the 30-degree sector's ray, gave that cell 3.83 degrees (the brute force's) within 640 m,
 *  marched exactly, and unlimited, where it lay in the sweep's 32 exact columns, but 0 at 800
 *  m and 2 km, far-marched with K = 8: a horizon can drop when a longer distance takes a
 *  sector from the exact march to the far march. On a field of 40 such towers (50-400 m,
 *  12 sectors, 250 cells) the horizon's MAE was 0.31 degree and its p99 7.3 far-marched at 2
 *  km, 0.041 and 1.4 swept unlimited: beyond the accuracy bounds, which hold on natural
 *  terrain. A larger near_field (up to 64 columns exact) finds such features that near; it
 *  costs 10-20% more time at 10 km on the benchmark's 1024^2 DEM at 32 or 64 columns.
 *  Straight edges met at a grazing angle (a cliff, a wall in a DSM): the sweep evaluates the
 *  cell's ray at its two lines' tangent columns only, which can lie cells past the edge (the
 *  lines meet it up to a cell / tan(angle) apart). A probe (2026-12-07), a 100 m step 100 m
 *  east on 10 m cells, D = 360, no curvature: unlimited, exact within the 32 exact columns,
 *  then up to 1.2 degrees low (the step met at 16 degrees, 36 columns out), 0.6 beyond 64;
 *  far-marched at 10 km, up to 2.0 low 8 to 32 columns out (the column samples), 0.3 beyond.
 *
 *  Geometry: cell sizes are given per row in metres, so lat/lon DEMs are exact: the lines
 *  follow constant ground azimuth (rhumb lines) and bend in index space as the east-west cell
 *  size changes with latitude. With Ψ(r) the sum of dy/dx over the rows up to row r (whole rows
 *  by trapezoids, linear between them: the isometric latitude in columns), a rhumb line at
 *  grid azimuth φ keeps Ψ(row) − cot φ · column constant; the sweep's lines are the levels
 *  σ k of it (whole k), σ = dy/dx of the DEM's centre row, so they lie a row apart there and
 *  dx / dx(centre) rows apart elsewhere (sectors that cross rows faster than columns: line k
 *  at column k + tan φ · Ψ(row)). Along the axes (|cos φ| or |sin φ| ≤ 1e-12) the lines are
 *  the rows or the columns themselves, on which every ray then runs. They depend on the DEM's
 *  rows alone, not on where a piece of it starts (whole_dx, origin_row). Sector d is centred
 *  on true azimuth φ_d = 2π d / D (clockwise from north, d = 0 north); with a projected DEM,
 *  pass the meridian convergence γ at the DEM centre as azimuth_offset and the sweep runs at
 *  grid azimuth φ_d − γ.
 *
 *  Near a side of the DEM, where a cell's ray still runs on the grid after the bracketing
 *  line on that side has left it, the sweep samples the cell's own ray over that last stretch
 *  (at most 1/|shift per column| + 1 columns; only where the DEM's highest cell could raise
 *  the slope): the hulls hold nothing of it. It and the far march also take the point where
 *  the ray leaves the grid through a side between two view columns (linear along the edge
 *  row), up to a column beyond the last column crossing: in a bowl rising to the DEM's edge
 *  the horizon lies there (up to 3 degrees low without it). In the x-major sectors of lat/lon
 *  grids, whose lines bend, ap_horizon_accumulate samples that stretch and that point for the
 *  rows it adds, before adding them (a bowl rising to the edge was up to 7.8 degrees low).
 *
 *  Terrain beyond the DEM edge is invisible (it does not exist for the sweep). Nodata (NaN)
 *  never occludes; nodata cells get NaN products. Beside nodata the terrain is the bilinear
 *  patches whose four corners have data and the grid lines between two cells with data (a
 *  one-cell-wide strip of land between nodata stands as a ridge line). The near field finds
 *  it exactly; beyond it a ray is sampled where it crosses the view's columns, linear between
 *  the column's two cells. Where one of them is nodata the points where the ray crosses a view
 *  row next to that sample are taken too, up to the search distance (a shore, a one-cell strip
 *  of land crossed between two columns): by the far march, and for the sweep by
 *  ap_horizon_accumulate after it; the sweep also marches a cell's ray where a sample one of
 *  its two lines lost to nodata beside data could rise above the cell's horizon (the line's
 *  ghosts). That keeps the accuracy above beside nodata (a coast, against a brute force:
 *  horizon MAE 0.003 deg, p99 0.1 far-marched; MAE 0.003-0.005, p99 0.14, largest 1 deg swept;
 *  beside a one-cell pier 150 m high the column samples miss up to 7 deg of its patches, as
 *  they would without nodata), at a cost on DEMs with nodata only (kernel instructions,
 *  far-marched: +5% for a few voids, +19% half sea, +47% for 1% scattered nodata cells;
 *  swept: +5 to +15%).
 *  A direction with no terrain sample at all (the ray leaves the DEM at once) has horizon
 *  −π/2.
 *
 *  ## Products, from the sector horizons in one pass (ALGORITHMS.md §2.2)
 *  Per sector d (width Δ = 2π/D, grid azimuth φ) with terrain horizon h_t, the cell's own
 *  tangent-plane elevation h_s = atan(g·(sin φ, cos φ)) (g = elevation gradient, Horn 1981) and
 *  h = max(h_t, h_s, 0) (the visible sky is above the horizontal, the terrain and the tangent
 *  plane), with the horizon taken constant within the sector:
 *      VisibleSolidAngle  A  = Σ Δ (1 − sin h)                               [sr]
 *      ApertureRadius     rp = acos(1 − A / 2π) = 2 asin(sqrt(A / 4π))       [rad]
 *      B = Σ ( 2 sin(Δ/2) sin φ · Q(h),  2 sin(Δ/2) cos φ · Q(h),  (Δ/2) cos² h ),
 *          Q(h) = ½ [(π/2 − h) − sin h cos h]        (B = ∫ V ω dω over the visible sky)
 *      BentNormal         B / |B|   (unit; grid frame: x grid east, y grid north, z up)
 *      DiffuseSkyFactor   n·B / π   (Dozier & Frew 1990 eq. 7b with Dozier 2022's self-shadow
 *                         correction: isotropic sky irradiance on the tilted cell relative to
 *                         an unobstructed horizontal surface; n = unit normal from g)
 *      SkyViewFactor      1 − (1/D) Σ sin max(h_t, 0)   (Zakšek et al. 2011: the unweighted
 *                         visible fraction of the upper hemisphere above the horizontal plane;
 *                         it ignores the cell's own slope — not the same as DiffuseSkyFactor)
 *      PositiveOpenness   (1/D) Σ (π/2 − h_t)    (Yokoyama et al. 2002, radians)
 *      EdgeTruncated      1 where, in some sector, the DEM ends closer than the search limit:
 *                         max_distance; without one, with curvature on, sqrt((z_max − z)/c),
 *                         beyond which terrain no higher than the DEM's highest cell stays
 *                         below the cell's horizontal (without curvature every cell is
 *                         flagged). So it guards the products clipped at the horizontal (A,
 *                         rp, B, DiffuseSkyFactor, SkyViewFactor), not PositiveOpenness and
 *                         h_t below the horizontal, which terrain beyond the edge could raise
 *                         on unflagged cells (on an endless plain with curvature no cell is
 *                         flagged, yet an edge cell's openness is 132.2° at D = 32, a
 *                         corner's 154.7°, with azimuth_offset 135° and 157.5°: the sectors
 *                         leaving the DEM at once count −π/2). With a max_distance the flag
 *                         does not use z_max, which a piece of a DEM would not know.
 *                         With constant cell sizes every search takes the distance at which
 *                         the cell's own ray leaves the grid (the sweep took the nearer
 *                         bracketing line's until 2026-12-07, flagging the second ring of
 *                         cells where the limit was under a cell).
 *                         On a grid with per-row cell sizes the sweep takes a cell's reach
 *                         from the two lines that bracket it (the nearer of their last
 *                         samples on the grid), not from its own rhumb line: the flag can be
 *                         set on cells whose own ray reaches up to about a row farther than
 *                         the limit (0.6% of a global 0.5° DEM's cells without a distance; a
 *                         probe of 2026-12-06 found none missed; the second ring of cells
 *                         where the limit is under a row), and on a global DEM those cells
 *                         change with the seam's place (the products clipped at the
 *                         horizontal do not).
 *  The sums converge as O(1/D²) to the continuous integrals. With scale_metric each sector's
 *  terms carry its weight ω and B's horizontal its ground direction (see there). The sums are
 *  single precision, their terms in forms that keep float's relative precision up to the
 *  zenith (1 − sin h as cos² h / (1 + sin h), Q from the zenith distance by its series): a
 *  shaft whose every horizon lies within 1e-4 rad of the zenith keeps A, rp and
 *  DiffuseSkyFactor within 1e-5 of their values, relatively, and BentNormal within 1e-5.
 *
 *  ## Use and threads
 *      ap_horizon_params_init(&p);  ...set fields...
 *      ap_horizon_create(&grid, &p, &products, &hz);          (validates once, allocates)
 *      for d in 0..D-1:
 *          ap_horizon_prepare(hz, d);
 *          split [0, ap_horizon_near_field_count(hz)) into ranges; ap_horizon_near_field() each
 *          split [0, ap_horizon_bracket_count(hz)) into ranges; ap_horizon_sweep() each
 *          split [0, ny) into row ranges;                      ap_horizon_accumulate() each
 *      split [0, ny) into row ranges;                          ap_horizon_finish() each
 *      ap_horizon_destroy(hz);
 *  The range functions are reentrant for disjoint ranges (run them from any threads; they
 *  never create threads), and the results are bit-identical for any split, because every cell
 *  is computed by exactly one call and accumulates its sectors in order. ap_horizon_run() does
 *  all of it on the calling thread.
 */
#ifndef AP_HORIZON_H
#define AP_HORIZON_H

#include <stddef.h>

#include "ap_grid.h"
#include "ap_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A DEM with metric cell sizes. Rows run south to north (row 0 south). */
typedef struct ap_horizon_grid {
  ap_grid_view z;   /**< elevations (m), finite or NaN (= nodata); at least 2 x 2 */
  const double *dx; /**< ny east-west cell sizes (m) per row, > 0; NULL: all rows dx0 */
  const double *dy; /**< ny south-north cell sizes (m) per row, > 0; NULL: all rows dy0 */
  double dx0, dy0;  /**< cell sizes (m) used when dx / dy are NULL */
} ap_horizon_grid;

/** The near field K of ap_horizon_params.near_field = 0, per sector. The hulls sample a
 *  cell's ray only where its two bracketing lines' hulls are tangent, which misses most near
 *  the cell, where a metre of height is the largest angle: on the embedded DEM (and the same
 *  relabelled to 75 N), unlimited, K = 8 left a 99th percentile of 0.10 (0.16) deg and a
 *  largest error of 0.6 (3.0) deg against the brute force, K = 32 leaves 0.024 (0.046) and
 *  0.14 (0.31), for 10-15% more time. The far march samples every column crossing beyond K,
 *  so there a longer exact stretch buys little: K = 8. */
#define AP_HORIZON_NEAR_FIELD_SWEPT 32
#define AP_HORIZON_NEAR_FIELD_MARCHED 8

/** The largest |origin_col| and |origin_row| of ap_horizon_params: a piece of a larger DEM
 *  starts within 10^9 cells of its corner, so a DEM of more cells a side cannot be cut into
 *  pieces everywhere (none is that large: 10^9 cells of 1 mm are 1000 km). */
#define AP_HORIZON_MAX_ORIGIN 1000000000L

/** Options; always start from ap_horizon_params_init(). */
typedef struct ap_horizon_params {
  int directions;         /**< D azimuth sectors, 4..360 (default 32) */
  double azimuth_offset;  /**< radians; sweep at grid azimuth = true azimuth − offset: the
                               meridian convergence γ at the DEM centre (default 0) */
  double max_distance;    /**< search distance (m), > 0; INFINITY = unlimited (default) */
  int curvature;          /**< nonzero: Earth curvature with refraction (default 1) */
  double refraction;      /**< refraction coefficient k in [0, 1) (default 0.13) */
  double radius_meridian; /**< M: meridional radius of curvature (m) at the DEM centre
                               (default 6371000) */
  double radius_normal;   /**< N: prime-vertical radius of curvature (m) (default 6371000) */
  int near_field;         /**< K: samples 1..K-1 along each cell's own ray are marched
                               exactly before the hulls (or the far march) take over;
                               1..64, or 0 (default): per sector, AP_HORIZON_NEAR_FIELD_SWEPT
                               where the hulls search and AP_HORIZON_NEAR_FIELD_MARCHED where
                               the far march does (see those) */
  int march_columns;      /**< when max_distance spans at most this many view columns of a
                               sector (steps of the shortest row), every ray is marched
                               exactly to max_distance and the hulls are skipped: exact on
                               the bilinear surface, and 2-4x faster than the sweep for such
                               short distances; 0..64, 0 = always sweep (default 64) */
  int far_march_columns;  /**< when max_distance spans more than
                               march_columns but at most this many view columns, the
                               columns from K on are marched along every cell's own ray
                               instead of swept (the far march: the largest slope over the
                               ray's crossings of the view columns, as the hulls hold them;
                               a conservative bound from tile maxima skips the stretches
                               that cannot rise above the slope found so far, so results
                               equal the full march bit for bit). Cost O(distance) at worst,
                               yet 1.6-2x below the sweep's at 10 km on 30 m grids (2.6x
                               on a 3-arc-second lat/lon tile); beyond this limit the sweep
                               runs.
                               0..65536, 0 = never (default 1024) */
  long origin_col;        /**< the grid is a piece of a larger DEM whose cell (origin_col,
                               origin_row) is the grid's cell (0, 0), |values| at most
                               AP_HORIZON_MAX_ORIGIN; the
                               sweep's lines lie on that DEM's lattice of lines, so a piece
                               cut with a margin of max_distance around a region gets the
                               larger DEM's results there (up to the rounding of a last bit:
                               distances along the lines run from the piece's edge). With
                               per-row cell sizes the lattice is defined by the larger DEM's
                               rows: pass them as whole_dx / whole_dy, else the grid is taken
                               as the whole DEM (origin 0, 0) for the sweep. Default 0, 0 */
  long origin_row;
  const double *whole_dx; /**< with per-row cell sizes (grid dx or dy set): the larger DEM's
                               east-west cell sizes (m) for its whole_rows rows, of which
                               this grid's rows are rows origin_row.. origin_row + ny − 1;
                               they set the sweep's lattice of lines and the choices that
                               depend on the whole DEM (which sectors cross columns faster
                               than rows, at its centre row; whether a distance is marched,
                               by its shortest row). Caller-owned, read by
                               ap_horizon_create only. NULL (default): the grid's own rows.
                               Ignored with constant cell sizes */
  const double *whole_dy; /**< the larger DEM's south-north cell sizes (m), as whole_dx;
                               both NULL or both set, else AP_ERR_INVALID_ARGUMENT, as for
                               too few rows, a size not positive and finite, or rows
                               origin_row.. that differ from the grid's own */
  size_t whole_rows;      /**< rows of whole_dx / whole_dy (default 0) */
  size_t region_i0;       /**< the cells to compute: columns region_i0 ..
                               region_i0 + region_nx − 1 and rows region_j0 ..
                               region_j0 + region_ny − 1 of the grid, inside it; the rest of
                               the grid is terrain only (the halo of a piece). Each cell gets
                               the value a run over the whole grid gives it, bit for bit, and
                               costs only what the region needs: marched sectors march the
                               region's cells alone, swept ones query the hulls only there
                               (their lines still cross the grid up to the region) and stop
                               past it. All four 0 (default): every cell. A region not inside
                               the grid, or with one size 0, is AP_ERR_INVALID_ARGUMENT */
  size_t region_j0;
  size_t region_nx;
  size_t region_ny;
  const double *scale_metric; /**< constant cell sizes only (else AP_ERR_INVALID_ARGUMENT):
                               the ground metric of one grid step where a projection's scale
                               changes across the DEM, on a lattice over the larger DEM
                               (origin_col, origin_row): node (a, b) lies at its column
                               a * scale_span_cols / (scale_cols − 1) and row
                               b * scale_span_rows / (scale_rows − 1) and holds, at
                               [3 (b * scale_cols + a)], |E|², E·N and |N|² (m²), where E and N
                               are the ground vectors of one step along the row and one along
                               the column (E·N = 0 for a conformal projection). Bilinear
                               between nodes, each cell's ground distance in the prepared
                               sector is ρ times the one from dx0, dy0 (ρ² = the metric of the
                               sector's step over that step's squared length from dx0, dy0),
                               so its terrain and tangent-plane tangents are divided by ρ.
                               With S the square root of the relative metric (ground vector
                               of a step u = Q S u, Q a rotation), the sector's ground
                               direction is S u / |S u|, and the sectors, even in grid
                               azimuth, lie unevenly on the ground where the projection is not
                               conformal: each sector's terms are weighted by ω = half the
                               ground angle between its two neighbours' directions over Δ
                               (ω = 1 on a conformal projection; the ω of a cell sum to D),
                               B's horizontal is summed along the ground directions and
                               DiffuseSkyFactor's normal taken through S⁻¹, so B and
                               BentNormal lie in S's frame (the ground's turned by Q⁻¹: a
                               caller turns them by Q; HorizonAngles stay at the sectors' own
                               ground directions, which a caller may interpolate to even
                               azimuths). The search distance and the curvature drop stay at
                               dx0, dy0's scale (off by ρ − 1: under 0.01 deg at 100 km for a
                               2% scale change). Each node: finite, |E|², |N|² > 0,
                               |E|²|N|² > (E·N)². Caller-owned, read by ap_horizon_create
                               only. NULL (default): every cell at dx0, dy0 */
  size_t scale_cols;          /**< lattice nodes per row and column, 2..1025 each */
  size_t scale_rows;
  double scale_span_cols;     /**< the larger DEM's columns and rows the lattice spans, from
                               column and row 0: > 0 and finite (its sizes − 1) */
  double scale_span_rows;
} ap_horizon_params;

/** Output arrays, caller-owned, one value per cell of the region (ap_horizon_params; by
 *  default the whole grid, nx * ny cells) in grid order: cell (i, j) at
 *  (j − region_j0) * region_nx + (i − region_i0), so j * nx + i for the whole grid. Each may
 *  be NULL when not wanted. Angles in radians. */
typedef struct ap_sky_products {
  float *visible_solid_angle;   /**< A (sr), [0, 2π] */
  float *aperture_radius;       /**< rp (rad), [0, π/2] */
  float *bent_normal;           /**< 3 per cell, unit vector in the grid frame (in S's
                                     frame with ap_horizon_params.scale_metric) */
  float *sky_view_factor;       /**< Zakšek SVF, [0, 1] */
  float *diffuse_sky_factor;    /**< Dozier–Frew V_d, [0, 1] */
  float *positive_openness;     /**< radians, [0, π] */
  unsigned char *edge_truncated; /**< 0 or 1 */
  float *horizon_angles;        /**< D per cell, sector d at [cell * D + d] (rad) */
} ap_sky_products;

/** Opaque state of one horizon computation. */
typedef struct ap_horizon ap_horizon;

/** Set the defaults documented on each field. */
void ap_horizon_params_init(ap_horizon_params *p);

/** S, the square root of one node of ap_horizon_params.scale_metric relative to cells of
 *  dx0 x dy0 m (m[0] / dx0², m[1] / (dx0 dy0), m[2] / dy0²), as xx, xy, yy in s: symmetric
 *  and positive definite, the ground vector of a step u (in metres of dx0, dy0) is Q S u for a
 *  rotation Q. The node must be valid (see scale_metric); no check. */
void ap_horizon_metric_root(const double m[3], double dx0, double dy0, double s[3]);

/** Check a grid and options without allocating: AP_OK or the first problem
 *  (AP_ERR_INVALID_ARGUMENT for an option out of range or a cell size that is not positive
 *  and finite, AP_ERR_GRID_TOO_SMALL, AP_ERR_SIZE_OVERFLOW for a side of more than
 *  AP_HORIZON_MAX_ORIGIN + 1 cells or more than SIZE_MAX / 32 cells, AP_ERR_ALL_NODATA,
 *  AP_ERR_OUT_OF_RANGE for an infinite elevation, ...). */
ap_status ap_horizon_validate(const ap_horizon_grid *g, const ap_horizon_params *p);

/** Validate, then allocate the state: a transposed copy of the elevations (4 bytes per
 *  cell), the gradients (8 per cell of the region), one direction's horizons and edge flags
 *  (5), and accumulators for the bent-normal sums when bent_normal is NULL but the diffuse sky
 *  factor is wanted (12 per cell of the region). Writes only the transposed copy: the
 *  gradients and the requested outputs (the accumulators until ap_horizon_finish) are started
 *  by the first sector's ap_horizon_accumulate, in the caller's parallel phase. The grid's and
 *  the outputs' memory must stay valid until ap_horizon_destroy. */
ap_status ap_horizon_create(const ap_horizon_grid *g, const ap_horizon_params *p,
                            const ap_sky_products *out, ap_horizon **hz);

/** Bytes per cell that ap_horizon_create allocates for the state above, for callers that
 *  estimate a run's memory: 17, plus 12 when the diffuse sky factor is wanted without the
 *  bent normal (both flags 0 or 1); with a region, the gradients and those accumulators are
 *  per cell of the region, so this bounds the state from above. The per-sector and
 *  per-thread buffers, O(nx + ny) each, the far march's tile maxima (under 0.02 bytes per
 *  cell) and the caller's outputs are not counted. */
size_t ap_horizon_state_bytes_per_cell(int diffuse_sky_factor, int bent_normal);

/** Free everything ap_horizon_create allocated (NULL is fine). */
void ap_horizon_destroy(ap_horizon *hz);

/** Number of sectors D. */
int ap_horizon_directions(const ap_horizon *hz);

/** True azimuth (radians, clockwise from north) of sector d's centre. */
double ap_horizon_azimuth(const ap_horizon *hz, int d);

/** Set up sector d (0 <= d < D) for ap_horizon_sweep; not thread-safe (call between
 *  parallel phases). */
ap_status ap_horizon_prepare(ap_horizon *hz, int d);

/** Number of units the prepared sector's near field splits into: its view columns (the DEM's
 *  columns or rows, whichever the sector's direction crosses faster), or the DEM's rows when
 *  its rows cross columns and their cell sizes differ (lat/lon DEMs), so that each unit's
 *  loops run along a grid row. */
size_t ap_horizon_near_field_count(const ap_horizon *hz);

/** The near field (the first K − 1 samples of every cell's ray, exactly on the bilinear
 *  surface) of units [u0, u1) of the prepared sector. Every unit must be done before any
 *  ap_horizon_sweep of the sector, which reads these results. In a sector whose search
 *  distance is within march_columns, or far_march_columns where the far march runs, it is the
 *  whole search, edge flags included (and a call should then span a few units: the far march
 *  goes through them in chunks of cells, which keeps the columns it reads in cache). Returns
 *  AP_ERR_OUT_OF_MEMORY if a row's buffer cannot be allocated. */
ap_status ap_horizon_near_field(const ap_horizon *hz, size_t u0, size_t u1);

/** Brackets per ap_horizon_sweep call that perform best, as ap_horizon_run and the VTK filter
 *  split them (the filter as its threads' grain): a band's hulls and windows stay in cache. One
 *  call over every bracket of a 2048^2 DEM (10 km) took 31.5 s instead of 18.8 s on one core,
 *  and two threads took 15.3-15.5 s with 256 per call against 11.4-13.7 s with 16. Results do
 *  not depend on the split. */
#define AP_HORIZON_SWEEP_BAND 16

/** Number of brackets (gaps between neighbouring sweep lines) of the prepared sector. */
size_t ap_horizon_bracket_count(const ap_horizon *hz);

/** Sweep brackets [b0, b1) of the prepared sector after its near field: computes the horizon
 *  and edge flag of every cell between those lines (nothing to do, AP_OK, in a sector whose
 *  search distance the near field covered: within march_columns, or far_march_columns where
 *  the far march runs). Allocates and frees its own hull stacks;
 *  returns AP_ERR_OUT_OF_MEMORY if that fails (the products are then incomplete). */
ap_status ap_horizon_sweep(const ap_horizon *hz, size_t b0, size_t b1);

/** Add the prepared sector's horizons of grid rows [j0, j1) to the products (only the
 *  region's cells of them: rows outside it have nothing to do), after its sweep
 *  (for the first sector prepared: compute those rows' gradients and start their sums, so
 *  every row must be accumulated for each sector before the next is prepared, as the sequence
 *  above does; in swept x-major sectors of grids with per-row cell sizes it first samples
 *  those rows' rays near the side they leave through, see above). Allocates a tile of 16
 *  rows (80 bytes per column) for x-major sectors, and 3 doubles per column and one per row
 *  for that sampling; returns AP_ERR_OUT_OF_MEMORY if that fails (nothing is then added). */
ap_status ap_horizon_accumulate(const ap_horizon *hz, size_t j0, size_t j1);

/** After the last sector: turn the sums of grid rows [j0, j1) (the region's cells of them)
 *  into the products. Does nothing for a NULL hz or before any sector was prepared; the rows
 *  must have been accumulated for every sector (the sequence above). */
void ap_horizon_finish(const ap_horizon *hz, size_t j0, size_t j1);

/** Everything on the calling thread: create, every sector, finish, destroy. */
ap_status ap_horizon_run(const ap_horizon_grid *g, const ap_horizon_params *p,
                         const ap_sky_products *out);

#ifdef __cplusplus
}
#endif

#endif /* AP_HORIZON_H */
