"""Scenes: TOML files that say which mechanism, bearing, initial state, run settings and
joint effects a simulation has. Loading validates everything before any integration:
an unknown key, a value out of range or a missing required value is a ``ValueError``
naming it (``scene.effects.contact.poisson must lie in [0, 0.5), got 0.7``).
"""
from __future__ import annotations

import difflib
import math
from dataclasses import dataclass, field
from pathlib import Path

try:
    import tomllib
except ModuleNotFoundError:  # Python < 3.11
    import tomli as tomllib

from bearingfem import Bearing, ElasticBush, Groove, Roughness
from bearingfem.accuracy import check_rtol
from bearingfem.bearing import plausibility_errors
from bearingfem.fields import EdgeProfile
from bearingfem.lubricant import Lubricant, iso_vg_grade
from bearingfem.oil_range import check_oil_temperature
from bearingfem.models import film_model
from bearingfem.thermal import Thermal

from .parameters import Mechanism, check_crank_speed

__all__ = ["Scene", "load_scene", "parse_scene", "INTEGRATORS"]

INTEGRATORS = ("lsoda", "bdf", "radau", "rk45", "dop853")


@dataclass(frozen=True)
class Lubrication:
    model: str
    options: dict = field(default_factory=dict)
    eps_max: float = 0.999
    rtol: float | None = None    # an accuracy asked instead of a mesh (bearingfem.accuracy)


@dataclass(frozen=True)
class Contact:
    young_modulus: float = 207e9
    poisson: float = 0.3
    restitution: float = 0.9
    exponent: float = 1.5


@dataclass(frozen=True)
class Friction:
    coefficient: float
    v_reg: float = 1e-4


@dataclass(frozen=True)
class Spring:
    stiffness: float
    damping: float = 0.0


@dataclass(frozen=True)
class Run:
    turns: float = 5.0
    record_from_turn: float = 0.0
    samples_per_turn: int = 720
    integrator: str = "lsoda"
    rtol: float = 1e-6
    atol: float | None = None      # length tolerance [m]; default 1e-3 clearance (or 1e-9 m)
    max_step: float | None = None  # [s]


@dataclass(frozen=True)
class Scene:
    """Everything one simulation needs; build it with :func:`load_scene`."""

    name: str
    mechanism: Mechanism
    bearing: Bearing | None
    joint: str                      # "clearance" or "ideal"
    crank_angle: float
    crank_speed: float
    run: Run
    gravity: bool
    slider_force: float
    crank_torque: float
    lubrication: Lubrication | None
    contact: Contact | None
    friction: Friction | None
    spring: Spring | None = None
    description: str = ""

    def __post_init__(self):
        # also a scene changed with dataclasses.replace (a sweep's crank_speed, say)
        object.__setattr__(self, "crank_speed",
                           check_crank_speed(self.mechanism, self.crank_speed))


#: how alike an unknown key and a known one must be to be named as its typo (difflib's
#: ratio; 0.6 as the command line's: 'rnu' for 'run' is 0.67)
_CLOSE = 0.6


class _Table:
    """A TOML table being consumed: every key must be used exactly once."""

    def __init__(self, data, where):
        if not isinstance(data, dict):
            raise ValueError(f"{where} must be a table, got {type(data).__name__}")
        self.data, self.where, self.used = data, where, set()

    def get(self, key, default=None, required=False):
        self.used.add(key)
        if key not in self.data:
            if required:
                raise ValueError(f"{self.where}.{key} is required but missing"
                                 f"{self.typo_of(key)}")
            return default
        return self.data[key]

    def typo_of(self, key) -> str:
        """' (unknown key K: did you mean key?)' for the unused keys spelt like ``key``."""
        typo = [k for k in self.data if k not in self.used
                and difflib.get_close_matches(k, [key], n=1, cutoff=_CLOSE)]
        return "".join(f" (unknown key {k}: did you mean {key}?)" for k in typo)

    def number(self, key, default=None, lo=None, hi=None, lo_open=False, hi_open=False,
               required=False):
        v = self.get(key, default, required)
        if v is None:
            return None
        name = f"{self.where}.{key}"
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise ValueError(f"{name} must be a finite number, got {v!r}")
        bad_lo = lo is not None and (v <= lo if lo_open else v < lo)
        bad_hi = hi is not None and (v >= hi if hi_open else v > hi)
        if bad_lo or bad_hi:
            a = "(" if lo_open else "["
            b = ")" if hi_open else "]"
            rng = f"{a}{'-inf' if lo is None else lo}, {'inf' if hi is None else hi}{b}"
            raise ValueError(f"{name} must lie in {rng}, got {v!r}")
        return float(v)

    def choice(self, key, allowed, default=None, required=False):
        v = self.get(key, default, required)
        if v not in allowed:
            raise ValueError(f"{self.where}.{key} must be one of "
                             f"{', '.join(map(repr, allowed))}, got {v!r}")
        return v

    def table(self, key):
        v = self.get(key)
        return None if v is None else _Table(v, f"{self.where}.{key}")

    def done(self):
        extra = sorted(set(self.data) - self.used)
        if extra:
            def named(k):
                near = difflib.get_close_matches(k, sorted(self.used), n=1, cutoff=_CLOSE)
                return f"{k} (did you mean {near[0]}?)" if near else k
            raise ValueError(f"{self.where} has unknown key(s): {', '.join(map(named, extra))}")


def _mechanism(t: _Table | None) -> Mechanism:
    if t is None:
        return Mechanism()
    d = Mechanism()
    kw = {}
    for k in ("crank_length", "rod_length", "crank_inertia", "rod_inertia", "crank_mass",
              "rod_mass", "slider_mass"):
        kw[k] = t.number(k, getattr(d, k), lo=0.0, lo_open=True)
    for k in ("crank_cm", "rod_cm"):
        v = t.get(k, list(getattr(d, k)))
        if not (isinstance(v, list) and len(v) == 2):
            raise ValueError(f"{t.where}.{k} must be a pair [U, V] in metres, got {v!r}")
        kw[k] = tuple(v)
    t.done()
    try:
        return Mechanism(**kw)
    except ValueError as err:
        raise ValueError(f"{t.where}: {err}") from None


def _bearing(t: _Table) -> Bearing:
    D = t.number("diameter", required=True, lo=0.0, lo_open=True)
    length = t.number("length", None, lo=0.0, lo_open=True)
    ratio = t.number("length_ratio", None, lo=0.0, lo_open=True)
    if (length is None) == (ratio is None):
        raise ValueError(f"{t.where} needs exactly one of length [m] or length_ratio (L/D)")
    c = t.number("clearance", required=True, lo=0.0, hi=0.1 * D, lo_open=True)
    if t.get("oil") is None:
        mu = t.number("viscosity", required=True, lo=0.0, lo_open=True)
    elif "viscosity" in t.data:
        raise ValueError(f"{t.where} takes one of viscosity [Pa s] or oil (an ISO VG grade)")
    else:
        mu = oil_viscosity(t.get("oil"), t.number("oil_temperature", 40.0),
                           (f"{t.where}.oil", f"{t.where}.oil_temperature"))
    t.done()
    ld, ld_name = (ratio, "length_ratio") if length is None else (length / D,
                                                                   "length / diameter")
    names = tuple(f"{t.where}.{k}" for k in ("diameter", ld_name, "clearance", "viscosity"))
    bad = plausibility_errors(D, ld, c, mu, names)
    if bad:
        raise ValueError("; ".join(bad))
    return Bearing(radius=D / 2, length=length if length is not None else ratio * D,
                   clearance=c, viscosity=mu)


def oil_viscosity(grade, temperature_c: float, names=("oil", "oil_temperature")) -> float:
    """An ISO VG grade ('ISO VG 32', 'ISO-VG-32', 'VG32', '32' or 32) at ``temperature_c``
    [degC] -> its dynamic viscosity [Pa s] (:meth:`bearingfem.lubricant.Lubricant.iso_vg`, a VI 100
    mineral oil); ``names``: how the caller spells the two inputs."""
    g = iso_vg_grade(grade, names[0])
    check_oil_temperature(names[1], temperature_c, unit="degC")
    oil = Lubricant.iso_vg(g)
    return float(oil.viscosity_at(0.0, temperature=temperature_c + 273.15))


def _lubrication(t: _Table) -> Lubrication:
    """The film model and its options: names, defaults and ranges are the model's own
    (:data:`bearingfem.models.FILM_MODELS`)."""
    model = t.get("model", required=True)
    try:
        m = film_model(model, f"{t.where}.model")
    except ValueError as err:
        raise ValueError(str(err)) from None
    eps_max = t.number("eps_max", 0.999 if m.numeric else 1.0 - 1e-6,
                       lo=0.5, hi=1.0, hi_open=True)
    given = {k: t.get(k) for k in sorted(set(t.data) - {"model", "eps_max", "rtol"})}
    rtol = t.get("rtol")
    if rtol is not None:    # an accuracy instead of a mesh: chosen when the run starts
        rtol = check_rtol(rtol, f"{t.where}.rtol")
        if not {"n_theta", "n_z"} <= set(m.defaults):
            raise ValueError(f"{t.where}.rtol needs a film model on a mesh, got {model!r}")
        if {"n_theta", "n_z"} & set(given):
            raise ValueError(f"{t.where}: give rtol or the mesh (n_theta, n_z), not both")
    if "roughness" in given and "roughness" in m.defaults:   # mixed lubrication
        given["roughness"] = _roughness(_Table(given["roughness"], f"{t.where}.roughness"))
    if isinstance(given.get("grooves"), list):    # [[...grooves]] tables: angle, width [rad]
        try:
            given["grooves"] = tuple(Groove(**g) for g in given["grooves"])
        except (TypeError, ValueError) as err:
            raise ValueError(f"{t.where}.grooves: {err}") from None
    if "oil" in given and "lubricant" in m.defaults:    # the thermal film's oil by grade
        if "lubricant" in given:
            raise ValueError(f"{t.where} takes one of oil (an ISO VG grade) or lubricant")
        given["lubricant"] = Lubricant.iso_vg(iso_vg_grade(given.pop("oil"), f"{t.where}.oil"))
    for key, cls in (("lubricant", Lubricant), ("bush", ElasticBush),     # the EHD film
                     ("profile", EdgeProfile), ("thermal", Thermal)):     # and the THD film
        if isinstance(given.get(key), dict) and key in m.defaults:
            try:
                given[key] = cls(**given[key])
            except (TypeError, ValueError) as err:
                raise ValueError(f"{t.where}.{key}: {err}") from None
    opts = m.options(given, where=t.where)
    if isinstance(opts.get("thermal"), Thermal) and isinstance(opts.get("lubricant"), Lubricant):
        try:      # before any work, not when the run starts (a partial result at t = 0)
            opts["thermal"].check_fluid(opts["lubricant"])
        except ValueError as err:
            raise ValueError(f"{t.where}.thermal: {err}") from None
    t.done()
    if rtol is not None:     # the mesh (and the element, unless given) is chosen at the start
        opts = {k: v for k, v in opts.items()
                if k in given or k not in ("n_theta", "n_z", "element")}
    return Lubrication(model=model, options=opts, eps_max=eps_max, rtol=rtol)


def _roughness(t: _Table) -> Roughness:
    """Greenwood-Tripp rough surfaces (mixed lubrication: the film model's asperity
    contact, :class:`bearingfem.Roughness`)."""
    kw = dict(sigma=t.number("sigma", required=True, lo=0.0, lo_open=True),
              contact_modulus=t.number("contact_modulus", required=True, lo=0.0, lo_open=True),
              friction=t.number("friction", 0.0, lo=0.0))
    for k in ("elastic_factor", "asperity_density", "asperity_radius"):
        kw[k] = t.number(k, None, lo=0.0, lo_open=True)
    t.done()
    try:
        return Roughness(**kw)
    except ValueError as err:
        raise ValueError(f"{t.where}: {err}") from None


def _crank_speed(t: _Table, mech: Mechanism) -> float:
    """crank_speed [rad/s] or rpm [1/min] (one of them; default 250 rad/s), refused when it
    drives the crank pin faster than any slider-crank's (a speed in rpm typed as rad/s)."""
    speed = t.number("crank_speed", None, lo=0.0, lo_open=True)
    rpm = t.number("rpm", None, lo=0.0, lo_open=True)
    if speed is not None and rpm is not None:
        raise ValueError(f"{t.where} takes one of crank_speed [rad/s] or rpm [1/min], "
                         f"got both")
    if rpm is not None:
        return check_crank_speed(mech, rpm * math.pi / 30.0, f"{t.where}.rpm", rpm=True)
    return check_crank_speed(mech, 250.0 if speed is None else speed,
                             f"{t.where}.crank_speed")


def parse_scene(data: dict, name: str = "scene") -> Scene:
    """Validate a scene given as a dict (the parsed TOML)."""
    top = _Table(data, "scene")
    name = str(top.get("name", name))
    description = str(top.get("description", ""))
    joint = top.choice("joint", ("clearance", "ideal"), "clearance")
    mech = _mechanism(top.table("mechanism"))
    bt = top.table("bearing")
    init = top.table("initial") or _Table({}, "scene.initial")
    crank_angle = init.number("crank_angle", 0.0)
    crank_speed = _crank_speed(init, mech)
    init.done()
    rt = top.table("run") or _Table({}, "scene.run")
    run = Run(
        turns=rt.number("turns", 5.0, lo=0.0, lo_open=True, hi=1000.0),
        record_from_turn=rt.number("record_from_turn", 0.0, lo=0.0),
        samples_per_turn=int(rt.number("samples_per_turn", 720, lo=8, hi=1e6)),
        integrator=rt.choice("integrator", INTEGRATORS, "lsoda"),
        rtol=rt.number("rtol", 1e-6, lo=1e-13, hi=0.1),
        atol=rt.number("atol", None, lo=0.0, lo_open=True),
        max_step=rt.number("max_step", None, lo=0.0, lo_open=True))
    rt.done()
    if run.record_from_turn >= run.turns:
        raise ValueError(f"scene.run.record_from_turn must be smaller than scene.run.turns "
                         f"({run.turns}), got {run.record_from_turn}")
    et = top.table("effects") or _Table({}, "scene.effects")
    gravity = et.get("gravity", True)
    if not isinstance(gravity, bool):
        raise ValueError(f"scene.effects.gravity must be true or false, got {gravity!r}")
    slider_force = et.number("slider_force", 0.0)
    crank_torque = et.number("crank_torque", 0.0)
    lt, ct, ft = et.table("lubrication"), et.table("contact"), et.table("friction")
    st = et.table("spring")
    spring = None
    if st is not None:
        spring = Spring(stiffness=st.number("stiffness", required=True, lo=0.0, lo_open=True),
                        damping=st.number("damping", 0.0, lo=0.0))
        st.done()
    lub = _lubrication(lt) if lt is not None else None
    contact = None
    if ct is not None:
        contact = Contact(
            young_modulus=ct.number("young_modulus", 207e9, lo=0.0, lo_open=True),
            poisson=ct.number("poisson", 0.3, lo=0.0, hi=0.5, hi_open=True),
            restitution=ct.number("restitution", 0.9, lo=0.0, hi=1.0),
            exponent=ct.number("exponent", 1.5, lo=1.0, hi=3.0))
        ct.done()
    friction = None
    if ft is not None:
        friction = Friction(coefficient=ft.number("coefficient", required=True, lo=0.0, hi=2.0),
                            v_reg=ft.number("v_reg", 1e-4, lo=0.0, lo_open=True))
        ft.done()
    et.done()
    if contact is not None and lub is not None and lub.options.get("roughness") is not None:
        raise ValueError("scene.effects.lubrication.roughness is the joint's contact (the "
                         "asperities of mixed lubrication): remove scene.effects.contact")
    if friction is not None and contact is None:
        raise ValueError("scene.effects.friction acts at the contact: add scene.effects.contact")
    if joint == "ideal":
        if bt is not None or lub or contact or spring:
            raise ValueError("scene.joint = 'ideal' has no clearance: remove scene.bearing and "
                             "the lubrication/contact/friction/spring effects")
        bearing = None
    else:
        if bt is None:
            raise ValueError(f"scene.bearing is required for joint = 'clearance'"
                             f"{top.typo_of('bearing')}")
        bearing = _bearing(bt)
    top.done()
    return Scene(name=name, mechanism=mech, bearing=bearing, joint=joint,
                 crank_angle=crank_angle, crank_speed=crank_speed, run=run, gravity=gravity,
                 slider_force=slider_force, crank_torque=crank_torque, lubrication=lub,
                 contact=contact, friction=friction, spring=spring, description=description)


def read_toml(path, what: str = "scene") -> dict:
    """The parsed TOML file; a missing or malformed file is one error naming ``what``."""
    p = Path(path)
    if not p.is_file():
        raise ValueError(f"{what} file not found: {p}")
    try:
        return tomllib.loads(p.read_text())
    except tomllib.TOMLDecodeError as err:
        raise ValueError(f"{what} file {p} is not valid TOML: {err}") from None


#: Scenes shipped with the toolkit (the seed's Section 3), found by name from anywhere.
SCENES = Path(__file__).resolve().parent / "scenes"


def shipped_scenes() -> list[str]:
    """Names of the shipped scenes (``load_scene(name)`` reads them)."""
    return sorted(p.stem for p in SCENES.glob("*.toml"))


def scene_path(path) -> Path:
    """The scene file ``path`` if it exists; else the shipped scene of that name, given as
    ``paper-short-fem``, ``paper-short-fem.toml`` or ``scenes/paper-short-fem.toml`` (the
    checkout's path, so the same command works outside it)."""
    return shipped_file(path, SCENES)


def shipped_file(path, folder: Path) -> Path:
    """``path`` if it is a file; else ``folder``'s TOML file of that name, given as NAME,
    NAME.toml or <folder name>/NAME.toml (the checkout's path); else ``path`` unchanged
    (the caller's check names it)."""
    p = Path(path)
    if p.is_file():
        return p
    shipped = folder / f"{p.stem}.toml"
    if (p.suffix in ("", ".toml") and p.parent in (Path("."), Path(folder.name))
            and shipped.is_file()):
        return shipped
    return p


def load_scene(path) -> Scene:
    """Read and validate a scene TOML file, or a shipped scene by name."""
    p = scene_path(path)
    if not p.is_file():
        raise ValueError(f"scene file not found: {path} (shipped scenes: "
                         f"{', '.join(shipped_scenes())})")
    return parse_scene(read_toml(p, "scene"), name=p.stem)
