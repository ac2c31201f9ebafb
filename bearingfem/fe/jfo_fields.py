"""The film the JFO balance sees on the nodes' control volumes: the rigid cylinder or any
gap, viscosity and density fields (:mod:`bearingfem.fields`), with a tilt.

The balance of :mod:`bearingfem.fe.jfo` needs, per control volume, the content of the
full film int rho H, the Couette content crossing its downstream face int rho H dzeta,
the squeeze int d(rho H)/dt and, for the Poiseuille flow, the stiffness of
-div(rho H^3/mu grad P) (the general assembly's, :func:`~bearingfem.fe.general.film_system`:
one owner of the Reynolds terms). The JFO equation on fields reads

    div(rho H^3/mu grad P) = 6 w d(rho phi H)/dtheta + 12 d(rho phi H)/dt.

For the rigid cylinder H = 1 + eps cos(theta) these integrals are exact
(:func:`~bearingfem.film.film_thickness_integral`). On fields the integrals are split: the
rigid cylinder of the state, exact as on the fast path, plus the departure of the fields
from it by Gauss quadrature (``GAUSS`` points on each half of a volume, in each
direction: the halves end at the node, where a nodal field has its kinks). So the rigid
cylinder given as fields is the fast path's balance to round-off (its departure is zero),
and a smooth departure is integrated to round-off too (3-point Gauss on a half cell of
pi/60 errs by ~h^7/2e6 of its size). With a density field the flows are mass flows over
the reference density rho0.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..bearing import Bearing, JournalState
from ..fields import FilmFields, check_tilt, tilted_gap, to_nodes
from ..film import film_thickness
from .assembly import FilmOperator
from .general import film_system, general_film
from .jfo_balance import full_content, cos_integral, film_volumes
from .multilevel import prolongation
from .volumes import ControlVolumes, transport_matrix

__all__ = ["BalanceFilm", "FilmSpec", "rigid_balance_film", "field_balance_film",
           "balance_films", "GAUSS"]

#: Gauss points on each half of a control volume, per direction.
GAUSS = 3

FIELD_NAMES = ("gap", "gap_rate", "viscosity", "density", "density_rate")


@dataclass(frozen=True, eq=False)
class BalanceFilm:
    """The film of one JFO balance on a P1 mesh (dimensionless, per node).

    Attributes
    ----------
    values : Poiseuille stiffness on the operator's pattern, -div(rho H^3/mu grad P)
    content : int rho H over each control volume (its content when full)
    face : int rho H over each volume's downstream theta face (d zeta)
    squeeze : int d(rho H)/dt over each volume [1/s] (the steady film's storage)
    fields : the fields at the element quadrature points (None: the rigid cylinder)
    gap : nodal H (None: the rigid cylinder)
    """

    values: np.ndarray
    content: np.ndarray
    face: np.ndarray
    squeeze: np.ndarray
    fields: FilmFields | None = None
    gap: np.ndarray | None = None

    def transport(self, cv: ControlVolumes, speed: float) -> sp.csr_matrix:
        """Upwind transport of 6 x speed x rho phi H across the volumes' theta faces."""
        return transport_matrix(cv, 6.0 * speed * self.face)


def rigid_balance_film(op: FilmOperator, state: JournalState) -> BalanceFilm:
    """The rigid cylinder's film of ``state`` (exact integrals)."""
    cv = film_volumes(op.mesh)
    return BalanceFilm(values=op.values(state.eps), content=full_content(cv, state.eps),
                       face=film_thickness(cv.face, state.eps) * cv.width,
                       squeeze=state.eps_dot * cos_integral(cv))


def halves(lo, node, hi):
    """Gauss points and weights (nodes x 2 GAUSS) of [lo, node] and [node, hi]."""
    x, w = np.polynomial.legendre.leggauss(GAUSS)
    pts, wts = [], []
    for a, b in ((lo, node), (node, hi)):
        pts.append(0.5 * (a + b)[:, None] + 0.5 * (b - a)[:, None] * x)
        wts.append(0.5 * (b - a)[:, None] * w)
    return np.hstack(pts), np.hstack(wts)


def zeta_extent(op: FilmOperator, cv: ControlVolumes):
    """(lower, node, upper) zeta of each control volume."""
    ze = op.mesh.axes[1]
    j = cv.row
    node = ze[j]
    lo = np.where(j > 0, 0.5 * (ze[np.maximum(j - 1, 0)] + node), node)
    hi = np.where(j < len(ze) - 1, 0.5 * (ze[np.minimum(j + 1, len(ze) - 1)] + node), node)
    return lo, node, hi


class _Departure:
    """The fields (and tilt) less the rigid cylinder of ``state`` at given points."""

    def __init__(self, bearing, op, state, spec: FilmFields, tilt, tilt_rate, profile=None):
        self.bearing, self.op, self.state, self.spec = bearing, op, state, spec
        self.tilt, self.tilt_rate, self.profile = tilt, tilt_rate, profile
        self.nodal = any(np.ndim(getattr(spec, n)) in (1, 2) and not callable(getattr(spec, n))
                         for n in FIELD_NAMES)

    def __call__(self, theta, zeta):
        """(rho H - H_rigid, d(rho H)/dt - dH_rigid/dt) at the points."""
        op, s = self.op, self.state
        interp = (prolongation(op.mesh, theta.ravel(), zeta.ravel()) if self.nodal
                  else None)
        f = self.spec.at_points(op, s, theta, zeta, interp)
        H, rate = f.gap, f.gap_rate
        if any(self.tilt) or any(self.tilt_rate):
            dH, dH_dt = tilted_gap(self.bearing, s, theta, zeta, self.tilt, self.tilt_rate)
            H, rate = H + dH, rate + dH_dt
        if self.profile is not None:
            H = H + self.profile.film_gap(self.bearing, zeta)
        return (f.density * H - film_thickness(theta, s.eps),
                f.density * rate + f.density_rate * H - s.eps_dot * np.cos(theta))


def field_balance_film(bearing: Bearing, op: FilmOperator, state: JournalState,
                       spec: FilmFields | None = None, tilt=(0.0, 0.0),
                       tilt_rate=(0.0, 0.0), profile=None) -> BalanceFilm:
    """The film of ``spec`` (None: the rigid cylinder's fields) with a tilt and a bush
    edge ``profile`` (:class:`~bearingfem.fields.EdgeProfile`) on ``op``'s mesh; raises
    ValueError for a bad field or a tilt that touches the bush."""
    spec = spec or FilmFields()
    fields, gap = general_film(bearing, state, op, spec, tilt, tilt_rate, profile)
    values, _ = film_system(op, fields, 0.0)
    rigid = rigid_balance_film(op, state)
    cv = film_volumes(op.mesh)
    departure = _Departure(bearing, op, state, spec, tilt, tilt_rate, profile)
    xs, wx = halves(cv.x_lo, op.mesh.axes[0][cv.column], cv.x_hi)
    ys, wy = halves(*zeta_extent(op, cv))
    TH = np.broadcast_to(xs[:, :, None], xs.shape + (ys.shape[1],))
    ZE = np.broadcast_to(ys[:, None, :], TH.shape)
    W = wx[:, :, None] * wy[:, None, :]
    d_content, d_squeeze = departure(TH, ZE)
    d_face, _ = departure(np.broadcast_to(cv.face[:, None], ys.shape), ys)
    content = rigid.content + np.sum(W * d_content, axis=(1, 2))
    if not np.all(content > 0.0):
        raise ValueError("the fields' content rho H must be > 0 in every control volume")
    return BalanceFilm(values=values, content=content,
                       face=rigid.face + np.sum(wy * d_face, axis=1),
                       squeeze=rigid.squeeze + np.sum(W * d_squeeze, axis=(1, 2)),
                       fields=fields, gap=gap)


def _as_functions(spec: FilmFields, op: FilmOperator) -> FilmFields:
    """``spec`` with its arrays (nodal values or values at the quadrature points of
    ``op``'s mesh) turned into functions of (theta, zeta) interpolating them on that mesh:
    what the coarser meshes of a nested solve evaluate."""
    def function(name, f):
        if f is None or callable(f) or np.ndim(f) == 0:
            return f
        v = np.asarray(f, float)
        if v.ndim == 2 and v.shape == op.qp_theta.shape:
            v = to_nodes(name, op.mesh.basis, v)
        if v.shape != (op.mesh.ndofs,):
            FilmFields(**{name: f}).on(op, JournalState(eps=0.0))    # raises by name
        return lambda t, z: (prolongation(op.mesh, np.ravel(t), np.ravel(z)) @ v
                             ).reshape(np.shape(t))
    return FilmFields(**{name: function(name, getattr(spec, name)) for name in FIELD_NAMES})


def balance_films(bearing: Bearing, state: JournalState, fine: FilmOperator,
                  spec: FilmFields | None = None, tilt=(0.0, 0.0), tilt_rate=(0.0, 0.0),
                  profile=None):
    """The function op -> :class:`BalanceFilm` that the JFO solves take: ``spec``, the
    tilt and the bush edge ``profile`` on the mesh ``fine`` as given, on the coarser
    meshes of the nested solve with
    their arrays interpolated from ``fine`` (one film per mesh, kept). Evaluates the fine
    film at once, so bad fields raise before any solve."""
    spec = spec or FilmFields()
    coarse = _as_functions(spec, fine)
    films = {}

    def film(op: FilmOperator) -> BalanceFilm:
        if op not in films:
            films[op] = field_balance_film(bearing, op, state, spec if op is fine else coarse,
                                           tilt, tilt_rate, profile)
        return films[op]
    film(fine)
    return film


@dataclass(frozen=True)
class FilmSpec:
    """What a transient film on fields is given: ``fields`` (a FilmFields, a function
    (state, t) -> FilmFields or None), ``tilt`` and ``tilt_rate`` (pairs [rad], [rad/s],
    or functions t -> pair), t the time [s]."""

    fields: object
    tilt: object
    tilt_rate: object

    @classmethod
    def checked(cls, fields, tilt, tilt_rate) -> "FilmSpec | None":
        """The spec, or None for the rigid cylinder (no fields, no tilt); ValueError
        naming a bad argument."""
        if fields is not None and not (isinstance(fields, FilmFields) or callable(fields)):
            raise ValueError("fields must be a FilmFields or a function (state, t) -> "
                             f"FilmFields, got {type(fields).__name__}")
        pairs = {}
        for name, v in (("tilt", tilt), ("tilt_rate", tilt_rate)):
            pairs[name] = v if callable(v) else check_tilt(name, v)
        if fields is None and not any(callable(v) or any(v) for v in pairs.values()):
            return None
        return cls(fields, pairs["tilt"], pairs["tilt_rate"])

    def at(self, state: JournalState, t: float):
        """(FilmFields or None, tilt, tilt_rate) at ``state`` and time ``t`` [s]."""
        spec = self.fields(state, t) if callable(self.fields) else self.fields
        if spec is not None and not isinstance(spec, FilmFields):
            raise ValueError(f"fields(state, t) must return a FilmFields, got "
                             f"{type(spec).__name__}")
        tilt = check_tilt("tilt", self.tilt(t)) if callable(self.tilt) else self.tilt
        rate = (check_tilt("tilt_rate", self.tilt_rate(t)) if callable(self.tilt_rate)
                else self.tilt_rate)
        return spec, tilt, rate
