"""FE-accurate film forces at closed-form cost: a table of the dimensionless force.

The load of the Reynolds equation is f = 6 w eps sin(theta) - 12 eps_dot cos(theta),
w = omega - 2 gamma_dot. With v = (eps_dot, eps w / 2) = |v| (cos phi, sin phi),

    f = -12 |v| cos(theta + phi),

so the pressure, and with it the force, is |v| times a function of (eps, phi) alone for
one L/D: linear for a full film, positively homogeneous for the clipped (Gumbel) and the
complementarity (Reynolds) film. Near contact the squeeze part outgrows the wedge part by
about (1 - eps^2)^-1/2, so the force turns sharply with phi around the pure-wedge
direction; the table therefore uses the balanced velocity v' = (r eps_dot, eps w / 2),
r = (1 - eps^2)^-1/2, and its angle phi' (the same homogeneity holds in v'). That
function is tabulated from FE solves on a grid in

    u = -ln(1 - eps)   (nodes clustered toward eps = 1)  x  phi' (periodic),

as g = (1 - eps)^k F / |v'| (k = SCALE_EXPONENT), which stays bounded as eps -> 1, and
interpolated by bicubic splines. A table is built once per (L/D, mesh, cavitation, grid), kept on disk with its
inputs and the toolkit version, and rebuilt when either differs.
"""
from __future__ import annotations

import hashlib
import json
import logging
import os
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy.interpolate import RectBivariateSpline

from ..bearing import Bearing, JournalState
from ..caches import cached
from ..scales import half_film_factor
from ..solvers.cavitation import active_set
from ..solvers.linsolve import factorise
from ..validation import CAVITATION, check_choice, check_int
from ..version import __version__
from .assembly import fe_operator, film_operator
from .kernel import rigid_force
from .mesh import ELEMENTS, MIN_N_THETA, MIN_N_Z

__all__ = ["ForceTable", "build_force_table", "force_table", "table_force", "cache_dir",
           "TABLE_DEFAULTS"]

FORMAT = 3          # bump when the tabulated quantity changes: old files go stale
_PAD = 3          # phi nodes wrapped onto each side so the spline sees the periodicity
SCALE_EXPONENT = 2.0   # k in g = (1 - eps)^k F / |v'|
#: The "fem-table" model's defaults (the registry reads them here). A table is built once,
#: so its mesh can be finer than a per-step solve's: P2 64x16 is within 0.06 % of converged
#: forces at L/D 0.2-2 (measured against P2 384x96; 96x16 P1 was 1.8-2.5 % off).
TABLE_DEFAULTS = dict(n_theta=64, n_z=16, element="P2", cavitation="gumbel", n_eps=60,
                      n_phi=96)
_D = TABLE_DEFAULTS


#: progress of a table's build (tens of seconds at the defaults): INFO, shown by the CLI
LOG = logging.getLogger(__name__)


def cache_dir() -> Path:
    """Where tables are kept: $BEARINGFEM_CACHE, else ~/.cache/bearingfem."""
    root = os.environ.get("BEARINGFEM_CACHE") or Path.home() / ".cache" / "bearingfem"
    return Path(root)


@dataclass(frozen=True, eq=False)
class ForceTable:
    """Dimensionless film force on an (eps, phi) grid for one L/D and mesh.

    ``g_r``, ``g_t`` have shape (n_eps, n_phi): (1 - eps)^k times the force over
    force_scale |v'| (half-domain symmetry already doubled), phi being the angle of v'.
    """

    key: dict                  # what the table was built from (JSON-able)
    eps: np.ndarray
    phi: np.ndarray
    g_r: np.ndarray
    g_t: np.ndarray
    #: the table mesh's force error: largest relative gap to a mesh twice as fine over a
    #: few states, measured when the table was built (its interpolation error is apart)
    mesh_error: float = 0.0
    _splines: tuple = field(init=False, repr=False)

    def __post_init__(self):
        u = -np.log1p(-self.eps)
        dphi = self.phi[1] - self.phi[0]
        phi_ext = np.concatenate([self.phi[-_PAD:] - 2 * np.pi, self.phi,
                                  self.phi[:_PAD] + 2 * np.pi])
        assert np.allclose(np.diff(phi_ext), dphi)
        wrap = lambda g: np.concatenate([g[:, -_PAD:], g, g[:, :_PAD]], axis=1)
        object.__setattr__(self, "_splines", tuple(
            RectBivariateSpline(u, phi_ext, wrap(g), kx=3, ky=3, s=0)
            for g in (self.g_r, self.g_t)))

    @property
    def eps_max(self) -> float:
        return float(self.eps[-1])

    def evaluate(self, eps, phi):
        """Dimensionless (F_r, F_t) / |v'| at (eps, phi'), arrays broadcast together.

        Beyond the last tabulated eps, g is held at its edge value: the force keeps
        growing as (1 - eps)^-2 but is not accurate there (keep eps_max at the film
        model's cap, 0.999 by default).
        """
        eps, phi = np.broadcast_arrays(np.asarray(eps, float), np.asarray(phi, float))
        u = -np.log1p(-np.minimum(eps, self.eps_max))
        ph = np.mod(phi, 2 * np.pi)
        scale = 1.0 / (1.0 - eps) ** SCALE_EXPONENT
        return tuple(s(u, ph, grid=False) * scale for s in self._splines)


def squeeze_weight(eps):
    """r = (1 - eps^2)^-1/2: squeeze over wedge sensitivity of the force near contact."""
    return 1.0 / np.sqrt(1.0 - np.minimum(eps, 0.999999) ** 2)


def _eps_nodes(n_eps: int, eps_max: float) -> np.ndarray:
    return -np.expm1(-np.linspace(0.0, -np.log1p(-eps_max), n_eps))


def build_force_table(length_ratio: float, n_theta=_D["n_theta"], n_z=_D["n_z"],
                      element=_D["element"], cavitation=_D["cavitation"], n_eps=_D["n_eps"],
                      n_phi=_D["n_phi"], eps_max=0.999) -> ForceTable:
    """Tabulate the dimensionless force from FE solves (see the module docstring)."""
    op = film_operator(n_theta, n_z, element, float(length_ratio), None, True)
    free = op.mesh.free
    eps = _eps_nodes(n_eps, eps_max)
    phi = np.linspace(0.0, 2 * np.pi, n_phi, endpoint=False)
    mult = half_film_factor(op.mesh.half)
    g = np.zeros((2, n_eps, n_phi))
    # f = 12 (sin phi * sin(theta) - cos phi * cos(theta)) on the unit-|v| film.
    b_s, b_c = 12.0 * op.b_sin[free], -12.0 * op.b_cos[free]
    for i, e in enumerate(eps):
        K = op.free_stiffness(e)
        sq = 1.0 / squeeze_weight(e)      # eps_dot per unit of the balanced v' component
        if cavitation == "reynolds":
            P = np.zeros((n_phi, op.mesh.ndofs))
            prev = None
            for j, ph in enumerate(phi):   # neighbours in phi warm-start each other
                res = active_set(K, np.sin(ph) * b_s + sq * np.cos(ph) * b_c,
                                 active0=None if prev is None else prev.active,
                                 factor=None if prev is None else prev.factor)
                P[j, free] = res.pressure
                prev = res
        else:   # linear film: two solves give every direction
            lu = factorise(K)
            Ps, Pc = np.zeros(op.mesh.ndofs), np.zeros(op.mesh.ndofs)
            Ps[free], Pc[free] = lu.solve(b_s), lu.solve(b_c)
            P = np.sin(phi)[:, None] * Ps + sq * np.cos(phi)[:, None] * Pc
        g[:, i] = mult * op.force_integrals(P, clip=cavitation == "gumbel")
    g *= ((1.0 - eps) ** SCALE_EXPONENT)[None, :, None]
    key = _key(length_ratio, n_theta, n_z, element, cavitation, n_eps, n_phi, eps_max)
    error = _mesh_error(length_ratio, n_theta, n_z, element, cavitation, eps_max)
    return ForceTable(key, eps, phi, g[0], g[1], error)


def _force(bearing, state, n_theta, n_z, element, cavitation) -> tuple:
    """(F_r, F_t) [N] of the rigid FE film (half length, film frame): the table's own."""
    op = fe_operator(bearing, state, n_theta, n_z, element, None, True)
    return rigid_force(bearing, state, op, cavitation)[0]


def _mesh_error(length_ratio, n_theta, n_z, element, cavitation, eps_max) -> float:
    """Largest relative force gap between the table's mesh and one twice as fine, over
    wedge, squeeze and mixed states at eps 0.3 to 0.9 (a dozen solves)."""
    b = Bearing(radius=1.0, length=2.0 * length_ratio, clearance=1e-3, viscosity=1.0)
    gaps = []
    for e in (0.3, 0.6, min(0.9, eps_max)):
        for ed, w in ((0.0, 1.0), (1.0, 0.0), (0.5, 1.0), (-0.5, 1.0)):
            s = JournalState(e, ed, 0.0, 0.0, w)
            coarse = np.array(_force(b, s, n_theta, n_z, element, cavitation))
            fine = np.array(_force(b, s, 2 * n_theta, 2 * n_z, element, cavitation))
            gaps.append(np.linalg.norm(coarse - fine) / max(np.linalg.norm(fine), 1e-300))
    return float(max(gaps))


def _key(length_ratio, n_theta, n_z, element, cavitation, n_eps, n_phi, eps_max) -> dict:
    return dict(format=FORMAT, version=__version__, length_ratio=float(length_ratio),
                n_theta=int(n_theta), n_z=int(n_z), element=str(element),
                cavitation=str(cavitation), n_eps=int(n_eps), n_phi=int(n_phi),
                eps_max=float(eps_max))


def _load(path: Path, key: dict) -> ForceTable | None:
    try:
        with np.load(path) as z:
            if json.loads(str(z["key"])) != key:
                return None                      # stale: other version or inputs
            return ForceTable(key, z["eps"], z["phi"], z["g_r"], z["g_t"],
                              float(z["mesh_error"]))
    except (OSError, KeyError, ValueError):
        return None


def _save(path: Path, table: ForceTable) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(f".{os.getpid()}.tmp.npz")
    np.savez(tmp, key=json.dumps(table.key), eps=table.eps, phi=table.phi,
             g_r=table.g_r, g_t=table.g_t, mesh_error=table.mesh_error)
    os.replace(tmp, path)                        # atomic: readers never see half a file


@cached(maxsize=16)
def force_table(length_ratio: float, n_theta=_D["n_theta"], n_z=_D["n_z"],
                element=_D["element"], cavitation=_D["cavitation"], n_eps=_D["n_eps"],
                n_phi=_D["n_phi"], eps_max=0.999) -> ForceTable:
    """The table for these inputs: from memory, else from disk, else built and saved."""
    check_int("n_theta", n_theta, MIN_N_THETA)
    check_int("n_z", n_z, MIN_N_Z)
    check_choice("element", element, tuple(ELEMENTS))
    check_choice("cavitation", cavitation, CAVITATION)
    check_int("n_eps", n_eps, 6)
    check_int("n_phi", n_phi, 16)
    if not 0.5 <= eps_max <= 0.999:
        raise ValueError(f"eps_max of the table must lie in [0.5, 0.999], got {eps_max!r}")
    key = _key(length_ratio, n_theta, n_z, element, cavitation, n_eps, n_phi, eps_max)
    name = hashlib.sha1(json.dumps(key, sort_keys=True).encode()).hexdigest()[:16]
    path = cache_dir() / f"force-table-{name}.npz"
    table = _load(path, key)
    if table is None:
        LOG.info("fem-table: building the force table of L/D %g once (%d x %d states on %s "
                 "%d x %d, kept in %s)", length_ratio, n_eps, n_phi, element, n_theta, n_z,
                 path.parent)
        t0 = time.perf_counter()
        table = build_force_table(length_ratio, n_theta, n_z, element, cavitation,
                                  n_eps, n_phi, eps_max)
        LOG.info("fem-table: built in %.1f s", time.perf_counter() - t0)
        try:
            _save(path, table)
        except OSError:
            pass                                 # a read-only cache only costs a rebuild
    return table


def table_force(bearing, state, n_theta=_D["n_theta"], n_z=_D["n_z"], element=_D["element"],
                cavitation=_D["cavitation"], n_eps=_D["n_eps"], n_phi=_D["n_phi"],
                eps_max=0.999):
    """(F_r, F_t) [N] on the journal from the cached table (the "fem-table" model)."""
    vx = squeeze_weight(state.eps) * state.eps_dot
    vy = 0.5 * state.eps * state.wedge_speed
    speed = float(np.hypot(vx, vy))
    if speed == 0.0:
        return 0.0, 0.0
    table = force_table(bearing.length_ratio, n_theta, n_z, element, cavitation,
                        n_eps, n_phi, eps_max)
    g_r, g_t = table.evaluate(state.eps, np.arctan2(vy, vx))
    k = bearing.force_scale * speed
    return k * float(g_r), k * float(g_t)
