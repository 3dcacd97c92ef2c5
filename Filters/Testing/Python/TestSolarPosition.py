# SPDX-License-Identifier: BSD-3-Clause
"""vtkApertureSolarPosition against an independent ephemeris, PyEphem (Debian python3-ephem:
libastro's full VSOP87 theory for the Earth, its own nutation, aberration and parallax), at
places across every latitude band, in both hemispheres, in polar day and night, over the years
1900..2100 and at any time of day.

Tolerance 0.01 deg on the geometric (unrefracted) direction. The two models differ in the
truncation of VSOP87 (SPA keeps the terms of Meeus's tables: a few 0.0001 deg), the nutation
series and the Earth model used for parallax (SPA: the report's 6378.14 km sphere-like
ellipsoid; up to 0.002 deg at most). Both are given the same Delta T (PyEphem's own), so Earth
rotation does not enter; measured, they agree to better than 0.001 deg. Angular radius within
0.001 deg at perihelion and aphelion; sunrise and sunset within 30 s (both use the sun's centre
at -0.8333 deg; SPA's one-step interpolation is good to a few seconds there); the equation of
time within 0.02 min of the one PyEphem's meridian transit implies.
"""
import calendar
import math
import unittest

from vtkmodules.test import Testing

import aperture

try:
    import ephem
except ImportError:  # python3-ephem is in Utilities/debian-packages.txt
    ephem = None

DEG = 180.0 / math.pi

# name, latitude, longitude, height (m), UTC time
CASES = [
    ("Zurich summer morning", 47.3769, 8.5417, 408, "2024-06-20 10:00:00"),
    ("Sydney December", -33.8688, 151.2093, 0, "2024-12-21 02:00:00"),
    ("Quito equinox, near zenith", -0.1807, -78.4678, 2850, "2025-03-20 17:00:00"),
    ("Tromso midnight sun", 69.6492, 18.9553, 0, "2025-06-21 22:30:00"),
    ("Tromso polar night noon", 69.6492, 18.9553, 0, "2025-12-21 11:00:00"),
    ("Denver 1900 winter afternoon", 39.742476, -105.1786, 1830, "1900-01-15 21:00:00"),
    ("Cape Town 1955 winter", -33.9249, 18.4241, 0, "1955-06-21 14:30:00"),
    ("Anchorage 2100 near sunset", 61.2181, -149.9003, 0, "2100-11-01 01:30:00"),
    ("McMurdo 2075 polar day midnight", -77.8463, 166.6682, 10, "2075-12-21 12:00:00"),
    ("Singapore 1925 morning", 1.3521, 103.8198, 15, "1925-03-10 01:00:00"),
    ("Reykjavik 2040 equinox evening", 64.1466, -21.9426, 20, "2040-09-23 18:00:00"),
    ("Honolulu 2099 night", 21.3069, -157.8583, 5, "2099-07-04 10:00:00"),
    ("South Pole 1990 polar night", -90.0, 0.0, 2835, "1990-06-21 12:00:00"),
    ("Ushuaia 2010 summer", -54.8019, -68.3030, 0, "2010-01-10 16:00:00"),
]


def unix(text):
    return calendar.timegm(tuple(int(v) for v in text.replace("-", " ").replace(":", " ").split()))


def observer(lat, lon, height, when):
    o = ephem.Observer()
    o.lat, o.lon, o.elevation = str(lat), str(lon), height
    o.date = ephem.Date(when.replace("-", "/"))
    o.pressure = 0  # geometric
    return o


def separation(alt1, az1, alt2, az2):
    """Angle between two directions given as elevation/azimuth (deg)."""
    a1, b1, a2, b2 = (math.radians(v) for v in (alt1, az1, alt2, az2))
    c = (math.sin(a1) * math.sin(a2) + math.cos(a1) * math.cos(a2) * math.cos(b1 - b2))
    return math.degrees(math.acos(max(-1.0, min(1.0, c))))


@unittest.skipIf(ephem is None, "python3-ephem is not installed")
class TestSolarPosition(Testing.vtkTest):
    def setUp(self):
        from aperture.errors import quiet_vtk_output
        quiet_vtk_output()  # the bad-input checks below expect errors

    def sun(self, lat, lon, height, when, delta_t=None):
        s = aperture.vtkApertureSolarPosition()
        s.SetLatitude(lat)
        s.SetLongitude(lon)
        s.SetHeight(height)
        s.SetUnixTime(unix(when))
        if delta_t is not None:
            s.SetDeltaT(delta_t)
        self.assertTrue(s.Compute(), s.GetErrorMessage())
        return s

    def testAgainstPyEphem(self):
        worst = 0.0
        for name, lat, lon, height, when in CASES:
            o = observer(lat, lon, height, when)
            ref = ephem.Sun(o)
            s = self.sun(lat, lon, height, when, ephem.delta_t(o.date))
            alt, az = float(ref.alt) * DEG, float(ref.az) * DEG
            d = separation(s.GetElevationTrue(), s.GetAzimuth(), alt, az)
            worst = max(worst, d)
            self.assertLess(d, 0.01, "%s: ours %.5f/%.5f, PyEphem %.5f/%.5f"
                            % (name, s.GetElevationTrue(), s.GetAzimuth(), alt, az))
            # the elevation alone, where the azimuth is ill-conditioned (poles, zenith)
            self.assertAlmostEqual(s.GetElevationTrue(), alt, delta=0.01, msg=name)
            # PyEphem's earth_distance (float32) and SPA's R differ by up to 5e-5 AU, about
            # the Earth-Moon barycentre's distance from the Earth's centre (4700 km), which
            # the two theories may treat differently (not traced further).
            self.assertAlmostEqual(s.GetDistance(), ref.earth_distance, delta=1e-4, msg=name)
        print("worst direction difference vs PyEphem over %d cases: %.5f deg"
              % (len(CASES), worst))

    def testPolarDayAndNight(self):
        for name, lat, lon, height, when, kind in [
                ("Tromso", 69.6492, 18.9553, 0, "2025-06-21 22:30:00", 1),
                ("Tromso", 69.6492, 18.9553, 0, "2025-12-21 11:00:00", 2),
                ("McMurdo", -77.8463, 166.6682, 10, "2075-12-21 12:00:00", 1),
                ("South Pole", -90.0, 0.0, 2835, "1990-06-21 12:00:00", 2)]:
            s = self.sun(lat, lon, height, when)
            self.assertEqual(s.GetDayKind(), kind, name)
            self.assertEqual(s.GetSunriseString(), "", name)
            self.assertEqual(s.GetSunsetString(), "", name)
            self.assertTrue(math.isnan(s.GetSunrise()))
            self.assertNotEqual(s.GetTransitString(), "", name)
            self.assertEqual(s.GetElevationTrue() > 0, kind == 1, name)

    def testRiseAndSet(self):
        # Days on which the UTC day is the local day (longitudes near 0).
        for lat, lon, day in [(47.3769, 8.5417, "2024-06-20"), (-33.9249, 18.4241, "1955-06-21"),
                              (51.4779, -0.0015, "2100-03-21"), (64.1466, -21.9426, "1980-10-01")]:
            s = self.sun(lat, lon, 0, day + " 12:00:00")
            o = observer(lat, lon, 0, day + " 00:00:00")
            o.horizon = "-0:50"
            rise = o.next_rising(ephem.Sun(), use_center=True)
            setting = o.next_setting(ephem.Sun(), use_center=True)
            transit = o.next_transit(ephem.Sun())
            to_unix = lambda d: (float(d) - float(ephem.Date("1970/1/1"))) * 86400.0
            self.assertEqual(s.GetDayKind(), 0)
            self.assertAlmostEqual(s.GetSunrise(), to_unix(rise), delta=30, msg=day)
            self.assertAlmostEqual(s.GetSunset(), to_unix(setting), delta=30, msg=day)
            self.assertAlmostEqual(s.GetTransit(), to_unix(transit), delta=5, msg=day)
            # Equation of time = apparent - mean solar time: at PyEphem's transit the sun is
            # on the meridian (apparent noon), so EoT = 12:00 - (UTC of transit + lon / 15 h).
            at_transit = self.sun(lat, lon, 0, "1970-01-01 00:00:00")
            at_transit.SetUnixTime(to_unix(transit))
            self.assertTrue(at_transit.Compute())
            minutes = (to_unix(transit) % 86400) / 60.0 + 4.0 * lon
            self.assertAlmostEqual(at_transit.GetEquationOfTime(), 720.0 - minutes, delta=0.02,
                                   msg=day)

    def testEventsFollowEveryInput(self):
        # One object computing a sequence of times and places (as a time series reuses one):
        # each day's events are those a new object gives for the same inputs, bit for bit,
        # whichever input changed since the last Compute (it keeps the last day's events).
        def start(s):
            s.SetLatitude(47.3769)
            s.SetLongitude(8.5417)
            s.SetUnixTime(unix("2026-03-28 22:30:00"))

        def later(seconds):
            return lambda s: s.SetUnixTime(s.GetUnixTime() + seconds)

        steps = [("an hour later, the same day", later(3600)),
                 ("the next day", later(86400)),
                 ("a time zone whose day is another (UTC+1, then DST)",
                  lambda s: s.SetTimeZone("Europe/Zurich")),
                 ("the same zone's next day, in summer time", later(86400)),
                 ("latitude", lambda s: s.SetLatitude(-33.9)),
                 ("longitude", lambda s: s.SetLongitude(18.4)),
                 ("pressure", lambda s: s.SetPressure(700.0)),
                 ("temperature", lambda s: s.SetTemperature(-30.0)),
                 ("no refraction", lambda s: s.SetRefraction(False)),
                 ("delta T", lambda s: s.SetDeltaT(300.0)),
                 ("delta UT1", lambda s: s.SetDeltaUT1(0.9)),
                 ("a polar night", lambda s: s.SetLatitude(-80.0)),
                 ("back to the first latitude", lambda s: s.SetLatitude(47.3769))]

        def events(s):
            self.assertTrue(s.Compute(), s.GetErrorMessage())
            return [s.GetSunrise(), s.GetTransit(), s.GetSunset(), s.GetDayKind(),
                    s.GetSunriseString(), s.GetTransitString(), s.GetSunsetString()]

        reused = aperture.vtkApertureSolarPosition()
        start(reused)
        previous = events(reused)
        changed = 0
        for k, (name, change) in enumerate(steps):
            change(reused)
            got = events(reused)
            new = aperture.vtkApertureSolarPosition()
            start(new)
            for _, c in steps[:k + 1]:
                c(new)
            expected = events(new)
            self.assertEqual(str(got), str(expected), name)  # (str: NaN equals NaN)
            changed += str(got) != str(previous)
            previous = got
        self.assertGreaterEqual(changed, 8)  # (most steps move the events)

    def testAngularRadius(self):
        # 2025 perihelion (Jan 4) and aphelion (Jul 4): 0.27108 and 0.26220 deg (959.63"/r).
        for when, expected in [("2025-01-04 13:00:00", 0.27108), ("2025-07-04 20:00:00", 0.26220)]:
            s = self.sun(45.0, 0.0, 0.0, when)
            ref = ephem.Sun(observer(45.0, 0.0, 0.0, when))
            self.assertAlmostEqual(s.GetAngularRadius(), float(ref.radius) * DEG, delta=0.001)
            self.assertAlmostEqual(s.GetAngularRadius(), expected, delta=0.0001)

    def testLight(self):
        # Rec.709 luminance (the Y row of the sRGB-to-XYZ matrix, D65)
        lum = lambda rgb: 0.2126390059 * rgb[0] + 0.7151686788 * rgb[1] + 0.0721923154 * rgb[2]
        s = self.sun(47.3769, 8.5417, 408, "2024-06-20 11:30:00")  # high summer sun
        self.assertLess(s.GetAirMass(), 1.2)
        dni = s.GetDirectNormalIrradiance()
        self.assertTrue(800 < dni < 1050, dni)  # clear sky, Linke turbidity 3
        rgb = [0.0] * 3
        s.GetSunColor(rgb)
        self.assertAlmostEqual(lum(rgb), dni, delta=1e-6 * dni)
        # The whole upper hemisphere seen by a horizontal surface is the sky's horizontal
        # irradiance (two computations: the cap quadrature and the model's own scale).
        mean, irr = [0.0] * 3, [0.0] * 3
        self.assertTrue(s.GetSkyCap([0, 0, 1], 90.0, [0, 0, 1], mean, irr))
        eh = s.GetSkyHorizontalIrradiance()
        self.assertTrue(50 < eh < 300, eh)
        self.assertAlmostEqual(lum(irr), eh, delta=5e-4 * eh)
        # Near the sun the Preetham sky is brighter than opposite it; below the horizon dark.
        d = [0.0] * 3
        s.GetDirection(d)
        near, far, below = [0.0] * 3, [0.0] * 3, [0.0] * 3
        self.assertTrue(s.GetSkyRadiance([d[0], d[1], d[2] + 0.3], near))
        self.assertTrue(s.GetSkyRadiance([-d[0], -d[1], d[2] + 0.3], far))
        self.assertTrue(s.GetSkyRadiance([1, 0, -0.1], below))
        self.assertGreater(lum(near), 2 * lum(far))
        self.assertEqual(below, [0.0, 0.0, 0.0])
        # A low sun is weaker and redder.
        low = self.sun(47.3769, 8.5417, 408, "2024-06-20 19:00:00")
        self.assertTrue(0 < low.GetElevation() < 10)
        low_rgb = [0.0] * 3
        low.GetSunColor(low_rgb)
        self.assertLess(low.GetDirectNormalIrradiance(), 0.8 * dni)
        self.assertGreater(low_rgb[0] / low_rgb[2], 1.2 * rgb[0] / rgb[2])
        # Night: no beam.
        night = self.sun(47.3769, 8.5417, 408, "2024-06-20 23:00:00")
        self.assertEqual(night.GetDirectNormalIrradiance(), 0.0)
        # Overcast with a given horizontal irradiance: zenith 3x the horizon (Moon & Spencer),
        # and the hemisphere integral returns the given irradiance.
        s.SetSkyModelToCIEOvercast()
        s.SetDiffuseHorizontalIrradiance(100.0)
        self.assertTrue(s.Compute())
        zen, hor = [0.0] * 3, [0.0] * 3
        s.GetSkyRadiance([0, 0, 1], zen)
        s.GetSkyRadiance([1, 0, 1e-9], hor)
        self.assertAlmostEqual(lum(zen) / lum(hor), 3.0, delta=1e-6)
        s.GetSkyCap([0, 0, 1], 90.0, [0, 0, 1], mean, irr)
        self.assertAlmostEqual(lum(irr), 100.0, delta=0.05)
        # Bad input
        s.SetTurbidity(1.0)
        self.assertFalse(s.Compute())
        self.assertIn("Turbidity", s.GetErrorMessage())
        s.SetTurbidity(3.0)
        self.assertTrue(s.Compute())
        self.assertFalse(s.GetSkyCap([0, 0, 0], 10.0, [0, 0, 1], mean, irr))
        self.assertFalse(s.GetSkyCap([0, 0, 1], 100.0, [0, 0, 1], mean, irr))

    def testRefraction(self):
        # Refraction lifts a low sun by about half a degree and a high one by almost nothing;
        # off, the apparent values are the geometric ones.
        s = self.sun(69.6492, 18.9553, 0, "2025-06-21 22:30:00")
        self.assertAlmostEqual(s.GetElevation() - s.GetElevationTrue(), 0.22, delta=0.03)
        s.SetRefraction(False)
        self.assertTrue(s.Compute())
        self.assertEqual(s.GetElevation(), s.GetElevationTrue())

    def testOutOfRange(self):
        # Each parameter out of range is named with its value and its range; a time past the
        # years the ISO formatter covers by its year (mid-year -2001: 3970.5 mean Gregorian
        # years before 1970).
        before = -3970.5 * 365.2425 * 86400.0
        cases = [("SetPressure", -5.0, "the pressure -5 hPa is outside 0..5000 hPa"),
                 ("SetTemperature", -300.0, "the temperature -300 C is outside -100..100 C"),
                 ("SetDeltaT", float("inf"), "delta T inf s is outside -100000..100000 s"),
                 ("SetDeltaUT1", 1.5, "delta UT1 1.5 s is outside -1..1 s"),
                 ("SetHeight", 1e20, "the height 1e+20 m is outside -6500..100000 km"),
                 ("SetUnixTime", unix("6001-01-01 00:00:00"), "the time in the year 6001 is "
                  "outside the years the algorithm covers (-2000..6000)"),
                 ("SetUnixTime", before, "the time in the year -2001 is outside"),
                 ("SetUnixTime", -1e300, "the time -1e+300 s after 1970 is outside")]
        for setter, value, message in cases:
            s = self.sun(47.3769, 8.5417, 408, "2024-06-20 10:00:00")
            getattr(s, setter)(value)
            self.assertFalse(s.Compute(), setter)
            self.assertIn(message, s.GetErrorMessage())
        # The last second of the range is in it.
        self.sun(47.3769, 8.5417, 408, "6000-12-31 23:59:59")

if __name__ == "__main__":
    Testing.main([(TestSolarPosition, "test")])
