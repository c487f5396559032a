# SPDX-License-Identifier: BSD-2-Clause
"""The hypotheses of the paper's results: a failing one raises HypothesisError naming it,
over numpy arrays (the first failing element is named), all failures at once."""
import numpy as np


class HypothesisError(ValueError):
    """Arguments outside the hypotheses of the paper's result being evaluated.

    ``hypotheses`` lists the failing hypotheses (as written in the message).
    """

    def __init__(self, message, hypotheses=()):
        super().__init__(message)
        self.hypotheses = list(hypotheses)


def as_result(x):
    """Float for 0-d results, the array otherwise."""
    x = np.asarray(x)
    return x.item() if x.ndim == 0 else x


def floats(x):
    """x as a float array."""
    return np.asarray(x, dtype=float)


def fmt(x):
    return f"{float(x):.4g}"


class Hypotheses:
    """Collects failing hypotheses of `who` over broadcast arrays, then raises once."""

    def __init__(self, who, *arrays):
        self.who, self.fails = who, []
        shapes = [np.shape(x) for x in arrays if x is not None]
        self.shape = np.broadcast_shapes(*shapes) if any(shapes) else ()

    def bc(self, x):
        # x as it is where it has the shape already (a sweep's scalar case: broadcast_to's
        # own cost is most of a prediction's)
        x = floats(x)
        return x if x.shape == self.shape else np.broadcast_to(x, self.shape)

    def need(self, ok, hyp, got, note=None):
        """Record `hyp` if any element of ok is False; got(i)/note(i) describe flat element i."""
        ok = np.asarray(ok, dtype=bool)
        if ok.all():
            return
        bad = ~(ok if ok.shape == self.shape else np.broadcast_to(ok, self.shape))
        if bad.any():
            i = int(np.flatnonzero(bad.ravel())[0])
            where = (f" at element {tuple(int(k) for k in np.unravel_index(i, self.shape))}"
                     if self.shape else "")
            extra = f" ({note(i)})" if note else ""
            self.fails.append((hyp, f"{extra}; got {got(i)}{where}"))

    def scalar(self, name, x, ok_fn, hyp):
        if x is not None:
            xb = self.bc(x)
            self.need(ok_fn(xb), hyp, lambda i: f"{name} = {fmt(xb.ravel()[i])}")

    def done(self):
        if self.fails:
            msg = "; ".join(f"{self.who} needs {hyp}{extra}" for hyp, extra in self.fails)
            raise HypothesisError(msg, [hyp for hyp, _ in self.fails])


def rod_parameters(alpha, mu, who="the rod model"):
    """alpha > 0 and mu >= 0, as float arrays."""
    h = Hypotheses(who, alpha, mu)
    h.scalar("alpha", alpha, lambda x: x > 0, "alpha > 0")
    h.scalar("mu", mu, lambda x: x >= 0, "mu >= 0")
    h.done()
    return floats(alpha), floats(mu)
