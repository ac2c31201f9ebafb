"""The application layer (bearingfem_app): bugs planted one at a time that its tests did
not notice (docs/mutation.md), each checked here against a hand value."""
import math

import pytest

from bearingfem_app.sweep import run_case

SEED = dict(diameter=0.02, length_ratio=0.25, clearance=20e-6, viscosity=0.0117,
            omega=250.0)


@pytest.mark.parametrize("kind", ["film", "design"])
@pytest.mark.parametrize("eps", [0.3, 0.7])
def test_sweep_case_attitude_and_sommerfeld_by_hand(kind, eps):
    """A short-bearing case against Ocvirk's closed form by hand: attitude
    tan(phi) = pi sqrt(1 - eps^2) / (4 eps); load W = mu U L^3 eps / (4 c^2 (1 - eps^2)^2)
    sqrt(16 eps^2 + pi^2 (1 - eps^2)) with U = omega R, and S = (R/c)^2 mu N / P with
    N = omega / 2 pi [1/s], P = W / (L D). Fails with the attitude measured from +r instead
    of from the load line (cases.py: atan2(f_t, f_r))."""
    row = run_case(kind, dict(SEED, eps=eps, model="short"))
    R, c, mu, w = 0.01, 20e-6, 0.0117, 250.0
    L = 0.25 * 2 * R
    phi = math.degrees(math.atan(math.pi * math.sqrt(1 - eps ** 2) / (4 * eps)))
    W = (mu * w * R * L ** 3 * eps / (4 * c ** 2 * (1 - eps ** 2) ** 2)
         * math.sqrt(16 * eps ** 2 + math.pi ** 2 * (1 - eps ** 2)))
    S = (R / c) ** 2 * mu * (w / (2 * math.pi)) / (W / (L * 2 * R))
    assert row["attitude_deg"] == pytest.approx(phi, rel=1e-9)
    assert row["force"] == pytest.approx(W, rel=1e-9)
    assert row["sommerfeld"] == pytest.approx(S, rel=1e-9)


def test_design_case_coefficients_keep_their_indices():
    """K_ij, C_ij of a design case are the load-frame coefficients' [i-1, j-1] (K_12 is
    the force along axis 1 from a displacement along axis 2; the short film's K is far
    from symmetric). Fails with the indices swapped (cases.py)."""
    import numpy as np

    from bearingfem import Bearing, JournalState
    from bearingfem.design import coefficients
    row = run_case("design", dict(SEED, eps=0.5, model="short"))
    b = Bearing(radius=0.01, length=0.005, clearance=20e-6, viscosity=0.0117)
    k, c = coefficients(b, JournalState(0.5, omega=250.0), "short",
                        frame="load").dimensionless()
    assert abs(k[0, 1] - k[1, 0]) > 0.1 * np.abs(k).max()
    for (i, j), v in np.ndenumerate(k):
        assert row[f"K{i + 1}{j + 1}"] == pytest.approx(v, rel=1e-12)
    for (i, j), v in np.ndenumerate(c):
        assert row[f"C{i + 1}{j + 1}"] == pytest.approx(v, rel=1e-12)


@pytest.mark.parametrize("eps", [0.3, 0.6])
def test_design_case_flow_variable_is_the_short_bearings(eps):
    """Raimondi & Boyd's side-flow variable Q_s / (R c N L) of a narrow film against the
    short bearing's by hand: its pressure spans the half film 0 < theta < pi, so what leaves
    the ends is the Couette flow in at the widest gap less the flow out at the narrowest,
    U L c (1 + eps) / 2 - U L c (1 - eps) / 2 = U L c eps, U = omega R, N = omega / 2 pi:
    2 pi eps. The FE film (P2 72 x 8, Reynolds' condition) at L/D 1/4, 1/8, 1/16 falls
    1.04 %, 0.27 %, 0.04 % short of it (the finite length's share, ~4x per halving): 0.5 %
    at L/D 1/8. No test read the flow variable before: it survived L replaced by D (8x)."""
    row = run_case("design", dict(SEED, eps=eps, length_ratio=0.125, model="fem",
                                  element="P2", n_theta=72, n_z=8, cavitation="reynolds"))
    assert row["flow_variable"] == pytest.approx(2 * math.pi * eps, rel=5e-3)
