"""The code base is ruff-clean (lint and format, configured in pyproject.toml)."""

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def _ruff():
    exe = shutil.which("ruff", path=str(Path(sys.executable).parent)) or shutil.which("ruff")
    if exe is None:
        pytest.skip("ruff is not installed (pip install '.[test]')")
    return exe


@pytest.mark.parametrize("args", [["check", "."], ["format", "--check", "."]])
def test_ruff(args):
    proc = subprocess.run([_ruff(), *args], cwd=ROOT, capture_output=True, text=True)
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_console_script_installed():
    # the README's main job calls the `tiremesh` console script
    if not (Path(sys.prefix) / "bin" / "tiremesh").exists() and shutil.which("tiremesh") is None:
        pytest.skip("package not installed in this environment (pip install '.[test]')")
    exe = shutil.which("tiremesh", path=str(Path(sys.executable).parent)) or shutil.which(
        "tiremesh"
    )
    out = subprocess.run([exe, "--help"], capture_output=True, text=True)
    assert out.returncode == 0 and "solve" in out.stdout
