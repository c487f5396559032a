"""The coupled study's figure: the rod and the table over time, and the contact forces on
both sides of the coupling (the rod's outputs, and the inputs the table held: steps, since the
master holds each value over a communication step)."""
from __future__ import annotations

import numpy as np

from .coupled import ROD, TABLE


def coupled_figure(r, path, *, setup, title="", dpi=150):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rod, table = setup.rod_values(), setup.table_values()
    t = np.concatenate(([0.0], r["time"]))

    def series(name, start):
        return np.concatenate(([start], r[name]))

    fig, (ax_y, ax_w, ax_f) = plt.subplots(3, 1, figsize=(9, 9), sharex=True)
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
    ax_f.plot(r["time"], r[f"{ROD}.F_N"], label="F_N on the rod (up): rod output")
    ax_f.step(r["time"], -r[f"{TABLE}.F_N"], where="pre", label="-F_N on the table (down): held input")
    ax_f.plot(r["time"], -r[f"{ROD}.F_T"], label="-F_T on the rod (along x): rod output")
    ax_f.step(r["time"], r[f"{TABLE}.F_T"], where="pre", label="F_T on the table: held input")
    ax_f.set_ylabel("force [N]")
    ax_f.set_xlabel("time [s]")
    ax_f.legend(loc="best", fontsize="small")
    if title:
        fig.suptitle(title, fontsize="medium")
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return path
