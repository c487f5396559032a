# SPDX-License-Identifier: BSD-2-Clause
"""The coupled study: PainleveRodSI on a ShakerTable, one SSP archive, run by a
co-simulation master (painleve.coupling.masters).

Coupling (docs/coupling.md): rod.y_floor <- table.position, rod.w_floor <- table.velocity,
rod.v_floor <- table.belt_velocity, and the contact forces, table.F_N <- rod.F_N_mean, table.F_T <-
rod.F_T_mean: the rod's forces averaged over the last communication step (the impulse its solver
integrated / h), which the table holds over the next step, so it receives exactly the impulse the
rod received, one step later, however short the contact (`coupling="mean"`, the default). The
instantaneous coupling, table.F_N <- rod.F_N, table.F_T <- rod.F_T (samples at the communication
points), stays selectable (`coupling="instantaneous"`) to show the difference. The rod's F_N pushes
it up and the table down (Newton's third law across the connection); F_T is in the paper's sign,
-F_T on the rod along x, +F_T on the table.

What a run gives and what the physics fixes about it (the tests' independent checks):
- the impulse the table receives from the rod is the sum of h times the F_N it holds in each
  step (`impulse_on_table`); the impulse the rod receives is, by its momentum, m (vy_cm(T) -
  vy_cm(0)) + m g T with no applied load (`impulse_on_rod`); a Jacobi master with a zero-order
  hold hands the table the rod's F_N at the start of each step, a left Riemann sum, so the two
  differ by O(h): the difference halves with the step;
- the table's own momentum, M (z'(T) - z'(0)) = int(-K z - C z' + F0 sin(2 pi f t)) dt - the
  impulse it holds (`table_momentum_impulse`);
- the system's vertical momentum (`momentum_balance`): the rod's change plus the table's equals
  the external impulses (gravity on the rod, the table's mount and drive, from their step means)
  plus the impulse still in flight (given to the rod in the last step, handed to the table in the
  next): closed to the solvers' accuracy with the mean coupling, off by the sampling's error with
  the instantaneous one.
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
ROD_OUTPUTS = ("x", "v", "y", "w", "theta", "phi", "F_N", "F_T", "F_N_mean", "F_T_mean", "energy", "x_cm", "y_cm",
               "vx_cm", "vy_cm", "gap", "t_contact_end")
TABLE_OUTPUTS = ("position", "velocity", "belt_velocity", "energy", "mount_force_mean", "drive_force_mean")
# what the table's loads F_N, F_T are connected to: the rod's step means, or its forces at the communication points
COUPLINGS = {"mean": ("F_N_mean", "F_T_mean"), "instantaneous": ("F_N", "F_T")}


def connections(coupling="mean"):
    """The five connections of the system, the contact forces' as `coupling` says (COUPLINGS)."""
    normal, tangential = COUPLINGS[coupling]
    return (Connection((TABLE, "position"), (ROD, "y_floor")),
            Connection((TABLE, "velocity"), (ROD, "w_floor")),
            Connection((TABLE, "belt_velocity"), (ROD, "v_floor")),
            Connection((ROD, normal), (TABLE, "F_N")),
            Connection((ROD, tangential), (TABLE, "F_T")))


CONNECTIONS = connections()
# every variable a run records: the components' outputs and the inputs as each FMU held them
RECORD = tuple(f"{ROD}.{n}" for n in ROD_OUTPUTS + ROD_INPUTS) + \
    tuple(f"{TABLE}.{n}" for n in TABLE_OUTPUTS + TABLE_INPUTS)

# The models' defaults: the rod's (painleve.coupling.si's SIRod and SIState), the table's.
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


def write_coupled_ssp(path, rod_fmu, table_fmu, setup=None, *, stop_time=1.0, coupling="mean"):
    """The archive of the rod on the table, with the setup's start values bound."""
    setup = setup or Setup()
    comps = [Component(ROD, rod_fmu, setup.rod_values(), inputs=ROD_INPUTS, outputs=ROD_OUTPUTS),
             Component(TABLE, table_fmu, setup.table_values(), inputs=TABLE_INPUTS, outputs=TABLE_OUTPUTS)]
    return write_ssp(path, "rod_on_shaker_table", comps, connections(coupling), stop_time=stop_time)


def run_coupled(rod_fmu, table_fmu, setup=None, *, stop_time, step, master="fmpy", coupling="mean"):
    """One coupled run in a temporary archive (removed after): the master's table (painleve.coupling.masters)."""
    from .masters import run
    with tempfile.TemporaryDirectory(prefix="painleve-couple-") as work:
        ssp = write_coupled_ssp(pathlib.Path(work) / "coupled.ssp", rod_fmu, table_fmu, setup, stop_time=stop_time,
                                coupling=coupling)
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


@dataclass(frozen=True)
class MomentumBalance:
    """The system's vertical momentum over a run [N s]: the rod's change m (vy_cm(T) - vy_cm(0)),
    the table's M (z'(T) - z'(0)), and the external impulses: gravity and F_y on the rod, the
    table's mount (-K z - C z') and drive from their step means (sum of h times each step's mean:
    the integral its solver took); `in_flight`, h times the rod's last output on the table's
    connection (the impulse the table holds in the step after the run); `contact`, the impulse of
    F_N on the rod (sum of h F_N_mean), the scale."""
    rod: float
    table: float
    gravity: float
    mount: float
    drive: float
    in_flight: float
    contact: float

    @property
    def residual(self):
        """Momentum gained minus what the external impulses and the impulse in flight explain:
        0 when the table receives exactly the impulses the rod received."""
        return self.rod + self.table - (self.gravity + self.mount + self.drive + self.in_flight)


def momentum_balance(r, setup, step, coupling="mean"):
    """The MomentumBalance of run r (a master's table with RECORD's columns)."""
    p, t = setup.rod_values(), setup.table_values()
    vy0 = p["w"] + p["l"] * math.cos(p["theta"]) * p["phi"]
    T = r["time"][-1]
    return MomentumBalance(
        rod=p["m"] * (r[f"{ROD}.vy_cm"][-1] - vy0), table=t["M"] * (r[f"{TABLE}.velocity"][-1] - t["velocity"]),
        gravity=(p.get("F_y", 0.0) - p["m"] * p["g"]) * T,
        mount=step * float(np.sum(r[f"{TABLE}.mount_force_mean"])),
        drive=step * float(np.sum(r[f"{TABLE}.drive_force_mean"])),
        in_flight=step * float(r[f"{ROD}.{COUPLINGS[coupling][0]}"][-1]),
        contact=step * float(np.sum(r[f"{ROD}.F_N_mean"])))


def total_energy(r):
    """The rod's mechanical energy plus the table's (kinetic and spring about its static
    equilibrium, gravity's share in it) at each communication point [J]."""
    return r[f"{ROD}.energy"] + r[f"{TABLE}.energy"]


def initial_energy(setup):
    """total_energy at t = 0, from the start values (the rod off the floor's spring or at gap 0:
    1/2 m |V_cm|^2 + 1/2 J phi^2 + m g y_cm; the table 1/2 M z'^2 + 1/2 K z^2)."""
    p, t = setup.rod_values(), setup.table_values()
    sn, cs = math.sin(p["theta"]), math.cos(p["theta"])
    vx, vy = p["v"] + p["l"] * p["phi"] * sn, p["w"] + p["l"] * p["phi"] * cs
    rod = 0.5 * p["m"] * (vx * vx + vy * vy) + 0.5 * p["J"] * p["phi"] ** 2 + p["m"] * p["g"] * (p["y"] + p["l"] * sn)
    return rod + 0.5 * t["M"] * t["velocity"] ** 2 + 0.5 * t["K"] * t["position"] ** 2
