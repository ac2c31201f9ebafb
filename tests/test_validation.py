"""Bad input fails before any work, with a message naming the parameter and range."""
import math

import pytest

from bearingfem import (Bearing, JournalState, fvm_reynolds, long_bearing_force,
                        short_bearing_force, solve_reynolds)


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
