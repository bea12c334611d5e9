"""Exception hierarchy of :mod:`contactpatch`."""

from __future__ import annotations

from typing import Any


class ContactPatchError(Exception):
    """Base class of every error raised by :mod:`contactpatch`."""


class InvalidInput(ContactPatchError, ValueError):
    """An input is outside what the function accepts (names the parameter).

    Parameters
    ----------
    name : str
        The parameter (or table column) at fault.
    value : object
        What was given.
    allowed : str
        What would be accepted, for the message.
    """

    def __init__(self, name: str, value: Any, allowed: str) -> None:
        self.name, self.value, self.allowed = name, value, allowed
        super().__init__(f"{name} = {value!r} is invalid: allowed {allowed}")


class NoPatch(ContactPatchError):
    """No contact patch was found (e.g. no mesh face lies on the support surface)."""
