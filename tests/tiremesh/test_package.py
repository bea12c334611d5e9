"""tiremesh as a whole: it imports none of the other packages, no module imports
another's private names, public docstrings are NumPy style, functions stay short,
and the examples in docstrings run."""

import ast
import doctest
import importlib
import pkgutil
from pathlib import Path

import pytest

import tiremesh as tm
from tests.docrules import check_numpy_docstring, public_objects

PACKAGE = Path(tm.__file__).parent
MODULES = sorted(m.name for m in pkgutil.walk_packages([str(PACKAGE)], prefix="tiremesh."))
SRC = sorted(PACKAGE.rglob("*.py"))


def _import_nodes(path):
    return [
        n
        for n in ast.walk(ast.parse(path.read_text()))
        if isinstance(n, ast.Import | ast.ImportFrom)
    ]


def test_tiremesh_imports_none_of_ours():
    for path in SRC:
        for node in _import_nodes(path):
            names = (
                [a.name for a in node.names]
                if isinstance(node, ast.Import)
                else [node.module or ""]
            )
            for name in names:
                assert not name.startswith(("contactpatch", "inkprint")), f"{path.name}: {name}"


def test_no_private_name_imported_across_modules():
    for path in SRC:
        for node in _import_nodes(path):
            if isinstance(node, ast.ImportFrom):
                private = [
                    a.name
                    for a in node.names
                    if a.name.startswith("_") and not a.name.startswith("__")
                ]
                assert not private, f"{path.relative_to(PACKAGE)} imports {private}"


@pytest.mark.parametrize(
    ("name", "obj"), public_objects(MODULES), ids=lambda x: x if isinstance(x, str) else None
)
def test_public_docstrings_numpy_style(name, obj):
    check_numpy_docstring(name, obj)


def test_no_long_functions_or_many_positionals():
    for path in SRC:
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.FunctionDef):
                n = node.end_lineno - node.lineno + 1
                assert n <= 90, f"{path.name}:{node.name} has {n} lines"
                public = not node.name.startswith("_")
                positional = len(node.args.posonlyargs) + len(node.args.args)
                positional -= bool(node.args.args and node.args.args[0].arg in ("self", "cls"))
                assert not public or positional <= 5, f"{path.name}:{node.name}"


@pytest.mark.parametrize("modname", MODULES)
def test_doctests(modname):
    result = doctest.testmod(importlib.import_module(modname), optionflags=doctest.ELLIPSIS)
    assert result.failed == 0


def test_main_entry_points_have_examples():
    for func in (tm.solve, tm.LoadCase):
        assert doctest.DocTestFinder().find(func, func.__name__)[0].examples
