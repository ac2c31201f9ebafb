"""point_contact: the circular EHL point contact as one call, in SI units.

Scaling (Hertz): x = a X, p = p_h P, h = (a^2/R) H with a = (3 w R/(2 E'))^(1/3) and
p_h = 3 w/(2 pi a^2); see :mod:`bearingfem.ehl.point` for the equations and the solver and
:mod:`bearingfem.ehl.pointspace` for the half-space.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.interpolate

from ..errors import ConvergenceError
from ..lubricant import Lubricant
from ..solvers.continuation import Ratios, attempt
from .contact import _positive, _pressure_laws
from .fits import FilmFit
from .point import DimensionlessPoint, solve_point

__all__ = ["PointContact", "point_contact", "HertzPoint", "hertz_point", "hamrock_dowson_point",
           "DEFAULT_POINT_NODES"]

# nodes along the rolling direction: h_c within 1-3.5 % of its mesh limit at M = 26 ... 78
# (second order; 10-30 % at 33 nodes), a few seconds with the multilevel step (docs/ehl.md)
DEFAULT_POINT_NODES = 97
COARSEST = 33                   # mesh sequencing starts on a grid of at least this many
POINT_NODES_RANGE = (17, 257)
SIDE = 2.0                      # [a] the domain spans |Y| <= SIDE
#: The load ramp from a quarter: the fraction doubles; a failed step is not retried.
LOAD_STEPS = Ratios(2.0, 2.0)


@dataclass(frozen=True)
class HertzPoint:
    """Hertz's dry circular contact: radius a [m], peak pressure p_h [Pa], approach [m]."""

    radius: float
    pressure: float
    approach: float


def hertz_point(radius: float, reduced_modulus: float, load: float) -> HertzPoint:
    """a = (3 w R/(2 E'))^(1/3), p_h = 3 w/(2 pi a^2), delta = a^2/R (Johnson 1985,
    Eqs. 4.22-4.23 with E* = E'/2)."""
    a = (3.0 * load * radius / (2.0 * reduced_modulus)) ** (1.0 / 3.0)
    return HertzPoint(a, 3.0 * load / (2.0 * math.pi * a**2), a**2 / radius)


def hamrock_dowson_point(radius, reduced_modulus, viscosity, mean_speed, load,
                         pressure_viscosity, ellipticity: float = 1.0) -> FilmFit:
    """Hamrock & Dowson (J. Lubr. Technol. 99 (1977) 264-276), fitted to their numerical
    point-contact solutions: with U = mu0 u_m/(E' R), W = w/(E' R^2), G = alpha E',
    h_c/R = 2.69 U^0.67 G^0.53 W^-0.067 (1 - 0.61 e^(-0.73 k)),
    h_min/R = 3.63 U^0.68 G^0.49 W^-0.073 (1 - e^(-0.68 k)); k = 1 is circular."""
    U = viscosity * mean_speed / (reduced_modulus * radius)
    W = load / (reduced_modulus * radius**2)
    G = pressure_viscosity * reduced_modulus
    k = ellipticity
    return FilmFit(radius * 2.69 * U**0.67 * G**0.53 * W**-0.067 * (1 - 0.61 * math.exp(-0.73 * k)),
                   radius * 3.63 * U**0.68 * G**0.49 * W**-0.073 * (1 - math.exp(-0.68 * k)))


@dataclass(frozen=True)
class PointContact:
    """A converged circular EHL point contact (SI; origin at the centre of the Hertz
    contact, rolling along +x; arrays indexed [i, j] = (x_i, y_j))."""

    x: np.ndarray                  # [m] nodes along the rolling direction, inlet first
    y: np.ndarray                  # [m] nodes across it, symmetric about 0
    pressure: np.ndarray           # [Pa] gauge film pressure, >= 0
    film: np.ndarray               # [m] film thickness h(x, y)
    film_central: float            # [m] h at the origin
    film_min: float                # [m] smallest h over the nodes
    pressure_max: float            # [Pa]
    load: float                    # [N] int int p dx dy (equals the load asked for)
    hertz_radius: float            # [m] a
    hertz_pressure: float          # [Pa] p_h
    moes_M: float                  # Moes load parameter M = W (2U)^(-3/4)
    moes_L: float                  # Moes lubricant parameter L = G (2U)^(1/4)
    iterations: int                # Newton iterations over all grids and continuation steps
    continuation_steps: int        # 1 for a cold start that converged
    residual: float                # final complementarity residual (Hertz units)


def point_contact(*, radius: float, reduced_modulus: float, lubricant: Lubricant,
                  mean_speed: float, load: float, nodes: int = DEFAULT_POINT_NODES,
                  inlet: float = -3.5, outlet: float = 1.5, tol: float = 1e-8) -> PointContact:
    """Solve the isothermal circular EHL point contact (fully flooded).

    Parameters
    ----------
    radius : reduced radius R [m] (equal in both directions), 1/R = 1/R1 + 1/R2.
    reduced_modulus : E' [Pa], 2/E' = (1 - nu1^2)/E1 + (1 - nu2^2)/E2.
    lubricant : the oil (viscosity and density laws).
    mean_speed : u_m = (u1 + u2)/2 [m/s], > 0, along x.
    load : w [N], > 0.
    nodes : nodes along x over [inlet, outlet], in [17, 257]; square cells, the y extent
        is |y| <= 2 a. An odd count lets the mesh sequence halve the cells (from >= 33
        nodes). Grids above 33 nodes take the multilevel Newton step: ~0.1 s at 33, ~3-5 s
        at 97, ~30-70 s at 193.
    inlet, outlet : domain ends in Hertz radii a (inlet <= -1.5, outlet >= 1).
    """
    R = _positive("radius", radius, "m")
    E = _positive("reduced_modulus", reduced_modulus, "Pa")
    u = _positive("mean_speed", mean_speed, "m/s")
    w = _positive("load", load, "N")
    if not isinstance(lubricant, Lubricant):
        raise ValueError(f"lubricant must be a bearingfem.Lubricant, got {type(lubricant).__name__}")
    if isinstance(nodes, bool) or not isinstance(nodes, (int, np.integer)) \
            or not POINT_NODES_RANGE[0] <= nodes <= POINT_NODES_RANGE[1]:
        raise ValueError(f"nodes must be an integer in [{POINT_NODES_RANGE[0]}, "
                         f"{POINT_NODES_RANGE[1]}], got {nodes!r}")
    if isinstance(inlet, bool) or not (isinstance(inlet, (int, float)) and math.isfinite(inlet)
                                       and inlet <= -1.5):
        raise ValueError(f"inlet must be a finite number <= -1.5 [Hertz radii], got {inlet!r}")
    if isinstance(outlet, bool) or not (isinstance(outlet, (int, float)) and math.isfinite(outlet)
                                        and outlet >= 1.0):
        raise ValueError(f"outlet must be a finite number >= 1 [Hertz radii], got {outlet!r}")
    _positive("tol", tol, "-")

    hz = hertz_point(R, E, w)
    a, ph = hz.radius, hz.pressure
    mu0, alpha = lubricant.viscosity, lubricant.pressure_viscosity
    U, W, G = mu0 * u / (E * R), w / (E * R**2), alpha * E
    film_scale = a**2 / R
    lam = 12.0 * mu0 * u * R**2 / (a**3 * ph)
    eta, rho = _pressure_laws(lubricant, ph)

    # the first film guess: Hamrock-Dowson's for a piezoviscous oil, else a rigid-like
    # film from the isoviscous lambda (H ~ lambda^(2/3) at light load)
    guess = hamrock_dowson_point(R, E, mu0, u, w, alpha).central / film_scale if alpha > 0 \
        else lam ** (2.0 / 3.0)
    # mesh sequencing: the coarsest grid (>= COARSEST nodes along x) from a cold start, each
    # finer one (twice the cells) from the coarser answer, as the line contact does
    grids = [nodes]
    while (grids[-1] + 1) // 2 >= COARSEST and grids[-1] % 2 == 1:
        grids.append((grids[-1] + 1) // 2)
    record = X_coarse = Y_coarse = None
    for n in reversed(grids):
        d = (outlet - inlet) / (n - 1)
        half = int(math.ceil(SIDE / d))
        X = inlet + d * np.arange(n)
        Y = d * np.arange(-half, half + 1)
        prob = DimensionlessPoint(X, Y, lam, eta, rho)
        if record is None:
            record, steps, iterations = _solve_with_continuation(prob, guess, tol)
        else:
            P0 = scipy.interpolate.RegularGridInterpolator(
                (X_coarse, Y_coarse), record.pressure, bounds_error=False,
                fill_value=0.0)(np.stack(np.meshgrid(X, Y, indexing="ij"), axis=-1))
            record = solve_point(prob, P0, record.approach, tol=tol)
            iterations += record.iterations
        X_coarse, Y_coarse = X, Y
    x, y = a * X, a * Y
    h, p = film_scale * record.film, ph * record.pressure
    return PointContact(
        x=x, y=y, pressure=p, film=h, film_central=float(np.interp(0.0, x, h[:, half])),
        film_min=float(h.min()), pressure_max=float(p.max()),
        load=float(p.sum() * (a * d) ** 2), hertz_radius=a, hertz_pressure=ph,
        moes_M=W * (2 * U) ** -0.75, moes_L=G * (2 * U) ** 0.25, iterations=iterations,
        continuation_steps=steps, residual=record.residual)


def _start(prob: DimensionlessPoint, f: float, H_c: float):
    """Hertz's pressure of the load fraction f (radius f^(1/3)) and H0 that leaves a
    central film H_c over Hertz's approach f^(2/3)."""
    r2 = prob.X[:, None] ** 2 + prob.Y[None, :] ** 2
    c = f ** (1.0 / 3.0)
    return c * np.sqrt(np.clip(1.0 - r2 / c**2, 0.0, None)), H_c - c**2


def _solve_with_continuation(prob, H_c, tol):
    """Cold start from Hertz; if it fails, double the load from a quarter."""
    try:
        record = solve_point(prob, *_start(prob, 1.0, H_c), tol=tol)
        return record, 1, record.iterations
    except ConvergenceError as cold:
        failure = cold
    f = 0.25
    first, _ = _attempt(prob, _start(prob, f, H_c / f**0.07), f, tol)
    if first is None:
        raise ConvergenceError("EHL point contact load continuation", 0, None,
                               f"failed at load fraction {f}; cold start: {failure}")
    walk = LOAD_STEPS.walk(lambda x, record: _attempt(prob, (record.pressure * 1.0,
                                                             record.approach), x, tol),
                           first, f, 1.0, "EHL point contact load continuation",
                           "load fraction", f"cold start: {failure}")
    return walk.state, 1 + walk.steps, first.iterations + walk.iterations


def _attempt(prob, start, f, tol):
    """(the contact at load fraction f from ``start`` = (P, H0), or None; its iterations)."""
    return attempt(solve_point, prob, *start, tol=tol, load=f)
