# SPDX-License-Identifier: BSD-3-Clause
"""Fuzz the DEM and EXR readers with damaged files: a bake of a corner of the embedded DEM
(a GeoTIFF and an EXR) is mutated (bytes changed in the header or anywhere, or the file cut
short), and each mutant is read in a child process, so that a crash (a signal) or a hang
(over 30 s) is caught and its file kept. Run on purpose, not in the test suite:

    build/bin/aperture-python Utilities/fuzz_readers.py [--count N] [--seed S] [--keep DIR]

Prints, per format, how many mutants were read, refused with an error, crashed or hung;
exit status 1 when any crashed or hung (their files are left in --keep).
"""
import argparse
import os
import random
import shutil
import subprocess
import sys
import tempfile

# The child: 0 read, 3 refused with an error (VTK's error output is silenced); a signal or
# any other status is a failure of the reader.
CHILD = """
import sys
import aperture
from vtkmodules.vtkCommonCore import vtkObject
vtkObject.GlobalWarningDisplayOff()
reader = (aperture.vtkApertureEXRReader() if sys.argv[1].endswith(".exr")
          else aperture.vtkApertureDEMReader())
reader.SetFileName(sys.argv[1])
ok = reader.GetExecutive().Update() and reader.GetOutput().GetNumberOfPoints() > 0
sys.exit(0 if ok else 3)
"""


def seeds(folder):
    """A GeoTIFF and an EXR of the bake of a 40 x 30 corner of the embedded DEM."""
    import aperture
    tif, exr = os.path.join(folder, "seed.tif"), os.path.join(folder, "seed.exr")
    subprocess.run([sys.executable, "-m", "aperture", "bake", aperture.default_dem(), tif,
                    "--srcwin", "10", "10", "40", "30", "--radius", "500", "--exr", exr, "-q"],
                   check=True)
    return [tif, exr]


def mutate(data, rng):
    b = bytearray(data)
    mode = rng.random()
    if mode < 0.8:  # bytes changed: in the header (the first 2000), or anywhere
        span = min(len(b), 2000) if mode < 0.5 else len(b)
        for _ in range(rng.randint(1, 8)):
            b[rng.randrange(span)] = rng.randrange(256)
        return bytes(b)
    return bytes(b[:rng.randrange(len(b))])  # cut short


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--count", type=int, default=300, help="mutants per format")
    parser.add_argument("--seed", type=int, default=1, help="random seed")
    parser.add_argument("--keep", default="fuzz-failures",
                        help="folder for the files that crashed or hung a reader")
    args = parser.parse_args()
    rng = random.Random(args.seed)
    failures = 0
    with tempfile.TemporaryDirectory() as work:
        child = os.path.join(work, "read.py")
        with open(child, "w") as f:
            f.write(CHILD)
        for seed in seeds(work):
            data = open(seed, "rb").read()
            ext = os.path.splitext(seed)[1]
            counts = {"read": 0, "refused": 0, "crashed": 0, "hung": 0}
            for k in range(args.count):
                path = os.path.join(work, "mutant%05d%s" % (k, ext))
                with open(path, "wb") as f:
                    f.write(mutate(data, rng))
                try:
                    status = subprocess.run([sys.executable, child, path], capture_output=True,
                                            timeout=30).returncode
                    kind = {0: "read", 3: "refused"}.get(status, "crashed")
                except subprocess.TimeoutExpired:
                    kind = "hung"
                counts[kind] += 1
                if kind in ("crashed", "hung"):
                    failures += 1
                    os.makedirs(args.keep, exist_ok=True)
                    shutil.copy(path, args.keep)
                    print("%s: %s" % (kind, os.path.join(args.keep, os.path.basename(path))))
                os.remove(path)
            print("%s: %d mutants: %s" % (ext, args.count, ", ".join(
                "%d %s" % (n, kind) for kind, n in counts.items())))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
