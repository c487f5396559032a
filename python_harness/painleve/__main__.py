# SPDX-License-Identifier: BSD-2-Clause
"""`python -m painleve`: the `painleve` command."""
import sys

from .cli.main import main

sys.exit(main())
