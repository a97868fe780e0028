"""tumble.MassProperties and tumble.RigidBody: validation, and M, f_v, Q, accelerations and
energies against the equations of motion written in NumPy."""

import numpy as np
import pytest

import tumble
from conftest import ALL

INERTIA = np.array([[0.3, 0.01, 0.02], [0.01, 0.4, 0.03], [0.02, 0.03, 0.5]])


def state(body, rng):
    p = body.parameterization
    theta = p.from_quaternion([0.9, 0.1, -0.3, 0.2] / np.linalg.norm([0.9, 0.1, -0.3, 0.2]))
    thetadot = p.thetadot(theta, rng.normal(size=3))
    if body.reference == "fixed_point":
        return theta, thetadot
    return np.r_[rng.normal(size=3), theta], np.r_[rng.normal(size=3), thetadot]


def test_mass_properties_are_validated():
    with pytest.raises(ValueError, match="mass"):
        tumble.MassProperties.about_centroid(-1.0, INERTIA)
    with pytest.raises(ValueError, match="'inertia' has a non-finite entry"):
        tumble.MassProperties.about_centroid(1.0, np.full((3, 3), np.nan))
    with pytest.raises(ValueError):
        tumble.MassProperties.about_centroid(1.0, np.diag([1.0, 1.0, 3.0]))  # 1 + 1 < 3
    with pytest.raises(ValueError, match=r"'inertia' must have shape \(3, 3\)"):
        tumble.MassProperties.about_centroid(1.0, np.eye(2))
    mp = tumble.MassProperties.about_reference(2.0, INERTIA + 2.0 * 0.01 * (np.eye(3) - 0),
                                               [0.0, 0.0, 0.1])
    assert mp.mass == 2.0
    assert np.allclose(mp.centroid, [0, 0, 0.1])


def test_reference_point_is_checked():
    mp = tumble.MassProperties.about_centroid(1.0, INERTIA, [0.1, 0, 0])
    with pytest.raises(ValueError, match="reference='offset'"):
        tumble.RigidBody("EulerZYX", mp)
    with pytest.raises(ValueError, match="unknown reference point 'middle'"):
        tumble.RigidBody("EulerZYX", mp, reference="middle")
    with pytest.raises(ValueError, match="unknown parameterization"):
        tumble.RigidBody("Quaternion", mp, reference="offset")


@pytest.mark.parametrize("name", ALL)
@pytest.mark.parametrize("reference", ["centroid", "offset", "fixed_point"])
def test_equations_of_motion(name, reference, rng):
    r_g = np.zeros(3) if reference == "centroid" else np.array([0.1, -0.05, 0.2])
    mp = tumble.MassProperties.about_centroid(2.5, INERTIA, r_g)
    body = tumble.RigidBody(name, mp, reference=reference,
                            fixed_point=[0, 0, 1] if reference == "fixed_point" else [0, 0, 0])
    assert body.parameterization.name == name and body.reference == reference
    q, qdot = state(body, rng)
    n = body.nq
    assert q.shape == (n,)
    m = body.mass_matrix(q)
    assert np.allclose(m, m.T, atol=1e-15)
    # T = 1/2 qdot^T M qdot (Eq. 1.23) and, for a free body, T = 1/2 m v_g^2 + 1/2 w.I_g w.
    assert body.kinetic_energy(q, qdot) == pytest.approx(0.5 * qdot @ m @ qdot, rel=1e-13)
    force, moment = np.array([1.0, -2.0, 3.0]), np.array([0.1, 0.2, -0.3])
    gen = body.generalized_force(q, force, moment)
    qdd = body.accelerations(q, qdot, force=force, moment=moment)
    assert np.allclose(body.accelerations(q, qdot, Q=gen), qdd, atol=1e-12)
    fv = body.centrifugal_coriolis(q, qdot)
    # M qddot = f_v + Q (Eq. 1.32); for Euler parameters with the constraint's multiplier along
    # [0; p], which the residual's component along it absorbs.
    residual = m @ qdd - fv - gen
    if name == "EulerParameters":
        k = n - 4
        p = q[k:]
        null = np.zeros(n)
        null[k:] = p / np.linalg.norm(p)
        residual -= null * (null @ residual)
        # p . pddot = -|pdot|^2
        assert p @ qdd[k:] == pytest.approx(-qdot[k:] @ qdot[k:], abs=1e-12)
    assert np.allclose(residual, 0, atol=1e-11)


def test_body_bad_input():
    body = tumble.RigidBody("EulerParameters",
                            tumble.MassProperties.about_centroid(1.0, INERTIA))
    with pytest.raises(ValueError, match=r"'q' must have shape \(7,\), got shape \(6,\)"):
        body.mass_matrix(np.zeros(6))
    with pytest.raises(ValueError, match="'qdot' has a non-finite entry"):
        body.kinetic_energy([0, 0, 0, 1, 0, 0, 0], [0, 0, 0, 0, np.nan, 0, 0])
    with pytest.raises(ValueError, match="either Q or force/moment"):
        body.accelerations([0, 0, 0, 1, 0, 0, 0], np.zeros(7), force=[1, 0, 0], Q=np.zeros(7))
