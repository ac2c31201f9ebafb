"""The thermal film's energy equation as discretised: its order on a manufactured
solution, the SUPG parameter against its written formula, the operator's tables against
scikit-fem forms, the arcs' quadrature, the operator's maps, and the coupled solve against
a plain fixed point whose energy equation is assembled by those forms."""
import math

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from skfem import Basis, BilinearForm, LinearForm

from bearingfem import solve_reynolds
from bearingfem.fe.mesh import film_mesh
from bearingfem.fields import FilmFields
from bearingfem.routes.thd import solve_thd, thermal_operator
from bearingfem.thermal.mixing import groove_mixing
from bearingfem.thermal import Thermal
from bearingfem.thermal.energy import (
    EnergyFlow,
    Mixing,
    energy_operator,
    energy_system,
    film_flow,
    solve_energy,
)
from bearingfem.thermal.operator import _supg_tau
from tests.test_thermal_film import BEARING, GROOVES, STATE, SUPPLY, VG32


def _manufactured(n):
    """L2 error of the energy equation's solve against T = 300 + 20 (1 - cos theta)
    (1 + 0.3 cos(pi zeta / lam)) on a supply-line mesh of n x n/2 cells, with a swirling
    flow, diffusion (Pe ~ 100 per cell at n = 16) and a bush term."""
    lam = BEARING.length_ratio
    mesh = film_mesh(n, n // 2, "P1", lam, theta0=0.0, half=False)
    op = energy_operator(mesh)
    basis = op.basis
    R = BEARING.radius
    th, ze = (np.asarray(x) for x in basis.global_coordinates())
    k = math.pi / lam
    g = 1.0 + 0.3 * np.cos(k * ze)
    T = 300.0 + 20.0 * (1.0 - np.cos(th)) * g
    Tt = 20.0 * np.sin(th) * g
    Tz = -20.0 * (1.0 - np.cos(th)) * 0.3 * k * np.sin(k * ze)
    lap = 20.0 * np.cos(th) * g - 20.0 * (1.0 - np.cos(th)) * 0.3 * k * k * np.cos(k * ze)
    bt, bz = 300.0 * (1.0 + 0.5 * np.cos(th)), 60.0 * np.sin(k * ze)
    D, sigma = 1e-4, 500.0
    source = (bt * Tt + bz * Tz) / R - D * lap / R ** 2 + sigma * T
    flow = EnergyFlow(beta_theta=bt, beta_zeta=bz, diffusivity=np.full_like(th, D),
                      dissipation=source)
    sol = solve_energy(BEARING, op, flow, Mixing.held([300.0]), (sigma, 0.0, 0.0, 0.0))
    Th = np.asarray(basis.interpolate(sol.temperature))
    return math.sqrt(float(np.sum((Th - T) ** 2 * basis.dx)) / float(np.sum(basis.dx)))


def test_manufactured_solution_order():
    """SUPG on P1 for a smooth manufactured temperature: the L2 error falls at order 2 or
    better (measured 2.2, 0.35, 0.063, 0.012 K on 16 .. 128 cells: orders 2.7, 2.5, 2.4,
    with the arcs' 3-point rule as with the 6-point rule before it: 2.1, 0.35, 0.064, 0.012;
    the convection-dominated pre-asymptotic range; theory: 1.5 .. 2), where a first-order
    upwind scheme falls at 1. Fails with the SUPG share of the source dropped (an
    inconsistent scheme)."""
    errors = np.array([_manufactured(n) for n in (16, 32, 64)])
    orders = np.log2(errors[:-1] / errors[1:])
    assert np.all(orders > 1.8), (errors, orders)
    assert errors[-1] < 0.08


# -- the coupled solve against the plain fixed point, assembled by scikit-fem forms --------

@BilinearForm
def _energy_form(u, v, w):
    # the energy equation's form as first written (per d(theta) d(zeta)), for reference
    bu = w["bt"] * u.grad[0] + w["bz"] * u.grad[1]
    bv = w["bt"] * v.grad[0] + w["bz"] * v.grad[1]
    return (w["R"] * bu * v + w["D"] * (u.grad[0] * v.grad[0] + u.grad[1] * v.grad[1])
            + w["R"] ** 2 * w["s"] * u * v + w["tau"] * bv * (bu + w["R"] * w["s"] * u))


@LinearForm
def _energy_load(v, w):
    bv = w["bt"] * v.grad[0] + w["bz"] * v.grad[1]
    return w["R"] ** 2 * w["f"] * v + w["tau"] * bv * w["R"] * w["f"]


@LinearForm
def _value_load(v, w):
    return w["R"] ** 2 * w["f"] * v


def held_rows(edges, mixing, N):
    """The held (inflow and groove) rows as equations: T_i - sum_k w_k T_src,k = fresh for
    each groove's held dofs (its mixing written out row by row, independently of the
    operator's Woodbury form). Returns (rows at ``edges.held``, (N,) right-hand side)."""
    rows, cols, vals, rhs_held = [], [], [], np.zeros(N)
    for k, (d_in, d_int) in enumerate(zip(edges.inflow, edges.interior)):
        d = np.concatenate([d_in, d_int]).astype(int)
        src = np.asarray(mixing.dofs[k], int)
        for i in d:
            rows += [i] * (1 + len(src))
            cols += [i, *src]
            vals += [1.0, *(-np.asarray(mixing.weights[k]))]
        rhs_held[d] = mixing.fresh[k]
    return sp.csr_matrix((vals, (rows, cols)), shape=(N, N))[edges.held], rhs_held


def _reference_energy(op, flow, mixing, walls):
    """The energy equation assembled by the forms above and solved by a general sparse LU
    (the held rows and the zero-flux journal as extra rows): nodal T and T_j."""
    R, basis, edges = BEARING.radius, op.basis, op.edges
    hb, ta, hj, tj = walls
    tau = _supg_tau(op, flow, R)
    common = dict(bt=flow.beta_theta, bz=flow.beta_zeta, tau=tau, R=R)
    A = _energy_form.assemble(basis, D=flow.diffusivity, s=hb + hj, **common).tocsr()
    b = _energy_load.assemble(basis, f=flow.dissipation + hb * ta, **common)
    N, held = basis.N, edges.held
    free = np.setdiff1d(np.arange(N), held)
    H, rhs_held = held_rows(edges, mixing, N)
    cj = -_energy_load.assemble(basis, f=np.full_like(tau, hj), **common)
    if hj > 0.0 and tj is None:
        mj = _value_load.assemble(basis, f=np.full_like(tau, hj), R=R)
        K = sp.bmat([[A[free], sp.csr_matrix(cj[free][:, None])], [H, None],
                     [sp.csr_matrix(mj[None, :]), sp.csr_matrix([[-float(mj.sum())]])]],
                    format="csc")
        x = spla.spsolve(K, np.concatenate([b[free], rhs_held[held], [0.0]]))
        return x[:-1], float(x[-1])
    t_j = ta if tj is None else tj
    K = sp.vstack([A[free], H], format="csc")
    return spla.spsolve(K, np.concatenate([b[free] - cj[free] * t_j, rhs_held[held]])), t_j


def _plain_fixed_point(thermal, n=(48, 8)):
    """T_{k+1} = the energy equation's T on the film of mu(p_k, T_k), the dissipation
    lagged, each film by the general-field route on the film frame's mesh (the thermal
    film's bearing-fixed mesh turned by gamma: the same nodes and points in the same
    order), each energy equation by the forms."""
    op = energy_operator(film_mesh_of(n))
    mesh = op.basis
    T = np.full(op.N, SUPPLY)
    p = np.zeros(op.N)
    fop = thermal_operator(BEARING, STATE, *n, grooves=GROOVES)
    for _ in range(200):
        mu_q = VG32.viscosity_at(fop.at_quadrature(p), temperature=fop.at_quadrature(T))
        sol = solve_reynolds(BEARING, STATE, *n, grooves=GROOVES, half=False,
                             fields=FilmFields(viscosity=mu_q / BEARING.viscosity))
        mu = VG32.viscosity_at(np.asarray(mesh.interpolate(sol.pressure)),
                               temperature=np.asarray(mesh.interpolate(T)))
        P = sol.pressure / BEARING.pressure_scale
        flow = film_flow(BEARING, STATE, mesh, P, np.ones(op.N), mu, VG32)
        mixing = groove_mixing(BEARING, STATE, fop.mesh, op.edges, P, np.ones(op.N),
                               VG32.viscosity_at(sol.pressure, temperature=T), thermal)
        T_new, t_j = _reference_energy(op, flow, mixing, thermal.walls)
        change, p_change = np.max(np.abs(T_new - T)), np.max(np.abs(sol.pressure - p))
        T, p = T_new, sol.pressure
        if change < 1e-9 and p_change < 1e-11 * np.max(p):
            return sol, T, t_j
    raise AssertionError("the plain fixed point did not settle")


def film_mesh_of(n):
    return thermal_operator(BEARING, STATE, *n, grooves=GROOVES).mesh


@pytest.mark.parametrize("thermal", [
    Thermal(SUPPLY, carry_over=0.8),
    Thermal(SUPPLY, model="conducting", carry_over=0.5),
], ids=["adiabatic-carry-over", "conducting-zero-flux"])
def test_coupled_solve_is_the_plain_fixed_points_answer(thermal):
    """The thermal route (implicit dissipation, tables, banded solve with the carried-over
    oil by Woodbury's identity, the journal eliminated) lands where the plain fixed point
    lands whose energy equation is assembled by scikit-fem forms and solved by a general
    sparse LU: temperatures to 1e-6 K (the route's tolerance; measured 2e-9 K), force to
    1e-8. Fails with a wrong sign of the linearised dissipation's shift (1 K off), a
    dropped carry-over term (5 K) or the journal's row taken off (several K)."""
    ref, T_ref, tj_ref = _plain_fixed_point(thermal)
    sol = solve_thd(BEARING, STATE, 48, 8, lubricant=VG32, thermal=thermal, grooves=GROOVES)
    assert np.max(np.abs(sol.temperature - T_ref)) < 1e-6
    assert abs(sol.thermal.journal_temperature - tj_ref) < 1e-6
    assert np.allclose(sol.force, ref.force, rtol=1e-8, atol=0.0)
    assert sol.friction_torque == pytest.approx(ref.friction_torque, rel=1e-8)


def test_supg_tau_is_the_written_formula_at_every_peclet_number():
    """tau = h_e / (2 |beta|) (coth Pe - 1/Pe), Pe = |beta| h_e / (2 k h), written out with
    mpmath-free numpy (coth as 1/tanh) at Peclet numbers from 1e-5 to 1e6 and at rest (tau
    0): the operator's (series below 1e-3, 1 - 1/Pe above 20 without tanh) to 1e-9
    relative: coth Pe - 1/Pe cancels to ~1e-16 / Pe^2 just above Pe = 1e-3, where the two
    sides' Pe differ in the last bit (measured 3e-10 there, 4e-16 above Pe = 1; fails with
    the no-tanh branch from Pe = 2)."""
    op = energy_operator(film_mesh_of((24, 6)))
    shape = op.theta.shape
    pe_target = np.geomspace(1e-5, 1e6, op.theta.size).reshape(shape)
    angle = np.linspace(0.0, 2.0 * np.pi, op.theta.size).reshape(shape)
    bt, bz = 300.0 * np.cos(angle), 300.0 * np.sin(angle)
    bt[0, 0] = bz[0, 0] = 0.0                       # a point at rest
    R = BEARING.radius
    speed = np.hypot(bt, bz)
    he = R * (np.abs(bt) * op.cell[0] + np.abs(bz) * op.cell[1]) / np.where(speed > 0, speed, 1)
    k_h = np.where(speed > 0, speed * he / (2.0 * pe_target), 1.0)
    flow = EnergyFlow(beta_theta=bt, beta_zeta=bz, diffusivity=k_h,
                      dissipation=np.zeros(shape))
    pe = speed * he / (2.0 * k_h)
    small = pe < 1e-3
    coth_less = np.where(small, pe / 3.0, 1.0 / np.tanh(np.where(small, 1.0, pe))
                         - 1.0 / np.where(small, 1.0, pe))
    expected = np.where(speed > 0, he / (2.0 * np.where(speed > 0, speed, 1)) * coth_less, 0.0)
    tau = _supg_tau(op, flow, R)
    assert tau[0, 0] == 0.0
    np.testing.assert_allclose(tau, expected, rtol=1e-9, atol=0.0)
    np.testing.assert_allclose(tau[pe > 1.0], expected[pe > 1.0], rtol=1e-14, atol=0.0)


def test_energy_operator_assembles_the_forms():
    """The operator's tables give the matrix and load the scikit-fem forms give (1e-12),
    on a flow with both components and a source that vary over the film."""
    op = energy_operator(film_mesh_of((24, 6)))
    th = op.theta
    flow = EnergyFlow(beta_theta=300.0 * (1.0 + 0.5 * np.cos(th)),
                      beta_zeta=40.0 * np.sin(3.0 * th), diffusivity=np.full_like(th, 1e-3),
                      dissipation=1e4 * (2.0 + np.sin(th)))
    R = BEARING.radius
    tau = _supg_tau(op, flow, R)
    common = dict(bt=flow.beta_theta, bz=flow.beta_zeta, tau=tau, R=R)
    s = 100.0 + 50.0 * np.cos(th)
    A_ref = _energy_form.assemble(op.basis, D=flow.diffusivity, s=s, **common)
    b_ref = _energy_load.assemble(op.basis, f=flow.dissipation, **common)
    A, b, _ = energy_system(op, flow, s, flow.dissipation, R)
    assert abs(A - A_ref).max() < 1e-12 * abs(A_ref).max()
    assert np.max(np.abs(b - b_ref)) < 1e-12 * np.max(np.abs(b_ref))


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_arc_rule_is_exact_on_element_constant_coefficients(element):
    """The arcs' quadrature (ARC_DEGREE: 3 points on P1, 6 on P2) integrates the system
    exactly where the coefficients are constant on each element (the degree argument of
    :data:`~bearingfem.thermal.operator.ARC_DEGREE`): matrix and load equal the forms
    assembled by a 12-point rule (degree 6) on the same elements to 1e-12. Fails with a
    one-point rule on P1 (the reaction's v T, degree 2, is then not integrated exactly)."""
    op = energy_operator(thermal_operator(BEARING, STATE, 24, 6, element,
                                          grooves=GROOVES).mesh)
    m = op.basis.mesh
    centre = m.p[:, m.t[:, op.basis.tind]].mean(axis=1)      # (2, elements)
    th, ze = centre[0][:, None], centre[1][:, None]

    def constant(values, points):
        return np.broadcast_to(values, (len(centre[0]), points)).copy()
    Q = op.dx.shape[1]
    bt, bz = 300.0 * (1.0 + 0.5 * np.cos(th)), 40.0 * np.sin(3.0 * th) * np.cos(ze)
    D, s, f = 1e-3 * (1.0 + ze ** 2), 100.0 + 50.0 * np.cos(th), 1e4 * (2.0 + np.sin(th))
    flow = EnergyFlow(beta_theta=constant(bt, Q), beta_zeta=constant(bz, Q),
                      diffusivity=constant(D, Q), dissipation=constant(f, Q))
    R = BEARING.radius
    tau = _supg_tau(op, flow, R)
    A, b, _ = energy_system(op, flow, constant(s, Q), flow.dissipation, R)
    fine = Basis(m, op.basis.elem, intorder=6, elements=op.basis.tind, dofs=op.basis.dofs)
    Qf = fine.dx.shape[1]
    common = dict(bt=constant(bt, Qf), bz=constant(bz, Qf), tau=constant(tau[:, :1], Qf),
                  R=R)
    A_ref = _energy_form.assemble(fine, D=constant(D, Qf), s=constant(s, Qf), **common)
    b_ref = _energy_load.assemble(fine, f=constant(f, Qf), **common)
    assert Q < Qf
    assert abs(A - A_ref).max() < 1e-12 * abs(A_ref).max()
    assert np.max(np.abs(b - b_ref)) < 1e-12 * np.max(np.abs(b_ref))


def test_operator_maps_take_several_fields_in_one_product():
    """at_points of k nodal fields (N, k) is each field's values at the points, stacked
    (k, elements, points), and gradient's one stacked product is d/dtheta and d/dzeta by
    their own maps: bit for bit. Fails with the (N, k) product reshaped without moving
    the fields' axis first (the fields' values interleaved)."""
    op = energy_operator(film_mesh_of((24, 6)))
    rng = np.random.default_rng(3)
    a, b, c = rng.standard_normal((3, op.N))
    both = op.at_points(np.column_stack([a, b, c]))
    assert both.shape == (3, *op.dx.shape)
    for k, f in enumerate((a, b, c)):
        assert np.array_equal(both[k], op.at_points(f))
    g = op.gradient(a)
    assert np.array_equal(g[0], (op.d_theta @ a).reshape(op.dx.shape))
    assert np.array_equal(g[1], (op.d_zeta @ a).reshape(op.dx.shape))
