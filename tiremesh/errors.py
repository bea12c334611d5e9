"""Exception hierarchy of :mod:`tiremesh`.

``TireModelError`` is the base; catch it to catch everything the model raises.
"""

from __future__ import annotations

from typing import Any


class TireModelError(Exception):
    """Base class of every error raised by :mod:`tiremesh`."""


class InvalidParameter(TireModelError, ValueError):
    """A parameter is outside the range the model accepts.

    Attributes
    ----------
    name : str
        Parameter name as the caller spelled it.
    value : Any
        The offending value.
    allowed : str
        Human-readable allowed range.
    """

    def __init__(self, name: str, value: Any, allowed: str, detail: str = "") -> None:
        self.name = name
        self.value = value
        self.allowed = allowed
        msg = f"{name} = {value!r} is invalid: allowed {allowed}"
        if detail:
            msg += f" ({detail})"
        super().__init__(msg)


class LoadTooHigh(InvalidParameter):
    """The tire cannot carry the requested load at this pressure.

    Attributes
    ----------
    max_load : float [N]
        Largest vertical load the model carries before a bead reaches the ground.
    """

    def __init__(self, name: str, value: Any, max_load: float, detail: str = "") -> None:
        self.max_load = float(max_load)
        super().__init__(
            name,
            value,
            f"0 < {name} <= {self.max_load:.6g} N (the largest load this tire carries "
            "at this pressure before the rim reaches the ground)",
            detail,
        )


class ModelLimit(InvalidParameter):
    """The input lies beyond a geometric limit of Rotta's construction (chapter 5).

    Attributes
    ----------
    limit : str
        Which limit: ``'rim bottoms'``, ``'bulge out of carcass'``, ``'patch end'``,
        ``'slip beyond contact'`` or ``'surface too curved'``.
    state : dict
        What the solver reached (case index, deflection, the offending section).
    """

    limit = "model limit"

    def __init__(self, name: str, value: Any, allowed: str, state: dict | None = None) -> None:
        self.state = dict(state or {})
        detail = f"{self.limit} reached"
        if self.state:
            detail += "; state: " + ", ".join(
                f"{k}={v:.6g}" if isinstance(v, float) else f"{k}={v!r}"
                for k, v in self.state.items()
            )
        super().__init__(name, value, allowed, detail)


class RimBottoms(ModelLimit):
    """A bead (the rim) would reach the support surface: the deflection is too large."""

    limit = "rim bottoms"


class BulgeLimit(ModelLimit):
    """A side bulge would need more carcass than it has: the section's sideways
    displacement (from camber, slip, lateral displacement or a curved track) is
    beyond Rotta's construction."""

    limit = "bulge out of carcass"


class PatchEndLimit(ModelLimit):
    """The patch end cannot be found: sections beyond where the surface reaches the
    unloaded tire still have a contact width (extreme slip, lateral displacement or
    camber for this tire)."""

    limit = "patch end"


class SlipLimit(ModelLimit):
    """The slip displaces sections inside the patch sideways beyond their contact:
    the tread line turned by the slip angle (``x tan(slip)``, equation 5-17) moves a
    section inside the patch so far that its edges cross (no contact width), so no
    patch carries the load (section 5.4, large slip)."""

    limit = "slip beyond contact"


class SurfaceTooCurved(ModelLimit):
    """A patch end reaches the edge of the curved surface's cross-section along the
    wheel (``R sin(phi) >= R_s``, equations 5-20 and 5-23): the drum or disk track is
    too small for this tire and deflection."""

    limit = "surface too curved"


class NoContact(TireModelError):
    """The tire does not touch the support surface (e.g. zero deflection, or a
    lateral displacement so large that even the central section's edges cross)."""


class NotConverged(TireModelError):
    """An iteration did not converge; ``state`` holds what it reached.

    Attributes
    ----------
    what : str
        The iteration (e.g. ``"friction iteration"``), quoted in the message.
    state : dict of str to Any
        What it reached (residuals, iteration counts, case indices), quoted too.
    """

    def __init__(self, what: str, state: dict[str, Any]) -> None:
        self.what = what
        self.state = state
        parts = ", ".join(f"{k}={v!r}" for k, v in state.items())
        super().__init__(f"{what} did not converge; state reached: {parts}")
