"""The thermal film's inputs: bad input names the parameter, temperatures are kelvin for
any fluid (degrees Celsius typed for kelvin refused before any work), a cryogen's film
solves, and a film or supply beyond the oil law's range warns with its numbers."""
import math
import warnings
from dataclasses import replace

import numpy as np
import pytest

from bearingfem import Bearing, Groove, JournalState, Lubricant, solve_reynolds
from bearingfem.errors import OilRangeWarning
from bearingfem.routes.thd import solve_thd
from bearingfem.thermal import Thermal
from mechanism.scene import oil_viscosity
from tests.test_thermal_film import BEARING, GROOVES, STATE, SUPPLY, VG32


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
    # a supply below the oil range is refused by the oil's own viscosity there (the tests
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


def test_supply_temperature_typed_in_celsius_is_refused_before_any_work():
    """40 for 40 C reached the solvers as 40 K (the ISO VG law's viscosity inf there) and
    stopped in "Factor is exactly singular"; 150 K (1.5e21 Pa s) in "the energy equation
    gave a non-finite temperature (a film without flow through it?)", the equilibrium in a
    Bearing's "typed in cSt?". A cold start inside the oil range and a cryogen's own law
    are taken; a supply in [200 K, the oil range) where the law's viscosity exceeds any
    lubricant's is refused by the law's own number. The equilibrium refuses a supply
    above a Bearing's 10 Pa s by name (its isothermal start's Bearing refused -50 C as
    "typed in cSt?")."""
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
    # 200 K, below the oil range: the ISO VG 460 law's viscosity there exceeds any oil's
    heavy = Lubricant.iso_vg(460)
    assert heavy.viscosity_at(0.0, temperature=200.0) > 1e4
    Thermal(supply_temperature=223.15).check_fluid(oil)       # -50 C: 232 Pa s
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
    cold = Thermal(supply_temperature=223.15, model="adiabatic")
    with pytest.raises(ValueError, match=r"supply_temperature 223.15 K .* the equilibrium's "
                                         r"isothermal start takes \(at most 10 Pa s"):
        equilibrium(BEARING, (0.0, -2000.0), STATE.omega, "fem", n_theta=24, n_z=4,
                    grooves=GROOVES, lubricant=oil, thermal=cold)
    cryogen = Lubricant.two_point((77.0, 1.6e-4), (90.0, 1.2e-4), density=800.0,
                                  specific_heat=2000.0, conductivity=0.14, law="exponential")
    Thermal(supply_temperature=77.0).check_fluid(cryogen)


def test_a_cold_start_inside_the_oil_range_solves_and_the_equilibrium_refuses_it():
    """ISO VG 32 fed at -50 C (232 Pa s at the supply, the oil range's end) is a cold
    start the thermal film at a given position solves: the fixed point and the coupled
    Newton, two methods, agree on the temperatures within the fixed point's
    temperature_tol 1e-6 K (1.2e-8 K measured at 24 x 4; T_max 349.36 K). The
    equilibrium, whose isothermal start is a Bearing at the supply's viscosity, refuses
    a supply above a Bearing's 10 Pa s by name before any work, from Walther's line
    inverted by hand, T = 10^((A - log10 log10(nu + 0.7)) / B) at nu = 10 Pa s / rho,
    1e-9 below it (the law's round-off ~1e-15). Fails with the supply refused above
    10 Pa s at any temperature (the film's cold start refused), and with the
    equilibrium's check removed (its Bearing's "typed in cSt?")."""
    from bearingfem.design import equilibrium
    from bearingfem.routes.thd_newton import solve_thd_newton
    cold = Thermal(supply_temperature=223.15, model="adiabatic")
    assert VG32.viscosity_at(0.0, temperature=223.15) > 200.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OilRangeWarning)
        fixed = solve_reynolds(BEARING, STATE, 24, 4, grooves=GROOVES, lubricant=VG32,
                               thermal=cold)
        newton = solve_thd_newton(BEARING, STATE, 24, 4, lubricant=VG32, thermal=cold,
                                  grooves=GROOVES)
    assert np.max(np.abs(fixed.temperature - newton.temperature)) < 1e-6
    assert fixed.temperature_max > 340.0
    a, b = VG32.walther
    nu = 1e6 * 10.0 / VG32.mass_density                      # [mm^2/s]
    limit = 10.0 ** ((a - math.log10(math.log10(nu + 0.7))) / b)      # 241.0 K
    for t in (limit * (1.0 - 1e-9), 223.15):
        with pytest.raises(ValueError, match=rf"supply_temperature {t:g} K gives the "
                                             r"lubricant a viscosity of .* more than the "
                                             r"equilibrium's isothermal start takes "
                                             r"\(at most 10 Pa s"):
            equilibrium(BEARING, (0.0, -2000.0), STATE.omega, "fem", n_theta=24, n_z=4,
                        grooves=GROOVES, lubricant=VG32,
                        thermal=Thermal(supply_temperature=t, model="adiabatic"))
