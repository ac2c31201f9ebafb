"""The mechanism's thermal film ("fem-thd"): its isothermal limit is the "fem" model's run,
its film steps keep the energy balance (each step to round-off, and the stored heat
summed over the steps is the film's change of heat content), its steps settle on the
steady thermal film, and a scene names its oil and heat exchanges."""
import math
from dataclasses import replace

import numpy as np
import pytest

from bearingfem import JournalState, Lubricant
from bearingfem.elastic import ElasticBush
from bearingfem.film import film_thickness
from bearingfem.models import FILM_MODELS
from bearingfem.routes.thd import solve_thd, thermal_operator
from bearingfem.thermal import BushConduction, Thermal
from bearingfem.thermal.energy import energy_operator
from studies.thd_designer import BEARING, GROOVES, OMEGA, SUPPLY
from studies.thd_designer import OIL as VG32

MESH = dict(n_theta=48, n_z=8, grooves=GROOVES)
THERMAL = Thermal(SUPPLY, carry_over=0.8)
BUSH = Thermal(SUPPLY, model="conducting", carry_over=0.8, ambient_temperature=300.0,
               bush=BushConduction(ElasticBush(outer_radius=2.0 * BEARING.radius,
                                               model="solid"),
                                   conductivity=50.0, outer_coefficient=80.0))


def _orbit(k):
    """A whirling, squeezing journal at step k of 1 ms."""
    t = 1e-3 * k
    w = 2.0 * math.pi * 50.0
    return t, JournalState(eps=0.6 + 0.1 * math.sin(w * t), omega=OMEGA,
                           gamma=-1.0 + 0.2 * math.sin(0.5 * w * t),
                           eps_dot=0.1 * w * math.cos(w * t),
                           gamma_dot=0.1 * w * math.cos(0.5 * w * t))


def test_isothermal_limit_is_the_fem_models_run():
    """An oil without a temperature law: along an orbit with squeeze and whirl, the
    fem-thd run's force (film steps committed at every state) is the "fem" model's run
    with Reynolds' condition to 1e-10 of its size (2e-13 measured), and the steady force
    at a state alone too. Fails if the bearing-fixed mesh's film is not turned into the
    journal's frame (gamma), or the kept viscosity is not taken relative to the bearing's."""
    flat = Lubricant(0.0278, mass_density=870.0, specific_heat=1950.0, conductivity=0.13)
    oily = replace(BEARING, viscosity=0.0278)     # the bearing's own is a scale only
    thd = FILM_MODELS["fem-thd"].along_run(BEARING, dict(MESH, lubricant=flat,
                                                         thermal=THERMAL))
    fem = FILM_MODELS["fem"].along_run(oily, dict(MESH, cavitation="reynolds"))
    for k in range(8):
        t, state = _orbit(k)
        a, b = np.array(thd.force(state, t)), np.array(fem.force(state, t))
        assert np.max(np.abs(a - b)) < 1e-10 * np.hypot(*b), (k, a, b)
        thd.commit(state, t)
        fem.commit(state, t)
    _, state = _orbit(3)
    steady = FILM_MODELS["fem-thd"].film_force(BEARING, state, lubricant=flat,
                                               thermal=THERMAL, **MESH)
    iso = FILM_MODELS["fem"].film_force(oily, state, cavitation="reynolds", **MESH)
    assert np.max(np.abs(np.subtract(steady, iso))) < 1e-10 * np.hypot(*iso)


def _heat_content(state, T):
    """int rho cp h T dA over the arcs [J] (the energy equation's storage term's
    integrand, on its own points)."""
    op = thermal_operator(BEARING, state, MESH["n_theta"], MESH["n_z"], grooves=GROOVES)
    eop = energy_operator(op.mesh)
    h = BEARING.clearance * film_thickness(eop.theta - state.gamma, state.eps)
    return float(np.sum(VG32.mass_density * VG32.specific_heat * h * eop.at_points(T)
                        * BEARING.radius ** 2 * eop.dx))


def test_film_steps_keep_the_energy_balance_and_settle_on_the_steady_film():
    """From the supply temperature at a fixed state, film steps of 20 ms: each step's
    balance dissipation = convected + grooves + stored closes to 1e-10; the stored heat
    summed over the steps (times dt) is the film's change of heat content int rho cp h T
    dA to 1e-10 (backward Euler telescopes); the oil heats monotonically towards, and
    after 40 steps sits on, the steady thermal film's temperatures (1e-6 K). Fails if the
    storage term's old temperatures enter with the wrong sign or the step's dt is not
    the time since the last film step."""
    state = JournalState(eps=0.7, omega=OMEGA, gamma=-1.0)
    run = FILM_MODELS["fem-thd"].along_run(BEARING, dict(MESH, lubricant=VG32,
                                                         thermal=THERMAL, initial="supply"))
    run.start(state, 0.0)
    T0 = run.snapshot().temperature
    dt, stored, peaks = 2e-2, 0.0, []
    for k in range(1, 41):
        step = run.commit(state, k * dt)
        bal = step.solution.thermal.balance
        assert abs(bal.residual) < 1e-10 * bal.dissipation
        stored += bal.stored * dt
        peaks.append(step.solution.temperature_max)
    T = run.snapshot().temperature
    change = _heat_content(state, T) - _heat_content(state, T0)
    assert stored == pytest.approx(change, rel=1e-10)
    assert np.all(np.diff(peaks[:10]) > 0.0)
    steady = solve_thd(BEARING, state, MESH["n_theta"], MESH["n_z"], lubricant=VG32,
                       thermal=THERMAL, grooves=GROOVES)
    assert np.max(np.abs(T - steady.temperature)) < 1e-6
    assert abs(bal.stored) < 1e-6 * bal.dissipation


def test_film_steps_with_a_conducting_bush_keep_the_balance_and_settle_on_the_steady_film():
    """The conducting bush (solid, R -> 2R, k 50, h_o 80, ambient 300 K) along a run, as a
    quasi-steady conductor: from the supply temperature at a fixed state, 30 film steps
    of 20 ms; each step's balance dissipation = convected + bush + journal + grooves +
    stored closes to 1e-10 (1e-14 measured), the bush takes a share of the heat and gives
    it all to the ambient (no heat capacity: heat out = heat in to 1e-10); the steps sit
    on the steady thermal film with the same bush (1e-6 K; 4e-10 K measured, the steady
    film's own tolerance; 3e-5 K after 15 steps). Fails if the bush is dropped at film
    steps (its share of the heat 0; the steps settle 5.3 K off the steady film)."""
    thermal = BUSH
    state = JournalState(eps=0.7, omega=OMEGA, gamma=-1.0)
    run = FILM_MODELS["fem-thd"].along_run(BEARING, dict(MESH, lubricant=VG32,
                                                         thermal=thermal, initial="supply"))
    run.start(state, 0.0)
    for k in range(1, 31):
        step = run.commit(state, k * 2e-2)
        record = step.solution.thermal
        bal = record.balance
        assert abs(bal.residual) < 1e-10 * bal.dissipation
        assert bal.convected + bal.bush + bal.journal + bal.grooves + bal.stored == \
            pytest.approx(bal.dissipation, rel=1e-10)
        assert 0.05 * bal.dissipation < bal.bush < bal.dissipation
        assert record.bush.heat_in == pytest.approx(bal.bush, rel=1e-10)
        assert record.bush.heat_out == pytest.approx(bal.bush, rel=1e-10)
    steady = solve_thd(BEARING, state, MESH["n_theta"], MESH["n_z"], lubricant=VG32,
                       thermal=thermal, grooves=GROOVES)
    assert np.max(np.abs(run.snapshot().temperature - steady.temperature)) < 1e-6
    assert abs(bal.stored) < 1e-6 * bal.dissipation


@pytest.mark.parametrize("thermal", [THERMAL, BUSH], ids=["adiabatic", "bush"])
def test_run_starts_on_the_steady_film_and_snapshots_restore(thermal):
    """initial "steady": the first film is the steady thermal film's (force to 1e-10);
    a snapshot restored gives the same next film step (bit for bit; with the conducting
    bush the snapshot keeps its inner temperatures, the next step's GMRES start)."""
    _, state = _orbit(0)
    run = FILM_MODELS["fem-thd"].along_run(BEARING, dict(MESH, lubricant=VG32,
                                                         thermal=thermal))
    f = np.array(run.force(state, 0.0))
    steady = FILM_MODELS["fem-thd"].film_force(BEARING, state, lubricant=VG32,
                                               thermal=thermal, **MESH)
    assert np.max(np.abs(f - steady)) < 1e-10 * np.hypot(*steady)
    t, s1 = _orbit(1)
    if thermal.bush is not None:
        run.commit(s1, t)           # a film step first: the bush's inner start is kept
        t, s1 = _orbit(2)
    kept = run.snapshot()
    a = run.commit(s1, t)
    run.restore(kept)
    b = run.commit(s1, t)
    np.testing.assert_array_equal(a.solution.temperature, b.solution.temperature)
    assert a.force_local == b.force_local


@pytest.mark.parametrize("options, name", [
    (dict(MESH, thermal=THERMAL), "lubricant"),
    (dict(n_theta=48, n_z=8, lubricant=VG32, thermal=THERMAL), "grooves"),
    (dict(MESH, lubricant=VG32, thermal=THERMAL, initial="cold"), "initial"),
])
def test_bad_options_name_the_parameter(options, name):
    _, state = _orbit(0)
    with pytest.raises(ValueError, match=name):
        FILM_MODELS["fem-thd"].along_run(BEARING, options).start(state, 0.0)


def test_steady_start_at_rest_is_refused():
    """A journal at rest has no steady thermal film: the steady start names omega and
    the supply start."""
    run = FILM_MODELS["fem-thd"].along_run(BEARING, dict(MESH, lubricant=VG32,
                                                         thermal=THERMAL))
    t, state = _orbit(0)
    with pytest.raises(ValueError, match="omega.*supply"):
        run.start(replace(state, omega=0.0), t)


def test_scene_names_the_oil_and_the_heat_exchanges():
    """[effects.lubrication] with model "fem-thd": oil = "ISO VG 32" is the grade's
    Lubricant, a [thermal] table the Thermal; a grade that is not one is refused by name."""
    from mechanism.scene import _lubrication, _Table
    table = dict(model="fem-thd", n_theta=48, n_z=8, oil="ISO VG 32",
                 grooves=[dict(angle=0.0, width=0.35), dict(angle=math.pi, width=0.35)],
                 thermal=dict(supply_temperature=SUPPLY, carry_over=0.8))
    lub = _lubrication(_Table(dict(table), "effects.lubrication"))
    assert lub.options["lubricant"].viscosity_at(temperature=SUPPLY) == \
        pytest.approx(VG32.viscosity_at(temperature=SUPPLY), rel=1e-14)
    assert lub.options["thermal"] == THERMAL
    with pytest.raises(ValueError, match="effects.lubrication.oil"):
        _lubrication(_Table(dict(table, oil="ISO VG 33"), "effects.lubrication"))
    # 40 typed for 40 C: refused at the scene, against the oil's law (it ran at 40 K)
    degc = dict(table, thermal=dict(supply_temperature=40.0))
    with pytest.raises(ValueError, match=r"effects.lubrication.thermal: supply_temperature "
                                         r"must lie in \[200, inf\) K .* 40.0 degC is 313.15"):
        _lubrication(_Table(degc, "effects.lubrication"))


def test_film_steps_with_a_piezoviscous_oil_settle_on_the_steady_film():
    """ISO VG 32 with a Barus coefficient of 2e-8 1/Pa (the film's peak of ~5 MPa raises its
    viscosity by ~10 %), from the supply temperature at a fixed state: 40 film steps of 20
    ms sit on the steady thermal film's temperatures (1e-6 K; 5.9e-9 K measured), the fixed point whose
    energy equation takes the viscosity at the pressure in Pa. Fails with the film steps'
    energy equation taking the viscosity at the dimensionless pressure (run once: 0.51 K off)."""
    oil = Lubricant.iso_vg(32, barus=2e-8)
    state = JournalState(eps=0.7, omega=OMEGA, gamma=-1.0)
    run = FILM_MODELS["fem-thd"].along_run(BEARING, dict(MESH, lubricant=oil,
                                                         thermal=THERMAL, initial="supply"))
    run.start(state, 0.0)
    for k in range(1, 41):
        run.commit(state, k * 2e-2)
    steady = solve_thd(BEARING, state, MESH["n_theta"], MESH["n_z"], lubricant=oil,
                       thermal=THERMAL, grooves=GROOVES)
    T = run.snapshot().temperature
    assert np.max(np.abs(T - steady.temperature)) < 1e-6


def test_scene_refuses_a_supply_temperature_in_celsius_before_the_run():
    """A scene's thermal table with supply_temperature = 40 (meant as 40 C) ran and stopped
    at t = 0 with "non-finite temperature", leaving a partial result; now refused when the
    scene is read, naming the key."""
    from mechanism.scene import _lubrication, _Table
    table = dict(model="fem-thd", n_theta=48, n_z=8, oil="ISO VG 32",
                 grooves=[dict(angle=0.0, width=0.35), dict(angle=math.pi, width=0.35)],
                 thermal=dict(supply_temperature=40.0, carry_over=0.8))
    with pytest.raises(ValueError, match=r"effects.lubrication.thermal: supply_temperature "
                                         r"must lie in .*typed in degC\?"):
        _lubrication(_Table(dict(table), "effects.lubrication"))
