"""The report's manifest-only parts started early (issue 13 item 6): the same files
as the report built in one go, whatever the prework got, and never a hang."""

import pytest

from contactpatch import build_report
from contactpatch.study.compare import case_of
from contactpatch.study.prework import Prework
from contactpatch.study.samples import synthetic_print_rows
from contactpatch.study.worker import WorkerError


@pytest.fixture(autouse=True)
def _private_cache(tmp_path, monkeypatch):
    """Workers inherit the environment: no test reads or fills the user's cache."""
    monkeypatch.setenv("ROTTA_CACHE_DIR", str(tmp_path / "cache"))


def _files(folder):
    return {p.relative_to(folder): p.read_bytes() for p in folder.rglob("*") if p.is_file()}


def test_build_report_precomputed_writes_the_same_files(tmp_path):
    rows = synthetic_print_rows(8)
    ref = tmp_path / "ref"
    build_report(rows, ref, renders=True, validation=False)
    pre = Prework(rows, renders=True, validation=False)
    model = pre.result("model")
    assert case_of(rows[0]) in model["cache"]  # solved in the worker
    assert len(model["renders"]) == len(model["cases"]) >= 2
    new = tmp_path / "new"
    build_report(rows, new, renders=True, validation=False, precomputed=pre)
    ref_files, new_files = _files(ref), _files(new)
    assert sorted(new_files) == sorted(ref_files)
    assert any(p.name.startswith("render_") for p in ref_files)
    for name, data in ref_files.items():
        assert new_files[name] == data, name


def test_build_report_precomputed_for_other_cases_changes_nothing(tmp_path):
    rows = synthetic_print_rows(8)
    ref = tmp_path / "ref"
    build_report(rows, ref, renders=False, validation=False)
    other = [dict(r, load_N=float(r["load_N"]) * 1.1) for r in synthetic_print_rows(6, seed=5)]
    new = tmp_path / "new"
    pre = Prework(other, renders=False, validation=False)
    build_report(rows, new, renders=False, validation=False, precomputed=pre)
    assert _files(new) == _files(ref)


def test_prework_result_stops_a_worker_past_its_timeout():
    pre = Prework(synthetic_print_rows(8), renders=False, validation=False, timeout=0.01)
    with pytest.raises(WorkerError, match=r"model_parts\) did not finish within 0.01 s"):
        pre.result("model")
    pre.cancel()  # twice is fine


def test_prework_result_of_a_part_not_started_is_none():
    with Prework(synthetic_print_rows(4), renders=False, validation=False) as pre:
        assert pre.result("validation") is None


def test_model_parts_reads_its_cache_and_recomputes_a_damaged_entry(tmp_path, monkeypatch):
    from contactpatch.study import prework

    monkeypatch.setenv("ROTTA_CACHE_DIR", str(tmp_path / "cache"))
    rows = synthetic_print_rows(4)
    first = prework.model_parts(rows, tmp_path, renders=False)
    (entry,) = (tmp_path / "cache" / "report-model").glob("*.pkl")
    assert entry.stem == prework.parts_key(rows, False)

    def no_solving(*args):
        raise AssertionError("solved again")

    monkeypatch.setattr(prework, "_compute_parts", no_solving)
    again = prework.model_parts(rows, tmp_path, renders=False)
    assert again["cache"] == first["cache"] and again["cases"] == first["cases"]
    entry.write_bytes(b"not a pickle")
    with pytest.raises(AssertionError, match="solved again"):
        prework.model_parts(rows, tmp_path, renders=False)


def test_parts_key_changes_with_the_rows_and_the_render_flag():
    from contactpatch.study.prework import parts_key

    rows = synthetic_print_rows(4)
    key = parts_key(rows, True)
    assert len(key) == 64 and key == parts_key([dict(r) for r in rows], True)
    assert parts_key(rows, False) != key
    assert parts_key([dict(rows[0], load_N=1.0), *rows[1:]], True) != key
