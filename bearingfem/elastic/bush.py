"""The elastic bush: material and geometry of the linear, isotropic sleeve that carries the
film on its inner surface (elastohydrodynamic, EHD, journal bearings)."""
from __future__ import annotations

from dataclasses import dataclass, replace

from ..bearing import check_finite, check_positive

__all__ = ["ElasticBush", "MODELS", "ENDS", "OUTER_RATIO"]

#: the held outer radius over the film radius R when ``outer_radius`` is not given: the
#: seed pin's bronze bush (R 10 mm, held at 16 mm), scaled with R so that any journal gets
#: a bush (a fixed 16 mm was refused from D = 32 mm on, and was a thin liner just below)
OUTER_RATIO = 1.6

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
    outer_radius : radius of the held outer surface [m], > R (checked where R is known);
        None (default): :data:`OUTER_RATIO` R, resolved where R is known
        (:meth:`at_radius`: 16 mm for the seed's R = 10 mm)
    modulus : Young's modulus E [Pa], > 0
    poisson : Poisson's ratio nu, in (-1, 0.5)
    model : "solid", "ring", "liner" or "solid-3d" (see :data:`MODELS`); the liner's
        thickness is the wall, outer_radius - R
    ends : end faces of the solid model (see :data:`ENDS`); the ring and liner ignore it
    """

    outer_radius: float | None = None
    modulus: float = 110e9
    poisson: float = 0.34
    model: str = "solid"
    ends: str = "free"

    def __post_init__(self):
        if self.outer_radius is not None:
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
        """The film radius R [m], checked against the bush: 0 < R < outer_radius (any
        R > 0 when the outer radius is the default's, OUTER_RATIO R)."""
        radius = check_positive("radius", radius)
        if self.outer_radius is not None and radius >= self.outer_radius:
            raise ValueError(f"outer_radius must exceed the film radius R={radius!r}, "
                             f"got outer_radius={self.outer_radius!r} (leave it out for "
                             f"the default, {OUTER_RATIO:g} R = "
                             f"{self._default_outer(radius):g} m)")
        return radius

    def at_radius(self, radius: float) -> "ElasticBush":
        """The bush under a film of radius R [m]: R checked (:meth:`check_inner_radius`)
        and the outer radius resolved (:data:`OUTER_RATIO` R when not given); the bush
        itself when it was given."""
        radius = self.check_inner_radius(radius)
        if self.outer_radius is not None:
            return self
        return replace(self, outer_radius=self._default_outer(radius))

    @staticmethod
    def _default_outer(radius: float) -> float:
        # 12 significant digits: 0.04, not 0.04000000000000001 (R 25 mm), where it is shown
        return float(f"{OUTER_RATIO * radius:.12g}")

    @property
    def lame(self) -> tuple[float, float]:
        """Lame parameters (lambda, mu) [Pa]."""
        from skfem.models.elasticity import lame_parameters
        return lame_parameters(self.modulus, self.poisson)
