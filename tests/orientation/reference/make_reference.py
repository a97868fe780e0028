#!/usr/bin/env python3
"""50-digit reference values for tests/orientation/properties.test.cpp.

For a handful of fixed states (theta, thetadot, omega, alpha) of every orientation
parameterization of tumble, this script computes with mpmath, at 60+ significant digits,

    R                 the rotation matrix (body -> inertial, r_F = R r_f),
    G                 the 3 x n matrix of omega = G thetadot (reference chapter, Eq. 1.5),
    Gdot              d/dt G(theta + t thetadot) at t = 0 (a 3 x n matrix),
    Gdot_thetadot     the product of Eq. (1.10),
    thetadot(omega)   the inverse map, G thetadot = omega (tangent to |p| = 1 for Euler parameters),
    thetaddot         the solution of G thetaddot = alpha - Gdot thetadot (Eq. 1.10), plus
                      p . pddot = -|pdot|^2 for Euler parameters,

and writes them to reference_values.hpp, which the C++ test compares the double results with.

The route is independent of the C++ formulas on purpose:
  * R comes from the DEFINITIONS (docs/conventions.md): the intrinsic product
    R_a1(t1) R_a2(t2) R_a3(t3) for Euler angles, and Rodrigues' axis-angle formula
    R = cos(phi) I + sin(phi) S(n) + (1 - cos(phi)) n n^T for the rest, with the angle and axis
    read off the coordinates by their definitions: Euler parameters (cos(phi/2), n sin(phi/2)),
    the Gibbs vector n tan(phi/2), modified Rodrigues parameters n tan(phi/4), the rotation vector
    phi n. No C++ closed form for R, G or Gdot thetadot is used.
  * G comes from the definition of the angular velocity, S(omega) = R^T Rdot (Eq. 1.3 in body
    components): column j of G is vee(R^T dR/dtheta_j), with dR/dtheta_j by mpmath.diff.
    For Euler parameters R is evaluated at p / |p| (R depends on the direction of p only), so the
    radial column combination is zero, G p = 0, as for the unit-norm constraint.
  * Gdot_thetadot = d/dt vee(R^T Rdot) along theta(t) = theta + t thetadot, i.e.
    vee(Rdot^T Rdot + R^T Rddot) with Rdot, Rddot by mpmath.diff (first and second derivative);
    Gdot (the matrix) by mixed partial derivatives d^2 R / dtheta_j dt, and the script checks that
    Gdot thetadot from the matrix equals the product from the second derivative.
  * The inverse map and thetaddot solve the linear systems with G at working precision.

mpmath.diff evaluates central differences with a step of 2^-(prec + 10) at (prec + 20)(n + 1)
bits, so a derivative keeps about prec bits. Everything is computed twice, at 60 and at 80
digits, and the script stops unless both agree to 1e-50 relative: the header's 50 digits are
then correct.

Inputs are doubles (written to the header as exact hexadecimal literals), so the C++ test and
this script start from the same numbers. Euler parameters are normalized in double only, so
|p|^2 = 1 + O(1e-16); the reference is the exact attitude of p / |p|, and the C++ results differ
from it by that O(eps) as well, which is part of the measured error.

Usage:  python3 tests/orientation/reference/make_reference.py   (rewrites reference_values.hpp)
Needs mpmath (pip install mpmath; sympy ships it).
"""

import math
import os
import random
import sys
import time

import mpmath
from mpmath import mp, mpf

DIGITS_WRITTEN = 50
CHECK_DIGITS = 50

# --------------------------------------------------------------------------------------------
# Definitions: R(theta) for every parameterization, in mpmath.
# --------------------------------------------------------------------------------------------

AXES = {"X": 0, "Y": 1, "Z": 2}


def eye3():
    return mp.eye(3)


def skew(a):
    return mp.matrix([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])


def vee_antisymmetric(m):
    """vee of the antisymmetric part of a 3 x 3 matrix."""
    return [(m[2, 1] - m[1, 2]) / 2, (m[0, 2] - m[2, 0]) / 2, (m[1, 0] - m[0, 1]) / 2]


def axis_angle(n, phi):
    """Rodrigues' formula for the rotation by phi about the unit axis n (active, body -> inertial)."""
    c, s = mp.cos(phi), mp.sin(phi)
    nn = mp.matrix(3, 1)
    for i in range(3):
        nn[i] = n[i]
    return c * eye3() + s * skew(n) + (1 - c) * (nn * nn.T)


def elementary(axis, t):
    """R_axis(t): the active rotation by t about the coordinate axis (R_x = [1 0 0; 0 c -s; 0 s c])."""
    e = [0, 0, 0]
    e[axis] = 1
    return axis_angle(e, t)


def norm3(v):
    return mp.sqrt(v[0] ** 2 + v[1] ** 2 + v[2] ** 2)


def rotation_from_axis_vector(v, angle_of_norm):
    """R for coordinates v = n f(phi): phi = angle_of_norm(|v|), n = v / |v|."""
    nv = norm3(v)
    if nv == 0:
        return eye3()
    return axis_angle([x / nv for x in v], angle_of_norm(nv))


def rotation(kind, theta):
    if kind.startswith("Euler") and kind != "EulerParameters":
        a = [AXES[c] for c in kind[5:8]]
        return elementary(a[0], theta[0]) * elementary(a[1], theta[1]) * elementary(a[2], theta[2])
    if kind == "EulerParameters":
        # Unit quaternion (e0, e) = (cos(phi/2), n sin(phi/2)); evaluated at p / |p|.
        norm = mp.sqrt(sum(x ** 2 for x in theta))
        p = [x / norm for x in theta]
        e = p[1:]
        ne = norm3(e)
        if ne == 0:
            return eye3()
        return axis_angle([x / ne for x in e], 2 * mp.atan2(ne, p[0]))
    if kind == "RodriguesParameters":  # g = n tan(phi/2)
        return rotation_from_axis_vector(theta, lambda r: 2 * mp.atan(r))
    if kind == "ModifiedRodriguesParameters":  # sigma = n tan(phi/4)
        return rotation_from_axis_vector(theta, lambda r: 4 * mp.atan(r))
    if kind == "RotationVector":  # v = phi n
        return rotation_from_axis_vector(theta, lambda r: r)
    raise ValueError(kind)


# --------------------------------------------------------------------------------------------
# Derivatives by mpmath.diff (entry by entry).
# --------------------------------------------------------------------------------------------


def matrix_diff(f, n=1):
    """d^n/dt^n f(t) at t = 0 for a 3 x 3 matrix function f, entry by entry with mpmath.diff."""
    out = mp.matrix(3, 3)
    for i in range(3):
        for j in range(3):
            out[i, j] = mp.diff(lambda t: f(t)[i, j], 0, n)
    return out


def matrix_mixed(f):
    """d^2/(ds dt) f(s, t) at (0, 0), entry by entry with mpmath.diff."""
    out = mp.matrix(3, 3)
    for i in range(3):
        for j in range(3):
            out[i, j] = mp.diff(lambda s, t: f(s, t)[i, j], (0, 0), (1, 1))
    return out


def along(theta, direction, t):
    return [theta[k] + t * direction[k] for k in range(len(theta))]


def unit(k, n):
    e = [0] * n
    e[k] = 1
    return e


def compute_state(kind, theta_d, td_d, omega_d, alpha_d):
    """All reference quantities of one state at the current mp precision."""
    theta = [mpf(x) for x in theta_d]
    td = [mpf(x) for x in td_d]
    omega = [mpf(x) for x in omega_d]
    alpha = [mpf(x) for x in alpha_d]
    n = len(theta)
    R = rotation(kind, theta)

    # G, column j = vee(R^T dR/dtheta_j)   (S(omega) = R^T Rdot, Eq. 1.5).
    G = mp.matrix(3, n)
    for j in range(n):
        dR = matrix_diff(lambda t: rotation(kind, along(theta, unit(j, n), t)))
        col = vee_antisymmetric(R.T * dR)
        for i in range(3):
            G[i, j] = col[i]

    # Gdot thetadot = d/dt vee(R^T Rdot) along theta + t thetadot   (Eq. 1.10).
    line = lambda t: rotation(kind, along(theta, td, t))
    Rdot = matrix_diff(line, 1)
    Rddot = matrix_diff(line, 2)
    gdot_td = vee_antisymmetric(Rdot.T * Rdot + R.T * Rddot)

    # Gdot (matrix): column j = d/dt vee(R^T dR/dtheta_j) = vee(Rdot^T dR_j + R^T d2R/dtheta_j dt).
    Gdot = mp.matrix(3, n)
    for j in range(n):
        dR = matrix_diff(lambda s: rotation(kind, along(theta, unit(j, n), s)))
        d2R = matrix_mixed(
            lambda s, t: rotation(kind, along(along(theta, unit(j, n), s), td, t)))
        col = vee_antisymmetric(Rdot.T * dR + R.T * d2R)
        for i in range(3):
            Gdot[i, j] = col[i]
    # Self-check: the matrix times thetadot is the product computed along the line.
    gdot_td_matrix = [sum(Gdot[i, j] * td[j] for j in range(n)) for i in range(3)]
    scale = max(abs(x) for x in Gdot) * max(abs(x) for x in td)
    for i in range(3):
        if abs(gdot_td_matrix[i] - gdot_td[i]) > mpf(10) ** (-CHECK_DIGITS) * scale:
            sys.exit(f"{kind}: Gdot thetadot from the matrix and from the line disagree")

    # Inverse map and thetaddot: G x = b, plus p . x = c for Euler parameters (the tangent
    # condition p . pdot = 0 and the second derivative of |p|^2 = 1, p . pddot = -|pdot|^2).
    def solve(b, c):
        if n == 3:
            return list(mp.lu_solve(G, mp.matrix(b)))
        A = mp.matrix(4, 4)
        rhs = mp.matrix(4, 1)
        for i in range(3):
            for j in range(4):
                A[i, j] = G[i, j]
            rhs[i] = b[i]
        for j in range(4):
            A[3, j] = theta[j]
        rhs[3] = c
        return list(mp.lu_solve(A, rhs))

    td_of_omega = solve(omega, 0)
    tdd = solve([alpha[i] - gdot_td[i] for i in range(3)], -sum(x ** 2 for x in td))

    return {
        "R": [R[i, j] for i in range(3) for j in range(3)],
        "G": [G[i, j] for i in range(3) for j in range(n)],
        "Gdot": [Gdot[i, j] for i in range(3) for j in range(n)],
        "Gdot_thetadot": gdot_td,
        "thetadot_of_omega": td_of_omega,
        "thetaddot": tdd,
    }


# --------------------------------------------------------------------------------------------
# The fixed states.
# --------------------------------------------------------------------------------------------

EULER_SEQUENCES = ["XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX", "XYX", "XZX", "YXY", "YZY", "ZXZ",
                   "ZYZ"]


def gaussian3(rng, scale=1.0):
    return [scale * rng.gauss(0.0, 1.0) for _ in range(3)]


def with_norm(rng, r):
    v = gaussian3(rng)
    nv = math.sqrt(sum(x * x for x in v))
    return [r * x / nv for x in v]


def states_for(kind, rng):
    """(theta, label) lists: generic states and a few special ones per parameterization."""
    out = []
    if kind == "EulerParameters":
        for _ in range(5):
            q = [rng.gauss(0.0, 1.0) for _ in range(4)]
            nq = math.sqrt(sum(x * x for x in q))
            out.append(([x / nq for x in q], "random unit quaternion"))
        # 179 degrees: e0 = cos(89.5 deg) small.
        n = with_norm(rng, 1.0)
        h = math.radians(179.0) / 2
        out.append(([math.cos(h)] + [math.sin(h) * x for x in n], "179 degrees"))
    elif kind.startswith("Euler"):
        tait_bryan = kind[5] != kind[7]
        for _ in range(4):
            t1, t3 = rng.uniform(-math.pi, math.pi), rng.uniform(-math.pi, math.pi)
            t2 = rng.uniform(-1.4, 1.4) if tait_bryan else rng.uniform(0.2, 2.9)
            out.append(([t1, t2, t3], "random"))
        if tait_bryan:
            out.append(([1.0e-3 * x for x in gaussian3(rng)], "small angles (1e-3)"))
            out.append(([0.4, 1.5, -2.0], "t2 = 1.5 (cond G ~ 14)"))
        else:
            out.append(([2.0e-3, 0.7, -1.0e-3], "small t1, t3"))
            out.append(([-0.3, 3.0, 2.5], "t2 = 3.0 (cond G ~ 7)"))
    else:
        big = {"RodriguesParameters": (30.0, "|g| = 30 (173.8 degrees)"),
               "ModifiedRodriguesParameters": (2.5, "shadow set, |s| = 2.5"),
               "RotationVector": (5.0, "|v| = 5 > pi")}[kind]
        lo, hi = {"RodriguesParameters": (0.1, 3.0), "ModifiedRodriguesParameters": (0.1, 1.0),
                  "RotationVector": (0.2, 3.0)}[kind]
        for _ in range(3):
            out.append((with_norm(rng, rng.uniform(lo, hi)), "random"))
        out.append((with_norm(rng, 1.0e-3), "small (|theta| = 1e-3)"))
        out.append((with_norm(rng, 1.0e-7), "tiny (|theta| = 1e-7)"))
        out.append((with_norm(rng, big[0]), big[1]))
    return out


def rate_for(kind, theta, rng):
    td = [rng.gauss(0.0, 1.0) for _ in theta]
    if kind == "EulerParameters":
        # Tangent to |p| = 1 (in double; exact tangency is not needed: see the module docstring).
        d = sum(a * b for a, b in zip(theta, td))
        td = [b - d * a for a, b in zip(theta, td)]
    return td


def parameterizations():
    return (["EulerParameters"] + ["Euler" + s for s in EULER_SEQUENCES] +
            ["RodriguesParameters", "ModifiedRodriguesParameters", "RotationVector"])


def make_states():
    rng = random.Random(20261121)
    states = []
    for kind in parameterizations():
        for theta, label in states_for(kind, rng):
            td = rate_for(kind, theta, rng)
            states.append({"kind": kind, "label": label, "theta": theta, "thetadot": td,
                           "omega": gaussian3(rng), "alpha": gaussian3(rng)})
    return states


# --------------------------------------------------------------------------------------------
# Output.
# --------------------------------------------------------------------------------------------


def long_double_literal(x):
    if x == 0:
        return "0.0L"
    return mpmath.nstr(x, DIGITS_WRITTEN, min_fixed=1, max_fixed=0, strip_zeros=False) + "L"


def hex_literal(x):
    return float(x).hex()


def padded(values, n, fmt):
    return ", ".join(fmt(v) for v in values) + "".join(", " + fmt(0) for _ in range(n - len(values)))


def write_header(path, states, results):
    lines = [
        "#pragma once",
        "// 50-digit reference values for the orientation property suite, GENERATED by",
        "// tests/orientation/reference/make_reference.py (mpmath): do not edit, re-run the script.",
        "//",
        "// R from the definitions (intrinsic Euler products, axis-angle), G from S(omega) = R^T Rdot",
        "// by mpmath numerical differentiation (Eq. 1.5), Gdot and Gdot thetadot (Eq. 1.10) from second",
        "// derivatives, the inverse map and thetaddot by solving with G at working precision. See the",
        "// script's docstring for the route and its self-checks. Matrices are row-major, 3 x size.",
        "",
        "#include <string_view>",
        "",
        "namespace tumble::test::reference {",
        "",
        "struct State {",
        "  std::string_view parameterization;  // P::name",
        "  std::string_view label;",
        "  int size;",
        "  double theta[4];  // inputs: exact doubles",
        "  double thetadot[4];",
        "  double omega[3];  // for the inverse map",
        "  double alpha[3];  // for thetaddot",
        "  long double R[9];",
        "  long double G[12];",
        "  long double Gdot[12];  // d/dt G(theta + t thetadot)",
        "  long double Gdot_thetadot[3];",
        "  long double thetadot_of_omega[4];",
        "  long double thetaddot[4];",
        "};",
        "",
        "// clang-format off",
        "inline constexpr State states[] = {",
    ]
    for s, r in zip(states, results):
        n = len(s["theta"])
        ld = lambda vals, m: padded(vals, m, long_double_literal)
        hx = lambda vals, m: padded(vals, m, hex_literal)
        lines += [
            f"    {{\"{s['kind']}\", \"{s['label']}\", {n},",
            f"     {{{hx(s['theta'], 4)}}},",
            f"     {{{hx(s['thetadot'], 4)}}},",
            f"     {{{hx(s['omega'], 3)}}},",
            f"     {{{hx(s['alpha'], 3)}}},",
            f"     {{{ld(r['R'], 9)}}},",
            f"     {{{ld(r['G'], 12)}}},",
            f"     {{{ld(r['Gdot'], 12)}}},",
            f"     {{{ld(r['Gdot_thetadot'], 3)}}},",
            f"     {{{ld(r['thetadot_of_omega'], 4)}}},",
            f"     {{{ld(r['thetaddot'], 4)}}}}},",
        ]
    lines += ["};", "// clang-format on", "", "}  // namespace tumble::test::reference", ""]
    with open(path, "w") as f:
        f.write("\n".join(lines))


def agree(a, b, td):
    """The first quantity where a and b differ by more than 1e-50 of its scale, or None. The
    scale of Gdot thetadot is |Gdot| |thetadot| (the product itself is O(eps) for Euler
    parameters, whose Gdot thetadot vanishes for unit p)."""
    for key in a:
        va, vb = a[key], b[key]
        scale = max(abs(x) for x in vb)
        if key == "Gdot_thetadot":
            scale = max(abs(x) for x in b["Gdot"]) * max(abs(mpf(x)) for x in td)
        scale = scale or mpf(1)
        for x, y in zip(va, vb):
            if abs(x - y) > mpf(10) ** (-CHECK_DIGITS) * scale:
                return key
    return None


def main():
    start = time.time()
    states = make_states()
    results = []
    for s in states:
        args = (s["kind"], s["theta"], s["thetadot"], s["omega"], s["alpha"])
        mp.dps = 60
        lo = compute_state(*args)
        mp.dps = 80
        hi = compute_state(*args)
        bad = agree(lo, hi, s["thetadot"])
        if bad:
            sys.exit(f"{s['kind']} ({s['label']}): {bad} at 60 and 80 digits disagree beyond 1e-50")
        results.append(hi)
    mp.dps = 80
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "reference_values.hpp")
    write_header(path, states, results)
    print(f"wrote {len(states)} states to {path} in {time.time() - start:.1f} s")


if __name__ == "__main__":
    main()
