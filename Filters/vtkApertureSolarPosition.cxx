// SPDX-License-Identifier: BSD-3-Clause
#include "vtkApertureSolarPosition.h"

#include "vtkApertureElevation.h"
#include "vtkApertureGeoreference.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include "ap_sky.h"
#include "ap_sun.h"
#include "ap_time.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cmath>
#include <cstring>
#include <limits>
#include <locale>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkApertureSolarPosition);

namespace
{
const double kDeg = 3.14159265358979323846 / 180.0;
const double kNaN = std::numeric_limits<double>::quiet_NaN();
// (the time is NaN until one is set, or after SetUnixTime(NaN))
const char* const kNoTime = "no time is set (it is NaN): call SetTime, or SetUnixTime with a "
                            "number of seconds";

// (seconds beyond +-2^62, NaN among them, go to +-2^62, far past the years any consumer takes:
// converting a double beyond int64_t's range is undefined behaviour)
ap_instant ToInstant(double seconds)
{
  const double limit = 4611686018427387904.0; // 2^62
  ap_instant t;
  const double whole = std::floor(seconds);
  if (!(std::fabs(whole) <= limit))
  {
    t.unix_seconds = static_cast<int64_t>(whole > 0.0 ? limit : -limit);
    t.fraction = 0.0;
    return t;
  }
  t.unix_seconds = static_cast<int64_t>(whole);
  t.fraction = seconds - whole;
  return t;
}

// What is wrong with a date of numbers (YYYY-MM-DD, the year with up to 6 digits and a sign)
// that names no day of the calendar: "February 2023 has 28 days", "there is no month 13";
// "" for any other text, and for text that would not parse with its day and month 01 (so that
// a fixed day does not meet another error).
std::string NoSuchDay(const std::string& text)
{
  static const char* const months[] = { "January", "February", "March", "April", "May", "June",
    "July", "August", "September", "October", "November", "December" };
  size_t k = text[0] == '+' || text[0] == '-' ? 1 : 0;
  const size_t digits = k;
  while (k < text.size() && k - digits < 6 && std::isdigit(static_cast<unsigned char>(text[k])))
  {
    ++k;
  }
  if (k - digits < 4 || text.size() < k + 6 || text[k] != '-' || text[k + 3] != '-' ||
    !std::isdigit(static_cast<unsigned char>(text[k + 1])) ||
    !std::isdigit(static_cast<unsigned char>(text[k + 2])) ||
    !std::isdigit(static_cast<unsigned char>(text[k + 4])) ||
    !std::isdigit(static_cast<unsigned char>(text[k + 5])))
  {
    return std::string();
  }
  std::string firstDay = text;
  firstDay.replace(k + 1, 2, "01");
  firstDay.replace(k + 4, 2, "01");
  ap_parsed_time parsed;
  if (ap_time_parse_iso8601(firstDay.c_str(), &parsed) != AP_OK)
  {
    return std::string();
  }
  const long long year = std::stoll(text.substr(0, k));
  const int month = std::stoi(text.substr(k + 1, 2)), day = std::stoi(text.substr(k + 4, 2));
  if (month < 1 || month > 12)
  {
    return "there is no month " + text.substr(k + 1, 2) + " (01 to 12)";
  }
  const int last = ap_time_days_in_month(year, month);
  if (day < 1 || day > last)
  {
    return std::string(months[month - 1]) + " " + std::to_string(year) + " has " +
      std::to_string(last) + " days";
  }
  return std::string();
}

double FromInstant(const ap_instant& t)
{
  return static_cast<double>(t.unix_seconds) + t.fraction;
}

/** ISO 8601 UTC with `digits` fraction digits (rounded; 0: to the second), or "" for NaN. */
std::string FormatUTC(double seconds, int digits = 0)
{
  char buf[64];
  if (!std::isfinite(seconds) ||
    ap_instant_format_iso8601(ToInstant(seconds), digits, buf, sizeof(buf)) != AP_OK)
  {
    return std::string();
  }
  return buf;
}

/** The fraction digits that write an instant as it was given: 0, 3 or 6, the fewest that hold
 *  it within half a microsecond, or within two of the double's steps where those are longer
 *  and six digits are not written; at most the digits a step resolves (6 within 2^32 s of
 *  1970, 1833-11-24 to 2106-02-07, then 3: a double of 1e11 s has steps of 15 us):
 *  "12:00:00.5" is written 12:00:00.500, and not rounded to a second it is not. */
int FractionDigits(double seconds)
{
  if (!std::isfinite(seconds))
  {
    return 0;
  }
  const double fraction = seconds - std::floor(seconds);
  const double step = std::nextafter(std::fabs(seconds), HUGE_VAL) - std::fabs(seconds);
  const int most = step <= 5e-7 ? 6 : step <= 5e-4 ? 3 : 0;
  // (two steps beside six digits, up to 0.95 us from 2038 on, took .000001 for a whole second)
  const double tolerance = most == 6 ? 5e-7 : std::max(5e-7, 2.0 * step);
  for (int digits = 0; digits < most; digits += 3)
  {
    const double scale = digits == 0 ? 1.0 : 1e3;
    if (std::fabs(fraction - std::round(fraction * scale) / scale) <= tolerance)
    {
      return digits;
    }
  }
  return most;
}

/** Degrees reduced to [0, 360): a tiny negative angle, which adding 360 rounds to 360, is 0,
 *  and so is -0 (ComputeForDirection(-1e-17, e) gave 360, (-0.0, e) -0, until 2026-12-07). */
double Wrap360(double degrees)
{
  double r = std::fmod(degrees, 360.0) + 0.0;
  r = r < 0.0 ? r + 360.0 : r;
  return r < 360.0 ? r : 0.0;
}

/** An instant as ISO 8601 local time at `offset` (seconds east) with `digits` fraction digits,
 *  or "" for NaN and a local year outside the range. */
std::string FormatLocal(double seconds, int32_t offset, int digits = 0)
{
  char buf[64];
  if (!std::isfinite(seconds) ||
    ap_instant_format_iso8601_local(ToInstant(seconds), offset, digits, buf, sizeof(buf)) !=
      AP_OK)
  {
    return std::string();
  }
  return buf;
}

/** An instant as ISO 8601 UTC with its fraction of a second (FractionDigits), or "". */
std::string FormatInstant(double seconds)
{
  return FormatUTC(seconds, FractionDigits(seconds));
}

/** A number as %g gives it, so that 1e20 reads as 1e+20 and not as twenty digits (with a '.'
 * in any locale). */
std::string Number(double value)
{
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << value; // (%g: precision 6, neither fixed nor scientific)
  return s.str();
}

/** An instant for a message: ISO 8601 UTC, or the year when the formatter's range ends. */
std::string TimeText(double seconds)
{
  const std::string iso = FormatUTC(seconds);
  const double days = std::floor(seconds / 86400.0);
  if (!iso.empty() || !(std::fabs(days) < 1e15))
  {
    return iso.empty() ? Number(seconds) + " s after 1970" : iso;
  }
  int64_t year;
  int month, day;
  ap_time_civil_from_days(static_cast<int64_t>(days), &year, &month, &day);
  return "in the year " + std::to_string(year);
}

/** Which of the atmosphere and time-scale parameters ap_sun_params_validate refused, with its
 *  range as ap_sun_params_invalid gives it. */
std::string ParameterProblem(const ap_sun_params& p)
{
  double lo = 0.0, hi = 0.0;
  const char* field = ap_sun_params_invalid(&p, &lo, &hi);
  const struct
  {
    const char *field, *label;
    double value;
    const char* unit;
  } texts[] = { { "pressure", "the pressure", p.pressure, "hPa" },
    { "temperature", "the temperature", p.temperature, "C" },
    { "delta_t", "delta T", p.delta_t, "s" }, { "delta_ut1", "delta UT1", p.delta_ut1, "s" },
    { "atmos_refract", "the refraction at the horizon", p.atmos_refract, "deg" } };
  for (const auto& t : texts)
  {
    if (field && std::strcmp(field, t.field) == 0)
    {
      return std::string(t.label) + " " + Number(t.value) + " " + t.unit + " is outside " +
        Number(lo) + ".." + Number(hi) + " " + t.unit;
    }
  }
  return std::string("the solar position's parameter ") + (field ? field : "(unknown)") +
    " is outside " + Number(lo) + ".." + Number(hi);
}

/** Local wall-clock text "2026-03-29T02:30" (minutes; seconds when not zero). */
std::string FormatCivil(const ap_civil_time& c)
{
  char buf[64];
  if (c.second != 0 || c.fraction != 0.0)
  {
    std::snprintf(buf, sizeof(buf), "%04d-%02d-%02dT%02d:%02d:%02d", c.year, c.month, c.day,
      c.hour, c.minute, c.second);
    if (c.fraction > 0.0 && c.fraction < 1.0)
    {
      // (the digits as given, up to the parser's 9, not cut: "02:30:00.5" was "02:30:00")
      char digits[16];
      std::snprintf(digits, sizeof(digits), "%.9f", c.fraction);
      std::string text(digits + 1); // (".500000000")
      text.erase(text.find_last_not_of('0') + 1);
      return buf + text;
    }
  }
  else
  {
    std::snprintf(
      buf, sizeof(buf), "%04d-%02d-%02dT%02d:%02d", c.year, c.month, c.day, c.hour, c.minute);
  }
  return buf;
}

/** The clocks' jump at instant `seconds` from offset `before` to `after`: "02:00 to 03:00",
 *  with the dates where the jump crosses one ("2011-12-30T00:00 to 2011-12-31T00:00", Samoa
 *  skipping a day). */
std::string FormatJump(double seconds, int32_t before, int32_t after)
{
  ap_civil_time a, b;
  if (ap_instant_to_civil(ToInstant(seconds + before), &a) != AP_OK ||
    ap_instant_to_civil(ToInstant(seconds + after), &b) != AP_OK)
  {
    return "? to ?";
  }
  if (a.year != b.year || a.month != b.month || a.day != b.day)
  {
    return FormatCivil(a) + " to " + FormatCivil(b);
  }
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%02d:%02d to %02d:%02d", a.hour, a.minute, b.hour, b.minute);
  return buf;
}

std::string FormatOffset(int32_t offset)
{
  char buf[32];
  const int32_t a = offset < 0 ? -offset : offset;
  std::snprintf(buf, sizeof(buf), "%c%02d:%02d", offset < 0 ? '-' : '+', a / 3600, (a / 60) % 60);
  return buf;
}

/** The meridian convergence (degrees) at lon/lat in the DEM's projection: 0 without a DEM
 *  (a place given by latitude and longitude only) and on a local CRS (its grid's +y axis is
 *  north by convention), NaN where the projection fails. */
double ConvergenceAt(vtkApertureGeoreference* geo, double lon, double lat)
{
  return geo && !geo->IsLocal() ? geo->ComputeMeridianConvergence(lon, lat) : 0.0;
}

struct ZoneDeleter
{
  void operator()(ap_tz* tz) const { ap_tz_free(tz); }
};
}

struct vtkApertureSolarPosition::Internals
{
  std::unique_ptr<ap_tz, ZoneDeleter> Zone;
  std::string ZoneName;
  bool HasGivenOffset = false; // SetTime was given an explicit offset
  int32_t GivenOffset = 0;
  vtkSmartPointer<vtkApertureGeoreference> Geo; // the DEM of SetPlaceFromImage
  std::string Error;
  std::string RefusedTime; // why the last SetTime failed, until a time is set

  // Why there is no time (UnixTime is NaN).
  std::string NoTime() const
  {
    return this->RefusedTime.empty() ? std::string(kNoTime)
                                     : "no time is set: SetTime refused the last one (" +
        this->RefusedTime + ")";
  }
  std::string TimeString, LocalTimeString, Sunrise, Transit, Sunset;
  std::string SunriseLocal, TransitLocal, SunsetLocal;
  ap_sun_position_result Sun;
  ap_sky_sunlight Beam;
  // The sky, prepared on first use (PrepareSky) from the parameters and sun direction of the
  // last ComputeLight: its horizontal irradiance is a quadrature (0.23 ms for the Preetham and
  // CIE clear skies, 17 times the position's cost), which a series of positions never needs.
  ap_sky_state Sky;
  ap_sky_params SkyParams;
  double SkySun[3];
  bool SkyReady = false;

  // The last local day's events and what they were computed from: a time series computes
  // them once a day instead of once a row (70 us of a row's 245 with the Preetham sky).
  struct DayEvents
  {
    bool Valid = false;
    ap_sun_params P;
    ap_civil_time Day;
    int32_t Offset;
    double Latitude, Longitude;
    ap_sun_rts_result Rts;

    bool Same(const ap_sun_params& p, const ap_civil_time& day, int32_t offset, double lat,
      double lon) const
    {
      const auto same = [](double a, double b) {
        return a == b || (std::isnan(a) && std::isnan(b));
      };
      return this->Valid && same(this->P.delta_t, p.delta_t) &&
        same(this->P.delta_ut1, p.delta_ut1) && same(this->P.pressure, p.pressure) &&
        same(this->P.temperature, p.temperature) &&
        same(this->P.atmos_refract, p.atmos_refract) && this->P.refraction == p.refraction &&
        this->Day.year == day.year && this->Day.month == day.month && this->Day.day == day.day &&
        this->Offset == offset && this->Latitude == lat && this->Longitude == lon;
    }

    /** Computes and keeps the events of `day`; whether they were computed. */
    bool Compute(const ap_sun_params& p, const ap_civil_time& day, int32_t offset, double lat,
      double lon)
    {
      this->Valid = ap_sun_rise_transit_set(
                      &p, day.year, day.month, day.day, offset / 3600.0, lat, lon, &this->Rts) ==
        AP_OK;
      this->P = p;
      this->Day = day;
      this->Offset = offset;
      this->Latitude = lat;
      this->Longitude = lon;
      return this->Valid;
    }
  } LastDay, LastDayEnd; // (the day at its start's UTC offset, and at its end's)

  ap_sun_params Params(const vtkApertureSolarPosition* self) const
  {
    ap_sun_params p;
    ap_sun_params_init(&p);
    p.pressure = self->Pressure;
    p.temperature = self->Temperature;
    p.refraction = self->Refraction ? 1 : 0;
    p.delta_t = self->DeltaT;
    p.delta_ut1 = self->DeltaUT1;
    return p;
  }

  /** UTC offset (s) that defines the local day of instant t: the zone's at t (the zone is
   *  what the caller named for the local day, whatever offset an instant was written with),
   *  else `fallback` (the offset SetTime was given, else 0, unless the caller knows better:
   *  also where the zone has none for t, an instant beyond the years). */
  int32_t DayOffset(double t, int32_t fallback) const
  {
    ap_tz_info info;
    // (a non-finite instant, or one beyond any zone's years, which ToInstant would take to
    // +-2^62: `fallback`)
    if (this->Zone && std::fabs(t) < 4.6e18 &&
      ap_tz_lookup(this->Zone.get(), ToInstant(t), &info) == AP_OK)
    {
      return info.utc_offset;
    }
    return fallback;
  }
  int32_t DayOffset(double t) const
  {
    return this->DayOffset(t, this->HasGivenOffset ? this->GivenOffset : 0);
  }

  void ClearEvents()
  {
    for (std::string* text :
      { &this->Sunrise, &this->Transit, &this->Sunset, &this->SunriseLocal, &this->TransitLocal,
        &this->SunsetLocal })
    {
      text->clear();
    }
  }
};

//------------------------------------------------------------------------------
vtkApertureSolarPosition::vtkApertureSolarPosition()
  : UnixTime(kNaN)
  , DeltaT(kNaN)
  , Impl(new Internals)
{
  std::fill(std::begin(this->Result), std::end(this->Result), kNaN);
  std::fill(std::begin(this->Events), std::end(this->Events), kNaN);
  std::fill(std::begin(this->Light), std::end(this->Light), kNaN);
}

vtkApertureSolarPosition::~vtkApertureSolarPosition() = default;

//------------------------------------------------------------------------------
bool vtkApertureSolarPosition::SetTime(const char* iso8601)
{
  Internals& d = *this->Impl;
  const std::string text = iso8601 ? iso8601 : "";
  // A refused time leaves none, so that Compute() fails saying why instead of giving the sun
  // of the time before (a script stepping local times across a clock change got the previous
  // step's sun, and success, until 2026-12-07).
  const auto refuse = [this, &d]() {
    vtkErrorMacro(<< d.Error);
    d.RefusedTime = d.Error;
    this->UnixTime = kNaN;
    this->Computed = false;
    this->Modified();
    return false;
  };
  ap_parsed_time parsed;
  ap_status st = ap_time_parse_iso8601(text.c_str(), &parsed);
  if (st != AP_OK)
  {
    // (two forms ISO 8601 has that are not taken here, said as such)
    // (the time of day after the date's separator: a signed year's date is longer)
    const size_t separator = text.find_first_of("Tt ", 1);
    const std::string clock =
      separator == std::string::npos ? std::string() : text.substr(separator + 1);
    const std::string noSuchDay = text.empty() ? std::string() : NoSuchDay(text);
    size_t digits = 0; // (of a fraction of a second: the parser takes up to 9)
    if (clock.size() > 9 && (clock[8] == '.' || clock[8] == ','))
    {
      while (9 + digits < clock.size() &&
        std::isdigit(static_cast<unsigned char>(clock[9 + digits])))
      {
        ++digits;
      }
    }
    d.Error = "cannot read the time '" + text + "': " +
      (st == AP_ERR_OUT_OF_RANGE ? std::string("the year is outside -2000..6000")
          : !noSuchDay.empty() ? noSuchDay
          : clock.compare(0, 3, "24:") == 0
          ? std::string("24:00 is not taken: write 00:00 of the next day")
          : clock.size() >= 8 && clock.compare(5, 3, ":60") == 0
          ? std::string("a leap second (:60) is not taken: times here are UTC without leap "
                        "seconds (POSIX time); write :59, or :00 of the next minute")
          : digits > 9 ? "a second's fraction of " + std::to_string(digits) +
            " digits: at most 9 (nanoseconds) are taken"
          : std::string("not a valid ISO 8601 date and time (such as 2026-06-21T14:00+02:00 or "
                        "2026-06-21T12:00Z, or a local time with a time zone)"));
    return refuse();
  }
  if (!parsed.has_offset && !d.Zone)
  {
    d.Error = "the time '" + text +
      "' has no UTC offset: add one (Z, +02:00) or set a time zone (e.g. Europe/Zurich)";
    return refuse();
  }
  ap_instant instant;
  ap_tz_local_result detail;
  st = ap_parsed_time_to_instant(
    &parsed, d.Zone.get(), AP_TZ_CHOOSE_ERROR, AP_TZ_CHOOSE_ERROR, &instant, &detail);
  if (st == AP_ERR_TIME_NONEXISTENT)
  {
    const double change = FromInstant(detail.transition);
    d.Error = "the local time " + FormatCivil(parsed.local) + " does not exist in " +
      d.ZoneName + ": clocks jump from " +
      FormatJump(change, detail.before.utc_offset, detail.after.utc_offset) + " (" +
      FormatUTC(change) +
      "); give an offset (" + FormatOffset(detail.before.utc_offset) + " or " +
      FormatOffset(detail.after.utc_offset) + ") to choose";
    return refuse();
  }
  if (st == AP_ERR_TIME_AMBIGUOUS)
  {
    d.Error = "the local time " + FormatCivil(parsed.local) + " occurs twice in " + d.ZoneName +
      ": " + FormatInstant(FromInstant(detail.earlier)) + " (" +
      FormatOffset(detail.before.utc_offset) + ", " + detail.before.abbreviation + ") and " +
      FormatInstant(FromInstant(detail.later)) + " (" + FormatOffset(detail.after.utc_offset) +
      ", " + detail.after.abbreviation + "); give the offset to choose";
    return refuse();
  }
  if (st != AP_OK)
  {
    // (a local time within the years whose instant is not: its offset takes it past an end)
    d.Error = "cannot convert the time '" + text + "': " +
      (st == AP_ERR_OUT_OF_RANGE ? std::string("in UTC the year is outside -2000..6000")
                                 : std::string(ap_status_string(st)));
    return refuse();
  }
  d.HasGivenOffset = parsed.has_offset != 0;
  d.GivenOffset = parsed.utc_offset;
  this->UnixTime = FromInstant(instant);
  this->Computed = false;
  d.Error.clear();
  d.RefusedTime.clear();
  this->Modified();
  return true;
}

void vtkApertureSolarPosition::SetUnixTime(double seconds)
{
  // (the offset SetTime was given stays the clock of the local day: a series of instants
  // stepped from one written with +09:00 keeps its days at +09:00)
  this->Impl->RefusedTime.clear();
  if (this->UnixTime != seconds)
  {
    this->UnixTime = seconds;
    this->Computed = false;
    this->Modified();
  }
}

const char* vtkApertureSolarPosition::GetTimeString()
{
  this->Impl->TimeString = FormatInstant(this->UnixTime);
  return this->Impl->TimeString.c_str();
}

const char* vtkApertureSolarPosition::GetLocalTimeString()
{
  const double t = this->UnixTime;
  this->Impl->LocalTimeString = FormatLocal(t, this->Impl->DayOffset(t), FractionDigits(t));
  return this->Impl->LocalTimeString.c_str();
}

//------------------------------------------------------------------------------
bool vtkApertureSolarPosition::SetTimeZone(const char* name)
{
  Internals& d = *this->Impl;
  if (!name || !*name)
  {
    d.Zone.reset();
    d.ZoneName.clear();
    d.Error.clear(); // (a success, as the header says)
    this->Computed = false;
    this->Modified();
    return true;
  }
  ap_tz* zone = nullptr;
  const ap_status st = ap_tz_load(name, nullptr, &zone);
  if (st != AP_OK)
  {
    d.Error = std::string("time zone '") + name + "': " +
      (st == AP_ERR_NOT_FOUND
          ? std::string("unknown (an IANA name such as Europe/Zurich, America/New_York or UTC; "
                        "the zone files come from the tzdata package)")
          : st == AP_ERR_BAD_FILE && std::strncmp(name, "right/", 6) == 0
          ? "a zone of tzdata's right/ files, whose clocks count leap seconds: times here are "
            "UTC without them (POSIX time), as in the zone '" + std::string(name + 6) + "'"
          : std::string(ap_status_string(st)));
    vtkErrorMacro(<< d.Error);
    return false;
  }
  d.Zone.reset(zone);
  d.ZoneName = name;
  d.Error.clear();
  this->Computed = false; // (the local day's events are the next Compute()'s)
  this->Modified();
  return true;
}

const char* vtkApertureSolarPosition::GetTimeZone()
{
  return this->Impl->ZoneName.c_str();
}

const char* vtkApertureSolarPosition::GetErrorMessage()
{
  return this->Impl->Error.c_str();
}

//------------------------------------------------------------------------------
bool vtkApertureSolarPosition::SetPlaceFromImage(vtkImageData* dem)
{
  Internals& d = *this->Impl;
  this->Computed = false;
  this->Modified();
  if (!dem)
  {
    d.Geo = nullptr;
    this->Convergence = 0.0;
    return true;
  }
  // (an image made by hand whose geometry was never set is placed by it: at latitude 0, or
  // beyond a pole, named by the warning)
  vtkApertureGeoreference::WarnOfDefaultGeometry(this, dem);
  vtkNew<vtkApertureGeoreference> geo;
  // (a site grid in a local CRS has no place on the Earth: no latitude and longitude)
  double lonlat[2] = { kNaN, kNaN };
  if (!geo->SetFromImage(dem) || (!geo->IsLocal() && !geo->GetCentreLonLat(lonlat)))
  {
    // (the place is forgotten: a caller that does not check would have computed the sun of
    // the place set before, with no error)
    d.Geo = nullptr;
    this->Convergence = 0.0;
    this->Latitude = this->Longitude = kNaN;
    this->Height = 0.0; // (the last DEM's would have set ComputeForDirection's light)
    d.Error = std::string("the DEM has no usable georeference: ") + geo->GetErrorMessage();
    vtkErrorMacro(<< d.Error);
    return false;
  }
  // Height: the DEM at its centre, else the nearest valid cell (by grid distance), else 0.
  double height = 0.0;
  int dims[3];
  dem->GetDimensions(dims);
  std::string missing; // (no elevations: the height is 0)
  vtkDataArray* z = vtkApertureElevationArray(dem->GetPointData(), "Elevation", &missing);
  if (z && z->GetNumberOfTuples() == static_cast<vtkIdType>(dims[0]) * dims[1])
  {
    const double ic = 0.5 * (dims[0] - 1), jc = 0.5 * (dims[1] - 1);
    // The cell nearest the centre (the first of the tied ones in scan order) is usually valid:
    // read it alone, and scan the grid only when it is nodata.
    const double centre =
      z->GetComponent(static_cast<vtkIdType>(dims[1] - 1) / 2 * dims[0] + (dims[0] - 1) / 2, 0);
    double best = std::isfinite(centre) ? 0.0 : std::numeric_limits<double>::infinity();
    height = std::isfinite(centre) ? centre : 0.0;
    for (int j = 0; best > 0.0 && j < dims[1]; ++j)
    {
      for (int i = 0; i < dims[0]; ++i)
      {
        const double r2 = (i - ic) * (i - ic) + (j - jc) * (j - jc);
        if (r2 < best)
        {
          const double v = z->GetComponent(static_cast<vtkIdType>(j) * dims[0] + i, 0);
          if (std::isfinite(v))
          {
            best = r2;
            height = v;
          }
        }
      }
    }
  }
  d.Geo = geo;
  // (into [-180, 180]: a lat/lon grid may run 0..360, or on past 180 across the antimeridian)
  this->Longitude = std::remainder(lonlat[0], 360.0);
  this->Latitude = lonlat[1];
  this->Height = height;
  // (the new DEM's at once: the last one's stayed until a Compute succeeded, so that a local
  // grid, on which Compute fails for want of a place, kept a UTM DEM's)
  this->Convergence = ConvergenceAt(geo, this->Longitude, this->Latitude);
  d.Error.clear();
  return true;
}

//------------------------------------------------------------------------------
void vtkApertureSolarPosition::ClearResults()
{
  this->Computed = false;
  std::fill(std::begin(this->Result), std::end(this->Result), kNaN);
  std::fill(std::begin(this->Events), std::end(this->Events), kNaN);
  std::fill(std::begin(this->Light), std::end(this->Light), kNaN);
  this->DayKind = -1;
  this->Impl->ClearEvents();
}

//------------------------------------------------------------------------------
bool vtkApertureSolarPosition::Compute()
{
  Internals& d = *this->Impl;
  this->ClearResults();

  std::string problem;
  if (d.Geo && d.Geo->IsLocal() && (std::isnan(this->Latitude) || std::isnan(this->Longitude)))
  {
    problem = "the DEM is in a local CRS (a site grid, no place on the Earth), so the sun has "
              "no position for a time there: set the site's Latitude and Longitude, or give "
              "the sun's direction (ComputeForDirection)";
  }
  else if (!(std::fabs(this->Latitude) <= 90.0))
  {
    problem = "the latitude must be within -90..90 degrees";
  }
  else if (!(std::fabs(this->Longitude) <= 180.0))
  {
    problem = "the longitude must be within -180..180 degrees";
  }
  else if (std::isnan(this->UnixTime))
  {
    problem = d.NoTime();
  }
  else if (!std::isfinite(this->UnixTime))
  {
    problem = "the time is not set to a finite instant";
  }
  const ap_sun_params p = d.Params(this);
  if (problem.empty() && ap_sun_params_validate(&p) != AP_OK)
  {
    problem = ParameterProblem(p);
  }
  ap_sun_position_result& r = d.Sun;
  if (problem.empty())
  {
    const ap_status st =
      ap_sun_position(&p, this->UnixTime, this->Latitude, this->Longitude, this->Height, &r);
    if (st != AP_OK)
    {
      problem = !(this->Height >= -6.5e6 && this->Height <= 1e8)
        ? "the height " + Number(this->Height) + " m is outside -6500..100000 km"
        : "the time " + TimeText(this->UnixTime) +
          " is outside the years the algorithm covers (-2000..6000)";
    }
  }
  if (!problem.empty())
  {
    d.Error = problem;
    vtkErrorMacro(<< d.Error);
    return false;
  }
  const double values[11] = { r.azimuth, r.elevation, r.zenith, r.elevation_true, r.zenith_true,
    r.angular_radius, r.topo_declination, r.topo_hour_angle, r.distance, r.equation_of_time,
    r.delta_t };
  std::copy(values, values + 11, this->Result);

  // The local day's events: from its midnight to the next, at the UTC offsets in force then
  // (23 or 25 hours on a day the clocks change). The kernel's day is 24 hours at one offset:
  // on such a day it runs at the offset of each end, and the events within the day are kept
  // (at one offset the day would end an hour early or late, and its events could be another
  // day's and depend on the hour asked about).
  // (an end of the day beyond the years, which the zone cannot place, keeps the instant's
  // offset: at offset 0 a day west of UTC ended hours early and lost its sunset until
  // 2026-12-07; its events beyond the years then void the day, below)
  const int32_t offset = d.DayOffset(this->UnixTime);
  const double localStart = std::floor((this->UnixTime + offset) / 86400.0) * 86400.0;
  const auto midnight = [&d, offset](double local) {
    // (the instant of local time `local`; twice, for an offset that changes across it)
    double t = local - offset;
    t = local - d.DayOffset(t, offset);
    return local - d.DayOffset(t, offset);
  };
  const double start = midnight(localStart);
  const double end = midnight(localStart + 86400.0);
  const int32_t startOffset = static_cast<int32_t>(localStart - start);
  const int32_t endOffset = static_cast<int32_t>(localStart + 86400.0 - end);
  ap_civil_time day;
  bool computed = ap_instant_to_civil(ToInstant(localStart), &day) == AP_OK &&
    (d.LastDay.Same(p, day, startOffset, this->Latitude, this->Longitude) ||
      d.LastDay.Compute(p, day, startOffset, this->Latitude, this->Longitude));
  ap_sun_day_kind kind = AP_SUN_DAY_NORMAL;
  if (computed && endOffset == startOffset)
  {
    const ap_sun_rts_result& rts = d.LastDay.Rts;
    this->Events[0] = rts.sunrise;
    this->Events[1] = rts.transit;
    this->Events[2] = rts.sunset;
    kind = rts.kind;
  }
  else if (computed)
  {
    computed = d.LastDayEnd.Same(p, day, endOffset, this->Latitude, this->Longitude) ||
      d.LastDayEnd.Compute(p, day, endOffset, this->Latitude, this->Longitude);
    if (computed)
    {
      const ap_sun_rts_result& a = d.LastDay.Rts;
      const ap_sun_rts_result& b = d.LastDayEnd.Rts;
      const auto within = [start, end](double t) { return t >= start && t < end; };
      const auto pick = [&within](double x, double y) {
        return within(x) ? x : within(y) ? y : kNaN;
      };
      this->Events[0] = pick(a.sunrise, b.sunrise);
      this->Events[1] = pick(a.transit, b.transit);
      this->Events[2] = pick(a.sunset, b.sunset);
      kind = a.kind == b.kind ? a.kind
        : !std::isnan(this->Events[0]) || !std::isnan(this->Events[2]) ? AP_SUN_DAY_NORMAL
                                                                          : a.kind;
    }
  }
  if (computed)
  {
    this->DayKind = kind == AP_SUN_DAY_POLAR_DAY ? 1 : kind == AP_SUN_DAY_POLAR_NIGHT ? 2 : 0;
  }
  // (to the second; the local ones each on the clock of its own instant, rounded alike)
  std::string* utc[] = { &d.Sunrise, &d.Transit, &d.Sunset };
  std::string* local[] = { &d.SunriseLocal, &d.TransitLocal, &d.SunsetLocal };
  bool unwritten = false; // (an event the UTC form cannot write)
  for (int k = 0; k < 3; ++k)
  {
    *utc[k] = FormatUTC(this->Events[k]);
    *local[k] = FormatLocal(this->Events[k], d.DayOffset(this->Events[k]));
    unwritten = unwritten || (!std::isnan(this->Events[k]) && utc[k]->empty());
  }
  if (!computed || unwritten)
  {
    // (a local day at the edge of the years, whose events lie partly beyond them: no events
    // rather than some of them, which would read as a day on which the sun only sets)
    std::fill(std::begin(this->Events), std::end(this->Events), kNaN);
    this->DayKind = -1;
    d.ClearEvents();
  }

  this->Convergence = ConvergenceAt(d.Geo, this->Longitude, this->Latitude);
  if (!std::isfinite(this->Convergence))
  {
    d.Error = std::string("meridian convergence at the DEM centre: ") + d.Geo->GetErrorMessage();
    vtkErrorMacro(<< d.Error);
    this->ClearResults(); // (a failed Compute leaves no position behind: all of it or none)
    return false;
  }
  // The light: the beam for the apparent zenith, and the sky for the sun's direction.
  if (!this->ComputeLight(r.distance))
  {
    this->ClearResults();
    return false;
  }
  d.Error.clear();
  this->Computed = true;
  return true;
}

//------------------------------------------------------------------------------
bool vtkApertureSolarPosition::ComputeLight(double distance)
{
  Internals& d = *this->Impl;
  ap_sky_params sp;
  ap_sky_params_init(&sp);
  sp.model = static_cast<ap_sky_model>(this->SkyModel);
  sp.turbidity = this->Turbidity;
  sp.linke_turbidity = this->LinkeTurbidity;
  sp.earth_sun_distance = distance;
  sp.site_height = this->Height;
  sp.diffuse_horizontal = this->DiffuseHorizontalIrradiance;
  double sunDir[3];
  const double a = this->GetAzimuth() * kDeg, e = this->GetElevation() * kDeg;
  sunDir[0] = std::cos(e) * std::sin(a);
  sunDir[1] = std::cos(e) * std::cos(a);
  sunDir[2] = std::sin(e);
  d.SkyReady = false;
  double lo = 0.0, hi = 0.0;
  const char* field = ap_sky_params_invalid(&sp, &lo, &hi);
  const ap_status st = field ? AP_ERR_INVALID_ARGUMENT
                             : ap_sky_sunlight_compute(&sp, this->GetZenith() * kDeg, &d.Beam);
  if (st != AP_OK)
  {
    // (the fields these properties reach, with the kernel's ranges)
    const std::string name = field ? field : "";
    const std::string range = Number(lo) + ".." + Number(hi);
    std::ostringstream msg;
    msg << "the light: ";
    if (name == "turbidity")
    {
      msg << "Turbidity must be within " << range << ", not " << this->Turbidity;
    }
    else if (name == "linke_turbidity")
    {
      msg << "LinkeTurbidity must be within " << range << ", not " << this->LinkeTurbidity;
    }
    else if (name == "site_height")
    {
      msg << "the site's height, " << this->Height << " m";
      if (d.Geo)
      {
        msg << " (the DEM's elevation at its centre: a nodata value the DEM does not declare, "
               "or heights not in metres?)";
      }
      msg << ", is outside " << range << " m";
    }
    else if (name == "diffuse_horizontal")
    {
      msg << "DiffuseHorizontalIrradiance must be finite, not "
          << this->DiffuseHorizontalIrradiance;
    }
    else if (field)
    {
      msg << "the sky's " << name << " is outside " << range;
    }
    else
    {
      msg << "the direct beam at a zenith angle of " << this->GetZenith()
          << " degrees: " << ap_status_string(st);
    }
    d.Error = msg.str();
    vtkErrorMacro(<< d.Error);
    return false;
  }
  this->Light[0] = d.Beam.air_mass;
  this->Light[1] = d.Beam.dni;
  this->Light[2] = kNaN; // (PrepareSky's)
  d.SkyParams = sp;
  std::copy(sunDir, sunDir + 3, d.SkySun);
  return true;
}

//------------------------------------------------------------------------------
bool vtkApertureSolarPosition::PrepareSky()
{
  Internals& d = *this->Impl;
  if (!this->Computed)
  {
    return false;
  }
  if (!d.SkyReady)
  {
    // (the parameters were validated and the direction is a unit vector: it cannot fail)
    if (ap_sky_prepare(&d.SkyParams, d.SkySun, &d.Sky) != AP_OK)
    {
      return false;
    }
    this->Light[2] = d.Sky.horizontal_irradiance;
    d.SkyReady = true;
  }
  return true;
}

double vtkApertureSolarPosition::GetSkyHorizontalIrradiance()
{
  return this->PrepareSky() ? this->Light[2] : kNaN;
}

//------------------------------------------------------------------------------
bool vtkApertureSolarPosition::ComputeForDirection(double azimuth, double elevation)
{
  Internals& d = *this->Impl;
  this->ClearResults();
  if (!std::isfinite(azimuth) || !(std::fabs(elevation) <= 90.0))
  {
    d.Error = "the sun's elevation must be within -90..90 degrees and its azimuth finite";
    vtkErrorMacro(<< d.Error);
    return false;
  }
  this->Result[0] = Wrap360(azimuth);
  this->Result[1] = this->Result[3] = elevation;
  this->Result[2] = this->Result[4] = 90.0 - elevation;
  this->Result[5] = 959.63 / 3600.0; // the disc at 1 AU
  this->Result[8] = 1.0;
  // a sun given by its direction needs no projection: a failing one counts as no convergence
  this->Convergence = ConvergenceAt(d.Geo, this->Longitude, this->Latitude);
  if (!std::isfinite(this->Convergence))
  {
    this->Convergence = 0.0;
  }
  if (!this->ComputeLight(1.0))
  {
    this->ClearResults();
    return false;
  }
  d.Error.clear();
  this->Computed = true;
  return true;
}

void vtkApertureSolarPosition::GetSunColor(double rgb[3])
{
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = this->Computed ? this->Impl->Beam.rgb[c] : kNaN;
  }
}

bool vtkApertureSolarPosition::GetSkyRadiance(const double enu[3], double rgb[3])
{
  if (!this->PrepareSky() || ap_sky_radiance(&this->Impl->Sky, enu, rgb) != AP_OK)
  {
    this->Impl->Error = this->Computed ? "GetSkyRadiance: the direction must be finite and not zero"
                                       : "GetSkyRadiance before a successful Compute()";
    vtkErrorMacro(<< this->Impl->Error);
    return false;
  }
  return true;
}

bool vtkApertureSolarPosition::GetSkyCap(const double axis[3], double radius,
  const double normal[3], double meanRGB[3], double irradianceRGB[3])
{
  if (!this->PrepareSky() ||
    ap_sky_cap(&this->Impl->Sky, axis, radius * kDeg, normal, meanRGB, irradianceRGB) != AP_OK)
  {
    this->Impl->Error = this->Computed
      ? "GetSkyCap: the axis and normal must be finite and not zero, the radius within 0..90"
      : "GetSkyCap before a successful Compute()";
    vtkErrorMacro(<< this->Impl->Error);
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
double vtkApertureSolarPosition::GetIncidence(double slope, double aspect)
{
  double incidence = kNaN;
  if (this->Computed)
  {
    // the position the getters give, Compute()'s or ComputeForDirection()'s (which has no
    // ephemeris: the rest of the result is not filled)
    ap_sun_position_result sun = ap_sun_position_result();
    sun.zenith = this->GetZenith();
    sun.azimuth = this->GetAzimuth();
    ap_sun_incidence(&sun, slope, aspect, &incidence);
  }
  return incidence;
}

int vtkApertureSolarPosition::GetLocalOffset()
{
  return static_cast<int>(this->Impl->DayOffset(this->UnixTime));
}

int vtkApertureSolarPosition::GetLocalOffsetAt(double unixSeconds)
{
  return static_cast<int>(this->Impl->DayOffset(unixSeconds));
}

const char* vtkApertureSolarPosition::GetSunriseString()
{
  return this->Impl->Sunrise.c_str();
}

const char* vtkApertureSolarPosition::GetTransitString()
{
  return this->Impl->Transit.c_str();
}

const char* vtkApertureSolarPosition::GetSunsetString()
{
  return this->Impl->Sunset.c_str();
}

const char* vtkApertureSolarPosition::GetSunriseLocalString()
{
  return this->Impl->SunriseLocal.c_str();
}

const char* vtkApertureSolarPosition::GetTransitLocalString()
{
  return this->Impl->TransitLocal.c_str();
}

const char* vtkApertureSolarPosition::GetSunsetLocalString()
{
  return this->Impl->SunsetLocal.c_str();
}

void vtkApertureSolarPosition::GetDirection(double enu[3])
{
  if (!this->Computed)
  {
    enu[0] = enu[1] = enu[2] = 0.0;
    return;
  }
  const double a = this->GetAzimuth() * kDeg, e = this->GetElevation() * kDeg;
  enu[0] = std::cos(e) * std::sin(a);
  enu[1] = std::cos(e) * std::cos(a);
  enu[2] = std::sin(e);
}

double vtkApertureSolarPosition::GetGridAzimuth()
{
  if (!this->Computed)
  {
    return kNaN;
  }
  return Wrap360(this->GetAzimuth() - this->Convergence);
}

//------------------------------------------------------------------------------
bool vtkApertureSolarPosition::AddSunDirectionArray(vtkImageData* dem, const char* name)
{
  Internals& d = *this->Impl;
  if (!dem || !name || !*name)
  {
    d.Error = "AddSunDirectionArray needs a DEM image and an array name";
    vtkErrorMacro(<< d.Error);
    return false;
  }
  if (std::isnan(this->UnixTime))
  {
    d.Error = d.NoTime();
    vtkErrorMacro(<< d.Error);
    return false;
  }
  vtkDataArray* scalars = dem->GetPointData()->GetScalars();
  if (scalars && scalars->GetName() && std::string(scalars->GetName()) == name)
  {
    // (it replaced the elevations with the directions, without a word)
    d.Error = std::string("'") + name + "' is the DEM's elevation array (its active scalars); " +
      "give the direction array another name";
    vtkErrorMacro(<< d.Error);
    return false;
  }
  vtkAbstractArray* existing = dem->GetPointData()->GetAbstractArray(name);
  if (existing &&
    (existing->GetDataType() != VTK_FLOAT || existing->GetNumberOfComponents() != 3))
  {
    // (an elevation array that is not the active scalars, named for the filters, was replaced
    // just the same); a direction array of an earlier time is replaced, as documented
    const int components = existing->GetNumberOfComponents();
    d.Error = std::string("the DEM has a point array '") + name + "' that is no direction " +
      "array (a " + existing->GetClassName() + " of " + std::to_string(components) +
      (components == 1 ? " component" : " components") + "); give the direction array " +
      "another name";
    vtkErrorMacro(<< d.Error);
    return false;
  }
  vtkApertureGeoreference::WarnOfDefaultGeometry(this, dem);
  vtkNew<vtkApertureGeoreference> geo;
  if (!geo->SetFromImage(dem))
  {
    d.Error = std::string("the DEM has no usable georeference: ") + geo->GetErrorMessage();
    vtkErrorMacro(<< d.Error);
    return false;
  }
  int dims[3];
  dem->GetDimensions(dims);
  const int nx = dims[0], ny = dims[1];
  if (nx < 1 || ny < 1)
  {
    d.Error = "the DEM has no cells";
    vtkErrorMacro(<< d.Error);
    return false;
  }
  double origin[3], spacing[3];
  dem->GetOrigin(origin);
  dem->GetSpacing(spacing);
  int extent[6];
  dem->GetExtent(extent);

  // Exact positions on a lattice of at most 17 x 17 cells (the corners included).
  const int lx = std::min(nx, 17), ly = std::min(ny, 17);
  auto latticeIndex = [](int k, int n, int cells) {
    return n == 1 ? 0.0 : static_cast<double>(k) * (cells - 1) / (n - 1);
  };
  const ap_sun_params p = d.Params(this);
  std::vector<double> node(3 * static_cast<size_t>(lx) * ly);
  for (int b = 0; b < ly; ++b)
  {
    for (int a = 0; a < lx; ++a)
    {
      const double fi = latticeIndex(a, lx, nx), fj = latticeIndex(b, ly, ny);
      const double x = origin[0] + (extent[0] + fi) * spacing[0];
      const double y = origin[1] + (extent[2] + fj) * spacing[1];
      double lonlat[2];
      ap_sun_position_result r;
      double gamma;
      if (!geo->CRSToLonLat(x, y, lonlat) ||
        !std::isfinite(gamma = geo->ComputeMeridianConvergence(lonlat[0], lonlat[1])))
      {
        d.Error = std::string("a DEM point has no geographic coordinates: ") +
          geo->GetErrorMessage();
        vtkErrorMacro(<< d.Error);
        return false;
      }
      const ap_status st =
        ap_sun_position(&p, this->UnixTime, lonlat[1], std::remainder(lonlat[0], 360.0),
          this->Height, &r);
      if (st != AP_OK)
      {
        d.Error = std::string("sun position at a DEM point: ") + ap_status_string(st);
        vtkErrorMacro(<< d.Error);
        return false;
      }
      // (the geometric direction: refraction, which stops below the report's cut-off with a
      // jump of 0.6 degree, is added to each cell's own below)
      const double g = (r.azimuth - gamma) * kDeg, e = r.elevation_true * kDeg;
      double* v = &node[3 * (static_cast<size_t>(b) * lx + a)];
      v[0] = std::cos(e) * std::sin(g);
      v[1] = std::cos(e) * std::cos(g);
      v[2] = std::sin(e);
    }
  }

  vtkNew<vtkFloatArray> out;
  out->SetName(name);
  out->SetNumberOfComponents(3);
  out->SetComponentName(0, "X");
  out->SetComponentName(1, "Y");
  out->SetComponentName(2, "Z");
  out->SetNumberOfTuples(static_cast<vtkIdType>(nx) * ny);
  float* o = out->GetPointer(0);
  for (int j = 0; j < ny; ++j)
  {
    const double tj = ly == 1 ? 0.0 : static_cast<double>(j) * (ly - 1) / std::max(1, ny - 1);
    const int b0 = std::min(static_cast<int>(tj), std::max(0, ly - 2));
    const double wb = ly == 1 ? 0.0 : tj - b0;
    for (int i = 0; i < nx; ++i)
    {
      const double ti = lx == 1 ? 0.0 : static_cast<double>(i) * (lx - 1) / std::max(1, nx - 1);
      const int a0 = std::min(static_cast<int>(ti), std::max(0, lx - 2));
      const double wa = lx == 1 ? 0.0 : ti - a0;
      const int a1 = std::min(a0 + 1, lx - 1), b1 = std::min(b0 + 1, ly - 1);
      double v[3], len = 0.0;
      for (int c = 0; c < 3; ++c)
      {
        const double v00 = node[3 * (static_cast<size_t>(b0) * lx + a0) + c];
        const double v10 = node[3 * (static_cast<size_t>(b0) * lx + a1) + c];
        const double v01 = node[3 * (static_cast<size_t>(b1) * lx + a0) + c];
        const double v11 = node[3 * (static_cast<size_t>(b1) * lx + a1) + c];
        v[c] = (1 - wb) * ((1 - wa) * v00 + wa * v10) + wb * ((1 - wa) * v01 + wa * v11);
        len += v[c] * v[c];
      }
      len = std::sqrt(len);
      const double h = std::hypot(v[0], v[1]);
      const double eTrue = std::atan2(v[2], h) / kDeg;
      const double e = (eTrue + ap_sun_refraction(&p, eTrue)) * kDeg;
      float* t = o + 3 * (static_cast<size_t>(j) * nx + i);
      if (h > 0.0)
      {
        t[0] = static_cast<float>(std::cos(e) * v[0] / h);
        t[1] = static_cast<float>(std::cos(e) * v[1] / h);
        t[2] = static_cast<float>(std::sin(e));
      }
      else
      {
        for (int c = 0; c < 3; ++c)
        {
          t[c] = static_cast<float>(v[c] / len);
        }
      }
    }
  }
  dem->GetPointData()->AddArray(out);
  d.Error.clear();
  return true;
}

//------------------------------------------------------------------------------
bool vtkApertureSolarPosition::ComputeSkyTable(
  vtkFloatArray* table, int azimuths, int elevations, int radii)
{
  Internals& d = *this->Impl;
  if (!table || azimuths < 4 || azimuths > 256 || elevations < 2 || elevations > 256 ||
    radii < 2 || radii > 256 || !this->PrepareSky())
  {
    d.Error = !this->Computed ? "ComputeSkyTable before a successful Compute()"
                              : "ComputeSkyTable needs a table and sizes within 4..256 "
                                "(azimuths), 2..256 (elevations, radii)";
    vtkErrorMacro(<< d.Error);
    return false;
  }
  const double halfPi = 0.5 * 3.14159265358979323846;
  table->SetNumberOfComponents(3);
  table->SetNumberOfTuples(static_cast<vtkIdType>(azimuths) * elevations * radii);
  float* out = table->GetPointer(0);
  for (int k = 0; k < radii; ++k)
  {
    const double r = k * halfPi / (radii - 1);
    for (int j = 0; j < elevations; ++j)
    {
      const double el = j * halfPi / (elevations - 1);
      for (int i = 0; i < azimuths; ++i)
      {
        const double az = (i + 0.5) * 4.0 * halfPi / azimuths;
        const double axis[3] = { std::cos(el) * std::sin(az), std::cos(el) * std::cos(az),
          std::sin(el) };
        // the cap's radiance weighted by the cosine to its axis: ∫cap L (a·ω) dω / (π sin² r),
        // so that an aperture facing its own axis (level open ground, a pit's floor) gets the
        // sky's exact irradiance; the point cap's is the radiance at the axis
        double value[3];
        const double sr = std::sin(r);
        const ap_status st = k == 0
          ? ap_sky_cap(&d.Sky, axis, 0.0, nullptr, value, nullptr)
          : ap_sky_cap(&d.Sky, axis, r, axis, nullptr, value);
        if (st != AP_OK)
        {
          d.Error = "ComputeSkyTable: the sky model failed for a cap";
          vtkErrorMacro(<< d.Error);
          return false;
        }
        const double scale = k == 0 ? 1.0 : 1.0 / (2.0 * halfPi * sr * sr);
        float* v = out + 3 * ((static_cast<size_t>(k) * elevations + j) * azimuths + i);
        for (int c = 0; c < 3; ++c)
        {
          v[c] = static_cast<float>(std::max(0.0, value[c] * scale));
        }
      }
    }
  }
  // (a table refilled at the same size keeps its MTime through SetNumberOfTuples: the
  // lighting mapper uploads it again only when that changes)
  table->Modified();
  return true;
}

//------------------------------------------------------------------------------
bool vtkApertureSolarPosition::ConfigureLight(vtkLight* light)
{
  if (!light || !this->Computed)
  {
    this->Impl->Error = light ? "ConfigureLight before a successful Compute()" : "no light";
    vtkErrorMacro(<< this->Impl->Error);
    return false;
  }
  double dir[3];
  this->GetDirection(dir);
  light->SetLightTypeToSceneLight();
  light->SetPositional(false);
  light->SetFocalPoint(0.0, 0.0, 0.0);
  light->SetPosition(dir);
  light->SetSwitch(this->GetElevation() > -this->GetAngularRadius());
  return true;
}

//------------------------------------------------------------------------------
void vtkApertureSolarPosition::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Time: " << this->GetTimeString() << "\n";
  os << indent << "TimeZone: " << this->Impl->ZoneName << "\n";
  os << indent << "Latitude: " << this->Latitude << "\n";
  os << indent << "Longitude: " << this->Longitude << "\n";
  os << indent << "Height: " << this->Height << "\n";
  os << indent << "Pressure: " << this->Pressure << "\n";
  os << indent << "Temperature: " << this->Temperature << "\n";
  os << indent << "Refraction: " << this->Refraction << "\n";
  os << indent << "DeltaT: " << this->DeltaT << "\n";
  os << indent << "DeltaUT1: " << this->DeltaUT1 << "\n";
  os << indent << "SkyModel: " << this->SkyModel << "\n";
  os << indent << "Turbidity: " << this->Turbidity << "\n";
  os << indent << "LinkeTurbidity: " << this->LinkeTurbidity << "\n";
  os << indent << "DiffuseHorizontalIrradiance: " << this->DiffuseHorizontalIrradiance << "\n";
  if (this->Computed)
  {
    os << indent << "Azimuth: " << this->GetAzimuth() << "\n";
    os << indent << "Elevation: " << this->GetElevation() << "\n";
    os << indent << "DirectNormalIrradiance: " << this->GetDirectNormalIrradiance() << "\n";
  }
}
