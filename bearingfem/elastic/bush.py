"""The elastic bush: material and geometry of the linear, isotropic sleeve that carries the
film on its inner surface (elastohydrodynamic, EHD, journal bearings)."""
from __future__ import annotations

from dataclasses import dataclass

from ..bearing import check_finite, check_positive

__all__ = ["ElasticBush", "MODELS", "ENDS"]

#: "solid": the bush as a 3-D body, by finite elements on its (r, z) section per
#: circumferential harmonic (:mod:`.fourier`); "solid-3d": the same body by 3-D finite
#: elements (hexahedra, one sparse LU of the whole bush: the comparison, costly);
#: "ring": a plane-strain ring per axial slice of the film, slices independent; "liner":
#: a thin liner (wall t = outer_radius - R << R) compressing locally, w = t p / M
#: (Winkler, :mod:`.liner`).
MODELS = ("solid", "ring", "liner", "solid-3d")
#: End faces of the solid (both forms): "free" (traction-free) or "plane-strain" (held axially, free to
#: slide radially and tangentially, so a z-independent load gives the plane-strain field).
ENDS = ("free", "plane-strain")


@dataclass(frozen=True)
class ElasticBush:
    """A linear isotropic bush between the film (inner radius R, that of the bearing) and a
    rigid housing (``outer_radius``) that holds its outer surface fixed (no displacement).

    Parameters
    ----------
    outer_radius : radius of the held outer surface [m], > R (checked where R is known)
    modulus : Young's modulus E [Pa], > 0
    poisson : Poisson's ratio nu, in (-1, 0.5)
    model : "solid", "ring", "liner" or "solid-3d" (see :data:`MODELS`); the liner's
        thickness is the wall, outer_radius - R
    ends : end faces of the solid model (see :data:`ENDS`); the ring and liner ignore it
    """

    outer_radius: float = 0.016
    modulus: float = 110e9
    poisson: float = 0.34
    model: str = "solid"
    ends: str = "free"

    def __post_init__(self):
        object.__setattr__(self, "outer_radius", check_positive("outer_radius",
                                                                self.outer_radius))
        object.__setattr__(self, "modulus", check_positive("modulus", self.modulus))
        nu = check_finite("poisson", self.poisson)
        if not -1.0 < nu < 0.5:
            raise ValueError(f"poisson must be in (-1, 0.5), got {self.poisson!r}")
        object.__setattr__(self, "poisson", nu)
        for name, allowed in (("model", MODELS), ("ends", ENDS)):
            if getattr(self, name) not in allowed:
                raise ValueError(f"{name} must be one of {', '.join(map(repr, allowed))}, "
                                 f"got {getattr(self, name)!r}")

    def check_inner_radius(self, radius: float) -> float:
        """The film radius R [m], checked against the bush: 0 < R < outer_radius."""
        radius = check_positive("radius", radius)
        if radius >= self.outer_radius:
            raise ValueError(f"outer_radius must exceed the film radius R={radius!r}, "
                             f"got outer_radius={self.outer_radius!r}")
        return radius

    @property
    def lame(self) -> tuple[float, float]:
        """Lame parameters (lambda, mu) [Pa]."""
        from skfem.models.elasticity import lame_parameters
        return lame_parameters(self.modulus, self.poisson)
