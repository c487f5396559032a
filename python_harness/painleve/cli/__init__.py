# SPDX-License-Identifier: BSD-2-Clause
"""The `painleve` command (main.main): one module per command, each parsing its options and
delegating to the layers below; errors.py turns a failure into one line and an exit status."""
