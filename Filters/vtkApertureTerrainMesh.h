// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkApertureTerrainMesh
 * @brief   Triangle mesh of a DEM in a local East-North-Up frame, in metres.
 *
 * Input: a DEM image as vtkApertureDEMReader produces it (point array `Elevation` in metres,
 * NaN = nodata, `CRS` in the field data; see vtkApertureGeoreference for the conventions).
 * Any elevation that is not finite is nodata too, as the reader makes it; finite ones beyond
 * any on the Earth (below -11,100 or above 9,000 m: an undeclared nodata value such as -32768,
 * heights not in metres) are meshed as they are, with a warning naming their range, as is a
 * relief over ten times the input's larger side (degrees taken for metres: a projected CRS
 * given to a lat/lon DEM).
 * Lat/lon and projected DEMs are both handled: every cell centre is converted to geographic
 * coordinates on the CRS's own ellipsoid, then with GeographicLib's LocalCartesian to a local
 * East-North-Up frame (x east, y north, z up, metres) whose origin is the centre of the DEM's
 * whole extent at height 0 on that ellipsoid. Earth curvature is therefore in the geometry:
 * far from the origin the surface drops below z = elevation by about d^2 / (2 R). A DEM in a
 * local CRS (a site grid, vtkApertureGeoreference::IsLocal) lies on the sphere of
 * vtkApertureGeoreference::GetLocalSphereRadius, its centre at latitude and longitude 0 and its
 * +y axis north, each point at its azimuthal equidistant place about the centre (so its ground
 * distance and direction from the centre are the grid's), as vtkApertureSkyVisibility bakes it;
 * FrameOrigin is then (0, 0, 0) and FrameEllipsoid that sphere.
 *
 * Output: one vertex per input point, vertex id = input point id (i + j * columns), so every
 * input point array (Elevation and later products) is carried over, unchanged except
 * `BentNormal` (below). Triangles follow
 * ap_mesh_triangulate(): two per cell, and nodata cells leave holes (a quad with one nodata
 * corner keeps the triangle of its three valid corners). Vertices of nodata points are kept
 * (with NaN normals, at the lowest valid elevation of the input the update read, which for
 * a piece may be another than the whole DEM's) so ids stay aligned with the grid; no
 * triangle uses them.
 *
 * A global DEM (vtkApertureGeoreference::WrapsAround: 360 degrees of longitude, at least 3
 * columns) is closed: its east and west edges are joined by a column of quads to one more
 * vertex per row after the grid's (id columns * rows + j: a copy of row j's point in column 0,
 * every point array's values included, with texture coordinate u = 1 + 0.5 / columns so that
 * an image covering the globe continues across the seam); normals there take the neighbours
 * across the seam. An end row whose outer edge is at latitude +-90 (the DEM reaches a pole) is
 * closed by a fan of triangles over its ring of points when none of them is nodata
 * (ap_mesh_cap), so that a pole-to-pole DEM is a closed surface: watertight once the seam's
 * copies are merged with their originals (vtkCleanPolyData; until then the seam's edges count as
 * boundary edges, to vtkFeatureEdges or vtkMassProperties).
 *
 * Streaming: a request for piece p of n is translated into the input extent of that piece
 * (vtkExtentTranslator's blocks, or a global DEM's bands below; pieces sharing their boundary rows
 * or columns) and, with ComputeNormals, one point more on every side where the DEM goes on, so the
 * reader reads little more than that part, the mesh holds only the piece, and the pieces' meshes
 * join without gaps. Every piece uses the frame of the whole extent, so their vertices coincide
 * with those of the whole mesh (but nodata's, placed as above), and their normals are the whole
 * mesh's, bit for bit, along their boundaries too (taken across them, from that margin). With ghost
 * levels (UpdatePiece(p, n, g), g > 0) the piece is meshed over g more points on every side where
 * the DEM goes on (the margin beyond them), and marked in vtkGhostType arrays as VTK's filters mark
 * ghosts: the triangles of quads outside the piece, and a pole's cap another piece owns (the one
 * with the row of quads beside it), DUPLICATECELL; the points outside it DUPLICATEPOINT
 * (vtkRemoveGhosts leaves the piece's own mesh). A piece that does not exist (p >= n) is an empty
 * mesh. A global DEM's pieces are bands of whole rows, each with its seam, the rows of quads shared
 * out evenly (a piece left without one is empty), when its CRS is known while the request is
 * planned (published by vtkApertureDEMReader and passed on by vtkApertureSkyVisibility, which
 * publishes an image's given to it with SetInputData, or an image given with SetInputData);
 * else blocks, without seams (behind a VTK filter that drops the CRS from the pipeline
 * information, such as vtkImageShiftScale), whatever was updated before. An input that holds more
 * than the piece (updated whole before, or given with SetInputData) is meshed over the piece's
 * extent alone. An update that fails or is aborted (AbortExecute, checked after each twentieth of
 * the points) leaves an empty mesh, and the next update runs again.
 *
 * Elevations taken from the input's active scalars, asked for (a null or empty
 * ElevationArrayName, a selection of the scalars) or for want of an `Elevation` array (an
 * image made by hand), come out as the point array `Elevation` too (the same values and type,
 * sharing their memory): instead of unnamed scalars, beside named ones; not over another array
 * so named.
 * Point arrays added: `Normals` (unit, ENU, of the output geometry including the vertical
 * exaggeration; active normals) and `TextureCoordinates` (u east, v north, spanning the outer
 * edges of the whole extent, so an image covering the DEM's bounds drapes exactly).
 * A 3-component input array `BentNormal` (vtkApertureSkyVisibility's: unit vectors in each
 * point's own local East-North-Up) is carried rotated into the mesh's frame, as float, NaN at
 * nodata points: it and `Normals` then share one frame, as vtkApertureLightingMapper expects.
 * (The local frames of a DEM's points differ from the mesh's by their angular distance from
 * its centre: 0.1 degree at 11 km, degrees on a lat/lon DEM of a region.)
 * Field data added: `FrameOrigin` (latitude, longitude in degrees, height in metres of the ENU
 * origin), `FrameEllipsoid` (semi-major axis in metres, flattening) and
 * `VerticalExaggeration`; the input's `CRS` is passed through, and `GeoTransform` is that of the
 * grid meshed (the input image's geometry, which wins over its field data, Rasters.md; a
 * piece's own grid with its ghost layers).
 *
 * An input of no points (an empty image, or an empty update extent) gives an empty mesh and no
 * error, as VTK's filters do.
 * Errors (vtkErrorMacro and a failed update): no elevation array or one of several components,
 * a whole DEM smaller than 2 x 2 (a streamed piece that thin just gives an empty mesh), a point
 * array without one tuple per point of the input, no CRS or one without geographic coordinates
 * (other than a local one), a lat/lon grid reaching beyond a pole, one or a Mercator or
 * equirectangular grid wider than the Earth (found in the pipeline information before a whole
 * DEM is read), every point nodata or no
 * triangle at all (too few or too scattered valid points: no 2 x 2 block with three valid
 * corners; a streamed piece just gives an empty mesh), a NaN VerticalExaggeration, or a mesh
 * beyond MemoryLimit or the process's memory (the message gives the size).
 *
 * @warning VTK 9.1's vtkDecimatePro reads outside its arrays, and can crash, on a mesh with
 * points no triangle uses, as a DEM with nodata gives (valgrind: GetCellEdgeNeighbors from
 * EvaluateVertex, on a mesh of the Luxembourg SRTM tile; none once they were gone): run
 * vtkCleanPolyData (PointMergingOff keeps the other points in place, renumbered: point ids no
 * longer follow the grid's) before it. vtkQuadricDecimation takes the mesh as it is.
 *
 * @warning Heights are used as given (usually orthometric, above the geoid) as heights above
 * the ellipsoid; over one DEM the geoid separation is nearly constant and shifts the whole mesh
 * rather than deforming it.
 * @sa vtkApertureDEMReader vtkApertureGeoreference
 */
#ifndef vtkApertureTerrainMesh_h
#define vtkApertureTerrainMesh_h

#include "ApertureFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // for RefusedRequest

class APERTUREFILTERS_EXPORT vtkApertureTerrainMesh : public vtkPolyDataAlgorithm
{
public:
  static vtkApertureTerrainMesh* New();
  vtkTypeMacro(vtkApertureTerrainMesh, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Name of the input's point array of elevations (metres; one component, any numeric type).
   *  Default "Elevation", which an input without an array so named takes from its active point
   *  scalars; a null or empty name, the active point scalars; a name the input lacks is an
   *  error naming the arrays it has.
   *  SetInputArrayToProcess(0, 0, 0, points, name), the way VTK's filters and ParaView select
   *  arrays, selects one in its place (or the point scalars, by attribute type); a selection of
   *  cell data or of another attribute is an error. Of the two, the one made last holds. */
  void SetElevationArrayName(const char* name);
  vtkGetStringMacro(ElevationArrayName);
  ///@}

  ///@{
  /**
   * Vertical exaggeration: vertices are placed at height VerticalExaggeration * elevation
   * above the ellipsoid. Default 1; range [0, 1000] (NaN: the update fails). Normals follow
   * the exaggerated surface.
   */
  vtkSetClampMacro(VerticalExaggeration, double, 0.0, 1000.0);
  vtkGetMacro(VerticalExaggeration, double);
  ///@}

  ///@{
  /**
   * Precision of the output points: vtkAlgorithm::SINGLE_PRECISION (default; ENU coordinates
   * within 200 km of the origin are then exact to about 1 cm) or DOUBLE_PRECISION.
   */
  vtkSetClampMacro(OutputPointsPrecision, int, SINGLE_PRECISION, DOUBLE_PRECISION);
  vtkGetMacro(OutputPointsPrecision, int);
  ///@}

  ///@{
  /** Whether to add the `Normals` and `TextureCoordinates` arrays. Default on. */
  vtkSetMacro(ComputeNormals, bool);
  vtkGetMacro(ComputeNormals, bool);
  vtkBooleanMacro(ComputeNormals, bool);
  vtkSetMacro(GenerateTextureCoordinates, bool);
  vtkGetMacro(GenerateTextureCoordinates, bool);
  vtkBooleanMacro(GenerateTextureCoordinates, bool);
  ///@}

  ///@{
  /**
   * Most bytes one update may allocate (estimated: per point the elevations' float copy 4, the
   * East-North-Up scratch 24, the points 12 or 24, normals 12, texture coordinates 8, a rotated
   * BentNormal 12 when the input has one; two triangles of three ids and an offset, 4 bytes
   * each, 8 past 2^31 points; a global DEM's seam copies the input's point arrays; so do
   * crops of an input larger than the update, a streamed piece's boundary normals take
   * 40 bytes a point of the piece and its margin, and its ghost marks 3 a point).
   * 0 (default): the memory this process may use (the machine's, or its control group's
   * limit) less the input image's size; under an address-space limit (ulimit -v), what that
   * leaves (vtkApertureSkyVisibility::GetUsableMemory), which excludes the input already.
   * An update beyond it is refused before allocating, naming the size: Linux does not fail an
   * allocation past physical memory, it kills the process later.
   */
  vtkSetClampMacro(MemoryLimit, vtkTypeInt64, 0, VTK_TYPE_INT64_MAX);
  vtkGetMacro(MemoryLimit, vtkTypeInt64);
  ///@}

  /** The bytes MemoryLimit's estimate gives an update of n points (with the current
   *  OutputPointsPrecision), an input with a `BentNormal` array or not, and `copied` bytes of
   *  input point data and scratch copied (a global DEM's seam, crops, a streamed piece's
   *  margin and ghost marks; 0 for a whole DEM given whole): for planning beforehand. */
  double EstimateBytes(double n, bool bentNormal, double copied) const;

protected:
  vtkApertureTerrainMesh();
  ~vtkApertureTerrainMesh() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  /** RequestData's work; RequestData turns a failed allocation in it into an error. */
  int RunRequestData(vtkInformationVector** inputVector, vtkInformationVector* outputVector);

  char* ElevationArrayName;
  vtkMTimeType ArraySelectionMade; // (the input array selection's MTime when made)
  double VerticalExaggeration;
  int OutputPointsPrecision;
  bool ComputeNormals;
  bool GenerateTextureCoordinates;
  vtkTypeInt64 MemoryLimit;
  std::string RefusedRequest; // (RequestUpdateExtent's refusal, for RequestData to report)
  // (the piece RequestUpdateExtent planned, piece and pieces, and its own extent: RequestData
  // meshes that one, decided once)
  int PlannedPiece[2] = { -1, 0 };
  int PlannedExtent[6] = { 0, -1, 0, -1, 0, -1 };


private:
  vtkApertureTerrainMesh(const vtkApertureTerrainMesh&) = delete;
  void operator=(const vtkApertureTerrainMesh&) = delete;
};

#endif
