"""contactpatch: contact-patch polygons, metrics and ellipse fits.

One definition of length, width, area, hull, shape factor and fitted ellipses,
shared by the Rotta model's patches (from :mod:`tiremesh`) and scanned ink prints.
Coordinates in mm (any consistent unit works).

Public API
----------
Metrics   : measure, PatchMetrics, as_geometry
Ellipses  : fit_ellipse_direct, fit_ellipse_lsq, ellipse_from_moments, ellipse_from_mask,
            EllipseFit
From mesh : patch_from_mesh, contact_faces
Model     : patch_polygon, appendix_points, appendix_ellipse
Compare   : pair_prints (compare.py), trend_table / sign_agreement / drum_plate_ratios (trends.py),
            build_report (report.py)
Errors    : ContactPatchError, InvalidInput, NoPatch
Tolerances: tol
"""

__version__ = "0.1.0"

from ._tol import tol
from .compare import pair_prints
from .ellipse import (
    EllipseFit,
    ellipse_from_mask,
    ellipse_from_moments,
    fit_ellipse_direct,
    fit_ellipse_lsq,
)
from .errors import ContactPatchError, InvalidInput, NoPatch
from .extract import contact_faces, patch_from_mesh
from .metrics import PatchMetrics, as_geometry, measure
from .model import appendix_ellipse, appendix_points, patch_polygon

__all__ = [
    "ContactPatchError",
    "EllipseFit",
    "InvalidInput",
    "NoPatch",
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
    "pair_prints",
    "patch_from_mesh",
    "patch_polygon",
    "tol",
]
