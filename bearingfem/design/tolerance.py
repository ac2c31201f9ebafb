"""The designer functions to a requested accuracy: a film model's mesh options chosen by
:mod:`bearingfem.accuracy` for an equilibrium or a linearisation, or the error of a mesh
given (its h/2h pair with the half mesh)."""
from __future__ import annotations

from typing import Callable

from ..accuracy import check_rtol, estimate_at, nominal_order, refine_to_tolerance
from ..models import FilmModel

__all__ = ["answer_to_tolerance"]


def answer_to_tolerance(m: FilmModel, what: str, key, options: dict, evaluate: Callable,
                        difference: Callable, rtol: float | None):
    """(answer, coarse answer, record): ``evaluate(options)`` with the model's mesh options
    (n_theta, n_z and, if the model has it, element) chosen to reach ``rtol`` (relative,
    ``difference(fine, coarse)``), or, with ``rtol`` None, on the mesh of ``options`` with
    its error estimated. ``what`` names the quantity in messages; ``key`` (hashable or
    None) the memo entry, to which the model and its other options are added."""
    if not {"n_theta", "n_z"} <= set(m.defaults):
        raise ValueError(f"rtol and error estimates are for film models on a mesh (options "
                         f"n_theta, n_z); model {m.name!r} has none")
    if rtol is not None:
        rtol = check_rtol(rtol)
    has_element = "element" in m.defaults
    element = options.get("element") if has_element else None
    given = element is not None
    element = element or ("P2" if has_element and rtol is not None else
                          m.defaults.get("element", "P1"))
    cavitation = options.get("cavitation", m.defaults.get("cavitation", "reynolds"))
    smooth = cavitation == "none" and not options.get("grooves")
    order = nominal_order(element, smooth)

    def run(n_theta, n_z, el):
        o = {**options, "n_theta": n_theta, "n_z": n_z}
        if has_element:
            o["element"] = el
        return evaluate(o)

    if rtol is None:
        o = m.options(options)
        return estimate_at(run, difference, (o["n_theta"], o["n_z"]), element=element,
                           order=order)
    rest = {k: v for k, v in options.items() if k not in ("n_theta", "n_z", "element")}
    try:
        memo = (what, m.name, key, given, tuple(sorted((k, repr(v)) for k, v in rest.items())))
        hash(memo)
    except TypeError:
        memo = None
    start = (24, 4) if element == "P2" else (48, 8)
    return refine_to_tolerance(run, difference, rtol, element=element, start_mesh=start,
                               order=order, key=memo)
