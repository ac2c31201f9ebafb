"""Numbers of a film over every route and model, to compare two versions of the toolkit.

    python -m tools.film_fingerprint OUT.json           # in each version's checkout
    python -m tools.film_fingerprint --compare A.json B.json

A refactoring that must not change behaviour (the route table, the model modules) is
checked by the largest relative difference per case: 0 means bit-identical.
"""
import json
import sys

import numpy as np

from bearingfem import (Bearing, ElasticBush, Groove, JournalState, Lubricant, Roughness,
                        fvm_reynolds, solve_reynolds, equilibrium, coefficients)
from bearingfem.fields import FilmFields
from bearingfem.models import FILM_MODELS
def fingerprint() -> dict:
    """The numbers of every case (forces [N], peak pressure [Pa], torque, flows)."""
    B = Bearing(radius=0.01, length=0.01, clearance=20e-6, viscosity=0.0117)
    S = JournalState(eps=0.6, eps_dot=3.0, gamma=0.3, gamma_dot=1.0, omega=250.0)
    G = (Groove(angle=np.pi / 2, width=0.2, pressure=1e5),)
    OIL = Lubricant(viscosity=0.0117, barus=2e-8)
    EL = Lubricant(viscosity=0.0117, bulk_modulus=1e9)
    RING = ElasticBush(outer_radius=0.016, modulus=110e9, poisson=0.34, model="ring")
    R = Roughness(sigma=0.31e-6, contact_modulus=53.3e9, elastic_factor=1e-3)
    cases = {
     "rigid": ("reynolds", {}), "rigidP2g": ("gumbel", dict(element="P2")),
     "supply": ("reynolds", dict(supply_angle=0.2)), "psor": ("reynolds", dict(method="psor")),
     "grooved": ("reynolds", dict(grooves=G)), "groovedwhole": ("reynolds", dict(grooves=G, half=False)),
     "general": ("reynolds", dict(tilt=(0.0, 1e-4))), "fields": ("none", dict(fields=FilmFields(viscosity=2.0))),
     "ehd": ("reynolds", dict(lubricant=OIL)), "ehdbush": ("reynolds", dict(bush=RING)),
     "rough": ("reynolds", dict(roughness=R)), "roughg": ("reynolds", dict(grooves=G, roughness=R)),
     "jfo": ("jfo", dict(ambient_pressure=1e5)), "jfog": ("jfo", dict(grooves=G)),
     "jfogr": ("jfo", dict(grooves=G, roughness=R)), "jfot": ("jfo", dict(ambient_pressure=1e5, tilt=(0, 1e-4))),
     "jfoc": ("jfo", dict(ambient_pressure=1e5, lubricant=EL)),
     "ehdjfo": ("jfo", dict(ambient_pressure=1e5, bush=RING)),
    }
    out = {}
    for k, (cav, o) in cases.items():
        sol = solve_reynolds(B, S, 32, 4, cavitation=cav, **o)
        out[k] = [*sol.force_local, sol.pressure_max, sol.friction_torque, sol.side_leakage or 0.0,
                  *sol.asperity_force]
    for cav in ("reynolds", "jfo"):
        sol = fvm_reynolds(B, S, 32, 4, cav, **({"ambient_pressure": 1e5} if cav == "jfo" else {}))
        out["fv" + cav] = [*sol.force_local, sol.pressure_max]
    st = JournalState(eps=0.6, omega=250.0)
    for name in sorted(FILM_MODELS):
        if name == "fem-table":
            continue
        m = FILM_MODELS[name]
        out["model-" + name] = list(m.film_force(B, st, **({"n_theta": 24, "n_z": 4} if m.numeric else {})))
    eq = equilibrium(B, (0.0, -300.0), 250.0, "fem", n_theta=36, n_z=8, grooves=G, element="P2", cavitation="reynolds")
    kc = coefficients(B, eq.state, "fem", n_theta=36, n_z=8, grooves=G, element="P2", cavitation="reynolds")
    out["eq"] = [eq.eps, eq.attitude, *kc.K.ravel(), *kc.C.ravel()]
    return out


def compare(a: dict, b: dict) -> dict:
    """Largest relative difference per case."""
    return {k: float(np.max(np.abs(np.subtract(a[k], b[k]))
                            / np.maximum(np.abs(a[k]), 1e-300), initial=0.0)) for k in a}


if __name__ == "__main__":
    if sys.argv[1] == "--compare":
        diff = compare(*(json.load(open(p)) for p in sys.argv[2:4]))
        for k, d in diff.items():
            print(f"{k:28s} {d:.2e}")
    else:
        json.dump(fingerprint(), open(sys.argv[1], "w"))
