"""The Rotta model around the wheel: kinematics, patch ends, load search (sections
5.2, 5.3, 5.4 and 5.5, Appendix C).

Modules, in the order a solve runs through them:

``arrays``      load cases as (m, 1) arrays, grouped by surface
``kinematics``  section displacements (equations 5-14, 5-15, 5-17, 5-18, 5-21),
                sections, ground map
``ends``        patch ends (5.2) and the track offset of a curved track (5.3.2)
``load``        the wheel deflection that carries a load (Appendix C ``find_sinkage``)
``evaluate``    sections between the ends, area, forces, outline (equations 5-25,
                5-26)
``patch``       :class:`ContactPatch`, the result for one case
``api``         :func:`solve`, :func:`solve_many`, :func:`find_sinkage`, :func:`max_load`

Public API
----------
solve, solve_patch, solve_many, find_sinkage, max_load, ContactPatch,
clenshaw_curtis, section_to_ground, area_jacobian
"""

from .api import find_sinkage, max_load, solve, solve_many, solve_patch
from .kinematics import area_jacobian, section_to_ground
from .patch import ContactPatch
from .quadrature import clenshaw_curtis

__all__ = [
    "ContactPatch",
    "area_jacobian",
    "clenshaw_curtis",
    "find_sinkage",
    "max_load",
    "section_to_ground",
    "solve",
    "solve_many",
    "solve_patch",
]
