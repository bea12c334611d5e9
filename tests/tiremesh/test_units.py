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


# --- issue 12: units always explicit at the edges ---------------------------------------


@pytest.mark.parametrize("text", ["60", "0.4", 60, 0.4, "4 "])
def test_parse_pressure_require_unit_refuses_a_bare_number(text):
    with pytest.raises(tm.InvalidParameter, match=r"4bar, 60psi, 400kPa, 0\.4MPa") as info:
        parse_pressure(text, require_unit=True, name="--pressure")
    assert info.value.name == "--pressure"


@pytest.mark.parametrize("text", ["400", 400, "40 "])
def test_parse_force_require_unit_refuses_a_bare_number(text):
    with pytest.raises(tm.InvalidParameter, match="400N, 40kg") as info:
        parse_force(text, require_unit=True, name="--load")
    assert info.value.name == "--load"


@pytest.mark.parametrize(
    ("text", "expected"), [("4bar", 0.4), ("60psi", 60 * 0.00689475728), ("400kPa", 0.4)]
)
def test_parse_pressure_require_unit_accepts_units(text, expected):
    assert_allclose(parse_pressure(text, require_unit=True, positive=True), expected, rtol=1e-12)


@pytest.mark.parametrize("text", ["0bar", "-1bar", "-0.1MPa"])
def test_parse_pressure_positive_refuses_zero_and_negative(text):
    with pytest.raises(tm.InvalidParameter, match="> 0"):
        parse_pressure(text, require_unit=True, positive=True)


@pytest.mark.parametrize("text", ["0N", "-5N", "-1kg"])
def test_parse_force_positive_refuses_zero_and_negative(text):
    with pytest.raises(tm.InvalidParameter, match="> 0"):
        parse_force(text, require_unit=True, positive=True)


def test_parse_force_library_defaults_stay_backward_compatible():
    # library callers (sweeps, notebooks) may still pass plain numbers in N and bar
    assert parse_force(400.0) == 400.0 and parse_force("-5") == -5.0
    assert parse_pressure(4.0) == pytest.approx(0.4)


def test_parse_length_require_unit_and_positive():
    with pytest.raises(tm.InvalidParameter, match="25mm"):
        parse_length("25", require_unit=True)
    with pytest.raises(tm.InvalidParameter, match="> 0"):
        parse_length("0mm", positive=True)


def test_parse_pressure_refuses_a_bool():
    with pytest.raises(tm.InvalidParameter, match="pressure"):
        parse_pressure(True)
