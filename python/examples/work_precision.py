"""Work precision from Python: the run time tumble needs for an accuracy, beside scipy's solve_ivp.

Problem: the tumbling body, the project's standard problem (python/benchmarks/tumbling.py):
principal inertia I = diag(1, 2, 3) kg m^2, m = 1 kg, held at its centroid, no loads, omega0 =
(0.1, 2, 0.05) rad/s in the body frame, 50 s, outputs at t = 0, 0.5, ..., 50 s. It spins near its
intermediate axis and flips every 8.8 s (the Dzhanibekov effect), which makes errors grow fast.
The error of a run: the largest attitude error over the outputs (rad) against the exact solution
(Jacobi elliptic functions). Tolerances rtol = atol = 1e-4, 1e-5, ..., 1e-12.

Curves:
- tumble, method="auto" (the front door) and method="fehlberg78" (Boost.Odeint's Fehlberg 7(8)):
  Euler parameters, the body held at its centroid (reference="fixed_point"), the scene's
  quasi-velocity form [p; omega], the integration in C++;
- scipy's solve_ivp, DOP853, on a right-hand side written by hand in Python: Euler's equations
  I omega' = -omega x I omega and the quaternion kinematics p' = 1/2 p (x) (0, omega), state
  [p; omega] (7 plain floats per call: the fastest of the forms python/benchmarks/bench.py tried);
- solve_ivp DOP853 on Pinocchio's forward dynamics (pin.aba of a free-flyer body), when
  Pinocchio is installed (pip install pin).
solve_ivp's curves need scipy (pip install scipy); without it, or without Pinocchio, those curves
are left out with a message. Times: CPU time of the calling thread, the best of 3 runs.
Units: SI (kg m^2, rad/s, s); errors in rad.

Run: python python/examples/work_precision.py [output folder]   (default: the current folder)
     writes work_precision_py.csv and, with matplotlib, work_precision_py.png
"""

import pathlib
import sys
import time

import numpy as np

import tumble

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "benchmarks"))
import tumbling  # noqa: E402  (python/benchmarks/tumbling.py: the problem and its exact solution)

TOLERANCES = [10.0**-k for k in range(4, 13)]


def cpu_time(fn, reps=3):
    """The best of reps CPU times of fn() on this thread, and fn()'s last result."""
    best, result = float("inf"), None
    for _ in range(reps):
        start = time.thread_time()
        result = fn()
        best = min(best, time.thread_time() - start)
    return best, result


def tumble_curve(method):
    mp = tumble.MassProperties.about_centroid(tumbling.MASS, np.diag(tumbling.INERTIA))
    scene = tumble.Scene()
    body = scene.add(tumble.RigidBody("EulerParameters", mp, reference="fixed_point",
                                      fixed_point=[0.0, 0.0, 0.0]), omega=tumbling.OMEGA0)

    def run(tol):
        trajectory = scene.integrate(tumbling.TIMES, method=method, rtol=tol, atol=tol)
        return tumbling.quaternion_to_matrix(trajectory.quaternion[:, body])

    return run


def solve_ivp_curve(solve_ivp, rhs, y0, rotations, method="DOP853"):
    def run(tol):
        sol = solve_ivp(rhs, (0.0, tumbling.T_END), y0, method=method, t_eval=tumbling.TIMES,
                        rtol=tol, atol=tol)
        if not sol.success:
            raise RuntimeError(sol.message)
        return rotations(sol.y)

    return run


def main(out="."):
    curves = {"tumble, method='auto'": tumble_curve("auto"),
              "tumble, method='fehlberg78'": tumble_curve("fehlberg78")}
    try:
        from scipy.integrate import solve_ivp
    except ImportError:
        solve_ivp = None
        print("scipy is not installed: no solve_ivp curves (pip install scipy)")
    if solve_ivp is not None:
        curves["solve_ivp DOP853, NumPy f by hand"] = solve_ivp_curve(
            solve_ivp, tumbling.floor_rhs(), tumbling.floor_state(), tumbling.floor_rotations)
        try:
            import pinocchio as pin
        except ImportError:
            print("Pinocchio is not installed: no Pinocchio curve (pip install pin)")
        else:
            model = tumbling.pinocchio_model(pin)
            curves["solve_ivp DOP853, Pinocchio aba"] = solve_ivp_curve(
                solve_ivp, tumbling.pinocchio_rhs(pin, model), tumbling.pinocchio_state(),
                tumbling.pinocchio_rotations)

    exact = tumbling.TorqueFreeBody().rotation(tumbling.TIMES)
    rows = []
    print(f"{'curve':36s} {'tol':>7s} {'CPU time':>10s} {'max error':>10s}")
    for name, run in curves.items():
        for tol in TOLERANCES:
            seconds, rotations = cpu_time(lambda run=run, tol=tol: run(tol))
            error = tumbling.max_attitude_error(exact, rotations)
            rows.append((name, tol, seconds, error))
            print(f"{name:36s} {tol:7.0e} {seconds * 1e3:8.3f} ms {error:10.2e}")

    out = pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "work_precision_py.csv", "w") as f:
        f.write("curve,tol,cpu_time_s,max_attitude_error_rad\n")
        for name, tol, seconds, error in rows:
            f.write(f'"{name}",{tol:.0e},{seconds:.6e},{error:.6e}\n')
    try:
        import matplotlib
    except ImportError:
        print(f"wrote {out / 'work_precision_py.csv'} (no matplotlib: no plot)")
        return 0
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 5.5))
    for name in curves:
        pts = [(error, seconds) for n, _, seconds, error in rows if n == name]
        ax.loglog(*zip(*pts), marker="o", label=name)
    ax.set(xlabel="max attitude error over the outputs (rad)", ylabel="CPU time per run (s)",
           title="Tumbling body, 50 s: tumble from Python beside solve_ivp")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.savefig(out / "work_precision_py.png", dpi=100, bbox_inches="tight")
    print(f"wrote {out / 'work_precision_py.csv'} and {out / 'work_precision_py.png'}")
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:2]))
