# SPDX-License-Identifier: BSD-2-Clause
"""What a sweep runs: a grid or a random sample over the parameters of `Case`,
each case known by an integer id, so any worker can rebuild any case from
(spec, id) alone and a resumed sweep knows which cases are done.

A parameter is given as text:
    1.0              one value
    0.5,1,1.2        a list (grid: each value; random: one of them, uniformly)
    lo:hi:n          grid: n values evenly spaced from lo to hi (ends included)
    lo:hi:n:log      grid: n values evenly spaced in log
    lo:hi            random: uniform in [lo, hi]
    lo:hi:log        random: log-uniform in [lo, hi]
"""
import json
import math
from dataclasses import asdict, dataclass, fields

import numpy as np

from ..experiments.case import RANGES, Case
from .draws import uniform

PARAMS = ("theta0", "phi0", "delta", "epsilon", "v0", "w10", "alpha", "mu", "kappa", "beta")
DEFAULTS = {f.name: f.default for f in fields(Case)}
# What each parameter must satisfy before any case runs: the FMU's ranges (case.RANGES, docs/model.md).
LIMITS = {
    "epsilon": (lambda x: RANGES["epsilon"][0] <= x <= RANGES["epsilon"][1],
                "eps must be in [1e-8, 1]: the contact stiffness is eps^-2"),
    "delta": (lambda x: RANGES["delta"][0] <= x <= RANGES["delta"][1], "delta must be in [0, 1e6] (contact damping)"),
    "alpha": (lambda x: RANGES["alpha"][0] <= x <= RANGES["alpha"][1],
              "alpha = m l^2 / I must be in [1e-6, 1e6] (3 for a uniform rod)"),
    "mu": (lambda x: RANGES["mu"][0] <= x <= RANGES["mu"][1], "mu must be in [0, 1e6] (friction coefficient)"),
    "kappa": (lambda x: RANGES["kappa"][0] <= x <= RANGES["kappa"][1],
              "kappa must be in [0, 1e6] (the compliance law's stiffening; < 0 would soften it)"),
    "beta": (lambda x: RANGES["beta"][0] <= x <= RANGES["beta"][1],
             "beta must be in [0, 1e6] (the damping's growth with penetration)"),
}
# The most cases one sweep may hold, checked before anything is allocated: every case's id is
# held in memory (8 bytes) and each row is ~300 bytes on disk; at ~1000 cases/s on two workers
# ten million cases are about three hours.
MAX_CASES = 10_000_000


class SpecError(ValueError):
    """A parameter text that cannot be read; the message says what to write instead."""


def _option(name):
    """The command-line option of a parameter."""
    return "--eps" if name == "epsilon" else f"--{name}"


def _number(name, text):
    try:
        x = float(text)
    except ValueError:
        raise SpecError(f"{_option(name)}: {text!r} is not a number") from None
    if not math.isfinite(x):
        raise SpecError(f"{_option(name)}: {text!r} is not a finite number")
    return x


def check_value(name, x):
    ok, rule = LIMITS.get(name, (lambda _: True, ""))
    if not ok(x):
        raise SpecError(f"{_option(name)} {x:g}: {rule}")
    return x


@dataclass(frozen=True)
class Axis:
    """One parameter's values: fixed, a list, or a range (grid points or a random interval)."""
    name: str
    values: tuple = ()        # one value, or a list
    lo: float = math.nan
    hi: float = math.nan
    n: int = 0                # grid points of a range (0 in a random sample)
    log: bool = False

    @classmethod
    def parse(cls, name, text, *, random):
        text = str(text).strip()
        if ":" not in text:
            values = tuple(check_value(name, _number(name, t)) for t in text.split(",") if t.strip())
            if not values:
                raise SpecError(f"{_option(name)}: give a value, a list a,b,c, or a range "
                                f"lo:hi{'' if random else ':n'}")
            return cls(name, values=values)
        parts = text.split(":")
        log = parts[-1].strip().lower() == "log"
        parts = parts[:-1] if log else parts
        want = 2 if random else 3
        example = "lo:hi or lo:hi:log" if random else "lo:hi:n or lo:hi:n:log"
        if len(parts) != want:
            where = "a random sample" if random else "a grid"
            raise SpecError(f"{_option(name)} {text}: a range is {example} in {where}")
        lo, hi = (check_value(name, _number(name, p)) for p in parts[:2])
        if log and (lo <= 0 or hi <= 0):
            raise SpecError(f"{_option(name)} {text}: a log range needs lo, hi > 0")
        n = 0
        if not random:
            try:
                n = int(parts[2])
            except ValueError:
                raise SpecError(f"{_option(name)} {text}: the count n in lo:hi:n must be an integer") from None
            if n < 1:
                raise SpecError(f"{_option(name)} {text}: the count n in lo:hi:n must be >= 1")
        return cls(name, lo=lo, hi=hi, n=n, log=log)

    @property
    def size(self):
        """The number of grid values, without making them."""
        return len(self.values) if self.values else self.n

    def grid(self):
        if self.values:
            return np.array(self.values, dtype=float)
        if self.n == 1:
            return np.array([self.lo])
        if self.log:
            return np.geomspace(self.lo, self.hi, self.n)
        return np.linspace(self.lo, self.hi, self.n)

    def sample(self, u):
        """The values at uniform draws u in [0, 1)."""
        if self.values:
            return np.asarray(self.values)[np.minimum((u * len(self.values)).astype(int), len(self.values) - 1)]
        if self.log:
            return np.exp(np.log(self.lo) + u * (np.log(self.hi) - np.log(self.lo)))
        return self.lo + u * (self.hi - self.lo)

    def text(self):
        if self.values:
            return ",".join(repr(v) for v in self.values)
        parts = [repr(self.lo), repr(self.hi)] + ([str(self.n)] if self.n else []) + (["log"] if self.log else [])
        return ":".join(parts)


@dataclass(frozen=True)
class SweepSpec:
    """A grid (the product of the axes, row-major in PARAMS order) or `samples` random cases."""
    axes: tuple
    samples: int = 0          # 0: a grid
    seed: int = 0

    @classmethod
    def from_texts(cls, texts, *, samples=0, seed=0):
        """texts: {param: text} for the parameters given; the others keep Case's defaults."""
        unknown = set(texts) - set(PARAMS)
        if unknown:
            raise SpecError(f"unknown parameter {sorted(unknown)[0]!r}; the parameters are {', '.join(PARAMS)}")
        random = samples > 0
        axes = tuple(Axis.parse(p, texts.get(p, repr(DEFAULTS[p])), random=random) for p in PARAMS)
        spec = cls(axes=axes, samples=int(samples), seed=int(seed))
        if spec.total > MAX_CASES:
            sizes = " x ".join(f"{a.size} {a.name}" for a in axes if a.size > 1)
            raise SpecError(f"{spec.total:,} cases ({sizes if not random else '--random'}) is more than one sweep "
                            f"holds ({MAX_CASES:,}): use fewer points, or split it into several sweeps")
        return spec

    @property
    def shape(self):
        return tuple(a.size for a in self.axes)

    @property
    def total(self):
        """The number of cases, as a Python int (no overflow, nothing allocated)."""
        return self.samples if self.samples else math.prod(self.shape)

    def columns(self, ids):
        """{param: array of values} for the cases `ids`."""
        ids = np.asarray(ids, dtype=np.int64)
        if not self.samples:
            index = np.unravel_index(ids, self.shape)
            return {a.name: a.grid()[i] for a, i in zip(self.axes, index)}
        # One generator per case, seeded by (seed, id): a case's values do not depend on batching
        # (draws.uniform: numpy's default_rng([seed, id]).random, over the batch's arrays).
        u = uniform(self.seed, ids, len(PARAMS))
        return {a.name: a.sample(u[:, k]) for k, a in enumerate(self.axes)}

    def cases(self, ids):
        cols = self.columns(ids)     # as Python floats (tolist), in Case's order of fields
        return [Case(*values) for values in zip(*(np.asarray(cols[f.name], dtype=float).tolist()
                                                     for f in fields(Case)))]

    def describe(self):
        """The identity of a sweep: what a resumed run must match."""
        return {"mode": "random" if self.samples else "grid", "samples": self.samples, "seed": self.seed,
                "params": {a.name: a.text() for a in self.axes}, "total": self.total}

    def to_json(self):
        return json.dumps({"axes": [asdict(a) for a in self.axes], "samples": self.samples, "seed": self.seed})

    @classmethod
    def from_json(cls, text):
        d = json.loads(text)
        return cls(axes=tuple(Axis(**{**a, "values": tuple(a["values"])}) for a in d["axes"]),
                   samples=d["samples"], seed=d["seed"])
