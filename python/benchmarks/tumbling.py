"""The tumbling body, the project's standard problem, for the Python benchmarks and examples.

Problem: principal inertia I = diag(1, 2, 3) kg m^2, m = 1 kg, held at its centroid, no loads,
omega0 = (0.1, 2, 0.05) rad/s in the body frame, R(0) = identity, 50 s, 101 output times
(t = 0, 0.5, ..., 50 s). It spins near its intermediate axis and flips (the Dzhanibekov effect).
The error of a run: the largest attitude error over the outputs, the angle (rad) of R_exact^T R.

What is here, NumPy only (scipy and Pinocchio are imported by the callers, when installed):
- TorqueFreeBody: the exact solution, omega(t) in Jacobi elliptic functions and R(t) from the
  constant angular momentum and the precession angle psi(t) by quadrature; the same solution as
  tests/support/torque_free.hpp (whose comment derives it; Landau & Lifshitz, Mechanics, Sec. 37),
  written again in NumPy: sn, cn, dn by the AGM amplitude recursion (Abramowitz & Stegun 16.4.3),
  the phase by Carlson's R_F (DLMF 19.25.5, 19.36.1), psi by composite Gauss-Legendre quadrature.
- floor_rhs: the hand-written right-hand side of the same body for scipy's solve_ivp, state
  [p (4, scalar first); omega (3)]: Euler's equations I omega' = -omega x I omega and the
  quaternion kinematics p' = 1/2 p (x) (0, omega).
- pinocchio_rhs: the same body as a Pinocchio free flyer, its forward dynamics by pin.aba.
- max_attitude_error: the error measure.
Conventions (docs/conventions.md): R maps body to inertial components, omega in the body frame,
quaternions scalar first (Pinocchio's configuration stores them x, y, z, w: converted where read).
"""

import math

import numpy as np

INERTIA = (1.0, 2.0, 3.0)  # kg m^2, principal
MASS = 1.0  # kg
OMEGA0 = (0.1, 2.0, 0.05)  # rad/s, body frame
T_END = 50.0  # s
TIMES = np.linspace(0.0, T_END, 101)  # s, the output times


# ---- the exact solution ---------------------------------------------------------------------

def _agm(m, m1):
    """The AGM sequences a, b, c of A&S 16.4.2 from (1, sqrt(m1), sqrt(m)), to c_n <= eps a_n."""
    a, b, c = [1.0], [math.sqrt(m1)], [math.sqrt(m)]
    while c[-1] > np.finfo(float).eps * a[-1] and len(a) < 64:
        a.append(0.5 * (a[-1] + b[-1]))
        b.append(math.sqrt(a[-2] * b[-1]))
        c.append(c[-1] * c[-1] / (4.0 * a[-1]))  # (a_n - b_n) / 2 without the cancellation
    return a, b, c


def jacobi_sn_cn_dn(u, m, m1):
    """sn, cn, dn (u | m), m1 = 1 - m given apart (its accuracy near m = 1): the amplitude
    recursion of A&S 16.4.3 on u reduced modulo the period 4K; dn = sqrt(m1 + m cn^2) (A&S 16.9.1,
    no 0/0 where cn = 0)."""
    a, _, c = _agm(m, m1)
    n = len(a) - 1
    quarter = math.pi / (2.0 * a[n])  # K(m)
    phi = np.mod(np.asarray(u, dtype=float), 4.0 * quarter) * (2.0**n * a[n])
    for k in range(n, 0, -1):
        phi = 0.5 * (phi + np.arcsin(c[k] / a[k] * np.sin(phi)))
    sn, cn = np.sin(phi), np.cos(phi)
    return sn, cn, np.sqrt(m1 + m * cn * cn), quarter


def _carlson_rf(x, y, z):
    """Carlson's R_F(x, y, z) by duplication (B. C. Carlson, Numer. Algorithms 10 (1995) 13-26)."""
    while True:
        mean = (x + y + z) / 3.0
        dx, dy = 1.0 - x / mean, 1.0 - y / mean
        dz = -(dx + dy)
        if max(abs(dx), abs(dy), abs(dz)) < 1e-3:  # the series below then errs by ~1e-18
            e2, e3 = dx * dy - dz * dz, dx * dy * dz
            return (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0) \
                / math.sqrt(mean)
        lam = math.sqrt(x * y) + math.sqrt(y * z) + math.sqrt(z * x)
        x, y, z = (x + lam) / 4.0, (y + lam) / 4.0, (z + lam) / 4.0


def _elliptic_f(phi, m, m1, quarter):
    """F(phi | m) for phi in [-pi, pi]: sin(phi) R_F(cos^2, cos^2 + m1 sin^2, 1) on [-pi/2, pi/2],
    and F(phi) = 2K - F(pi - phi) beyond (DLMF 19.25.5, 19.2.10)."""
    if abs(phi) > math.pi / 2:
        sign = math.copysign(1.0, phi)
        return sign * 2.0 * quarter - _elliptic_f(sign * math.pi - phi, m, m1, quarter)
    s, c = math.sin(phi), math.cos(phi)
    return s * _carlson_rf(c * c, c * c + m1 * s * s, 1.0)


def _rot_x(angle):
    c, s = np.cos(angle), np.sin(angle)
    out = np.zeros(np.shape(angle) + (3, 3))
    out[..., 0, 0] = 1.0
    out[..., 1, 1], out[..., 1, 2], out[..., 2, 1], out[..., 2, 2] = c, -s, s, c
    return out


def _rot_z(angle):
    c, s = np.cos(angle), np.sin(angle)
    out = np.zeros(np.shape(angle) + (3, 3))
    out[..., 2, 2] = 1.0
    out[..., 0, 0], out[..., 0, 1], out[..., 1, 0], out[..., 1, 1] = c, -s, s, c
    return out


class TorqueFreeBody:
    """The exact motion of a torque-free body with distinct principal moments, from R(0) = I.

    omega: w_a = A_a cn(u), w_b = s_b A_b sn(u), w_c = s_c A_c dn(u), u = u0 + lambda t, with b the
    intermediate axis, c the axis the polhode encircles (tests/support/torque_free.hpp has the
    amplitudes, lambda, m and the signs). Attitude: R(t) = R_h(0)^T R_h(t), R_h = R_z(psi)
    R_x(theta) R_z(phi) P (3-1-3 angles of the constant angular momentum h in the permuted body
    frame P, (i, j, k) cyclic), psi' = H (I_i w_i^2 + I_j w_j^2) / (I_i^2 w_i^2 + I_j^2 w_j^2).
    """

    def __init__(self, inertia=INERTIA, omega0=OMEGA0, panel=0.05):
        inertia, w = np.asarray(inertia, dtype=float), np.asarray(omega0, dtype=float)
        if len(set(inertia.tolist())) != 3 or np.count_nonzero(w) < 2:
            raise ValueError("TorqueFreeBody: distinct moments and a non-steady spin only")
        self.inertia, self.panel = inertia, panel
        ii = inertia
        two_t, h2 = float(ii @ (w * w)), float((ii * ii) @ (w * w))
        b = int(np.argsort(ii)[1])
        c = int(np.argmax(ii)) if h2 > two_t * ii[b] else int(np.argmin(ii))
        a = 3 - b - c

        def d(x, sign):  # sum_i I_i (I_i - I_x) w_i^2 (times sign): no cancellation
            return sign * float(ii @ ((ii - ii[x]) * w * w))

        d_a, d_b, d_c = d(a, 1.0), d(b, 1.0), d(c, -1.0)
        amp = np.empty(3)
        amp[a] = math.sqrt(d_c / (ii[a] * (ii[c] - ii[a])))
        amp[b] = math.sqrt(d_c / (ii[b] * (ii[c] - ii[b])))
        amp[c] = math.sqrt(d_a / (ii[c] * (ii[c] - ii[a])))
        self.rate = math.sqrt((ii[c] - ii[b]) * d_a / (ii[a] * ii[b] * ii[c]))  # lambda
        self.m = (ii[b] - ii[a]) * d_c / ((ii[c] - ii[b]) * d_a)
        self.m1 = (ii[c] - ii[a]) * d_b / ((ii[c] - ii[b]) * d_a)
        cyclic = 1.0 if (a, b, c) in ((0, 1, 2), (1, 2, 0), (2, 0, 1)) else -1.0
        sign = np.ones(3)
        sign[c] = math.copysign(1.0, w[c])
        sign[b] = cyclic * math.copysign(1.0, ii[c] - ii[a]) * sign[c]
        self.axes, self.amplitude = (a, b, c), sign * amp
        _, _, _, quarter = jacobi_sn_cn_dn(0.0, self.m, self.m1)
        phase = math.atan2(w[b] / self.amplitude[b], w[a] / self.amplitude[a])
        self.u0 = _elliptic_f(phase, self.m, self.m1, quarter)
        # k: of a and c, the axis that keeps H^2 - h_k^2 (the denominator of psi') larger.
        k = c if (ii[a] * amp[a]) ** 2 >= (ii[c] * amp[c]) ** 2 else a
        self.perm = ((k + 1) % 3, (k + 2) % 3, k)  # (i, j, k), cyclic: P is a rotation
        self.h = math.sqrt(h2)

    def omega(self, t):
        """omega(t) (..., 3), rad/s, body frame."""
        sn, cn, dn, _ = jacobi_sn_cn_dn(self.u0 + self.rate * np.asarray(t, dtype=float),
                                        self.m, self.m1)
        a, b, c = self.axes
        out = np.empty(np.shape(t) + (3,))
        out[..., a], out[..., b], out[..., c] = (self.amplitude[a] * cn, self.amplitude[b] * sn,
                                                 self.amplitude[c] * dn)
        return out

    def _psidot(self, t):
        w2 = self.omega(t) ** 2
        i, j, _ = self.perm
        ii = self.inertia
        return self.h * (ii[i] * w2[..., i] + ii[j] * w2[..., j]) \
            / (ii[i] ** 2 * w2[..., i] + ii[j] ** 2 * w2[..., j])

    def _psi(self, times):
        """psi at the sorted times >= 0, from psi(0) = 0: 10-point Gauss-Legendre on panels of at
        most self.panel seconds between successive times."""
        x, wts = np.polynomial.legendre.leggauss(10)
        out, total, prev = np.empty(len(times)), 0.0, 0.0
        for n, t in enumerate(times):
            panels = max(1, math.ceil((t - prev) / self.panel))
            edges = np.linspace(prev, t, panels + 1)
            half = 0.5 * np.diff(edges)[:, None]
            nodes = 0.5 * (edges[:-1, None] + edges[1:, None]) + half * x
            total += float(np.sum(half * wts * self._psidot(nodes)))
            out[n], prev = total, t
        return out

    def _rotation_h(self, t, psi):
        """R_h(t) (..., 3, 3): body -> the frame whose z axis is h."""
        hb = self.inertia * self.omega(t)
        i, j, k = self.perm
        hij = np.hypot(hb[..., i], hb[..., j])
        theta = np.arctan2(hij, hb[..., k])
        phi = np.arctan2(hb[..., i], hb[..., j])
        perm = np.zeros((3, 3))
        perm[0, i] = perm[1, j] = perm[2, k] = 1.0
        return _rot_z(psi) @ _rot_x(theta) @ _rot_z(phi) @ perm

    def rotation(self, times):
        """R(t) (T, 3, 3), body -> inertial, at the times t >= 0 (any order)."""
        times = np.asarray(times, dtype=float)
        order = np.argsort(times)
        psi = np.empty(len(times))
        psi[order] = self._psi(times[order])
        start = self._rotation_h(np.array(0.0), np.array(0.0))
        return start.T @ self._rotation_h(times, psi)


# ---- attitudes and their errors ---------------------------------------------------------------

def quaternion_to_matrix(q):
    """R (..., 3, 3) of quaternions q (..., 4) = (w, x, y, z), normalized first."""
    q = np.asarray(q, dtype=float)
    w, x, y, z = np.moveaxis(q / np.linalg.norm(q, axis=-1, keepdims=True), -1, 0)
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1),
    ], -2)


def max_attitude_error(exact, rotations):
    """The largest angle (rad) of exact^T R over the outputs: ||exact - R||_F = 2 sqrt(2)
    sin(angle / 2), which keeps its accuracy at small angles (arccos of the trace does not)."""
    diff = np.linalg.norm(np.asarray(exact) - np.asarray(rotations), axis=(-2, -1))
    return float(np.max(2.0 * np.arcsin(np.minimum(1.0, diff / (2.0 * math.sqrt(2.0))))))


# ---- right-hand sides written by hand -----------------------------------------------------------

def floor_state():
    """[p (w, x, y, z); omega] at t = 0."""
    return np.array([1.0, 0.0, 0.0, 0.0, *OMEGA0])


def floor_rhs(inertia=INERTIA):
    """f(t, y) for y = [p0, p1, p2, p3, w1, w2, w3]: p' = 1/2 p (x) (0, omega) (scalar first,
    omega in the body frame), I omega' = -omega x I omega. Plain floats: for 7 states, cheaper
    than NumPy's element-wise operations (floor_rhs_numpy; python/benchmarks/bench.py times both);
    a list back, which solve_ivp turns into an array (it keeps what f returns: no shared buffer)."""
    i1, i2, i3 = inertia
    k1, k2, k3 = (i2 - i3) / i1, (i3 - i1) / i2, (i1 - i2) / i3

    def rhs(t, y):
        p0, p1, p2, p3, w1, w2, w3 = y.tolist()
        return [-0.5 * (p1 * w1 + p2 * w2 + p3 * w3), 0.5 * (p0 * w1 + p2 * w3 - p3 * w2),
                0.5 * (p0 * w2 + p3 * w1 - p1 * w3), 0.5 * (p0 * w3 + p1 * w2 - p2 * w1),
                k1 * w2 * w3, k2 * w3 * w1, k3 * w1 * w2]

    return rhs


def floor_rhs_numpy(inertia=INERTIA):
    """The same as floor_rhs with NumPy's array operations (kept to show which is faster): p' as
    sums of products picked by index arrays, omega' element-wise."""
    inertia = np.asarray(inertia, dtype=float)
    k = (np.roll(inertia, -1) - np.roll(inertia, -2)) / inertia
    # p'_i = 1/2 sum_m sign[i, m] omega[a[i, m]] p[j[i, m]], from p' = 1/2 p (x) (0, omega)
    a = np.array([[0, 1, 2], [0, 2, 1], [1, 0, 2], [2, 1, 0]])
    j = np.array([[1, 2, 3], [0, 2, 3], [0, 3, 1], [0, 1, 2]])
    sign = 0.5 * np.array([[-1.0, -1.0, -1.0], [1.0, 1.0, -1.0], [1.0, 1.0, -1.0],
                           [1.0, 1.0, -1.0]])
    first, second = np.array([1, 2, 0]), np.array([2, 0, 1])

    def rhs(t, y):
        p, w = y[:4], y[4:]
        return np.concatenate(((sign * w[a] * p[j]).sum(axis=1), k * w[first] * w[second]))

    return rhs


def floor_rotations(y):
    """R (T, 3, 3) from floor states y (T, 7) or (7, T) as solve_ivp returns them."""
    y = np.asarray(y)
    return quaternion_to_matrix((y if y.shape[-1] == 7 else y.T)[:, :4])


# ---- Pinocchio ----------------------------------------------------------------------------------

def pinocchio_model(pin, inertia=INERTIA, mass=MASS):
    """One body on a free-flyer joint, its centroid at the joint's origin, no gravity."""
    model = pin.Model()
    joint = model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), "body")
    model.appendBodyToJoint(joint, pin.Inertia(mass, np.zeros(3), np.diag(inertia)),
                            pin.SE3.Identity())
    model.gravity.setZero()
    return model


def pinocchio_state():
    """[configuration (x, y, z, qx, qy, qz, qw); velocity (v local, omega body)] at t = 0."""
    return np.array([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, *OMEGA0])


def pinocchio_rhs(pin, model):
    """f(t, y) for y = [configuration (7); velocity (6)]: the accelerations by pin.aba (no
    torques), the configuration's rates written here (Pinocchio has no q' for its quaternion in
    Python): x' = R v, quaternion' = 1/2 q (x) (0, omega). R is needed for x' only; the body is at
    its centroid with v = 0, but the rate is computed as a free body's would be."""
    data = model.createData()
    tau = np.zeros(6)
    aba = pin.aba

    def rhs(t, y):
        acc = aba(model, data, y[:7], y[7:], tau)
        _, _, _, qx, qy, qz, qw, vx, vy, vz, w1, w2, w3 = y.tolist()
        n = qw * qw + qx * qx + qy * qy + qz * qz
        s = 2.0 / n  # R of a non-unit quaternion, normalized
        r = ((1 - s * (qy * qy + qz * qz), s * (qx * qy - qw * qz), s * (qx * qz + qw * qy)),
             (s * (qx * qy + qw * qz), 1 - s * (qx * qx + qz * qz), s * (qy * qz - qw * qx)),
             (s * (qx * qz - qw * qy), s * (qy * qz + qw * qx), 1 - s * (qx * qx + qy * qy)))
        return [r[0][0] * vx + r[0][1] * vy + r[0][2] * vz,
                r[1][0] * vx + r[1][1] * vy + r[1][2] * vz,
                r[2][0] * vx + r[2][1] * vy + r[2][2] * vz,
                0.5 * (qw * w1 + qy * w3 - qz * w2), 0.5 * (qw * w2 + qz * w1 - qx * w3),
                0.5 * (qw * w3 + qx * w2 - qy * w1), -0.5 * (qx * w1 + qy * w2 + qz * w3),
                *acc.tolist()]

    return rhs


def pinocchio_rotations(y):
    """R (T, 3, 3) from Pinocchio states y (13, T) as solve_ivp returns them."""
    q = np.asarray(y)[3:7].T  # (T, 4): x, y, z, w
    return quaternion_to_matrix(q[:, [3, 0, 1, 2]])
