"""Load cases on which the deformed-tire mesh is checked against the solver's patch.

Shared by ``tests/tiremesh/test_mesh.py`` and ``tests/contactpatch/test_mesh_cut.py``
(one table, so both test the same cases): a 37-622 tire at 400 N and 0.4 N/mm^2 on
every surface kind, with and without camber, and one case with lateral slip.
"""

import math

import tiremesh as tm

T37 = tm.TireGeometry.from_size(37, 18.7)
LOAD_N, PRESSURE = 400.0, 0.4  # [N], [N/mm^2]
CASES = {
    "flat": dict(),
    "flat-camber30": dict(camber=math.radians(30)),
    "drum": dict(surface=tm.Drum(2500)),
    "drum-camber30": dict(surface=tm.Drum(2500), camber=math.radians(30)),
    "disk-toward-camber30": dict(surface=tm.Disk(3000, "toward"), camber=math.radians(30)),
    "disk-away": dict(surface=tm.Disk(3000, "away")),
    "lateral-slip": dict(lateral=0.5, slip=math.radians(1)),
}


def solve_case(name: str):
    """The solver's patch of case ``name`` of :data:`CASES`."""
    return tm.solve(T37, load=LOAD_N, pressure=PRESSURE, **CASES[name])
