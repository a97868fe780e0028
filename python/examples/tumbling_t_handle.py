"""The tumbling T-handle from Python: the Dzhanibekov effect (intermediate-axis theorem).

Problem: a T-shaped handle spun about its intermediate principal axis in free space flips
periodically by 180 degrees. We build its mass properties from its two rods, integrate the
torque-free motion with tumble's front door, and write omega(t) as a CSV file and, when
matplotlib is installed, a PNG plot. The same problem as examples/tumbling_t_handle.cpp.

Equations: torque-free rigid body, M qddot = f_v (reference chapter Eq. 1.33 with Q = 0), solved as
I alpha = -omega x I omega in the body frame; the kinetic energy and the inertial angular momentum
are constants of the motion (printed as a check).
Units: SI (m, kg, s, rad). Orientation: Euler parameters.

Run: python python/examples/tumbling_t_handle.py [output folder]   (default: the current folder)
"""

import pathlib
import sys

import numpy as np

import tumble


def rod_inertia(mass, length, axis):
    """A thin rod along `axis` (0, 1, 2) about its own centroid, kg m^2."""
    moments = np.ones(3)
    moments[axis] = 1e-9
    return np.diag(moments) * mass * length**2 / 12


def parallel_axis(mass, r):
    """m (|r|^2 I - r r^T): the parallel-axis term, kg m^2."""
    r = np.asarray(r, dtype=float)
    return mass * (r @ r * np.eye(3) - np.outer(r, r))


def main(out):
    # Two rods of 0.1 kg: the handle (0.10 m along x) and the bar (0.08 m along y), welded at the
    # handle's end, which is the reference point; inertia about it, then about the centroid.
    m_rod, l_handle, l_bar = 0.1, 0.10, 0.08
    c_handle, c_bar = np.array([l_handle / 2, 0, 0]), np.zeros(3)
    i_joint = (rod_inertia(m_rod, l_handle, 0) + parallel_axis(m_rod, c_handle)
               + rod_inertia(m_rod, l_bar, 1) + parallel_axis(m_rod, c_bar))
    m = 2 * m_rod
    centroid = (m_rod * c_handle + m_rod * c_bar) / m
    joint = tumble.MassProperties.about_reference(m, i_joint, centroid)
    print("principal moments about the centroid:", joint.principal_moments, "kg m^2")

    # The body frame at the centroid (axes along the rods, principal by symmetry), spun about the
    # intermediate axis y with a tiny perturbation.
    body = tumble.RigidBody("EulerParameters",
                            tumble.MassProperties.about_centroid(m, joint.inertia_centroid))
    scene = tumble.Scene()
    b = scene.add(body, omega=[0.01, 10.0, 0.0])
    times = np.linspace(0.0, 10.0, 2001)
    run = scene.integrate(times, rtol=1e-10, atol=1e-12)

    omega = run.omega[:, b]  # (2001, 3), rad/s, body frame
    flips = int(np.count_nonzero(np.diff(np.sign(omega[:, 1])) != 0))
    h = np.array([scene.angular_momentum(run.state(k)) for k in (0, len(run) - 1)])
    print(f"sign changes of omega_y (flips) in {times[-1]:.0f} s: {flips}")
    print(f"relative energy drift: {np.ptp(run.energy) / run.energy[0]:.2e}, "
          f"angular momentum drift: {np.linalg.norm(h[1] - h[0]) / np.linalg.norm(h[0]):.2e}")
    print(f"{run.statistics.method}: {run.statistics.steps} steps, "
          f"{run.statistics.rhs_evals} right-hand sides")

    out = pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    np.savetxt(out / "t_handle_omega_py.csv", np.column_stack([run.t, omega]), delimiter=",",
               header="t_s,omega_x_rad_s,omega_y_rad_s,omega_z_rad_s", comments="")
    try:
        import matplotlib
    except ImportError:
        print(f"wrote {out / 't_handle_omega_py.csv'} (no matplotlib: no plot)")
        return flips
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 5))
    for k, label in enumerate(["omega x", "omega y", "omega z"]):
        ax.plot(run.t, omega[:, k], label=label)
    ax.set(xlabel="t (s)", ylabel="omega (rad/s)",
           title="T-handle: body angular velocity (Dzhanibekov effect)")
    ax.legend()
    fig.savefig(out / "t_handle_omega_py.png", dpi=100)
    print(f"wrote {out / 't_handle_omega_py.csv'} and {out / 't_handle_omega_py.png'}")
    return flips


if __name__ == "__main__":
    sys.exit(0 if main(sys.argv[1] if len(sys.argv) > 1 else ".") > 0 else 1)
