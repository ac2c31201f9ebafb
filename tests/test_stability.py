"""Lund's verdict near the centre, where the old threshold called a whirling journal stable.

The limit every test here leans on (long bearing, S = mu R^3 L / c^3, film p ~ eps sin theta
at eps -> 0): the full (Sommerfeld) film has F_r = 0 and F_t = 6 pi S c omega eps, so
K = [[0, 6 pi S omega], [-6 pi S omega, 0]] and C = 12 pi S I - k / C = omega / 2, K_eq = 0:
unstable for any mass, whirling at exactly half speed. Gumbel's half film halves k and C
(same ratio) and adds K_rr = 12 S omega eps, K_tt = 6 S omega eps: m_crit ~ eps -> 0.
"""
import math

import numpy as np
import pytest

from bearingfem import Bearing, JournalState
from bearingfem.design import Verdict, coefficients, lund_stability
from bearingfem.design.coefficients import DynamicCoefficients

B = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
OMEGA = 250.0
S = B.viscosity * B.radius ** 3 * B.length / B.clearance ** 3      # [N s/m]


def _hand_built(K, C, omega=OMEGA):
    s = JournalState(0.0, omega=omega)
    z = np.zeros((2, 2))
    return DynamicCoefficients(np.asarray(K, float), np.asarray(C, float), "inertial",
                               np.eye(2), s, (0.0, 0.0), "hand", "closed form",
                               B.clearance, z)


def test_full_sommerfeld_limit_is_unstable_for_any_mass_at_half_speed():
    """K, C of the centred full film (module docstring, derived by hand): every mass whirls,
    at nu / omega = 1/2 exactly. Fails on the old threshold, which turned K_eq = 0 into a
    critical mass of inf (stable for any mass) and a whirl ratio of 0."""
    k, c0 = 6 * math.pi * S * OMEGA, 12 * math.pi * S
    st = lund_stability(_hand_built([[0.0, k], [-k, 0.0]], c0 * np.eye(2)))
    assert st.verdict is Verdict.UNSTABLE_FOR_ANY_MASS
    assert st.critical_mass is None
    assert st.whirl_ratio == pytest.approx(0.5, rel=1e-12)
    for mass in (1e-6, 1.0, 1e6):       # the eigenvalues agree with the verdict
        A = np.block([[np.zeros((2, 2)), np.eye(2)],
                      [-np.array([[0, k], [-k, 0]]) / mass, -c0 * np.eye(2) / mass]])
        assert np.linalg.eigvals(A).real.max() > 0.0
        assert not st.stable(mass)


def test_negative_equivalent_stiffness_is_unstable_not_infinitely_stable():
    """A little negative direct stiffness (the FE noise the old code met at eps = 0):
    K_eq < 0, no crossing at a positive mass, unstable for every mass. Fails on the old
    threshold (inf)."""
    k, c0 = 6 * math.pi * S * OMEGA, 12 * math.pi * S
    st = lund_stability(_hand_built([[-12.3, k], [-k, -31.2]], c0 * np.eye(2)))
    assert st.stiffness_eq < 0.0
    assert st.verdict is Verdict.UNSTABLE_FOR_ANY_MASS and not st.stable(1e-9)


def test_stiff_isotropic_film_is_stable_for_any_mass():
    """No cross-coupling, positive K and C: nu^2 = 0, stable for any mass (the third
    verdict). Fails if the no-crossing branch reports unstable."""
    st = lund_stability(_hand_built(1e6 * np.eye(2), 1e3 * np.eye(2)))
    assert st.verdict is Verdict.STABLE_FOR_ANY_MASS
    assert st.critical_mass is None and st.whirl_ratio is None
    assert st.stable(1e9)


@pytest.mark.parametrize("model, opts", [("fem", dict(cavitation="reynolds")),
                                         ("fem", dict(cavitation="gumbel")),
                                         ("fem", dict(cavitation="none")),
                                         ("long", {}), ("short", {})])
def test_centred_journal_has_no_direct_stiffness_and_whirls(model, opts):
    """At eps = 0 the film is attitude-free: K_xx = K_yy = 0 exactly, K_xy = -K_yx, whatever
    gamma, and the journal is unstable for any mass. Fails on the old linearisation at
    EPS_FLOOR (FE Reynolds: K_xx = -12.3, K_yy = -31.2 N/m, critical mass inf)."""
    ks = []
    for gamma in (0.0, 1.0):
        kc = coefficients(B, JournalState(0.0, omega=OMEGA, gamma=gamma), model, **opts)
        assert kc.K[0, 0] == 0.0 and kc.K[1, 1] == 0.0
        assert kc.K[0, 1] == -kc.K[1, 0] > 0.0
        assert kc.force == (0.0, 0.0)
        st = lund_stability(kc)
        assert st.verdict is Verdict.UNSTABLE_FOR_ANY_MASS
        # half-frequency whirl; the FE Reynolds film's C_rr, C_tt differ by its mesh error
        # (0.49483 at the default mesh, 0.49930 at 120 x 20)
        assert st.whirl_ratio == pytest.approx(0.5, abs=6e-3)
        ks.append(kc.K[0, 1])
    assert ks[0] == pytest.approx(ks[1], rel=1e-9)


def test_gumbel_critical_mass_vanishes_linearly_toward_the_centre():
    """Long bearing, Gumbel's film: K_rr / (S omega eps) -> 12, K_tt -> 6, K_rt -> 3 pi (the
    steady half-Sommerfeld force, by hand), m_crit ~ eps and nu / omega -> 1/2. Measured
    m_crit omega / (S eps) = 52.2741 at eps 1e-3, 52.2782 at 1e-2 (-> 24 + 9 pi). Fails with
    the wedge column of C halved (-W / eps for -2 W / eps: the whirl ratio leaves 1/2). The old
    code passed it: its defect was at eps = 0 and K_eq <= 0 only."""
    m = []
    for eps in (1e-3, 1e-2):
        kc = coefficients(B, JournalState(eps, omega=OMEGA), "long", frame="local")
        K = kc.K / (S * OMEGA)
        assert K[0, 0] / eps == pytest.approx(12.0, rel=1e-3)
        assert K[1, 1] / eps == pytest.approx(6.0, rel=1e-3)
        assert K[0, 1] == pytest.approx(3 * math.pi, rel=1e-3)
        st = lund_stability(kc)
        assert st.verdict is Verdict.CRITICAL_MASS
        assert st.whirl_ratio == pytest.approx(0.5, abs=2e-5)
        m.append(st.critical_mass * OMEGA / (S * eps))
    assert m[0] == pytest.approx(m[1], rel=1e-4)
    assert m[0] == pytest.approx(24 + 9 * math.pi, rel=1e-4)


def test_fe_reynolds_critical_mass_is_linear_in_eps():
    """FE film, Reynolds' condition, 120 x 20: m_crit / eps = 1812.7, 1809.7 kg at eps 1e-2,
    1e-3 (the cavity, symmetric about theta = pi/2 to leading order, keeps F_r ~ eps^2).
    Fails if the critical mass does not go to zero with eps (passes on the old code, which was
    wrong only at eps < 1e-6)."""
    r = []
    for eps in (1e-3, 1e-2):
        st = lund_stability(coefficients(B, JournalState(eps, omega=OMEGA), "fem",
                                         n_theta=120, n_z=20, cavitation="reynolds"))
        assert st.verdict is Verdict.CRITICAL_MASS
        r.append(st.critical_mass / eps)
    assert r[0] == pytest.approx(r[1], rel=5e-3)


def test_cli_names_the_verdict_at_the_centre(capsys):
    """``bearingfem coefficients --eps 0`` says 'unstable for any mass' (it printed a
    critical mass of inf, i.e. stable for any mass, and a whirl ratio of 0)."""
    from bearingfem_app.cli import main
    assert main(["coefficients", "--ld", "1", "--eps", "0", "--model", "short"]) == 0
    out = capsys.readouterr().out
    assert "rigid journal at eps 0, 250 rad/s: unstable for any mass" in out
    assert "inf" not in out


def test_reynolds_condition_whirls_at_half_speed_in_the_mesh_limit():
    """Reynolds' condition near the centre: C_rr and C_tt differ by the mesh error only, so
    nu / omega -> 1/2 (measured 1/2 - 0.4966 = 3.4e-3 at 60 x 10, 7.0e-4 at 120 x 20,
    8.2e-5 at 240 x 40). Fails if the whirl ratio tends elsewhere (e.g. with C_tt halved)."""
    gaps = []
    for n_theta, n_z in ((60, 10), (120, 20)):
        st = lund_stability(coefficients(B, JournalState(1e-3, omega=OMEGA), "fem",
                                         n_theta=n_theta, n_z=n_z, cavitation="reynolds"))
        gaps.append(abs(st.whirl_ratio - 0.5))
    assert gaps[1] < 0.3 * gaps[0] and gaps[1] < 1e-3


def test_stability_prints_as_a_sentence():
    """print(lund_stability(kc)) is one sentence with the verdict, the critical mass and
    the whirl (old: a 15-line dataclass repr)."""
    from bearingfem import JournalState
    from bearingfem.bearing import seed_bearing
    from bearingfem.design import coefficients, lund_stability
    st = lund_stability(coefficients(seed_bearing(0.5), JournalState(0.5, omega=250.0),
                                     "short"))
    text = str(st)
    assert len(text.splitlines()) == 1 and not text.startswith("Stability(")
    assert st.verdict.value in text and f"{st.critical_mass:.6g} kg" in text
    assert f"{st.whirl_ratio:.3g} of the running speed" in text


def test_threshold_speed_default_range_reaches_its_high_end():
    """The default range ends at 300 m/s of surface speed, 30000 rad/s here; exp(log(hi))
    rounds to 30000.000000000007, which the equilibrium's speed check refused as above
    300 m/s: the default range failed for this bearing before any threshold was sought."""
    from bearingfem.design import equilibrium, threshold_speed
    eq = equilibrium(B, (0.0, -300.0), 1000.0, "short")
    mass = lund_stability(coefficients(B, eq.state, "short")).critical_mass
    th = threshold_speed(B, (0.0, -300.0), mass, "short")
    assert th.omega == pytest.approx(1000.0, rel=1e-6)


@pytest.mark.parametrize("bad, match", [
    (dict(turns=0.0), "turns"), (dict(turns=-1.0), "turns"),   # -1 hung the integrator
    (dict(samples=0), "samples"), (dict(samples=1), "samples"),
    (dict(kick=0.0), "kick"), (dict(kick=2.0), "kick"), (dict(kick=-2.0), "kick"),
    (dict(kick=float("nan")), "kick")])
def test_journal_orbit_refuses_bad_run_options_by_name(bad, match):
    """turns 0 / samples 0 raised IndexError, kick 0 returned a growth of 9e4 (a ratio of
    round-off), kick 2 started outside the clearance, NaN reached scipy's own message."""
    from bearingfem.design import equilibrium, journal_orbit
    eq = equilibrium(B, (0.0, -300.0), OMEGA, "short")
    with pytest.raises(ValueError, match=match):
        journal_orbit(B, eq, 100.0, "short", **{"turns": 5.0, "samples": 200, **bad})
    with pytest.raises(ValueError, match="eq must be an Equilibrium"):
        journal_orbit(B, eq.state, 100.0, "short")
    with pytest.raises(ValueError, match="kc must be the DynamicCoefficients"):
        lund_stability(eq)


def test_journal_orbit_takes_a_kick_against_the_load_and_refuses_a_start_past_the_bush():
    """The kick is a displacement along the load in clearances: a negative one (toward
    the bush centre) is an orbit as good as any (it was refused as not > 0); one that
    puts the start outside the clearance is refused, however small (0.95 < 1 was taken
    from eps 0.65 and the film capped at the wall)."""
    from bearingfem.design import equilibrium, journal_orbit
    eq = equilibrium(B, (0.0, -1000.0), OMEGA, "short")
    assert eq.eps > 0.5
    orbit = journal_orbit(B, eq, 0.01, "short", kick=-0.02, turns=3.0, samples=200)
    start = np.hypot(orbit.x[0], orbit.y[0]) / B.clearance
    assert orbit.distance[0] == pytest.approx(0.02 * B.clearance, rel=1e-12)
    assert start < eq.eps       # moved toward the centre, against the downward load
    with pytest.raises(ValueError, match=r"kick must be non-zero and keep the start inside "
                                         r"the clearance \(eps 1\.[0-9]+ there"):
        journal_orbit(B, eq, 0.01, "short", kick=0.95, turns=3.0, samples=200)


def test_threshold_and_orbit_tolerances_have_their_own_names_and_rtol_is_refused():
    """``rtol`` is the toolkit's film accuracy; threshold_speed's root tolerance and
    journal_orbit's integrator tolerance were called rtol too (rtol=1e-2, 1 % film accuracy
    asked, loosened Brent's search). Now ``xtol`` and ``integrator_rtol``; rtol is refused
    by name before any film. A loose value moves the answers off the default's by what it
    allows (short film, closed form): wired to nothing, or to the default, this fails."""
    from bearingfem.design import equilibrium, journal_orbit, threshold_speed
    with pytest.raises(ValueError, match=r"rtol is a film-accuracy request, got rtol=0.01; "
                                         r"the root search's tolerance is xtol"):
        threshold_speed(B, (0.0, -300.0), -1.0, "short", rtol=1e-2)   # before mass
    with pytest.raises(ValueError, match=r"xtol must lie in"):
        threshold_speed(B, (0.0, -300.0), 1.0, "short", xtol=0.0)
    eq = equilibrium(B, (0.0, -300.0), 1000.0, "short")
    mass = lund_stability(coefficients(B, eq.state, "short")).critical_mass
    # measured: 1000.14 rad/s at xtol 1e-3 against 1000.0000000000 at the default
    loose_w = threshold_speed(B, (0.0, -300.0), mass, "short", xtol=1e-3).omega
    tight_w = threshold_speed(B, (0.0, -300.0), mass, "short").omega
    assert tight_w == pytest.approx(1000.0, rel=1e-9)
    assert 1e-6 < abs(loose_w - tight_w) / tight_w < 1e-3

    eq = equilibrium(B, (0.0, -1000.0), OMEGA, "short")
    with pytest.raises(ValueError, match=r"rtol is a film-accuracy request, got rtol=0.01; "
                                         r"the orbit integrator's tolerance is "
                                         r"integrator_rtol"):
        journal_orbit(B, eq, -1.0, "short", rtol=1e-2)
    with pytest.raises(ValueError, match=r"integrator_rtol must lie in \(0, 1\)"):
        journal_orbit(B, eq, 0.01, "short", integrator_rtol=0.0)
    run = dict(turns=3.0, samples=200)
    loose = journal_orbit(B, eq, 0.01, "short", integrator_rtol=1e-4, **run)
    tight = journal_orbit(B, eq, 0.01, "short", **run)
    # measured: the loose orbit's end 2.4e-9 and 7.5e-10 off the default's (LSODA at
    # 1e-4 against 1e-9 over three turns)
    for lo, ti in ((loose.x[-1], tight.x[-1]), (loose.y[-1], tight.y[-1])):
        assert 1e-11 < abs(lo - ti) / abs(ti) < 1e-6
