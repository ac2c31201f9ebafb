"""Mesh-convergence study: Richardson/GCI arithmetic, and observed orders on a real film."""
import numpy as np
import pytest

from bearingfem import JournalState
from bearingfem.outputs.convergence import convergence_study, richardson
from conftest import table1_bearing


def test_richardson_recovers_a_known_sequence():
    exact, c, p = 3.0, 0.7, 2.0
    f = [exact + c * h ** p for h in (0.4, 0.2, 0.1)]   # coarse .. fine
    order, ext, gci = richardson(f[2], f[1], f[0])
    assert order == pytest.approx(p, abs=1e-12) and ext == pytest.approx(exact, rel=1e-12)
    assert gci == pytest.approx(1.25 * abs((f[2] - f[1]) / f[2]) / 3.0)
    assert np.isnan(richardson(1.0, 2.0, 1.5)[0])   # oscillating: no order claimed


def test_study_orders_and_files(tmp_path):
    s = convergence_study(table1_bearing(1.0), JournalState(0.6, omega=250.0), levels=4,
                          n_theta=24, n_z=4, cavitation="gumbel", methods=("P1", "fvm"))
    orders = {(r["method"], r["quantity"]): r["order"] for r in s.summary}
    # measured 1.974 / 1.960 (force), 1.977 / 1.957 (friction): the README's +-0.15 holds
    for method in ("P1", "fvm"):
        for quantity in ("force", "friction_force"):
            assert orders[(method, quantity)] == pytest.approx(2.0, abs=0.15)
    s.write_csv(tmp_path / "c.csv")
    s.plot(tmp_path / "c.png")
    assert (tmp_path / "c_summary.csv").read_text().count("\n") == 1 + 2 * 7
    assert (tmp_path / "c.png").stat().st_size > 5000


def test_study_rejects_bad_levels():
    with pytest.raises(ValueError, match="levels"):
        convergence_study(table1_bearing(1.0), JournalState(0.6, omega=250.0), levels=2)
