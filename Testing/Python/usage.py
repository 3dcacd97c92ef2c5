# SPDX-License-Identifier: BSD-3-Clause
"""The command line's usage errors, as the tests expect them."""


def usage_error(test, command, result):
    """The last stderr line of a run (status, stdout, stderr) that must be a usage error of
    `aperture COMMAND`: exit status 2, nothing on stdout, the command's usage, then one line
    naming the mistake (as argparse reports the mistakes it finds itself)."""
    status, out, err = result
    test.assertEqual((status, out), (2, ""), err)
    test.assertTrue(err.startswith("usage: aperture %s " % command), err)
    last = err.strip().splitlines()[-1]
    test.assertTrue(last.startswith("aperture %s: error: " % command), err)
    return last + "\n"
