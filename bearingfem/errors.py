"""Errors the toolkit raises besides ``ValueError`` (bad input)."""
from __future__ import annotations

__all__ = ["ConvergenceError", "LoadCapacityError", "OilRangeWarning",
           "TemperatureRangeError"]


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


class LoadCapacityError(ValueError):
    """A steady load beyond what the film carries before contact (its force at
    ``eps_max``): bad input, refused before an equilibrium is searched past the wall.

    The capacity is that of the film as solved: on a mesh too coarse for the film at
    ``eps_max`` it is the mesh's, not the bearing's (D 50 mm, L/D 0.5, c 50 um, ISO VG 32,
    3000 rpm: 8 x 2 cells carried 1991 N where 120 x 20 carry 2.5e5 N), and a finer
    ``n_theta`` (or ``rtol``) is what helps; on a
    mesh that resolves the film, a larger bearing or a lighter load.

    Parameters
    ----------
    load : the load's magnitude [N]
    capacity : what the film carries at ``eps_max`` [N]
    eps_max : the largest eccentricity ratio searched
    model : the film model's name
    mesh : the film's mesh options the capacity was found on (``n_theta``, ``n_z`` and,
        for the FE film, ``element``), or None for a model without a mesh
    note : words that end the message (e.g. that the mesh was an error estimate's), or ""
    """

    def __init__(self, load: float, capacity: float, eps_max: float, model: str,
                 mesh: dict | None = None, note: str = ""):
        self.load, self.capacity, self.eps_max, self.model = (
            float(load), float(capacity), float(eps_max), model)
        self.mesh, self.note = (None if mesh is None else dict(mesh)), note
        super().__init__(f"load {self.load:.6g} N exceeds what the film carries before "
                         f"contact: {self.capacity:.6g} N at eps_max = {self.eps_max:g} "
                         f"({model} model){f', {note}' if note else ''}")

    def __reduce__(self):      # picklable (dask workers send errors back)
        return LoadCapacityError, (self.load, self.capacity, self.eps_max, self.model,
                                   self.mesh, self.note)


class TemperatureRangeError(ValueError):
    """A temperature [K] where a lubricant's viscosity law gives no finite viscosity
    (<= 0 K, NaN, or outside :attr:`bearingfem.lubricant.Lubricant.temperature_range`).
    A ValueError, as any input refused; typed so that a solver can tell its own iterate
    leaving the law (a diverged step) from any other ValueError."""


class OilRangeWarning(UserWarning):
    """A solved thermal film whose temperature left the oil law's range
    (:data:`bearingfem.oil_range.OIL_TEMPERATURE_RANGE`): its viscosity, and so its
    numbers, are the law's extrapolation there. The message gives the temperature."""
