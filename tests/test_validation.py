"""Bad input fails before any work, with a message naming the parameter and range."""
import math

import pytest

from bearingfem import (Bearing, JournalState, fvm_reynolds, long_bearing_force,
                        short_bearing_force, solve_reynolds)
from bearingfem.design import equilibrium


@pytest.mark.parametrize("field", ["radius", "length", "clearance", "viscosity"])
@pytest.mark.parametrize("bad", [0.0, -1.0, math.nan, math.inf, "x"])
def test_bearing_rejects(field, bad):
    kw = dict(radius=0.01, length=0.004, clearance=20e-6, viscosity=0.0117)
    kw[field] = bad
    with pytest.raises(ValueError, match=field):
        Bearing(**kw)


@pytest.mark.parametrize("eps", [-0.1, 1.0, 1.5, math.nan])
def test_state_rejects_eps(eps):
    with pytest.raises(ValueError, match=r"eps must lie in \[0, 1\)|eps must be finite"):
        JournalState(eps=eps)


@pytest.mark.parametrize("field", ["eps_dot", "gamma", "gamma_dot", "omega"])
def test_state_rejects_nonfinite(field):
    with pytest.raises(ValueError, match=field):
        JournalState(eps=0.5, **{field: math.inf})


@pytest.mark.parametrize("kw,name", [
    (dict(n_theta=4), "n_theta"), (dict(n_z=1), "n_z"), (dict(n_theta=12.5), "n_theta"),
    (dict(element="P3"), "element"), (dict(cavitation="swift"), "cavitation"),
    (dict(method="cg"), "method"), (dict(supply_angle=math.nan), "supply_angle"),
])
def test_solver_rejects(kw, name):
    b = Bearing(radius=0.01, length=0.004, clearance=20e-6, viscosity=0.0117)
    s = JournalState(eps=0.5, omega=100.0)
    with pytest.raises(ValueError, match=name):
        solve_reynolds(b, s, **kw)
    if name not in ("element",):
        with pytest.raises(ValueError, match=name):
            fvm_reynolds(b, s, **kw)


def test_closed_forms_reject_wrong_types():
    s = JournalState(eps=0.5, omega=100.0)
    with pytest.raises(ValueError, match="bearing"):
        short_bearing_force(None, s)
    with pytest.raises(ValueError, match="state"):
        long_bearing_force(Bearing(0.01, 0.04, 20e-6, 0.01), (0.5, 0, 0, 0, 100))


@pytest.mark.parametrize("solver", ["fem", "fvm"])
def test_every_bad_parameter_is_named_at_once(solver):
    from bearingfem import Bearing, JournalState, fvm_reynolds, solve_reynolds
    b = Bearing(radius=0.01, length=0.004, clearance=20e-6, viscosity=0.0117)
    call = solve_reynolds if solver == "fem" else fvm_reynolds
    with pytest.raises(ValueError) as err:
        call(b, JournalState(0.5), 2, 1, cavitation="swift")
    msg = str(err.value)
    for name in ("n_theta must be an integer >= 8", "n_z must be an integer >= 2",
                 "cavitation must be one of"):
        assert name in msg


@pytest.mark.parametrize("kw, needles", [
    (dict(radius=25.0, length=25.0), ("diameter", "typed in mm", "0.05 m")),
    (dict(viscosity=32.0), ("viscosity 32", "cSt", "0.0278")),
    (dict(clearance=0.002), ("clearance", "0.2 of the radius", "typed in mm")),
    (dict(clearance=1e-8), ("clearance", "1e-06 of the radius", "radial, in m")),
    (dict(length=0.5), ("L/D", "25")),
    (dict(viscosity=1e-8), ("viscosity", "Pa s")),
])
def test_bearing_outside_any_journal_bearing_names_the_unit(kw, needles):
    """A journal bearing has a diameter of 0.5 mm to 5 m, c/R 1e-5 to 0.05, L/D 0.01 to
    10, mu 1e-6 to 10 Pa s: outside, the likely unit mistake is named (the first case is
    a 50 mm diameter typed as 50, the second ISO VG 32 typed as Pa s)."""
    base = dict(radius=0.01, length=0.01, clearance=20e-6, viscosity=0.0117) | kw
    with pytest.raises(ValueError) as err:
        Bearing(**base)
    for n in needles:
        assert n in str(err.value)


def test_journal_bearings_at_the_ends_of_the_range_are_accepted():
    """A 2 mm spindle bearing, a 2 m turbine bearing, air and cold heavy oil."""
    Bearing(radius=1e-3, length=2e-3, clearance=2e-6, viscosity=1.8e-5)
    Bearing(radius=1.0, length=1.6, clearance=1e-3, viscosity=5.0)


@pytest.mark.parametrize("clearance, unit", [(50.0, "typed in um? (50 um = 5e-05 m)"),
                                             (0.05, "typed in mm? (0.05 mm = 5e-05 m)")])
def test_a_clearance_in_um_or_mm_is_named(clearance, unit):
    """A clearance of 50 (um) or 0.05 (mm) on a 50 mm journal: the unit that brings it
    into the range is named (old: 'clearance must be smaller than radius')."""
    with pytest.raises(ValueError) as err:
        Bearing(radius=0.025, length=0.025, clearance=clearance, viscosity=0.03)
    assert unit in str(err.value)


@pytest.mark.parametrize("call", [
    lambda b: solve_reynolds(b, JournalState(eps=0.5, omega=2e4), 24, 4),
    lambda b: fvm_reynolds(b, JournalState(eps=0.5, omega=-2e4), 24, 4),
    lambda b: equilibrium(b, 2000.0, 3000.0 * 60.0, "short")])
def test_a_surface_speed_above_any_journal_bearings_is_refused_by_the_python_api(call):
    """|omega| R above 300 m/s (a speed in rpm given as rad/s, say) is refused before any
    work in the Python API too, as on the command line."""
    b = Bearing(radius=0.025, length=0.025, clearance=50e-6, viscosity=0.03)
    with pytest.raises(ValueError, match=r"omega .* surface speed of (500|4500) m/s"):
        call(b)
    # 11459 rpm at this radius is 30 m/s: a journal bearing's speed, accepted
    solve_reynolds(b, JournalState(eps=0.5, omega=1200.0), 24, 4)


@pytest.mark.parametrize("call", [
    lambda b, s, g: solve_reynolds(b, s, 24, 4, grooves=g),
    lambda b, s, g: fvm_reynolds(b, s, 24, 4, grooves=g),
    lambda b, s, g: equilibrium(b, (0.0, -100.0), 250.0, "fem", n_theta=24, n_z=4,
                                grooves=g)])
def test_one_groove_not_in_a_list_is_named(call):
    """grooves=Groove(...) (one, not a sequence): a ValueError naming grooves and the fix.
    Old: TypeError "'Groove' object is not iterable" from inside the solve."""
    from bearingfem import Groove
    b = Bearing(radius=0.01, length=0.004, clearance=20e-6, viscosity=0.0117)
    s = JournalState(eps=0.6, omega=250.0)
    with pytest.raises(ValueError, match=r"grooves must be a sequence .*grooves=\[Groove"):
        call(b, s, Groove(0.0, 0.3))
    with pytest.raises(ValueError, match="grooves must be a sequence of Groove objects, "
                                         "got int"):
        call(b, s, 5)


@pytest.mark.parametrize("load", [(0.0, -100.0, 0.0), (100.0,), "100", "10", b"10"])
def test_a_load_not_of_two_components_is_named(load):
    """Old: a 3-vector load raised "too many values to unpack (expected 2)", naming
    nothing; a two-character string ("10") was taken as the vector (1, 0) N."""
    b = Bearing(radius=0.01, length=0.004, clearance=20e-6, viscosity=0.0117)
    with pytest.raises(ValueError, match=r"load must be a vector \(W_x, W_y\) \[N\]"):
        equilibrium(b, load, 250.0, "short")


@pytest.mark.parametrize("solver, element", [(solve_reynolds, "P1"), (solve_reynolds, "P2"),
                                             (fvm_reynolds, None)])
def test_a_mesh_beyond_memory_is_refused_before_it_is_built(solver, element):
    """100000 x 10000 (a mistyped size) was built until the process was killed for memory
    (24 GB resident); now refused at once, naming n_theta and n_z. The toolkit's finest
    meshes pass the check (1920 x 320 P1, 1536 x 256 P2)."""
    from bearingfem.validation import MAX_UNKNOWNS, estimated_unknowns
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    kw = {} if element is None else {"element": element}
    with pytest.raises(ValueError, match=r"n_theta x n_z = 100000 x 10000"):
        solver(b, JournalState(0.5, omega=250.0), 100000, 10000, **kw)
    assert estimated_unknowns(1920, 320) < estimated_unknowns(1536, 256, "P2") < MAX_UNKNOWNS
    assert estimated_unknowns(1000, 2000, "P2") > MAX_UNKNOWNS
