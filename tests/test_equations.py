"""Equation tags of Dressel (2013), chapter 5, in the code (docs/model.md, "Equation index").

Rule: every implemented equation is tagged exactly once in ``tiremesh/**/*.py``, as a
trailing ``# Eq. 5-N`` comment on the code line that implements it, so that
``grep -rn "Eq. 5-N" tiremesh`` lands on the code. Every other mention says
"equation 5-N"; ranges ("Eq. 5-18 to 5-21") are not used. The index table in
docs/model.md names, per equation, the file and function the tag is in and the tests
that check it; this module keeps the table and the tags in step.
"""

from __future__ import annotations

import ast
import io
import re
import tokenize
from functools import cache
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "tiremesh"
MODEL_MD = ROOT / "docs" / "model.md"

ALL_EQUATIONS = tuple(range(1, 34))  # Eq. 5-1 .. 5-33
NOT_IMPLEMENTED = (1, 9, 16)  # definition, identity, superseded (see the index)
IMPLEMENTED = tuple(n for n in ALL_EQUATIONS if n not in NOT_IMPLEMENTED)

RANGE_PATTERNS = (
    re.compile(r"Eq\.\s*5-\d+\s+to\b"),
    re.compile(r"(?:Eq\.|[Ee]quations?)\s*5-\d+\s*(?:to|\u2013|\u2014)\s*(?:Eq\.\s*)?5-\d+"),
)


def tag_pattern(n: int) -> re.Pattern:
    return re.compile(rf"Eq\.\s*5-{n}\b")


@cache
def sources() -> tuple[Path, ...]:
    return tuple(sorted(PACKAGE.rglob("*.py")))


@cache
def text(path: Path) -> str:
    return path.read_text(encoding="utf-8")


@cache
def comments(path: Path) -> dict[int, tuple[int, str]]:
    """Line -> (column, text) of each comment token (never inside a string)."""
    out = {}
    for tok in tokenize.generate_tokens(io.StringIO(text(path)).readline):
        if tok.type == tokenize.COMMENT:
            out[tok.start[0]] = (tok.start[1], tok.string)
    return out


@cache
def scopes(path: Path) -> tuple[tuple[int, int, str], ...]:
    """(first line, last line, dotted qualname) of every class and function."""
    found = []

    def walk(node, prefix):
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
                name = f"{prefix}{child.name}"
                found.append((child.lineno, child.end_lineno, name))
                walk(child, name + ".")
            else:
                walk(child, prefix)

    walk(ast.parse(text(path)), "")
    return tuple(found)


def enclosing(path: Path, line: int) -> str:
    """Qualname of the innermost class or function holding ``line`` ('' at module level)."""
    inside = [(last - first, name) for first, last, name in scopes(path) if first <= line <= last]
    return min(inside)[1] if inside else ""


def occurrences(n: int) -> list[tuple[Path, int, str]]:
    pat = tag_pattern(n)
    return [
        (path, i, line)
        for path in sources()
        for i, line in enumerate(text(path).splitlines(), 1)
        if pat.search(line)
    ]


def where(occ) -> str:
    return "\n".join(f"  {p.relative_to(ROOT)}:{i}: {line.strip()}" for p, i, line in occ)


@cache
def index_rows() -> dict[int, dict]:
    """The docs/model.md "Equation index" table, by equation number."""
    md = text(MODEL_MD)
    start = md.index("## Equation index")
    end = md.find("\n## ", start + 1)
    section = md[start : end if end >= 0 else len(md)]
    rows: dict[int, dict] = {}
    row = re.compile(r"^\|\s*Eq\. 5-(\d+)\s*\|(.*)\|(.*)\|(.*)\|\s*$")
    for line in section.splitlines():
        m = row.match(line)
        if not m:
            continue
        n = int(m.group(1))
        assert n not in rows, f"Eq. 5-{n} is listed twice in the equation index"
        loc = re.search(r"`(tiremesh/[\w/]+\.py):([\w.]+)`", m.group(3))
        rows[n] = {
            "what": m.group(2).strip(),
            "where": m.group(3).strip(),
            "file": loc.group(1) if loc else None,
            "function": loc.group(2) if loc else None,
            "tests": re.findall(r"`(tests/[\w/]+\.py)::(\w+)`", m.group(4)),
        }
    return rows


def test_index_lists_every_equation_once():
    assert sorted(index_rows()) == list(ALL_EQUATIONS)


def test_index_agrees_with_implemented_set():
    rows = index_rows()
    listed = tuple(n for n in ALL_EQUATIONS if rows[n]["file"] is not None)
    assert listed == IMPLEMENTED
    for n in NOT_IMPLEMENTED:
        assert rows[n]["where"].startswith("not implemented ("), rows[n]["where"]


@pytest.mark.parametrize("n", IMPLEMENTED, ids=lambda n: f"Eq. 5-{n}")
def test_tag_once_on_a_code_line(n):
    occ = occurrences(n)
    assert len(occ) == 1, (
        f"'Eq. 5-{n}' must appear exactly once in tiremesh/**/*.py, as the tag on the "
        f"implementing line (other mentions: 'equation 5-{n}'); found {len(occ)}:\n{where(occ)}"
    )
    path, line, src = occ[0]
    comment = comments(path).get(line)
    assert comment is not None and tag_pattern(n).search(comment[1]), (
        f"'Eq. 5-{n}' is not in a comment:\n{where(occ)}"
    )
    assert src[: comment[0]].strip(), f"'Eq. 5-{n}' is not on a line of code:\n{where(occ)}"


@pytest.mark.parametrize("n", NOT_IMPLEMENTED, ids=lambda n: f"Eq. 5-{n}")
def test_unimplemented_equation_not_tagged(n):
    occ = occurrences(n)
    assert not occ, f"Eq. 5-{n} is not implemented (docs/model.md) but tagged:\n{where(occ)}"


@pytest.mark.parametrize("n", IMPLEMENTED, ids=lambda n: f"Eq. 5-{n}")
def test_tag_location_matches_index(n):
    row = index_rows()[n]
    occ = occurrences(n)
    assert occ, f"Eq. 5-{n} is not tagged (the index says {row['where']})"
    for path, line, _ in occ:
        assert path.relative_to(ROOT).as_posix() == row["file"], (
            f"Eq. 5-{n}: tagged in {path.relative_to(ROOT)}:{line}, index says {row['file']}"
        )
        scope = enclosing(path, line)
        fn = row["function"]
        assert scope == fn or scope.startswith(fn + "."), (
            f"Eq. 5-{n}: tagged in {scope or 'module level'} "
            f"({path.relative_to(ROOT)}:{line}), index says {fn}"
        )


@pytest.mark.parametrize("n", ALL_EQUATIONS, ids=lambda n: f"Eq. 5-{n}")
def test_index_cites_existing_tests(n):
    for file, name in index_rows()[n]["tests"]:
        path = ROOT / file
        assert path.is_file(), f"Eq. 5-{n}: {file} does not exist"
        defs = {
            node.name
            for node in ast.parse(text(path)).body
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef)
        }
        assert name in defs, f"Eq. 5-{n}: {file}::{name} does not exist"


def test_no_equation_ranges():
    bad = []
    for path in (*sources(), MODEL_MD, ROOT / "docs" / "architecture.md"):
        for i, line in enumerate(text(path).splitlines(), 1):
            if any(p.search(line) for p in RANGE_PATTERNS):
                bad.append((path, i, line))
    assert not bad, "equation ranges (list each equation instead):\n" + where(bad)


def test_no_equation_tags_outside_tiremesh():
    # contactpatch and inkprint refer to tiremesh's functions ("equation 5-N" at most),
    # so that grep "Eq. 5-N" over the packages lands on the implementing line alone
    bad = []
    for pkg in ("contactpatch", "inkprint"):
        for path in sorted((ROOT / pkg).rglob("*.py")):
            for i, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                if re.search(r"Eq\.\s*5-\d+", line):
                    bad.append((path, i, line))
    assert not bad, "tags outside tiremesh:\n" + where(bad)
