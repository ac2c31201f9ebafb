"""Grooved films on the bearing-fixed mesh (bearingfem.fe.grooved): the same discrete film
as the grooves' moving mesh, exact partials in gamma, and no rebuild for a new angle."""
import math
from dataclasses import replace

import numpy as np
import pytest
from skfem import BilinearForm
from skfem.helpers import dot, grad

from bearingfem import Bearing, Groove, JournalState, solve_reynolds
from bearingfem.fe.assembly import fe_operator, film_operator
from bearingfem.fe.grooved import groove_operator_for, grooved_derivatives, grooved_force
from bearingfem.fe.kernel import fe_pressure, groove_pressures
from bearingfem.routes import fe_force
from bearingfem.scales import force_factor
from bearingfem.caches import clear_caches
from bearingfem.fe.grooved import grooved_pressure

B = Bearing(radius=0.05, length=0.1, clearance=100e-6, viscosity=0.02)
OMEGA = 100.0 * math.pi
#: odd widths and places (edges nowhere near a uniform grid), one groove pressurised
GROOVES = (Groove(angle=0.3, width=math.radians(17.0)),
           Groove(angle=0.3 + 2.9, width=math.radians(23.0), pressure=2e4))
#: squeezing and whirling: every term of the source and of the wedge speed
MOVING = JournalState(0.6, 0.3, 1.3, 2.0, OMEGA)
CASES = [(cav, el, n, z) for cav in ("none", "gumbel", "reynolds")
         for el, n, z in (("P1", 41, 8), ("P2", 23, 4))]


def moving_mesh_force(state, n, z, element, cavitation):
    """The grooved film as it was solved before: a mesh in the film frame whose first line
    is the first groove's edge at this journal angle (rebuilt per angle)."""
    op = fe_operator(B, state, n, z, element, None, True, GROOVES)
    res = fe_pressure(op, state, cavitation, dirichlet=groove_pressures(B, op, GROOVES))
    return force_factor(B, True) * op.force_integrals(res.pressure, cavitation == "gumbel")


@pytest.mark.parametrize("cavitation, element, n, z", CASES)
def test_the_bearing_fixed_mesh_solves_the_moving_meshs_film(cavitation, element, n, z):
    """Both meshes start at the first groove's edge and grade the same arcs, so the fixed
    mesh is the moving one turned by gamma: the forces agree to round-off (measured
    <= 5e-14 relative). Fails with the force's rotation (or the load's) turned the wrong
    way, or the gap's harmonics read at phi + gamma."""
    for gamma in (0.0, 1.3, -2.2):
        s = replace(MOVING, gamma=gamma)
        old = moving_mesh_force(s, n, z, element, cavitation)
        new, _ = grooved_force(B, s, groove_operator_for(B, n, z, element, GROOVES), GROOVES,
                               cavitation)
        np.testing.assert_allclose(new, old, rtol=0, atol=1e-11 * np.abs(old).max())


def test_the_harmonic_tables_equal_a_direct_assembly_of_the_turned_gap():
    """sum_m of the seven tables at (eps, gamma) against scikit-fem assembling
    (1 + eps cos(phi - gamma))^3 grad u . grad v directly, and its gamma-partial against
    the assembled 3 H^2 eps sin(phi - gamma): equal to round-off (both at the basis's own
    quadrature). Fails with any harmonic's amplitude (A_1 = a_1 + 3 a_3 / 4, ...) wrong."""
    gop = groove_operator_for(B, 30, 6, "P2", GROOVES)
    op = gop.op
    eps, gamma = 0.7, 2.1

    @BilinearForm
    def turned(u, v, w):
        return (1.0 + eps * np.cos(w.x[0] - gamma)) ** 3 * dot(grad(u), grad(v))

    @BilinearForm
    def turned_dgamma(u, v, w):
        H = 1.0 + eps * np.cos(w.x[0] - gamma)
        return 3.0 * H ** 2 * eps * np.sin(w.x[0] - gamma) * dot(grad(u), grad(v))

    for form, wrt in ((turned, None), (turned_dgamma, "gamma")):
        direct = form.assemble(op.mesh.basis).toarray()
        ours = op.stiffness(0.0).copy()
        ours.data = gop.values(eps, gamma, wrt)
        np.testing.assert_allclose(ours.toarray(), direct, rtol=0,
                                   atol=1e-12 * np.abs(direct).max())


@pytest.mark.parametrize("cavitation, element, n, z", CASES)
def test_the_exact_partials_match_central_differences(cavitation, element, n, z):
    """d/dgamma (and d/deps, d/deps_dot, d/dw = -d/dgamma_dot / 2) by sensitivity on the
    solve's factors against central differences of the force (h = 1e-6: agreement measured at <= 3e-9 of
    the largest partial, the cavitated set held across the step). Fails with the rotation
    term (F_t, -F_r) dropped, the dK/dgamma P term dropped or the load's partial's sign
    flipped."""
    gop = groove_operator_for(B, n, z, element, GROOVES)
    d = grooved_derivatives(B, MOVING, gop, GROOVES, cavitation)
    h = 1e-6

    def force(**shift):
        s = replace(MOVING, **{k: getattr(MOVING, k) + v for k, v in shift.items()})
        return np.array(grooved_force(B, s, gop, GROOVES, cavitation)[0])

    for name, exact in (("gamma", d.d_gamma), ("eps", d.d_eps), ("eps_dot", d.d_eps_dot),
                        ("gamma_dot", -2.0 * np.array(d.d_wedge))):
        fd = (force(**{name: h}) - force(**{name: -h})) / (2.0 * h)
        np.testing.assert_allclose(exact, fd, rtol=0, atol=1e-6 * np.abs(fd).max(),
                                   err_msg=name)


def test_a_new_journal_angle_builds_no_mesh_and_no_operator():
    """The force, its partials and the whole film at new journal angles reuse the one
    bearing-fixed operator: the mesh/operator cache gains no entry (the moving mesh built
    one per angle). Fails if the grooved films are routed back to the moving mesh."""
    s = JournalState(0.6, omega=OMEGA, gamma=0.1)
    fe_force(B, s, 24, 4, "P2", "reynolds", grooves=GROOVES)
    before = film_operator.cache_info().misses
    for gamma in np.linspace(0.2, 6.0, 7):
        t = replace(s, gamma=float(gamma))
        fe_force(B, t, 24, 4, "P2", "reynolds", grooves=GROOVES)
        solve_reynolds(B, t, 24, 4, "P2", "reynolds", grooves=GROOVES)
    assert film_operator.cache_info().misses == before


@pytest.mark.parametrize("cavitation", ["none", "reynolds"])
def test_the_whole_film_equals_the_moving_meshs_whole_length_film(cavitation):
    """solve_reynolds on the half bearing-fixed mesh against the whole-length film (still
    solved on the grooves' moving mesh, mirrored diagonals: the same half, doubled): force,
    friction, leakage, feed, peak and its film angle agree to round-off. Fails with the
    nodes' film angles left in phi (the peak's angle moves by gamma) or the friction read
    on the gap at phi."""
    s = replace(MOVING, gamma=2.0)
    half = solve_reynolds(B, s, 41, 8, "P1", cavitation, grooves=GROOVES)
    whole = solve_reynolds(B, s, 41, 8, "P1", cavitation, grooves=GROOVES, half=False)
    for name in ("force_local", "friction_force", "side_leakage", "pressure_max",
                 "pressure_max_theta", "pressure_max_angle", "cavitated_fraction"):
        np.testing.assert_allclose(getattr(half, name), getattr(whole, name), rtol=1e-9,
                                   atol=1e-12, err_msg=name)
    if cavitation == "none":
        assert half.flow_in == pytest.approx(whole.flow_in, rel=1e-9)


def test_warm_starts_change_the_cost_not_the_answer():
    """fe_force warm from a nearby state's result, and the designer's partials after a
    solve at a far state (the operator's last set), give the cold answers to the solver's
    tolerance (measured 1e-14), the warm force in fewer active-set iterations. Fails if
    the last film is reused at another state, or the warm set is dropped (as many
    iterations as cold)."""
    s = JournalState(0.6, omega=OMEGA, gamma=-0.7)
    near = replace(s, eps=0.603, gamma=-0.69)
    cold_f, cold = fe_force(B, s, 24, 4, "P2", "reynolds", grooves=GROOVES)
    _, prev = fe_force(B, near, 24, 4, "P2", "reynolds", grooves=GROOVES)
    warm_f, warm = fe_force(B, s, 24, 4, "P2", "reynolds", grooves=GROOVES, warm=prev)
    np.testing.assert_allclose(warm_f, cold_f, rtol=1e-10)
    assert warm.iterations < cold.iterations
    gop = groove_operator_for(B, 24, 4, "P2", GROOVES)
    ref = grooved_derivatives(B, s, gop, GROOVES)
    grooved_force(B, replace(s, eps=0.2, gamma=2.0), gop, GROOVES)     # far away
    again = grooved_derivatives(B, s, gop, GROOVES)
    for name in ("force", "d_eps", "d_eps_dot", "d_wedge", "d_gamma"):
        np.testing.assert_allclose(getattr(again, name), getattr(ref, name), rtol=1e-10,
                                   err_msg=name)


def test_a_film_solved_on_another_mesh_starts_the_next_mesh():
    """A mesh search solves one state on several meshes: the second mesh's first cavitated
    set comes from the first mesh's film, interpolated, instead of its coarse levels. The
    answer is the cold solve's to round-off (measured 3e-15, the same cavitated set), in
    fewer active-set iterations (measured 3 against 7) and without building a coarse level.
    Fails if the first film is not kept (the coarse level is built) or its pressure is not
    interpolated (a start from no cavity: 26 iterations against the cold 7; both tried)."""
    s = JournalState(0.7, 0.0, 1.1, 0.0, OMEGA)
    grading = (1.3, 0.6)
    clear_caches()
    cold = grooved_pressure(groove_operator_for(B, 144, 24, "P2", GROOVES, grading), B, s,
                            GROOVES)
    clear_caches()
    grooved_pressure(groove_operator_for(B, 72, 12, "P2", GROOVES, grading), B, s, GROOVES)
    gop = groove_operator_for(B, 144, 24, "P2", GROOVES, grading)
    warm = grooved_pressure(gop, B, s, GROOVES)
    np.testing.assert_allclose(warm.pressure, cold.pressure, rtol=0,
                               atol=1e-12 * cold.pressure.max())
    assert "coarse" not in gop.levels
    assert warm.iterations < cold.iterations
    clear_caches()


def _clear_operators():
    from bearingfem.fe.grooved import grooved_operator
    from bearingfem.fe.mesh import film_mesh
    film_operator.cache_clear()
    film_mesh.cache_clear()
    grooved_operator.cache_clear()


def test_equilibrium_hands_its_last_film_to_the_solution_and_coefficients():
    """equilibrium() keeps the film at its answer with its exact partials on the grooved
    operator; the Equilibrium's solution and coefficients() there take them, and equal a
    cold solve and cold coefficients (caches cleared) to 1e-8 (measured 4e-15, round-off);
    K/C at another state after it are that state's own. Fails if the kept partials are
    returned at another state (the key check dropped: K at the nearby state would be the
    equilibrium's, 11 % off; run), or the solution is taken from a film of another state
    (eps 0.1 % off: Newton's residual check raises; run)."""
    from bearingfem.design import coefficients, equilibrium
    opts = dict(n_theta=30, n_z=6, element="P2", cavitation="reynolds", grooves=GROOVES)
    _clear_operators()
    eq = equilibrium(B, (0.0, -2.0e4), OMEGA, "fem", **opts)
    kc = coefficients(B, eq.state, "fem", **opts)
    near = replace(eq.state, eps=eq.eps + 0.02)
    kc_near = coefficients(B, near, "fem", **opts)
    _clear_operators()
    cold_sol = solve_reynolds(B, eq.state, **opts)
    _clear_operators()
    cold = coefficients(B, eq.state, "fem", **opts)
    _clear_operators()
    cold_near = coefficients(B, near, "fem", **opts)
    for got, ref in ((kc, cold), (kc_near, cold_near)):
        np.testing.assert_allclose(got.K, ref.K, rtol=1e-8, atol=1e-8 * np.abs(ref.K).max())
        np.testing.assert_allclose(got.C, ref.C, rtol=1e-8, atol=1e-8 * np.abs(ref.C).max())
    np.testing.assert_allclose(eq.solution.pressure, cold_sol.pressure, rtol=1e-8,
                               atol=1e-8 * cold_sol.pressure_max)
    assert eq.pressure_max == pytest.approx(cold_sol.pressure_max, rel=1e-8)


def test_a_second_bearing_of_the_same_shape_gets_its_own_coefficients():
    """The bearing-fixed operator is shared by every bearing of one L/D, and keeps the last
    film and its partials. K and C of a second bearing (its viscosity 1.5 times the first's,
    the same state, right after the first's) must be its own: with the grooves at ambient
    pressure the dimensionless film is the same, so K and C scale with the viscosity exactly.
    Old: the first bearing's K and C came back (the kept film's key held no bearing)."""
    from dataclasses import replace

    from bearingfem import coefficients
    grooves = (Groove(angle=0.5 * np.pi, width=0.3), Groove(angle=-0.5 * np.pi, width=0.3))
    b1 = Bearing(radius=0.02, length=0.02, clearance=40e-6, viscosity=0.02)
    b2 = replace(b1, viscosity=0.03)
    s = JournalState(eps=0.5, omega=200.0, gamma=-1.2)
    opts = dict(n_theta=24, n_z=4, element="P2", cavitation="reynolds", grooves=grooves)
    k1 = coefficients(b1, s, "fem", **opts)
    k2 = coefficients(b2, s, "fem", **opts)
    np.testing.assert_allclose(k2.K, 1.5 * k1.K, rtol=1e-9, atol=1e-9 * np.abs(k1.K).max())
    np.testing.assert_allclose(k2.C, 1.5 * k1.C, rtol=1e-9, atol=1e-9 * np.abs(k1.C).max())
