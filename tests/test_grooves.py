"""Axial supply grooves on the Reynolds-condition films, FE and FV."""
import numpy as np
import pytest

from bearingfem import Bearing, Groove, JournalState, fvm_reynolds, solve_reynolds

B = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
MOVING = JournalState(0.3, 20.0, 0.4, 5.0, 250.0)


def test_a_narrowing_groove_at_the_maximum_film_becomes_the_supply_line():
    """An ambient groove of width w centred at the maximum film tends to the supply line
    there (Raimondi & Boyd's film) as w -> 0, at first order in w (measured gaps 5.06,
    2.36, 1.14 N at w = 0.2, 0.1, 0.05 rad on 120x20 P1)."""
    s = JournalState(0.6, omega=250.0)
    line = np.array(solve_reynolds(B, s, 120, 20, "P1", "none",
                                   supply_angle=s.gamma + np.pi).force_local)
    gaps = [np.linalg.norm(np.array(solve_reynolds(
        B, s, 120, 20, "P1", "none",
        grooves=[Groove(angle=s.gamma + np.pi, width=w)]).force_local) - line)
        for w in (0.2, 0.1, 0.05)]
    assert gaps[2] < 0.005 * np.linalg.norm(line)
    assert 1.7 < gaps[0] / gaps[1] < 2.5 and 1.7 < gaps[1] / gaps[2] < 2.5


@pytest.mark.parametrize("pressure", [0.0, 2e5])
@pytest.mark.parametrize("solver", ["fem", "fvm"])
def test_full_film_feed_equals_side_leakage(solver, pressure):
    """Mass: in the full film what two grooves feed leaves through the ends, to round-off,
    whether the journal turns, squeezes or whirls (both discretisations are conservative)."""
    gr = [Groove(angle=1.0, width=0.3, pressure=pressure),
          Groove(angle=1.0 + np.pi, width=0.3, pressure=pressure)]
    sol = (solve_reynolds(B, MOVING, 120, 20, "P1", "none", grooves=gr) if solver == "fem"
           else fvm_reynolds(B, MOVING, 120, 20, "none", grooves=gr))
    assert sol.flow_in == pytest.approx(sol.side_leakage, rel=1e-10)
    assert abs(sol.flow_in) > 1e-9
    # the Reynolds-condition films do not conserve mass: they report no feed
    cav = solve_reynolds(B, MOVING, 60, 10, "P1", "reynolds", grooves=gr)
    assert cav.flow_in is None


def test_fe_and_fv_meet_on_a_grooved_film():
    """Two ambient grooves, Reynolds condition: the FE-FV force gap closes with the mesh
    (measured 4.47 %, 3.04 %, 0.56 % at 60x12, 120x24, 240x48; 4.77, 3.22, 0.57 % before
    the FE mesh put its lines on the groove edges: the finite volumes still snap the edges
    to their grid within half a cell, so the gap is first order, not smooth)."""
    gr = [Groove(angle=1.0, width=0.3), Groove(angle=1.0 + np.pi, width=0.3)]
    gaps = []
    for n_theta, n_z in ((60, 12), (120, 24), (240, 48)):
        fe = np.array(solve_reynolds(B, MOVING, n_theta, n_z, "P1", "reynolds",
                                     grooves=gr).force_local)
        fv = np.array(fvm_reynolds(B, MOVING, n_theta, n_z, "reynolds", grooves=gr).force_local)
        gaps.append(np.linalg.norm(fe - fv) / np.linalg.norm(fe))
    assert gaps[2] < gaps[1] < gaps[0] and gaps[2] < 0.01


def test_a_flooded_groove_holds_its_pressure_and_feeds_the_film():
    s = JournalState(0.0, omega=0.0)          # no motion: the film is the groove's alone
    g = Groove(angle=0.5, width=0.4, pressure=1e5)
    sol = solve_reynolds(B, s, 60, 10, "P1", "reynolds", grooves=[g])
    assert sol.pressure_max == pytest.approx(1e5)
    assert sol.pressure.min() == 0.0           # a cavity (p >= 0 holds by clipping)
    # a centred journal is pushed away from a single pressurised groove
    fx, fy = sol.force
    assert np.hypot(fx, fy) > 0 and np.cos(np.arctan2(fy, fx) - (g.angle + np.pi)) > 0.99


@pytest.mark.parametrize("kwargs, message", [
    (dict(grooves=[Groove(angle=0.0, width=0.2, fraction=0.5)]), "a starved groove"),
    (dict(grooves=[Groove(angle=0.0, width=0.2)], supply_angle=0.0), "not both"),
    (dict(grooves=["groove"]), "grooves must be bearingfem.Groove"),
])
def test_grooves_refuse_what_they_cannot_do(kwargs, message):
    with pytest.raises(ValueError, match=message):
        solve_reynolds(B, MOVING, 60, 10, **kwargs)
    with pytest.raises(ValueError, match="groove width must lie in"):
        Groove(angle=0.0, width=4.0)


def test_grooved_film_starts_from_its_coarser_meshes(monkeypatch):
    """Nested iteration holds the grooves at their pressures on every coarse level, so a
    cold grooved Reynolds-condition solve takes two or three set iterations (from its own
    full film it took 15) and gives the same pressure."""
    import bearingfem.fe.grooved as grooved
    import bearingfem.fe.multilevel as multilevel
    s = JournalState(eps=0.8, omega=250.0, gamma=1.0)
    g = [Groove(angle=0.5, width=0.3, pressure=2e5), Groove(angle=3.5, width=0.2,
                                                            pressure=1e5)]
    nested = solve_reynolds(B, s, 240, 40, cavitation="reynolds", grooves=g)
    assert nested.iterations <= 3
    grooved.bearing_fixed_operator.cache_clear()    # the grooved film's levels with it
    monkeypatch.setattr(multilevel, "COARSEST_FREE_DOFS", 10 ** 9)
    cold = solve_reynolds(B, s, 240, 40, cavitation="reynolds", grooves=g)
    grooved.bearing_fixed_operator.cache_clear()
    assert cold.iterations > 10
    np.testing.assert_allclose(nested.pressure, cold.pressure, rtol=0,
                               atol=1e-9 * cold.pressure.max())


def test_a_groove_angle_in_degrees_is_named():
    """An angle of more than a turn is the degrees a reader typed, refused with its value
    in radians (Groove(angle=90, ...) was a groove at 90 rad); a turn's angles, negative
    ones too, are kept."""
    with pytest.raises(ValueError, match=r"groove angle 90 rad is more than a turn: typed in "
                                         r"degrees\? \(90 deg = 1.571 rad\)"):
        Groove(angle=90.0, width=0.3)
    assert Groove(angle=-np.pi, width=0.3).angle == -np.pi
    assert Groove(angle=2 * np.pi, width=0.3).angle == 2 * np.pi
    # the refusal names the range, and the way for a computed angle (a pad's pivot + 90 deg)
    with pytest.raises(ValueError, match=r"lies in \[-2 pi, 2 pi\] rad \(a computed one: "
                                         r"wrap it, angle % \(2 pi\)\)"):
        Groove(angle=np.radians(420.0), width=0.3)
