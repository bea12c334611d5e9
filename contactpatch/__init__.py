"""contactpatch: the ruler for contact patches, and the study of prints vs model.

One definition of length, width, area, hull, shape factor and fitted ellipses
(Dressel 2013, section 4.1.1 and Figure 5-15), shared by the Rotta model's patches
(from :mod:`tiremesh`) and scanned ink prints (:mod:`inkprint`); and the study that
pairs prints with the model (chapter 6). Coordinates in mm.

Two layers; the study uses the ruler, the ruler never imports the study:

``contactpatch.ruler``  measuring: metrics, ellipse fits, the patch cut from a mesh,
                        the model's patch as a region
``contactpatch.study``  pairing prints with model load cases, trends, figures, report,
                        the command line

The measuring layer is named ``ruler``, not ``measure``, because ``measure`` is the
package's main function: a subpackage ``contactpatch.measure`` would be bound to the
same attribute by the import system and could shadow ``contactpatch.measure(...)``.

Public API
----------
All importable from here.

Metrics   : measure, PatchMetrics, as_geometry
Ellipses  : fit_ellipse_direct, fit_ellipse_lsq, ellipse_from_moments, ellipse_from_mask,
            EllipseFit
From mesh : patch_from_mesh, contact_faces, surface_coordinates
Model     : patch_polygon, appendix_points, appendix_ellipse
Study     : case_of, pair_prints, trend_table, sign_agreement, drum_plate_ratios,
            build_report
Validation: validate, report_section (the model vs the measurements of Dressel 2013,
            :mod:`contactpatch.study.validate`)
Errors    : ContactPatchError, InvalidInput, NoPatch (also the module ``errors``)
Tolerances: tol (numerical epsilons only)
"""

__version__ = "0.2.0"

from . import errors
from ._tol import tol
from .errors import ContactPatchError, InvalidInput, NoPatch
from .ruler import (
    EllipseFit,
    PatchMetrics,
    appendix_ellipse,
    appendix_points,
    as_geometry,
    contact_faces,
    ellipse_from_mask,
    ellipse_from_moments,
    fit_ellipse_direct,
    fit_ellipse_lsq,
    measure,
    patch_from_mesh,
    patch_polygon,
    surface_coordinates,
)

# The study (figures, report, validation: ~0.1 s of imports) loads on first use
# (PEP 562): measuring a print (inkprint) needs only the ruler.
_LAZY = {
    "build_report": ".study",
    "case_of": ".study",
    "drum_plate_ratios": ".study",
    "pair_prints": ".study",
    "sign_agreement": ".study",
    "trend_table": ".study",
    "report_section": ".study.validate",
    "validate": ".study.validate",
}

__all__ = [
    "ContactPatchError",
    "EllipseFit",
    "InvalidInput",
    "NoPatch",
    "PatchMetrics",
    "appendix_ellipse",
    "appendix_points",
    "as_geometry",
    "build_report",
    "case_of",
    "contact_faces",
    "drum_plate_ratios",
    "ellipse_from_mask",
    "ellipse_from_moments",
    "errors",
    "fit_ellipse_direct",
    "fit_ellipse_lsq",
    "measure",
    "pair_prints",
    "patch_from_mesh",
    "patch_polygon",
    "report_section",
    "sign_agreement",
    "surface_coordinates",
    "tol",
    "trend_table",
    "validate",
]


from tiremesh.lazy import lazy_attributes  # noqa: E402

__getattr__, __dir__ = lazy_attributes(__name__, globals(), _LAZY)
