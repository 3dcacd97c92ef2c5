// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkApertureSkyVisibility
 * @brief   What every cell of a DEM sees of the sky: horizon angles in D azimuth sectors and,
 *          from the same pass, visible solid angle, aperture radius, bent normal, sky-view
 *          factor, diffuse sky factor, positive openness and edge truncation.
 *
 * Input: a DEM image as vtkApertureDEMReader produces it (`Elevation` in metres, NaN = nodata,
 * `CRS` in the field data; lat/lon or projected). Output: the same image (its point, cell and
 * field data, over the output's extent) with these point arrays added (float32; angles in
 * radians):
 *
 * - `VisibleSolidAngle`: A (sr), the solid angle of the sky visible above the horizontal,
 *   the terrain and the cell's own tangent plane;
 * - `ApertureRadius`: rp = acos(1 − A/2π) (rad), the radius of the spherical cap of the same
 *   area (Oat & Sander 2007);
 * - `BentNormal`: the unit mean direction of that visible sky, East-North-Up at the cell
 *   (components E, N, U);
 * - `SkyViewFactor`: Zakšek et al. (2011), 1 − mean sin of the terrain horizon clamped at 0:
 *   the visible share of the upper hemisphere over a *horizontal* plane, ignoring the cell's
 *   slope;
 * - `DiffuseSkyFactor`: Dozier & Frew (1990), with Dozier's (2022) self-shadowing: isotropic
 *   sky irradiance on the *tilted* cell relative to an unobstructed horizontal surface
 *   (cosine-weighted);
 * - `PositiveOpenness`: Yokoyama et al. (2002), the mean zenith angle of the terrain horizon
 *   (rad);
 * - `EdgeTruncated`: 1 where in some sector the DEM ends closer than the search limit
 *   (unsigned char); the DEM's edge only: nodata within the limit (a void, the nodata margin
 *   of a rotated raster, a coastline) hides the terrain behind it just as the edge does, but
 *   does not set the flag;
 * - `HorizonAngles` (optional): D components, the terrain horizon elevation per sector (rad),
 *   components named by azimuth ("az011.25").
 *
 * The formulas, the algorithms and their accuracy are documented in ap_horizon.h: without a
 * search distance, or beyond 1024 steps of a sector, a convex-hull line sweep (amortised O(1)
 * per cell and direction, independent of the distance); within them, marches along each
 * cell's own ray (O(distance) at worst, with tile bounds skipping what cannot rise; cheaper
 * than the sweep there).
 * Sector d is centred on true azimuth 360 d / D degrees, clockwise from north. For projected DEMs
 * the sweep runs at grid azimuths using the meridian convergence at the DEM centre; BentNormal is
 * rotated into each cell's true East-North-Up with the convergence there (bilinear between the
 * nodes of a 33 x 33 lattice, or each cell's own where that misses by more than 0.006 degree:
 * around a pole, where it takes every value), so A, rp, SkyViewFactor, DiffuseSkyFactor and
 * BentNormal are exact everywhere, a DEM on a pole too. The sweep's sector d looks at true azimuth
 * φ_d + γ(cell) − γ(centre) (a fraction of a degree apart across a UTM DEM, 9 degrees at the ends
 * of a strip 700 km long at 70 N in polar stereographic): HorizonAngles give each cell's horizon at
 * φ_d itself, linear between its two sectors either side (the nearer one's where the other is an
 * empty direction, -90 degrees; on a plane rising 0.7 degree north, 0.002 degree from the closed
 * form; the error grows with the sectors' width, in proportion where the turn is small
 * against it: on a plane rising 17 degrees, 8.6 degrees of turn from the centre, 1.4 degrees
 * at D = 4, 0.7 at 8, 0.03 at 36). Cell sizes
 * are metric per row (GeographicLib geodesics on the CRS's ellipsoid), so lat/lon DEMs are
 * exact, and so are DEMs in a normal-aspect cylindrical projection (Mercator, Web Mercator,
 * equirectangular, cylindrical equal-area: rows are parallels, columns meridians,
 * vtkApertureGeoreference::HasMeridianColumns), whose rows get their own sizes the same way. On any
 * other projection the scale changes across the DEM (about 0.1% across a whole UTM zone, 7% from 60
 * to 88 N in polar stereographic): each cell takes its own ground metric (the lengths of, and angle
 * between, its steps along the row and the column: vtkApertureGeoreference::GetCellMetricAt on a
 * lattice of up to 33 x 33 nodes over the whole DEM, bilinear between them), so a sector's
 * distances from that cell are exact up to the scale's change along its ray (7e-5 over 3 km at 60 N
 * in polar stereographic), as is its tangent plane. The search distance and the curvature drop stay
 * at the centre's scale. Where the projection is not conformal (Albers, Lambert azimuthal
 * equal-area, sinusoidal) it also turns directions on the ground, so the sectors, evenly spaced on
 * the grid, lie unevenly on the ground: each sector's terms are weighted by its share of the
 * ground's directions, BentNormal sums their ground directions, and HorizonAngles are interpolated
 * from their ground azimuths (a plane in sinusoidal at 45 N, 15 E, where directions turn by 5.4
 * degrees: SkyViewFactor within 3e-5 of the closed form, bent normals within 0.03 degree and
 * horizons 0.011 at 64 sectors). Where some lattice node has no geographic coordinates (a DEM
 * reaching off the projection's domain), every cell takes the centre's cell size instead, and a
 * size change of more than 0.5% (a corner's or an edge midpoint's against the centre's) is warned
 * about. Earth curvature uses the ellipsoid's radius of curvature in each azimuth at the DEM
 * centre. A DEM in a local CRS (a site or mine grid, vtkApertureGeoreference::IsLocal: no
 * place on the Earth) has cells of its spacing in the CRS's unit, its grid's +y axis taken as
 * north (the sectors' azimuths, BentNormal and HorizonAngles are the grid's) and curvature on
 * a sphere of the Earth's mean radius, 6,371,008.8 m.
 *
 * Terrain beyond the DEM edge is invisible; EdgeTruncated marks the cells where that may matter for
 * the sky above the horizontal (A, rp, BentNormal, both sky-view factors). A global DEM, whose
 * columns span 360 degrees of longitude (lat/lon, or a cylindrical projection's such as Web
 * Mercator: vtkApertureGeoreference::WrapsAround), has no east and west edges: they join, and the
 * cells beside the antimeridian see the terrain on its other side (within the search distance; a
 * sub-extent whose halo crosses it reads every column). Without a distance a ray along a parallel
 * runs on past the seam for half the globe's columns, so it stops between half a round of the globe
 * and one and a half, where the seam puts it: the horizons below the horizontal (PositiveOpenness,
 * HorizonAngles) depend on where the seam lies. The products clipped at the horizontal do not
 * (EdgeTruncated without a search distance can: ap_horizon.h says where), except in rows near a
 * pole (within about a degree; by far less a few degrees farther: the README has measured cases),
 * where rays that would circle the pole (along the parallel, or oblique ones winding towards it)
 * stop where the seam's copy ends. (The sweep's copy of the elevations and its state then cover
 * those columns too, GetWrapColumns on each side: up to twice the DEM's without a distance.)
 * PositiveOpenness and HorizonAngles below the horizontal may differ near the edge on unflagged
 * cells too (a sector whose ray leaves the DEM at once has horizon -90 degrees).
 * Nodata (NaN, and any elevation that is not finite, as vtkApertureDEMReader makes it) never
 * occludes and gives NaN products; beside it the terrain is the cells with data and the grid
 * lines between two of them (ap_horizon.h says how closely each search follows it). Finite
 * elevations are taken as they are, but those beyond the Earth's range (below -11,100 m or
 * above 9,000 m: undeclared nodata values such as -32768, or heights not in metres) raise a
 * warning naming the range, as does a relief over ten times the input's larger side, which no
 * terrain has (coordinates in degrees taken for metres: a projected CRS given to a lat/lon DEM).
 *
 * Streaming: a request for a sub-extent reads the input extent grown by the search distance
 * on every side (the whole extent when the distance is unlimited, or when the CRS is not known
 * before data flows: directly behind vtkApertureDEMReader it is) and computes the region's
 * cells alone (the halo is terrain only; its output arrays cover the region), so pieces cost
 * about what the whole run does: 4 pieces of a 1024^2 DEM, reading included, took 1.16 times
 * the whole run's time at 10 km and 1.27 times unlimited (bench/bench_pieces.py; the sweep's
 * lines still cross the halo up to the region). Inside the region the results are the
 * whole-DEM run's: what depends on the DEM as a whole (its centre's cell size, the lattice of
 * ground metrics, curvature radii and meridian convergence, and the lattice of the sweep's
 * lines, on lat/lon DEMs laid out by the whole DEM's rows) is taken from the whole extent, so
 * a piece is bit-identical to the whole run there, projected or lat/lon, swept or marched (the
 * tests compare every bit; the sweep measures distances along its lines from the piece's own
 * edge, so a horizon may round its last bit differently: 2 of 5,500 random pieces in a stress
 * test, by 4e-8 rad). The DEM may have at most 10^9 + 1 cells a side (AP_HORIZON_MAX_ORIGIN;
 * a global DEM's columns count with the halo swept again beyond its seam, up to twice them),
 * and on lat/lon DEMs the lattice takes 32 bytes for each of the whole DEM's rows: a window of
 * a larger grid is refused with the reason. The output's pipeline information carries the CRS
 * (vtkApertureGeoreference::CRS_KEY) when the input's does, or when the input is an image given
 * with SetInputData that has one (unless its origin and spacing are VTK's defaults, contradicting
 * its GeoTransform, and put it beyond a pole or around the Earth more than once:
 * vtkApertureGeoreference::GetDefaultGeometryWarning, which this filter gives before it refuses
 * such a grid), so that vtkApertureTerrainMesh plans its pieces by it.
 *
 * A piece whose input (its extent and halo) is nodata in every cell, a stretch of sea in a
 * coastal DEM, is no error: its products are nodata (NaN; EdgeTruncated 0, or NaN as float),
 * as the whole run's are there, and GetInputAllNodata() says so.
 *
 * An input of no points (an empty image, or an empty update extent of a pipeline that has not
 * run: VTK's executive keeps an earlier update's output for one) gives an empty output and no
 * error, as VTK's filters do.
 * Errors (vtkErrorMacro, failed update): no elevation array, a DEM smaller than 2 x 2, a point
 * array without one tuple per point of the input, no CRS or no metric cell size (a lat/lon,
 * Mercator or equirectangular grid wider than 360 degrees, a lat/lon grid beyond a pole, a
 * projected one whose first, middle or last row PROJ gives no geographic coordinates, a
 * sub-extent of such a grid too, is refused without reading its input when the CRS is in the
 * pipeline information, as vtkApertureDEMReader puts it), every cell
 * nodata in an input that is the whole DEM (an update of all of it, or an unlimited distance),
 * NumberOfDirections outside 4..360, a negative MaximumDistance, a refraction coefficient outside
 * [0, 1), and not enough memory for the outputs and the sweep: refused before allocating when the
 * estimate exceeds MemoryLimit (default: the memory the process may use, physical or its control
 * group's limit, beside the input image, since past it Linux kills the process rather than fail an
 * allocation; or what an address-space limit leaves), or an allocation that fails (e.g. under
 * `ulimit -v`); the message gives the estimated need (HorizonAngles take 4 bytes per cell and
 * direction).
 *
 * Progress and abort: ProgressEvent at 0 three times in the serial set-up (after the
 * elevations' copy, before the outputs, after the sweep's state: seconds apart on a DEM of 10^8
 * cells), at the end of each sector d ((d + 1) / (D + 1)), and on
 * DEMs of more than 8 Mi cells also inside it (its phases run in slices of about that many
 * cells); then twice in the last part, the end (after the sums' finish, (D + 0.5) / (D + 1),
 * and after the bent normals' rotation, (D + 0.9) / (D + 1)), which takes about as long as a
 * sector. AbortExecute, checked at each, stops the update there: an empty output (the update
 * fails).
 *
 * @warning Threads: NumberOfThreads (default all cores, through vtkSMPTools' STDThread
 * backend); the results are bit-identical for any thread count.
 * @sa vtkApertureDEMReader vtkApertureTerrainMesh
 */
#ifndef vtkApertureSkyVisibility_h
#define vtkApertureSkyVisibility_h

#include "ApertureFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

#include <string> // for CheckMemory, FormatBytes

class APERTUREFILTERS_EXPORT vtkApertureSkyVisibility : public vtkImageAlgorithm
{
public:
  static vtkApertureSkyVisibility* New();
  vtkTypeMacro(vtkApertureSkyVisibility, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Azimuth sectors D, 4..360. Default 32. */
  vtkSetMacro(NumberOfDirections, int);
  vtkGetMacro(NumberOfDirections, int);
  ///@}

  ///@{
  /** Search distance in metres; 0 (default) = unlimited. Negative, infinite or NaN values are
   *  an error at the update. A distance of at most GetMarchColumns() (64) steps of a sector
   *  (1.9 km on a 30 m grid) is searched by marching every cell's ray exactly; one of at most
   *  GetFarMarchColumns() (1024) steps (30 km) by sampling every cell's ray where it crosses
   *  the grid's columns (the far march; on lat/lon DEMs along each ray's rhumb line); both are
   *  faster there than the hull sweep, which searches longer distances and no limit
   *  (ap_horizon.h). */
  vtkSetMacro(MaximumDistance, double);
  vtkGetMacro(MaximumDistance, double);
  ///@}

  /** Steps of a sector up to which a MaximumDistance is marched ray by ray instead of swept
   *  (the kernel's march_columns). */
  static int GetMarchColumns();

  /** Steps of a sector up to which a MaximumDistance is far-marched instead of swept (the
   *  kernel's far_march_columns). */
  static int GetFarMarchColumns();

  /** The automatic NearField (0) of swept sectors (32) and of far-marched ones (8). */
  static int GetSweptNearField();
  static int GetMarchedNearField();

  ///@{
  /** Earth curvature with refraction (default on) and the refraction coefficient k
   *  (default 0.13, the usual value for visible light; [0, 1)). */
  vtkSetMacro(EarthCurvature, bool);
  vtkGetMacro(EarthCurvature, bool);
  vtkBooleanMacro(EarthCurvature, bool);
  vtkSetMacro(RefractionCoefficient, double);
  vtkGetMacro(RefractionCoefficient, double);
  ///@}

  ///@{
  /** Columns of each cell's own ray evaluated exactly on the bilinear surface before the
   *  hulls or the far march take over: 1..64, or 0 (default) for 32 in the sectors the hulls
   *  search and 8 where the far march runs (ap_horizon.h gives the accuracy it buys). Beyond
   *  them a ray sees the terrain where it crosses the grid's columns (or rows), not inside
   *  the cells between: natural terrain loses little, but a feature one cell wide (a mast, a
   *  chimney in a DSM) that a ray passes between crossings is missed, so that a longer
   *  MaximumDistance, which far-marches what a shorter one marched exactly, can even lower a
   *  horizon. For DSMs of such features, 64 finds them within 64 cells (10-20% more time). */
  vtkSetClampMacro(NearField, int, 0, 64);
  vtkGetMacro(NearField, int);
  ///@}

  ///@{
  /** Threads; 0 (default) = all the cores the process may use (GetUsableCores), which also cap
   *  larger values. Results do not depend on it. They run on vtkSMPTools' STDThread backend
   *  whatever VTK's default backend is: the TBB backend of Debian's VTK 9.1 applies a scope's
   *  thread count only when it differs from the previous scope's (a second update on one thread ran
   *  on every core). One thread runs in the calling thread (Sequential backend), starting none;
   *  threads the system refuses to start (no memory for their stacks) fail the update with an error
   *  saying so. The backend and count are set for the process while the update's parallel work
   *  runs (vtkSMPTools::LocalScope); an Aperture update whose work starts meanwhile on another
   *  thread runs on them instead of its own, so that the process's configuration is restored.
   *  VTK's environment variables VTK_SMP_BACKEND_IN_USE and VTK_SMP_MAX_THREADS do not apply:
   *  this property (the command line's --threads) sets the count. */
  vtkSetClampMacro(NumberOfThreads, int, 0, VTK_INT_MAX);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /** Most bytes one update may allocate for its outputs and the sweep's state (estimated as
   *  the error message gives them); 0 (default) = GetUsableMemory() less the input image's
   *  size (not under an address-space limit, whose usable memory excludes it already:
   *  IsMemoryAddressLimited). */
  vtkSetClampMacro(MemoryLimit, vtkTypeInt64, 0, VTK_TYPE_INT64_MAX);
  vtkGetMacro(MemoryLimit, vtkTypeInt64);
  ///@}

  /** The bytes of memory this process may use, the lowest of: the machine's physical memory;
   *  the memory limit of the Linux control group it runs in, less 128 MiB (at most half of
   *  it) for what the process holds before its data (a container run with a limit: past it
   *  the kernel ends the process, as past physical memory), IsMemoryGrouped() then true; an
   *  address-space limit (`ulimit -v`) less the address space the process has mapped already
   *  and 128 MiB (at most half) for threads' stacks and arenas (past it allocations fail).
   *  Read at each call. */
  static vtkTypeInt64 GetUsableMemory();
  static bool IsMemoryGrouped();
  /** True when GetUsableMemory() is an address-space limit's: what it leaves beside all the
   *  process has mapped, so memory held already is not to be subtracted from it again. */
  static bool IsMemoryAddressLimited();

  /** Whose memory GetUsableMemory() is, as the messages say it: "this process may use under
   *  its control group's limit", "this process may use under its address-space limit
   *  (ulimit -v)" or "this machine has". */
  static std::string GetUsableMemoryOwner();

  /** A byte count as every message of Aperture writes it: "512 bytes", "1.500 KiB", ...,
   *  "3.353 GiB" (binary units, three decimals). */
  static std::string FormatBytes(double bytes);

  /** The cores this process may run on, NumberOfThreads 0's count (and the cap of larger
   *  ones): the machine's, or fewer where its CPU affinity (taskset, a container's
   *  --cpuset-cpus) or its control group's CPU quota rounded up (--cpus) allows fewer. */
  static int GetUsableCores();

  /** Bytes an update over n input cells allocates with the current products and
   *  NumberOfDirections: the outputs, the filter's float copy of the elevations and the
   *  sweep's state (ap_horizon_state_bytes_per_cell); the estimate MemoryLimit is compared
   *  with, for callers that check before reading a DEM. */
  double EstimateBytes(double n) const;

  /** The same for an update of a sub-extent of outN cells whose input, the sub-extent and its
   *  halo, has n: the outputs cover the sub-extent alone (and it gets a copy of the input's
   *  arrays, 4 bytes a cell). EstimateBytes(n, n) = EstimateBytes(n). */
  double EstimateBytes(double n, double outN) const;

  /** Why an update over an nx x ny input would be refused for memory, or "" when it fits:
   *  EstimateBytes(nx * ny) against MemoryLimit, or (MemoryLimit 0) against GetUsableMemory() less
   *  `held` bytes, what the input occupies (4 x nx x ny for float elevations not yet read; when
   *  that alone exceeds the memory, the text says so; an update passes its input's bytes, or
   *  0 under an address-space limit, which leaves GetUsableMemory() beside them). The update
   *  refuses with this text and advice; a caller can ask before reading a DEM and add its own
   *  advice. */
  std::string CheckMemory(int nx, int ny, double held) const;

  /** The same for an update extent of outNx x outNy cells whose input (the extent with its
   *  halo: ComputeInputExtent) is nx x ny. */
  std::string CheckMemory(int nx, int ny, int outNx, int outNy, double held) const;

  /** The extent of the input an update of `extent` reads (after UpdateInformation): the
   *  extent grown by the halo of MaximumDistance (its cells at the smallest metric cell sizes
   *  of the rows within the distance, and 2 more), clipped to the input's whole extent; the
   *  whole extent when the distance is unlimited, the input publishes no CRS, or a row there
   *  has no metric cell size. False, with an error, without input information, and for an
   *  update refused before anything is read (a grid whose first, middle or last row has no
   *  metric cell size, as a lat/lon, Mercator or equirectangular grid wider than 360
   *  degrees or a lat/lon grid beyond a pole, its CRS in the pipeline information). For
   *  sizing a request before anything runs (CheckMemory). */
  bool ComputeInputExtent(const int extent[6], int input[6]);

  /** Columns of the other side an update whose input extent is `input` (ComputeInputExtent's)
   *  adds to each side of a global DEM (vtkApertureGeoreference::WrapsAround) so that its
   *  east and west edges join: the distance's halo in columns, at most half the DEM's (half
   *  without a distance); 0 for other DEMs, an input without every column, or no input
   *  information (the CRS from it, else from an image given with SetInputData). The update's
   *  memory is CheckMemory's for nx + 2 x this columns. */
  int GetWrapColumns(const int input[6]);

  /** Threads that ran the last update's parallel work (0 before any; at most
   *  NumberOfThreads when that is set). */
  vtkGetMacro(NumberOfThreadsUsed, int);

  /** Whether the last update's input, a part of the DEM (the requested extent and its halo),
   *  was nodata in every cell, so that every product is nodata (false before any update). A
   *  caller streaming a DEM in pieces learns from it whether any piece had data. */
  vtkGetMacro(InputAllNodata, bool);

  ///@{
  /** Which products to add. All derived products default on; HorizonAngles off. */
  vtkSetMacro(ComputeVisibleSolidAngle, bool);
  vtkGetMacro(ComputeVisibleSolidAngle, bool);
  vtkBooleanMacro(ComputeVisibleSolidAngle, bool);
  vtkSetMacro(ComputeApertureRadius, bool);
  vtkGetMacro(ComputeApertureRadius, bool);
  vtkBooleanMacro(ComputeApertureRadius, bool);
  vtkSetMacro(ComputeBentNormal, bool);
  vtkGetMacro(ComputeBentNormal, bool);
  vtkBooleanMacro(ComputeBentNormal, bool);
  vtkSetMacro(ComputeSkyViewFactor, bool);
  vtkGetMacro(ComputeSkyViewFactor, bool);
  vtkBooleanMacro(ComputeSkyViewFactor, bool);
  vtkSetMacro(ComputeDiffuseSkyFactor, bool);
  vtkGetMacro(ComputeDiffuseSkyFactor, bool);
  vtkBooleanMacro(ComputeDiffuseSkyFactor, bool);
  vtkSetMacro(ComputePositiveOpenness, bool);
  vtkGetMacro(ComputePositiveOpenness, bool);
  vtkBooleanMacro(ComputePositiveOpenness, bool);
  vtkSetMacro(ComputeEdgeTruncated, bool);
  vtkGetMacro(ComputeEdgeTruncated, bool);
  vtkBooleanMacro(ComputeEdgeTruncated, bool);
  vtkSetMacro(ComputeHorizonAngles, bool);
  vtkGetMacro(ComputeHorizonAngles, bool);
  vtkBooleanMacro(ComputeHorizonAngles, bool);
  ///@}

  ///@{
  /** For files whose bands share one unit and sample type (what `aperture bake` writes):
   *  AnglesInDegrees puts ApertureRadius, PositiveOpenness and HorizonAngles in degrees
   *  instead of radians; FloatEdgeTruncated makes EdgeTruncated a float array, 0 or 1 and NaN
   *  on nodata cells, instead of unsigned char 0 or 1 (0 on nodata). Both default off. */
  vtkSetMacro(AnglesInDegrees, bool);
  vtkGetMacro(AnglesInDegrees, bool);
  vtkBooleanMacro(AnglesInDegrees, bool);
  vtkSetMacro(FloatEdgeTruncated, bool);
  vtkGetMacro(FloatEdgeTruncated, bool);
  vtkBooleanMacro(FloatEdgeTruncated, bool);
  ///@}

  ///@{
  /** Name of the input's point array of elevations (metres; one component, any numeric type).
   *  Default "Elevation", which an input without an array so named takes from its active point
   *  scalars; a null or empty name takes them in any case, as does a selection of them (below).
   *  Scalars so taken come out as the point array `Elevation` too, as from the reader (the
   *  same values, sharing their memory; instead of unnamed scalars, beside named ones; not
   *  over another array so named). A name the input lacks is an error naming the arrays it
   *  has. SetInputArrayToProcess(0, 0,
   *  0, points, name), the way VTK's filters and ParaView select arrays, selects one in its
   *  place (or the point scalars, by attribute type); a selection of cell data or of another
   *  attribute is an error. Of the two, the one made last holds. */
  void SetElevationArrayName(const char* name);
  vtkGetStringMacro(ElevationArrayName);
  ///@}

protected:
  /** "" when `need` bytes fit within MemoryLimit, or the usable memory less `held` bytes; else
   *  `needs` (what needs them) and the memory they exceed, as CheckMemory words it. */
  std::string BeyondMemory(double need, double held, const std::string& needs) const;

  vtkApertureSkyVisibility();
  ~vtkApertureSkyVisibility() override;

  /** Marks the output as able to produce any sub-extent, so that the pipeline turns piece
   *  requests (UpdatePiece, ParaView's ranks) into extents; RequestUpdateExtent adds the halo. */
  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestUpdateExtent(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  /** RequestData's work; RequestData turns a failed allocation in it into an error. */
  int RunRequestData(vtkInformationVector** inputVector, vtkInformationVector* outputVector);
  /** Bytes of the requested outputs per cell. */
  double OutputBytesPerCell() const;

  int NumberOfDirections;
  double MaximumDistance;
  bool EarthCurvature;
  double RefractionCoefficient;
  int NearField;
  int NumberOfThreads;
  int NumberOfThreadsUsed;
  bool InputAllNodata;
  vtkTypeInt64 MemoryLimit;
  bool ComputeVisibleSolidAngle;
  bool ComputeApertureRadius;
  bool ComputeBentNormal;
  bool ComputeSkyViewFactor;
  bool ComputeDiffuseSkyFactor;
  bool ComputePositiveOpenness;
  bool ComputeEdgeTruncated;
  bool ComputeHorizonAngles;
  bool AnglesInDegrees;
  bool FloatEdgeTruncated;
  char* ElevationArrayName;
  vtkMTimeType ArraySelectionMade; // (the input array selection's MTime when made)
  std::string RefusedRequest;       // (RequestUpdateExtent's refusal, for RequestData to report)

private:
  vtkApertureSkyVisibility(const vtkApertureSkyVisibility&) = delete;
  void operator=(const vtkApertureSkyVisibility&) = delete;
};

#endif
