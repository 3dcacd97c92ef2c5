# SPDX-License-Identifier: BSD-3-Clause
"""`aperture render` end to end (runs under Xvfb): a PNG of the requested size that is not
blank, for both views, and one-line errors for bad options."""
import os
import subprocess
import sys
import tempfile
import unittest

from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

BUILD = os.environ.get("APERTURE_BUILD_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
APERTURE = os.path.join(BUILD, "bin", "aperture")


def run(*args):
    p = subprocess.run([APERTURE] + [str(a) for a in args], capture_output=True, text=True,
                       timeout=300)
    return p.returncode, p.stdout, p.stderr


class TestCommandLineRender(unittest.TestCase):
    def test_views(self):
        with tempfile.TemporaryDirectory() as tmp:
            for view, size in (("top", (320, 200)), ("oblique", (200, 150))):
                out = os.path.join(tmp, view + ".png")
                status, stdout, stderr = run("render", "-o", out, "--view", view,
                                             "--size", "%dx%d" % size)
                self.assertEqual(status, 0, stderr)
                self.assertIn("wrote " + out, stdout)
                reader = vtkPNGReader()
                reader.SetFileName(out)
                reader.Update()
                image = reader.GetOutput()
                self.assertEqual(image.GetDimensions()[:2], size)
                rgb = vtk_to_numpy(image.GetPointData().GetScalars())[:, :3].astype(float)
                # Terrain, not an empty background: many distinct shades, mostly non-white.
                self.assertGreater(rgb.std(), 20.0)
                self.assertGreater((rgb.sum(axis=1) < 700).mean(), 0.3)

    def test_bad_options(self):
        with tempfile.TemporaryDirectory() as tmp:
            for args, expected in ((("--light-el", "95"), "--sun-el must be within"),
                                   (("--sun-scale", "0"), "--sun-scale must be"),
                                   (("--at", "2026-06-21T12:00Z", "--sun-az", "10"), "not both"),
                                   (("--albedo", "/nonexistent.png"), "does not exist"),
                                   (("--baked", "/nonexistent.tif"), "cannot read the baked"),
                                   (("--exaggeration", "-1"), "--exaggeration must be within"),
                                   (("-o", os.path.join(tmp, "no", "x.png")), "does not exist")):
                status, stdout, stderr = run("render", *args)
                self.assertEqual(status, 1, stderr)
                self.assertEqual(len(stderr.strip().splitlines()), 1, stderr)
                self.assertIn(expected, stderr)
            status, _, stderr = run("render", "--size", "10x10")
            self.assertEqual(status, 2)
            self.assertIn("width and height must be within 16..16384", stderr)


if __name__ == "__main__":
    sys.exit(0 if unittest.main(exit=False).result.wasSuccessful() else 1)
