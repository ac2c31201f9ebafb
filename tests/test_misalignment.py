"""Misaligned journal: the tilted gap through the general film, its moment, and checks
that hold exactly (the aligned limit, mirror symmetry, reciprocity of squeeze damping)
plus a second method (finite volumes on the same gap)."""
import numpy as np
import pytest

from bearingfem import Bearing, JournalState, fvm_reynolds, solve_reynolds
from bearingfem.fe.general import film_system
from bearingfem.fe.kernel import fe_operator, fe_pressure, film_moment
from bearingfem.fields import FilmFields, tilted_gap

B = Bearing(radius=0.01, length=0.01, clearance=20e-6, viscosity=0.0117)
S = JournalState(eps=0.6, eps_dot=0.0, gamma=0.3, gamma_dot=0.0, omega=250.0)
TILT = (1.0e-3, -0.5e-3)       # rad: |tilt| L/2 / c = 0.28 of the clearance at the ends


def test_zero_tilt_is_the_aligned_film():
    """tilt = (0, 0) returns today's film; solved on the whole length by the general
    assembly it equals the half-film fast path to 1e-10 (the weak Couette term's
    quadrature, 1.4e-12 of P at 120x20) with a zero moment (mirror-symmetric mesh).
    Fails if the tilt gap is added where it should vanish or the moment's lever is not
    measured from the mid-plane."""
    aligned = solve_reynolds(B, S, 120, 20)
    assert solve_reynolds(B, S, 120, 20, tilt=(0.0, 0.0)).force == aligned.force
    op = fe_operator(B, S, 120, 20, "P1", None, False)
    film = FilmFields().on(op, S)
    dH, dH_dt = tilted_gap(B, S, op.qp_theta, op.qp_zeta, (0.0, 0.0))
    system = film_system(op, film.plus(gap=dH, gap_rate=dH_dt), S.wedge_speed)
    res = fe_pressure(op, S, "reynolds", system=system)
    F = 2.0 * B.force_scale * 0.5 * np.array(op.force_integrals(res.pressure))
    assert F == pytest.approx(aligned.force_local, rel=1e-10)
    M = film_moment(B, op, res.pressure, S.gamma)
    assert np.abs(M).max() <= 1e-12 * np.hypot(*aligned.force) * B.length


@pytest.mark.parametrize("element", ["P1", "P2"])
@pytest.mark.parametrize("cavitation", ["none", "gumbel", "reynolds"])
def test_tilt_mirror_symmetry(element, cavitation):
    """Tilts (tx, ty) and (-tx, -ty) are mirror images in the mid-plane: equal forces,
    opposite moments, to round-off on the mirror-symmetric mesh. Fails with the tilt's
    gap not odd in z or the moment taken about another point."""
    plus = solve_reynolds(B, S, 48, 8, element, cavitation, tilt=TILT)
    minus = solve_reynolds(B, S, 48, 8, element, cavitation, tilt=(-TILT[0], -TILT[1]))
    f = np.hypot(*plus.force)
    assert np.abs(np.subtract(plus.force, minus.force)).max() <= 1e-11 * f
    assert np.abs(np.add(plus.moment, minus.moment)).max() <= 1e-11 * f * B.length
    assert np.abs(plus.moment).max() > 1e-3 * f * B.length     # not trivially zero


def test_tilt_moment_restores():
    """A journal tilted about y (its centre at z > 0 moved to +x) meets a film that
    pushes it back: M_y < 0; tilted about x (z > 0 moved to -y, the film pushes it to +y
    there, M_x = -int z dF_y): M_x < 0. Fails with the gap's tilt term or the moment's
    sign flipped."""
    my = solve_reynolds(B, S, 48, 8, tilt=(0.0, 1e-3)).moment[1]
    mx = solve_reynolds(B, S, 48, 8, tilt=(1e-3, 0.0)).moment[0]
    assert my < 0.0 and mx < 0.0


def _squeeze(state, tilt, tilt_rate):
    return solve_reynolds(B, state, 32, 8, "P2", "none", tilt=tilt, tilt_rate=tilt_rate)


@pytest.mark.parametrize("axis", ["x", "y"])
def test_squeeze_damping_is_reciprocal(axis):
    """Full film, no rotation: the film operator is self-adjoint, so the squeeze damping
    over (e_x, e_y, tilt_x, tilt_y) is a symmetric matrix (the generalised forces
    F_x, F_y, M_x, M_y are c int p dH/dq). Hence the force from a tilt rate equals the
    moment from a translation rate: dF_x/d(tilt_y') = dM_y/d(e_x') and
    dF_y/d(tilt_x') = dM_x/d(e_y') (dh/dtilt_x = z sin(alpha), dF_y = -p sin(alpha) dA,
    M_x = -int z dF_y). Checked at a tilted state
    (general gap), to round-off. Fails with the tilt rate's sign or axis swapped, or the
    moment's lever arm or sign wrong."""
    gamma = 0.0 if axis == "x" else np.pi / 2     # eps_dot moves the centre along x or y
    still = JournalState(eps=0.4, eps_dot=0.0, gamma=gamma, omega=0.0)
    moving = JournalState(eps=0.4, eps_dot=1.0 / B.clearance, gamma=gamma, omega=0.0)
    rate = (0.0, 1.0) if axis == "x" else (1.0, 0.0)
    force = _squeeze(still, TILT, rate).force[0 if axis == "x" else 1]
    M = _squeeze(moving, TILT, (0.0, 0.0)).moment
    moment = M[1] if axis == "x" else M[0]
    assert force == pytest.approx(moment, rel=1e-10)
    assert abs(force) > 0.0


def test_bad_tilt_raises():
    with pytest.raises(ValueError, match="tilt"):
        solve_reynolds(B, S, 16, 4, tilt=(np.nan, 0.0))
    with pytest.raises(ValueError, match="tilt_rate"):
        solve_reynolds(B, S, 16, 4, tilt_rate=0.1)
    with pytest.raises(ValueError, match="into the bush"):
        solve_reynolds(B, S, 16, 4, tilt=(0.0, 0.01))


@pytest.mark.parametrize("cavitation", ["none", "reynolds"])
def test_finite_volumes_on_the_tilted_gap(cavitation):
    """Second method: the finite-volume film on the same tilted gap (face conductances,
    Couette fluxes) converges to the FE film. Its second-order error extrapolated out
    (Richardson, 120x20 and 240x40) meets FE P2 at 120x20 to 0.2 % of the force and
    of the moment (measured <= 0.05 %: FV 60x10 / 120x20 / 240x40 give M_y 0.0632 / 0.0576
    / 0.0561 N m, ratio of differences 3.7, FE 0.0556). Fails with the FV or the FE tilt
    term's sign flipped, or the moment's lever measured from an end."""
    fe = solve_reynolds(B, S, 120, 20, "P2", cavitation, tilt=TILT)
    coarse, fine = (fvm_reynolds(B, S, 120 * k, 20 * k, cavitation, tilt=TILT) for k in (1, 2))
    for name in ("force", "moment"):
        a, b = np.array(getattr(coarse, name)), np.array(getattr(fine, name))
        extrapolated = b + (b - a) / 3.0
        ref = np.array(getattr(fe, name))
        assert np.abs(extrapolated - ref).max() <= 2e-3 * np.abs(ref).max(), name
    assert fine.side_leakage == pytest.approx(fe.side_leakage, rel=2e-3, abs=1e-15)


def test_finite_volumes_on_a_squeezing_and_tilting_journal():
    """Second method with the gap moving: eps_dot = 30 1/s and a tilt rate (0.05, 0.02)
    rad/s on the tilted gap, full film. The FV squeeze on a gap field is the rigid part
    eps_dot cos(theta) integrated exactly plus the rest at the cell centre; extrapolated
    (120x20, 240x40) it meets FE P2 at 120x20 to 2e-3 of the force and of the moment
    (measured 7.4e-5 and 4.0e-4; FE P2 120x20 against 240x40: 2.8e-5 and 1.4e-4). Fails
    with the rigid part added to the rest instead of taken out of it (force 1.5 off:
    planted once), which the steady tilted films above cannot see.

    The tilt rate moves the force by 1 % only, so its own part is checked apart: the full
    film is linear in its source, and the films with and without the tilt rate differ by
    the rate's film alone; that difference meets FE P2's to 2e-3 of itself (measured 4.7e-4
    force, 3.9e-4 moment). Fails with the rest taken at the cells' west faces instead of
    their centres (4.2e-2 and 2.7e-2; the whole moment 1.9e-3 off, inside the bound above:
    planted once)."""
    state = JournalState(eps=0.6, eps_dot=30.0, gamma=0.3, gamma_dot=0.0, omega=250.0)
    rate = (0.05, 0.02)

    def films(solve, *mesh):
        return (solve(B, state, *mesh, "none", tilt=TILT, tilt_rate=rate),
                solve(B, state, *mesh, "none", tilt=TILT))
    fe = films(solve_reynolds, 120, 20, "P2")
    coarse, fine = (films(fvm_reynolds, 120 * k, 20 * k) for k in (1, 2))
    for name in ("force", "moment"):
        def whole_and_rate(sols):
            moving, still = (np.array(getattr(s, name)) for s in sols)
            return moving, moving - still
        for a, b, ref in zip(*map(whole_and_rate, (coarse, fine, fe))):
            extrapolated = b + (b - a) / 3.0
            assert np.abs(extrapolated - ref).max() <= 2e-3 * np.abs(ref).max(), name


def test_equilibrium_with_a_prescribed_misalignment():
    """The tilted film balances the load (residual of the 2-D root <= 1e-8 of W); a tilt
    and its mirror image sit at the same mid-plane position with opposite moments; the
    misalignment thins the least film. Fails if the tilt is dropped on the way to the
    film (then the moment is zero and the film no thinner)."""
    from bearingfem import equilibrium
    W = (0.0, -100.0)
    opts = dict(n_theta=48, n_z=8)
    aligned = equilibrium(B, W, 250.0, "fem", **opts)
    plus = equilibrium(B, W, 250.0, "fem", tilt=(0.0, 1e-3), **opts)
    minus = equilibrium(B, W, 250.0, "fem", tilt=(0.0, -1e-3), **opts)
    assert np.abs(np.add(plus.film_force, W)).max() <= 1e-8 * 100.0
    assert plus.eps == pytest.approx(minus.eps, rel=1e-9)
    assert np.add(plus.solution.moment, minus.solution.moment) == pytest.approx(
        (0.0, 0.0), abs=1e-9 * np.abs(plus.solution.moment).max())
    assert plus.film_min < aligned.film_min
    with pytest.raises(ValueError, match="tilt needs a model that solves a tilted journal"):
        equilibrium(B, W, 250.0, "short", tilt=(0.0, 1e-3))


# (load [N], tilt [rad], options) -> (eps, gamma [rad], moment (M_x, M_y) [N m]) found by the
# previous tilted equilibrium (Powell's hybrid root, scipy.optimize.root "hybr" with its
# finite-difference Jacobian, xtol 1e-12, from the aligned equilibrium) before it moved onto
# Newton's method, rerun on the current discrete film (the Couette load's reference cylinder
# in strong form): its force residual 7e-17 and 4e-16 of the load, in 13 and 17 film solves.
# The P1 film moved the root by 3.7e-11 (eps) from the all-weak-form film's
# 0.6659124350581946; the P2 film by 3.5e-15.
PREVIOUS_TILTED_EQUILIBRIA = (
    ((0.0, -100.0), (0.0, 1e-3), dict(n_theta=48, n_z=8),
     (0.6659124350826455, -0.8082035668897363, (-0.05139060013099008, -0.03193678981654502))),
    ((30.0, -400.0), (5e-4, -5e-4), dict(n_theta=48, n_z=8, element="P2", cavitation="gumbel"),
     (0.8608017706357225, -0.9441673914991008, (-0.19975481334998746, 0.013782314842084043))),
)


@pytest.mark.parametrize("case", PREVIOUS_TILTED_EQUILIBRIA)
def test_tilted_equilibrium_matches_the_previous_root(case):
    """Newton's method on the exact 4x4 stiffness lands where the previous 2-D root did:
    eps to 1e-11 relative, gamma to 1e-11 rad, the moment to 1e-9 (measured 3e-16, 4e-16,
    5e-15; Newton stops on a step below sqrt(rtol) |q| = 3e-7 |q| and takes it, leaving
    1.4e-15 and 2.7e-15 of the load), in 5-6 film evaluations (the root took 19-27). Fails with the position
    columns of the stiffness taken on the fixed mesh: Newton then stops 6e-11 (eps) and
    2e-10 rad (gamma) off."""
    from bearingfem import equilibrium
    load, tilt, opts, (eps, gamma, moment) = case
    eq = equilibrium(B, load, 250.0, "fem", tilt=tilt, **opts)
    assert eq.eps == pytest.approx(eps, rel=1e-11)
    assert eq.state.gamma == pytest.approx(gamma, abs=1e-11)
    assert eq.solution.moment == pytest.approx(moment, rel=1e-9)
    assert eq.iterations <= 8
    assert np.abs(np.add(eq.film_force, load)).max() <= 1e-10 * np.hypot(*load)
    assert eq.friction_force == pytest.approx(eq.solution.friction_force, rel=1e-14)


@pytest.mark.parametrize("case", PREVIOUS_TILTED_EQUILIBRIA)
def test_recorded_previous_root_is_powells_on_the_current_film(case):
    """The record above is the previous route rerun on today's film: Powell's hybrid root
    (finite-difference Jacobian, xtol 1e-12) of the tilted force from the aligned
    equilibrium, to the tolerances the Newton test uses. Fails as soon as the discrete
    film changes (then rerun this route and record its values)."""
    import math
    from scipy.optimize import root
    from bearingfem import equilibrium
    load, tilt, opts, (eps, gamma, moment) = case
    o = {"element": "P1", "cavitation": "gumbel", **opts}    # the fem model's defaults
    aligned = equilibrium(B, load, 250.0, "fem", **opts)
    W = math.hypot(*load)

    def film(q):
        state = JournalState(math.hypot(*q), omega=250.0, gamma=math.atan2(q[1], q[0]))
        return solve_reynolds(B, state, o["n_theta"], o["n_z"], o["element"],
                              o["cavitation"], tilt=tilt)

    def residual(q):
        return np.add(film(q).force, load) / W

    q0 = aligned.eps * np.array([math.cos(aligned.state.gamma), math.sin(aligned.state.gamma)])
    sol = root(residual, q0, method="hybr", options=dict(xtol=1e-12))
    assert sol.success and np.abs(residual(sol.x)).max() <= 1e-10
    assert math.hypot(*sol.x) == pytest.approx(eps, rel=1e-11)
    assert math.atan2(sol.x[1], sol.x[0]) == pytest.approx(gamma, abs=1e-11)
    assert film(sol.x).moment == pytest.approx(moment, rel=1e-9)


def test_least_film_of_a_tilted_journal():
    """The equilibrium's film_min and its angle are the exact least gap of the tilted
    journal (at an end, where its centre is farthest out): against the gap of
    :func:`tilted_gap` sampled every 0.001 deg over both ends (agreement 1e-9 c, the
    sampling's error ~ eps (dtheta)^2 / 2 = 1e-10 c). Fails with the end offset's sign or
    axis swapped (then the other end, or the wrong side, is taken)."""
    from bearingfem.design.equilibrium import least_film
    state = JournalState(eps=0.6, gamma=0.3, omega=250.0)
    tilt = (1e-3, -0.5e-3)
    h_min, angle = least_film(B, state, tilt)
    theta = np.linspace(0.0, 2 * np.pi, 360001)
    c = B.clearance
    gaps = []
    for zeta in (-0.5 * B.length / B.radius, 0.5 * B.length / B.radius):
        H = 1.0 + state.eps * np.cos(theta) + tilted_gap(B, state, theta, zeta, tilt)[0]
        gaps.append(H)
    gaps = np.array(gaps)
    i = np.unravel_index(np.argmin(gaps), gaps.shape)
    assert h_min == pytest.approx(c * gaps[i], abs=1e-9 * c)
    # theta is measured from the maximum film: the least film's inertial angle is
    # theta + gamma + pi
    expected = np.mod(theta[i[1]] + state.gamma + np.pi, 2 * np.pi)
    assert abs(np.angle(np.exp(1j * (angle - expected)))) <= 1e-4
    assert least_film(B, state, (0.0, 0.0)) == pytest.approx(
        (c * (1 - state.eps), state.gamma), rel=1e-15)


def test_tilted_equilibrium_refuses_what_it_cannot_do():
    from bearingfem import Groove, equilibrium
    with pytest.raises(ValueError, match="tilt with grooves"):
        equilibrium(B, (0.0, -100.0), 250.0, "fem", n_theta=48, n_z=8, tilt=(0.0, 1e-3),
                    grooves=[Groove(angle=0.0, width=0.2)])
    with pytest.raises(ValueError, match=r"\|tilt\| L / \(2 c\) must be < eps_max"):
        equilibrium(B, (0.0, -100.0), 250.0, "fem", n_theta=48, n_z=8, tilt=(0.0, 4e-3))
    with pytest.raises(ValueError, match="exceeds what the film carries"):
        equilibrium(B, (0.0, -1e5), 250.0, "fem", n_theta=48, n_z=8, tilt=(0.0, 1e-3))
