# SPDX-License-Identifier: BSD-3-Clause
"""Turn VTK error and warning events into Python exceptions and plain messages.

vtkErrorMacro text looks like "ERROR: In file.cxx, line N\\nvtkClass (0x...): message"; the
command line and scripts want just "message".
"""
import os
import re

from vtkmodules.util.misc import calldata_type
from vtkmodules.vtkCommonCore import (
    VTK_STRING,
    vtkLogger,
    vtkOutputWindow,
    vtkStringOutputWindow,
)


class ApertureError(RuntimeError):
    """A pipeline step failed; the message is the first VTK error it reported."""


_HEADER = re.compile(r"^(?:ERROR|Warning): In .*?, line \d+\s*\n[^\n]*?\(0x[0-9a-fA-F]+\): ",
                     re.S)


def native_path(path):
    """A file name for a VTK object's SetFileName: `path` itself, or its bytes where it is not
    UTF-8 (a name from an older system, in Latin-1, which Python holds with surrogates and
    VTK's wrapping cannot pass as a string)."""
    try:
        path.encode("utf-8")
        return path
    except UnicodeEncodeError:
        return os.fsencode(path)
    except AttributeError:  # (None, bytes)
        return path


def clean_message(text):
    """The message part of a vtkErrorMacro / vtkWarningMacro text."""
    text = _HEADER.sub("", text or "")
    return " ".join(text.split())


def _unpassed(obj):
    """What to say for a message VTK could not pass to Python: one that is not UTF-8, as a file
    name in it may be (VTK then passes None)."""
    name = obj.GetFileName() if hasattr(obj, "GetFileName") else None
    if name is None:
        return "%s failed (its message is not UTF-8 text)" % obj.GetClassName()
    return ("%s failed on '%s' (its message could not be passed on: the file name is not "
            "UTF-8)" % (obj.GetClassName(), os.fsdecode(name)))


def _failure(what, message):
    """The ApertureError of `message`, said of `what` (a step's name) when given."""
    return ApertureError(message if not what else "%s: %s" % (what, message))


class Watcher:
    """Collects the errors and warnings of the VTK objects it watches.

        w = Watcher()
        reader = w.watch(vtkApertureDEMReader())
        w.update(reader)          # raises ApertureError with the reader's message on failure
    """

    def __init__(self, on_warning=None):
        self.errors = []
        self.warnings = []
        self._on_warning = on_warning
        self._failed = []  # the objects that reported the errors not yet raised

    def watch(self, obj):
        obj.AddObserver("ErrorEvent", self._error)
        obj.AddObserver("WarningEvent", self._warning)
        return obj

    @calldata_type(VTK_STRING)
    def _error(self, obj, event, text):
        self.errors.append(clean_message(text) if text is not None else _unpassed(obj))
        self._failed.append(obj)

    @calldata_type(VTK_STRING)
    def _warning(self, obj, event, text):
        message = clean_message(text) if text is not None else _unpassed(obj)
        self.warnings.append(message)
        if self._on_warning:
            self._on_warning(message)

    def clear(self):
        """Forget the errors reported so far (ones expected, and handled by the caller)."""
        self.errors = []
        self._failed = []

    def check(self, what=None):
        """Raise ApertureError if any watched object reported an error. The objects that did
        are marked modified, so that the next update runs them again (VTK's executive would
        otherwise take the failed run as up to date and hand out its empty output)."""
        if self.errors:
            message, failed = self.errors[0], self._failed
            self.clear()
            for obj in failed:
                obj.Modified()
            raise _failure(what, message)

    def update(self, algorithm, what=None, extent=None):
        """algorithm.Update() (algorithm.UpdateExtent(extent) when given: six integers x0, x1,
        y0, y1, z0, z1 within the whole extent, each range not empty), then raise on any
        reported error, or for an extent outside those rules, naming it."""
        if extent is None:
            algorithm.Update()
        else:
            self.update_information(algorithm, what)
            from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline
            whole = algorithm.GetOutputInformation(0).Get(
                vtkStreamingDemandDrivenPipeline.WHOLE_EXTENT())
            extent = list(extent)
            if (whole is None or len(extent) != 6 or
                    any(extent[2 * k] > extent[2 * k + 1] or extent[2 * k] < whole[2 * k] or
                        extent[2 * k + 1] > whole[2 * k + 1] for k in range(3))):
                raise _failure(what, "the extent %s is not a non-empty part of the whole "
                                     "extent %s" % (extent, list(whole) if whole else "(none)"))
            algorithm.UpdateExtent(extent)
        self.check(what)
        return algorithm.GetOutputDataObject(0)

    def update_information(self, algorithm, what=None):
        """algorithm.UpdateInformation(), then raise on any reported error."""
        algorithm.UpdateInformation()
        self.check(what)

    def write(self, writer, what=None):
        """writer.Write(), then raise on any reported error."""
        writer.Write()
        self.check(what)


def quiet_vtk_output():
    """Keep VTK's own console output (its logger, and the executive's follow-up messages) off
    the terminal, so only our one-line messages reach it; returns the string window that
    collects what VTK would have printed."""
    vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_OFF)
    window = vtkStringOutputWindow()
    vtkOutputWindow.SetInstance(window)
    return window
