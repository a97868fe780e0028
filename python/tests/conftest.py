"""Shared inputs of the tests of the Python module (python/tests)."""

import numpy as np
import pytest

import tumble


def quat_to_matrix(q):
    """R of the unit quaternion q = (w, x, y, z), Hamilton convention, written out in NumPy:
    an independent path to the rotation matrices the module computes."""
    w, x, y, z = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])


def axis_rotation(axis, angle):
    """The rotation about a coordinate axis (0, 1, 2) by angle (rad)."""
    c, s = np.cos(angle), np.sin(angle)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    r = np.eye(3)
    r[i, i] = r[j, j] = c
    r[i, j], r[j, i] = -s, s
    return r


@pytest.fixture
def rng():
    return np.random.default_rng(20261126)


def random_quaternions(rng, n):
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    q[q[:, 0] < 0] *= -1
    return q


ALL = tumble.parameterization_names()
