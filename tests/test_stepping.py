"""The integration loop of mechanism.stepping: stopping on an interrupt."""
import numpy as np

from mechanism.stepping import integrate


def test_an_interrupt_stops_the_loop_between_steps():
    """A Ctrl-C the caller's handler counted (``interrupted``) stops the loop at the next
    accepted step, in Python, not inside the solver's compiled callback (where it can be
    lost), and gives back the steps taken (status INTERRUPTED). Fails with the check
    dropped (the decay then runs to its end)."""
    from mechanism.stepping import INTERRUPTED
    steps = []
    seg = integrate(lambda t, y: -y, (0.0, 10.0), np.array([1.0]), method="LSODA",
                    accept=lambda t, y: steps.append(t), interrupted=lambda: len(steps) >= 3)
    assert len(steps) == 3 and seg.status == INTERRUPTED
    assert list(seg.t[1:]) == steps and np.allclose(seg.y[0], np.exp(-seg.t), rtol=1e-2)
