"""Exception hierarchy of :mod:`inkprint`.

A single call raises; in a batch every one of these becomes an error row for its
file and the batch goes on.
"""

from __future__ import annotations

from typing import Any


class InkPrintError(Exception):
    """Base class of every error raised by :mod:`inkprint`."""


class InvalidInput(InkPrintError, ValueError):
    """A parameter is outside what the function accepts (names the parameter)."""

    def __init__(self, name: str, value: Any, allowed: str) -> None:
        self.name, self.value, self.allowed = name, value, allowed
        super().__init__(f"{name} = {value!r} is invalid: allowed {allowed}")


class ScanReadError(InkPrintError):
    """The file cannot be read as a scan (empty, truncated, not an image, bad PDF)."""


class ImageTooLarge(ScanReadError):
    """The image is larger than ``AnalysisOptions.max_pixels`` (decompression-bomb guard)."""


class ScaleMissing(InkPrintError):
    """No scale: the file has no usable DPI and none was given (``--dpi`` or
    ``--mm-per-px``), and pixels were not asked for."""


class ScaleUntrusted(ScaleMissing):
    """The file's DPI is 72 or 96, the default of cameras and screen software, not a
    scanner's resolution: give ``--dpi`` (or ``--trust-dpi`` if it is right)."""


class NoInk(InkPrintError):
    """No print found on the sheet (blank page, or only specks and marks)."""


class AllInk(InkPrintError):
    """The sheet is (nearly) all ink: no paper to threshold against."""


class OutputLocked(InkPrintError):
    """Another batch is writing the same output table (its lock file is held)."""
