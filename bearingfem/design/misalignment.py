"""The literature's misalignment parameters mapped onto ``tilt=(tilt_x, tilt_y)``.

Published studies of misaligned journal bearings (Vijayaraghavan & Keith, J. Tribol. 112
(1990); restated by Jang & Khonsari, Lubricants 3 (2015) 27-53, Sec. 1.2) describe the
tilt by the projection of the journal's axis on the mid-plane: the centre at the end of
the bearing sits e' away from the mid-plane centre, at the angle alpha from the line of
centres (in the sense of theta, i.e. of rotation), so that the film is

    h = c (1 + eps cos theta) + e' (2 z / L) cos(theta - alpha),   -L/2 <= z <= L/2,

theta from the maximum film. The degree of misalignment D_m = e' / e'_max scales e' by
its largest value, the one at which an end touches the bush: the ends sit at
eps r +- (e'/c) m with m at alpha from r, and |eps r +- (e'/c) m| = 1 first for the end
offset towards the eccentricity,

    e'_max / c = -eps |cos(alpha)| + sqrt(1 - eps^2 sin(alpha)^2),

the published form -eps cos(alpha) + ... for |alpha| <= 90 deg; beyond it the other end
(offset -e') is the one that touches.

Derivation of the mapping: our journal centre at z is e + z (tilt_y, -tilt_x)
(:func:`bearingfem.fields.tilted_gap`), so the end z = L/2 is offset by
(L/2)(tilt_y, -tilt_x) = e' (cos(gamma + alpha), sin(gamma + alpha)), i.e.

    tilt_x = -(2 e' / L) sin(gamma + alpha),   tilt_y = (2 e' / L) cos(gamma + alpha),

and then tilted_gap's (R/c) zeta (tilt_y cos(theta + gamma) - tilt_x sin(theta + gamma))
is (e'/c)(2 z / L) cos(theta - alpha), the film above. Check a paper's own definition of
alpha (sense, origin) before comparing: conventions differ between authors.
"""
from __future__ import annotations

import math

from ..bearing import Bearing, JournalState, check_finite, check_turn_angle
from ..validation import check_inputs

__all__ = ["misalignment_tilt", "degree_of_misalignment", "largest_end_offset"]


def largest_end_offset(eps: float, angle: float) -> float:
    """e'_max / c: the end offset at ``angle`` [rad] from the line of centres at which one
    of the journal's ends touches the bush (module docstring)."""
    return -eps * abs(math.cos(angle)) + math.sqrt(1.0 - (eps * math.sin(angle)) ** 2)


def misalignment_tilt(bearing: Bearing, state: JournalState, degree: float,
                      angle: float) -> tuple:
    """(tilt_x, tilt_y) [rad] of the degree of misalignment D_m = ``degree`` in [0, 1) and
    the angle of misalignment alpha = ``angle`` [rad] at the journal position ``state``."""
    check_inputs(bearing, state)
    degree, angle = check_finite("degree", degree), check_turn_angle("angle", angle)
    if not 0.0 <= degree < 1.0:
        raise ValueError(f"degree (of misalignment) must lie in [0, 1): 1 is the end touching "
                         f"the bush, got {degree!r}")
    offset = degree * largest_end_offset(state.eps, angle) * bearing.clearance
    k = 2.0 * offset / bearing.length
    a = state.gamma + angle
    return (-k * math.sin(a), k * math.cos(a))


def degree_of_misalignment(bearing: Bearing, state: JournalState, tilt) -> tuple:
    """(D_m, alpha [rad]) of ``tilt`` at the journal position ``state``: the inverse of
    :func:`misalignment_tilt` (alpha = 0 for an aligned journal)."""
    check_inputs(bearing, state)
    tx, ty = (check_finite(f"tilt[{i}]", v) for i, v in enumerate(tilt))
    offset = 0.5 * bearing.length * math.hypot(tx, ty)
    if offset == 0.0:
        return 0.0, 0.0
    angle = math.atan2(-tx, ty) - state.gamma
    angle = math.atan2(math.sin(angle), math.cos(angle))
    return offset / (bearing.clearance * largest_end_offset(state.eps, angle)), angle
