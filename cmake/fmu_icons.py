# SPDX-License-Identifier: BSD-2-Clause
"""The FMUs' icons, one drawing per model: the rod leaning on the rough floor (PainleveRod,
PainleveRodSI), the two-link arm whose tip drags on the floor (TwoLinkArm), the shaker table
on its spring (ShakerTable). Written as fmu_src/models/NAME/icon.png (256 x 256 pixels),
which the build packs as model.png (FMI 2.0) and terminalsAndIcons/icon.png (FMI 3.0). The
PNGs are committed (the build needs no matplotlib); run this after changing a drawing:

    python cmake/fmu_icons.py [OUT_DIR]      (default: fmu_src/models)
"""
import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Circle, FancyBboxPatch  # noqa: E402

SIZE = 256
INK, ROD, FLOOR, ACCENT = "#1f2a36", "#c0392b", "#7f8c8d", "#2e86c1"


def canvas():
    fig = plt.figure(figsize=(1, 1), dpi=SIZE)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    ax.set_aspect("equal")
    ax.axis("off")
    return fig, ax


def hatched_floor(ax, y):
    """The rough floor: a line with the hatching of a fixed surface below it."""
    ax.plot([0.05, 0.95], [y, y], color=INK, lw=2.2, solid_capstyle="butt")
    for k in range(10):
        x = 0.08 + 0.09 * k
        ax.plot([x, x - 0.05], [y, y - 0.05], color=FLOOR, lw=1.2)


def rod(ax, theta=math.radians(40), length=0.72, floor=0.22):
    """The rod touching the floor at its lower end, its centre of mass marked, the slip arrow."""
    hatched_floor(ax, floor)
    x0 = 0.2
    x1, y1 = x0 + length * math.cos(theta), floor + length * math.sin(theta)
    ax.plot([x0, x1], [floor, y1], color=ROD, lw=7, solid_capstyle="round")
    ax.add_patch(Circle(((x0 + x1) / 2, (floor + y1) / 2), 0.035, color=INK, zorder=3))
    ax.annotate("", xy=(0.08, floor - 0.09), xytext=(0.3, floor - 0.09),
                arrowprops=dict(arrowstyle="-|>", color=ACCENT, lw=2))
    ax.annotate("", xy=(x0 - 0.03, floor + 0.2), xytext=(x0 - 0.03, floor + 0.02),
                arrowprops=dict(arrowstyle="-|>", color=ACCENT, lw=2))


def arm(ax, floor=0.22):
    """A fixed pivot, two links, the tip on the floor."""
    hatched_floor(ax, floor)
    pivot = (0.22, 0.8)
    elbow = (0.55, 0.72)
    tip = (0.78, floor)
    ax.plot([pivot[0] - 0.08, pivot[0] + 0.08], [pivot[1] + 0.06, pivot[1] + 0.06], color=INK, lw=2.2)
    ax.plot([pivot[0], elbow[0], tip[0]], [pivot[1], elbow[1], tip[1]], color=ROD, lw=7, solid_capstyle="round")
    for point in (pivot, elbow):
        ax.add_patch(Circle(point, 0.035, facecolor="white", edgecolor=INK, lw=2, zorder=3))
    ax.annotate("", xy=(0.92, floor - 0.09), xytext=(0.7, floor - 0.09),
                arrowprops=dict(arrowstyle="-|>", color=ACCENT, lw=2))


def table(ax, ground=0.12):
    """The table top on a spring over the ground, the drive's up-and-down arrow, a rod resting on it."""
    hatched_floor(ax, ground)
    coils = 6
    ys = [ground + 0.02 + k * 0.3 / (2 * coils) for k in range(2 * coils + 1)]
    xs = [0.5 + (0.08 if k % 2 else -0.08) * (0 < k < 2 * coils) for k in range(2 * coils + 1)]
    ax.plot(xs, ys, color=INK, lw=2)
    top = ys[-1]
    ax.add_patch(FancyBboxPatch((0.14, top), 0.72, 0.09, boxstyle="round,pad=0.01", facecolor=ACCENT,
                                edgecolor=INK, lw=2))
    ax.plot([0.3, 0.74], [top + 0.1, top + 0.36], color=ROD, lw=6, solid_capstyle="round")
    ax.annotate("", xy=(0.08, top + 0.3), xytext=(0.08, top + 0.05),
                arrowprops=dict(arrowstyle="<|-|>", color=ACCENT, lw=2))


DRAWINGS = {"PainleveRod": rod, "PainleveRodSI": rod, "TwoLinkArm": arm, "ShakerTable": table}


def write(name, path):
    fig, ax = canvas()
    DRAWINGS[name](ax)
    fig.savefig(path, dpi=SIZE, transparent=True, metadata={"Software": None})
    plt.close(fig)


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parents[1] / "fmu_src" / "models"
    for name in DRAWINGS:
        (out / name).mkdir(parents=True, exist_ok=True)
        write(name, out / name / "icon.png")
        print(out / name / "icon.png")


if __name__ == "__main__":
    main()
