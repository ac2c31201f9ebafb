"""The compressible (Elrod-type) JFO film along a time integration: the "fem-jfo-compressible"
model's :class:`~bearingfem.contract.RunFilm`.

The stepping policy is :class:`~bearingfem.transient.TransientJFO`'s (film steps at accepted
integrator steps, spaced by ``film_step``, early when the line of centres has turned by half
a cell, their change of force faded in); the film is a
:class:`~bearingfem.fe.jfo_compressible.CompressibleJFOFilm`. It never asks for an early
film step on a refill: between film steps a kept cavity the gap closes on is compressed
(its pressure rises from zero with the closing gap), so the force the integrator sees has
no refill jump.
"""
from __future__ import annotations

from .bearing import Bearing, JournalState, check_positive
from .fe.jfo_compressible import CompressibleJFOFilm
from .transient import TransientJFO

__all__ = ["CompressibleTransientJFO", "OIL_BULK_MODULUS"]

#: [Pa] a mineral oil's isentropic bulk modulus near ambient pressure and 40 C (about
#: 1.5-2 GPa; the lower end, the softer film).
OIL_BULK_MODULUS = 1.5e9


class CompressibleTransientJFO(TransientJFO):
    """:class:`TransientJFO` on the compressible film; ``bulk_modulus`` B [Pa] > 0."""

    def __init__(self, bearing: Bearing, n_theta: int, n_z: int, grooves=(),
                 ambient_pressure: float = 0.0, film_step: float = 0.0,
                 bulk_modulus: float = OIL_BULK_MODULUS):
        super().__init__(bearing, n_theta, n_z, grooves, ambient_pressure, film_step)
        self.bulk_modulus = check_positive("bulk_modulus", bulk_modulus)

    def start(self, state: JournalState, t: float) -> None:
        """Begin a full film at ``state``, time ``t`` [s]."""
        # the compressible film takes no fields or tilt (the constructor gives none)
        options = {k: v for k, v in self._film_options.items()
                   if k not in ("fields", "tilt", "tilt_rate")}
        self.film = CompressibleJFOFilm(self.bearing, state, bulk_modulus=self.bulk_modulus,
                                        time=float(t), **options)
        self.t = float(t)
        self._warm, self._jump, self._fade, self.steps = None, (0.0, 0.0), 1.0, 0
