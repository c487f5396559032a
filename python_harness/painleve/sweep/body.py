# SPDX-License-Identifier: BSD-2-Clause
"""A sweep of any body FMU (`painleve sweep --fmu TwoLinkArm.fmu --set theta1=-1.2:-0.8:9 --set mu=1,2`):
a grid, or `samples` random draws (seeded: draw `id` is numpy's default_rng([seed, id]), as the rod's
sweep draws), over start values and parameters the user names, with eps, delta, v0 and w10, each case
(an experiments.case.BodyCase) run through fmu.body (its start solved onto the floor, with the
parameters named in `solve`, the theory from the FMU's own coefficients): `BodySweep`, which sweep.run
runs as it runs the rod's (here or on dask, written as chunks finish, resumable), or run_body_sweep,
its rows in this process. A row holds
the case, the theory there (the quadrant, p_plus, b, the theorem, e, w1*, and what it predicts:
`predicts_iwc`) and the simulation (whether the contact point stuck, w and v at the return, the
phases), and the start solved (start_NAME): over the configurations, the paradox map from simulation
(`iwc`) beside the theory's p_plus < 0 (figures.body.sweep_map_figure draws the two).

A case runs whenever a start on the floor is found, inside the theorems' hypotheses ("ok") or not
("outside": simulated all the same, for the map); a run that is not back on the floor within
2^DOUBLINGS eps of its own time is "no return"; no start found, or the FMU stopping, is "failed"."""
import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..experiments.case import BodyCase
from ..experiments.outcome import NoReturn, SimulationError
from ..fmu.body import Body, BodyError
from ..fmu.body_case import predict
from ..theory import general
from .draws import uniform
from .spec import Axis, SpecError

CASE_AXES = ("epsilon", "delta", "v0", "w10")     # the case's own axes; the start values are the user's names
DOUBLINGS = 8
PHASES = ("compression", "stick", "lift_off", "flight_back")


def axes_of(given, case_texts, *, random=False):
    """The axes: `given` {name: SPEC} (start values, parameters), and `case_texts` {eps, delta, v0, w10:
    SPEC} for those given; a SPEC as the rod's sweep reads it (a value, a list, lo:hi:n[:log] in a grid,
    lo:hi[:log] in a random sample)."""
    unknown = [k for k in case_texts if k not in CASE_AXES]
    if unknown:
        raise SpecError(f"a body's sweep has no case parameter {unknown[0]!r}; give start values with --set")
    return tuple(Axis.parse(name, text, random=random) for name, text in {**given, **case_texts}.items())


def points(axes, samples=0, seed=0):
    """(id, {axis: value}) of every grid point, row-major in the axes' order, or of `samples` random draws
    (draw id: uniform(seed, [id]), so a draw does not depend on how many are made): BodySweep.points."""
    spec = BodySweep(axes=tuple(axes), samples=samples, seed=seed)
    return spec.points(range(spec.total))


def case_of(point, guess=(), solve=()):
    """The BodyCase of a point {axis: value}: eps, delta, v0, w10 from their axes, the rest start values."""
    given = {k: v for k, v in point.items() if k not in CASE_AXES}
    eps = point.get("epsilon", 1e-3)
    return BodyCase(given=tuple(given.items()), v0=point.get("v0"), epsilon=eps, delta=point.get("delta", 1.0),
                    w0=eps * point.get("w10", 0.0), guess=tuple(guess), solve=tuple(solve))


def cases(axes, guess=(), solve=(), samples=0, seed=0):
    """(id, {axis: value}, BodyCase) of every point (see points)."""
    for i, point in points(axes, samples, seed):
        yield i, point, case_of(point, guess, solve)


@dataclass(frozen=True)
class BodySweep:
    """A body's sweep as sweep.run runs a sweep (here or on dask, its rows written as chunks finish,
    resumable): the grid of `axes`, or `samples` draws from them with `seed` (see points); `guess` and
    `solve` as floor_start takes them. The counterpart of sweep.spec.SweepSpec: total, describe, and
    `frame(body, ids)`, the rows of the cases `ids`."""
    axes: tuple
    samples: int = 0
    seed: int = 0
    guess: tuple = ()
    solve: tuple = ()

    @property
    def total(self):
        return self.samples or math.prod(a.size for a in self.axes)

    def describe(self):
        """The identity of the sweep: what a resumed run must match."""
        return {"mode": "random" if self.samples else "grid", "samples": self.samples, "seed": self.seed,
                "params": {a.name: a.text() for a in self.axes}, "guess": [list(g) for g in self.guess],
                "solve": list(self.solve), "total": self.total}

    def points(self, ids):
        """(id, {axis: value}) of the cases `ids`, whatever the chunk: the grid's points row-major in the
        axes' order, or the draws (draw id: uniform(seed, [id]))."""
        ids = np.asarray(ids, dtype=np.int64).tolist()
        if not self.samples:
            grids = [a.grid().tolist() for a in self.axes]
            index = np.unravel_index(ids, [len(g) for g in grids]) if ids else [[] for _ in grids]
            return [(i, {a.name: grids[k][int(index[k][j])] for k, a in enumerate(self.axes)})
                    for j, i in enumerate(ids)]
        u = uniform(self.seed, ids, len(self.axes))
        return [(i, {a.name: float(a.sample(u[j, k])) for k, a in enumerate(self.axes)}) for j, i in enumerate(ids)]

    def columns(self, body):
        """The rows' columns, the same for every chunk: _row's, then start_NAME for each start value solved
        or set that is not an axis (Body.start_names)."""
        names = [a.name for a in self.axes]
        given = [n for n in names if n not in CASE_AXES]
        head = ["id", "status", "message"] + names
        fixed = [c for c in ROW if c not in head]
        return head + fixed + [f"start_{n}" for n in body.start_names(given, self.solve) if n not in names]

    def frame(self, body, ids):
        """The typed rows (a DataFrame in `columns` order) of the cases `ids` on `body`."""
        rows = [_row(body, i, point, case_of(point, self.guess, self.solve)) for i, point in self.points(ids)]
        return typed(pd.DataFrame(rows, columns=self.columns(body)))


# A row's columns after the case's axes, in _row's order, and the types of those not float64.
ROW = ("epsilon", "delta", "v0", "quadrant", "p_plus", "b", "theorem", "e", "w1_star", "predicts_iwc", "iwc",
       "w", "v", "t_return") + PHASES + ("events", "w_error")
TYPES = {"id": "int64", "status": "string", "message": "string", "quadrant": "string", "theorem": "Int64",
         "predicts_iwc": "boolean", "iwc": "boolean", "events": "Int64"}


def typed(df):
    """The rows with every chunk's types (so a chunk with no run writes the columns of one that ran)."""
    return df.astype({c: TYPES.get(c, "float64") for c in df.columns})


def run_body_sweep(fmu, axes, *, fmi_type="ModelExchange", guess=(), solve=(), samples=0, seed=0, progress=None):
    """The rows (dicts) of the grid `axes`, or of `samples` draws from them, on the body FMU, through the
    interface `fmi_type`; `solve`: parameters solved for with the states not given (fmu.body.floor_start)."""
    rows = []
    with Body(fmu, fmi_type=fmi_type) as body:
        for case_id, point, case in cases(axes, guess, solve, samples, seed):
            rows.append(_row(body, case_id, point, case))
            if progress:
                progress(len(rows))
    return rows


def predicts_iwc(co, w10, w1_star, hypotheses):
    """What the theory predicts from the coefficients at the start: no IWC outside the paradox (p_plus >= 0);
    inside it, where Theorem 1 or 2 covers the start (`hypotheses` empty), IWC for b < 0 and, for b > 0,
    below the separatrix (w10 < w1*); None where the theorems say nothing."""
    if not general.paradox(co):
        return False
    if general.theorem_of(co) == 2:
        return bool(w10 < w1_star) if not hypotheses or "starts moving down" in hypotheses else None
    return None if hypotheses else True


def _row(body, case_id, point, case):
    nan = math.nan
    row = dict(id=case_id, status="failed", message="", **point)
    row.update(epsilon=case.epsilon, delta=case.delta, v0=case.v0 if case.v0 is not None else nan, quadrant="",
               p_plus=nan, b=nan, theorem=0, e=nan, w1_star=nan, predicts_iwc=None, iwc=None, w=nan, v=nan,
               t_return=nan, **dict.fromkeys(PHASES, nan), events=-1, w_error=nan)
    try:
        predicted = predict(body, case)
    except (BodyError, SimulationError) as err:
        row["message"] = str(err)
        return row
    co = predicted.coefficients
    row.update({f"start_{k}": v for k, v in predicted.start.items() if k not in point})
    row.update(v0=predicted.start_v0, quadrant=predicted.quadrant, p_plus=float(co.p_plus), b=float(co.b),
               theorem=predicted.theorem, e=predicted.e, w1_star=predicted.w1_star,
               predicts_iwc=predicts_iwc(co, case.w0 / case.epsilon, predicted.w1_star, predicted.hypotheses),
               status="outside" if predicted.hypotheses else "ok", message=predicted.hypotheses)
    try:
        outcome = body.run(case, predicted, doublings=DOUBLINGS)
    except NoReturn as err:     # no lift-off back to the floor: not an IWC
        row.update(status="no return", message=str(err), iwc=False)
        return row
    except SimulationError as err:
        row.update(status="failed", message=str(err))
        return row
    row.update(iwc=outcome.iwc, w=outcome.w, v=outcome.v, t_return=outcome.t_return, events=outcome.events,
               w_error=outcome.w_error,
               **{k: getattr(outcome, k) for k in PHASES})
    return row
