# SPDX-License-Identifier: BSD-3-Clause
"""A command run with its stderr on a terminal (a pseudo-terminal), for the tests of what the
command line shows only there (GDAL-style progress)."""
import os
import pty
import subprocess


def run_with_terminal_stderr(argv, timeout):
    """Run argv with stdout piped and stderr on a new pseudo-terminal; returns (the completed
    process, its stdout text in .stdout, and every byte it wrote to the terminal: newlines
    arrive as CR LF)."""
    master, slave = pty.openpty()
    try:
        p = subprocess.run(argv, stdout=subprocess.PIPE, stderr=slave, text=True,
                           timeout=timeout)
    finally:
        os.close(slave)
    seen = b""
    try:
        while True:
            try:
                chunk = os.read(master, 4096)
            except OSError:  # EIO: the child's end is closed
                break
            if not chunk:
                break
            seen += chunk
    finally:
        os.close(master)
    return p, seen
