"""tiremesh: Rotta's model of an inflated bicycle tire pressed on a surface.

After A. E. Dressel, *Measuring and Modeling the Mechanical Properties of Bicycle
Tires* (2013), chapter 5 and Appendix C. Units everywhere: mm, N, N/mm^2, rad.

Public API
----------
Load case     : LoadCase, CaseTable, Relaxation, Footprint (plain Rotta patch or the
                rounded print footprint, beyond the dissertation: docs/model.md)
Geometry      : TireGeometry, get_tire, find_tire, load_catalog
Surfaces      : Surface, SurfaceBase, Flat, Drum, Disk, parse_surface, register_surface
Cross section : solve_sections, SectionSolution
Whole tire    : solve, solve_patch, find_sinkage, max_load, solve_many, ContactPatch
Lateral       : solve_lateral, LateralResult, stiffnesses
Relations     : fit_relations, evaluate_relation, write_relations, read_relations, Relation
                (closed-form fits to dense sweeps, docs/relations.md)
Errors        : TireModelError, InvalidParameter, LoadTooHigh, ModelLimit (RimBottoms,
                BulgeLimit, PatchEndLimit, SlipLimit, SurfaceTooCurved), NoContact, NotConverged
Tolerances    : tol (numerical epsilons only); SolverOptions (judgement thresholds,
                passed as options= and sent to workers)
Shared tools  : tiremesh.io (atomic files, tables, figures), tiremesh.parallel,
                tiremesh.units

References
----------
A. E. Dressel, "Measuring and Modeling the Mechanical Properties of Bicycle Tires",
PhD dissertation, University of Wisconsin-Milwaukee, 2013.
"""

from ._tol import tol
from .case import CaseTable, LoadCase, Relaxation
from .catalog import find_tire, get_tire, load_catalog
from .errors import (
    BulgeLimit,
    InvalidParameter,
    LoadTooHigh,
    ModelLimit,
    NoContact,
    NotConverged,
    PatchEndLimit,
    RimBottoms,
    SlipLimit,
    SurfaceTooCurved,
    TireModelError,
)
from .footprint import Footprint
from .geometry import TireGeometry
from .lateral import LateralResult, solve_lateral, stiffnesses
from .options import SolverOptions
from .relations import Relation, evaluate_relation, fit_relations, read_relations, write_relations
from .section import SectionSolution, solve_sections
from .solver import ContactPatch, find_sinkage, max_load, solve, solve_many, solve_patch
from .surface import Disk, Drum, Flat, Surface, SurfaceBase, parse_surface, register_surface

__version__ = "0.2.0"

__all__ = [
    "BulgeLimit",
    "CaseTable",
    "ContactPatch",
    "Disk",
    "Drum",
    "Flat",
    "Footprint",
    "InvalidParameter",
    "LateralResult",
    "LoadCase",
    "LoadTooHigh",
    "ModelLimit",
    "NoContact",
    "NotConverged",
    "PatchEndLimit",
    "Relation",
    "Relaxation",
    "RimBottoms",
    "SectionSolution",
    "SlipLimit",
    "SolverOptions",
    "Surface",
    "SurfaceBase",
    "SurfaceTooCurved",
    "TireGeometry",
    "TireModelError",
    "evaluate_relation",
    "find_sinkage",
    "find_tire",
    "fit_relations",
    "get_tire",
    "load_catalog",
    "max_load",
    "parse_surface",
    "read_relations",
    "register_surface",
    "solve",
    "solve_lateral",
    "solve_many",
    "solve_patch",
    "solve_sections",
    "stiffnesses",
    "tol",
    "write_relations",
]
