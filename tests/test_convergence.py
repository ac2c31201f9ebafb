"""Mesh-convergence study: Richardson/GCI arithmetic, and observed orders on a real film."""
import numpy as np
import pytest

from bearingfem import JournalState, solve_reynolds
from bearingfem.outputs.convergence import convergence_study, richardson
from conftest import table1_bearing


def test_richardson_recovers_a_known_sequence():
    exact, c, p = 3.0, 0.7, 2.0
    f = [exact + c * h ** p for h in (0.4, 0.2, 0.1)]   # coarse .. fine
    order, ext, gci = richardson(f[2], f[1], f[0])
    assert order == pytest.approx(p, abs=1e-12) and ext == pytest.approx(exact, rel=1e-12)
    assert gci == pytest.approx(1.25 * abs((f[2] - f[1]) / f[2]) / 3.0)
    assert np.isnan(richardson(1.0, 2.0, 1.5)[0])   # oscillating: no order claimed


def test_richardson_claims_no_order_for_a_growing_difference():
    """Monotone but not converging (differences 0.1 then 0.3, as P2's cavitated share of
    L/D 1, eps 0.6 over 24 x 4 .. 96 x 16): the order was -1.65 and the GCI -5.3 %."""
    for f in ((1.75, 1.25, 1.0), (1.5, 1.25, 1.0)):      # fine .. coarse: growing, equal
        assert all(np.isnan(v) for v in richardson(*f))


def test_richardson_claims_no_order_for_an_oscillating_sequence():
    """Differences of alternating sign (fine .. coarse 1.0, 1.1, 0.6: -0.1 then +0.5) are
    not in the asymptotic range, however fast they shrink: no order, no extrapolation, no
    GCI (Roache, Verification and Validation in Computational Science and Engineering,
    1998, sec. 5.9). Fails with the sign check dropped (order 2.32 and a GCI claimed)."""
    assert all(np.isnan(v) for v in richardson(1.0, 1.1, 0.6))


def test_study_rows_are_the_films_own_forces():
    """Each row's |F| is the film's force magnitude, here taken from the inertial
    (F_x, F_y) of a solve of its own on the row's mesh (a second route: the study reads
    the local (F_r, F_t)), and its F_r, F_t the local pair. Fails with |F| summed
    componentwise (|F_r| + |F_t|: 1.38 |F| here)."""
    b, s = table1_bearing(1.0), JournalState(0.6, omega=250.0, gamma=0.7)
    study = convergence_study(b, s, levels=3, n_theta=24, n_z=4, cavitation="gumbel",
                              methods=("P1",))
    for row in study.rows:
        sol = solve_reynolds(b, s, row["n_theta"], row["n_z"], "P1", "gumbel")
        assert row["force"] == pytest.approx(np.hypot(*sol.force), rel=1e-12)
        assert (row["F_r"], row["F_t"]) == pytest.approx(sol.force_local, rel=1e-12)


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
    # each summary row names its quantity's SI unit (the CLI prints them)
    units = {r["quantity"]: r["unit"] for r in s.summary}
    assert units == {"force": "N", "F_r": "N", "F_t": "N", "pressure_max": "Pa",
                     "cavitated_fraction": "1", "friction_force": "N", "side_leakage": "m^3/s"}
    assert (tmp_path / "c_summary.csv").read_text().startswith("method,quantity,unit,finest")
    assert (tmp_path / "c.png").stat().st_size > 5000


def test_study_rejects_bad_levels():
    with pytest.raises(ValueError, match="levels"):
        convergence_study(table1_bearing(1.0), JournalState(0.6, omega=250.0), levels=2)


def test_plot_shows_every_method_with_units_and_the_case(tmp_path, monkeypatch):
    import matplotlib.figure
    from bearingfem.outputs.convergence import ConvergenceStudy
    saved = []
    monkeypatch.setattr(matplotlib.figure.Figure, "savefig",
                        lambda self, *a, **k: saved.append(self))
    rows = ([{"method": "P1", "dofs": d, "force": 1.0 + 1.0 / d} for d in (100, 400, 1600)]
            + [{"method": "P2", "dofs": d, "force": f}
               for d, f in ((100, 1.01), (400, 0.995), (1600, 1.002))])
    summary = [{"method": "P1", "quantity": "force", "order": 2.0, "extrapolated": 1.0,
                "gci": 1e-3},
               {"method": "P2", "quantity": "force", "order": np.nan, "extrapolated": np.nan,
                "gci": np.nan}]
    ConvergenceStudy(rows, summary, "L/D 1, eps 0.6").plot(tmp_path / "c.png")
    ax = saved[0].axes[0]
    names = [t.get_text() for t in ax.get_legend().get_texts()]
    assert names[0].startswith("P1: observed order 2.00") and names[1].startswith("P2: no order")
    assert "L/D 1, eps 0.6" in ax.get_title() and ax.get_xlabel().endswith("[-]")


def test_ctrl_c_keeps_the_meshes_solved(tmp_path, monkeypatch, capsys):
    """Ctrl-C during `bearingfem convergence` writes the meshes solved so far to
    convergence_partial.csv (PARTIAL on stdout too) and exits 130; it wrote nothing, losing a
    long study's fine levels."""
    import bearingfem.outputs.convergence as conv
    from bearingfem_app.cli import main
    real, calls = conv.solve_reynolds, []

    def interrupted_on_the_third(*args, **kwargs):
        calls.append(1)
        if len(calls) == 3:
            raise KeyboardInterrupt
        return real(*args, **kwargs)
    monkeypatch.setattr(conv, "solve_reynolds", interrupted_on_the_third)
    out = tmp_path / "conv"
    out.mkdir()
    (out / "convergence.csv").write_text("an earlier, complete study\n")
    assert main(["convergence", "--methods", "P1", "--levels", "4", "-o", str(out)]) == 130
    lines = (out / "convergence_partial.csv").read_text().splitlines()
    assert len(lines) == 3 and lines[1].startswith("P1,24,4,") and lines[2].startswith("P1,48,8,")
    assert "wrote the 2 meshes solved" in capsys.readouterr().out
    assert not (out / "convergence_summary.csv").exists()
    # a complete study's table in the folder is kept (it was overwritten by the partial one)
    assert (out / "convergence.csv").read_text() == "an earlier, complete study\n"
    # the study run again to its end leaves no partial table beside its own
    assert main(["convergence", "--methods", "P1", "--levels", "3", "-o", str(out)]) == 0
    assert not (out / "convergence_partial.csv").exists()
    assert len((out / "convergence.csv").read_text().splitlines()) == 4
