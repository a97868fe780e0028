#!/usr/bin/env python3
"""tumble_bench, study (e): Exudyn on the IFToMM mechanisms A01-A05 and the open chain.

Run by peers/exudyn_mechanisms.cpp through the Python found at configure time:

    python exudyn_mechanisms.py INPUT.json OUTPUT.txt

INPUT (written by the C++ side from the data of tumble's own problem):
    problem   "a01", "a02", "a03", "a04", "a05" or "chain"
    times     the output times (s), increasing, from the first output to the end
    ladder    steps per output interval, one run per entry (the step h = first time / entry)
    solvers   Exudyn's DynamicSolverType names to run, e.g. ["GeneralizedAlpha"]
    reps, slow_run, clock   tumble's Timing: best of `reps` runs, one run once a run takes
              longer than `slow_run` s; "wall" or "cpu" decides which clock those refer to
    budget    s: a ladder stops after a run that took longer (the finer steps would take longer)
    pendulum  A01: mass (kg), inertia (kg m^2, about the centroid, isotropic), pivot, start,
              gravity (m, m/s^2); the bob hangs on a massless bar of |start - pivot|
    linkage   A02, A03: mechanisms.hpp's PlanarLinkage (links with their starting rates, loops,
              gravity, spring and motor: none when the stiffness or the torque is 0)
    spatial   A04 and the chain: bodies (centroid, rotation body -> world, mass, inertia about
              the centroid in body axes, the centroid's velocity and the angular velocity in the
              world at the start), hinges (bodies a, b, -1 the ground; a point and an axis in the
              world), gravity, the tracked point (body, point in body axes), redundant (whether
              the hinges' rows are of deficient rank: A04's are, the chain's are not)
    flyball   A05: mechanisms.hpp's FlyballGovernor (z up, the shaft from the origin, the rods'
              hinges at (+-offset, 0, top), everything turning about z at `spin` at the start)

OUTPUT, tab-separated lines (a file, since Exudyn prints on stdout):
    run  solver  substeps  h  ok  steps  newton_iterations  jacobians  |C|  walls  cpus  message
    point  k  x  y  z         A01, A04, chain: the tracked point at output k (after each
                              successful run); A05: the slider's height as (s, 0, 0)
    angles  k  a0  a1 ...     A02/A03: the links' absolute angles at output k (rad, over the turns)
    end                       written last: the file is complete

The models are in absolute coordinates, as tumble's: A01, A04, A05 and the chain rigid bodies with
Euler parameters (NodeRigidBodyEP, ObjectRigidBody), A02 and A03 planar rigid bodies (NodeRigidBody2D:
x, y and the angle per link, Exudyn's element for a planar linkage, which avoids the nine
redundant rows of spatial hinges in a plane). Exudyn's explicit solvers refuse joints (its
documentation: "explicit solvers are in general only applicable for systems without
constraints"), so the solvers are the implicit index-3 generalized-alpha and the index-2
trapezoidal rule, both of second order, over a ladder of fixed steps. Only exu.SolveDynamic is
timed (it includes the solver's initialization, as tumble's rows include their integrator's
construction); building and assembling the model is not.
"""

import json
import math
import sys
import time
import traceback

sys.exudynFast = True  # Exudyn's build without range checks (its documentation: 30 % faster)
import exudyn as exu  # noqa: E402
import numpy as np  # noqa: E402
from exudyn.itemInterface import (  # noqa: E402
    LoadMassProportional, LoadTorqueVector, MarkerBodyMass, MarkerBodyPosition, MarkerBodyRigid,
    NodeRigidBody2D, NodeRigidBodyEP, ObjectConnectorDistance, ObjectConnectorSpringDamper,
    ObjectGround, ObjectJointPrismaticX, ObjectJointRevolute2D, ObjectJointRevoluteZ,
    ObjectRigidBody, ObjectRigidBody2D, SensorBody, SensorNode)
from exudyn.rigidBodyUtilities import (  # noqa: E402
    AngularVelocity2EulerParameters_t, RotationMatrix2EulerParameters)


def frame_with_z(axis):
    """An orthonormal frame whose third column is `axis` (a hinge's marker frame: JointRevoluteZ
    turns about the markers' z; their x and y need not agree)."""
    z = np.asarray(axis, float) / np.linalg.norm(axis)
    helper = np.array([1.0, 0, 0]) if abs(z[0]) < 0.9 else np.array([0, 1.0, 0])
    x = np.cross(helper, z)
    x /= np.linalg.norm(x)
    return np.column_stack([x, np.cross(z, x), z])


def frame_with_x(axis):
    """An orthonormal frame whose first column is `axis` (a prismatic joint's marker frame:
    JointPrismaticX slides along the markers' x)."""
    f = frame_with_z(axis)
    return np.column_stack([f[:, 2], f[:, 0], f[:, 1]])


def marker_with_frame(mbs, body, local, frame):
    """A rigid marker on `body` at `local` (body axes) and the joint's frame there: in the marker
    (Exudyn >= 1.12.244) or, returned, for the joint's rotationMarker argument."""
    if hasattr(exu, "HT"):
        return mbs.AddMarker(MarkerBodyRigid(
            bodyNumber=body, localHT=exu.HT(rotation=frame, translation=list(local)))), None
    return mbs.AddMarker(MarkerBodyRigid(bodyNumber=body, localPosition=list(local))), frame


def joint_frames(fa, fb):
    """A joint's rotationMarker arguments: none when the markers carry the frames
    (marker_with_frame returned None), else the two frames."""
    return {} if fa is None else {"rotationMarker0": fa, "rotationMarker1": fb}


class Model:
    """An assembled Exudyn system, what the run records and how |C| is measured after it."""

    def __init__(self):
        self.sc = exu.SystemContainer()
        self.mbs = self.sc.AddSystem()
        self.ground = self.mbs.AddObject(ObjectGround())
        self.sensor = None  # the tracked point (A01, A04)
        self.pairs = []  # (body, local point, body, local point) that must coincide: |C|
        self.nodes = None  # A02/A03: (sensor, starting angle) per link, its angle stored
        self.redundant = False  # A04: constraint rows of deficient rank
        self.height = False  # A05: the tracked point's height z is written, as (z, 0, 0)

    def point(self, body, local):
        """A body point in the world (Exudyn's output at the current state), m."""
        if body is None:
            return np.asarray(local, float)
        return np.asarray(self.mbs.GetObjectOutputBody(
            body, exu.OutputVariableType.Position, localPosition=list(local)), float)[:3]

    def residual(self):
        return max((np.linalg.norm(self.point(a, pa) - self.point(b, pb))
                    for a, pa, b, pb in self.pairs), default=0.0)


def pendulum(data):
    """A01: the bob a rigid body with Euler parameters, its centre on an ObjectConnectorDistance
    to the pivot (a massless bar with spherical ends, as tumble's Distance joint)."""
    m = Model()
    mbs = m.mbs
    start, pivot = np.asarray(data["start"], float), np.asarray(data["pivot"], float)
    node = mbs.AddNode(NodeRigidBodyEP(referenceCoordinates=list(start) + [1.0, 0, 0, 0]))
    j = data["inertia"]
    bob = mbs.AddObject(ObjectRigidBody(mass=data["mass"], inertia=[j, j, j, 0, 0, 0],
                                        nodeNumber=node))
    on_ground = mbs.AddMarker(MarkerBodyPosition(bodyNumber=m.ground, localPosition=list(pivot)))
    on_bob = mbs.AddMarker(MarkerBodyPosition(bodyNumber=bob, localPosition=[0, 0, 0]))
    mbs.AddObject(ObjectConnectorDistance(markerNumbers=[on_ground, on_bob],
                                          distance=float(np.linalg.norm(start - pivot))))
    mbs.AddLoad(LoadMassProportional(markerNumber=mbs.AddMarker(MarkerBodyMass(bodyNumber=bob)),
                                     loadVector=list(data["gravity"])))
    m.sensor = mbs.AddSensor(SensorBody(bodyNumber=bob, localPosition=[0, 0, 0],
                                        storeInternal=True,
                                        outputVariableType=exu.OutputVariableType.Position))
    length = float(np.linalg.norm(start - pivot))
    m.residual = lambda: abs(np.linalg.norm(m.point(bob, [0, 0, 0]) - pivot) - length)
    return m


def spatial(data):
    """A04 and the chain: rigid bodies with Euler parameters at their centroids, moving at the
    start as given (the parameters' rates from the world angular velocity), a JointRevoluteZ per
    hinge."""
    m = Model()
    mbs = m.mbs
    bodies, frames = [], []
    for b in data["bodies"]:
        rot = np.asarray(b["rotation"], float)
        ep = RotationMatrix2EulerParameters(rot)
        rates = AngularVelocity2EulerParameters_t(np.asarray(b.get("omega", [0.0] * 3), float), ep)
        node = mbs.AddNode(NodeRigidBodyEP(
            referenceCoordinates=list(b["centroid"]) + list(ep),
            initialVelocities=list(b.get("velocity", [0.0] * 3)) + list(rates)))
        j = np.asarray(b["inertia"], float)  # Exudyn's order: xx, yy, zz, yz, xz, xy
        body = mbs.AddObject(ObjectRigidBody(
            mass=b["mass"], inertia=[j[0, 0], j[1, 1], j[2, 2], j[1, 2], j[0, 2], j[0, 1]],
            nodeNumber=node))
        mbs.AddLoad(LoadMassProportional(
            markerNumber=mbs.AddMarker(MarkerBodyMass(bodyNumber=body)),
            loadVector=list(data["gravity"])))
        bodies.append(body)
        frames.append((np.asarray(b["centroid"], float), rot))

    def marker(index, at, axis):  # a hinge's marker on body `index` (-1: the ground)
        if index < 0:
            body, local, frame = m.ground, at, frame_with_z(axis)
        else:
            c, rot = frames[index]
            body, local, frame = bodies[index], rot.T @ (at - c), frame_with_z(rot.T @ axis)
        number, given = marker_with_frame(mbs, body, local, frame)
        return number, given, (None if index < 0 else body), local

    for h in data["hinges"]:
        at, axis = np.asarray(h["at"], float), np.asarray(h["axis"], float)
        ma, fa, ba, la = marker(h["a"], at, axis)
        mb, fb, bb, lb = marker(h["b"], at, axis)
        mbs.AddObject(ObjectJointRevoluteZ(markerNumbers=[ma, mb], **joint_frames(fa, fb)))
        m.pairs.append((ba, la, bb, lb))
    track = data["track"]
    m.sensor = mbs.AddSensor(SensorBody(bodyNumber=bodies[track["body"]],
                                        localPosition=list(track["point"]), storeInternal=True,
                                        outputVariableType=exu.OutputVariableType.Position))
    m.redundant = data.get("redundant", True)
    return m


def flyball(data):
    """A05: shaft, slider and the two rods (each with its ball one body) as rigid bodies with Euler
    parameters at their centroids, all turning about z at `spin` at the start; the shaft on a
    JointRevoluteZ to the ground at the origin, the slider on a JointPrismaticX along the shaft's
    axis (it turns with the shaft), each rod on a JointRevoluteZ about y at the shaft's top, the
    spring-dampers ObjectConnectorSpringDamper from each rod's midpoint to the slider's point
    (+-offset, 0, 0), gravity by LoadMassProportional. The tracked point: the slider's centre,
    its height written."""
    m = Model()
    mbs = m.mbs
    spin = np.array([0.0, 0.0, data["spin"]])
    gravity = [0.0, 0.0, -data["gravity"]]

    def body(centroid, rot, mass, inertia):  # inertia: the principal moments in body axes
        centroid = np.asarray(centroid, float)
        ep = RotationMatrix2EulerParameters(rot)
        node = mbs.AddNode(NodeRigidBodyEP(
            referenceCoordinates=list(centroid) + list(ep),
            initialVelocities=list(np.cross(spin, centroid)) +
            list(AngularVelocity2EulerParameters_t(spin, ep))))
        number = mbs.AddObject(ObjectRigidBody(mass=mass, inertia=list(inertia) + [0, 0, 0],
                                               nodeNumber=node))
        mbs.AddLoad(LoadMassProportional(
            markerNumber=mbs.AddMarker(MarkerBodyMass(bodyNumber=number)), loadVector=gravity))
        return number

    half = 0.5 * data["shaft_length"]
    shaft = body([0, 0, half], np.eye(3), data["shaft_mass"], data["shaft_inertia"])
    j = data["slider_inertia"]
    slider = body([0, 0, data["s0"]], np.eye(3), data["slider_mass"], [j, j, j])
    z, y = np.array([0.0, 0, 1]), np.array([0.0, 1, 0])
    # The shaft turns about z at its bottom end, the origin.
    ma, fa = marker_with_frame(mbs, m.ground, [0, 0, 0], frame_with_z(z))
    mb, fb = marker_with_frame(mbs, shaft, [0, 0, -half], frame_with_z(z))
    mbs.AddObject(ObjectJointRevoluteZ(markerNumbers=[ma, mb], **joint_frames(fa, fb)))
    m.pairs.append((None, [0, 0, 0], shaft, [0, 0, -half]))
    # The slider slides along the shaft's axis and turns with it.
    ma, fa = marker_with_frame(mbs, shaft, [0, 0, data["s0"] - half], frame_with_x(z))
    mb, fb = marker_with_frame(mbs, slider, [0, 0, 0], frame_with_x(z))
    mbs.AddObject(ObjectJointPrismaticX(markerNumbers=[ma, mb], **joint_frames(fa, fb)))
    alpha, c = data["alpha"], data["rod_centroid"]
    for side in (1.0, -1.0):
        hinge = np.array([side * data["offset"], 0, data["top"]])
        along = np.array([side * math.cos(alpha), 0, -math.sin(alpha)])
        turn = alpha if side > 0 else math.pi - alpha  # about y: body x from hinge to ball
        rot = np.array([[math.cos(turn), 0, math.sin(turn)], [0, 1, 0],
                        [-math.sin(turn), 0, math.cos(turn)]])
        rod = body(hinge + c * along, rot, data["rod_mass"],
                   [data["rod_axial"], data["rod_transverse"], data["rod_transverse"]])
        on_shaft = hinge - np.array([0, 0, half])
        ma, fa = marker_with_frame(mbs, rod, [-c, 0, 0], frame_with_z(y))
        mb, fb = marker_with_frame(mbs, shaft, on_shaft, frame_with_z(y))
        mbs.AddObject(ObjectJointRevoluteZ(markerNumbers=[ma, mb], **joint_frames(fa, fb)))
        m.pairs.append((rod, [-c, 0, 0], shaft, list(on_shaft)))
        mid = mbs.AddMarker(MarkerBodyPosition(
            bodyNumber=rod, localPosition=[0.5 * data["rod_length"] - c, 0, 0]))
        end = mbs.AddMarker(MarkerBodyPosition(bodyNumber=slider,
                                               localPosition=[side * data["offset"], 0, 0]))
        mbs.AddObject(ObjectConnectorSpringDamper(
            markerNumbers=[mid, end], stiffness=data["stiffness"], damping=data["damping"],
            referenceLength=data["rest_length"]))
    m.sensor = mbs.AddSensor(SensorBody(bodyNumber=slider, localPosition=[0, 0, 0],
                                        storeInternal=True,
                                        outputVariableType=exu.OutputVariableType.Position))
    m.height = True
    hinges = m.residual

    def residual():  # the hinges' points apart, and the slider's centre off the shaft's axis
        axis = m.point(shaft, [0, 0, 0]), m.point(shaft, [0, 0, half])
        u = (axis[1] - axis[0]) / np.linalg.norm(axis[1] - axis[0])
        d = m.point(slider, [0, 0, 0]) - axis[0]
        return max(hinges(), float(np.linalg.norm(d - d.dot(u) * u)))
    m.residual = residual
    return m


def planar(data):
    """A02, A03: a NodeRigidBody2D (x, y, angle) per link at its centroid, a JointRevolute2D per
    hinge (each link's to its parent, and the loops'), gravity by LoadMassProportional; the spring,
    when there is one, an ObjectConnectorSpringDamper from D to C, the motor, when there is one, a
    LoadTorqueVector about z on the crank. The starting velocities are the nodes' (absolute
    coordinates): each centroid's, from the links' rates along the tree."""
    m = Model()
    mbs = m.mbs
    links = data["links"]

    def velocity(index, at):  # the velocity of link `index`'s point at `at` (x, y) at the start
        if index < 0:
            return np.zeros(2)
        link = links[index]
        r = np.asarray(at, float) - np.asarray(link["hinge"], float)
        w = link.get("rate", 0.0)  # w x r in the plane: w (-r_y, r_x)
        return velocity(link["parent"], link["hinge"]) + w * np.array([-r[1], r[0]])

    nodes, bodies = [], []
    gravity = list(data.get("gravity", [0.0, 0.0])) + [0.0]
    for i, link in enumerate(links):
        c = link["centroid"]
        v = velocity(i, c)
        nodes.append(mbs.AddNode(NodeRigidBody2D(
            referenceCoordinates=[c[0], c[1], link["angle"]],
            initialVelocities=[float(v[0]), float(v[1]), link.get("rate", 0.0)])))
        bodies.append(mbs.AddObject(ObjectRigidBody2D(mass=link["mass"],
                                                      inertia=link["inertia"],
                                                      nodeNumber=nodes[-1])))
        if any(gravity):
            mbs.AddLoad(LoadMassProportional(
                markerNumber=mbs.AddMarker(MarkerBodyMass(bodyNumber=bodies[-1])),
                loadVector=gravity))

    def local(index, at):  # a world point (x, y) of the starting configuration in link axes
        link = links[index]
        d = np.asarray(at, float) - np.asarray(link["centroid"], float)
        ca, sa = math.cos(link["angle"]), math.sin(link["angle"])
        return [ca * d[0] + sa * d[1], -sa * d[0] + ca * d[1], 0.0]

    def marker(index, at):
        if index < 0:
            return (mbs.AddMarker(MarkerBodyPosition(bodyNumber=m.ground,
                                                     localPosition=[at[0], at[1], 0.0])),
                    None, [at[0], at[1], 0.0])
        p = local(index, at)
        return (mbs.AddMarker(MarkerBodyPosition(bodyNumber=bodies[index], localPosition=p)),
                bodies[index], p)

    def hinge(a, b, at):
        ma, ba, pa = marker(a, at)
        mb, bb, pb = marker(b, at)
        mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[ma, mb]))
        m.pairs.append((ba, pa, bb, pb))

    for i, link in enumerate(links):
        hinge(i, link["parent"], link["hinge"])
    for loop in data["loops"]:
        hinge(loop["a"], loop["b"], loop["at"])
    if data["stiffness"] != 0:
        on_link = marker(data["spring_link"], data["spring_on_link"])[0]
        on_ground = marker(-1, data["spring_on_ground"])[0]
        mbs.AddObject(ObjectConnectorSpringDamper(markerNumbers=[on_link, on_ground],
                                                  stiffness=data["stiffness"], damping=0.0,
                                                  referenceLength=data["rest_length"]))
    if data["torque"] != 0:
        motor = mbs.AddMarker(MarkerBodyRigid(bodyNumber=bodies[data["motor_link"]],
                                              localPosition=[0, 0, 0]))
        mbs.AddLoad(LoadTorqueVector(markerNumber=motor, loadVector=[0, 0, data["torque"]]))
    # The angle is a coordinate of the node, counted over the turns (reference + displacement):
    # a sensor per node stores its coordinates (x, y, angle displacement) at every output.
    m.nodes = [(mbs.AddSensor(SensorNode(nodeNumber=n, storeInternal=True, writeToFile=False,
                                         outputVariableType=exu.OutputVariableType.Coordinates)),
                link["angle"]) for n, link in zip(nodes, links)]
    return m


def settings(model, solver, t_end, steps, write_period):
    s = exu.SimulationSettings()
    ti = s.timeIntegration
    ti.endTime = t_end
    ti.numberOfSteps = steps
    ti.verboseMode = 0
    # Newton: tight enough that its tolerance does not limit the error on any rung. Exudyn's
    # default, relative 1e-8 and absolute 1e-10, does on A01 (2.3e-2 m instead of 1.8e-3 m at 64
    # steps per output); 1e-10 and 1e-12 give the errors of 1e-12 and 1e-14 within 0.2 % on every
    # rung, 5 % faster (docs/benchmarks/mechanisms.md). Modified Newton (the Jacobian kept while
    # it converges), Exudyn's default, is as fast as full Newton here.
    ti.newton.relativeTolerance = 1e-10
    ti.newton.absoluteTolerance = 1e-12
    ti.newton.maxIterations = 50
    ti.adaptiveStep = False  # a fixed step: a Newton failure fails the run instead of refining
    # generalized-alpha: Exudyn's default spectral radius at infinity, 0.9. 1.0 (no numerical
    # damping) fails with index-3 constraints; 0.99 fails at the coarse steps and is 1 % more
    # accurate than 0.9 elsewhere (A01). The trapezoidal rule does not use it.
    ti.generalizedAlpha.spectralRadius = 0.9
    if model.redundant:  # Exudyn's remedy for redundant constraints: full-pivoting LU
        s.linearSolver.solverType = exu.LinearSolverType.EigenDense
        s.linearSolver.ignoreSingularJacobian = True
    s.solution.file.write = False
    s.solution.sensors.writePeriod = write_period
    s.parallel.numberOfThreads = 1
    return s


def outputs(stored, times):
    """The rows of a sensor's stored data (time first) at the output times; ValueError when one
    is missing."""
    stored = np.asarray(stored)
    rows = []
    for t in times:
        i = int(np.argmin(np.abs(stored[:, 0] - t)))
        if abs(stored[i, 0] - t) > 1e-9 * t:
            raise ValueError(f"no sensor output at t = {t} s")
        rows.append(stored[i])
    return rows


def run(data, build, solver, substeps, out):
    times = data["times"]
    h = times[0] / substeps
    steps = int(round(times[-1] / h))
    model = build()
    model.mbs.Assemble()
    s = settings(model, solver, times[-1], steps, times[0])
    walls, cpus = [], []
    ok, message = True, ""
    attempt = time.perf_counter()
    stats = (0, 0, 0)
    try:
        while True:
            w0, c0 = time.perf_counter(), time.thread_time()
            model.mbs.SolveDynamic(s, solverType=getattr(exu.DynamicSolverType, solver),
                                   storeSolver=True)
            walls.append(time.perf_counter() - w0)
            cpus.append(time.thread_time() - c0)
            base = cpus if data["clock"] == "cpu" else walls
            if len(base) >= data["reps"] or (len(base) == 1 and base[0] > data["slow_run"]):
                break
        it = model.mbs.sys["dynamicSolver"].it
        stats = (it.currentStepIndex, it.newtonStepsCount, it.newtonJacobiCount)
    except Exception as e:  # Exudyn raises SolverError, and others, when a run fails
        ok, message = False, "Exudyn: " + (str(e) or type(e).__name__)
    drift = model.residual() if ok else float("nan")
    record = []
    try:
        if ok and model.sensor is not None:
            stored = outputs(model.mbs.GetSensorStoredData(model.sensor), times)
            record = ["point\t%d\t%.17g\t%.17g\t%.17g" % (
                (k,) + ((row[3], 0.0, 0.0) if model.height else tuple(row[1:4])))
                for k, row in enumerate(stored)]
        if ok and model.nodes is not None:
            stored = [outputs(model.mbs.GetSensorStoredData(sensor), times)
                      for sensor, _ in model.nodes]
            record = ["angles\t%d\t" % k + "\t".join(
                "%.17g" % (angle + rows[k][3]) for rows, (_, angle) in zip(stored, model.nodes))
                for k in range(len(times))]
    except ValueError as e:
        ok, message, record = False, str(e), []
    fields = [solver, substeps, "%.17g" % h, int(ok), *stats, "%.17g" % drift,
              ",".join("%.9g" % w for w in walls), ",".join("%.9g" % c for c in cpus),
              " ".join(message.split())]
    out.write("run\t" + "\t".join(str(f) for f in fields) + "\n")
    for line in record:
        out.write(line + "\n")
    out.flush()
    base = cpus if data["clock"] == "cpu" else walls
    return min(base) if ok else time.perf_counter() - attempt


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    with open(sys.argv[1]) as f:
        data = json.load(f)
    builders = {"a01": lambda: pendulum(data["pendulum"]),
                "a02": lambda: planar(data["linkage"]),
                "a03": lambda: planar(data["linkage"]),
                "a04": lambda: spatial(data["spatial"]),
                "a05": lambda: flyball(data["flyball"]),
                "chain": lambda: spatial(data["spatial"])}
    build = builders[data["problem"]]
    with open(sys.argv[2], "w") as out:
        for solver in data["solvers"]:
            for substeps in data["ladder"]:
                # A failed run (Newton diverged at a coarse step) does not end the ladder;
                # a slow one does: the finer steps would take longer still.
                if run(data, build, solver, substeps, out) > data["budget"]:
                    break
        out.write("end\n")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except Exception:  # a clear message for tumble_bench's stderr
        traceback.print_exc()
        sys.exit(1)
