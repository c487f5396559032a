# SPDX-License-Identifier: BSD-2-Clause
"""The coupled study's figure: the rod and the table over time, and the contact forces on
both sides of the coupling (the rod's outputs, and the inputs the table held: steps, since the
master holds each value over a communication step)."""
from __future__ import annotations

import numpy as np

from ..coupling.coupled import ROD, TABLE


def coupled_figure(r, path, *, setup, title="", dpi=150):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rod, table = setup.rod_values(), setup.table_values()
    t = np.concatenate(([0.0], r["time"]))

    def series(name, start):
        return np.concatenate(([start], r[name]))

    fig, (ax_y, ax_w, ax_n, ax_t) = plt.subplots(4, 1, figsize=(9, 11), sharex=True)
    ax_y.plot(t, 1e3 * series(f"{ROD}.y", rod["y"]), label="rod: contact end y")
    ax_y.plot(t, 1e3 * series(f"{TABLE}.position", table["position"]), label="table: surface z")
    ax_y.plot(t, 1e3 * series(f"{ROD}.y_cm", rod["y"] + rod["l"] * np.sin(rod["theta"])), ":",
              label="rod: centre of mass y_cm")
    ax_y.set_ylabel("height [mm]")
    ax_y.legend(loc="best", fontsize="small")
    ax_w.plot(t, series(f"{ROD}.w", rod["w"]), label="rod: w (contact end)")
    ax_w.plot(t, series(f"{TABLE}.velocity", table["velocity"]), label="table: z'")
    ax_w.set_ylabel("vertical velocity [m/s]")
    ax_w.legend(loc="best", fontsize="small")
    # Both sides of each force, in the same sign: on the rod as the rod computes it (its output at
    # each communication point), on the table as the table held it (a step per communication step).
    ax_n.plot(r["time"], r[f"{ROD}.F_N"], label="F_N on the rod, upwards (rod's output)")
    ax_n.step(t, np.concatenate((r[f"{TABLE}.F_N"][:1], r[f"{TABLE}.F_N"])), where="post", linestyle="--",
              label="F_N on the table, downwards (the input it held)")
    ax_n.set_ylabel("normal force [N]")
    ax_t.plot(r["time"], r[f"{ROD}.F_T"], label="F_T: on the rod -F_T along x (rod's output)")
    ax_t.step(t, np.concatenate((r[f"{TABLE}.F_T"][:1], r[f"{TABLE}.F_T"])), where="post", linestyle="--",
              label="F_T: on the table +F_T along x (the input it held)")
    ax_t.set_ylabel("tangential force [N]")
    ax_t.set_xlabel("time [s]")
    for ax in (ax_n, ax_t):
        ax.set_yscale("symlog", linthresh=1.0)      # the impact's kN beside the resting rod's N
        ax.legend(loc="best", fontsize="small")
    if title:
        fig.suptitle(title, fontsize="medium")
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return path
