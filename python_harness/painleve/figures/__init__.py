# SPDX-License-Identifier: BSD-2-Clause
"""Figures: the paper's, from runs of the FMU (paper: the numbers; plots: matplotlib), and the
coupled study's (coupled)."""
