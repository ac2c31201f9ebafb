"""Heat conduction in the bush (bearingfem.thermal.bush): radial conduction through the
wall against its closed form, an angular flux against the separated solution, the heat
balance, bad input."""
import math

import numpy as np
import pytest

from bearingfem.elastic import ElasticBush
from bearingfem.thermal.bush import bush_heat, radial_conduction

R, RO, K, H, TA, Q = 0.025, 0.05, 50.0, 80.0, 300.0, 2e4


def _heat(model, n, flux=Q):
    return bush_heat(ElasticBush(outer_radius=RO, model=model), R, 0.025, conductivity=K,
                     outer_coefficient=H, ambient_temperature=TA, inner_flux=flux,
                     n_theta=24 * n, n_radial=4 * n, n_axial=2)


@pytest.mark.parametrize("model", ["ring", "solid"])
def test_radial_conduction_closed_form_and_order(model):
    """A uniform flux 2e4 W/m^2 into a steel-like wall (k 50, R 25 -> 50 mm) with outer
    convection 80 W/(m^2 K): T(r) = T_a + q R (1/(h R_o) + ln(R_o/r)/k), a 132 K rise.
    Nodal error 7.8e-2, 2.0e-2, 4.9e-3 K on 24x4, 48x8, 96x16 cells (order 2.0: the
    polygonal circles and bilinear elements); the heat out equals the heat in to 1e-11.
    Fails with the Robin term's ambient dropped (300 K off) or k on the flux (x 50)."""
    errors = []
    for n in (1, 2, 4):
        sol = _heat(model, n)
        r = np.hypot(*sol.mesh.mesh.p[:2])
        errors.append(np.max(np.abs(sol.temperature - radial_conduction(r, R, RO, K, H, TA, Q))))
        assert sol.heat_out == pytest.approx(sol.heat_in, rel=1e-11)
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(orders > 1.9), (errors, orders)
    assert errors[-1] < 1e-2


def test_angular_flux_separated_solution():
    """q = q1 cos(theta) on the ring: T = T_a + (C r + D / r) cos(theta) with -k T1'(R) =
    q1 and -k T1'(R_o) = h T1(R_o); nodal error falls at order 2 (measured 8.3e-2, 2.1e-2,
    5.3e-3 K on a 7.7 K amplitude) and no net heat crosses (1e-9 of the flux's amplitude times the area)."""
    q1 = 1e4
    # -k (C - D/R^2) = q1, -k (C - D/Ro^2) = h (C Ro + D/Ro)
    M = np.array([[-K, K / R ** 2], [-K - H * RO, K / RO ** 2 - H / RO]])
    C, D = np.linalg.solve(M, [q1, 0.0])
    errors = []
    for n in (1, 2, 4):
        sol = _heat("ring", n, lambda theta, z: q1 * np.cos(theta))
        x, y = sol.mesh.mesh.p
        r, th = np.hypot(x, y), np.arctan2(y, x)
        exact = TA + (C * r + D / r) * np.cos(th)
        errors.append(np.max(np.abs(sol.temperature - exact)))
        assert abs(sol.heat_in) < 1e-9 * q1 * 2 * math.pi * R
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(orders > 1.8), (errors, orders)


@pytest.mark.parametrize("kwargs, name", [
    (dict(conductivity=0.0), "conductivity"),
    (dict(outer_coefficient=-1.0), "outer_coefficient"),
    (dict(ambient_temperature=float("nan")), "ambient_temperature"),
    (dict(inner_flux=lambda t, z: np.full_like(t, np.inf)), "inner_flux"),
])
def test_bad_input_names_the_parameter(kwargs, name):
    args = dict(conductivity=K, outer_coefficient=H, ambient_temperature=TA, inner_flux=Q)
    args.update(kwargs)
    with pytest.raises(ValueError, match=name):
        bush_heat(ElasticBush(outer_radius=RO, model="ring"), R, 0.025, **args)
