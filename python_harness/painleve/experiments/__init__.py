# SPDX-License-Identifier: BSD-2-Clause
"""An IWC experiment, whatever runs it: the Case (input), the Outcome and its phases (what a run
did), the acceptance rules of Theorems 1 and 2, studies over many cases, and the scipy reference
that runs a case without an FMU; strict_json, results as JSON. No fmpy."""
