"""A result's table columns as a pandas DataFrame (the `to_dataframe` of every result type)."""

from __future__ import annotations

import numpy as np


def frame(columns: dict):
    """`columns` (name -> array or list) as a pandas DataFrame, in their order."""
    import pandas as pd  # pandas (installed with xarray): loaded only when a table is asked for

    return pd.DataFrame({k: v if isinstance(v, np.ndarray) else list(v) for k, v in columns.items()})
