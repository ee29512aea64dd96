"""Extended simulator (an extension of ship.py): fine RK4 (h=0.01) of
[servo rudder d, v', r', psi] with optional effective-rudder nonlinearity between the LOGGED
rudder d and the rudder acting on the hull, cubic yaw damping and white yaw-moment noise."""
import os, sys
import math, numpy as np
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "filter_error_coverage"))
import ship as S  # the two hulls, shared with the coverage harness

def simulate(name, h=0.01, servo_T=1.0, backlash=0.0, deadzone=0.0, ratelim=0.0,
             nrrr=0.0, q_yaw=0.0, seed=0):
    sh = S.SHIPS[name]
    A, Bv, C = S.state_space(sh)
    a11, a12, a21, a22 = map(float, A.ravel()); b1, b2 = map(float, Bv); s = float(C[1])
    cmdf = S.multisine(sh)
    n = int(round(sh["duration"] / h)) + 1
    th = np.arange(2 * n + 1) * (h / 2)
    cm = cmdf(th).tolist()
    rng = np.random.default_rng(seed)
    W = (rng.standard_normal(n) * math.sqrt(q_yaw / h)).tolist() if q_yaw > 0 else None
    bl = math.radians(backlash) / 2; dz = math.radians(deadzone); rl = math.radians(ratelim)
    d = v = r = p = 0.0; de = 0.0       # de: backlash / rate-limit state (effective rudder)
    D = np.empty(n); P = np.empty(n); R = np.empty(n); DE = np.empty(n)
    def eff(dd):
        if bl > 0 or rl > 0: return de
        if dz > 0:
            return 0.0 if abs(dd) < dz else dd - math.copysign(dz, dd)
        return dd
    for k in range(n):
        D[k] = d; P[k] = p; R[k] = s * r; DE[k] = eff(d)
        if k == n - 1: break
        w = W[k] if W else 0.0
        c0, c1, c2 = cm[2 * k], cm[2 * k + 1], cm[2 * k + 2]
        def f(d_, v_, r_, c):
            e = eff(d_)
            return ((c - d_) / servo_T, a11 * v_ + a12 * r_ + b1 * e,
                    a21 * v_ + a22 * r_ + b2 * e - nrrr * r_ ** 3 + w, s * r_)
        k1 = f(d, v, r, c0)
        k2 = f(d + h/2*k1[0], v + h/2*k1[1], r + h/2*k1[2], c1)
        k3 = f(d + h/2*k2[0], v + h/2*k2[1], r + h/2*k2[2], c1)
        k4 = f(d + h*k3[0], v + h*k3[1], r + h*k3[2], c2)
        d += h/6*(k1[0]+2*k2[0]+2*k3[0]+k4[0]); v += h/6*(k1[1]+2*k2[1]+2*k3[1]+k4[1])
        r += h/6*(k1[2]+2*k2[2]+2*k3[2]+k4[2]); p += h/6*(k1[3]+2*k2[3]+2*k3[3]+k4[3])
        # update effective-rudder memory after the step
        if bl > 0:
            if d - de > bl: de = d - bl
            elif d - de < -bl: de = d + bl
        elif rl > 0:
            de += max(-rl * h, min(rl * h, d - de))
    return np.arange(n) * h, D, P, R, DE
