"""tumble.Scene: physics the integration must keep (energy, momenta, a parabola, a reaction at
rest), every method, the ensemble against single runs to the bit, errors, and the GIL released."""

import threading
import time

import numpy as np
import pytest

import tumble

DIAG = np.diag([1.0, 2.0, 3.0])
TIMES = np.linspace(0.0, 20.0, 41)


def tumbling_scene(name="EulerParameters"):
    scene = tumble.Scene()
    body = scene.add(tumble.RigidBody(name, tumble.MassProperties.about_centroid(1.0, DIAG)),
                     omega=[0.1, 2.0, 0.05])
    return scene, body


@pytest.mark.parametrize("name", tumble.scene_parameterizations())
def test_torque_free_body_keeps_energy_and_momentum(name):
    scene, body = tumbling_scene(name)
    run = scene.integrate(TIMES, rtol=1e-11, atol=1e-11)
    assert run.t.shape == (41,) and run.y.shape == (41, scene.size)
    assert run.omega.shape == (41, 1, 3) and run.quaternion.shape == (41, 1, 4)
    assert np.ptp(run.energy) < 1e-9
    h = [scene.angular_momentum(run.state(k)) for k in range(len(run))]
    assert np.ptp(h, axis=0).max() < 1e-9
    # The Dzhanibekov flip: omega_y changes sign within 20 s, through any chart's singularity.
    assert run.omega[:, 0, 1].min() < -1.5 and run.omega[:, 0, 1].max() > 1.5
    if name != "EulerParameters":
        assert run.statistics.chart_switches > 0
    assert run.statistics.steps > 0 and run.statistics.rhs_evals > run.statistics.steps
    assert run.statistics.choices and run.statistics.method


@pytest.mark.parametrize("name", tumble.scene_parameterizations())
@pytest.mark.parametrize("reference", ["centroid", "offset", "fixed_point"])
def test_a_lone_body_as_in_a_scene_with_loads(name, reference):
    # One body without loads runs in a scene type of its own (no load types: the lean type a C++
    # user writes); a zero moment puts the same body in the scene type of any loads. The same
    # arithmetic: the same doubles, single runs and ensembles, every method.
    def scene(loaded):
        s = tumble.Scene()
        mp = tumble.MassProperties.about_centroid(
            2.0, DIAG, [0.0, 0.0, 0.0] if reference == "centroid" else [0.1, -0.2, 0.3])
        held = reference == "fixed_point"
        b = s.add(tumble.RigidBody(name, mp, reference=reference, fixed_point=[0.0, 0.0, 0.0]),
                  omega=[0.1, 2.0, 0.05], **({} if held else {"velocity": [0.3, 0.0, 0.1]}))
        if loaded:
            s.add_moment(b, [0.0, 0.0, 0.0])
        return s

    lean, loaded = scene(False), scene(True)
    times = np.linspace(0.0, 10.0, 11)
    for method in ("auto", "fehlberg78", "dopri5", "bdf", "adams"):
        a = lean.integrate(times, rtol=1e-9, atol=1e-9, method=method)
        b = loaded.integrate(times, rtol=1e-9, atol=1e-9, method=method)
        assert np.array_equal(a.y, b.y), method
        assert a.statistics.steps == b.statistics.steps, method
    y0 = np.tile(lean.initial_state().y, (3, 1))
    y0[:, -1] += [0.0, 0.01, 0.02]
    a = lean.ensemble(times, y0, threads=2)
    b = loaded.ensemble(times, y0, threads=2)
    assert np.array_equal(a.y, b.y) and a.errors == b.errors == []


def test_trajectory_state_is_its_rows():
    # state(k) is assembled from y and bases when asked: the same state, through chart switches,
    # two bodies, negative k, and out of range.
    scene = tumble.Scene()
    mp = tumble.MassProperties.about_centroid(1.0, DIAG)
    a = scene.add(tumble.RigidBody("EulerZYX", mp), omega=[0.1, 2.0, 0.05])
    b = scene.add(tumble.RigidBody("EulerZYX", mp), position=[1.0, 0.0, 0.0], omega=[0.3, 0.1, 2.0])
    run = scene.integrate(TIMES, method="fehlberg78")
    assert run.statistics.chart_switches > 0 and len(run) == len(TIMES)
    for k in (*range(len(run)), -1, -len(run)):
        s = run.state(k)
        assert np.array_equal(s.y, run.y[k])
        for body in (a, b):
            assert np.array_equal(s.bases[body], run.bases[k, body])
            assert np.allclose(scene.omega(body, s), run.omega[k, body], rtol=0, atol=1e-14)
    with pytest.raises(ValueError, match="output"):
        run.state(len(run))


@pytest.mark.parametrize("method", ["auto", "fehlberg78", "dopri5", "cash_karp54", "bdf", "adams"])
def test_every_method_agrees(method):
    scene, _ = tumbling_scene()
    reference = scene.integrate([5.0], method="fehlberg78", rtol=1e-12, atol=1e-12)
    run = scene.integrate([5.0], method=method, rtol=1e-10, atol=1e-10)
    assert np.allclose(run.omega, reference.omega, atol=2e-6)
    if method != "auto":
        assert run.statistics.choices[0][2] == "asked for"


def test_offset_body_under_gravity_follows_a_parabola():
    r_g = np.array([0.1, -0.2, 0.3])
    mp = tumble.MassProperties.about_centroid(2.0, DIAG, r_g)
    scene = tumble.Scene()
    b = scene.add(tumble.RigidBody("ModifiedRodriguesParameters", mp, reference="offset"),
                  velocity=[1.0, 0.0, 2.0], omega=[0.5, 3.0, -1.0])
    g = np.array([0.0, 0.0, -9.81])
    scene.add_gravity(b, g)
    run = scene.integrate(TIMES[:11], rtol=1e-11, atol=1e-11)
    for k, t in enumerate(run.t):
        s = run.state(k)
        centroid = scene.position(b, s) + scene.rotation(b, s) @ r_g
        expected = r_g + np.array([1.0, 0.0, 2.0]) * t + 0.5 * g * t * t
        # v_g(0) = v + R (omega x r_g) with R = I at t = 0.
        expected += np.cross([0.5, 3.0, -1.0], r_g) * t
        assert np.allclose(centroid, expected, atol=1e-8)
    assert np.ptp(run.energy) < 1e-8


def test_fixed_point_reaction_at_rest():
    mp = tumble.MassProperties.about_centroid(3.0, DIAG, [0.0, 0.0, -0.5])
    scene = tumble.Scene()
    b = scene.add(tumble.RigidBody("EulerParameters", mp, reference="fixed_point",
                                   fixed_point=[0.0, 0.0, 2.0]))
    scene.add_gravity(b)
    s = scene.initial_state()
    assert np.allclose(scene.position(b, s), [0, 0, 2])
    assert np.allclose(scene.reaction_force(b, s), [0, 0, 3.0 * 9.81], atol=1e-12)
    assert scene.layout(b).keys() == {"theta", "omega"}
    run = scene.integrate([1.0, 2.0])
    assert np.allclose(run.omega, 0, atol=1e-12)  # hanging straight down: at rest


def test_loads_spring_between_and_user_load():
    mp = tumble.MassProperties.about_centroid(1.0, DIAG)
    scene = tumble.Scene()
    # The rotation vector where the module has its scene (a build may compile fewer: CI's does).
    name = "RotationVector" if "RotationVector" in tumble.scene_parameterizations() else "EulerZYX"
    a = scene.add(tumble.RigidBody(name, mp), omega=[0, 0, 1])
    b = scene.add(tumble.RigidBody(name, mp), position=[0, 0, -1], omega=[1, 0, 0])
    scene.add_spring_between(a, b, [0, 0, 0], [0, 0, 0.1], stiffness=50.0, rest_length=0.8)
    scene.add_spring(a, [0.1, 0, 0], [0, 0, 0.5], stiffness=10.0)
    scene.add_point_force(b, [0, 0.1, 0], [0, 0, 1.0], components="body")
    run = scene.integrate([1.0, 2.0], rtol=1e-10, atol=1e-10)
    assert run.position.shape == (2, 2, 3)
    # A constant moment as a Python load gives what BodyMoment gives.
    results = []
    for user in (False, True):
        scene, body = tumbling_scene("EulerZYX")
        if user:
            scene.add_user_load(body, lambda t, r, R, v, w: ((0, 0, 0), (0.0, 0.01, 0.02)))
        else:
            scene.add_moment(body, [0.0, 0.01, 0.02])
        results.append(scene.integrate([1.0, 3.0], method="fehlberg78").y)
    assert np.array_equal(results[0], results[1])


@pytest.mark.parametrize("method", ["auto", "fehlberg78", "dopri5", "bdf", "adams"])
@pytest.mark.parametrize("after", [-1.0, 0.25])  # raises from the start, or from t > 0.25
def test_user_load_errors_are_integration_errors_caused_by_the_python_exception(method, after):
    def load(t, r, R, v, w):
        if t > after:
            return 1 / 0
        return (0, 0, 0), (0, 0, 0)

    scene, body = tumbling_scene()
    scene.add_user_load(body, load)
    with pytest.raises(tumble.IntegrationError,
                       match="ZeroDivisionError: division by zero") as caught:
        scene.integrate([0.5, 1.0], method=method)
    e = caught.value
    assert e.reason == "callback"
    assert 0.0 <= e.time <= max(after, 0.0)
    assert "rhs() threw at t = " in str(e)
    # The Python exception the load raised, itself, as `raise ... from` would chain it.
    assert isinstance(e.__cause__, ZeroDivisionError)
    assert str(e.__cause__) == "division by zero"
    assert e.__cause__.__traceback__ is not None


def test_integration_error():
    scene, _ = tumbling_scene()
    with pytest.raises(tumble.IntegrationError) as caught:
        scene.integrate([50.0], method="fehlberg78", max_steps=3)
    assert caught.value.reason == "step_budget"
    assert 0.0 < caught.value.time < 50.0
    assert isinstance(caught.value, RuntimeError) and str(caught.value)


def test_scene_bad_input():
    scene, body = tumbling_scene()
    with pytest.raises(ValueError, match="non-decreasing"):
        scene.integrate([2.0, 1.0])
    with pytest.raises(ValueError, match="'times' has a non-finite entry"):
        scene.integrate([1.0, np.nan])
    with pytest.raises(ValueError, match="unknown method 'rk4'"):
        scene.integrate([1.0], method="rk4")
    with pytest.raises(ValueError, match="rtol"):
        scene.integrate([1.0], rtol=-1.0)
    with pytest.raises(ValueError, match=r"'state' must have shape \(13,\)"):
        scene.integrate([1.0], state=np.zeros(12))
    with pytest.raises(ValueError, match=r"'initial' must have shape \(runs, 13\)"):
        scene.ensemble([1.0], np.zeros((4, 12)))
    with pytest.raises(ValueError, match="share one parameterization"):
        scene.add(tumble.RigidBody("EulerZYX", tumble.MassProperties.about_centroid(1.0, DIAG)))
    with pytest.raises(ValueError, match="is not a body of this scene"):
        scene.add_moment(5, [0, 0, 1])
    with pytest.raises(ValueError):  # not a rotation
        scene.add(tumble.RigidBody("EulerParameters",
                                   tumble.MassProperties.about_centroid(1.0, DIAG)),
                  rotation=2 * np.eye(3))
    missing = sorted(set(tumble.parameterization_names()) - set(tumble.scene_parameterizations()))
    if missing:
        other = tumble.Scene()
        with pytest.raises(ValueError, match="TUMBLE_PYTHON_SCENE_PARAMETERIZATIONS"):
            other.add(tumble.RigidBody(missing[0], tumble.MassProperties.about_centroid(1.0, DIAG)))
    with pytest.raises(ValueError, match="no body yet"):
        tumble.Scene().integrate([1.0])


def dispersed(scene, body, runs, rng):
    y0 = np.tile(scene.initial_state().y, (runs, 1))
    y0[:, scene.layout(body)["omega"]] *= 1 + 0.01 * rng.uniform(-1, 1, size=(runs, 3))
    return y0


@pytest.mark.parametrize("method", ["auto", "fehlberg78", "bdf"])
def test_ensemble_is_each_run_to_the_bit(method, rng):
    scene, body = tumbling_scene("ModifiedRodriguesParameters")
    y0 = dispersed(scene, body, 6, rng)
    times = [1.0, 7.0, 12.5]
    out = scene.ensemble(times, y0, method=method, threads=2, rtol=1e-9, atol=1e-9)
    assert out.y.shape == (6, 3, scene.size) and out.omega.shape == (6, 3, 1, 3)
    assert out.errors == []
    serial = scene.ensemble(times, y0, method=method, threads=1, rtol=1e-9, atol=1e-9)
    assert np.array_equal(out.y, serial.y)
    for i in range(6):
        run = scene.integrate(times, state=y0[i], method=method, rtol=1e-9, atol=1e-9)
        assert np.array_equal(out.y[i], run.y)
        assert np.array_equal(out.quaternion[i], run.quaternion)
        assert np.array_equal(out.energy[i], run.energy)


@pytest.mark.parametrize("name", ["EulerParameters", "ModifiedRodriguesParameters"])
@pytest.mark.parametrize("held", [False, True])
@pytest.mark.parametrize("method", ["fehlberg78", "dopri5", "cash_karp54"])
def test_one_body_runs_as_that_body_among_others(name, held, method):
    # A scene of one body runs Odeint with its size at compile time (a std::array state), a scene
    # of two with the size at run time: a copy of the body beside it changes neither the error
    # test (the largest over the entries) nor the steps, so the first body moves the same. The
    # initial step is given: its estimate averages over the entries, the order of a sum rounding
    # differently in the two.
    mp = tumble.MassProperties.about_centroid(1.0, DIAG)
    kw = dict(reference="fixed_point", fixed_point=[0.0, 0.0, 0.0]) if held else {}

    def scene_of(copies):
        scene = tumble.Scene()
        for _ in range(copies):
            scene.add(tumble.RigidBody(name, mp, **kw), omega=[0.1, 2.0, 0.05])
        return scene

    one, two = scene_of(1), scene_of(2)
    options = dict(method=method, rtol=1e-9, atol=1e-9, initial_step=1e-3)
    a = one.integrate(TIMES, **options)
    b = two.integrate(TIMES, **options)
    assert a.statistics.steps == b.statistics.steps > 0
    assert np.allclose(a.y, b.y[:, :one.size], rtol=0, atol=1e-13)
    assert np.allclose(a.quaternion[:, 0], b.quaternion[:, 1], rtol=0, atol=1e-13)
    y0 = np.tile(one.initial_state().y, (3, 1))
    y0[:, one.layout(0)["omega"]] *= [[1.0], [1.001], [0.999]]
    ens = one.ensemble(TIMES, y0, threads=2, **options)
    assert ens.errors == []
    assert np.array_equal(ens.y[0], a.y)


def test_ensemble_failures_are_per_run(rng):
    scene, body = tumbling_scene()
    y0 = dispersed(scene, body, 4, rng)
    y0[2, scene.layout(body)["theta"]] = 0.0  # no attitude: |p| = 0
    out = scene.ensemble([1.0], y0, threads=2)
    assert [run for run, _ in out.errors] == [2]
    assert out.errors[0][1]
    assert np.isnan(out.y[2]).all() and np.isfinite(np.delete(out.y, 2, axis=0)).all()


def test_the_gil_is_released_during_an_ensemble(rng):
    scene, body = tumbling_scene()
    y0 = dispersed(scene, body, 400, rng)
    done = {}

    def work():
        start = time.perf_counter()
        done["result"] = scene.ensemble([200.0], y0, threads=1, rtol=1e-10, atol=1e-10)
        done["seconds"] = time.perf_counter() - start

    worker = threading.Thread(target=work)
    worker.start()
    counted = 0
    while worker.is_alive():
        counted += 1  # Python runs here only if the ensemble does not hold the GIL
    worker.join()
    assert done["result"].errors == []
    assert done["seconds"] > 0.05, "the ensemble was too short to tell"
    # With the GIL held for the whole ensemble this loop would run a handful of times at most.
    assert counted > 10000
