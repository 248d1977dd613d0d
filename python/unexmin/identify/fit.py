"""The fit: scipy.optimize.least_squares on the equation error, uncertainties from its Jacobian, and
the parameters the bag cannot identify (flat directions), which keep their nominal value.

1. Weights: each of the six equations is divided by its residual RMS at the nominal parameters, then
   by the RMS of a first fit (so forces [N] and moments [N m] count alike).
2. Uncertainty: covariance s^2 (J^T J)^-1 of the weighted problem, s^2 the residual variance per
   degree of freedom; the residuals of neighbouring samples are correlated by the Savitzky-Golay
   window, so s^2 is multiplied by the window's length in samples (one independent sample per window).
3. Flat directions: a parameter whose 1-sigma exceeds its tolerance (TOLERANCE below: half of the
   accuracy the identification promises) is fixed at its nominal value, the worst first, and the fit
   is repeated until every free parameter meets its tolerance.
"""

import numpy as np
from scipy.optimize import least_squares

from unexmin.identify.model import DOF, INDEX, PARAMS, EquationError

# Lower bounds (the physics): damping and added mass >= 0, thrust gains > 0.
LOWER = np.full(len(PARAMS), -np.inf)
for _name in PARAMS:
    if _name.startswith(("damping_", "added_")):
        LOWER[INDEX[_name]] = 0.0
    if _name.startswith("thrust_gain"):
        LOWER[INDEX[_name]] = 0.05


def tolerance(name, value, nominal, physics, signals):
    """1-sigma a parameter must reach to count as identified: half of the promised accuracy."""
    if name == "buoyancy_kg":
        return 0.01                                   # [kg]
    if name.startswith("cog_"):
        return 0.001                                  # [m]
    if name.startswith("thrust_gain"):
        return 0.05 * max(abs(value), abs(nominal))
    if name == "added_mass":
        return 0.05 * (physics.mass + max(value, nominal))   # of the mass the engine integrates
    if name.startswith("added_inertia"):
        k = DOF.index(name.split("_")[-1]) - 3
        return 0.05 * (physics.inertia[k] + max(value, nominal))
    k = DOF.index(name.split("_")[-1])
    if name.startswith("damping_quadratic"):
        return 0.05 * max(abs(value), abs(nominal))
    # linear damping: 5 % of the damping felt at the mission's RMS speed in that DOF (linear + quadratic)
    speed = signals.v[:, k] if k < 3 else signals.w[:, k - 3]
    rms = float(np.sqrt(np.mean(speed ** 2)))
    return 0.05 * max(abs(value), abs(nominal), physics.quadratic_damping[k] * rms)


class Fit:
    """Result: x (all parameters), sigma (nan where fixed), free mask, unidentifiable names, residual RMS."""

    def __init__(self, x, sigma, free, unidentifiable, dropped_sigma, rms, rms_nominal, weights, problem):
        self.x, self.sigma, self.free, self.unidentifiable = x, sigma, free, unidentifiable
        self.dropped_sigma, self.rms, self.rms_nominal, self.weights = dropped_sigma, rms, rms_nominal, weights
        self.problem = problem


def _solve(problem, x0, free, weights, max_nfev=200):
    fixed_part = problem.A[:, :, ~free] @ x0[~free] + problem.c
    A_free = (problem.A[:, :, free] * weights[None, :, None]).reshape(-1, free.sum())

    def fun(xf):
        return A_free @ xf + (fixed_part * weights).ravel()

    lb, ub = LOWER[free], np.full(free.sum(), np.inf)
    start = np.clip(x0[free], lb + 1e-12, ub)
    sol = least_squares(fun, start, jac=lambda xf: A_free, bounds=(lb, ub), x_scale="jac", max_nfev=max_nfev,
                        method="trf")
    x = x0.copy()
    x[free] = sol.x
    return x, sol


def _sigma(sol, n_free, window):
    r = sol.fun
    dof = max(1, r.size - n_free)
    s2 = float(r @ r) / dof * window
    jtj = sol.jac.T @ sol.jac
    try:
        cov = np.linalg.pinv(jtj) * s2
    except np.linalg.LinAlgError:
        return np.full(n_free, np.inf)
    return np.sqrt(np.clip(np.diag(cov), 0.0, None))


def identify(signals, physics, nominal, fixed=(), progress=None):
    """Fit the parameters (all but `fixed` names) to the signals; returns a Fit."""
    problem = EquationError(signals, physics)
    r0 = problem.residual(nominal)
    weights = 1.0 / np.maximum(np.sqrt(np.mean(r0 ** 2, axis=0)), 1e-9)
    free = np.ones(len(PARAMS), bool)
    for name in fixed:
        free[INDEX[name]] = False
    x, _ = _solve(problem, nominal, free, weights)
    if progress:
        progress(1)
    r1 = problem.residual(x)
    weights = 1.0 / np.maximum(np.sqrt(np.mean(r1 ** 2, axis=0)), 1e-9)
    unidentifiable, dropped_sigma = [], {}
    while True:
        x, sol = _solve(problem, nominal, free, weights)
        if progress:
            progress(1)
        sig = np.full(len(PARAMS), np.nan)
        sig[free] = _sigma(sol, int(free.sum()), signals.window)
        ratio = np.full(len(PARAMS), 0.0)
        for i in np.flatnonzero(free):
            ratio[i] = sig[i] / tolerance(PARAMS[i], x[i], nominal[i], physics, signals)
        worst = int(np.argmax(ratio))
        if ratio[worst] <= 1.0 or free.sum() <= 1:
            break
        free[worst] = False
        unidentifiable.append(PARAMS[worst])
        dropped_sigma[PARAMS[worst]] = float(sig[worst])
        x = x.copy()
    x[~free] = nominal[~free]
    rms = np.sqrt(np.mean(problem.residual(x) ** 2, axis=0))
    return Fit(x, sig, free, unidentifiable, dropped_sigma, rms, np.sqrt(np.mean(r0 ** 2, axis=0)), weights, problem)
