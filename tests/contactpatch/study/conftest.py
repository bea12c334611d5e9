"""Shared fixture of the study's tests: a print table from the bundled scans."""

import csv
import shutil
from pathlib import Path

import pytest

from inkprint.batch import Options, run_batch
from tiremesh.io import read_table

SAMPLES = Path(__file__).resolve().parents[3] / "assets" / "prints"


@pytest.fixture(scope="session")
def print_table(tmp_path_factory):
    """A batch table of a subset of the bundled scans (one tire, 4 sheets, 8 prints)."""
    d = tmp_path_factory.mktemp("subset")
    for f in sorted(SAMPLES.glob("tire06_*.jpg")):
        shutil.copy(f, d / f.name)
    manifest = [r for r in read_table(SAMPLES / "manifest.csv") if r["file"].startswith("tire06_")]
    with (d / "manifest.csv").open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(manifest[0]))
        w.writeheader()
        w.writerows(manifest)
    res = run_batch(
        None,
        d / "prints.csv",
        manifest=d / "manifest.csv",
        options=Options(sensitivity=False),
        workers=2,
        progress=False,
    )
    return res.rows, d
