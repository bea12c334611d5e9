"""Tables, atomic outputs and clear output errors (tiremesh.io, issue 12).

Every table is reopened with an independent reader: the csv module, json, pyarrow.
"""

import csv
import json
import math
import os
import sys

import pytest

import tiremesh as tm
from tiremesh.io import (
    MissingDependency,
    OutputError,
    atomic_path,
    check_output_path,
    check_table_path,
    csv_cell,
    read_table,
    write_table,
)

ROWS = [
    {"tire": "big apple", "pressure_bar": 4.0, "load_N": 400, "status": "ok", "note": None},
    {"tire": 5, "pressure_bar": math.nan, "load_N": 9000, "status": "error", "ok": True},
]
INJECTIONS = ['=HYPERLINK("http://x","y")', "+cmd|' /C calc'!A0", "-2+3", "@SUM(A1)", "\tx", "\rx"]


def test_write_table_csv_json_parquet_round_trip(tmp_path):
    pq = pytest.importorskip("pyarrow.parquet")
    paths = [write_table(ROWS, tmp_path / f"t{ext}") for ext in (".csv", ".json", ".parquet")]
    with paths[0].open(newline="", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    assert rows[0]["tire"] == "big apple" and float(rows[0]["pressure_bar"]) == 4.0
    data = json.loads(paths[1].read_text())
    assert data[1]["pressure_bar"] is None and data[1]["ok"] is True
    assert paths[2].read_bytes()[:4] == b"PAR1"
    table = pq.read_table(paths[2])
    assert table.column_names == ["tire", "pressure_bar", "load_N", "status", "note", "ok"]
    assert table.column("tire").to_pylist() == ["big apple", "5"]  # mixed column: text
    assert str(table.schema.field("load_N").type) == "int64"
    p = table.column("pressure_bar").to_pylist()
    assert p[0] == 4.0 and math.isnan(p[1])  # NaN kept as NaN
    assert table.column("ok").to_pylist() == [None, True]
    assert read_table(paths[2])[0]["tire"] == "big apple"


def test_write_table_csv_quotes_formula_cells(tmp_path):
    rows = [{"name": text, "value": -3.5, "text_number": "-1e-3"} for text in INJECTIONS]
    rows.append({"=cmd": "x"})  # a header cell too
    path = write_table(rows, tmp_path / "t.csv")
    with path.open(newline="", encoding="utf-8") as fh:
        got = list(csv.reader(fh))
    assert got[0] == ["name", "value", "text_number", "'=cmd"]
    for text, row in zip(INJECTIONS, got[1:], strict=False):
        assert row[0] == "'" + text
        assert row[1] == "-3.5" and row[2] == "-1e-3"  # real numbers stay numeric


@pytest.mark.parametrize(
    ("value", "written"),
    [
        ("=1+1", "'=1+1"),
        ("-", "'-"),
        ("-3.5", "-3.5"),
        ("+2", "+2"),
        ("-1e-3", "-1e-3"),
        (-3.5, -3.5),
        (None, ""),
        ("plain", "plain"),
        ("a=b", "a=b"),
    ],
)
def test_csv_cell_quotes_text_but_not_numbers(value, written):
    assert csv_cell(value) == written


def test_write_table_json_and_parquet_keep_text_verbatim(tmp_path):
    pytest.importorskip("pyarrow")
    rows = [{"name": text} for text in INJECTIONS]
    assert [r["name"] for r in read_table(write_table(rows, tmp_path / "t.json"))] == INJECTIONS
    assert [r["name"] for r in read_table(write_table(rows, tmp_path / "t.parquet"))] == INJECTIONS


def test_write_table_unknown_extension_refused_before_writing(tmp_path):
    with pytest.raises(tm.InvalidParameter, match=r"\.csv, \.json, \.parquet"):
        write_table(ROWS, tmp_path / "t.xlsx")
    with pytest.raises(tm.InvalidParameter, match="--output"):
        check_table_path(tmp_path / "t.txt", option="--output")
    assert list(tmp_path.iterdir()) == []


def test_write_table_format_overrides_the_suffix(tmp_path):
    path = write_table(ROWS, tmp_path / "t.dat", format="json")
    assert json.loads(path.read_text())[0]["tire"] == "big apple"
    assert read_table(path, format="json")[0]["load_N"] == 400
    with pytest.raises(tm.InvalidParameter, match="format"):
        write_table(ROWS, tmp_path / "t.csv", format="xlsx")


def test_write_table_parquet_without_pyarrow_is_clear(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "pyarrow", None)
    monkeypatch.setitem(sys.modules, "pyarrow.parquet", None)
    with pytest.raises(MissingDependency, match=r"pip install 'rotta-tire\[parquet\]'"):
        check_table_path(tmp_path / "t.parquet")
    with pytest.raises(MissingDependency, match="pyarrow"):
        write_table(ROWS, tmp_path / "t.parquet")
    assert list(tmp_path.iterdir()) == []


def test_read_table_skips_an_excel_bom(tmp_path):
    path = tmp_path / "excel.csv"
    path.write_bytes("\ufefftire,load_N\r\nbig apple,400\r\n".encode())
    assert read_table(path) == [{"tire": "big apple", "load_N": "400"}]


@pytest.mark.parametrize("path", ["/proc/x.csv", "/proc/sub/x.csv"])
def test_write_table_unwritable_path_names_path_and_reason(path):
    with pytest.raises(OutputError) as info:
        write_table(ROWS, path)
    err = info.value
    assert isinstance(err, OSError) and isinstance(err, tm.TireModelError)
    assert err.path == path and path in str(err) and err.reason in str(err)


def test_write_table_folder_as_file_is_refused(tmp_path):
    folder = tmp_path / "t.csv"
    folder.mkdir()
    with pytest.raises(OutputError, match="it is a folder"):
        write_table(ROWS, folder)
    with pytest.raises(OutputError, match="given as -o"):
        check_table_path(folder, option="-o")


def test_check_output_path_parent_is_a_file(tmp_path):
    (tmp_path / "f").write_text("x")
    with pytest.raises(OutputError, match="is a file, not a folder"):
        check_output_path(tmp_path / "f" / "t.csv")


def test_check_output_path_leaves_nothing_behind(tmp_path):
    target = tmp_path / "new" / "t.csv"
    assert check_output_path(target) == target
    assert not target.exists() and list((tmp_path / "new").iterdir()) == []


def test_atomic_path_error_inside_leaves_no_file(tmp_path):
    target = tmp_path / "t.csv"
    with pytest.raises(RuntimeError), atomic_path(target) as tmp:
        tmp.write_text("half")
        raise RuntimeError("interrupted")
    assert list(tmp_path.iterdir()) == []


def test_atomic_path_write_error_names_the_target(tmp_path):
    target = tmp_path / "t.csv"
    with (
        pytest.raises(OutputError, match=f"cannot write {target}: No space left"),
        atomic_path(target),
    ):
        raise OSError(28, os.strerror(28))
    assert list(tmp_path.iterdir()) == []


def test_atomic_path_keeps_other_oserrors(tmp_path):
    # an input that cannot be read inside the block is not an output error
    with pytest.raises(FileNotFoundError), atomic_path(tmp_path / "t.csv"):
        open(tmp_path / "missing.csv")


def test_write_table_csv_carriage_return_cannot_split_a_row(tmp_path):
    rows = [{"a": "x\ry", "b": 1.5}, {"a": "plain", "b": 2}]
    path = write_table(rows, tmp_path / "t.csv")
    with path.open(newline="", encoding="utf-8") as fh:
        got = list(csv.reader(fh))
    assert got == [["a", "b"], ["x\ry", "1.5"], ["plain", "2"]]
