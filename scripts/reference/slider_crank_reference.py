#!/usr/bin/python3
"""Independent reference solution: slider-crank with spring-mass (benchmarks.md sec. 1,
Arnold & Bruls 2007 sec. 5.1).

Run from the repository root:
    /usr/bin/python3 scripts/reference/slider_crank_reference.py
Writes tests/reference/slider_crank.csv with columns
    t,theta1,x3,x4,u4,pivot_fx,pivot_fy,omega1      (t = 0, 0.01, ..., 1 s)
pivot_fx, pivot_fy = force of the ground on the crank at O [N]; theta1 unwrapped [rad].

Model: l1=0.3, l2=0.6, m1=0.36, m2=0.15 (uniform slender bars, J=m l^2/12 about the
mid-length centre), point masses m3=0.1 (slider) and m4=0.7 on the x-axis, spring
k=1000 N/m acting along x, force k(x4-x3) on body 3 (rest length 0), torque T=1 N m
(counter-clockwise) on the crank, no gravity. Initially theta1=pi/2, at rest,
x3(0) = x4(0) = l1 cos(theta1) + sqrt(l2^2 - (l1 sin theta1)^2) = sqrt(0.27) = 0.5196...

Two independent formulations, both integrated with scipy DOP853 at rtol=atol=1e-13, restarted
at every output time (no dense-output interpolation):
  A (written to the CSV). Minimal coordinates (theta1, x4), Lagrange's equations; the rod angle
    theta2 = asin(-l1 sin(theta1)/l2) and x3 follow from the loop closure. The reaction at O
    is recovered by Newton-Euler on the slider, the rod and the crank.
  B (cross-check). The paper's 10 absolute coordinates q=[x1,y1,th1,x2,y2,th2,x3,x4,x5,y5],
    8 constraints, index-1 form: [[M, G^T],[G, 0]] [q''; lam] = [f; gamma] with
    M q'' + G^T lam = f; the ground force on the crank at O is (-lam1, -lam2).
Achieved accuracy (max |diff| over the 101 rows, as printed by this script):
  A at 1e-13 vs A at 1e-12:  theta1 1.9e-11 rad, x3/x4 6e-12 m, pivot force 2.9e-9 N,
                             omega1 6.8e-10 rad/s   (an upper bound for the CSV's error)
  A vs B (both 1e-13):       theta1 9.6e-13 rad, x4 1.8e-13 m, pivot force 1.8e-10 N
  A energy balance (kinetic + spring - T*(theta1 - pi/2)): 3e-13 J; B constraint drift 1e-14.
So the CSV is accurate to ~1e-11 rad / 1e-11 m / 3e-9 N or better (probably ~1e-12 / 2e-10 N).
"""
import os
import numpy as np
from scipy.integrate import solve_ivp

l1, l2, m1, m2, m3, m4 = 0.3, 0.6, 0.36, 0.15, 0.1, 0.7
J1, J2 = m1 * l1**2 / 12, m2 * l2**2 / 12
k, T = 1000.0, 1.0
th0 = np.pi / 2


# ---------------- A: minimal coordinates (theta1, x4) ----------------
def kin(th):
    """Loop-closure kinematics. Returns for c1, theta2, c2, x3 their value, d/dtheta1 and
    d2/dtheta1^2 (c1, c2 are 2-vectors), plus theta2."""
    s, c = np.sin(th), np.cos(th)
    sp = -l1 * s / l2
    cp = np.sqrt(1 - sp**2)
    p1 = -l1 * c / (l2 * cp)                                   # dtheta2/dtheta1
    p2 = l1 * s / (l2 * cp) - l1 * c * sp * p1 / (l2 * cp**2)  # d2theta2/dtheta1^2
    e, en = np.array([cp, sp]), np.array([-sp, cp])
    u, un = np.array([c, s]), np.array([-s, c])
    c1, c1t, c1tt = 0.5 * l1 * u, 0.5 * l1 * un, -0.5 * l1 * u
    c2 = l1 * u + 0.5 * l2 * e
    c2t = l1 * un + 0.5 * l2 * en * p1
    c2tt = -l1 * u + 0.5 * l2 * (-e * p1**2 + en * p2)
    x3 = l1 * c + l2 * cp
    x3t = -l1 * s - l2 * sp * p1
    x3tt = -l1 * c - l2 * (cp * p1**2 + sp * p2)
    return dict(th2=np.arctan2(sp, cp), e=e, p1=p1, p2=p2, c1=c1, c1t=c1t, c1tt=c1tt,
                c2=c2, c2t=c2t, c2tt=c2tt, x3=x3, x3t=x3t, x3tt=x3tt)


def accel_min(y):
    th, x4, w, v4 = y
    K = kin(th)
    mass = m1 * K['c1t'] @ K['c1t'] + J1 + m2 * K['c2t'] @ K['c2t'] + J2 * K['p1']**2 \
        + m3 * K['x3t']**2
    h = m1 * K['c1t'] @ K['c1tt'] + m2 * K['c2t'] @ K['c2tt'] + J2 * K['p1'] * K['p2'] \
        + m3 * K['x3t'] * K['x3tt']
    fs = k * (x4 - K['x3'])                 # spring force on body 3 (+x)
    thdd = (T + fs * K['x3t'] - h * w**2) / mass
    return thdd, -fs / m4, K


def rhs_min(t, y):
    thdd, x4dd, _ = accel_min(y)
    return [y[2], y[3], thdd, x4dd]


def pivot_force_min(y):
    """Newton-Euler on slider (x), rod (x, y, moment about its centre) and crank."""
    th, x4, w, v4 = y
    thdd, _, K = accel_min(y)
    a1 = K['c1t'] * thdd + K['c1tt'] * w**2
    a2 = K['c2t'] * thdd + K['c2tt'] * w**2
    a3 = K['x3t'] * thdd + K['x3tt'] * w**2
    th2dd = K['p1'] * thdd + K['p2'] * w**2
    e = K['e']
    cross = lambda a, b: a[0] * b[1] - a[1] * b[0]
    FBx = m3 * a3 - k * (x4 - K['x3'])      # force of the rod on the slider, x
    # rod: m2 a2 = H - FB, J2 th2dd = (-(l2/2) e) x H + ((l2/2) e) x (-FB), H = m2 a2 + FB
    FBy = ((-J2 * th2dd - 0.5 * l2 * cross(e, m2 * a2)) / l2 + e[1] * FBx) / e[0]
    H = m2 * a2 + np.array([FBx, FBy])      # force of the crank on the rod at the hinge
    return m1 * a1 + H                      # crank: m1 a1 = F_O - H


x0 = kin(th0)['x3']   # = l1 cos(th0) + sqrt(l2^2 - (l1 sin th0)^2); x4(0) = x0 too


# ---------------- B: 10 absolute coordinates, index-1 DAE ----------------
# constraint i = L[i] @ q + sum of coef*cos/sin(q[angle]) terms
L = np.zeros((8, 10))
for i, row in enumerate([{0: 1}, {1: 1}, {0: 1, 8: -1}, {1: 1, 9: -1},
                         {3: 1, 8: -1}, {4: 1, 9: -1}, {3: 1, 6: -1}, {4: 1}]):
    for j, v in row.items():
        L[i, j] = v
TRIG = [(0, -l1 / 2, 'c', 2), (1, -l1 / 2, 's', 2), (2, l1 / 2, 'c', 2), (3, l1 / 2, 's', 2),
        (4, -l2 / 2, 'c', 5), (5, -l2 / 2, 's', 5), (6, l2 / 2, 'c', 5), (7, l2 / 2, 's', 5)]
Mabs = np.diag([m1, m1, J1, m2, m2, J2, m3, m4, 0, 0])


def constraints(q, v):
    g, G, gam = L @ q, L.copy(), np.zeros(8)
    for i, a, kind, j in TRIG:
        tr, dtr = (np.cos(q[j]), -np.sin(q[j])) if kind == 'c' else (np.sin(q[j]), np.cos(q[j]))
        g[i] += a * tr
        G[i, j] += a * dtr
        gam[i] += a * tr * v[j]**2          # G q'' = gam  (from d2g/dt2 = 0)
    return g, G, gam


def solve_abs(y):
    q, v = y[:10], y[10:]
    _, G, gam = constraints(q, v)
    f = np.zeros(10)
    f[2] = T
    f[6], f[7] = k * (q[7] - q[6]), -k * (q[7] - q[6])
    A = np.block([[Mabs, G.T], [G, np.zeros((8, 8))]])
    sol = np.linalg.solve(A, np.concatenate([f, gam]))
    return sol[:10], sol[10:]


def rhs_abs(t, y):
    return np.concatenate([y[10:], solve_abs(y)[0]])


def y0_abs():
    K = kin(th0)
    P = l1 * np.array([np.cos(th0), np.sin(th0)])
    q = np.array([*K['c1'], th0, *K['c2'], K['th2'], x0, x0, *P])
    return np.concatenate([q, np.zeros(10)])


# ---------------- driver ----------------
def integrate(rhs, y0, times, tol):
    ys, y = [np.array(y0, float)], np.array(y0, float)
    for ta, tb in zip(times[:-1], times[1:]):
        r = solve_ivp(rhs, (ta, tb), y, method='DOP853', rtol=tol, atol=tol)
        assert r.success, r.message
        y = r.y[:, -1]
        ys.append(y)
    return np.array(ys)


def energy_residual(y):
    """kinetic + spring energy - work of the torque (zero for the exact solution)"""
    th, x4, w, v4 = y
    K = kin(th)
    m = m1 * K['c1t'] @ K['c1t'] + J1 + m2 * K['c2t'] @ K['c2t'] + J2 * K['p1']**2 \
        + m3 * K['x3t']**2
    return 0.5 * m * w**2 + 0.5 * m4 * v4**2 + 0.5 * k * (x4 - K['x3'])**2 - T * (th - th0)


def table_min(tol, times):
    Y = integrate(rhs_min, [th0, x0, 0.0, 0.0], times, tol)
    F = np.array([pivot_force_min(y) for y in Y])
    x3 = np.array([kin(y[0])['x3'] for y in Y])
    energy = max(abs(energy_residual(y)) for y in Y)
    return np.column_stack([times, Y[:, 0], x3, Y[:, 1], Y[:, 1] - x0, F, Y[:, 2]]), energy


def table_abs(tol, times):
    Y = integrate(rhs_abs, y0_abs(), times, tol)
    lam = np.array([solve_abs(y)[1] for y in Y])
    drift = max(np.abs(constraints(y[:10], y[10:])[0]).max() for y in Y)
    tab = np.column_stack([times, Y[:, 2], Y[:, 6], Y[:, 7], Y[:, 7] - x0,
                           -lam[:, 0], -lam[:, 1], Y[:, 12]])
    return tab, drift


def maxdiff(a, b):
    d = np.abs(a - b).max(axis=0)
    return dict(theta1=d[1], x3=d[2], x4=d[3], pivot_f=max(d[5], d[6]), omega1=d[7])


if __name__ == '__main__':
    times = np.round(np.arange(101) * 0.01, 12)
    ref, energy = table_min(1e-13, times)   # the CSV
    coarse, _ = table_min(1e-12, times)
    absref, drift = table_abs(1e-13, times)
    print('A: tol 1e-13 vs 1e-12, max |diff|:', maxdiff(ref, coarse))
    print('A vs B (both 1e-13), max |diff|:  ', maxdiff(ref, absref))
    print('A: max |energy balance residual| over the run: %.1e J' % energy)
    print('B: max |constraint residual| over the run: %.1e' % drift)
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'tests',
                       'reference', 'slider_crank.csv')
    with open(os.path.normpath(out), 'w') as fh:
        fh.write('t,theta1,x3,x4,u4,pivot_fx,pivot_fy,omega1\n')
        for row in ref:
            fh.write(','.join([repr(float(row[0]))] + ['%.17g' % v for v in row[1:]]) + '\n')
    r = ref[-1]
    print('t=1: theta1=%.15g x3=%.15g x4=%.15g u4=%.15g pivot_fx=%.15g pivot_fy=%.15g '
          'omega1=%.15g' % tuple(r[1:]))
    print('wrote', os.path.normpath(out))
