// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkApertureSolarPosition
 * @brief   Where the sun is for a time and place (NREL SPA), the day's sunrise, transit and
 *          sunset, the sun's direction in a DEM's own frames, and the light it and the sky give.
 *
 * Set a time (SetTime with an ISO 8601 string, or SetUnixTime), a place (SetLatitude,
 * SetLongitude, SetHeight, or SetPlaceFromImage with a DEM) and optionally the atmosphere, then
 * call Compute(); the results are read with the getters. Compute() returns false on bad input
 * (latitude outside ±90°, longitude outside ±180°, a year outside −2000..6000, pressure or
 * temperature out of range), with the reason in GetErrorMessage() and a vtkErrorMacro.
 *
 * Position: the Solar Position Algorithm of Reda & Andreas (NREL/TP-560-34302, ±0.0003° for
 * the years −2000..6000), implemented in the C core (ap_sun.h). Azimuths are clockwise from
 * true north; elevations and zeniths are apparent (refracted with Pressure and Temperature,
 * SPA's refraction model, which adds none while the sun's centre is more than 0.8333° below
 * the horizon: they step by about 0.6° there) unless named True. ΔT defaults to the Espenak
 * & Meeus (2006) estimate for the date (DeltaT = NaN); give the IERS value for the last
 * 0.00001°.
 *
 * Time: SetTime accepts ISO 8601 with an offset ("2026-06-21T14:00+02:00", "...Z") or a local
 * time without one, which is read in the IANA zone of SetTimeZone ("Europe/Zurich") from the
 * system's tzdata (daylight saving included). A local time skipped by a clock change, or one
 * that occurs twice, is an error naming both readings, never a silent guess.
 *
 * Frames: with a DEM (SetPlaceFromImage), the place is the DEM's centre, where the terrain
 * mesh of vtkApertureTerrainMesh has its East-North-Up frame; GetDirection gives the unit
 * vector to the sun in that frame. For a projected DEM, GetGridAzimuth is the azimuth from the
 * grid's north (its +y axis): azimuth − γ, with γ the meridian convergence at the centre
 * (vtkApertureGeoreference::ComputeMeridianConvergence). Over a large DEM the sun's azimuth and
 * elevation change from place to place: AddSunDirectionArray stores the per-cell direction.
 *
 * Light (ap_sky.h, every model and constant cited there): Compute() also evaluates the direct
 * beam through a clear atmosphere (Kasten & Young air mass at the site's height, ESRA direct
 * normal irradiance with a Linke turbidity, its colour from Preetham's spectral transmittance
 * with the Preetham turbidity, as linear Rec.709 RGB in W/m² whose luminance is the DNI) and
 * prepares a sky (Preetham, CIE clear, CIE overcast or uniform) whose radiance (W/m²/sr, linear
 * Rec.709 RGB) is available in any direction and averaged over a spherical cap, e.g. the
 * aperture of a terrain cell. Below the horizon the beam is zero; no model has twilight. (The
 * sky is prepared when first asked for after a Compute, with that Compute's parameters: its
 * horizontal irradiance is a quadrature, 0.23 ms for the Preetham and CIE clear skies, 17 times
 * the position's cost, which a series of positions alone does not pay.)
 *
 * @sa vtkApertureGeoreference vtkApertureTerrainMesh vtkApertureSkyVisibility
 */
#ifndef vtkApertureSolarPosition_h
#define vtkApertureSolarPosition_h

#include "ApertureFiltersModule.h" // for export macro
#include "vtkObject.h"

#include <memory> // for std::unique_ptr

class vtkFloatArray;
class vtkImageData;
class vtkLight;

class APERTUREFILTERS_EXPORT vtkApertureSolarPosition : public vtkObject
{
public:
  static vtkApertureSolarPosition* New();
  vtkTypeMacro(vtkApertureSolarPosition, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The instant. SetTime parses ISO 8601: "YYYY-MM-DD" (midnight, a local time in TimeZone)
   * or "YYYY-MM-DDTHH:MM[:SS[.fff]]" followed by "Z", "±HH:MM", "±HHMM" or "±HH", or by
   * nothing: a local time in TimeZone (a date alone takes no offset). False for text that
   * does not parse, an impossible date, a year outside −2000..6000, a local time without a
   * TimeZone, or one that a clock change skips or repeats: the time is then unset (NaN), and
   * Compute() fails naming the refusal, never giving the sun of the time before.
   * There is no default time: until one is set, GetUnixTime is NaN and Compute() fails
   * saying so.
   * SetUnixTime sets POSIX seconds (UTC, no leap seconds) directly, keeping the offset the
   * last SetTime was given as the clock of the local day (a series stepped from an instant
   * written with +09:00 keeps its days at +09:00; "Z" sets 0). GetTimeString gives the
   * instant as ISO 8601 UTC ("2026-06-21T12:00:00Z"), with 3 or 6 fraction digits when it has
   * a fraction of a second ("2026-06-21T12:00:00.500Z"; rounded to the microsecond from
   * 1833-11-24 to 2106-02-07, beyond to the millisecond, as far as the double resolves them);
   * GetLocalTimeString the same instant on the clock of GetLocalOffsetAt(GetUnixTime())
   * ("2026-06-21T14:00:00.500+02:00"); both "" for no time (and the local one for a local
   * year outside −2000..6000). The strings returned here and by Get{Sunrise,Transit,
   * Sunset}String are owned by this object and valid until the next call of the same getter
   * or the next Compute(): copy them to keep them.
   */
  bool SetTime(const char* iso8601);
  void SetUnixTime(double seconds);
  double GetUnixTime() const { return this->UnixTime; }
  const char* GetTimeString();
  const char* GetLocalTimeString();
  ///@}

  ///@{
  /**
   * IANA time zone ("Europe/Zurich", "UTC") for local times in SetTime, and for the local day
   * of sunrise and sunset. nullptr or "" clears it (local times are then rejected, and the day
   * is the UTC day, or the day at the offset SetTime was given). False for an unknown zone or
   * a corrupt zone file, keeping the previous zone. Zones are read from $TZDIR, else
   * /usr/share/zoneinfo (Debian package tzdata). Like a new time, a new zone asks for a new
   * Compute() (the local day's events change).
   */
  bool SetTimeZone(const char* name);
  const char* GetTimeZone();
  ///@}

  ///@{
  /** Place: geodetic latitude and longitude (degrees, north and east positive) and height
   *  above the ellipsoid (metres). Defaults 0, 0, 0. */
  vtkSetMacro(Latitude, double);
  vtkGetMacro(Latitude, double);
  vtkSetMacro(Longitude, double);
  vtkGetMacro(Longitude, double);
  vtkSetMacro(Height, double);
  vtkGetMacro(Height, double);
  ///@}

  /**
   * Take the place from a DEM image (as vtkApertureDEMReader produces it): its centre, which is
   * the origin of vtkApertureTerrainMesh's frame, at the height of the DEM there (the nearest
   * valid cell of its point array "Elevation", else of its one-component active scalars; 0 if
   * none); its longitude is taken into [-180, 180] (a lat/lon grid may run 0..360 degrees).
   * Also remembers the DEM's georeference for GetGridAzimuth and
   * GetGridConvergence. False (with the reason) when the image has no CRS, or its centre no
   * geographic coordinates: the place is then forgotten (Latitude and Longitude NaN, Height 0,
   * no DEM), so that Compute() fails rather than use the one set before. A DEM in a local CRS
   * (vtkApertureGeoreference::IsLocal: a site grid, its +y axis north, γ = 0) is taken but has
   * no place on the Earth: Latitude and Longitude become NaN, so Compute() fails saying so
   * until they are set, while ComputeForDirection works. SetLatitude/SetLongitude afterwards
   * do not forget the DEM: call with nullptr. The place is the image's geometry's: an image
   * whose origin and spacing are VTK's defaults while its field data's GeoTransform describes
   * another grid is warned about (vtkApertureGeoreference::GetDefaultGeometryWarning), here
   * and by AddSunDirectionArray.
   */
  bool SetPlaceFromImage(vtkImageData* dem);

  ///@{
  /** Atmosphere for refraction: mean air pressure (hPa, 0..5000, default 1013.25) and
   *  temperature (°C, −100..100, default 15); Refraction off gives geometric
   *  elevations (default on). Values out of range make Compute() fail, naming them.
   *  Sunrise and sunset are where the sun's centre is at −0.8333° geometric (its upper limb
   *  on the horizon through the standard 34′ of refraction), whatever the pressure and
   *  temperature; with Refraction off at −0.26667° (the upper limb on the geometric
   *  horizon), which moves them by minutes and may turn polar day into a day with a sunset.
   *  As SPA defines them, that is the sun seen from the Earth's centre: GetElevationTrue, seen
   *  from the place, is lower by the solar parallax (0.0024°) then, which moves the events by
   *  1-2 s at mid-latitudes, more where the sun meets the horizon at a shallow angle (13 s
   *  at 70° N in late November). */
  vtkSetMacro(Pressure, double);
  vtkGetMacro(Pressure, double);
  vtkSetMacro(Temperature, double);
  vtkGetMacro(Temperature, double);
  vtkSetMacro(Refraction, bool);
  vtkGetMacro(Refraction, bool);
  vtkBooleanMacro(Refraction, bool);
  ///@}

  ///@{
  /** ΔT = TT − UT1 in seconds (|value| <= 100000; default NaN: estimated for the date) and
   *  UT1 − UTC (s, default 0, |value| < 1). Values out of range make Compute() fail. */
  vtkSetMacro(DeltaT, double);
  vtkGetMacro(DeltaT, double);
  vtkSetMacro(DeltaUT1, double);
  vtkGetMacro(DeltaUT1, double);
  ///@}

  ///@{
  /**
   * Atmosphere for the light: sky model (SKY_PREETHAM, default; SKY_CIE_CLEAR; SKY_CIE_OVERCAST;
   * SKY_UNIFORM), Preetham turbidity (2..10, default 3: clear), Linke turbidity for the beam's
   * strength (1..8, default 3), and the sky's horizontal irradiance in W/m² (negative, the
   * default: from the model; Preetham has its own scale, CIE overcast a quarter of the clear
   * day's global irradiance, the others ESRA's diffuse). The direct beam is the clear-sky beam
   * of the Linke turbidity whatever the sky: an overcast day, whose sky then holds all its
   * light, is its sky without the beam (leave the sun's light out).
   */
  enum SkyModels
  {
    SKY_UNIFORM = 0,
    SKY_CIE_OVERCAST = 1,
    SKY_CIE_CLEAR = 2,
    SKY_PREETHAM = 3
  };
  vtkSetClampMacro(SkyModel, int, SKY_UNIFORM, SKY_PREETHAM);
  vtkGetMacro(SkyModel, int);
  void SetSkyModelToPreetham() { this->SetSkyModel(SKY_PREETHAM); }
  void SetSkyModelToCIEClear() { this->SetSkyModel(SKY_CIE_CLEAR); }
  void SetSkyModelToCIEOvercast() { this->SetSkyModel(SKY_CIE_OVERCAST); }
  void SetSkyModelToUniform() { this->SetSkyModel(SKY_UNIFORM); }
  vtkSetMacro(Turbidity, double);
  vtkGetMacro(Turbidity, double);
  vtkSetMacro(LinkeTurbidity, double);
  vtkGetMacro(LinkeTurbidity, double);
  vtkSetMacro(DiffuseHorizontalIrradiance, double);
  vtkGetMacro(DiffuseHorizontalIrradiance, double);
  ///@}

  /** Compute the position, the day's events and the light. False on bad input (see the class
   *  notes; also turbidities out of range, or a height outside -1000..10000 m for the light),
   *  every result then NaN (DayKind -1), as before any Compute. */
  bool Compute();

  /**
   * No time or ephemeris: put the sun at this azimuth (from true north) and elevation (degrees,
   * e.g. for a hillshade-like picture; the elevation is both the apparent and the geometric
   * one: no refraction is added), at 1 AU with its mean disc (0.26656°), and compute the light
   * for it as Compute() does. Time results (sunrise, equation of time, ...) are NaN. False for an
   * elevation outside −90..90 or a non-finite azimuth.
   */
  bool ComputeForDirection(double azimuth, double elevation);

  /** Why the last failing call failed ("" after a success). */
  const char* GetErrorMessage();

  ///@{
  /** Results of Compute(), degrees: azimuth clockwise from true north [0, 360), apparent
   *  (refracted) elevation and zenith, geometric (true) elevation and zenith, the sun disc's
   *  apparent angular radius, declination and local hour angle (topocentric). */
  double GetAzimuth() const { return this->Result[0]; }
  double GetElevation() const { return this->Result[1]; }
  double GetZenith() const { return this->Result[2]; }
  double GetElevationTrue() const { return this->Result[3]; }
  double GetZenithTrue() const { return this->Result[4]; }
  double GetAngularRadius() const { return this->Result[5]; }
  double GetDeclination() const { return this->Result[6]; }
  double GetHourAngle() const { return this->Result[7]; }
  ///@}

  /** Earth–Sun distance (AU), equation of time (minutes: apparent − mean solar time) and the
   *  ΔT used (s). */
  double GetDistance() const { return this->Result[8]; }
  double GetEquationOfTime() const { return this->Result[9]; }
  double GetDeltaTUsed() const { return this->Result[10]; }

  /** Angle of incidence (degrees) of sunlight on a plane of slope `slope` (degrees from
   *  horizontal) facing azimuth `aspect` (degrees clockwise from north), for the sun of the last
   *  Compute() or ComputeForDirection() (its apparent zenith and azimuth). NaN before either,
   *  or for a slope outside 0..180 or a non-finite aspect. */
  double GetIncidence(double slope, double aspect);

  ///@{
  /**
   * Sunrise, transit and sunset of the local day of the instant (the day in TimeZone, else at the
   * offset SetTime was given, else the UTC day), as POSIX seconds and as ISO 8601 UTC strings
   * (ap_sun_rise_transit_set: each within the day, from its midnight to the next, 23 or 25 hours on
   * a day the clocks change). Sunrise and sunset are NaN / "" when the sun does not rise or set
   * that day: GetDayKind() is then 1 (polar day) or 2 (polar night); 0 on a day on which it rises
   * or sets, which next to polar day or night may have only one of the two, as may a day of 23
   * hours (or, on a place far from its zone's meridian, even lack the transit; so does a day
   * between two transits more than 24 hours apart that straddle it, a few days a year where
   * midnight falls within a minute of solar noon). -1, all three NaN, before Compute, after
   * ComputeForDirection, or when the local day lies outside the years -2000..6000 (an instant at
   * its edge).
   */
  double GetSunrise() const { return this->Events[0]; }
  double GetTransit() const { return this->Events[1]; }
  double GetSunset() const { return this->Events[2]; }
  const char* GetSunriseString();
  const char* GetTransitString();
  const char* GetSunsetString();
  int GetDayKind() const { return this->DayKind; }
  ///@}

  ///@{
  /**
   * The same events as ISO 8601 local times to the second, each on the clock of its own
   * instant, GetLocalOffsetAt(event) ("2003-10-17T06:12:43-07:00"; a sunset after a clock
   * change has the new offset); "" where the UTC string is "", and for a local time in a year
   * outside -2000..6000. Owned by this object like the strings above.
   */
  const char* GetSunriseLocalString();
  const char* GetTransitLocalString();
  const char* GetSunsetLocalString();
  ///@}

  /** UTC offset (seconds east) of the local day above: TimeZone's offset at the instant, else
   *  the offset SetTime was given, else 0. */
  int GetLocalOffset();

  /** UTC offset (seconds east) of the clock at another instant (POSIX seconds): TimeZone's
   *  offset then (a sunset after a clock change has the new one), else the offset SetTime was
   *  given, else 0; the same fallback for a non-finite instant. */
  int GetLocalOffsetAt(double unixSeconds);

  /**
   * Unit vector to the sun (refracted) in the East-North-Up frame at the place: with a DEM,
   * the frame of vtkApertureTerrainMesh's output. (0, 0, 0) before a successful Compute.
   */
  void GetDirection(double enu[3]);

  /**
   * Meridian convergence γ at the DEM centre (degrees; 0 for lat/lon DEMs and without a DEM):
   * the angle from true north to grid north, clockwise (positive when grid north lies east of
   * true north, as east of a UTM zone's central meridian in the northern hemisphere).
   */
  double GetGridConvergence() const { return this->Convergence; }

  /** Azimuth from the DEM grid's north (+y axis), clockwise: GetAzimuth() − γ, in [0, 360). */
  double GetGridAzimuth();

  /**
   * Sun direction at every cell of a DEM image, as a 3-component float point array `name`
   * (default "SunDirection") added to `dem`: unit vectors in each cell's grid-aligned local
   * frame (x = the grid's +x axis, y = its +y axis, both horizontal at the cell, z = up), so
   * that sweeps and shading in grid coordinates need no rotation. The place changes across the
   * DEM (azimuth, elevation and γ): the position is computed exactly on a lattice of at most
   * 17 x 17 cells, its geometric direction interpolated bilinearly between them (it changes
   * by a fraction of the sun's angular radius between lattice points, even across a
   * continent), and each cell's refraction added to it (interpolating the refracted direction
   * smeared the refraction's cut-off below the horizon over the lattice's cells: 0.57 degree
   * off along the terminator, a visible sun put below the horizon). Cells
   * below the horizon get their direction too (z < 0). Uses the time (UnixTime), the
   * atmosphere and the Height set here for every cell, not the latitude and longitude (each
   * cell has its own). An array `name` of 3 floats already there (an earlier time's) is
   * replaced. False (GetErrorMessage) when `name` is the DEM's active scalars (its elevations)
   * or another point array (not 3 floats), the DEM has no georeference or only a local one (no
   * place on the Earth), a lattice point has no geographic coordinates, or the sun's position
   * fails there (a time or atmosphere out of range).
   */
  bool AddSunDirectionArray(vtkImageData* dem, const char* name = "SunDirection");

  ///@{
  /**
   * The direct beam after Compute(): relative air mass (infinite below the horizon), direct
   * normal irradiance (W/m², 0 below the horizon) and its colour as linear Rec.709 RGB
   * irradiance normal to the beam (W/m² per channel; luminance = DNI). NaN before a successful
   * Compute() or ComputeForDirection().
   */
  double GetAirMass() const { return this->Light[0]; }
  double GetDirectNormalIrradiance() const { return this->Light[1]; }
  void GetSunColor(double rgb[3]);
  ///@}

  /** The sky's irradiance on an unobstructed horizontal surface (W/m², luminance-weighted);
   *  NaN before Compute. */
  double GetSkyHorizontalIrradiance();

  /**
   * Sky radiance (W/m²/sr, linear Rec.709 RGB) seen in direction `enu` (any length > 0, in the
   * frame of GetDirection); 0 below the horizon. False before Compute or for a zero vector.
   */
  bool GetSkyRadiance(const double enu[3], double rgb[3]);

  /**
   * The sky over the spherical cap of axis `axis` (ENU) and angular radius `radius` (degrees,
   * 0..90): its mean radiance (W/m²/sr, RGB; directions below the horizon count as dark) and
   * the irradiance it sends onto a surface of normal `normal` (W/m², RGB, cosine-weighted).
   * Deterministic quadrature: errors below 2e-4 of the zenith radiance (Preetham sky), below
   * 5e-4 (CIE clear) with the sun above about 15°, up to 3e-3 with it lower (about 0.1% of the
   * value; ap_sky.h gives the measure). False on bad input.
   */
  bool GetSkyCap(const double axis[3], double radius, const double normal[3], double meanRGB[3],
    double irradianceRGB[3]);

  /**
   * Tabulate the sky for vtkApertureLightingMapper's SKY_TABLE mode: the radiance (W/m²/sr, RGB;
   * dark below the horizon) of caps weighted by the cosine to the cap's axis a, that is GetSkyCap's
   * irradiance onto a surface facing a over π sin² r (the radiance at a for r = 0), so that the
   * lighting's L · C(n·a, sin² r) is the sky's irradiance through the cap for a surface that faces
   * its axis (exactly at the table's nodes, such as level open ground: the horizontal irradiance;
   * else as the lookup interpolates), and close to it for others. The axes sample azimuth
   * (`azimuths` cells, centred on (i + ½) 360 / azimuths degrees), elevation (`elevations` nodes
   * from 0 to 90°) and radius (`radii` nodes from 0 to 90°), in the layout and with the
   * interpolation of ap_light_sky_lookup (ap_light.h). `table` gets 3 components and azimuths ×
   * elevations × radii tuples. False before Compute or for sizes outside 4..256, 2..256, 2..256.
   * About 35 µs per cap: 32 × 9 × 9 caps take 90 ms (Preetham sky).
   */
  bool ComputeSkyTable(vtkFloatArray* table, int azimuths = 32, int elevations = 9, int radii = 9);

  /**
   * Point `light` at the sun: a directional (non-positional) scene light coming from
   * GetDirection() in the mesh frame (focal point at the origin, position on the unit sphere),
   * switched off once the sun's whole disc is below the horizon (apparent elevation at or below
   * minus its angular radius). Colour and intensity are left as they are
   * (use the radiometry of ap_sky for physically scaled values). False before Compute.
   */
  bool ConfigureLight(vtkLight* light);

protected:
  vtkApertureSolarPosition();
  ~vtkApertureSolarPosition() override;

  // The sky of the last successful Compute, prepared once; false before one.
  bool PrepareSky();

  double UnixTime; // NaN until SetTime or SetUnixTime
  double Latitude = 0.0;
  double Longitude = 0.0;
  double Height = 0.0;
  double Pressure = 1013.25;
  double Temperature = 15.0;
  bool Refraction = true;
  double DeltaT;
  double DeltaUT1 = 0.0;

  int SkyModel = SKY_PREETHAM;
  double Turbidity = 3.0;
  double LinkeTurbidity = 3.0;
  double DiffuseHorizontalIrradiance = -1.0;

  double Result[11];
  double Light[3];
  double Events[3];
  int DayKind = -1;
  double Convergence = 0.0;
  bool Computed = false;

private:
  vtkApertureSolarPosition(const vtkApertureSolarPosition&) = delete;
  void operator=(const vtkApertureSolarPosition&) = delete;

  bool ComputeLight(double distance);
  void ClearResults();

  struct Internals;
  std::unique_ptr<Internals> Impl;
};

#endif
