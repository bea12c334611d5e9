import numpy as np
import pytest

from inkprint.synth import PrintSpec, SheetSpec, drum_and_plate_sheet, render_sheet, save_scan


@pytest.fixture(scope="session")
def sheet_factory(tmp_path_factory):
    """Write a synthetic sheet; returns (path, truths)."""
    root = tmp_path_factory.mktemp("scans")
    cache = {}

    def make(name="sheet.png", **kw):
        key = (name, tuple(sorted(kw.items())))
        if key not in cache:
            spec = kw.pop("spec", None) or drum_and_plate_sheet(**kw)
            img, truths = render_sheet(spec)
            cache[key] = (save_scan(img, root / name, dpi=spec.dpi), truths)
        return cache[key]

    return make


def one_print_sheet(dpi=300.0, **kw):
    p = PrintSpec(kw.pop("length", 70.0), kw.pop("width", 8.0), (100.0, 120.0), **kw)
    return SheetSpec((p,), dpi=dpi)


__all__ = ["np", "one_print_sheet"]
