"""Issue 12: a sweep writes the catalogue tire id as given (``8``), not ``8.0``."""

import csv

import pytest

from tiremesh.cli import main
from tiremesh.sweep import parse_grid, read_cases


def test_parse_grid_tire_id_stays_an_integer():
    cases = parse_grid("tire=5,8 pressure_bar=4 load_N=304")
    assert [c["tire"] for c in cases] == [5, 8]
    assert all(type(c["tire"]) is int for c in cases)
    assert type(cases[0]["pressure_bar"]) is float  # the quantities stay floats
    assert parse_grid("tire=Schwalbe pressure_bar=4 load_N=304")[0]["tire"] == "Schwalbe"


def test_read_cases_tire_id_stays_an_integer(tmp_path):
    path = tmp_path / "cases.csv"
    path.write_text("tire,pressure_bar,load_N\n8,4,304\n8.0,4.5,304\n")
    cases = read_cases(path)
    assert [c["tire"] for c in cases] == [8, 8] and all(type(c["tire"]) is int for c in cases)
    assert cases[1]["pressure_bar"] == 4.5


def test_sweep_cli_csv_writes_tire_8_not_8_0(tmp_path, capsys):
    out = tmp_path / "s.csv"
    assert main(["-q", "sweep", "--grid", "tire=8 pressure_bar=4 load_N=304", "-o", str(out)]) == 0
    with out.open(newline="") as fh:
        (row,) = list(csv.DictReader(fh))
    assert row["tire"] == "8" and row["status"] == "ok"


def test_sweep_cli_parquet_tire_column_is_int64(tmp_path):
    pq = pytest.importorskip("pyarrow.parquet")
    out = tmp_path / "s.parquet"
    grid = "tire=5,8 pressure_bar=4 load_N=304"
    assert main(["-q", "sweep", "--grid", grid, "-o", str(out)]) == 0
    table = pq.read_table(out)
    assert str(table.schema.field("tire").type) == "int64"
    assert table.column("tire").to_pylist() == [5, 8]
