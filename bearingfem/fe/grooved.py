"""Grooved films on a mesh fixed in the bearing: a new journal angle rebuilds nothing.

Axial grooves are fixed in the bearing, so their edges are mesh lines of one mesh whose
angle is phi = theta + gamma, the film angle of a journal at gamma = 0 (the grooves' film
angles at gamma = 0; :func:`~bearingfem.fe.mesh.film_mesh` grades the cells per arc so
every edge is a grid line, on any n_theta). The journal's angle only moves the gap,

    H = 1 + eps cos(phi - gamma),
    H^3 = A_0 + sum_{m=1..3} A_m cos(m (phi - gamma)),
    A_0 = a_0 + a_2/2, A_1 = a_1 + 3 a_3/4, A_2 = a_2/2, A_3 = a_3/4,

with a_k = (1, 3 eps, 3 eps^2, eps^3) the film's cos^k coefficients
(:func:`~bearingfem.film.cubed_thickness_coefficients`), and cos(m (phi - gamma)) =
cos(m phi) cos(m gamma) + sin(m phi) sin(m gamma). The stiffness of -div(H^3 grad P) is
then a combination of seven matrices int {1, cos m phi, sin m phi} grad u . grad v,
assembled once per mesh (by the general-field tables, :mod:`bearingfem.fe.general`) and
combined per state like the periodic film's four; the load of the source
a_sin sin(theta) + a_cos cos(theta) combines b_sin and b_cos of phi. The forces rotate:
F_r = k (I_c cos gamma + I_s sin gamma), F_t = k (I_s cos gamma - I_c sin gamma) with
I_c, I_s the integrals of P cos phi and P sin phi.

Because the mesh is the moving mesh of the grooves turned by gamma (both start at the
first groove's edge and grade the same arcs), the discrete film is the one the grooves'
moving mesh solved, at the same quadrature points: the results agree to round-off. The
partial in gamma is exact (the same sensitivity as in eps, on the solve's own factors):
K_II dP_I/dgamma = db_I/dgamma - (dK/dgamma P)_I, plus the rotation of the force.

Flooded grooves with the Reynolds-family films ("none", "gumbel", "reynolds"); the
mass-conserving JFO film (starved grooves) keeps its moving mesh (:mod:`bearingfem.fe.jfo`
is not built on fields).
"""
from __future__ import annotations

import math
from collections import OrderedDict
from dataclasses import dataclass, field

import numpy as np

from ..bearing import Bearing, JournalState
from ..caches import cached, kept
from ..errors import ConvergenceError
from ..film import cubed_thickness_coefficients, film_thickness, source_coefficients
from ..scales import force_factor
from ..solution import FilmSolution, ForceDerivatives
from ..solvers.blocksolve import DENSE_DOFS, PinnedFactor, bordered_solve, inactive_solve
from ..solvers.cavitation import LCPResult
from ..fields import FilmFields
from .assembly import FilmOperator
from .general import general_assembly
from .kernel import fe_pressure, film_outputs
from .grooved_build import build_grooved_tables, harmonic_weights
from .mesh import check_grading, film_mesh
from .multilevel import coarse_shape, prolongation

__all__ = ["GroovedOperator", "grooved_operator", "bearing_fixed_operator", "groove_operator_for",
           "grooved_pressure", "grooved_force", "grooved_derivatives", "grooved_solution",
           "check_grading"]


@dataclass(frozen=True, eq=False)
class GroovedOperator:
    """The film operator of a grooved bearing on its bearing-fixed mesh.

    Attributes
    ----------
    op : the :class:`~bearingfem.fe.assembly.FilmOperator` of the mesh in phi (the film
        angle at gamma = 0), grooves on mesh lines
    harmonics : (7, nnz) values of int w(phi) grad u . grad v on op's pattern for
        w = 1, cos phi, sin phi, cos 2 phi, sin 2 phi, cos 3 phi, sin 3 phi
    last : the last solve on this operator (its film's key and result), which the
        designer's partials start from (:func:`grooved_derivatives`); the answer does not
        depend on it beyond the solver's tolerance, only the number of solves
    levels : the cold starts on this operator so far and, once built, its coarse level
        (:func:`_coarse_active`)
    """

    op: FilmOperator
    harmonics: np.ndarray
    last: dict = field(default_factory=dict, repr=False)
    levels: dict = field(default_factory=dict, repr=False)

    def coefficients(self, eps: float, gamma: float, wrt: str | None = None) -> np.ndarray:
        """The seven weights of :attr:`harmonics` at (eps, gamma); ``wrt`` "eps" or
        "gamma" gives their partial."""
        a0, a1, a2, a3 = cubed_thickness_coefficients(eps, wrt == "eps")
        out = [0.0 if wrt == "gamma" else a0 + 0.5 * a2]
        for m, amp in ((1, a1 + 0.75 * a3), (2, 0.5 * a2), (3, 0.25 * a3)):
            c, s = math.cos(m * gamma), math.sin(m * gamma)
            out += [-m * amp * s, m * amp * c] if wrt == "gamma" else [amp * c, amp * s]
        return np.array(out)

    def values(self, eps: float, gamma: float, wrt: str | None = None) -> np.ndarray:
        """Stiffness values on the pattern at (eps, gamma) (a partial with ``wrt``)."""
        return self.coefficients(eps, gamma, wrt) @ self.harmonics

    def load(self, eps: float, eps_dot: float, wedge_speed: float, gamma: float,
             wrt_gamma: bool = False) -> np.ndarray:
        """Load of the source a_sin sin(phi - gamma) + a_cos cos(phi - gamma) (its
        gamma-partial with ``wrt_gamma``)."""
        a_sin, a_cos = source_coefficients(eps, eps_dot, wedge_speed)
        c, s = math.cos(gamma), math.sin(gamma)
        b_sin, b_cos = self.op.b_sin, self.op.b_cos
        if wrt_gamma:
            return (a_cos * c - a_sin * s) * b_sin - (a_sin * c + a_cos * s) * b_cos
        return (a_sin * c + a_cos * s) * b_sin + (a_cos * c - a_sin * s) * b_cos

    def film_angle(self, gamma: float) -> np.ndarray:
        """theta = phi - gamma at the quadrature points."""
        return self.op.qp_theta - gamma


@cached(maxsize=16)
def grooved_operator(op: FilmOperator) -> GroovedOperator:
    """The harmonic tables of ``op``'s mesh (cached per operator)."""
    ga = general_assembly(op)
    return GroovedOperator(op, np.array([ga.stiffness_values(w)
                                         for w in harmonic_weights(op.qp_theta)]))


@cached(maxsize=16)
def bearing_fixed_operator(n_theta: int, n_z: int, element: str, length_ratio: float,
                           arcs: tuple, grading: tuple | None = None) -> GroovedOperator:
    """The grooved operator of the bearing-fixed mesh (half length, from the first groove's
    edge), its tables built by numpy from the element matrices
    (:mod:`bearingfem.fe.grooved_build`; cached)."""
    mesh = film_mesh(n_theta, n_z, element, length_ratio, arcs[0][0], True, arcs, grading)
    return GroovedOperator(*build_grooved_tables(mesh))


@cached(maxsize=64)
def _mesh_arcs(grooves: tuple) -> tuple:
    """The grooves' arcs in the mesh angle, rounded to 1e-12 rad (the operator cache's key;
    cached: a design asks for them at every film evaluation)."""
    return tuple((float(np.round(lo, 12)), float(np.round(hi, 12)))
                 for lo, hi in (g.arc(0.0) for g in grooves))


def groove_operator_for(bearing: Bearing, n_theta: int, n_z: int, element: str,
                        grooves, grading=None) -> GroovedOperator:
    """The bearing-fixed grooved operator (half length) of ``grooves`` on this mesh;
    ``grading`` (angle, strength): theta cells concentrated towards the inertial ``angle``
    [rad] (e.g. where the heaviest load puts the minimum film), sized like
    1 - strength cos (:func:`~bearingfem.fe.mesh.film_mesh`); None: uniform per arc."""
    arcs = _mesh_arcs(tuple(grooves))
    grading = check_grading(grading, angle=True)
    if grading is not None:     # the mesh angle is the film angle at gamma = 0
        grading = (float(np.round(np.mod(grading[0] - math.pi, 2.0 * math.pi), 12)),
                   grading[1])
    return bearing_fixed_operator(int(n_theta), int(n_z), element, bearing.length_ratio, arcs,
                                  grading)


def _held(bearing: Bearing, gop: GroovedOperator, grooves) -> np.ndarray:
    G = np.zeros(gop.op.mesh.ndofs)
    for g, dofs in zip(grooves, gop.op.mesh.grooves):
        G[dofs] = g.pressure / bearing.pressure_scale
    return G


def _system(gop, state):
    values = gop.values(state.eps, state.gamma)
    load = gop.load(state.eps, state.eps_dot, state.wedge_speed, state.gamma)
    return values, load


def _grooved_coarse_level(gop: GroovedOperator):
    """(the P1 grooved operator half as fine, the interpolation from its dofs to ``gop``'s
    free dofs), or None at the coarsest level: :func:`~bearingfem.fe.multilevel.coarse_level`
    on the bearing-fixed mesh, built by numpy when a cold start first asks for it."""
    if "coarse" not in gop.levels:
        m = gop.op.mesh
        shape = coarse_shape(m)
        coarse = None if shape is None else bearing_fixed_operator(*shape, "P1", m.length_ratio,
                                                                   m.arcs)
        if coarse is not None and coarse.op.mesh.ndofs < m.ndofs:
            gop.levels["coarse"] = (coarse, prolongation(coarse.op.mesh, m.theta[m.free],
                                                         m.zeta[m.free]))
        else:       # already at the coarsest mesh
            gop.levels["coarse"] = None
    return gop.levels["coarse"]


#: Up to this many free dofs the first cold start on an operator begins from the film
#: without cavities (the set then moves in 4-8 iterations) instead of building the coarse
#: level: measured on the Lund & Thomsen bearing's cold equilibrium + K/C, P2 30x6 (300
#: free dofs) 17 ms against 23 ms, 36x6 (372) 19 against 22 ms; at 48x8 (656) the
#: coarse level wins (29 against 30 ms).
FIRST_COLD_START_DOFS = 500


def _first_set(op, P0, values, load, G) -> np.ndarray:
    """The cavitated set of the semismooth Newton step from the start pressure ``P0`` (on
    ``op``'s free dofs): where the active-set method takes a start pressure."""
    free = op.mesh.free
    K = op.free_stiffness(0.0, values)
    b = (load - op.matrix(values) @ G)[free]
    active = np.zeros(op.mesh.ndofs, bool)
    active[free] = P0 < (K @ P0 - b) / K.diagonal()
    return active


#: The last grooved films solved, by film key and mesh family (L/D, grooves' arcs): a
#: mesh search solves one state on several meshes (a pair, its split, a shifted partner),
#: and each new mesh then starts from the film already solved on another one, interpolated
#: (:func:`_other_mesh_active`), instead of building and solving its coarse levels
_FILMS: "OrderedDict[tuple, tuple]" = kept(OrderedDict())
_FILMS_SIZE = 8


@dataclass(frozen=True)
class _Nodes:
    """What interpolating from a mesh needs (:func:`~bearingfem.fe.multilevel.prolongation`),
    without the mesh's basis (kept films would otherwise hold large meshes alive)."""

    theta: np.ndarray
    zeta: np.ndarray
    periodic: bool
    shape: tuple


def _family(gop) -> tuple:
    m = gop.op.mesh
    return (round(m.length_ratio, 12), m.arcs)


def _shape(m) -> tuple:
    return (m.n_theta, m.n_z, m.ndofs, m.grading)


def _other_mesh_active(gop, key, values, load, G):
    """The first cavitated set from this very film solved on another mesh of the family
    (its pressure interpolated to this mesh's free dofs), or None when there is none."""
    kept_film = _FILMS.get((key, _family(gop)))
    m = gop.op.mesh
    if kept_film is None or kept_film[0].shape == _shape(m):
        return None
    mesh, pressure = kept_film
    free = m.free
    P0 = np.maximum(prolongation(mesh, m.theta[free], m.zeta[free]) @ pressure, 0.0)
    return _first_set(gop.op, P0, values, load, G)


def _coarse_active(gop, bearing, state, grooves, tol, values, load, G):
    """The first cavitated set from the film solved on the coarser levels (the
    multilevel start of :mod:`bearingfem.fe.multilevel`, here with the grooved film). The
    levels are built lazily: a small film's first cold start is from no cavity (all
    dofs free); from its second on, when the levels pay for themselves, they are built."""
    cold = gop.levels.get("cold_starts", 0)
    gop.levels["cold_starts"] = cold + 1
    if cold == 0 and len(gop.op.mesh.free) <= FIRST_COLD_START_DOFS:
        return np.zeros(gop.op.mesh.ndofs, bool)
    level = _grooved_coarse_level(gop)
    if level is None:
        return None
    coarse, prolong = level
    res = grooved_pressure(coarse, bearing, state, grooves, "reynolds", tol=tol)
    return _first_set(gop.op, np.maximum(prolong @ res.pressure, 0.0), values, load, G)


def _film_key(bearing, state, grooves, cavitation, method="active-set", tol=1e-10):
    """What makes a grooved film on one operator: equal keys, the same solve. The operator
    is shared by every bearing of its L/D, so the bearing is part of the key (its scales
    turn the held groove pressures and the partials into its own)."""
    return (bearing, state.eps, state.eps_dot, state.wedge_speed, state.gamma, cavitation,
            method, tol, tuple(g.pressure for g in grooves))


def grooved_pressure(gop: GroovedOperator, bearing: Bearing, state: JournalState, grooves,
                     cavitation: str = "reynolds", method: str = "active-set",
                     tol: float = 1e-10, start: np.ndarray | None = None,
                     reuse: bool = False) -> LCPResult:
    """Nodal dimensionless pressure of the grooved film at ``state`` (groove pressures held
    on their dofs). The Reynolds active set starts from ``start`` (a cavitated set over
    the dofs, e.g. a nearby state's ``LCPResult.active``) or, without one (or when it
    does not settle), from the coarser levels: the answer is the same to the solver's
    tolerance; a mesh new to the state starts from the state's film on another mesh when
    one was solved (:data:`_FILMS`). With ``reuse`` the last solve on this operator is
    returned when it was of
    this very film (K/C after the film's solve). Every solve is kept as
    ``gop.last``."""
    key = _film_key(bearing, state, grooves, cavitation, method, tol)
    if reuse and gop.last.get("key") == key:
        return gop.last["result"]
    G = _held(bearing, gop, grooves)
    values, load = _system(gop, state)
    res = None
    if cavitation != "reynolds" or method != "active-set":
        res = fe_pressure(gop.op, state, cavitation, method, tol, dirichlet=G,
                          system=(values, load))
    elif start is not None and np.shape(start) == (gop.op.mesh.ndofs,):
        try:
            res = fe_pressure(gop.op, state, cavitation, method, tol, active0=start,
                              dirichlet=G, system=(values, load))
        except ConvergenceError:     # a set from too far away: start from the coarse levels
            res = None
    if res is None:
        other = _other_mesh_active(gop, key, values, load, G)
        if other is not None:
            try:
                res = fe_pressure(gop.op, state, cavitation, method, tol, active0=other,
                                  dirichlet=G, system=(values, load))
            except ConvergenceError:     # too far: start from the coarse levels
                res = None
    if res is None:
        res = fe_pressure(gop.op, state, cavitation, method, tol,
                          active0=_coarse_active(gop, bearing, state, grooves, tol, values,
                                                 load, G),
                          dirichlet=G, system=(values, load))
    gop.last.update(key=key, result=res)
    if cavitation == "reynolds" and method == "active-set":
        m = gop.op.mesh
        _FILMS[(key, _family(gop))] = (_Nodes(m.theta, m.zeta, m.periodic, _shape(m)),
                                       res.pressure)
        _FILMS.move_to_end((key, _family(gop)))
        while len(_FILMS) > _FILMS_SIZE:
            _FILMS.popitem(last=False)
    return res


def rotated(I: np.ndarray, gamma: float) -> np.ndarray:
    """(F_r, F_t) / k from (int P cos phi, int P sin phi) (leading axis of I)."""
    c, s = np.cos(gamma), np.sin(gamma)
    return np.stack([c * I[0] + s * I[1], c * I[1] - s * I[0]])


def _force(bearing, gop, P, gamma, cavitation):
    I = gop.op.force_integrals(P, cavitation == "gumbel")
    k = force_factor(bearing, True)
    return tuple(float(f) for f in k * rotated(I, gamma))


def grooved_force(bearing: Bearing, state: JournalState, gop: GroovedOperator, grooves,
                  cavitation: str = "reynolds", method: str = "active-set", warm=None):
    """(F_r, F_t) [N] of the grooved film and its :class:`LCPResult`; ``warm``: a nearby
    state's result on this operator, whose cavitated set starts the solve."""
    res = grooved_pressure(gop, bearing, state, grooves, cavitation, method,
                           start=None if warm is None else warm.active)
    return _force(bearing, gop, res.pressure, state.gamma, cavitation), res


def partials_load(gop: GroovedOperator, state: JournalState, P: np.ndarray) -> np.ndarray:
    """The four right-hand sides [ndofs, 4] whose solutions on the film's matrix are
    dP/d(eps, eps_dot, w, gamma) at the pressure ``P``: the load's partial less the
    matrix's partial times P."""
    op = gop.op
    e, ed, w, g = state.eps, state.eps_dot, state.wedge_speed, state.gamma

    def dK(wrt):
        return op.matrix(gop.values(e, g, wrt))

    # the source is linear in eps (wedge), eps_dot and w: unit values give its partials
    return np.column_stack([gop.load(1.0, 0.0, w, g) - dK("eps") @ P,
                            gop.load(e, 1.0, 0.0, g), gop.load(e, 0.0, 1.0, g),
                            gop.load(e, ed, w, g, wrt_gamma=True) - dK("gamma") @ P])


def grooved_derivatives(bearing: Bearing, state: JournalState, gop: GroovedOperator, grooves,
                        cavitation: str = "reynolds") -> ForceDerivatives:
    """(F_r, F_t) [N] and the exact partials in eps, eps_dot, w and gamma (module
    docstring), four right-hand sides on the factors of the film solve. The designer's
    path (Newton's steps, K/C, charts): the solve starts from the operator's last
    cavitated set, and at the state of the last solve takes its film; asked again at
    the state of the last partials (K/C at a Newton equilibrium) returns them."""
    key = _film_key(bearing, state, grooves, cavitation)
    kept = gop.last.get("derivatives")
    if kept is not None and kept[0] == key and gop.last.get("key") == key:
        return kept[1]
    op = gop.op
    last = gop.last.get("result")
    res = grooved_pressure(gop, bearing, state, grooves, cavitation,
                           start=None if last is None else last.active, reuse=True)
    P = res.pressure
    e, g = state.eps, state.gamma
    rhs = partials_load(gop, state, P)
    free = op.mesh.free
    inactive = ~res.active[free] if cavitation == "reynolds" else np.ones(len(free), bool)
    dP = np.zeros((op.mesh.ndofs, 4))
    K = op.free_stiffness(e, gop.values(e, g))
    if len(free) <= DENSE_DOFS:     # tiny films: LAPACK beats setting up sparse factors
        block = np.flatnonzero(inactive)
        dP[free[block]] = np.linalg.solve(K.toarray()[np.ix_(block, block)],
                                          rhs[free[block]])
    elif isinstance(res.factor, PinnedFactor) and not np.array_equal(~res.factor.active,
                                                                     inactive):
        # the four columns in one bordered solve: the changed dofs' columns are solved once
        # (the periodic film keeps its column-by-column solves, bit-identical)
        dP[free] = bordered_solve(res.factor.lu, K, np.where(inactive[:, None], rhs[free], 0.0),
                                  ~res.factor.active, inactive)
    else:
        dP[free] = inactive_solve(K, res.factor, inactive, rhs[free])
    k = force_factor(bearing, True)
    where = op.at_quadrature(P) > 0.0 if cavitation == "gumbel" else None
    I = op.force_integrals(np.concatenate([P[None], dP.T]), where=where)    # (2, 5)
    F = k * rotated(I, g)
    # turning the journal also turns the frame the force is read in: d/dgamma of the
    # rotation is (F_t, -F_r)
    d_gamma = F[:, 4] + np.array([F[1, 0], -F[0, 0]])
    col = [tuple(float(x) for x in F[:, j]) for j in range(4)]
    d = ForceDerivatives(col[0], col[1], col[2], col[3], "exact-sensitivity",
                         tuple(float(x) for x in d_gamma))
    gop.last["derivatives"] = (key, d)
    return d


def grooved_solution(bearing: Bearing, state: JournalState, gop: GroovedOperator, grooves,
                     cavitation: str, method: str, tol: float, cavitated_shear: str,
                     element: str) -> FilmSolution:
    """The whole grooved film (:func:`~bearingfem.solve_reynolds`'s outputs),
    nodes reported at their film angles theta = phi - gamma; a cold solve (the active set
    from the coarser levels, or from this very film solved on another mesh; never from
    another state's set), except that the film of the
    designer's last partials (:func:`grooved_derivatives`) is taken when it was this very
    film (an equilibrium's answer: the same film to the solver's tolerance)."""
    op = gop.op
    kept = gop.last.get("derivatives")
    designer = kept is not None and kept[0] == _film_key(bearing, state, grooves, cavitation,
                                                          method, tol)
    res = grooved_pressure(gop, bearing, state, grooves, cavitation, method, tol,
                           reuse=designer)
    values, load = _system(gop, state)
    film = FilmFields(gap=film_thickness(gop.film_angle(state.gamma), state.eps))
    return film_outputs(bearing, state, op, res, values, load, film, cavitation,
                        cavitated_shear, grooves,
                        f"fem-{element}" + (f"/{method}" if cavitation == "reynolds" else ""),
                        force=_force(bearing, gop, res.pressure, state.gamma, cavitation),
                        theta=op.mesh.theta - state.gamma)
