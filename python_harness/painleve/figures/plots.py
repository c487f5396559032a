# SPDX-License-Identifier: BSD-2-Clause
"""Drawing the figures of `figures` with matplotlib: simulated points as
markers, the paper's analytic curves as lines, written as PNG files."""
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ..theory import analytic as an  # noqa: E402

QUADRANT_STYLE = {   # marker, colour
    "indeterminate": ("^", "tab:purple"),
    "lift-off": ("o", "tab:blue"),
    "slipping": ("s", "tab:green"),
    "inconsistent": ("D", "tab:red"),
}
GREEN, BLUE = "tab:green", "tab:blue"


def _save(fig, path, dpi):
    fig.savefig(path, dpi=dpi, bbox_inches="tight")
    plt.close(fig)
    return path


def plot_gb(d, path, *, dpi=150):
    """fig:GB: quadrants of the (theta, phi) plane around P, lines b = 0 and p_+ = 0."""
    p = d["params"]
    fig, ax = plt.subplots(figsize=(9.5, 6))
    for name, (marker, colour) in QUADRANT_STYLE.items():
        pts = [q for q in d["points"] if q["simulated"] == name]
        if pts:
            ax.scatter([q["theta"] for q in pts], [q["phi"] for q in pts], marker=marker, s=22, color=colour,
                       alpha=0.8, label=f"FMU: {name}")
    wrong = [q for q in d["points"] if q["simulated"] != q["analytic"]]
    if wrong:
        ax.scatter([q["theta"] for q in wrong], [q["phi"] for q in wrong], s=90, facecolors="none",
                   edgecolors="k", linewidths=0.8, label="FMU differs from the quadrant")
    thetas = np.linspace(min(q["theta"] for q in d["points"]), max(q["theta"] for q in d["points"]), 400)
    ax.plot(thetas, 1 / np.sqrt(np.sin(thetas)), "k-", lw=1.6, label=r"$b = 0$: $\phi = \sqrt{\csc\theta}$")
    for t in (d["theta_1"], d["theta_2"]):
        ax.axvline(t, color="k", ls="--", lw=1.2)
    ax.plot([], [], "k--", label=r"$p_+ = 0$: $\theta = \theta_{1,2}$")
    ax.plot(*d["P"], "ko", ms=7)
    ax.annotate("P", d["P"], xytext=(-14, 6), textcoords="offset points", fontsize=12)
    labels = [("indeterminate\n" r"$b>0,\ p_+<0$", 1.09, 1.5), ("lift-off\n" r"$b>0,\ p_+>0$", 0.86, 1.5),
              ("slipping\n" r"$b<0,\ p_+>0$", 0.86, 0.6), ("inconsistent\n" r"$b<0,\ p_+<0$", 1.09, 0.6)]
    for text, x, y in labels:
        ax.text(x, y, text, ha="center", va="center", fontsize=9,
                bbox=dict(boxstyle="round", fc="white", ec="0.6", alpha=0.85))
    ax.set_xlabel(r"$\theta$")
    ax.set_ylabel(r"$\phi$")
    ax.set_title(rf"Quadrants of the $(\theta,\phi)$-plane, $\alpha={p['alpha']:g}$, $\mu={p['mu']:g}$; points: what the "
                 rf"FMU's rod does ($\epsilon={p['epsilon']:g}$)", fontsize=10)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, framealpha=0.9)
    return _save(fig, path, dpi)


def plot_edelta0(d, path, *, dpi=150):
    """fig:eDelta0: (a) e(0, theta0) on the wedge, (b) e(delta, theta0) with the small and large delta asymptotes."""
    p = d["params"]
    al, mu = p["alpha"], p["mu"]
    fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(12, 4.8))
    t1, t2 = d["theta_1"], d["theta_2"]
    th = np.linspace(t1 + 1e-6, t2 - 1e-6, 400)
    ax_a.plot(th, an.e_zero(th, alpha=al, mu=mu), "k-", lw=1.5, label=r"$e(0,\theta_0)$, the closed form")
    for eps, style in zip(sorted({q["epsilon"] for q in d["a"]}, reverse=True), ("o", "x")):
        pts = [q for q in d["a"] if q["epsilon"] == eps]
        ax_a.plot([q["theta0"] for q in pts], [q["e_simulated"] for q in pts], style, color="tab:red",
                  mfc="none" if style == "o" else None, ms=7, label=rf"FMU $w/v_0$, $\epsilon={eps:g}$")
    for t, name in ((t1, r"$\theta_1$"), (t2, r"$\theta_2$")):
        ax_a.axvline(t, color="0.5", ls=":", lw=1)
        ax_a.text(t, 0.002, name, ha="center", va="bottom", fontsize=10)
    ax_a.set_xlabel(r"$\theta_0$")
    ax_a.set_ylabel(r"$e(0,\theta_0)$")
    ax_a.set_ylim(bottom=0)
    ax_a.set_title(f"(a) $\\delta = 0$, $\\alpha={al:g}$, $\\mu={mu:g}$", fontsize=10)
    ax_a.legend(fontsize=8)

    deltas = np.linspace(0, max(q["delta"] for q in d["b"]), 400)
    top = 0
    for theta0, colour in zip(sorted({q["theta0"] for q in d["b"]}), ("tab:blue", "tab:orange")):
        curve = an.e(deltas, theta0, alpha=al, mu=mu)
        top = max(top, float(np.max(curve)))
        ax_b.plot(deltas, curve, "-", color=colour, lw=1.5, label=rf"$e(\delta,{theta0:g})$")
        small = deltas[deltas <= 1.5]
        ax_b.plot(small, an.e_small_delta(small, theta0, alpha=al, mu=mu), "--", color=colour, lw=1)
        large = deltas[deltas >= 0.8]
        ax_b.plot(large, an.e_large_delta(large, theta0, alpha=al, mu=mu), "--", color=colour, lw=1)
        pts = [q for q in d["b"] if q["theta0"] == theta0]
        ax_b.plot([q["delta"] for q in pts], [q["e_simulated"] for q in pts], "x", color="tab:red", ms=7)
    ax_b.plot([], [], "k--", lw=1, label="asymptotes for small and large delta")
    ax_b.plot([], [], "x", color="tab:red", label=rf"FMU $w/v_0$, $\epsilon={d['b'][0]['epsilon']:g}$")
    ax_b.set_ylim(0, 1.15 * top)
    ax_b.set_xlabel(r"$\delta$")
    ax_b.set_ylabel(r"$e(\delta,\theta_0)$")
    ax_b.set_title(f"(b) $\\alpha={al:g}$, $\\mu={mu:g}$", fontsize=10)
    ax_b.legend(fontsize=8)
    fig.suptitle("The horizontal coefficient of restitution: analytic curves, FMU points", fontsize=11)
    return _save(fig, path, dpi)


def _rod(ax, state, colour, **kw):
    x, y, th = state["x"], state["y"], state["theta"]
    ax.plot([x, x - 2 * math.cos(th)], [y, y + 2 * math.sin(th)], "-", color=colour, lw=2.2, **kw)
    ax.plot([x], [y], "o", color=colour, ms=3.5)


def plot_video(d, path, *, dpi=150):
    """video: (a) the rods at t = 0, 0.25, 0.5, 1; (b) the (w, y/eps) plane; (c) w(t); (d) v(t) near the graze."""
    p, traj = d["params"], d["trajectories"]
    eps, delta = p["epsilon"], p["delta"]
    fig, axes = plt.subplots(2, 2, figsize=(13, 9))
    ax_a, ax_b, ax_c, ax_d = axes.ravel()
    colours = {"green": GREEN, "blue": BLUE}
    for name, r in traj.items():
        for t in (0.0, 0.25, 0.5, 1.0):
            i = int(np.argmin(np.abs(r["time"] - t)))
            _rod(ax_a, {k: r[k][i] for k in ("x", "y", "theta")}, colours[name], alpha=0.85)
    for t in (0.0, 0.25, 0.5, 1.0):
        r = traj["green"]
        i = int(np.argmin(np.abs(r["time"] - t)))
        ax_a.annotate(f"t = {t:g}", (r["x"][i] - math.cos(r["theta"][i]), r["y"][i] + 2 * math.sin(r["theta"][i])),
                      xytext=(0, 8), textcoords="offset points", ha="center", fontsize=8)
    ax_a.axhline(0, color="k", lw=1)
    ax_a.fill_between(ax_a.get_xlim(), -0.15, 0, color="0.85")
    ax_a.set_aspect("equal")
    ax_a.set_ylim(-0.15, ax_a.get_ylim()[1] + 0.35)
    ax_a.set_xlabel("x")
    ax_a.set_ylabel("y")
    ax_a.set_title(rf"(a) two rods {p['separation']:g} apart at t = 0: green IWC, blue lifts off", fontsize=10)

    g = d["rods"]["green"]
    t0, t1 = g["touch"]["time"] - 0.4 * (g["t_return"] - g["touch"]["time"]), g["t_return"] + 4e-3
    lam, v0 = d["lambda_plus"], g["touch"]["v"]
    w_stick = g["predicted_min_w"]
    wline = np.linspace(1.15 * w_stick, 1.15 * g["predicted_w"], 50)
    ax_b.fill_between(wline, np.minimum(-delta * wline, 0), -10, color="0.9", label=r"$\hat F_N > 0$")
    for name, r in traj.items():
        m = (r["time"] >= t0) & (r["time"] <= t1)
        ax_b.plot(r["w"][m], r["y"][m] / eps, "-", color=colours[name], lw=1.6, label=f"{name} (FMU)")
    ws = np.linspace(w_stick, 0, 50)
    ax_b.plot(ws, ws / lam, "-", color="tab:red", lw=4, alpha=0.45, zorder=1,
              label=r"$\gamma^u$: $\hat y = w/\lambda_+$, the unstable manifold")
    ax_b.plot(wline, -delta * wline, "k--", lw=1, label=r"$\hat y + \delta w = 0$")
    ax_b.plot([w_stick], [w_stick / lam], "o", mfc="none", color="k", ms=9,
              label=r"stick starts (end of slipping compression)")
    ax_b.plot([g["predicted_w"]], [-delta * g["predicted_w"]], "s", mfc="none", color="k", ms=9,
              label=r"lift-off $w = e v_0$ (Thm 1)")
    green = traj["green"]
    lo = float(np.min(green["y"][(green["time"] >= t0) & (green["time"] <= t1)])) / eps
    ax_b.set_ylim(1.15 * lo, 0.3 * abs(lo))
    ax_b.set_xlim(wline[0], wline[-1])
    ax_b.set_xlabel("w")
    ax_b.set_ylabel(r"$\hat y = y/\epsilon$")
    ax_b.set_title(r"(b) the $(w,\hat y)$-plane", fontsize=10)
    ax_b.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(1.01, 1.0))

    for ax, key, title in ((ax_c, "w", "(c) w(t)"), (ax_d, "v", "(d) v(t)")):
        for name, r in traj.items():
            m = (r["time"] >= t0) & (r["time"] <= t1)
            ax.plot(r["time"][m], r[key][m], "-", color=colours[name], lw=1.6, label=f"{name} (FMU)")
        ax.set_xlabel("t")
        ax.set_ylabel(key)
        ax.set_title(title, fontsize=10)
    ax_c.axhline(g["predicted_w"], color="k", ls="--", lw=1, label=rf"$w = e v_0$ = {g['predicted_w']:.4f}")
    ax_c.axhline(w_stick, color="k", ls=":", lw=1, label=rf"$w = -p_+ v_0/q_+$ = {w_stick:.4f}")
    ax_c.legend(fontsize=8)
    ax_d.legend(fontsize=8)
    fig.suptitle(rf"video — $\mu=\alpha={p['alpha']:g}$, $\delta={delta:g}$, $\epsilon={eps:g}$: graze at "
                 rf"$\theta\approx{p['theta']}$, $\phi\approx{p['phi']}$, $v\approx{v0:.2f}$; "
                 rf"$w_{{1*}}={d['w1_star']:.3f}$", fontsize=11)
    return _save(fig, path, dpi)


def plot_elaw(d, path, *, dpi=150):
    """e(delta, theta0) against the compliance law's kappa (a) and beta (b): the rigid limit
    (painleve.theory.rigid_limit) as curves, the FMU's w/v0 at small eps as points."""
    from ..theory import rigid_limit
    p = d["params"]
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    for ax, parameter, what in zip(axes, ("kappa", "beta"), ("(a) a stiffening spring", "(b) damping that grows "
                                                                                          "with penetration")):
        pts = [q for q in d["points"] if q["parameter"] == parameter]
        values = np.linspace(0.0, max(q["value"] for q in pts), 60)
        for delta, colour in zip(sorted({q["delta"] for q in pts}), ("tab:blue", "tab:orange", "tab:green")):
            curve = rigid_limit.e(delta, p["theta0"], v0=p["v0"], alpha=p["alpha"], mu=p["mu"],
                                  **{parameter: values})
            ax.plot(values, curve, "-", color=colour, lw=1.5, label=rf"rigid limit, $\delta={delta:g}$")
            mine = [q for q in pts if q["delta"] == delta]
            ax.plot([q["value"] for q in mine], [q["e_simulated"] for q in mine], "x", color=colour, ms=8)
        ax.plot([], [], "kx", label=rf"FMU $w/v_0$, $\epsilon={p['epsilon']:g}$")
        ax.set_xlabel(rf"$\{parameter}$")
        ax.set_ylabel(r"$e$")
        ax.set_ylim(bottom=0)
        ax.set_title(what, fontsize=10)
        ax.legend(fontsize=8)
    fig.suptitle(rf"e against the compliance law's nonlinearity: $\theta_0={p['theta0']:g}$, "
                 rf"$\alpha={p['alpha']:g}$, $\mu={p['mu']:g}$, $v_0={p['v0']:g}$", fontsize=11)
    return _save(fig, path, dpi)
