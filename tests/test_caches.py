"""The library's caches: all registered in one place, all emptied by ``clear_caches``."""
import ast
import importlib
import pkgutil
from pathlib import Path

import numpy as np

import bearingfem
from bearingfem import Bearing, Groove, JournalState, clear_caches, fvm_reynolds, solve_reynolds
from bearingfem.caches import registered

PACKAGE = Path(bearingfem.__file__).parent
B = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
STATE = JournalState(0.6, omega=250.0)


def _warm():
    """A few solves that fill the mesh, operator, groove, FV and JFO caches."""
    return (solve_reynolds(B, STATE, 24, 4, "P1", "reynolds").force_local,
            solve_reynolds(B, STATE, 24, 4, "P1", "none",
                           grooves=[Groove(angle=0.5, width=0.2)]).force_local,
            fvm_reynolds(B, STATE, 24, 4, "reynolds").force_local,
            solve_reynolds(B, STATE, 24, 4, "P1", "jfo",
                           supply_angle=np.pi).force_local)


def test_clear_caches_empties_every_registered_cache_and_changes_no_result():
    clear_caches()
    cold = _warm()
    names = {m.__qualname__ for m in registered() if m.cache_info().currsize}
    assert {"film_mesh", "film_operator", "bearing_fixed_operator", "fvm_grid",
            "film_volumes"} <= names
    clear_caches()
    assert [m.__qualname__ for m in registered() if m.cache_info().currsize] == []
    assert np.array_equal(np.array(_warm()), np.array(cold))    # a cache holds, never changes


def _cache_sites(path: Path):
    """(line, what) of every functools cache written in ``path`` and of every module-level
    name holding a cache by its name (a dict kept between calls)."""
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, (ast.Name, ast.Attribute)):
            name = node.id if isinstance(node, ast.Name) else node.attr
            if name in ("lru_cache", "cache"):
                yield node.lineno, name
        elif isinstance(node, ast.ImportFrom) and node.module == "functools":
            yield from ((node.lineno, a.name) for a in node.names
                        if a.name in ("lru_cache", "cache"))
    for node in tree.body:
        targets = node.targets if isinstance(node, ast.Assign) else (
            [node.target] if isinstance(node, ast.AnnAssign) else [])
        yield from ((node.lineno, t.id) for t in targets
                    if isinstance(t, ast.Name) and "cache" in t.id.lower())


def test_every_cache_of_the_library_is_registered():
    """A cache written with functools (or a module-level cache dict) is not in the register,
    so clear_caches would miss it: every one must be declared with caches.cached."""
    unregistered = [f"{p.relative_to(PACKAGE.parent)}:{line} {what}"
                    for p in sorted(PACKAGE.rglob("*.py")) if p.name != "caches.py"
                    for line, what in _cache_sites(p)]
    assert unregistered == []


def test_every_cached_function_is_in_the_register():
    """Each ``@cached`` of the source is one registered cache once its module is imported."""
    for info in pkgutil.walk_packages([str(PACKAGE)], "bearingfem."):
        importlib.import_module(info.name)
    written = set()
    for p in PACKAGE.rglob("*.py"):
        module = ".".join(p.relative_to(PACKAGE.parent).with_suffix("").parts)
        for node in ast.walk(ast.parse(p.read_text())):
            if isinstance(node, ast.FunctionDef) and any(
                    isinstance(d, ast.Call) and getattr(d.func, "id", None) == "cached"
                    for d in node.decorator_list):
                written.add((module, node.name))
    assert {(m.__module__, m.__qualname__) for m in registered()} == written
    assert len(written) >= 20
