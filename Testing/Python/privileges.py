# SPDX-License-Identifier: BSD-3-Clause
"""Running a child without root's power over file permissions, for the tests of files it may
not read or write."""
import os
import shutil
import subprocess


def unprivileged(test, path, access):
    """The argv prefix that runs a child unable to `access` ("read" or "write") `path`, which
    the caller made so by its permissions: none for a user other than root; for root, setpriv
    dropping the capabilities that override permissions (a clone may be under /root, which
    another user could not enter). Skips the test where that cannot be had."""
    prefix = []
    if os.geteuid() == 0:
        if not shutil.which("setpriv"):
            test.skipTest("no setpriv (util-linux)")
        prefix = ["setpriv", "--bounding-set", "-dac_override,-dac_read_search,-fowner", "--"]
        if subprocess.run(prefix + ["true"], capture_output=True).returncode != 0:
            # (its own failure, without CAP_SETPCAP, would read as access denied below)
            test.skipTest("setpriv cannot drop capabilities here")
    probe = subprocess.run(prefix + ["sh", "-c", ('cat "$0" > /dev/null' if access == "read"
                                                  else 'true >> "$0"'), path],
                           capture_output=True)
    if probe.returncode == 0:
        test.skipTest("this process may %s %s all the same (capabilities not droppable)"
                      % (access, path))
    return prefix
