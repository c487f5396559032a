# SPDX-License-Identifier: BSD-2-Clause
"""Loading and running an FMU on fmpy: Experiment (FMI 2.0 and 3.0, Model Exchange and
Co-Simulation), the fast loops it runs a case in, and the fmpy internals they use."""
