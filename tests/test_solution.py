"""The film's result record (bearingfem.solution.FilmSolution) as a user reads it."""
from bearingfem import Bearing, JournalState, solve_reynolds


def test_printed_solution_is_a_record_not_its_fields():
    """print(sol) shows the record's numbers, not the nodal fields (before: every pressure,
    theta, z and film thickness, ~1300 numbers each at README example 1's 120 x 20 mesh,
    and a printed Equilibrium carried them too); the fields are still there, and the
    inertial force is plain floats like the local one (before: np.float64(...) in print)."""
    b = Bearing(radius=0.01, length=0.004, clearance=20e-6, viscosity=0.0117)
    sol = solve_reynolds(b, JournalState(0.6, omega=250.0), 120, 20, "P1", "reynolds")
    text = repr(sol)
    assert len(text) < 2000 and "array(" not in text and "np.float64" not in text
    assert "pressure_max=" in text and "force_local=" in text
    assert sol.pressure.shape == sol.theta.shape == sol.z.shape == sol.film_thickness.shape
    assert len(sol.pressure) > 1000
    assert all(type(f) is float for f in sol.force)


def test_summary_names_the_mesh_an_accuracy_chose():
    """A solve asked for an accuracy says which mesh it chose (before: its unknowns only,
    so `bearingfem solve --rtol` never said on which mesh its answer was found); a solve
    on a given mesh prints no such words."""
    b = Bearing(radius=0.01, length=0.004, clearance=20e-6, viscosity=0.0117)
    s = JournalState(0.6, omega=250.0)
    sol = solve_reynolds(b, s, cavitation="reynolds", rtol=1e-2)
    n_theta, n_z = sol.accuracy.mesh
    assert f"mesh {n_theta} x {n_z} chosen for rtol 0.01" in sol.summary().splitlines()[0]
    assert "chosen" not in solve_reynolds(b, s, 24, 4).summary()


def test_summary_gives_the_outflow_where_the_ends_also_draw_oil_in():
    """A full (Sommerfeld) film draws oil in at its ends where p < 0 and loses as much where
    p > 0: its net side leakage is zero to round-off, so the summary also says what leaves
    (side_outflow, > 0). A Reynolds-condition film draws nothing in at its ends (its
    outflow is its leakage): the summary gives the leakage alone."""
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    s = JournalState(0.6, omega=250.0)
    full = solve_reynolds(b, s, 48, 8, "P1", "none")
    assert abs(full.side_leakage) < 1e-9 * full.side_outflow
    assert f"{full.side_outflow:.6g} m^3/s leave where the film is above ambient" in \
        full.summary()
    cavitated = solve_reynolds(b, s, 48, 8, "P1", "reynolds")
    assert cavitated.side_outflow == cavitated.side_leakage > 0.0
    assert "leave where" not in cavitated.summary()


def test_summary_of_a_film_without_pressure_places_no_peak():
    """A centred journal (eps 0) carries no pressure: the summary said 'peak pressure 0 Pa
    at theta 3.0 deg from the maximum film' (the first node's angle) and 'side leakage
    -0 m^3/s'."""
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    text = solve_reynolds(b, JournalState(0.0, omega=250.0), 24, 4).summary()
    assert "no pressure in the film (peak 0 Pa)" in text and "at theta" not in text
    assert "-0 " not in text and "side leakage 0 m^3/s" in text
    loaded = solve_reynolds(b, JournalState(0.6, omega=250.0), 24, 4).summary()
    assert "Pa at theta" in loaded and "no pressure" not in loaded


def test_peak_pressure_sits_where_ocvirk_puts_it_in_both_frames():
    """The peak's film angle and its inertial angle against Ocvirk's short bearing, whose
    pressure eps sin(theta) / H^3 peaks at cos(theta_m) = (1 - sqrt(1 + 24 eps^2)) / (4
    eps), at the inertial angle theta_m + gamma + pi. A P2 240 x 8 Gumbel film at L/D 1/8
    is within 0.83 deg of it at eps 0.3, 0.6, 0.8 (nodes 0.75 deg apart), whatever gamma;
    bound 1.5 deg. Fails with the inertial angle turned by -gamma (planted once: 127 deg
    off at gamma 1.1), which films at gamma = 0 cannot tell."""
    import numpy as np
    b = Bearing(radius=0.01, length=0.0025, clearance=20e-6, viscosity=0.0117)
    for eps, gamma in ((0.6, 1.1), (0.6, 4.0), (0.8, 2.5)):
        theta_m = np.arccos((1.0 - np.sqrt(1.0 + 24.0 * eps ** 2)) / (4.0 * eps))
        sol = solve_reynolds(b, JournalState(eps, gamma=gamma, omega=250.0), 240, 8, "P2",
                             "gumbel")
        assert abs(sol.pressure_max_theta - theta_m) <= np.radians(1.5)
        turned = np.mod(sol.pressure_max_angle - (theta_m + gamma + np.pi) + np.pi,
                        2.0 * np.pi) - np.pi
        assert abs(turned) <= np.radians(1.5)
