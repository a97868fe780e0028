"""Attitude dispersion of a tumbling satellite from Python: a Monte Carlo ensemble across the cores.

Problem: a satellite with principal moments of inertia I = diag(1, 2, 3) kg m^2 tumbles from
omega0 = (0.1, 2, 0.05) rad/s (body frame), nearly about its intermediate axis, so it flips (the
Dzhanibekov effect) and small uncertainties grow. Each run draws its omega0 components from a
normal distribution with a 1 % standard deviation. After 50 s, the pointing error of a run is the
angle between its body x axis (a boresight) and the nominal run's. The runs are one call of
tumble.Scene.ensemble (tumble::Ensemble, oneTBB, the GIL released); then a summary, a CSV of every
run and, with matplotlib, a PNG histogram of the pointing error.

Unlike examples/attitude_dispersion.cpp, the inertia is not dispersed: a Python scene's
ensemble shares one scene (per-run scenes, tumble::integrate_variants, are not bound yet).

Equations: torque-free rigid body, I omega' = -omega x I omega (reference chapter Eq. 1.33 with
Q = 0), MRP in the quasi-velocity form, Boost.Odeint's Fehlberg 7(8), rtol = atol = 1e-10.
Units: SI (kg m^2, rad/s, s); the pointing error in degrees.

Run: python python/examples/attitude_dispersion.py [output folder] [runs]
     (defaults: the current folder, 10000)
"""

import pathlib
import sys
import time

import numpy as np

import tumble


def quaternion_x_axis(q):
    """The first column of R for unit quaternions q (..., 4) = (w, x, y, z): the body x axis."""
    w, x, y, z = np.moveaxis(q, -1, 0)
    return np.stack([1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)], axis=-1)


def main(out=".", runs=10000):
    omega0 = np.array([0.1, 2.0, 0.05])
    scene = tumble.Scene()
    body = scene.add(
        tumble.RigidBody("ModifiedRodriguesParameters",
                         tumble.MassProperties.about_centroid(1.0, np.diag([1.0, 2.0, 3.0]))),
        omega=omega0)

    rng = np.random.default_rng(2026)
    y0 = np.tile(scene.initial_state().y, (runs, 1))
    y0[1:, scene.layout(body)["omega"]] = omega0 * (1 + 0.01 * rng.standard_normal((runs - 1, 3)))
    start = time.perf_counter()
    mc = scene.ensemble([50.0], y0, method="fehlberg78", rtol=1e-10, atol=1e-10)
    seconds = time.perf_counter() - start
    for run, message in mc.errors:
        print(f"run {run} failed: {message}")

    x_axis = quaternion_x_axis(mc.quaternion[:, 0, body])  # (runs, 3)
    error = np.degrees(np.arccos(np.clip(x_axis @ x_axis[0], -1.0, 1.0)))  # run 0: nominal
    ok = np.isfinite(error)
    print(f"{runs} runs of 50 s in {seconds:.2f} s on {mc.threads} threads "
          f"({runs / seconds:.0f} runs/s), {len(mc.errors)} failed")
    for p in (50, 90, 99, 100):
        print(f"  pointing error, {p:3d}th percentile: {np.percentile(error[ok], p):7.2f} deg")

    out = pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    np.savetxt(out / "attitude_dispersion_py.csv",
               np.column_stack([np.arange(runs), y0[:, scene.layout(body)["omega"]], error]),
               delimiter=",", comments="",
               header="run,omega0_x_rad_s,omega0_y_rad_s,omega0_z_rad_s,pointing_error_deg")
    try:
        import matplotlib
    except ImportError:
        print(f"wrote {out / 'attitude_dispersion_py.csv'} (no matplotlib: no plot)")
        return len(mc.errors)
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 5))
    ax.hist(error[ok], bins=60)
    ax.set(xlabel="pointing error after 50 s (deg)", ylabel="runs",
           title=f"Attitude dispersion: {runs} runs, omega0 dispersed by 1 %")
    fig.savefig(out / "attitude_dispersion_py.png", dpi=100)
    print(f"wrote {out / 'attitude_dispersion_py.csv'} and {out / 'attitude_dispersion_py.png'}")
    return len(mc.errors)


if __name__ == "__main__":
    sys.exit(1 if main(*(sys.argv[1:2] or ["."]), *(map(int, sys.argv[2:3]))) else 0)
