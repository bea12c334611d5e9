"""The ruler: one definition of a contact patch's size and shape.

Measures any region -- a scanned ink print, the Rotta model's patch, the patch cut
from a deformed-tire mesh -- the same way. Imports nothing from
:mod:`contactpatch.study`.

Modules
-------
``metrics``  :func:`measure`, :class:`PatchMetrics`, :func:`as_geometry`
             (print metrics, Dressel 2013 section 4.1.1)
``ellipse``  :class:`EllipseFit` and the fits (section 5.4, Figure 5-15)
``extract``  the patch cut from a mesh: :func:`patch_from_mesh`, :func:`contact_faces`
``model``    the solver's patch as a region and Appendix C's ellipse
"""

from .ellipse import (
    EllipseFit,
    ellipse_from_mask,
    ellipse_from_moments,
    fit_ellipse_direct,
    fit_ellipse_lsq,
)
from .extract import contact_faces, patch_from_mesh, surface_coordinates
from .metrics import PatchMetrics, as_geometry, measure
from .model import appendix_ellipse, appendix_points, patch_polygon

__all__ = [
    "EllipseFit",
    "PatchMetrics",
    "appendix_ellipse",
    "appendix_points",
    "as_geometry",
    "contact_faces",
    "ellipse_from_mask",
    "ellipse_from_moments",
    "fit_ellipse_direct",
    "fit_ellipse_lsq",
    "measure",
    "patch_from_mesh",
    "patch_polygon",
    "surface_coordinates",
]
