"""Design-chart sweep cases and figures (the Dask run itself is tested in test_sweep.py)."""
import math

import pytest

from bearingfem import Bearing, JournalState, solve_reynolds
from studies.design_charts import plot_design_charts
from bearingfem_app.sweep import parse_sweep, run_case, sweep_cases


def test_design_case_matches_the_film_and_raimondi_boyd():
    row = run_case("design", dict(eps=0.6, length_ratio=1.0, model="fem", element="P2",
                                  n_theta=72, n_z=12, cavitation="reynolds", omega=250.0))
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    sol = solve_reynolds(b, JournalState(0.6, omega=250.0), 72, 12, "P2", "reynolds")
    assert row["load"] == pytest.approx(math.hypot(*sol.force_local), rel=1e-9)
    # Raimondi & Boyd (L/D 1, eps 0.6): S 0.121, phi 50.58 deg, (R/c) f 3.22; their film
    # starts at the maximum film, ours is periodic: within 2 %, 1.5 deg, 3 %
    assert row["sommerfeld"] == pytest.approx(0.121, rel=0.02)
    assert row["attitude_deg"] == pytest.approx(50.58, abs=1.5)
    assert row["friction_variable"] == pytest.approx(3.22, rel=0.03)
    assert row["coefficient_method"] == "exact-sensitivity"
    assert {f"{n}{i}{j}" for n in "KC" for i in "12" for j in "12"} <= set(row)


def test_design_sweep_validates_and_plots(tmp_path):
    sw = parse_sweep({"kind": "design", "base": {"model": "short"},
                      "vary": {"eps": [0.2, 0.5, 0.8], "length_ratio": [0.25, 0.5]}})
    rows = [run_case("design", p) for p in sweep_cases(sw)]
    assert all(r["coefficient_method"] == "analytic" for r in rows)
    paths = plot_design_charts(rows, tmp_path)
    assert all(p.stat().st_size > 10_000 for p in paths)
    with pytest.raises(ValueError, match="sweep.vary.eps_dot is not a design sweep parameter"):
        parse_sweep({"kind": "design", "vary": {"eps_dot": [1.0]}})
