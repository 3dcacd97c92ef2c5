// SPDX-License-Identifier: BSD-3-Clause
#include "vtkApertureTerrainMesh.h"

#include "vtkApertureElevation.h"
#include "vtkApertureGeoreference.h"
#include "vtkApertureMemory.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExtentTranslator.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPThreadLocalObject.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include "ap_grid.h"
#include "ap_mesh.h"

#include <GeographicLib/AzimuthalEquidistant.hpp>
#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/LocalCartesian.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <new>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

vtkStandardNewMacro(vtkApertureTerrainMesh);

static_assert(sizeof(vtkTypeInt64) == sizeof(int64_t), "the C core writes 64-bit vertex ids");

//------------------------------------------------------------------------------
vtkApertureTerrainMesh::vtkApertureTerrainMesh()
  : ElevationArrayName(nullptr)
  , ArraySelectionMade(0)
  , VerticalExaggeration(1.0)
  , OutputPointsPrecision(SINGLE_PRECISION)
  , ComputeNormals(true)
  , GenerateTextureCoordinates(true)
  , MemoryLimit(0)
{
  // (taking any default selection away: the name holds until SetInputArrayToProcess selects
  // an array, the scalars included)
  this->SetElevationArrayName("Elevation");
}

//------------------------------------------------------------------------------
vtkApertureTerrainMesh::~vtkApertureTerrainMesh()
{
  this->SetElevationArrayName(nullptr);
}

//------------------------------------------------------------------------------
int vtkApertureTerrainMesh::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

namespace
{
// The extent of the DEM that piece `piece` of `pieces` meshes (pieces share their boundary
// points, so their meshes join). A global DEM's pieces are bands of whole rows, so that each
// joins its east and west edges (RequestData's seam), the quad rows shared out evenly (VTK's
// Y slabs split the columns too once the pieces outnumber the rows, and such pieces had no
// seam until 2026-12-07); a piece left without a quad row is empty. The CRS is known here when
// vtkApertureDEMReader published it, or from the input image itself when it is given with
// SetInputData. A piece that does not exist (p >= n) has an empty extent (ext[1] < ext[0]).
void PieceExtent(vtkInformation* inInfo, int piece, int pieces, int ext[6])
{
  int whole[6] = { 0, -1, 0, -1, 0, -1 }; // (empty without a whole extent)
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  std::copy(whole, whole + 6, ext);
  if (piece < 0 || piece >= std::max(pieces, 1))
  {
    const int empty[6] = { 0, -1, 0, -1, 0, -1 };
    std::copy(empty, empty + 6, ext);
  }
  else if (pieces > 1)
  {
    vtkNew<vtkApertureGeoreference> geo;
    // (an image given with SetInputData is there, whole, before any request; behind a filter
    // that drops the CRS from the information, the image held is whatever was read last, the
    // whole DEM or a piece, so it cannot decide: blocks then, whatever came before)
    vtkImageData* given = vtkApertureGivenImage(inInfo);
    const bool wraps = (geo->SetFromInformation(inInfo) ||
                         (given && given->GetNumberOfPoints() > 0 &&
                           geo->SetFromImage(given))) &&
      geo->WrapsAround();
    if (wraps)
    {
      const long long rows = static_cast<long long>(whole[3]) - whole[2];
      const long long first = whole[2] + rows * piece / pieces;
      const long long last = whole[2] + rows * (piece + 1) / pieces;
      ext[2] = static_cast<int>(first);
      ext[3] = static_cast<int>(last);
      if (last == first)
      {
        const int empty[6] = { 0, -1, 0, -1, 0, -1 };
        std::copy(empty, empty + 6, ext);
      }
    }
    else
    {
      vtkNew<vtkExtentTranslator> translator;
      translator->PieceToExtentThreadSafe(
        piece, pieces, 0, whole, ext, vtkExtentTranslator::BLOCK_MODE, 0);
    }
  }
}

// The layers of ghost cells a request for one of `pieces` pieces asks for (none for the whole
// DEM, which has no neighbours).
int GhostLevels(vtkInformation* outInfo, int pieces)
{
  const auto key = vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS();
  return pieces > 1 && outInfo->Has(key) ? std::max(0, outInfo->Get(key)) : 0;
}

// ext grown by `by` points on every side, within whole (a no-op on an empty extent).
void GrowExtent(int ext[6], const int whole[6], int by)
{
  for (int a = 0; a < 4 && ext[0] <= ext[1] && by > 0; a += 2)
  {
    ext[a] = static_cast<int>(std::max<long long>(whole[a], static_cast<long long>(ext[a]) - by));
    ext[a + 1] =
      static_cast<int>(std::min<long long>(whole[a + 1], static_cast<long long>(ext[a + 1]) + by));
  }
}

// vtkGhostType of a piece meshed over `ext` (its own extent `own` and ghost layers around it),
// whose nx x ny grid's triangles are `polys`, the quads' of grid row j from rowStart[j], then
// the caps' (a seam's copies of column 0 are the points from nx * ny on, one a row): the
// triangles of quads outside own's, and the caps another piece owns, are DUPLICATECELL; the
// points outside own's, used by such triangles alone, DUPLICATEPOINT.
void MarkGhosts(vtkPolyData* output, vtkCellArray* polys, const int ext[6], const int own[6],
  size_t nx, size_t ny, const std::vector<size_t>& rowStart)
{
  const size_t n = nx * ny;
  // (the column and row in the whole grid of point `id`: a seam copy is column nx)
  const auto column = [&](vtkIdType id) {
    return ext[0] + static_cast<long long>(static_cast<size_t>(id) < n ? id % nx : nx);
  };
  const auto row = [&](vtkIdType id) {
    return ext[2] + static_cast<long long>(static_cast<size_t>(id) < n ? id / nx : id - n);
  };
  vtkUnsignedCharArray* points = output->AllocatePointGhostArray();
  for (vtkIdType id = 0; id < points->GetNumberOfTuples(); ++id)
  {
    const long long i = column(id), j = row(id);
    const bool inside = (i >= own[0] && i <= own[1]) || static_cast<size_t>(id) >= n;
    if (!inside || j < own[2] || j > own[3])
    {
      // (added to the marks of a vtkGhostType the input passed on)
      points->SetValue(id, points->GetValue(id) | vtkDataSetAttributes::DUPLICATEPOINT);
    }
  }
  vtkUnsignedCharArray* cells = output->AllocateCellGhostArray();
  vtkNew<vtkIdList> ids;
  for (vtkIdType t = 0; t < polys->GetNumberOfCells(); ++t)
  {
    polys->GetCellAtId(t, ids);
    long long i = std::numeric_limits<long long>::max(), j = i;
    for (vtkIdType v = 0; v < ids->GetNumberOfIds(); ++v)
    {
      // (a quad's triangle has one of its two western corners, and one of its southern ones)
      i = std::min(i, column(ids->GetId(v)));
      j = std::min(j, row(ids->GetId(v)));
    }
    const bool cap = static_cast<size_t>(t) >= rowStart.back();
    // (a seam's quads start in the last column, which no other grid's do; a cap is the
    // piece's that owns the row of quads beside it, of two pieces sharing its row of points)
    const bool owned = cap
      ? (j == own[2] && own[3] > j) || (j == own[3] && own[2] < j)
      : i >= own[0] && (i < own[1] || own[1] == ext[1]) && j >= own[2] && j < own[3];
    if (!owned)
    {
      cells->SetValue(t, cells->GetValue(t) | vtkDataSetAttributes::DUPLICATECELL);
    }
  }
}

// Why a whole lat/lon grid cannot be meshed, found in the pipeline information before it is
// read (RequestData asks the same of the image): wider than the Earth (a gridline-registered
// global grid; a Mercator or equirectangular one too), beyond a pole, or cells of no size on
// the ground; "" for anything else, and when the information has no CRS (RequestData then has
// the image's).
std::string UnreadRefusal(vtkInformation* inInfo)
{
  vtkNew<vtkApertureGeoreference> geo;
  double bounds[4], cell[2];
  if (!geo->SetFromInformation(inInfo) || geo->IsLocal())
  {
    return std::string();
  }
  if (!geo->IsGeographic())
  {
    // (a Mercator or equirectangular grid wider than the Earth: read whole, then refused,
    // until 2026-12-07; other projected grids' questions need the grid)
    // (the span first: HasMeridianColumns measures the columns again, so it is asked only of
    // a grid refused, to tell one too wide from a CRS without geographic coordinates)
    if (geo->CheckLongitudeSpan())
    {
      return std::string();
    }
    const std::string why = geo->GetErrorMessage();
    return geo->HasMeridianColumns() ? why : std::string();
  }
  if (geo->GetBoundsLonLat(bounds) && geo->GetCellSizeMetres(cell))
  {
    return std::string();
  }
  return geo->GetErrorMessage();
}

// A streamed piece's normals (3 floats a point of the piece's extent `ext`) from its ENU
// positions and the one-point margin read around it (`margin`, whose elevations are the array
// `name`, placed with `exaggeration` in the frame at lonlat0 on `ellipsoid`; a site grid's
// with its unit in metres, else siteUnit 0); "" or what failed.
std::string MarginNormals(vtkImageData* margin, const char* name, double exaggeration,
  const int ext[6], const double* enu, vtkApertureGeoreference* geo, const double lonlat0[2],
  const double ellipsoid[2], const double centre[2], double siteUnit, bool seam, float* normals)
{
  // The margin's grid: the piece's ENU positions where it has them, the margin's points placed
  // as the piece's are (RequestData's step 4), nodata NaN; then the normals of that grid's
  // rows of the piece, of which the piece's columns are its normals.
  int mext[6];
  margin->GetExtent(mext);
  const size_t nx = static_cast<size_t>(ext[1] - ext[0] + 1);
  const size_t ny = static_cast<size_t>(ext[3] - ext[2] + 1);
  const size_t mx = static_cast<size_t>(mext[1] - mext[0] + 1);
  const size_t my = static_cast<size_t>(mext[3] - mext[2] + 1);
  const size_t ox = static_cast<size_t>(ext[0] - mext[0]);
  const size_t oy = static_cast<size_t>(ext[2] - mext[2]);
  const size_t mn = mx * my;
  std::vector<double> menu(3 * mn, std::numeric_limits<double>::quiet_NaN());
  for (size_t j = 0; j < ny; ++j)
  {
    std::copy(enu + 3 * j * nx, enu + 3 * (j + 1) * nx, menu.data() + 3 * ((j + oy) * mx + ox));
  }
  vtkDataArray* elevation =
    vtkApertureElevationArray(margin->GetPointData(), name, nullptr);
  if (!elevation)
  {
    return "the margin around the piece has no elevations";
  }
  std::vector<float> z(mn);
  vtkApertureCopyElevations(elevation, 0, static_cast<vtkIdType>(mn), z.data());
  std::vector<size_t> ring;
  std::vector<double> xy, ll;
  double origin[3], spacing[3];
  margin->GetOrigin(origin);
  margin->GetSpacing(spacing);
  for (size_t j = 0; j < my; ++j)
  {
    for (size_t i = 0; i < mx; ++i)
    {
      const bool inner = i >= ox && i < ox + nx && j >= oy && j < oy + ny;
      if (!inner && !std::isnan(z[j * mx + i]))
      {
        ring.push_back(j * mx + i);
        xy.push_back(origin[0] + (mext[0] + static_cast<double>(i)) * spacing[0]);
        xy.push_back(origin[1] + (mext[2] + static_cast<double>(j)) * spacing[1]);
      }
    }
  }
  ll.resize(xy.size());
  try
  {
    const GeographicLib::Geocentric earth(ellipsoid[0], ellipsoid[1]);
    const GeographicLib::LocalCartesian frame(lonlat0[1], lonlat0[0], 0.0, earth);
    if (siteUnit > 0.0)
    {
      const GeographicLib::Geodesic sphere(ellipsoid[0], ellipsoid[1]);
      const GeographicLib::AzimuthalEquidistant siteMap(sphere);
      for (size_t q = 0; q < ring.size(); ++q)
      {
        siteMap.Reverse(0.0, 0.0, (xy[2 * q] - centre[0]) * siteUnit,
          (xy[2 * q + 1] - centre[1]) * siteUnit, ll[2 * q + 1], ll[2 * q]);
      }
    }
    else if (!ring.empty() &&
      !geo->CRSToLonLatPoints(static_cast<vtkIdType>(ring.size()), xy.data(), ll.data()))
    {
      return "converting the margin's coordinates to geographic failed: " +
        std::string(geo->GetErrorMessage());
    }
    for (size_t q = 0; q < ring.size(); ++q)
    {
      double* p = &menu[3 * ring[q]];
      if (!std::isnan(ll[2 * q])) // (outside the CRS's domain: nodata, as in the piece)
      {
        frame.Forward(ll[2 * q + 1], ll[2 * q], exaggeration * z[ring[q]], p[0],
          p[1], p[2]);
      }
    }
  }
  catch (const std::exception& e)
  {
    return std::string("GeographicLib: ") + e.what();
  }
  std::vector<float> mnormals(3 * mn);
  const ap_status st = ap_mesh_normals_validate(menu.data(), mx, my, seam, mnormals.data());
  if (st != AP_OK)
  {
    return ap_status_string(st);
  }
  vtkSMPTools::For(static_cast<vtkIdType>(oy), static_cast<vtkIdType>(oy + ny),
    [&](vtkIdType j0, vtkIdType j1) {
      ap_mesh_normals_rows(menu.data(), mx, my, seam, static_cast<size_t>(j0),
        static_cast<size_t>(j1), mnormals.data());
    });
  for (size_t j = 0; j < ny; ++j)
  {
    const float* from = mnormals.data() + 3 * ((j + oy) * mx + ox);
    std::copy(from, from + 3 * nx, normals + 3 * j * nx);
  }
  return std::string();
}

} // namespace

//------------------------------------------------------------------------------
int vtkApertureTerrainMesh::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Turn the requested piece of the mesh into the extent of the DEM it needs: the piece's own
  // points and one more on every side where the DEM has them, for its boundary normals to
  // take their neighbours beyond it as the whole mesh's do (RequestData meshes the piece
  // alone).
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  const int piece = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER());
  const int pieces = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES());
  int whole[6] = { 0, -1, 0, -1, 0, -1 }, ext[6];
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  PieceExtent(inInfo, piece, pieces, ext);
  this->PlannedPiece[0] = piece;
  this->PlannedPiece[1] = pieces;
  std::copy(ext, ext + 6, this->PlannedExtent);
  // A whole grid RequestData would refuse is refused before it is read (a 20 GB global grid
  // was read whole first): VTK 9.1 goes on after a failed RequestUpdateExtent, so the input is
  // asked for nothing and RequestData reports the refusal. (A piece is meshed, or refused, on
  // its own grid, once read.)
  this->RefusedRequest = pieces > 1 ? std::string() : UnreadRefusal(inInfo);
  if (!this->RefusedRequest.empty())
  {
    const int nothing[6] = { 0, -1, 0, -1, 0, -1 };
    std::copy(nothing, nothing + 6, ext);
  }
  // (the piece's ghost layers, then the margin beyond them)
  GrowExtent(ext, whole, GhostLevels(outInfo, pieces));
  GrowExtent(ext, whole, pieces > 1 && this->ComputeNormals ? 1 : 0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ext, 6);
  // The request is this extent, not a piece: the pipeline copies the piece request upstream,
  // and a reader that produces sub-extents would intersect it with its own split (a quarter
  // of the DEM for the first of two pieces).
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkApertureTerrainMesh::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  try
  {
    const int ok = this->RunRequestData(inputVector, outputVector);
    if (!ok)
    {
      // An aborted or failed update leaves no mesh; without this mark the executive would
      // count the empty output as generated and hand it out again on the next Update.
      outputVector->GetInformationObject(0)->Set(
        vtkDemandDrivenPipeline::DATA_NOT_GENERATED(), 1);
    }
    return ok;
  }
  catch (const std::bad_alloc&)
  {
    // (VTK's arrays, std::vector and new throw; a process limit such as ulimit -v makes them)
    int dims[3];
    vtkApertureInputDimensions(inputVector[0], dims);
    vtkImageData* input = vtkImageData::GetData(inputVector[0]);
    const double bytes = this->EstimateBytes(double(dims[0]) * dims[1],
      input && input->GetPointData()->GetArray("BentNormal"), 0.0);
    vtkPolyData* output = vtkPolyData::GetData(outputVector);
    if (output)
    {
      output->Initialize(); // no half-built mesh
    }
    vtkErrorMacro(<< "out of memory: a mesh of " << dims[0] << " x " << dims[1]
                  << " points needs about " << std::ceil(bytes / 1048576.0)
                  << " MiB; decimate the DEM");
    return 0;
  }
}

//------------------------------------------------------------------------------
double vtkApertureTerrainMesh::EstimateBytes(double n, bool bentNormal, double copied) const
{
  const double pointBytes = this->OutputPointsPrecision == DOUBLE_PRECISION ? 24.0 : 12.0;
  const double idBytes = n > 2147483647.0 ? 8.0 : 4.0;
  // elevations, ENU scratch, points, normals, texture coordinates, a rotated bent normal; two
  // triangles a cell of three ids and an offset; a global DEM's copied point data
  return n * (4.0 + 24.0 + pointBytes + 12.0 + 8.0 + (bentNormal ? 12.0 : 0.0)) +
    n * 2.0 * 4.0 * idBytes + copied;
}

//------------------------------------------------------------------------------
int vtkApertureTerrainMesh::RunRequestData(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (std::isnan(this->VerticalExaggeration))
  {
    // (vtkSetClampMacro lets NaN through: every point would be NaN)
    vtkErrorMacro(<< "VerticalExaggeration is NaN");
    return 0;
  }
  if (!this->RefusedRequest.empty())
  {
    vtkErrorMacro(<< this->RefusedRequest);
    return 0;
  }
  if (!input || input->GetNumberOfPoints() == 0)
  {
    return 1; // empty in, empty out
  }
  vtkImageData* const given = input; // (held upstream: the crops below copy parts of it)
  // A piece that does not exist (p >= n of UpdatePiece): an empty mesh, as VTK's filters give.
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int piece = outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    : 0;
  const int pieces = outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    : 1;
  if (piece < 0 || piece >= std::max(pieces, 1))
  {
    return 1;
  }
  // So does one that VTK's split leaves without points (more pieces than the DEM has rows or
  // columns to give): the input still holds an earlier update, which was meshed again (1000
  // pieces of a 20 x 20 DEM summed 609 times its triangles until 2026-12-06).
  int own[6] = { 0, -1, 0, -1, 0, -1 }; // (a streamed piece's, without its ghost layers)
  const bool streamed =
    pieces > 1 && inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
  if (streamed)
  {
    // (the extent planned for this piece: whether a global DEM's pieces are bands was decided
    // from what was known then, and deciding again from the piece read could differ)
    if (this->PlannedPiece[0] == piece && this->PlannedPiece[1] == pieces)
    {
      std::copy(this->PlannedExtent, this->PlannedExtent + 6, own);
    }
    else
    {
      PieceExtent(inInfo, piece, pieces, own);
    }
    if (own[1] < own[0] || own[3] < own[2])
    {
      return 1;
    }
  }
  // An input that holds more than this update asked for (a reader updated whole before, an
  // image given with SetInputData): the requested extent alone (a copy of it), so that a
  // streamed piece meshes its own part, not the whole DEM each time.
  std::string cropProblem;
  vtkNew<vtkImageData> cropped;
  if (inInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
  {
    int asked[6];
    inInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), asked);
    input = vtkApertureCropTo(input, asked, cropped, false, cropProblem);
  }
  // A streamed piece read with a margin (RequestUpdateExtent): meshed over its own extent and
  // the ghost layers asked for, the margin kept for their boundary normals.
  vtkSmartPointer<vtkImageData> margin;
  vtkNew<vtkImageData> pieceImage;
  const int ghostLevels = streamed ? GhostLevels(outInfo, pieces) : 0;
  if (input && streamed && this->ComputeNormals)
  {
    int meshed[6], wholeExtent[6];
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), wholeExtent);
    std::copy(own, own + 6, meshed);
    GrowExtent(meshed, wholeExtent, ghostLevels);
    vtkImageData* alone = vtkApertureCropTo(input, meshed, pieceImage, false, cropProblem);
    if (alone != input)
    {
      margin = input;
      input = alone;
    }
  }
  if (!input)
  {
    vtkErrorMacro(<< cropProblem);
    return 0;
  }

  // 1. Validate the grid and its elevation array.
  int ext[6];
  input->GetExtent(ext);
  if (ext[4] != ext[5])
  {
    vtkErrorMacro(<< "the DEM must be a 2-D image (one slice); this one has "
                  << (ext[5] - ext[4] + 1) << " slices");
    return 0;
  }
  const size_t nx = static_cast<size_t>(ext[1] - ext[0] + 1);
  const size_t ny = static_cast<size_t>(ext[3] - ext[2] + 1);
  int whole[6];
  std::copy(ext, ext + 6, whole);
  if (inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  }
  if (nx < 2 || ny < 2)
  {
    const bool piece = ext[0] > whole[0] || ext[1] < whole[1] || ext[2] > whole[2] ||
      ext[3] < whole[3];
    if (piece)
    {
      return 1; // a streamed piece one point thin has no triangles
    }
    vtkErrorMacro(<< "the DEM has " << nx << " x " << ny
                  << " points; a mesh needs at least 2 x 2");
    return 0;
  }
  std::string missing;
  std::string elevationName;
  vtkDataArray* elevation = vtkApertureSelectedElevation(this, this->ArraySelectionMade,
    input->GetPointData(), this->ElevationArrayName, elevationName, &missing);
  if (!elevation)
  {
    vtkErrorMacro(<< missing);
    return 0;
  }
  const vtkIdType n = static_cast<vtkIdType>(nx * ny);
  const std::string inconsistent = vtkApertureCheckPointArrays(
    input->GetPointData(), static_cast<vtkIdType>(nx), static_cast<vtkIdType>(ny));
  if (!inconsistent.empty())
  {
    vtkErrorMacro(<< inconsistent);
    return 0;
  }
  vtkNew<vtkApertureGeoreference> geo;
  double lonlatBounds[4];
  // (before the refusals it may explain: cells of one degree from latitude 0 past the pole)
  vtkApertureGeoreference::WarnOfDefaultGeometry(this, input);
  if (!geo->SetFromImage(input) || (!geo->IsLocal() && !geo->CheckLongitudeSpan()) ||
    (geo->IsGeographic() && !geo->GetBoundsLonLat(lonlatBounds)))
  {
    // (a lat/lon grid beyond a pole: its points there had no place, NaN in triangles drawn)
    vtkErrorMacro(<< geo->GetErrorMessage());
    return 0;
  }
  {
    // A grid whose cells have no size on the ground (a longitude of 1e17, at which a cell's
    // width is lost to rounding) would collapse its columns into one: refused, as the sky
    // filter refuses it.
    double cell[2];
    if (!geo->GetCellSizeMetres(cell))
    {
      vtkErrorMacro(<< geo->GetErrorMessage());
      return 0;
    }
  }
  // A global DEM (360 degrees of longitude) joins its east and west edges when this piece has
  // every column: each row's copy of its column-0 point closes the seam (ap_mesh.h).
  const bool seam = nx >= 3 && ext[0] == whole[0] && ext[1] == whole[1] && geo->WrapsAround();
  const vtkIdType nv = n + (seam ? static_cast<vtkIdType>(ny) : 0);
  {
    // refused before allocating: past physical memory Linux kills the process instead. Beside
    // the mesh: a global DEM's seam copies, the crops of the given image (to the update, to
    // the piece within its margin) and a streamed piece's margin normals (MarginNormals: an
    // ENU grid, elevations and normals, 40 bytes a point of the margin).
    double copies =
      seam ? 1024.0 * static_cast<double>(input->GetPointData()->GetActualMemorySize()) : 0.0;
    for (vtkImageData* copy : { input, margin.GetPointer() })
    {
      if (copy && copy != given)
      {
        // (made already: under an address-space limit, in what it leaves, not counted again)
        const double bytes = 1024.0 * static_cast<double>(copy->GetActualMemorySize());
        copies += this->MemoryLimit > 0 ? bytes : vtkApertureHeldNow(bytes);
      }
    }
    if (margin)
    {
      copies += 40.0 * static_cast<double>(margin->GetNumberOfPoints());
    }
    // (ghost marks: a byte a point and a triangle)
    copies += ghostLevels > 0 ? 3.0 * static_cast<double>(nv) : 0.0;
    const double need = this->EstimateBytes(static_cast<double>(nv),
      input->GetPointData()->GetArray("BentNormal") != nullptr, copies);
    std::ostringstream needs;
    needs << "a mesh of " << nx << " x " << ny << " points needs about "
          << vtkApertureHumanBytes(need);
    const std::string problem = vtkApertureBeyondMemory(need,
      vtkApertureHeldNow(1024.0 * static_cast<double>(given->GetActualMemorySize())),
      this->MemoryLimit, needs.str());
    if (!problem.empty())
    {
      vtkErrorMacro(<< problem << "; decimate the DEM");
      return 0;
    }
  }

  // A site grid in a local CRS lies on the sphere of GetLocalSphereRadius, its centre at
  // latitude and longitude 0, +y north: each point at its azimuthal equidistant place there
  // (its distance and direction from the centre on the ground are the grid's).
  const bool site = geo->IsLocal();
  const double siteUnit = site ? geo->GetCRSUnitMetres() : 0.0;

  // 2. Frame origin: the centre of the whole extent (shared by every piece of a streamed DEM).
  double origin[3], spacing[3];
  input->GetOrigin(origin);
  input->GetSpacing(spacing);
  const double centre[2] = { origin[0] + 0.5 * (whole[0] + whole[1]) * spacing[0],
    origin[1] + 0.5 * (whole[2] + whole[3]) * spacing[1] };
  double lonlat0[2] = { 0.0, 0.0 };
  double ellipsoid[2] = { vtkApertureGeoreference::GetLocalSphereRadius(), 0.0 };
  if (!site && (!geo->CRSToLonLat(centre[0], centre[1], lonlat0) || !geo->GetEllipsoid(ellipsoid)))
  {
    vtkErrorMacro(<< geo->GetErrorMessage());
    return 0;
  }

  // 3. Elevations as contiguous float with NaN for nodata, and for any that is not finite, as
  //    the reader makes them (a copy: the input may be double or not array-of-structs, and
  //    points outside the CRS's domain become nodata below).
  std::unique_ptr<float[]> zBuffer(new float[static_cast<size_t>(n)]);
  float* z = zBuffer.get();
  vtkSMPTools::For(0, n, [&](vtkIdType begin, vtkIdType end) {
    vtkApertureCopyElevations(elevation, begin, end, z);
  });
  const ap_grid_view grid = ap_grid_view_make(z, nx, ny);
  ap_grid_stats stats;
  ap_status st = ap_grid_stats_compute(&grid, &stats);
  if (st != AP_OK)
  {
    vtkErrorMacro(<< "elevation statistics: " << ap_status_string(st));
    return 0;
  }
  if (stats.valid == 0)
  {
    vtkErrorMacro(<< "every point of the DEM is nodata; there is no terrain to mesh");
    return 0;
  }
  const std::string implausible =
    geo->GetElevationWarning(stats.min, stats.max, "A mesh and pictures made of them");
  if (!implausible.empty())
  {
    vtkWarningMacro(<< implausible);
  }
  this->UpdateProgress(0.1);

  // 4. Vertex positions, in parallel blocks of rows: CRS -> geographic (one transformer per
  //    thread; OGR transformations are not thread-safe) -> East-North-Up with GeographicLib's
  //    LocalCartesian (Forward is const). Each point is computed alone, so the result does not
  //    depend on the threads. `enu` keeps NaN for nodata, which the normals kernel skips;
  //    the output points put nodata vertices at finite places (on the grid, at the lowest
  //    valid height) so bounds and pickers stay sane; no triangle uses them.
  const std::string crs = geo->GetCRS();
  const double exaggeration = this->VerticalExaggeration;
  const double parkHeight = exaggeration * stats.min;
  std::unique_ptr<double[]> enuBuffer(new double[3 * static_cast<size_t>(n)]);
  double* enu = enuBuffer.get();
  vtkNew<vtkPoints> points;
  points->SetDataType(this->OutputPointsPrecision == DOUBLE_PRECISION ? VTK_DOUBLE : VTK_FLOAT);
  vtkApertureAllocate(points->GetData(), "Points", 3, nv);
  vtkDataArray* pointData = points->GetData();
  float* outFloat = this->OutputPointsPrecision == DOUBLE_PRECISION
    ? nullptr
    : static_cast<vtkFloatArray*>(pointData)->GetPointer(0);
  double* outDouble = outFloat ? nullptr : static_cast<vtkDoubleArray*>(pointData)->GetPointer(0);
  // A bent normal (vtkApertureSkyVisibility: unit, in each point's own local East-North-Up) is
  // rotated into the mesh's frame as the points are placed, with GeographicLib's rotation from
  // the local frame at the point to the LocalCartesian one.
  vtkDataArray* bentIn = input->GetPointData()->GetArray("BentNormal");
  vtkSmartPointer<vtkFloatArray> bentOut;
  if (bentIn && bentIn->GetNumberOfComponents() == 3 && bentIn->GetNumberOfTuples() == n)
  {
    bentOut = vtkSmartPointer<vtkFloatArray>::New();
    vtkApertureAllocate(bentOut, "BentNormal", 3, nv);
  }
  float* bent = bentOut ? bentOut->GetPointer(0) : nullptr;
  vtkSMPThreadLocalObject<vtkApertureGeoreference> transformers;
  vtkSMPThreadLocal<vtkIdType> unprojectable(0);
  std::atomic<bool> failed(false);
  try
  {
    const GeographicLib::Geocentric earth(ellipsoid[0], ellipsoid[1]);
    const GeographicLib::LocalCartesian frame(lonlat0[1], lonlat0[0], 0.0, earth);
    const GeographicLib::Geodesic sphere(ellipsoid[0], ellipsoid[1]); // (a site's: a sphere)
    const GeographicLib::AzimuthalEquidistant siteMap(sphere);
    const vtkIdType grain = std::max<vtkIdType>(1, 65536 / static_cast<vtkIdType>(nx));
    const auto placeRows = [&](vtkIdType j0, vtkIdType j1) {
      vtkApertureGeoreference* local = transformers.Local();
      if (!site && !local->HasCRS() && !local->SetCRS(crs.c_str()))
      {
        failed = true;
        return;
      }
      const size_t first = static_cast<size_t>(j0) * nx;
      const size_t count = static_cast<size_t>(j1 - j0) * nx;
      // (Forward is given the rotation, of 9 elements, only with a bent normal to turn)
      std::vector<double> xy(2 * count), ll(2 * count), rotation(bent ? 9 : 0);
      for (size_t q = 0; q < count; ++q)
      {
        const size_t i = q % nx, j = static_cast<size_t>(j0) + q / nx;
        xy[2 * q] = origin[0] + (ext[0] + static_cast<double>(i)) * spacing[0];
        xy[2 * q + 1] = origin[1] + (ext[2] + static_cast<double>(j)) * spacing[1];
      }
      if (site)
      {
        for (size_t q = 0; q < count; ++q)
        {
          siteMap.Reverse(0.0, 0.0, (xy[2 * q] - centre[0]) * siteUnit,
            (xy[2 * q + 1] - centre[1]) * siteUnit, ll[2 * q + 1], ll[2 * q]);
        }
      }
      else if (!local->CRSToLonLatPoints(static_cast<vtkIdType>(count), xy.data(), ll.data()))
      {
        failed = true;
        return;
      }
      for (size_t q = 0; q < count; ++q)
      {
        const size_t k = first + q;
        double* p = &enu[3 * k];
        const double lat = ll[2 * q + 1], lon = ll[2 * q];
        double stored[3] = { 0.0, 0.0, parkHeight };
        if (std::isnan(lon) && !std::isnan(z[k]))
        {
          z[k] = std::numeric_limits<float>::quiet_NaN(); // outside the CRS's domain
          ++unprojectable.Local();
        }
        if (std::isnan(z[k]))
        {
          p[0] = p[1] = p[2] = std::numeric_limits<double>::quiet_NaN();
          if (!std::isnan(lon))
          {
            frame.Forward(lat, lon, parkHeight, stored[0], stored[1], stored[2]);
          }
          if (bent)
          {
            std::fill(bent + 3 * k, bent + 3 * k + 3, std::numeric_limits<float>::quiet_NaN());
          }
        }
        else
        {
          if (bent) // (GeographicLib offsets an empty rotation's data pointer: UB, clang says)
          {
            frame.Forward(lat, lon, exaggeration * z[k], p[0], p[1], p[2], rotation);
          }
          else
          {
            frame.Forward(lat, lon, exaggeration * z[k], p[0], p[1], p[2]);
          }
          std::copy(p, p + 3, stored);
          if (bent)
          {
            double v[3];
            bentIn->GetTuple(static_cast<vtkIdType>(k), v);
            for (int r = 0; r < 3; ++r)
            {
              bent[3 * k + r] = static_cast<float>(
                rotation[3 * r] * v[0] + rotation[3 * r + 1] * v[1] + rotation[3 * r + 2] * v[2]);
            }
          }
        }
        if (outFloat)
        {
          for (int c = 0; c < 3; ++c)
          {
            outFloat[3 * k + c] = static_cast<float>(stored[c]);
          }
        }
        else
        {
          std::copy(stored, stored + 3, outDouble + 3 * k);
        }
      }
    };
    // in up to 20 bands of rows, with progress and a check for an abort (Ctrl-C in the
    // command line) after each: a DEM of 10^8 points takes half a minute here
    const vtkIdType bands = std::min<vtkIdType>(20, static_cast<vtkIdType>(ny));
    for (vtkIdType band = 0; band < bands && !failed; ++band)
    {
      const vtkIdType rows = static_cast<vtkIdType>(ny);
      vtkSMPTools::For(band * rows / bands, (band + 1) * rows / bands, grain, placeRows);
      this->UpdateProgress(0.1 + 0.6 * static_cast<double>(band + 1) / bands);
      if (this->GetAbortExecute())
      {
        output->Initialize(); // no half-built mesh
        return 0;
      }
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "GeographicLib: " << e.what());
    return 0;
  }
  if (failed)
  {
    vtkErrorMacro(<< "converting the DEM's coordinates to geographic failed: "
                  << geo->GetErrorMessage());
    return 0;
  }
  vtkIdType outside = 0;
  for (vtkIdType c : unprojectable)
  {
    outside += c;
  }
  if (outside)
  {
    vtkWarningMacro(<< outside << " points lie outside the domain of the CRS '"
                    << geo->GetCRSName() << "' and are treated as nodata");
  }
  // the seam's copies of column 0 (its points, rotated bent normals, normals: ap_mesh.h)
  const auto copySeam = [&](vtkDataArray* array) {
    for (size_t j = 0; seam && j < ny; ++j)
    {
      array->SetTuple(n + static_cast<vtkIdType>(j), static_cast<vtkIdType>(j * nx), array);
    }
  };
  copySeam(pointData);
  if (bentOut)
  {
    copySeam(bentOut);
  }
  pointData->Modified();
  output->SetPoints(points);

  // 6. Triangles, with holes at nodata: count per quad row, place rows by a prefix sum, fill
  //    in parallel (same order as a serial run). 32-bit ids whenever they fit.
  int fit32 = 0;
  st = ap_mesh_triangulate_validate(&grid, seam, &fit32);
  if (st != AP_OK)
  {
    vtkErrorMacro(<< "triangulation: " << ap_status_string(st));
    output->Initialize(); // (no points without their triangles)
    return 0;
  }
  const vtkIdType quadRows = static_cast<vtkIdType>(ny - 1);
  std::vector<size_t> rowStart(static_cast<size_t>(quadRows) + 1, 0);
  vtkSMPTools::For(0, quadRows, [&](vtkIdType j0, vtkIdType j1) {
    for (vtkIdType j = j0; j < j1; ++j)
    {
      rowStart[static_cast<size_t>(j) + 1] =
        ap_mesh_count_rows(&grid, seam, static_cast<size_t>(j), static_cast<size_t>(j) + 1);
    }
  });
  for (size_t j = 1; j < rowStart.size(); ++j)
  {
    rowStart[j] += rowStart[j - 1];
  }
  // A seam's end rows that circle a pole (their outer edges at latitude +-90 degrees) close
  // the hole there (ap_mesh_cap). Rows of the whole DEM only: a piece's inner rows are not.
  std::vector<int64_t> caps;
  for (int end = 0; seam && end < 2; ++end)
  {
    const size_t row = end ? ny - 1 : 0;
    if (ext[2 + end] != whole[2 + end])
    {
      continue;
    }
    const double yEdge = origin[1] + (ext[2] + static_cast<double>(row) + (end ? 0.5 : -0.5)) *
      spacing[1];
    double north[2], south[2];
    const bool atPole = (geo->LonLatToCRS(lonlat0[0], 90.0, north) &&
                          std::fabs(yEdge - north[1]) <= 1e-6 * std::fabs(spacing[1])) ||
      (geo->LonLatToCRS(lonlat0[0], -90.0, south) &&
        std::fabs(yEdge - south[1]) <= 1e-6 * std::fabs(spacing[1]));
    if (atPole)
    {
      const size_t at = caps.size();
      caps.resize(at + 3 * ap_mesh_cap(&grid, row, nullptr));
      ap_mesh_cap(&grid, row, caps.data() + at);
    }
  }
  const vtkIdType ntri = static_cast<vtkIdType>(rowStart.back() + caps.size() / 3);
  if (ntri == 0 && std::equal(ext, ext + 6, whole))
  {
    // (a streamed piece of nodata has none; the whole DEM must have a triangle to draw)
    vtkErrorMacro(<< "no 2 x 2 block of the DEM's points has three valid corners, which a "
                     "triangle needs: its valid points ("
                  << stats.valid
                  << ") are too few or too scattered among nodata; there is no terrain to mesh");
    output->Initialize();
    return 0;
  }
  vtkNew<vtkCellArray> polys;
  auto fill = [&](auto* offsets, auto* connectivity, auto writeRows) {
    vtkApertureAllocate(offsets, nullptr, 1, ntri + 1);
    vtkApertureAllocate(connectivity, nullptr, 1, 3 * ntri);
    auto* ids = connectivity->GetPointer(0);
    auto* offs = offsets->GetPointer(0);
    vtkSMPTools::For(0, quadRows, [&](vtkIdType j0, vtkIdType j1) {
      writeRows(static_cast<size_t>(j0), static_cast<size_t>(j1), ids + 3 * rowStart[j0]);
    });
    std::copy(caps.begin(), caps.end(), ids + 3 * rowStart.back());
    vtkSMPTools::For(0, ntri + 1, [&](vtkIdType t0, vtkIdType t1) {
      for (vtkIdType t = t0; t < t1; ++t)
      {
        offs[t] = static_cast<typename std::remove_pointer<decltype(offs)>::type>(3 * t);
      }
    });
    polys->SetData(offsets, connectivity);
  };
  if (fit32)
  {
    vtkNew<vtkTypeInt32Array> offsets, connectivity;
    fill(offsets.GetPointer(), connectivity.GetPointer(),
      [&](size_t j0, size_t j1, vtkTypeInt32* out) {
      ap_mesh_triangulate_rows_i32(&grid, seam, j0, j1, out);
    });
  }
  else
  {
    vtkNew<vtkTypeInt64Array> offsets, connectivity;
    fill(offsets.GetPointer(), connectivity.GetPointer(),
      [&](size_t j0, size_t j1, vtkTypeInt64* out) {
      ap_mesh_triangulate_rows(&grid, seam, j0, j1, reinterpret_cast<int64_t*>(out));
    });
  }
  output->SetPolys(polys);
  this->UpdateProgress(0.85);
  if (this->GetAbortExecute())
  {
    output->Initialize();
    return 0;
  }

  // 7. Point data: the DEM's arrays (vertex id = point id; BentNormal rotated above), then ours.
  vtkPointData* outPD = output->GetPointData();
  if (seam)
  {
    // (copies: the seam's vertices repeat column 0's values)
    vtkPointData* inPD = input->GetPointData();
    outPD->CopyAllocate(inPD, nv);
    outPD->CopyData(inPD, 0, n, 0);
    for (size_t j = 0; j < ny; ++j)
    {
      outPD->CopyData(inPD, static_cast<vtkIdType>(j * nx), n + static_cast<vtkIdType>(j));
    }
  }
  else
  {
    outPD->PassData(input->GetPointData());
  }
  vtkApertureNameElevation(input->GetPointData(), outPD, elevationName.c_str());
  if (bentOut)
  {
    outPD->RemoveArray("BentNormal");
    outPD->AddArray(bentOut);
  }
  if (this->ComputeNormals)
  {
    vtkNew<vtkFloatArray> normals;
    vtkApertureAllocate(normals, "Normals", 3, nv);
    float* nptr = normals->GetPointer(0);
    st = ap_mesh_normals_validate(enu, nx, ny, seam, nptr);
    if (st != AP_OK)
    {
      vtkErrorMacro(<< "normals: " << ap_status_string(st));
      output->Initialize();
      return 0;
    }
    if (margin)
    {
      const std::string problem = MarginNormals(margin, elevationName.c_str(), exaggeration,
        ext, enu, geo, lonlat0, ellipsoid, centre, site ? siteUnit : 0.0, seam, nptr);
      if (!problem.empty())
      {
        vtkErrorMacro(<< "normals: " << problem);
        output->Initialize();
        return 0;
      }
    }
    else
    {
      vtkSMPTools::For(0, static_cast<vtkIdType>(ny), [&](vtkIdType j0, vtkIdType j1) {
        ap_mesh_normals_rows(
          enu, nx, ny, seam, static_cast<size_t>(j0), static_cast<size_t>(j1), nptr);
      });
    }
    copySeam(normals);
    outPD->SetNormals(normals);
  }
  if (this->GenerateTextureCoordinates)
  {
    vtkNew<vtkFloatArray> tcoords;
    vtkApertureAllocate(tcoords, "TextureCoordinates", 2, nv);
    const double wnx = whole[1] - whole[0] + 1, wny = whole[3] - whole[2] + 1;
    float* t = tcoords->GetPointer(0);
    for (size_t j = 0; j < ny; ++j)
    {
      const float v = static_cast<float>((ext[2] + static_cast<double>(j) - whole[2] + 0.5) / wny);
      for (size_t i = 0; i < nx; ++i)
      {
        const size_t k = j * nx + i;
        t[2 * k] = static_cast<float>((ext[0] + static_cast<double>(i) - whole[0] + 0.5) / wnx);
        t[2 * k + 1] = v;
      }
      if (seam)
      {
        // past the east edge: an image covering the globe continues across the seam
        const size_t k = static_cast<size_t>(n) + j;
        t[2 * k] = static_cast<float>((static_cast<double>(nx) + 0.5) / wnx);
        t[2 * k + 1] = v;
      }
    }
    outPD->SetTCoords(tcoords);
  }
  if (ghostLevels > 0)
  {
    MarkGhosts(output, polys, ext, own, nx, ny, rowStart);
  }

  // 8. Field data: the CRS passed through, the GeoTransform of the grid meshed (the input's
  //    geometry: a VTK filter upstream that crops, resamples or moves the image passes on the
  //    field data of the grid before, which the mesh carried until 2026-12-07), frame recorded.
  output->GetFieldData()->PassData(input->GetFieldData());
  {
    double gt[6];
    geo->GetGeoTransform(gt);
    vtkNew<vtkDoubleArray> meshed;
    meshed->SetName(vtkApertureGeoreference::GetGeoTransformArrayName());
    meshed->SetNumberOfValues(6);
    std::copy(gt, gt + 6, meshed->GetPointer(0));
    output->GetFieldData()->AddArray(meshed); // (in place of the one passed)
  }
  vtkNew<vtkDoubleArray> frameOrigin;
  frameOrigin->SetName("FrameOrigin");
  frameOrigin->SetNumberOfValues(3);
  frameOrigin->SetValue(0, lonlat0[1]);
  frameOrigin->SetValue(1, lonlat0[0]);
  frameOrigin->SetValue(2, 0.0);
  vtkNew<vtkDoubleArray> frameEllipsoid;
  frameEllipsoid->SetName("FrameEllipsoid");
  frameEllipsoid->SetNumberOfValues(2);
  frameEllipsoid->SetValue(0, ellipsoid[0]);
  frameEllipsoid->SetValue(1, ellipsoid[1]);
  vtkNew<vtkDoubleArray> exaggerationArray;
  exaggerationArray->SetName("VerticalExaggeration");
  exaggerationArray->SetNumberOfValues(1);
  exaggerationArray->SetValue(0, exaggeration);
  vtkFieldData* fd = output->GetFieldData();
  fd->AddArray(frameOrigin);
  fd->AddArray(frameEllipsoid);
  fd->AddArray(exaggerationArray);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkApertureTerrainMesh::SetElevationArrayName(const char* name)
{
  if (vtkApertureDropElevationSelection(this, this->ArraySelectionMade))
  {
    this->Modified();
  }
  vtkSetStringBodyMacro(ElevationArrayName, name);
}

//------------------------------------------------------------------------------
void vtkApertureTerrainMesh::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ElevationArrayName: "
     << (this->ElevationArrayName ? this->ElevationArrayName : "(none)") << "\n";
  os << indent << "VerticalExaggeration: " << this->VerticalExaggeration << "\n";
  os << indent << "OutputPointsPrecision: " << this->OutputPointsPrecision << "\n";
  os << indent << "ComputeNormals: " << this->ComputeNormals << "\n";
  os << indent << "GenerateTextureCoordinates: " << this->GenerateTextureCoordinates << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << "\n";
}
