"""Building the report (issue 12 items 4-5, issue 13): Markdown safe from manifest
cells, a report never left half-written, a thousand prints, the progress bar."""

import pytest

from contactpatch import build_report
from contactpatch.study import report as R
from contactpatch.study.pages import md_text
from contactpatch.study.samples import synthetic_print_rows

SCRIPT = "<script>alert(1)</script>"
IMG = "<img src=x onerror=alert(2)>"


def test_md_text_escapes_html_pipes_and_line_breaks():
    assert md_text(SCRIPT) == "&lt;script&gt;alert(1)&lt;/script&gt;"
    assert md_text("a|b\nc & d") == "a\\|b c &amp; d"
    assert md_text(4.5) == "4.5"


def test_markdown_page_carries_no_markup_from_manifest_cells(tmp_path):
    rows = [
        dict(r, tire=f"Tire {SCRIPT}", file=f"{IMG}{k}.png")
        for k, r in enumerate(synthetic_print_rows(8))
    ]
    build_report(rows, tmp_path, renders=False, validation=False, source=f"{IMG}.csv")
    md = (tmp_path / "report.md").read_text()
    assert "<script" not in md and "<img" not in md
    assert "&lt;script&gt;" in md  # shown as text, in the table
    assert "- source: &lt;img src=x onerror=alert(2)&gt;.csv" in md
    page = (tmp_path / "index.html").read_text()
    assert SCRIPT not in page and IMG not in page


def test_build_report_failing_step_leaves_the_previous_report(tmp_path, monkeypatch):
    out = tmp_path / "report"
    rows = synthetic_print_rows(8)
    build_report(rows, out, renders=False, validation=False)
    (out / "notes.txt").write_text("mine")
    before = {p.relative_to(out): p.read_bytes() for p in out.rglob("*") if p.is_file()}

    def broken(*args, **kwargs):
        raise RuntimeError("figure step failed")

    monkeypatch.setattr(R, "draw_figures", broken)
    with pytest.raises(RuntimeError, match="figure step failed"):
        build_report(synthetic_print_rows(12, seed=3), out, renders=False, validation=False)
    after = {p.relative_to(out): p.read_bytes() for p in out.rglob("*") if p.is_file()}
    assert after == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["report"]  # no partial folder left


def test_build_report_replaces_a_previous_report_whole(tmp_path):
    build_report(synthetic_print_rows(16), tmp_path, renders=False, validation=False)
    (tmp_path / "figures" / "stale.svg").write_text("<svg/>")
    (tmp_path / "notes.txt").write_text("mine")
    index = build_report(synthetic_print_rows(8), tmp_path, renders=False, validation=False)
    assert index == tmp_path / "index.html" and index.read_text().count("<tr>") >= 8
    assert not (tmp_path / "figures" / "stale.svg").exists()
    assert (tmp_path / "notes.txt").read_text() == "mine"
    assert not [p for p in tmp_path.parent.iterdir() if p.name.startswith(f".{tmp_path.name}.")]


def test_a_report_of_1000_prints_stays_usable(tmp_path):
    index = build_report(synthetic_print_rows(1000), tmp_path, renders=False, validation=False)
    text = index.read_text()
    assert len(text.encode()) < 5_000_000  # 3.2 MB when written
    # every print in the paired table, which the inline script filters and sorts
    table = text[text.index('id="paired-table"') :]
    table = table[: table.index("</table>")]
    assert table.count("<tr>") >= 1000
    assert 'data-filter="paired-table"' in text
    script = text[text.rindex("<script>") :]
    assert 'querySelectorAll("input[data-filter]")' in script and "aria-sort" in script
    # aggregate figures: 4 summary figures and one trend figure per tire, no more
    assert text.count('<figure id="fig-') == 4 + 4
    assert "<details open>" not in text
    assert (tmp_path / "tables" / "paired.csv").read_text().count("\n") == 1001


def test_build_report_shows_a_progress_bar(tmp_path, capsys):
    build_report(synthetic_print_rows(8), tmp_path, renders=False, validation=False, progress=True)
    err = capsys.readouterr().err
    assert "report" in err and "100%" in err
    build_report(
        synthetic_print_rows(8), tmp_path, renders=False, validation=False, progress=False
    )
    assert "100%" not in capsys.readouterr().err


# --- figures: ticks, legends, colours ------------------------------------------------


def test_log_ticks_never_fewer_than_two():
    from contactpatch.study.svgplot import log_ticks

    assert len(log_ticks(95.0, 105.0, [100.0])) >= 2  # one data value on a short axis
    assert len(log_ticks(1.01, 1.03)) >= 2
    ticks = log_ticks(3.9, 7.2, [4.0])
    assert len(ticks) >= 2 and all(3.9 <= t <= 7.2 for t in ticks)


def test_tire_colours_follow_the_name_not_the_order():
    from contactpatch.study.style import PALETTE, tire_colour_slot, tire_colours

    a = tire_colours(["Schwalbe Big Apple 55-622"])
    b = tire_colours(["Aaa first", "Schwalbe Big Apple 55-622"][::-1])
    assert a["Schwalbe Big Apple 55-622"] == PALETTE[tire_colour_slot("Schwalbe Big Apple 55-622")]
    assert list(b) == ["Aaa first", "Schwalbe Big Apple 55-622"]  # sorted names
    many = tire_colours(f"tire {k}" for k in range(7))
    assert len(set(many.values())) == 7  # no two tires of a report share a colour


def test_key_figure_legend_matches_what_is_drawn(tmp_path):
    from contactpatch import pair_prints
    from contactpatch.study import figures as F
    from contactpatch.study.style import tire_colours

    paired = pair_prints(synthetic_print_rows(8))
    svg = F.area_vs_length_width(paired, tire_colours(r["tire"] for r in paired))
    assert "prints: filled" in svg and "model: open" in svg
    assert "solid" not in svg and "dashed" not in svg and "stroke-dasharray" not in svg
