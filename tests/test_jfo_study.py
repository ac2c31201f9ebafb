"""The Reynolds-vs-JFO study of the seed's piston pin runs and says what it found."""
from studies import jfo_paper


def test_jfo_paper_study_smoke(tmp_path, capsys):
    rows, forms, collapses, per_bin = jfo_paper.main(["-o", str(tmp_path), "--turns", "0.3",
                                             "--no-progress"])
    out = capsys.readouterr().out
    assert [r["film"] for r in rows] == ["FE, Reynolds' condition", "FE, JFO"]
    assert "JFO cavity forms at crank" in out and "cost JFO / Reynolds" in out
    assert (tmp_path / "jfo_paper.png").stat().st_size > 10_000
    assert (tmp_path / "jfo_paper_films.png").stat().st_size > 10_000
    assert all(0.0 < r["peak_eps"] < 1.0 for r in rows)
    assert all(r["friction_power_W"] > 0.0 for r in rows)     # shear dissipates power
    # a run shorter than a turn is recorded whole: every accepted step up to the last
    # saved sample (within 1/720 turn of the end) is counted in its crank-angle interval
    # (0.3 turn: the first four)
    for h, r in zip(per_bin.values(), rows):
        assert 0.95 * r["steps"] <= h.sum() <= r["steps"] and h[4:].sum() == 0
