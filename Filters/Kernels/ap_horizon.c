/* SPDX-License-Identifier: BSD-3-Clause */
/* Horizon sweep and sky-visibility products; the contract and formulas are in ap_horizon.h.
 *
 * Vocabulary. For one sector the grid is seen through a "view": a primary axis p along which
 * the sweep lines advance (towards the occluders as p grows) and a secondary axis s across
 * them. A sector whose ground direction crosses columns faster than rows (in index units) is
 * "x-major": p runs along columns (east or west) and s is the row; otherwise p runs along rows
 * and s is the column. x-major views read a transposed copy of the elevations so that every
 * view column is contiguous in memory.
 *
 * Line k starts at s = k on the last column (p = np - 1) and moves by m rows/columns per
 * primary step, m = the lateral index shift of a constant-ground-azimuth line. With constant
 * cell sizes m is constant (straight parallel lines, the classic Dozier–Frew "skew"); with cell
 * sizes varying by row (lat/lon DEMs) m depends on the row: for row-major views the same for
 * every line at a given p, for column-major views on each line's own row, so lines bend
 * slightly and their spacing drifts by the relative change of the cell size (a few percent
 * over a whole DEM), which the bracketing below handles.
 */
#include "ap_horizon.h"

#include "ap_atanf.h"
#include "ap_zenith.h"
#include "ap_memory.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define AP_PI 3.14159265358979323846
#define AP_HALF_PI 1.57079632679489661923

/* GCC's and Clang's vector extensions and bit builtins for the far march's groups of 16 cells
 * (fm_lanes, shore_voids, shore_lowest); other compilers, and a build with
 * AP_HORIZON_NO_VECTORS (the test Kernels-portable-equality, which compares its results with
 * the library's bit for bit), take the plain C loops beside them. */
#if defined(__GNUC__) && !defined(AP_HORIZON_NO_VECTORS)
#define AP_FM_VECTORS 1
#else
#define AP_FM_VECTORS 0
#endif

/* Software prefetch (a hint: no effect on results), and how many view columns ahead the sweep
 * fetches. */
#if defined(__GNUC__)
#define AP_PREFETCH(addr) __builtin_prefetch((addr))
#else
#define AP_PREFETCH(addr) ((void)(addr))
#endif
#define AP_PREFETCH_COLUMNS 4

/* For the few small functions of the inner loops that GCC would otherwise call (a call costs
 * as much as their body). */
#if defined(__GNUC__)
#define AP_INLINE static inline __attribute__((always_inline))
#else
#define AP_INLINE static inline
#endif

/* For the window's rebuilds, kept out of the sweep's hot loop (inlined there, they cost it
 * registers). */
#if defined(__GNUC__)
#define AP_NOINLINE __attribute__((noinline))
#else
#define AP_NOINLINE
#endif

/* Unroll the next loop twice: the sweep's two-line loop, whose two hull queries are then
 * scheduled together (and no loop branch mispredicts between them). */
#if defined(__clang__) || (defined(__GNUC__) && __GNUC__ >= 8)
#define AP_UNROLL_2 _Pragma("GCC unroll 2")
#else
#define AP_UNROLL_2
#endif

/* ---------------------------------------------------------------------------------------- */
/* Upper convex hulls of the samples along one line, queried from a point on the near side
 * (smaller x than every sample). A sample remembers where it was taken (view column and the
 * line's lateral position there), so a query can return the column of the tangent point. */

typedef struct sample {
  double x;  /* distance along the line (m) */
  double u;  /* height minus the curvature drop: z - c x^2 */
  double s;  /* the line's lateral position (view index) on that column */
  long col;  /* view column */
} sample;

/* The line through two neighbouring hull vertices, u = b + e x. */
typedef struct hull_edge {
  double e, b;
} hull_edge;

/* The line through two samples (p->x != q->x). */
AP_INLINE hull_edge edge_through(const sample *p, const sample *q)
{
  hull_edge r;
  r.e = (p->u - q->u) / (p->x - q->x);
  r.b = q->u - r.e * q->x;
  return r;
}

/* The line's height at x. */
AP_INLINE double edge_at(const hull_edge *ed, double x)
{
  return ed->b + ed->e * x;
}

/* v[0] is the farthest vertex, v[n - 1] the nearest; ed[k] (k >= 1) is the line through v[k - 1]
 * and v[k], so that the two tests on a vertex pair below, which are about a point's position
 * relative to that line, cost a multiply and a compare (the slope is divided once per push). */
typedef struct hull {
  sample *v;
  hull_edge *ed;
  int n, cap, ecap;
} hull;

/* Make the array *pa (elements of size bytes, capacity *cap) hold at least need elements,
 * doubling; 0 when out of memory (the array is then unchanged). pa points to the array's
 * pointer, of any object type. */
static int grow(void *pa, int *cap, int need, size_t size)
{
  int c;
  void *old, *nv;
  if (need <= *cap) {
    return 1;
  }
  c = *cap ? *cap : 16;
  while (c < need) {
    c *= 2;
  }
  memcpy(&old, pa, sizeof(old));
  nv = realloc(old, (size_t)c * size);
  if (!nv) {
    return 0;
  }
  memcpy(pa, &nv, sizeof(nv));
  *cap = c;
  return 1;
}
#define GROW(arr, cap, need) ((need) <= (cap) || grow(&(arr), &(cap), (need), sizeof(*(arr))))

static void hull_free(hull *h)
{
  free(h->v);
  free(h->ed);
  h->v = NULL;
  h->ed = NULL;
  h->n = h->cap = h->ecap = 0;
}

/* Push a sample nearer than every sample in the hull (Timonen & Westerholm, Algorithm 1;
 * Andrew's monotone chain): the top is dropped while the new sample lies on or above the line
 * through the second and the top (the second is then at least as steep from it), because the
 * top can then never be the tangent point again. (Inlined: the sweep is compiled twice, and
 * GCC then stopped inlining it there: 3% more instructions in the sweep.) */
AP_INLINE int hull_push_near(hull *h, const sample *q)
{
  while (h->n >= 2 && q->u >= edge_at(&h->ed[h->n - 1], q->x)) {
    --h->n;
  }
  if (!GROW(h->v, h->cap, h->n + 1) || !GROW(h->ed, h->ecap, h->n + 1)) {
    return 0;
  }
  if (h->n >= 1) {
    h->ed[h->n] = edge_through(&h->v[h->n - 1], q);
  }
  h->v[h->n++] = *q;
  return 1;
}

/* The vertex with the largest slope (u_i - uq) / (x_i - xq), for xq below every x_i, or NULL
 * when empty. Along an upper hull these slopes are unimodal: "the slope rises to the next
 * vertex", i.e. the query point lies below the line through the two (the lines of an upper
 * hull's edges, taken at xq, fall from the farthest edge to the nearest), holds for every index
 * below the tangent vertex and for none from it on, so any search for that boundary finds the
 * same vertex. The search gallops from *hint (the index a previous query of this hull returned;
 * successive columns' tangents are mostly close) and then bisects: a few steps instead of
 * log2(n). *hint is updated. */
AP_INLINE const sample *hull_tangent(const hull *h, double xq, double uq, int *hint)
{
  const hull_edge *ed = h->ed;
  const int last = h->n - 1; /* the boundary lies in [0, last] */
  int lo, hi, step, i;
  if (h->n == 0) {
    return NULL;
  }
#define RISING(k) (uq < edge_at(&ed[(k) + 1], xq))
  i = *hint > last ? last : *hint; /* a hint is never negative */
  if (i < last && RISING(i)) {
    /* the boundary is above i: gallop up */
    lo = i + 1;
    step = 1;
    hi = lo;
    while (hi < last && RISING(hi)) {
      lo = hi + 1;
      hi += step;
      step *= 2;
      if (hi > last) {
        hi = last;
      }
    }
    /* boundary in [lo, hi]: RISING false at hi (or hi == last) */
  } else {
    /* the boundary is at or below i: gallop down */
    hi = i;
    step = 1;
    lo = i - 1;
    while (lo >= 0 && !RISING(lo)) {
      hi = lo;
      lo -= step;
      step *= 2;
    }
    lo = lo < 0 ? 0 : lo + 1;
    /* boundary in [lo, hi] */
  }
  while (lo < hi) {
    const int mid = lo + ((hi - lo) >> 1);
    if (RISING(mid)) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
#undef RISING
  *hint = lo;
  return &h->v[lo];
}

/* ---------------------------------------------------------------------------------------- */
/* A line's samples within a sliding window (x_q, x_q + L], for a maximum search distance.
 * The window only ever gains samples on the near side and loses them on the far side, so it is
 * a queue, kept as two stacks (the classic two-stack queue): "in" receives new samples (with
 * the near-pushed hull above); "out" holds older samples and gives them up farthest first.
 * When "out" runs dry, all of "in" moves over and "out"'s hull is rebuilt by adding the samples
 * from nearest to farthest (Andrew's chain in increasing x), logging what each addition popped
 * so that removing the farthest sample undoes exactly that addition. Every sample is added,
 * popped and restored at most once: O(1) amortised. The tangent to the whole window is the
 * better of the two hulls' tangents.
 *
 * A line takes at most one sample per column, so the window's samples live in a ring indexed
 * by column (longer than any window), and the stacks, hulls and undo log move 4-byte column
 * numbers instead of samples. Beside each ring slot are the lines (as in the unlimited hull) to
 * the column's neighbour in each hull: in "in", its farther neighbour; in "out", its nearer one.
 * A vertex keeps that neighbour while it is in its hull, and one that "out" popped gets it back
 * when it is restored, so these lines stay valid until the slot's column leaves the window.
 *
 * Most queries never need the window: the tangent to the line's unlimited hull is the answer
 * whenever it lies within the distance (on a 1024^2 DEM at 10 km, 92% of them). So the stacks
 * are kept only while a line needs them: the ring is always written, the first query that
 * needs the window builds "out" from the ring's samples within the distance (as a transfer
 * would), and a line whose window went unused for a ring's length of samples drops its stacks.
 * A build adds at most a ring's length of samples, and stacks are dropped only after that many
 * pushes, so the builds after a line's first are paid for by those pushes: O(1) amortised. The
 * window's content, and so every result, is the same as if it had been kept all along. */

typedef struct window {
  sample *ring;      /* the sample of column col is ring[col & mask] while in the window */
  hull_edge *in_edge;  /* per ring slot: the line to the column's farther neighbour in "in" */
  hull_edge *out_edge; /* per ring slot: the line to the column's nearer neighbour in "out" */
  int mask;          /* ring length - 1, the length a power of two */
  int *in_raw;       /* columns of "in", in arrival order (decreasing) */
  int *in_hull;      /* "in"'s upper hull: columns, farthest first */
  int in_n, in_hn;
  int in_cap;        /* capacity of in_raw and in_hull (in_hn <= in_n) */
  int *out_raw;      /* columns of "out", increasing (last = farthest) */
  int *out_popped;   /* per out_raw entry: how many hull vertices its addition popped */
  double *out_umax;  /* per out_raw entry: the largest u from out_raw[0] to it */
  double *out_x;     /* per out_raw entry: its x (read on eviction without touching the ring) */
  int *out_hull;     /* "out"'s upper hull: columns, increasing */
  int *undo;         /* the popped vertices, a stack */
  int out_n, out_hn, undo_n;
  int out_cap;       /* capacity of the six out arrays (out_hn + undo_n <= out_n: every
                      * sample of "out" is a vertex of its hull or popped once) */
  double out_last_x; /* x of out_raw's last (farthest) sample, when out_n > 0 */
  double in_first_x; /* x of in_raw's first (farthest) sample, when in_n > 0 */
  int newest;        /* column of the newest sample in the ring; -1: none yet */
  int active;        /* the stacks and hulls are kept (else only the ring is written) */
  int idle;          /* samples pushed since a query last needed the window */
} window;

static void window_free(window *w)
{
  free(w->ring);
  free(w->in_edge);
  free(w->out_edge);
  free(w->in_raw);
  free(w->in_hull);
  free(w->out_raw);
  free(w->out_popped);
  free(w->out_umax);
  free(w->out_x);
  free(w->out_hull);
  free(w->undo);
  memset(w, 0, sizeof(*w));
}

/* Grow the n arrays *arrays[k] (element sizes sizes[k]) that share the capacity *cap to hold at
 * least need elements; 0 when out of memory (*cap then still holds for every array). */
static int grow_together(void *const *arrays, const size_t *sizes, int n, int *cap, int need)
{
  int k, least = -1;
  for (k = 0; k < n; ++k) {
    int c = *cap;
    if (!grow(arrays[k], &c, need, sizes[k])) {
      return 0;
    }
    least = least < 0 || c < least ? c : least;
  }
  *cap = least;
  return 1;
}

/* Make room for need entries in the in (out) arrays, need > their capacity; 0 when out of
 * memory. (The callers check the capacity inline: it is almost never short.) */
static int in_reserve(window *w, int need)
{
  void *const arrays[2] = { &w->in_raw, &w->in_hull };
  const size_t sizes[2] = { sizeof(*w->in_raw), sizeof(*w->in_hull) };
  return grow_together(arrays, sizes, 2, &w->in_cap, need);
}

static int out_reserve(window *w, int need)
{
  void *const arrays[6] = { &w->out_raw, &w->out_popped, &w->out_umax,
                            &w->out_x,   &w->out_hull,   &w->undo };
  const size_t sizes[6] = { sizeof(*w->out_raw), sizeof(*w->out_popped), sizeof(*w->out_umax),
                            sizeof(*w->out_x),   sizeof(*w->out_hull),   sizeof(*w->undo) };
  return grow_together(arrays, sizes, 6, &w->out_cap, need);
}

#define SLOT(w, col) ((col) & (w)->mask)
#define RING(w, col) (&(w)->ring[SLOT(w, col)])

static int window_push(window *w, const sample *q, int W)
{
  const int col = (int)q->col;
  int c;
  if (!w->ring) {
    int len = 16;
    while (len < W) {
      len *= 2;
    }
    w->ring = (sample *)malloc((size_t)len * sizeof(sample));
    w->in_edge = (hull_edge *)malloc((size_t)len * sizeof(hull_edge));
    w->out_edge = (hull_edge *)malloc((size_t)len * sizeof(hull_edge));
    if (!w->ring || !w->in_edge || !w->out_edge) {
      return 0;
    }
    w->mask = len - 1;
    for (c = 0; c < len; ++c) {
      w->ring[c].col = -1; /* no sample: window_activate reads the ring by column */
    }
    /* The window never holds more samples than the ring: size its stacks for that at once
     * (the reserves below still guard every push), instead of doubling them up from 16 in
     * every chunk of lines. */
    if ((len > w->in_cap && !in_reserve(w, len)) || (len > w->out_cap && !out_reserve(w, len))) {
      return 0;
    }
  }
  *RING(w, col) = *q;
  w->newest = col;
  if (!w->active) {
    return 1;
  }
  if (++w->idle > w->mask) {
    /* Not needed for a ring's length of samples: stop keeping the stacks. */
    w->in_n = w->in_hn = w->out_n = w->out_hn = w->undo_n = 0;
    w->active = 0;
    return 1;
  }
  if (w->in_n >= w->in_cap && !in_reserve(w, w->in_n + 1)) {
    return 0;
  }
  if (w->in_n == 0) {
    w->in_first_x = q->x;
  }
  w->in_raw[w->in_n++] = col;
  /* the near-pushed hull of "in": the pop rule of hull_push_near */
  while (w->in_hn >= 2) {
    if (q->u >= edge_at(&w->in_edge[SLOT(w, w->in_hull[w->in_hn - 1])], q->x)) {
      --w->in_hn;
    } else {
      break;
    }
  }
  if (w->in_hn >= 1) {
    w->in_edge[SLOT(w, col)] = edge_through(RING(w, w->in_hull[w->in_hn - 1]), q);
  }
  w->in_hull[w->in_hn++] = col;
  return 1;
}

/* Add the count columns cols[0], cols[step], ... (nearest first, each farther than every
 * sample of "out") to "out" and its hull, logging the popped vertices. One loop with the
 * window's counts and arrays in locals (stores through the int arrays could otherwise alias the
 * counts): a build or a transfer adds hundreds of samples at a time. */
AP_NOINLINE static int out_add_far(window *w, const int *cols, int count, int step)
{
  const sample *ring = w->ring;
  const int mask = w->mask;
  int *hull, *undo, *raw, *npop;
  double *umax, *xs;
  hull_edge *edge;
  int n = w->out_n, hn = w->out_hn, un = w->undo_n, k;
  if (count <= 0) {
    return 1;
  }
  if (n + count > w->out_cap && !out_reserve(w, n + count)) {
    return 0;
  }
  hull = w->out_hull;
  undo = w->undo;
  raw = w->out_raw;
  npop = w->out_popped;
  umax = w->out_umax;
  xs = w->out_x;
  edge = w->out_edge;
  for (k = 0; k < count; ++k) {
    const int col = cols[(ptrdiff_t)k * step];
    const sample *q = &ring[col & mask];
    const double qu = q->u, qx = q->x;
    int popped = 0;
    while (hn >= 2) {
      /* The last vertex b is on or below the chord from the one before it (a) to q, i.e. q is
       * on or above the line through a and b: b can never be a tangent point from the near
       * side. */
      if (qu >= edge_at(&edge[hull[hn - 1] & mask], qx)) {
        undo[un++] = hull[--hn];
        ++popped;
      } else {
        break;
      }
    }
    if (hn >= 1) {
      edge[col & mask] = edge_through(&ring[hull[hn - 1] & mask], q);
    }
    hull[hn++] = col;
    raw[n] = col;
    npop[n] = popped;
    umax[n] = (n > 0 && umax[n - 1] > qu) ? umax[n - 1] : qu;
    xs[n] = qx;
    ++n;
  }
  w->out_n = n;
  w->out_hn = hn;
  w->undo_n = un;
  w->out_last_x = xs[n - 1];
  return 1;
}

/* Remove the farthest sample of "out" (the last one added) and restore what it popped. */
static void out_remove_far(window *w)
{
  int k = w->out_popped[--w->out_n];
  --w->out_hn; /* the farthest sample is always the hull's last vertex */
  while (k-- > 0) {
    w->out_hull[w->out_hn++] = w->undo[--w->undo_n];
  }
  if (w->out_n > 0) {
    w->out_last_x = w->out_x[w->out_n - 1];
  }
}

/* Drop every sample farther than xlimit. The farthest distances are cached in the window, so
 * that the common case (nothing to drop) reads no sample: the lines' rings together are far
 * larger than the caches. */
static int window_evict(window *w, double xlimit)
{
  for (;;) {
    if (w->out_n > 0) {
      if (w->out_last_x > xlimit) {
        out_remove_far(w);
        continue;
      }
      return 1;
    }
    if (w->in_n > 0 && w->in_first_x > xlimit) {
      /* Move all of "in" to "out", nearest first; "in" starts afresh. */
      if (!out_add_far(w, w->in_raw + w->in_n - 1, w->in_n, -1)) {
        return 0;
      }
      w->in_n = 0;
      w->in_hn = 0;
      continue;
    }
    return 1;
  }
}

/* Start keeping the stacks: every sample in the ring within xlimit goes to "out", nearest
 * first, exactly as a transfer from "in" would put it. (The columns are listed in in_raw,
 * which is empty while the stacks are not kept.) */
static int window_activate(window *w, double xlimit)
{
  int c, count = 0;
  w->active = 1;
  w->idle = 0;
  if (!w->ring || w->newest < 0) {
    return 1;
  }
  for (c = w->newest; c <= w->newest + w->mask; ++c) {
    const sample *q = RING(w, c);
    if (q->col != c) {
      continue; /* no sample on that column (nodata, or the line was outside the grid) */
    }
    if (q->x > xlimit) {
      break;
    }
    w->in_raw[count++] = c; /* (in_raw holds a ring's length) */
  }
  return out_add_far(w, w->in_raw, count, 1);
}

/* The vertex of a hull of columns with the largest slope from (xq, uq), by bisection on the
 * same boundary as hull_tangent; NULL when empty. ed holds each vertex's line to its previous
 * vertex in h; the slope rises from h[k] to h[k + 1] when the query point lies below that line
 * if h runs farthest first ("in"), above it if nearest first ("out"). */
static const sample *ring_tangent(const window *w, const int *h, int n, const hull_edge *ed,
                                  int far_first, double xq, double uq, double *slope)
{
  int lo = 0, m = n - 1; /* the first index whose slope is not below the next one's, in
                          * about log2(n) halvings written as selects; GCC 12 still compiles
                          * them as a branch (mask arithmetic instead gave no measurable gain) */
  const sample *v;
  if (n == 0) {
    return NULL;
  }
  while (m > 0) {
    const int half = m >> 1, mid = lo + half;
    const double line = edge_at(&ed[SLOT(w, h[mid + 1])], xq);
    const int rising = far_first ? uq < line : uq > line;
    lo = rising ? mid + 1 : lo;
    m = rising ? m - half - 1 : half;
  }
  v = RING(w, h[lo]);
  *slope = (v->u - uq) / (v->x - xq);
  return v;
}

/* The tangent vertex of the whole window (the better of the two hulls'), or NULL. "out" is
 * searched only if a bound on its slopes (its highest sample at its nearest distance, or at
 * its farthest when below the query) can beat the tangent to "in". */
static const sample *window_tangent(const window *w, double xq, double uq)
{
  double sa = -INFINITY, sb = -INFINITY;
  const sample *a = ring_tangent(w, w->in_hull, w->in_hn, w->in_edge, 1, xq, uq, &sa);
  const sample *b = NULL;
  if (w->out_hn > 0) {
    const double rise = w->out_umax[w->out_n - 1] - uq;
    const double d = rise >= 0.0 ? RING(w, w->out_raw[0])->x - xq
                                 : RING(w, w->out_raw[w->out_n - 1])->x - xq;
    if (!a || rise / d > sa) {
      b = ring_tangent(w, w->out_hull, w->out_hn, w->out_edge, 0, xq, uq, &sb);
    }
  }
  if (!a) {
    return b;
  }
  if (!b) {
    return a;
  }
  return sa >= sb ? a : b;
}

typedef struct patch_rec {
  long dp, ds;       /* the patch's lower corner relative to the ray's start node (view) */
  int first;         /* the first patch of the ray (it starts at the cell's own node) */
  float t1, t2;      /* the ray's segment on the patch (m); t1 = 0 on the first patch */
  float dt, inv_t1, inv_t2, t1x2; /* t2 - t1; 1/t1 (0 on the first patch); 1/t2; 2 t1 */
  float u1, v1, u1v1; /* where the ray enters the patch (the patch's coordinates); their product */
  float wa, wb, wk, wab; /* a, b (the ray's columns and rows per metre), k = u1 b + v1 a, a b */
  int ea, eb;        /* where the ray leaves the patch, on the grid line between corners ea
                      * and eb (0: z00, 1: z10, 2: z01, 3: z11) at ew of the way to eb; at a
                      * corner ea = eb, ew = 0; -1 inside the patch (the pattern's end) */
  float ew;
} patch_rec;

typedef struct pattern {
  double m, len;     /* the ray: lateral shift per column, ground length per column (m) */
  double lp, ls;     /* the point at the search distance L: L / len columns, m L / len rows */
  size_t first, n;   /* its records in the pool */
} pattern;

/* ---------------------------------------------------------------------------------------- */
/* State */

static int build_pattern(ap_horizon *hz, double m, double len, double tmax);
static int fm_tiles_init(ap_horizon *hz);
static int fm_tiles_alloc(const ap_horizon *hz, float *t[2]);
static void fm_coarsen(const ap_horizon *hz, float *fine, float *coarse);
static int fm_shore_init(ap_horizon *hz);
static int fm_steps_init(ap_horizon *hz);
static void fm_side_max_init(ap_horizon *hz);
struct fm_step;
static void fm_step_set(struct fm_step *st, double sh, double t, double c);


#define AP_SIDE_ROWS 8 /* rows next to a side with their own bound (sweep_side_rows) */
#define AP_VOID_HIT 1u  /* the sweep's rare cases of a cell (see sweep) */
#define AP_FAILED 2u
#define AP_VOID_LINE 4u

struct ap_horizon {
  ap_horizon_grid g;
  ap_horizon_params p;
  ap_sky_products out;
  size_t nx, ny;
  double *dxr, *dyr;    /* per-row cell sizes (m) */
  float *zt;            /* transposed elevations: zt[i * ny + j] = z(i, j) */
  size_t *data_span;    /* per grid row j: its first column with data and one past its last
                         * ([2 j], [2 j + 1]; 0, 0 when none); then per grid column i, rows
                         * ([2 (ny + i)], ...): nodata cells outside never need a search */
  unsigned char *holes; /* DEMs with nodata: per grid row j ([j]) and column i ([ny + i]), 1
                         * where it has nodata between its first and last cells with data */
  size_t *void_before;  /* DEMs with nodata: the grid rows before row j that have a nodata
                         * cell ([j], j <= ny), then the columns before column i ([ny + 1 + i]) */
  float *grad;          /* Horn gradient (dz/dx east, dz/dy north) per cell of the region,
                         * in the outputs' order */
  float *slope;         /* prepared sector, per cell: the near field's slope (tangent of the
                         * elevation angle) after ap_horizon_near_field, the terrain horizon's
                         * after ap_horizon_sweep */
  unsigned char *edge;  /* prepared sector: 1 where the search reached the DEM edge */
  float *bsum;          /* bent-normal sums when out.bent_normal is NULL (region cells) */
  float zmax;
  int has_nodata;       /* some cell is NaN: the near field's exit edges (near_column) and
                         * the sweep's rare cases (sweep) are needed */
  size_t ri0, ri1, rj0, rj1, rnx; /* the region: grid columns [ri0, ri1), rows [rj0, rj1) */
  int first;            /* the prepared sector is the first: its ap_horizon_accumulate
                         * computes grad and starts the sums (create leaves both unwritten,
                         * so that their memory is first touched by the parallel phase) */

  /* per-row cell sizes: the lattice of lines of the larger DEM (p.whole_*, or the grid's own
   * rows), see ap_horizon_prepare */
  int lattice;            /* the grid has per-row cell sizes */
  double *psi;            /* nw values: Ψ at the larger DEM's rows, the sum of dy/dx */
  double *psi_inv;        /* nw - 1 values: 1 / (psi[j + 1] - psi[j]) */
  size_t nw;
  long ocol, orow;        /* this grid's cell (0, 0) in the larger DEM */
  double wdx_c, wdy_c;    /* the larger DEM's centre row cell sizes (m) */
  double wdx_min, wdy_min; /* its smallest */
  double *ycum;           /* ny values: the grid's south-north distance (m) from row 0 */
  float side_max[2][AP_SIDE_ROWS]; /* the highest cell (NaN ignored) at most d rows from
                                    * row 0 ([0][d]) and from row ny - 1 ([1][d]) */

  /* the prepared sector */
  int d;
  double phi;             /* grid azimuth (rad) */
  int xmajor, flip;       /* view: p along columns (xmajor) or rows; p reversed (flip) */
  size_t np, ns;          /* view sizes */
  size_t vp0, vp1, vs0, vs1; /* the region in the view: p in [vp0, vp1), s in [vs0, vs1) */
  double c;               /* curvature coefficient (1/m) */
  double *m_row, *len_row; /* per grid row: lateral shift per p step, ground length per step */
  double *cum_m, *cum_len; /* row-major views: prefix sums over p of the step shift / length */
  const float **colp;     /* view column p as a contiguous array of ns elevations */
  int parallel;           /* all lines shift alike at each p (no per-row bending) */
  int side;               /* parallel lines: the sign of their shift with p (0: none), the
                           * side rays leave the grid through (s < 0 or s > ns - 1) */
  size_t side_cols;       /* then the columns over which a ray crosses one view row, plus 1 */
  long kmin;              /* line k = kmin + index starts at s = k + phase on p = np - 1
                           * (per-row sizes: see lat_off) */
  double phase;           /* in [0, 1): puts the lines on the lattice of the larger DEM */
  double *lat_off;        /* per-row sizes, per view position p: line k lies at column
                           * k + lat_off[p] of the larger DEM (row-major views) or at the row
                           * where Ψ = sigma k + lat_off[p] (x-major views) */
  double sigma;           /* x-major, per-row sizes: Psi between neighbouring lines */
  int row_lines;          /* x-major, per-row sizes, along the rows (|cos phi| <= 1e-12): line
                           * k is the larger DEM's row k, and every ray keeps to its row */
  size_t nlines;
  /* near-field patch patterns (see build_pattern): a pool of records, the patterns, and which
   * pattern serves each view position (indexed by p for row-major views, s for x-major) */
  patch_rec *recs;
  size_t nrecs, caprecs;
  pattern *pats;
  size_t npats, cappats;
  int *pat_of;
  double shortest;        /* the shortest view step (m): len_row's minimum */
  int by_rows;            /* x-major view whose rows take different patterns (per-row cell
                           * sizes): the near field runs row by row (see near_rows) */
  int march;              /* the search distance lies within march_columns: the near field
                           * covers it all and the sweep has nothing to do; far_march below
                           * likewise */
  /* the far march (see far_march_column): per-sector steps 0..fm_kmax, and the elevations'
   * tile maxima (grid order, NaN ignored, -inf for a tile without data) of fm_tile[0]
   * (AP_FM_FINE cells square) and fm_tile[1] (AP_FM_COARSE), made once by ap_horizon_create
   * when a far march can happen */
  int far_march;
  int shore_sweep;        /* swept sector of a DEM with nodata: ap_horizon_accumulate adds
                           * the crossings beside nodata (far_shore_column, far_shore_row) to
                           * the sweep's horizons, along fm (constant cell sizes) or the
                           * rays' own steps (lattice_steps_*, at most fm_kmax + 1) */
  int near_field;         /* the prepared sector's K: p.near_field, or when that is 0 the
                           * automatic value for the sector's search (see prepare) */
  struct fm_step *fm;
  long fm_kmax;
  float *fm_tile[2];
  float *fm_shore[2];     /* DEMs with nodata: the same tiles' maxima of the cells with data
                           * beside nodata (see far_shore_column), -inf where none; else NULL */
  size_t fm_tnx[2];
  float fm_eps;           /* added to a tile maximum: covers the interpolation's rounding */
  float fm_side_max;      /* the highest cell of the view's side the rays leave through */

  /* p.scale_metric: a copy, its nodes divided by dx0², dx0 dy0, dy0² (so 1, 0, 1 where the
   * cells measure dx0 x dy0); its square root S and that one's inverse at every node (xx, xy,
   * yy each); and the prepared sector's 1 / ρ and weight ω at every node */
  double *metric;
  double *sroot;
  double *sinv;
  float *inv_rho;
  float *weight;
  size_t *scale_col;      /* per grid column: its lattice cell's first node (scale_node) */
  float *scale_frac;      /* and the fraction towards the next */
};

/* Cell sizes of row j. */
static double row_dx(const ap_horizon_grid *g, size_t j)
{
  return g->dx ? g->dx[j] : g->dx0;
}

static double row_dy(const ap_horizon_grid *g, size_t j)
{
  return g->dy ? g->dy[j] : g->dy0;
}

static int positive_finite(double v)
{
  return isfinite(v) && v > 0.0;
}

void ap_horizon_params_init(ap_horizon_params *p)
{
  if (!p) {
    return;
  }
  p->directions = 32;
  p->azimuth_offset = 0.0;
  p->max_distance = INFINITY;
  p->curvature = 1;
  p->refraction = 0.13;
  p->radius_meridian = 6371000.0;
  p->radius_normal = 6371000.0;
  p->near_field = 0;
  p->march_columns = 64;
  p->far_march_columns = 1024;
  p->origin_col = 0;
  p->origin_row = 0;
  p->whole_dx = NULL;
  p->whole_dy = NULL;
  p->whole_rows = 0;
  p->region_i0 = p->region_j0 = p->region_nx = p->region_ny = 0;
  p->scale_metric = NULL;
  p->scale_cols = p->scale_rows = 0;
  p->scale_span_cols = p->scale_span_rows = 0.0;
}

/* p.scale_metric's lattice: sizes and spans in range, every node a positive definite metric */
static int scale_metric_valid(const ap_horizon_params *p)
{
  size_t k;
  if (p->scale_cols < 2 || p->scale_cols > 1025 || p->scale_rows < 2 ||
      p->scale_rows > 1025 || !positive_finite(p->scale_span_cols) ||
      !positive_finite(p->scale_span_rows)) {
    return 0;
  }
  for (k = 0; k < p->scale_cols * p->scale_rows; ++k) {
    const double *m = p->scale_metric + 3 * k;
    if (!positive_finite(m[0]) || !positive_finite(m[2]) || !isfinite(m[1]) ||
        !(m[0] * m[2] - m[1] * m[1] > 0.0)) {
      return 0;
    }
  }
  return 1;
}

/* ap_horizon_validate, also giving the elevations' statistics when AP_OK. */
static ap_status validate(const ap_horizon_grid *g, const ap_horizon_params *p,
                          ap_grid_stats *stats)
{
  ap_status st;
  size_t j, cells;
  if (!g || !p) {
    return AP_ERR_NULL_POINTER;
  }
  st = ap_grid_validate(&g->z, 2, 2);
  if (st != AP_OK) {
    return st;
  }
  /* (the sweep counts a line's columns and its rings in int: a side of at most 10^9 + 1 cells
   * keeps them below 2^30) */
  if (ap_size_mul(g->z.nx, g->z.ny, &cells) != AP_OK || cells > SIZE_MAX / 32 ||
      g->z.nx > (size_t)AP_HORIZON_MAX_ORIGIN + 1 || g->z.ny > (size_t)AP_HORIZON_MAX_ORIGIN + 1) {
    return AP_ERR_SIZE_OVERFLOW;
  }
  if (p->directions < 4 || p->directions > 360 || !(p->max_distance > 0.0) ||
      !(p->refraction >= 0.0 && p->refraction < 1.0) || !positive_finite(p->radius_meridian) ||
      !positive_finite(p->radius_normal) || p->near_field < 0 || p->near_field > 64 ||
      p->march_columns < 0 || p->march_columns > 64 || p->far_march_columns < 0 ||
      p->far_march_columns > 65536 || !isfinite(p->azimuth_offset) ||
      p->origin_col < -AP_HORIZON_MAX_ORIGIN || p->origin_col > AP_HORIZON_MAX_ORIGIN ||
      p->origin_row < -AP_HORIZON_MAX_ORIGIN || p->origin_row > AP_HORIZON_MAX_ORIGIN) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  if ((!g->dx && !positive_finite(g->dx0)) || (!g->dy && !positive_finite(g->dy0))) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  if (p->region_i0 || p->region_j0 || p->region_nx || p->region_ny) {
    if (p->region_nx == 0 || p->region_ny == 0 || p->region_i0 >= g->z.nx ||
        p->region_nx > g->z.nx - p->region_i0 || p->region_j0 >= g->z.ny ||
        p->region_ny > g->z.ny - p->region_j0) {
      return AP_ERR_INVALID_ARGUMENT;
    }
  }
  for (j = 0; j < g->z.ny; ++j) {
    if (!positive_finite(row_dx(g, j)) || !positive_finite(row_dy(g, j))) {
      return AP_ERR_INVALID_ARGUMENT;
    }
  }
  if ((p->whole_dx == NULL) != (p->whole_dy == NULL)) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  if (p->scale_metric && (g->dx || g->dy || !scale_metric_valid(p))) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  if (p->whole_dx && (g->dx || g->dy)) {
    if (p->origin_row < 0 || p->whole_rows < g->z.ny ||
        (size_t)p->origin_row > p->whole_rows - g->z.ny) {
      return AP_ERR_INVALID_ARGUMENT;
    }
    for (j = 0; j < p->whole_rows; ++j) {
      if (!positive_finite(p->whole_dx[j]) || !positive_finite(p->whole_dy[j])) {
        return AP_ERR_INVALID_ARGUMENT;
      }
    }
    for (j = 0; j < g->z.ny; ++j) { /* the grid's rows are those of the larger DEM */
      if (row_dx(g, j) != p->whole_dx[(size_t)p->origin_row + j] ||
          row_dy(g, j) != p->whole_dy[(size_t)p->origin_row + j]) {
        return AP_ERR_INVALID_ARGUMENT;
      }
    }
  }
  st = ap_grid_stats_compute(&g->z, stats);
  if (st != AP_OK) {
    return st;
  }
  if (stats->valid == 0) {
    return AP_ERR_ALL_NODATA;
  }
  return isfinite(stats->min) && isfinite(stats->max) ? AP_OK : AP_ERR_OUT_OF_RANGE;
}

ap_status ap_horizon_validate(const ap_horizon_grid *g, const ap_horizon_params *p)
{
  ap_grid_stats stats;
  return validate(g, p, &stats);
}

/* Grid row j of the elevations (row_stride may be negative). */
static const float *grid_row(const ap_horizon *hz, long j)
{
  return hz->g.z.z + (ptrdiff_t)j * hz->g.z.row_stride;
}

static float zat(const ap_horizon *hz, size_t i, size_t j)
{
  return grid_row(hz, (long)j)[i];
}

/* One difference along a row or column of the 3 x 3 window: (after - before) / (2 h) with both
 * neighbours, one-sided with the middle and one neighbour, none otherwise. Returns 1 if any. */
static int difference(double before, double middle, double after, double h, double *out)
{
  if (!isnan(before) && !isnan(after)) {
    *out = (after - before) / (2.0 * h);
  } else if (!isnan(after) && !isnan(middle)) {
    *out = (after - middle) / h;
  } else if (!isnan(before) && !isnan(middle)) {
    *out = (middle - before) / h;
  } else {
    return 0;
  }
  return 1;
}

/* Elevation gradient (dz/dx east, dz/dy north) of cell (i, j) by Horn's (1981) weighted
 * differences, the method of gdaldem slope:
 *   dz/dx = ((c + 2f + i) - (a + 2d + g)) / (8 dx),  dz/dy = ((a + 2b + c) - (g + 2h + i)) / (8 dy)
 * (a b c / d e f / g h i, north row first), written as the 1-2-1 weighted mean of the three
 * rows' (columns') central differences. Where the window is cut by the DEM edge or nodata, the
 * mean runs over the differences that exist, one-sided where needed — exact on a plane, and
 * Horn's formula when all nine cells exist. No difference at all gives 0. */
static void horn_gradient(const ap_horizon *hz, size_t i, size_t j, float out[2])
{
  double v[3][3]; /* v[dj + 1][di + 1], NaN outside or nodata */
  double sx = 0.0, wx = 0.0, sy = 0.0, wy = 0.0, g;
  int di, dj, k;
  static const double weight[3] = { 1.0, 2.0, 1.0 };
  for (dj = -1; dj <= 1; ++dj) {
    for (di = -1; di <= 1; ++di) {
      const ptrdiff_t ii = (ptrdiff_t)i + di, jj = (ptrdiff_t)j + dj;
      v[dj + 1][di + 1] = (ii >= 0 && jj >= 0 && (size_t)ii < hz->nx && (size_t)jj < hz->ny)
                            ? (double)zat(hz, (size_t)ii, (size_t)jj)
                            : NAN;
    }
  }
  for (k = 0; k < 3; ++k) {
    if (difference(v[k][0], v[k][1], v[k][2], hz->dxr[j], &g)) {
      sx += weight[k] * g;
      wx += weight[k];
    }
    if (difference(v[0][k], v[1][k], v[2][k], hz->dyr[j], &g)) {
      sy += weight[k] * g;
      wy += weight[k];
    }
  }
  out[0] = wx > 0.0 ? (float)(sx / wx) : 0.0f;
  out[1] = wy > 0.0 ? (float)(sy / wy) : 0.0f;
}

/* zt, the transposed elevations, in blocks of 32 x 32 cells (a column at a time would write
 * each cache line 16 times, a whole column apart). */
static void transpose(ap_horizon *hz)
{
  enum { B = 32 };
  size_t i0, j0, i, j;
  for (j0 = 0; j0 < hz->ny; j0 += B) {
    const size_t j1 = hz->ny - j0 < B ? hz->ny : j0 + B;
    for (i0 = 0; i0 < hz->nx; i0 += B) {
      const size_t i1 = hz->nx - i0 < B ? hz->nx : i0 + B;
      for (j = j0; j < j1; ++j) {
        const float *row = grid_row(hz, (long)j);
        for (i = i0; i < i1; ++i) {
          hz->zt[i * hz->ny + j] = row[i];
        }
      }
    }
  }
}

/* The first and one past the last non-NaN of v[0 .. n) into span[0], span[1] (0, 0 if none). */
static void data_span(const float *v, size_t n, size_t *span)
{
  size_t a = 0, b = n;
  while (a < n && isnan(v[a])) {
    ++a;
  }
  while (b > a && isnan(v[b - 1])) {
    --b;
  }
  span[0] = a < b ? a : 0;
  span[1] = a < b ? b : 0;
}

/* Whether v[a .. b) has a NaN. */
static unsigned char has_hole(const float *v, size_t a, size_t b)
{
  for (; a < b; ++a) {
    if (isnan(v[a])) {
      return 1;
    }
  }
  return 0;
}

/* Whether grid row g (g < ny) or grid column g - ny has data in every cell of [a, b]. */
AP_INLINE int all_data(const ap_horizon *hz, size_t g, long a, long b)
{
  const size_t *span = hz->data_span + 2 * g;
  return !hz->holes[g] && a >= (long)span[0] && b < (long)span[1];
}

/* hz->data_span of every grid row and column, and for DEMs with nodata hz->holes; 0 when out
 * of memory. */
static int data_spans_init(ap_horizon *hz)
{
  size_t i, j;
  size_t *sp;
  hz->data_span = sp = (size_t *)malloc(2 * (hz->ny + hz->nx) * sizeof(size_t));
  if (hz->has_nodata) { /* (without nodata no line has holes, nor is all_data asked) */
    hz->holes = (unsigned char *)malloc(hz->ny + hz->nx);
  }
  if (hz->has_nodata) {
    hz->void_before = (size_t *)malloc((hz->ny + hz->nx + 2) * sizeof(size_t));
  }
  if (!hz->data_span || (hz->has_nodata && (!hz->holes || !hz->void_before))) {
    return 0;
  }
  for (j = 0; j < hz->ny; ++j) {
    const float *v = grid_row(hz, (long)j);
    data_span(v, hz->nx, sp + 2 * j);
    if (hz->holes) {
      hz->holes[j] = has_hole(v, sp[2 * j], sp[2 * j + 1]);
    }
  }
  for (i = 0; i < hz->nx; ++i) {
    const float *v = hz->zt + i * hz->ny;
    const size_t g = hz->ny + i;
    data_span(v, hz->ny, sp + 2 * g);
    if (hz->holes) {
      hz->holes[g] = has_hole(v, sp[2 * g], sp[2 * g + 1]);
    }
  }
  if (hz->void_before) {
    size_t *vb = hz->void_before, g = 0;
    for (i = 0; i < 2; ++i) { /* (rows, then columns) */
      const size_t n = i ? hz->nx : hz->ny, len = i ? hz->ny : hz->nx; /* (lines, their cells) */
      size_t *before = vb + (i ? hz->ny + 1 : 0), k;
      before[0] = 0;
      for (k = 0; k < n; ++k, ++g) {
        before[k + 1] = before[k] + (size_t)!all_data(hz, g, 0, (long)len - 1);
      }
    }
  }
  return 1;
}

/* DEMs with nodata: whether some cell of grid rows [b[0], b[1]] and some cell of grid columns
 * [b[2], b[3]] (each clamped to the grid) are nodata; 0 guarantees that no cell of that box
 * is. (Two look-ups of void_before.) */
AP_INLINE int box_may_void(const ap_horizon *hz, const long b[4])
{
#if defined(AP_HORIZON_NO_VOID_SKIP)
  /* (a test build: every box may, which must change no result; Kernels-void-skip-equality) */
  (void)hz;
  (void)b;
  return 1;
#else
  const size_t *rows = hz->void_before, *cols = hz->void_before + hz->ny + 1;
  long r0 = b[0], r1 = b[1], c0 = b[2], c1 = b[3];
  r0 = r0 < 0 ? 0 : r0;
  c0 = c0 < 0 ? 0 : c0;
  r1 = r1 > (long)hz->ny - 1 ? (long)hz->ny - 1 : r1;
  c1 = c1 > (long)hz->nx - 1 ? (long)hz->nx - 1 : c1;
  return r0 <= r1 && c0 <= c1 && rows[r1 + 1] > rows[r0] && cols[c1 + 1] > cols[c0];
#endif
}

static void free_sector(ap_horizon *hz)
{
  free(hz->m_row);
  free(hz->len_row);
  free(hz->cum_m);
  free(hz->cum_len);
  free(hz->lat_off);
  hz->lat_off = NULL;
  free((void *)hz->colp);
  hz->colp = NULL;
  /* (the patterns' records and the patterns keep their memory for the next sector: a tall
   * lat/lon DEM has a pattern or more per row, which growing again from nothing in every
   * sector copied over and over) */
  hz->nrecs = hz->npats = 0;
  free(hz->pat_of);
  free(hz->fm);
  hz->fm = NULL;
  hz->far_march = 0;
  hz->m_row = hz->len_row = hz->cum_m = hz->cum_len = NULL;
  hz->pat_of = NULL;
}

void ap_horizon_destroy(ap_horizon *hz)
{
  if (!hz) {
    return;
  }
  free_sector(hz);
  free(hz->recs);
  free(hz->pats);
  free(hz->dxr);
  free(hz->dyr);
  free(hz->psi);
  free(hz->psi_inv);
  free(hz->ycum);
  free(hz->zt);
  free(hz->data_span);
  free(hz->holes);
  free(hz->void_before);
  free(hz->grad);
  free(hz->slope);
  free(hz->edge);
  free(hz->bsum);
  free(hz->fm_tile[0]);
  free(hz->fm_tile[1]);
  free(hz->fm_shore[0]);
  free(hz->fm_shore[1]);
  free(hz->metric);
  free(hz->sroot);
  free(hz->sinv);
  free(hz->inv_rho);
  free(hz->weight);
  free(hz->scale_col);
  free(hz->scale_frac);
  free(hz);
}

/* Per-row cell sizes: Ψ at the rows of the larger DEM (p.whole_*, else the grid's own), its
 * centre row's and smallest cell sizes, and where the grid sits in it. 0 when out of memory. */
static int lattice_init(ap_horizon *hz)
{
  const int whole = hz->p.whole_dx != NULL;
  const double *wdx = whole ? hz->p.whole_dx : hz->dxr, *wdy = whole ? hz->p.whole_dy : hz->dyr;
  size_t j;
  hz->nw = whole ? hz->p.whole_rows : hz->ny;
  hz->ocol = whole ? hz->p.origin_col : 0;
  hz->orow = whole ? hz->p.origin_row : 0;
  hz->psi = (double *)malloc(hz->nw * sizeof(double));
  hz->psi_inv = (double *)malloc((hz->nw - 1) * sizeof(double));
  if (!hz->psi || !hz->psi_inv) {
    return 0;
  }
  /* (for sweep_side_rows: distances along the rows, and the highest cells near each side) */
  hz->ycum = (double *)malloc(hz->ny * sizeof(double));
  if (!hz->ycum) {
    return 0;
  }
  hz->ycum[0] = 0.0;
  for (j = 1; j < hz->ny; ++j) {
    hz->ycum[j] = hz->ycum[j - 1] + 0.5 * (hz->dyr[j - 1] + hz->dyr[j]);
  }
  for (j = 0; j < AP_SIDE_ROWS; ++j) {
    int side;
    for (side = 0; side < 2; ++side) {
      float *m = &hz->side_max[side][j];
      *m = j > 0 ? m[-1] : -INFINITY;
      if (j < hz->ny) {
        const float *zr = grid_row(hz, side ? (long)(hz->ny - 1 - j) : (long)j);
        size_t q;
        for (q = 0; q < hz->nx; ++q) {
          *m = zr[q] > *m ? zr[q] : *m;
        }
      }
    }
  }
  hz->psi[0] = 0.0;
  hz->wdx_min = wdx[0];
  hz->wdy_min = wdy[0];
  for (j = 1; j < hz->nw; ++j) {
    hz->psi[j] = hz->psi[j - 1] + 0.5 * (wdy[j - 1] / wdx[j - 1] + wdy[j] / wdx[j]);
    hz->wdx_min = fmin(hz->wdx_min, wdx[j]);
    hz->wdy_min = fmin(hz->wdy_min, wdy[j]);
  }
  for (j = 0; j + 1 < hz->nw; ++j) {
    hz->psi_inv[j] = 1.0 / (hz->psi[j + 1] - hz->psi[j]);
  }
  hz->wdx_c = wdx[hz->nw / 2];
  hz->wdy_c = wdy[hz->nw / 2];
  return 1;
}

/* Keep in step with the allocations of ap_horizon_create below. */
size_t ap_horizon_state_bytes_per_cell(int diffuse_sky_factor, int bent_normal)
{
  const size_t state = sizeof(float)   /* zt */
                       + 2 * sizeof(float) /* grad */
                       + sizeof(float)     /* slope: one sector's horizons */
                       + 1;                /* edge */
  return state + (diffuse_sky_factor && !bent_normal ? 3 * sizeof(float) : 0); /* bsum */
}

void ap_horizon_metric_root(const double m[3], double dx0, double dy0, double s[3])
{
  /* S = sqrt(r) = (r + q I) / t, q = sqrt(det r), t = sqrt(trace r + 2 q) */
  const double r0 = m[0] / (dx0 * dx0), r1 = m[1] / (dx0 * dy0), r2 = m[2] / (dy0 * dy0);
  const double q = sqrt(r0 * r2 - r1 * r1), t = sqrt(r0 + r2 + 2.0 * q);
  s[0] = (r0 + q) / t;
  s[1] = r1 / t;
  s[2] = (r2 + q) / t;
}

/* The lattice cell of p.scale_metric around grid column i (axis 0) or row i (axis 1): its
 * first node and the fraction towards the next. From the larger DEM's index alone, so a piece
 * of it interpolates as the whole does. */
static size_t scale_node(const ap_horizon *hz, int axis, size_t i, float *t)
{
  const size_t n = axis ? hz->p.scale_rows : hz->p.scale_cols;
  const double span = axis ? hz->p.scale_span_rows : hz->p.scale_span_cols;
  const long whole = (long)i + (axis ? hz->p.origin_row : hz->p.origin_col);
  const double f = fmin(fmax((double)whole * (double)(n - 1) / span, 0.0), (double)(n - 1));
  size_t a = (size_t)f;
  a = a > n - 2 ? n - 2 : a;
  *t = (float)(f - (double)a);
  return a;
}

/* p.scale_metric: copied and relative to dx0, dy0 (hz->metric), its square root and that
 * one's inverse (hz->sroot, hz->sinv), with room for the sector's 1 / rho and weight
 * (hz->inv_rho, hz->weight), and every grid column's place between the nodes. 0 when out of
 * memory. */
static int scale_metric_init(ap_horizon *hz)
{
  const size_t nodes = hz->p.scale_cols * hz->p.scale_rows;
  const double dx0 = hz->g.dx0, dy0 = hz->g.dy0;
  size_t k;
  hz->metric = (double *)malloc(3 * nodes * sizeof(double));
  hz->sroot = (double *)malloc(3 * nodes * sizeof(double));
  hz->sinv = (double *)malloc(3 * nodes * sizeof(double));
  hz->inv_rho = (float *)malloc(nodes * sizeof(float));
  hz->weight = (float *)malloc(nodes * sizeof(float));
  hz->scale_col = (size_t *)malloc(hz->nx * sizeof(size_t));
  hz->scale_frac = (float *)malloc(hz->nx * sizeof(float));
  if (!hz->metric || !hz->sroot || !hz->sinv || !hz->inv_rho || !hz->weight ||
      !hz->scale_col || !hz->scale_frac) {
    return 0;
  }
  for (k = 0; k < nodes; ++k) {
    const double *m = hz->p.scale_metric + 3 * k;
    double *r = hz->metric + 3 * k, *v = hz->sinv + 3 * k, *sr = hz->sroot + 3 * k, det;
    r[0] = m[0] / (dx0 * dx0);
    r[1] = m[1] / (dx0 * dy0);
    r[2] = m[2] / (dy0 * dy0);
    ap_horizon_metric_root(m, dx0, dy0, sr);
    det = sr[0] * sr[2] - sr[1] * sr[1];
    v[0] = sr[2] / det;
    v[1] = -sr[1] / det;
    v[2] = sr[0] / det;
  }
  for (k = 0; k < hz->nx; ++k) {
    hz->scale_col[k] = scale_node(hz, 0, k, hz->scale_frac + k);
  }
  hz->p.scale_metric = NULL; /* (read here only) */
  return 1;
}

/* A value of the prepared sector given at the lattice's nodes (hz->inv_rho, hz->weight) for
 * grid cells [i0, i0 + n) of grid row j: between the lattice's rows, then between its
 * columns. */
static void scale_block(const ap_horizon *hz, const float *nodes, size_t j, size_t i0, size_t n,
                        float *out)
{
  enum { MAX_NODES = 1025 };
  const size_t cols = hz->p.scale_cols;
  float tb, row[MAX_NODES];
  const size_t b = scale_node(hz, 1, j, &tb);
  const float *r0 = nodes + b * cols, *r1 = r0 + cols;
  const size_t a0 = hz->scale_col[i0], a1 = hz->scale_col[i0 + n - 1] + 1;
  size_t a, k;
  for (a = a0; a <= a1; ++a) {
    row[a] = r0[a] + tb * (r1[a] - r0[a]);
  }
  for (k = 0; k < n;) {
    /* the cells between nodes c and c + 1: a loop without gathers */
    const size_t c = hz->scale_col[i0 + k];
    const float lo = row[c], step = row[c + 1] - row[c];
    const float *f = hz->scale_frac + i0;
    size_t e = k + 1;
    while (e < n && hz->scale_col[i0 + e] == c) {
      ++e;
    }
    for (; k < e; ++k) {
      out[k] = lo + f[k] * step;
    }
  }
}

/* The vector xy times a 2 x 2 symmetric matrix given at the lattice's nodes (xx, xy, yy:
 * hz->sroot, hz->sinv), at grid column i of a row between the lattice's rows b and b + 1 (at
 * fraction tb; scale_node), bilinear between the nodes. */
static void scale_matrix_times(const ap_horizon *hz, const double *nodes, size_t b, double tb,
                               size_t i, double xy[2])
{
  const size_t a = hz->scale_col[i];
  const double ta = hz->scale_frac[i];
  const double *n0 = nodes + 3 * (b * hz->p.scale_cols + a), *n1 = n0 + 3 * hz->p.scale_cols;
  double v[3], x;
  int c;
  for (c = 0; c < 3; ++c) {
    const double lo = n0[c] + ta * (n0[3 + c] - n0[c]), hi = n1[c] + ta * (n1[3 + c] - n1[c]);
    v[c] = lo + tb * (hi - lo);
  }
  x = v[0] * xy[0] + v[1] * xy[1];
  xy[1] = v[1] * xy[0] + v[2] * xy[1];
  xy[0] = x;
}

ap_status ap_horizon_create(const ap_horizon_grid *g, const ap_horizon_params *p,
                            const ap_sky_products *out, ap_horizon **result)
{
  ap_horizon *hz;
  size_t j, n, nr;
  ap_grid_stats stats;
  ap_status st;
  if (!result || !out) {
    return AP_ERR_NULL_POINTER;
  }
  *result = NULL;
  st = validate(g, p, &stats);
  if (st != AP_OK) {
    return st;
  }
  hz = (ap_horizon *)calloc(1, sizeof(*hz));
  if (!hz) {
    return AP_ERR_OUT_OF_MEMORY;
  }
  hz->g = *g;
  hz->p = *p;
  hz->out = *out;
  hz->nx = g->z.nx;
  hz->ny = g->z.ny;
  hz->d = -1;
  n = hz->nx * hz->ny;
  if (p->region_nx > 0) {
    hz->ri0 = p->region_i0;
    hz->rj0 = p->region_j0;
    hz->rnx = p->region_nx;
    hz->ri1 = p->region_i0 + p->region_nx;
    hz->rj1 = p->region_j0 + p->region_ny;
  } else {
    hz->ri0 = hz->rj0 = 0;
    hz->ri1 = hz->rnx = hz->nx;
    hz->rj1 = hz->ny;
  }
  nr = hz->rnx * (hz->rj1 - hz->rj0);
  hz->dxr = (double *)malloc(hz->ny * sizeof(double));
  hz->dyr = (double *)malloc(hz->ny * sizeof(double));
  hz->zt = (float *)ap_alloc_huge(n * sizeof(float));
  hz->grad = (float *)ap_alloc_huge(2 * nr * sizeof(float));
  hz->slope = (float *)ap_alloc_huge(n * sizeof(float));
  hz->edge = (unsigned char *)ap_alloc_huge(n);
  if (out->diffuse_sky_factor && !out->bent_normal) {
    hz->bsum = (float *)ap_alloc_huge(3 * nr * sizeof(float));
  }
  if (!hz->dxr || !hz->dyr || !hz->zt || !hz->grad || !hz->slope || !hz->edge ||
      (out->diffuse_sky_factor && !out->bent_normal && !hz->bsum)) {
    ap_horizon_destroy(hz);
    return AP_ERR_OUT_OF_MEMORY;
  }
  hz->zmax = (float)stats.max; /* (the largest of floats: exact) */
  hz->has_nodata = stats.nodata > 0;
  for (j = 0; j < hz->ny; ++j) {
    hz->dxr[j] = row_dx(g, j);
    hz->dyr[j] = row_dy(g, j);
  }
  transpose(hz);
  if (!data_spans_init(hz)) {
    ap_horizon_destroy(hz);
    return AP_ERR_OUT_OF_MEMORY;
  }
  if (p->scale_metric && !scale_metric_init(hz)) {
    ap_horizon_destroy(hz);
    return AP_ERR_OUT_OF_MEMORY;
  }
  hz->lattice = g->dx != NULL || g->dy != NULL;
  if (hz->lattice && !lattice_init(hz)) {
    ap_horizon_destroy(hz);
    return AP_ERR_OUT_OF_MEMORY;
  }
  if (((isfinite(p->max_distance) && p->far_march_columns > 0) || hz->has_nodata) &&
      !fm_tiles_init(hz)) {
    ap_horizon_destroy(hz);
    return AP_ERR_OUT_OF_MEMORY;
  }
  /* The outputs are the accumulators until ap_horizon_finish; the first sector's
   * ap_horizon_accumulate starts them (see first). */
  *result = hz;
  return AP_OK;
}

int ap_horizon_directions(const ap_horizon *hz)
{
  return hz ? hz->p.directions : 0;
}

double ap_horizon_azimuth(const ap_horizon *hz, int d)
{
  return hz ? 2.0 * AP_PI * (double)d / (double)hz->p.directions : 0.0;
}

/* Grid index along the primary axis of view position p. */
static size_t prim_index(const ap_horizon *hz, size_t p)
{
  return hz->flip ? hz->np - 1 - p : p;
}

/* Row-major views: the step at view position p of a prefix sum over p (cum_m or cum_len), the
 * step to p + 1, or from p - 1 on the last position. */
static double view_step(const double *cum, size_t np, size_t p)
{
  const size_t a = p + 1 < np ? p : p - 1;
  return cum[a + 1] - cum[a];
}

/* A per-row quantity at fractional row r, linearly interpolated, clamped to the grid. */
static double row_value(const double *table, size_t ny, double r)
{
  size_t r0;
  double t;
  if (!(r > 0.0)) {
    return table[0];
  }
  if (r >= (double)(ny - 1)) {
    return table[ny - 1];
  }
  r0 = (size_t)r;
  t = r - (double)r0;
  return table[r0] + t * (table[r0 + 1] - table[r0]);
}

/* The segment of the larger DEM's rows holding Psi = T: the j in [0, nw - 2] with
 * psi[j] <= T < psi[j + 1], 0 below psi[0], nw - 2 from psi[nw - 1] up; j is a hint (-1: none).
 * The answer depends on T alone. */
static long lattice_seek(const ap_horizon *hz, double T, long j)
{
  const double *psi = hz->psi;
  const long last = (long)hz->nw - 2;
  if (j < 0 || j > last) {
    long lo = 0, hi = last; /* the last j in [0, last] with psi[j] <= T, else 0 */
    while (lo < hi) {
      const long mid = lo + (hi - lo + 1) / 2;
      if (psi[mid] <= T) {
        lo = mid;
      } else {
        hi = mid - 1;
      }
    }
    return lo;
  }
  while (j < last && psi[j + 1] <= T) {
    ++j;
  }
  while (j > 0 && psi[j] > T) {
    --j;
  }
  return j;
}

/* The view row (this grid's rows) where Psi = T, linear on its segment of the larger DEM's
 * rows; *j is lattice_seek's hint, and becomes the segment. */
AP_INLINE double psi_row(const ap_horizon *hz, double T, long *j)
{
  *j = lattice_seek(hz, T, *j);
  return ((double)*j + (T - hz->psi[*j]) * hz->psi_inv[*j]) - (double)hz->orow;
}

/* Per-row cell sizes: the sector's lines on the larger DEM's lattice. A rhumb line at grid
 * azimuth phi moves tan(phi) dy/dx columns per row, so in a row-major view line k lies at
 * column k + tan(phi) Psi(row) of the larger DEM, and in an x-major view at the row where
 * Psi = sigma k + cot(phi) column. Both are functions of the larger DEM's rows and columns
 * alone, computed the same way in every piece; subtracting the piece's origin (a whole number)
 * from a position inside the piece is exact. Lines kmin..kmin + nlines - 1 cover the grid with
 * two to spare on each side. 0 when out of memory. */
static int lattice_lines(ap_horizon *hz, double sphi, double cphi)
{
  double lo = INFINITY, hi = -INFINITY, first, last;
  size_t p;
  hz->lat_off = (double *)malloc(hz->np * sizeof(double));
  if (!hz->lat_off) {
    return 0;
  }
  hz->phase = 0.0;
  hz->sigma = hz->wdy_c / hz->wdx_c;
  for (p = 0; p < hz->np; ++p) {
    const long q = (long)prim_index(hz, p);
    /* (along the columns, |sin phi| <= 1e-12, the lines are the columns themselves: with
     * offsets of rounding noise the line of a DEM's first or last column lay off the grid, and
     * its cells took their horizons from the next line alone, up to 21 degrees low) */
    const double off = hz->xmajor          ? (cphi / sphi) * (double)(q + hz->ocol)
                       : fabs(sphi) > 1e-12 ? (sphi / cphi) * hz->psi[q + hz->orow]
                                            : 0.0;
    hz->lat_off[p] = off;
    lo = fmin(lo, off);
    hi = fmax(hi, off);
  }
  if (hz->xmajor) {
    /* rows orow .. orow + ny - 1 at every column: Psi - lat_off from first - hi to last - lo */
    first = (hz->psi[hz->orow] - hi) / hz->sigma;
    last = (hz->psi[hz->orow + (long)hz->ny - 1] - lo) / hz->sigma;
  } else {
    first = (double)hz->ocol - hi;
    last = (double)(hz->ocol + (long)hz->nx - 1) - lo;
  }
  hz->kmin = (long)floor(first) - 2;
  hz->nlines = (size_t)((long)ceil(last) + 2 - hz->kmin + 1);
  /* Along the rows every ray keeps to its row, but lines spaced sigma apart in Psi lie between
   * rows wherever the cell size differs from the centre row's. The DEM's first and last rows
   * then had one line, a fraction of a row away (up to 15 degrees low there), and a row with
   * data between rows of nodata (a pier, a dyke, the row beside a nodata row) was void on both
   * of its lines (20 degrees along a one-row pier at 50 N, test_nodata_coast). There the rows
   * themselves are the lines, two to spare on each side. */
  hz->row_lines = hz->xmajor && !(fabs(cphi) > 1e-12);
  if (hz->row_lines) {
    hz->kmin = hz->orow - 2;
    hz->nlines = hz->ny + 4;
  }
  return 1;
}

ap_status ap_horizon_prepare(ap_horizon *hz, int d)
{
  double sphi, cphi, m_lo = INFINITY, m_hi = -INFINITY, R;
  size_t j, p;
  if (!hz) {
    return AP_ERR_NULL_POINTER;
  }
  if (d < 0 || d >= hz->p.directions) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  free_sector(hz);
  hz->first = hz->d < 0;
  hz->d = d;
  hz->phi = ap_horizon_azimuth(hz, d) - hz->p.azimuth_offset;
  sphi = sin(hz->phi);
  cphi = cos(hz->phi);
  if (hz->metric) {
    /* rho^2 = the relative metric of the sector's unit step u = (sin phi, cos phi); the
     * weight: half the angle on the ground between the neighbouring sectors' directions,
     * S u(phi - delta) and S u(phi + delta), over delta */
    const double delta = 2.0 * AP_PI / (double)hz->p.directions;
    const double u[3][2] = { { sin(hz->phi - delta), cos(hz->phi - delta) },
                             { sphi, cphi },
                             { sin(hz->phi + delta), cos(hz->phi + delta) } };
    for (p = 0; p < hz->p.scale_cols * hz->p.scale_rows; ++p) {
      const double *m = hz->metric + 3 * p, *sr = hz->sroot + 3 * p;
      const double r2 = m[0] * sphi * sphi + 2.0 * m[1] * sphi * cphi + m[2] * cphi * cphi;
      double v[3][2], turn = 0.0;
      int e;
      for (e = 0; e < 3; ++e) {
        v[e][0] = sr[0] * u[e][0] + sr[1] * u[e][1];
        v[e][1] = sr[1] * u[e][0] + sr[2] * u[e][1];
      }
      for (e = 0; e < 2; ++e) { /* (clockwise, each in (0, pi): S keeps the orientation) */
        turn += atan2(v[e][1] * v[e + 1][0] - v[e][0] * v[e + 1][1],
                      v[e][0] * v[e + 1][0] + v[e][1] * v[e + 1][1]);
      }
      hz->inv_rho[p] = (float)(1.0 / sqrt(r2));
      hz->weight[p] = (float)(0.5 * turn / delta);
    }
  }
  /* Index-space speed of the ground direction at the centre row (of the larger DEM, with
   * per-row sizes) decides the view. */
  if (hz->lattice) {
    hz->xmajor = fabs(sphi) / hz->wdx_c >= fabs(cphi) / hz->wdy_c;
  } else {
    const size_t jc = hz->ny / 2;
    hz->xmajor = fabs(sphi) / hz->dxr[jc] >= fabs(cphi) / hz->dyr[jc];
  }
  hz->flip = hz->xmajor ? (sphi < 0.0) : (cphi < 0.0);
  /* Lines bend only in column-major views of grids whose cell size varies by row. */
  hz->parallel = hz->lattice ? !hz->xmajor : 1;
  hz->np = hz->xmajor ? hz->nx : hz->ny;
  hz->ns = hz->xmajor ? hz->ny : hz->nx;
  {
    /* the region in the view: p runs along the grid's columns (x-major) or rows, reversed
     * when flipped; s along the other axis */
    const size_t a0 = hz->xmajor ? hz->ri0 : hz->rj0, a1 = hz->xmajor ? hz->ri1 : hz->rj1;
    hz->vp0 = hz->flip ? hz->np - a1 : a0;
    hz->vp1 = hz->flip ? hz->np - a0 : a1;
    hz->vs0 = hz->xmajor ? hz->rj0 : hz->ri0;
    hz->vs1 = hz->xmajor ? hz->rj1 : hz->ri1;
  }
  hz->colp = (const float **)malloc(hz->np * sizeof(*hz->colp));
  if (!hz->colp) {
    free_sector(hz);
    return AP_ERR_OUT_OF_MEMORY;
  }
  for (p = 0; p < hz->np; ++p) {
    const size_t q = prim_index(hz, p);
    hz->colp[p] = hz->xmajor ? hz->zt + q * hz->ny : hz->g.z.z + (ptrdiff_t)q * hz->g.z.row_stride;
  }
  R = 1.0 / (cphi * cphi / hz->p.radius_meridian + sphi * sphi / hz->p.radius_normal);
  hz->c = hz->p.curvature ? (1.0 - hz->p.refraction) / (2.0 * R) : 0.0;

  hz->m_row = (double *)malloc(hz->ny * sizeof(double));
  hz->len_row = (double *)malloc(hz->ny * sizeof(double));
  if (!hz->m_row || !hz->len_row) {
    free_sector(hz);
    return AP_ERR_OUT_OF_MEMORY;
  }
  for (j = 0; j < hz->ny; ++j) {
    const double dx = hz->dxr[j], dy = hz->dyr[j];
    if (hz->xmajor) {
      /* one column (dx metres east or west) per step; rows move by dx cot(phi) / dy */
      hz->m_row[j] = dx * cphi / (dy * fabs(sphi));
      hz->len_row[j] = dx / fabs(sphi);
    } else {
      hz->m_row[j] = dy * sphi / (dx * fabs(cphi));
      hz->len_row[j] = dy / fabs(cphi);
    }
    if (fabs(hz->m_row[j]) < 1e-12) {
      /* along a grid axis: cos(pi/2) is 6e-17, not 0, and lines a rounding error off the
       * DEM's side would take no samples there (a fixed bound: the same for any piece) */
      hz->m_row[j] = 0.0;
    }
    if (hz->m_row[j] < m_lo) m_lo = hz->m_row[j];
    if (hz->m_row[j] > m_hi) m_hi = hz->m_row[j];
  }
  hz->side = !hz->parallel ? 0 : (m_hi > 0.0 ? 1 : (m_lo < 0.0 ? -1 : 0));
  if (hz->side != 0) {
    /* (the smallest |m| of the rows: m_row has one sign) */
    const double cols = ceil(1.0 / fmin(fabs(m_lo), fabs(m_hi))) + 1.0;
    hz->side_cols = cols < (double)hz->np ? (size_t)cols : hz->np;
  }
  if (!hz->xmajor) {
    /* Row-major view: the step from p to p + 1 shifts every line by the same amount, the mean
     * of the two rows' shifts; prefix sums give any span in O(1). */
    hz->cum_m = (double *)malloc(hz->np * sizeof(double));
    hz->cum_len = (double *)malloc(hz->np * sizeof(double));
    if (!hz->cum_m || !hz->cum_len) {
      free_sector(hz);
      return AP_ERR_OUT_OF_MEMORY;
    }
    hz->cum_m[0] = hz->cum_len[0] = 0.0;
    for (p = 0; p + 1 < hz->np; ++p) {
      const size_t a = prim_index(hz, p), b = prim_index(hz, p + 1);
      hz->cum_m[p + 1] = hz->cum_m[p] + 0.5 * (hz->m_row[a] + hz->m_row[b]);
      hz->cum_len[p + 1] = hz->cum_len[p] + 0.5 * (hz->len_row[a] + hz->len_row[b]);
    }
  }
  /* Short search distances: march every ray exactly to the distance when it spans at most
   * march_columns view steps (a step is never shorter than the shortest row's). */
  hz->shortest = INFINITY;
  for (j = 0; j < hz->ny; ++j) {
    hz->shortest = fmin(hz->shortest, hz->len_row[j]);
  }
  {
    /* (with per-row sizes the larger DEM's shortest step decides, so that its pieces march
     * where it does; the window's capacity below takes the shorter of the two) */
    double decides = hz->shortest;
    if (hz->lattice) {
      decides = hz->xmajor ? hz->wdx_min / fabs(sphi) : hz->wdy_min / fabs(cphi);
      hz->shortest = fmin(hz->shortest, decides);
    }
    hz->march = isfinite(hz->p.max_distance) &&
                hz->p.max_distance <= (double)hz->p.march_columns * decides;
    hz->far_march = !hz->march && hz->fm_tile[0] &&
                    hz->p.max_distance <= (double)hz->p.far_march_columns * decides;
  }
  hz->near_field = hz->p.near_field ? hz->p.near_field
                   : hz->march || hz->far_march ? AP_HORIZON_NEAR_FIELD_MARCHED
                                                : AP_HORIZON_NEAR_FIELD_SWEPT;
  hz->shore_sweep = !hz->march && !hz->far_march && hz->has_nodata && hz->fm_tile[0] != NULL;
  if ((hz->far_march || hz->shore_sweep) && !hz->lattice && !fm_steps_init(hz)) {
    free_sector(hz);
    return AP_ERR_OUT_OF_MEMORY;
  }
  if (hz->far_march && hz->lattice) {
    /* the columns' own steps (lattice_steps_col): at most this many within the distance */
    hz->fm_kmax = (long)floor(hz->p.max_distance / hz->shortest) + 1;
    fm_side_max_init(hz);
  }
  if (hz->shore_sweep && hz->lattice) {
    /* (the same, or the view's length) */
    hz->fm_kmax = hz->p.max_distance / hz->shortest < (double)hz->np
                    ? (long)floor(hz->p.max_distance / hz->shortest) + 1
                    : (long)hz->np;
  }
  /* Near-field patterns. With constant cell sizes all positions share one pattern of the
   * exact step. With per-row sizes a position takes the pattern of its step rounded to a
   * lattice, tol in m and 1e-4 in log(len): a function of that position's own rows, so a piece
   * of a DEM (p.origin_*) uses the whole DEM's patterns, each within tol / 2 rows of drift
   * over the near field and 5e-5 of length of the exact step. */
  {
    /* rows of drift allowed over the near field */
    const double tol = 1e-3 / (double)(hz->march ? hz->p.march_columns : hz->near_field);
    const size_t npos = hz->xmajor ? hz->ns : hz->np;
    double key_m = 0.0, key_len = 0.0;
    size_t q;
    hz->pat_of = (int *)malloc(npos * sizeof(int));
    if (!hz->pat_of) {
      free_sector(hz);
      return AP_ERR_OUT_OF_MEMORY;
    }
    for (q = 0; q < npos; ++q) {
      double m, len;
      int fresh = q == 0;
      if (hz->xmajor) {
        m = hz->m_row[q];
        len = hz->len_row[q];
      } else {
        m = view_step(hz->cum_m, hz->np, q);
        len = view_step(hz->cum_len, hz->np, q);
      }
      if (hz->lattice) {
        const double km = floor(m / tol + 0.5), kl = floor(log(len) / 1e-4 + 0.5);
        fresh = fresh || km != key_m || kl != key_len;
        key_m = km;
        key_len = kl;
        m = km * tol;
        len = exp(kl * 1e-4);
      }
      if (fresh) {
        const double tmax = hz->march ? hz->p.max_distance
                                      : fmin(hz->p.max_distance, (double)hz->near_field * len);
        if (!build_pattern(hz, m, len, tmax)) {
          free_sector(hz);
          return AP_ERR_OUT_OF_MEMORY;
        }
      }
      hz->pat_of[q] = (int)(hz->npats - 1);
    }
    /* (per-row sizes far-march x-major views by rows, whatever their patterns) */
    hz->by_rows = hz->xmajor && (hz->npats > 1 || (hz->lattice && hz->far_march));
  }
  if (hz->lattice) {
    if (!lattice_lines(hz, sphi, cphi)) {
      free_sector(hz);
      return AP_ERR_OUT_OF_MEMORY;
    }
    return AP_OK;
  }
  /* Lines k in [kmin, kmax] cover s in [0, ns - 1] at every p: line k is at s = k on the last
   * column and drifts by at most m_lo..m_hi per step on the way back. Two extra lines on each
   * side keep every cell strictly bracketed. */
  {
    const double span = (double)(hz->np - 1);
    const double lo = fmin(0.0, m_lo * span), hi = fmax(0.0, m_hi * span);
    const long kmin = (long)floor(lo) - 2;
    const long kmax = (long)ceil((double)(hz->ns - 1) + hi) + 2;
    hz->kmin = kmin;
    hz->nlines = (size_t)(kmax - kmin + 1);
  }
  /* The larger DEM's lines (p.origin_col, p.origin_row) pass through whole s at its view
   * column of grid index 0 and, as s grows by m per view step (p grows towards the
   * occluders), lie at s = integer + sign m q on the column of grid index q (sign -1 for
   * flipped views). On this grid's last view column, grid index q_last, offset by the
   * origin, that is this grid's s = k + phase. A phase below 1 keeps the margin of the
   * extra lines above. */
  {
    const long q0 = hz->xmajor ? hz->p.origin_col : hz->p.origin_row;
    const double m = hz->m_row[hz->ny / 2];
    const double span = (double)((long)prim_index(hz, hz->np - 1) + q0);
    const double t = (hz->flip ? -m : m) * span;
    hz->phase = t - floor(t);
    if (!(hz->phase < 1.0)) {
      hz->phase = 0.0; /* (t - floor(t) rounds up to 1 for t just below a whole number) */
    }
  }
  return AP_OK;
}

size_t ap_horizon_bracket_count(const ap_horizon *hz)
{
  return (hz && hz->d >= 0 && hz->nlines > 1) ? hz->nlines - 1 : 0;
}

size_t ap_horizon_near_field_count(const ap_horizon *hz)
{
  if (!hz || hz->d < 0) {
    return 0;
  }
  return hz->by_rows ? hz->ns : hz->np;
}

/* View column p as a contiguous array of ns elevations. */
static const float *view_column(const ap_horizon *hz, size_t p)
{
  return hz->colp[p];
}

/* The grid row (g < ny) or grid column g - ny that view column p is (data_span's, holes'
 * index g). */
AP_INLINE size_t view_line(const ap_horizon *hz, size_t p)
{
  return hz->xmajor ? hz->ny + prim_index(hz, p) : prim_index(hz, p);
}

/* Clamp view rows [*sa, *sb) of view column p to the cells with data in it, where searching
 * matters: a nodata cell's NaN height never raises a slope (*sb <= *sa when none is left). */
AP_INLINE void clamp_to_data(const ap_horizon *hz, size_t p, long *sa, long *sb)
{
  const size_t *span = hz->data_span + 2 * view_line(hz, p);
  *sa = *sa > (long)span[0] ? *sa : (long)span[0];
  *sb = *sb < (long)span[1] ? *sb : (long)span[1];
}

/* Elevation at fractional s of a view column of ns cells (smax = ns - 1), linear between the
 * two nearest cells; NaN when outside or when a cell with non-zero weight is nodata. (At
 * s = smax the weight of the cell above is zero. Signed conversions: one instruction each.) */
AP_INLINE double interp(const float *col, double smax, double s)
{
  long s0;
  double t;
  if (!(s >= 0.0) || s > smax) {
    return NAN;
  }
  s0 = (long)s;
  t = s - (double)s0;
  if (t == 0.0) {
    return col[s0];
  }
  return (double)col[s0] + t * ((double)col[s0 + 1] - (double)col[s0]);
}

/* interp, but where that is NaN inside the column, a position within 1e-9 of a whole row reads
 * that cell alone, as the far march's steps do (fm_step_set): lines and rays of the diagonals
 * run through cells up to rounding, and a nodata neighbour of a weight of rounding noise must
 * not void them (a cell looking at 45 degrees past nodata lost the single cell its ray meets
 * beyond, up to 11 degrees). The same as interp wherever that is not NaN. */
AP_INLINE double interp_snap(const float *col, double smax, double s)
{
  const double z = interp(col, smax, s), r = nearbyint(s);
  if (isnan(z) && s >= 0.0 && s <= smax && fabs(s - r) < 1e-9) {
    return col[(long)r];
  }
  return z;
}

/* The sweep's sample: interp_snap on DEMs with nodata, interp alone on others (nodata is a
 * constant in each of the sweep's two variants, so the other keeps its loop as it was). */
AP_INLINE double interp_nd(const float *col, double smax, double s, int nodata)
{
  return nodata ? interp_snap(col, smax, s) : interp(col, smax, s);
}

/* Where the result of view cell (p, s) goes in the sector scratch: x-major sectors are stored
 * transposed (grid column-major), so the sweep writes contiguously. */
static size_t scratch_index(const ap_horizon *hz, size_t p, size_t s)
{
  const size_t q = prim_index(hz, p);
  return hz->xmajor ? q * hz->ny + s : s + q * hz->nx;
}

/* ---------------------------------------------------------------------------------------- */
/* Near field on the bilinear surface.
 *
 * For the first K columns of its ray a cell takes the largest slope (z(t) - zq)/t - c t over
 * the DEM's bilinear surface exactly. On one patch the surface along a straight ray is a
 * quadratic, z(t) = A + B t + C t^2, so the slope is f(t) = alpha/t + B + gamma t
 * (alpha = A - zq, gamma = C - c), whose maximum over a segment [t1, t2] lies at an end or at
 * t* = sqrt(alpha/gamma). The first patch starts at the cell's own node (alpha = 0), where f
 * tends to B, the surface's slope along the ray.
 *
 * A ray from any node with the same direction crosses the same sequence of patches at the same
 * distances, so the crossings and the corner weights of A, B, C are computed once per sector
 * ("pattern") and applied to whole view columns at a time, a loop over contiguous cells that
 * compilers vectorise. That is a phase of its own (ap_horizon_near_field) before the sweep:
 * there a band of 16 lines spans 16 cells of a column, too short a loop for vectors (the near
 * field took twice the instructions inside the sweep). Where the cell size varies by row
 * (lat/lon DEMs), rows (x-major) or columns (row-major) whose rays differ by less than a
 * thousandth of a row over the near field share a pattern. In x-major views those runs of rows
 * are a few cells long, so there the near field runs row by row instead (near_row), each
 * record over a whole grid row. (An 1800^2 SRTM grid at 50 N, unlimited distance, one
 * thread: 122 ns per cell and direction as lat/lon against 73 as UTM before, 88 against 84.)
 * A patch with a nodata corner is no terrain, but the grid line the ray leaves it through is
 * where its two cells have data (patch_rec's exit edge): DEMs with nodata run a second
 * variant of the loops that evaluates it there. */

static int push_rec(ap_horizon *hz, const patch_rec *r)
{
  if (hz->nrecs == hz->caprecs) {
    const size_t c = hz->caprecs ? 2 * hz->caprecs : 64;
    patch_rec *nr = (patch_rec *)realloc(hz->recs, c * sizeof(patch_rec));
    if (!nr) {
      return 0;
    }
    hz->recs = nr;
    hz->caprecs = c;
  }
  hz->recs[hz->nrecs++] = *r;
  return 1;
}

/* Where the ray leaves its patch (see patch_rec): through the patch's edge u = 1 (it crossed
 * column line P + 1: at_p), through v = 1 (rising, b > 0) or v = 0 (falling) when it crossed a
 * row line (at_s), at their corner when both, along the lower edge v = 0 when it runs along a
 * row (b = 0), or inside the patch; (u2, v2) the exit point in the patch's coordinates. A
 * point within 1e-9 of a corner is that corner, so that a nodata corner of a weight of
 * rounding noise does not void it. */
static void exit_edge(patch_rec *r, int at_p, int at_s, double b, double u2, double v2)
{
  const int on_row = b == 0.0, up = b > 0.0 ? 2 : 0; /* the row the ray leaves through */
  double w = 0.0;
  if (at_p && (at_s || on_row)) {
    r->ea = r->eb = 1 + up;
  } else if (at_p) {
    r->ea = 1; /* z10 to z11 */
    r->eb = 3;
    w = v2;
  } else if (at_s || on_row) {
    r->ea = up; /* z00 to z10, or z01 to z11 */
    r->eb = up + 1;
    w = u2;
  } else {
    r->ea = r->eb = -1;
  }
  if (w < 1e-9) {
    r->eb = r->ea;
    w = 0.0;
  } else if (w > 1.0 - 1e-9) {
    r->ea = r->eb;
    w = 0.0;
  }
  r->ew = (float)w;
}

/* Walk a ray from node (0, 0) of the view, a = 1/len columns and b = m/len rows per metre,
 * recording every patch it crosses up to distance tmax. */
static int build_pattern(ap_horizon *hz, double m, double len, double tmax)
{
  /* a ray that drifts by less than 1e-9 rows over the pattern runs along its row (the axis
   * sectors: cos(pi/2) is 6e-17, not 0), entering every patch at its lower edge */
  const double a = 1.0 / len, b = fabs(m) * tmax / len < 1e-9 ? 0.0 : m / len;
  long P = 0, S = b >= 0.0 ? 0 : -1;
  double t1 = 0.0;
  pattern pt;
  pt.m = b == 0.0 ? 0.0 : m; /* 0 for a ray along its row */
  pt.len = len;
  pt.lp = hz->p.max_distance / len;
  pt.ls = pt.m * hz->p.max_distance / len;
  pt.first = hz->nrecs;
  while (t1 < tmax) {
    const double tp = (double)(P + 1) / a;
    const double ts = b > 0.0 ? (double)(S + 1) / b : (b < 0.0 ? (double)S / b : INFINITY);
    const double t2 = fmin(fmin(tp, ts), tmax);
    /* Where the ray enters the patch, in the patch's own coordinates (u along p, v along s,
     * both in [0, 1]), so that every weight below stays bounded. */
    const double u1 = a * t1 - (double)P, v1 = b * t1 - (double)S, k = u1 * b + v1 * a;
    patch_rec r;
    r.dp = P;
    r.ds = S;
    r.t1 = (float)t1;
    r.t2 = (float)t2;
    r.dt = (float)(t2 - t1);
    r.inv_t1 = t1 > 0.0 ? (float)(1.0 / t1) : 0.0f;
    r.inv_t2 = (float)(1.0 / t2);
    r.t1x2 = (float)(2.0 * t1);
    r.first = !(t1 > 0.0);
    /* z(u, v) = z00 (1-u)(1-v) + z10 u (1-v) + z01 (1-u) v + z11 u v along the segment, with
     * tau = t - t1: z = A1 + B1 tau + C tau^2, A1 = z(u1, v1),
     * B1 = e a + f b + g (u1 b + v1 a), C = g a b, where e = z10 - z00, f = z01 - z00,
     * g = z11 - z10 - z01 + z00. */
    r.u1 = (float)u1;
    r.v1 = (float)v1;
    r.u1v1 = (float)(u1 * v1);
    r.wa = (float)a;
    r.wb = (float)b;
    r.wk = (float)k;
    r.wab = (float)(a * b);
    exit_edge(&r, tp <= t2, ts <= t2, b, a * t2 - (double)P, b * t2 - (double)S);
    if (!push_rec(hz, &r)) {
      return 0;
    }
    if (tp <= t2) ++P;
    if (ts <= t2) S += b > 0.0 ? 1 : -1;
    if (t2 >= tmax) {
      break;
    }
    t1 = t2;
  }
  pt.n = hz->nrecs - pt.first;
  if (hz->npats == hz->cappats) {
    const size_t c = hz->cappats ? 2 * hz->cappats : 16;
    pattern *np = (pattern *)realloc(hz->pats, c * sizeof(pattern));
    if (!np) {
      return 0;
    }
    hz->pats = np;
    hz->cappats = c;
  }
  hz->pats[hz->npats++] = pt;
  return 1;
}

/* The largest slope from a cell at height zq along its ray over one patch (rec) with corners
 * z00, z10 (column p, p + 1 at the lower row) and z01, z11 (the upper row): the near field's
 * body, in single precision and branch-free so that the loop over cells vectorises. */
AP_INLINE float patch_slope(const patch_rec *rec, float cf, float zq, float z00, float z10,
                          float z01, float z11)
{
  const float d00 = z00 - zq, e = z10 - z00, f = z01 - z00, g = (z11 - z10) - f;
  const float a1 = d00 + rec->u1 * e + rec->v1 * f + rec->u1v1 * g; /* A1 - zq */
  const float B1 = rec->wa * e + rec->wb * f + rec->wk * g;
  const float C = rec->wab * g;
  const float f2 = (a1 + (B1 + C * rec->dt) * rec->dt) * rec->inv_t2 - cf * rec->t2;
  /* In absolute distance t the slope is f(t) = alpha/t + B + gamma t with
   * alpha = A1 - zq - B1 t1 + C t1^2, B = B1 - 2 C t1, gamma = C - c. An interior maximum
   * needs alpha < 0 and gamma < 0 (f'' = 2 alpha / t^3 < 0); it lies in the segment iff
   * t1^2 <= alpha/gamma <= t2^2, i.e. gamma t2^2 <= alpha <= gamma t1^2, and there
   * f(t*) = B - 2 sqrt(alpha gamma): no division. Those two bounds alone imply
   * gamma <= 0 (t2 > t1) and so alpha <= 0; where one is 0, sqrt gives 0 and B is then
   * the supremum of f on the segment, so the sign tests are not needed. */
  const float alpha = a1 - (B1 - C * rec->t1) * rec->t1;
  const float gamma = C - cf;
  const int inside =
    (alpha >= gamma * rec->t2 * rec->t2) & (alpha <= gamma * rec->t1 * rec->t1);
  const float fi = inside ? (B1 - C * rec->t1x2) - 2.0f * sqrtf(alpha * gamma) : f2;
  const float f1 = rec->first ? B1 : a1 * rec->inv_t1 - cf * rec->t1;
  float v = f1 > f2 ? f1 : f2;
  v = fi > v ? fi : v;
  return v;
}

/* The slope from a cell at height zq to where its ray leaves the patch (rec), on the grid line
 * between heights za and zb (at rec->ew of the way to zb; za itself at a corner). */
AP_INLINE float exit_slope(const patch_rec *rec, float cf, float zq, float za, float zb)
{
  return (za + rec->ew * (zb - za) - zq) * rec->inv_t2 - cf * rec->t2;
}

/* Corner k of a patch (patch_rec's ea, eb) whose lower corners are columns c0, c1 (the upper
 * ones one further) */
#define CORNER(c0, c1, k) (((k) & 1 ? (c1) : (c0)) + ((k) >> 1))

/* Largest near-field slope of cells [sa, sb) of view column p into best[] (max-merged).
 * Compiled three times where the compiler supports it (GCC function multi-versioning): for
 * x86-64-v4 (AVX-512: mask registers for the compares and selects, 7-8% off the whole kernel
 * against the AVX2 clone on an AMD EPYC), with AVX2 (eight cells per instruction) and for the
 * baseline; the CPU picks at run time. All make the same IEEE operations in the same order
 * (ISO C mode: no fused multiply-add contraction), so the results are identical on every
 * machine; the test Kernels-isa-equality compares the picked clones with a build without
 * them. AP_HORIZON_NO_MULTIVERSION builds the baseline alone. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) &&   \
  !defined(AP_HORIZON_NO_MULTIVERSION)
#define AP_MULTIVERSION __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#else
#define AP_MULTIVERSION
#endif
AP_MULTIVERSION
static void near_column(const ap_horizon *hz, const pattern *pt, size_t p, long sa, long sb,
                        const float *col, double c, float *best)
{
  const long ns = (long)hz->ns;
  const float cf = (float)c;
  size_t r;
  for (r = 0; r < pt->n; ++r) {
    const patch_rec *rec = &hz->recs[pt->first + r];
    const float *c0, *c1;
    long s, lo, hi;
    if (p + (size_t)rec->dp + 1 >= hz->np) {
      break; /* records run forward in p: the rest is off the grid too */
    }
    c0 = view_column(hz, p + (size_t)rec->dp) + rec->ds;
    c1 = view_column(hz, p + (size_t)rec->dp + 1) + rec->ds;
    lo = sa > -rec->ds ? sa : -rec->ds;
    hi = sb < ns - 1 - rec->ds ? sb : ns - 1 - rec->ds;
    /* Branch-free single precision so that it vectorises eight cells at a time. It works on
     * the patch's corner differences e, f, g (exact for nearby heights, Sterbenz), on the
     * height difference from the cell, and on each patch from where the ray enters it, so the
     * weights stay bounded and float rounding stays near 1e-7 of a slope. On the first patch
     * the ray leaves the cell's own node (A1 = zq) and the slope tends to B1. (A patch's start
     * is the previous patch's end, but that one gives NaN when one of its corners is nodata.) */
    if (!hz->has_nodata || rec->ea < 0 ||
        (all_data(hz, view_line(hz, p + (size_t)rec->dp), lo + rec->ds, hi + rec->ds) &&
         all_data(hz, view_line(hz, p + (size_t)rec->dp + 1), lo + rec->ds, hi + rec->ds))) {
      /* (no corner of these patches is nodata) */
      for (s = lo; s < hi; ++s) {
        const float v = patch_slope(rec, cf, col[s], c0[s], c1[s], c0[s + 1], c1[s + 1]);
        best[s] = v > best[s] ? v : best[s]; /* NaN (nodata corner) never wins */
      }
    } else {
      /* A patch with a nodata corner is no terrain, but the grid line the ray leaves it
       * through is where its two cells have data (as the far field's samples between two
       * cells of a column are): a one-cell-wide strip of land has no patch of its own, and a
       * ray along a row beside nodata runs on such patches only. */
      const float *za = CORNER(c0, c1, rec->ea), *zb = CORNER(c0, c1, rec->eb);
      for (s = lo; s < hi; ++s) {
        const float v = patch_slope(rec, cf, col[s], c0[s], c1[s], c0[s + 1], c1[s + 1]);
        const float ve = exit_slope(rec, cf, col[s], za[s], zb[s]);
        const float u = v == v ? v : ve;
        best[s] = u > best[s] ? u : best[s];
      }
    }
    /* A ray along a row of the view (no lateral shift: every patch entered at its lower
     * edge) on the last row has no patch above it; the upper row's weights are zero there, so
     * the row itself stands in for it (its exit lies on the row too). */
    if (rec->wb == 0.0f && rec->v1 == 0.0f) {
      s = ns - 1 - rec->ds;
      if (s >= sa && s < sb) {
        float v = patch_slope(rec, cf, col[s], c0[s], c1[s], c0[s], c1[s]);
        if (v != v && rec->ea >= 0) {
          const float *za = CORNER(c0, c1, rec->ea), *zb = CORNER(c0, c1, rec->eb);
          v = exit_slope(rec, cf, col[s], za[s], zb[s]);
        }
        best[s] = v > best[s] ? v : best[s];
      }
    }
  }
}

/* The far point's lateral offset in rows, ls (pattern pt): an offset within 1e-9 of a whole
 * cell is that cell, so that a nodata neighbour with a weight of rounding noise does not void
 * the point. */
AP_INLINE double far_offset(const pattern *pt)
{
  return fabs(pt->ls - nearbyint(pt->ls)) < 1e-9 ? nearbyint(pt->ls) : pt->ls;
}

/* The slope to the far point from a cell at height zq: bilinear in the corners a0, a1 (its
 * lower view column, rows s + o and s + o + up) and b0, b1 (the column above), weights t
 * (rows) and tp (columns); L the distance, cl = c L. Both layouts (far_point_column,
 * far_point_row) use it, so their results agree bit for bit. */
AP_INLINE double far_slope(double a0, double a1, double b0, double b1, double t, double tp,
                           double zq, double L, double cl)
{
  const double i0 = a0 + t * (a1 - a0), i1 = b0 + t * (b1 - b0);
  const double zl = (1.0 - tp) * i0 + tp * i1;
  return (zl - zq) / L - cl;
}

/* The point exactly at the search distance L on the rays of cells [sa, sb) of view column p
 * (pattern pt), max-merged into best[]: rising terrain peaks there, between the column samples
 * the hulls hold. Only where that point lies beyond the near field: always in row-major views
 * (the caller checks the column), per row (x-major: s is the row) otherwise. The point of cell s
 * is at s + ls on the column pf = p + lp, the same offset for every cell: so it is bilinear with
 * the same weights between cells s + o and s + o + 1 (o = floor(ls)) of the two view columns
 * around pf, a loop over contiguous cells that vectorises. Each weight degenerates exactly as
 * interp()'s does (a zero weight reads the same cell twice: x + 0 (y - x) = x); a point off
 * the grid is skipped, one on nodata gives NaN, which never wins. Storing the float max
 * here rounds exactly as the sweep's final float max would (rounding is monotonic). */
AP_MULTIVERSION
static void far_point_column(const ap_horizon *hz, const pattern *pt, size_t p, long sa,
                             long sb, const float *col, float *best)
{
  const double L = hz->p.max_distance, c = hz->c, K = (double)hz->near_field;
  const double pf = (double)p + pt->lp, cl = c * L;
  const long ns = (long)hz->ns;
  const int xmajor = hz->xmajor;
  const double *len_row = hz->len_row;
  const double ls = far_offset(pt);
  const double of = floor(ls), t = ls - of;
  long o, up, s, lo, hi;
  size_t p0;
  double tp;
  const float *z0, *z1;
  if (!(pf >= 0.0) || pf > (double)(hz->np - 1) || !(fabs(of) < (double)ns)) {
    return;
  }
  p0 = (size_t)pf;
  tp = pf - (double)p0;
  z0 = view_column(hz, p0);
  z1 = tp == 0.0 ? z0 : view_column(hz, p0 + 1); /* (pf <= np - 1: p0 = np - 1 has tp = 0) */
  o = (long)of;
  up = t == 0.0 ? 0 : 1;
  /* on the grid: 0 <= s + o and s + o + up <= ns - 1 */
  lo = sa > -o ? sa : -o;
  hi = sb < ns - o - up ? sb : ns - o - up;
  for (s = lo; s < hi; ++s) {
    const long s1 = s + o + up;
    const double sl = far_slope(z0[s + o], z0[s1], z1[s + o], z1[s1], t, tp, col[s], L, cl);
    const int use = xmajor ? L > K * len_row[s] : 1; /* (len_row has ny entries) */
    best[s] = (use & (sl > (double)best[s])) ? (float)sl : best[s];
  }
}

/* The edge flag of a cell at height zq whose search reaches `reach` metres before the DEM
 * ends: truncated when that is short of the search limit, the distance L, or without one, with
 * curvature c, sqrt((zmax - zq) / c), beyond which terrain no higher than the DEM's highest
 * cell stays below the cell's horizontal (compared squared: reach^2 c < zmax - zq). (Not with a
 * distance: a piece of a DEM knows only its own highest cell, and would flag fewer cells.) */
AP_INLINE unsigned char search_truncated(double reach, double L, double c, double zmax, double zq)
{
  return reach < L && (L < INFINITY || c <= 0.0 || reach * reach * c < zmax - zq);
}

/* The edge flag of view cell (p, s) at height zq when the near field covers the whole search
 * (hz->march): whether its own ray (pattern pt: m view rows and len metres per column) leaves
 * the grid before the search limit (search_truncated). */
AP_INLINE unsigned char march_edge(const ap_horizon *hz, const pattern *pt, size_t p, long s,
                                   double zq)
{
  double steps = (double)(hz->np - 1 - p); /* columns left before the far edge */
  if (pt->m > 0.0) {
    steps = fmin(steps, ((double)hz->ns - 1.0 - (double)s) / pt->m);
  } else if (pt->m < 0.0) {
    steps = fmin(steps, (double)s / -pt->m);
  }
  return search_truncated(steps * pt->len, hz->p.max_distance, hz->c, (double)hz->zmax, zq);
}

/* The slope to the point where a ray leaves the grid through a side of the view (view row 0 or
 * ns - 1) between two view columns: k steps of len metres from its cell (k not whole), at
 * view column p + k, linear along that edge row between the cells of columns floor(p + k)
 * and the next: the terrain the samples at column crossings stop short of (up to a column).
 * In a bowl rising to the DEM's edge that last stretch holds the horizon: without it the far
 * march and the sweep were up to 3 degrees low there, and 0.05 on average over a 48 x 40
 * bowl's cells and directions, against a brute force that marches to the edge. */
AP_INLINE double side_exit_slope(const ap_horizon *hz, size_t p, double k, long edge, double len,
                                 double zq)
{
  /* (the columns from k's whole part, not from p + k: k just short of a whole number, on the
   * diagonals where the slope m is 1 + 2e-16, rounded p + k up to the last column, and read a
   * column beyond it; the callers' k < np - 1 - p keeps q + 1 on the grid) */
  const double kw = floor(k), t = k * len;
  const size_t q = p + (size_t)kw;
  const double f = k - kw;
  const double z0 = view_column(hz, q)[edge], z1 = view_column(hz, q + 1)[edge];
  return ((z0 + f * (z1 - z0)) - zq) / t - hz->c * t;
}

/* When the near field covers the whole search (hz->march or hz->far_march), it also finishes
 * cells [sa, sb) of view column p as the sweep would: nodata cells get NaN, the others their
 * edge flag. */
static void march_finish(const ap_horizon *hz, const pattern *pt, size_t p, long sa, long sb,
                         const float *col, float *best, unsigned char *edge)
{
  long s;
  for (s = sa; s < sb; ++s) {
    const double zq = col[s];
    if (isnan(zq)) {
      best[s] = NAN;
      edge[s] = 0;
      continue;
    }
    edge[s] = march_edge(hz, pt, p, s, zq);
  }
}

/* ---------------------------------------------------------------------------------------- */
/* The far march: a search distance of more than march_columns but at most far_march_columns
 * view steps. Every cell's own ray is sampled where it crosses view
 * columns K..fm_kmax (linear between the column's two cells, as the hulls' samples are), and
 * the largest slope (z - zq)/t - c t is max-merged into the near field's. That is what the
 * sweep's hulls approximate (the sweep evaluates the cell's own ray only at the columns where
 * its two bracketing lines' hulls are tangent), at O(distance) instead of O(1) per cell and
 * direction; but it has no data-dependent branches, runs 16 cells of a view column as one
 * vector loop, and skips most of its work: a stretch of steps whose terrain, bounded by the
 * maxima of fixed tiles of the elevations, cannot rise above the slope a cell has found so far
 * is skipped for all 16 (tested on 64 steps, then on 16). The bound holds in the rounded
 * arithmetic too (every operation below is monotonic in the elevation and in the step, and
 * the tile maximum is raised by fm_eps for the interpolation's rounding), so skipping never
 * changes a result: it equals the full march bit for bit, and so does not depend on the split
 * into threads or on where a piece of a DEM starts. (The whole kernel on Big Tujunga at 10 km,
 * one core, 32 sectors: 47 against the sweep's 75 ns per cell and direction; 49 against 101 on
 * a 2048^2 fractal DEM; bench/bake-notes.md.) With constant cell sizes every ray of the sector
 * takes the same steps (hz->fm); with per-row sizes (lat/lon) the rays of one grid row do:
 * a view column's in row-major views (lattice_steps_col, far_march_column), a grid row's in
 * x-major ones, marched 16 neighbouring cells of the row at a time (lattice_steps_row,
 * far_march_row). */

#define AP_FM_LANES 16  /* cells of a view column marched together */
#define AP_FM_FINE 16   /* steps (and tile size) of the fine test */
#define AP_FM_COARSE 64 /* of the coarse test */
#define AP_FM_CHUNK 256 /* cells of a view column marched before the next unit's (a multiple
                         * of AP_FM_LANES) */

typedef struct fm_step {
  long o;   /* view rows from the cell to the lower of the two cells the ray passes between */
  float f;  /* the upper cell's weight; 0 where the ray meets the lower cell's centre */
  float it; /* 1 / t, t = k len the distance (m) */
  float ct; /* c t */
} fm_step;

/* The tile maxima of the elevations (NaN ignored; -inf for a tile of nodata). 0 when out of
 * memory. */
static int fm_tiles_init(ap_horizon *hz)
{
  const size_t F = AP_FM_FINE, r = AP_FM_COARSE / AP_FM_FINE;
  const size_t fnx = (hz->nx + F - 1) / F;
  float zabs = 0.0f, *fine, *coarse;
  size_t i, j;
  hz->fm_tnx[0] = fnx;
  hz->fm_tnx[1] = (fnx + r - 1) / r;
  if (!fm_tiles_alloc(hz, hz->fm_tile)) {
    return 0;
  }
  fine = hz->fm_tile[0];
  coarse = hz->fm_tile[1];
  for (i = 0; i < hz->nx; ++i) { /* (the transposed copy, in its memory order) */
    const float *zcol = hz->zt + i * hz->ny;
    float *tcol = fine + i / F;
    for (j = 0; j < hz->ny; ++j) {
      const float z = zcol[j];
      tcol[(j / F) * fnx] = z > tcol[(j / F) * fnx] ? z : tcol[(j / F) * fnx];
      zabs = fabsf(z) > zabs ? fabsf(z) : zabs;
    }
  }
  fm_coarsen(hz, fine, coarse);
  /* a + f (b - a) rounds to at most a few units in the last place of the largest |z| above
   * max(a, b); 2^-18 of it is a margin of 32 such units (4 mm at 1000 m) */
  hz->fm_eps = zabs * (1.0f / 262144.0f);
  return !hz->has_nodata || fm_shore_init(hz);
}

/* Both levels of an array of tiles laid out as fm_tile (fm_tnx set), every tile -inf, into
 * t[0] (fine) and t[1] (coarse). 0 when out of memory (what was allocated is in t[], for
 * ap_horizon_destroy). */
static int fm_tiles_alloc(const ap_horizon *hz, float *t[2])
{
  const size_t n0 = hz->fm_tnx[0] * ((hz->ny + AP_FM_FINE - 1) / AP_FM_FINE);
  const size_t n1 = hz->fm_tnx[1] * ((hz->ny + AP_FM_COARSE - 1) / AP_FM_COARSE);
  size_t i;
  t[0] = (float *)malloc(n0 * sizeof(float));
  t[1] = (float *)malloc(n1 * sizeof(float));
  if (!t[0] || !t[1]) {
    return 0;
  }
  for (i = 0; i < n0; ++i) {
    t[0][i] = -INFINITY;
  }
  for (i = 0; i < n1; ++i) {
    t[1][i] = -INFINITY;
  }
  return 1;
}

/* The coarse tiles' maxima from the fine ones' (a coarse tile is r x r fine ones: AP_FM_COARSE
 * divides; both levels -inf-initialised by fm_tiles_alloc). */
static void fm_coarsen(const ap_horizon *hz, float *fine, float *coarse)
{
  const size_t F = AP_FM_FINE, r = AP_FM_COARSE / AP_FM_FINE;
  const size_t fnx = hz->fm_tnx[0], cnx = hz->fm_tnx[1], fny = (hz->ny + F - 1) / F;
  size_t i, j;
  for (j = 0; j < fny; ++j) {
    for (i = 0; i < fnx; ++i) {
      float *t = coarse + (j / r) * cnx + i / r;
      *t = fine[j * fnx + i] > *t ? fine[j * fnx + i] : *t;
    }
  }
}

/* DEMs with nodata: fm_shore, the tiles' maxima of the cells with data that have a nodata cell
 * among their eight neighbours (far_shore_column). 0 when out of memory. */
static int fm_shore_init(ap_horizon *hz)
{
  const size_t nx = hz->nx, ny = hz->ny, F = AP_FM_FINE, fnx = hz->fm_tnx[0];
  unsigned char *near = (unsigned char *)malloc(3 * nx); /* rows j - 1, j, j + 1, cyclically */
  float *fine;
  size_t i, j;
  if (!fm_tiles_alloc(hz, hz->fm_shore) || !near) {
    free(near);
    return 0;
  }
  fine = hz->fm_shore[0];
  /* near[(j % 3) nx + i]: whether row j has nodata in columns i - 1 .. i + 1 */
  for (j = 0; j <= ny; ++j) {
    if (j < ny) {
      const float *z = grid_row(hz, (long)j);
      unsigned char *h = near + (j % 3) * nx;
      for (i = 0; i < nx; ++i) {
        h[i] = (unsigned char)((i > 0 && isnan(z[i - 1])) || isnan(z[i]) ||
                               (i + 1 < nx && isnan(z[i + 1])));
      }
    }
    if (j > 0) { /* row j - 1, with rows j - 2 (if any) and j (if any) read */
      const size_t row = j - 1;
      const float *z = grid_row(hz, (long)row);
      const unsigned char *a = row > 0 ? near + ((row - 1) % 3) * nx : NULL;
      const unsigned char *b = near + (row % 3) * nx, *c = j < ny ? near + (j % 3) * nx : NULL;
      float *t = fine + (row / F) * fnx;
      for (i = 0; i < nx; ++i) {
        if (!isnan(z[i]) && (b[i] || (a && a[i]) || (c && c[i])) && z[i] > t[i / F]) {
          t[i / F] = z[i];
        }
      }
    }
  }
  free(near);
  fm_coarsen(hz, fine, hz->fm_shore[1]);
  return 1;
}

/* The highest cell of the view's side the prepared sector's rays leave through (by the sign of
 * the rows' shift: one sign in every row), -inf when they leave through none. */
static void fm_side_max_init(ap_horizon *hz)
{
  const double m = hz->m_row[0];
  hz->fm_side_max = -INFINITY;
  if (m != 0.0) {
    const size_t e = m > 0.0 ? hz->ns - 1 : 0;
    size_t q;
    for (q = 0; q < hz->np; ++q) {
      const float z = view_column(hz, q)[e];
      hz->fm_side_max = z > hz->fm_side_max ? z : hz->fm_side_max; /* (NaN ignored) */
    }
  }
}

/* The prepared sector's steps 0..fm_kmax (the samples within the distance). 0 when out of
 * memory. */
static int fm_steps_init(ap_horizon *hz)
{
  const double len = hz->len_row[0], L = hz->p.max_distance;
  double m = hz->m_row[0];
  long k;
  /* (no ray takes more steps than the view has columns; a swept sector's L may be infinite) */
  hz->fm_kmax = L / len < (double)(hz->np - 1) ? (long)floor(L / len) : (long)hz->np - 1;
  if (fabs(m) * (double)hz->fm_kmax < 1e-9) {
    m = 0.0; /* a ray along its row (cos(pi/2) is 6e-17, not 0), as build_pattern */
  }
  hz->fm = (fm_step *)malloc((size_t)(hz->fm_kmax + 1) * sizeof(fm_step));
  if (!hz->fm) {
    return 0;
  }
  for (k = 0; k <= hz->fm_kmax; ++k) {
    fm_step_set(&hz->fm[k], m * (double)k, (double)k * len, hz->c);
  }
  if (m != 0.0) {
    fm_side_max_init(hz);
  } else {
    hz->fm_side_max = -INFINITY;
  }
  return 1;
}

/* The lowest and one past the highest view row a ray from row 0 reads at step k. */
AP_INLINE long fm_lo(const fm_step *st)
{
  return st->o;
}

AP_INLINE long fm_hi(const fm_step *st)
{
  return st->o + (st->f != 0.0f ? 2 : 1);
}

/* The last step in [k0 - 1, kend] up to which a ray from view row s stays on the grid (its
 * offsets move one way, so the steps on the grid are a prefix); k0 - 1 when none. */
static long fm_last_on_grid(const ap_horizon *hz, const fm_step *fm, long s, long k0, long kend)
{
  const long ns = (long)hz->ns;
  long lo = k0 - 1, hi = kend; /* invariant: steps up to lo are on the grid */
  while (lo < hi) {
    const long mid = lo + (hi - lo + 1) / 2;
    const fm_step *st = &fm[mid];
    if (s + fm_lo(st) >= 0 && s + fm_hi(st) <= ns) {
      lo = mid;
    } else {
      hi = mid - 1;
    }
  }
  return lo;
}

/* The grid rows [b[0], b[1]] and columns [b[2], b[3]] (clamped to the grid) of every sample
 * that cells [s0, s0 + n) of view column p read at steps [ka, kb]. */
AP_INLINE void fm_box_cells(const ap_horizon *hz, const fm_step *fm, size_t p, long s0, long n,
                            long ka, long kb, long b[4])
{
  const fm_step *sa = &fm[ka], *sb = &fm[kb];
  const long ns = (long)hz->ns;
  long r0 = s0 + (fm_lo(sa) < fm_lo(sb) ? fm_lo(sa) : fm_lo(sb));
  long r1 = s0 + n - 1 + (fm_hi(sa) > fm_hi(sb) ? fm_hi(sa) : fm_hi(sb)) - 1;
  const long qa = (long)prim_index(hz, p + (size_t)ka), qb = (long)prim_index(hz, p + (size_t)kb);
  const long q0 = qa < qb ? qa : qb, q1 = qa < qb ? qb : qa;
  r0 = r0 < 0 ? 0 : r0;
  r1 = r1 > ns - 1 ? ns - 1 : r1;
  b[0] = hz->xmajor ? r0 : q0; /* (x-major: view p = grid column, s = grid row) */
  b[1] = hz->xmajor ? r1 : q1;
  b[2] = hz->xmajor ? q0 : r0;
  b[3] = hz->xmajor ? q1 : r1;
}

/* The largest tile (B cells square) of `tile` (an array laid out as fm_tile[l]) over grid
 * rows [b[0], b[1]] and columns [b[2], b[3]], raised by fm_eps. */
AP_INLINE float fm_box_tiles(const ap_horizon *hz, const float *tile, int l, const long b[4])
{
  const size_t B = l ? AP_FM_COARSE : AP_FM_FINE, tnx = hz->fm_tnx[l];
  size_t i, j;
  float Z = -INFINITY;
  for (j = (size_t)b[0] / B; j <= (size_t)b[1] / B; ++j) {
    for (i = (size_t)b[2] / B; i <= (size_t)b[3] / B; ++i) {
      const float t = tile[j * tnx + i];
      Z = t > Z ? t : Z;
    }
  }
  return Z + hz->fm_eps;
}

/* The box of tile maxima (level l of fm_tile, or of another array of the same tiles) around
 * every sample that cells [s0, s0 + n) of view column p read at steps [ka, kb], raised by
 * fm_eps: at least every elevation those samples interpolate, and that of any cell of those
 * rows and columns between them (-inf when the box holds no data). */
AP_INLINE float fm_box_in(const ap_horizon *hz, const float *tile, const fm_step *fm, int l,
                          size_t p, long s0, long n, long ka, long kb)
{
  long b[4];
  fm_box_cells(hz, fm, p, s0, n, ka, kb, b);
  return fm_box_tiles(hz, tile, l, b);
}

AP_INLINE float fm_box_max(const ap_horizon *hz, const fm_step *fm, int l, size_t p, long s0,
                           long n, long ka, long kb)
{
  return fm_box_in(hz, hz->fm_tile[l], fm, l, p, s0, n, ka, kb);
}

/* Whether a cell at height zq whose slope so far is b could find a larger one at steps
 * [ka, kb] from heights up to Z: a slope at t in [ta, tb] is at most the larger of
 * (Z - zq)/ta and (Z - zq)/tb (by the sign of Z - zq) less c ta. Never for a NaN zq (nodata)
 * or Z = -inf (no data). Each operation is monotonic, so this holds rounded too. */
#define AP_FM_RISES(Z, zq, sa, sb, b)                                                          \
  (((((Z) - (zq)) * (sa)->it > ((Z) - (zq)) * (sb)->it ? ((Z) - (zq)) * (sa)->it              \
                                                        : ((Z) - (zq)) * (sb)->it) -          \
    (sa)->ct) > (b))

#if AP_FM_VECTORS
/* 16 cells as two vectors of 8 (GCC/Clang vector extensions: AVX2 in the avx2 clone, pairs of
 * SSE2 operations in the default one; the same IEEE operations per cell as the scalar code). */
typedef float fm_v8 __attribute__((vector_size(32)));
typedef int fm_i8 __attribute__((vector_size(32)));

typedef long long fm_l4 __attribute__((vector_size(32)));

/* (Macros, not functions: vectors passed or returned by value would change the default
 * clone's calling convention, which GCC warns about.) */
#define AP_FM_LOAD(v, z) memcpy(&(v), (z), sizeof(v))
/* b becomes v where v > b: NaN never wins */
#define AP_FM_MAX(b, v) ((b) = (fm_v8)(((fm_i8)(v) & ((v) > (b))) | ((fm_i8)(b) & ~((v) > (b)))))
/* whether any lane of the mask m is set */
#define AP_FM_ANY(m)                                                                           \
  ((((fm_l4)(m))[0] | ((fm_l4)(m))[1]) != 0 || (((fm_l4)(m))[2] | ((fm_l4)(m))[3]) != 0)

typedef struct fm_lanes {
  fm_v8 zq[2], b[2];
} fm_lanes;

AP_INLINE void fm_lanes_get(fm_lanes *g, const float *zq, const float *b)
{
  AP_FM_LOAD(g->zq[0], zq);
  AP_FM_LOAD(g->zq[1], zq + 8);
  AP_FM_LOAD(g->b[0], b);
  AP_FM_LOAD(g->b[1], b + 8);
}

AP_INLINE void fm_lanes_put(const fm_lanes *g, float *b)
{
  memcpy(b, &g->b[0], sizeof g->b[0]);
  memcpy(b + 8, &g->b[1], sizeof g->b[1]);
}

AP_INLINE int fm_lanes_rise(const fm_lanes *g, float Z, const fm_step *sa, const fm_step *sb)
{
  const float ita = sa->it, itb = sb->it, ct = sa->ct;
  const fm_v8 dz0 = Z - g->zq[0], dz1 = Z - g->zq[1];
  fm_v8 q0 = dz0 * itb, q1 = dz1 * itb; /* the larger of the two quotients, less c ta */
  fm_i8 any;
  AP_FM_MAX(q0, dz0 * ita);
  AP_FM_MAX(q1, dz1 * ita);
  any = ((q0 - ct) > g->b[0]) | ((q1 - ct) > g->b[1]);
  return AP_FM_ANY(any);
}

AP_INLINE void fm_lanes_march(const ap_horizon *hz, const fm_step *fm, size_t p, long s0,
                              long ka, long kb, fm_lanes *g)
{
  long k;
  for (k = ka; k <= kb; ++k) {
    const fm_step *st = &fm[k];
    const float *z = view_column(hz, p + (size_t)k) + s0 + st->o;
    const float it = st->it, ct = st->ct, f = st->f; /* (scalars: broadcast by the compiler) */
    int h;
    for (h = 0; h < 2; ++h) {
      fm_v8 z0, v;
      AP_FM_LOAD(z0, z + 8 * h);
      if (f != 0.0f) {
        fm_v8 z1;
        AP_FM_LOAD(z1, z + 8 * h + 1);
        v = ((z0 + f * (z1 - z0)) - g->zq[h]) * it - ct;
      } else {
        v = (z0 - g->zq[h]) * it - ct;
      }
      AP_FM_MAX(g->b[h], v);
    }
  }
}
#else
typedef struct fm_lanes {
  float zq[AP_FM_LANES], b[AP_FM_LANES];
} fm_lanes;

AP_INLINE void fm_lanes_get(fm_lanes *g, const float *zq, const float *b)
{
  memcpy(g->zq, zq, sizeof g->zq);
  memcpy(g->b, b, sizeof g->b);
}

AP_INLINE void fm_lanes_put(const fm_lanes *g, float *b)
{
  memcpy(b, g->b, sizeof g->b);
}

AP_INLINE int fm_lanes_rise(const fm_lanes *g, float Z, const fm_step *sa, const fm_step *sb)
{
  int c, any = 0;
  for (c = 0; c < AP_FM_LANES; ++c) {
    any |= AP_FM_RISES(Z, g->zq[c], sa, sb, g->b[c]);
  }
  return any;
}

#endif

/* Steps [ka, kb] of one cell (view row s) at height zq, slope so far *b: the same operations
 * as for 16 cells. */
static void fm_march_one(const ap_horizon *hz, const fm_step *fm, size_t p, long s, long ka,
                         long kb, float zq, float *b)
{
  long k;
  for (k = ka; k <= kb; ++k) {
    const fm_step *st = &fm[k];
    const float *z = view_column(hz, p + (size_t)k) + s + st->o;
    /* the slope to the point between z[0] and z[1] (f the weight of z[1]) */
    const float v = st->f != 0.0f ? ((z[0] + st->f * (z[1] - z[0])) - zq) * st->it - st->ct
                                  : (z[0] - zq) * st->it - st->ct;
    *b = v > *b ? v : *b;
  }
}

#if !AP_FM_VECTORS
AP_INLINE void fm_lanes_march(const ap_horizon *hz, const fm_step *fm, size_t p, long s0,
                              long ka, long kb, fm_lanes *g)
{
  int c;
  for (c = 0; c < AP_FM_LANES; ++c) {
    fm_march_one(hz, fm, p, s0 + c, ka, kb, g->zq[c], &g->b[c]);
  }
}
#endif

/* An fm_step for a shift of sh view rows at distance t (m): the two cells the ray passes
 * between, within 1e-9 of a cell that cell alone (as far_offset). */
static void fm_step_set(fm_step *st, double sh, double t, double c)
{
  const double r = nearbyint(sh);
  if (fabs(sh - r) < 1e-9) {
    st->o = (long)r;
    st->f = 0.0f;
  } else {
    st->o = (long)floor(sh);
    st->f = (float)(sh - floor(sh));
  }
  st->it = t > 0.0 ? (float)(1.0 / t) : 0.0f;
  st->ct = (float)(c * t);
}

/* Per-row cell sizes, row-major view: the steps of the rays of view column p (grid row
 * prim_index(p)) to the view columns p + k, into fm[k] and their distances into t[k], from
 * k = 0 until the first beyond the search distance or the far edge, whichever comes first:
 * returns that last k; *kmax is the last within the distance. The shift is the rhumb line's,
 * tan(phi) (Psi(row) - Psi(row of p)) columns, as the sweep's lines (lat_off), and the distance
 * sums the rows' step lengths from p on: both depend on the rows alone, not on where a piece of
 * the DEM starts. Holds at most hz->fm_kmax + 1 steps (the distance over the shortest step). */
static long lattice_steps_col(const ap_horizon *hz, size_t p, fm_step *fm, double *t, long *kmax)
{
  const double L = hz->p.max_distance;
  double dist = 0.0;
  long k;
  *kmax = 0;
  for (k = 0; k <= hz->fm_kmax && p + (size_t)k < hz->np; ++k) {
    if (k > 0) {
      const size_t a = prim_index(hz, p + (size_t)k - 1), b = prim_index(hz, p + (size_t)k);
      dist += 0.5 * (hz->len_row[a] + hz->len_row[b]);
    }
    fm_step_set(&fm[k], hz->lat_off[p + (size_t)k] - hz->lat_off[p], dist, hz->c);
    t[k] = dist;
    if (!(dist <= L)) {
      return k;
    }
    *kmax = k;
  }
  return k - 1;
}

/* Per-row cell sizes, after the far march of view column p along its steps fm[0..kt] (t: their
 * distances; lattice_steps_col): each cell's edge flag from where its own ray leaves the grid
 * (march_edge's extrapolated pattern would be off by the rows' change over the distance), and
 * the point where it leaves through a side beyond the near field and within the distance
 * (side_exit_slope, here between the steps' distances), unless the side's highest cell could
 * not raise its slope. */
static void lattice_finish_col(const ap_horizon *hz, const fm_step *fm, const double *t, long kt,
                               size_t p, long sa, long sb, const float *col, float *best,
                               unsigned char *edge)
{
  const long ns = (long)hz->ns, F = (long)(hz->np - 1 - p), kend = kt < F ? kt : F;
  const double L = hz->p.max_distance, c = hz->c, K1 = (double)(hz->near_field - 1);
  const double side_max = (double)hz->fm_side_max + (double)hz->fm_eps;
  long s;
  for (s = sa; s < sb; ++s) {
    const double zq = col[s];
    double reach = INFINITY;
    long kl = kend;
    if (isnan(zq)) {
      continue; /* (march_finish made it NaN, edge 0) */
    }
    if (!(s + fm_lo(&fm[kend]) >= 0 && s + fm_hi(&fm[kend]) <= ns)) {
      kl = fm_last_on_grid(hz, fm, s, 1, kend);
    }
    if (kl < kend) {
      /* it leaves through a side between steps kl and kl + 1 */
      const double a = (double)s + (double)fm[kl].o + (double)fm[kl].f;
      const double b = (double)s + (double)fm[kl + 1].o + (double)fm[kl + 1].f;
      const long e = b < 0.0 ? 0 : ns - 1;
      const double fr = b != a ? ((double)e - a) / (b - a) : 0.0;
      const double te = t[kl] + fr * (t[kl + 1] - t[kl]);
      reach = te;
      if (te <= L && te > 0.0 && (double)kl + fr > K1 &&
          (side_max - zq) / te - c * te > (double)best[s]) {
        const double za = view_column(hz, p + (size_t)kl)[e];
        const double zb = view_column(hz, p + (size_t)kl + 1)[e];
        const double sl = ((za + fr * (zb - za)) - zq) / te - c * te;
        best[s] = sl > (double)best[s] ? (float)sl : best[s];
      }
    } else if (kend == F) {
      reach = t[F]; /* the far edge */
    }
    edge[s] = search_truncated(reach, L, c, (double)hz->zmax, zq);
  }
}

/* Per-row cell sizes, x-major view: the steps of the rays of grid row s to the view columns
 * p + k, into fm[k], distances into t[k], as lattice_steps_col (the same end and *kmax; also
 * ending one step off the grid's rows). The rhumb line keeps Psi - cot(phi) column constant:
 * at step k it is at the row where Psi = Psi(s) + k cos(phi) / |sin(phi)| on the larger DEM's
 * lattice (as the sweep's lines), and the distance sums the step lengths at the rows it
 * passes (trapezoids of len_row, linear between rows), both functions of the rows alone. */
static long lattice_steps_row(const ap_horizon *hz, long s, fm_step *fm, double *t, long *kmax)
{
  const double L = hz->p.max_distance, cot = cos(hz->phi) / fabs(sin(hz->phi));
  const double T0 = hz->psi[s + hz->orow];
  double dist = 0.0, len_prev = hz->len_row[s], y = (double)s;
  long k, j = s + hz->orow;
  *kmax = 0;
  for (k = 0; k <= hz->fm_kmax && (size_t)k < hz->np; ++k) {
    if (k > 0) {
      const double T = T0 + (double)k * cot;
      double len;
      y = psi_row(hz, T, &j);
      len = row_value(hz->len_row, hz->ny, y);
      dist += 0.5 * (len_prev + len);
      len_prev = len;
    }
    fm_step_set(&fm[k], y - (double)s, dist, hz->c);
    t[k] = dist;
    if (!(dist <= L)) {
      return k;
    }
    *kmax = k;
    if (y < -1.0 || y > (double)hz->ny) {
      return k; /* off the rows: so is every later step */
    }
  }
  return k - 1;
}

/* lattice_finish_col for grid row s of an x-major view after far_march_row: every cell's ray
 * leaves through a side (rows 0 or ny - 1) at the same step and fraction, unless its far edge
 * comes first. */
static void lattice_finish_row(const ap_horizon *hz, const fm_step *fm, const double *t, long kt,
                               long s, const float *zrow, float *best)
{
  const long nx = (long)hz->np, ny = (long)hz->ny, dir = hz->flip ? -1 : 1;
  const double L = hz->p.max_distance, c = hz->c, K1 = (double)(hz->near_field - 1);
  const double side_max = (double)hz->fm_side_max + (double)hz->fm_eps;
  const long kl = fm_last_on_grid(hz, fm, s, 1, kt);
  double fr = 0.0, te = INFINITY;
  long e = 0, q;
  if (kl < kt) {
    const double a = (double)s + (double)fm[kl].o + (double)fm[kl].f;
    const double b = (double)s + (double)fm[kl + 1].o + (double)fm[kl + 1].f;
    e = b < 0.0 ? 0 : ny - 1;
    fr = b != a ? ((double)e - a) / (b - a) : 0.0;
    te = t[kl] + fr * (t[kl + 1] - t[kl]);
  }
  for (q = 0; q < nx; ++q) {
    const double zq = zrow[q];
    const long F = dir > 0 ? nx - 1 - q : q, kend = kt < F ? kt : F;
    const size_t pv = (size_t)(dir > 0 ? q : nx - 1 - q);
    double reach = INFINITY;
    if (isnan(zq)) {
      continue; /* (march_finish_row made it NaN, edge 0) */
    }
    if (kl < kend) {
      reach = te;
      if (te <= L && te > 0.0 && (double)kl + fr > K1 &&
          (side_max - zq) / te - c * te > (double)best[q]) {
        const float *edge_row = grid_row(hz, e);
        const double za = edge_row[q + dir * kl], zb = edge_row[q + dir * (kl + 1)];
        const double sl = ((za + fr * (zb - za)) - zq) / te - c * te;
        best[q] = sl > (double)best[q] ? (float)sl : best[q];
      }
    } else if (kend == F) {
      reach = t[F];
    }
    hz->edge[scratch_index(hz, pv, (size_t)s)] =
      search_truncated(reach, L, c, (double)hz->zmax, zq);
  }
}

/* After the far march of cells [sa, sb) of view column p: the point where a ray leaves
 * through a side beyond the near field, within the distance and before the far edge
 * (side_exit_slope; the near field reaches it when closer), unless the side's highest cell,
 * then the fine tiles of the point's two cells, show it cannot raise the slope found. (Not
 * inlined into far_march_column: its registers are the vector loop's.) */
static void far_side_exits(const ap_horizon *hz, size_t p, long sa, long sb, const float *col,
                           float *best)
{
  const double m = hz->m_row[0], len = hz->len_row[0];
  const long K = hz->near_field;
  if (m != 0.0) {
    const double K1 = (double)(K - 1), L = hz->p.max_distance, c = hz->c;
    const double far_end = (double)(hz->np - 1 - p);
    const long e = m > 0.0 ? (long)hz->ns - 1 : 0;
    const size_t tnx = hz->fm_tnx[0], te = (size_t)e / AP_FM_FINE;
    const double inv_m = 1.0 / m, side_max = (double)hz->fm_side_max + (double)hz->fm_eps;
    /* the cells whose rays can leave within min(far_end, L / len) steps (a margin of a row;
     * the tests below decide) */
    const double reach = fabs(m) * fmin(far_end, L / len) + 1.0;
    long s = sa, s_end = sb;
    if (reach < (double)hz->ns) {
      if (m > 0.0) {
        const long first = (long)hz->ns - 1 - (long)reach;
        s = first > s ? first : s;
      } else {
        const long last = (long)reach + 1;
        s_end = last < s_end ? last : s_end;
      }
    }
    for (; s < s_end; ++s) {
      const double zq = col[s];
      const double k = (double)(m > 0.0 ? (long)hz->ns - 1 - s : -s) * inv_m;
      const double t = k * len;
      if (k > K1 && k < far_end && t <= L && k != floor(k) &&
          (side_max - zq) / t - c * t > (double)best[s]) {
        /* the fine tiles of the two cells bound the point's elevation */
        const size_t q0 = prim_index(hz, p + (size_t)k), q1 = prim_index(hz, p + (size_t)k + 1);
        const size_t a = hz->xmajor ? te * tnx + q0 / AP_FM_FINE : (q0 / AP_FM_FINE) * tnx + te;
        const size_t b = hz->xmajor ? te * tnx + q1 / AP_FM_FINE : (q1 / AP_FM_FINE) * tnx + te;
        const float Z = (hz->fm_tile[0][a] > hz->fm_tile[0][b] ? hz->fm_tile[0][a]
                                                                : hz->fm_tile[0][b]) + hz->fm_eps;
        if (((double)Z - zq) / t - c * t > (double)best[s]) {
          const double sl = side_exit_slope(hz, p, k, e, len, zq);
          best[s] = sl > (double)best[s] ? (float)sl : best[s];
        }
      }
    }
  }
}

/* The far march of cells [sa, sb) of view column p into best[] (max-merged), along the steps
 * fm[0..kmax] (hz->fm, or with per-row cell sizes the column's own: lattice_steps_col). */
AP_MULTIVERSION
static void far_march_column(const ap_horizon *hz, const fm_step *fm, long kmax, size_t p,
                             long sa, long sb, const float *col, float *best)
{
  const long K = hz->near_field;
  long kend = kmax, s0;
  if ((long)(hz->np - 1 - p) < kend) {
    kend = (long)(hz->np - 1 - p); /* the columns left */
  }
  if (kend < K) {
    return;
  }
  for (s0 = sa; s0 < sb; s0 += AP_FM_LANES) {
    const long n = sb - s0 < AP_FM_LANES ? sb - s0 : AP_FM_LANES;
    long kvec = K - 1, k, c;
    if (n == AP_FM_LANES) {
      /* the steps on which all 16 rays stay on the grid: those of both outer cells */
      const long lo = fm_last_on_grid(hz, fm, s0, K, kend);
      const long hi = fm_last_on_grid(hz, fm, s0 + n - 1, K, kend);
      fm_lanes g;
      kvec = lo < hi ? lo : hi;
      fm_lanes_get(&g, col + s0, best + s0);
      for (k = K; k <= kvec;) {
        long k1 = k + AP_FM_COARSE - 1 < kvec ? k + AP_FM_COARSE - 1 : kvec;
        if (!fm_lanes_rise(&g, fm_box_max(hz, fm, 1, p, s0, n, k, k1), &fm[k], &fm[k1])) {
          k = k1 + 1;
          continue;
        }
        k1 = k + AP_FM_FINE - 1 < kvec ? k + AP_FM_FINE - 1 : kvec;
        if (fm_lanes_rise(&g, fm_box_max(hz, fm, 0, p, s0, n, k, k1), &fm[k], &fm[k1])) {
          fm_lanes_march(hz, fm, p, s0, k, k1, &g);
        }
        k = k1 + 1;
      }
      fm_lanes_put(&g, best + s0);
    }
    if (kvec >= kend) {
      continue;
    }
    /* the rest cell by cell: a short group's cells, and the steps after some of the 16 rays
     * left the grid */
    for (c = 0; c < n; ++c) {
      const long last = fm_last_on_grid(hz, fm, s0 + c, kvec + 1, kend);
      const float zq = col[s0 + c];
      for (k = kvec + 1; k <= last;) {
        const long k1 = k + AP_FM_FINE - 1 < last ? k + AP_FM_FINE - 1 : last;
        const float Z = fm_box_max(hz, fm, 0, p, s0 + c, 1, k, k1);
        if (AP_FM_RISES(Z, zq, &fm[k], &fm[k1], best[s0 + c])) {
          fm_march_one(hz, fm, p, s0 + c, k, k1, zq, best + s0 + c);
        }
        k = k1 + 1;
      }
    }
  }
}

/* ---------------------------------------------------------------------------------------- */
/* The far field beside nodata. The far march samples a ray where it crosses the view columns,
 * linear between two cells of the column; where one of them is nodata the sample is not
 * terrain, but the ray still crosses the view rows between two columns, and where both cells
 * of such a crossing have data (a shore, a one-cell-wide pier along a row) that point is
 * terrain: the brute force's, and the near field's (a patch's exit edge). Without these points
 * cells along a coast lost up to 20 degrees beyond the near field (test_nodata_coast: MAE
 * 0.013-0.021, p99 0.20-0.57 deg against the brute force; with them, up to the search
 * distance, 0.0026-0.0037, p99 0.08-0.10, largest 0.36-0.51). Only beside a column sample on
 * nodata, so DEMs without nodata never come here and the far field elsewhere stays the column
 * samples. The two cells of such a crossing each have a nodata cell among their eight
 * neighbours when the ray moves at most one view row per column (the cell of the void sample's
 * column, or the next column's cell beside it), so
 * fm_shore's tiles (the maxima of such cells) bound them and rule out most stretches; where a
 * ray moves more than a row per column (lat/lon rows far from the DEM's centre row), fm_tile's
 * do (every cell). */

/* One ray of the far march, by columns (view column p + k at step k, the cell's view row s;
 * rows = 0) or by rows (grid row s + o, grid column q + dir k; rows = 1, p = q). */
typedef struct shore_ray {
  const ap_horizon *hz;
  int rows;
  size_t p;
  long s, dir;
} shore_ray;

/* The elevation r view rows from the ray's cell on the column it reaches at step k. */
AP_INLINE float shore_cell(const shore_ray *ry, long k, long r)
{
  return ry->rows ? grid_row(ry->hz, ry->s + r)[(long)ry->p + ry->dir * k]
                  : view_column(ry->hz, ry->p + (size_t)k)[ry->s + r];
}

/* Whether the ray's column sample at step k reads a nodata cell (of non-zero weight). */
AP_INLINE int shore_void(const shore_ray *ry, const fm_step *st, long k)
{
  return isnan(shore_cell(ry, k, st->o)) ||
         (st->f != 0.0f && isnan(shore_cell(ry, k, st->o + 1)));
}

AP_INLINE double shore_y(const fm_step *st)
{
  return (double)st->o + (double)st->f;
}

/* The distance of step k: t[k] (per-row cell sizes), or k len (t NULL). */
AP_INLINE double shore_t(const double *t, double len, long k)
{
  return t ? t[k] : (double)k * len;
}

/* Whether a ray crosses a view row strictly between steps a and b (shore_stretch's rows): in
 * integers, from the steps' lower cells and whether they meet them (f = 0). */
AP_INLINE int shore_crosses(const fm_step *a, const fm_step *b)
{
  return b->o > a->o ? a->o + 1 <= (b->f != 0.0f ? b->o : b->o - 1)
                     : b->o + 1 <= (a->f != 0.0f ? a->o : a->o - 1);
}

/* The points where the ray of a cell at height zq crosses a view row between its steps k and
 * k + 1 (view rows y0, y1 from the cell, distances t0, t1), within the distance, linear along
 * that row between its cells on the two columns (NaN, never winning, when either is nodata),
 * max-merged into its slope *b. */
static void shore_stretch(const shore_ray *ry, long k, double y0, double y1, double t0,
                          double t1, double zq, float *b)
{
  const double c = ry->hz->c, L = ry->hz->p.max_distance;
  const double hi = y0 > y1 ? y0 : y1;
  double r;
  for (r = floor(y0 < y1 ? y0 : y1) + 1.0; r < hi; r += 1.0) {
    const float za = shore_cell(ry, k, (long)r), zb = shore_cell(ry, k + 1, (long)r);
    if (za == za && zb == zb) { /* (most crossings beside nodata are nodata too) */
      const double fr = (r - y0) / (y1 - y0), t = t0 + fr * (t1 - t0);
      const double z = (double)za + fr * ((double)zb - (double)za);
      const double sl = (z - zq) / t - c * t;
      if (t <= L && sl > (double)*b) {
        *b = (float)sl;
      }
    }
  }
}

/* Stretches k in [ka, kb) (from step k to k + 1, both on the grid) of the ray of a cell at
 * height zq, slope so far *b: shore_stretch where the column sample at either end reads
 * nodata; t: the steps' distances, or NULL for k len. */
static void shore_scan(const shore_ray *ry, const fm_step *fm, const double *t, double len,
                       long ka, long kb, double zq, float *b)
{
  int v0 = shore_void(ry, &fm[ka], ka);
  long k;
  for (k = ka; k < kb; ++k) {
    const int v1 = shore_void(ry, &fm[k + 1], k + 1);
    if ((v0 || v1) && shore_crosses(&fm[k], &fm[k + 1])) {
      shore_stretch(ry, k, shore_y(&fm[k]), shore_y(&fm[k + 1]), shore_t(t, len, k),
                    shore_t(t, len, k + 1), zq, b);
    }
    v0 = v1;
  }
}

/* The last stretch of the rays, from their last step within the distance, kmax (>= 1),
 * towards the next, which lies beyond it but whose crossing may not (the brute force's ray
 * ends at the distance, and the far point there, far_point_column, is bilinear in four cells:
 * NaN beside nodata): both steps' view rows and distances, the next extrapolated from the last
 * two (exact with constant cell sizes; the rows' change over a step otherwise), with its o and
 * f (unsnapped: only its void flag is read); t as shore_scan's. The same for every ray of a
 * view column (by rows: of a grid row). */
typedef struct shore_last {
  fm_step next;
  double y0, y1, t0, t1;
} shore_last;

static void shore_last_init(shore_last *sl, const fm_step *fm, const double *t, double len,
                            long kmax)
{
  sl->y0 = shore_y(&fm[kmax]);
  sl->y1 = 2.0 * sl->y0 - shore_y(&fm[kmax - 1]);
  sl->t0 = shore_t(t, len, kmax);
  sl->t1 = t ? 2.0 * sl->t0 - t[kmax - 1] : shore_t(t, len, kmax + 1);
  sl->next.o = (long)floor(sl->y1);
  sl->next.f = (float)(sl->y1 - floor(sl->y1));
}

/* That last stretch of the ray of a cell at height zq (ry), slope *b, whose ray is on the
 * grid up to step kmax, when the next step is on the grid too (ns rows). */
AP_INLINE void shore_tail(const shore_ray *ry, const fm_step *fm, const shore_last *sl, long kmax,
                          long ns, double zq, float *b)
{
  if (ry->s + fm_lo(&sl->next) >= 0 && ry->s + fm_hi(&sl->next) <= ns &&
      (shore_void(ry, &fm[kmax], kmax) || shore_void(ry, &sl->next, kmax + 1))) {
    shore_stretch(ry, kmax, sl->y0, sl->y1, sl->t0, sl->t1, zq, b);
  }
}

/* The largest of the coarse tiles of `tile` (an array laid out as fm_tile[1]) over grid columns
 * [i0, i1] and rows [j0, j1], clamped to the grid (-inf when that is empty). */
static float shore_region(const ap_horizon *hz, const float *tile, long i0, long i1, long j0,
                          long j1)
{
  const long B = AP_FM_COARSE, tnx = (long)hz->fm_tnx[1];
  float Z = -INFINITY;
  long i, j;
  i0 = i0 < 0 ? 0 : i0;
  j0 = j0 < 0 ? 0 : j0;
  i1 = i1 > (long)hz->nx - 1 ? (long)hz->nx - 1 : i1;
  j1 = j1 > (long)hz->ny - 1 ? (long)hz->ny - 1 : j1;
  for (j = j0 / B; i0 <= i1 && j0 <= j1 && j <= j1 / B; ++j) {
    for (i = i0 / B; i <= i1 / B; ++i) {
      Z = tile[j * tnx + i] > Z ? tile[j * tnx + i] : Z;
    }
  }
  return Z;
}

/* Whether the steps fm[ka..kb] move a ray more than one view row at some step: then the
 * crossings' cells need not lie beside nodata, and fm_tile bounds them instead of fm_shore. */
static int shore_wide(const fm_step *fm, long ka, long kb)
{
  long k;
  for (k = ka; k < kb; ++k) {
    if (fabs(shore_y(&fm[k + 1]) - shore_y(&fm[k])) > 1.0) {
      return 1;
    }
  }
  return 0;
}

/* The rise test (AP_FM_RISES) of n <= 16 cells: bit c set where the cell at height zq[c],
 * slope so far b[c], could find a larger slope at steps [sa, sb] from heights up to Z. */
AP_INLINE unsigned shore_rises(float Z, const float *zq, const float *b, long n, const fm_step *sa,
                               const fm_step *sb)
{
  unsigned r = 0;
  long c;
  if (n == AP_FM_LANES) {
    fm_lanes g; /* (the far march's test of any of 16 first: most stretches rule out all) */
    fm_lanes_get(&g, zq, b);
    if (!fm_lanes_rise(&g, Z, sa, sb)) {
      return 0;
    }
  }
  for (c = 0; c < n; ++c) {
    r |= (unsigned)AP_FM_RISES(Z, zq[c], sa, sb, b[c]) << c;
  }
  return r;
}

/* The void flags of 16 cells' column samples at one step, as bits: bit c set where the ray
 * of lane c reads a nodata cell there (shore_void for 16 cells at once), from its two rows of
 * cells, lo (weight 1 - f) and hi (lo + 1 in a view column; f != 0 only). */
#if AP_FM_VECTORS
AP_INLINE unsigned shore_voids(const float *lo, const float *hi, float f)
{
  fm_v8 a0, a1;
  fm_i8 m0, m1;
  int v[8], c;
  unsigned bits = 0;
  AP_FM_LOAD(a0, lo);
  AP_FM_LOAD(a1, lo + 8);
  m0 = a0 != a0;
  m1 = a1 != a1;
  if (f != 0.0f) {
    fm_v8 b0, b1;
    AP_FM_LOAD(b0, hi);
    AP_FM_LOAD(b1, hi + 8);
    m0 |= b0 != b0;
    m1 |= b1 != b1;
  }
  {
    const fm_i8 w0 = { 1, 2, 4, 8, 16, 32, 64, 128 };
    const fm_i8 w1 = { 256, 512, 1024, 2048, 4096, 8192, 16384, 32768 };
    const fm_i8 w = (m0 & w0) | (m1 & w1);
    memcpy(v, &w, sizeof w);
  }
  for (c = 0; c < 8; ++c) {
    bits |= (unsigned)v[c];
  }
  return bits;
}
#else
AP_INLINE unsigned shore_voids(const float *lo, const float *hi, float f)
{
  unsigned bits = 0;
  int c;
  for (c = 0; c < AP_FM_LANES; ++c) {
    bits |= (unsigned)(isnan(lo[c]) || (f != 0.0f && isnan(hi[c]))) << c;
  }
  return bits;
}
#endif

/* The lowest set bit's index of m != 0. */
AP_INLINE int shore_lowest(unsigned m)
{
#if AP_FM_VECTORS
  return __builtin_ctz(m);
#else
  int c = 0;
  while (!((m >> c) & 1u)) {
    ++c;
  }
  return c;
#endif
}

/* For the cells `lanes` (bits) of a group of 16 (cell c: view row base + c by columns, grid
 * column base + c by rows; height zq[c], slope b[c]) whose rays stay on the grid over steps
 * [ka, kb]: shore_stretch on each stretch [k, k + 1] in [ka, kb) where the column sample at
 * either end reads nodata, from the void bits vm[k - ka] of the steps (shore_voids): the
 * same stretches as shore_scan's, each cell's in the same order. */
static void shore_lanes(shore_ray *ry, const fm_step *fm, const double *t, double len, long ka,
                        long kb, const unsigned *vm, unsigned lanes, long base, const float *zq,
                        float *b)
{
  long k;
  for (k = ka; k < kb; ++k) {
    unsigned m = (vm[k - ka] | vm[k + 1 - ka]) & lanes;
    if (!m || !shore_crosses(&fm[k], &fm[k + 1])) {
      continue; /* (the same steps for the 16 rays) */
    }
    for (; m; m &= m - 1u) {
      const int c = shore_lowest(m);
      if (ry->rows) {
        ry->p = (size_t)(base + c);
      } else {
        ry->s = base + c;
      }
      shore_stretch(ry, k, shore_y(&fm[k]), shore_y(&fm[k + 1]), shore_t(t, len, k),
                    shore_t(t, len, k + 1), zq[c], b + c);
    }
  }
}

/* DEMs with nodata, after the far march of cells [sa, sb) of view column p (steps fm[0..kmax];
 * t their distances with per-row cell sizes, NULL with constant ones): the crossings beside
 * nodata (above) within the distance, max-merged into best[]. A group of 16 cells skips a
 * stretch of 64, then 16 steps whose box of samples (fm_box_cells) lies in grid rows or
 * columns without nodata (box_may_void: no sample there is void, so no crossing is taken; two
 * look-ups where the tiles take several) or whose tiles cannot raise any of its slopes, as the
 * far march does (the tiles bound the crossings of the stretches between the box's first and
 * last steps); in a stretch that some can raise, each of those cells evaluates the crossings
 * next to its column samples on nodata (found for the 16 at once while all their rays are on
 * the grid, else cell by cell), then the last, partial step (shore_tail). */
AP_MULTIVERSION
static void far_shore_column(const ap_horizon *hz, const fm_step *fm, const double *t, long kmax,
                             size_t p, long sa, long sb, const float *col, float *best)
{
  const long K = hz->near_field, k0 = K - 1 > 1 ? K - 1 : 1; /* (t > 0 from step 1 on) */
  const long ns = (long)hz->ns;
  const double len = hz->len_row[0];
  long kend = kmax, s0;
  const float *const *tiles;
  shore_ray ry;
  if ((long)(hz->np - 1 - p) < kend) {
    kend = (long)(hz->np - 1 - p); /* the columns left */
  }
  if (kend <= k0) {
    return;
  }
  /* (constant cell sizes: the view's shift per column, |m| <= 1) */
  tiles = (const float *const *)((t ? shore_wide(fm, k0, kend) : fabs(hz->m_row[0]) > 1.0)
                                   ? hz->fm_tile
                                   : hz->fm_shore);
  {
    /* none of the crossings' cells anywhere on the rays (and the last, partial step's
     * column): nothing to do, as along most columns of a DEM with a few voids */
    const long pe = (long)p + kend + 1 < (long)hz->np ? (long)p + kend + 1 : (long)hz->np - 1;
    const long lo = fm_lo(&fm[kend]) < 0 ? fm_lo(&fm[kend]) : 0;
    const long hi = fm_hi(&fm[kend]) > 1 ? fm_hi(&fm[kend]) : 1;
    const long r0 = sa + lo - 2, r1 = sb - 1 + hi + 2; /* (the partial step: 2 rows more) */
    const long q0 = (long)prim_index(hz, p), q1 = (long)prim_index(hz, (size_t)pe);
    const long qa = q0 < q1 ? q0 : q1, qb = q0 < q1 ? q1 : q0;
    if ((hz->xmajor ? shore_region(hz, tiles[1], qa, qb, r0, r1)
                    : shore_region(hz, tiles[1], r0, r1, qa, qb)) == -INFINITY) {
      return;
    }
  }
  ry.hz = hz;
  ry.rows = 0;
  ry.p = p;
  ry.s = sa;
  ry.dir = 1;
  for (s0 = sa; s0 < sb; s0 += AP_FM_LANES) {
    const long n = sb - s0 < AP_FM_LANES ? sb - s0 : AP_FM_LANES;
    long last[AP_FM_LANES], k, c;
    for (c = 0; c < n; ++c) {
      last[c] = -1; /* each ray's last step on the grid, when needed */
    }
    for (k = k0; k < kend; k += AP_FM_COARSE) {
      const long k1 = k + AP_FM_COARSE < kend ? k + AP_FM_COARSE : kend;
      long kf, b[4];
      if (s0 + fm_lo(&fm[k]) > ns - 1 || s0 + n - 1 + fm_hi(&fm[k]) - 1 < 0) {
        break; /* every ray has left the grid (the box would hold no row of it) */
      }
      fm_box_cells(hz, fm, p, s0, n, k, k1, b);
      if (!box_may_void(hz, b) ||
          !shore_rises(fm_box_tiles(hz, tiles[1], 1, b), col + s0, best + s0, n, &fm[k],
                       &fm[k1])) {
        continue;
      }
      for (kf = k; kf < k1; kf += AP_FM_FINE) {
        const long kf1 = kf + AP_FM_FINE < k1 ? kf + AP_FM_FINE : k1;
        unsigned r;
        if (s0 + fm_lo(&fm[kf]) > ns - 1 || s0 + n - 1 + fm_hi(&fm[kf]) - 1 < 0) {
          break;
        }
        fm_box_cells(hz, fm, p, s0, n, kf, kf1, b);
        r = box_may_void(hz, b) ? shore_rises(fm_box_tiles(hz, tiles[0], 0, b), col + s0,
                                              best + s0, n, &fm[kf], &fm[kf1])
                                : 0u;
        if (!r) {
          continue;
        }
        if (n == AP_FM_LANES && s0 + fm_lo(&fm[kf1]) >= 0 && s0 + n - 1 + fm_hi(&fm[kf1]) <= ns) {
          /* (the outer rays on the grid at kf1: every ray at every step up to it) */
          unsigned vm[AP_FM_FINE + 1], acc = 0;
          long j;
          for (j = kf; j <= kf1; ++j) {
            const float *z = view_column(hz, p + (size_t)j) + s0 + fm[j].o;
            vm[j - kf] = shore_voids(z, z + 1, fm[j].f);
            acc |= vm[j - kf];
          }
          if (acc & r) {
            shore_lanes(&ry, fm, t, len, kf, kf1, vm, acc & r, s0, col + s0, best + s0);
          }
          continue;
        }
        for (c = 0; c < n; ++c) {
          long kb;
          if (!((r >> c) & 1u)) {
            continue;
          }
          if (last[c] < 0) {
            last[c] = fm_last_on_grid(hz, fm, s0 + c, k0, kend);
          }
          kb = kf1 < last[c] ? kf1 : last[c];
          if (kb > kf) {
            ry.s = s0 + c;
            shore_scan(&ry, fm, t, len, kf, kb, col[s0 + c], best + s0 + c);
          }
        }
      }
    }
    if (kend == kmax && (long)(hz->np - 1 - p) > kmax) {
      shore_last sl;
      shore_last_init(&sl, fm, t, len, kmax);
      for (c = 0; c < n; ++c) {
        const long sc = s0 + c;
        if (sc + fm_lo(&fm[kmax]) >= 0 && sc + fm_hi(&fm[kmax]) <= ns && !isnan(col[sc])) {
          /* (on the grid up to the distance, and a column beyond) */
          ry.s = sc;
          shore_tail(&ry, fm, &sl, kmax, ns, col[sc], best + sc);
        }
      }
    }
  }
}

/* ---------------------------------------------------------------------------------------- */
/* The far march by rows: x-major sectors of grids with per-row cell sizes. The rays of the
 * cells of one grid row s follow the same rhumb line, moved by a column from cell to cell
 * (the row's steps, lattice_steps_row: rows s + o .. s + o + 1 at step k), so 16 neighbouring
 * cells of the row march together, reading 16 contiguous cells of each of the two grid rows
 * at columns q0 + dir k (dir = -1 in flipped views), with the same operations per cell as
 * fm_march_one. best[] and zrow[] are indexed by grid column, as in near_row. */

/* fm_box_cells for the cells of columns [q0, q0 + n) of grid row s. */
AP_INLINE void fm_box_cells_rows(const ap_horizon *hz, const fm_step *fm, long s, long q0,
                                 long n, long dir, long ka, long kb, long b[4])
{
  const fm_step *sa = &fm[ka], *sb = &fm[kb];
  const long ny = (long)hz->ny, nx = (long)hz->nx;
  const long r0 = s + (fm_lo(sa) < fm_lo(sb) ? fm_lo(sa) : fm_lo(sb));
  const long r1 = s + (fm_hi(sa) > fm_hi(sb) ? fm_hi(sa) : fm_hi(sb)) - 1;
  const long c0 = dir > 0 ? q0 + ka : q0 - kb, c1 = dir > 0 ? q0 + n - 1 + kb : q0 + n - 1 - ka;
  b[0] = r0 < 0 ? 0 : r0;
  b[1] = r1 > ny - 1 ? ny - 1 : r1;
  b[2] = c0 < 0 ? 0 : c0;
  b[3] = c1 > nx - 1 ? nx - 1 : c1;
}

/* The box of tile maxima (level l) around every sample that the cells of columns
 * [q0, q0 + n) of grid row s read at steps [ka, kb], raised by fm_eps. */
AP_INLINE float fm_box_in_rows(const ap_horizon *hz, const float *tile, const fm_step *fm, int l,
                               long s, long q0, long n, long dir, long ka, long kb)
{
  long b[4];
  fm_box_cells_rows(hz, fm, s, q0, n, dir, ka, kb, b);
  return fm_box_tiles(hz, tile, l, b);
}

AP_INLINE float fm_box_max_rows(const ap_horizon *hz, const fm_step *fm, int l, long s, long q0,
                                long n, long dir, long ka, long kb)
{
  return fm_box_in_rows(hz, hz->fm_tile[l], fm, l, s, q0, n, dir, ka, kb);
}

/* Steps [ka, kb] of the cell of grid column q in row s at height zq, slope so far *b. */
static void fm_march_one_rows(const ap_horizon *hz, const fm_step *fm, long s, long q, long dir,
                              long ka, long kb, float zq, float *b)
{
  long k;
  for (k = ka; k <= kb; ++k) {
    const fm_step *st = &fm[k];
    const long col = q + dir * k;
    const float z0 = grid_row(hz, s + st->o)[col];
    const float v = st->f != 0.0f
                      ? ((z0 + st->f * (grid_row(hz, s + st->o + 1)[col] - z0)) - zq) * st->it -
                          st->ct
                      : (z0 - zq) * st->it - st->ct;
    *b = v > *b ? v : *b;
  }
}

#if AP_FM_VECTORS
AP_INLINE void fm_lanes_march_rows(const ap_horizon *hz, const fm_step *fm, long s, long q0,
                                   long dir, long ka, long kb, fm_lanes *g)
{
  long k;
  for (k = ka; k <= kb; ++k) {
    const fm_step *st = &fm[k];
    const float *z = grid_row(hz, s + st->o) + q0 + dir * k;
    const float it = st->it, ct = st->ct, f = st->f;
    int h;
    if (f != 0.0f) {
      const float *z1 = grid_row(hz, s + st->o + 1) + q0 + dir * k;
      for (h = 0; h < 2; ++h) {
        fm_v8 a, b, v;
        AP_FM_LOAD(a, z + 8 * h);
        AP_FM_LOAD(b, z1 + 8 * h);
        v = ((a + f * (b - a)) - g->zq[h]) * it - ct;
        AP_FM_MAX(g->b[h], v);
      }
    } else {
      for (h = 0; h < 2; ++h) {
        fm_v8 a, v;
        AP_FM_LOAD(a, z + 8 * h);
        v = (a - g->zq[h]) * it - ct;
        AP_FM_MAX(g->b[h], v);
      }
    }
  }
}
#else
AP_INLINE void fm_lanes_march_rows(const ap_horizon *hz, const fm_step *fm, long s, long q0,
                                   long dir, long ka, long kb, fm_lanes *g)
{
  int c;
  for (c = 0; c < AP_FM_LANES; ++c) {
    fm_march_one_rows(hz, fm, s, q0 + c, dir, ka, kb, g->zq[c], &g->b[c]);
  }
}
#endif

/* The far march of grid row s (every column) along the row's steps fm[0..kmax], max-merged
 * into best[] (indexed by grid column). */
AP_MULTIVERSION
static void far_march_row(const ap_horizon *hz, const fm_step *fm, long kmax, long s,
                          const float *zrow, float *best)
{
  const long K = hz->near_field, nx = (long)hz->np, dir = hz->flip ? -1 : 1;
  long side, q0, k, c;
  if (kmax < K) {
    return;
  }
  side = fm_last_on_grid(hz, fm, s, K, kmax); /* the steps between the sides */
  for (q0 = 0; q0 < nx; q0 += AP_FM_LANES) {
    const long n = nx - q0 < AP_FM_LANES ? nx - q0 : AP_FM_LANES;
    long kvec = K - 1;
    if (n == AP_FM_LANES) {
      /* the steps on which all 16 rays stay on the grid: the lane nearest the far edge ends
       * first */
      const long fe = dir > 0 ? nx - 1 - (q0 + n - 1) : q0;
      fm_lanes g;
      kvec = side < fe ? side : fe;
      fm_lanes_get(&g, zrow + q0, best + q0);
      for (k = K; k <= kvec;) {
        long k1 = k + AP_FM_COARSE - 1 < kvec ? k + AP_FM_COARSE - 1 : kvec;
        if (!fm_lanes_rise(&g, fm_box_max_rows(hz, fm, 1, s, q0, n, dir, k, k1), &fm[k],
                           &fm[k1])) {
          k = k1 + 1;
          continue;
        }
        k1 = k + AP_FM_FINE - 1 < kvec ? k + AP_FM_FINE - 1 : kvec;
        if (fm_lanes_rise(&g, fm_box_max_rows(hz, fm, 0, s, q0, n, dir, k, k1), &fm[k],
                          &fm[k1])) {
          fm_lanes_march_rows(hz, fm, s, q0, dir, k, k1, &g);
        }
        k = k1 + 1;
      }
      fm_lanes_put(&g, best + q0);
    }
    /* the rest cell by cell: a short group's cells, and the steps after the first far edge */
    for (c = 0; c < n; ++c) {
      const long q = q0 + c, fe = dir > 0 ? nx - 1 - q : q;
      const long last = side < fe ? side : fe;
      const float zq = zrow[q];
      for (k = kvec + 1 > K ? kvec + 1 : K; k <= last;) {
        const long k1 = k + AP_FM_FINE - 1 < last ? k + AP_FM_FINE - 1 : last;
        const float Z = fm_box_max_rows(hz, fm, 0, s, q, 1, dir, k, k1);
        if (AP_FM_RISES(Z, zq, &fm[k], &fm[k1], best[q])) {
          fm_march_one_rows(hz, fm, s, q, dir, k, k1, zq, best + q);
        }
        k = k1 + 1;
      }
    }
  }
}

/* far_shore_column for grid row s of an x-major view after far_march_row (steps fm[0..kmax],
 * distances t): best[] and zrow[] indexed by grid column. */
AP_MULTIVERSION
static void far_shore_row(const ap_horizon *hz, const fm_step *fm, const double *t, long kmax,
                          long s, const float *zrow, float *best)
{
  const long K = hz->near_field, k0 = K - 1 > 1 ? K - 1 : 1;
  const long nx = (long)hz->np, ny = (long)hz->ny, dir = hz->flip ? -1 : 1;
  const float *const *tiles;
  long side, q0;
  shore_ray ry;
  shore_last sl;
  if (kmax <= k0) {
    return;
  }
  side = fm_last_on_grid(hz, fm, s, k0, kmax); /* the steps between the sides */
  tiles = (const float *const *)(shore_wide(fm, k0, kmax) ? hz->fm_tile : hz->fm_shore);
  {
    /* (as in far_shore_column: no crossing's cells along the row's rays) */
    const long lo = fm_lo(&fm[kmax]) < 0 ? fm_lo(&fm[kmax]) : 0;
    const long hi = fm_hi(&fm[kmax]) > 1 ? fm_hi(&fm[kmax]) : 1;
    if (shore_region(hz, tiles[1], 0, nx - 1, s + lo - 2, s + hi + 2) == -INFINITY) {
      return;
    }
  }
  shore_last_init(&sl, fm, t, 0.0, kmax);
  ry.hz = hz;
  ry.rows = 1;
  ry.p = 0;
  ry.s = s;
  ry.dir = dir;
  for (q0 = 0; q0 < nx; q0 += AP_FM_LANES) {
    const long n = nx - q0 < AP_FM_LANES ? nx - q0 : AP_FM_LANES;
    long last[AP_FM_LANES], k, c, kg = k0;
    for (c = 0; c < n; ++c) { /* each ray's last step on the grid: a side or the far edge */
      const long q = q0 + c, fe = dir > 0 ? nx - 1 - q : q;
      last[c] = side < fe ? side : fe;
      kg = last[c] > kg ? last[c] : kg;
    }
    for (k = k0; k < kg; k += AP_FM_COARSE) {
      const long k1 = k + AP_FM_COARSE < kg ? k + AP_FM_COARSE : kg;
      long kf, b[4];
      fm_box_cells_rows(hz, fm, s, q0, n, dir, k, k1, b);
      if (!box_may_void(hz, b) ||
          !shore_rises(fm_box_tiles(hz, tiles[1], 1, b), zrow + q0, best + q0, n, &fm[k],
                       &fm[k1])) {
        continue;
      }
      for (kf = k; kf < k1; kf += AP_FM_FINE) {
        const long kf1 = kf + AP_FM_FINE < k1 ? kf + AP_FM_FINE : k1;
        unsigned r;
        fm_box_cells_rows(hz, fm, s, q0, n, dir, kf, kf1, b);
        r = box_may_void(hz, b) ? shore_rises(fm_box_tiles(hz, tiles[0], 0, b), zrow + q0,
                                              best + q0, n, &fm[kf], &fm[kf1])
                                : 0u;
        if (!r) {
          continue;
        }
        if (n == AP_FM_LANES && kf1 <= side && kf1 <= (dir > 0 ? nx - 1 - (q0 + n - 1) : q0)) {
          /* (every ray of the 16 on the grid up to kf1) */
          unsigned vm[AP_FM_FINE + 1], acc = 0;
          long j;
          for (j = kf; j <= kf1; ++j) {
            const long qk = q0 + dir * j;
            const float *lo = grid_row(hz, s + fm[j].o) + qk;
            const float *hi = fm[j].f != 0.0f ? grid_row(hz, s + fm[j].o + 1) + qk : lo;
            vm[j - kf] = shore_voids(lo, hi, fm[j].f);
            acc |= vm[j - kf];
          }
          if (acc & r) {
            shore_lanes(&ry, fm, t, 0.0, kf, kf1, vm, acc & r, q0, zrow + q0, best + q0);
          }
          continue;
        }
        for (c = 0; c < n; ++c) {
          const long kb = kf1 < last[c] ? kf1 : last[c];
          if (((r >> c) & 1u) && kb > kf) {
            ry.p = (size_t)(q0 + c);
            shore_scan(&ry, fm, t, 0.0, kf, kb, zrow[q0 + c], best + q0 + c);
          }
        }
      }
    }
    for (c = 0; c < n; ++c) {
      const long q = q0 + c, fe = dir > 0 ? nx - 1 - q : q;
      if (side >= kmax && fe > kmax && !isnan(zrow[q])) {
        /* (on the grid up to the distance, a column beyond) */
        ry.p = (size_t)q;
        shore_tail(&ry, fm, &sl, kmax, ny, zrow[q], best + q);
      }
    }
  }
}

/* Row by row (hz->by_rows: x-major views of grids with per-row cell sizes, whose rows take
 * their own patterns in runs of a few rows, too short for near_column's vectors): the same
 * operations for every cell in the same order, so the same results bit for bit, but each
 * record applied to a whole view row, whose cells lie along a grid row: contiguous in grid
 * column q (view column p = q, or nx - 1 - q in flipped views). best[] is indexed by q. */
AP_MULTIVERSION
static void near_row(const ap_horizon *hz, const pattern *pt, long s, const float *zrow,
                     float *best)
{
  const long ns = (long)hz->ns, nx = (long)hz->np;
  const float cf = (float)hz->c;
  size_t r;
  for (r = 0; r < pt->n; ++r) {
    const patch_rec *rec = &hz->recs[pt->first + r];
    const long dp = rec->dp, ds = rec->ds;
    const float *lo_row, *hi_row;
    long a0, a1, qlo, qhi, q, clo, chi;
    if (dp + 1 >= nx) {
      break; /* (near_column: off the grid for every view column from here on) */
    }
    if (s + ds >= 0 && s < ns - 1 - ds) {
      lo_row = grid_row(hz, s + ds);
      hi_row = grid_row(hz, s + ds + 1);
    } else if (rec->wb == 0.0f && rec->v1 == 0.0f && s == ns - 1 - ds) {
      lo_row = hi_row = grid_row(hz, s + ds); /* (near_column's last-row case) */
    } else {
      continue;
    }
    /* the cells with p + dp + 1 < np; the corners' grid columns q + a0 and q + a1 */
    if (hz->flip) {
      a0 = -dp;
      a1 = -dp - 1;
      qlo = dp + 1;
      qhi = nx;
    } else {
      a0 = dp;
      a1 = dp + 1;
      qlo = 0;
      qhi = nx - dp - 1;
    }
    /* (the corners' grid columns: from qlo + the smaller of a0, a1 to qhi - 1 + the larger) */
    clo = qlo + (a0 < a1 ? a0 : a1);
    chi = qhi - 1 + (a0 < a1 ? a1 : a0);
    if (!hz->has_nodata || rec->ea < 0 ||
        (all_data(hz, (size_t)(s + ds), clo, chi) &&
         all_data(hz, (size_t)(s + ds + (hi_row != lo_row)), clo, chi))) {
      for (q = qlo; q < qhi; ++q) {
        const float v = patch_slope(rec, cf, zrow[q], lo_row[q + a0], lo_row[q + a1],
                                    hi_row[q + a0], hi_row[q + a1]);
        best[q] = v > best[q] ? v : best[q];
      }
    } else {
      /* (near_column's exit edges) */
      const float *za = (rec->ea >> 1 ? hi_row : lo_row) + (rec->ea & 1 ? a1 : a0);
      const float *zb = (rec->eb >> 1 ? hi_row : lo_row) + (rec->eb & 1 ? a1 : a0);
      for (q = qlo; q < qhi; ++q) {
        const float v = patch_slope(rec, cf, zrow[q], lo_row[q + a0], lo_row[q + a1],
                                    hi_row[q + a0], hi_row[q + a1]);
        const float ve = exit_slope(rec, cf, zrow[q], za[q], zb[q]);
        const float u = v == v ? v : ve;
        best[q] = u > best[q] ? u : best[q];
      }
    }
  }
}

/* far_point_column for view row s (x-major views). */
static void far_point_row(const ap_horizon *hz, const pattern *pt, long s, const float *zrow,
                          float *best)
{
  const double L = hz->p.max_distance, c = hz->c, K = (double)hz->near_field;
  const double cl = c * L;
  const long ns = (long)hz->ns;
  const size_t np = hz->np;
  const double ls = far_offset(pt);
  const double of = floor(ls), t = ls - of;
  const float *r0, *r1;
  long o, up;
  size_t p;
  if (!(fabs(of) < (double)ns) || !(L > K * hz->len_row[s])) {
    return;
  }
  o = (long)of;
  up = t == 0.0 ? 0 : 1;
  if (s < -o || s >= ns - o - up) {
    return;
  }
  r0 = grid_row(hz, s + o);
  r1 = grid_row(hz, s + o + up);
  for (p = 0; p < np; ++p) {
    const double pf = (double)p + pt->lp;
    const size_t qp = prim_index(hz, p);
    size_t p0, q0, q1;
    double tp, sl;
    if (!(pf >= 0.0) || pf > (double)(np - 1)) {
      continue;
    }
    p0 = (size_t)pf;
    tp = pf - (double)p0;
    q0 = prim_index(hz, p0);
    q1 = tp == 0.0 ? q0 : prim_index(hz, p0 + 1);
    sl = far_slope(r0[q0], r1[q0], r0[q1], r1[q1], t, tp, zrow[qp], L, cl);
    best[qp] = sl > (double)best[qp] ? (float)sl : best[qp];
  }
}

/* march_finish for view row s (x-major views). */
static void march_finish_row(const ap_horizon *hz, const pattern *pt, long s, const float *zrow,
                             float *best)
{
  size_t p;
  for (p = 0; p < hz->np; ++p) {
    const size_t q = prim_index(hz, p);
    const double zq = zrow[q];
    unsigned char *edge = hz->edge + scratch_index(hz, p, (size_t)s);
    if (isnan(zq)) {
      best[q] = NAN;
      *edge = 0;
      continue;
    }
    *edge = march_edge(hz, pt, p, s, zq);
  }
}

static ap_status near_field_rows(const ap_horizon *hz, size_t r0, size_t r1)
{
  const size_t nx = hz->np;
  const int far_point = !hz->march && isfinite(hz->p.max_distance);
  const size_t cap = hz->far_march ? (size_t)hz->fm_kmax + 1 : 1;
  float *best = (float *)malloc(nx * sizeof(float));
  fm_step *fm = (fm_step *)malloc(cap * sizeof(fm_step));
  double *t = (double *)malloc(cap * sizeof(double));
  size_t s, q;
  if (!best || !fm || !t) {
    free(best);
    free(fm);
    free(t);
    return AP_ERR_OUT_OF_MEMORY;
  }
  /* (the region's rows: a row's cells march together, so all of them) */
  for (s = r0 > hz->vs0 ? r0 : hz->vs0; s < r1 && s < hz->vs1; ++s) {
    const pattern *pt = &hz->pats[hz->pat_of[s]];
    const float *zrow = grid_row(hz, (long)s);
    for (q = 0; q < nx; ++q) {
      best[q] = -INFINITY;
    }
    near_row(hz, pt, (long)s, zrow, best);
    if (far_point) {
      far_point_row(hz, pt, (long)s, zrow, best);
    }
    if (hz->march || hz->far_march) {
      march_finish_row(hz, pt, (long)s, zrow, best);
    }
    if (hz->far_march) {
      /* (per-row cell sizes: the far march of constant ones runs by columns) */
      long kmax;
      const long kt = lattice_steps_row(hz, (long)s, fm, t, &kmax);
      far_march_row(hz, fm, kmax, (long)s, zrow, best);
      if (hz->has_nodata) {
        far_shore_row(hz, fm, t, kmax, (long)s, zrow, best);
      }
      lattice_finish_row(hz, fm, t, kt, (long)s, zrow, best);
    }
    for (q = 0; q < nx; ++q) {
      hz->slope[q * hz->ny + s] = best[q]; /* (scratch_index of x-major views) */
    }
  }
  free(best);
  free(fm);
  free(t);
  return AP_OK;
}

/* The near field of units [u0, u1) into the slope scratch: view columns, or view rows when
 * hz->by_rows. */
ap_status ap_horizon_near_field(const ap_horizon *hz, size_t u0, size_t u1)
{
  size_t p;
  if (!hz) {
    return AP_ERR_NULL_POINTER;
  }
  if (hz->d < 0) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  if (hz->by_rows) {
    return near_field_rows(hz, u0, u1);
  }
  /* the region's view columns, and its cells of them: [vs0, vs1) */
  if (u0 < hz->vp0) {
    u0 = hz->vp0;
  }
  if (u1 > hz->vp1) {
    u1 = hz->vp1;
  }
  for (p = u0; p < u1; ++p) {
    const float *col = view_column(hz, p);
    float *best = hz->slope + scratch_index(hz, p, 0);
    const long vs0 = (long)hz->vs0, ns = (long)hz->vs1;
    /* in row-major views, whether the point at the search distance lies beyond the near field
     * is the same for the whole column; x-major views check each row */
    const int far_point =
      !hz->march && isfinite(hz->p.max_distance) &&
      (hz->xmajor || hz->p.max_distance > (double)hz->near_field *
                                             view_step(hz->cum_len, hz->np, p));
    long run, s;
    for (s = vs0; s < ns; ++s) {
      best[s] = -INFINITY;
    }
    for (run = vs0; run < ns;) {
      long run_end = ns;
      int pat;
      if (hz->xmajor) {
        pat = hz->pat_of[run];
        run_end = run + 1;
        while (run_end < ns && hz->pat_of[run_end] == pat) {
          ++run_end;
        }
      } else {
        pat = hz->pat_of[p];
      }
      {
        long a = run, b = run_end; /* (nodata cells keep -inf: their NaN never wins) */
        clamp_to_data(hz, p, &a, &b);
        if (a < b) {
          near_column(hz, &hz->pats[pat], p, a, b, col, hz->c, best);
          if (far_point) {
            far_point_column(hz, &hz->pats[pat], p, a, b, col, best);
          }
        }
      }
      if (hz->march || hz->far_march) {
        /* (before the far march below: a nodata cell's NaN never changes there) */
        march_finish(hz, &hz->pats[pat], p, run, run_end, col, best,
                     hz->edge + scratch_index(hz, p, 0));
      }
      run = run_end;
    }
  }
  if (hz->far_march) {
    /* By chunks of AP_FM_CHUNK cells across the units' columns, so that the view columns their
     * rays cross stay in cache from one unit to the next (a 2048^2 grid at 10 km, one core:
     * 49-50 instead of 54-55 ns per cell and direction; no gain measured on 4096^2). */
    const long vs0 = (long)hz->vs0, ns = (long)hz->vs1;
    long s0;
    if (hz->lattice) {
      /* per-row cell sizes (row-major views; x-major ones go by rows): each view column's
       * rays take their own steps, so a column at a time */
      const size_t cap = (size_t)hz->fm_kmax + 1;
      fm_step *fm = (fm_step *)malloc(cap * sizeof(fm_step));
      double *t = (double *)malloc(cap * sizeof(double));
      if (!fm || !t) {
        free(fm);
        free(t);
        return AP_ERR_OUT_OF_MEMORY;
      }
      for (p = u0; p < u1; ++p) {
        long kmax;
        const long kt = lattice_steps_col(hz, p, fm, t, &kmax);
        float *best = hz->slope + scratch_index(hz, p, 0);
        long a = vs0, b = ns;
        clamp_to_data(hz, p, &a, &b);
        if (a < b) {
          far_march_column(hz, fm, kmax, p, a, b, view_column(hz, p), best);
          if (hz->has_nodata) {
            far_shore_column(hz, fm, t, kmax, p, a, b, view_column(hz, p), best);
          }
        }
        lattice_finish_col(hz, fm, t, kt, p, vs0, ns, view_column(hz, p), best,
                           hz->edge + scratch_index(hz, p, 0));
      }
      free(fm);
      free(t);
      return AP_OK;
    }
    for (s0 = vs0; s0 < ns; s0 += AP_FM_CHUNK) {
      const long s1 = s0 + AP_FM_CHUNK < ns ? s0 + AP_FM_CHUNK : ns;
      for (p = u0; p < u1; ++p) {
        float *best = hz->slope + scratch_index(hz, p, 0);
        long a = s0, b = s1; /* (nodata cells: their NaN never raises a slope) */
        clamp_to_data(hz, p, &a, &b);
        if (a < b) {
          far_march_column(hz, hz->fm, hz->fm_kmax, p, a, b, view_column(hz, p), best);
          far_side_exits(hz, p, a, b, view_column(hz, p), best);
          if (hz->has_nodata) {
            far_shore_column(hz, hz->fm, NULL, hz->fm_kmax, p, a, b, view_column(hz, p), best);
          }
        }
      }
    }
  }
  return AP_OK;
}

/* Parallel lines (hz->parallel): how far every line moves sideways (view rows) from view column
 * p to q > p, and how far along (m). */
AP_INLINE double par_shift(const ap_horizon *hz, size_t p, size_t q)
{
  if (hz->xmajor) {
    return (double)(q - p) * hz->m_row[0];
  }
  return hz->lattice ? hz->lat_off[q] - hz->lat_off[p] : hz->cum_m[q] - hz->cum_m[p];
}

AP_INLINE double par_dist(const ap_horizon *hz, size_t p, size_t q)
{
  return hz->xmajor ? (double)(q - p) * hz->len_row[0] : hz->cum_len[q] - hz->cum_len[p];
}

/* Parallel lines: the last view column on which the ray of view cell (p, sq) is on the grid
 * (the ray moves one way: a binary search). */
static size_t ray_end(const ap_horizon *hz, size_t p, double sq)
{
  const double smax = (double)(hz->ns - 1);
  size_t lo = p, hi = hz->np - 1; /* the ray is on the grid up to lo */
  while (lo < hi) {
    const size_t mid = lo + (hi - lo + 1) / 2;
    const double sn = sq + par_shift(hz, p, mid);
    if (sn >= 0.0 && sn <= smax) {
      lo = mid;
    } else {
      hi = mid - 1;
    }
  }
  return lo;
}

/* Whether nothing at distance d (m) or beyond can rise above slope best for a cell at
 * height zq: the DEM's highest cell, a micrometre higher for rounding, at distance d is no
 * higher (that bound only falls with d). The marches below stop there. */
AP_INLINE int march_done(double zb, double zq, double c, double d, double best)
{
  return (zb > zq ? zb - zq : 0.0) - c * d * d <= best * d;
}

/* The DEM's highest cell, as march_done takes it. */
AP_INLINE double march_top(const ap_horizon *hz)
{
  return (double)hz->zmax + 1e-6 * (fabs((double)hz->zmax) + 1.0);
}

/* Parallel lines: the largest slope of view cell (p, sq) at height zq on its own ray from view
 * column g > p on, as long as the ray stays on the grid and within the distance, sampled as
 * the hulls' samples are, and at the point where it leaves the grid through a side between
 * two columns, linear along that edge row (as side_exit_slope in the far march) when that
 * lies within the distance (-inf when none); it stops where nothing farther could rise above
 * the larger of what it found and least, the caller's slope (so it may return less than
 * least). See the sweep's uses near a side of the DEM and beside nodata. */
static double ray_march(const ap_horizon *hz, size_t p, double sq, double zq, size_t g,
                        double least)
{
  const double smax = (double)(hz->ns - 1), L = hz->p.max_distance, c = hz->c;
  const double zb = march_top(hz);
  double best = -INFINITY;
  double sp = sq + par_shift(hz, p, g - 1), dp = par_dist(hz, p, g - 1); /* column q - 1 */
  size_t q;
  for (q = g; q < hz->np; ++q) {
    const double sn = sq + par_shift(hz, p, q), dn = par_dist(hz, p, q);
    double zn;
    if (!(sn >= 0.0 && sn <= smax)) {
      if (sp >= 0.0 && sp <= smax && sn != sp) {
        /* leaves through the side between columns q - 1 and q */
        const double edge = sn < 0.0 ? 0.0 : smax, f = (edge - sp) / (sn - sp);
        const double de = dp + f * (dn - dp);
        if (de <= L && de > 0.0) {
          const float *a = view_column(hz, q - 1), *b = view_column(hz, q);
          const size_t e = (size_t)edge;
          const double ze = a[e] + f * ((double)b[e] - (double)a[e]);
          const double slope = (ze - zq) / de - c * de;
          best = slope > best ? slope : best; /* (NaN never wins) */
        }
      }
      break;
    }
    if (dn > L || (dn > 0.0 && march_done(zb, zq, c, dn, best > least ? best : least))) {
      break;
    }
    zn = interp_snap(view_column(hz, q), smax, sn);
    if (!isnan(zn) && dn > 0.0) {
      const double slope = (zn - zq) / dn - c * dn;
      best = slope > best ? slope : best;
    }
    sp = sn;
    dp = dn;
  }
  return best;
}

/* Bending lines (x-major views of grids with per-row cell sizes): the largest slope of the cell
 * of view column p on grid row j at height zq along its own rhumb line from K view columns on
 * (Psi(row) = Psi(j) + k cot phi at step k, as sweep_side_rows walks it), linear between the
 * two cells of each grid column, as long as the ray stays on the grid and within the distance
 * (-inf when none), stopping as ray_march does above least. The sweep's fallback for a cell
 * whose lines met nodata (see the sweep). */
static double ray_march_rows(const ap_horizon *hz, size_t p, long j, double zq, long K,
                             double least)
{
  const double cphi = cos(hz->phi), sphi = sin(hz->phi);
  const double L = hz->p.max_distance, c = hz->c, smax = (double)(hz->ny - 1);
  const long np = (long)hz->np;
  const double *Y = hz->ycum;
  const int along = hz->row_lines; /* along the row: the row is a line (lattice_lines) */
  const double cot = cphi / fabs(sphi), zb = march_top(hz);
  double best = -INFINITY;
  long k, jj = j + hz->orow;
  for (k = K; (long)p + k < np; ++k) {
    const double y = along ? (double)j : psi_row(hz, hz->psi[j + hz->orow] + (double)k * cot, &jj);
    double t, z;
    if (y < 0.0 || y > smax) {
      break; /* (left through a side) */
    }
    t = along ? (double)k * hz->len_row[j]
              : fabs(row_value(Y, hz->ny, y) - Y[j]) / fabs(cphi);
    if (t > L || (t > 0.0 && march_done(zb, zq, c, t, best > least ? best : least))) {
      break;
    }
    z = interp_snap(view_column(hz, p + (size_t)k), smax, y); /* (x-major: the grid's column) */
    if (t > 0.0) {
      const double sl = (z - zq) / t - c * t;
      best = sl > best ? sl : best; /* (NaN never wins) */
    }
  }
  return best;
}

typedef struct line_state {
  double s, x;   /* position on the current column; distance along the line (m) */
  double xend;   /* distance of the farthest sample position inside the grid; NAN: none yet */
  size_t pend;   /* its column */
  double avail;  /* xend - x on the current column (0 when none): how far the line sees */
  int met_nodata; /* a sample of the line on the grid fell on nodata (it was not pushed) */
  int before;    /* bending lines: whether the line has only been beyond a side of the grid,
                  * rows <= 0 (1) or >= ns - 1 (2), up to the previous column; 3 not; 0 not
                  * yet known */
  hull h;        /* unlimited search: the hull of the samples at least K columns away */
  int hint[2];   /* the last tangent index of h for the cell below (0) and above (1) */
  window w;      /* limited search: the window of those samples within the distance */
  hull ghost;    /* DEMs with nodata: the line's samples at least K columns away that fell on
                  * one nodata and one data cell, at that cell's height (see ghost_push) */
  int ghint[2];  /* as hint, for ghost */
} line_state;

/* A sample q of a line that fell on nodata, on view column col: where exactly one of its two
 * cells has data, a ghost at that cell's height goes into the line's ghost hull. The line
 * lost the sample, but a cell's ray between this line and the next reads the same column
 * from the next line's pair of cells, which holds that data cell: without the line's sample
 * the hulls have no bracket for the ray there (a pier seen obliquely, whose one row of data
 * lies between two of nodata, was up to 3.7 degrees low). The ghost, the most the ray reads
 * there unless its pair's other cell is higher (which the next line's hull brackets as it
 * would without nodata), is the sweep's test whether such a ray must be marched
 * (ghost_above). Samples on two nodata cells need none: a ray there reads one of them.
 * 0 when out of memory. */
static int ghost_push(hull *g, const sample *q, const float *col, long ns, double c)
{
  const long r0 = (long)floor(q->s);
  const double za = r0 >= 0 && r0 < ns ? (double)col[r0] : NAN;
  const double zb = r0 + 1 >= 0 && r0 + 1 < ns ? (double)col[r0 + 1] : NAN;
  const double z = isnan(za) ? zb : (isnan(zb) ? za : NAN);
  sample v;
  if (isnan(z)) {
    return 1;
  }
  v = *q;
  v.u = z - c * q->x * q->x;
  return hull_push_near(g, &v);
}

/* Whether a ghost of line ln (ghost_push), the cell's bracketing line e (0 below, 1 above),
 * could give the cell at height zq a slope above best: the largest slope to the ghosts is
 * the tangent's, as for the line's hull. All of them, even beyond a search distance: the
 * march that follows keeps to it. */
AP_INLINE int ghost_above(line_state *ln, int e, double zq, double c, double best)
{
  const sample *v;
  double dn;
  if (ln->ghost.n == 0) {
    return 0;
  }
  v = hull_tangent(&ln->ghost, ln->x, zq - c * ln->x * ln->x, &ln->ghint[1 - e]);
  dn = v->x - ln->x;
  return dn > 0.0 && (v->u + c * v->x * v->x - zq) / dn - c * dn > best;
}

/* Per-row sizes, x-major (bending lines): the view row of line k at view column p, where
 * ap_horizon_sweep puts it (the row where Psi = sigma k + lat_off[p], linear on its segment of
 * the larger DEM's rows); j is a segment hint for lattice_seek (-1: none). */
AP_INLINE double lattice_row(const ap_horizon *hz, long k, size_t p, long *j)
{
  if (hz->row_lines) {
    return (double)(k - hz->orow);
  }
  return psi_row(hz, hz->sigma * (double)k + hz->lat_off[p], j);
}

/* The view rows of the first and the last of the lines k0 .. k0 + nl - 1 at view column p, where
 * ap_horizon_sweep puts them: parallel lines moved by par_shift from the last column, or on the
 * lattice; bending lines on theirs (lattice_row). */
AP_INLINE void band_rows(const ap_horizon *hz, long k0, size_t nl, size_t p, double *first,
                         double *last)
{
  if (hz->parallel) {
    *first = hz->lattice ? ((double)k0 + hz->lat_off[p]) - (double)hz->ocol
                         : ((double)k0 + hz->phase) - par_shift(hz, p, hz->np - 1);
    *last = *first + (double)(nl - 1);
  } else {
    long j = -1;
    *first = lattice_row(hz, k0, p, &j);
    *last = lattice_row(hz, k0 + (long)(nl - 1), p, &j);
  }
}

/* The view columns [*pa, *pb) on which some of the lines k0 .. k0 + nl - 1 lie within view
 * rows [lo, hi]; *pb <= *pa when none. Every line's row moves one way with p, all of them the
 * same way (the band's first row is monotonic in p, and so is its last), so the columns are an
 * interval: binary searches, so that a band of a long, narrow DEM does not walk every column
 * of it. */
static void band_columns(const ap_horizon *hz, long k0, size_t nl, double lo, double hi,
                         size_t *pa, size_t *pb)
{
  const size_t np = hz->np;
  double r0, r1, e0, e1;
  int up;
  size_t a = 0, b = np;
  band_rows(hz, k0, nl, 0, &r0, &r1);
  band_rows(hz, k0, nl, np - 1, &e0, &e1);
  up = r0 <= e0;
  while (a < b) { /* the first column where the band has reached the rows */
    const size_t mid = a + (b - a) / 2;
    band_rows(hz, k0, nl, mid, &r0, &r1);
    if (up ? r1 >= lo : r0 <= hi) {
      b = mid;
    } else {
      a = mid + 1;
    }
  }
  *pa = a;
  a = 0;
  b = np;
  while (a < b) { /* the first column where it has left them */
    const size_t mid = a + (b - a) / 2;
    band_rows(hz, k0, nl, mid, &r0, &r1);
    if (up ? r0 > hi : r1 < lo) {
      b = mid;
    } else {
      a = mid + 1;
    }
  }
  *pb = a;
}

/* Whether the band of nl lines from bracket b0 brackets a cell of the region at some view
 * column of it (a margin of two cells). A band that does not has nothing to compute. */
static int band_meets_region(const ap_horizon *hz, size_t b0, size_t nl)
{
  size_t pa, pb;
  if (hz->vs0 == 0 && hz->vs1 == hz->ns) {
    return 1; /* (every band brackets some cell of every view column) */
  }
  band_columns(hz, hz->kmin + (long)b0, nl, (double)hz->vs0 - 2.0,
               (double)hz->vs1 + 1.0, &pa, &pb);
  return (pa > hz->vp0 ? pa : hz->vp0) < (pb < hz->vp1 ? pb : hz->vp1);
}

/* ap_horizon_sweep, compiled twice: nodata (a constant) keeps the rare cases' bookkeeping of
 * DEMs with nodata out of the other's loop, where it cost 2% of the sweep's instructions. */
AP_INLINE ap_status sweep(const ap_horizon *hz, size_t b0, size_t b1, const int nodata)
{
  int K, limited, W;
  double L, c;
  size_t np, ns, nl, l, pp, pcol0, pcol1;
  line_state *lines = NULL;
  sample *ring = NULL; /* per line, K pending samples (u NaN: none) */
  unsigned char *remarch = NULL; /* per cell of the column: its ray is to be marched */
  size_t nremarch = 0;
  double shift, xc, x0, k0, phase, smax;
  long jfirst = -1; /* per-row sizes, x-major: the first line's segment of rows (lattice_seek) */
  ap_status st = AP_OK;
  if (!hz) {
    return AP_ERR_NULL_POINTER;
  }
  if (hz->d < 0) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  if (hz->march || hz->far_march) {
    return AP_OK; /* the near field did it all */
  }
  K = hz->near_field;
  limited = isfinite(hz->p.max_distance);
  L = hz->p.max_distance;
  c = hz->c;
  np = hz->np;
  ns = hz->ns;
  smax = (double)(ns - 1);
  /* A window holds the samples of at most L / (shortest step) + 1 columns, plus the K - 1
   * pending ones; a ring a little longer never overwrites a sample still in use. */
  W = limited ? (int)fmin((double)np + 2.0, ceil(L / hz->shortest) + (double)K + 4.0) : 0;
  if (b1 > ap_horizon_bracket_count(hz)) {
    b1 = ap_horizon_bracket_count(hz);
  }
  if (b0 >= b1) {
    return AP_OK;
  }
  nl = b1 - b0 + 1; /* brackets b0..b1-1 need lines b0..b1 */
  if (!band_meets_region(hz, b0, nl)) {
    return AP_OK; /* (with a region: its cells lie beside this band's lines) */
  }
  lines = (line_state *)calloc(nl, sizeof(line_state));
  ring = (sample *)malloc(nl * (size_t)K * sizeof(sample));
  remarch = nodata ? (unsigned char *)calloc(ns, 1) : NULL;
  if (!lines || !ring || (nodata && !remarch)) {
    st = AP_ERR_OUT_OF_MEMORY;
    goto done;
  }
  for (l = 0; l < nl; ++l) {
    int r;
    lines[l].s = (double)(hz->kmin + (long)(b0 + l)) + hz->phase;
    /* Distances are measured from the middle of the line so that c x^2 stays modest. */
    lines[l].x = 0.5 * (double)(np - 1) * hz->len_row[hz->ny / 2];
    lines[l].xend = NAN;
    lines[l].w.newest = -1;
    for (r = 0; r < K; ++r) {
      ring[l * (size_t)K + (size_t)r].u = NAN;
      ring[l * (size_t)K + (size_t)r].col = -1;
    }
  }

  /* Parallel lines: line l sits at s = (k0 + l + phase) - shift with shift and distance xc
   * shared (k0 + l is the line's whole number, so its position does not depend on b0). */
  shift = 0.0;
  x0 = xc = lines[0].x;
  k0 = (double)(hz->kmin + (long)b0);
  phase = hz->phase;
  /* the band's columns [pcol0, pcol1) (within two rows of the grid: outside, a band brackets
   * no cell) */
  band_columns(hz, hz->kmin + (long)b0, nl, -2.0, (double)ns + 1.0, &pcol0, &pcol1);
  if (limited && pcol1 > pcol0 && (double)(pcol1 - pcol0) + 2.0 < (double)W) {
    /* every sample of the band lies on its columns, so a window never holds more than those:
     * a band crossing a long, narrow DEM in a few columns gets rings of a few samples, not of
     * the distance's columns (each line's ring is written whole when it starts) */
    W = (int)(pcol1 - pcol0) + 2;
  }
  if (!hz->parallel && pcol1 < np) {
    /* bending lines starting after the last column: each one's row on the column before
     * (lines[l].s is the row of the previous column p + 1 in the loop below) */
    long j = -1;
    for (l = 0; l < nl; ++l) {
      lines[l].s = lattice_row(hz, hz->kmin + (long)(b0 + l), pcol1, &j);
    }
  }

  for (pp = pcol1; pp-- > pcol0;) {
    const size_t p = pp;
    const float *col = view_column(hz, p);
    const int slot = (int)(p % (size_t)K);
    long cell;
    if (p < hz->vp0) {
      break; /* past the region: nothing more to query */
    }
    /* A band touches a cache line or two of each column's elevations and scratch, one page
     * (4 KiB or more) apart from the previous column's: no hardware prefetcher follows that,
     * so fetch a few columns ahead. */
    if (p >= AP_PREFETCH_COLUMNS) {
      const size_t pf = p - AP_PREFETCH_COLUMNS;
      const double s_first = hz->parallel && !hz->lattice ? k0 + phase - shift : lines[0].s;
      /* the band's first and last cells, kept inside the column (a band can lie wholly
       * beside the grid at this column, and a pointer past the column is not to be formed) */
      const size_t sa =
        s_first <= 0.0 ? 0 : (s_first < (double)(ns - 1) ? (size_t)s_first : ns - 1);
      const size_t sb = sa + nl < ns ? sa + nl : ns - 1;
      AP_PREFETCH(view_column(hz, pf) + sa);
      AP_PREFETCH(view_column(hz, pf) + sb);
      AP_PREFETCH(hz->slope + scratch_index(hz, pf, sa));
      AP_PREFETCH(hz->slope + scratch_index(hz, pf, sb));
      AP_PREFETCH(hz->edge + scratch_index(hz, pf, sa));
    }
    /* 1. Move the lines to column p and take the samples of those inside the grid (delayed
     *    into the hulls by K - 1 columns through the ring; a slot remembers its column). */
    if (!hz->parallel) {
      /* Per-row sizes, x-major: the lines bend; each one's row from the lattice (see
       * lattice_lines), its distance stepped with the length of the step it ends. (What the
       * loop reads of hz in locals: the stores below might alias hz for the compiler.) */
      const double off = hz->lat_off[p], sigma = hz->sigma, orow = (double)hz->orow;
      const double *const psi = hz->psi, *const psi_inv = hz->psi_inv;
      const long last = (long)hz->nw - 2, kfirst = hz->kmin + (long)b0;
      const int row_lines = hz->row_lines;
      long j = 0;
      for (l = 0; l < nl; ++l) {
        line_state *ln = &lines[l];
        const double T = sigma * (double)(kfirst + (long)l) + off;
        if (p + 1 < np) {
          /* the step from the previous column, by the length at the line's row there; while
           * the line has come from beyond one side of the grid (clamped lengths), in closed
           * form, so that its distances do not depend on the column its band starts on */
          const double sp = ln->s;
          const int side = sp >= smax ? 2 : (!(sp > 0.0) ? 1 : 0);
          if (ln->before == 0) {
            ln->before = side ? side : 3; /* (the line's first step) */
          }
          if (ln->before == side) {
            ln->x = x0 - (double)(np - 1 - p) * hz->len_row[side == 2 ? hz->ny - 1 : 0];
          } else {
            ln->before = 3;
            ln->x -= row_value(hz->len_row, hz->ny, sp);
          }
        }
        if (row_lines) {
          ln->s = (double)(kfirst + (long)l) - orow; /* (line k: the larger DEM's row k) */
        } else {
          if (l == 0) {
            /* the band's first line: from its segment on the previous column */
            j = jfirst = lattice_seek(hz, T, jfirst);
          } else {
            /* the next ones lie higher, about a row apart: walk up (one step, mostly) */
            while (j < last && psi[j + 1] <= T) {
              ++j;
            }
          }
          /* the larger DEM's row where Psi = T (linear on segment j), in this grid's rows */
          ln->s = ((double)j + (T - psi[j]) * psi_inv[j]) - orow;
        }
        if (ln->s >= 0.0 && ln->s <= smax) {
          sample *q = &ring[l * (size_t)K + (size_t)slot];
          if (isnan(ln->xend)) {
            ln->xend = ln->x;
          }
          q->x = ln->x;
          q->u = interp_nd(col, smax, ln->s, nodata) - c * ln->x * ln->x;
          q->s = ln->s;
          q->col = (long)p;
        }
        ln->avail = isnan(ln->xend) ? 0.0 : ln->xend - ln->x;
      }
    } else {
      /* Parallel lines: every line has the same shift and distance, so only those inside are
       * touched. */
      /* (in closed form: a band starts at its first column on the grid, band_columns) */
      shift = par_shift(hz, p, np - 1);
      xc = x0 - par_dist(hz, p, np - 1);
      if (hz->lattice) {
        /* per-row sizes, row-major: line k at column k + lat_off[p] of the larger DEM */
        const double off = hz->lat_off[p], oc = (double)hz->ocol;
        for (l = 0; l < nl; ++l) {
          lines[l].s = ((double)(hz->kmin + (long)(b0 + l)) + off) - oc;
        }
      } else {
        /* line l is at s = k0 + l + phase - shift */
        for (l = 0; l < nl; ++l) {
          /* ((long): a one-instruction conversion) */
          lines[l].s = (k0 + (double)(long)l + phase) - shift;
        }
      }
      for (l = 0; l < nl; ++l) {
        lines[l].x = xc;
        lines[l].avail = isnan(lines[l].xend) ? 0.0 : lines[l].xend - xc;
      }
      {
        /* the lines inside, 0 <= s <= ns - 1: s = l - a up to rounding, so the bounds one
         * wider and each line's own s tested (a depends on the band's first line, s does not:
         * which lines are inside, and where each line ends (pend), must not depend on the
         * split into bands) */
        const double a = hz->lattice ? (double)hz->ocol - hz->lat_off[p] - k0 : shift - k0 - phase;
        const double lo = ceil(a) - 1.0, hi = floor((double)(ns - 1) + a) + 1.0;
        const size_t la = lo > 0.0 ? (size_t)lo : 0;
        const size_t lb = hi < 0.0 ? 0 : (hi + 1.0 < (double)nl ? (size_t)hi + 1 : nl);
        for (l = la; l < lb; ++l) {
          line_state *ln = &lines[l];
          sample *q = &ring[l * (size_t)K + (size_t)slot];
          if (!(ln->s >= 0.0 && ln->s <= smax)) {
            continue;
          }
          if (isnan(ln->xend)) {
            ln->xend = xc; /* avail stays 0 */
            ln->pend = p;
          }
          q->x = xc;
          q->u = interp_nd(col, smax, ln->s, nodata) - c * xc * xc; /* NaN on nodata */
          q->s = ln->s;
          q->col = (long)p;
        }
      }
    }

    /* 2. Every cell of column p bracketed by this band's lines (in the region). */
    l = 0;
    if (p < hz->vp1) {
      /* the sector scratch of this column (contiguous there) and what the loop reads of hz, in
       * locals */
      const size_t out_base = scratch_index(hz, p, 0);
      float *const slope_out = hz->slope + out_base;
      unsigned char *const edge_out = hz->edge + out_base;
      const float *const *const colp = hz->colp;
      const double zmax = (double)hz->zmax;
      const int parallel = hz->parallel;
      const double first = lines[0].s, last = lines[nl - 1].s;
      const long vs0 = (long)hz->vs0, vs1 = (long)hz->vs1;
      const long s_first = first <= 0.0 ? 0 : (long)ceil(first);
      const long s_last = last > (double)ns ? (long)ns : (long)ceil(last);
      const long s_begin = s_first > vs0 ? s_first : vs0, s_end = s_last < vs1 ? s_last : vs1;
      for (cell = s_begin; cell < s_end; ++cell) {
        const double sq = (double)cell;
        const double zq = col[cell];
        double near = slope_out[cell], far = -INFINITY, avail;
        while (l + 2 < nl && lines[l + 1].s <= sq) {
          ++l;
        }
        if (isnan(zq)) {
          slope_out[cell] = NAN;
          edge_out[cell] = 0;
          continue;
        }
        /* Far field: the hulls of the two bracketing lines, each queried with the cell's own
         * height for the column of its tangent point; the cell's own ray is then evaluated on
         * those columns (the cell keeps its lateral offset from the line). Blending the two
         * lines' slopes instead is off by a degree where the horizon is reached everywhere
         * along the ray (planes, V-valleys): the two tangent points then lie at very different
         * distances. u = z - c x^2 makes the curvature exact (ALGORITHMS.md 3.5). */
        {
          line_state *bl[2];
          long done = -1; /* the column the cell's ray was evaluated on */
          int e, lost = 0; /* a line's tangent lay where the cell's ray is off the grid */
          /* rare cases, flagged off the common path: a line's tangent lay where the cell's
           * ray meets nodata (AP_VOID_HIT), or could not be used at all (AP_FAILED); a line
           * gave none, all it met within reach being nodata (AP_VOID_LINE) */
          unsigned rare = 0;
          bl[0] = &lines[l];
          bl[1] = &lines[l + 1];
          AP_UNROLL_2
          for (e = 0; e < 2; ++e) {
            line_state *ln = bl[e];
            const sample *v;
            if (limited) {
              /* The tangent to all samples behind is the window's too when it lies within
               * the distance (the window is a subset holding it); only beyond it does the
               * window's own search run. */
              const double uq = zq - c * ln->x * ln->x;
              window *w = &ln->w;
              if (w->active && !window_evict(w, ln->x + L)) {
                st = AP_ERR_OUT_OF_MEMORY;
                goto done;
              }
              v = hull_tangent(&ln->h, ln->x, uq, &ln->hint[1 - e]);
              if (v && v->x > ln->x + L) {
                if (!w->active && !window_activate(w, ln->x + L)) {
                  st = AP_ERR_OUT_OF_MEMORY;
                  goto done;
                }
                w->idle = 0;
                v = window_tangent(w, ln->x, uq);
              }
            } else {
              v = hull_tangent(&ln->h, ln->x, zq - c * ln->x * ln->x, &ln->hint[1 - e]);
            }
            double sn, zn, dn, slope;
            if (!v) {
              if (nodata) {
                rare |= ln->met_nodata ? AP_VOID_LINE : 0u;
              }
              continue;
            }
            if (parallel && v->col == done) {
              continue; /* parallel lines: the same column is the same point of the ray */
            }
            done = v->col;
            sn = sq + (v->s - ln->s);
            if (parallel && !(sn >= 0.0 && sn <= smax)) {
              lost = 1;
              rare |= AP_FAILED;
              continue;
            }
            zn = interp_nd(colp[v->col], smax, sn, nodata);
            dn = v->x - ln->x;
            if (isnan(zn) || !(dn > 0.0)) {
              rare |= isnan(zn) && sn >= 0.0 && sn <= smax ? AP_VOID_HIT | AP_FAILED : AP_FAILED;
              continue;
            }
            slope = (zn - zq) / dn - c * dn;
            if (slope > far) {
              far = slope;
            }
          }
          if (parallel && hz->side != 0) {
            /* Near a side of the DEM. Rays leave through the side s = 0 (side -1) or
             * s = ns - 1, and the bracketing line on that side leaves first, at its column
             * pend (or has left at p already): the hulls hold nothing of the cell's ray after
             * that (one line has ended, the other passes beside it). And where the other
             * line's tangent lies beyond the end of the cell's ray (lost), its terrain along
             * the side is out of the cell's reach, but the cell's ray passes within a cell of
             * it over its last side_cols columns. A bowl's rim seen along a side was missed by
             * up to 4.5 degrees 20 cells from the edge, 33 on the edge row. So the cell's own
             * ray is sampled over those stretches (at most side_cols columns), unless the
             * DEM's highest cell there could not raise its slope. */
            const line_state *in = bl[hz->side < 0 ? 0 : 1];
            size_t g = (!isnan(in->xend) && in->s >= 0.0 && in->s <= smax) ? in->pend + 1 : p + 1;
            if (lost) {
              const size_t end = ray_end(hz, p, sq);
              const size_t back = end > hz->side_cols ? end - hz->side_cols : 0;
              g = back < g ? back : g;
            }
            g = g > p + (size_t)K ? g : p + (size_t)K;
            if (g < np) {
              /* (the point where the ray leaves may lie before column g, after g - 1) */
              const double d0 = par_dist(hz, p, g - 1), best = near > far ? near : far;
              if (d0 <= L && !(d0 > 0.0 && march_done(march_top(hz), zq, c, d0, best))) {
                const double gs = ray_march(hz, p, sq, zq, g, -INFINITY);
                far = gs > far ? gs : far;
              }
            }
          }
          if (nodata && ((far == -INFINITY &&
                          ((rare & AP_VOID_HIT) ||
                           (rare & (AP_VOID_LINE | AP_FAILED)) == (AP_VOID_LINE | AP_FAILED))) ||
                         ghost_above(bl[0], 0, zq, c, near > far ? near : far) ||
                         ghost_above(bl[1], 1, zq, c, near > far ? near : far))) {
            /* The hulls cannot say what else the ray meets, so it is marched: where neither
             * line gave the cell a slope because one's tangent lay where the cell's ray meets
             * nodata, or one could not be used and the other met only nodata within reach
             * (without it such a cell lost its whole horizon along a shore, up to 74 degrees;
             * 37 on lat/lon rows), and where a sample a line lost to nodata beside data could
             * rise above the cell's slope (ghost_above: up to 7 degrees past a gap or along
             * nodata). 0.4-1.6% of the cell-directions of DEMs with a coast, voids or 1%
             * scattered nodata, 2.4% with a nodata row and column every few dozen cells
             * (512^2, unlimited); see march_done. Where both lines met only nodata and gave no
             * slope, so does the ray, nearly: it is not marched (a coast's cells looking out
             * to sea, which took half again the sweep's time). */
            remarch[cell] = 1; /* (after the column's cells: a call here slows the loop) */
            ++nremarch;
          }
          avail = bl[0]->avail < bl[1]->avail ? bl[0]->avail : bl[1]->avail;
        }
        slope_out[cell] = (float)(near > far ? near : far);
        /* With constant cell sizes the cell's own ray says where it leaves the grid, as the
         * marches take it: the nearer bracketing line can leave a column earlier, at once
         * beside a side of the DEM, which flagged the second ring of cells where the limit
         * was under a cell (until 2026-12-07); per-row sizes keep the lines' reach (their
         * rhumb lines' ends are not extrapolated: ap_horizon.h) */
        edge_out[cell] = hz->lattice ? search_truncated(avail, L, c, zmax, zq)
                                     : march_edge(hz, hz->pats, p, cell, zq);
      }
      for (cell = s_begin; nremarch > 0 && cell < s_end; ++cell) {
        if (remarch[cell]) {
          /* (rounding to float is monotonic: the float max is the rounded max of all three;
           * the march stops where nothing could rise above the cell's slope so far) */
          const double zc = col[cell], fl = slope_out[cell];
          const float gs = (float)(!parallel ? ray_march_rows(hz, p, cell, zc, K, fl)
                                   : p + (size_t)K < np ? ray_march(hz, p, (double)cell, zc,
                                                                    p + (size_t)K, fl)
                                                        : -INFINITY);
          slope_out[cell] = gs > slope_out[cell] ? gs : slope_out[cell];
          remarch[cell] = 0;
          --nremarch;
        }
      }
    }

    /* 3. Feed the hulls with the samples of column p + K - 1, so that for column p - 1 they
     *    hold exactly the samples at least K columns away. */
    if (p + (size_t)K - 1 < np) {
      const int fslot = (int)((p + (size_t)K - 1) % (size_t)K);
      for (l = 0; l < nl; ++l) {
        const sample *q = &ring[l * (size_t)K + (size_t)fslot];
        int ok;
        if (q->col != (long)(p + (size_t)K - 1) || isnan(q->u)) {
          if (nodata && q->col == (long)(p + (size_t)K - 1)) {
            lines[l].met_nodata = 1;
            if (!ghost_push(&lines[l].ghost, q, hz->colp[q->col], (long)ns, c)) {
              st = AP_ERR_OUT_OF_MEMORY;
              goto done;
            }
          }
          continue; /* no sample there: the line was outside the grid, or on nodata */
        }
        ok = hull_push_near(&lines[l].h, q) && (!limited || window_push(&lines[l].w, q, W));
        if (!ok) {
          st = AP_ERR_OUT_OF_MEMORY;
          goto done;
        }
      }
    }
  }

done:
  if (lines) {
    for (l = 0; l < nl; ++l) {
      window_free(&lines[l].w);
      hull_free(&lines[l].h);
      hull_free(&lines[l].ghost);
    }
  }
  free(lines);
  free(ring);
  free(remarch);
  return st;
}

ap_status ap_horizon_sweep(const ap_horizon *hz, size_t b0, size_t b1)
{
  return hz && hz->has_nodata ? sweep(hz, b0, b1, 1) : sweep(hz, b0, b1, 0);
}

/* Tangents above this are clamped (an elevation angle within 1e-18 rad of the zenith), so that
 * their squares stay finite in single precision. */
#define AP_TAN_MAX 1e18f

/* The per-cell terms of one sector for n cells, in single precision: the cosine ce and sine se
 * of the effective horizon (tangent te), its zenith distance u (ap_zenith_distance: accurate
 * to float's relative precision up to the zenith), and the arctangent of the terrain horizon
 * (tangent tt_in, the sector scratch, contiguous), tangents times the cells' 1 / rho (inv: 1
 * without p.scale_metric, which changes no bit). Branch-free so that it vectorises (AVX2 clone
 * where available, the same operations in the same order). A nodata cell (tt NaN) gets
 * meaningless terms, which ap_horizon_finish overwrites. */
AP_MULTIVERSION
static void sector_terms(size_t n, const float *tt_in, const float *inv, const float *grad,
                         float sphi, float cphi, int want_ht, float *restrict ce_out,
                         float *restrict se_out, float *restrict u_out, float *restrict ht_out)
{
  size_t k;
  for (k = 0; k < n; ++k) {
    const float tt = tt_in[k] * inv[k];
    const float ts = (grad[2 * k] * sphi + grad[2 * k + 1] * cphi) * inv[k];
    /* The sky a cell sees lies above the horizontal, the terrain and its own tangent plane. */
    float te = tt > ts ? tt : ts;
    float ce;
    te = te > 0.0f ? te : 0.0f;
    te = te < AP_TAN_MAX ? te : AP_TAN_MAX;
    ce = 1.0f / sqrtf(1.0f + te * te);
    ce_out[k] = ce;
    se_out[k] = te * ce;
    u_out[k] = ap_zenith_distance(te);
  }
  if (want_ht) {
    for (k = 0; k < n; ++k) {
      ht_out[k] = ap_atanf(tt_in[k] * inv[k]); /* -pi/2 for an empty direction (tt = -inf) */
    }
  }
}

/* Add one sector's terms for the n cells from output index c0 (their edge flags contiguous at
 * e, their terrain horizon tangents at tt, to be multiplied by inv as in sector_terms) to the
 * sums, each weighted by the cell's omega (wt; the horizontal of B by omega / rho, the unit
 * direction once ap_horizon_finish applies S; all 1 without p.scale_metric, which changes no
 * bit). Its own function so that the loops vectorise in the AVX2 clone (the same operations
 * in the same order: no result depends on the clone). The terms that vanish at the zenith keep
 * float's relative precision there (ap_zenith.h): 1 - sin h as cos^2 h / (1 + sin h), and
 * Q(h) from the zenith distance (sector_terms) by ap_zenith_q. */
AP_MULTIVERSION
static void accumulate_terms(const ap_horizon *hz, size_t c0, const unsigned char *restrict e,
                             size_t n, const float *restrict ce, const float *restrict se,
                             const float *restrict u, const float *restrict ht,
                             const float *restrict tt, const float *restrict inv,
                             const float *restrict wt, double sphi, double cphi)
{
  const double delta = 2.0 * AP_PI / (double)hz->p.directions;
  const double w = 2.0 * sin(0.5 * delta);
  const float fdelta = (float)delta, fhalf_delta = (float)(0.5 * delta);
  const float wsphi = (float)(w * sphi), wcphi = (float)(w * cphi), half_pi = (float)AP_HALF_PI;
  const ap_sky_products *o = &hz->out;
  float *A = o->visible_solid_angle ? o->visible_solid_angle : o->aperture_radius;
  float *B = o->bent_normal ? o->bent_normal : hz->bsum;
  const int D = hz->p.directions, d = hz->d;
  size_t k;
  if (hz->first) { /* the first sector starts the sums (create leaves them unwritten) */
    if (A) memset(A + c0, 0, n * sizeof(float));
    if (B) memset(B + 3 * c0, 0, 3 * n * sizeof(float));
    if (o->sky_view_factor) memset(o->sky_view_factor + c0, 0, n * sizeof(float));
    if (o->positive_openness) memset(o->positive_openness + c0, 0, n * sizeof(float));
    if (o->edge_truncated) memset(o->edge_truncated + c0, 0, n);
  }
  if (A) {
    float *a = A + c0;
    for (k = 0; k < n; ++k) {
      a[k] += fdelta * ((ce[k] * ce[k] / (1.0f + se[k])) * wt[k]);
    }
  }
  if (B) {
    float *b = B + 3 * c0;
    for (k = 0; k < n; ++k) {
      const float Qh = ap_zenith_q(u[k], se[k], ce[k]) * (wt[k] * inv[k]);
      b[3 * k] += wsphi * Qh;
      b[3 * k + 1] += wcphi * Qh;
      b[3 * k + 2] += fhalf_delta * ((ce[k] * ce[k]) * wt[k]);
    }
  }
  if (o->sky_view_factor) {
    float *v = o->sky_view_factor + c0;
    for (k = 0; k < n; ++k) {
      const float tk = tt[k] * inv[k];
      const float t = tk < AP_TAN_MAX ? tk : AP_TAN_MAX;
      v[k] += (t > 0.0f ? t / sqrtf(1.0f + t * t) : 0.0f) * wt[k];
    }
  }
  if (o->positive_openness) {
    float *v = o->positive_openness + c0;
    for (k = 0; k < n; ++k) {
      v[k] += (half_pi - ht[k]) * wt[k];
    }
  }
  if (o->edge_truncated) {
    unsigned char *v = o->edge_truncated + c0;
    for (k = 0; k < n; ++k) {
      v[k] |= e[k];
    }
  }
  if (o->horizon_angles) {
    for (k = 0; k < n; ++k) {
      o->horizon_angles[(c0 + k) * (size_t)D + (size_t)d] = ht[k];
    }
  }
}

/* The sweep of an x-major sector of a grid with per-row cell sizes, where the lines bend: near
 * the side its rays leave through (grid row 0 or ny - 1), the bracketing line on that side
 * leaves the grid first, and the hulls hold nothing of the cell's ray after that; and where
 * the ray leaves within the distance, the other line's tangent may lie beyond the ray's end.
 * So, as ap_horizon_sweep does for parallel lines, after the sweep the rays of grid rows
 * [j0, j1) are sampled over that last stretch and at the point where they leave (linear along
 * the side's row), unless the DEM's highest cell could not raise the slope. Every ray of a row
 * leaves at the same step k* (where Psi = Psi(row) + k cot(phi) is the side row's); a cell's
 * inner line, at lattice coordinate ceil or floor of the cell's kappa = (Psi - lat_off) /
 * sigma, leaves (kappa's distance to it) sigma / |cot(phi)| steps earlier, and where the ray
 * leaves within the distance its last ceil(sigma / |cot(phi)|) + 2 steps are sampled: both
 * from the whole DEM's lattice, so a piece of it gets the same samples. Distances along the
 * rhumb line from the rows' south-north sizes: |Y(row) - Y(start)| / |cos(phi)|. A bowl rising
 * to the DEM's edge was up to 7.8 degrees low there (tests: test_side_edges). */
static ap_status sweep_side_rows(const ap_horizon *hz, size_t j0, size_t j1)
{
  const double cphi = cos(hz->phi), sphi = sin(hz->phi);
  const double cot = cphi / fabs(sphi), L = hz->p.max_distance, c = hz->c;
  const double zmax = (double)hz->zmax;
  const long ny = (long)hz->ny, nx = (long)hz->np, dir = hz->flip ? -1 : 1;
  const long e = cot > 0.0 ? ny - 1 : 0; /* the side row */
  /* the highest cell at most d rows from the side (NaN ignored): the bound for a stretch
   * that starts there, tighter than zmax; and the distances along the rows */
  const float *near_side = hz->side_max[cot > 0.0 ? 1 : 0];
  const double *Y = hz->ycum;
  double *ys, *ts, *zbs;
  long W, j;
  if (hz->m_row[0] == 0.0 || hz->row_lines) {
    return AP_OK; /* along the rows: no ray leaves through a side */
  }
  /* (from the whole DEM's lattice alone; the table below holds at most nx steps) */
  W = (long)fmin(ceil(hz->sigma / fabs(cot)) + 2.0, 1e9);
  ys = (double *)malloc(3 * (size_t)nx * sizeof(double));
  if (!ys) {
    return AP_ERR_OUT_OF_MEMORY;
  }
  ts = ys + nx;  /* per step of a row: the distance, */
  zbs = ts + nx; /* and the bound on the elevations from there to the side */
  for (j = (long)j0; j < (long)j1; ++j) {
    /* the step where the rays of row j leave: Psi(side) = Psi(j) + k cot(phi) */
    const double kx = (hz->psi[e + hz->orow] - hz->psi[j + hz->orow]) / cot;
    const long kl = (long)floor(kx), k0 = kl - W > 1 ? kl - W : 1;
    const long nk = (kl < nx - 1 ? kl : nx - 1) - k0 + 1; /* steps k0 .. min(kl, nx - 1) */
    const float *zrow = grid_row(hz, j);
    const double te = fabs(Y[e] - Y[j]) / fabs(cphi); /* where the rays leave */
    long k, q, jj = j + hz->orow;
    if (!(kx > 0.0) || nk <= 0) {
      continue; /* (on the side row, or every ray reaches the far edge first) */
    }
    for (k = 0; k < nk; ++k) {
      const double T = hz->psi[j + hz->orow] + (double)(k0 + k) * cot;
      double rows, z0;
      ys[k] = psi_row(hz, T, &jj);
      ts[k] = fabs(row_value(Y, (size_t)ny, ys[k]) - Y[j]) / fabs(cphi);
      /* rows from this step to the side bound the elevations of the stretch from here */
      rows = cot > 0.0 ? (double)e - floor(ys[k]) : ceil(ys[k]) - (double)e;
      z0 = rows >= 0.0 && rows < (double)AP_SIDE_ROWS ? (double)near_side[(int)rows] : zmax;
      zbs[k] = z0 + 1e-9 * (fabs(z0) + 1.0); /* (the interpolation's rounding) */
    }
    for (q = (long)hz->ri0; q < (long)hz->ri1; ++q) { /* (the region's columns) */
      const long F = dir > 0 ? nx - 1 - q : q; /* steps to the far edge */
      const size_t pv = (size_t)(dir > 0 ? q : nx - 1 - q);
      float *slope = hz->slope + scratch_index(hz, pv, (size_t)j);
      const double zq = zrow[q];
      double best = *slope, t0;
      long ka = 0;
      if (isnan(zq) || k0 > F) {
        continue; /* (the far edge first: the hulls held the ray to its end) */
      }
      if (!(te <= L)) {
        /* beyond the distance: only after the inner line has left */
        const double kappa =
          (hz->psi[j + hz->orow] - (cphi / sphi) * (double)(q + hz->ocol)) / hz->sigma;
        const double gap = cot > 0.0 ? ceil(kappa) - kappa : kappa - floor(kappa);
        const long kin = (long)floor(kx - gap * hz->sigma / fabs(cot)) - 1;
        ka = kin > k0 ? kin - k0 : 0;
        if (ka >= nk) {
          ka = nk - 1;
        }
      }
      t0 = ts[ka];
      if (!(t0 > 0.0) || t0 > L ||
          (zbs[ka] > zq ? (zbs[ka] - zq) / t0 : 0.0) - c * t0 <= best) {
        continue;
      }
      for (k = ka; k < nk && k0 + k <= F; ++k) {
        const double y = ys[k], t = ts[k];
        const long col = q + dir * (k0 + k);
        long r0 = (long)floor(y);
        double fy, z;
        if (t > L || y < 0.0 || y > (double)(ny - 1)) {
          continue;
        }
        r0 = r0 > ny - 2 ? ny - 2 : r0;
        fy = y - (double)r0;
        z = grid_row(hz, r0)[col] + fy * ((double)grid_row(hz, r0 + 1)[col] -
                                          (double)grid_row(hz, r0)[col]);
        if (isnan(z) && (fy < 1e-9 || fy > 1.0 - 1e-9)) {
          z = grid_row(hz, fy < 0.5 ? r0 : r0 + 1)[col]; /* (as interp_snap) */
        }
        if (t > 0.0) {
          const double sl = (z - zq) / t - c * t;
          best = sl > best ? sl : best; /* (NaN never wins) */
        }
      }
      {
        /* the point where the ray leaves, between steps kl and kl + 1 on the side row */
        const double fr = kx - (double)kl, t = te;
        const long ca = q + dir * kl, cb = q + dir * (kl + 1);
        if (t > 0.0 && t <= L && kl + 1 <= F) {
          const double za = grid_row(hz, e)[ca], zb = grid_row(hz, e)[cb];
          const double sl = ((za + fr * (zb - za)) - zq) / t - c * t;
          best = sl > best ? sl : best;
        }
      }
      *slope = best > (double)*slope ? (float)best : *slope;
    }
  }
  free(ys);
  return AP_OK;
}

/* Per-row cell sizes, x-major view, DEMs with nodata: whether the rays of grid row s may read
 * a nodata cell over the steps lattice_steps_row takes (the last, partial step's too): some
 * grid row between s and the row they reach, 2 more on either side, has one. Their Psi moves
 * one way, so they keep between those rows. */
static int row_rays_may_void(const ap_horizon *hz, long s)
{
  const double cot = cos(hz->phi) / fabs(sin(hz->phi)), ny = (double)hz->ny;
  const long kcap = hz->fm_kmax < (long)hz->np - 1 ? hz->fm_kmax : (long)hz->np - 1;
  long j = s + hz->orow;
  double y = psi_row(hz, hz->psi[s + hz->orow] + (double)(kcap + 1) * cot, &j);
  if (isnan(y)) {
    return 1;
  }
  y = y > -3.0 ? (y < ny + 3.0 ? y : ny + 3.0) : -3.0;
  {
    const long b[4] = { (long)floor(y < (double)s ? y : (double)s) - 2,
                        (long)ceil(y > (double)s ? y : (double)s) + 2, 0, (long)hz->nx - 1 };
    return box_may_void(hz, b);
  }
}

/* A swept sector of a DEM with nodata (hz->shore_sweep): the crossings beside nodata
 * (far_shore_column, far_shore_row) along every ray of the region's cells of grid rows
 * [j0, j1), to the search distance or the grid's edge, max-merged into the sweep's horizons.
 * The hulls hold the column samples alone, so without them a cell along a coast lost up to
 * 20 deg at p99 0.44-0.91 (test_nodata_coast); the sweep's other losses beside nodata stay.
 * AP_ERR_OUT_OF_MEMORY for the per-row steps' buffers. */
static ap_status shore_sweep_rows(const ap_horizon *hz, size_t j0, size_t j1)
{
  const size_t cap = hz->lattice ? (size_t)hz->fm_kmax + 2 : 1;
  fm_step *fm = hz->lattice ? (fm_step *)malloc(cap * sizeof(fm_step)) : hz->fm;
  double *t = hz->lattice ? (double *)malloc(cap * sizeof(double)) : NULL;
  float *row = hz->lattice && hz->xmajor ? (float *)malloc(hz->nx * sizeof(float)) : NULL;
  const long kmax0 = hz->fm_kmax;
  size_t u, q;
  if (hz->lattice && (!fm || !t || (hz->xmajor && !row))) {
    free(fm);
    free(t);
    free(row);
    return AP_ERR_OUT_OF_MEMORY;
  }
  if (hz->lattice && hz->xmajor) {
    /* grid rows, every cell's rays along the row's own steps; the slopes copied out of the
     * column-major scratch (cells outside the region +inf: nothing to raise there) */
    for (u = j0; u < j1; ++u) {
      long kmax;
      if (!row_rays_may_void(hz, (long)u)) {
        continue; /* (no crossing to take: nor its steps to compute, most of the time here) */
      }
      for (q = 0; q < hz->nx; ++q) {
        row[q] = q >= hz->ri0 && q < hz->ri1 ? hz->slope[q * hz->ny + u] : INFINITY;
      }
      (void)lattice_steps_row(hz, (long)u, fm, t, &kmax);
      far_shore_row(hz, fm, t, kmax, (long)u, grid_row(hz, (long)u), row);
      for (q = hz->ri0; q < hz->ri1; ++q) {
        hz->slope[q * hz->ny + u] = row[q];
      }
    }
  } else {
    /* x-major: view columns the region's grid columns, view rows grid rows; else view columns
     * grid rows, view rows the region's grid columns */
    const size_t ua = hz->xmajor ? hz->ri0 : j0, ub = hz->xmajor ? hz->ri1 : j1;
    for (u = ua; u < ub; ++u) {
      const size_t p = hz->flip ? hz->np - 1 - u : u;
      long a = hz->xmajor ? (long)j0 : (long)hz->ri0, b = hz->xmajor ? (long)j1 : (long)hz->ri1;
      long kmax = kmax0;
      clamp_to_data(hz, p, &a, &b);
      if (a >= b) {
        continue;
      }
      if (hz->lattice) {
        (void)lattice_steps_col(hz, p, fm, t, &kmax);
      }
      far_shore_column(hz, fm, t, kmax, p, a, b, view_column(hz, p),
                       hz->slope + scratch_index(hz, p, 0));
    }
  }
  if (hz->lattice) {
    free(fm);
    free(t);
    free(row);
  }
  return AP_OK;
}

ap_status ap_horizon_accumulate(const ap_horizon *hz, size_t j0, size_t j1)
{
  /* Cells in blocks of BLOCK along a row, row after row. An x-major sector's scratch is
   * column-major: there ROWS whole rows are first copied out column by column (contiguous
   * reads of ROWS cells) instead of reading each row at a stride of a whole column. */
  enum { BLOCK = 256, ROWS = 16 };
  float ce[BLOCK], se[BLOCK], u[BLOCK], ht[BLOCK];
  float inv[BLOCK]; /* the cells' 1 / rho (p.scale_metric), else 1 */
  float wgt[BLOCK]; /* and their weight omega, else 1 */
  float *tile = NULL;
  unsigned char *etile = NULL;
  double sphi, cphi;
  int want_ht;
  size_t i0, j, r, k;
  if (!hz) {
    return AP_ERR_NULL_POINTER;
  }
  if (hz->d < 0) {
    return AP_ERR_INVALID_ARGUMENT;
  }
  sphi = sin(hz->phi);
  cphi = cos(hz->phi);
  want_ht = hz->out.positive_openness || hz->out.horizon_angles;
  for (k = 0; k < BLOCK; ++k) {
    inv[k] = wgt[k] = 1.0f;
  }
  /* the region's rows, and its columns [ri0, ri1) of them */
  if (j0 < hz->rj0) {
    j0 = hz->rj0;
  }
  if (j1 > hz->rj1) {
    j1 = hz->rj1;
  }
  if (j0 >= j1) {
    return AP_OK;
  }
  if (hz->lattice && hz->xmajor && !hz->march && !hz->far_march) {
    const ap_status st = sweep_side_rows(hz, j0, j1);
    if (st != AP_OK) {
      return st;
    }
  }
  if (hz->shore_sweep) {
    const ap_status st = shore_sweep_rows(hz, j0, j1);
    if (st != AP_OK) {
      return st;
    }
  }
  if (hz->xmajor) {
    tile = (float *)malloc(ROWS * hz->rnx * sizeof(float));
    etile = (unsigned char *)malloc(ROWS * hz->rnx);
    if (!tile || !etile) {
      free(tile);
      free(etile);
      return AP_ERR_OUT_OF_MEMORY;
    }
  }
  for (j = j0; j < j1; j += ROWS) {
    const size_t nr = j1 - j < ROWS ? j1 - j : ROWS;
    const size_t rnx = hz->rnx, ri0 = hz->ri0;
    if (hz->first) {
      for (r = 0; r < nr; ++r) {
        for (k = 0; k < rnx; ++k) {
          horn_gradient(hz, ri0 + k, j + r, hz->grad + 2 * ((j + r - hz->rj0) * rnx + k));
        }
      }
    }
    if (hz->xmajor) {
      for (k = 0; k < rnx; ++k) {
        const float *sl = hz->slope + (ri0 + k) * hz->ny + j;
        const unsigned char *ed = hz->edge + (ri0 + k) * hz->ny + j;
        for (r = 0; r < nr; ++r) {
          tile[r * rnx + k] = sl[r];
          etile[r * rnx + k] = ed[r];
        }
      }
    }
    for (r = 0; r < nr; ++r) {
      for (i0 = 0; i0 < rnx; i0 += BLOCK) {
        const size_t n = rnx - i0 < BLOCK ? rnx - i0 : BLOCK;
        const size_t c0 = (j + r) * hz->nx + ri0 + i0;   /* the first cell, in the grid */
        const size_t o0 = (j + r - hz->rj0) * rnx + i0; /* and in the outputs */
        const float *slope = hz->xmajor ? tile + r * rnx + i0 : hz->slope + c0;
        const unsigned char *edge = hz->xmajor ? etile + r * rnx + i0 : hz->edge + c0;
        if (hz->metric) {
          /* the cells' ground distances are rho times the sweep's: tangents over rho; and
           * the sector's share of the ground's directions */
          scale_block(hz, hz->inv_rho, j + r, ri0 + i0, n, inv);
          scale_block(hz, hz->weight, j + r, ri0 + i0, n, wgt);
        }
        sector_terms(n, slope, inv, hz->grad + 2 * o0, (float)sphi, (float)cphi, want_ht, ce,
                     se, u, ht);
        accumulate_terms(hz, o0, edge, n, ce, se, u, ht, slope, inv, wgt, sphi, cphi);
      }
    }
  }
  free(tile);
  free(etile);
  return AP_OK;
}

void ap_horizon_finish(const ap_horizon *hz, size_t j0, size_t j1)
{
  if (!hz || hz->d < 0) {
    return;
  }
  const ap_sky_products *o = &hz->out;
  const double D = (double)hz->p.directions;
  float *B = o->bent_normal ? o->bent_normal : hz->bsum;
  size_t i, j;
  for (j = j0 > hz->rj0 ? j0 : hz->rj0; j < j1 && j < hz->rj1; ++j) {
    float tb = 0.0f;
    const size_t b = hz->sinv ? scale_node(hz, 1, j, &tb) : 0;
    for (i = hz->ri0; i < hz->ri1; ++i) {
      const size_t k = (j - hz->rj0) * hz->rnx + (i - hz->ri0); /* the output's index */
      if (isnan(zat(hz, i, j))) {
        if (o->visible_solid_angle) o->visible_solid_angle[k] = NAN;
        if (o->aperture_radius) o->aperture_radius[k] = NAN;
        if (o->bent_normal) {
          o->bent_normal[3 * k] = o->bent_normal[3 * k + 1] = o->bent_normal[3 * k + 2] = NAN;
        }
        if (o->sky_view_factor) o->sky_view_factor[k] = NAN;
        if (o->diffuse_sky_factor) o->diffuse_sky_factor[k] = NAN;
        if (o->positive_openness) o->positive_openness[k] = NAN;
        if (o->horizon_angles) {
          size_t d;
          for (d = 0; d < (size_t)hz->p.directions; ++d) {
            o->horizon_angles[k * (size_t)hz->p.directions + d] = NAN;
          }
        }
        continue;
      }
      /* The single-precision sums can end an ulp or two outside a product's range (a full
       * sky summed to 2pi + 1.4e-6 sr, an ApertureRadius of 90.00001 degrees; a spike's
       * PositiveOpenness 180.00003): A, rp, SkyViewFactor and PositiveOpenness are clamped. */
      if (o->visible_solid_angle) {
        o->visible_solid_angle[k] =
          fminf((float)(2.0 * AP_PI), fmaxf(0.0f, o->visible_solid_angle[k]));
      }
      if (o->aperture_radius) {
        /* rp = acos(1 - A/2pi) in the half-angle form: 1 - cos r = 2 sin^2(r/2). */
        const double A = o->visible_solid_angle ? o->visible_solid_angle[k] : o->aperture_radius[k];
        const double s = sqrt(fmin(0.5, fmax(0.0, A / (4.0 * AP_PI))));
        o->aperture_radius[k] = (float)(2.0 * asin(s));
      }
      if (B) {
        double bh[2] = { B[3 * k], B[3 * k + 1] };
        const double bz = B[3 * k + 2];
        if (hz->sroot) {
          /* the frame where the cell's steps have their ground lengths and directions (up to
           * a rotation), S = sqrt of the relative metric (a step u measures |S u|): B's
           * horizontal was summed as omega / rho times u, which S turns into the sectors'
           * ground directions */
          scale_matrix_times(hz, hz->sroot, b, tb, i, bh);
        }
        if (o->diffuse_sky_factor) {
          double g[2] = { hz->grad[2 * k], hz->grad[2 * k + 1] };
          if (hz->sinv) {
            scale_matrix_times(hz, hz->sinv, b, tb, i, g); /* (the gradient in that frame) */
          }
          const double inv = 1.0 / sqrt(1.0 + g[0] * g[0] + g[1] * g[1]);
          /* in [0, 1] by construction (the visible sky lies above the tangent plane and the
           * horizontal); clamped against rounding, which on walls of 1e37 m left -1e-26 */
          const double v = (-g[0] * bh[0] - g[1] * bh[1] + bz) * inv / AP_PI;
          o->diffuse_sky_factor[k] = (float)fmin(1.0, fmax(0.0, v));
        }
        if (o->bent_normal) {
          const double len = sqrt(bh[0] * bh[0] + bh[1] * bh[1] + bz * bz);
          if (len > 0.0) {
            o->bent_normal[3 * k] = (float)(bh[0] / len);
            o->bent_normal[3 * k + 1] = (float)(bh[1] / len);
            o->bent_normal[3 * k + 2] = (float)(bz / len);
          } else {
            o->bent_normal[3 * k] = o->bent_normal[3 * k + 1] = 0.0f;
            o->bent_normal[3 * k + 2] = 1.0f;
          }
        }
      }
      if (o->sky_view_factor) {
        o->sky_view_factor[k] = (float)fmax(0.0, 1.0 - o->sky_view_factor[k] / D);
      }
      if (o->positive_openness) {
        o->positive_openness[k] = (float)fmin(AP_PI, fmax(0.0, o->positive_openness[k] / D));
      }
    }
  }
}

ap_status ap_horizon_run(const ap_horizon_grid *g, const ap_horizon_params *p,
                         const ap_sky_products *out)
{
  ap_horizon *hz = NULL;
  ap_status st = ap_horizon_create(g, p, out, &hz);
  int d;
  if (st != AP_OK) {
    return st;
  }
  for (d = 0; d < p->directions && st == AP_OK; ++d) {
    st = ap_horizon_prepare(hz, d);
    if (st == AP_OK) {
      st = ap_horizon_near_field(hz, 0, ap_horizon_near_field_count(hz));
    }
    if (st == AP_OK) {
      const size_t nb = ap_horizon_bracket_count(hz), band = AP_HORIZON_SWEEP_BAND;
      size_t b;
      for (b = 0; b < nb && st == AP_OK; b += band) {
        st = ap_horizon_sweep(hz, b, b + band < nb ? b + band : nb);
      }
    }
    if (st == AP_OK) {
      st = ap_horizon_accumulate(hz, 0, g->z.ny);
    }
  }
  if (st == AP_OK) {
    ap_horizon_finish(hz, 0, g->z.ny);
  }
  ap_horizon_destroy(hz);
  return st;
}
