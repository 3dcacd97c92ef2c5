// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkApertureGeoreference
 * @brief   Georeference of a north-up DEM grid: its CRS, its cells, and the way to geographic
 *          coordinates and metres.
 *
 * A DEM in Aperture is a 2-D vtkImageData whose origin and spacing are in the units of its
 * coordinate reference system (CRS): the origin is the centre of the south-west cell, spacing
 * is the (positive) cell size east and north, point (i, j) is the centre of the cell in column i
 * (west to east) and row j (south to north), and the direction matrix is the identity (or
 * one that flips z alone, which a one-slice DEM does not extend along: HasNorthUpAxes).
 *
 * The georeference travels with the image in one documented place, its field data:
 * - `CRS`: a vtkStringArray with one value, the CRS as WKT (WKT2:2019).
 * - `GeoTransform`: a vtkDoubleArray with 6 values, GDAL's geotransform of the grid the image
 *   holds (x of the west edge, cell width, 0, y of the north edge, 0, minus the cell height).
 *   It mirrors the image geometry; when the two disagree (a filter resampled the image), the
 *   image's origin and spacing win.
 *
 * This class reads and writes those arrays and answers geodetic questions about the grid:
 * geographic coordinates of any CRS point (on the CRS's own datum and ellipsoid, in degrees,
 * longitude east of Greenwich), lat/lon bounds, the grid centre, the cell size in metres
 * (geodesic distances on the CRS's ellipsoid), and the ellipsoid itself. Lat/lon (geographic)
 * and projected CRSs are both handled. A local (engineering) CRS, a site grid with no
 * geographic equivalent, answers only what its linear unit says (IsLocal): every geographic
 * question about it is an error.
 *
 * Queries return false on failure and leave the reason in GetErrorMessage(); they never call
 * vtkErrorMacro, so callers decide how to report.
 *
 * @warning Not thread-safe: one instance per thread.
 * @sa vtkApertureDEMReader vtkApertureTerrainMesh
 */
#ifndef vtkApertureGeoreference_h
#define vtkApertureGeoreference_h

#include "ApertureFiltersModule.h" // for export macro
#include "vtkObject.h"
#include "vtkWrappingHints.h" // for VTK_WRAPEXCLUDE

#include <string> // for GetElevationWarning, GetDefaultGeometryWarning

class vtkDataObject;
class vtkImageData;
class vtkInformation;
class vtkInformationStringKey;

class APERTUREFILTERS_EXPORT vtkApertureGeoreference : public vtkObject
{
public:
  static vtkApertureGeoreference* New();
  vtkTypeMacro(vtkApertureGeoreference, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Pipeline information key under which vtkApertureDEMReader also publishes the CRS (WKT)
   * of its output during RequestInformation (and vtkApertureSkyVisibility passes it on, or
   * publishes the CRS of an image given to it with SetInputData), so that downstream filters
   * can plan update extents in metres before any data flows. The field data stays the place
   * of record.
   */
  static vtkInformationStringKey* CRS_KEY();

  ///@{
  /** Names of the field-data arrays that carry the georeference ("CRS", "GeoTransform"). */
  static const char* GetCRSArrayName();
  static const char* GetGeoTransformArrayName();
  ///@}

  /** The CRS a data object carries in its field data (the array GetCRSArrayName(), as
   *  AttachToImage stores it), or nullptr when it has none (no such string array, or an empty
   *  value). Points into that array: valid while the array is unchanged. */
  static const char* GetAttachedCRS(vtkDataObject* data);

  /**
   * Set the CRS from anything GDAL's OSRSetFromUserInput accepts: WKT, "EPSG:32611", a PROJ
   * string. Stored as WKT2:2019. Returns false (and keeps the previous CRS, GetErrorMessage
   * says why) if GDAL cannot parse it, or for a geographic CRS whose coordinates are not
   * longitude east and latitude north: a rotated pole (derived geographic, as climate models'
   * grids), or an axis pointing west or south; the grid would be placed elsewhere on Earth.
   * An empty string or nullptr clears the CRS.
   */
  bool SetCRS(const char* definition);

  /** The CRS as WKT2:2019, or an empty string when none is set. */
  const char* GetCRS();

  /** Its horizontal part, what places the grid, as WKT2:2019: of a compound CRS (a projected
   *  or geographic one with heights, EPSG:2263+6360) that CRS without its vertical part, else
   *  the CRS itself; an empty string when none is set, or when GDAL cannot separate it
   *  (GetErrorMessage says so). What the writers record: the products are not heights, and
   *  elevations are written in metres whatever the height unit was. */
  const char* GetHorizontalCRS();

  /** True when a CRS is set. */
  bool HasCRS();

  /**
   * Describe the grid: x0, y0 = CRS coordinates of the centre of the south-west cell,
   * dx, dy = cell size east and north (> 0, CRS units), nx, ny = columns and rows. Taken as
   * given; the queries that use the grid (GetBoundsLonLat, GetCellSizeMetres...) return false
   * for a grid that describes no cells (dx or dy not positive and finite, nx or ny below 1,
   * an origin that is not finite).
   */
  void SetGrid(double x0, double y0, double dx, double dy, int nx, int ny);

  ///@{
  /** The grid as set by SetGrid or SetFromImage. */
  vtkGetVector2Macro(GridOrigin, double);
  vtkGetVector2Macro(GridSpacing, double);
  vtkGetVector2Macro(GridSize, int);
  ///@}

  /** GDAL geotransform of the grid (north-up; gt[5] = -dy). */
  void GetGeoTransform(double gt[6]);

  /**
   * Take the CRS from the image's field data (`CRS`) and the grid from the image's origin,
   * spacing and extent (the extent it holds). False, with a message, if the image has no CRS,
   * a direction matrix that turns its x and y axes (HasNorthUpAxes), a spacing that is not
   * positive and finite, an origin that is not finite, or edges beyond the range of doubles
   * (a spacing of 1e308).
   */
  bool SetFromImage(vtkImageData* image);

  /** True when the image's direction matrix leaves its x and y axes as they are (east and
   *  north): the identity, or a matrix that only flips z, which a one-slice DEM does not
   *  extend along. False for a rotated or mirrored grid, which no GeoTransform describes. */
  static bool HasNorthUpAxes(vtkImageData* image);

  /** A warning when the image's origin and spacing are VTK's defaults (x, y origin 0 and
   *  spacing 1) while its field data's `GeoTransform` describes another grid: cells other than
   *  north-up 1 x 1 ones, or a west or north edge off the half-integers, east of the image's
   *  west edge or south of its north edge (a whole grid's GeoTransform passed to a piece or a
   *  crop of it has its edges at or beyond theirs): an image made by hand whose geometry was
   *  never set, which SetFromImage (the geometry wins: Rasters.md) takes as cells of one CRS
   *  unit at the CRS's origin. "" otherwise, also for a grid of 1-unit cells made by hand
   *  whose north-west corner happens to lie at or beyond the image's on that lattice.
   *  Aperture's filters, writers and vtkApertureSolarPosition give it (WarnOfDefaultGeometry).
   */
  static std::string GetDefaultGeometryWarning(vtkImageData* image);

  /** Gives GetDefaultGeometryWarning's warning, if any, as `caller`'s (vtkWarningWithObjectMacro:
   *  its WarningEvent observers see it); true when it did. */
  static bool WarnOfDefaultGeometry(vtkObject* caller, vtkImageData* image);

  /**
   * The georeference of a whole grid before any data flows: the CRS from CRS_KEY and the grid
   * from the extent, origin and spacing (WHOLE_EXTENT, ORIGIN, SPACING) of pipeline
   * information, as vtkApertureDEMReader publishes them during RequestInformation (the grid an
   * image of the whole extent gives SetFromImage). False, with a message, when the
   * information lacks the grid (nothing changes), or lacks the CRS or has one GDAL cannot
   * parse (the grid is set, and the CRS cleared or, unparsable, kept as it was).
   */
  bool SetFromInformation(vtkInformation* info);

  /**
   * Store the CRS and the GeoTransform of the image's current extent in the image's field
   * data, replacing earlier values. False (the image unchanged) if no CRS is set, or for an
   * image SetFromImage refuses for its grid: a direction matrix that turns its x and y axes, a
   * spacing that is not positive and finite (VTK's rows run south to north), edges beyond
   * the doubles.
   */
  bool AttachToImage(vtkImageData* image);

  /** True when the CRS is geographic (lat/lon). Requires a CRS. */
  bool IsGeographic();

  /**
   * True when the CRS is local (engineering: LOCAL_CS, a site or mine grid): it has no
   * geographic coordinates, so CRSToLonLat, GetCentreLonLat, GetBoundsLonLat, GetEllipsoid and
   * ComputeMeridianConvergence fail, but its linear unit gives metric cells: every cell
   * measures the spacing times GetCRSUnitMetres (GetCellSizeMetres[At], GetCellMetricAt with
   * E·N = 0, GetRowCellSizesMetres), and HasMeridianColumns is true (the grid's axes are taken
   * as east and north). False without a CRS.
   */
  bool IsLocal();

  /** Radius (m) of the sphere a local CRS is placed on, its grid's centre at latitude and
   *  longitude 0 and +y north: the Earth's mean radius, IUGG's R1 of GRS 80 (6,371,008.8 m).
   *  vtkApertureSkyVisibility's curvature and vtkApertureTerrainMesh's geometry use it. */
  static double GetLocalSphereRadius() { return 6371008.8; }

  /**
   * True when the grid's columns are meridians and its rows parallels: a geographic CRS, or a
   * normal-aspect cylindrical projection (Mercator, Web Mercator, equirectangular, cylindrical
   * equal-area), with longitude linear in x, or a local CRS (IsLocal). Checked on the cells of the
   * first, middle and last rows and columns, and a column up to 90 degrees of longitude from the
   * first (to a millionth of a cell; longitudes modulo 360, so around the globe too). Ground cell
   * sizes then depend on the row alone, so GetRowCellSizesMetres holds for every cell, and the
   * meridian convergence is 0. False for other projections (transverse Mercator, conic, polar,
   * sinusoidal), without a CRS, and for a projection without a grid of at least 2 x 2 cells (a
   * geographic or local CRS needs no grid: true for any).
   */
  bool HasMeridianColumns();

  /** Name of the CRS ("WGS 84", "WGS 84 / UTM zone 11N"), or "" when none. */
  const char* GetCRSName();

  /** Name of the horizontal unit of the CRS ("degree", "metre", "US survey foot"). */
  const char* GetCRSUnitName();

  /** Metres per horizontal unit of a projected or local CRS (1 for metres, 0.3048 for feet);
   *  0 for a geographic CRS or none. */
  double GetCRSUnitMetres();

  ///@{
  /** The height unit of a compound CRS (e.g. EPSG:2263+6360, its vertical part NAVD88 height
   *  in US survey feet) or of a vertical one: its name and metres per unit; "" and 0 when the
   *  CRS has no vertical part (a plain projected or geographic CRS says nothing of heights). */
  const char* GetVerticalUnitName();
  double GetVerticalUnitMetres();
  ///@}

  /** Semi-major axis (m) and flattening of the CRS's ellipsoid. */
  bool GetEllipsoid(double ellipsoid[2]);

  /** Geographic coordinates (longitude, latitude; degrees, Greenwich) of a CRS point. A
   *  geographic CRS's are passed through unchecked (longitudes beyond 180 not wrapped,
   *  latitudes beyond 90 not refused); PROJ normally gives a projected CRS's within -180..180. */
  bool CRSToLonLat(double x, double y, double lonlat[2]);

  /** CRS coordinates of a geographic point (degrees). */
  bool LonLatToCRS(double lon, double lat, double xy[2]);

  /**
   * Batch form of CRSToLonLat: n points, xy interleaved (x0, y0, x1, y1, ...), lonlat likewise.
   * A point that is NaN or cannot be transformed gives NaN. False only if the CRS has no
   * geographic equivalent.
   */
  VTK_WRAPEXCLUDE bool CRSToLonLatPoints(vtkIdType n, const double* xy, double* lonlat);

  /**
   * False (with GetErrorMessage giving the span) when the grid spans more than 360 degrees of
   * longitude by over a thousandth of a cell, so that its columns would cover the same ground
   * twice (a wrong cell size or unit, or a gridline-registered global grid; cell sizes rounded
   * to 9 or 10 digits stay within): a lat/lon grid, or a projected one of at least 2 x 2 cells
   * whose columns are meridians (HasMeridianColumns: Mercator, equirectangular). True
   * otherwise, and for other projected grids. False without a geographic form of the CRS (a
   * local one). GetBoundsLonLat and GetRowCellSizesMetres check it first.
   */
  bool CheckLongitudeSpan();

  /**
   * True when the grid's columns span 360 degrees of longitude (to a thousandth of a cell), so
   * that its east and west edges meet: a global DEM, whose last column's eastern neighbour is
   * its first. A lat/lon grid, or a projected one whose columns are meridians
   * (HasMeridianColumns: Mercator, Web Mercator, equirectangular). False otherwise, for a local
   * CRS, and without a CRS or grid.
   */
  bool WrapsAround();

  /** Longitude and latitude (degrees) of the grid centre (the centre of its outer bounds).
   *  False (GetErrorMessage) when it has none, or lies beyond a pole. */
  bool GetCentreLonLat(double lonlat[2]);

  /**
   * Geographic bounds of the grid's outer edges (cell edges, not centres): west, south, east,
   * north, degrees. For a projected CRS the edges are densified (21 points each), so curved
   * edges are bounded correctly. A geographic grid's longitudes are its own (a 0..360 grid's
   * east half beyond 180); one whose edge lies beyond a pole is an error. On false, bounds
   * are NaN.
   */
  bool GetBoundsLonLat(double bounds[4]);

  /**
   * Ground size of one cell at the grid centre, metres: east-west and south-north, measured as
   * geodesic distances on the ellipsoid between the centres of the cell's opposite edges.
   */
  bool GetCellSizeMetres(double size[2]);

  /**
   * The warning for valid elevations from min to max (m) on this grid, "" when they could be
   * terrain: heights beyond any on the Earth (below -11,100 or above 9,000 m: an undeclared
   * nodata value, or heights not in metres), else a relief over ten times the grid's larger
   * side at GetCellSizeMetres (a mean slope beyond 84 degrees across the grid, which no
   * terrain has, while coordinates in degrees taken for metres, a projected CRS given to a
   * lat/lon DEM, make cells of a millimetre and such a relief). `what` ends the message,
   * naming what is made of them ("Sky products computed from them"); the filters and
   * `aperture info` say it.
   */
  std::string GetElevationWarning(double min, double max, const char* what);

  /**
   * Ground size of one cell centred at CRS point (x, y), as GetCellSizeMetres (which is this at
   * the grid centre): for a projected CRS it changes across the grid with the projection's
   * scale factor. False (GetErrorMessage) when the cell has no geographic coordinates, or
   * reaches beyond a pole.
   */
  bool GetCellSizeMetresAt(double x, double y, double size[2]);

  /**
   * Ground metric of one cell centred at CRS point (x, y), m²: |E|², E·N and |N|², where E and N
   * are the ground vectors from the centre of the cell's west edge to its east edge and from its
   * south edge to its north edge (lengths of geodesics on the ellipsoid; the angle between them
   * from their chords, which holds near and on a pole). |E| and |N| are GetCellSizeMetresAt's
   * sizes; E·N is 0 on a conformal projection and on a lat/lon grid, and the angle between E and N
   * differs from 90° on others (Albers, sinusoidal). False (GetErrorMessage) when the cell has no
   * geographic coordinates, or reaches beyond a pole.
   */
  bool GetCellMetricAt(double x, double y, double metric[3]);

  /**
   * Meridian convergence γ at a geographic point (degrees): the angle from true north to grid
   * north, clockwise: positive when grid north lies east of true north (east of the central
   * meridian of a transverse Mercator zone in the northern hemisphere, where the meridians
   * lean towards the central one). A true azimuth A has grid azimuth A − γ. Computed from the
   * CRS itself by finite differences (the grid bearing of a short step north is −γ), so it
   * holds for any projection; 0 for a geographic CRS. NaN on failure.
   */
  double ComputeMeridianConvergence(double lon, double lat);

  /**
   * Ground size of the cells of every row, metres: dx[j] east-west and dy[j] south-north for
   * row j (0 = south), geodesic distances between the centres of opposite cell edges at the
   * grid's central column. For a lat/lon grid they change with latitude; for a projected grid
   * they change little (scale factor). dx and dy hold GridSize[1] values each. False (with
   * GetErrorMessage naming the row) when a row has no geographic coordinates, reaches beyond a
   * pole (an edge on the pole is fine) or gets a size that is not positive.
   */
  VTK_WRAPEXCLUDE bool GetRowCellSizesMetres(double* dx, double* dy);

  /**
   * GetRowCellSizesMetres for `count` rows from row `first` (0 = south) alone, the same values
   * (still at the whole grid's central column) into dx[0..count-1] and dy[0..count-1]: a window
   * of a grid of millions of rows needs only its own. False also for rows outside the grid.
   */
  VTK_WRAPEXCLUDE bool GetRowCellSizesMetres(int first, int count, double* dx, double* dy);

  /** Why the last failing call failed ("" after a success). */
  const char* GetErrorMessage();

protected:
  vtkApertureGeoreference();
  ~vtkApertureGeoreference() override;

  double GridOrigin[2];
  double GridSpacing[2];
  int GridSize[2];

private:
  vtkApertureGeoreference(const vtkApertureGeoreference&) = delete;
  void operator=(const vtkApertureGeoreference&) = delete;

  struct Internals;
  Internals* Impl;

  // False, with the reason as the error, for a grid that describes no cells: an origin that is
  // not finite, a cell size that is not positive and finite, no columns or rows (SetGrid takes
  // what it is given; the queries of the grid check it).
  bool CheckGrid();
};

#endif
