#!/usr/bin/python3
"""Independent reference solution: quick-return (slotted-lever) mechanism with gravity, a
crank torque and a spring-damper on the lever tip.

Run from the repository root:
    /usr/bin/python3 scripts/reference/quick_return_reference.py
Writes tests/reference/quick_return.csv with columns
    t,phi,psi,slot_fx,slot_fy,O_fx,O_fy,Bx,By      (t = 0, 0.01, ..., 1 s: 101 rows)
phi = crank angle (unwrapped), psi = lever angle [rad]; slot_f = force of the slot (lever) on
the crank at the pin P, normal to the lever axis [N]; O_f = force of the ground on the crank
at O [N]; (Bx, By) = lever tip B [m].

Model (SI, planar, y up, angles counter-clockwise from +x), gravity g = (0, -9.81) on both
bodies:
  crank: uniform slender bar r = 0.1, m1 = 0.5, J1 = m1 r^2/12, pinned to the ground at
    O = (0, 0); pin P = r (cos phi, sin phi); centre of mass at P/2.
  lever: uniform slender bar L = 0.5, m2 = 1.0, J2 = m2 L^2/12, pinned to the ground at
    A = (0, -d), d = 0.3; centre of mass A + (L/2) e, tip B = A + L e, e = (cos psi, sin psi).
  slot: the crank point P slides without friction along the lever axis (line through A, dir.
    e); the slot force on the crank is lam * n, n = (-sin psi, cos psi), and -lam * n acts on
    the lever at P. Since r < d: psi = atan2(r sin phi + d, r cos phi), one degree of freedom.
  torque T = 5 N m (counter-clockwise) on the crank.
  spring-damper B -- C = (0.4, 0.25): k = 200 N/m, c = 2 N s/m, l0 = 0.15 m, tension
    N = k (l - l0) + c l', l = |B - C|, force -N (B - C)/l on B.
  initially phi = 0, phi' = 0 (psi(0) = atan2(d, r)); t in [0, 1] s.

Two formulations, both integrated with scipy DOP853, restarted at every output time (no
dense-output interpolation):
  A (written to the CSV, rtol = atol = 1e-13). Lagrange's equation in the single coordinate
    phi: with rho^2 = |P - A|^2 = r^2 + d^2 + 2 r d sin phi,
      psi'(phi) = r (r + d sin phi) / rho^2,  psi''(phi) = r d (d^2 - r^2) cos phi / rho^4,
      (I_O + I_A psi'^2) phi'' + I_A psi' psi'' phi'^2 = Q,   I_O = m1 r^2/3, I_A = m2 L^2/3,
      Q = T - m1 g (r/2) cos phi - m2 g (L/2) cos psi psi' - N dl/dphi.
    The slot multiplier follows from the lever's moment equation about A,
      I_A psi'' = -lam rho - m2 g (L/2) cos psi + (B - A) x F_B   (rho >= d - r > 0),
    and the ground force from Newton's law for the crank, F_O = m1 a_1 - lam n - m1 g.
    The crank's own moment equation about O, I_O phi'' = T + P x (lam n) - m1 g (r/2) cos phi,
    is not used and is checked instead (residual printed).
    The dissipated energy W_d = int c l'^2 dt is carried as an extra state for the energy
    balance  E = T_kin + V_grav + k (l - l0)^2 / 2 - T (phi - phi0) + W_d = E(0).
  B (cross-check, rtol = atol = 1e-13). 6 absolute coordinates q = [x1, y1, phi, x2, y2, psi]
    (centres of mass and angles), 5 constraints (2 for each ground pin and the slot
    g5 = (P - c2) . n, with P taken on the crank and n on the lever), index-1 form
    [[M, G^T], [G, 0]] [q''; mu] = [f; gamma], M q'' + G^T mu = f, gamma = -(G q')' q'.
    The ground force on the crank is (-mu1, -mu2) and the slot force on it is -mu5 n.
Achieved accuracy (max |diff| over the 101 rows, as printed by this script):
  A at 1e-13 vs A at 1e-12:  phi 1.0e-12 rad, psi 2.4e-13 rad, slot force 1.8e-11 N,
                             O force 3.8e-11 N, B 1.2e-13 m   (an upper bound for the CSV)
  A at 1e-13 vs A at 3e-14:  phi 1.0e-13 rad, slot force 1.8e-12 N, O force 3.9e-12 N
  A vs B (both at 1e-13):    phi 3.7e-13 rad, psi 3.4e-14 rad, slot force 3.5e-12 N,
                             O force 5.2e-12 N, B 1.9e-14 m
  A energy balance: E(0) = 0.453680006234021 J, max |E(t) - E(0)| = 7.8e-14 J; crank
  moment-equation residual 3.7e-15 N m; slot force along the lever axis 3.6e-15 N;
  B constraint drift 2.5e-14 m.
So the CSV is accurate to ~1e-12 rad / 1e-13 m / 4e-11 N or better (probably ~2e-13 rad /
5e-12 N).
"""
import os
import numpy as np
from scipy.integrate import solve_ivp

g = 9.81
r, m1 = 0.1, 0.5
L, m2 = 0.5, 1.0
d = 0.3
J1, J2 = m1 * r**2 / 12, m2 * L**2 / 12
IO, IA = J1 + m1 * (r / 2)**2, J2 + m2 * (L / 2)**2     # inertias about the ground pins
T = 5.0
k, c, l0 = 200.0, 2.0, 0.15
A = np.array([0.0, -d])
C = np.array([0.4, 0.25])
phi0 = 0.0


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


# ---------------- A: Lagrange in phi ----------------
def kin(phi):
    """psi(phi), dpsi/dphi, d2psi/dphi2 and rho = |P - A|."""
    s, co = np.sin(phi), np.cos(phi)
    rho2 = r * r + d * d + 2 * r * d * s
    psi = np.arctan2(r * s + d, r * co)
    p1 = r * (r + d * s) / rho2
    p2 = r * d * (d * d - r * r) * co / rho2**2
    return psi, p1, p2, np.sqrt(rho2)


def spring(psi, psidot):
    """B, Bdot, l, ldot, tension N and the force F_B on B."""
    e, n = np.array([np.cos(psi), np.sin(psi)]), np.array([-np.sin(psi), np.cos(psi)])
    B = A + L * e
    Bd = L * psidot * n
    BC = B - C
    ell = np.hypot(*BC)
    ell_d = BC @ Bd / ell
    N = k * (ell - l0) + c * ell_d
    return B, Bd, ell, ell_d, N, -N * BC / ell


def accel_min(y):
    phi, w = y[0], y[1]
    psi, p1, p2, rho = kin(phi)
    psid = p1 * w
    B, Bd, ell, ell_d, N, FB = spring(psi, psid)
    dl_dphi = (B - C) @ (L * p1 * np.array([-np.sin(psi), np.cos(psi)])) / ell
    Q = T - m1 * g * 0.5 * r * np.cos(phi) - m2 * g * 0.5 * L * np.cos(psi) * p1 - N * dl_dphi
    phidd = (Q - IA * p1 * p2 * w**2) / (IO + IA * p1**2)
    return phidd, dict(psi=psi, p1=p1, p2=p2, rho=rho, psid=psid, B=B, ell=ell, ell_d=ell_d,
                       N=N, FB=FB)


def rhs_min(t, y):
    phidd, K = accel_min(y)
    return [y[1], phidd, c * K['ell_d']**2]


def forces_min(y):
    """slot force on the crank (x, y), ground force on the crank at O (x, y), crank moment
    residual."""
    phi, w = y[0], y[1]
    phidd, K = accel_min(y)
    psi = K['psi']
    psidd = K['p1'] * phidd + K['p2'] * w**2
    e, n = np.array([np.cos(psi), np.sin(psi)]), np.array([-np.sin(psi), np.cos(psi)])
    MA = -m2 * g * 0.5 * L * np.cos(psi) + cross(L * e, K['FB'])
    lam = (MA - IA * psidd) / K['rho']
    Fs = lam * n
    u, un = np.array([np.cos(phi), np.sin(phi)]), np.array([-np.sin(phi), np.cos(phi)])
    a1 = 0.5 * r * (un * phidd - u * w**2)
    FO = m1 * a1 - Fs - m1 * np.array([0.0, -g])
    res = IO * phidd - (T + cross(r * u, Fs) - m1 * g * 0.5 * r * np.cos(phi))
    return Fs, FO, res


def energy_min(y):
    phi, w, Wd = y
    psi, p1, _, _ = kin(phi)
    _, _, ell, _, _, _ = spring(psi, p1 * w)
    kinetic = 0.5 * (IO + IA * p1**2) * w**2
    vgrav = m1 * g * 0.5 * r * np.sin(phi) + m2 * g * (-d + 0.5 * L * np.sin(psi))
    return kinetic + vgrav + 0.5 * k * (ell - l0)**2 - T * (phi - phi0) + Wd


# ---------------- B: 6 absolute coordinates, index-1 DAE ----------------
Mabs = np.diag([m1, m1, J1, m2, m2, J2])


def constraints(q, v):
    x1, y1, ph, x2, y2, ps = q
    vx1, vy1, w1, vx2, vy2, w2 = v
    u, un = np.array([np.cos(ph), np.sin(ph)]), np.array([-np.sin(ph), np.cos(ph)])
    e, n = np.array([np.cos(ps), np.sin(ps)]), np.array([-np.sin(ps), np.cos(ps)])
    P = np.array([x1, y1]) + 0.5 * r * u
    Pd = np.array([vx1, vy1]) + 0.5 * r * un * w1
    Dl = P - np.array([x2, y2])                 # P relative to the lever's centre
    Dld = Pd - np.array([vx2, vy2])
    gv = np.array([x1 - 0.5 * r * u[0], y1 - 0.5 * r * u[1],
                   x2 - 0.5 * L * e[0], y2 + d - 0.5 * L * e[1], Dl @ n])
    G = np.zeros((5, 6))
    G[0, 0], G[0, 2] = 1, 0.5 * r * u[1]
    G[1, 1], G[1, 2] = 1, -0.5 * r * u[0]
    G[2, 3], G[2, 5] = 1, 0.5 * L * e[1]
    G[3, 4], G[3, 5] = 1, -0.5 * L * e[0]
    G[4, 0], G[4, 1], G[4, 2] = n[0], n[1], 0.5 * r * un @ n
    G[4, 3], G[4, 4], G[4, 5] = -n[0], -n[1], -Dl @ e
    # gamma = -(terms of d2g/dt2 that are quadratic in the velocities)
    gam = np.array([-0.5 * r * u[0] * w1**2, -0.5 * r * u[1] * w1**2,
                    -0.5 * L * e[0] * w2**2, -0.5 * L * e[1] * w2**2,
                    -(-0.5 * r * (u @ n) * w1**2 - 2 * (Dld @ e) * w2 - (Dl @ n) * w2**2)])
    return gv, G, gam


def solve_abs(y):
    q, v = y[:6], y[6:12]
    _, G, gam = constraints(q, v)
    ps, w2 = q[5], v[5]
    e, n = np.array([np.cos(ps), np.sin(ps)]), np.array([-np.sin(ps), np.cos(ps)])
    B = q[3:5] + 0.5 * L * e
    Bd = v[3:5] + 0.5 * L * w2 * n
    ell = np.hypot(*(B - C))
    ell_d = (B - C) @ Bd / ell
    FB = -(k * (ell - l0) + c * ell_d) * (B - C) / ell
    f = np.array([0.0, -m1 * g, T, FB[0], FB[1] - m2 * g, cross(0.5 * L * e, FB)])
    Mat = np.block([[Mabs, G.T], [G, np.zeros((5, 5))]])
    sol = np.linalg.solve(Mat, np.concatenate([f, gam]))
    return sol[:6], sol[6:], c * ell_d**2


def rhs_abs(t, y):
    qdd, _, pdiss = solve_abs(y)
    return np.concatenate([y[6:12], qdd, [pdiss]])


def y0_abs():
    psi = kin(phi0)[0]
    q = [0.5 * r * np.cos(phi0), 0.5 * r * np.sin(phi0), phi0,
         0.5 * L * np.cos(psi), -d + 0.5 * L * np.sin(psi), psi]
    return np.array(q + [0.0] * 7)


# ---------------- driver ----------------
def integrate(rhs, y0, times, tol):
    ys, y = [np.array(y0, float)], np.array(y0, float)
    for ta, tb in zip(times[:-1], times[1:]):
        sol = solve_ivp(rhs, (ta, tb), y, method='DOP853', rtol=tol, atol=tol)
        assert sol.success, sol.message
        y = sol.y[:, -1]
        ys.append(y)
    return np.array(ys)


def table_min(tol, times):
    Y = integrate(rhs_min, [phi0, 0.0, 0.0], times, tol)
    rows, res = [], 0.0
    for t, y in zip(times, Y):
        Fs, FO, rm = forces_min(y)
        K = accel_min(y)[1]
        rows.append([t, y[0], K['psi'], *Fs, *FO, *K['B']])
        res = max(res, abs(rm))
    E = np.array([energy_min(y) for y in Y])
    return np.array(rows), np.abs(E - E[0]).max(), res, E[0]


def table_abs(tol, times):
    Y = integrate(rhs_abs, y0_abs(), times, tol)
    rows, drift = [], 0.0
    for t, y in zip(times, Y):
        _, mu, _ = solve_abs(y)
        ps = y[5]
        n = np.array([-np.sin(ps), np.cos(ps)])
        B = y[3:5] + 0.5 * L * np.array([np.cos(ps), np.sin(ps)])
        rows.append([t, y[2], ps, *(-mu[4] * n), -mu[0], -mu[1], *B])
        drift = max(drift, np.abs(constraints(y[:6], y[6:12])[0]).max())
    return np.array(rows), drift


def maxdiff(a, b):
    dd = np.abs(a - b).max(axis=0)
    return 'phi %.1e, psi %.1e, slot f %.1e, O f %.1e, B %.1e' % (
        dd[1], dd[2], max(dd[3], dd[4]), max(dd[5], dd[6]), max(dd[7], dd[8]))


if __name__ == '__main__':
    times = np.round(np.arange(101) * 0.01, 12)
    ref, dE, res, E0 = table_min(1e-13, times)      # the CSV
    coarse = table_min(1e-12, times)[0]
    fine = table_min(3e-14, times)[0]
    absref, drift = table_abs(1e-13, times)
    print('A: tol 1e-13 vs 1e-12, max |diff|:', maxdiff(ref, coarse))
    print('A: tol 1e-13 vs 3e-14, max |diff|:', maxdiff(ref, fine))
    print('A vs B (both 1e-13), max |diff|:  ', maxdiff(ref, absref))
    print('A: energy balance E(0) = %.15g J, max |E(t) - E(0)| = %.1e J' % (E0, dE))
    print('A: max |crank moment-equation residual| = %.1e N m' % res)
    print('B: max |constraint residual| = %.1e m' % drift)
    # the slot force is normal to the lever axis by construction; check it anyway
    normal = max(abs(row[3] * np.cos(row[2]) + row[4] * np.sin(row[2])) for row in ref)
    print('slot force . lever axis: max %.1e N' % normal)
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'tests',
                       'reference', 'quick_return.csv')
    with open(os.path.normpath(out), 'w') as fh:
        fh.write('t,phi,psi,slot_fx,slot_fy,O_fx,O_fy,Bx,By\n')
        for row in ref:
            fh.write(','.join([repr(float(row[0]))] + ['%.17g' % v for v in row[1:]]) + '\n')
    for i in (50, 100):
        print('t=%g: ' % ref[i, 0] + ' '.join(
            '%s=%.15g' % (nm, v) for nm, v in
            zip(['phi', 'psi', 'slot_fx', 'slot_fy', 'O_fx', 'O_fy', 'Bx', 'By'], ref[i, 1:])))
    print('wrote', os.path.normpath(out))
