"""tumble.Scene.add_event: event times against closed forms under every method (a falling body
and its bounce, a body spinning about a principal axis), direction filtering counted against the
crossings, errors, ensembles, and the GIL released between the Python calls."""

import gc
import sys
import threading
import time
import weakref

import numpy as np
import pytest

from conftest import quat_to_matrix

import tumble

METHODS = ["auto", "fehlberg78", "dopri5", "cash_karp54", "bdf", "adams"]
DIAG = np.diag([1.0, 2.0, 3.0])
G = 9.81


def falling_scene(height, name="EulerParameters"):
    scene = tumble.Scene()
    b = scene.add(tumble.RigidBody(name, tumble.MassProperties.about_centroid(2.0, DIAG)),
                  position=[0.3, -0.2, height], omega=[0.1, 0.2, 0.3])
    scene.add_gravity(b, [0.0, 0.0, -G])
    return scene, b


@pytest.mark.parametrize("method", METHODS)
def test_falling_body_hits_the_ground_at_the_closed_form_time(method):
    h = 5.0
    scene, b = falling_scene(h)
    seen = []
    scene.add_event(lambda t, s: s.position[b, 2], direction=-1,
                    action=lambda t, s: seen.append((t, s.position[b, 2], s.velocity[b, 2])))
    run = scene.integrate([0.5, 3.0], method=method, rtol=1e-10, atol=1e-10)
    # z = h - g t^2 / 2 reaches 0 at sqrt(2 h / g), with the speed g t.
    t1 = np.sqrt(2 * h / G)
    assert len(seen) == 1 and run.statistics.events == 1
    t, z, vz = seen[0]
    assert t == pytest.approx(t1, abs=1e-8)
    assert abs(z) < 1e-8 and vz == pytest.approx(-G * t1, rel=1e-8)
    # No action changed the state: the body falls on through the ground.
    assert run.position[-1, b, 2] == pytest.approx(h - G * 9.0 / 2, abs=1e-7)


@pytest.mark.parametrize("method", METHODS)
def test_a_bounce_gives_the_closed_form_time_of_the_second_impact(method):
    h = 5.0
    scene, b = falling_scene(h)
    vz = scene.layout(b)["velocity"].start + 2
    impacts = []

    def bounce(t, s):
        impacts.append(t)
        y = s.y
        y[vz] = -y[vz]  # an elastic impact: the vertical velocity reversed
        return y

    scene.add_event(lambda t, s: s.position[b, 2], direction=-1, action=bounce)
    # A step over the whole rise and fall after an impact would see no sign change.
    run = scene.integrate([1.0, 4.0], method=method, rtol=1e-10, atol=1e-10, max_step=0.1)
    # Down in t1 = sqrt(2 h / g) at the speed g t1, up and down again in 2 t1: the second impact
    # at 3 t1, the third (5 t1 = 5.05 s) after the end.
    t1 = np.sqrt(2 * h / G)
    assert impacts == pytest.approx([t1, 3 * t1], abs=1e-7)
    assert run.statistics.events == 2
    # At t = 4 s: going up from the second impact at the speed g t1.
    tau = 4.0 - 3 * t1
    assert run.position[-1, b, 2] == pytest.approx(G * t1 * tau - G * tau * tau / 2, abs=1e-6)
    assert run.velocity[-1, b, 2] == pytest.approx(G * t1 - G * tau, abs=1e-6)
    # Before the first impact nothing has happened yet.
    assert run.position[0, b, 2] == pytest.approx(h - G / 2, abs=1e-8)


OMEGA = 2.0  # rad/s about the principal axis z (the largest moment of inertia)
SPIN_END = 8.5  # 17 rad


def spin_crossings(direction):
    """The times at which cos(angle) = R[0, 0] crosses zero, angle = OMEGA t: at angle pi/2 + k pi,
    falling for even k and rising for odd k, up to SPIN_END."""
    k = np.arange(int((OMEGA * SPIN_END - np.pi / 2) / np.pi) + 1)
    t = (np.pi / 2 + k * np.pi) / OMEGA
    keep = {0: k >= 0, -1: k % 2 == 0, 1: k % 2 == 1}[direction]
    return t[keep]


def spinning_scene(name):
    scene = tumble.Scene()
    b = scene.add(tumble.RigidBody(name, tumble.MassProperties.about_centroid(1.0, DIAG)),
                  omega=[0.0, 0.0, OMEGA])
    return scene, b


def r00(t, s):
    """cos(angle) of the spin: R[0, 0] of the first body's quaternion (conftest's formula)."""
    return quat_to_matrix(s.quaternion[0])[0, 0]


# A step over two crossings of one function sees no sign change: the steps are bounded well below
# the crossings' spacing (pi / OMEGA), which the angles of EulerZYX or the rotation vector, linear
# in t here, would otherwise step over (any step is exact for them).
SPIN_OPTIONS = dict(rtol=1e-10, atol=1e-10, max_step=0.25)
# The crossings are located on the trajectory, whose own error they have: BDF's angle at these
# times, without events, is off by up to 1.6e-6 rad for Euler parameters (7e-8 rad for MRP); the
# explicit pairs' by 1e-10 rad at most.
SPIN_TIME_TOLERANCE = {"bdf": 5e-6, "adams": 5e-6}


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("direction", [1, -1, 0])
@pytest.mark.parametrize("name", ["ModifiedRodriguesParameters", "EulerZYX", "RotationVector",
                                  "EulerParameters"])
def test_spin_angle_crossings_under_each_direction(method, direction, name):
    if name not in tumble.scene_parameterizations():
        pytest.skip(f"no compiled scene for {name} in this build")
    scene, _ = spinning_scene(name)
    times = []
    scene.add_event(r00, direction=direction, action=lambda t, s: times.append(t))
    run = scene.integrate([SPIN_END], method=method, **SPIN_OPTIONS)
    expected = spin_crossings(direction)
    assert len(expected) == {1: 2, -1: 3, 0: 5}[direction]
    assert run.statistics.events == len(expected)
    assert times == pytest.approx(expected, abs=SPIN_TIME_TOLERANCE.get(method, 1e-8))
    # The same count without an action (nothing changes the state).
    counted, _ = spinning_scene(name)
    counted.add_event(r00, direction=direction)
    assert counted.integrate([SPIN_END], method=method, **SPIN_OPTIONS).statistics.events == len(
        expected)


def test_event_state_is_the_state_and_its_bodies():
    scene = tumble.Scene()
    mp = tumble.MassProperties.about_centroid(1.0, DIAG)
    a = scene.add(tumble.RigidBody("EulerZYX", mp), omega=[0.1, 2.0, 0.05])
    b = scene.add(tumble.RigidBody("EulerZYX", mp), position=[1.0, 0.0, 0.0],
                  velocity=[0.0, 1.0, 0.0], omega=[0.3, 0.1, 2.0])
    checked = []

    def function(t, s):
        assert isinstance(s, tumble.State) and isinstance(s, tumble.EventState)
        assert s.y.shape == (scene.size,) and s.bases.shape == (2, 3, 3)
        assert s.position.shape == (2, 3) and s.quaternion.shape == (2, 4)
        for body in (a, b):
            assert np.allclose(quat_to_matrix(s.quaternion[body]), scene.rotation(body, s),
                               rtol=0, atol=1e-14)
            assert np.array_equal(s.omega[body], scene.omega(body, s))
            assert np.array_equal(s.position[body], scene.position(body, s))
            assert np.array_equal(s.velocity[body], scene.velocity(body, s))
        checked.append(t)
        return s.position[b, 1] - 1.5  # body b moves along y at 1 m/s: 0 at t = 1.5 s

    hits = []
    scene.add_event(function, action=lambda t, s: hits.append(t))
    run = scene.integrate([3.0], method="fehlberg78")
    assert checked and hits == pytest.approx([1.5], abs=1e-9)
    assert run.statistics.events == 1


def test_bad_input():
    scene, b = falling_scene(5.0)
    with pytest.raises(ValueError, match="'function' must be callable"):
        scene.add_event(3.0)
    with pytest.raises(ValueError,
                       match=r"'direction' must be \+1 \(rising\), -1 \(falling\) or 0"):
        scene.add_event(lambda t, s: 1.0, direction=2)
    with pytest.raises(ValueError, match="'action' must be None or callable"):
        scene.add_event(lambda t, s: 1.0, action="bounce")
    scene.integrate([1.0])  # none of them was added

    def ground(t, s):
        return s.position[b, 2]

    for action, message in [
        (lambda t, s: s.y[:-1], r"an event action must return None or a new y of shape \(13,\), "
                                r"got shape \(12,\)"),
        (lambda t, s: s.y.reshape(1, -1), r"got shape \(1, 13\)"),
        (lambda t, s: np.full(13, np.nan), "non-finite entry at index 0"),
        (lambda t, s: "up", "not an array of numbers"),
    ]:
        scene, b = falling_scene(5.0)
        scene.add_event(ground, direction=-1, action=action)
        for method in ("fehlberg78", "bdf"):
            with pytest.raises(ValueError, match=message):
                scene.integrate([2.0], method=method)


@pytest.mark.parametrize("method", METHODS)
def test_function_errors_are_integration_errors_caused_by_the_python_exception(method):
    def function(t, s):
        if t > 0.25:
            return 1 / 0
        return 1.0

    scene, _ = falling_scene(5.0)
    scene.add_event(function)
    with pytest.raises(tumble.IntegrationError,
                       match="the event function raised ZeroDivisionError: division by zero") as c:
        scene.integrate([0.5, 1.0], method=method)
    e = c.value
    assert e.reason == "callback" and "roots() threw at t = " in str(e)
    assert 0.0 < e.time <= 0.5  # the time reached: near 0.25, where the function raised
    assert isinstance(e.__cause__, ZeroDivisionError) and e.__cause__.__traceback__ is not None
    # A function that returns no number, or NaN: the same, with a TypeError or a ValueError.
    for bad, cause, message in [(None, TypeError, "must return a float, got NoneType"),
                                (float("nan"), ValueError, "returned nan")]:
        scene, _ = falling_scene(5.0)
        scene.add_event(lambda t, s: bad)
        with pytest.raises(tumble.IntegrationError, match=message) as c:
            scene.integrate([1.0], method=method)
        assert c.value.reason == "callback" and isinstance(c.value.__cause__, cause)


@pytest.mark.parametrize("method", METHODS)
def test_action_errors_reach_the_caller_unchanged(method):
    # As tumble::Event's actions: run between steps, what they throw passes through.
    class Impact(Exception):
        pass

    def action(t, s):
        raise Impact(f"at {t:.3f}")

    scene, b = falling_scene(5.0)
    scene.add_event(lambda t, s: s.position[b, 2], direction=-1, action=action)
    with pytest.raises(Impact, match=r"at 1\.010"):
        scene.integrate([2.0], method=method)


def test_the_scene_cannot_change_while_it_integrates():
    scene, b = falling_scene(5.0)
    scene.add_event(lambda t, s: s.position[b, 2], direction=-1,
                    action=lambda t, s: scene.add_event(lambda t, s: 1.0))
    with pytest.raises(ValueError, match="cannot change while it integrates"):
        scene.integrate([2.0])
    scene.add_event(lambda t, s: 1.0)  # after the run it can


@pytest.mark.parametrize("method", ["auto", "fehlberg78", "bdf"])
def test_ensemble_with_events_is_each_run(method, rng):
    scene, b = falling_scene(5.0)
    z = scene.layout(b)["position"].start + 2
    vz = scene.layout(b)["velocity"].start + 2

    def bounce(t, s):
        y = s.y
        y[vz] = -y[vz]
        return y

    scene.add_event(lambda t, s: s.position[b, 2], direction=-1, action=bounce)
    y0 = np.tile(scene.initial_state().y, (6, 1))
    y0[:, z] = rng.uniform(1.0, 10.0, 6)
    times = np.array([0.5, 2.0, 4.0])
    options = dict(method=method, rtol=1e-10, atol=1e-10, max_step=0.1)  # see the bounce above
    out = scene.ensemble(times, y0, threads=2, **options)
    assert out.errors == []
    for i in range(6):
        run = scene.integrate(times, state=y0[i], **options)
        assert np.array_equal(out.y[i], run.y)
        # Dropped from h, bouncing elastically: impacts at (2k - 1) t1, t1 = sqrt(2 h / g), each
        # sending it up at g t1.
        t1 = np.sqrt(2 * y0[i, z] / G)
        k = np.floor((times / t1 + 1) / 2)  # impacts before t
        expected = np.where(k == 0, -G * times, G * t1 - G * (times - (2 * k - 1) * t1))
        assert np.allclose(out.velocity[i, :, b, 2], expected, rtol=0, atol=1e-6)
    # A run whose event function raises fails alone, with its message.
    failing = tumble.Scene()
    c = failing.add(tumble.RigidBody("EulerParameters",
                                     tumble.MassProperties.about_centroid(1.0, DIAG)))
    failing.add_gravity(c)
    failing.add_event(lambda t, s: 1 / 0 if s.y[0] > 0.5 else 1.0)
    y0 = np.tile(failing.initial_state().y, (4, 1))
    y0[1, 0] = 1.0
    res = failing.ensemble([1.0], y0, method=method, threads=2)
    assert [run for run, _ in res.errors] == [1]
    assert "the event function raised ZeroDivisionError" in res.errors[0][1]
    assert np.isnan(res.y[1]).all() and np.isfinite(np.delete(res.y, 1, axis=0)).all()


def test_the_gil_is_released_between_the_event_calls():
    scene = tumble.Scene()
    b = scene.add(tumble.RigidBody("EulerParameters",
                                   tumble.MassProperties.about_centroid(1.0, DIAG)),
                  omega=[0.1, 2.0, 0.05])
    calls = []

    def function(t, s):
        calls.append(t)
        return s.omega[b, 1]  # the Dzhanibekov flips: omega_y changes sign

    scene.add_event(function)
    done = {}

    def work():
        # Repeated until 0.2 s have passed: one run took 9 ms on CI, too short to tell.
        start = time.perf_counter()
        done["runs"] = 0
        while time.perf_counter() - start < 0.2:
            done["run"] = scene.integrate([200.0], rtol=1e-11, atol=1e-11, method="fehlberg78")
            done["runs"] += 1

    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-4)  # each event call waits for the main thread's slice to end
    try:
        worker = threading.Thread(target=work)
        worker.start()
        counted = 0
        while worker.is_alive():
            counted += 1  # Python runs here only while the integration does not hold the GIL
        worker.join()
    finally:
        sys.setswitchinterval(interval)
    assert done["run"].statistics.events > 4 and len(calls) > 100 * done["runs"]
    assert counted > 1000


def test_a_scene_and_its_callables_are_collected():
    # An event that refers to its scene (a closure over it) makes a cycle through C++: Python's
    # cycle collector must see it, or the scene and its callables would never be freed.
    scene, b = falling_scene(5.0)

    def function(t, s):
        return scene.position(b, s)[2]

    def load(t, r, R, v, w):
        return scene.size * np.zeros(3), np.zeros(3)

    scene.add_event(function, direction=-1, action=lambda t, s: scene.state(s.y).y)
    scene.add_user_load(b, load)
    assert scene.integrate([2.0]).statistics.events == 1
    refs = [weakref.ref(function), weakref.ref(load)]
    del scene, function, load
    gc.collect()
    assert [r() for r in refs] == [None, None]
