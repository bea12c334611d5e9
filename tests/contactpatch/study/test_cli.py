"""contactpatch.study.cli: the ``contactpatch compare`` and ``report`` commands."""

import subprocess
import sys

from tiremesh.io import read_table


def test_cli_compare_and_report(print_table, tmp_path):
    _, d = print_table
    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "contactpatch.cli",
            "compare",
            str(d / "prints.csv"),
            "-o",
            str(tmp_path / "paired.csv"),
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert out.returncode == 0, out.stderr
    assert len(read_table(tmp_path / "paired.csv")) == 8
    rep = subprocess.run(
        [
            sys.executable,
            "-m",
            "contactpatch.cli",
            "report",
            str(d / "prints.csv"),
            "-o",
            str(tmp_path / "rep"),
            "--no-renders",
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert rep.returncode == 0, rep.stderr
    assert (tmp_path / "rep" / "index.html").is_file()
    bad = subprocess.run(
        [
            sys.executable,
            "-m",
            "contactpatch.cli",
            "report",
            str(tmp_path / "none.csv"),
            "-o",
            str(tmp_path / "x"),
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert bad.returncode == 2 and "Traceback" not in bad.stderr
