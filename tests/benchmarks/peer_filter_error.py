#!/usr/bin/env python3
"""Textbook filter-error peer for benchmarking vesselid's filter-error method.

Method: the maximum-likelihood filter-error method (output error with process noise) of
  R. E. Maine & K. W. Iliff, "Formulation and implementation of a practical algorithm for
  parameter estimation with process and measurement noise", SIAM J. Appl. Math. 41(3), 1981;
  R. V. Jategaonkar, "Flight Vehicle System Identification - A Time Domain Methodology",
  AIAA, 2006 (2nd ed. 2015), chapter 5 "Filter Error Method" (equation numbers: 2nd ed.),
written as a careful user would with NumPy/SciPy and the book's usual choices:

  * model: linear state space  x' = A x + B (u + delta_0) + F w,  y = C x + v,
    w white with unit spectral density (so F F^T = diag of spectral densities q),
    v white with variance G G^T;
  * steady-state Kalman filter (time-invariant gain), state propagation by the exact
    zero-order-hold discretisation  Phi = expm(A dt), Gamma = int_0^dt expm(A s) ds B
    (scipy.linalg.expm of the augmented matrix [[A, B], [0, 0]] dt; the input is taken as
    held constant between samples);
  * the gain from the book's steady-state Riccati equation (there solved by Potter's method,
    eigenvectors of the Hamiltonian, eq. 5.15-5.17; here by scipy.linalg.solve_continuous_are)
        A P + P A^T - (1/dt) P C^T R^-1 C P + F F^T = 0,      K = P C^T R^-1,
    where R is the covariance of the innovations (the book's R, not the sensor noise alone);
    the measurement noise follows as  G G^T = R - C P C^T, which must stay positive (the
    book's constraint; here enforced by rejecting, i.e. halving, steps that violate it).
    `--riccati discrete` instead solves the same condition exactly in discrete time (the
    discrete Riccati equation whose innovation variance C P C^T + G G^T equals R; a scalar
    root in G G^T since psi is the only output) - not the book, offered for comparison;
  * the relaxation algorithm (Maine & Iliff; Jategaonkar ch. 5): per iteration
      (1) R = 1/N sum nu nu^T  (closed-form maximum-likelihood estimate at fixed parameters),
      (2) "F-G compensation" (Jategaonkar eq. 5.41, heuristic): rescale the process-noise
          intensities by R_new / R_old so that the Kalman gain is unchanged by the R update
          (with one output the book's formula reduces to F_new = F_old sqrt(R_new / R_old),
          which leaves K exactly unchanged; applied to every process-noise intensity,
          including the unobserved eta2 for which the book's diagonal formula reads 0/0),
      (3) one Gauss-Newton step on all other parameters (model parameters and process-noise
          intensities together) at fixed R, with the innovations' sensitivities by finite
          differences of whole filter runs (central by default, forward with --fd forward;
          the gain is recomputed in every perturbed run, so its dependence on the parameters
          is included) and step halving when the cost or the G G^T > 0 constraint fails;
  * warm-up: until the other parameters have nearly converged (their Gauss-Newton step
    would lower -log L by less than 1; at most 20 iterations) the process-noise intensity q
    is held at its (compensated) start - the book's advice to start the filter-error method
    from (near) output-error estimates, inside one run. From a start 30 % off, a free q
    otherwise jumps by orders of magnitude in the first step (a wrong model is best
    "explained" by a large gain) and the fit runs off (--no-warmup to see it). The AR(1)
    parameters stay free: held at a poor start, the model bends to mimic the coloured
    noise (T3 -> 30 s in the self test) and the fit then crawls back, or not at all;
  * converged when the Gauss-Newton step's predicted decrease of -log L is below 1e-3 and
    the closed-form R changed by less than 1e-4 (relative) in its last update; no descent in
    12 halvings, or --max-iterations steps, stops the fit as not converged;
  * standard errors from the Gauss-Newton information matrix of the final iteration,
    M = sum dnu^T R^-1 dnu, Cov = M^-1 (the Cramer-Rao bound the book reports).

Model (vesselid family `second_order_rates`, second-order Nomoto in rates form):
    psi'  = eta1 + T3 eta2
    eta1' = eta2
    eta2' = b (delta + delta_0) - a0 eta1 - a1 eta2 + w,    E[w w] = q delta(t - t')
    y = psi (+ z with --ar1) + v
    --ar1: z' = -z / tau + w_z, stationary SD sigma (spectral density 2 sigma^2 / tau)
Estimated: a1, a0, b, T3 (delta_0 with --delta0), log q (and log tau, log sigma with --ar1)
by Gauss-Newton; R by the relaxation step. (The book estimates F = sqrt(q) directly; the
logarithm keeps the intensities positive and the steps well scaled. Standard errors of q,
tau and sigma are by the delta method.)

Initial state: psi(0) = first measurement, eta1(0) = least-squares slope of psi over the
first second (r = eta1 + T3 eta2 with eta2(0) = 0), eta2(0) = 0, z(0) = 0; the filter starts
from it with the steady-state covariance. The first sample only sets psi(0) (its innovation
is zero by construction), so the likelihood sums over samples 1..N-1.

Usage:
  peer_filter_error.py --csv FILE --time t --input delta --output psi [--degrees] [--ar1]
                       --start a1,a0,b,T3 [--q-start Q] [--ar1-start TAU,SIGMA] [--delta0]
                       [--max-iterations 50] [--json OUT]
                       [--riccati continuous|discrete] [--fd central|forward]
                       [--no-fg-compensation] [--no-warmup] [--verbose]
  peer_filter_error.py --selftest [--ar1] [--seed N] [--psi-noise SD] [--periods P1,P2,...]
--degrees: psi and delta columns in degrees (converted to rad; psi is unwrapped either way).

Output (stdout, and --json OUT): {"estimates", "std_errors", "noise": {"R" (measurement
noise variance G G^T, rad^2), "innovation_variance" (the relaxation's R), "q", "tau",
"sigma"}, "iterations", "cpu_seconds" (time.process_time of the fit), "converged",
"negative_log_likelihood" (1/2 sum (nu^2/R + ln R + ln 2 pi) over samples 1..N-1)}.
Dependencies: numpy and scipy only; single-threaded (OMP/BLAS threads set to 1).
"""
import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")  # one core: the matrices are tiny anyway

import argparse  # noqa: E402
import csv  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402
from scipy.linalg import expm, solve_continuous_are, solve_discrete_are  # noqa: E402
from scipy.optimize import brentq  # noqa: E402

MODEL_NAMES = ["a1", "a0", "b", "T3"]


# ---------------------------------------------------------------------------------------------
# Model and parameter vector
# ---------------------------------------------------------------------------------------------
class Model:
    """Parameter layout and state-space matrices of the second-order rates Nomoto model.

    theta = [a1, a0, b, T3, (delta_0), log q, (log tau, log sigma)]
    """

    def __init__(self, ar1=False, delta0=False):
        self.ar1 = ar1
        self.delta0 = delta0
        self.names = list(MODEL_NAMES) + (["delta_0"] if delta0 else []) + ["log_q"]
        if ar1:
            self.names += ["log_tau", "log_sigma"]
        self.index = {name: i for i, name in enumerate(self.names)}
        self.n = 4 if ar1 else 3
        self.C = np.zeros(self.n)
        self.C[0] = 1.0
        if ar1:
            self.C[3] = 1.0

    def pack(self, model_params, q, delta_0=0.0, tau=None, sigma=None):
        theta = list(model_params)
        if self.delta0:
            theta.append(delta_0)
        theta.append(math.log(q))
        if self.ar1:
            theta += [math.log(tau), math.log(sigma)]
        return np.array(theta, dtype=float)

    def noise(self, theta):
        """(q, tau, sigma) from theta (tau, sigma None without --ar1)."""
        q = math.exp(theta[self.index["log_q"]])
        if not self.ar1:
            return q, None, None
        return q, math.exp(theta[self.index["log_tau"]]), math.exp(theta[self.index["log_sigma"]])

    def continuous(self, theta):
        """A, B (rudder), Qc = F F^T (spectral densities), input offset delta_0."""
        a1, a0, b, t3 = theta[:4]
        d0 = theta[self.index["delta_0"]] if self.delta0 else 0.0
        q, tau, sigma = self.noise(theta)
        n = self.n
        A = np.zeros((n, n))
        A[0, 1], A[0, 2] = 1.0, t3
        A[1, 2] = 1.0
        A[2, 1], A[2, 2] = -a0, -a1
        B = np.zeros(n)
        B[2] = b
        Qc = np.zeros((n, n))
        Qc[2, 2] = q
        if self.ar1:
            A[3, 3] = -1.0 / tau
            Qc[3, 3] = 2.0 * sigma ** 2 / tau
        return A, B, Qc, d0

    def compensate(self, theta, ratio):
        """F-G compensation: scale every process-noise intensity by ratio = R_new / R_old.

        F F^T -> ratio F F^T together with R -> ratio R scales P by ratio and leaves
        K = P C^T R^-1 unchanged (both Riccati forms are homogeneous of degree one).
        """
        theta = theta.copy()
        theta[self.index["log_q"]] += math.log(ratio)
        if self.ar1:
            theta[self.index["log_sigma"]] += 0.5 * math.log(ratio)  # 2 sigma^2 / tau
        return theta


def zoh(A, B, dt):
    """Exact zero-order-hold discretisation (input held constant over each interval)."""
    n = A.shape[0]
    M = np.zeros((n + 1, n + 1))
    M[:n, :n] = A
    M[:n, n] = B
    E = expm(M * dt)
    return E[:n, :n], E[:n, n]


def van_loan(A, Qc, dt):
    """Exact discrete covariance of the integrated white process noise over dt."""
    n = A.shape[0]
    M = np.zeros((2 * n, 2 * n))
    M[:n, :n] = -A
    M[:n, n:] = Qc
    M[n:, n:] = A.T
    E = expm(M * dt)
    Phi = E[n:, n:].T
    Qd = Phi @ E[:n, n:]
    return 0.5 * (Qd + Qd.T)


# ---------------------------------------------------------------------------------------------
# Steady-state Kalman filter
# ---------------------------------------------------------------------------------------------
class Infeasible(Exception):
    """The gain does not exist or violates G G^T = R - C P C^T > 0."""


def steady_state_gain(model, A, Qc, Phi, R, dt, riccati):
    """Kalman gain K = P C^T R^-1 and C P C^T at fixed innovation variance R."""
    C = model.C
    if riccati == "continuous":
        # The book's first-order form: A P + P A^T - P C^T (R dt)^-1 C P + F F^T = 0.
        try:
            with np.errstate(all="ignore"):  # extreme trial values: judged by P below
                P = solve_continuous_are(A.T, C[:, None], Qc, np.array([[R * dt]]))
        except (np.linalg.LinAlgError, ValueError) as error:
            raise Infeasible(str(error))
    else:
        # Exact discrete form: the a-priori covariance P of the discrete Riccati equation with
        # measurement noise g = G G^T chosen so that C P C^T + g = R (monotone in g).
        Qd = van_loan(A, Qc, dt)

        def dare(g):
            return solve_discrete_are(Phi.T, C[:, None], Qd, np.array([[g]]))

        def excess(g):
            return g + C @ dare(g) @ C - R

        try:
            g_low = 1e-9 * R
            if excess(g_low) >= 0.0:
                raise Infeasible("process noise alone exceeds the innovation variance")
            g = brentq(excess, g_low, R, xtol=1e-14 * R, rtol=1e-12)
            P = dare(g)
        except (np.linalg.LinAlgError, ValueError) as error:
            raise Infeasible(str(error))
    P = 0.5 * (P + P.T)
    cpc = float(C @ P @ C)
    if not np.all(np.isfinite(P)) or cpc >= R:
        raise Infeasible("G G^T = R - C P C^T <= 0")
    return P @ C / R, cpc


def run_filter(model, theta, R, data, riccati):
    """Innovations nu_k = y_k - C x~_k, k = 1..N-1, of the steady-state filter, and C P C^T.

      x^_k = x~_k + K nu_k,   x~_{k+1} = Phi x^_k + Gamma (u_k + delta_0)
    i.e. x~_{k+1} = Phi (I - K C) x~_k + Phi K y_k + Gamma (u_k + delta_0).
    """
    dt, y, u = data["dt"], data["y"], data["u"]
    try:
        A, B, Qc, d0 = model.continuous(theta)
    except (OverflowError, ZeroDivisionError) as error:  # a wild trial step in log tau etc.
        raise Infeasible(str(error))
    if not np.all(np.isfinite(A)) or not np.all(np.isfinite(Qc)):
        raise Infeasible("non-finite model matrices")
    Phi, Gam = zoh(A, B, dt)
    K, cpc = steady_state_gain(model, A, Qc, Phi, R, dt, riccati)
    C = model.C
    PhiK = Phi @ K
    Abar = Phi - np.outer(PhiK, C)
    drive = np.outer(y, PhiK) + np.outer(u + d0, Gam)  # per step input of the recursion
    x = np.zeros(model.n)
    x[0], x[1] = data["psi0"], data["r0"]  # eta2(0) = 0, z(0) = 0
    xs = np.empty((len(y), model.n))
    for k in range(len(y)):  # plain recursion, as a textbook user writes it
        xs[k] = x
        x = Abar @ x + drive[k]
    nu = y[1:] - xs[1:] @ C  # sample 0 only initialises psi(0): its innovation is 0
    if not np.all(np.isfinite(nu)):
        raise Infeasible("filter diverged")
    return nu, cpc


# ---------------------------------------------------------------------------------------------
# Relaxation algorithm: closed-form R, F-G compensation, Gauss-Newton on the rest
# ---------------------------------------------------------------------------------------------
def sensitivities(model, theta, R, data, riccati, nu0, fd, free):
    """d nu / d theta[free] by finite differences of whole filter runs (a column each)."""
    jac = np.empty((len(nu0), len(free)))
    for col, j in enumerate(free):
        # Relative step: cube root of machine epsilon for central, square root for forward;
        # floors 1e-2 for a1, a0, b, T3 and 1e-3 for delta_0 [rad] (log parameters are O(1+)).
        rel = 6e-6 if fd == "central" else 1.5e-8
        h = rel * max(abs(theta[j]), 1e-2 if j < 4 else 1e-3)
        up, down = theta.copy(), theta.copy()
        up[j] += h
        down[j] -= h
        try:
            nu_up, _ = run_filter(model, up, R, data, riccati)
        except Infeasible:  # at the constraint's edge: the one-sided difference backwards
            nu_down, _ = run_filter(model, down, R, data, riccati)
            jac[:, col] = (nu0 - nu_down) / h
            continue
        if fd == "central":
            try:
                nu_down, _ = run_filter(model, down, R, data, riccati)
                jac[:, col] = (nu_up - nu_down) / (2.0 * h)
                continue
            except Infeasible:
                pass
        jac[:, col] = (nu_up - nu0) / h
    return jac


def solve_information(M, g):
    """Gauss-Newton step -M^-1 g; the minimum-norm step if M is singular (rank-deficient)."""
    try:
        return -np.linalg.solve(M, g)
    except np.linalg.LinAlgError:
        return -np.linalg.lstsq(M, g, rcond=1e-12)[0]


def fit(data, model, theta0, max_iterations=50, riccati="continuous", fd="central",
        fg_compensation=True, warmup=True, tol_cost=1e-3, tol_r=1e-4, warmup_decrement=1.0,
        max_warmup=20, fixed=(), verbose=False):
    """Relaxation-algorithm filter-error fit. Returns a dict of results (see module doc).

    Convergence: the Gauss-Newton step's predicted cost decrease below tol_cost (units of
    -log L) and the closed-form R changed by less than tol_r (relative) in its last update.
    `fixed`: names in model.names held at theta0 (used by the self test's profile at truth).
    """
    cpu0 = time.process_time()
    theta = theta0.copy()

    # Starting R: the closed-form estimate made consistent with the start's own gain (a few
    # fixed-point passes R <- mean nu^2 at the start values, q held at its start).
    R = max(float(np.var(np.diff(data["y"]))), 1e-12)
    # The relaxation algorithm updates R after every step anyway: a start R that is feasible
    # (the start's gain exists) is enough; the passes only bring it closer.
    feasible = False
    for _ in range(40):
        try:
            nu, _ = run_filter(model, theta, R, data, riccati)
        except Infeasible:  # R below the start's own C P C^T: raise it and try again
            R *= 4.0
            continue
        feasible = True
        R_new = float(np.mean(nu ** 2))
        try:
            run_filter(model, theta, R_new, data, riccati)
        except Infeasible:
            break  # keep the last feasible R
        converged = abs(R_new / R - 1.0) < 1e-3
        R = R_new
        if converged:
            break
    if not feasible:
        raise Infeasible("no innovation variance consistent with the start values")

    converged = False
    iterations = 0
    all_free = np.array([i for i, name in enumerate(model.names) if name not in fixed], int)
    model_free = np.array([i for i in all_free if model.names[i] != "log_q"], int)  # warm-up
    warming = warmup and len(model_free) > 0
    M = None
    halvings_total = 0
    while True:
        # (1) Closed-form R at the current parameters (the filter run with the previous R).
        nu, _ = run_filter(model, theta, R, data, riccati)
        R_new = float(np.mean(nu ** 2))
        ratio = R_new / R
        # (2) F-G compensation: keep the gain while R moves.
        if fg_compensation:
            theta = model.compensate(theta, ratio)
        R = R_new
        nu, _ = run_filter(model, theta, R, data, riccati)
        cost = 0.5 * float(nu @ nu) / R

        # (3) Gauss-Newton at fixed R: gradient g = sum dnu^T R^-1 nu, M = sum dnu^T R^-1 dnu.
        # Warm-up: the process-noise intensity q stays at its (compensated) start until the
        # other parameters have nearly converged (their step would gain less than
        # warmup_decrement in -log L) or max_warmup iterations have passed; a wrong model is
        # best "explained" by a large gain, and a free q runs away from a poor start. This is
        # the book's advice to start the filter-error method from (near) output-error
        # estimates, done inside one run (see the module docstring).
        while True:
            free = model_free if warming else all_free
            jac = sensitivities(model, theta, R, data, riccati, nu, fd, free)
            g = jac.T @ nu / R
            M = jac.T @ jac / R
            step_free = solve_information(M, g)
            decrement = 0.5 * float(-g @ step_free)  # predicted cost reduction of the step
            if warming and (decrement < warmup_decrement or iterations >= max_warmup):
                warming = False
                continue
            break
        step = np.zeros(len(theta))
        step[free] = step_free
        if verbose:
            q, tau, sigma = model.noise(theta)
            print(f"  iter {iterations:2d}: R {R:.4e} q {q:.3e} decrement {decrement:.3e}"
                  f"{' (warm-up)' if warming else ''} "
                  f"theta {np.array2string(theta, precision=5)}", file=sys.stderr)
        if not warming and decrement < tol_cost and abs(ratio - 1.0) < tol_r:
            converged = True
            break
        if iterations >= max_iterations:
            break

        # Step halving on the cost at fixed R and on the constraint G G^T > 0.
        alpha = 1.0
        accepted = False
        for _ in range(12):
            trial = theta + alpha * step
            try:
                nu_trial, _ = run_filter(model, trial, R, data, riccati)
                if 0.5 * float(nu_trial @ nu_trial) / R <= cost:
                    accepted = True
                    break
            except Infeasible:
                pass
            alpha *= 0.5
            halvings_total += 1
        iterations += 1
        if not accepted:
            break  # no descent along the Gauss-Newton direction: stop, not converged
        theta = trial

    # Final quantities at the last iterate (its R is the closed-form value of this iterate).
    nu, cpc = run_filter(model, theta, R, data, riccati)
    n_used = len(nu)
    nll = 0.5 * (float(nu @ nu) / R + n_used * (math.log(R) + math.log(2.0 * math.pi)))
    if M.shape[0] != len(all_free):  # stopped during the warm-up: the full information matrix
        jac = sensitivities(model, theta, R, data, riccati, nu, fd, all_free)
        M = jac.T @ jac / R
    se_theta = np.zeros(len(theta))  # fixed parameters: 0
    try:
        se_theta[all_free] = np.sqrt(np.maximum(np.diag(np.linalg.inv(M)), 0.0))
    except np.linalg.LinAlgError:
        # Singular information: parameters without any sensitivity (e.g. tau once the AR(1)
        # part has vanished, sigma -> 0) get no finite SE; the others from the rest of M.
        seen = np.diag(M) > 0.0
        se_free = np.full(len(all_free), np.inf)
        try:
            se_free[seen] = np.sqrt(np.maximum(np.diag(np.linalg.inv(M[np.ix_(seen, seen)])), 0))
        except np.linalg.LinAlgError:
            pass
        se_theta[all_free] = se_free
    cpu = time.process_time() - cpu0
    q, tau, sigma = model.noise(theta)
    estimates = {name: float(theta[i]) for i, name in enumerate(MODEL_NAMES)}
    std_errors = {name: float(se_theta[i]) for i, name in enumerate(MODEL_NAMES)}
    if model.delta0:
        i = model.index["delta_0"]
        estimates["delta_0"], std_errors["delta_0"] = float(theta[i]), float(se_theta[i])
    std_errors["q"] = q * float(se_theta[model.index["log_q"]])  # delta method
    noise = {"R": R - cpc, "innovation_variance": R, "q": q, "tau": tau, "sigma": sigma}
    if model.ar1:
        std_errors["tau"] = tau * float(se_theta[model.index["log_tau"]])
        std_errors["sigma"] = sigma * float(se_theta[model.index["log_sigma"]])
    return {"estimates": estimates, "std_errors": std_errors, "noise": noise,
            "iterations": iterations, "cpu_seconds": cpu, "converged": converged,
            "negative_log_likelihood": nll, "samples": n_used, "riccati": riccati,
            "finite_differences": fd, "fg_compensation": fg_compensation, "warmup": warmup,
            "step_halvings": halvings_total}


# ---------------------------------------------------------------------------------------------
# Data
# ---------------------------------------------------------------------------------------------
def prepare(t, delta, psi):
    """Sample interval, unwrapped heading and the initial state from the first samples."""
    t = np.asarray(t, float)
    dts = np.diff(t)
    dt = float(np.median(dts))
    if np.max(np.abs(dts - dt)) > 1e-6 * max(dt, 1.0) + 1e-9:
        print("warning: non-uniform sampling; the steady-state filter assumes the median "
              f"interval {dt:g} s", file=sys.stderr)
    psi = np.unwrap(np.asarray(psi, float))
    first = t <= t[0] + 1.0  # yaw rate from the first second's least-squares slope
    if np.count_nonzero(first) < 3:
        first = np.arange(len(t)) < 3
    r0 = float(np.polyfit(t[first] - t[0], psi[first], 1)[0])
    return {"dt": dt, "y": psi, "u": np.asarray(delta, float), "psi0": float(psi[0]), "r0": r0}


def read_csv(path, time_col, input_col, output_col, degrees):
    with open(path, newline="") as handle:
        rows = list(csv.DictReader(handle))
    cols = {name: [] for name in (time_col, input_col, output_col)}
    for row in rows:
        values = [row.get(name, "") for name in cols]
        if any(v is None or v.strip() == "" for v in values):
            continue  # rows without all three columns are skipped
        for name in cols:
            cols[name].append(float(row[name]))
    t, delta, psi = (np.array(cols[name]) for name in (time_col, input_col, output_col))
    if degrees:
        delta, psi = np.radians(delta), np.radians(psi)
    return t, delta, psi


# ---------------------------------------------------------------------------------------------
# Self test
# ---------------------------------------------------------------------------------------------
def simulate(truth, ar1, seed=1, dt=0.1, duration=600.0, q=1e-6, white_sd=0.003,
             ar1_tau=3.0, ar1_sd=0.01, periods=(40.0, 17.0, 9.0, 5.0)):
    """A record of the model with exact discrete process noise (Van Loan) and sensor noise."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, duration + 0.5 * dt, dt)
    m = len(periods)
    phases = [-math.pi * k * (k - 1) / m for k in range(1, m + 1)]  # Schroeder phases
    delta = sum(np.sin(2 * np.pi * t / T + p) for T, p in zip(periods, phases))
    delta *= np.radians(10.0) / np.max(np.abs(delta))  # peak 10 deg
    model = Model(ar1=False)
    A, B, Qc, _ = model.continuous(model.pack(truth, q))
    Phi, Gam = zoh(A, B, dt)
    L = np.linalg.cholesky(van_loan(A, Qc, dt) + 1e-30 * np.eye(3))
    x = np.zeros(3)
    psi = np.empty(len(t))
    for k in range(len(t)):
        psi[k] = x[0]
        x = Phi @ x + Gam * delta[k] + L @ rng.standard_normal(3)
    y = psi + white_sd * rng.standard_normal(len(t))
    if ar1:
        a = math.exp(-dt / ar1_tau)
        z = np.empty(len(t))
        z[0] = ar1_sd * rng.standard_normal()
        e = ar1_sd * math.sqrt(1 - a * a) * rng.standard_normal(len(t))
        for k in range(1, len(t)):
            z[k] = a * z[k - 1] + e[k]
        y = y + z
    return t, delta, y


def selftest(args):
    """Simulate a record with known parameters, fit it from 30 % off, compare with the truth.

    With the default input (periods 40 to 5 s, 0.003 rad noise) the fast pole T2 = 0.3 s and
    the zero T3 = 0.2 s are only weakly separable: the data fix about T3 - T2, and the
    likelihood has a long curved ridge in (a1, a0, b, T3) running from T2 ~ T3 to T2 -> 0
    (a1, a0, b, q -> infinity together). The linearised SE at an estimate on the ridge's
    steep end is then several times too small, the Cramer-Rao SE at the truth too small for
    an estimate out on its flat end. The test therefore reports
      * z against the reported SE (Gauss-Newton information at the estimate),
      * z against the Cramer-Rao SE at the truth (the same information matrix evaluated at
        the true parameters, noise re-estimated there),
      * the likelihood ratio of the true model parameters,
        2 (-log L at truth, noise re-estimated) - 2 (-log L at the estimate) ~ chi2(4).
    PASS: converged, every |estimate - truth| < 3 x (the larger of the two SEs), and the
    likelihood ratio below chi2(4)'s 99 % quantile. `--psi-noise 0.0005 --periods
    40,17,9,5,2.5,1.3` gives a well-identified record, on which the reported SEs alone hold.
    """
    truth = [3.833, 1.667, -0.2833, 0.2]  # T1 2 s, T2 0.3 s, K -0.17, T3 0.2 s
    q_true, tau_true, sigma_true = 1e-6, 3.0, 0.01
    periods = [float(v) for v in args.periods.split(",")]
    t, delta, y = simulate(truth, args.ar1, seed=args.seed, q=q_true, white_sd=args.psi_noise,
                           periods=periods)
    data = prepare(t, delta, y)
    start = [truth[0] * 1.3, truth[1] * 0.7, truth[2] * 1.3, truth[3] * 0.7]  # 30 % off
    model = Model(ar1=args.ar1)
    ar1_start = dict(tau=5.0, sigma=0.005) if args.ar1 else {}
    theta0 = model.pack(start, q_true * 3.0, **ar1_start)
    options = dict(riccati=args.riccati, fd=args.fd, fg_compensation=not args.no_fg_compensation,
                   warmup=not args.no_warmup)
    result = fit(data, model, theta0, args.max_iterations, verbose=args.verbose, **options)

    # Yardsticks at the truth: the noise re-estimated with the model parameters held.
    truth_ar1 = dict(tau=tau_true, sigma=sigma_true) if args.ar1 else {}
    theta_true = model.pack(truth, q_true, **truth_ar1)
    at_truth = fit(data, model, theta_true, args.max_iterations, fixed=MODEL_NAMES, **options)
    theta_t = model.pack(truth, at_truth["noise"]["q"],
                         **(dict(tau=at_truth["noise"]["tau"], sigma=at_truth["noise"]["sigma"])
                            if args.ar1 else {}))
    R_t = at_truth["noise"]["innovation_variance"]
    nu_t, _ = run_filter(model, theta_t, R_t, data, args.riccati)
    jac = sensitivities(model, theta_t, R_t, data, args.riccati, nu_t, args.fd,
                        np.arange(len(theta_t)))
    crb = np.sqrt(np.diag(np.linalg.inv(jac.T @ jac / R_t)))
    lr = 2.0 * (at_truth["negative_log_likelihood"] - result["negative_log_likelihood"])
    lr_limit = 13.28  # chi2(4) 99 % quantile

    print(f"self test (seed {args.seed}): second_order_rates, {len(t)} samples at 10 Hz, "
          f"multisine 10 deg (periods {args.periods} s), q {q_true:g}, "
          f"white psi noise {args.psi_noise:g} rad" +
          (f", AR(1) tau {tau_true:g} s SD {sigma_true:g} rad" if args.ar1 else ""))
    print(f"{'name':>6} {'truth':>10} {'start':>10} {'estimate':>10} {'SE':>9} {'z(SE)':>7} "
          f"{'CRB@truth':>10} {'z(CRB)':>7}")
    rows = [(name, tr, st, crb[i]) for i, (name, tr, st) in enumerate(zip(MODEL_NAMES, truth, start))]
    rows.append(("q", q_true, q_true * 3.0, q_true * crb[model.index["log_q"]]))
    if args.ar1:
        rows += [("tau", tau_true, 5.0, tau_true * crb[model.index["log_tau"]]),
                 ("sigma", sigma_true, 0.005, sigma_true * crb[model.index["log_sigma"]])]
    worst_se = worst_crb = worst_either = 0.0
    for name, true, st, crb_se in rows:
        est = result["estimates"].get(name, result["noise"].get(name))
        se = result["std_errors"][name]
        z_se, z_crb = (est - true) / se, (est - true) / crb_se
        worst_se, worst_crb = max(worst_se, abs(z_se)), max(worst_crb, abs(z_crb))
        worst_either = max(worst_either, min(abs(z_se), abs(z_crb)))
        print(f"{name:>6} {true:10.4g} {st:10.4g} {est:10.4g} {se:9.3g} {z_se:7.2f} "
              f"{crb_se:10.3g} {z_crb:7.2f}")
    print(f"measurement noise variance G G^T {result['noise']['R']:.4e} "
          f"(truth {args.psi_noise ** 2:.4e}), "
          f"innovation variance {result['noise']['innovation_variance']:.4e}")
    print(f"iterations {result['iterations']}, converged {result['converged']}, "
          f"-log L {result['negative_log_likelihood']:.3f} (at truth, noise re-estimated: "
          f"{at_truth['negative_log_likelihood']:.3f}), fit CPU {result['cpu_seconds']:.2f} s")
    print(f"largest |z| against the reported SE {worst_se:.2f}, against the CRB at truth "
          f"{worst_crb:.2f}, against the larger of the two {worst_either:.2f}; likelihood ratio "
          f"of the true model parameters {lr:.2f} (chi2(4) 99 %: {lr_limit})")
    ok = result["converged"] and worst_either < 3.0 and lr < lr_limit
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


# ---------------------------------------------------------------------------------------------
def finite_or_null(value):
    """The result with non-finite numbers (an unidentifiable parameter's SE) as JSON null."""
    if isinstance(value, dict):
        return {key: finite_or_null(item) for key, item in value.items()}
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--csv")
    parser.add_argument("--time", default="t")
    parser.add_argument("--input", default="delta")
    parser.add_argument("--output", default="psi")
    parser.add_argument("--degrees", action="store_true", help="psi and delta in degrees")
    parser.add_argument("--ar1", action="store_true", help="AR(1) sensor noise on psi")
    parser.add_argument("--ar1-start", default="5,0.005", help="tau [s], sigma [rad]")
    parser.add_argument("--delta0", action="store_true", help="estimate the rudder offset")
    parser.add_argument("--start", help="a1,a0,b,T3")
    parser.add_argument("--q-start", type=float, default=1e-6,
                        help="process-noise spectral density on eta2 [rad^2/s^5]")
    parser.add_argument("--max-iterations", type=int, default=50)
    parser.add_argument("--riccati", choices=["continuous", "discrete"], default="continuous",
                        help="continuous: the book's eq. 5.15 (default); discrete: exact")
    parser.add_argument("--fd", choices=["central", "forward"], default="central")
    parser.add_argument("--no-fg-compensation", action="store_true")
    parser.add_argument("--no-warmup", action="store_true",
                        help="free the noise parameters from the first iteration")
    parser.add_argument("--json")
    parser.add_argument("--selftest", action="store_true")
    parser.add_argument("--seed", type=int, default=1, help="self test's noise seed")
    parser.add_argument("--psi-noise", type=float, default=0.003,
                        help="self test's white psi noise SD [rad]")
    parser.add_argument("--periods", default="40,17,9,5",
                        help="self test's multisine periods [s]")
    parser.add_argument("--verbose", action="store_true", help="iteration log on stderr")
    args = parser.parse_args()

    if args.selftest:
        return selftest(args)
    if not args.csv or not args.start:
        parser.error("--csv and --start are required (or --selftest)")
    start = [float(v) for v in args.start.split(",")]
    if len(start) != 4:
        parser.error("--start takes a1,a0,b,T3")
    tau0, sigma0 = (float(v) for v in args.ar1_start.split(","))
    t, delta, psi = read_csv(args.csv, args.time, args.input, args.output, args.degrees)
    data = prepare(t, delta, psi)
    model = Model(ar1=args.ar1, delta0=args.delta0)
    theta0 = model.pack(start, args.q_start, tau=tau0, sigma=sigma0)
    try:
        result = fit(data, model, theta0, args.max_iterations, args.riccati, args.fd,
                     not args.no_fg_compensation, not args.no_warmup, verbose=args.verbose)
    except (Infeasible, np.linalg.LinAlgError) as error:
        result = {"converged": False, "error": f"{type(error).__name__}: {error}"}
    text = json.dumps(finite_or_null(result), indent=2, allow_nan=False)
    print(text)
    if args.json:
        with open(args.json, "w") as handle:
            handle.write(text + "\n")
    return 2 if "error" in result else 0


if __name__ == "__main__":
    sys.exit(main())
