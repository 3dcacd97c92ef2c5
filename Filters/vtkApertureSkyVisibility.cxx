// SPDX-License-Identifier: BSD-3-Clause
#include "vtkApertureSkyVisibility.h"

#include "vtkApertureElevation.h"
#include "vtkApertureEmptyOutput.h"
#include "vtkApertureGeoreference.h"
#include "vtkApertureMemory.h"
#include "vtkApertureSMPThreads.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStructuredData.h"
#include "vtkUnsignedCharArray.h"

#include "ap_horizon.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <locale>
#include <memory>
#include <new>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

vtkStandardNewMacro(vtkApertureSkyVisibility);

namespace
{
// A projected DEM's ground cell size may differ from its centre's by this much (relative) at
// its corners and edge midpoints before the filter warns: a horizon's tangent there is off by
// as much (a 45-degree horizon by 0.14 degree at 0.5%; a whole UTM zone changes by 0.1%).
constexpr double ScaleChangeWarning = 0.005;
// Nodes per side of the lattices over a projected DEM (at most: one per cell on smaller grids)
// of ground metrics and of meridian convergences, bilinear between them: across a DEM of
// 1000 km, nodes 31 km apart leave the scale factor's curvature (about 1 / R^2) some 3e-6 of
// it.
constexpr int LatticeNodes = 33;
// Relative metric changes below this leave the kernel at the centre's cell size: a float's
// rounding (and the same bits as without a lattice on small DEMs).
constexpr double ScaleChangeApplied = 1e-6;
// A projection that turns the grid's directions on the ground by more than this (degrees)
// somewhere on the DEM (not conformal: Albers, LAEA, sinusoidal) has each cell's sector
// azimuths from its own metric (RequestData, step 5); below, from the meridian convergence
// alone, which is off by at most as much.
constexpr double ConformalTurn = 1e-4;
// The meridian convergence is bilinear between the lattice's nodes where that misses it by at
// most this much (rad, 0.006 degree) at the lattice cell's centre, else each cell's own
// (within some lattice cells of a pole).
constexpr double GammaTolerance = 1e-4;
// Cells of the grid above which a sector's phases run in slices, reporting progress between
// them (RequestData): some 0.1-0.4 s of a sector's costliest phase on two threads.
constexpr double SliceCells = 8.0 * 1024 * 1024;

// The start of both out-of-memory messages: "a NX x NY DEM with these products needs about
// SIZE", and what HorizonAngles cost when they are asked for.
// (an output of onx x ony cells smaller than the nx x ny input is a sub-extent and its halo)
std::string NeedsText(
  int nx, int ny, int onx, int ony, const std::string& size, bool horizonAngles)
{
  std::ostringstream s;
  if (static_cast<double>(onx) * ony < static_cast<double>(nx) * ny)
  {
    s << "the products of " << onx << " x " << ony << " cells, with the " << nx << " x " << ny
      << " cells of DEM around them, need about " << size;
  }
  else
  {
    s << "a " << nx << " x " << ny << " DEM with these products needs about " << size;
  }
  s << (horizonAngles ? " (HorizonAngles take 4 bytes per cell and direction)" : "");
  return s.str();
}

// Describe the grid of the whole extent `whole` of an image with this origin and spacing
// (RequestUpdateExtent sizes the halo on it, RequestData takes the DEM-wide values from it).
void SetWholeGrid(
  vtkApertureGeoreference* geo, const double origin[3], const double spacing[3], const int whole[6])
{
  geo->SetGrid(origin[0] + whole[0] * spacing[0], origin[1] + whole[2] * spacing[1], spacing[0],
    spacing[1], whole[1] - whole[0] + 1, whole[3] - whole[2] + 1);
}

// The refusal of a grid (geo describing the whole grid) with no metric cell size, or "": a
// lat/lon grid wider than the Earth (a gridline-registered global grid's duplicate meridian, a
// wrong cell size), or a first, middle or last row without one (beyond a pole, off the
// projection's domain: a grid's rows fail at its ends first). RequestData measures these rows,
// or all, so this finds what it would. For an update of a sub-extent (`piece`), also why a
// piece cannot leave the whole grid's problem out.
std::string WholeGridProblem(vtkApertureGeoreference* geo, bool piece)
{
  int size[2];
  geo->GetGridSize(size);
  double dx, dy;
  for (const int row : { 0, size[1] / 2, size[1] - 1 })
  {
    // (which checks the longitude span first)
    if (!geo->GetRowCellSizesMetres(row, 1, &dx, &dy))
    {
      return std::string("no metric cell size: ") + geo->GetErrorMessage() +
        (piece ? "; that is the whole grid's: a sub-extent's cells are measured on the whole "
                 "grid, so that sub-extents tile it"
               : "");
    }
  }
  return std::string();
}

// WholeGridProblem for an update of `ext` of the input whose pipeline information is inInfo,
// found there before anything is read; "" too when the information has no CRS.
std::string UnreadRefusal(vtkInformation* inInfo, const int ext[6])
{
  vtkNew<vtkApertureGeoreference> geo;
  if (!geo->SetFromInformation(inInfo))
  {
    return std::string();
  }
  int whole[6];
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  return WholeGridProblem(geo, !std::equal(ext, ext + 6, whole));
}

// For a projected grid (geo describing the whole grid): a warning when its ground cell size s at
// a corner or an edge midpoint differs from the centre's c, which the sweep uses for every
// cell, by more than ScaleChangeWarning (the projection's scale factor changes across the
// grid): horizon tangents there are s / c times the truth. "" otherwise, and for the points
// whose sizes cannot be measured.
std::string ScaleChange(vtkApertureGeoreference* geo)
{
  double origin[2], spacing[2], sizes[9][2];
  bool measured[9];
  int size[2];
  geo->GetGridOrigin(origin);
  geo->GetGridSpacing(spacing);
  geo->GetGridSize(size);
  for (int k = 0; k < 9; ++k) // (corners, edge midpoints and the centre, k = 4)
  {
    measured[k] = geo->GetCellSizeMetresAt(origin[0] + 0.5 * (k % 3) * (size[0] - 1) * spacing[0],
      origin[1] + 0.5 * (k / 3) * (size[1] - 1) * spacing[1], sizes[k]);
  }
  const double* centre = sizes[4];
  if (!measured[4] || !(centre[0] > 0) || !(centre[1] > 0))
  {
    return "";
  }
  double lo[2] = { centre[0], centre[1] }, hi[2] = { centre[0], centre[1] }, worst = 0.0;
  for (int k = 0; k < 9; ++k)
  {
    for (int c = 0; c < 2 && measured[k]; ++c)
    {
      lo[c] = std::min(lo[c], sizes[k][c]);
      hi[c] = std::max(hi[c], sizes[k][c]);
      worst = std::max(worst, std::fabs(sizes[k][c] / centre[c] - 1.0));
    }
  }
  if (!(worst > ScaleChangeWarning))
  {
    return "";
  }
  // (metres to four significant digits, without an exponent)
  const auto metres = [](double v) {
    const int digits = std::max(0, 3 - static_cast<int>(std::floor(std::log10(v))));
    std::ostringstream s;
    s << std::fixed << std::setprecision(digits) << v;
    return s.str();
  };
  std::ostringstream m;
  m << "the projection's scale changes across this DEM: its cells measure " << metres(lo[0])
    << " to " << metres(hi[0]) << " m east-west and " << metres(lo[1]) << " to "
    << metres(hi[1]) << " m south-north on the ground, against " << metres(centre[0]) << " x "
    << metres(centre[1]) << " m at its centre, which the sweep uses for every cell, so "
    << "horizon tangents are off by up to " << std::fixed << std::setprecision(2)
    << 100.0 * worst << "% towards its edges; bake smaller pieces, or the DEM reprojected to a "
    << "projection centred on it";
  return m.str();
}

// Node a of `nodes` spread evenly over `cells` columns (or rows), the first and last on the
// first and last: its place in cells from the first. The lattices over a projected DEM (its
// ground metrics, its meridian convergences) put their nodes there.
double LatticeNode(int a, int nodes, int cells)
{
  return (cells - 1.0) * a / (nodes - 1);
}

// The ground metric of one grid step (vtkApertureGeoreference::GetCellMetricAt) at
// cols x rows nodes spread evenly over geo's grid (LatticeNode), for the kernel's
// scale_metric (ap_horizon.h). False when a node has no geographic coordinates.
bool ScaleMetric(vtkApertureGeoreference* geo, int cols, int rows, std::vector<double>& metric)
{
  double origin[2], spacing[2];
  int size[2];
  geo->GetGridOrigin(origin);
  geo->GetGridSpacing(spacing);
  geo->GetGridSize(size);
  metric.resize(3 * static_cast<size_t>(cols) * rows);
  for (int b = 0; b < rows; ++b)
  {
    for (int a = 0; a < cols; ++a)
    {
      const double i = LatticeNode(a, cols, size[0]), j = LatticeNode(b, rows, size[1]);
      if (!geo->GetCellMetricAt(origin[0] + i * spacing[0], origin[1] + j * spacing[1],
            metric.data() + 3 * (static_cast<size_t>(b) * cols + a)))
      {
        metric.clear();
        return false;
      }
    }
  }
  return true;
}

// Over the nodes of a metric lattice taken relative to cells of dx0 x dy0 m: the largest
// change of a step's ground length (relative, |rho - 1| over every direction: the metric's
// singular values' square roots), and the largest angle (degrees) by which it turns a
// direction on the ground (asin((s1 - s2) / (s1 + s2)) for the square roots s1 >= s2; 0 on a
// conformal projection).
void MetricChange(const std::vector<double>& metric, double dx0, double dy0, double& scale,
  double& turn)
{
  scale = turn = 0.0;
  for (size_t k = 0; k + 2 < metric.size(); k += 3)
  {
    const double a = metric[k] / (dx0 * dx0), b = metric[k + 1] / (dx0 * dy0),
                 c = metric[k + 2] / (dy0 * dy0);
    const double mean = 0.5 * (a + c), dev = std::hypot(0.5 * (a - c), b);
    const double s1 = std::sqrt(mean + dev), s2 = std::sqrt(std::max(0.0, mean - dev));
    scale = std::max(scale, std::max(std::fabs(s1 - 1.0), std::fabs(s2 - 1.0)));
    turn = std::max(turn, std::asin((s1 - s2) / (s1 + s2)) * 180.0 / M_PI);
  }
}

// Halo (in cells along i and j) that a search distance needs around grid rows j0..j1 (0 = the
// grid's south row), from the smallest metric cell sizes of the rows within the distance: the
// rows are measured outwards from the region (as GetRowCellSizesMetres, a chunk at a time) until
// the rows the halo spans are all measured, or it spans the whole grid. A window of a grid of
// millions of rows measures its own rows and those around it, not all. False when a row has no
// metric cell size.
bool HaloCells(vtkApertureGeoreference* geo, double distance, int j0, int j1, int halo[2])
{
  int size[2];
  geo->GetGridSize(size);
  const auto cells = [distance](double m) {
    return static_cast<int>(std::min(1e9, std::ceil(distance / m))) + 2;
  };
  double mx = std::numeric_limits<double>::infinity(), my = mx;
  const int chunk = 4096;
  std::vector<double> dx(chunk), dy(chunk);
  // A lat/lon grid's cells narrow (dx) and lengthen (dy, the meridian's radius) from the
  // equator towards either pole: the smallest of a run of rows are at its ends and at the row
  // nearest the equator, which are all it measures (a DEM declaring 2^31 rows of 1e-10 degree
  // measured each, an hour before its memory was found wanting).
  double grid[2], spacing[2];
  geo->GetGridOrigin(grid);
  geo->GetGridSpacing(spacing);
  const double equator = -grid[1] / spacing[1]; // (the grid row at latitude 0)
  const bool byLatitude = geo->IsGeographic() && std::isfinite(equator);
  const auto measure = [&](int first, int count) {
    if (byLatitude && count > 4)
    {
      const double last = first + count - 1.0;
      const double near = std::max<double>(first, std::min(last, std::floor(equator)));
      const int rows[4] = { first, static_cast<int>(near),
        static_cast<int>(std::min(last, near + 1.0)), first + count - 1 };
      for (int r : rows)
      {
        if (!geo->GetRowCellSizesMetres(r, 1, dx.data(), dy.data()))
        {
          return false;
        }
        mx = std::min(mx, dx[0]);
        my = std::min(my, dy[0]);
      }
      return true;
    }
    for (int c = 0; c < count; c += chunk)
    {
      const int n = std::min(chunk, count - c);
      if (!geo->GetRowCellSizesMetres(first + c, n, dx.data(), dy.data()))
      {
        return false;
      }
      mx = std::min(mx, *std::min_element(dx.begin(), dx.begin() + n));
      my = std::min(my, *std::min_element(dy.begin(), dy.begin() + n));
    }
    return true;
  };
  j0 = std::max(0, std::min(j0, size[1] - 1));
  j1 = std::max(j0, std::min(j1, size[1] - 1));
  int lo = j0, hi = j1; // the rows measured
  if (!measure(lo, hi - lo + 1))
  {
    return false;
  }
  for (;;)
  {
    if (!(mx > 0) || !(my > 0))
    {
      return false;
    }
    const int rows = cells(my);
    const int want0 = static_cast<int>(std::max<long long>(0, static_cast<long long>(j0) - rows));
    const int want1 =
      static_cast<int>(std::min<long long>(size[1] - 1, static_cast<long long>(j1) + rows));
    if ((want0 == lo && want1 == hi) || (cells(mx) >= size[0] && rows >= size[1]))
    {
      break; // (the halo's rows are all measured, or it covers the grid whatever they hold)
    }
    // one chunk further on each side at a time, so that a halo covering the grid stops early
    const int south = std::min(lo - want0, chunk), north = std::min(want1 - hi, chunk);
    if ((south > 0 && !measure(lo - south, south)) || (north > 0 && !measure(hi + 1, north)))
    {
      return false;
    }
    lo -= south;
    hi += north;
  }
  halo[0] = cells(mx);
  halo[1] = cells(my);
  return true;
}

// The columns of the other side a global DEM's sweep adds to each side for an input extent
// `in` of the whole extent `whole`, which geo's grid describes (vtkApertureSkyVisibility.h,
// GetWrapColumns): 0 unless its grid wraps around and `in` spans every column.
int WrapColumns(vtkApertureGeoreference* geo, double distance, const int in[6], const int whole[6])
{
  const int nxWhole = whole[1] - whole[0] + 1, nyWhole = whole[3] - whole[2] + 1;
  if (in[0] != whole[0] || in[1] != whole[1] || !geo->WrapsAround())
  {
    return 0;
  }
  int halo[2] = { nxWhole, nyWhole };
  if (distance > 0 && !HaloCells(geo, distance, in[2] - whole[2], in[3] - whole[2], halo))
  {
    halo[0] = nxWhole;
  }
  return std::min((nxWhole + 1) / 2, halo[0]);
}

// The extent of a grid whose whole extent is `whole` (described by geo, its CRS set) that an
// update of `ext` reads: `ext` grown by the halo of the search distance, clipped to the whole
// extent. A region sees terrain up to the search distance away; unlimited distance, or no way
// to know metres, needs the whole.
void InputExtentOf(
  vtkApertureGeoreference* geo, const int whole[6], double distance, const int ext[6], int in[6])
{
  std::copy(whole, whole + 6, in);
  int halo[2];
  // (the whole extent needs no halo: measuring every row of a projected grid declaring 2^31
  // of them for one took an hour)
  const bool all = ext[0] <= whole[0] && ext[1] >= whole[1] && ext[2] <= whole[2] &&
    ext[3] >= whole[3];
  if (all || !(distance > 0) ||
    !HaloCells(geo, distance, ext[2] - whole[2], ext[3] - whole[2], halo))
  {
    return;
  }
  // (in 64 bits: a halo beside an extent at the end of int's range)
  const auto grown = [](int bound, long long e, long long h, bool low) {
    return static_cast<int>(
      low ? std::max<long long>(bound, e - h) : std::min<long long>(bound, e + h));
  };
  in[0] = grown(whole[0], ext[0], halo[0], true);
  in[1] = grown(whole[1], ext[1], halo[0], false);
  in[2] = grown(whole[2], ext[2], halo[1], true);
  in[3] = grown(whole[3], ext[3], halo[1], false);
  if (geo->WrapsAround() &&
    (static_cast<long long>(ext[0]) - halo[0] < whole[0] ||
      static_cast<long long>(ext[1]) + halo[0] > whole[1]))
  {
    // a global DEM's halo across its antimeridian: the terrain on the other side, in every
    // column (an extent cannot wrap; RequestData joins the edges)
    in[0] = whole[0];
    in[1] = whole[1];
  }
}

// The same for the input whose pipeline information is inInfo (the CRS is published by
// vtkApertureDEMReader as pipeline information; without it, the whole extent).
void InputExtent(vtkInformation* inInfo, double distance, const int ext[6], int in[6])
{
  int whole[6];
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  std::copy(whole, whole + 6, in);
  vtkNew<vtkApertureGeoreference> geo;
  if (distance > 0 && geo->SetFromInformation(inInfo))
  {
    InputExtentOf(geo, whole, distance, ext, in);
  }
}

// Whether the elevations z of the input extent inExt (NaN nodata) are nodata in every cell of
// `part`, an extent within it.
bool NodataWithin(const float* z, const int inExt[6], const int part[6])
{
  const size_t nx = static_cast<size_t>(inExt[1] - inExt[0] + 1);
  for (int j = part[2]; j <= part[3]; ++j)
  {
    const float* row = z + static_cast<size_t>(j - inExt[2]) * nx;
    for (int i = part[0]; i <= part[1]; ++i)
    {
      if (!std::isnan(row[i - inExt[0]]))
      {
        return false;
      }
    }
  }
  return true;
}
} // namespace

//------------------------------------------------------------------------------
vtkApertureSkyVisibility::vtkApertureSkyVisibility()
  : NumberOfDirections(32)
  , MaximumDistance(0.0)
  , EarthCurvature(true)
  , RefractionCoefficient(0.13)
  , NearField(0)
  , NumberOfThreads(0)
  , NumberOfThreadsUsed(0)
  , InputAllNodata(false)
  , MemoryLimit(0)
  , ComputeVisibleSolidAngle(true)
  , ComputeApertureRadius(true)
  , ComputeBentNormal(true)
  , ComputeSkyViewFactor(true)
  , ComputeDiffuseSkyFactor(true)
  , ComputePositiveOpenness(true)
  , ComputeEdgeTruncated(true)
  , ComputeHorizonAngles(false)
  , AnglesInDegrees(false)
  , FloatEdgeTruncated(false)
  , ElevationArrayName(nullptr)
  , ArraySelectionMade(0)
{
  // (taking vtkImageAlgorithm's default selection of the point scalars away: the name holds
  // until SetInputArrayToProcess selects an array, the scalars included)
  this->SetElevationArrayName("Elevation");
}

//------------------------------------------------------------------------------
vtkApertureSkyVisibility::~vtkApertureSkyVisibility()
{
  this->SetElevationArrayName(nullptr);
}

//------------------------------------------------------------------------------
int vtkApertureSkyVisibility::GetMarchColumns()
{
  ap_horizon_params p;
  ap_horizon_params_init(&p);
  return p.march_columns;
}

//------------------------------------------------------------------------------
int vtkApertureSkyVisibility::GetFarMarchColumns()
{
  ap_horizon_params p;
  ap_horizon_params_init(&p);
  return p.far_march_columns;
}

//------------------------------------------------------------------------------
int vtkApertureSkyVisibility::GetSweptNearField()
{
  return AP_HORIZON_NEAR_FIELD_SWEPT;
}

//------------------------------------------------------------------------------
int vtkApertureSkyVisibility::GetMarchedNearField()
{
  return AP_HORIZON_NEAR_FIELD_MARCHED;
}

//------------------------------------------------------------------------------
int vtkApertureSkyVisibility::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestInformation(request, inputVector, outputVector))
  {
    return 0;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  // the output is on the input's grid: its CRS, for the filters downstream (the pipeline does
  // not pass our key on by itself)
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  const char* crs = inInfo ? inInfo->Get(vtkApertureGeoreference::CRS_KEY()) : nullptr;
  if (!crs && inInfo)
  {
    // an image given with SetInputData publishes nothing: its own CRS then, so that the
    // filters downstream plan as behind the reader (a mesher's pieces of a global DEM were
    // blocks, without their seams, until 2026-12-07); not for an image whose geometry was
    // never set and cannot be measured as it is (beyond a pole), whose refusal downstream
    // would come before this filter's warning about it (a review's)
    vtkImageData* given = vtkApertureGivenImage(inInfo);
    if (given)
    {
      crs = vtkApertureGeoreference::GetAttachedCRS(given);
      vtkNew<vtkApertureGeoreference> geo;
      if (crs && !vtkApertureGeoreference::GetDefaultGeometryWarning(given).empty() &&
        (!geo->SetFromImage(given) || !WholeGridProblem(geo, false).empty()))
      {
        crs = nullptr;
      }
    }
  }
  if (crs)
  {
    outInfo->Set(vtkApertureGeoreference::CRS_KEY(), crs);
  }
  else
  {
    outInfo->Remove(vtkApertureGeoreference::CRS_KEY());
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkApertureSkyVisibility::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int ext[6], in[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ext);
  this->RefusedRequest.clear();
  if (vtkStructuredData::GetDataDescriptionFromExtent(ext) == VTK_EMPTY)
  {
    // an empty request (VTK's way to ask for nothing) asks nothing of the input either
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ext, 6);
    return 1;
  }
  // A grid with no metric cell size (wider than the Earth, beyond a pole) is refused before the
  // DEM is read (a 20 GB global grid was read whole first): VTK 9.1 goes on after a failed
  // RequestUpdateExtent, so the input is asked for nothing and RequestData reports the refusal
  // (it refuses one itself whose CRS the pipeline information lacks).
  this->RefusedRequest = UnreadRefusal(inInfo, ext);
  if (!this->RefusedRequest.empty())
  {
    const int nothing[6] = { 0, -1, 0, -1, 0, -1 };
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), nothing, 6);
    return 1;
  }
  InputExtent(inInfo, this->MaximumDistance, ext, in);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), in, 6);
  // The request is this extent, not a piece: the pipeline copies a piece request upstream, and
  // a source that produces sub-extents would turn it into its own, halo-less extent.
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  return 1;
}

//------------------------------------------------------------------------------
bool vtkApertureSkyVisibility::ComputeInputExtent(const int extent[6], int input[6])
{
  vtkInformation* inInfo =
    this->GetNumberOfInputConnections(0) > 0 ? this->GetInputInformation(0, 0) : nullptr;
  if (!inInfo || !inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    vtkErrorMacro(<< "no input information (connect an input and call UpdateInformation)");
    return false;
  }
  // (a caller planning an update learns of a refusal before it reads anything: the command
  // line read a whole global grid, or refused it for memory, before the update refused it)
  const std::string refusal = UnreadRefusal(inInfo, extent);
  if (!refusal.empty())
  {
    vtkErrorMacro(<< refusal);
    return false;
  }
  InputExtent(inInfo, this->MaximumDistance, extent, input);
  return true;
}

//------------------------------------------------------------------------------
int vtkApertureSkyVisibility::GetWrapColumns(const int input[6])
{
  vtkInformation* inInfo =
    this->GetNumberOfInputConnections(0) > 0 ? this->GetInputInformation(0, 0) : nullptr;
  vtkNew<vtkApertureGeoreference> geo;
  if (!geo->SetFromInformation(inInfo))
  {
    // (an image given with SetInputData carries its CRS in its field data, not in the
    // information: the update wraps it all the same)
    const char* crs = inInfo && inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT())
      ? vtkApertureGeoreference::GetAttachedCRS(this->GetInputDataObject(0, 0))
      : nullptr;
    if (!crs || !geo->SetCRS(crs))
    {
      return 0;
    }
  }
  int whole[6];
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  return WrapColumns(geo, this->MaximumDistance, input, whole);
}

// The input's cell data over the output's cells, as vtkImageAlgorithm::CopyAttributeData
// copies it: a cell extent is the point extent less one on each axis of more than one point.
// An output collapsed on an axis the input is not (a one-column piece: its cells are lines,
// not the input's quads) gets none, rather than arrays shorter than its cells.
static void CopyCellData(vtkImageData* input, const int inExt[6], vtkImageData* output,
  const int outExt[6])
{
  int inCells[6], outCells[6];
  bool inside = true;
  for (int a = 0; a < 3; ++a)
  {
    inCells[2 * a] = inExt[2 * a];
    inCells[2 * a + 1] = inExt[2 * a + 1] - (inExt[2 * a] < inExt[2 * a + 1] ? 1 : 0);
    outCells[2 * a] = outExt[2 * a];
    outCells[2 * a + 1] = outExt[2 * a + 1] - (outExt[2 * a] < outExt[2 * a + 1] ? 1 : 0);
    inside = inside && (outExt[2 * a] < outExt[2 * a + 1]) == (inExt[2 * a] < inExt[2 * a + 1]) &&
      outCells[2 * a] >= inCells[2 * a] && outCells[2 * a + 1] <= inCells[2 * a + 1];
  }
  if (!inside || input->GetCellData()->GetNumberOfArrays() == 0)
  {
    return;
  }
  output->GetCellData()->CopyAllocate(input->GetCellData(), output->GetNumberOfCells());
  output->GetCellData()->CopyStructuredData(input->GetCellData(), inCells, outCells);
}

//------------------------------------------------------------------------------
int vtkApertureSkyVisibility::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  int ok = 0;
  try
  {
    ok = this->RunRequestData(inputVector, outputVector);
  }
  catch (const std::bad_alloc&)
  {
    // (VTK's arrays and std::vector throw; RunRequestData throws on the kernel's
    // AP_ERR_OUT_OF_MEMORY)
    int dims[3], ext[6];
    vtkApertureInputDimensions(inputVector[0], dims);
    outputVector->GetInformationObject(0)->Get(
      vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ext);
    const int onx = ext[1] - ext[0] + 1, ony = ext[3] - ext[2] + 1;
    const double mib = std::ceil(this->EstimateBytes(
                                   double(dims[0]) * dims[1], double(onx) * ony) / 1048576.0);
    std::ostringstream size;
    size << mib << " MiB";
    vtkErrorMacro(<< "out of memory: "
                  << NeedsText(
                       dims[0], dims[1], onx, ony, size.str(), this->ComputeHorizonAngles));
  }
  catch (const std::system_error& e)
  {
    // (vtkSMPTools' STDThread backend starting its threads: std::thread throws when the
    // system refuses one, e.g. no memory left for its stack)
    vtkErrorMacro(<< vtkApertureThreadsRefused(
                    vtkApertureSMPConfig(this->NumberOfThreads).MaxNumberOfThreads, e));
  }
  return vtkApertureEmptyOutputUnless(ok, outputVector);
}

//------------------------------------------------------------------------------
double vtkApertureSkyVisibility::EstimateBytes(double n) const
{
  // the outputs, the elevations' float copy, and the sweep's own state
  return (this->OutputBytesPerCell() + 4.0 +
           static_cast<double>(ap_horizon_state_bytes_per_cell(
             this->ComputeDiffuseSkyFactor ? 1 : 0, this->ComputeBentNormal ? 1 : 0))) *
    n;
}

//------------------------------------------------------------------------------
double vtkApertureSkyVisibility::EstimateBytes(double n, double outN) const
{
  // a sub-extent's outputs cover it alone; the input arrays passed are copied to it
  return outN < n ? this->EstimateBytes(n) - this->OutputBytesPerCell() * (n - outN) + 4.0 * outN
                  : this->EstimateBytes(n);
}

//------------------------------------------------------------------------------
vtkTypeInt64 vtkApertureSkyVisibility::GetUsableMemory()
{
  return vtkApertureUsableMemory();
}

//------------------------------------------------------------------------------
int vtkApertureSkyVisibility::GetUsableCores()
{
  return vtkApertureCores();
}

//------------------------------------------------------------------------------
bool vtkApertureSkyVisibility::IsMemoryGrouped()
{
  int source = AP_MEMORY_MACHINE;
  vtkApertureUsableMemory(&source);
  return source == AP_MEMORY_GROUP;
}

//------------------------------------------------------------------------------
bool vtkApertureSkyVisibility::IsMemoryAddressLimited()
{
  int source = AP_MEMORY_MACHINE;
  vtkApertureUsableMemory(&source);
  return source == AP_MEMORY_ADDRESS_SPACE;
}

//------------------------------------------------------------------------------
std::string vtkApertureSkyVisibility::GetUsableMemoryOwner()
{
  int source = AP_MEMORY_MACHINE;
  vtkApertureUsableMemory(&source);
  return vtkApertureUsableMemoryOwner(source);
}

//------------------------------------------------------------------------------
std::string vtkApertureSkyVisibility::FormatBytes(double bytes)
{
  return vtkApertureHumanBytes(bytes);
}

//------------------------------------------------------------------------------
std::string vtkApertureSkyVisibility::CheckMemory(int nx, int ny, double held) const
{
  return this->CheckMemory(nx, ny, nx, ny, held);
}

//------------------------------------------------------------------------------
std::string vtkApertureSkyVisibility::CheckMemory(
  int nx, int ny, int outNx, int outNy, double held) const
{
  const double n = static_cast<double>(nx) * ny, outN = static_cast<double>(outNx) * outNy;
  const double need = this->EstimateBytes(n, outN);
  return this->BeyondMemory(need, held,
    NeedsText(nx, ny, outNx, outNy, vtkApertureHumanBytes(need), this->ComputeHorizonAngles));
}

//------------------------------------------------------------------------------
std::string vtkApertureSkyVisibility::BeyondMemory(
  double need, double held, const std::string& needs) const
{
  return vtkApertureBeyondMemory(need, held, this->MemoryLimit, needs);
}

//------------------------------------------------------------------------------
double vtkApertureSkyVisibility::OutputBytesPerCell() const
{
  const bool floats[] = { this->ComputeVisibleSolidAngle, this->ComputeApertureRadius,
    this->ComputeSkyViewFactor, this->ComputeDiffuseSkyFactor, this->ComputePositiveOpenness };
  double perCell = 0.0;
  for (bool f : floats)
  {
    perCell += f ? 4.0 : 0.0;
  }
  perCell += this->ComputeBentNormal ? 12.0 : 0.0;
  // (as float: 4 bytes, and the kernel's byte flags beside them)
  perCell += this->ComputeEdgeTruncated ? (this->FloatEdgeTruncated ? 5.0 : 1.0) : 0.0;
  perCell += this->ComputeHorizonAngles ? 4.0 * this->NumberOfDirections : 0.0;
  return perCell;
}

//------------------------------------------------------------------------------
int vtkApertureSkyVisibility::RunRequestData(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  this->NumberOfThreadsUsed = 0;
  this->InputAllNodata = false;
  if (!this->RefusedRequest.empty())
  {
    vtkErrorMacro(<< this->RefusedRequest);
    return 0;
  }
  if (!input || input->GetNumberOfPoints() == 0)
  {
    return 1;
  }
  // The DEM is the extent this update asked of the input (the output's and its halo, within
  // the whole extent), also where the input holds more: vtkImageClip with ClipData off passes
  // all of its input on, and its terrain beyond the clip is no part of the DEM.
  vtkNew<vtkImageData> cropped;
  {
    vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
    int asked[6];
    std::string problem;
    if (inInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
    {
      inInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), asked);
      input = vtkApertureCropTo(input, asked, cropped, true, problem);
    }
    if (!input)
    {
      vtkErrorMacro(<< problem);
      return 0;
    }
  }

  // 1. Parameters.
  if (this->NumberOfDirections < 4 || this->NumberOfDirections > 360)
  {
    vtkErrorMacro(<< "NumberOfDirections must be within 4..360, not "
                  << this->NumberOfDirections);
    return 0;
  }
  if (!(this->MaximumDistance >= 0) || std::isinf(this->MaximumDistance))
  {
    vtkErrorMacro(<< "MaximumDistance must be a distance in metres >= 0 (0 = unlimited), not "
                  << this->MaximumDistance);
    return 0;
  }
  if (!(this->RefractionCoefficient >= 0 && this->RefractionCoefficient < 1))
  {
    vtkErrorMacro(<< "RefractionCoefficient must be within [0, 1), not "
                  << this->RefractionCoefficient);
    return 0;
  }

  // 2. The grid.
  int inExt[6], outExt[6];
  input->GetExtent(inExt);
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), outExt);
  for (int k = 0; k < 3; ++k)
  {
    outExt[2 * k] = std::max(outExt[2 * k], inExt[2 * k]);
    outExt[2 * k + 1] = std::min(outExt[2 * k + 1], inExt[2 * k + 1]);
  }
  if (vtkStructuredData::GetDataDescriptionFromExtent(outExt) == VTK_EMPTY)
  {
    return 1; // an empty request, or one outside the DEM: an empty output
  }
  if (inExt[4] != inExt[5])
  {
    vtkErrorMacro(<< "the DEM must be a 2-D image (one slice)");
    return 0;
  }
  const int nx = inExt[1] - inExt[0] + 1, ny = inExt[3] - inExt[2] + 1;
  std::string missing;
  std::string elevationName;
  vtkDataArray* elevation = vtkApertureSelectedElevation(this, this->ArraySelectionMade,
    input->GetPointData(), this->ElevationArrayName, elevationName, &missing);
  if (!elevation)
  {
    vtkErrorMacro(<< missing);
    return 0;
  }
  if (nx < 2 || ny < 2)
  {
    vtkErrorMacro(<< "the DEM has " << nx << " x " << ny << " cells; at least 2 x 2 are needed");
    return 0;
  }
  const std::string inconsistent = vtkApertureCheckPointArrays(input->GetPointData(), nx, ny);
  if (!inconsistent.empty())
  {
    vtkErrorMacro(<< inconsistent);
    return 0;
  }
  vtkNew<vtkApertureGeoreference> geo;
  // (before the refusals it may explain: cells of one degree from latitude 0 past the pole)
  vtkApertureGeoreference::WarnOfDefaultGeometry(this, input);
  if (!geo->SetFromImage(input))
  {
    vtkErrorMacro(<< "no metric cell size: " << geo->GetErrorMessage());
    return 0;
  }
  const size_t n = static_cast<size_t>(nx) * static_cast<size_t>(ny);
  // the output is the input's extent (no halo), else the kernel computes the output's region
  // of the input (the rest is the halo's terrain); products go straight into the output
  const bool whole = std::equal(inExt, inExt + 6, outExt);
  const int onx = outExt[1] - outExt[0] + 1, ony = outExt[3] - outExt[2] + 1;
  const size_t outN = static_cast<size_t>(onx) * static_cast<size_t>(ony);
  // Memory: refuse before allocating what cannot fit. Linux overcommits, so past physical
  // memory an allocation does not fail: the process is killed later, mid-sweep.
  {
    const std::string problem = this->CheckMemory(nx, ny, onx, ony,
      vtkApertureHeldNow(1024.0 * static_cast<double>(input->GetActualMemorySize())));
    if (!problem.empty())
    {
      vtkErrorMacro(<< problem << "; bake a part of the DEM, a decimated one, or fewer products");
      return 0;
    }
  }
  // Non-finite elevations (also doubles beyond the float range) are nodata, as the reader
  // makes them; finite ones beyond any on Earth are kept but named in a warning.
  struct Free
  {
    void operator()(float* p) const { std::free(p); }
  };
  const std::unique_ptr<float[], Free> z(static_cast<float*>(ap_alloc_huge(n * sizeof(float))));
  if (!z)
  {
    throw std::bad_alloc();
  }
  vtkApertureCopyElevations(elevation, 0, static_cast<vtkIdType>(n), z.get());
  const ap_grid_view zview =
    ap_grid_view_make(z.get(), static_cast<size_t>(nx), static_cast<size_t>(ny));
  // (the one statistics pass here: the kernel's validation in ap_horizon_create is the other)
  ap_grid_stats range;
  ap_status st = ap_grid_stats_compute(&zview, &range);
  if (st != AP_OK)
  {
    vtkErrorMacro(<< "elevation statistics: " << ap_status_string(st));
    return 0;
  }
  const std::string implausible = range.valid > 0
    ? geo->GetElevationWarning(range.min, range.max, "Sky products computed from them")
    : std::string();
  if (!implausible.empty())
  {
    vtkWarningMacro(<< implausible);
  }
  // Abort checkpoints in the serial set-up, which takes seconds on a DEM of 10^8 cells and more
  // before the first sector reports: a ProgressEvent at 0 (whose observers may abort), then
  // AbortExecute, as after each sector.
  const auto stopped = [this]() {
    this->UpdateProgress(0.0);
    return this->GetAbortExecute() != 0;
  };
  if (stopped())
  {
    return 0;
  }
  // What depends on the DEM as a whole (its centre's cell size, curvature radii and meridian
  // convergence, and the lattice of the sweep's lines) comes from the whole extent, so that a
  // streamed piece gets the whole run's values (the piece starts at its column pieceI, row pieceJ).
  int wholeExt[6];
  std::copy(inExt, inExt + 6, wholeExt);
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), wholeExt);
    if (!vtkApertureExtentInside(inExt, wholeExt))
    {
      std::copy(inExt, inExt + 6, wholeExt); // (not a sub-extent: use the data's own)
    }
  }
  const int nxWhole = wholeExt[1] - wholeExt[0] + 1, nyWhole = wholeExt[3] - wholeExt[2] + 1;
  const int pieceI = inExt[0] - wholeExt[0], pieceJ = inExt[2] - wholeExt[2];
  if (nxWhole - 1 > AP_HORIZON_MAX_ORIGIN || nyWhole - 1 > AP_HORIZON_MAX_ORIGIN)
  {
    vtkErrorMacro(<< "the DEM's grid of " << nxWhole << " x " << nyWhole
                  << " cells has more than the " << AP_HORIZON_MAX_ORIGIN + 1
                  << " cells a side the sweep can place its pieces in; bake a decimated DEM");
    return 0;
  }
  double origin[3], spacing[3];
  input->GetOrigin(origin);
  input->GetSpacing(spacing);
  // (from here on geo describes the whole grid; AttachToImage below uses only its CRS)
  SetWholeGrid(geo, origin, spacing, wholeExt);
  {
    const std::string problem =
      WholeGridProblem(geo, !std::equal(outExt, outExt + 6, wholeExt));
    if (!problem.empty())
    {
      vtkErrorMacro(<< problem);
      return 0;
    }
  }
  // Grids whose columns are meridians and rows parallels (lat/lon, Mercator, equirectangular)
  // get their cell sizes row by row, exact for every cell, and the sweep's lattice needs those
  // of every row of the whole grid; other projected grids are metric to within the
  // projection's scale factor, taken at the centre row (WholeGridProblem above measured the
  // first and last rows too, so that a grid reaching off its projection's domain is refused,
  // as a lat/lon one is).
  // A local CRS (a sphere of the mean radius, the grid's axes east and north) has cells all of
  // one size: the constant size is exact there, and the kernel's per-row steps, rounded so that
  // rows share their patterns, would only cost time and accuracy.
  const bool local = geo->IsLocal();
  const bool rowSizes = !local && geo->HasMeridianColumns();
  const bool northUp = rowSizes || local; // (the meridian convergence is 0 at every cell)
  const size_t sizedRows = rowSizes ? static_cast<size_t>(nyWhole) : 1;
  if (rowSizes)
  {
    // (per row of the whole grid: its two cell sizes here, the lattice's Ψ and steps in the
    // kernel; a window of a grid of a billion rows would take them past any memory)
    const double rowBytes = 32.0 * nyWhole;
    const std::string problem = this->BeyondMemory(rowBytes,
      vtkApertureHeldNow(4.0 * static_cast<double>(n)),
      "the sweep's lattice needs " + vtkApertureHumanBytes(rowBytes) +
        " for the cell sizes of every one of the grid's " + std::to_string(nyWhole) + " rows");
    if (!problem.empty())
    {
      vtkErrorMacro(<< problem << "; bake a decimated DEM");
      return 0;
    }
  }
  std::vector<double> dx(sizedRows), dy(sizedRows);
  // (a local CRS: its sphere, the centre at latitude 0)
  double centre[2] = { 0.0, 0.0 };
  double ellipsoid[2] = { vtkApertureGeoreference::GetLocalSphereRadius(), 0.0 };
  if (!geo->GetRowCellSizesMetres(rowSizes ? 0 : nyWhole / 2, static_cast<int>(sizedRows),
        dx.data(), dy.data()) ||
    (!local && (!geo->GetCentreLonLat(centre) || !geo->GetEllipsoid(ellipsoid))))
  {
    vtkErrorMacro(<< "no metric cell size: " << geo->GetErrorMessage());
    return 0;
  }
  // A global DEM (360 degrees of longitude, vtkApertureGeoreference::WrapsAround) read across
  // all its columns has no east and west edges: the sweep runs on a copy with `wrap` columns
  // of the other side added to each (the search distance's halo, at most half the globe; half
  // of it without a distance), its region the DEM's columns, as a piece of the endless
  // periodic DEM (origin_col -wrap). A piece whose halo stays inside reads and computes as any.
  const int wrap = WrapColumns(geo, this->MaximumDistance, inExt, wholeExt);
  std::unique_ptr<float[], Free> zWrapped;
  ap_grid_view kernelZ = zview;
  if (wrap > 0 && static_cast<long>(nx) + 2L * wrap - 1 > AP_HORIZON_MAX_ORIGIN)
  {
    vtkErrorMacro(<< "the global DEM's " << nx << " columns and the " << wrap
                  << " it sweeps again on each side have more than the "
                  << AP_HORIZON_MAX_ORIGIN + 1 << " a sweep can take; bake a decimated DEM, "
                  << "or give a MaximumDistance");
    return 0;
  }
  if (wrap > 0)
  {
    const int wnx = nx + 2 * wrap;
    const std::string problem = this->CheckMemory(wnx, ny, onx, ony,
      vtkApertureHeldNow(1024.0 * static_cast<double>(input->GetActualMemorySize())));
    if (!problem.empty())
    {
      vtkErrorMacro(<< problem << " (a global DEM with " << wrap
                    << " columns of the other side on each: its edges join); bake a part of the "
                       "DEM, a decimated one, or fewer products");
      return 0;
    }
    zWrapped.reset(static_cast<float*>(
      ap_alloc_huge(static_cast<size_t>(wnx) * static_cast<size_t>(ny) * sizeof(float))));
    if (!zWrapped)
    {
      throw std::bad_alloc();
    }
    vtkSMPTools::For(0, ny, [&](vtkIdType j0, vtkIdType j1) {
      for (vtkIdType j = j0; j < j1; ++j)
      {
        const float* row = z.get() + static_cast<size_t>(j) * nx;
        float* to = zWrapped.get() + static_cast<size_t>(j) * wnx;
        std::copy(row + nx - wrap, row + nx, to);
        std::copy(row, row + nx, to + wrap);
        std::copy(row, row + wrap, to + wrap + nx);
      }
    });
    kernelZ = ap_grid_view_make(zWrapped.get(), static_cast<size_t>(wnx), static_cast<size_t>(ny));
  }
  ap_horizon_grid grid;
  grid.z = kernelZ;
  grid.dx = rowSizes ? dx.data() + pieceJ : nullptr;
  grid.dy = rowSizes ? dy.data() + pieceJ : nullptr;
  grid.dx0 = dx[rowSizes ? static_cast<size_t>(nyWhole) / 2 : 0];
  grid.dy0 = dy[rowSizes ? static_cast<size_t>(nyWhole) / 2 : 0];

  ap_horizon_params params;
  ap_horizon_params_init(&params);
  params.directions = this->NumberOfDirections;
  params.max_distance =
    this->MaximumDistance > 0 ? this->MaximumDistance : std::numeric_limits<double>::infinity();
  params.curvature = this->EarthCurvature ? 1 : 0;
  params.refraction = this->RefractionCoefficient;
  params.near_field = this->NearField;
  params.origin_col = pieceI - wrap;
  params.origin_row = pieceJ;
  params.region_i0 = static_cast<size_t>(outExt[0] - inExt[0] + wrap);
  params.region_j0 = static_cast<size_t>(outExt[2] - inExt[2]);
  params.region_nx = static_cast<size_t>(onx);
  params.region_ny = static_cast<size_t>(ony);
  if (rowSizes)
  {
    // the sweep's lines bend with the rows' cell sizes: their lattice is the whole DEM's rows'
    params.whole_dx = dx.data();
    params.whole_dy = dy.data();
    params.whole_rows = static_cast<size_t>(nyWhole);
  }
  {
    // Radii of curvature of the ellipsoid at the DEM centre.
    const double a = ellipsoid[0], f = ellipsoid[1], e2 = f * (2 - f);
    const double s = std::sin(centre[1] * M_PI / 180.0), w2 = 1 - e2 * s * s;
    params.radius_normal = a / std::sqrt(w2);
    params.radius_meridian = a * (1 - e2) / (w2 * std::sqrt(w2));
  }
  const double gammaCentre = // (0 where the columns are meridians)
    northUp ? 0.0 : geo->ComputeMeridianConvergence(centre[0], centre[1]);
  if (std::isnan(gammaCentre))
  {
    vtkErrorMacro(<< "meridian convergence: " << geo->GetErrorMessage());
    return 0;
  }
  params.azimuth_offset = gammaCentre * M_PI / 180.0;
  // Other projections' scale changes across the DEM: each cell's ground distances from a
  // lattice of ground metrics (exact to the lattice's interpolation; on projections that are
  // not conformal the kernel weights each sector by its share of the ground's directions, and
  // step 5 takes its azimuths per cell). Without one (a node off the projection's domain), the
  // centre's cell size for every cell, warned about where that is off by more than
  // ScaleChangeWarning.
  std::vector<double> metric;
  bool sheared = false; // (the lattice is applied and turns directions: ConformalTurn)
  if (!northUp)
  {
    const int lx = std::min(nxWhole, LatticeNodes), ly = std::min(nyWhole, LatticeNodes);
    double scale = 0.0, turn = 0.0;
    if (ScaleMetric(geo, lx, ly, metric))
    {
      MetricChange(metric, grid.dx0, grid.dy0, scale, turn);
    }
    if (metric.empty())
    {
      const std::string warning = ScaleChange(geo);
      if (!warning.empty())
      {
        vtkWarningMacro(<< warning);
      }
    }
    else if (scale > ScaleChangeApplied)
    {
      params.scale_metric = metric.data();
      params.scale_cols = static_cast<size_t>(lx);
      params.scale_rows = static_cast<size_t>(ly);
      params.scale_span_cols = nxWhole - 1.0;
      params.scale_span_rows = nyWhole - 1.0;
    }
    sheared = params.scale_metric && turn > ConformalTurn;
  }
  // Nodata everywhere: an error for the whole DEM; a piece of one (a stretch of sea and its
  // halo) gets nodata products, as the whole run's cells there do. (The parameters are
  // validated by ap_horizon_create, with the elevations' second statistics pass.)
  if (range.valid == 0 && nx == nxWhole && ny == nyWhole)
  {
    vtkErrorMacro(<< "every cell of the DEM is nodata");
    return 0;
  }
  bool allNodata = range.valid == 0;
  if (!allNodata && !whole && this->MaximumDistance > 0 && NodataWithin(z.get(), inExt, outExt))
  {
    // An input holding more than this update reads (an image given whole with SetInputData):
    // judged, as a piece read with its halo is, by the extent and its halo alone. (Only when
    // the extent itself has no data: else neither has, and its halo is not measured again for
    // every strip of a streamed bake.)
    int part[6];
    InputExtentOf(geo, wholeExt, this->MaximumDistance, outExt, part);
    for (int k = 0; k < 6; k += 2)
    {
      part[k] = std::max(part[k], inExt[k]);
      part[k + 1] = std::min(part[k + 1], inExt[k + 1]);
    }
    allNodata = NodataWithin(z.get(), inExt, part);
  }

  if (stopped())
  {
    return 0;
  }

  // 3. Outputs: the output's arrays, over its extent.
  const int D = this->NumberOfDirections;
  struct Product
  {
    const char* Name;
    bool Wanted;
    int Components;
    vtkSmartPointer<vtkDataArray> Array;
  };
  Product products[8] = { { "VisibleSolidAngle", this->ComputeVisibleSolidAngle, 1, nullptr },
    { "ApertureRadius", this->ComputeApertureRadius, 1, nullptr },
    { "BentNormal", this->ComputeBentNormal, 3, nullptr },
    { "SkyViewFactor", this->ComputeSkyViewFactor, 1, nullptr },
    { "DiffuseSkyFactor", this->ComputeDiffuseSkyFactor, 1, nullptr },
    { "PositiveOpenness", this->ComputePositiveOpenness, 1, nullptr },
    { "EdgeTruncated", this->ComputeEdgeTruncated, 1, nullptr },
    { "HorizonAngles", this->ComputeHorizonAngles, D, nullptr } };
  for (Product& pr : products)
  {
    if (!pr.Wanted)
    {
      continue;
    }
    if (std::string(pr.Name) == "EdgeTruncated" && !this->FloatEdgeTruncated)
    {
      pr.Array = vtkSmartPointer<vtkUnsignedCharArray>::New();
    }
    else
    {
      pr.Array = vtkSmartPointer<vtkFloatArray>::New();
    }
    vtkApertureAllocate(pr.Array, pr.Name, pr.Components, static_cast<vtkIdType>(outN));
  }
  auto fptr = [&](int k) {
    return products[k].Array ? static_cast<vtkFloatArray*>(products[k].Array.Get())->GetPointer(0)
                            : nullptr;
  };
  ap_sky_products out;
  out.visible_solid_angle = fptr(0);
  out.aperture_radius = fptr(1);
  out.bent_normal = fptr(2);
  out.sky_view_factor = fptr(3);
  out.diffuse_sky_factor = fptr(4);
  out.positive_openness = fptr(5);
  // (float EdgeTruncated: the kernel's flags go to bytes here, converted in step 6)
  std::vector<unsigned char> edgeBytes(products[6].Array && this->FloatEdgeTruncated ? outN : 0);
  out.edge_truncated = !products[6].Array ? nullptr
    : this->FloatEdgeTruncated
    ? edgeBytes.data()
    : static_cast<vtkUnsignedCharArray*>(products[6].Array.Get())->GetPointer(0);
  out.horizon_angles = fptr(7);

  // 7. The output, made last (at once for a piece of nodata): the input's arrays and geometry
  //    over the requested extent, plus ours.
  const auto attach = [&]() {
    output->SetExtent(outExt);
    output->SetOrigin(input->GetOrigin());
    output->SetSpacing(input->GetSpacing());
    if (whole)
    {
      output->GetPointData()->PassData(input->GetPointData());
      output->GetCellData()->PassData(input->GetCellData());
    }
    else
    {
      output->GetPointData()->CopyAllocate(input->GetPointData(), static_cast<vtkIdType>(outN));
      output->GetPointData()->CopyStructuredData(input->GetPointData(), inExt, outExt);
      CopyCellData(input, inExt, output, outExt);
    }
    output->GetFieldData()->PassData(input->GetFieldData());
    vtkApertureNameElevation(input->GetPointData(), output->GetPointData(), elevationName.c_str());
    geo->AttachToImage(output); // the GeoTransform of the output's extent
    for (Product& pr : products)
    {
      if (!pr.Array)
      {
        continue;
      }
      vtkDataArray* arr = pr.Array;
      if (std::string(pr.Name) == "BentNormal")
      {
        arr->SetComponentName(0, "E");
        arr->SetComponentName(1, "N");
        arr->SetComponentName(2, "U");
      }
      if (std::string(pr.Name) == "HorizonAngles")
      {
        for (int d = 0; d < D; ++d)
        {
          // ("az011.25" in any locale: a program's LC_NUMERIC would make it "az011,25" in
          // printf, and so in the band descriptions and EXR channels written from it)
          std::ostringstream label;
          label.imbue(std::locale::classic());
          label << "az" << std::fixed << std::setprecision(2) << std::setw(6)
                << std::setfill('0') << 360.0 * d / D;
          arr->SetComponentName(d, label.str().c_str());
        }
      }
      output->GetPointData()->AddArray(arr);
    }
    return 1;
  };
  if (allNodata)
  {
    for (Product& pr : products)
    {
      if (pr.Array)
      {
        // (EdgeTruncated as bytes: 0, as the kernel gives a nodata cell)
        pr.Array->Fill(pr.Array->GetDataType() == VTK_UNSIGNED_CHAR
            ? 0.0
            : std::numeric_limits<double>::quiet_NaN());
      }
    }
    this->InputAllNodata = true;
    this->UpdateProgress(1.0);
    return attach();
  }

  // 4. The sweep, sector by sector; each sector's lines and rows in parallel.
  ap_horizon* hz = nullptr;
  st = ap_horizon_create(&grid, &params, &out, &hz);
  struct Destroy
  {
    void operator()(ap_horizon* h) const { ap_horizon_destroy(h); }
  };
  std::unique_ptr<ap_horizon, Destroy> owner(hz); // (freed also when starting threads throws)
  if (st == AP_ERR_OUT_OF_MEMORY)
  {
    throw std::bad_alloc(); // (RequestData names the size needed)
  }
  if (st != AP_OK)
  {
    vtkErrorMacro(<< "horizon computation: " << ap_status_string(st));
    return 0;
  }
  if (stopped())
  {
    return 0;
  }
  std::atomic<int> failure(AP_OK);
  auto record = [&failure](ap_status s) {
    if (s != AP_OK)
    {
      failure = s;
    }
  };
  bool aborted = false;
  vtkApertureThreadTally tally;
  // Progress within a sector too, on large DEMs (a sector of a 10000^2 DEM takes seconds): a
  // phase over more than SliceCells cells runs as slices of whole grains, each its own
  // parallel loop (the same chunks, so the same results), and after each slice but a sector's
  // last the filter reports progress and checks AbortExecute; smaller DEMs report once a
  // sector. A phase's share of its sector comes from the previous sector's times (a third
  // each in the first). The sectors take D of D + 1 parts of the progress; the end (the sums'
  // finish, then the bent normals' rotation and the horizons' azimuths) the last one, in two
  // reports: about as long as a sector takes.
  using Clock = std::chrono::steady_clock;
  const double parts = D + 1.0;
  const double cells = static_cast<double>(nx + 2 * wrap) * ny;
  double share[3] = { 1.0 / 3, 1.0 / 3, 1.0 / 3 }; // (of the sector's time, per phase)
  double seconds[3] = { 0.0, 0.0, 0.0 };            // (of the sector in progress)
  auto sliced = [&](int d, int phase, vtkIdType units, vtkIdType grain,
                  ap_status (*run)(const ap_horizon*, size_t, size_t)) {
    const Clock::time_point start = Clock::now();
    const vtkIdType grains = (units + grain - 1) / grain;
    const vtkIdType slices = std::max<vtkIdType>(
      1, std::min(grains, static_cast<vtkIdType>(std::ceil(cells / SliceCells))));
    double before = 0.0;
    for (int p = 0; p < phase; ++p)
    {
      before += share[p];
    }
    for (vtkIdType s = 0; s < slices && failure == AP_OK && !aborted; ++s)
    {
      const vtkIdType first = grains * s / slices * grain;
      const vtkIdType last = std::min(units, grains * (s + 1) / slices * grain);
      vtkSMPTools::For(first, last, grain, [&](vtkIdType a, vtkIdType b) {
        tally.Note();
        record(run(hz, static_cast<size_t>(a), static_cast<size_t>(b)));
      });
      if (slices > 1 && failure == AP_OK && (phase < 2 || s + 1 < slices))
      {
        const double f = before + share[phase] * (s + 1.0) / slices;
        this->UpdateProgress((d + std::min(f, 1.0)) / parts); // (shares sum to 1 +- rounding)
        aborted = this->GetAbortExecute() != 0;
      }
    }
    seconds[phase] = std::chrono::duration<double>(Clock::now() - start).count();
  };
  const vtkSMPTools::Config threads = vtkApertureSMPConfig(this->NumberOfThreads);
  vtkApertureSMPScope(threads, [&]() {
    for (int d = 0; d < D && failure == AP_OK && !aborted; ++d)
    {
      ap_status ps = ap_horizon_prepare(hz, d);
      if (ps != AP_OK)
      {
        failure = ps;
        break;
      }
      sliced(d, 0, static_cast<vtkIdType>(ap_horizon_near_field_count(hz)), 16,
        ap_horizon_near_field);
      // Small chunks of lines (ap_horizon.h): their hulls and windows stay in cache, and no
      // thread idles long at the end of a direction. Results do not depend on the chunks.
      sliced(d, 1, static_cast<vtkIdType>(ap_horizon_bracket_count(hz)),
        AP_HORIZON_SWEEP_BAND, ap_horizon_sweep);
      sliced(d, 2, ny, 64, ap_horizon_accumulate);
      if (failure != AP_OK || aborted)
      {
        break; // (no progress reported for a failed sector)
      }
      this->UpdateProgress((d + 1.0) / parts);
      aborted = this->GetAbortExecute() != 0;
      const double sector = seconds[0] + seconds[1] + seconds[2];
      for (int p = 0; p < 3 && sector > 0.0; ++p)
      {
        share[p] = seconds[p] / sector;
      }
    }
    if (failure == AP_OK && !aborted)
    {
      vtkSMPTools::For(0, ny, 64, [&](vtkIdType j0, vtkIdType j1) {
        tally.Note();
        ap_horizon_finish(hz, static_cast<size_t>(j0), static_cast<size_t>(j1));
      });
      this->UpdateProgress((D + 0.5) / parts);
      aborted = this->GetAbortExecute() != 0;
    }
  });
  owner.reset(); // (the sweep's state goes before the outputs are finished: peak memory)
  // (VTK's pool runs a short range in the calling thread itself, which the tally counts too:
  // threads at once, not distinct ones, are at most the configuration's)
  this->NumberOfThreadsUsed = std::min(tally.Count(), threads.MaxNumberOfThreads);
  if (failure == AP_ERR_OUT_OF_MEMORY)
  {
    throw std::bad_alloc();
  }
  if (failure != AP_OK)
  {
    vtkErrorMacro(<< "horizon computation: "
                  << ap_status_string(static_cast<ap_status>(failure.load())));
    return 0;
  }
  if (aborted)
  {
    return 0;
  }

  // 5. Bent normals into each cell's true East-North-Up: the sweep ran in the grid frame;
  //    the meridian convergence γ (from a coarse lattice over the whole extent, bilinear
  //    between where that holds, each cell's own elsewhere) rotates them. The sweep's sector d
  //    points at true azimuth φ_d + γ − γ(centre) at a cell: its HorizonAngles go back to φ_d,
  //    linear between the two sectors either side (the nearer one's where the other is an
  //    empty direction, -π/2). Where the projection is not conformal (sheared), the kernel's
  //    bent normal lies in the frame of S, the square root of the cell's relative metric
  //    (ap_horizon.h), which the ground's is a rotation of: the one that takes S w_N north,
  //    w_N the grid step towards true north (grid bearing −γ); and sector d points at the
  //    ground azimuth of S u(ψ_d) after it, u(ψ_d) the sector's grid direction.
  float* const horizons = out.horizon_angles;
  if ((out.bent_normal || horizons) && !northUp)
  {
    const int lx = std::min(nxWhole, LatticeNodes), ly = std::min(nyWhole, LatticeNodes);
    // γ (rad) at the whole DEM's cell (i, j), counted from its first column and row
    const auto exact = [&](double i, double j) {
      double ll[2];
      double g = gammaCentre;
      if (geo->CRSToLonLat(origin[0] + (wholeExt[0] + i) * spacing[0],
            origin[1] + (wholeExt[2] + j) * spacing[1], ll))
      {
        const double v = geo->ComputeMeridianConvergence(ll[0], ll[1]);
        g = std::isnan(v) ? gammaCentre : v;
      }
      return g * M_PI / 180.0;
    };
    const auto nodeI = [&](int a) { return LatticeNode(a, lx, nxWhole); };
    const auto nodeJ = [&](int b) { return LatticeNode(b, ly, nyWhole); };
    std::vector<double> gamma(static_cast<size_t>(lx * ly));
    for (int b = 0; b < ly; ++b)
    {
      for (int a = 0; a < lx; ++a)
      {
        gamma[static_cast<size_t>(b * lx + a)] = exact(nodeI(a), nodeJ(b));
      }
    }
    // Where γ is far from bilinear between the nodes (around a pole, where it takes every
    // value), the cells of that lattice cell get their own (serially: the CRS's
    // transformations are not thread-safe): GammaPatch.
    const auto cellOf = [](int k, int whole, int n) { // (the lattice cell of a column or row)
      return std::min(static_cast<int>(k * (n - 1.0) / (whole - 1.0)), n - 2);
    };
    struct GammaPatch
    {
      int I0, I1, J0, J1; // (output columns and rows)
      std::vector<double> Values;
    };
    std::vector<int> patchOf(static_cast<size_t>((lx - 1) * (ly - 1)), -1);
    std::vector<GammaPatch> patches;
    const int oi = outExt[0] - wholeExt[0], oj = outExt[2] - wholeExt[2];
    for (int b = 0; b + 1 < ly; ++b)
    {
      for (int a = 0; a + 1 < lx; ++a)
      {
        const double mean = 0.25 * (gamma[b * lx + a] + gamma[b * lx + a + 1] +
                                     gamma[(b + 1) * lx + a] + gamma[(b + 1) * lx + a + 1]);
        const double centre =
          exact(0.5 * (nodeI(a) + nodeI(a + 1)), 0.5 * (nodeJ(b) + nodeJ(b + 1)));
        if (!(std::fabs(std::remainder(centre - mean, 2.0 * M_PI)) > GammaTolerance))
        {
          continue;
        }
        GammaPatch patch{ onx, 0, ony, 0, {} };
        for (int i = 0; i < onx; ++i)
        {
          if (cellOf(i + oi, nxWhole, lx) == a)
          {
            patch.I0 = std::min(patch.I0, i);
            patch.I1 = i + 1;
          }
        }
        for (int j = 0; j < ony; ++j)
        {
          if (cellOf(j + oj, nyWhole, ly) == b)
          {
            patch.J0 = std::min(patch.J0, j);
            patch.J1 = j + 1;
          }
        }
        if (patch.I0 >= patch.I1 || patch.J0 >= patch.J1)
        {
          continue; // (none of the output's cells)
        }
        for (int j = patch.J0; j < patch.J1; ++j)
        {
          for (int i = patch.I0; i < patch.I1; ++i)
          {
            patch.Values.push_back(exact(i + oi, j + oj));
          }
        }
        patchOf[static_cast<size_t>(b * (lx - 1) + a)] = static_cast<int>(patches.size());
        patches.push_back(std::move(patch));
      }
    }
    const double sector = 2.0 * M_PI / D, centre = gammaCentre * M_PI / 180.0;
    // a horizon at fraction t from horizon lo to hi: linear, but the nearer one's where either
    // is an empty direction (-π/2)
    const auto between = [](float lo, float hi, double t) {
      const float empty = -static_cast<float>(M_PI / 2);
      return lo == empty || hi == empty ? (t < 0.5 ? lo : hi)
                                        : static_cast<float>(lo + t * (hi - lo));
    };
    // sheared: S at the metric lattice's nodes (its nodes are the convergences'), relative to
    // the kernel's cells of dx0 x dy0, and with HorizonAngles each sector's turn there, the
    // bearing of S u(ψ_d) less ψ_d (within ±π/2: u · S u > 0), bilinear between the nodes
    // as S is; then a step east and north of the grid in the kernel's metres
    std::vector<double> sroot, sectorTurn;
    if (sheared)
    {
      sroot.resize(metric.size());
      for (size_t k = 0; k + 2 < metric.size(); k += 3)
      {
        ap_horizon_metric_root(metric.data() + k, grid.dx0, grid.dy0, sroot.data() + k);
        for (int d = 0; horizons && d < D; ++d)
        {
          const double psi = d * sector - centre, su = std::sin(psi), cu = std::cos(psi);
          const double x = sroot[k] * su + sroot[k + 1] * cu;
          const double y = sroot[k + 1] * su + sroot[k + 2] * cu;
          sectorTurn.push_back(std::remainder(std::atan2(x, y) - psi, 2.0 * M_PI));
        }
      }
    }
    const double eastStep = grid.dx0 / spacing[0], northStep = grid.dy0 / spacing[1];
    vtkApertureSMPScope(threads, [&]() {
      // (output rows and columns; the output's cell (0, 0) is the whole DEM's (oi, oj))
      vtkSMPTools::For(0, ony, 64, [&](vtkIdType j0, vtkIdType j1) {
        tally.Note();
        std::vector<float> h(horizons ? static_cast<size_t>(D) : 0);
        std::vector<double> at(sheared && horizons ? static_cast<size_t>(D) + 1 : 0);
        for (vtkIdType j = j0; j < j1; ++j)
        {
          const double fb = ly > 1 ? (j + oj) * (ly - 1.0) / (nyWhole - 1.0) : 0.0;
          const int b0 = std::min(static_cast<int>(fb), ly - 1), b1 = std::min(b0 + 1, ly - 1);
          const double tb = fb - b0;
          for (int i = 0; i < onx; ++i)
          {
            const double fa = lx > 1 ? (i + oi) * (lx - 1.0) / (nxWhole - 1.0) : 0.0;
            const int a0 = std::min(static_cast<int>(fa), lx - 1), a1 = std::min(a0 + 1, lx - 1);
            const double ta = fa - a0;
            // (the lattice cell, as cellOf gives it: fa and fb are its arithmetic)
            const int patch =
              patchOf[static_cast<size_t>(std::min(b0, ly - 2) * (lx - 1) + std::min(a0, lx - 2))];
            const GammaPatch* gp = patch < 0 ? nullptr : &patches[static_cast<size_t>(patch)];
            const double g = gp
              ? gp->Values[static_cast<size_t>((j - gp->J0) * (gp->I1 - gp->I0) + i - gp->I0)]
              : (1 - tb) * ((1 - ta) * gamma[b0 * lx + a0] + ta * gamma[b0 * lx + a1]) +
                tb * ((1 - ta) * gamma[b1 * lx + a0] + ta * gamma[b1 * lx + a1]);
            const size_t k = static_cast<size_t>(j) * onx + i;
            double S[3] = { 1.0, 0.0, 1.0 }, rotation = g; // (of the bent normal)
            if (sheared)
            {
              for (int c = 0; c < 3; ++c)
              {
                const auto node = [&](int a, int b) { return sroot[3 * (b * lx + a) + c]; };
                S[c] = (1 - tb) * ((1 - ta) * node(a0, b0) + ta * node(a1, b0)) +
                  tb * ((1 - ta) * node(a0, b1) + ta * node(a1, b1));
              }
              const double wx = -std::sin(g) * eastStep, wy = std::cos(g) * northStep;
              rotation = -std::atan2(S[0] * wx + S[1] * wy, S[1] * wx + S[2] * wy);
            }
            // (a nodata cell's NaN stays as it is: -e sin would make the north one -NaN,
            // other bits than the same cell's in a piece of nodata, filled above)
            if (out.bent_normal && !std::isnan(out.bent_normal[3 * k]))
            {
              float* v = out.bent_normal + 3 * k;
              const double e = v[0], nn = v[1];
              v[0] = static_cast<float>(e * std::cos(rotation) + nn * std::sin(rotation));
              v[1] = static_cast<float>(-e * std::sin(rotation) + nn * std::cos(rotation));
            }
            if (horizons && sheared)
            {
              // each sector's ground azimuth in sectors from north, at[d] = d + its offset
              // from φ_d: the sector's turn, and the rotation less γ(centre) (so at[] rises: S
              // keeps the orientation); at[D] = at[0] + D
              float* v = horizons + k * D;
              const double* t00 = sectorTurn.data() + static_cast<size_t>(b0 * lx + a0) * D;
              const double* t10 = sectorTurn.data() + static_cast<size_t>(b0 * lx + a1) * D;
              const double* t01 = sectorTurn.data() + static_cast<size_t>(b1 * lx + a0) * D;
              const double* t11 = sectorTurn.data() + static_cast<size_t>(b1 * lx + a1) * D;
              const double w00 = (1 - ta) * (1 - tb), w10 = ta * (1 - tb), w01 = (1 - ta) * tb,
                           w11 = ta * tb, common = std::remainder(rotation - centre, 2.0 * M_PI);
              for (int d = 0; d < D; ++d)
              {
                at[d] = d +
                  (w00 * t00[d] + w10 * t10[d] + w01 * t01[d] + w11 * t11[d] + common) / sector;
              }
              at[D] = at[0] + D;
              std::copy(v, v + D, h.begin());
              int seg = 0;
              for (int d = 0; d < D; ++d)
              {
                // φ_d, as a place in [at[0], at[0] + D), lies in at[seg], at[seg + 1]
                const double x = d - D * std::floor((d - at[0]) / D);
                while (seg > 0 && at[seg] > x)
                {
                  --seg;
                }
                while (seg < D - 1 && at[seg + 1] <= x)
                {
                  ++seg;
                }
                v[d] = between(h[seg], h[(seg + 1) % D], (x - at[seg]) / (at[seg + 1] - at[seg]));
              }
            }
            else if (horizons)
            {
              // true azimuth φ_d lies (γ(centre) − γ) / sector sectors from sector d
              float* v = horizons + k * D;
              const double shift = (centre - g) / sector;
              const double fl = std::floor(shift), t = shift - fl;
              const int s0 = static_cast<int>(((static_cast<long>(fl) % D) + D) % D);
              if (t == 0.0 && s0 == 0)
              {
                continue;
              }
              std::copy(v, v + D, h.begin());
              for (int d = 0; d < D; ++d)
              {
                v[d] = between(h[(d + s0) % D], h[(d + s0 + 1) % D], t);
              }
            }
          }
        }
      });
    });
    this->NumberOfThreadsUsed = std::min(tally.Count(), threads.MaxNumberOfThreads);
  }
  this->UpdateProgress((D + 0.9) / parts);
  if (this->GetAbortExecute())
  {
    return 0;
  }

  // 6. Units for files (AnglesInDegrees, FloatEdgeTruncated): elementwise.
  float* edgeFloat = this->FloatEdgeTruncated ? fptr(6) : nullptr;
  if (this->AnglesInDegrees || edgeFloat)
  {
    const double toDegrees = 180.0 / M_PI; // (in double: the float nearest the product)
    float* const angles[3] = { out.aperture_radius, out.positive_openness, out.horizon_angles };
    const size_t components[3] = { 1, 1, static_cast<size_t>(D) };
    const bool degrees = this->AnglesInDegrees;
    vtkApertureSMPScope(threads, [&]() {
      vtkSMPTools::For(0, static_cast<vtkIdType>(outN), 4096, [&](vtkIdType k0, vtkIdType k1) {
        for (int a = 0; a < 3; ++a)
        {
          if (!degrees || !angles[a])
          {
            continue;
          }
          for (size_t k = k0 * components[a]; k < k1 * components[a]; ++k)
          {
            angles[a][k] = static_cast<float>(angles[a][k] * toDegrees);
          }
        }
        for (vtkIdType k = k0; edgeFloat && k < k1; ++k)
        {
          // (the cell's elevation: output cell k in the input's grid)
          const size_t zk = (static_cast<size_t>(k / onx) + params.region_j0) * nx +
            static_cast<size_t>(k % onx) + params.region_i0 - static_cast<size_t>(wrap);
          edgeFloat[k] = std::isnan(z[zk])
            ? std::numeric_limits<float>::quiet_NaN()
            : static_cast<float>(edgeBytes[static_cast<size_t>(k)]);
        }
      });
    });
  }

  return attach();
}

//------------------------------------------------------------------------------
void vtkApertureSkyVisibility::SetElevationArrayName(const char* name)
{
  if (vtkApertureDropElevationSelection(this, this->ArraySelectionMade))
  {
    this->Modified();
  }
  vtkSetStringBodyMacro(ElevationArrayName, name);
}

//------------------------------------------------------------------------------
void vtkApertureSkyVisibility::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfDirections: " << this->NumberOfDirections << "\n";
  os << indent << "MaximumDistance: " << this->MaximumDistance << "\n";
  os << indent << "EarthCurvature: " << this->EarthCurvature << "\n";
  os << indent << "RefractionCoefficient: " << this->RefractionCoefficient << "\n";
  os << indent << "NearField: " << this->NearField << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "NumberOfThreadsUsed: " << this->NumberOfThreadsUsed << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << "\n";
  os << indent << "ComputeVisibleSolidAngle: " << this->ComputeVisibleSolidAngle << "\n";
  os << indent << "ComputeApertureRadius: " << this->ComputeApertureRadius << "\n";
  os << indent << "ComputeBentNormal: " << this->ComputeBentNormal << "\n";
  os << indent << "ComputeSkyViewFactor: " << this->ComputeSkyViewFactor << "\n";
  os << indent << "ComputeDiffuseSkyFactor: " << this->ComputeDiffuseSkyFactor << "\n";
  os << indent << "ComputePositiveOpenness: " << this->ComputePositiveOpenness << "\n";
  os << indent << "ComputeEdgeTruncated: " << this->ComputeEdgeTruncated << "\n";
  os << indent << "ComputeHorizonAngles: " << this->ComputeHorizonAngles << "\n";
  os << indent << "AnglesInDegrees: " << this->AnglesInDegrees << "\n";
  os << indent << "FloatEdgeTruncated: " << this->FloatEdgeTruncated << "\n";
  os << indent << "ElevationArrayName: "
     << (this->ElevationArrayName ? this->ElevationArrayName : "(none)") << "\n";
  os << indent << "InputAllNodata: " << this->InputAllNodata << "\n";
}
