"""The oscillation study runs, and its answer holds on a short run: the Eq. 9 force spikes
appear with both integrators at both tolerances, the exact model has none."""
import pytest

from studies.hard_cases import run


@pytest.mark.slow   # 7 s: runs the oscillation study with two integrators
def test_spikes_belong_to_the_model(tmp_path):
    rows = run(tmp_path, turns=2.0)
    spikes = {(m, i, r): s for m, i, r, *_, s in rows}
    assert all(spikes[("short", i, r)] > 0 for i in ("lsoda", "bdf") for r in (1e-4, 1e-8))
    assert all(spikes[("short-exact", i, r)] == 0 for i in ("lsoda", "bdf") for r in (1e-4, 1e-8))
    assert (tmp_path / "short_bearing_oscillations.png").is_file()
