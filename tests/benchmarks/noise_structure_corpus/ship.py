"""Linear sway-yaw ship from Clarke (1983) hull formulas (Fossen), its Nomoto constants and the
second_order_rates parameters, plus a fine-RK4 simulator with a first-order rudder servo."""
import numpy as np

SHIPS = {
    # L [m], B, T, CB, speed, sample rate [Hz], multisine periods [s], duration [s]
    "patrol": dict(L=30.0, B=6.5, T=1.5, CB=0.40, U=6.0, rate=5.0,
                   periods=[60, 30, 15, 7.5, 4, 2], duration=600.0),
    "supply": dict(L=76.0, B=12.0, T=6.0, CB=0.50, U=6.0, rate=2.0,
                   periods=[120, 60, 30, 15, 8, 4], duration=1200.0),
}

def clarke(L, B, T, CB, **_):
    f = -np.pi * (T / L) ** 2
    Yvd = f * (1 + 0.16 * CB * B / T - 5.1 * (B / L) ** 2)
    Yrd = f * (0.67 * B / L - 0.0033 * (B / T) ** 2)
    Nvd = f * (1.1 * B / L - 0.041 * B / T)
    Nrd = f * (1 / 12 + 0.017 * CB * B / T - 0.33 * B / L)
    Yv = f * (1 + 0.4 * CB * B / T)
    Yr = f * (-0.5 + 2.2 * B / L - 0.08 * B / T)
    Nv = f * (0.5 + 2.4 * T / L)
    Nr = f * (0.25 + 0.039 * B / T - 0.56 * B / L)
    m = CB * L * B * T / (0.5 * L ** 3)            # m' = rho CB L B T / (rho/2 L^3)
    Iz = m * 0.25 ** 2                              # radius of gyration 0.25 L, x_g = 0
    M = np.array([[m - Yvd, -Yrd], [-Nvd, Iz - Nrd]])
    N = np.array([[-Yv, m - Yr], [-Nv, -Nr]])
    Yd = 0.05 * T / L                               # rudder: A_R = 0.02 L T, C_L,alpha = 2.5
    Nd = -0.5 * Yd                                  # at x_R = -L/2
    return M, N, np.array([Yd, Nd])

def state_space(ship):
    """x = (v/U, r L/U), dx/dt = A x + B delta, r = C x (dimensional time)."""
    M, N, bp = clarke(**ship)
    s = ship["U"] / ship["L"]
    A = -s * np.linalg.solve(M, N)
    Bv = s * np.linalg.solve(M, bp)
    C = np.array([0.0, s])
    return A, Bv, C

def truth(ship):
    A, Bv, C = state_space(ship)
    a1 = -np.trace(A); a0 = np.linalg.det(A)
    s = C[1]
    c1 = s * Bv[1]
    c0 = s * (A[1, 0] * Bv[0] - A[0, 0] * Bv[1])   # adj(sI-A) row 2: [A21, s - A11]
    b = c0; T3 = c1 / c0
    disc = np.sqrt(a1 ** 2 - 4 * a0)
    p1, p2 = (a1 - disc) / 2, (a1 + disc) / 2
    T1, T2 = 1 / p1, 1 / p2
    K = b / a0
    return dict(a1=a1, a0=a0, b=b, T3=T3, T1=T1, T2=T2, K=K)

def multisine(ship, amp_deg=24.0):
    P = np.array(ship["periods"], float)
    n = len(P)
    ph = -np.pi * np.arange(1, n + 1) * np.arange(n) / n   # Schroeder phases
    tt = np.arange(0, ship["duration"], 0.01)
    raw = np.sum([np.sin(2 * np.pi * tt / p + f) for p, f in zip(P, ph)], axis=0)
    scale = np.deg2rad(amp_deg) / np.max(np.abs(raw))
    return lambda t: scale * np.sum([np.sin(2 * np.pi * np.asarray(t)[..., None] / P + ph)], axis=0).sum(-1)

def simulate(ship, h=0.01, servo_T=1.0):
    """RK4 with step h of [delta, x1, x2, psi]; returns t, delta, psi, r, delta_cmd on the h grid."""
    A, Bv, C = state_space(ship)
    cmd = multisine(ship)
    n = int(round(ship["duration"] / h)) + 1
    t = np.arange(n) * h
    def f(x, tc):
        dc = cmd(tc)
        d = x[0]
        dx = (dc - d) / servo_T
        v = A @ x[1:3] + Bv * d
        return np.array([dx, v[0], v[1], C @ x[1:3]])
    X = np.zeros((n, 4))
    x = np.zeros(4)
    for k in range(n - 1):
        tk = t[k]
        k1 = f(x, tk); k2 = f(x + h / 2 * k1, tk + h / 2)
        k3 = f(x + h / 2 * k2, tk + h / 2); k4 = f(x + h * k3, tk + h)
        x = x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        X[k + 1] = x
    return t, X[:, 0], X[:, 3], X @ np.r_[0, C, 0], cmd(t)

if __name__ == "__main__":
    for name, s in SHIPS.items():
        tr = truth(s)
        print(name, {k: float("%.6g" % v) for k, v in tr.items()})
        # cross-check with Fossen's closed forms
        M, N, bp = clarke(**s)
        detN = np.linalg.det(N)
        T1T2 = np.linalg.det(M) / detN
        T1pT2 = (N[0, 0] * M[1, 1] + N[1, 1] * M[0, 0] - N[0, 1] * M[1, 0] - N[1, 0] * M[0, 1]) / detN
        K = (N[1, 0] * bp[0] - N[0, 0] * bp[1]) / detN
        KT3 = (M[1, 0] * bp[0] - M[0, 0] * bp[1]) / detN
        LU = s["L"] / s["U"]
        print("  Fossen closed form: T1T2 %.5g T1+T2 %.5g K %.5g T3 %.5g" % (T1T2 * LU**2, T1pT2 * LU, K / LU, KT3 / K * LU))
