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


def test_main_conventions_version_exit_codes_and_errors(tmp_path, capsys):
    import contactpatch
    from contactpatch.study.cli import main

    assert main(["--version"]) == 0
    assert contactpatch.__version__ in capsys.readouterr().out
    assert main(["compare", str(tmp_path / "missing.csv"), "-o", str(tmp_path / "p.csv")]) == 2
    assert "missing.csv" in capsys.readouterr().err
    prints = tmp_path / "prints.csv"
    prints.write_text("file,tire,length_mm\na.png,5,100\n")
    assert main(["compare", str(prints), "-o", "/proc/x.csv"]) == 2
    assert "cannot write /proc/x.csv" in capsys.readouterr().err
    assert main(["compare", str(prints), "-o", str(tmp_path / "p.xlsx")]) == 2
    # a row the model cannot pair: the table is written, exit 1 with the count on stderr
    assert main(["-q", "compare", str(prints), "-o", str(tmp_path / "p.csv")]) == 1
    captured = capsys.readouterr()
    assert "1 rows not paired" in captured.err and captured.out == ""
    assert (tmp_path / "p.csv").is_file()


def test_report_command_rows_failed_exit_1_with_count(tmp_path, capsys):
    # issue 12: a table without pressure / load columns gave 4 error rows and exit 0
    from contactpatch.study.cli import main

    prints = tmp_path / "nop.csv"
    prints.write_text(
        "file,print,status,tire,length_mm,width_mm,hull_area_mm2\n"
        + "".join(f"{f}.png,0,ok,5,100,30,2000\n" for f in "abcd")
    )
    code = main(["report", str(prints), "-o", str(tmp_path / "rep"), "--no-renders"])
    captured = capsys.readouterr()
    assert code == 1
    assert "4 of 4 rows failed" in captured.err
    assert "errors.csv" in captured.err
    assert (tmp_path / "rep" / "index.html").is_file()
    # -q: nothing on stdout, the count still on stderr
    code = main(["-q", "report", str(prints), "-o", str(tmp_path / "rep2"), "--no-renders"])
    captured = capsys.readouterr()
    assert code == 1 and captured.out == "" and "4 of 4 rows failed" in captured.err


def test_main_usage_error_exit_2(capsys):
    from contactpatch.study.cli import main

    assert main(["report"]) == 2
    assert main(["nosuchcommand"]) == 2
    assert "usage" in capsys.readouterr().err
