"""Atomic output and unit parsing for the packages above :mod:`tiremesh` (re-exported
so the package graph stays one-way: inkprint -> contactpatch -> tiremesh)."""

from tiremesh._io import atomic_path, write_text_atomic
from tiremesh.units import (
    MPA_PER_BAR,
    MPA_PER_PSI,
    N_PER_KG,
    parse_force,
    parse_length,
    parse_pressure,
)

__all__ = [
    "MPA_PER_BAR",
    "MPA_PER_PSI",
    "N_PER_KG",
    "atomic_path",
    "parse_force",
    "parse_length",
    "parse_pressure",
    "write_text_atomic",
]
