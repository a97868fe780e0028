"""The bindings against C++ to the bit: python/tests/reference/reference.cpp calls the headers
directly on the same inputs and prints its results with 17 significant digits (exact for a
double); the module must give the same doubles. The program is built here with CMake against the
checkout (about a minute); the test is skipped where CMake or a compiler is missing, or with
TUMBLE_SKIP_CPP_REFERENCE=1."""

import json
import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

import tumble

HERE = pathlib.Path(__file__).resolve().parent


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    if os.environ.get("TUMBLE_SKIP_CPP_REFERENCE") == "1":
        pytest.skip("TUMBLE_SKIP_CPP_REFERENCE=1")
    if shutil.which("cmake") is None:
        pytest.skip("no cmake")
    build = tmp_path_factory.mktemp("reference")
    jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", "2")
    for command in (["cmake", "-S", str(HERE / "reference"), "-B", str(build),
                     "-DCMAKE_BUILD_TYPE=Release"],
                    ["cmake", "--build", str(build), "-j", jobs]):
        done = subprocess.run(command, capture_output=True, text=True)
        if done.returncode != 0:
            pytest.fail(f"{' '.join(command)} failed:\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}")
    out = subprocess.run([str(build / "reference")], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def same(a, b):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return a.shape == b.shape and np.array_equal(a, b)


def test_orientation_to_the_bit(reference):
    assert set(reference["orientation"]) == set(tumble.parameterization_names())
    for name, r in reference["orientation"].items():
        p = tumble.parameterization(name)
        theta = np.array(r["theta"])
        assert same(p.from_quaternion(r["q0"]), theta), name
        assert same(p.rotation(theta), r["R"]), name
        assert same(p.G(theta), r["G"]), name
        thetadot = p.thetadot(theta, [0.3, -0.2, 0.7])
        assert same(thetadot, r["thetadot"]), name
        assert same(p.Gdot_thetadot(theta, thetadot), r["Gdot_thetadot"]), name
        assert same(p.omega(theta, thetadot), r["omega"]), name
        assert same(p.to_quaternion(theta), r["quaternion"]), name
        assert p.singularity_distance(theta) == r["singularity_distance"], name


def test_bodies_to_the_bit(reference):
    inertia = np.array([[0.3, 0.01, 0.02], [0.01, 0.4, 0.03], [0.02, 0.03, 0.5]])
    for key, r in reference["body"].items():
        name, ref = key.split("/")
        r_g = [0.0, 0.0, 0.0] if ref == "centroid" else [0.1, -0.05, 0.2]
        body = tumble.RigidBody(name, tumble.MassProperties.about_centroid(2.5, inertia, r_g),
                                reference=ref,
                                fixed_point=[0.0, 0.0, 1.0] if ref == "fixed_point" else [0, 0, 0])
        q, qdot = np.array(r["q"]), np.array(r["qdot"])
        force, moment = [1.0, -2.0, 3.0], [0.1, 0.2, -0.3]
        assert same(body.mass_matrix(q), r["M"]), key
        assert same(body.centrifugal_coriolis(q, qdot), r["fv"]), key
        assert same(body.generalized_force(q, force, moment), r["Q"]), key
        assert same(body.accelerations(q, qdot, force=force, moment=moment), r["qddot"]), key
        assert body.kinetic_energy(q, qdot) == r["T"], key
        assert same(body.linear_momentum(q, qdot), r["p"]), key
        assert same(body.angular_momentum(q, qdot), r["h"]), key


@pytest.mark.parametrize("name", ["EulerParameters", "EulerZYX"])
def test_front_door_to_the_bit(reference, name):
    r = reference["tumbling"][name]
    scene = tumble.Scene()
    scene.add(tumble.RigidBody(name, tumble.MassProperties.about_centroid(
        1.0, np.diag([1.0, 2.0, 3.0]))), omega=[0.1, 2.0, 0.05])
    run = scene.integrate(0.5 * np.arange(101), rtol=1e-10, atol=1e-10)
    assert run.statistics.method == r["method"]
    assert run.statistics.steps == r["steps"]
    assert run.statistics.rhs_evals == r["rhs_evals"]
    assert run.statistics.chart_switches == r["chart_switches"]
    assert same(run.y, r["y"])
