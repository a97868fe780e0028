"""tumble.Parameterization: all 16 parameterizations against NumPy's own quaternion algebra and
their round trips (tolerances at the rounding level), and bad input."""

import math

import numpy as np
import pytest

import tumble
from conftest import ALL, axis_rotation, quat_to_matrix, random_quaternions

EULER = [n for n in ALL if n.startswith("Euler") and n != "EulerParameters"]


def test_all_sixteen_are_there():
    assert len(ALL) == 16
    assert len(EULER) == 12
    assert {"EulerParameters", "RodriguesParameters", "ModifiedRodriguesParameters",
            "RotationVector"} <= set(ALL)
    for name in ALL:
        p = tumble.parameterization(name)
        assert p.name == name and getattr(tumble, name).name == name
        assert p.size == (4 if name == "EulerParameters" else 3)


@pytest.mark.parametrize("name", ALL)
def test_rotation_matches_quaternion_algebra(name, rng):
    p = tumble.parameterization(name)
    for q in random_quaternions(rng, 50):
        theta = p.from_quaternion(q)
        assert np.allclose(p.rotation(theta), quat_to_matrix(q), rtol=0, atol=1e-14)
        back = p.to_quaternion(theta)
        assert np.allclose(back * np.sign(back[0]), q, rtol=0, atol=1e-14)


@pytest.mark.parametrize("name", ALL)
def test_from_rotation_round_trip(name, rng):
    p = tumble.parameterization(name)
    for q in random_quaternions(rng, 50):
        r = quat_to_matrix(q)
        assert np.allclose(p.rotation(p.from_rotation(r)), r, rtol=0, atol=1e-13)


@pytest.mark.parametrize("name", EULER)
def test_euler_angles_are_intrinsic_sequences(name, rng):
    axes = ["XYZ".index(c) for c in name[len("Euler"):]]
    p = tumble.parameterization(name)
    for theta in rng.uniform(-3, 3, size=(20, 3)):
        r = axis_rotation(axes[0], theta[0]) @ axis_rotation(axes[1], theta[1]) @ axis_rotation(
            axes[2], theta[2])
        assert np.allclose(p.rotation(theta), r, rtol=0, atol=1e-14)


@pytest.mark.parametrize("name", ALL)
def test_kinematic_map_and_its_inverse(name, rng):
    p = tumble.parameterization(name)
    for q in random_quaternions(rng, 20):
        theta = p.from_quaternion(q)
        if p.singularity_distance(theta) < 0.2:
            continue
        omega = rng.normal(size=3)
        thetadot = p.thetadot(theta, omega)
        assert np.allclose(p.G(theta) @ thetadot, omega, rtol=0, atol=1e-12)
        assert np.allclose(p.omega(theta, thetadot), omega, rtol=0, atol=1e-12)
        # omega against a finite difference of R: R^T dR/dt = skew(omega), through NumPy.
        h = 1e-6
        rp = p.rotation(theta + h * thetadot)
        rm = p.rotation(theta - h * thetadot)
        skew = p.rotation(theta).T @ (rp - rm) / (2 * h)
        assert np.allclose([skew[2, 1], skew[0, 2], skew[1, 0]], omega, atol=1e-7)


def test_singularity_distance():
    assert tumble.EulerParameters.singularity_distance([1, 0, 0, 0]) == math.inf
    assert tumble.EulerZYX.singularity_distance([0.3, math.pi / 2, 0.1]) == pytest.approx(0, abs=1e-12)
    assert tumble.EulerZYX.singularity_distance([0.3, 0.0, 0.1]) == pytest.approx(math.pi / 2)


@pytest.mark.parametrize("name", ALL)
def test_convert(name, rng):
    p = tumble.parameterization(name)
    q = random_quaternions(rng, 1)[0]
    theta = tumble.RotationVector.from_quaternion(q)
    converted = tumble.RotationVector.convert(theta, p)
    assert np.allclose(p.rotation(converted), quat_to_matrix(q), atol=1e-14)


def test_bad_input_is_a_value_error():
    p = tumble.EulerZYX
    with pytest.raises(ValueError, match=r"'theta' has a non-finite entry"):
        p.rotation([0.1, float("nan"), 0.2])
    with pytest.raises(ValueError, match=r"'theta' must have shape \(3,\), got shape \(4,\)"):
        p.rotation([0.1, 0.2, 0.3, 0.4])
    with pytest.raises(ValueError, match=r"'theta' must have shape \(3,\), got shape \(1, 3\)"):
        p.rotation([[0.1, 0.2, 0.3]])
    with pytest.raises(ValueError, match="not an array of numbers"):
        p.rotation(["a", "b", "c"])
    with pytest.raises(ValueError, match="not a rotation matrix"):
        p.from_rotation(2 * np.eye(3))
    with pytest.raises(ValueError, match="unit quaternion"):
        p.from_quaternion([1.0, 1.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="unknown parameterization 'Euler123'; known: EulerXYZ"):
        tumble.parameterization("Euler123")


def test_lists_tuples_and_integer_arrays_are_accepted():
    expected = tumble.EulerZYX.rotation(np.array([0.0, 1.0, 0.0]))
    assert (tumble.EulerZYX.rotation([0, 1, 0]) == expected).all()
    assert (tumble.EulerZYX.rotation((0, 1, 0)) == expected).all()
    assert (tumble.EulerZYX.rotation(np.array([0, 1, 0])) == expected).all()
