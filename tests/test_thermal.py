"""Thermal films: the energy equation's balance, its order on a manufactured solution, the
adiabatic Couette film's closed-form temperature rise, the isothermal limit, the
dissipation against the film's power loss, groove mixing and bad input."""
import math
import warnings
from dataclasses import replace

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from skfem import Basis, BilinearForm, LinearForm

from bearingfem import Bearing, Groove, JournalState, Lubricant, solve_reynolds
from bearingfem.errors import OilRangeWarning
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
from mechanism.scene import oil_viscosity

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


def test_zero_flux_journal_sits_between_inlet_and_peak():
    sol = solve_thd(BEARING, STATE, 48, 8, lubricant=VG32, grooves=GROOVES,
                    thermal=Thermal(SUPPLY, model="conducting"))
    tj = sol.thermal.journal_temperature
    assert SUPPLY < tj < sol.temperature_max


@pytest.mark.parametrize("kwargs, name", [
    (dict(thermal="hot"), "thermal"),
    (dict(lubricant=Lubricant(0.02)), "mass_density"),
    (dict(cavitation="gumbel"), "cavitation"),
    (dict(grooves=()), "supply"),
    (dict(relaxation=0.0), "relaxation"),
    (dict(state=replace(STATE, eps_dot=1.0)), "eps_dot"),
    (dict(state=replace(STATE, omega=0.0)), "omega"),
])
def test_bad_input_names_the_parameter(kwargs, name):
    args = dict(state=STATE, lubricant=VG32, thermal=Thermal(SUPPLY), grooves=GROOVES)
    args.update(kwargs)
    state = args.pop("state")
    with pytest.raises(ValueError, match=name):
        solve_thd(BEARING, state, 48, 8, **args)


@pytest.mark.parametrize("kwargs, name", [
    (dict(supply_temperature=-1.0), "supply_temperature"),
    (dict(supply_temperature=SUPPLY, model="radiating"), "model"),
    (dict(supply_temperature=SUPPLY, carry_over=1.5), "carry_over"),
    (dict(supply_temperature=SUPPLY, bush_coefficient=100.0), "bush_coefficient"),
    (dict(supply_temperature=SUPPLY, model="conducting", journal_coefficient=-1.0),
     "journal_coefficient"),
])
def test_bad_thermal_spec_names_the_parameter(kwargs, name):
    with pytest.raises(ValueError, match=name):
        Thermal(**kwargs)


@pytest.mark.parametrize("name", ["supply_temperature", "ambient_temperature",
                                  "journal_temperature"])
def test_thermal_temperatures_take_any_fluid_and_refuse_degc_for_an_oil(name):
    """A Thermal's temperatures are any fluid's, not the command line's ISO VG range: a
    300 C (573.15 K) supply and an aircraft's ambient at altitude (ISA -56.5 C, 216.65 K)
    are taken (both refused when the ISO VG range applied here); 0 K and below are refused
    naming the parameter. With an oil (its law referenced at or above
    oil_range.LEAST_KELVIN, 200 K) a number below 200 K is degrees Celsius typed for
    kelvin: 40.0 was taken and the film only warned once solved (OilRangeWarning, the
    oil's law extrapolated to 40 K); it is refused before any work, naming the parameter,
    the range and the slip. A cryogen's law (liquid nitrogen's, 77-90 K) takes 80 K. The
    ISO VG oil of --oil-temperature keeps its -50 to 200 C."""
    base = dict(supply_temperature=SUPPLY, model="conducting")
    # a supply below the oil range is refused by the oil's own viscosity there (the test
    # below): -50 C, the range's end, is its coldest
    for value in ((573.15, 223.15) if name == "supply_temperature" else (573.15, 216.65, 200.0)):
        thermal = Thermal(**dict(base, **{name: value}))
        assert getattr(thermal, name) == value
        thermal.check_fluid(VG32)
    for value in (0.0, -300.0):
        with pytest.raises(ValueError, match=rf"{name} must be finite and > 0 \[K\]"):
            Thermal(**dict(base, **{name: value}))
    span = (r"must lie in \[200, inf\) K \(-73.15 C up: kelvin, not degC\) with a "
            r"lubricant referenced at 313.15 K, got ")
    degc = Thermal(**dict(base, **{name: 40.0}))
    with pytest.raises(ValueError, match=rf"^{name} {span}40.0 \(typed in degC\? 40.0 degC "
                                         r"is 313.15 K\)$"):
        degc.check_fluid(VG32)
    with pytest.raises(ValueError, match=rf"^{name} {span}40.0 \(typed in degC"):
        solve_thd(BEARING, STATE, 48, 8, lubricant=VG32, thermal=degc, grooves=GROOVES)
    with pytest.raises(ValueError, match=rf"^{name} {span}199.9 \(typed in degC\? "):
        Thermal(**dict(base, **{name: 199.9})).check_fluid(VG32)
    cryogen = Lubricant.two_point((77.0, 1.6e-4), (90.0, 1.2e-4), law="exponential",
                                  density=808.0, specific_heat=2040.0, conductivity=0.14)
    Thermal(**dict(base, **{"supply_temperature": 80.0, name: 80.0})).check_fluid(cryogen)
    with pytest.raises(ValueError, match=r"oil_temperature must lie in \[-50, 200\] degC"):
        oil_viscosity("ISO VG 32", 300.0)


def test_a_cryogens_thermal_film_solves():
    """Liquid nitrogen (its exponential law through 77 and 90 K) fed at 80 K: the thermal
    film solves, warmer than its supply, and warns that it left the oil law's range (it
    was refused as degC typed for K when every Thermal took 200 K at least)."""
    b = Bearing(radius=0.025, length=0.025, clearance=50e-6, viscosity=1.6e-4)
    ln2 = Lubricant.two_point((77.0, 1.6e-4), (90.0, 1.2e-4), law="exponential",
                              density=808.0, specific_heat=2040.0, conductivity=0.14)
    state = JournalState(eps=0.6, omega=30000 * 2 * math.pi / 60, gamma=-0.3)
    with pytest.warns(OilRangeWarning):
        sol = solve_thd(b, state, 48, 8, lubricant=ln2, thermal=Thermal(80.0),
                        grooves=GROOVES)
    assert 80.0 < sol.temperature_max < 90.0


def test_a_supply_above_the_oil_range_solves_and_warns():
    """A 220 C supply (an oil heated past the ISO VG chart) is solved, not refused: the
    film returns with an OilRangeWarning naming the temperature it reached, its numbers
    finite."""
    b = Bearing(radius=0.025, length=0.025, clearance=50e-6,
                viscosity=float(VG32.viscosity_at(temperature=493.15)))
    grooves = [Groove(angle=0.0, width=math.radians(20)),
               Groove(angle=math.pi, width=math.radians(20))]
    state = JournalState(eps=0.5, omega=3000 * 2 * math.pi / 60, gamma=-1.0)
    with pytest.warns(OilRangeWarning, match="outside the oil law's range"):
        hot = solve_reynolds(b, state, 24, 4, grooves=grooves, lubricant=VG32,
                             thermal=Thermal(493.15, carry_over=0.8))
    assert hot.temperature_max > 493.15 and np.all(np.isfinite(hot.pressure))


def test_a_film_beyond_the_oil_range_says_so_with_its_numbers():
    """The designer's bearing at eps 0.999 on 48 x 8 reaches ~2150 C (the Walther law
    extrapolated far beyond any oil): the solve warns with the temperature it reached and
    the range (it printed the peak silently); at eps 0.7 (67 C) it says nothing. The
    thermal numbers are unchanged: the warning only reads them."""
    b = Bearing(radius=0.025, length=0.025, clearance=50e-6,
                viscosity=float(VG32.viscosity_at(temperature=SUPPLY)))
    grooves = [Groove(angle=0.0, width=math.radians(20)),
               Groove(angle=math.pi, width=math.radians(20))]
    th = Thermal(SUPPLY, carry_over=0.8)
    state = JournalState(eps=0.999, omega=3000 * 2 * math.pi / 60, gamma=-1.0)
    with pytest.warns(OilRangeWarning, match="outside the oil law's range "
                                             r"\[223.15, 473.15\] K") as seen:
        hot = solve_reynolds(b, state, 48, 8, grooves=grooves, lubricant=VG32, thermal=th)
    assert hot.temperature_max > 1500.0 + 273.15
    assert f"{hot.temperature_max:.6g} K" in str(seen[0].message)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        cool = solve_reynolds(b, replace(state, eps=0.7), 48, 8, grooves=grooves,
                              lubricant=VG32, thermal=th)
    assert cool.temperature_max < 473.15


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


def test_supply_temperature_typed_in_celsius_is_refused_before_any_work():
    """40 for 40 C reached the solvers as 40 K (the ISO VG law's viscosity inf there) and
    stopped in "Factor is exactly singular"; 150 K (1.5e21 Pa s) in "the energy equation
    gave a non-finite temperature (a film without flow through it?)", the equilibrium in a
    Bearing's "typed in cSt?". A cold start inside the oil range and a cryogen's own law
    are taken; a supply in [200 K, the oil range) where the law's viscosity exceeds any
    lubricant's is refused by the law's own number."""
    from bearingfem.design import equilibrium
    oil = Lubricant.iso_vg(32)
    for t in (40.0, 150.0):
        th = Thermal(supply_temperature=t, model="adiabatic")
        with pytest.raises(ValueError, match=rf"supply_temperature must lie in .* got {t!r} "
                                             rf"\(typed in degC\? {t!r} degC is "):
            solve_reynolds(BEARING, STATE, 24, 4, grooves=GROOVES, lubricant=oil, thermal=th)
        with pytest.raises(ValueError, match=f"supply_temperature must lie in .* got {t!r}"):
            equilibrium(BEARING, (0.0, -2000.0), STATE.omega, "fem", n_theta=24, n_z=4,
                        grooves=GROOVES, lubricant=oil, thermal=th)
    Thermal(supply_temperature=223.15).check_fluid(oil)       # -50 C: 232 Pa s
    # 200 K, below the oil range: the ISO VG 460 law's viscosity there exceeds any oil's
    heavy = Lubricant.iso_vg(460)
    assert heavy.viscosity_at(0.0, temperature=200.0) > 1e4
    with pytest.raises(ValueError, match=r"supply_temperature 200 K gives the lubricant a "
                                         r"viscosity of .* below the oil range's .* "
                                         r"typed in degC\? \(200 C = "):
        Thermal(supply_temperature=200.0).check_fluid(heavy)
    # just below the range the message says the limit is there, not that 240 Pa s is more
    # than any lubricant's (232 Pa s at 223.15 K is taken)
    with pytest.raises(ValueError, match=r"supply_temperature 223 K gives the lubricant a "
                                         r"viscosity of 239.8[0-9]* Pa s below the oil range's "
                                         r"223.15 K, where its law is extrapolated"):
        Thermal(supply_temperature=223.0).check_fluid(oil)
    cryogen = Lubricant.two_point((77.0, 1.6e-4), (90.0, 1.2e-4), density=800.0,
                                  specific_heat=2000.0, conductivity=0.14, law="exponential")
    Thermal(supply_temperature=77.0).check_fluid(cryogen)
