"""Unit parsing at the CLI edge (units.py)."""

import pytest
from numpy.testing import assert_allclose

import tiremesh as tm
from tiremesh.units import parse_force, parse_length, parse_pressure


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("4bar", 0.4),
        ("4 bar", 0.4),
        ("100psi", 0.689475728),
        ("400kPa", 0.4),
        ("0.4MPa", 0.4),
        (4, 0.4),
        ("4", 0.4),
    ],
)
def test_parse_pressure(text, expected):
    assert_allclose(parse_pressure(text), expected, rtol=1e-12)


@pytest.mark.parametrize(
    ("text", "expected"), [("400N", 400.0), ("31kg", 304.11), ("1kN", 1000.0), ("400", 400.0)]
)
def test_parse_force(text, expected):
    # section 4.1.1: 31 kg is 304 N (g = 9.81 m/s^2, Appendix C)
    assert_allclose(parse_force(text), expected, rtol=1e-12)


def test_parse_length():
    assert parse_length("2.5m") == 2500.0
    assert parse_length("25.4") == 25.4


@pytest.mark.parametrize("text", ["4 furlongs", "bar", "", "nan", "1e999bar"])
def test_parse_pressure_invalid(text):
    with pytest.raises(tm.InvalidParameter, match="pressure"):
        parse_pressure(text)


def test_bar_is_one_constant_at_every_edge():
    from tiremesh.sweep import case_from_row
    from tiremesh.units import MPA_PER_BAR

    assert parse_pressure("1bar") == MPA_PER_BAR
    case = tm.LoadCase.from_units(tm.get_tire(5), pressure_bar=4.0, load_N=400.0)
    assert case.pressure == 4.0 * MPA_PER_BAR
    assert case_from_row(dict(tire=5, pressure_bar=4.0, load_N=400.0)).pressure == case.pressure
    assert case.describe()["pressure_bar"] == 4.0
