# SPDX-License-Identifier: BSD-3-Clause
"""The README's Python tour runs as written: its ```python blocks, in order, as one script, in
an empty temporary folder (they write dem.tif and sky.exr there)."""
import os
import re
import subprocess
import sys
import tempfile
import unittest

README = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "README.md")


class ReadmeTourTest(unittest.TestCase):
    def test_tour(self):
        with open(README) as f:
            blocks = re.findall(r"```python\n(.*?)```", f.read(), re.S)
        self.assertGreaterEqual(len(blocks), 3)
        with tempfile.TemporaryDirectory() as tmp:
            script = os.path.join(tmp, "tour.py")
            with open(script, "w") as f:
                f.write("\n".join(blocks))
            p = subprocess.run([sys.executable, script], cwd=tmp, capture_output=True,
                               text=True, timeout=300)
            self.assertEqual(p.returncode, 0, p.stderr[-3000:])
            for name in ("dem.tif", "sky.exr"):
                self.assertTrue(os.path.getsize(os.path.join(tmp, name)) > 1000, name)


if __name__ == "__main__":
    sys.exit(0 if unittest.main(exit=False).result.wasSuccessful() else 1)
