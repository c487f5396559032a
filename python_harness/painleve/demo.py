"""The main job until the `painleve` command lands: the default IWC case of the
FMU at decreasing eps, simulated beside the paper's prediction.

    python -m painleve.demo build/PainleveRod.fmu
"""
import sys

from .experiment import Case, Experiment


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 1:
        sys.exit("usage: python -m painleve.demo PATH/TO/PainleveRod.fmu")
    base = Case()
    print(f"IWC of the Painleve rod, Theorem 1: alpha={base.alpha}, mu={base.mu}, delta={base.delta}, "
          f"theta0={base.theta0}, phi0={base.phi0}, v0={base.v0}")
    print(f"analytic e(delta, theta0) = {base.e:.8f}, phi after IWC = {base.predicted_phi:.8f}")
    print(f"{'eps':>8} {'w/v0':>11} {'(w/v0-e)/e':>11} {'phi - pred':>11} {'v':>10} {'t_return':>10} {'events':>6}")
    with Experiment(argv[0]) as experiment:
        for k in range(2, 7):
            o = experiment.run(Case(epsilon=10.0**-k))
            print(f"{o.case.epsilon:8.0e} {o.w / o.case.v0:11.8f} {o.w_error / o.case.e:11.2e} "
                  f"{o.phi_error:11.2e} {o.v:10.1e} {o.t_return:10.3e} {o.events:6d}")


if __name__ == "__main__":
    main()
