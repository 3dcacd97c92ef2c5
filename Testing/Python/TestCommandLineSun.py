# SPDX-License-Identifier: BSD-3-Clause
"""`aperture sun` as a user runs it: the published SPA case through the command line, --json
keys, local times in IANA zones (daylight saving, skipped and repeated times), a DEM's frame
(UTM near a zone edge: grid azimuth = azimuth - the closed-form convergence of ALGORITHMS.md 5),
time series, and one clear error line with status 1 for every bad input."""
import datetime
import json
import math
import os
import subprocess
import tempfile
import unittest

import numpy as np
from osgeo import gdal, osr

from rasters import make_dem
from usage import usage_error

gdal.UseExceptions()

BUILD = os.environ.get("APERTURE_BUILD_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
APERTURE = os.path.join(BUILD, "bin", "aperture")
KEYS = {"azimuth_deg", "elevation_deg", "zenith_deg", "elevation_true_deg", "angular_radius_deg",
        "distance_au", "equation_of_time_min", "sunrise", "transit", "sunset"}


def run(*args):
    p = subprocess.run([APERTURE, "sun"] + [str(a) for a in args], capture_output=True,
                       text=True, timeout=120)
    return p.returncode, p.stdout, p.stderr


def convergence_tm(lat, dlon):
    """Meridian convergence of transverse Mercator on WGS 84 (degrees), the ellipsoidal series
    of ALGORITHMS.md 5 (good to 2.4e-8 deg at a zone edge)."""
    f = 1 / 298.257223563
    e2 = f * (2 - f)
    ep2 = e2 / (1 - e2)
    p, l = math.radians(lat), math.radians(dlon)
    eta2 = ep2 * math.cos(p) ** 2
    c2 = l * l * math.cos(p) ** 2
    g = l * math.sin(p) * (1 + c2 / 3 * (1 + 3 * eta2 + 2 * eta2 ** 2)
                           + c2 * c2 / 15 * (2 - math.tan(p) ** 2))
    return math.degrees(g)


class CommandLineSunTest(unittest.TestCase):
    def json_of(self, *args):
        status, out, err = run(*args, "--json")
        self.assertEqual(status, 0, err)
        return json.loads(out)

    def error_of(self, *args):
        status, out, err = run(*args)
        self.assertEqual(status, 1, out + err)
        self.assertEqual(len(err.strip().splitlines()), 1, err)
        self.assertTrue(err.startswith("aperture: error: "), err)
        return err

    def usage_error_of(self, *args):
        """A mistake in the options (a value out of range, options that do not go together):
        a usage error, as argparse's own checks report (-d 3 said 1 and no usage where
        --camera 30,95 said 2, until 2026-12-06)."""
        return usage_error(self, "sun", run(*args))

    def test_values_starting_with_a_minus(self):
        # A year before 1 (ISO 8601's -1000 is 1001 BC) after --at, as written after --at=:
        # argparse alone took it for an option and stopped ("expected one argument").
        first = self.json_of("--at", "-1000-06-21T12:00Z", "--lat", -33.9, "--lon", -18.4)
        self.assertEqual(first["time_utc"], "-1000-06-21T12:00:00Z")
        self.assertEqual((first["latitude_deg"], first["longitude_deg"]), (-33.9, -18.4))
        self.assertEqual(self.json_of("--at=-1000-06-21T12:00Z", "--lat=-33.9", "--lon=-18.4"),
                         first)
        # -inf and -nan get the option's range (argparse said "expected one argument")
        for option, value, expected in (("--lon", "-inf", "-inf is outside -180..180"),
                                        ("--lat", "-nan", "-nan is outside -90..90")):
            message = self.usage_error_of("--at", "2026-06-21T12:00Z", "--lat", 0, "--lon", 0,
                                          option, value)
            self.assertIn("argument %s: %s degrees" % (option, expected), message)

    def test_local_times_before_year_1(self):
        # The years -2000..0 have local times as the UTC strings have them (null and "n/a"
        # until 2026-12-07: Python's datetime has the years 1..9999): the clock of the offset,
        # its date across a year's end, year 0 a leap year (1 BC)
        for at, utc, local in (
                ("0000-01-01T12:00+01:00", "0000-01-01T11:00:00Z", "0000-01-01T12:00:00+01:00"),
                ("-0001-01-01T01:00+03:00", "-0002-12-31T22:00:00Z",
                 "-0001-01-01T01:00:00+03:00"),
                ("0000-02-29T23:30-05:00", "0000-03-01T04:30:00Z", "0000-02-29T23:30:00-05:00"),
                ("-2000-01-01T10:00-01:30", "-2000-01-01T11:30:00Z",
                 "-2000-01-01T10:00:00-01:30")):
            r = self.json_of("--at", at, "--lat", 10, "--lon", 10)
            self.assertEqual((r["time_utc"], r["time_local"]), (utc, local))
            offset = int(local[-6:-3]) * 3600 + int(local[-6] + local[-2:]) * 60
            for event in ("sunrise", "transit", "sunset"):
                # each local event the UTC one on the offset's clock, by the UTC string's
                # seconds of the day (these days' events lie within one date at both)
                hms = lambda t: sum(int(v) * f for v, f in zip(t.split("T")[1][:8].split(":"),
                                                                (3600, 60, 1)))
                self.assertEqual((hms(r[event]) + offset) % 86400, hms(r[event + "_local"]),
                                 (at, event, r[event], r[event + "_local"]))
                self.assertEqual(r[event + "_local"][-6:], local[-6:])
            status, stdout, stderr = run("--at", at, "--lat", 10, "--lon", 10)
            self.assertEqual(status, 0, stderr)
            self.assertNotIn("n/a", stdout)
            self.assertIn("local: sunrise %s, " % r["sunrise_local"].split("T")[1][:8], stdout)

    def test_no_refraction(self):
        # Refraction off: geometric elevations, labelled so (they were "apparent (refracted)"
        # in the text), and sunrise and sunset where the upper limb meets the geometric
        # horizon (the centre at -0.26667 deg, as the help says): at 66 N on the solstice a
        # polar day with refraction, a sunset and a sunrise without it. PyEphem 4.1.4 (sun
        # centre at -0.26667 deg, no refraction) has 00:40:02Z and 23:23:32Z; the report's
        # model is within 60 s of it this far north
        args = ("--at", "2026-06-21T12:00Z", "--lat", 66, "--lon", 0)
        self.assertEqual(self.json_of(*args)["day_kind"], "polar_day")
        r = self.json_of(*args, "--no-refraction")
        self.assertEqual(r["elevation_deg"], r["elevation_true_deg"])
        self.assertEqual(r["day_kind"], "normal")
        for event, reference in (("sunrise", 40 * 60 + 2), ("sunset", 23 * 3600 + 23 * 60 + 32)):
            h, m, sec = map(int, r[event][11:19].split(":"))
            self.assertLessEqual(abs(3600 * h + 60 * m + sec - reference), 60, r[event])
        status, stdout, stderr = run(*args, "--no-refraction")
        self.assertEqual(status, 0, stderr)
        self.assertNotIn("apparent", stdout)
        self.assertIn("Elevation:   %.4f deg geometric (--no-refraction)"
                      % r["elevation_true_deg"], stdout)
        # (--pressure 0: geometric elevations too, the day the standard refraction's)
        self.assertEqual(self.json_of(*args, "--pressure", 0)["day_kind"], "polar_day")

    def test_spa_case(self):
        r = self.json_of("--at", "2003-10-17T12:30:30-07:00", "--lat", 39.742476,
                         "--lon", -105.1786, "--height", 1830.14, "--pressure", 820,
                         "--temperature", 11, "--delta-t", 67)
        self.assertTrue(KEYS <= set(r), KEYS - set(r))
        self.assertAlmostEqual(r["zenith_deg"], 50.111622, delta=5e-7)
        self.assertAlmostEqual(r["azimuth_deg"], 194.340241, delta=5e-7)
        self.assertAlmostEqual(r["elevation_deg"], 90 - 50.111622, delta=5e-7)
        self.assertGreater(r["elevation_deg"], r["elevation_true_deg"])
        self.assertEqual(r["sunrise"], "2003-10-17T13:12:43Z")  # 06:12:43 local (the report)
        self.assertEqual(r["sunrise_local"], "2003-10-17T06:12:43-07:00")
        self.assertEqual(r["time_utc"], "2003-10-17T19:30:30Z")
        self.assertNotIn("grid_azimuth_deg", r)
        # the light: 40 deg sun at 1830 m through a clear sky; RGB luminance = DNI
        self.assertTrue(700 < r["direct_normal_irradiance_w_m2"] < 1000)
        y = 0.2126390059 * r["sun_rgb_w_m2"][0] + 0.7151686788 * r["sun_rgb_w_m2"][1] \
            + 0.0721923154 * r["sun_rgb_w_m2"][2]
        self.assertAlmostEqual(y, r["direct_normal_irradiance_w_m2"], delta=1e-6 * y)
        self.assertEqual(r["sky_model"], "preetham")

    def test_text_output(self):
        status, out, err = run("--at", "2026-06-21T14:00", "--tz", "Europe/Zurich",
                               "--lat", 47.3769, "--lon", 8.5417)
        self.assertEqual(status, 0, err)
        self.assertIn("2026-06-21T12:00:00Z (local 2026-06-21T14:00:00+02:00)", out)
        self.assertIn("Azimuth:", out)
        self.assertIn("sunrise", out)
        self.assertNotIn("Note:", out)
        # At Anchorage (149.9 W) the UTC day runs from 14:00 to 14:00 local solar time: its
        # sunset (07:42Z) ends the night before its sunrise (12:20Z), which the text notes; at
        # the place's offset the events are in order and there is no note.
        status, out, err = run("--at", "2026-06-21T12:00Z", "--lat", 61.2, "--lon", -149.9)
        self.assertEqual(status, 0, err)
        self.assertIn("sunset 2026-06-21T07:42", out)
        note = " ".join(out.split("Note:", 1)[1].split())
        self.assertEqual(note, "the day of the clock at +00:00 is 10.0 h ahead of the solar time "
                         "at longitude -149.9000, so its events are not in the order sunrise, "
                         "transit, sunset; for the place's own day give --tz with its time zone, "
                         "or its UTC offset in --at")
        status, out, err = run("--at", "2026-06-21T12:00-08:00", "--lat", 61.2, "--lon", -149.9)
        self.assertIn("sunset 2026-06-22T07:42", out)
        self.assertNotIn("Note:", out)
        # A zone far from the place: Zurich on Tokyo's clock is 8.5 h behind it.
        status, out, err = run("--at", "2026-06-21T12:00", "--tz", "Asia/Tokyo", "--lat", 47,
                               "--lon", 8)
        self.assertIn("at +09:00 is 8.5 h ahead of the solar time at longitude 8.0000",
                      " ".join(out.split()))
        # (with --tz, an offset in --at does not change the day: only the zone is advised)
        self.assertIn("for the place's own day give --tz the place's own time zone",
                      " ".join(out.split()))

    def test_time_zones(self):
        summer = self.json_of("--at", "2026-06-21T14:00", "--tz", "Europe/Zurich",
                              "--lat", 47.3769, "--lon", 8.5417)
        self.assertEqual(summer["time_utc"], "2026-06-21T12:00:00Z")
        self.assertEqual(summer["utc_offset"], "+02:00")
        winter = self.json_of("--at", "2026-01-15T14:00", "--tz", "Europe/Zurich",
                              "--lat", 47.3769, "--lon", 8.5417)
        self.assertEqual(winter["time_utc"], "2026-01-15T13:00:00Z")
        # Southern-hemisphere daylight saving: Sydney is +11:00 in January.
        sydney = self.json_of("--at", "2026-01-15T12:00", "--tz", "Australia/Sydney",
                              "--lat", -33.8688, "--lon", 151.2093)
        self.assertEqual(sydney["time_utc"], "2026-01-15T01:00:00Z")
        err = self.usage_error_of("--at", "2026-03-29T02:30", "--tz", "Europe/Zurich",
                                  "--lat", 47, "--lon", 8)
        self.assertIn("does not exist in Europe/Zurich: clocks jump from 02:00 to 03:00", err)
        # a day skipped whole (Samoa, 2011-12-30): the jump's dates (it said "00:00 to 00:00")
        err = self.usage_error_of("--at", "2011-12-30T12:00", "--tz", "Pacific/Apia",
                                  "--lat", -13.8, "--lon", -171.8)
        self.assertIn("does not exist in Pacific/Apia: clocks jump from 2011-12-30T00:00 to "
                      "2011-12-31T00:00 (2011-12-30T10:00:00Z)", err)
        err = self.usage_error_of("--at", "2026-10-25T02:30", "--tz", "Europe/Zurich",
                                  "--lat", 47, "--lon", 8)
        self.assertIn("occurs twice", err)
        self.assertIn("2026-10-25T00:30:00Z", err)
        # --tz names the local day even for an instant given in UTC: 23:30Z is 08:30 on the
        # next day in Tokyo, whose sunrise (04:25 local) comes before its transit.
        r = self.json_of("--at", "2026-06-21T23:30Z", "--tz", "Asia/Tokyo",
                         "--lat", 35.68, "--lon", 139.69)
        self.assertEqual(r["utc_offset"], "+09:00")
        self.assertTrue(r["sunrise_local"].startswith("2026-06-22T04:2"), r["sunrise_local"])
        self.assertTrue(r["sunset_local"].startswith("2026-06-22T19:0"), r["sunset_local"])
        # A series stepped from an instant written with an offset keeps that clock (no --tz).
        status, out, err = run("--at", "2026-06-21T12:00+09:00", "--lat", 35.68, "--lon",
                               139.69, "--days", 1, "--step", 360)
        self.assertEqual(status, 0, err)
        rows = [line.split("\t") for line in out.splitlines()[1:]]
        self.assertEqual([r[1] for r in rows], [
            "2026-06-21T12:00:00+09:00", "2026-06-21T18:00:00+09:00",
            "2026-06-22T00:00:00+09:00", "2026-06-22T06:00:00+09:00"])
        # An explicit offset settles it.
        r = self.json_of("--at", "2026-10-25T02:30+01:00", "--tz", "Europe/Zurich",
                         "--lat", 47, "--lon", 8)
        self.assertEqual(r["time_utc"], "2026-10-25T01:30:00Z")
        # On the day of a clock change each event is on the clock of its own moment: the
        # clocks go forward at 01:00Z on 2026-03-29 and back at 01:00Z on 2026-10-25, before
        # sunrise, so the day's events are at +02:00 from midnight at +01:00, and back.
        for day, before, after in (("2026-03-29", "+01:00", "+02:00"),
                                   ("2026-10-25", "+02:00", "+01:00")):
            r = self.json_of("--at", day + "T00:00", "--tz", "Europe/Zurich",
                             "--lat", 47, "--lon", 8)
            self.assertEqual(r["time_local"], day + "T00:00:00" + before)
            hours = 2 if after == "+02:00" else 1
            for event in ("sunrise", "transit", "sunset"):
                utc = datetime.datetime.fromisoformat(r[event].replace("Z", "+00:00"))
                local = (utc + datetime.timedelta(hours=hours)).strftime("%Y-%m-%dT%H:%M:%S")
                self.assertEqual(r[event + "_local"], local + after, event)
            status, out, err = run("--at", day + "T00:00", "--tz", "Europe/Zurich",
                                   "--lat", 47, "--lon", 8)
            self.assertEqual(status, 0, err)
            line = [l for l in out.splitlines() if "local: sunrise" in l][0]
            self.assertIn("sunrise %s%s" % (r["sunrise_local"][11:19], after), line)

    def test_fractions_of_a_second_and_delta_t(self):
        # An instant with a fraction of a second is written with it, to the millisecond or
        # the microsecond, in the UTC and the local time alike: the sun is computed for that
        # instant (12:00:00.5 was written 12:00:01, a second it was not, until 2026-12-07)
        status, out, err = run("--at", "2026-06-21T12:00:00.5Z", "--lat", 47, "--lon", 8)
        self.assertEqual(status, 0, err)
        self.assertIn("Time:        2026-06-21T12:00:00.500Z (UTC's clock and day: --tz ZONE "
                      "gives the place's)", out)
        # (in UTC without --tz: no local times, which read as the place's, were UTC's until
        # 2026-12-07; with --tz UTC they are asked for)
        self.assertIn("sunset 2026-06-21T19:26:45Z (the UTC day)\n", out)
        self.assertNotIn("local", out)
        status, out, err = run("--at", "2026-06-21T12:00:00.5Z", "--lat", 47, "--lon", 8,
                               "--tz", "UTC")
        self.assertEqual(status, 0, err)
        self.assertIn("2026-06-21T12:00:00.500Z (local 2026-06-21T12:00:00.500+00:00)", out)
        self.assertIn("(local +00:00)\n             local: sunrise 03:32:52, ", out)
        for at, utc, local in (
                ("2026-06-21T14:00:00,25", "2026-06-21T12:00:00.250Z",
                 "2026-06-21T14:00:00.250+02:00"),
                ("2026-06-21T14:00:00.123456", "2026-06-21T12:00:00.123456Z",
                 "2026-06-21T14:00:00.123456+02:00"),
                ("2026-06-21T14:00:00.1234567", "2026-06-21T12:00:00.123457Z",  # (rounded)
                 "2026-06-21T14:00:00.123457+02:00"),
                ("2026-06-21T14:00:00.9999999", "2026-06-21T12:00:01Z",  # (within 0.5 us)
                 "2026-06-21T14:00:01+02:00"),
                ("1969-12-31T23:59:59.75", "1969-12-31T22:59:59.750Z",  # (before 1970)
                 "1969-12-31T23:59:59.750+01:00")):
            r = self.json_of("--at", at, "--tz", "Europe/Zurich", "--lat", 47, "--lon", 8)
            self.assertEqual((r["time_utc"], r["time_local"]), (utc, local), at)
            self.assertEqual(len(r["sunrise"]), len("2026-06-21T03:29:02Z"))  # (events: seconds)
        # a series stepped by 1.5 s: each row its instant
        status, out, err = run("--at", "2026-06-21T12:00Z", "--lat", 47, "--lon", 8, "--days", 1,
                               "--step", 0.025)
        self.assertEqual(status, 0, err)
        self.assertEqual([row.split("\t")[:2] for row in out.splitlines()[1:4]],
                         [["2026-06-21T12:00:00Z", "2026-06-21T12:00:00+00:00"],
                          ["2026-06-21T12:00:01.500Z", "2026-06-21T12:00:01.500+00:00"],
                          ["2026-06-21T12:00:03Z", "2026-06-21T12:00:03+00:00"]])
        # the step taken to the microsecond the times are written to: the minimum as the help
        # writes it, 0.016666667 minutes (1.00000002 s), drifted to 12:00:58.000001Z at the 59th
        status, out, err = run("--at", "2026-06-21T12:00Z", "--lat", 47, "--lon", 8, "--days", 1,
                               "--step", 0.016666667)
        self.assertEqual(status, 0, err)
        self.assertEqual(out.splitlines()[59].split("\t")[0], "2026-06-21T12:00:58Z")
        # a step longer than the day: its one time (NaN in the review's draft of the rounding)
        status, out, err = run("--at", "2026-06-21T12:00Z", "--lat", 47, "--lon", 8, "--step",
                               "1e307")
        self.assertEqual(status, 0, err)
        self.assertEqual([row.split("\t")[0] for row in out.splitlines()[1:]],
                         ["2026-06-21T12:00:00Z"])
        # the range's last second keeps its digits, and is not rounded past its end, which the
        # parser refuses (until 2026-12-07 "6001-01-01T00:00:00Z", twice)
        status, out, err = run("--at", "6000-12-31T23:59:59.9Z", "--lat", 47, "--lon", 8)
        self.assertEqual(status, 0, err)
        self.assertIn("Time:        6000-12-31T23:59:59.900Z (UTC's", out)
        # nor as a local time in the year 6001, east of UTC, which --at would refuse
        r = self.json_of("--at", "6000-12-31T23:59:59.9Z", "--lat", 35, "--lon", 139, "--tz",
                         "Asia/Tokyo")
        self.assertEqual((r["time_utc"], r["time_local"]), ("6000-12-31T23:59:59.900Z", None))
        # --delta-t nan was the estimate, without a word
        for value in ("nan", "1e300", "-100001"):  # (1e300 was refused by the light's check)
            self.assertEqual(self.usage_error_of("--at", "2026-06-21T12:00Z", "--lat", 47,
                                                 "--lon", 8, "--delta-t", value),
                             "aperture sun: error: argument --delta-t: %s is outside "
                             "-100000..100000 s\n" % value)

    def test_polar(self):
        r = self.json_of("--at", "2025-06-21T22:30Z", "--lat", 69.6492, "--lon", 18.9553)
        self.assertEqual(r["day_kind"], "polar_day")
        self.assertIsNone(r["sunrise"])
        self.assertIsNone(r["sunset"])
        self.assertIsNotNone(r["transit"])
        r = self.json_of("--at", "2025-12-21T11:00Z", "--lat", 69.6492, "--lon", 18.9553)
        self.assertEqual(r["day_kind"], "polar_night")
        self.assertLess(r["elevation_deg"], 0)

    def test_polar_transitions(self):
        # Days next to polar day and night (PyEphem 4.1.4, the sun's centre at -0:50, no
        # refraction): at 89 N on 2026-03-16 the sun rises at 09:53:38 and sets at 14:54:36 UTC
        # (was 05:39:55 and 19:02:31); at 82.967 S on 1973-04-10 at UTC-3 it does not rise
        # (was a normal day, its sunrise at 14:25 after its sunset at 08:39, with a note
        # blaming the offset); at 66 N, 15 E on 2026-06-12 at UTC+1 it rises at 00:12:12 local
        # and does not set before the next day (PyEphem: always up at 2026-06-12 22:59 UTC).
        def seconds(text):
            t = datetime.datetime.fromisoformat(text.replace("Z", "+00:00"))
            return t.hour * 3600 + t.minute * 60 + t.second
        r = self.json_of("--at", "2026-03-16T12:00Z", "--lat", 89, "--lon", 0)
        self.assertEqual(r["day_kind"], "normal")
        self.assertAlmostEqual(seconds(r["sunrise"]), 9 * 3600 + 53 * 60 + 38, delta=90)
        self.assertAlmostEqual(seconds(r["sunset"]), 14 * 3600 + 54 * 60 + 36, delta=90)
        args = ("--at", "1973-04-10T12:00-03:00", "--lat", -82.967, "--lon", -37.521)
        r = self.json_of(*args)
        self.assertEqual((r["day_kind"], r["sunrise"], r["sunset"]), ("polar_night", None, None))
        status, stdout, stderr = run(*args)
        self.assertEqual(status, 0, stderr)
        self.assertIn("polar night: the sun does not rise", stdout)
        self.assertNotIn("Note:", stdout)
        args = ("--at", "2026-06-12T12:00+01:00", "--lat", 66, "--lon", 15)
        r = self.json_of(*args)
        self.assertEqual((r["day_kind"], r["sunset"], r["sunset_local"]), ("normal", None, None))
        self.assertEqual(r["sunrise_local"][:16], "2026-06-12T00:12")
        status, stdout, stderr = run(*args)
        self.assertEqual(status, 0, stderr)
        self.assertIn("sunset n/a (none that day)", stdout)
        self.assertIn("local: sunrise 00:12:", stdout)
        self.assertNotIn("Note:", stdout)

    def test_day_beyond_the_years(self):
        # The instant lies in the years the algorithm covers, its local day (or that day's
        # events) not: no events, and no day kind, rather than a stale or partial one.
        for args in (("--at", "6000-12-31T20:00Z", "--tz", "Pacific/Kiritimati", "--lat", 1.87,
                      "--lon", -157.4),
                     ("--at", "-2000-01-01T02:00Z", "--tz", "Pacific/Pago_Pago", "--lat", -14.3,
                      "--lon", -170.7),
                     # (west of UTC, the day's end beyond the years: it was a normal day
                     # without its sunset until 2026-12-07, the end placed at 00:00Z)
                     ("--at", "6000-12-31T12:00", "--tz", "America/Los_Angeles", "--lat", 34,
                      "--lon", -118)):
            r = self.json_of(*args)
            self.assertEqual([r[k] for k in ("day_kind", "sunrise", "transit", "sunset")],
                             [None] * 4, args)
            self.assertTrue(math.isfinite(r["elevation_deg"]))
            status, stdout, stderr = run(*args)
            self.assertEqual(status, 0, stderr)
            self.assertIn("Day:         n/a: the local day reaches beyond the years -2000..6000",
                          stdout)
            self.assertNotIn("None", stdout)
        # a UTC+0 zone's last day ends at the end of the years: it lies within them
        for zone in ("UTC", "Europe/London"):
            r = self.json_of("--at", "6000-12-31T12:00", "--tz", zone, "--lat", 0, "--lon", 0)
            self.assertEqual(r["day_kind"], "normal", zone)
            self.assertTrue(r["sunrise"] < r["transit"] < r["sunset"] < "6001", zone)
        # one object, first a polar day, then such a day: its day kind is not the polar day's
        import aperture
        sun = aperture.vtkApertureSolarPosition()
        sun.SetLatitude(1.87)
        sun.SetLongitude(-157.4)
        self.assertTrue(sun.SetTime("2025-06-21T22:30Z"))
        sun.SetLatitude(69.6492)
        self.assertTrue(sun.Compute())
        self.assertEqual(sun.GetDayKind(), 1)
        sun.SetLatitude(1.87)
        self.assertTrue(sun.SetTimeZone("Pacific/Kiritimati"))
        self.assertTrue(sun.SetTime("6000-12-31T20:00Z"))
        self.assertTrue(sun.Compute())
        self.assertEqual(sun.GetDayKind(), -1)
        self.assertTrue(math.isnan(sun.GetTransit()))
        self.assertTrue(sun.ComputeForDirection(100.0, 20.0))
        self.assertEqual(sun.GetDayKind(), -1)

    def test_dem_frame(self):
        # A UTM 33N DEM centred 2.9 deg east of the central meridian at 60 N.
        lat, lon = 60.0, 17.9
        srs = osr.SpatialReference()
        srs.ImportFromEPSG(32633)
        wgs = osr.SpatialReference()
        wgs.ImportFromEPSG(4326)
        wgs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
        x, y, _ = osr.CoordinateTransformation(wgs, srs).TransformPoint(lon, lat)
        with tempfile.TemporaryDirectory() as tmp:
            path = make_dem(os.path.join(tmp, "utm.tif"), np.full((101, 101), 300.0),
                             (x - 50.5 * 100, 100, 0, y + 50.5 * 100, 0, -100), 32633)
            r = self.json_of("--at", "2026-06-21T13:30Z", "--dem", path)
        self.assertAlmostEqual(r["latitude_deg"], lat, delta=1e-6)
        self.assertAlmostEqual(r["longitude_deg"], lon, delta=1e-6)
        self.assertEqual(r["height_m"], 300.0)
        gamma = convergence_tm(lat, lon - 15.0)
        self.assertAlmostEqual(r["meridian_convergence_deg"], gamma, delta=1e-5)
        self.assertAlmostEqual(r["grid_azimuth_deg"], (r["azimuth_deg"] - gamma) % 360, delta=1e-5)
        e, nn, u = r["direction_enu"]
        self.assertAlmostEqual(e * e + nn * nn + u * u, 1.0, delta=1e-12)
        self.assertAlmostEqual(math.degrees(math.atan2(e, nn)) % 360, r["azimuth_deg"], delta=1e-9)
        self.assertAlmostEqual(math.degrees(math.asin(u)), r["elevation_deg"], delta=1e-9)

    def test_dem_longitudes_past_180(self):
        # A lat/lon DEM in 0..360 degrees of longitude (190.505 E is 169.495 W): the sun of
        # that place (it failed: "the longitude must be within -180..180 degrees").
        with tempfile.TemporaryDirectory() as tmp:
            path = make_dem(os.path.join(tmp, "east.tif"), np.full((3, 3), 50.0),
                             (190.49, 0.01, 0, 10.01, 0, -0.01), 4326)
            r = self.json_of("--at", "2026-06-21T22:00Z", "--dem", path)
        # (the centre of 3 cells of 0.01 degree from 190.49 E, 10.01 N)
        self.assertAlmostEqual(r["longitude_deg"], -169.495, delta=1e-9)
        self.assertAlmostEqual(r["latitude_deg"], 9.995, delta=1e-9)
        plain = self.json_of("--at", "2026-06-21T22:00Z", "--lat", 9.995, "--lon", -169.495,
                             "--height", 50)
        self.assertAlmostEqual(r["azimuth_deg"], plain["azimuth_deg"], delta=1e-6)
        self.assertAlmostEqual(r["elevation_deg"], plain["elevation_deg"], delta=1e-6)

    def test_dem_larger_than_memory(self):
        # The place of a DEM of 10^12 cells (3.6 TiB as float32): the cells at its centre are
        # read, not the whole grid (a memory error before). A VRT of 1 m cells in UTM 11N,
        # nodata but for 4 x 4 cells of 100 m around its centre.
        with tempfile.TemporaryDirectory() as tmp:
            small = os.path.join(tmp, "centre.tif")
            ds = gdal.GetDriverByName("GTiff").Create(small, 4, 4, 1, gdal.GDT_Float32)
            ds.GetRasterBand(1).WriteArray(np.full((4, 4), 100.0))
            ds = None
            n = 1000000
            vrt = os.path.join(tmp, "huge.vrt")
            with open(vrt, "w") as f:
                f.write('<VRTDataset rasterXSize="%d" rasterYSize="%d">\n'
                        '  <SRS>EPSG:32611</SRS>\n'
                        '  <GeoTransform>0, 1, 0, 4000000, 0, -1</GeoTransform>\n'
                        '  <VRTRasterBand dataType="Float32" band="1">\n'
                        '    <NoDataValue>-1</NoDataValue><SimpleSource>\n'
                        '    <SourceFilename relativeToVRT="0">%s</SourceFilename>\n'
                        '    <SourceBand>1</SourceBand>\n'
                        '    <SrcRect xOff="0" yOff="0" xSize="4" ySize="4"/>\n'
                        '    <DstRect xOff="%d" yOff="%d" xSize="4" ySize="4"/>\n'
                        '    </SimpleSource></VRTRasterBand>\n'
                        '</VRTDataset>\n' % (n, n, small, n // 2 - 2, n // 2 - 2))
            r = self.json_of("--at", "2026-06-21T20:00Z", "--dem", vrt)
        self.assertEqual(r["height_m"], 100.0)
        utm = osr.SpatialReference()
        utm.ImportFromEPSG(32611)
        wgs = osr.SpatialReference()
        wgs.ImportFromEPSG(4326)
        wgs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
        lon, lat, _ = osr.CoordinateTransformation(utm, wgs).TransformPoint(n / 2, 4000000 - n / 2)
        self.assertAlmostEqual(r["longitude_deg"], lon, delta=1e-9)
        self.assertAlmostEqual(r["latitude_deg"], lat, delta=1e-9)

    def test_days_the_clocks_change(self):
        # A local day runs from its midnight to the next: 23 hours on 2026-03-29 in
        # Europe/Zurich, 25 on 2026-10-25. The events were those of 24 hours at the offset of
        # the hour asked about (until 2026-12-06): at 66.3 W in Zurich's zone, 03-29 at 12:00
        # gave the sunset of the 28th (23:33+01:00), at 01:00 that of the 30th (00:33+02:00).
        # Now every event lies within the day (its bounds from Python's zoneinfo), whatever
        # the hour asked about; that day at 66.3 W has no sunset, its neighbours' lying just
        # outside it.
        import zoneinfo
        zone = zoneinfo.ZoneInfo("Europe/Zurich")
        keys = ("sunrise", "transit", "sunset")
        for date, hours in (("2026-03-29", 23), ("2026-10-25", 25)):
            y, m, d = (int(v) for v in date.split("-"))
            first = datetime.datetime(y, m, d, tzinfo=zone)
            last = first + datetime.timedelta(days=1)  # (wall clock: the next midnight)
            start, end = first.timestamp(), last.timestamp()
            self.assertEqual(end - start, hours * 3600)
            for lon in (8.54, -66.3, 100.0):
                days = []
                for clock in ("00:30", "12:00", "23:30"):
                    r = self.json_of("--at", "%sT%s" % (date, clock), "--tz", "Europe/Zurich",
                                     "--lat", 0 if lon != 8.54 else 47.37, "--lon", lon)
                    days.append([r[k] for k in keys])
                    for k in keys:
                        if r[k] is not None:
                            t = datetime.datetime.fromisoformat(
                                r[k].replace("Z", "+00:00")).timestamp()
                            self.assertTrue(start <= t < end, (date, lon, clock, k, r[k]))
                self.assertEqual(days[0], days[1], (date, lon))
                self.assertEqual(days[0], days[2], (date, lon))
                if lon == 8.54:  # (an ordinary place in its zone: every event)
                    self.assertNotIn(None, days[0], date)
        r = self.json_of("--at", "2026-03-29T12:00", "--tz", "Europe/Zurich", "--lat", 0,
                         "--lon", -66.3)
        self.assertIsNone(r["sunset"])
        self.assertEqual(r["day_kind"], "normal")
        before = self.json_of("--at", "2026-03-28T12:00", "--tz", "Europe/Zurich", "--lat", 0,
                              "--lon", -66.3)
        after = self.json_of("--at", "2026-03-30T12:00", "--tz", "Europe/Zurich", "--lat", 0,
                             "--lon", -66.3)
        self.assertEqual(before["sunset_local"][:16], "2026-03-28T23:33")
        self.assertEqual(after["sunset_local"][:16], "2026-03-30T00:33")

    def test_dem_centre_of_nodata(self):
        # The centre's 3 x 3 cells all nodata: the height is the nearest valid cell's. The
        # whole grid was to be read then, but the reader's request stayed the centre's, so the
        # height was 0 with no word (until 2026-12-06). 9 x 9 cells of 30 m, 100 + 10 row +
        # column, a void over rows 2..6 and columns 3..6: the nearest valid cell to the centre
        # (4, 4) is (4, 2), 60 m west (the others are 90 m away).
        z = 100.0 + np.add.outer(10.0 * np.arange(9), np.arange(9))
        z[2:7, 3:7] = np.nan
        with tempfile.TemporaryDirectory() as tmp:
            path = make_dem(os.path.join(tmp, "void.tif"), z, (500000, 30, 0, 5200000, 0, -30),
                             32633)
            r = self.json_of("--at", "2026-06-21T12:00Z", "--dem", path)
        self.assertEqual(r["height_m"], 142.0)

    def test_height_range(self):
        # one limit, said at once (20 km passed the position, then the light refused it)
        for h in ("20000", "-1001", "nan"):
            err = self.usage_error_of("--at", "2026-06-21T12:00Z", "--lat", 47, "--lon", 8,
                                "--height", h)
            self.assertIn("--height must be within -1000..10000 m, the range of the sunlight "
                          "and sky models", err)

    def test_dem_reading_options(self):
        # The reading options of the other commands: a two-band DEM in feet without a CRS.
        srs = osr.SpatialReference()
        srs.ImportFromEPSG(32633)
        wgs = osr.SpatialReference()
        wgs.ImportFromEPSG(4326)
        wgs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
        to_wgs = osr.CoordinateTransformation(srs, wgs)
        x0, y0, n, cell = 600000.0, 6650000.0, 100, 100.0
        at = ["--at", "2026-06-21T13:30Z"]
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "two-bands.tif")
            ds = gdal.GetDriverByName("GTiff").Create(path, n, n, 2, gdal.GDT_Float32)
            ds.SetGeoTransform((x0, cell, 0, y0, 0, -cell))
            ds.GetRasterBand(1).WriteArray(np.full((n, n), 300.0))
            ds.GetRasterBand(2).WriteArray(np.full((n, n), 1000.0))
            ds = None
            self.assertIn("give one with --srs", self.error_of(*at, "--dem", path, "--band", 1))
            r = self.json_of(*at, "--dem", path, "--srs", "EPSG:32633", "--band", 2,
                             "--zfactor", "ft")
            self.assertAlmostEqual(r["height_m"], 304.8, delta=1e-4)
            lon, lat, _ = to_wgs.TransformPoint(x0 + n / 2 * cell, y0 - n / 2 * cell)
            self.assertAlmostEqual(r["latitude_deg"], lat, delta=1e-7)
            self.assertAlmostEqual(r["longitude_deg"], lon, delta=1e-7)
            # the window's centre: its 10 x 20 cells from column 30, row 40
            r = self.json_of(*at, "--dem", path, "--srs", "EPSG:32633", "--srcwin", 30, 40,
                             10, 20)
            self.assertEqual(r["height_m"], 300.0)
            lon, lat, _ = to_wgs.TransformPoint(x0 + 35 * cell, y0 - 50 * cell)
            self.assertAlmostEqual(r["latitude_deg"], lat, delta=1e-7)
            self.assertAlmostEqual(r["longitude_deg"], lon, delta=1e-7)
            # (and the text says the place is the window's centre: it said the file's until
            # 2026-12-07)
            status, out, err = run(*at, "--dem", path, "--srs", "EPSG:32633", "--srcwin", 30,
                                   40, 10, 20)
            self.assertEqual(status, 0, err)
            self.assertIn("Place:       latitude %.6f, longitude %.6f, height 300.0 m (centre of "
                          "--srcwin 30 40 10 20 of %s)" % (lat, lon, path), out)
        self.assertIn("--band, --zfactor read the DEM: give one with --dem",
                      self.usage_error_of(*at, "--lat", 60, "--lon", 18, "--band", 2,
                                          "--zfactor", 1))

    def test_time_series(self):
        status, out, err = run("--at", "2026-06-21T00:00", "--tz", "Europe/Zurich",
                               "--lat", 47.3769, "--lon", 8.5417, "--days", 2, "--step", 30)
        self.assertEqual(status, 0, err)
        lines = out.strip().splitlines()
        self.assertEqual(lines[0].split("\t")[:4], ["time_utc", "time_local", "azimuth",
                                                    "elevation"])
        self.assertEqual(len(lines), 1 + 2 * 48)
        self.assertEqual(lines[1].split("\t")[0], "2026-06-20T22:00:00Z")
        self.assertEqual(lines[-1].split("\t")[1], "2026-06-22T23:30:00+02:00")
        elevations = [float(l.split("\t")[3]) for l in lines[1:]]
        self.assertGreater(max(elevations), 65.0)   # noon near the solstice at 47 N
        self.assertLess(min(elevations), -18.0)     # midnight
        # Local days with --tz: from midnight to midnight, 25 hourly rows on the day New York's
        # clocks go back (01:00 twice) and 23 on the day they go forward (no 02:00); a day of
        # 24 hours gave 24 rows on both, ending at 22:00 or at 00:00 of the next day, until
        # 2026-12-06. Two days across the autumn change: 49 rows.
        for day, days, rows, clocks in (
                ("2026-11-01", 1, 25, ["00:00-04:00", "01:00-04:00", "01:00-05:00",
                                       "23:00-05:00"]),
                ("2026-03-08", 1, 23, ["00:00-05:00", "01:00-05:00", "03:00-04:00",
                                       "23:00-04:00"]),
                ("2026-10-31", 2, 49, ["00:00-04:00", "23:00-05:00"])):
            status, out, err = run("--at", day + "T00:00", "--tz", "America/New_York", "--lat",
                                   40.7, "--lon", -74.0, "--days", days, "--step", 60)
            self.assertEqual(status, 0, err)
            local = [l.split("\t")[1][11:16] + l.split("\t")[1][19:]
                     for l in out.strip().splitlines()[1:]]
            self.assertEqual(len(local), rows, day)
            self.assertEqual(local[:len(clocks) - 1], clocks[:-1], day)
            self.assertEqual(local[-1], clocks[-1], day)
        # The series ends where Python's zoneinfo puts the same clock time N days on (fold 0:
        # the first of two, or a skipped time read with the offset before the jump): Samoa
        # and Tokelau skipped 2011-12-30 and Kiritimati 1994-12-31 (a single row, until
        # 2026-12-06), Santiago, Havana and Beirut skip a midnight (an hour short), New York
        # skips 02:30 the day after the start.
        from zoneinfo import ZoneInfo
        for zone, at, days in (
                ("Pacific/Apia", "2011-12-29T00:00", 1), ("Pacific/Apia", "2011-12-28T12:00", 2),
                ("Pacific/Fakaofo", "2011-12-29T06:00", 1),
                ("Pacific/Kiritimati", "1994-12-30T06:00", 1),
                ("America/Santiago", "2026-09-05T00:00", 1),
                ("America/Havana", "2026-03-07T00:00", 1),
                ("Asia/Beirut", "2026-03-28T00:00", 1),
                ("America/New_York", "2026-03-07T02:30", 1),
                ("America/New_York", "2026-10-31T01:30", 1),
                ("Europe/London", "2026-03-28T00:30", 3)):
            first = datetime.datetime.fromisoformat(at).replace(tzinfo=ZoneInfo(zone))
            end = (first + datetime.timedelta(days=days)).timestamp()  # (wall clock, fold 0)
            hours = math.ceil((end - first.timestamp()) / 3600.0)
            status, out, err = run("--at", at, "--tz", zone, "--lat", 0, "--lon", 0, "--days",
                                   days, "--step", 60)
            self.assertEqual(status, 0, err)
            rows = out.strip().splitlines()[1:]
            self.assertEqual(len(rows), hours, (zone, at))
            self.assertGreaterEqual(hours, 23 * days, (zone, at))
            last = datetime.datetime.fromisoformat(rows[-1].split("\t")[0].replace("Z", "+00:00"))
            self.assertEqual(last.timestamp(), first.timestamp() + (hours - 1) * 3600, (zone, at))
        status, out, err = run("--at", "2026-06-21T00:00Z", "--lat", 0, "--lon", 0,
                               "--step", 360, "--json")
        self.assertEqual(status, 0, err)
        self.assertEqual(len(json.loads(out)), 4)
        # A step longer than the series: the start alone (was no row at all); a step that does
        # not divide the days: every time before the end.
        for extra, times in ((["--step", 2000], ["2026-06-21T00:00:00Z"]),
                             (["--step", 1000], ["2026-06-21T00:00:00Z", "2026-06-21T16:40:00Z"]),
                             (["--step", 1000, "--json"], ["2026-06-21T00:00:00Z",
                                                           "2026-06-21T16:40:00Z"])):
            status, out, err = run("--at", "2026-06-21T00:00Z", "--lat", 0, "--lon", 0, *extra)
            self.assertEqual(status, 0, err)
            if "--json" in extra:
                got = [r["time_utc"] for r in json.loads(out)]
            else:
                got = [l.split("\t")[0] for l in out.strip().splitlines()[1:]]
            self.assertEqual(got, times, extra)
        # The JSON list is streamed, as json.dumps(records, indent=1) prints it.
        status, out, err = run("--at", "2026-06-21T00:00Z", "--lat", 0, "--lon", 0,
                               "--step", 360, "--json")
        self.assertEqual(out, json.dumps(json.loads(out), indent=1) + "\n")

    def test_errors(self):
        place = ["--lat", 47, "--lon", 8]
        usage = self.usage_error_of
        noon = "2026-06-21T12:00Z"
        self.assertIn("argument --lat: 91 is outside -90..90 degrees",
                      usage("--at", noon, "--lat", 91, "--lon", 8))
        self.assertIn("argument --lon: 181 is outside -180..180 degrees",
                      usage("--at", noon, "--lat", 47, "--lon", 181))
        self.assertIn("not a valid ISO 8601", usage("--at", "noon", *place))
        self.assertIn("February 2026 has 28 days", usage("--at", "2026-02-30T12:00Z", *place))
        self.assertIn("-2000..6000", usage("--at", "9999-01-01T00:00Z", *place))
        self.assertIn("unknown", usage("--at", "2026-06-21T12:00", "--tz", "Europe/Atlantis",
                                       *place))
        self.assertIn("no UTC offset", usage("--at", "2026-06-21T12:00", *place))
        self.assertIn("--lat DEG --lon DEG", usage("--at", noon))
        self.assertIn("not both", usage("--at", noon, "--dem", "x.tif", *place))
        self.assertIn("argument --turbidity: 50 is outside 2..10",
                      usage("--at", noon, "--turbidity", 50, *place))
        self.assertIn("--days", usage("--at", noon, "--days", 0, *place))
        # A step below a second: 1e-300 minutes would not move the time (a series for ever).
        self.assertIn("--step must be a number of minutes of at least one second's, 1/60 "
                      "(0.016666667)",
                      usage("--at", noon, "--step", "1e-300", *place))
        # A series running past the year 6000 fails before it prints a row (it failed after
        # 1.9 million rows) and names the year it reaches.
        # (a fact of the options alone: a usage error since 2026-12-06, as --at 7000-01-01 is)
        err = usage("--at", "2026-06-21T12:00Z", "--days", 2000000, "--step", 1, *place)
        self.assertIn("the series over 2000000 days from 2026-06-21T12:00Z ends too late: the "
                      "time in the year 7502 is outside the years the algorithm covers", err)
        # (in a series too, as itself, not as the series' end)
        for series in ((), ("--days", 2)):
            self.assertEqual("aperture sun: error: argument --pressure: -1 is outside 0..5000 "
                             "hPa\n", self.usage_error_of("--at", "2026-06-21T12:00Z",
                                                          "--pressure", -1, *series, *place))
        # (-273..6000 C, SPA's, until 2026-12-07: at -272.9 the refraction lifted the sun by
        # 21 degrees, or past the zenith, "a zenith angle of -290 degrees")
        self.assertIn("argument --temperature: -272.9 is outside -100..100 C",
                      self.usage_error_of("--at", "2026-06-21T12:00Z", "--temperature",
                                          -272.9, *place))
        self.assertIn("argument --linke-turbidity: nan is outside 1..8",
                      self.usage_error_of("--at", "2026-06-21T12:00Z", "--linke-turbidity",
                                          "nan", *place))
        # the limits themselves are taken, by this check and the filter's alike
        self.json_of("--at", "2026-06-21T12:00Z", "--lat", -90, "--lon", 180, "--pressure", 0,
                     "--temperature", -100, "--turbidity", 10, "--linke-turbidity", 8)
        self.json_of("--at", "2026-06-21T12:00Z", "--lat", 90, "--lon", -180, "--pressure",
                     5000, "--temperature", 100, "--turbidity", 2, "--linke-turbidity", 1)
        self.assertIn("does not exist", self.error_of("--at", "2026-06-21T12:00Z",
                                                      "--dem", "/nonexistent/dem.tif"))


if __name__ == "__main__":
    unittest.main()
