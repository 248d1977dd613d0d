"""The fit: scipy.optimize.least_squares on the equation error, uncertainties from its Jacobian, and
the parameters the bag cannot identify (flat directions), which keep their nominal value.

1. Weights: each of the six equations is divided by a robust scale of its residual (1.4826 x the
   median absolute deviation, at least a third of the RMS, at most 100 x the weight of a sibling) at
   the nominal parameters, then after a first fit (so forces [N] and moments [N m] count alike).
   The linear least-squares solution is computed exactly (lsq_linear, bvls), then the soft_l1 loss
   with f_scale 3 is minimised from it, so a few samples far off the model (a contact with a wall or
   the anchor, a navigation jump) do not drag the fit.
2. Uncertainty: covariance s^2 (J^T J)^-1 of the weighted problem (inverted on its unit-diagonal form
   with floored eigenvalues, _inverse), s^2 the residual variance per
   degree of freedom; the residuals of neighbouring samples are correlated by the Savitzky-Golay
   window, so s^2 is multiplied by the window's length in samples (one independent sample per window).
3. Flat directions: a parameter whose 1-sigma exceeds its tolerance (TOLERANCE below: half of the
   accuracy the identification promises) is fixed at its nominal value, the worst first, and the fit
   is repeated until every free parameter meets its tolerance.
"""

from types import SimpleNamespace

import numpy as np
from scipy.optimize import least_squares, lsq_linear

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
        return 0.01  # [kg]
    if name.startswith("cog_"):
        return 0.001  # [m]
    if name.startswith("thrust_gain"):
        return 0.05 * max(abs(value), abs(nominal))
    if name == "added_mass":
        return 0.05 * (physics.hydro.mass + max(value, nominal))  # of the mass the engine integrates
    if name.startswith("added_inertia"):
        k = DOF.index(name.split("_")[-1]) - 3
        return 0.05 * (physics.hydro.inertia[k] + max(value, nominal))
    k = DOF.index(name.split("_")[-1])
    if name.startswith("damping_quadratic"):
        return 0.05 * max(abs(value), abs(nominal))
    # linear damping: 5 % of the damping felt at the mission's RMS speed in that DOF (linear + quadratic)
    speed = signals.v[:, k] if k < 3 else signals.w[:, k - 3]
    rms = float(np.sqrt(np.mean(speed**2)))
    return 0.05 * max(abs(value), abs(nominal), physics.hydro.quadratic_damping[k] * rms)


class Fit:
    """Result: x (all parameters), sigma (nan where fixed), free mask, unidentifiable names, residual RMS."""

    def __init__(self, x, sigma, free, unidentifiable, dropped_sigma, rms, rms_nominal, weights, problem):
        self.x, self.sigma, self.free, self.unidentifiable = x, sigma, free, unidentifiable
        self.dropped_sigma, self.rms, self.rms_nominal, self.weights = dropped_sigma, rms, rms_nominal, weights
        self.problem = problem


SCALE_FLOOR_RATIO = 0.01  # smallest residual scale of a degree of freedom, relative to its siblings' largest
F_SCALE = 3.0  # soft_l1 loss: weighted residuals beyond ~3 robust sigmas (a bump, a contact) count less


def _robust_scale(r):
    """Per-column 1.4826 x median absolute deviation of residual rows (a robust standard deviation), at
    least a third of the RMS: a robot at rest for most of a bag has a near-zero median residual in
    the degrees of freedom that only move now and then (roll and pitch: the pendulum step), and a
    scale from the quiet samples alone would make every sample of the step an outlier of the robust
    loss, leaving the centre of gravity's height without support."""
    mad = 1.4826 * np.median(np.abs(r - np.median(r, axis=0)), axis=0)
    scale = np.maximum(mad, np.sqrt(np.mean(r**2, axis=0)) / 3.0)
    # a degree of freedom the mission never moves (the roll of a robot with its centre of gravity on
    # the axis) has a residual of rounding size: its weight is capped at SCALE_FLOOR_RATIO^-1 times that
    # of the best-fitting sibling (forces among forces, moments among moments), so that its rows do
    # not make the parameters of that degree of freedom look exactly known
    for rows in (slice(0, 3), slice(3, 6)):
        scale[rows] = np.maximum(scale[rows], SCALE_FLOOR_RATIO * scale[rows].max())
    return np.maximum(scale, 1e-12)


def _solve(problem, x0, free, weights, max_nfev=200, loss="soft_l1"):
    fixed_part = problem.A[:, :, ~free] @ x0[~free] + problem.c
    A_free = (problem.A[:, :, free] * weights[None, :, None]).reshape(-1, free.sum())

    def fun(xf):
        return A_free @ xf + (fixed_part * weights).ravel()

    lb, ub = LOWER[free], np.full(free.sum(), np.inf)
    # the plain least-squares solution first, exactly (the problem is linear: bounded-variable least
    # squares; an iterative trust-region solve can stop far from it on this badly scaled problem),
    # then the robust loss from there
    b = -(fixed_part * weights).ravel()
    norms = np.maximum(np.linalg.norm(A_free, axis=0), 1e-300)
    lin = lsq_linear(A_free / norms, b, bounds=(lb * norms, ub), method="bvls")
    x_lin = np.clip(lin.x / norms, lb, ub)
    sol = SimpleNamespace(x=x_lin, fun=fun(x_lin))
    if loss != "linear":
        sol = least_squares(
            fun,
            np.clip(sol.x, lb + 1e-12, ub),
            jac=lambda xf: A_free,
            bounds=(lb, ub),
            x_scale="jac",
            max_nfev=max_nfev,
            method="trf",
            loss=loss,
            f_scale=F_SCALE,
        )
    x = x0.copy()
    x[free] = sol.x
    return x, sol, A_free


def _sigma(sol, A_free, window):
    """1-sigma of the free parameters: Gauss-Newton covariance on the samples the robust loss keeps
    (|weighted residual| <= 3 f_scale), residual variance per degree of freedom x window samples."""
    r = sol.fun
    inlier = np.abs(r) <= 3.0 * F_SCALE
    J = A_free[inlier]
    dof = max(1, int(inlier.sum()) - A_free.shape[1])
    s2 = float(r[inlier] @ r[inlier]) / dof * window
    return np.sqrt(np.clip(np.diag(_inverse(J.T @ J)) * s2, 0.0, None))


def _inverse(info, condition=1e12):
    """Inverse of the information matrix J^T J, computed on its unit-diagonal form (the columns differ
    by orders of magnitude: N/(N s^2/m^2) beside N/m) with the eigenvalues floored at 1/condition of
    the largest. A direction the data do not see gets a huge variance, never zero: np.linalg.pinv
    would drop it and report the parameters along it as exactly known."""
    d = 1.0 / np.sqrt(np.maximum(np.diag(info), 1e-300))
    lam, V = np.linalg.eigh(info * d[:, None] * d[None, :])
    lam = np.maximum(lam, lam.max() / condition)
    return (V / lam) @ V.T * d[:, None] * d[None, :]


def identify(signals, physics, nominal, fixed=(), progress=None):
    """Fit the parameters (all but `fixed` names) to the signals; returns a Fit."""
    problem = EquationError(signals, physics)
    r0 = problem.residual(nominal)
    weights = 1.0 / _robust_scale(r0)
    free = np.ones(len(PARAMS), bool)
    for name in fixed:
        free[INDEX[name]] = False
    x, _, _ = _solve(problem, nominal, free, weights)
    if progress:
        progress(1)
    r1 = problem.residual(x)
    weights = 1.0 / _robust_scale(r1)
    unidentifiable, dropped_sigma = [], {}
    while True:
        x, sol, A_free = _solve(problem, nominal, free, weights)
        if progress:
            progress(1)
        sig = np.full(len(PARAMS), np.nan)
        sig[free] = _sigma(sol, A_free, signals.window)
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
    return Fit(x, sig, free, unidentifiable, dropped_sigma, rms, np.sqrt(np.mean(r0**2, axis=0)), weights, problem)
