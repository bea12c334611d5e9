"""The study: ink prints held against the Rotta model (Dressel 2013, chapter 6).

Uses the ruler (:mod:`contactpatch.ruler`) and :mod:`tiremesh`; nothing below it
imports from here.

Modules
-------
``compare``  pairing of prints with model load cases: :func:`case_of`,
             :func:`pair_prints` (section 6.2, Figure 6-3)
``trends``   exponents with pressure and load, sign counts (6.2.4), drum / plate
             ratios (Table 4-1), rim-width sensitivity
``figures``  the report's matplotlib figures
``report``   :func:`build_report` in named steps; ``pages``: its HTML and Markdown
``cli``      the ``contactpatch compare`` and ``contactpatch report`` commands
"""

from .compare import case_of, pair_prints, solve_case
from .report import build_report
from .trends import (
    describe_agreement,
    drum_plate_ratios,
    power_law_fit,
    rim_sensitivity,
    sign_agreement,
    trend_table,
)

__all__ = [
    "build_report",
    "case_of",
    "describe_agreement",
    "drum_plate_ratios",
    "pair_prints",
    "power_law_fit",
    "rim_sensitivity",
    "sign_agreement",
    "solve_case",
    "trend_table",
]
