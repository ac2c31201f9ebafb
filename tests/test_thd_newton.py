"""The thermal film's coupled Newton: its block Jacobian against central differences of
its residual, quadratic convergence, and the plain fixed point's answer."""
import numpy as np
import pytest

from bearingfem import Lubricant
from bearingfem.routes.thd import ThermalIteration
from bearingfem.routes.thd_newton import ThermalNewton, solve_thd_newton
from bearingfem.thermal import Thermal
from tests.test_thermal import BEARING, GROOVES, STATE, SUPPLY, VG32, _plain_fixed_point

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


def _unknowns(nw, nu):
    x = [nw.P[nw._unknown], nw.T, nw.T_in]
    if nw.zero_flux:
        x.append([nw.t_journal])
    return np.concatenate(x)


def _set(nw, x, nu):
    N, G = len(nw.T), len(nw.T_in)
    nw.P[nw._unknown] = x[:nu]
    nw.T = x[nu:nu + N].copy()
    nw.T_in = x[nu + N:nu + N + G].copy()
    if nw.zero_flux:
        nw.t_journal = float(x[-1])


@pytest.mark.parametrize("oil", [VG32, Lubricant.iso_vg(32, barus=2e-8)], ids=["", "barus"])
@pytest.mark.parametrize("thermal", CASES, ids=IDS)
def test_block_jacobian_is_the_residuals_derivative(thermal, oil):
    """J v against central differences of the residual along v, v moving every unknown
    (pressure, temperature, inlet and journal temperatures) smoothly and evenly in z
    (the SUPG weight has a kink where the axial flow changes sign, at the mid-plane).
    The differences' error falls as the step squared: 1e-5 of the step 1e-4 of the
    fields relative, 2e-9 measured. Fails with any coupling block left out (e.g.
    the energy equation's d/dP through the viscosity, or the mixing's d/dP)."""
    nw = _newton(thermal, oil)
    r, J, nu, _ = nw.system(STATE)
    nw._unknown = np.setdiff1d(nw.op.mesh.free, np.flatnonzero(nw.active))
    x0 = _unknowns(nw, nu)
    mesh = nw.op.mesh
    th, zeta = mesh.theta, mesh.zeta
    vP = (nw.P * (1.0 + 0.3 * np.sin(th) + 0.2 * zeta ** 2))[nw._unknown]
    vT = 2.0 * np.cos(th) * (1.0 + zeta ** 2)
    v = np.concatenate([vP, vT, np.full(len(nw.T_in), 1.5)] + ([[0.7]] if nw.zero_flux else []))
    h = 1e-4

    def residual(x):
        _set(nw, x, nu)
        return nw.system(STATE)[0]
    fd = (residual(x0 + h * v) - residual(x0 - h * v)) / (2.0 * h)
    _set(nw, x0, nu)
    Jv = J @ v
    # film rows, energy rows and the rest, each against its own scale
    for rows in (slice(0, nu), slice(nu, nu + len(nw.free_rows)), slice(nu + len(nw.free_rows), None)):
        assert np.max(np.abs(Jv[rows] - fd[rows])) < 1e-5 * np.max(np.abs(fd[rows]))


@pytest.mark.parametrize("thermal", CASES, ids=IDS)
def test_newton_converges_quadratically_to_the_fixed_points_answer(thermal):
    """The Newton solve lands where the plain fixed point (test_thermal's reference, its
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
