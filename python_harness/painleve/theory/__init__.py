# SPDX-License-Identifier: BSD-2-Clause
"""The paper's results (Hogan & Kristiansen) as formulas: numpy and scipy only, no FMU, no fmpy.
hypotheses < rod_coefficients < rigid_limit < analytic (analytic.predict(case): all of them for one case)."""
