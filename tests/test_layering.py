"""Layering of the three packages (issue 9, item 6): no module of tiremesh,
contactpatch or inkprint imports another package's private (``_``-prefixed)
module or name. Within one package a private module is fine (``tiremesh._tol``)."""

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("tiremesh", "contactpatch", "inkprint")


def _private(dotted: str) -> bool:
    return any(p.startswith("_") and not p.startswith("__") for p in dotted.split("."))


def foreign_private_imports(source: str, package: str) -> list[str]:
    """Imports in ``source`` (a module of ``package``) of another package's private
    module or name, as ``"line: what"`` strings."""
    bad = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            targets = [(a.name, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            targets = [(node.module, f"{node.module}.{a.name}") for a in node.names]
        else:
            continue  # relative imports stay inside the package
        for module, full in targets:
            top = module.split(".")[0]
            if top in PACKAGES and top != package and _private(full):
                bad.append(f"{node.lineno}: {full}")
    return bad


@pytest.mark.parametrize("package", PACKAGES)
def test_no_private_import_from_another_package(package):
    sources = sorted((ROOT / package).rglob("*.py"))
    assert len(sources) > 5, f"{package}: sources not found"
    bad = [
        f"{path.relative_to(ROOT)}:{hit}"
        for path in sources
        for hit in foreign_private_imports(path.read_text(encoding="utf-8"), package)
    ]
    assert not bad, bad


def test_foreign_private_imports_flags_each_form():
    src = "\n".join(
        (
            "import tiremesh._tol",
            "from contactpatch._tol import tol",
            "from tiremesh import _roots",
            "from tiremesh.io import _private_helper",
            "import tiremesh.io",  # public: fine
            "from tiremesh.io import cell_number_or_nan as _f",  # public name, private alias
            "from ._tol import tol",  # relative: own package
            "from inkprint._x import y",  # own package
        )
    )
    assert foreign_private_imports(src, "inkprint") == [
        "1: tiremesh._tol",
        "2: contactpatch._tol.tol",
        "3: tiremesh._roots",
        "4: tiremesh.io._private_helper",
    ]
    assert foreign_private_imports("from tiremesh._tol import tol", "tiremesh") == []
