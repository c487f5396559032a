# SPDX-License-Identifier: BSD-2-Clause
"""`painleve validate`'s suite: the static checks of an FMU build (static), the theorems on it
(suite.validate) and the report of both (report)."""
