"""The docstring rule shared by the package tests (developer guide): every public
function and class of a module has a NumPy-style docstring, with Parameters (or a
class's Attributes) when it takes arguments and Returns (or Yields) for a function."""

import importlib
import inspect

PARAMETERS = "Parameters\n----------"
ATTRIBUTES = "Attributes\n----------"


def public_objects(modules):
    """``(qualified name, object)`` of every public function and class defined in
    ``modules`` (module names; ``__main__`` modules are skipped)."""
    out = []
    for modname in modules:
        if modname.endswith("__main__"):
            continue
        mod = importlib.import_module(modname)
        for name, obj in vars(mod).items():
            if name.startswith("_") or getattr(obj, "__module__", None) != modname:
                continue
            if inspect.isfunction(obj) or inspect.isclass(obj):
                out.append((f"{modname}.{name}", obj))
    return out


def check_numpy_docstring(name, obj):
    """Assert the rule on one public function or class (``name`` is for the message).
    An exception class without its own ``__init__`` and a Protocol need only a
    docstring."""
    doc = inspect.getdoc(obj) or ""
    assert doc, f"{name}: no docstring"
    if inspect.isclass(obj):
        if issubclass(obj, Exception) and "__init__" not in vars(obj):
            return
        if getattr(obj, "_is_protocol", False):
            return
    params = [p for p in inspect.signature(obj).parameters if p not in ("self", "cls")]
    if inspect.isclass(obj):
        assert not params or PARAMETERS in doc or ATTRIBUTES in doc, (
            f"{name}: no Parameters/Attributes"
        )
        return
    assert not params or PARAMETERS in doc, f"{name}: no Parameters section"
    assert "Returns\n-------" in doc or "Yields\n------" in doc, f"{name}: no Returns section"
