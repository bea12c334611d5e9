"""Tables as pandas DataFrames, for notebooks (pandas is an optional extra)."""

from __future__ import annotations

from .errors import InkPrintError


class MissingDependency(InkPrintError, ImportError):
    """An optional package is needed for this call (names the package)."""


def dataframe(rows: list[dict]):
    """Rows (dicts) as a pandas DataFrame.

    Parameters
    ----------
    rows : list of dict

    Returns
    -------
    pandas.DataFrame

    Raises
    ------
    MissingDependency
        pandas is not installed (``pip install pandas``).
    """
    try:
        import pandas as pd
    except ImportError as exc:
        raise MissingDependency(
            "to_dataframe() needs pandas, an optional extra: pip install pandas"
        ) from exc
    return pd.DataFrame.from_records(rows)


__all__ = ["MissingDependency", "dataframe"]
