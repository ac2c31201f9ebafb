"""Mass-conserving (JFO) films: exact squeeze film, mass balance, limits, hard cases."""
import numpy as np
import pytest

from bearingfem import Groove, JournalState, solve_reynolds
from bearingfem.bearing import seed_bearing
from bearingfem.fe.planar import PlanarJFO, solve_planar
from bearingfem.planar import PlanarFilm
from studies import squeeze_film as study


@pytest.fixture(scope="module")
def squeeze_runs():
    ex = study.exact()
    return [study.run(n, 5 * n, ex) for n in (50, 100, 200)]


def test_exact_squeeze_film_branches():
    """The exact solution reproduces its closed-form branches: the full film's load
    p_a l - k l^3 / 12 before the cavity opens, the opening where the mid-plane pressure
    p_a - k l^2 / 8 reaches zero, the rupture front sqrt(2 p_a / k)."""
    ex = study.exact()
    k = lambda t: study.gap_rate(t) / study.gap(t) ** 3      # 12 mu = 1  # noqa: E731
    t_open = ex.rupture_times[0]
    assert k(t_open) == pytest.approx(8 * study.AMBIENT, rel=1e-9)
    sel = ex.t < t_open - 1e-3
    assert np.allclose(ex.load[sel], study.AMBIENT - k(ex.t[sel]) / 12.0, rtol=1e-12)
    t = t_open + 0.01       # rupture branch (k still growing)
    assert np.interp(t, ex.t, ex.front) == pytest.approx(np.sqrt(2 * study.AMBIENT / k(t)),
                                                         rel=1e-4)
    # two openings and a collapse in two periods, the cavity always inside the plates
    assert len(ex.rupture_times) == 2 and len(ex.collapse_times) >= 1
    assert np.all((ex.front > 0.0) & (ex.front <= 0.5))


def test_squeeze_film_front_within_one_percent(squeeze_runs):
    """Cavity front within 1 % of the plate length over two periods (200 cells, 1000
    steps), away from the instants the cavity opens or collapses (+-0.01: there the
    exact front jumps). Measured 0.49 %; 0.98 % at half the resolution."""
    r = squeeze_runs[-1]
    assert r.front_error < 0.01
    assert r.load_error < 0.02       # measured 1.37 % of the peak load


def test_squeeze_film_converges_at_first_order(squeeze_runs):
    """Refined together in space and time (x2 each), front and load errors fall at the
    orders of upwind transport and backward Euler (measured 0.94-1.01 and 0.95-0.96;
    0.88 at 400 cells, where the event windows start to dominate)."""
    fo = study.orders([r.front_error for r in squeeze_runs])
    lo = study.orders([r.load_error for r in squeeze_runs])
    assert np.all((fo > 0.8) & (fo < 1.3)), fo
    assert np.all((lo > 0.8) & (lo < 1.3)), lo


def test_squeeze_film_mass_and_bounds(squeeze_runs):
    """Every step's global balance (inflow - outflow - change of content) holds to 1e-10
    of the run's throughput (the discrete scheme conserves mass; the flows themselves are
    checked against the pressure field in test_independent_jfo.py); the least phi is the
    exact h_min / h_max = 0.5. (phi <= 1 and p >= 0 are not asserted: the solver clips
    them.)"""
    for r in squeeze_runs:
        assert r.mass_balance < 1e-10
        # the content frozen at the smallest gap the steps see: h_min / h_max = 0.5
        assert 0.5 - 1e-12 <= r.fraction_range[0] < 0.5 + 1e-3


@pytest.fixture(scope="module")
def seed():
    return seed_bearing(1.0)


def test_flooded_groove_at_max_film_equals_reynolds(seed):
    """With a flooded groove at the maximum film, the film ruptures where Reynolds' condition
    puts it and reforms only at the groove, so JFO and Reynolds agree: their forces differ
    by the discretisation error only, falling at second order (measured 0.48, 0.13,
    0.031 % at 60x10, 120x20, 240x40: ratios 3.8, 4.0)."""
    s = JournalState(eps=0.6, omega=250.0)
    g = [Groove(angle=np.pi, width=0.1)]
    diffs = []
    for n in (30, 60, 120):
        r = solve_reynolds(seed, s, 2 * n, n // 3, cavitation="reynolds", grooves=g)
        j = solve_reynolds(seed, s, 2 * n, n // 3, cavitation="jfo", grooves=g)
        diffs.append(np.linalg.norm(np.subtract(j.force_local, r.force_local))
                     / np.linalg.norm(r.force_local))
    assert diffs[1] < 2e-3
    assert np.all(np.log2(np.array(diffs[:-1]) / diffs[1:]) > 1.8), diffs


def test_steady_journal_mass_balance(seed):
    """Steady: what the grooves feed leaves at the ends, to round-off (1e-10 relative):
    the discrete scheme conserves mass. Both flows come from the same solve's nodal
    residual, so this does not check their size: test_independent_jfo.py checks the flows
    against the Poiseuille flow through the ends integrated from the pressure field, and
    the fraction against the exact cavity law (the phi and p bounds once asserted here
    hold by clipping)."""
    s = JournalState(eps=0.7, omega=300.0, gamma=0.4)
    g = [Groove(angle=0.3, width=0.3, pressure=2e4), Groove(angle=3.5, width=0.2)]
    sol = solve_reynolds(seed, s, 96, 16, cavitation="jfo", grooves=g)
    assert sol.converged and sol.flow_in > 0
    assert abs(sol.mass_balance) < 1e-10 * sol.flow_in
    assert 0.0 < sol.cavitated_fraction < 1.0


def test_jfo_differs_from_reynolds_where_reformation_matters(seed):
    """A starved groove at the maximum film (H = 1.6) feeds the content 1.6 phi_g, which
    the Couette flow carries unchanged: the film fills only where H <= 1.6 phi_g. Below
    phi_g = H_min / 1.6 = 0.25 it never fills and carries nothing (Reynolds' condition
    would give the flooded film); above, the load grows with the supply up to the
    flooded film's at phi_g = 1."""
    s = JournalState(eps=0.6, omega=250.0)
    flooded = solve_reynolds(seed, s, 96, 16, cavitation="jfo", grooves=[Groove(np.pi, 0.1)])
    # the film's Couette throughput omega R c L / 2 [m^3/s] scales its balance when the
    # starved groove feeds (next to) nothing
    couette = 0.5 * s.omega * seed.radius * seed.clearance * seed.length
    loads = []
    for f in (0.2, 0.4, 0.7, 1.0):
        sol = solve_reynolds(seed, s, 96, 16, cavitation="jfo",
                             grooves=[Groove(np.pi, 0.1, fraction=f)])
        loads.append(np.hypot(*sol.force_local))
        assert abs(sol.mass_balance) < 1e-10 * max(sol.flow_in, couette)
        if f == 0.2:
            assert sol.pressure.max() == 0.0
            i = np.argmin(np.abs(np.mod(sol.theta, 2 * np.pi) - np.pi) + np.abs(sol.z))
            assert sol.fraction[i] == pytest.approx(1.6 * f / 0.4, rel=0.02)
    assert loads[0] == 0.0 < loads[1] < loads[2] < loads[3]
    assert loads[3] == pytest.approx(np.hypot(*flooded.force_local), rel=1e-12)


@pytest.mark.parametrize("state, grooves, ambient", [
    (JournalState(eps=0.99, omega=250.0), [Groove(np.pi, 0.1)], 0.0),
    (JournalState(eps=0.0, omega=250.0), [Groove(np.pi, 0.1)], 0.0),
    (JournalState(eps=0.5, eps_dot=30.0, omega=0.0), (), 1e5),     # pure squeeze
    (JournalState(eps=0.5, eps_dot=-30.0, omega=0.0), (), 1e5),
    (JournalState(eps=0.5), [Groove(np.pi, 0.1)], 0.0),               # nothing moves
    (JournalState(eps=0.6, omega=250.0), [Groove(np.pi, 0.1, fraction=0.0)], 0.0),
])
def test_hard_cases_no_nan(seed, state, grooves, ambient):
    """Near contact, zero eccentricity, pure squeeze, no motion, a fully starved groove:
    finite fields and the balance to round-off (p >= 0 and phi in [0, 1] hold by the
    solver's clipping, so they are not asserted)."""
    sol = solve_reynolds(seed, state, 48, 8, cavitation="jfo", grooves=grooves,
                         ambient_pressure=ambient)
    assert np.all(np.isfinite(sol.pressure)) and np.all(np.isfinite(sol.force_local))
    assert np.all(np.isfinite(sol.fraction))
    # scale: the flow the journal's motion drags or squeezes through the film
    couette = (abs(state.omega) + abs(state.eps_dot)) * seed.radius * seed.clearance \
        * seed.length
    scale = max(abs(sol.flow_in or 0.0), abs(sol.side_leakage), couette)
    assert abs(sol.mass_balance) <= 1e-10 * scale + 1e-25


def test_jfo_refusals(seed):
    s = JournalState(eps=0.5, omega=100.0)
    with pytest.raises(ValueError, match="needs a supply of oil"):
        solve_reynolds(seed, s, cavitation="jfo")
    with pytest.raises(ValueError, match="needs element 'P1'"):
        solve_reynolds(seed, s, element="P2", cavitation="jfo", grooves=[Groove(0.0, 0.1)])
    with pytest.raises(ValueError, match="ambient_pressure .* JFO-film option"):
        solve_reynolds(seed, s, ambient_pressure=1e5)
    with pytest.raises(ValueError, match="ambient_pressure must be >= 0"):
        solve_reynolds(seed, s, cavitation="jfo", ambient_pressure=-1.0)
    with pytest.raises(ValueError, match="starved groove"):
        solve_reynolds(seed, s, cavitation="reynolds", grooves=[Groove(0.0, 0.1, fraction=0.5)])


def test_planar_full_film_is_the_slider_solution():
    """A plane inclined slider (h from 2 h0 to h0) with flooded ends at ambient carries
    the classical load W = 6 mu U B^2 W / h0^2 (ln 2 - 2 (k - 1)/(k + 1)) / (k - 1)^2,
    k = 2, and needs no cavity: JFO = full film, to the mesh's error (second order)."""
    mu, U, B, Wd, h0 = 0.05, 2.0, 0.02, 0.01, 10e-6
    film = PlanarFilm(B, Wd, mu, lambda x, y, t: h0 * (2.0 - x / B), speed=U)
    exact = 6 * mu * U * B ** 2 * Wd / h0 ** 2 * (np.log(2.0) - 2.0 / 3.0)
    errs = []
    for n in (40, 80):
        sol = solve_planar(film, n, 2)
        assert sol.cavitated_fraction == 0.0
        errs.append(abs(sol.load / exact - 1))
    assert errs[1] < 1e-3 and errs[0] / errs[1] > 3.5


def test_planar_transient_reaches_the_steady_film():
    """A divergent-convergent slider pad marched in time from a full film settles on the
    steady JFO film (same cavity, same load)."""
    mu, U, B, Wd, h0 = 0.05, 2.0, 0.02, 0.01, 10e-6
    gap = lambda x, y, t: h0 * (1.0 + 0.8 * np.cos(2 * np.pi * x / B))   # noqa: E731
    film = PlanarFilm(B, Wd, mu, gap, speed=U, inlet_pressure=1e4, outlet_pressure=1e4)
    steady = solve_planar(film, 60, 2)
    tr = PlanarJFO(film, 60, 2)
    for _ in range(150):
        sol = tr.step(B / U / 10)
        assert abs(sol.mass_balance) <= 1e-10 * max(abs(sol.flow_in), abs(sol.flow_out))
    assert 0.05 < steady.cavitated_fraction < 0.9
    assert sol.load == pytest.approx(steady.load, rel=1e-6)
    assert np.allclose(sol.fraction, steady.fraction, atol=1e-6)


def test_fe_and_fv_jfo_converge_together(seed):
    """The FE film (node volumes, P1 Poiseuille) and the FV film (cells, two-point
    fluxes) of a starved groove converge to one answer: force difference 6.6, 1.8, 0.50 %
    at 48, 96, 192 cells around (ratios 3.7, 3.5); both balance to round-off."""
    from bearingfem import fvm_reynolds
    s = JournalState(eps=0.7, omega=300.0)
    w = 2 * np.pi / 12       # groove edges on grid lines of both meshes
    g = [Groove(angle=np.pi + w / 2, width=w, fraction=0.7)]
    diffs = []
    for n in (48, 96, 192):
        fe = solve_reynolds(seed, s, n, n // 6, cavitation="jfo", grooves=g)
        fv = fvm_reynolds(seed, s, n, n // 6, cavitation="jfo", grooves=g)
        diffs.append(np.linalg.norm(np.subtract(fe.force_local, fv.force_local))
                     / np.linalg.norm(fe.force_local))
        assert abs(fv.mass_balance) < 1e-10 * fv.flow_in
    assert diffs[2] < 0.006
    assert np.all(np.array(diffs[:-1]) / diffs[1:] > 3.0), diffs


def test_fe_and_fv_jfo_supply_line_converge_together(seed):
    """A flooded supply line (oil at 1 bar, 90 deg past the line of centres): the FE film
    (held nodes) and the FV film (held supply cells half a cell from its columns) converge
    to one force at second order (measured 6.3, 1.6, 0.39, 0.098 % at 48 ... 384 cells
    around) and one feed; both balance to round-off."""
    from bearingfem import fvm_reynolds
    s = JournalState(eps=0.7, omega=300.0, gamma=0.3)
    opts = dict(cavitation="jfo", supply_angle=0.3 + np.pi / 2, ambient_pressure=1e5)
    diffs = []
    for n in (48, 96, 192):
        fe = solve_reynolds(seed, s, n, n // 6, **opts)
        fv = fvm_reynolds(seed, s, n, n // 6, **opts)
        diffs.append(np.linalg.norm(np.subtract(fe.force_local, fv.force_local))
                     / np.linalg.norm(fe.force_local))
        for sol in (fe, fv):
            assert abs(sol.mass_balance) < 1e-10 * sol.flow_in
            assert 0.2 < sol.cavitated_fraction < 0.4
    assert diffs[2] < 0.005
    assert np.all(np.array(diffs[:-1]) / diffs[1:] > 3.5), diffs
    assert fv.flow_in == pytest.approx(fe.flow_in, rel=0.01)


def test_fraction_is_exported_and_rendered(seed, tmp_path):
    """JFO films carry the film fraction into VTU files and pictures; other films refuse
    the field by name."""
    import meshio
    from bearingfem.outputs.export import write_solution
    from bearingfem.outputs.render import render_film
    s = JournalState(eps=0.6, omega=250.0)
    sol = solve_reynolds(seed, s, 48, 8, cavitation="jfo",
                         grooves=[Groove(np.pi, 0.1, fraction=0.5)])
    write_solution(sol, tmp_path / "f.vtu")
    m = meshio.read(tmp_path / "f.vtu")
    assert np.isclose(m.point_data["fraction [1]"].min(), sol.fraction.min())
    assert len(m.point_data["fraction [1]"]) == 2 * len(sol.fraction)      # mirrored half
    render_film(sol, tmp_path / "f.png", field="fraction", surface="unwrapped")
    assert (tmp_path / "f.png").stat().st_size > 1000
    plain = solve_reynolds(seed, s, 48, 8)
    with pytest.raises(ValueError, match="needs a JFO film"):
        render_film(plain, tmp_path / "g.png", field="fraction")


def test_planar_periodic_sides_match_closed_sides_for_a_gap_uniform_across():
    """A gap that does not vary across the film has no flow across it: periodic and
    closed sides give the same film, up to the mesh's error (the triangles' diagonals
    couple the rows differently: 4.0e-4, 1.0e-4, 2.5e-5 at 60, 120, 240 cells - order 2),
    and the same cavity."""
    gap = lambda x, y, t: 10e-6 * (1.0 + 0.8 * np.cos(2 * np.pi * x / 0.02))   # noqa: E731
    gaps = []
    for n in (60, 120):
        sols = [solve_planar(PlanarFilm(0.02, 0.01, 0.05, gap, speed=2.0, inlet_pressure=1e4,
                                        outlet_pressure=1e4, sides=sides), n, 3)
                for sides in ("closed", "periodic")]
        assert sols[0].cavitated_fraction > 0.05
        assert sols[1].cavitated_fraction == pytest.approx(sols[0].cavitated_fraction)
        gaps.append(abs(sols[1].load / sols[0].load - 1))
    assert gaps[0] < 1e-3 and gaps[0] / gaps[1] > 3.5


def test_pocketed_pad_jfo_against_its_exact_film():
    """The pocketed pad of Almqvist, Fabricius, Spencer and Wall (J. Tribol. 2014): L 20 mm,
    a 3 mm pocket 10 um deep from x = 2 mm in a 1 um film, 1 m/s, mu 0.01 Pa s, oil 50 kPa
    above the cavitation pressure at both ends (their 100 kPa and 50 kPa). Exact 1D JFO
    film (derived here): the film ruptures at the pocket's edge, so the inlet carries
    q = U h0/2 + h0^3 p_a / (12 mu a); the pocket holds that content (theta = 2 q / (U h1))
    until its full part of length p_b h1^3 / (12 mu (U h1/2 - q)) rebuilds
    p_b = p_a (1 + (L - a - b) / a) ahead of the outlet land. Load 3780 N/m; Reynolds'
    condition, which keeps no content, lets the pocket sit at zero pressure and carries
    p_a (L - b) / 2 = 425 N/m. Computed: load error 8.0e-5, 3.4e-5, 1.1e-5 at 200, 400,
    800 cells; theta exact; the cavity's end within a cell."""
    L, a, b, h0, h1, mu, U, pa = 20e-3, 2e-3, 3e-3, 1e-6, 10e-6, 0.01, 1.0, 5e4
    q = U * h0 / 2 + h0 ** 3 * pa / (12 * mu * a)
    pb = pa * (1 + (L - a - b) / a)
    full = pb * h1 ** 3 / (12 * mu * (U * h1 / 2 - q))
    exact = pa * a / 2 + pb * full / 2 + (pb + pa) * (L - a - b) / 2
    reynolds = pa * (L - b) / 2
    assert exact / reynolds > 8
    gap = lambda x, y, t: np.where((x > a) & (x < a + b), h1, h0)   # noqa: E731
    film = PlanarFilm(L, 1e-3, mu, gap, speed=U, inlet_pressure=pa, outlet_pressure=pa)
    errs = []
    for n in (200, 400):
        s = solve_planar(film, n, 1)
        errs.append(abs(s.load / 1e-3 / exact - 1))
        cav = s.x[s.fraction < 1 - 1e-12]
        assert cav.min() == pytest.approx(a, abs=1e-12)
        assert abs(cav.max() - (a + b - full)) < L / n
        assert s.fraction.min() == pytest.approx(2 * q / (U * h1), rel=1e-10)
        assert abs(s.mass_balance) < 1e-10 * s.flow_in
    assert errs[1] < 5e-5 and errs[0] / errs[1] > 2
