"""Our side of benchmarks/ross31.py (ROSS itself never runs in the test suite): the bearing
it measures is Lund & Thomsen's, and the frame it reads ROSS's rows in is ours."""
import math

import numpy as np
import pytest

from benchmarks import _ross31_env, ross31


def test_the_two_groove_case_is_lund_and_thomsens_bearing():
    """Lund & Thomsen (1978), L/D 1, S 0.635: eps 0.224, attitude 63.54 deg from the load
    line (their table). Ours at P2 36x6 is 0.2243 / 63.59 deg (P2 192x32: within 2e-4 of
    it, benchmarks/ross31.py), so 0.002 and 0.2 deg hold (tests/test_lund_thomsen.py's
    tolerances). Fails (run) with the grooves turned onto the load line (eps 0.51)."""
    c = ross31.CASES["two_groove"]
    eps, gamma, K, C = ross31.design_numbers(c["bearing"], c["load"], c["omega"], (36, 6),
                                             c["grooves"])
    assert eps == pytest.approx(0.224, abs=0.002)
    # the load pulls down (-y): the attitude is the journal angle measured from -90 deg
    assert math.degrees(gamma) + 90.0 == pytest.approx(63.54, abs=0.2)
    assert K.shape == C.shape == (2, 2)


def test_ross_rows_are_read_in_our_frame():
    """ROSS reports the journal centre (xj, yj) / c in the same x (horizontal), y (up) frame
    as ours; its angle is atan2(yj, xj). Fails with atan2's arguments swapped (a
    journal at -30 deg read at -60 deg) or with eps taken from xj."""
    gamma = math.radians(-30.0)
    ours = (0.3, gamma, np.eye(2), 2 * np.eye(2))
    row = dict(eps=0.3, xj=0.3 * math.cos(gamma), yj=0.3 * math.sin(gamma),
               K=np.eye(2).tolist(), C=(2 * np.eye(2)).tolist())
    assert ross31.design_error(ross31.ross_design(row), ours) < 1e-15
    shifted = dict(row, xj=0.3 * math.cos(gamma + 0.01), yj=0.3 * math.sin(gamma + 0.01))
    assert ross31.design_error(ross31.ross_design(shifted), ours) == pytest.approx(0.01)


def test_ross_environment_needs_its_mirror(tmp_path, monkeypatch):
    """The installer refuses, naming the path, when the source snapshot is absent, and
    reuses an existing environment without touching the network. Fails if install()
    rebuilds over a recorded environment (it would look for the mirror and raise)."""
    monkeypatch.setattr(_ross31_env, "VENV", tmp_path / "venv")
    with pytest.raises(FileNotFoundError, match="nowhere"):
        _ross31_env.install(mirror=tmp_path / "nowhere")
    (tmp_path / "venv").mkdir()
    (tmp_path / "venv" / "ross31.json").write_text('{"ross_commit": "abc", "numba": "0"}')
    assert _ross31_env.install(mirror=tmp_path / "nowhere")["ross_commit"] == "abc"
