"""The package's import graph: circles, imports written inside functions, private names
reached across modules.

    python -m tools.imports            # a table of counts, then each finding

Read from the source with :mod:`ast` (nothing is imported), over the packages a user
installs (bearingfem, mechanism, bearingfem_app). ``tests/test_architecture.py`` holds
the counts to what the architecture promises.
"""
from __future__ import annotations

import ast
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("bearingfem", "mechanism", "bearingfem_app")


@dataclass
class ImportGraph:
    """Edges module -> imported module (within PACKAGES), and what was found on the way."""

    edges: dict = field(default_factory=dict)         # module -> set of modules (top level)
    inner: list = field(default_factory=list)         # (module, line, imported) in a def
    private: list = field(default_factory=list)       # (module, line, name) _name across modules


def module_name(path: Path) -> str:
    rel = path.relative_to(ROOT).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _resolve(module: str, is_package: bool, node: ast.ImportFrom) -> str:
    if node.level == 0:
        return node.module or ""
    base = module.split(".")
    base = base if is_package else base[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def _known(name: str, modules: set) -> str | None:
    """The longest known module that ``name`` is or lies in (None outside PACKAGES)."""
    while name:
        if name in modules:
            return name
        name = name.rpartition(".")[0]
    return None


def import_graph(packages=PACKAGES) -> ImportGraph:
    files = [p for pkg in packages for p in sorted((ROOT / pkg).rglob("*.py"))]
    modules = {module_name(p): p for p in files}
    g = ImportGraph(edges={m: set() for m in modules})
    for mod, path in modules.items():
        tree = ast.parse(path.read_text())
        is_package = path.name == "__init__.py"
        inside = set()
        for fn in ast.walk(tree):
            if isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
                inside.update(id(n) for n in ast.walk(fn) if n is not fn)
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                target = _resolve(mod, is_package, node)
                names = [target + "." + a.name for a in node.names]
                hits = {_known(n, set(modules)) for n in names} | {_known(target, set(modules))}
                hits.discard(None)
                if not hits:
                    continue
                if id(node) in inside:
                    g.inner.append((mod, node.lineno, target))
                    continue
                # a name imported from a module (not a submodule) is an edge to it
                for n in names:
                    k = _known(n, set(modules))
                    if k is not None:
                        g.edges[mod].add(k)
                for a in node.names:
                    if a.name.startswith("_") and not a.name.startswith("__") \
                            and _known(target, set(modules)) != mod:
                        g.private.append((mod, node.lineno, f"{target}.{a.name}"))
            elif isinstance(node, ast.Import):
                for a in node.names:
                    k = _known(a.name, set(modules))
                    if k is None:
                        continue
                    if id(node) in inside:
                        g.inner.append((mod, node.lineno, a.name))
                    else:
                        g.edges[mod].add(k)
    for m in g.edges:
        g.edges[m].discard(m)
    return g


def cycles(edges: dict) -> list:
    """Strongly connected components of more than one module (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(edges.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    import sys
    sys.setrecursionlimit(10000)
    for v in sorted(edges):
        if v not in index:
            visit(v)
    return out


def main() -> None:
    g = import_graph()
    circ = cycles(g.edges)
    print("| what | count |\n|---|---|")
    print(f"| modules | {len(g.edges)} |")
    print(f"| import circles (modules in them) | {len(circ)} ({sum(map(len, circ))}) |")
    print(f"| imports inside functions | {len(g.inner)} |")
    print(f"| private names imported across modules | {len(g.private)} |")
    for c in circ:
        print("circle:", " ".join(c))
    for m, line, t in g.inner:
        print(f"inner: {m}:{line} {t}")
    for m, line, t in g.private:
        print(f"private: {m}:{line} {t}")


if __name__ == "__main__":
    main()
