"""The Reynolds-vs-JFO study of the seed's piston pin runs and says what it found."""
from studies import jfo_paper


def test_jfo_paper_study_smoke(tmp_path, capsys):
    rows, forms, collapses = jfo_paper.main(["-o", str(tmp_path), "--turns", "0.3",
                                             "--no-progress"])
    out = capsys.readouterr().out
    assert [r["film"] for r in rows] == ["FE, Reynolds' condition", "FE, JFO"]
    assert "JFO cavity forms at crank" in out and "cost JFO / Reynolds" in out
    assert (tmp_path / "jfo_paper.png").stat().st_size > 10_000
    assert all(0.0 < r["peak_eps"] < 1.0 for r in rows)
