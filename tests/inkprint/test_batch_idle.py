"""The batch's default number of local workers: the idle cores (issue 13, speed)."""

import os

import pytest

from inkprint import batch


@pytest.mark.parametrize(
    ("cores", "load", "expected"),
    [(2, 0.0, 2), (2, 0.4, 2), (2, 0.9, 1), (2, 6.0, 1), (8, 3.0, 5), (4, 0.0, 4)],
)
def test_idle_cores_cpu_count_less_the_load(monkeypatch, cores, load, expected):
    monkeypatch.setattr(os, "cpu_count", lambda: cores)
    monkeypatch.setattr(os, "getloadavg", lambda: (load, load, load))
    assert batch.idle_cores() == expected


def test_run_batch_default_workers_follow_the_load(monkeypatch, tmp_path):
    """A busy machine: no worker processes (the batch runs in this process); an
    explicit ``workers`` is kept as given."""
    seen = []

    def fake_map(func, items, *, workers, **kw):
        seen.append(workers)
        return iter(())

    monkeypatch.setattr(batch, "parallel_map", fake_map)
    monkeypatch.setattr(batch, "idle_cores", lambda: 1)
    (tmp_path / "scans").mkdir()
    (tmp_path / "scans" / "a.png").write_bytes(b"not an image")
    batch.run_batch(tmp_path / "scans", tmp_path / "out.csv", progress=False)
    batch.run_batch(tmp_path / "scans", tmp_path / "out2.csv", progress=False, workers=3)
    assert seen == [1, 3]
