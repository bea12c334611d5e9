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

# Public names load on first use (PEP 562): ``import tiremesh.units`` (as inkprint
# does) must not pull in the solver, the relations and the lateral model (~0.4 s).
_LAZY = {
    "BulgeLimit": ".errors",
    "CaseTable": ".case",
    "ContactPatch": ".solver",
    "Disk": ".surface",
    "Drum": ".surface",
    "Flat": ".surface",
    "Footprint": ".footprint",
    "InvalidParameter": ".errors",
    "LateralResult": ".lateral",
    "LoadCase": ".case",
    "LoadTooHigh": ".errors",
    "ModelLimit": ".errors",
    "NoContact": ".errors",
    "NotConverged": ".errors",
    "PatchEndLimit": ".errors",
    "Relation": ".relations",
    "Relaxation": ".case",
    "RimBottoms": ".errors",
    "SectionSolution": ".section",
    "SlipLimit": ".errors",
    "SolverOptions": ".options",
    "Surface": ".surface",
    "SurfaceBase": ".surface",
    "SurfaceTooCurved": ".errors",
    "TireGeometry": ".geometry",
    "TireModelError": ".errors",
    "evaluate_relation": ".relations",
    "find_sinkage": ".solver",
    "find_tire": ".catalog",
    "fit_relations": ".relations",
    "get_tire": ".catalog",
    "load_catalog": ".catalog",
    "max_load": ".solver",
    "parse_surface": ".surface",
    "read_relations": ".relations",
    "register_surface": ".surface",
    "solve": ".solver",
    "solve_lateral": ".lateral",
    "solve_many": ".solver",
    "solve_patch": ".solver",
    "solve_sections": ".section",
    "stiffnesses": ".lateral",
    "tol": "._tol",
    "write_relations": ".relations",
}


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


from .lazy import lazy_attributes  # noqa: E402

__getattr__, __dir__ = lazy_attributes(__name__, globals(), _LAZY)
