"""Errors the toolkit raises besides ``ValueError`` (bad input)."""
from __future__ import annotations

__all__ = ["ConvergenceError", "OilRangeWarning"]


class ConvergenceError(RuntimeError):
    """An iterative solve stopped without converging; nothing unconverged is returned.

    Parameters
    ----------
    solve : what did not converge (e.g. "JFO active set")
    iterations : iterations it took before giving up
    residual : its residual when it stopped (relative, as the solve defines it), or None
    where : the time, step or state of the solve (e.g. "t = 0.0125 s, step 312"), or ""
    """

    def __init__(self, solve: str, iterations: int, residual: float | None = None,
                 where: str = ""):
        self.solve, self.iterations, self.residual, self.where = (
            solve, int(iterations), residual, where)
        res = "" if residual is None else f", residual {residual:.3g}"
        at = f" at {where}" if where else ""
        super().__init__(f"{solve} did not converge{at}: {self.iterations} iterations{res}")

    def at(self, where: str) -> "ConvergenceError":
        """The same failure with the time or step of the caller added to ``where``."""
        return ConvergenceError(self.solve, self.iterations, self.residual,
                                f"{self.where}, {where}" if self.where else where)

    def __reduce__(self):      # picklable (dask workers send errors back)
        return ConvergenceError, (self.solve, self.iterations, self.residual, self.where)


class OilRangeWarning(UserWarning):
    """A solved thermal film whose temperature left the oil law's range
    (:data:`bearingfem.oil_range.OIL_TEMPERATURE_RANGE`): its viscosity, and so its
    numbers, are the law's extrapolation there. The message gives the temperature."""
