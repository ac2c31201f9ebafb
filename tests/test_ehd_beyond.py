"""The elastic film beyond the rigid clearance circle (eps >= 1): the opt-in state, the
rigid films' refusal, the continuation in eps (bearingfem.ehd.beyond) and its checks."""
import numpy as np
import pytest

from bearingfem import Bearing, ElasticBush, ElasticJournalState, JournalState, solve_reynolds
from bearingfem.bearing import ELASTIC_EPS_CAP
from bearingfem.ehd.transient import ehd_compliance
from bearingfem.lubricant import Lubricant

B = Bearing(radius=0.01, length=0.004, clearance=20e-6, viscosity=0.0117)
SOLID = ElasticBush(outer_radius=0.016, modulus=110e9, poisson=0.34, model="solid")
RING = ElasticBush(outer_radius=0.016, modulus=110e9, poisson=0.34, model="ring")
OIL = Lubricant(viscosity=0.0117, barus=2e-8, density="dowson-higginson")
NT, NZ = 48, 8


def solve(eps, bush=SOLID, **kw):
    comp = ehd_compliance(bush, B.radius, B.length, NT, NZ, 0)
    return solve_reynolds(B, ElasticJournalState(eps=eps, gamma=0.3, omega=62.5), NT, NZ,
                          "P1", "reynolds", lubricant=OIL, bush=comp, **kw)


def test_the_elastic_state_admits_eps_beyond_one_up_to_its_cap_only():
    """The public JournalState keeps its rule; the opt-in state names eps and its cap.
    Fails with the cap check dropped (eps 2.5 accepted)."""
    with pytest.raises(ValueError, match=r"eps must lie in \[0, 1\)"):
        JournalState(eps=1.0)
    assert ElasticJournalState(eps=1.3).eps == 1.3
    for bad in (ELASTIC_EPS_CAP, 2.5, -0.1, float("nan")):
        with pytest.raises(ValueError, match="eps"):
            ElasticJournalState(eps=bad)


def test_rigid_films_refuse_eps_beyond_one_by_name():
    """A film without a bush has no gap at eps >= 1: solve_reynolds (rigid, and with a
    lubricant only) refuses it naming eps. Fails with the check in solve_reynolds
    dropped (the rigid film's negative gap reaches the solver)."""
    s = ElasticJournalState(eps=1.05, omega=62.5)
    with pytest.raises(ValueError, match=r"eps must lie in \[0, 1\)"):
        solve_reynolds(B, s, 24, 4)
    with pytest.raises(ValueError, match=r"eps must lie in \[0, 1\)"):
        solve_reynolds(B, s, 24, 4, "P1", "reynolds", lubricant=OIL)


def test_a_ring_bush_cannot_open_its_ends_and_is_refused_by_name():
    """The ring's slices are independent: its end slices carry the ambient pressure and
    never deflect, so the closed rigid gap there cannot open. Fails with check_opens
    dropped (the continuation then stalls with a ConvergenceError instead)."""
    with pytest.raises(ValueError, match="model='solid'"):
        solve(1.01, RING)


def test_force_is_continuous_across_the_clearance_circle():
    """The ordinary load continuation (eps < 1) and the continuation in eps (eps >= 1)
    meet at eps = 1: the jump between eps 1 - d and 1 + d falls with d like d (the force's
    slope there, ~9e3 N per unit eps on this mesh: measured 18.1, 1.78 and 0.178 N at d =
    1e-3, 1e-4, 1e-5).
    Fails with at_eps not moving the rigid gap (the continuation then solves at its start
    eps 0.95: a jump of ~130 N)."""
    jumps = []
    for d in (1e-3, 1e-4):
        lo, hi = solve(1.0 - d).force_local, solve(1.0 + d).force_local
        jumps.append(np.hypot(hi[0] - lo[0], hi[1] - lo[1]))
    assert jumps[1] < 0.2 * jumps[0]
    assert jumps[1] < 2.5                    # 1e-4 times the slope: 1.78 N of 322 N
    at_one = solve(1.0).force_local          # eps = 1 itself: the continuation's route
    below = solve(1.0 - 1e-6).force_local
    assert np.hypot(at_one[0] - below[0], at_one[1] - below[1]) < 0.1


def test_beyond_one_the_load_rises_steeply_and_the_deflection_opens_the_gap():
    """At eps >= 1 the load grows with eps, faster than below the circle (the bush is
    squeezed like an EHL contact), the elastic gap c (1 + eps cos) + w stays open, and the
    reported deflection is the compliance of the reported pressure (w = C p). Fails with
    the gap shift's sign flipped in at_eps (the continuation then moves eps backwards)."""
    eps = [0.98, 1.0, 1.02, 1.04, 1.06]
    sols = [solve(e) for e in eps]
    load = np.array([np.hypot(*s.force_local) for s in sols])
    assert np.all(np.diff(load) > 0.0)
    slope = np.diff(load) / 0.02
    assert np.all(np.diff(slope) > 0.0) and slope[-1] > 1.5 * slope[0]   # 7.4e3 to 1.4e4 N
    comp = ehd_compliance(SOLID, B.radius, B.length, NT, NZ, 0).matrix()
    for e, s in zip(eps, sols):
        h = B.clearance * (1 + e * np.cos(np.asarray(s.theta))) + s.deformation
        assert np.allclose(s.film_thickness, h, rtol=1e-9, atol=1e-15)
        assert s.film_min > 0.0 and np.all(np.isfinite(s.pressure))
    s = sols[-1]
    # w = C p at the grid nodes (the periodic mesh's nodes are the grid's, in order)
    th, z = np.asarray(s.theta), np.asarray(s.z)
    j = np.rint(th / (2 * np.pi / NT)).astype(int) % NT
    k = np.rint((z / B.radius + 0.2) / 0.4 * NZ).astype(int)
    node = j * (NZ + 1) + k
    p = np.zeros(NT * (NZ + 1))
    p[node] = s.pressure
    assert np.allclose(s.deformation, (comp @ p)[node], rtol=1e-9,
                       atol=1e-9 * np.max(np.abs(s.deformation)))


def test_only_a_model_declaring_beyond_clearance_takes_eps_beyond_one():
    """Contract rule 15 at the registry: "fem-ehd" declares the cap, the rigid models
    refuse eps >= 1 by name, before any work; the mechanism's film effect moves its wall
    to the declared cap for "fem-ehd" and keeps it at 1 for a rigid model. Fails with
    the registry's check_state dropped (the closed form then returns a force at eps 1.05)."""
    from bearingfem.models import FILM_MODELS
    from mechanism.effects import FilmEffect
    s = ElasticJournalState(eps=1.05, omega=62.5)
    for name in ("short", "fem"):
        with pytest.raises(ValueError, match=r"eps must lie in \[0, 1\)"):
            FILM_MODELS[name].film_force(B, s)
    assert FILM_MODELS["fem-ehd"].beyond_clearance == ELASTIC_EPS_CAP
    assert FILM_MODELS["fem"].beyond_clearance == 0.0
    assert FilmEffect(B, "fem-ehd", dict(n_theta=24, n_z=4, bush=SOLID, modes=8)).wall \
        == ELASTIC_EPS_CAP
    assert FilmEffect(B, "short").wall == 1.0


def test_a_warm_start_beyond_one_gives_the_cold_film():
    """A run's film solves start from the previous solution (``start``); beyond eps = 1
    that warm start is tried at full coupling before the continuation in eps. It must give
    the same film as the cold continuation (to the solver's tolerance: 4e-16 of the peak
    measured here). Fails with the warm Newton run at a coupling s = 0.9 (a film of 90 %
    of the deflection and viscosity rise, returned as converged: 7.8 % off in force, 10 %
    in pressure)."""
    cold = solve(1.03)
    near = solve(1.025)
    warm = solve(1.03, start=near)
    assert np.max(np.abs(warm.pressure - cold.pressure)) < 1e-7 * cold.pressure.max()
    assert np.allclose(warm.force_local, cold.force_local, rtol=1e-7)


def test_a_warm_start_inside_the_circle_gives_the_cold_film():
    """The same below eps = 1, where the warm start is tried at full coupling before the
    load continuation (bearingfem.ehd.newton.solve_ehd). Fails with the warm Newton run at
    a coupling s = 0.9 (only a benchmark's smoke test caught that before)."""
    cold = solve(0.9)
    warm = solve(0.9, start=solve(0.895))
    assert np.max(np.abs(warm.pressure - cold.pressure)) < 1e-7 * cold.pressure.max()
    assert np.allclose(warm.force_local, cold.force_local, rtol=1e-7)
