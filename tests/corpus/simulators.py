"""Ship simulators of the independent verdict corpus (LABELS.md), written from other
structures' equations than the engine's model families, integrated here (RK4 at 20 Hz, not the
engine's integrator), logged at 5 Hz with noise.

  LinearSwayYaw: the Davidson-Schiff linear sway-yaw equations in prime (non-dimensional)
    coefficients, M nu' + N nu = b delta with nu = (v/U, r L/U), Mariner-class coefficients
    (Chislett & Strom) varied per ship; its Nomoto constants follow from the matrices.
  Norrbin: T r' + r + alpha r^3 = K (delta + bias).
  SpeedLossShip: the linear sway-yaw equations at the ship's current speed U (time constants
    scale with L/U, the yaw-rate gain with U/L) and a surge equation, u' = v r - c_d delta^2 u
    - (u^2 - U0^2) / (U0 tau): the turn and the rudder's drag slow the ship, the propeller
    brings it back to U0 over tau.

Both are steered through a gear (first-order lag, rate limit) by a zigzag autopilot or an
open-loop sine / multisine command; a slow yaw disturbance (as equivalent rudder, not logged)
and a rudder bias (not logged) may be added.
"""
import math

import numpy as np

# Mariner class, prime coefficients (x 1e-5), L = 160.93 m at U = 7.7 m/s.
MARINER = dict(m=798.0, Iz=39.2, xG=-0.023, Yvdot=-748.0, Yrdot=-9.354, Nvdot=4.646,
               Nrdot=-43.8, Yv=-1160.0, Yr=-499.0, Nv=-264.0, Nr=-166.0, Yd=278.0, Nd=-139.0)


class LinearSwayYaw:
    """A Mariner-like ship; `scale` multiplies each hydrodynamic coefficient."""

    def __init__(self, scale=None, length=160.93, speed=7.7):
        c = dict(MARINER)
        for key, factor in (scale or {}).items():
            c[key] *= factor
        e = 1e-5
        m, iz, xg = c["m"] * e, c["Iz"] * e, c["xG"]
        mass = np.array([[m - c["Yvdot"] * e, m * xg - c["Yrdot"] * e],
                         [m * xg - c["Nvdot"] * e, iz - c["Nrdot"] * e]])
        damping = np.array([[-c["Yv"] * e, m - c["Yr"] * e],
                            [-c["Nv"] * e, m * xg - c["Nr"] * e]])
        rudder = np.array([c["Yd"] * e, c["Nd"] * e])
        self.a = -np.linalg.solve(mass, damping)  # prime time
        self.b = np.linalg.solve(mass, rudder)
        self.length, self.speed = length, speed
        # Plain floats for the integration loop (numpy's per-call cost dominates at 2 x 2).
        self._a = tuple(float(v) for v in self.a.ravel())
        self._b = tuple(float(v) for v in self.b)

    def nomoto(self):
        """(T1, T2, T3, K) in s and 1/s; None when the ship is not course-stable."""
        a, b = self.a, self.b
        poles = np.linalg.eigvals(a)
        if np.any(np.abs(poles.imag) > 1e-12) or np.any(poles.real >= 0):
            return None
        det = np.linalg.det(a)
        numerator0 = a[1, 0] * b[0] - a[0, 0] * b[1]
        t1, t2 = sorted((-1.0 / p.real for p in poles), reverse=True)
        k_prime = numerator0 / det
        t3_prime = b[1] / numerator0
        time = self.length / self.speed
        return t1 * time, t2 * time, t3_prime * time, k_prime / time

    def rates(self, state, delta):
        """d/dt of (v', r', psi) in real time."""
        scale = self.speed / self.length
        return self.prime_rates(state[0], state[1], delta, scale) + (state[1] * scale,)

    def prime_rates(self, v, r, delta, scale):
        """d/dt of (v', r') in real time, scale = U / L."""
        a00, a01, a10, a11 = self._a
        b0, b1 = self._b
        return (scale * ((a00 * v + a01 * r) + b0 * delta),
                scale * ((a10 * v + a11 * r) + b1 * delta))

    def initial(self):
        return (0.0, 0.0, 0.0)

    def yaw_rate(self, state):
        return state[1] * self.speed / self.length

    def gain_sign(self):
        return math.copysign(1.0, self.nomoto()[3])


class Norrbin:
    """T r' + r + alpha r^3 = K (delta + bias)."""

    def __init__(self, t, k, alpha):
        self.t, self.k, self.alpha = t, k, alpha

    def rates(self, state, delta):
        r = state[0]
        return ((self.k * delta - r - self.alpha * r ** 3) / self.t, r)

    def initial(self):
        return (0.0, 0.0)

    def yaw_rate(self, state):
        return state[0]

    def gain_sign(self):
        return math.copysign(1.0, self.k)


class SpeedLossShip:
    """A Mariner-like ship that loses speed in turns; state (u, v', r', psi)."""

    def __init__(self, scale, drag, recovery=60.0, length=160.93, speed=7.7):
        self.sway = LinearSwayYaw(scale, length, speed)
        self.drag, self.recovery = drag, recovery
        self.length, self.speed = length, speed
        self.u_min = speed

    def nomoto(self):
        """The sway-yaw equations' Nomoto constants at U0."""
        return self.sway.nomoto()

    def rates(self, state, delta):
        u = state[0]
        speed = max(u, 0.1 * self.speed)
        self.u_min = min(self.u_min, u)
        dv, dr = self.sway.prime_rates(state[1], state[2], delta, speed / self.length)
        v, r = state[1] * speed, state[2] * speed / self.length
        du = (v * r - self.drag * delta ** 2 * u
              - (u * u - self.speed ** 2) / (self.speed * self.recovery))
        return (du, dv, dr, r)

    def initial(self):
        self.u_min = self.speed
        return (self.speed, 0.0, 0.0, 0.0)

    def yaw_rate(self, state):
        return state[2] * max(state[0], 0.1 * self.speed) / self.length

    def gain_sign(self):
        return math.copysign(1.0, self.nomoto()[3])


def speed_loss(ship, excitation, duration, seed, **options):
    """1 - U_min / U0 of a noise-free run of a SpeedLossShip."""
    clean = dict(options, heading_noise_deg=0.0, rudder_noise_deg=0.0)
    simulate(ship, excitation, duration, seed, **clean)
    return 1.0 - ship.u_min / ship.speed


def command(excitation, t, psi, state):
    """The rudder command (rad) of an excitation dict at time t and heading psi."""
    kind = excitation["type"]
    if kind == "sine":
        return excitation["amplitude"] * math.sin(2 * math.pi * t / excitation["period"])
    if kind == "multisine":
        return excitation["amplitude"] / len(excitation["periods"]) * sum(
            math.sin(2 * math.pi * t / p + i) for i, p in enumerate(excitation["periods"]))
    # zigzag: rudder to +-delta_z, reversed when the heading passes +-psi_z the rudder's way
    side = state.setdefault("side", 1.0)
    if excitation["sign"] * side * psi >= excitation["heading"]:
        state["side"] = side = -side
    return side * excitation["rudder"]


def simulate(ship, excitation, duration, seed, gear_lag=1.0, rate_limit_deg=2.5, bias=0.0,
             disturbance=0.0, disturbance_period=200.0, heading_noise_deg=0.1,
             rudder_noise_deg=0.1, step=0.05, log_every=4, heading_noise_tau=0.0):
    """Columns t, delta (rad, the gear's angle with noise), psi (rad, with noise). With
    heading_noise_tau > 0 the heading's noise is coloured: an AR(1) of that time constant (s)
    and standard deviation heading_noise_deg, as a compass or a GNSS heading logs it."""
    rng = np.random.default_rng(seed)
    colour = math.exp(-step * log_every / heading_noise_tau) if heading_noise_tau > 0 else 0.0
    drift = None  # the AR(1) noise's current value
    excitation = dict(excitation)
    excitation["sign"] = ship.gain_sign()
    phase = rng.uniform(0, 2 * math.pi)
    x = ship.initial()
    delta = 0.0
    rate = math.radians(rate_limit_deg)
    zig = {}
    rows = []
    steps = int(round(duration / step))

    def derivative(x, delta, t):
        extra = bias + disturbance * math.sin(2 * math.pi * t / disturbance_period + phase)
        return ship.rates(x, delta + extra)

    def moved(x, h, k):
        return tuple(xi + h * ki for xi, ki in zip(x, k))

    for k in range(steps + 1):
        t = k * step
        psi = x[-1]
        if k % log_every == 0:
            rudder_noise = rng.normal(0, math.radians(rudder_noise_deg))
            noise = rng.normal(0, math.radians(heading_noise_deg))
            if colour > 0.0:  # n_k = c n_(k-1) + sqrt(1 - c^2) w_k: stationary, same SD
                drift = noise if drift is None else colour * drift + math.sqrt(1 - colour ** 2) * noise
                noise = drift
            rows.append((t, delta + rudder_noise, psi + noise))
        if k == steps:
            break
        target = command(excitation, t, psi, zig)
        delta += max(-rate * step, min(rate * step, (target - delta) * step / gear_lag))
        k1 = derivative(x, delta, t)
        k2 = derivative(moved(x, 0.5 * step, k1), delta, t + 0.5 * step)
        k3 = derivative(moved(x, 0.5 * step, k2), delta, t + 0.5 * step)
        k4 = derivative(moved(x, step, k3), delta, t + step)
        x = tuple(xi + step / 6.0 * (((a + 2 * b) + 2 * c) + d)
                  for xi, a, b, c, d in zip(x, k1, k2, k3, k4))
    return np.array(rows)


def largest_yaw_rate(ship, excitation, duration, seed, **options):
    """The largest |r| of a noise-free run (the Norrbin label's r_max)."""
    clean = dict(options, heading_noise_deg=0.0, rudder_noise_deg=0.0)
    rows = simulate(ship, excitation, duration, seed, **clean)
    psi = np.unwrap(rows[:, 2])
    return float(np.max(np.abs(np.gradient(psi, rows[:, 0]))))
