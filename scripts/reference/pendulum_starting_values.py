#!/usr/bin/env python3
# Evidence for docs/theory/starting_values.md §5 (not run by the tests): Algorithm 1 of Arnold & Brüls (2007)
# transcribed for the Cartesian pendulum (index 3, L = 1 m, θ0 = 1 rad), its multiplier error against the
# exact λ = m(|v|² − g y)/L² of a DOP853 solution, over the first 0.25 s and after, with the standard,
# corrected and smooth starting values.  Usage: /usr/bin/python3 pendulum_starting_values.py [θ̇0 in rad/s]
# Generalized-α (Arnold & Brüls 2007, Algorithm 1) on the Cartesian pendulum (index 3), start-up
# transient of λ with the standard, corrected and smooth starting values.
import numpy as np
from scipy.integrate import solve_ivp
m, L, g = 1.0, 1.0, 9.81
def params(rho):
    am = (2*rho-1)/(rho+1); af = rho/(rho+1); ga = 0.5+af-am; be = 0.25*(ga+0.5)**2
    return am, af, be, ga
def acc(q, v):  # index-1: m qdd = f - λ q, q·qdd + v·v = 0
    f = np.array([0.0, -m*g])
    lam = (q @ f/m + v @ v) / (q @ q / m)
    return (f - lam*q)/m, lam
def run(rho, h, n, start, v0=0.0):
    am, af, be, ga = params(rho)
    th0 = 1.0
    q = L*np.array([np.sin(th0), -np.cos(th0)]); v = v0*L*np.array([np.cos(th0), np.sin(th0)])
    w, lam = acc(q, v)
    a = w.copy()
    if start != 'standard':
        def ahead(s, q3):
            qq = q + s*v + 0.5*s*s*w + (s**3/6*q3 if q3 is not None else 0)
            vv = v + s*w + (0.5*s*s*q3 if q3 is not None else 0)
            return acc(qq, vv)[0]
        q3f = (ahead(h, None) - w)/h
        if start == 'corrected':
            a = w + (am-af)*h*q3f
        else:
            d1 = ahead(h, q3f) - w; d2 = ahead(2*h, q3f) - w
            q3 = (4*d1-d2)/(2*h); q4 = (d2-2*d1)/h**2
            r1 = 0.5-ga; r2 = ga*ga-0.5*ga-be+1/12; s2 = 0.5*ga-be-1/12; s3 = 0.25*(2*be-ga)*(2*ga-1)
            w1 = af-am-ga+0.5; w2 = af*af-af*am-af*ga+am*ga-be+ga*ga-0.5*ga+1/12
            a = w + r1*h*q3 + r2*h*h*q4
            v = v + s2*h*h*q3 + s3*h**3*q4
            w = w + w1*h*q3 + w2*h*h*q4
    lams = []
    bp = (1-am)/(h*h*be*(1-af)); gp = ga/(h*be)
    for k in range(n):
        # unknowns q1, λ1 ; qdd1 = (f - λ q1)/m ; a1 = ((1-af) qdd1 + af w - am a)/(1-am)
        # q1 = q + h v + h²(½-β)a + h²β a1
        f = np.array([0.0, -m*g])
        lam1 = lam
        for it in range(50):
            # solve for λ1 s.t. constraint holds: q1(λ1)
            def q1of(l):
                # fixed point on q1 since qdd1 depends on q1: solve linear system per λ
                # q1 = c + h²β/(1-am) (1-af)(f - l q1)/m  -> (1 + k l) q1 = c + k f
                kk = h*h*be*(1-af)/((1-am)*m)
                c = q + h*v + h*h*(0.5-be)*a + h*h*be*(af*w - am*a)/(1-am)
                return (c + kk*f)/(1+kk*l)
            r = lambda l: 0.5*(q1of(l) @ q1of(l) - L*L)
            dl = 1e-6*max(1, abs(lam1))
            step = r(lam1)/((r(lam1+dl)-r(lam1-dl))/(2*dl))
            lam1 -= step
            if abs(step) < 1e-13*max(1, abs(lam1)): break
        q1 = q1of(lam1); w1_ = (f - lam1*q1)/m
        a1 = ((1-af)*w1_ + af*w - am*a)/(1-am)
        v = v + h*(1-ga)*a + h*ga*a1
        q, a, w, lam = q1, a1, w1_, lam1
        lams.append(lam)
    return np.array(lams)
def exact(ts, v0=0.0):
    th0 = 1.0
    sol = solve_ivp(lambda t, y: [y[1], -g/L*np.sin(y[0])], (0, ts[-1]), [th0, v0], t_eval=ts, rtol=1e-13, atol=1e-13, method='DOP853')
    th, om = sol.y
    y = -L*np.cos(th); v2 = (L*om)**2
    return m*(v2 - g*y)/L**2
import sys
v0 = float(sys.argv[1]) if len(sys.argv) > 1 else 0.0
for rho in (0.5, 0.8, 0.95):
    for h in (1e-2, 5e-3, 2.5e-3):
        N = int(round(1.0/h)); n0 = int(round(0.25/h))
        ts = h*np.arange(1, N+1); ex = exact(ts, v0)
        out = []
        for st in ('standard', 'corrected', 'smooth'):
            e = run(rho, h, N, st, v0) - ex
            out.append(f'{st}: {abs(e[:n0]).max():.2e}/{abs(e[n0:]).max():.2e}')
        print(f'rho {rho} h {h:.1e}  ' + '  '.join(out))
