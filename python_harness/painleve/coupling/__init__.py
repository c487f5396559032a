# SPDX-License-Identifier: BSD-2-Clause
"""The rod in SI units with inputs (si, si_experiment), SSP archives (ssp, ssp_check), the
co-simulation masters that run them (masters), and the rod on the shaker table (coupled)."""
