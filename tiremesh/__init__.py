"""tiremesh: Rotta's model of an inflated bicycle tire pressed on a surface.

After A. E. Dressel, *Measuring and Modeling the Mechanical Properties of Bicycle
Tires* (2013), chapter 5 and Appendix C. Units everywhere: mm, N, N/mm^2, rad.

Public API
----------
Geometry      : TireGeometry, get_tire, find_tire, load_catalog
Cross section : solve_sections, SectionSolution
Whole tire    : solve, solve_patch, find_sinkage, max_load, solve_many, ContactPatch
Surfaces      : Flat, Drum, Disk, parse_surface
Errors        : TireModelError, InvalidParameter, LoadTooHigh, NoContact, NotConverged
Tolerances    : tol
"""

from ._tol import tol
from .catalog import find_tire, get_tire, load_catalog
from .errors import InvalidParameter, LoadTooHigh, NoContact, NotConverged, TireModelError
from .geometry import TireGeometry
from .load import find_sinkage, max_load, solve, solve_many
from .patch import ContactPatch, solve_patch
from .section import SectionSolution, solve_sections
from .surface import Disk, Drum, Flat, parse_surface

__version__ = "0.1.0"

__all__ = [
    "ContactPatch",
    "Disk",
    "Drum",
    "Flat",
    "InvalidParameter",
    "LoadTooHigh",
    "NoContact",
    "NotConverged",
    "SectionSolution",
    "TireGeometry",
    "TireModelError",
    "find_sinkage",
    "find_tire",
    "get_tire",
    "load_catalog",
    "max_load",
    "parse_surface",
    "solve",
    "solve_many",
    "solve_patch",
    "solve_sections",
    "tol",
]
