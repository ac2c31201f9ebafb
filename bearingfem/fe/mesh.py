"""The unwrapped film as a finite-element mesh in (theta, zeta = z/R).

theta spans one turn from ``theta0``: periodic when there is no supply line, otherwise the
supply line sits at both theta ends and holds ambient pressure. zeta spans the whole length
[-L/D, L/D] or, exploiting the symmetry of an aligned journal, the half [0, L/D] with a
natural (zero-flux) condition on the mid-plane.

With axial grooves every groove edge is a grid line: the n_theta cells are shared among the
arcs between consecutive edges in proportion to their length (uniform within each arc), so
grooves of any width and position are resolved exactly and the film converges at the
element's order on any n_theta. (Edges snapped to a uniform grid move by up to half a cell:
a first-order error in the groove's width.)

A ``grading`` (focus, strength) sizes the theta cells like the gap of a journal at
eccentricity ``strength`` whose minimum film is at the mesh angle ``focus``: cell width
proportional to 1 - strength cos(theta - focus), both in the cells' share per arc and
within each arc (a heavily loaded film's pressure peak is narrow where the film is thin).
A zero strength is the uniform mesh, bit for bit. The grooved film's bearing-fixed mesh
takes the focus it is given; the plain film, meshed in the film frame, is graded toward
its least film (:data:`LEAST_FILM`), which stays put whatever the journal's state.
"""
from __future__ import annotations

import logging
import math
from contextlib import contextmanager
from dataclasses import dataclass

import numpy as np
from skfem import Basis, ElementTriP1, ElementTriP2, MeshTri1, MeshTri1DG

from ..caches import cached
from ..validation import MIN_N_THETA, MIN_N_Z

__all__ = ["FilmMesh", "film_mesh", "ELEMENTS", "MIN_N_THETA", "MIN_N_Z", "LEAST_FILM",
           "check_grading", "GRADING_MAX"]

ELEMENTS = {"P1": ElementTriP1, "P2": ElementTriP2}
#: The film angle of the least film, where h = c (1 + eps cos theta) is smallest [rad]
LEAST_FILM = math.pi
#: The largest grading strength taken (cells 1 - s cos: at 0.99 the finest is 1/199 of
#: the coarsest)
GRADING_MAX = 0.99


def check_grading(grading, angle: bool | None = None):
    """A grading as the film routes take it: None; a strength alone (a float in [0,
    0.99]: a film meshed in the film frame, its cells concentrated toward its least
    film); or (angle, strength) as floats (the cells concentrated toward the inertial
    angle [rad]: the grooved film's bearing-fixed mesh, or a film-frame mesh at that
    angle's film angle). ``angle`` True asks for the pair (None: either). ValueError
    naming ``grading`` otherwise."""
    if grading is None:
        return None
    pair = "(angle [rad], strength in [0, 0.99])"
    lone = "a strength in [0, 0.99]"
    allowed = pair if angle else f"{lone} or {pair}"
    message = f"grading must be None or {allowed}, got {grading!r}"
    if isinstance(grading, (int, float, np.integer, np.floating)) and \
            not isinstance(grading, bool):
        if angle:
            raise ValueError(message + " (a grooved film's mesh is fixed in the bearing: "
                             "give the angle of its least film too)")
        strength = float(grading)
        if not 0.0 <= strength <= GRADING_MAX:
            raise ValueError(message)
        return strength
    try:
        if isinstance(grading, (str, bytes)):     # "00" would unpack as (0, 0)
            raise TypeError
        a, strength = (float(v) for v in grading)
    except (TypeError, ValueError):
        raise ValueError(message) from None
    if not (math.isfinite(a) and 0.0 <= strength <= GRADING_MAX):
        raise ValueError(message)
    return a, strength


@dataclass(frozen=True, eq=False)
class FilmMesh:
    """A scikit-fem basis on the unwrapped film with its boundary dof sets.

    Attributes
    ----------
    basis : scikit-fem ``CellBasis``
    fixed : indices of dofs held at ambient pressure (axial ends, supply line)
    free : the remaining dofs
    end : dofs on the axial end(s), where side leakage leaves
    theta, zeta : dof coordinates (theta in [theta0, theta0 + 2 pi], zeta = z/R)
    half : True when only zeta >= 0 is meshed (results are doubled)
    n_theta, n_z, length_ratio, theta0, arcs : the arguments the mesh was built from
    """

    basis: object
    fixed: np.ndarray
    free: np.ndarray
    end: np.ndarray
    theta: np.ndarray
    zeta: np.ndarray
    half: bool
    periodic: bool
    n_theta: int
    n_z: int
    length_ratio: float
    theta0: float | None
    grooves: tuple = ()        # dof indices held at each groove's pressure, one array each
    arcs: tuple = ()           # the grooves' (start, end) film angles
    grading: tuple | None = None   # (focus, strength) of the theta cells (module docstring)

    @property
    def ndofs(self) -> int:
        return self.basis.N

    @property
    def axes(self):
        """(theta, zeta) grid lines of the tensor mesh the elements were built on."""
        return _axes(self.n_theta, self.n_z, self.length_ratio, self.theta0, self.half,
                     self.arcs, self.grading)


@contextmanager
def quiet_skfem():
    """scikit-fem logs that it copies large coordinate arrays to C order: harmless here."""
    log = logging.getLogger("skfem")
    level = log.level
    log.setLevel(logging.ERROR)
    try:
        yield
    finally:
        log.setLevel(level)


def _axis(n: int, lo: float, hi: float) -> np.ndarray:
    return np.linspace(lo, hi, n + 1)


def _edges(t_lo: float, arcs) -> np.ndarray:
    """The grooves' edges as offsets in (0, 2 pi) from the mesh's first line, sorted."""
    turn = 2.0 * np.pi
    rel = np.mod(np.asarray(arcs, float).ravel() - t_lo, turn)
    rel = np.unique(np.round(rel, 12))
    return rel[(rel > 1e-9) & (rel < turn - 1e-9)]


def _cells_per_arc(n: int, lengths: np.ndarray) -> np.ndarray:
    """n cells shared among arcs in proportion to their lengths, at least one each
    (largest remainders first; ties to the earlier arc)."""
    ideal = n * lengths / lengths.sum()
    cells = np.maximum(1, np.floor(ideal)).astype(int)
    order = np.argsort(-(ideal - cells), kind="stable")
    while cells.sum() < n:      # at most len(lengths) passes
        k = n - cells.sum()
        cells[order[:k]] += 1
    while cells.sum() > n:      # only where the floor of one was raised to one
        big = np.flatnonzero(cells > 1)
        cells[big[np.argmin((ideal - cells)[big])]] -= 1
    return cells


def _graded_axis(n_theta: int, t_lo: float, arcs, grading) -> np.ndarray:
    """The grid lines of a ``grading`` (focus, strength): the arcs' breaks mapped to the
    cumulative cell density 1 / (1 - strength cos(theta - focus)) (exact integral), the
    cells shared by it and spaced uniformly in it within each arc."""
    focus, s = grading
    turn = 2.0 * np.pi
    breaks = np.concatenate([[0.0], _edges(t_lo, arcs), [turn]]) if arcs else \
        np.array([0.0, turn])
    if n_theta < len(breaks) - 1:
        raise ValueError(f"n_theta must be >= {len(breaks) - 1} (one cell per arc between "
                         f"groove edges), got {n_theta}")
    # the density's integral from the focus: 2/sqrt(1-s^2) atan(sqrt((1+s)/(1-s)) tan(x/2))
    # made continuous over the turn; inverted on a fine table (monotone)
    k, r = 2.0 / np.sqrt(1.0 - s * s), np.sqrt((1.0 + s) / (1.0 - s))

    def cdf(x):
        u = t_lo + x - focus
        return k * (np.arctan(r * np.tan(0.5 * u - np.pi * np.round(u / turn))) +
                    np.pi * np.round(u / turn))
    x = np.linspace(0.0, turn, 64 * n_theta + 1)
    c = cdf(x)
    c = np.maximum.accumulate(c)        # round-off at the atan's branch points
    w = np.interp(breaks, x, c)
    cells = _cells_per_arc(n_theta, np.diff(w))
    parts = [np.interp(np.linspace(a, b, m + 1)[:-1], c, x)
             for a, b, m in zip(w[:-1], w[1:], cells)]
    parts = [np.concatenate([[lo], p[1:]]) for lo, p in zip(breaks[:-1], parts)]
    return t_lo + np.concatenate(parts + [[turn]])


def _theta_axis(n_theta: int, t_lo: float, arcs, grading=None) -> np.ndarray:
    """Grid lines over one turn from t_lo with a line on every groove edge."""
    turn = 2.0 * np.pi
    if grading is not None and grading[1] > 0.0:   # a zero strength: the uniform axis
        return _graded_axis(n_theta, t_lo, arcs, grading)
    if not arcs:
        return _axis(n_theta, t_lo, t_lo + turn)
    breaks = np.concatenate([[0.0], _edges(t_lo, arcs), [turn]])
    if n_theta < len(breaks) - 1:
        raise ValueError(f"n_theta must be >= {len(breaks) - 1} (one cell per arc between "
                         f"groove edges), got {n_theta}")
    cells = _cells_per_arc(n_theta, np.diff(breaks))
    parts = [np.linspace(a, b, k + 1)[:-1] for a, b, k in zip(breaks[:-1], breaks[1:], cells)]
    return t_lo + np.concatenate(parts + [[turn]])


def _axes(n_theta, n_z, length_ratio, theta0, half, arcs=(), grading=None):
    t_lo = 0.0 if theta0 is None else float(theta0)
    th = _theta_axis(n_theta, t_lo, arcs, grading)
    lam = float(length_ratio)
    ze = _axis(max(1, -(-n_z // 2)), 0.0, lam) if half else _axis(n_z, -lam, lam)
    return th, ze


def _mirrored_tensor(th: np.ndarray, ze: np.ndarray) -> MeshTri1:
    """Tensor mesh of triangles whose diagonals are mirrored in the mid-plane: cells
    below zeta = 0 take the other diagonal, so a whole-length mesh with an even number of
    axial cells is symmetric in z (a tilted film and its mirror image are solved on the
    same mesh; an aligned film's moment vanishes to round-off)."""
    mesh = MeshTri1.init_tensor(th, ze)
    t = mesh.t.copy()
    nt = t.shape[1] // 2
    a, c, d, b = (t[0, :nt].copy(), t[1, :nt].copy(), t[2, :nt].copy(), t[1, nt:].copy())
    below = mesh.p[1, a] + mesh.p[1, d] < 0.0          # cell centre below the mid-plane
    t[:, :nt][:, below] = np.vstack([a, b, c])[:, below]
    t[:, nt:][:, below] = np.vstack([b, d, c])[:, below]
    return MeshTri1(mesh.p, t)


@cached(maxsize=32)
def film_mesh(n_theta: int, n_z: int, element: str, length_ratio: float,
              theta0: float | None = None, half: bool = True, arcs: tuple = (),
              grading: tuple | None = None) -> FilmMesh:
    """Build (and cache) the film mesh.

    Parameters
    ----------
    n_theta : cells around the circumference
    n_z : cells along the whole length L (the half domain gets ceil(n_z / 2))
    element : "P1" or "P2"
    length_ratio : L/D, the half length in units of R
    theta0 : None for a fully periodic film; otherwise the film angle of a supply line
        (with grooves: the first groove's start, so that its edge is a mesh line)
    half : mesh only zeta >= 0
    arcs : ((start, end), ...) film angles of axial grooves; their dofs are fixed. Every
        edge is a mesh line: the cells are graded per arc between edges (module docstring)
    grading : None (uniform per arc) or (focus, strength): theta cells sized like
        1 - strength cos(theta - focus), focus in the mesh's angle [rad], strength in [0, 1)
    """
    lam = float(length_ratio)
    th, ze = _axes(n_theta, n_z, lam, theta0, half, arcs, grading)
    with quiet_skfem():
        mesh = _mirrored_tensor(th, ze)
        if theta0 is None:      # as MeshTri1DG.init_tensor(th, ze, periodic=[0])
            lo = mesh.nodes_satisfying(lambda x: x[0] == th.min())
            hi = mesh.nodes_satisfying(lambda x: x[0] == th.max())
            ix, uniq = np.unique(lo, return_index=True)
            mesh = MeshTri1DG.periodic(mesh, ix, hi[uniq])
        basis = Basis(mesh, ELEMENTS[element](), intorder=4 if element == "P1" else 6)
    x = basis.doflocs
    # Select boundary dofs by their coordinates: get_dofs(lambda) misses dofs on periodic
    # meshes (scikit-fem 12), so the count is tested in tests/test_mesh.py.
    tol = 1e-9 * max(1.0, lam)
    end = np.flatnonzero(np.isclose(np.abs(x[1]), lam, rtol=0.0, atol=tol))
    fixed = end
    if theta0 is not None:
        supply = np.flatnonzero(np.isclose(x[0], th[0], atol=1e-9)
                                | np.isclose(x[0], th[-1], atol=1e-9))
        fixed = np.union1d(end, supply)
    grooves = []
    for lo, hi in arcs:        # dofs on [lo, hi], whose edges are mesh lines
        rel = np.mod(x[0] - lo, 2.0 * np.pi)
        rel = np.where(rel > 2.0 * np.pi - 1e-9, 0.0, rel)
        grooves.append(np.flatnonzero(rel <= np.mod(hi - lo, 2.0 * np.pi) + 1e-9))
        fixed = np.union1d(fixed, grooves[-1])
    free = np.setdiff1d(np.arange(basis.N), fixed)
    return FilmMesh(basis=basis, fixed=fixed, free=free, end=end,
                    theta=np.array(x[0]), zeta=np.array(x[1]), half=half,
                    periodic=theta0 is None, n_theta=n_theta, n_z=n_z, length_ratio=lam,
                    theta0=theta0, grooves=tuple(grooves), arcs=tuple(arcs), grading=grading)
