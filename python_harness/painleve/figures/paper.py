# SPDX-License-Identifier: BSD-2-Clause
"""The paper's figures regenerated from simulations of the FMU: the numbers
behind each plot, with the analytic values they are to lie on.

- fig:GB: a grid of (theta, phi) states at alpha = 3, mu = 1.4, each run from
  the floor; what the FMU's rod does there names the quadrant (it stays on the
  floor slipping; it sticks and leaves with w = O(1), IWC; it lifts off, and a
  rod knocking the floor harder at the same state sticks: indeterminate).
- fig:eDelta0: w/v0 of the FMU at eps = 1e-4 and 1e-6 beside e(0, theta0)
  across the wedge (a) and e(delta, 1), e(delta, 1.2) with their asymptotes (b).
- video: two rods, mu = alpha = 3, delta = 1, eps = 1e-3, released at t = 0
  1e-3 apart, graze the floor at t = 0.5; one undergoes IWC, one lifts off.
"""
import math
import pathlib
from dataclasses import replace

import numpy as np

from ..experiments.case import Case
from ..experiments.outcome import outcome_of_trajectory, w_error
from ..experiments.strict_json import to_json
from ..fmu.body import Body
from ..theory import analytic as an

FIGURES = ("GB", "eDelta0", "video", "eLaw", "paradox")     # paradox: every body FMU's (figures.body)


# ------------------------------------------------------------------ fig:GB
GB = dict(alpha=3.0, mu=1.4, delta=1.0, epsilon=1e-5, v0=1.0, horizon=0.02)
GB_THETAS = np.linspace(0.80, 1.40, 21)
GB_PHIS = np.linspace(0.50, 1.60, 19)
LEFT = 1e-6     # y at the horizon above which the rod has left the floor (a rod on the floor stays at O(eps^2))


def _what_the_rod_does(r):
    """'IWC' (stuck, then left the floor), 'left' (left without sticking) or 'stays' (on the floor)."""
    contact = r["contact"].astype(bool)
    up = r["y"][-1] > LEFT
    if up and np.any(r["mode"][contact] == 0):
        return "IWC"
    return "left" if up else "stays"


def gb_quadrant(experiment, theta, phi, p=GB):
    """The quadrant of (theta, phi) as the FMU's rod shows it, from one or two runs."""
    start = dict(alpha=p["alpha"], mu=p["mu"], delta=p["delta"], epsilon=p["epsilon"],
                 x=0.0, y=0.0, w=0.0, v=p["v0"], theta=theta, phi=phi)
    run = dict(stop_time=p["horizon"], output_interval=p["horizon"] / 100)
    first = _what_the_rod_does(experiment.simulate_from(start, **run))
    if first != "left":
        return {"IWC": "inconsistent", "stays": "slipping"}[first]
    # It lifted off. Knock the floor at w = -eps W: W >= 2|w1*| wherever a separatrix exists
    # (|w1*| = b/lambda_+ <= b/sqrt|p_+|), an O(1) knock in the contact's scale.
    knock = 2 * an.b(theta, phi) / math.sqrt(abs(an.p_plus(theta, alpha=p["alpha"], mu=p["mu"]))) + 1
    second = _what_the_rod_does(experiment.simulate_from(dict(start, w=-p["epsilon"] * knock), **run))
    return "indeterminate" if second == "IWC" else "lift-off"


def gb_data(experiment, thetas=GB_THETAS, phis=GB_PHIS):
    p = GB
    points = []
    for theta in thetas:
        for phi in phis:
            theta, phi = float(theta), float(phi)
            points.append(dict(theta=theta, phi=phi, simulated=gb_quadrant(experiment, theta, phi),
                               analytic=str(an.quadrant(theta, phi, alpha=p["alpha"], mu=p["mu"])),
                               b=float(an.b(theta, phi)), p_plus=float(an.p_plus(theta, alpha=p["alpha"], mu=p["mu"]))))
    t1 = float(an.theta_1(alpha=p["alpha"], mu=p["mu"]))
    agree = [q["simulated"] == q["analytic"] for q in points]
    return dict(params=p, theta_1=t1, theta_2=float(an.theta_2(alpha=p["alpha"], mu=p["mu"])),
                P=[t1, 1 / math.sqrt(math.sin(t1))], points=points, agreement=sum(agree) / len(agree))


# ------------------------------------------------------------------ fig:eDelta0
E = dict(alpha=3.0, mu=1.4, phi0=0.5, v0=1.0)
E_EPSILONS = (1e-4, 1e-6)
E_DELTAS = (0.0, 0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0)
E_THETAS_B = (1.0, 1.2)


def edelta0_data(body):
    t1, t2 = an.theta_1(alpha=E["alpha"], mu=E["mu"]), an.theta_2(alpha=E["alpha"], mu=E["mu"])
    thetas = t1 + (t2 - t1) * np.linspace(0.05, 0.95, 13)
    a = []
    for theta0 in thetas:
        case = Case(theta0=float(theta0), delta=0.0, **E)
        exact = float(an.e_zero(theta0, alpha=E["alpha"], mu=E["mu"]))
        for eps in E_EPSILONS:
            o = body.run(replace(case, epsilon=eps))
            a.append(dict(theta0=float(theta0), epsilon=eps, e_simulated=o.w / o.case.v0, e_analytic=exact,
                          rel_error=w_error(o.w, o.case.v0, exact) / exact))
    b = []
    for theta0 in E_THETAS_B:
        for delta in E_DELTAS:
            case = Case(theta0=theta0, delta=delta, epsilon=E_EPSILONS[-1], **E)
            o = body.run(case)
            e = an.predict(case).e
            b.append(dict(theta0=theta0, delta=delta, epsilon=case.epsilon, e_simulated=o.w / case.v0,
                          e_analytic=e, rel_error=o.w_error / e))
    return dict(params=E, theta_1=float(t1), theta_2=float(t2), a=a, b=b)


# ------------------------------------------------------------------ video
VIDEO = dict(alpha=3.0, mu=3.0, delta=1.0, epsilon=1e-3, theta=0.9463, phi=1.6654, v=1.0, t_graze=0.5,
             separation=1e-3, stop_time=1.0)


def flight_back(state, T):
    """The state T earlier of a rod in free flight (F_N = 0): it spins uniformly and its
    centre of mass (x - cos theta, y + sin theta) falls freely, so the end A has
    v' = -phi^2 cos theta, w' = -1 + phi^2 sin theta (eq PainleveEqs with F_N = 0)."""
    ph, thg = state["phi"], state["theta"]
    th0 = thg - ph * T
    v0 = state["v"] + ph * (math.sin(thg) - math.sin(th0))
    w0 = state["w"] + T + ph * (math.cos(thg) - math.cos(th0))
    y0 = state["y"] - (w0 * T - T * T / 2 - (math.sin(thg) - math.sin(th0)) + ph * math.cos(th0) * T)
    x0 = state["x"] - (v0 * T + (math.cos(thg) - math.cos(th0)) + ph * math.sin(th0) * T)
    return dict(x=x0, v=v0, y=y0, w=w0, theta=th0, phi=ph)


def video_rods(p=VIDEO):
    """The two rods' states at t = 0. Both reach y = 0 at t_graze in the same configuration
    (theta, phi, v), moving down at w = eps w10: blue at w10 = w1*/3 (above the separatrix,
    lift-off), green lower by what puts their t = 0 states `separation` apart in (y, w)."""
    w1s = float(an.w1_star(p["theta"], p["phi"], p["delta"], alpha=p["alpha"], mu=p["mu"]))
    T, eps = p["t_graze"], p["epsilon"]
    blue_w10 = w1s / 3
    green_w10 = blue_w10 - p["separation"] / (eps * math.hypot(1.0, T))   # |(dy, dw)(0)| = |dw_graze| sqrt(1 + T^2)
    rods = {}
    for name, w10 in (("green", green_w10), ("blue", blue_w10)):
        graze = dict(x=0.0, y=0.0, w=eps * w10, v=p["v"], theta=p["theta"], phi=p["phi"])
        start = flight_back(graze, T)
        rods[name] = dict(w10=w10, start={**start, "x": 0.0})
    return w1s, rods


def video_data(experiment, p=VIDEO):
    w1s, rods = video_rods(p)
    params = dict(alpha=p["alpha"], mu=p["mu"], delta=p["delta"], epsilon=p["epsilon"])
    pp = float(an.p_plus(p["theta"], alpha=p["alpha"], mu=p["mu"]))
    qp = float(an.q_plus(p["theta"], alpha=p["alpha"], mu=p["mu"]))
    lam = float(an.lambda_pm(p["theta"], p["delta"], alpha=p["alpha"], mu=p["mu"])[0])
    e = float(an.e(p["delta"], p["theta"], alpha=p["alpha"], mu=p["mu"]))
    out = dict(params=p, w1_star=w1s, e=e, p_plus=pp, q_plus=qp, lambda_plus=lam,
               b=float(an.b(p["theta"], p["phi"])), rods={}, trajectories={})
    a, b_ = rods["green"]["start"], rods["blue"]["start"]
    out["separation_at_t0"] = math.hypot(a["y"] - b_["y"], a["w"] - b_["w"])
    for name, rod in rods.items():
        r = experiment.simulate_from({**params, **rod["start"]}, stop_time=p["stop_time"],
                                     output_interval=p["epsilon"] / 20, relative_tolerance=1e-10)
        contact = r["contact"].astype(bool)
        touch = int(np.flatnonzero(contact)[0])
        at = {k: float(r[k][touch]) for k in ("time", "v", "w", "theta", "phi")}
        case = Case(theta0=at["theta"], phi0=at["phi"], v0=at["v"], delta=p["delta"], epsilon=p["epsilon"],
                    w10=at["w"] / p["epsilon"], alpha=p["alpha"], mu=p["mu"])
        o = outcome_of_trajectory(case, r[touch:])
        in_contact = r[contact]
        out["rods"][name] = dict(
            w10=rod["w10"], start=rod["start"], touch=at, iwc=o.iwc, w_return=o.w, t_return=o.t_return,
            predicted_w=e * at["v"], min_w=float(in_contact["w"].min()), predicted_min_w=-pp / qp * at["v"],
            w_at_t_end=float(r["w"][-1]), y_at_t_end=float(r["y"][-1]))
        out["trajectories"][name] = r
    return out


# ------------------------------------------------------------------ eLaw
# e(delta, theta0) against the compliance law's nonlinearity: the rigid limit (rigid_limit)
# beside the FMU's w/v0 at small eps, each parameter alone, for three dampings.
LAW = dict(alpha=3.0, mu=3.0, theta0=0.9, phi0=0.5, v0=1.0)
LAW_DELTAS = (0.5, 1.0, 2.0)
LAW_VALUES = (0.0, 1.0, 3.0, 10.0, 20.0)
LAW_EPSILON = 1e-6


def elaw_data(body):
    points = []
    for parameter in ("kappa", "beta"):
        for delta in LAW_DELTAS:
            for value in LAW_VALUES:
                case = Case(delta=delta, epsilon=LAW_EPSILON, **LAW, **{parameter: value})
                o, e = body.run(case), an.predict(case).e
                points.append(dict(parameter=parameter, value=value, delta=delta, e_simulated=o.w / case.v0,
                                   e_analytic=e, rel_error=o.w_error / e))
    return dict(params=dict(LAW, epsilon=LAW_EPSILON), points=points)


# ------------------------------------------------------------------ all of them
def make_figures(fmu_path, out_dir, *, only=None, dpi=150, points=81):
    """Simulates, plots and writes fig_*.png, figures.json and figures.md, and the paradox region every body
    FMU gets (figures.body.paradox_figure: p_plus < 0 over theta from the FMU's outputs, on `points` grid
    points); returns the paths written."""
    from . import plots
    from .body import paradox_figure
    out = pathlib.Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    names = list(FIGURES if only is None else only)
    numbers, written = {}, []
    # The IWC cases run through fmu.body.Body, the runner of every body FMU; the free runs from a state
    # (the quadrants, the two rods) are trajectories of its Experiment.
    with Body(fmu_path) as body:
        experiment = body.experiment
        if "GB" in names:
            numbers["GB"] = gb_data(experiment)
            written.append(plots.plot_gb(numbers["GB"], out / "fig_GB.png", dpi=dpi))
        if "eDelta0" in names:
            numbers["eDelta0"] = edelta0_data(body)
            written.append(plots.plot_edelta0(numbers["eDelta0"], out / "fig_eDelta0.png", dpi=dpi))
        if "video" in names:
            numbers["video"] = video_data(experiment)
            written.append(plots.plot_video(numbers["video"], out / "fig_video.png", dpi=dpi))
            numbers["video"].pop("trajectories")
        if "eLaw" in names:
            numbers["eLaw"] = elaw_data(body)
            written.append(plots.plot_elaw(numbers["eLaw"], out / "fig_eLaw.png", dpi=dpi))
    (out / "figures.json").write_text(to_json(numbers, indent=1))
    (out / "figures.md").write_text(summary_markdown(numbers, fmu_path))
    region = paradox_figure(fmu_path, out, n=points, dpi=dpi) if "paradox" in names else []
    return [str(p) for p in written] + [str(out / "figures.json"), str(out / "figures.md")] + region


def summary_markdown(numbers, fmu_path):
    lines = [f"# The paper's figures from simulations of {fmu_path}", ""]
    if "GB" in numbers:
        g = numbers["GB"]
        lines += ["## The quadrants of the (theta, phi) plane (fig_GB.png)", "",
                  f"{len(g['points'])} states on a grid, alpha = {g['params']['alpha']:g}, mu = {g['params']['mu']:g}, "
                  f"eps = {g['params']['epsilon']:g}: the FMU's rod names the analytic quadrant at "
                  f"{g['agreement']:.1%} of them (the others lie next to p_+ = 0, where the rigid picture "
                  f"needs eps -> 0 first).", ""]
    if "eDelta0" in numbers:
        d = numbers["eDelta0"]
        worst_a = max(abs(q["rel_error"]) for q in d["a"] if q["epsilon"] == E_EPSILONS[-1])
        worst_b = max(abs(q["rel_error"]) for q in d["b"])
        lines += ["## The coefficient e(delta, theta0) (fig_eDelta0.png)", "",
                  f"(a) w/v0 of the FMU beside e(0, theta0) across the wedge ({d['theta_1']:.4f}, {d['theta_2']:.4f}): "
                  f"largest relative deviation {worst_a:.2%} at eps = {E_EPSILONS[-1]:g}.",
                  f"(b) w/v0 beside e(delta, theta0) for theta0 = 1, 1.2: largest relative deviation "
                  f"{worst_b:.2%} at eps = {E_EPSILONS[-1]:g}.", ""]
    if "video" in numbers:
        v = numbers["video"]
        g, b = v["rods"]["green"], v["rods"]["blue"]
        lines += ["## Two rods, one IWC, one lift-off (fig_video.png)", "",
                  f"Two rods 1e-3 apart at t = 0 (|(dy, dw)| = {v['separation_at_t0']:.3g}) graze y = 0 at "
                  f"t = {g['touch']['time']:.4f} with w = {g['touch']['w']:.3g} (green) and {b['touch']['w']:.3g} "
                  f"(blue), either side of eps w1* = {v['params']['epsilon'] * v['w1_star']:.3g}.",
                  f"Green: IWC {g['iwc']}, leaves with w = {g['w_return']:.4f} vs e v0 = {g['predicted_w']:.4f}; "
                  f"deepest w = {g['min_w']:.4f} vs -p_+ v0/q_+ = {g['predicted_min_w']:.4f}.",
                  f"Blue: IWC {b['iwc']}, leaves with w = {b['w_return']:.3g} = "
                  f"{b['w_return'] / v['params']['epsilon']:.3g} eps.",
                  ""]
    if "eLaw" in numbers:
        d = numbers["eLaw"]
        worst = max(abs(q["rel_error"]) for q in d["points"])
        lines += ["## e against the compliance law's nonlinearity (fig_eLaw.png)", "",
                  f"w/v0 of the FMU at eps = {d['params']['epsilon']:g} beside the rigid limit's e for kappa and "
                  f"beta from 0 to {max(LAW_VALUES):g} (theta0 = {d['params']['theta0']:g}, delta = "
                  f"{', '.join(f'{x:g}' for x in LAW_DELTAS)}): largest relative deviation {worst:.1e}.", ""]
    return "\n".join(lines)
