"""Smoke test of the paper reproduction: the study runs, saves and plots (short runs)."""
import numpy as np

from mechanism import load_result
from studies.paper import run


def test_paper_study_quick(tmp_path):
    names = ["paper-short-analytic", "paper-long-analytic", "paper-long-fem"]
    results, rows = run(tmp_path, names, turns=0.5, progress=False)
    assert [r["status"] for r in rows] == ["completed"] * 3
    for n in names:
        r = load_result(tmp_path / n)
        assert np.all(np.isfinite(r.eps)) and r.eps.max() < 1.0
    assert (tmp_path / "paper-short.png").is_file() and (tmp_path / "paper-long.png").is_file()
    assert (tmp_path / "summary.csv").read_text().count("completed") == 3
