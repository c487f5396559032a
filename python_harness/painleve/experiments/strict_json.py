# SPDX-License-Identifier: BSD-2-Clause
"""Results as strict JSON (iwc --json, validate's report, figures.json): what a NaN
prediction or a numpy scalar becomes."""
import json
import math


def to_json(obj, **kw):
    """Strict JSON of results: numpy scalars as numbers, NaN and infinities (a prediction
    that does not apply) as null."""
    def clean(x):
        if isinstance(x, dict):
            return {str(k): clean(v) for k, v in x.items()}
        if isinstance(x, (list, tuple)):
            return [clean(v) for v in x]
        if hasattr(x, "item") and hasattr(x, "dtype"):
            x = x.item()
        if isinstance(x, float) and not math.isfinite(x):
            return None
        return x
    return json.dumps(clean(obj), allow_nan=False, **kw)
