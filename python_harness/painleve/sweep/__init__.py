# SPDX-License-Identifier: BSD-2-Clause
"""Sweeps over many IWC cases: what to run (spec), running it on dask (run) and the resumable
output (store)."""
