"""The continuation walk (bearingfem.solvers.continuation) shared by the EHD coupling, the
EHD-JFO coupling and the EHL load ramps: the parameter values it tries, against the rule
written out by hand, and its refusal when the step falls below the smallest."""
import pytest

from bearingfem.errors import ConvergenceError
from bearingfem.solvers.continuation import Increments, Ratios


def _solve_within(reach, tried):
    """A solve that converges only within ``reach`` of the state it starts from."""
    def solve(x, state):
        tried.append(x)
        return (x if x - state <= reach else None), 1
    return solve


def test_increments_quarter_a_failed_step_and_double_a_converged_one():
    """From 0 with reach 0.3: 1 fails; 0.25 converges; 0.75 (+ 0.5) fails; 0.375 (+ 0.125)
    and 0.625 (+ 0.25) converge; 1.0 (+ 0.5, capped at the target) fails; 0.75 (+ 0.125)
    and 1.0 (+ 0.25) converge."""
    tried = []
    walk = Increments(1.0, 1e-4).walk(_solve_within(0.3, tried), 0.0, 0.0, 1.0, "t", "s", "")
    assert tried == [1.0, 0.25, 0.75, 0.375, 0.625, 1.0, 0.75, 1.0]
    assert (walk.state, walk.steps, walk.rejected, walk.iterations) == (1.0, 5, 3, 8)


def test_ratios_take_the_square_root_of_a_failed_ratio_and_keep_a_converged_one():
    """From 1/4 with reach 0.3: 0.5 converges, 1.0 fails, 0.5 sqrt 2 converges, then
    1.0 (0.707 sqrt 2, capped)."""
    tried = []
    walk = Ratios(2.0, 1.02).walk(_solve_within(0.3, tried), 0.25, 0.25, 1.0, "t", "f", "")
    assert tried == pytest.approx([0.5, 1.0, 0.5 * 2 ** 0.5, 1.0])
    assert walk.state == 1.0 and (walk.steps, walk.rejected) == (3, 1)


@pytest.mark.parametrize("rule, start", [(Increments(1.0, 1e-4), 0.0), (Ratios(2.0, 2.0), 0.25)])
def test_a_walk_that_cannot_move_raises_naming_the_parameter(rule, start):
    """Nothing converges: the walk raises ConvergenceError with the value reached and the
    hint (a ratio rule whose smallest step is its step does not retry)."""
    tried = []
    with pytest.raises(ConvergenceError, match=f"coupling = {start:g}.*reduce the load"):
        rule.walk(_solve_within(-1.0, tried), start, start, 1.0, "walk", "coupling",
                  "reduce the load")
    assert len(tried) == (7 if isinstance(rule, Increments) else 1)   # 1, 1/4, ... 1/4^6


def test_a_failed_attempt_counts_its_iterations_and_says_what_follows(caplog):
    """attempt() gave (None, 0) for a solve that raised after 7 iterations (Walk's count
    'failed ones included' missed them), and the progress line read 'stalled in 0
    iterations' where a shorter step was tried next."""
    import logging
    from types import SimpleNamespace

    from bearingfem.solvers.continuation import attempt

    def solve(x):
        if x > 0.5:
            raise ConvergenceError("test solve", 7)
        return SimpleNamespace(x=x, iterations=3)
    assert attempt(solve, 1.0) == (None, 7)

    def walked(x, state):
        return attempt(solve, x)
    log = logging.getLogger("bearingfem.test_continuation")
    with caplog.at_level(logging.INFO, logger="bearingfem"):
        walk = Increments(1.0, 1e-4).walk(walked, 0.0, 0.0, 0.5, "walk", "s", "", log)
    said = [r.getMessage() for r in caplog.records]
    assert said[0] == "walk: s = 0.5 converged in 3 iterations" and walk.iterations == 3
    with caplog.at_level(logging.INFO, logger="bearingfem"):
        with pytest.raises(ConvergenceError):
            Increments(1.0, 0.6).walk(walked, 0.0, 0.0, 1.0, "walk", "s", "", log)
    assert "walk: s = 1 not converged (a shorter step next) in 7 iterations" in \
        [r.getMessage() for r in caplog.records]
