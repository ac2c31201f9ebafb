"""Thermal films: the energy equation's balance, the dissipation against the film's
power loss, the adiabatic Couette film's closed-form temperature rise, the isothermal
limit, heating and carry-over, the walls, the JFO thermal film, the thermal equilibrium
and its coefficients, the temperature drawn and exported (the scene BEARING, GROOVES,
STATE, VG32, SUPPLY is shared with the other test_thermal_*.py and test_thd_*.py)."""
import math
from dataclasses import replace

import numpy as np
import pytest

from bearingfem import Bearing, Groove, JournalState, Lubricant, solve_reynolds
from bearingfem.routes.thd import solve_thd
from bearingfem.thermal import Thermal
from bearingfem.thermal.energy import film_flow

BEARING = Bearing(radius=0.025, length=0.025, clearance=50e-6, viscosity=0.02)
GROOVES = [Groove(angle=0.5 * math.pi, width=0.2), Groove(angle=-0.5 * math.pi, width=0.2)]
STATE = JournalState(eps=0.6, omega=3000 * 2 * math.pi / 60, gamma=-0.3)
VG32 = Lubricant.iso_vg(32)
SUPPLY = 313.15                     # [K], 40 C


@pytest.mark.parametrize("thermal", [
    Thermal(SUPPLY),
    Thermal(SUPPLY, carry_over=0.8),
    Thermal(SUPPLY, model="conducting", carry_over=0.5),
    Thermal(SUPPLY, model="conducting", bush_coefficient=800.0, ambient_temperature=300.0,
            journal_coefficient=2000.0, journal_temperature=330.0),
], ids=["adiabatic", "adiabatic-carry-over", "conducting-zero-flux", "conducting-given"])
def test_energy_balance_closes_to_round_off(thermal):
    """dissipation = convected + bush + journal + grooves to 1e-11 of the dissipation, for
    every wall model; the zero-flux journal takes no net heat (1e-11); the oil is hotter
    than its supply. Fails if any part of the balance is reported from other fields than
    the ones solved (e.g. the bush's heat against 0 K, not the ambient)."""
    sol = solve_thd(BEARING, STATE, 48, 8, lubricant=VG32, thermal=thermal, grooves=GROOVES)
    bal = sol.thermal.balance
    assert abs(bal.residual) < 1e-11 * bal.dissipation
    parts = bal.convected + bal.bush + bal.journal + bal.grooves
    assert parts == pytest.approx(bal.dissipation, rel=1e-11)
    if thermal.model == "conducting" and thermal.journal_temperature is None:
        assert abs(bal.journal) < 1e-11 * bal.dissipation
        assert bal.bush > 0.0
    if thermal.model == "adiabatic":
        assert bal.bush == bal.journal == 0.0
    assert sol.temperature_max > SUPPLY + 5.0
    assert np.all(np.isfinite(sol.temperature))


def test_dissipation_is_the_films_power_loss():
    """int Phi over the whole film (grooves included) = friction torque x omega: the
    Reynolds equation tested with p itself turns the Poiseuille dissipation into the
    Couette wedge's pumping work (grooves at ambient, so no pumping power there). The
    discrete film holds the identity too (P K P = P b on the complementarity's solution,
    the quadratures alike): 2.4e-11 and 3.6e-11 measured at 48 x 8 and 96 x 16. The
    Poiseuille part alone is 5 % of the total, so a factor 2 slip in either part fails."""
    thermal = Thermal(SUPPLY, carry_over=0.8)
    errors = []
    for n in ((48, 8), (96, 16)):
        sol = solve_thd(BEARING, STATE, *n, lubricant=VG32, thermal=thermal, grooves=GROOVES)
        basis = sol.mesh.basis
        mu = VG32.viscosity_at(np.asarray(basis.interpolate(sol.pressure)),
                               temperature=np.asarray(basis.interpolate(sol.temperature)))
        flow = film_flow(BEARING, STATE, basis, sol.pressure / BEARING.pressure_scale,
                         np.ones(basis.N), mu, VG32)
        total = float(np.sum(flow.dissipation * BEARING.radius ** 2 * basis.dx))
        errors.append(abs(total / (sol.friction_torque * STATE.omega) - 1.0))
    assert max(errors) < 1e-9


def _couette_rise(oil, theta, beta):
    """The adiabatic concentric film's temperature [K] at the angle theta past the supply:
    rho cp (U h/2) dT/dx = mu(T) U^2/h with mu = mu0 exp(-beta (T - T0)) gives
    T = T0 + ln(1 + 2 beta mu0 U x / (rho cp h^2)) / beta (beta -> 0: linear)."""
    U, x, h = STATE.omega * BEARING.radius, BEARING.radius * theta, BEARING.clearance
    a = 2.0 * oil.viscosity * U * x / (oil.mass_density * oil.specific_heat * h ** 2)
    return SUPPLY + (np.log1p(beta * a) / beta if beta else a)


def _past_supply(sol):
    t = sol.theta - np.min(sol.theta)
    return np.where(np.isclose(sol.theta, np.max(sol.theta)), 2.0 * math.pi, t)


def test_adiabatic_couette_film_closed_form():
    """Concentric journal, a supply line, adiabatic: no pressure, and the temperature
    rises along the film as the closed form of :func:`_couette_rise` with the exponential
    oil (13 K over the turn). Nodal error 4.9e-3, 1.3e-3, 3.2e-4 K on 16, 32, 64 cells:
    order 2; the isoviscous oil's linear rise P1 holds exactly: to 6e-9 of it (2e-6 K,
    the conditioning of the solve at a cell Peclet number ~1e4).
    Fails with the Couette flux U h (not U h/2) or the dissipation mu U^2/(2h)."""
    oil = Lubricant.two_point((SUPPLY, 0.0278), (373.15, 0.00466), density=870.0,
                              specific_heat=1950.0, conductivity=0.13, law="exponential")
    state = replace(STATE, eps=0.0, gamma=0.0)
    errors = []
    for n in (16, 32, 64):
        sol = solve_thd(BEARING, state, n, 4, lubricant=oil, thermal=Thermal(SUPPLY),
                        supply_angle=math.pi)
        exact = _couette_rise(oil, _past_supply(sol), oil.temperature_exponent)
        errors.append(float(np.max(np.abs(sol.temperature - exact))))
    assert exact.max() - SUPPLY > 10.0
    orders = np.log2(np.array(errors[:-1]) / errors[1:])
    assert np.all(orders > 1.9), orders
    assert errors[-1] < 5e-4
    flat = Lubricant(0.0278, mass_density=870.0, specific_heat=1950.0, conductivity=0.13)
    sol = solve_thd(BEARING, state, 16, 4, lubricant=flat, thermal=Thermal(SUPPLY),
                    supply_angle=math.pi)
    np.testing.assert_allclose(sol.temperature, _couette_rise(flat, _past_supply(sol), 0.0),
                               rtol=3e-8)


@pytest.mark.parametrize("cavitation", ["reynolds", "jfo"])
def test_isothermal_limit_is_todays_film(cavitation):
    """An oil without a temperature law: the thermal film's pressure and forces are the
    isothermal film's (at the oil's viscosity, the bearing's reference scale set apart) to
    round-off (2e-14 measured), for the default grooved route. Fails if the viscosity
    field is not taken relative to the bearing's viscosity."""
    oil = Lubricant(0.0278, mass_density=870.0, specific_heat=1950.0, conductivity=0.13)
    sol = solve_thd(BEARING, STATE, 48, 8, lubricant=oil, thermal=Thermal(SUPPLY),
                    grooves=GROOVES, cavitation=cavitation)
    iso = solve_reynolds(replace(BEARING, viscosity=0.0278), STATE, 48, 8,
                         cavitation=cavitation, grooves=GROOVES)
    load = math.hypot(*iso.force)
    assert np.max(np.abs(np.subtract(sol.force, iso.force))) < 1e-12 * load
    assert sol.friction_torque == pytest.approx(iso.friction_torque, rel=1e-12)
    assert sol.pressure_max == pytest.approx(iso.pressure_max, rel=1e-12)
    # through solve_reynolds' thermal keyword: the same film
    routed = solve_reynolds(BEARING, STATE, 48, 8, grooves=GROOVES, cavitation=cavitation,
                            lubricant=oil, thermal=Thermal(SUPPLY))
    np.testing.assert_array_equal(routed.temperature, sol.temperature)


def test_heating_lowers_the_load_and_carry_over_heats_the_inlet():
    """ISO VG 32 at 40 C, 3000 rpm: the THD film carries less than the isothermal film at
    the supply temperature (0.84 of it measured), more carry-over gives hotter inlets and a
    hotter film."""
    iso = solve_reynolds(replace(BEARING, viscosity=VG32.viscosity), STATE, 48, 8,
                         grooves=GROOVES)
    hot = [solve_thd(BEARING, STATE, 48, 8, lubricant=VG32, grooves=GROOVES,
                     thermal=Thermal(SUPPLY, carry_over=lam)) for lam in (0.0, 0.8)]
    assert math.hypot(*hot[0].force) < 0.9 * math.hypot(*iso.force)
    assert np.allclose(hot[0].thermal.inlet_temperatures, SUPPLY, atol=1e-9)
    assert min(hot[1].thermal.inlet_temperatures) > SUPPLY + 1.0
    assert hot[1].temperature_max > hot[0].temperature_max


def test_zero_flux_journal_sits_between_inlet_and_peak():
    sol = solve_thd(BEARING, STATE, 48, 8, lubricant=VG32, grooves=GROOVES,
                    thermal=Thermal(SUPPLY, model="conducting"))
    tj = sol.thermal.journal_temperature
    assert SUPPLY < tj < sol.temperature_max


def test_temperature_renders_and_exports(tmp_path):
    """render_film(field="temperature") draws the thermal film; an isothermal film is
    refused with a message naming the field; the export carries the temperature."""
    from bearingfem.outputs.export import to_meshio
    from bearingfem.outputs.render import render_film
    sol = solve_thd(BEARING, STATE, 48, 8, lubricant=VG32, thermal=Thermal(SUPPLY),
                    grooves=GROOVES)
    path = render_film(sol, tmp_path / "t.png", field="temperature", surface="unwrapped")
    assert path.stat().st_size > 1000
    np.testing.assert_array_equal(to_meshio(sol, "journal").point_data["temperature [K]"],
                                  sol.temperature)
    with pytest.raises(ValueError, match="temperature"):
        render_film(solve_reynolds(BEARING, STATE, 48, 8, grooves=GROOVES),
                    tmp_path / "i.png", field="temperature", surface="unwrapped")


def test_thermal_equilibrium_and_frozen_coefficients():
    """equilibrium(..., thermal=) balances the load to 1e-9 with the THD film (hotter oil:
    a larger eccentricity than the isothermal film at the supply temperature); with an
    oil without a temperature law its K and C (central differences on the frozen field)
    are the isothermal film's exact-sensitivity K and C to 1e-6 of the largest entry
    (measured 7e-9 for K, 1e-12 for C at the step 1e-5 c; 3e-7 at 1e-4 c, 4e-8 at 1e-6 c:
    truncation, then round-off). Fails with the damping's velocity step not scaled back
    (C off by omega)."""
    from bearingfem.design import coefficients, equilibrium
    load, omega = (0.0, -2000.0), STATE.omega
    opts = dict(n_theta=48, n_z=8, grooves=GROOVES, cavitation="reynolds")
    eq = equilibrium(BEARING, load, omega, "fem", lubricant=VG32,
                     thermal=Thermal(SUPPLY, carry_over=0.8), **opts)
    assert math.hypot(*np.add(eq.film_force, load)) < 1e-9 * 2000.0
    assert eq.solution.temperature_max > SUPPLY + 10.0
    cold = equilibrium(replace(BEARING, viscosity=VG32.viscosity), load, omega, "fem", **opts)
    assert eq.eps > cold.eps
    assert eq.power_loss == pytest.approx(abs(eq.solution.friction_torque * omega))
    flat = Lubricant(VG32.viscosity, mass_density=870.0, specific_heat=1950.0,
                     conductivity=0.13)
    kc_thd = coefficients(BEARING, cold.state, "fem", lubricant=flat,
                          thermal=Thermal(SUPPLY), **opts)
    kc = coefficients(replace(BEARING, viscosity=VG32.viscosity), cold.state, "fem", **opts)
    for a, e in ((kc_thd.K, kc.K), (kc_thd.C, kc.C)):
        assert np.max(np.abs(a - e)) < 1e-6 * np.max(np.abs(e))


def test_jfo_thermal_film_at_high_eccentricity():
    """The designer's bearing (ISO VG 32 at 40 C, two 20 deg grooves, 3000 rpm) at eps 0.97,
    adiabatic with carry-over 0.8, 48 x 8: the JFO thermal film solves (the viscosity at
    its control volumes and coarse levels carried by a positive nodal mean; the L2
    projection went negative there) and lands on the Reynolds-condition thermal film's
    answer within what their cavities' content allows: measured 0.25 K in T_max (129 C)
    and 0.4 % in the force. The fine film does not see the carry: at eps 0.7 the force
    and temperature are the L2 projection's to the last bit (measured)."""
    oil = VG32
    b = Bearing(radius=0.025, length=0.025, clearance=50e-6,
                viscosity=float(oil.viscosity_at(temperature=SUPPLY)))
    grooves = [Groove(angle=0.0, width=math.radians(20)),
               Groove(angle=math.pi, width=math.radians(20))]
    state = JournalState(eps=0.97, omega=3000 * 2 * math.pi / 60)
    th = Thermal(SUPPLY, carry_over=0.8)
    sols = [solve_reynolds(b, state, 48, 8, grooves=grooves, lubricant=oil, thermal=th,
                           cavitation=cav) for cav in ("reynolds", "jfo")]
    rey, jfo = sols
    assert abs(jfo.temperature_max - rey.temperature_max) < 1.0
    assert np.hypot(*jfo.force) == pytest.approx(np.hypot(*rey.force), rel=0.01)
    assert jfo.temperature_max > SUPPLY + 80.0
    assert abs(jfo.thermal.balance.residual) < 1e-10 * jfo.thermal.balance.dissipation
