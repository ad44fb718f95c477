"""Reading the files the command line writes, to compare the package's results with them."""

import io
import os
from typing import Union

import pandas as pd

#: pandas before 3 parses floats fast but not always exactly unless asked; from 3 on exact
#: parsing is the default and the option is deprecated.
EXACT_FLOATS = {"float_precision": "round_trip"} if int(pd.__version__.split(".")[0]) < 3 else {}


def read(data: Union[bytes, str, os.PathLike]) -> pd.DataFrame:
    """A CSV file the command line wrote (its bytes, or a path) as a DataFrame: numbers read
    back exactly (the files hold each double in its shortest round-trip form), empty cells
    as NaN."""
    source = io.BytesIO(data) if isinstance(data, bytes) else data
    return pd.read_csv(source, keep_default_na=False, na_values=[""], **EXACT_FLOATS)
