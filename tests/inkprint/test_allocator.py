"""inkprint.allocator: the CLI's and workers' malloc tuning (glibc), in a child
process so the test process itself is left as it was."""

import subprocess
import sys

import pytest


def _run(code: str) -> str:
    return subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout.strip()


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="glibc mallopt only")
def test_keep_freed_memory_tunes_glibc_once():
    out = _run(
        "import platform; from inkprint.allocator import keep_freed_memory as k; "
        "print(platform.libc_ver()[0], k(), k())"
    )
    libc, first, second = out.split()
    if libc != "glibc":
        pytest.skip(f"not glibc: {libc!r}")
    assert (first, second) == ("True", "True")


def test_keep_freed_memory_leaves_results_unchanged(tmp_path):
    # the same sheet measured in a tuned and an untuned process: identical numbers
    from inkprint.synth import PrintSpec, SheetSpec, render_sheet, save_scan

    img, _ = render_sheet(SheetSpec((PrintSpec(60.0, 9.0, (50.0, 40.0)),), size=(100.0, 80.0)))
    path = save_scan(img, tmp_path / "one.png", dpi=150.0)
    code = (
        "import sys; {tune}from inkprint import analyze_scan; "
        f"m = analyze_scan({str(path)!r}).prints[0].metrics; "
        "print(repr((m.length, m.width, m.hull_area)))"
    )
    plain = _run(code.format(tune=""))
    tuned = _run(
        code.format(tune="from inkprint.allocator import keep_freed_memory; keep_freed_memory(); ")
    )
    assert plain == tuned
    assert plain.startswith("(")
