"""The general film assembly (any gap, viscosity and density field) against the rigid
cylinder's fast path, and the checks of film fields."""
import numpy as np
import pytest
import scipy.sparse as sp
from skfem import BilinearForm, LinearForm
from skfem.helpers import dot, grad

from bearingfem import Bearing, JournalState, solve_reynolds
from bearingfem.fe.general import film_system, general_assembly
from bearingfem.fe.kernel import fe_operator, fe_pressure
from bearingfem.fields import FilmFields, nodal_average

B = Bearing(radius=0.01, length=0.01, clearance=20e-6, viscosity=0.0117)
S = JournalState(eps=0.6, eps_dot=0.1, gamma=0.3, gamma_dot=0.0, omega=250.0)


@pytest.mark.parametrize("element", ["P1", "P2"])
@pytest.mark.parametrize("cavitation", ["none", "gumbel", "reynolds"])
def test_general_path_is_the_fast_path_on_the_rigid_gap(element, cavitation):
    """H = 1 + eps cos(theta) given as a field: the general assembly solves the fast path's
    film to round-off (the reference cylinder's Couette term is the fast path's strong
    load, the departure, zero here, is in weak form). Stiffness and load to 1e-14
    (measured 4.9e-16, 7e-17); pressure to 1e-12 at 120x20, what the conditioning makes
    of that (measured max |dP|/max P 2.8e-14 ... 2.9e-13, P2 the largest; before the
    split the weak form's quadrature error left 4.6e-9 at 30x6 and 1.4e-12 at 120x20).
    Fails with the Couette (or squeeze) sign flipped or the viscosity ratio left out."""
    op = fe_operator(B, S, 120, 20, element, None, False)
    fields = FilmFields(gap=lambda t, z: 1.0 + S.eps * np.cos(t)).on(op, S)
    values, load = film_system(op, fields, S.wedge_speed, S.eps)
    v0 = op.values(S.eps)
    load0 = op.load(S.eps, S.eps_dot, S.wedge_speed)
    assert np.max(np.abs(values - v0)) <= 1e-14 * np.max(np.abs(v0))
    assert np.max(np.abs(load - load0)) <= 1e-14 * np.max(np.abs(load0))
    fast = fe_pressure(op, S, cavitation)
    general = fe_pressure(op, S, cavitation, system=(values, load))
    scale = np.max(np.abs(fast.pressure))
    assert np.max(np.abs(general.pressure - fast.pressure)) <= 1e-12 * scale


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_general_stiffness_matches_scikit_fem(element):
    """The vectorised element tables against scikit-fem's own assembly of
    -div(k grad P) with a k that varies in theta and zeta (fails with a metric term
    transposed or dropped)."""
    op = fe_operator(B, S, 24, 6, element, 0.4, False)
    k = 1.0 + 0.3 * np.cos(op.qp_theta) * (1.0 + op.qp_zeta) ** 2

    @BilinearForm
    def form(u, v, w):
        return w["k"] * dot(grad(u), grad(v))

    ref = form.assemble(op.mesh.basis, k=k).toarray()
    fields = FilmFields(gap=1.0, viscosity=1.0 / k).on(op, S)
    values, _ = film_system(op, fields, 0.0)
    mine = sp.csr_matrix((values, op.indices, op.indptr), shape=op.shape).toarray()
    assert np.max(np.abs(mine - ref)) <= 1e-13 * np.max(np.abs(ref))


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_general_load_matches_scikit_fem(element):
    """The load int couette dv/dtheta + squeeze v, both varying in theta and zeta (the
    general assembly's precomputed sparse scatter), against scikit-fem's own assembly;
    the scalar stiffness's scatter against the element tables summed by hand. To 1e-13
    (measured 1e-16 .. 4e-16). Fails with the second reference gradient's share of
    d/dtheta dropped from the couette scatter, or the squeeze's weights on the element's
    nodes rolled."""
    op = fe_operator(B, S, 24, 6, element, 0.4, False)
    c = 1.0 + 0.3 * np.sin(op.qp_theta) * (1.0 + op.qp_zeta) ** 2
    s = np.cos(2.0 * op.qp_theta) + op.qp_zeta

    @LinearForm
    def form(v, w):
        return w["c"] * v.grad[0] + w["s"] * v

    ref = form.assemble(op.mesh.basis, c=c, s=s)
    ga = general_assembly(op)
    assert np.max(np.abs(ga.load(c, s) - ref)) <= 1e-13 * np.max(np.abs(ref))
    t = np.einsum("cde,cdqm->eqm", ga.metric, ga.stiff_tables)
    local = np.einsum("eq,eqm->em", c, t)
    by_hand = np.bincount(ga.positions.ravel(), local.ravel(),
                          minlength=len(op.indices) + 1)[:len(op.indices)]
    values = ga.stiffness_values(c)
    assert np.max(np.abs(values - by_hand)) <= 1e-13 * np.max(np.abs(by_hand))


def test_general_tables_follow_the_mesh_not_its_size():
    """Films on meshes of one size but another geometry (length, graded theta, supply
    line) or element, one after the other and back to the first, each against
    scikit-fem's own assembly on that mesh: the stiffness of -div(k grad P) and the load
    int 6 w (H - (1 + eps cos theta)) dv/dtheta - 12 dH/dt v plus the fast path's
    reference-cylinder load. To 1e-13 (measured <= 1e-15). Fails with the per-mesh tables
    (the scatters, the reference cylinder's cosine) kept by the mesh's size or number of
    points instead of by its operator (planted both, run once)."""
    long = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    meshes = [(B, {}), (long, {}), (B, {"grading": 0.6}), (B, {"supply_angle": 0.4}),
              (B, {"element": "P2"}), (B, {})]
    w, eps = 125.0, 0.6

    @BilinearForm
    def stiffness(u, v, w):
        return w["k"] * dot(grad(u), grad(v))

    @LinearForm
    def load_form(v, f):
        couette = 6.0 * w * (f["H"] - (1.0 + eps * np.cos(f.x[0])))
        return couette * v.grad[0] - 12.0 * f["Ht"] * v

    for bearing, kw in meshes:
        op = fe_operator(bearing, S, 24, 6, **{"element": "P1", "half": False, **kw})
        H = 1.0 + eps * np.cos(op.qp_theta) + 0.1 * op.qp_zeta ** 2
        Ht, mu = 0.1 * np.sin(op.qp_theta), 1.0 + 0.2 * op.qp_zeta
        values, load = film_system(op, FilmFields(gap=H, gap_rate=Ht, viscosity=mu), w, eps)
        basis = op.mesh.basis
        K = stiffness.assemble(basis, k=H ** 3 / mu).toarray()
        mine = sp.csr_matrix((values, op.indices, op.indptr), shape=op.shape).toarray()
        assert np.max(np.abs(mine - K)) <= 1e-13 * np.max(np.abs(K)), kw
        ref = load_form.assemble(basis, H=H, Ht=Ht) + op.load(eps, 0.0, w)
        assert np.max(np.abs(load - ref)) <= 1e-13 * np.max(np.abs(ref)), kw


def test_rigid_fields_take_the_fast_path():
    """Fields equal to the rigid cylinder's are solved by the fast path (by the data)."""
    rigid = solve_reynolds(B, S, 40, 8, half=False)
    given = solve_reynolds(B, S, 40, 8, fields=FilmFields(
        gap=lambda t, z: 1.0 + S.eps * np.cos(t), viscosity=1.0))
    assert given.force == rigid.force and given.friction_force == rigid.friction_force


def test_viscosity_scales_the_film():
    """A uniform viscosity ratio m scales pressure and force by m (the pressure scale
    uses the reference mu0) and leaves the flow as it is, to round-off (the general path
    is the fast path's film when the fields are the rigid cylinder's).
    Fails with the ratio applied as mu0/mu."""
    base = solve_reynolds(B, S, 40, 8, cavitation="none", half=False)
    thick = solve_reynolds(B, S, 40, 8, cavitation="none", fields=FilmFields(viscosity=2.5))
    assert np.array(thick.force) == pytest.approx(2.5 * np.array(base.force), rel=1e-11)
    assert thick.side_leakage == pytest.approx(base.side_leakage, rel=1e-9, abs=1e-18)


@pytest.mark.parametrize("kwargs, match", [
    (dict(gap=lambda t, z: 0.5 - np.cos(t)), "gap must be > 0"),
    (dict(viscosity=-1.0), "viscosity must be > 0"),
    (dict(density=np.nan), "density must be finite"),
    (dict(gap_rate=np.ones(7)), "gap_rate must be a number"),
    # a function returning the wrong shape met numpy's "could not be broadcast" unnamed
    (dict(gap=lambda t, z: np.ones(5)), r"film field gap: its function .* got shape \(5,\)"),
])
def test_bad_fields_raise(kwargs, match):
    with pytest.raises(ValueError, match=match):
        solve_reynolds(B, S, 16, 4, fields=FilmFields(**kwargs))


def test_a_field_function_may_return_what_broadcasts_to_the_points():
    """One value per element ((elements, 1), e.g. a viscosity taken at each element's
    mean angle) broadcasts over the element's points as numpy does: the same film as the
    array written out. A shape that does not broadcast is refused naming the field."""
    def per_element(t, z):
        return 1.0 + 0.5 * np.cos(t.mean(axis=1, keepdims=True))

    op = fe_operator(B, S, 16, 4, "P1", None, False)
    full = np.broadcast_to(per_element(op.qp_theta, op.qp_zeta), op.qp_theta.shape)
    a = solve_reynolds(B, S, 16, 4, fields=FilmFields(viscosity=per_element))
    b = solve_reynolds(B, S, 16, 4, fields=FilmFields(viscosity=lambda t, z: full))
    assert np.array_equal(a.pressure, b.pressure)
    with pytest.raises(ValueError, match=r"film field viscosity: .* got shape \(1, 3\)"):
        solve_reynolds(B, S, 16, 4, fields=FilmFields(viscosity=lambda t, z: np.ones((1, 3))))


def test_fields_with_jfo_need_p1():
    """The JFO film takes fields on P1 (its control volumes); P2 is refused by name."""
    with pytest.raises(ValueError, match="element"):
        solve_reynolds(B, S, 16, 4, "P2", cavitation="jfo", ambient_pressure=1e5,
                       fields=FilmFields(viscosity=2.0))


def test_fields_benchmark_smoke(capsys):
    """The benchmark runs and both paths solved the same film (timings are printed,
    never asserted)."""
    from benchmarks import fields
    rows = fields.main(["--quick", "--repeat", "1"])
    assert len(rows) == 6 and "general/fast" in capsys.readouterr().out
    assert all(r["gap"] < 1e-11 for r in rows)   # round-off (the rigid split)


def test_nodal_average_is_positive_and_exact_for_constants():
    """The quadrature values' carry to the nodes (the JFO films' control volumes and coarse
    levels take it): constants exactly, every nodal value within the point values'
    bounds (a field jumping by 1e4 within one cell row, where the L2 projection goes
    negative), and a smooth field at first order (one-sided at the boundary nodes:
    measured 0.18, 0.089, 0.044 on cos(theta)(1 + zeta) over 12, 24, 48 cells; the
    L2 projection is second order but not positive). Fails with the L2 projection
    (negative values) or the mean without its weights' normalisation (constants off)."""
    errors = []
    for n in (12, 24, 48):
        op = fe_operator(Bearing(radius=0.02, length=0.02, clearance=2e-5, viscosity=0.01),
                         JournalState(eps=0.5), n, n // 4, "P1", None, False, ())
        basis, th, ze = op.mesh.basis, op.qp_theta, op.qp_zeta
        assert np.allclose(nodal_average(basis, np.full(th.shape, 3.5)), 3.5, rtol=1e-14)
        step = np.where(np.abs(np.mod(th, 2 * np.pi) - 2.0) < np.pi / n, 1e4, 1.0)
        v = nodal_average(basis, step)
        assert np.all(v >= 1.0 - 1e-12) and np.all(v <= 1e4 + 1e-8)
        assert np.min(np.asarray(basis.project(step))) < 0.0     # what it replaces
        smooth = np.cos(th) * (1.0 + ze)
        x = op.mesh.theta, op.mesh.zeta
        errors.append(np.max(np.abs(nodal_average(basis, smooth)
                                    - np.cos(x[0]) * (1.0 + x[1]))))
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(orders > 0.95), (errors, orders)
