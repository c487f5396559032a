"""The coupled study of issue #15: PainleveRodSI on a ShakerTable, one SSP archive, run by a
co-simulation master (painleve.coupling.masters).

Coupling (docs/coupling.md): rod.y_floor <- table.position, rod.w_floor <- table.velocity,
rod.v_floor <- table.belt_velocity, table.F_N <- rod.F_N, table.F_T <- rod.F_T. The rod's F_N
pushes it up and the table down (Newton's third law across the connection); F_T is in the
paper's sign, -F_T on the rod along x, +F_T on the table.

What a run gives and what the physics fixes about it (the tests' independent checks):
- the impulse the table receives from the rod is the sum of h times the F_N it holds in each
  step (`impulse_on_table`); the impulse the rod receives is, by its momentum, m (vy_cm(T) -
  vy_cm(0)) + m g T with no applied load (`impulse_on_rod`); a Jacobi master with a zero-order
  hold hands the table the rod's F_N at the start of each step, a left Riemann sum, so the two
  differ by O(h): the difference halves with the step;
- the table's own momentum, M (z'(T) - z'(0)) = int(-K z - C z' + F0 sin(2 pi f t)) dt - the
  impulse it holds (`table_momentum_impulse`).
"""
from __future__ import annotations

import math
import pathlib
import tempfile
from dataclasses import dataclass, field

import numpy as np

from .si import Floor, SIRod, SIState, case_of
from .ssp import Component, Connection, write_ssp

ROD, TABLE = "rod", "table"
ROD_INPUTS = ("y_floor", "w_floor", "v_floor")
TABLE_INPUTS = ("F_N", "F_T")
ROD_OUTPUTS = ("x", "v", "y", "w", "theta", "phi", "F_N", "F_T", "energy", "x_cm", "y_cm", "vx_cm", "vy_cm",
               "gap", "t_contact_end")
TABLE_OUTPUTS = ("position", "velocity", "belt_velocity")
CONNECTIONS = (
    Connection((TABLE, "position"), (ROD, "y_floor")),
    Connection((TABLE, "velocity"), (ROD, "w_floor")),
    Connection((TABLE, "belt_velocity"), (ROD, "v_floor")),
    Connection((ROD, "F_N"), (TABLE, "F_N")),
    Connection((ROD, "F_T"), (TABLE, "F_T")),
)
# every variable a run records: the components' outputs and the inputs as each FMU held them
RECORD = tuple(f"{ROD}.{n}" for n in ROD_OUTPUTS + ROD_INPUTS) + \
    tuple(f"{TABLE}.{n}" for n in TABLE_OUTPUTS + TABLE_INPUTS)

# The models' defaults (ISSUE15.md): the rod's (painleve.coupling.si's SIRod and SIState), the table's.
ROD_DEFAULTS = {**SIRod().parameters(), **SIState().start_values()}
TABLE_DEFAULTS = dict(M=10.0, K=4e4, C=40.0, F0=50.0, frequency=5.0, belt_speed=0.0, position=0.0, velocity=0.0)


@dataclass
class Setup:
    """The coupled system's start values: the rod's (SI parameters and initial state) and the
    table's (parameters and initial state); whatever is not given keeps the defaults."""
    rod: dict = field(default_factory=dict)
    table: dict = field(default_factory=dict)

    def rod_values(self):
        return {**ROD_DEFAULTS, **self.rod}

    def table_values(self):
        return {**TABLE_DEFAULTS, **self.table}

    def si_rod(self):
        """The rod's parameters as painleve.coupling.si's SIRod."""
        return SIRod(**{k: v for k, v in self.rod_values().items() if k in SIRod.__dataclass_fields__})

    def case(self):
        """The paper's Case of the rod's start (painleve.coupling.si.case_of: alpha = m l^2/J, epsilon =
        sqrt(m g/(k l)), delta = c/sqrt(m k), theta0, v0 = (v - v_floor)/sqrt(g l), phi0 = phi
        sqrt(l/g), w10), relative to the table's surface at its start; None if the rod does not
        start on it."""
        t = self.table_values()
        state = SIState(**{k: v for k, v in self.rod_values().items() if k in SIState.__dataclass_fields__})
        try:
            return case_of(self.si_rod(), state, Floor(y0=t["position"], w=t["velocity"], v=t["belt_speed"]))
        except ValueError:
            return None


def write_coupled_ssp(path, rod_fmu, table_fmu, setup=None, *, stop_time=1.0):
    """The archive of the rod on the table, with the setup's start values bound."""
    setup = setup or Setup()
    comps = [Component(ROD, rod_fmu, setup.rod_values(), inputs=ROD_INPUTS, outputs=ROD_OUTPUTS),
             Component(TABLE, table_fmu, setup.table_values(), inputs=TABLE_INPUTS, outputs=TABLE_OUTPUTS)]
    return write_ssp(path, "rod_on_shaker_table", comps, CONNECTIONS, stop_time=stop_time)


def run_coupled(rod_fmu, table_fmu, setup=None, *, stop_time, step, master="fmpy"):
    """One coupled run in a temporary archive (removed after): the master's table (painleve.coupling.masters)."""
    from .masters import run
    with tempfile.TemporaryDirectory(prefix="painleve-couple-") as work:
        ssp = write_coupled_ssp(pathlib.Path(work) / "coupled.ssp", rod_fmu, table_fmu, setup, stop_time=stop_time)
        return run(master, ssp, stop_time, step, RECORD)


def impulse_on_table(r, step):
    """The rod's F_N as the table held it, integrated: what the table receives (downwards)."""
    return step * float(np.sum(r[f"{TABLE}.F_N"]))


def impulse_on_rod(r, setup):
    """What the floor gave the rod (upwards), from the rod's momentum: m (vy_cm(T) - vy_cm(0)) + m g T
    - F_y T, vy_cm(0) = w(0) + l cos(theta(0)) phi(0) by the rod's kinematics (centre of mass at
    y + l sin theta); the applied force F_y is not connected: its start value holds (0 by default)."""
    p = setup.rod_values()
    vy0 = p["w"] + p["l"] * math.cos(p["theta"]) * p["phi"]
    T = r["time"][-1]
    return p["m"] * (r[f"{ROD}.vy_cm"][-1] - vy0) + p["m"] * p["g"] * T - p.get("F_y", 0.0) * T


def table_momentum_impulse(r, setup):
    """The impulse of F_N on the table from the table's momentum balance:
    int F_N = int(-K z - C z' + F0 sin(2 pi f t)) dt - M (z'(T) - z'(0)), with int z' = z(T) - z(0)
    exact, int sin exact, int z by the trapezoid rule on the communication grid (O(h^2): z is C^1)."""
    p = setup.table_values()
    t = np.concatenate(([0.0], r["time"]))
    z = np.concatenate(([p["position"]], r[f"{TABLE}.position"]))
    T, omega = t[-1], 2 * math.pi * p["frequency"]
    drive = p["F0"] * (1 - math.cos(omega * T)) / omega if omega > 0 else 0.0
    spring = p["K"] * float(np.sum(np.diff(t) * (z[1:] + z[:-1]) / 2))
    damper = p["C"] * (z[-1] - z[0])
    return -spring - damper + drive - p["M"] * (r[f"{TABLE}.velocity"][-1] - p["velocity"])
