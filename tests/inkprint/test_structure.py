"""Code-shape rules of the inkprint refactor, checked on the source (ast).

* no private (underscored) name or module imported from contactpatch or tiremesh;
* pixels become mm only in inkprint/coords.py (no inch constant elsewhere);
* no function over 80 lines (its docstring not counted), no public function with
  more than 3 positional parameters;
* every public function and class has a NumPy-style docstring;
* every flag that makes a print unmeasurable has a row in docs/inkprint.md's flags
  table.
"""

import ast
import re
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[2] / "inkprint"
SOURCES = sorted(PACKAGE.glob("*.py"))
OTHER_PACKAGES = ("contactpatch", "tiremesh")


def trees():
    return [(p.name, ast.parse(p.read_text(encoding="utf-8"))) for p in SOURCES]


def functions(tree):
    """(qualified name, node, public) of every function, methods included."""
    out = []

    def visit(node, prefix, public):
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
                name = f"{prefix}{child.name}"
                pub = public and not child.name.startswith("_")
                if not isinstance(child, ast.ClassDef):
                    out.append((name, child, pub))
                visit(child, name + ".", pub)

    visit(tree, "", True)
    return out


def test_no_private_imports_from_other_packages():
    bad = []
    for fname, tree in trees():
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                parts = node.module.split(".")
                if parts[0] in OTHER_PACKAGES:
                    names = [a.name for a in node.names]
                    if any(p.startswith("_") for p in parts) or any(
                        n.startswith("_") for n in names
                    ):
                        bad.append(f"{fname}: from {node.module} import {', '.join(names)}")
            elif isinstance(node, ast.Import):
                for a in node.names:
                    parts = a.name.split(".")
                    if parts[0] in OTHER_PACKAGES and any(p.startswith("_") for p in parts):
                        bad.append(f"{fname}: import {a.name}")
    assert not bad, bad


def test_pixels_become_mm_only_in_coords():
    pattern = re.compile(r"25\.4|2\.54|MM_PER_IN")
    bad = [
        f"{p.name}:{i}"
        for p in SOURCES
        if p.name != "coords.py"
        for i, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1)
        if pattern.search(line.split("#")[0]) and ">>>" not in line
    ]
    assert not bad, bad
    assert not (PACKAGE / "_tol.py").exists()  # no module of mutable settings


def test_functions_are_short_with_few_positional_parameters():
    long, wide = [], []
    for fname, tree in trees():
        for name, node, public in functions(tree):
            lines = node.end_lineno - node.lineno + 1
            if ast.get_docstring(node) is not None:
                doc = node.body[0]
                lines -= doc.end_lineno - doc.lineno + 1
            if lines > 80:
                long.append(f"{fname}: {name}")
            positional = [a.arg for a in node.args.posonlyargs + node.args.args]
            positional = [a for a in positional if a not in ("self", "cls")]
            if public and len(positional) > 3:
                wide.append(f"{fname}: {name}{tuple(positional)}")
    assert not long, long
    assert not wide, wide


@pytest.mark.parametrize("source", SOURCES, ids=lambda p: p.name)
def test_public_functions_and_classes_have_numpy_docstrings(source):
    tree = ast.parse(source.read_text(encoding="utf-8"))
    bad = []
    for node in tree.body:
        if isinstance(node, ast.ClassDef) and not node.name.startswith("_"):
            if not ast.get_docstring(node):
                bad.append(f"class {node.name}: no docstring")
    for name, node, public in functions(tree):
        if not public or name.endswith("__"):
            continue
        doc = ast.get_docstring(node) or ""
        args = [a.arg for a in node.args.args + node.args.kwonlyargs if a.arg not in ("self",)]
        returns_none = isinstance(node.returns, ast.Constant) and node.returns.value is None
        is_property = any(getattr(d, "id", "") == "property" for d in node.decorator_list)
        if not doc:
            bad.append(f"{name}: no docstring")
        elif args and "Parameters\n" not in doc:
            bad.append(f"{name}: no Parameters section")
        elif not (returns_none or is_property) and not re.search(r"Returns\n|Yields\n", doc):
            bad.append(f"{name}: no Returns section")
    assert not bad, bad


def test_every_unmeasurable_flag_has_a_row_in_the_docs_flags_table():
    from inkprint.results import UNMEASURABLE

    docs = (PACKAGE.parent / "docs" / "inkprint.md").read_text(encoding="utf-8")
    rows = set(re.findall(r"^\| `(\w+)` \|", docs, flags=re.M))
    assert set(UNMEASURABLE) <= rows, sorted(set(UNMEASURABLE) - rows)
