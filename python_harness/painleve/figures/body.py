# SPDX-License-Identifier: BSD-2-Clause
"""The paradox region of any body FMU (p_plus < 0, forward slip) over its configuration, from the FMU's
own outputs: p_plus over a grid of the start values it depends on (its ModelStructure dependencies, or the
axes the user names), the curve p_plus = 0, and, in two dimensions, the configurations with the contact
point on the floor (y = 0), where an IWC can start. Writes the PNG and a JSON of the grid."""
import json
import pathlib

import numpy as np

from ..fmu.body import Body, BodyError


def configuration_axes(body: Body):
    """The start values p_plus depends on at the start (the FMU's ModelStructure, InitialUnknowns): the
    body's configuration coordinates."""
    md = body.experiment.model_description
    for out in md.initialUnknowns:
        if out.variable.name == "p_plus" and out.dependencies:
            return [d.name for d in out.dependencies if d.name in body.start_variables]
    raise BodyError(f"{body.name} declares no dependencies of p_plus: name the axes (--axes)")


def paradox_grid(body: Body, given, axes, ranges, n):
    """p_plus (and y) on an n-point grid per axis; the other start values from `given` and the FMU."""
    grids = [np.linspace(lo, hi, n) for lo, hi in ranges]
    mesh = np.meshgrid(*grids, indexing="ij")
    pp, yy = np.empty(mesh[0].shape), np.empty(mesh[0].shape)
    for idx in np.ndindex(mesh[0].shape):
        out = body.outputs(dict(given, **{a: float(m[idx]) for a, m in zip(axes, mesh)}), ("p_plus", "y"))
        pp[idx], yy[idx] = out["p_plus"], out["y"]
    return grids, pp, yy


def paradox_figure(fmu, out_dir, *, given=None, axes=None, ranges=None, n=81, dpi=150):
    """Writes paradox_region.png and paradox_region.json in out_dir; returns their paths."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    given = dict(given or {})
    with Body(fmu) as body:
        axes = list(axes or configuration_axes(body))
        if not 1 <= len(axes) <= 2:
            raise BodyError(f"the paradox region is drawn over 1 or 2 coordinates; {body.name} has {axes}")
        ranges = ranges or [(-np.pi, np.pi)] * len(axes)
        grids, pp, yy = paradox_grid(body, given, axes, ranges, n)
        name = body.name
        marked = {**body.defaults(axes), **{a: given[a] for a in axes if a in given}}
    out = pathlib.Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    fig, ax = plt.subplots(figsize=(6.5, 5.5))
    if len(axes) == 2:
        region = ax.contourf(grids[0], grids[1], pp.T, levels=[pp.min() - 1, 0], colors=["tab:red"], alpha=0.35)
        ax.contour(grids[0], grids[1], pp.T, levels=[0], colors="tab:red", linewidths=1.2)
        ax.contour(grids[0], grids[1], yy.T, levels=[0], colors="k", linewidths=1.0, linestyles="--")
        ax.set_xlabel(axes[0])
        ax.set_ylabel(axes[1])
        ax.plot([], [], color="tab:red", label="p_plus < 0 (Painleve paradox, forward slip)")
        ax.plot([], [], "k--", label="y = 0 (contact point on the floor)")
        if len(marked) == 2:
            ax.plot(marked[axes[0]], marked[axes[1]], "k*", ms=10, label="start values (the FMU's or --set)")
        del region
    else:
        ax.plot(grids[0], pp, color="k", label="p_plus")
        ax.fill_between(grids[0], pp, 0, where=pp < 0, color="tab:red", alpha=0.35, label="p_plus < 0")
        ax.axhline(0, color="gray", lw=0.8)
        ax.set_xlabel(axes[0])
        ax.set_ylabel("p_plus")
    ax.set_title(f"{name}: the paradox region from the FMU's outputs")
    ax.legend(loc="upper right", fontsize=8)
    png, data = out / "paradox_region.png", out / "paradox_region.json"
    fig.savefig(png, dpi=dpi)
    plt.close(fig)
    data.write_text(json.dumps({"fmu": str(fmu), "model": name, "axes": axes, "given": given,
                                "grids": [g.tolist() for g in grids], "p_plus": pp.tolist(), "y": yy.tolist(),
                                "paradox_fraction": float(np.mean(pp < 0)), "marked": marked}))
    return [str(png), str(data)]


def sweep_map_figure(rows, axes, path, *, title="", dpi=150):
    """Two panels over the sweep's axes (two names of its columns): left, each case as the simulation ended
    it (IWC, no IWC, not run); right, the theory at its start: p_plus < 0 (the paradox) or not, filled where
    Theorem 1 or 2 predicts an IWC. `rows`: sweep.body's rows (dicts, or their DataFrame). Returns the PNG's path."""
    import matplotlib
    import pandas as pd
    rows = rows if isinstance(rows, pd.DataFrame) else pd.DataFrame(rows)
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    x, y = (rows[a].to_numpy(dtype=float) for a in axes)
    ran = rows["iwc"].notna().to_numpy()
    stuck = ran & rows["iwc"].fillna(False).astype(bool).to_numpy()
    paradox = (rows["p_plus"] < 0).to_numpy()
    predicted = np.array([not pd.isna(v) and bool(v) for v in rows["predicts_iwc"]], dtype=bool)
    told = rows["predicts_iwc"].notna().to_numpy() & ran
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 6), sharex=True, sharey=True)
    left.scatter(x[stuck], y[stuck], c="tab:red", s=28, label="IWC (stuck, then lifted off)")
    left.scatter(x[ran & ~stuck], y[ran & ~stuck], facecolors="none", edgecolors="tab:blue", s=28, label="no IWC")
    left.scatter(x[~ran], y[~ran], marker="x", c="gray", s=20, label="no start on the floor, or failed")
    left.set_title("simulation")
    right.scatter(x[paradox & predicted], y[paradox & predicted], c="tab:red", s=28,
                  label="p_plus < 0, Theorem 1 or 2: IWC")
    right.scatter(x[paradox & ~predicted], y[paradox & ~predicted], facecolors="none", edgecolors="tab:red", s=28,
                  label="p_plus < 0, no IWC predicted (or no theorem)")
    right.scatter(x[~paradox], y[~paradox], facecolors="none", edgecolors="tab:blue", s=28, label="p_plus >= 0")
    agree = int(np.sum(predicted[told] == stuck[told]))
    right.set_title(f"theory (p_plus < 0); prediction met in {agree} of {int(told.sum())}")
    for ax in (left, right):
        ax.set_xlabel(axes[0])
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.12), fontsize=7)
    left.set_ylabel(axes[1])
    fig.suptitle(f"paradox map of {title}".strip(), fontsize=10)
    fig.tight_layout()
    out = pathlib.Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return str(out)
