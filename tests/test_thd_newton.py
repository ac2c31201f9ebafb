"""The thermal film's coupled Newton: its block Jacobian against central differences of
its residual, quadratic convergence, and the plain fixed point's answer."""
from dataclasses import replace

import numpy as np
import pytest

from bearingfem import Lubricant
from bearingfem.errors import ConvergenceError
from bearingfem.routes.thd import ThermalIteration
from bearingfem.routes.thd_newton import ThermalNewton, solve_thd_newton
from bearingfem.thermal import Thermal
from tests.test_bush_heat import _conducting
from tests.test_thermal_energy import _plain_fixed_point
from tests.test_thermal_film import BEARING, GROOVES, STATE, SUPPLY, VG32

CASES = [
    Thermal(SUPPLY),
    Thermal(SUPPLY, carry_over=0.8),
    Thermal(SUPPLY, model="conducting", carry_over=0.5),
]
IDS = ["adiabatic", "carry-over", "conducting-zero-flux"]


def _newton(thermal, oil=VG32, n=(24, 6)):
    it = ThermalIteration(BEARING, STATE, *n, lubricant=oil, thermal=thermal, grooves=GROOVES)
    it.film(STATE)
    it.energy(STATE)          # a temperature field away from the supply's, off the answer
    return ThermalNewton(it)


def _fields(nw):
    return nw.P.copy(), nw.T.copy(), nw.t_journal


def _put(nw, fields):
    nw.P, nw.T, nw.t_journal = fields[0].copy(), fields[1].copy(), fields[2]


def _residual(nw):
    s = nw.system(STATE)
    return s["r_film"], s["r_T"], s["r_j"]


@pytest.mark.parametrize("oil", [VG32, Lubricant.iso_vg(32, barus=2e-8)], ids=["", "barus"])
@pytest.mark.parametrize("thermal", CASES, ids=IDS)
def test_block_jacobian_is_the_residuals_derivative(thermal, oil):
    """J v (the blocks the Newton step solves with) against central differences of the
    residual along v, v moving every unknown (pressure, temperature, journal temperature)
    smoothly and evenly in z (the SUPG weight has a kink where the axial flow changes
    sign, at the mid-plane); each group of rows (film, temperature, journal) against its
    own scale. Step 1e-4 of the fields: the differences' error falls as its square, 1e-5
    allowed, 2e-9 measured. Fails with any coupling block left out (the film's d/dT, the
    energy equation's d/dP through the flow, or the mixing's d/dP)."""
    nw = _newton(thermal, oil)
    s = nw.system(STATE)
    u = s["unknown"]
    mesh = nw.op.mesh
    th, zeta = mesh.theta, mesh.zeta
    vP = np.zeros(len(nw.P))
    vP[u] = (nw.P * (1.0 + 0.3 * np.sin(th) + 0.2 * zeta ** 2))[u]
    vT = 2.0 * np.cos(th) * (1.0 + zeta ** 2)
    vj = 0.7 if nw.zero_flux else 0.0
    x0, h = _fields(nw), 1e-4
    _put(nw, (x0[0] + h * vP, x0[1] + h * vT, x0[2] + h * vj))
    plus = _residual(nw)
    _put(nw, (x0[0] - h * vP, x0[1] - h * vT, x0[2] - h * vj))
    minus = _residual(nw)
    _put(nw, x0)
    Jv = nw.apply(s, vP[u], vT, vj)
    for a, p, m in zip(Jv, plus, minus):
        fd = (np.asarray(p) - np.asarray(m)) / (2.0 * h)
        assert np.max(np.abs(a - fd)) <= 1e-5 * max(np.max(np.abs(fd)), 1e-300)


@pytest.mark.parametrize("thermal", CASES, ids=IDS)
def test_newton_converges_quadratically_to_the_fixed_points_answer(thermal):
    """The Newton solve lands where the plain fixed point (test_thermal_energy's reference, its
    energy equation by scikit-fem forms and a general LU) lands: temperatures to 1e-6 K
    (measured ~1e-12 K), force and friction to 1e-8; its energy residual falls
    quadratically, r_{k+1} <= 10 r_k^2 / r_0, down to round-off (measured r_k: 0.91,
    0.13, 8.4e-4, 3.2e-8 adiabatic at 48 x 8). A Newton with a coupling block left out
    converges linearly and fails the second check."""
    ref, T_ref, tj_ref = _plain_fixed_point(thermal)
    sol = solve_thd_newton(BEARING, STATE, 48, 8, lubricant=VG32, thermal=thermal,
                           grooves=GROOVES)
    assert np.max(np.abs(sol.temperature - T_ref)) < 1e-6
    assert abs(sol.thermal.journal_temperature - tj_ref) < 1e-6
    assert np.allclose(sol.force, ref.force, rtol=1e-8, atol=0.0)
    assert sol.friction_torque == pytest.approx(ref.friction_torque, rel=1e-8)
    bal = sol.thermal.balance
    assert abs(bal.residual) < 1e-11 * bal.dissipation
    it = ThermalIteration(BEARING, STATE, 48, 8, lubricant=VG32, thermal=thermal,
                          grooves=GROOVES)
    it.film(STATE)
    nw = ThermalNewton(it).solve(STATE)
    r = np.array(nw.history)
    assert r[-1] < 1e-10 * r[0]
    above = r[1:] > 1e-10 * r[0]
    assert np.sum(above) >= 2
    assert np.all(r[1:][above] <= 10.0 * r[:-1][above] ** 2 / r[0])


def test_newton_refuses_the_jfo_film():
    it = ThermalIteration(BEARING, STATE, 24, 6, lubricant=VG32, thermal=Thermal(SUPPLY),
                          grooves=GROOVES, cavitation="jfo")
    with pytest.raises(ValueError, match="Reynolds-condition"):
        ThermalNewton(it)


def test_warm_start_lands_on_the_cold_answer_and_unconverged_raises():
    """From a neighbouring state's film (an equilibrium's step) the Newton lands where it
    lands cold (1e-9 K, force 1e-10) in fewer steps; one step allowed from the supply
    temperature raises ConvergenceError, and bad input names its parameter."""
    cold = solve_thd_newton(BEARING, STATE, 24, 6, lubricant=VG32, thermal=CASES[1],
                            grooves=GROOVES)
    near = solve_thd_newton(BEARING, replace(STATE, eps=0.58), 24, 6, lubricant=VG32,
                            thermal=CASES[1], grooves=GROOVES)
    warm = solve_thd_newton(BEARING, STATE, 24, 6, lubricant=VG32, thermal=CASES[1],
                            grooves=GROOVES, start=near)
    assert np.max(np.abs(warm.temperature - cold.temperature)) < 1e-9
    assert np.allclose(warm.force, cold.force, rtol=1e-10, atol=0.0)
    assert warm.thermal.iterations < cold.thermal.iterations
    with pytest.raises(ConvergenceError):
        solve_thd_newton(BEARING, STATE, 24, 6, lubricant=VG32, thermal=CASES[1],
                         grooves=GROOVES, max_iterations=1)
    with pytest.raises(ValueError, match="thermal"):
        solve_thd_newton(BEARING, STATE, 24, 6, lubricant=VG32, thermal=None,
                         grooves=GROOVES)
    with pytest.raises(ValueError, match="supply"):
        solve_thd_newton(BEARING, STATE, 24, 6, lubricant=VG32, thermal=CASES[1])
    # a journal turning the other way is the fixed point's (the Newton's mixing and SUPG
    # derivatives are the forward film's: 8 K off at -omega before it was refused)
    with pytest.raises(ValueError, match="state.omega"):
        solve_thd_newton(BEARING, replace(STATE, omega=-STATE.omega), 24, 6,
                         lubricant=VG32, thermal=CASES[1], grooves=GROOVES)
    # a conducting bush is the fixed point's too (its energy solve carries the bush)
    with pytest.raises(ValueError, match="thermal.bush"):
        solve_thd_newton(BEARING, STATE, 24, 6, lubricant=VG32,
                         thermal=_conducting("ring"), grooves=GROOVES)


def test_an_iterate_outside_the_oils_law_is_an_unconverged_newton():
    """A Newton step whose temperatures leave the oil's law (ISO VG 32 below 76.57 K,
    where Walther's law overflows: its viscosity was inf, the next step NaN and the solve
    ConvergenceError) stays a ConvergenceError naming the temperature the lubricant
    refuses, not the lubricant's ValueError; the start's temperatures, an input, are
    refused as given (fails with the Newton's conversion removed)."""
    nw = _newton(CASES[0])
    nw.steps, nw.T = 1, np.full_like(nw.T, 40.0)         # as a step would leave them
    with pytest.raises(ConvergenceError, match=r"coupled Newton\) did not converge at "
                                               r"eps = .*: temperature 40 K is outside"):
        nw.solve(STATE)
    start = _newton(CASES[0])
    start.T = np.full_like(start.T, 40.0)
    with pytest.raises(ValueError, match="temperature 40 K is outside"):
        start.solve(STATE)


def test_only_the_oils_refusal_becomes_an_unconverged_newton(monkeypatch):
    """Any other ValueError inside a Newton step (a defect, say a shape) is raised as
    itself, not dressed as an unconverged solve (fails with the conversion catching every
    ValueError)."""
    nw = _newton(CASES[0])
    nw.steps = 1

    def broken(state):
        raise ValueError("operands could not be broadcast together")
    monkeypatch.setattr(nw, "system", broken)
    with pytest.raises(ValueError, match="broadcast") as caught:
        nw.solve(STATE)
    assert not isinstance(caught.value, ConvergenceError)
