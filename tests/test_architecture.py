"""The package's import graph keeps the architecture (tools/imports.py reads it from the
source): no import circle, no import running upward through the layers, and no import
written inside a function in the library. Each test fails on the defect it names: an
import of bearingfem.routes added to bearingfem/fe/kernel.py (upward and, through the
routes' import of the kernel, a circle) fails the first two; a `from ..routes import`
written inside a function of bearingfem/fe fails the third."""
from tools.imports import _known, cycles, import_graph

#: The layers, bottom up: a module imports only from its own layer's group or below.
LAYERS = [
    # the film: geometry, state, scales, records, checks, the model contract
    {"errors", "version", "caches", "accuracy", "film", "bearing", "validation", "fields",
     "solution",
     "differentiate", "lubricant", "oil_range", "contact", "planar", "scales", "contract"},
    {"solvers", "closed", "elastic", "ehl"},        # solvers, closed forms, the bush
    {"fe", "fv"},                                   # discretisations
    {"transient", "transient_compressible"},        # the JFO film along a run
    {"ehd", "thermal"},                             # the elastic film, the energy equation
    {"routes"},                                     # one way into the film
    {"reynolds"},                                   # its public fronts
    {"models", "outputs"},                          # film models by name; outputs
    {"design"},                                     # the designer's numbers
    {"bearingfem", "__main__"},                     # the package; python -m bearingfem
    {"mechanism"},
    {"bearingfem_app"},
]
RANK = {g: i for i, layer in enumerate(LAYERS) for g in layer}


def _group(module: str) -> str:
    parts = module.split(".")
    return parts[1] if parts[0] == "bearingfem" and len(parts) > 1 else parts[0]


GRAPH = import_graph()


def test_every_module_has_a_layer():
    assert {_group(m) for m in GRAPH.edges} <= set(RANK)


def test_no_import_circle():
    """Also with the imports written inside functions counted."""
    edges = {m: set(s) for m, s in GRAPH.edges.items()}
    for m, _, target in GRAPH.inner:
        known = _known(target, set(edges))
        if known and known != m:
            edges[m].add(known)
    assert cycles(edges) == []


def test_no_import_runs_upward():
    upward = sorted((a, b) for a, targets in GRAPH.edges.items() for b in targets
                    if RANK[_group(b)] > RANK[_group(a)])
    assert upward == []


def test_the_library_imports_nothing_inside_functions():
    """The library (bearingfem) only; the command line defers its imports to keep its
    start fast, and mechanism's renders import pyvista's layer on demand."""
    inner = [(m, line, t) for m, line, t in GRAPH.inner if _group(m) in RANK
             and m.split(".")[0] == "bearingfem"]
    assert inner == []
