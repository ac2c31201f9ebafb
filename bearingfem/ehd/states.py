"""The EHD films with the bush's deflection as states of the time integration, one
module each:

- :class:`ModalStateEHD` (:mod:`bearingfem.ehd.states_modal`): the deflection's leading
  modes of the reduced compliance integrated with the journal; the coupling itself (the
  Kelvin-Voigt bush, dq/dt eliminated from the Reynolds residual, its Newton, the
  summits' pressure, the tangent) is written there.
- :class:`FullStateEHD` (:mod:`bearingfem.ehd.states_full`, ``modes`` 0): the whole
  deflection on the bush's grid, no modes chosen (docs/ehd-states.md, "The whole
  deflection integrated").

Both are imported from here; so are the Newton tolerance ``TOL``, GMRES's
``STEP_TOLERANCE`` and :func:`full_bush_setup`, which the implicit-step film
(:mod:`bearingfem.ehd.implicit`) shares.
"""
from ..contract import StateTangent
from .states_full import STEP_TOLERANCE, FullStateEHD, full_bush_setup  # noqa: F401
from .states_modal import TOL, ModalStateEHD  # noqa: F401 (TOL: the implicit-step film)

__all__ = ["ModalStateEHD", "FullStateEHD", "StateTangent"]
