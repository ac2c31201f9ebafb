"""Continuation: a solve too hard from a cold start, reached through easier ones.

A parameter x (the EHD coupling s, the EHL load fraction f, the eccentricity beyond the
clearance) walks from a value where the problem is solved to its target; each converged
step's answer starts the next solve. A step that does not converge is retried shorter;
when the step falls below its smallest, :class:`~bearingfem.errors.ConvergenceError` names
the value reached. The step rule is the walk's only difference between problems:
:class:`Increments` adds (x + dx: a failed dx is cut to a quarter, a converged one
doubles, up to the first), :class:`Ratios` multiplies (x r: a failed ratio is replaced by
its square root, a converged one kept). ``x`` never passes the target: the last step lands
on it exactly.
"""
from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from typing import Callable

from ..errors import ConvergenceError

__all__ = ["Continuation", "Increments", "Ratios", "Walk", "attempt"]


def attempt(solve: Callable, *args, **kwargs) -> tuple:
    """One step of a walk: (the record ``solve(*args, **kwargs)`` returns, its
    ``iterations``), or (None, the iterations the error names) when it raises
    ConvergenceError (the walk then retries shorter; :class:`Walk` counts failed
    attempts' iterations too)."""
    try:
        record = solve(*args, **kwargs)
    except ConvergenceError as err:
        return None, err.iterations
    return record, record.iterations


@dataclass(frozen=True)
class Walk:
    """The end of a walk: the solve's ``state`` at the target; ``iterations`` over all
    attempts (as each solve counts them, failed ones included); ``steps`` converged;
    ``rejected`` attempts retried shorter."""

    state: object
    iterations: int
    steps: int
    rejected: int


@dataclass(frozen=True)
class Continuation:
    """A walk's step rule: the first (and, for growing rules, largest) ``step`` and the
    ``smallest`` step tried before the walk gives up."""

    step: float
    smallest: float

    def advance(self, x: float, step: float) -> float:
        raise NotImplementedError

    def shorter(self, step: float) -> float:
        raise NotImplementedError

    def longer(self, step: float) -> float:
        raise NotImplementedError

    def walk(self, solve: Callable, state, start: float, target: float, what: str,
             parameter: str, hint: str, log: logging.Logger | None = None) -> Walk:
        """Walk ``parameter`` from ``start`` (where ``state`` is the solved answer) to
        ``target``: ``solve(x, state)`` gives (the answer at x from ``state``, or None when
        it does not converge; its iterations). Raises ConvergenceError naming ``what``, the
        value reached and the ``hint`` when the step falls below ``smallest``. ``log``: a
        logger told of each attempt at INFO (a long solve's progress)."""
        done, step, iterations, steps, rejected = start, self.step, 0, 0, 0
        while done < target:
            x = min(target, self.advance(done, step))
            out, its = solve(x, state)
            iterations += its
            if log is not None:
                log.info("%s: %s = %.4g %s in %d iterations", what, parameter, x,
                         "not converged (a shorter step next)" if out is None
                         else "converged", its)
            if out is None:
                rejected += 1
                step = self.shorter(step)
                if step < self.smallest:
                    raise ConvergenceError(what, iterations, None,
                                           f"{parameter} = {done:.6g}, step below "
                                           f"{self.smallest}: {hint}")
                continue
            state, steps = out, steps + 1
            done, step = x, self.longer(step)
        return Walk(state, iterations, steps, rejected)


@dataclass(frozen=True)
class Increments(Continuation):
    """x -> x + dx; a failed dx is cut to ``shrink`` dx, a converged one grows by ``grow``
    (up to ``step``)."""

    shrink: float = 0.25
    grow: float = 2.0

    def advance(self, x: float, step: float) -> float:
        return x + step

    def shorter(self, step: float) -> float:
        return self.shrink * step

    def longer(self, step: float) -> float:
        return min(self.step, self.grow * step)


@dataclass(frozen=True)
class Ratios(Continuation):
    """x -> x r (x > 0, r > 1); a failed r is replaced by sqrt(r), a converged one kept.
    ``smallest`` >= ``step``: a failed step is not retried."""

    def advance(self, x: float, step: float) -> float:
        return x * step

    def shorter(self, step: float) -> float:
        return math.sqrt(step)

    def longer(self, step: float) -> float:
        return step
