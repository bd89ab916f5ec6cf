#!/usr/bin/python3
"""Cross-check of andrews_reference.py with an independently built model: Andrews' mechanism
in the 21 absolute coordinates of andrews.md sec. 1.6 (x, y of the centre of mass and the
angle of each body; 10 revolute joints = 20 constraints), assembled from the body table of
andrews.md sec. 1.2 alone (no use of the test set's M, f, g).

Run from the repository root:
    /usr/bin/python3 scripts/reference/andrews_absolute_check.py
Index-1 form [[M, C^T], [C, 0]] [q''; mu] = [f; gamma], DOP853, rtol = atol = 1e-13. Each joint
constraint is  p(body a) - p(body b) = 0  (or - ground point), so mu of the joint E:K2-Kj is the
force that K2 exerts on Kj at E, i.e. the test set's (lambda1..6). Prints, at t = 0.03, the seven
relative angles and the E forces next to tests/reference/andrews.csv and the published values;
also checks the absolute initial data of andrews.md sec. 1.4. Writes nothing.
"""
import os
import sys
import numpy as np
from scipy.integrate import solve_ivp
sys.dont_write_bytecode = True              # no __pycache__ in the source tree
import andrews_reference as R               # noqa: E402  (parameters, Q0, test-set values)
from andrews_reference import (  # noqa: E402
    rr, ra, d, da, ss, sa, sb, sc, sd, e, ea, zt, ta, tb, zf, fa, u, ua, ub,
    xa, ya, xb, yb, xc, yc, mom, c0, l0)

m = np.array([R.m1, R.m2, R.m3, R.m4, R.m5, R.m6, R.m7])
I = np.array([R.I1, R.I2, R.I3, R.I4, R.I5, R.I6, R.I7])
CM = [(ra, 0), (-da, 0), (sb, -sa), (0, -(e - ea)), (ta, tb), (zf - fa, 0), (ub, -ua)]
O, A, B = (0, 0), (xa, ya), (xb, yb)
# joints: (body a, local point on a, body b or None for ground, local point on b or world point)
JOINTS = [(0, (0, 0), None, O), (0, (rr, 0), 1, (0, 0)), (2, (0, 0), None, B),
          (4, (0, 0), None, A), (6, (0, 0), None, A), (3, (0, 0), 4, (zt, 0)),
          (5, (0, 0), 6, (0, -u)),
          (1, (-d, 0), 2, (0, -ss)), (1, (-d, 0), 3, (0, -e)), (1, (-d, 0), 5, (zf, 0))]
E_JOINTS = [7, 8, 9]                         # E: K2-K3, K2-K4, K2-K6
D_LOCAL = (sd, -sc)


def rot(th):
    return np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])


def arm(th, k, loc):
    """R(theta_k) (loc - cm_k): from the centre of mass of body k to a body point."""
    return rot(th) @ (np.array(loc, float) - np.array(CM[k], float))


def constraints(q, v):
    C, gam, g = np.zeros((20, 21)), np.zeros(20), np.zeros(20)
    for j, (a, la, b, lb) in enumerate(JOINTS):
        rows = slice(2 * j, 2 * j + 2)
        for body, loc, sgn in [(a, la, 1.0)] + ([(b, lb, -1.0)] if b is not None else []):
            th = q[3 * body + 2]
            r = arm(th, body, loc)
            C[rows, 3 * body:3 * body + 2] += sgn * np.eye(2)
            C[rows, 3 * body + 2] += sgn * np.array([-r[1], r[0]])
            gam[rows] += sgn * r * v[3 * body + 2]**2     # from d2/dt2 (R r) = R' r th'' - R r th'^2
            g[rows] += sgn * (q[3 * body:3 * body + 2] + r)
        if b is None:
            g[rows] -= np.array(lb, float)
    return g, C, gam


def forces(q):
    f = np.zeros(21)
    f[2] = mom
    r = arm(q[8], 2, D_LOCAL)
    D = q[6:8] + r
    L = np.linalg.norm(D - (xc, yc))
    F = -c0 * (L - l0) / L * (D - (xc, yc))
    f[6:8] += F
    f[8] += r[0] * F[1] - r[1] * F[0]
    return f


Mabs = np.diag(np.repeat(m, 3) * np.tile([1, 1, 0], 7) + np.repeat(I, 3) * np.tile([0, 0, 1], 7))


def accel(y):
    q, v = y[:21], y[21:]
    _, C, gam = constraints(q, v)
    K = np.block([[Mabs, C.T], [C, np.zeros((20, 20))]])
    s = np.linalg.solve(K, np.concatenate([forces(q), gam]))
    return s[:21], s[21:]


def initial_state(qrel):
    be, Th, ga, Ph, de, Om, ep = qrel
    th = [be, be + Th, ga, Ph + de, de, Om + ep, ep]
    P = rot(th[0]) @ (rr, 0)
    F = np.array(A) + rot(th[4]) @ (zt, 0)
    G = np.array(A) + rot(th[6]) @ (0, -u)
    origins = [O, P, B, F, A, G, A]
    q = np.zeros(21)
    for k in range(7):
        q[3 * k:3 * k + 2] = np.array(origins[k], float) + rot(th[k]) @ CM[k]
        q[3 * k + 2] = th[k]
    return np.concatenate([q, np.zeros(21)])


def relative(q):
    th = q[2::3]
    return np.array([th[0], th[1] - th[0], th[2], th[3] - th[4], th[4], th[5] - th[6], th[6]])


if __name__ == '__main__':
    y0 = initial_state(R.Q0)
    g0 = constraints(y0[:21], y0[21:])[0]
    print('|g(q0)| = %.1e m' % np.abs(g0).max())
    print('cm1..cm7(0) =', y0[:21].reshape(7, 3)[:, :2].tolist())
    qdd, mu = accel(y0)
    print('E forces at t=0:', mu[14:20], ' (andrews.md 1.4 lambda(0):', R.LAM0, ')')
    r = solve_ivp(lambda t, y: np.concatenate([y[21:], accel(y)[0]]), (0, 0.03), y0,
                  method='DOP853', rtol=1e-13, atol=1e-13)
    yT = r.y[:, -1]
    qrel, lam = relative(yT[:21]), accel(yT)[1][14:20]
    csv = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'tests',
                       'reference', 'andrews.csv')
    last = np.loadtxt(csv, delimiter=',', skiprows=1)[-1]
    print('constraint residual at t=0.03: %.1e m' % np.abs(constraints(yT[:21], yT[21:])[0]).max())
    print('%-9s %24s %24s %24s' % ('t=0.03', 'absolute (21 coords)', 'andrews.csv', 'test set'))
    for n, a, b, c in zip(R.NAMES + ['lambda%d' % i for i in range(1, 7)],
                          np.concatenate([qrel, lam]), last[1:],
                          np.concatenate([R.TESTSET_Q, R.TESTSET_LAM])):
        print('%-9s %24.16e %24.16e %24.16e' % (n, a, b, c))
    print('max |absolute - andrews.csv|: angles %.1e rad, lambda %.1e N' % (
        np.abs(qrel - last[1:8]).max(), np.abs(lam - last[8:]).max()))
