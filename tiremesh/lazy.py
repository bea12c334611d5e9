"""Lazy public names for a package's ``__init__`` (PEP 562), shared by ``tiremesh``,
``contactpatch`` and ``inkprint``: a name is imported from its module on first use, so importing
one light submodule (``tiremesh.units``) does not pull in the solver."""

from __future__ import annotations

import importlib


def lazy_attributes(package: str, namespace: dict, table: dict):
    """Module-level ``__getattr__`` and ``__dir__`` for a package.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    namespace : dict
        Its ``globals()``: a name is bound there once loaded.
    table : dict of str to str or (str, str)
        Public name -> relative module holding it (``".solver"``), or the module and
        the name there when it differs (``(".batch", "Options")``). A name not in the
        table is tried as a submodule (``tiremesh.case``), as eager imports bound them.

    Returns
    -------
    (callable, callable)
        ``__getattr__`` and ``__dir__`` to assign in the package.
    """

    def __getattr__(name: str):
        if name.startswith("__"):
            raise AttributeError(name)
        module = table.get(name)
        if module is None:
            try:
                value = importlib.import_module(f".{name}", package)
            except ModuleNotFoundError as e:
                if e.name != f"{package}.{name}":
                    raise
                raise AttributeError(f"module {package!r} has no attribute {name!r}") from None
        else:
            module, attr = module if isinstance(module, tuple) else (module, name)
            value = getattr(importlib.import_module(module, package), attr)
        namespace[name] = value
        return value

    def __dir__() -> list[str]:
        return sorted(set(namespace) | set(namespace.get("__all__", ())))

    return __getattr__, __dir__


__all__ = ["lazy_attributes"]
