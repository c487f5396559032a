# SPDX-License-Identifier: BSD-2-Clause
"""The lines of a validation report (`Check`) and how they are shown: a
terminal table, a Markdown report, and one line naming what failed."""
from dataclasses import asdict, dataclass, field


@dataclass
class Check:
    """One line of the report: what was checked, what was measured, the limit, pass or fail."""
    id: str
    what: str
    measured: str
    limit: str
    passed: bool
    numbers: dict = field(default_factory=dict)

    def as_dict(self):
        return asdict(self)


def _cut(text, width):
    return text if len(text) <= width else text[:width - 1] + "…"


def table(checks, *, width=140):
    """A pass/fail table for a terminal: one line per check with its measured errors,
    then the limits, once per kind of check."""
    idw = max([len(c.id) for c in checks] + [5])
    rest = max(40, width - idw - 8)
    lines = [f"{'':4}  {'check':<{idw}}  measured", "-" * min(width, idw + 8 + rest)]
    for c in checks:
        lines.append(f"{'PASS' if c.passed else 'FAIL':4}  {c.id:<{idw}}  {_cut(c.measured, rest)}")
    limits = {}
    for c in checks:
        limits.setdefault(_kind(c.id), c.limit)
    lines += ["", "limits:"] + [f"  {kind}: {limit}" for kind, limit in limits.items()] + ["", summary(checks)]
    return "\n".join(lines)


def _kind(check_id):
    """theorem2/ME/video/below -> theorem2/below: what the check is, without interface and case."""
    parts = check_id.split("/")
    return "/".join([parts[0]] + parts[3:])


def summary(checks):
    failed = [c.id for c in checks if not c.passed]
    if not failed:
        return f"all {len(checks)} checks passed"
    shown = ", ".join(failed[:8]) + (f" and {len(failed) - 8} more" if len(failed) > 8 else "")
    return f"{len(failed)} of {len(checks)} checks FAILED: {shown}"


def markdown(checks, *, fmu_path, sha256, seconds):
    def cell(text):
        return str(text).replace("|", "\\|")
    lines = [f"# Validation of {fmu_path}", "",
             f"SHA-256 `{sha256}`; {len(checks)} checks in {seconds:.1f} s: **{summary(checks)}**.", "",
             "What each check runs and what its numbers mean: the glossary in the repository's "
             "docs/model.md §5 (the model and the theorems: §1-3).", "",
             "| result | check | what | measured | limit |", "|---|---|---|---|---|"]
    for c in checks:
        lines.append(f"| {'PASS' if c.passed else '**FAIL**'} | `{c.id}` | {cell(c.what)} | {cell(c.measured)} | "
                     f"{cell(c.limit)} |")
    return "\n".join(lines) + "\n"
