"""EHL line contact: half-space, dry (Hertz) limit, rigid isoviscous limit, EHL film fits.

Every tolerance below comes from the convergence numbers quoted beside it (measured on
this code; the table is in docs/ehl.md).
"""
import math

import numpy as np
import pytest
import scipy.integrate
import scipy.optimize

from bearingfem import Lubricant, line_contact
from bearingfem.errors import ConvergenceError
from bearingfem.ehl.fits import (dowson_higginson, hertz_line, pan_hamrock,
                                 rigid_isoviscous_load, rigid_isoviscous_pressure)
from bearingfem.ehl.halfspace import LineCompliance, dry_line_contact, hertz_deflection
from bearingfem.ehl.line import DimensionlessLine, solve_dimensionless

STEEL = dict(radius=0.02, reduced_modulus=2.26e11)
OIL = Lubricant(viscosity=0.0117, barus=2e-8, density="dowson-higginson")


# -- half-space -----------------------------------------------------------------------
def test_fft_deflection_equals_dense_and_converges_to_hertz():
    """V of Hertz's pressure against the exact (1 + 2 ln 2)/4 - X^2/2 on |X| <= 1.

    Max errors 3.75e-3, 1.57e-3, 6.45e-4, 2.59e-4 on 61..481 nodes (order 1.3 -> 1.5,
    the sqrt edge of the pressure); the FFT product equals the dense one to 1e-15.
    Fails with the kernel's 1/pi dropped, its sign flipped, or the circulant wrapped wrong.
    """
    errors = []
    for n in (61, 121, 241, 481):
        X = np.linspace(-1.5, 1.5, n)
        P = np.sqrt(np.clip(1 - X**2, 0, None))
        c = LineCompliance(n, X[1] - X[0])
        V = c.deflection(P)
        np.testing.assert_allclose(V, c.matrix() @ P, rtol=0, atol=1e-13)
        inside = np.abs(X) <= 1
        errors.append(np.abs(V[inside] - hertz_deflection(X[inside])).max())
    ratios = np.array(errors[:-1]) / np.array(errors[1:])
    assert np.all(ratios > 2.2), errors
    assert errors[-1] < 3e-4


def test_dry_contact_tends_to_hertz():
    """The elastic contact alone (load pi/2) against P = sqrt(1 - X^2), H0 = -(1+2ln2)/4.

    Measured: max-norm 0.0527, 0.0373, 0.0264, 0.0186 on 61..481 nodes (order 1/2, set by
    the sqrt edge); inside |X| < 0.9: 1.2e-3, 3.2e-4, 7.2e-5, 1.7e-5 (order 2); approach
    2.2e-5 ... 3.7e-7 (order 2). Fails with the kernel's sign flipped.
    """
    exact_approach = -(1 + 2 * math.log(2)) / 4
    e_max, e_in, e_h0 = [], [], []
    for n in (61, 121, 241, 481):
        d = dry_line_contact(n)
        exact = np.sqrt(np.clip(1 - d.x**2, 0, None))
        e_max.append(np.abs(d.pressure - exact).max())
        e_in.append(np.abs(d.pressure - exact)[np.abs(d.x) < 0.9].max())
        e_h0.append(abs(d.approach - exact_approach))
        assert np.all(d.pressure >= 0) and np.all(d.gap >= -1e-12)
    for errs, ratio in ((e_max, 1.3), (e_in, 3.5), (e_h0, 3.5)):
        assert np.all(np.array(errs[:-1]) / np.array(errs[1:]) > ratio), errs
    assert e_max[-1] < 0.02 and e_in[-1] < 2e-5 and e_h0[-1] < 4e-7


# -- rigid isoviscous limit -------------------------------------------------------------
def test_martin_load_closed_form():
    """3/(1 + c^2) = 2.44748 with the exit c = 0.475130; the classical 2.4493 within 0.1 %;
    the closed-form load and pressure against plain quadrature of the Reynolds equation
    (fails with the by-parts sign flipped)."""
    assert rigid_isoviscous_load(-1e9) == pytest.approx(2.447484, abs=2e-6)
    assert rigid_isoviscous_load(-1e9) == pytest.approx(2.4493, rel=1e-3)
    inlet = -6.0
    p, c = rigid_isoviscous_pressure(np.array([0.0]), inlet)

    def g(s):
        return (s**2 - c**2) / (1 + s**2) ** 3
    assert p[0] == pytest.approx(scipy.integrate.quad(g, inlet, 0.0, epsabs=1e-14)[0], rel=1e-10)
    load = scipy.integrate.quad(
        lambda x: scipy.integrate.quad(g, inlet, x, epsabs=1e-14)[0], inlet, c, epsabs=1e-13)[0]
    assert rigid_isoviscous_load(inlet) == pytest.approx(12 * load, rel=1e-8)


def test_rigid_isoviscous_limit_converges():
    """E' -> inf, alpha = 0: the film approach h0 against the exact rigid film with the same
    inlet (solved from rigid_isoviscous_load). Measured relative errors of h(0):
    -2.7e-2, -8.5e-3, -2.4e-3, -4.8e-4 on 100..800 nodes (order 1.7 -> 2.3).
    Fails with the wedge term first-order upwind (order drops to 1) or with lambda's 12
    written 6."""
    oil = Lubricant(0.0117)
    R, u, w = 0.02, 1.0, 1e4
    errors = []
    for n in (100, 200, 400):
        r = line_contact(radius=R, reduced_modulus=1e19, lubricant=oil, mean_speed=u,
                         load_per_length=w, nodes=n)
        x_in = r.x[0]
        h0 = scipy.optimize.brentq(
            lambda h: w * h / (2 * 0.0117 * u * R) - rigid_isoviscous_load(x_in / math.sqrt(2 * R * h)),
            1e-9, 1e-5, xtol=1e-22)
        errors.append(abs(r.film_central / h0 - 1))
        assert np.all(np.isfinite(r.pressure)) and r.pressure.min() >= 0
    assert errors[0] / errors[1] > 2.5 and errors[1] / errors[2] > 3.0, errors
    assert errors[-1] < 4e-3


# -- EHL: fits --------------------------------------------------------------------------
CASES = [  # (mu0, alpha, u_m, w): Moes M from 10 to 97, L from 6.3 to 11
    (0.0117, 2e-8, 1.0, 1e5), (0.0117, 2e-8, 1.0, 1e6),
    (0.04, 2e-8, 2.0, 3e5), (0.04, 1.5e-8, 5.0, 1e6)]


@pytest.mark.parametrize("mu0, alpha, u, w", CASES)
def test_films_against_published_fits(mu0, alpha, u, w):
    """Barus + Dowson-Higginson oil, 1000 nodes (films within 1.3 % of the mesh limit at
    M = 97, 0.1 % at M = 10; second order, docs/ehl.md).

    Minimum film against Dowson & Higginson's h_min = 2.65 R U^0.7 G^0.54 W^-0.13: measured
    0.98-1.02 over these cases; central film against Pan & Hamrock (1989): 1.06-1.12 (their
    fit is to Roelands-oil solutions; the inlet sets the film, where Roelands and Barus
    agree, so a few percent apart). Fails with the density left out of the wedge term, with
    alpha halved, or with the elastic deflection left out of the film.
    """
    oil = Lubricant(mu0, barus=alpha, density="dowson-higginson")
    r = line_contact(**STEEL, lubricant=oil, mean_speed=u, load_per_length=w, nodes=1000)
    fit = pan_hamrock(0.02, 2.26e11, mu0, u, w, alpha)
    dh = dowson_higginson(0.02, 2.26e11, mu0, u, w, alpha)
    assert r.film_min / dh == pytest.approx(1.0, abs=0.04)
    assert 1.0 < r.film_central / fit.central < 1.16
    assert r.film_min < r.film_central
    assert r.pressure.min() >= 0 and np.all(np.isfinite(r.film))
    # load balance closes: int p dx = w
    assert np.sum(r.pressure) * (r.x[1] - r.x[0]) == pytest.approx(w, rel=1e-8)
    # near Hertz: peak pressure close to p_h, contact width close to 2b
    assert r.pressure_max == pytest.approx(r.hertz_pressure, rel=0.1)
    hz = hertz_line(0.02, 2.26e11, w)
    assert r.hertz_half_width == pytest.approx(hz.half_width)


ROELANDS_CASES = [  # (mu0, Z, u_m, w): M = 9.4 ... 97, L = 5.4 ... 9.2
    (0.0117, 0.6, 1.0, 1e5), (0.0117, 0.6, 1.0, 1e6), (0.0117, 0.6, 5.0, 2e6),
    (0.1, 0.5, 0.5, 2e5)]


@pytest.mark.parametrize("mu0, z, u, w", ROELANDS_CASES)
def test_roelands_films_against_pan_hamrock(mu0, z, u, w):
    """Roelands + Dowson-Higginson oil, the oil Pan & Hamrock (1989) fitted, G = alpha* E'.

    Measured at 1000 nodes: h_c / fit 1.019, 1.005, 1.051, 1.035 and h_min / fit 1.029,
    0.997, 1.020, 1.020; the mesh error is <= 1.2 % (docs/ehl.md), the rest is the fit's.
    (At L = 11 ... 16 the fit is 4-16 % below: outside this test, reported in the docs.)
    Fails with Roelands' 5.1e-9 written 5.1e-8 or with the wedge's density dropped.
    """
    oil = Lubricant(mu0, roelands=z, density="dowson-higginson")
    r = line_contact(**STEEL, lubricant=oil, mean_speed=u, load_per_length=w, nodes=1000)
    fit = pan_hamrock(0.02, 2.26e11, mu0, u, w, oil.pressure_viscosity)
    assert r.film_central / fit.central == pytest.approx(1.0, abs=0.06)
    assert r.film_min / fit.minimum == pytest.approx(1.0, abs=0.04)


def test_heavier_load_thins_film_slightly_and_raises_pressure():
    """h ~ w^-0.13: doubling the load thins h_min by about 9 %, not 50 % (a rigid film would
    halve). Fails if the elastic deflection is dropped (film halves)."""
    a = line_contact(**STEEL, lubricant=OIL, mean_speed=1.0, load_per_length=5e5, nodes=400)
    b = line_contact(**STEEL, lubricant=OIL, mean_speed=1.0, load_per_length=1e6, nodes=400)
    assert 0.8 < b.film_min / a.film_min < 0.97
    assert b.pressure_max > a.pressure_max


# -- hard cases -------------------------------------------------------------------------
@pytest.mark.parametrize("kwargs, name", [
    (dict(radius=0.0), "radius"), (dict(radius=float("nan")), "radius"),
    (dict(reduced_modulus=-1.0), "reduced_modulus"), (dict(mean_speed=0.0), "mean_speed"),
    (dict(mean_speed=float("inf")), "mean_speed"), (dict(load_per_length=-5.0), "load_per_length"),
    (dict(lubricant=0.0117), "lubricant"), (dict(nodes=10), "nodes"), (dict(nodes=500.0), "nodes"),
    (dict(nodes=10**5), "nodes"), (dict(inlet=0.5), "inlet"), (dict(outlet=0.2), "outlet"),
])
def test_bad_input_names_the_parameter(kwargs, name):
    args = dict(**STEEL, lubricant=OIL, mean_speed=1.0, load_per_length=5e5)
    args.update(kwargs)
    with pytest.raises(ValueError, match=name):
        line_contact(**args)


def test_unconverged_newton_raises():
    """One Newton iteration cannot converge: ConvergenceError, never a result."""
    X = np.linspace(-4.5, 1.5, 200)
    prob = DimensionlessLine(X, 0.01, lambda P: (np.exp(10 * P), 10 * np.exp(10 * P)),
                             lambda P: (np.ones_like(P), np.zeros_like(P)))
    P0 = np.sqrt(np.clip(1 - X**2, 0, None))
    with pytest.raises(ConvergenceError, match="Newton"):
        solve_dimensionless(prob, P0, 0.1, max_iter=1)
    assert issubclass(ConvergenceError, RuntimeError)


# -- docs and benchmark ----------------------------------------------------------------
def test_docs_page_snippets_run(monkeypatch):
    """docs/ehl.md's python blocks run as written (fails when the page drifts from the API)."""
    import re
    from pathlib import Path
    root = Path(__file__).resolve().parent.parent
    snippets = re.findall(r"```python\n(.*?)```", (root / "docs" / "ehl.md").read_text(), re.S)
    assert snippets
    monkeypatch.chdir(root)
    for code in snippets:
        exec(compile(code, "docs/ehl.md", "exec"), {"__name__": "docs"})


def test_benchmark_smoke(capsys):
    """benchmarks/ehl.py runs; its rows converge with the mesh and its two routes agree
    (times printed, not asserted)."""
    from benchmarks import ehl
    rows = ehl.main(["--quick"])
    assert [r["nodes"] for r in rows[:2]] == [250, 500]
    assert rows[1]["h_c"] == pytest.approx(rows[0]["h_c"], rel=0.02)
    route = [r for r in rows if "multilevel" in r]
    assert len(route) == 1 and route[0]["film"] < 1e-9
    out = capsys.readouterr().out
    assert "dense/FFT" in out and "multilevel" in out


@pytest.mark.slow
def test_default_nodes_within_one_percent_of_the_mesh_limit():
    """At M = 97 (the heaviest case above) the default grid's films are within 1 % of the
    Richardson limit of 2000 and 4000 nodes (second order: differences fall 4x a doubling).
    Fails if DEFAULT_NODES drops to 500 (4.7 % off). The default (8000) is set by the
    outlet spike (test_ehl_multilevel.py), the films need ~1500."""
    args = dict(**STEEL, lubricant=OIL, mean_speed=1.0, load_per_length=1e6)
    r = line_contact(**args)
    fine, finer = (line_contact(**args, nodes=n) for n in (2000, 4000))
    for name in ("film_central", "film_min"):
        limit = getattr(finer, name) + (getattr(finer, name) - getattr(fine, name)) / 3
        assert getattr(r, name) == pytest.approx(limit, rel=0.01)


def test_load_continuation_reaches_the_cold_start_answer(monkeypatch):
    """A cold start that fails (forced here) is rescued by ramping the load up from 1/4:
    same films to the Newton tolerance. Fails if the load fraction is not carried into the
    load balance or the ramp stops short (the film of a lighter contact comes back)."""
    from bearingfem.ehl import contact
    args = dict(**STEEL, lubricant=OIL, mean_speed=1.0, load_per_length=5e5, nodes=300)
    cold = line_contact(**args)
    real = contact.solve_dimensionless
    calls = []

    def fail_first(*a, **k):
        calls.append(k.get("load", 1.0))
        if len(calls) == 1:
            raise ConvergenceError("forced", 1)
        return real(*a, **k)

    monkeypatch.setattr(contact, "solve_dimensionless", fail_first)
    ramped = line_contact(**args)
    assert ramped.continuation_steps > 1 and calls[1] < 1.0 and calls[-1] == 1.0
    assert ramped.film_central == pytest.approx(cold.film_central, rel=1e-7)
    assert ramped.film_min == pytest.approx(cold.film_min, rel=1e-7)
    np.testing.assert_allclose(ramped.pressure, cold.pressure, rtol=0, atol=1e-6 * cold.pressure_max)


def test_extremes_converge_or_raise_never_nan():
    """M = 0.1 (nearly rigid: the inlet stretches to 25 rigid lengths) converges to a finite
    film close to the rigid one; M = 870 at 600 nodes is beyond this Newton solver and
    raises ConvergenceError rather than returning a film."""
    light = line_contact(**STEEL, lubricant=OIL, mean_speed=1.0, load_per_length=1e3, nodes=600)
    assert np.all(np.isfinite(light.pressure)) and np.all(np.isfinite(light.film))
    rigid = 2 * 2.44748 * 0.0117 * 1.0 * 0.02 / 1e3       # Martin's film, far inlet
    assert light.film_central == pytest.approx(rigid, rel=0.05)
    with pytest.raises(ConvergenceError, match="load continuation"):
        line_contact(**STEEL, lubricant=OIL, mean_speed=0.05, load_per_length=2e6, nodes=600)


@pytest.mark.parametrize("mu0, alpha, u, w", [(0.0117, 2e-8, 1.0, 1e5), (0.04, 1.5e-8, 5.0, 1e6)])
def test_moes_parameters_are_the_hertz_scaled_films_groups(mu0, alpha, u, w):
    """Moes' M and L fix the film problem in Hertz units: from Hertz's half-width
    b = sqrt(8 w R / (pi E')) and p_h = 2 w / (pi b) (Johnson 1985, Eq. 4.45, by hand), the
    Reynolds coefficient lambda = 12 mu0 u_m R^2 / (b^3 p_h) is 3 pi^2 / (8 M^2) and the
    pressure-viscosity alpha p_h is L sqrt(M / (2 pi)) (both follow from M = W (2U)^-1/2,
    L = G (2U)^1/4). Round-off. No test read the groups: they survived M = W U^-1/2 and
    L = G (2U)^1/2 (fits.py)."""
    from bearingfem.ehl.fits import moes_parameters
    R, E = STEEL["radius"], STEEL["reduced_modulus"]
    M, L = moes_parameters(R, E, mu0, u, w, alpha)
    b = math.sqrt(8 * w * R / (math.pi * E))
    ph = 2 * w / (math.pi * b)
    assert 12 * mu0 * u * R**2 / (b**3 * ph) == pytest.approx(3 * math.pi**2 / (8 * M**2),
                                                               rel=1e-12)
    assert alpha * ph == pytest.approx(L * math.sqrt(M / (2 * math.pi)), rel=1e-12)
