"""The Python package's performance targets, measured in one run, beside the same work in C++.

The four targets (docs/benchmarks/python.md, where the results are kept):
  1. one call from Python, RigidBody.accelerations of one Euler-parameter body at its centroid,
     costs at most 1 us more than the same call in C++;
  2. the tumbling body integrated from Python (Scene.integrate, Fehlberg 7(8)) within 1.1x of the
     same integration in C++;
  3. an ensemble of 10^5 tumbling runs from Python (Scene.ensemble, 2 threads) within 1.1x of the
     C++ ensemble's time;
  4. tumble from Python reaches an attitude error of 1e-6 rad on the tumbling body at least 50x
     faster than Pinocchio's aba in a right-hand side for scipy's solve_ivp.

The C++ side is the project's own benchmark programs, run from the build directory given by
--cxx-build (configured with -DCMAKE_BUILD_TYPE=Release and the benchmarks, as scripts/bench
does): tumble_micro for 1 (qddot/EulerParameters/centroid, Google Benchmark), tumble_bench for 2
(the row "Odeint F78 EP quasi": a Scene of one RigidBody<EulerParameters> held at its centroid
(ReferencePoint::fixed_point) in the quasi-velocity form [p; omega], OdeintIntegrator<Scene, 7>,
Fehlberg 7(8), rtol = atol = tol, the output
times 0.5, 1, ..., 50 s reached by stepping to them) and its ensemble study for 3 (MRP in the
quasi-velocity form, OdeintIntegrator<Scene, 12>, Fehlberg 7(8) at the loosest tolerance that
keeps the attitude error at 50 s within 1e-6 rad, 10^5 runs by Ensemble::fold on 2 threads, omega0
of run i dispersed by the formula of benchmarks/ensembles/runs.hpp). The Python side does the same
work through the package: the same body, method, tolerance, output times (plus t = 0, the initial
state, recorded without a step), the same runs and threads.

Clocks: 1, 2 and 4 on the calling thread's CPU time (time.thread_time; tumble_micro's and
tumble_bench's --clock cpu), which leaves out the waits for a core on a shared machine; 3 on the
wall clock (several threads), with the process's CPU time per run beside it. Every time is a
median over --reps rounds (3: over --ensemble-reps), each round a run of the C++ program and the
same work from Python, one after the other, so that the load of a shared machine, which moves
even CPU times (a busy sibling hardware thread, the caches), weighs on both sides alike.
Errors: the largest attitude error over the outputs against the exact solution (tumbling.py).

Run: python python/benchmarks/bench.py --cxx-build build [--reps 7] [--ensemble-reps 3]
     [--tol 1e-10] [--out DIR] [--skip 3,4]
Needs the package (pip install .), NumPy; scipy and Pinocchio (pip install scipy pin) for 4.
"""

import argparse
import csv
import datetime
import json
import math
import os
import pathlib
import platform
import shlex
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import tumble

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import tumbling  # noqa: E402  (beside this file)

TARGET_ERROR = 1e-6  # rad, target 4
LADDER = [10.0 ** (-3.0 - 0.5 * k) for k in range(19)]  # 1e-3, 10^-3.5, ..., 1e-12


def median(xs):
    return statistics.median(xs)


def cpu_seconds(fn, reps):
    """The median over reps of fn()'s CPU time on this thread (after one call not timed)."""
    fn()
    times = []
    for _ in range(reps):
        start = time.thread_time()
        fn()
        times.append(time.thread_time() - start)
    return median(times)


def run(command, **kwargs):
    """Runs a C++ benchmark program, its output kept for the error message."""
    done = subprocess.run(command, capture_output=True, text=True, **kwargs)
    if done.returncode != 0:
        raise RuntimeError(f"{shlex.join(map(str, command))} failed ({done.returncode}):\n"
                           f"{done.stdout[-2000:]}\n{done.stderr[-2000:]}")
    return done


def program(build, name):
    path = pathlib.Path(build) / "benchmarks" / name
    if not path.exists():
        raise SystemExit(f"bench.py: {path} not found: build it (cmake -S . -B {build} "
                         f"-DCMAKE_BUILD_TYPE=Release; cmake --build {build} --target {name})")
    return path


def euler_parameters_body():
    return tumble.RigidBody("EulerParameters", tumble.MassProperties.about_centroid(
        tumbling.MASS, np.diag(tumbling.INERTIA)))


def tumbling_scene(parameterization="EulerParameters", held=True):
    """The tumbling body in a scene: held at its centroid (reference="fixed_point", the fixed
    point at the centroid: state [theta; omega]) as tumble_bench's attitude-only rows, or free
    (reference="centroid": [r; theta; v; omega]) as its ensemble study."""
    mp = tumble.MassProperties.about_centroid(tumbling.MASS, np.diag(tumbling.INERTIA))
    body = (tumble.RigidBody(parameterization, mp, reference="fixed_point", fixed_point=[0, 0, 0])
            if held else tumble.RigidBody(parameterization, mp))
    scene = tumble.Scene()
    return scene, scene.add(body, omega=tumbling.OMEGA0)


# ---- target 1: one call ------------------------------------------------------------------------

def cxx_per_call(build):
    """tumble_micro's qddot/EulerParameters/centroid: CPU s per call (one Google Benchmark run)."""
    out = run([program(build, "tumble_micro"),
               "--benchmark_filter=^qddot/EulerParameters/centroid$", "--benchmark_format=json"])
    rows = [b for b in json.loads(out.stdout)["benchmarks"] if b.get("run_type") == "iteration"]
    scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[rows[0]["time_unit"]]
    return rows[0]["cpu_time"] * scale


def py_per_call_cases():
    """accelerations of the EP body at its centroid and, to tell the costs apart, calls with
    other inputs and outputs."""
    body = euler_parameters_body()
    q = np.array([0.0, 0.0, 0.0, 0.9, 0.1, -0.3, math.sqrt(1 - 0.91)])  # r (3), p (4)
    qdot = np.array([0.1, -0.2, 0.3, 0.05, -0.4, 0.2, 0.1])
    force, moment = np.array([0.1, 0.2, 0.3]), np.array([-0.1, 0.05, 0.2])
    ql, qdl = q.tolist(), qdot.tolist()
    accelerations, energy = body.accelerations, body.kinetic_energy
    return {
        "accelerations(q, qdot)": lambda: accelerations(q, qdot),
        "accelerations(q, qdot, force=, moment=)":
            lambda: accelerations(q, qdot, force=force, moment=moment),
        "accelerations(q, qdot), q and qdot lists": lambda: accelerations(ql, qdl),
        "kinetic_energy(q, qdot) (a float back)": lambda: energy(q, qdot),
        "an empty Python call (the loop's floor)": lambda: None,
    }


def py_per_call(fn, calls=100_000):
    """CPU seconds per call of fn from a Python loop (the loop's own cost included)."""
    def loop():
        for _ in range(calls):
            fn()
    return cpu_seconds(loop, 1) / calls


def target1(build, rounds):
    """rounds alternating runs of tumble_micro and of the Python loops (a shared machine's load
    then weighs on both alike): the medians over the rounds."""
    cases = py_per_call_cases()
    cxx, py = [], {name: [] for name in cases}
    for _ in range(rounds):
        cxx.append(cxx_per_call(build))
        for name, fn in cases.items():
            py[name].append(py_per_call(fn))
    return median(cxx), {name: median(xs) for name, xs in py.items()}


# ---- target 2: one integration -----------------------------------------------------------------

def cxx_integration(build, tol, reps, out):
    """tumble_bench's "Odeint F78 EP quasi" on the tumbling body at tol: CPU s (median of reps),
    error, steps."""
    folder = pathlib.Path(out) / "cxx_integration"
    run([program(build, "tumble_bench"), "--no-micro", "--no-scaling", "--no-ensemble",
         "--no-plots", "--problems", "tumbling", "--methods", "Odeint F78 EP quasi",
         "--tolerances", f"{tol:g}", "--reps", str(reps), "--outputs", "100", "--clock", "cpu",
         "--out", str(folder)])
    with open(folder / "work_precision_tumbling.csv", newline="") as f:
        rows = [r for r in csv.DictReader(f)
                if r["method"] == "tumble Odeint F78 EP quasi rkf78"]
    if len(rows) != 1 or rows[0]["ok"] != "1":
        raise RuntimeError(f"tumble_bench: no run of 'Odeint F78 EP quasi' in {folder}")
    r = rows[0]
    return {"seconds": float(r["time_median_s"]), "error": float(r["max_attitude_error_rad"]),
            "steps": int(r["steps"]), "rhs": int(r["rhs_evals"])}


def py_integration(tol, reps, exact):
    """Scene.integrate(method="fehlberg78") on the tumbling body: CPU s (median of reps), error,
    steps."""
    scene, body = tumbling_scene()
    times = tumbling.TIMES

    def once():
        return scene.integrate(times, method="fehlberg78", rtol=tol, atol=tol)

    seconds = cpu_seconds(once, reps)
    trajectory = once()
    rotations = tumbling.quaternion_to_matrix(trajectory.quaternion[:, body])
    return {"seconds": seconds, "error": tumbling.max_attitude_error(exact, rotations),
            "steps": trajectory.statistics.steps, "rhs": trajectory.statistics.rhs_evals}


def target2(build, tol, rounds, out, exact, reps=5):
    """rounds alternating runs of tumble_bench (the median of reps) and of Python (the same): the
    medians over the rounds of both."""
    cxx, py = [], []
    for _ in range(rounds):
        cxx.append(cxx_integration(build, tol, reps, out))
        py.append(py_integration(tol, reps, exact))
    for runs in (cxx, py):
        runs[0]["seconds"] = median([r["seconds"] for r in runs])
    return cxx[0], py[0]


# ---- target 3: the ensemble --------------------------------------------------------------------

def cxx_ensemble(build, out):
    """One run of tumble_bench's ensemble study (no MPI): the 10^5-run fold on 2 threads (wall s),
    its CPU time per run and cores, the tolerance it chose, and the 2-thread integrate row."""
    folder = pathlib.Path(out) / f"cxx_ensemble_{time.monotonic_ns()}"
    run([program(build, "tumble_bench"), "--ensemble-only", "--no-mpi", "--no-plots",
         "--out", str(folder)])
    with open(folder / "ensemble.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    named = {r["measurement"]: r["note"] for r in rows if r["label"] == ""}
    large = [r for r in rows if r["measurement"] == "fold" and int(r["runs"] or 0) == 100_000]
    if len(large) != 1 or large[0]["extrapolated"] != "0":
        raise RuntimeError(f"tumble_bench: the 10^5-run fold was not timed ({folder})")
    two = [r for r in rows if r["measurement"] == "threads" and r["threads"] == "2"][0]
    return {"seconds": float(large[0]["median_s"]), "cores": float(large[0]["cores"]),
            "cpu_per_run": float(large[0]["cpu_per_run_s"]), "tol": float(named["tolerance"]),
            "integrate_per_run": float(two["per_run_s"])}


def ensemble_omega0(runs):
    """Run i's omega0, as benchmarks/ensembles/runs.hpp (Tumbling::omega0) computes it."""
    x = np.arange(runs, dtype=float)
    d = np.stack([np.sin(1.1 * x), np.cos(0.7 * x), np.sin(0.3 * x)], axis=1)
    return np.asarray(tumbling.OMEGA0) * (1.0 + 0.01 * d)


def py_ensemble(tol, runs=100_000, threads=2, check=16):
    """Scene.ensemble of the same runs (MRP scene, Fehlberg 7(8)): wall s, CPU s per run, the
    threads, failed runs, the largest attitude error at 50 s over the first `check` runs."""
    scene, body = tumbling_scene("ModifiedRodriguesParameters", held=False)
    omega0 = ensemble_omega0(runs)
    y0 = np.tile(scene.initial_state().y, (runs, 1))
    y0[:, scene.layout(body)["omega"]] = omega0
    wall, cpu = time.perf_counter(), time.process_time()
    mc = scene.ensemble([tumbling.T_END], y0, method="fehlberg78", rtol=tol, atol=tol,
                        threads=threads)
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    error = 0.0
    for i in range(check):
        exact = tumbling.TorqueFreeBody(omega0=omega0[i]).rotation([tumbling.T_END])
        got = tumbling.quaternion_to_matrix(mc.quaternion[i, :, body])
        error = max(error, tumbling.max_attitude_error(exact, got))
    return {"seconds": wall, "cpu_per_run": cpu / runs, "cores": cpu / wall, "threads": mc.threads,
            "failed": len(mc.errors), "error": error}


# ---- target 4: time to an error of 1e-6 --------------------------------------------------------

def time_to_error(make_run, reps, exact):
    """Down the tolerance ladder, the first tolerance whose run ends within TARGET_ERROR of the
    exact attitudes; its CPU time (median of reps), error and tolerance. make_run(tol) returns a
    function that integrates and returns the rotations at the outputs."""
    for tol in LADDER:
        fn = make_run(tol)
        try:
            error = tumbling.max_attitude_error(exact, fn())
        except Exception:  # noqa: BLE001  (too loose to integrate: the next tolerance)
            continue
        if error <= TARGET_ERROR:
            return {"seconds": cpu_seconds(fn, reps), "error": error, "tol": tol}
    return None


def target4(reps, exact):
    """Each candidate's time to TARGET_ERROR: tumble (front door, Fehlberg 7(8)), Pinocchio and
    the hand-written NumPy right-hand side under solve_ivp (RK45, DOP853)."""
    results = {}
    scene, body = tumbling_scene()
    times = tumbling.TIMES
    for method in ("auto", "fehlberg78"):
        def make(tol, method=method):
            return lambda: tumbling.quaternion_to_matrix(scene.integrate(
                times, method=method, rtol=tol, atol=tol).quaternion[:, body])
        results[f"tumble, method='{method}'"] = time_to_error(make, reps, exact)
    try:
        from scipy.integrate import solve_ivp
    except ImportError:
        print("  scipy not installed: no solve_ivp runs (pip install scipy)")
        return results
    sides = [("hand-written NumPy f", tumbling.floor_rhs(), tumbling.floor_state(),
              tumbling.floor_rotations)]
    try:
        import pinocchio as pin
        model = tumbling.pinocchio_model(pin)
        sides.insert(0, ("Pinocchio aba", tumbling.pinocchio_rhs(pin, model),
                         tumbling.pinocchio_state(), tumbling.pinocchio_rotations))
    except ImportError:
        print("  Pinocchio not installed (pip install pin): target 4 cannot be measured")
    for name, rhs, y0, rotations in sides:
        for method in ("RK45", "DOP853"):
            def make(tol, rhs=rhs, y0=y0, rotations=rotations, method=method):
                def once():
                    sol = solve_ivp(rhs, (0.0, tumbling.T_END), y0, method=method, t_eval=times,
                                    rtol=tol, atol=tol)
                    if not sol.success:
                        raise RuntimeError(sol.message)
                    return rotations(sol.y)
                return once
            results[f"{name}, solve_ivp {method}"] = time_to_error(make, reps, exact)
    return results


# ---- the report ---------------------------------------------------------------------------------

def machine():
    model = "unknown CPU"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    load = " ".join(f"{x:.2f}" for x in os.getloadavg())
    versions = [f"Python {platform.python_version()}", f"NumPy {np.__version__}"]
    for module, label in (("scipy", "scipy"), ("pinocchio", "Pinocchio")):
        try:
            versions.append(f"{label} {__import__(module).__version__}")
        except ImportError:
            pass
    return (f"{model}, {os.cpu_count()} hardware threads, load {load}",
            ", ".join(versions) + f"; tumble scenes: {', '.join(tumble.scene_parameterizations())}")


def fmt_time(s):
    if s is None or not math.isfinite(s):
        return "-"
    for unit, scale in (("s", 1.0), ("ms", 1e-3), ("us", 1e-6), ("ns", 1e-9)):
        if abs(s) >= scale or unit == "ns":
            return f"{s / scale:.3g} {unit}"
    return f"{s:g}"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cxx-build", required=True,
                        help="C++ build directory with benchmarks/tumble_micro and tumble_bench")
    parser.add_argument("--reps", type=int, default=7, help="repetitions of 1, 2, 4 (median)")
    parser.add_argument("--ensemble-reps", type=int, default=3, help="repetitions of 3 (median)")
    parser.add_argument("--tol", type=float, default=1e-10, help="rtol = atol of target 2")
    parser.add_argument("--out", default=None, help="where the C++ programs write (a temp dir)")
    parser.add_argument("--skip", default="", help="targets not to run, e.g. 3,4")
    args = parser.parse_args(argv)
    skip = {int(x) for x in args.skip.split(",") if x}
    out = pathlib.Path(args.out or tempfile.mkdtemp(prefix="tumble_pybench_"))
    out.mkdir(parents=True, exist_ok=True)
    started = time.perf_counter()
    cpu, versions = machine()
    print("bench.py: the Python package's targets beside the same work in C++")
    print(f"  date      {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC")
    print(f"  command   {shlex.join([sys.executable, *sys.argv])}")
    print(f"  machine   {cpu}")
    print(f"  software  {versions}")
    print(f"  C++       {pathlib.Path(args.cxx_build).resolve()}/benchmarks: tumble_micro, "
          f"tumble_bench (output in {out})")
    print(f"  timing    median of {args.reps} (target 3: {args.ensemble_reps}); 1, 2, 4 thread "
          "CPU time, 3 wall clock")
    rows = []  # (target, what, Python, C++ or peer, comparison, goal, met)
    exact = tumbling.TorqueFreeBody().rotation(tumbling.TIMES)

    if 1 not in skip:
        print("target 1: one call ...", file=sys.stderr)
        cxx, py = target1(args.cxx_build, args.reps)
        acc = py["accelerations(q, qdot)"]
        print(f"\n(1) one call from Python, CPU time per call (median of {args.reps} rounds, "
              "each a run of tumble_micro and loops of 1e5 calls); C++ tumble_micro "
              f"qddot/EulerParameters/centroid: {fmt_time(cxx)}")
        for name, s in py.items():
            over = "" if name.startswith("an empty") else f"{fmt_time(s - cxx):>10s} over C++"
            print(f"  {name:44s} {fmt_time(s):>10s}   {over}")
        rows.append(("1", "RigidBody.accelerations, one EP body", fmt_time(acc), fmt_time(cxx),
                     f"+{fmt_time(acc - cxx)}", "<= +1 us", acc - cxx <= 1e-6))

    if 2 not in skip:
        print("target 2: the tumbling integration ...", file=sys.stderr)
        cxx, py = target2(args.cxx_build, args.tol, args.reps, out, exact)
        ratio = py["seconds"] / cxx["seconds"]
        print(f"\n(2) the tumbling body, Fehlberg 7(8), rtol = atol = {args.tol:g}, 50 s, CPU time "
              f"(median of {args.reps} rounds, each the median of 5 runs of tumble_bench and of "
              "5 from Python)")
        for name, r in (("Python Scene.integrate(method='fehlberg78')", py),
                        ("C++ tumble_bench 'Odeint F78 EP quasi'", cxx)):
            print(f"  {name:44s} {fmt_time(r['seconds']):>10s}  error {r['error']:.2e} rad, "
                  f"{r['steps']} steps, {r['rhs']} rhs")
        rows.append(("2", f"tumbling body, F78, tol {args.tol:g}", fmt_time(py["seconds"]),
                     fmt_time(cxx["seconds"]), f"{ratio:.2f}x", "<= 1.1x", ratio <= 1.1))

    if 3 not in skip:
        print("target 3: the ensembles ...", file=sys.stderr)
        cxx_runs, py_runs = [], []
        for _ in range(args.ensemble_reps):
            cxx_runs.append(cxx_ensemble(args.cxx_build, out))
            py_runs.append(py_ensemble(cxx_runs[-1]["tol"]))
        cxx_s = median([r["seconds"] for r in cxx_runs])
        py_s = median([r["seconds"] for r in py_runs])
        ratio = py_s / cxx_s
        print(f"\n(3) 10^5 tumbling runs of 50 s, MRP, Fehlberg 7(8) at rtol = atol = "
              f"{cxx_runs[0]['tol']:g}, 2 threads, wall time (median of {args.ensemble_reps}, "
              "each C++ run followed by a Python one)")
        print(f"  {'Python Scene.ensemble':44s} {fmt_time(py_s):>10s}  each: "
              + " ".join(fmt_time(r["seconds"]) for r in py_runs)
              + f"; CPU/run {fmt_time(median([r['cpu_per_run'] for r in py_runs]))}, cores "
              + " ".join(f"{r['cores']:.2f}" for r in py_runs)
              + f"; {py_runs[0]['threads']} threads, {max(r['failed'] for r in py_runs)} failed, "
              f"error at 50 s <= {max(r['error'] for r in py_runs):.1e} rad (16 runs)")
        print(f"  {'C++ Ensemble::fold (tumble_bench)':44s} {fmt_time(cxx_s):>10s}  each: "
              + " ".join(fmt_time(r["seconds"]) for r in cxx_runs)
              + f"; CPU/run {fmt_time(median([r['cpu_per_run'] for r in cxx_runs]))}, cores "
              + " ".join(f"{r['cores']:.2f}" for r in cxx_runs)
              + f"; Ensemble::integrate, 2 threads: "
              f"{fmt_time(median([r['integrate_per_run'] for r in cxx_runs]))} per run")
        cpu_ratio = (median([r["cpu_per_run"] for r in py_runs])
                     / median([r["cpu_per_run"] for r in cxx_runs]))
        print(f"  Python against C++: wall {ratio:.2f}x, CPU per run {cpu_ratio:.2f}x (read the "
              "cores: below 2, the machine lent the threads less than two cores)")
        rows.append(("3", "10^5-run ensemble, 2 threads", fmt_time(py_s), fmt_time(cxx_s),
                     f"{ratio:.2f}x", "<= 1.1x", ratio <= 1.1))

    if 4 not in skip:
        print("target 4: time to 1e-6 ...", file=sys.stderr)
        results = target4(args.reps, exact)
        print(f"\n(4) time to a max attitude error <= {TARGET_ERROR:g} rad over the 101 outputs: "
              "the first tolerance of 1e-3, 10^-3.5, ..., 1e-12 that reaches it, CPU time "
              f"(median of {args.reps})")
        for name, r in results.items():
            if r is None:
                print(f"  {name:44s} {'-':>10s}  not reached")
            else:
                print(f"  {name:44s} {fmt_time(r['seconds']):>10s}  tol {r['tol']:.1e}, "
                      f"error {r['error']:.2e} rad")
        pin_runs = [r for n, r in results.items() if n.startswith("Pinocchio") and r]
        front = results.get("tumble, method='auto'")
        if pin_runs and front:
            best_pin = min(r["seconds"] for r in pin_runs)
            for name in ("auto", "fehlberg78"):
                r = results[f"tumble, method='{name}'"]
                if r:
                    rows.append(("4", f"to 1e-6 vs pin + solve_ivp, tumble '{name}'",
                                 fmt_time(r["seconds"]), fmt_time(best_pin),
                                 f"{best_pin / r['seconds']:.0f}x faster", ">= 50x",
                                 best_pin / r["seconds"] >= 50))

    print("\ntargets (Python against C++ for 1-3, against the faster of Pinocchio + RK45 and "
          "+ DOP853 for 4)")
    print(f"  {'':3s}{'what':48s}{'Python':>10s}{'C++ / pin':>11s}  {'measured':15s}"
          f"{'goal':11s}met")
    for target, what, py, other, measured, goal, met in rows:
        print(f"  {target:3s}{what:48s}{py:>10s}{other:>11s}  {measured:15s}{goal:11s}"
              f"{'yes' if met else 'no'}")
    print(f"\nfinished in {time.perf_counter() - started:.0f} s")


if __name__ == "__main__":
    main()
