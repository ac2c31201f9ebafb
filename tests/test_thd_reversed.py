"""The thermal film of a journal turning the other way (omega < 0): the oil enters each arc
at the grooves' leading edges. Checked by symmetry (the mirror image of a bearing at
-omega is the bearing's film mirrored), by the isothermal limit along an orbit whose
rotation reverses (the "fem" model's run), by the energy balance of film steps
through a reversal and a state at rest (omega = 0: the temperatures held), and the
thermal equilibrium with its K and C mirrored in the load line."""
import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.spatial import cKDTree
from skfem import MeshTri1

import bearingfem.fe.mesh as film_meshes
from bearingfem import JournalState, Lubricant, clear_caches
from bearingfem.film import film_thickness
from bearingfem.models import FILM_MODELS
from bearingfem.routes.thd import solve_thd, thermal_operator
from bearingfem.thermal import Thermal
from bearingfem.thermal.energy import energy_operator
from tests.test_thd_model import BEARING, GROOVES, MESH, OMEGA, SUPPLY, THERMAL, VG32
from bearingfem.design import coefficients, equilibrium

TIGHT = dict(temperature_tol=1e-11, pressure_rtol=1e-13)
AXIS = 0.5          # the supply line's angle, the mirror's axis [rad]


def _theta_mirrored_tensor(axis):
    """A tensor mesh whose diagonals are mirrored in the angle ``axis`` (and, as the
    toolkit's, in the mid-plane): the mirror image of the film is solved on the mirror
    image of its mesh, so the two discrete problems are one (the toolkit's own mesh is
    mirrored in z only: its diagonals lean one way around the bearing)."""
    def tensor(th, ze):
        mesh = MeshTri1.init_tensor(th, ze)
        t = mesh.t.copy()
        nt = t.shape[1] // 2
        a, c, d, b = t[0, :nt].copy(), t[1, :nt].copy(), t[2, :nt].copy(), t[1, nt:].copy()
        x = 0.5 * (mesh.p[0, a] + mesh.p[0, d])
        side = np.sin(x - axis)
        side[np.abs(side) < 1e-12] = 0.0       # a column centred on the axis: its own image
        flip = side * (mesh.p[1, a] + mesh.p[1, d]) < 0.0
        t[:, :nt][:, flip] = np.vstack([a, b, c])[:, flip]
        t[:, nt:][:, flip] = np.vstack([b, d, c])[:, flip]
        return MeshTri1(mesh.p, t)
    return tensor


@pytest.fixture
def mirrored_meshes(monkeypatch):
    """Film meshes mirrored in the angle 0 (grooves at 0 and pi) or AXIS (the supply
    line): set with the axis, the mesh caches emptied before and after."""
    def use(axis):
        clear_caches()
        monkeypatch.setattr(film_meshes, "_mirrored_tensor", _theta_mirrored_tensor(axis))
    yield use
    monkeypatch.undo()
    clear_caches()


def _mirror_map(mesh, axis):
    """Node j of the mirror image of node i: angle 2 axis - phi within the mesh's turn,
    zeta -> -zeta (the film is symmetric in z). A supply line's mesh starts on the
    mirror's line (its angle the axis, or the axis + pi):
    its first and last lines (inlet and exit) are each other's images. A grooved mesh
    starts at the first groove's leading edge, whose image is that groove's trailing edge
    (one line): the first line's nodes (in the groove) are left out, and the trailing
    edge's image is the last line (on the arc)."""
    lo = float(np.min(mesh.theta))
    if abs(math.remainder(axis - lo, np.pi)) < 1e-12:     # the axis through the seam
        image = 2.0 * lo - mesh.theta + 2.0 * np.pi
    else:
        image = np.mod(2.0 * axis - mesh.theta - lo, 2.0 * np.pi)
        image = np.where(image < 1e-9, 2.0 * np.pi, image) + lo
    dist, j = cKDTree(np.c_[mesh.theta, mesh.zeta]).query(np.c_[image, -mesh.zeta])
    assert np.max(dist) < 1e-9
    return j


@pytest.mark.parametrize("supply, thermal, n_theta, t_tol, f_tol, cavitation", [
    # the supply line: its mesh's seam is on the axis, carry-over included: round-off
    ("line", THERMAL, 48, 1e-8, 1e-10, "reynolds"),
    ("line", Thermal(SUPPLY, model="conducting", carry_over=0.8), 48, 1e-8, 1e-10,
     "reynolds"),
    # grooves without carry-over: round-off (the JFO film too)
    ("grooves", Thermal(SUPPLY, carry_over=0.0), 48, 1e-8, 1e-10, "reynolds"),
    ("grooves", Thermal(SUPPLY, model="conducting"), 48, 1e-8, 1e-10, "reynolds"),
    ("grooves", Thermal(SUPPLY), 48, 1e-8, 1e-10, "jfo"),
    # grooves with carry-over: every arc's inlet and exit flows one-sided (each arc's own
    # dp/dtheta), so the mesh's seam is a groove edge like the others: round-off (the
    # whole mesh's projection left 1.0e-5 K and 1.4e-7 of the force at 36 x 8, 1.0e-7 K at
    # 72 x 8, 2e-11 K at 144 x 16: the seam's one-sided flow against its image's averaged)
    ("grooves", THERMAL, 36, 1e-8, 1e-10, "reynolds"),
    ("grooves", Thermal(SUPPLY, model="conducting", carry_over=0.8), 48, 1e-8, 1e-10,
     "reynolds"),
    ("grooves", THERMAL, 48, 1e-8, 1e-10, "jfo"),
])
def test_mirrored_bearing_at_reversed_rotation_is_the_mirror_image(
        mirrored_meshes, supply, thermal, n_theta, t_tol, f_tol, cavitation):
    """The bearing at (eps, gamma, omega) and its mirror image at (eps, 2 a - gamma,
    -omega), a the mirror's axis, on mirrored meshes: nodal temperatures, pressures, the
    radial force and the journal's temperature equal, the tangential force opposite, each
    groove's inlet temperature and the heat balance's parts equal (measured with grooves
    and carry-over at 36 x 8, 72 x 8, 144 x 16: 8e-12, 8e-12, 9e-12 K; force 1e-13). Fails
    if the energy equation's inlet and outlet edges are not swapped, the carried-over flow
    is counted against the oil's way, an arc runs into the wrong groove, or the mixing's
    flows take dp/dtheta across a groove's edge (the whole mesh's projection: 1e-5 K)."""
    axis = AXIS if supply == "line" else 0.0
    mirrored_meshes(axis)
    where = dict(supply_angle=AXIS) if supply == "line" else dict(grooves=GROOVES)
    state = JournalState(eps=0.7, omega=OMEGA, gamma=-1.0)
    image = JournalState(eps=0.7, omega=-OMEGA, gamma=2.0 * axis + 1.0)
    a = solve_thd(BEARING, state, n_theta, 8, lubricant=VG32, thermal=thermal, **where,
                  cavitation=cavitation, **TIGHT)
    b = solve_thd(BEARING, image, n_theta, 8, lubricant=VG32, thermal=thermal, **where,
                  cavitation=cavitation, **TIGHT)
    mesh = thermal_operator(BEARING, state, n_theta, 8, **where).mesh
    j = _mirror_map(mesh, axis)
    keep = np.ones(len(j), bool) if supply == "line" else \
        mesh.theta > np.min(mesh.theta) + 1e-9
    assert np.max(np.abs(a.temperature - b.temperature[j])[keep]) < t_tol
    peak = np.max(a.pressure)
    assert np.max(np.abs(a.pressure - b.pressure[j])[keep]) < f_tol * peak
    fa, fb = np.array(a.force_local), np.array(b.force_local)
    assert np.max(np.abs(fa - fb * (1.0, -1.0))) < f_tol * np.hypot(*fa)
    assert a.thermal.journal_temperature == pytest.approx(b.thermal.journal_temperature,
                                                          abs=t_tol)
    assert np.allclose(a.thermal.inlet_temperatures, b.thermal.inlet_temperatures,
                       rtol=0.0, atol=t_tol)
    ba, bb = a.thermal.balance, b.thermal.balance
    assert abs(bb.residual) < 1e-10 * bb.dissipation
    for part in ("dissipation", "convected", "bush", "grooves"):
        assert getattr(ba, part) == pytest.approx(getattr(bb, part),
                                                  rel=f_tol, abs=1e-10 * ba.dissipation)


def test_reversed_edges_swap_the_inlets():
    """The reversed operator holds the grooves' leading edges (and their interiors), the
    forward one their trailing edges: the same interiors, the edges exchanged."""
    op = thermal_operator(BEARING, JournalState(eps=0.5, omega=OMEGA), 48, 8,
                          grooves=GROOVES)
    ahead, back = energy_operator(op.mesh), energy_operator(op.mesh, reverse=True)
    for k in range(len(GROOVES)):
        np.testing.assert_array_equal(ahead.edges.inflow[k], back.edges.outflow[k])
        np.testing.assert_array_equal(ahead.edges.outflow[k], back.edges.inflow[k])
        np.testing.assert_array_equal(ahead.edges.interior[k], back.edges.interior[k])
    # each arc runs into the groove at its end (forward) or at its start (reversed)
    assert set(np.unique(ahead.edges.column_groove)) == {0, 1}
    assert np.all(ahead.edges.column_groove != back.edges.column_groove)


def _reversing(k):
    """A whirling, squeezing journal whose rotation reverses (omega = OMEGA cos), at step
    k of 1 ms; k = 5 is at rest exactly."""
    t = 1e-3 * k
    w = 2.0 * math.pi * 50.0
    return t, JournalState(eps=0.6 + 0.1 * math.sin(w * t),
                           omega=0.0 if k == 5 else OMEGA * math.cos(w * t),
                           gamma=-1.0 + 0.2 * math.sin(0.5 * w * t),
                           eps_dot=0.1 * w * math.cos(w * t),
                           gamma_dot=0.1 * w * math.cos(0.5 * w * t))


def test_isothermal_limit_along_a_reversing_orbit_is_the_fem_models_run():
    """An oil without a temperature law, along an orbit whose rotation reverses (through
    omega = 0 exactly), film steps at every state: the force is the "fem" model's run with
    Reynolds' condition to 1e-10 of its size. Fails if a reversed film step's film or
    kept viscosity differs from the forward one's (e.g. the reversed energy step leaves
    a non-uniform viscosity, or the state at rest is stepped with a stale field)."""
    flat = Lubricant(0.0278, mass_density=870.0, specific_heat=1950.0, conductivity=0.13)
    oily = replace(BEARING, viscosity=0.0278)
    thd = FILM_MODELS["fem-thd"].along_run(BEARING, dict(MESH, lubricant=flat,
                                                         thermal=THERMAL))
    fem = FILM_MODELS["fem"].along_run(oily, dict(MESH, cavitation="reynolds"))
    signs = set()
    for k in range(12):
        t, state = _reversing(k)
        signs.add(np.sign(state.omega))
        a, b = np.array(thd.force(state, t)), np.array(fem.force(state, t))
        assert np.max(np.abs(a - b)) < 1e-10 * np.hypot(*b), (k, a, b)
        thd.commit(state, t)
        fem.commit(state, t)
    assert signs == {-1.0, 0.0, 1.0}


def _heat_content(state, T):
    """int rho cp h T dA over the arcs [J]."""
    op = thermal_operator(BEARING, state, MESH["n_theta"], MESH["n_z"], grooves=GROOVES)
    eop = energy_operator(op.mesh)
    h = BEARING.clearance * film_thickness(eop.theta - state.gamma, state.eps)
    return float(np.sum(VG32.mass_density * VG32.specific_heat * h * eop.at_points(T)
                        * BEARING.radius ** 2 * eop.dx))


def test_film_steps_through_a_reversal_keep_the_balance_and_hold_at_rest():
    """From the steady film at +omega, film steps of 5 ms at a fixed position while the
    rotation runs down, stops (omega = 0 exactly: no step, the temperatures held) and
    turns the other way: each step's balance closes to 1e-10 of its dissipation; the
    stored heat summed over the steps, each times the time since the last film step (the
    one after the stop over two intervals), is the change of the film's heat content to
    1e-10; settled at -omega the temperatures are the steady film's at -omega (1e-6 K).
    Fails if the held step's time is dropped or the reversed step holds the wrong edges."""
    run = FILM_MODELS["fem-thd"].along_run(BEARING, dict(MESH, lubricant=VG32,
                                                         thermal=THERMAL))
    speeds = [0.5 * OMEGA, 0.0, -0.5 * OMEGA] + [-OMEGA] * 60
    state = JournalState(eps=0.7, omega=OMEGA, gamma=-1.0)
    run.start(state, 0.0)
    T0, stored, last, dt, held = run.snapshot().temperature, 0.0, 0.0, 5e-3, []
    for k, omega in enumerate(speeds, start=1):
        step = run.commit(replace(state, omega=omega), k * dt)
        if step is None:
            held.append(omega)
            continue
        bal = step.solution.thermal.balance
        assert abs(bal.residual) < 1e-10 * bal.dissipation
        stored += bal.stored * (step.t - last)
        last = step.t
    assert held == [0.0]
    T = run.snapshot().temperature
    assert stored == pytest.approx(_heat_content(state, T) - _heat_content(state, T0),
                                   rel=1e-10)
    steady = solve_thd(BEARING, replace(state, omega=-OMEGA), MESH["n_theta"], MESH["n_z"],
                       lubricant=VG32, thermal=THERMAL, grooves=GROOVES)
    assert np.max(np.abs(T - steady.temperature)) < 1e-6


def test_reversed_thermal_equilibrium_is_the_mirror_image():
    """Grooves at 0 and pi (mirror images about the vertical), a load straight down: the
    thermal equilibrium and its frozen-viscosity K and C at -omega are those at +omega
    mirrored in the load line (eps and T_max equal, the attitude and gamma's cosine
    opposite, K and C conjugated by diag(-1, 1)). The toolkit's mesh is not mirrored in
    that line (its diagonals lean one way, the seam at the first groove's leading edge),
    so the two are two discretisations: without carry-over they differ at 24x4, 48x8,
    96x16 by eps 9.0e-3, 2.7e-3, 6.0e-4; attitude 2.4e-2, 3.7e-3, 1.1e-3 rad; T_max 1.11,
    0.35, 0.074 K; K 1.9e-2, 3.9e-3, 3.4e-3 and C 8.3e-2, 1.8e-2, 2.5e-3 of their largest
    entries: the tolerances are twice the 48x8 differences. omega = 0 is refused by
    name. Fails with the forward energy operator at omega < 0 (the heat carried against
    the oil's way: the film leaves the oil's range), with the attitude's sign not flipped,
    or with K and C perturbed at +|omega|."""
    from bearingfem.design import coefficients, equilibrium
    opts = dict(n_theta=48, n_z=8, grooves=GROOVES, cavitation="reynolds", lubricant=VG32,
                thermal=Thermal(SUPPLY, carry_over=0.0))
    load, flip = (0.0, -2000.0), np.diag([-1.0, 1.0])
    a = equilibrium(BEARING, load, OMEGA, "fem", **opts)
    b = equilibrium(BEARING, load, -OMEGA, "fem", **opts)
    for eq in (a, b):       # balanced to the thermal equilibrium's rtol, 1e-8 of the load
        assert math.hypot(*np.add(eq.film_force, load)) < 1e-8 * 2000.0
    assert a.attitude > 0.0 > b.attitude
    assert b.eps == pytest.approx(a.eps, abs=6e-3)
    assert -b.attitude == pytest.approx(a.attitude, abs=8e-3)
    assert math.remainder(b.state.gamma - (math.pi - a.state.gamma), 2.0 * math.pi) == \
        pytest.approx(0.0, abs=8e-3)
    assert b.solution.temperature_max == pytest.approx(a.solution.temperature_max, abs=0.7)
    ka = coefficients(BEARING, a.state, "fem", solution=a.solution, **opts)
    kb = coefficients(BEARING, b.state, "fem", solution=b.solution, **opts)
    for x, y, tol in ((ka.K, kb.K, 8e-3), (ka.C, kb.C, 4e-2)):
        assert np.max(np.abs(x - flip @ y @ flip)) < tol * np.max(np.abs(x))
    with pytest.raises(ValueError, match="omega"):
        equilibrium(BEARING, load, 0.0, "fem", **opts)


def _angle_map(a, b):
    """(nodes of mesh ``a`` off its first line, the node of mesh ``b`` at each one's angle
    (mod 2 pi) and zeta). The first line of a grooved mesh is the seam's copy of the
    first groove's leading edge, on the groove's side only, left out on both meshes."""
    keep_a = np.flatnonzero(a.theta > np.min(a.theta) + 1e-9)
    keep_b = np.flatnonzero(b.theta > np.min(b.theta) + 1e-9)
    dist, j = cKDTree(np.c_[np.cos(b.theta), np.sin(b.theta), b.zeta][keep_b]).query(
        np.c_[np.cos(a.theta), np.sin(a.theta), a.zeta][keep_a])
    assert np.max(dist) < 1e-9
    return keep_a, keep_b[j]


@pytest.mark.parametrize("omega", [-OMEGA, OMEGA], ids=["reversed", "forward"])
def test_grooved_film_does_not_depend_on_the_grooves_order(omega):
    """Grooves at 0 and pi given in either order (the mesh's seam, the first groove's
    leading edge, at the one groove or the other: the same nodes and elements numbered
    from another place), carry-over 0.8, near the reversed equilibrium: nodal
    temperatures, pressure, force, each groove's inlet temperature and the heat balance
    equal to round-off (measured 4e-12 K, 6e-14 of the force reversed; 6e-12 K, 1e-14
    forward). Fails with dp/dtheta projected over the whole mesh (groove elements
    included): the inlet flow at the seam is then one-sided and at the other groove
    averaged with the groove's flat pressure (reversed: 0.72 K at the inlet and 2.1 % of
    the force at 48 x 8, 0.78 K and 2.2 % at 96 x 16; forward 1.2e-3 K, 1.1e-4 K)."""
    state = JournalState(eps=0.76, omega=omega, gamma=-0.93 if omega > 0 else math.pi + 0.93)
    sols = [solve_thd(BEARING, state, 48, 8, lubricant=VG32, thermal=THERMAL, grooves=g,
                      **TIGHT) for g in (GROOVES, GROOVES[::-1])]
    meshes = [thermal_operator(BEARING, state, 48, 8, grooves=g).mesh
              for g in (GROOVES, GROOVES[::-1])]
    assert abs(np.min(meshes[0].theta) - np.min(meshes[1].theta)) > 1.0   # two seams
    a, b = sols
    i, j = _angle_map(*meshes)
    assert np.max(np.abs(a.temperature[i] - b.temperature[j])) < 1e-9
    assert np.max(np.abs(a.pressure[i] - b.pressure[j])) < 1e-10 * np.max(a.pressure)
    fa, fb = np.array(a.force), np.array(b.force)
    assert np.max(np.abs(fa - fb)) < 1e-10 * np.hypot(*fa)
    assert np.allclose(a.thermal.inlet_temperatures, b.thermal.inlet_temperatures[::-1],
                       rtol=0.0, atol=1e-9)
    assert a.thermal.balance.grooves == pytest.approx(b.thermal.balance.grooves, rel=1e-10)


def test_reversed_thermal_equilibrium_with_carry_over_is_the_mirror_image(mirrored_meshes):
    """The thermal equilibrium with carry-over 0.8 (the designer's bearing, a load straight
    down) and its frozen-viscosity K and C at -omega are those at +omega mirrored in the
    load line, on meshes mirrored in that line (the angle pi/2: it swaps the grooves and
    maps the mesh's seam onto the other groove's trailing edge): the two discrete
    problems are one, so equal within the equilibrium's own tolerance: the two searches
    round off differently, and each stops anywhere inside the force balance's 1e-8 of the
    load, which leaves eps within ~2e-9 and T_max within ~2e-7 K (T_max moves by ~120 K
    per unit of eps here). Measured at 48 x 8: eps 9e-11, attitude 1e-10 rad, T_max
    1.1e-8 K (the same with the fixed point's tolerance 1e-8 K: the balance, not the
    temperatures, sets it), the inlets 5e-10 K, K 9e-10 and C 7e-10 of their largest
    entries (3e-12, 4e-12 rad, 6e-10 K when first measured; 5e-11, 4e-11 rad, 5e-9 K on
    the code before the looser inexact steps); asserted 1e-9, 1e-9 rad, 1e-7 K (the
    inlets 1e-8 K), 1e-8. Fails with the mixing's flows taken across the
    grooves' edges, the seam's inlet one-sided and its image's averaged: eps 3.5e-3 and
    T_max 0.73 K apart at 48 x 8 on these meshes. On the toolkit's own mesh the two are two
    discretisations: eps 2.3e-3, 5.6e-4, 1.5e-4 apart at 48 x 8, 96 x 16, 192 x 32, as
    without carry-over (docs/thd.md)."""
    mirrored_meshes(0.5 * math.pi)
    opts = dict(n_theta=48, n_z=8, grooves=GROOVES, cavitation="reynolds", lubricant=VG32,
                thermal=THERMAL)
    load, flip = (0.0, -2000.0), np.diag([-1.0, 1.0])
    a = equilibrium(BEARING, load, OMEGA, "fem", **opts)
    b = equilibrium(BEARING, load, -OMEGA, "fem", **opts)
    assert b.eps == pytest.approx(a.eps, abs=1e-9)
    assert -b.attitude == pytest.approx(a.attitude, abs=1e-9)
    assert b.solution.temperature_max == pytest.approx(a.solution.temperature_max, abs=1e-7)
    assert np.allclose(a.solution.thermal.inlet_temperatures,
                       b.solution.thermal.inlet_temperatures[::-1], rtol=0.0, atol=1e-8)
    ka = coefficients(BEARING, a.state, "fem", solution=a.solution, **opts)
    kb = coefficients(BEARING, b.state, "fem", solution=b.solution, **opts)
    for x, y in ((ka.K, kb.K), (ka.C, kb.C)):
        assert np.max(np.abs(x - flip @ y @ flip)) < 1e-8 * np.max(np.abs(x))
