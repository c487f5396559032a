# SPDX-License-Identifier: BSD-2-Clause
"""What an FMI 3.0 FMU made from an FMI 2.0 one (cmake/fmi3_model_description.py) must keep of it."""
from fmpy import read_model_description


def assert_same_variables_and_token(fmu2, fmu3):
    """Every FMI 2.0 variable is in the FMI 3.0 description with the same reference, causality,
    variability, start, unit and range; the token is the GUID; the outputs come in the same order.
    Returns both model descriptions, for the checks that differ between models."""
    md2, md3 = read_model_description(fmu2), read_model_description(fmu3)
    assert md3.guid == md2.guid
    vars3 = {v.name: v for v in md3.modelVariables}
    for v in md2.modelVariables:
        w = vars3[v.name]
        assert (w.valueReference, w.causality, w.variability, w.start, w.unit, w.min, w.max) == \
            (v.valueReference, v.causality, v.variability, v.start, v.unit, v.min, v.max), v.name
    assert [u.variable.name for u in md3.outputs] == [u.variable.name for u in md2.outputs]
    return md2, md3
