"""Lubricant: how the oil's viscosity and density follow the film pressure.

Pressures are gauge pressures [Pa] (zero at ambient), as in the films. Viscosity
(one of, or neither for a constant-viscosity oil):

* Barus (1893): mu = mu0 exp(alpha p), ``barus=alpha`` [1/Pa].
* Roelands (1966), in the form of Houpert (1985):
  mu = mu0 exp((ln mu0 + 9.67) (-1 + (1 + 5.1e-9 p)^Z)), ``roelands=Z``, mu0 in Pa s.
  Its slope at ambient is the equivalent Barus alpha* = 5.1e-9 Z (ln mu0 + 9.67).

Density (one of, or neither for an incompressible oil):

* ``density="dowson-higginson"`` (Dowson & Higginson 1966):
  rho/rho0 = 1 + 0.6e-9 p / (1 + 1.7e-9 p), tending to 1 + 0.6/1.7 = 1.353 as p -> inf.
* ``bulk_modulus=B`` [Pa]: a constant bulk modulus B = rho dp/drho, so
  rho/rho0 = exp(p/B), the law of Elrod's (1981) compressible cavitation algorithm.

Temperature is not modelled: every property is at the one reference temperature of
``viscosity``. A thermal model would add a ``temperature`` argument to
:meth:`Lubricant.viscosity_at` and :meth:`Lubricant.density_at` (e.g. Roelands'
temperature term, or mu0(T) of Vogel) with the pressure laws here unchanged.

References: C. Barus, Am. J. Sci. 45 (1893) 87-96. C.J.A. Roelands, Correlational
aspects of the viscosity-temperature-pressure relationship of lubricating oils, PhD
thesis, TU Delft (1966). L. Houpert, J. Tribol. 107 (1985) 241-248. D. Dowson and
G.R. Higginson, Elasto-hydrodynamic lubrication, Pergamon (1966). H.G. Elrod, J. Lubr.
Technol. 103 (1981) 350-354.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Lubricant"]

ROELANDS_P0 = 1.0 / 5.1e-9        # [Pa] Roelands' reference pressure, 196 MPa
ROELANDS_LN_MU_INF = -9.67         # ln(mu_inf / (1 Pa s)), mu_inf = 6.31e-5 Pa s
DH_A, DH_B = 0.6e-9, 1.7e-9        # [1/Pa] Dowson-Higginson constants
DENSITY_MODELS = (None, "dowson-higginson")


def _positive(name: str, value, *, allowed: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
        raise ValueError(f"{name} must be a number {allowed}, got {value!r}")
    value = float(value)
    if not (math.isfinite(value) and value > 0.0):
        raise ValueError(f"{name} must be finite and {allowed}, got {value!r}")
    return value


@dataclass(frozen=True)
class Lubricant:
    """A Newtonian oil with pressure-dependent viscosity and density.

    Parameters
    ----------
    viscosity : dynamic viscosity at ambient pressure mu0 [Pa s], > 0.
    barus : Barus pressure-viscosity coefficient alpha [1/Pa], >= 0 (0: constant).
    roelands : Roelands pressure-viscosity index Z [-], in (0, 2]; exclusive with barus.
    density : ``None`` (incompressible) or ``"dowson-higginson"``.
    bulk_modulus : constant bulk modulus B [Pa], > 0; rho/rho0 = exp(p/B). Exclusive with
        ``density``.
    """

    viscosity: float
    barus: float | None = None
    roelands: float | None = None
    density: str | None = None
    bulk_modulus: float | None = None

    def __post_init__(self):
        _positive("viscosity", self.viscosity, allowed="> 0 [Pa s]")
        if self.barus is not None and self.roelands is not None:
            raise ValueError("give barus or roelands, not both (one pressure-viscosity law)")
        if self.barus is not None:
            if self.barus != 0.0:
                _positive("barus", self.barus, allowed=">= 0 [1/Pa]")
        if self.roelands is not None:
            z = _positive("roelands", self.roelands, allowed="in (0, 2]")
            if z > 2.0:
                raise ValueError(f"roelands must be in (0, 2], got {z!r}")
        if self.density not in DENSITY_MODELS:
            raise ValueError(f"density must be one of {DENSITY_MODELS}, got {self.density!r}")
        if self.bulk_modulus is not None:
            _positive("bulk_modulus", self.bulk_modulus, allowed="> 0 [Pa]")
            if self.density is not None:
                raise ValueError("give density or bulk_modulus, not both (one density law)")

    # -- viscosity ---------------------------------------------------------------------
    @property
    def pressure_viscosity(self) -> float:
        """d ln(mu)/dp at ambient [1/Pa]: alpha for Barus, alpha* for Roelands, 0 else."""
        if self.roelands is not None:
            return self.roelands * (math.log(self.viscosity) - ROELANDS_LN_MU_INF) / ROELANDS_P0
        return float(self.barus or 0.0)

    def _log_viscosity_ratio(self, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """ln(mu/mu0) and its derivative d/dp at gauge pressure p."""
        if self.roelands is not None:
            z = self.roelands
            c = math.log(self.viscosity) - ROELANDS_LN_MU_INF
            # below -p0 the law has no meaning; clip so a Newton iterate cannot make NaN
            s = np.maximum(1.0 + p / ROELANDS_P0, 1e-12)
            return c * (s**z - 1.0), c * z * s**(z - 1.0) / ROELANDS_P0
        alpha = float(self.barus or 0.0)
        return alpha * p, np.full_like(p, alpha)

    def viscosity_at(self, p) -> np.ndarray:
        """Viscosity mu(p) [Pa s] at gauge pressure p [Pa] (array or scalar)."""
        p = np.asarray(p, dtype=float)
        return self.viscosity * np.exp(self._log_viscosity_ratio(p)[0])

    def viscosity_derivative(self, p) -> np.ndarray:
        """d mu / d p [Pa s / Pa] at gauge pressure p [Pa]."""
        p = np.asarray(p, dtype=float)
        log_ratio, slope = self._log_viscosity_ratio(p)
        return self.viscosity * np.exp(log_ratio) * slope

    # -- density -----------------------------------------------------------------------
    def density_at(self, p) -> np.ndarray:
        """Density ratio rho/rho0 [-] at gauge pressure p [Pa]."""
        p = np.asarray(p, dtype=float)
        if self.density == "dowson-higginson":
            return 1.0 + DH_A * p / (1.0 + DH_B * p)
        if self.bulk_modulus is not None:
            return np.exp(p / self.bulk_modulus)
        return np.ones_like(p)

    def density_derivative(self, p) -> np.ndarray:
        """d(rho/rho0)/dp [1/Pa] at gauge pressure p [Pa]."""
        p = np.asarray(p, dtype=float)
        if self.density == "dowson-higginson":
            return DH_A / (1.0 + DH_B * p) ** 2
        if self.bulk_modulus is not None:
            return np.exp(p / self.bulk_modulus) / self.bulk_modulus
        return np.zeros_like(p)
