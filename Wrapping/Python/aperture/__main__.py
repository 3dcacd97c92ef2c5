# SPDX-License-Identifier: BSD-3-Clause
"""`python -m aperture` runs the command line."""
import sys

from aperture.cli import main

sys.exit(main())
