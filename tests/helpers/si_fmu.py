# SPDX-License-Identifier: BSD-2-Clause
"""What the SI rod's tests share (the FMU is conftest's si_fmu_path): the rod's mechanics
computed here from the outputs by the laws of docs/si_model.md §9-10 (not by the model's
equations): energy and the inputs' work."""
import numpy as np


def energy(rod, r):
    """E = m |V_cm|^2/2 + J phi^2/2 + m g Y + k gap^2/2 while the contact acts, from the outputs.
    (The contact's mode, not F_N > 0: a row recorded just before the event that ends it has
    the force's bracket a rounding error below 0 and the spring still in E.)"""
    spring = np.where(r["contact"], 0.5 * rod.k * r["gap"] ** 2, 0.0)
    return (0.5 * rod.m * (r["vx_cm"] ** 2 + r["vy_cm"] ** 2) + 0.5 * rod.J * r["phi"] ** 2
            + rod.m * rod.g * r["y_cm"] + spring)


def contact_impulses(rod, r, loads):
    """(I_N, I_T): the integrals of F_N and F_T from t = 0, by the CoM's momentum (§9)."""
    t = r["time"]
    I_N = rod.m * (r["vy_cm"] - r["vy_cm"][0]) - (loads.F_y - rod.m * rod.g) * t
    I_T = loads.F_x * t - rod.m * (r["vx_cm"] - r["vx_cm"][0])
    return I_N, I_T


def input_work(rod, r, floor, loads):
    """The work of the inputs from t = 0 (§10): a floor at constant (v, w), constant loads."""
    I_N, I_T = contact_impulses(rod, r, loads)
    return (floor.w * I_N - floor.v * I_T + loads.F_x * (r["x_cm"] - r["x_cm"][0])
            + loads.F_y * (r["y_cm"] - r["y_cm"][0]) + loads.tau * (r["theta"] - r["theta"][0]))


def on_grid(r, interval):
    """The rows of a recorded run at the output grid's times (the last row at each, so after an
    event there), without the events' own rows."""
    t = r["time"]
    k = np.round(t / interval)
    keep = np.isclose(t, k * interval, rtol=1e-9, atol=1e-15) & np.append(t[1:] != t[:-1], True)
    return r[keep]
