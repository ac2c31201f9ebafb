"""line_contact: the EHL line contact as one call, in SI units.

Scaling (Hertz): x = b X, p = p_h P, h = (b^2/R) H with b = sqrt(8 w R/(pi E')) and
p_h = 2 w/(pi b); see :mod:`bearingfem.ehl.line` for the equations and the solver.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..lubricant import Lubricant
from ..errors import ConvergenceError
from ..solvers.continuation import Ratios, attempt
from .fits import (MARTIN_LOAD, hertz_line, moes_parameters, pan_hamrock,
                   rigid_isoviscous_pressure)
from .halfspace import LineCompliance
from .line import DimensionlessLine, solve_dimensionless

__all__ = ["LineContact", "line_contact", "DEFAULT_NODES"]

# Film nodes over the default domain. The films are within ~1 % of the mesh limit from
# 1500 nodes up to Moes M ~ 100 (second order: at M = 97, L = 6.8 h_c is 1.2 % off at 1000
# nodes, 0.3 % at 2000); the outlet pressure spike needs far more: at M = 7.4, L = 10.9
# (Roelands oil) p_max is 9.9 / 5.7 / 2.8 / 1.8 / 1.1 % below its Richardson limit at
# 1500 / 3000 / 6000 / 8000 / 12000 nodes (docs/ehl.md), so the default is 8000
# (a few seconds with the multilevel Newton step).
DEFAULT_NODES = 8000
NODES_RANGE = (64, 64000)
COARSEST = 200
#: The load ramp: the fraction doubles; a failed ratio is cut to its square root, down to 1.02.
LOAD_STEPS = Ratios(2.0, 1.02)


@dataclass(frozen=True)
class LineContact:
    """A converged EHL line contact (SI units; x = 0 at the line of centres, flow along +x)."""

    x: np.ndarray                  # [m] film nodes, inlet first
    pressure: np.ndarray           # [Pa] gauge film pressure, >= 0
    film: np.ndarray               # [m] film thickness h(x)
    film_central: float            # [m] h at x = 0
    film_min: float                # [m] smallest h over the nodes
    pressure_max: float            # [Pa]
    hertz_half_width: float        # [m] b
    hertz_pressure: float          # [Pa] p_h
    moes_M: float                  # Moes load parameter M = W (2U)^(-1/2)
    moes_L: float                  # Moes lubricant parameter L = G (2U)^(1/4), G = alpha* E'
    iterations: int                # Newton iterations over all grids and continuation steps
    continuation_steps: int        # 1 for a cold start that converged
    residual: float = field(default=0.0)   # final complementarity residual (Hertz units)


def _positive(name, value, unit):
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)) \
            or not math.isfinite(value) or value <= 0:
        raise ValueError(f"{name} must be a finite number > 0 [{unit}], got {value!r}")
    return float(value)


def _pressure_laws(lubricant: Lubricant, hertz_pressure: float):
    """(eta, rho): the oil's viscosity eta/mu0 and density rho/rho0 laws of the
    dimensionless pressure P = p/p_H, each returning (value, d value / dP)."""
    mu0, ph = lubricant.viscosity, hertz_pressure

    def eta(P):
        p = ph * P
        return lubricant.viscosity_at(p) / mu0, ph * lubricant.viscosity_derivative(p) / mu0

    def rho(P):
        p = ph * P
        return lubricant.density_at(p), ph * lubricant.density_derivative(p)

    return eta, rho


def line_contact(*, radius: float, reduced_modulus: float, lubricant: Lubricant,
                 mean_speed: float, load_per_length: float, nodes: int = DEFAULT_NODES,
                 inlet: float | None = None, outlet: float | None = None,
                 tol: float = 1e-9) -> LineContact:
    """Solve the isothermal EHL line contact (fully flooded, Reynolds exit).

    Parameters
    ----------
    radius : reduced radius R [m], 1/R = 1/R1 + 1/R2.
    reduced_modulus : E' [Pa], 2/E' = (1 - nu1^2)/E1 + (1 - nu2^2)/E2.
    lubricant : the oil (viscosity and density laws).
    mean_speed : u_m = (u1 + u2)/2 [m/s], > 0 (pure rolling or sliding alike: the film
        depends on u_m only while the oil is Newtonian and isothermal).
    load_per_length : w [N/m].
    nodes : film nodes over the domain, in [64, 6000].
    inlet, outlet : domain ends in Hertz half-widths b (inlet < 0 < outlet). Default:
        -4.5 and 1.5 (Venner & Lubrecht's), stretched in proportion to the rigid film's
        length sqrt(2 R h) when the film is thick against b, so the inlet stays flooded.
    """
    R = _positive("radius", radius, "m")
    E = _positive("reduced_modulus", reduced_modulus, "Pa")
    u = _positive("mean_speed", mean_speed, "m/s")
    w = _positive("load_per_length", load_per_length, "N/m")
    if not isinstance(lubricant, Lubricant):
        raise ValueError(f"lubricant must be a bearingfem.Lubricant, got {type(lubricant).__name__}")
    if isinstance(nodes, bool) or not isinstance(nodes, (int, np.integer)) \
            or not NODES_RANGE[0] <= nodes <= NODES_RANGE[1]:
        raise ValueError(f"nodes must be an integer in [{NODES_RANGE[0]}, {NODES_RANGE[1]}], "
                         f"got {nodes!r}")
    _positive("tol", tol, "-")

    hz = hertz_line(R, E, w)
    b, ph = hz.half_width, hz.pressure
    mu0, alpha = lubricant.viscosity, lubricant.pressure_viscosity
    M, L = moes_parameters(R, E, mu0, u, w, alpha)
    film_scale = b**2 / R                                   # h = film_scale * H
    h_rigid = 2 * MARTIN_LOAD * mu0 * u * R / w
    h_guess = max(h_rigid, pan_hamrock(R, E, mu0, u, w, alpha).minimum if alpha > 0 else 0.0)
    # sqrt(2 R h)/b: the rigid film's length against Hertz's width. The rigid isoviscous
    # film needs its inlet ~25 of those lengths upstream to carry 99.6 % of Martin's load
    # (fits.rigid_isoviscous_load(-25) = 2.4387); an EHL inlet zone is far shorter.
    s = math.sqrt(2 * h_guess / film_scale)
    x_in = -max(4.5, 25.0 * s * min(s, 1.0)) if inlet is None else float(inlet)
    x_out = max(1.5, 1.5 * s) if outlet is None else float(outlet)
    if not (math.isfinite(x_in) and x_in <= -1.0):
        raise ValueError(f"inlet must be a finite number <= -1 [Hertz half-widths], got {inlet!r}")
    if not (math.isfinite(x_out) and x_out >= 1.0):
        raise ValueError(f"outlet must be a finite number >= 1 [Hertz half-widths], got {outlet!r}")

    lam = 12.0 * mu0 * u * R**2 / (b**3 * ph)
    eta, rho = _pressure_laws(lubricant, ph)

    # mesh sequencing: the coarsest grid (>= COARSEST nodes) from a cold start (with load
    # continuation if need be), each finer one (twice the nodes) from the coarser answer,
    # so Newton only has to move the cavitation front a node or two per level
    grids = [nodes]
    while grids[-1] // 2 >= COARSEST:
        grids.append(grids[-1] // 2)
    record, steps, iterations = None, 0, 0
    for n in reversed(grids):
        prob = DimensionlessLine(np.linspace(x_in, x_out, n), lam, eta, rho)
        if record is None:
            record, steps, iterations = _solve_with_continuation(prob, h_guess / film_scale, tol)
            X_coarse = prob.X
            continue
        P0 = np.interp(prob.X, X_coarse, record.pressure)
        record = solve_dimensionless(prob, P0, record.approach, tol=tol)
        iterations += record.iterations
        X_coarse = prob.X
    X = prob.X

    x = b * X
    h = film_scale * record.film
    p = ph * record.pressure
    return LineContact(
        x=x, pressure=p, film=h, film_central=float(np.interp(0.0, x, h)),
        film_min=float(h.min()), pressure_max=float(p.max()), hertz_half_width=b,
        hertz_pressure=ph, moes_M=M, moes_L=L, iterations=iterations,
        continuation_steps=steps, residual=record.residual)


def _start(prob: DimensionlessLine, load: float, H_min: float):
    """A first (P, H0) for the load fraction: Hertz's pressure with H0 putting the film's
    minimum at H_min when Hertz's width is resolved and the film is thin against it;
    otherwise the rigid isoviscous pressure of a film H_min (a zero pressure would leave
    the Jacobian singular: the wedge term does not see H0)."""
    X, dx = prob.X, prob.X[1] - prob.X[0]
    P = np.sqrt(np.clip(1.0 - X**2 / load, 0.0, None))     # Hertz half-width sqrt(load)
    if np.count_nonzero(P) < 8 or 2 * H_min > 4 * load:
        width = math.sqrt(2 * H_min)                           # sqrt(2 R h0) / b
        P = rigid_isoviscous_pressure(X / width, X[0] / width)[0]
        H0 = H_min
    else:
        H0 = None
    P *= (load * np.pi / 2) / max(dx * P.sum(), np.finfo(float).tiny)
    if H0 is None:
        shape = X**2 / 2 + LineCompliance(X.size, dx).deflection(P)
        H0 = H_min - shape.min()
    return P, H0


def _solve_with_continuation(prob, H_guess, tol):
    """Cold start from Hertz; if it fails, ramp the load up from a light one."""
    P, H0 = _start(prob, 1.0, H_guess)
    try:
        record = solve_dimensionless(prob, P, H0, tol=tol)
        return record, 1, record.iterations
    except ConvergenceError as cold:
        failure = cold
    # continuation in load: in the target's Hertz units a load fraction f only changes the
    # load balance (dX sum P = f pi/2), so each converged state starts the next
    # (the film thickens as w^-0.13 in EHL, as 1/w when rigid: the first guess takes 1/sqrt).
    # The lightest start: f = 1/4, else a quarter of that, ... down to 1e-4.
    f = 0.25
    first, _ = _attempt(prob, _start(prob, f, H_guess / math.sqrt(f)), f, tol)
    while first is None:
        f /= 4
        if f < 1e-4:
            raise ConvergenceError("EHL line contact load continuation", 0, None,
                                   f"no load fraction down to {4 * f:.3g} converges from "
                                   f"Hertz; cold start: {failure}")
        first, _ = _attempt(prob, _start(prob, f, H_guess / math.sqrt(f)), f, tol)
    walk = LOAD_STEPS.walk(lambda x, record: _attempt(prob, (record.pressure, record.approach),
                                                      x, tol),
                           first, f, 1.0, "EHL line contact load continuation",
                           "load fraction", f"cold start: {failure}")
    return walk.state, 1 + walk.steps, first.iterations + walk.iterations


def _attempt(prob, start, f, tol):
    """(the film at load fraction f from ``start`` = (P, H0), or None; its iterations)."""
    return attempt(solve_dimensionless, prob, *start, tol=tol, load=f)
