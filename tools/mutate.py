"""Mutation testing for bearingfem: do the tests notice a deliberate bug?

Each mutant changes one AST node of one module: + <-> -, * <-> /, < <-> <=, > <-> >=,
a numeric constant changed (n -> n + 1, x -> 2 x, 0.0 -> 1.0), a term dropped from a sum
(a + b -> a, a - b -> a), a return value negated. The whole source tree is copied once into a
temporary folder; every mutant is written into that copy only (the working tree is never
touched) and the module's tests run there, in one forked process per mutant (numpy, scipy,
scikit-fem and pytest imported once, before the fork), under a timeout:

    nice -n 19 python tools/mutate.py bearingfem/film.py bearingfem/closed/short_bearing.py \
        --timeout 120 --jsonl mutation.jsonl

A sample for a shared machine (a fixed seed draws the same mutants again):

    python tools/mutate.py bearingfem/fe/assembly.py --sample 30 --seed 23 --jsonl m.jsonl
    python tools/mutate.py bearingfem/fe/assembly.py --survivors m.jsonl   # after new tests

A mutant is *killed* when the tests fail, *survives* when they pass, *timeout* when they
run past the limit. Tests for a module come from TESTS below or ``--tests`` (pytest
arguments, e.g. "tests/test_design.py -k lund").
"""
from __future__ import annotations

import argparse
import ast
import copy
import json
import os
import shlex
import shutil
import signal
import sys
import tempfile
import time
from dataclasses import asdict, dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# before numpy loads (it is preloaded here and inherited by every forked test run)
os.environ.update(OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", MPLBACKEND="Agg",
                  PYTHONDONTWRITEBYTECODE="1")
if sys.path and Path(sys.path[0]).resolve() == ROOT / "tools":
    sys.path.pop(0)                      # the project is imported from the copy only
sys.path = [p for p in sys.path if Path(p or ".").resolve() != ROOT]
os.environ.pop("PYTHONPATH", None)

#: leaves out the two long JFO tests (a closed-form squeeze front, an iteration benchmark)
QUICK_JFO = " -k 'not squeeze_film_front and not benchmark_smoke and not fraction_is_exported'"
JFO_FILM = ("tests/test_independent_jfo.py tests/test_jfo_solver.py tests/test_jfo.py "
            "tests/test_mutants_jfo.py" + QUICK_JFO)
#: module -> pytest arguments: tests that exercise the module and run in well under a minute
TESTS = {
    "bearingfem/film.py":
        "tests/test_closed_form.py tests/test_fe_vs_fvm.py tests/test_mutants_film.py",
    "bearingfem/closed/short_bearing.py":
        "tests/test_closed_form.py tests/test_mutants_short_bearing.py",
    "bearingfem/closed/long_bearing.py":
        "tests/test_closed_form.py tests/test_mutants_long_bearing.py",
    "bearingfem/closed/squeeze_film.py": "tests/test_jfo.py -k squeeze",
    "bearingfem/design/stability.py":
        "tests/test_design.py tests/test_mutants_stability.py "
        "-k 'lund or threshold or friswell or orbit or mutants_stability'",
    "bearingfem/contact/asperity.py": "tests/test_asperity.py",
    "bearingfem/contact/gaussian.py": "tests/test_asperity.py",
    # FE / FV / JFO films and their solvers: a few seconds of the most direct tests each
    # (a surviving mutant costs the whole selection; the machine is shared)
    "bearingfem/scales.py":
        "tests/test_fe_vs_fvm.py tests/test_independent_jfo.py tests/test_mutants_scales.py",
    "bearingfem/fields.py":
        "tests/test_manufactured_fields.py tests/test_misalignment.py "
        "tests/test_mutants_fields.py",
    "bearingfem/fe/assembly.py":
        "tests/test_manufactured.py tests/test_fe_vs_fvm.py tests/test_cavitation.py "
        "tests/test_mutants_assembly.py",
    "bearingfem/fe/kernel.py":
        "tests/test_manufactured.py tests/test_fe_vs_fvm.py tests/test_cavitation.py "
        "tests/test_mutants_reynolds.py",
    "bearingfem/fe/general.py":
        "tests/test_manufactured_fields.py tests/test_misalignment.py "
        "tests/test_mutants_general.py",
    "bearingfem/fe/sensitivity.py":
        "tests/test_tilt_coefficients.py tests/test_independent_coefficients.py "
        "tests/test_mutants_sensitivity.py",
    "bearingfem/fe/jfo.py": JFO_FILM,
    "bearingfem/fe/jfo_steady.py": JFO_FILM,
    "bearingfem/fe/jfo_balance.py":
        "tests/test_independent_jfo.py tests/test_jfo.py tests/test_mutants_jfo.py" + QUICK_JFO,
    "bearingfem/fe/volumes.py":
        "tests/test_jfo_transient.py tests/test_independent_jfo.py tests/test_mutants_volumes.py "
        "-k 'not load_reversing'",
    "bearingfem/fe/planar.py":
        "tests/test_jfo.py tests/test_jfo_convergence.py tests/test_mutants_planar.py "
        "-k 'planar or mutants'",
    "bearingfem/fv/fvm.py":
        "tests/test_fe_vs_fvm.py tests/test_manufactured.py tests/test_jfo.py "
        "tests/test_mutants_fvm.py -k 'not test_jfo or fe_and_fv or mutants'",
    "bearingfem/solvers/cavitation.py":
        "tests/test_cavitation.py tests/test_blocksolve.py tests/test_mutants_cavitation.py",
    "bearingfem/solvers/jfo.py":
        "tests/test_jfo_solver.py tests/test_independent_jfo.py tests/test_jfo.py "
        "tests/test_mutants_solvers_jfo.py" + QUICK_JFO,
    "bearingfem/solvers/linsolve.py":
        "tests/test_linsolve.py tests/test_blocksolve.py tests/test_mutants_linsolve.py",
    "bearingfem/solvers/blocksolve.py":
        "tests/test_blocksolve.py tests/test_mutants_blocksolve.py",
}
SWAP_BIN = {ast.Add: ast.Sub, ast.Sub: ast.Add, ast.Mult: ast.Div, ast.Div: ast.Mult}
SWAP_CMP = {ast.Lt: ast.LtE, ast.LtE: ast.Lt, ast.Gt: ast.GtE, ast.GtE: ast.Gt}
SYMBOL = {ast.Add: "+", ast.Sub: "-", ast.Mult: "*", ast.Div: "/", ast.Lt: "<", ast.LtE: "<=",
          ast.Gt: ">", ast.GtE: ">="}
IGNORE = shutil.ignore_patterns(".git", ".venv", "__pycache__", "*.pyc", ".pytest_cache",
                                "*.egg-info", "out", "build", "dist", ".mypy_cache")


@dataclass(frozen=True)
class Mutant:
    line: int
    col: int
    kind: str
    description: str


@dataclass
class Outcome:
    module: str
    line: int
    description: str
    status: str          # "killed", "survived", "timeout"
    seconds: float
    col: int = 0         # column of the mutated node (several on one line)
    node: int = -1       # its index in ast.walk order (nested operators share a column)


def _docstring_ids(tree) -> set:
    """ids of the constant nodes that are docstrings (never mutated)."""
    ids = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
                ids.add(id(body[0].value))
    return ids


def _annotation_ids(tree) -> set:
    ids = set()
    for node in ast.walk(tree):
        anns = []
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            anns = [a.annotation for a in node.args.args + node.args.kwonlyargs] + [node.returns]
        elif isinstance(node, ast.AnnAssign):
            anns = [node.annotation]
        for a in anns:
            if a is not None:
                ids.update(id(n) for n in ast.walk(a))
    return ids


def _sites(tree):
    """(node index in ast.walk order, Mutant) for every mutation of the tree."""
    skip = _docstring_ids(tree) | _annotation_ids(tree)
    out = []
    for i, node in enumerate(ast.walk(tree)):
        if id(node) in skip or not hasattr(node, "lineno"):
            continue
        where = (node.lineno, node.col_offset)
        if isinstance(node, ast.BinOp) and type(node.op) in SWAP_BIN and not _is_text(node):
            a, b = SYMBOL[type(node.op)], SYMBOL[SWAP_BIN[type(node.op)]]
            out.append((i, Mutant(*where, "swap", f"'{a}' -> '{b}'")))
            if isinstance(node.op, (ast.Add, ast.Sub)):
                out.append((i, Mutant(*where, "drop", f"'a {a} b' -> 'a' (term dropped)")))
        elif isinstance(node, ast.Compare) and len(node.ops) == 1 and type(node.ops[0]) in SWAP_CMP:
            a, b = SYMBOL[type(node.ops[0])], SYMBOL[SWAP_CMP[type(node.ops[0])]]
            out.append((i, Mutant(*where, "compare", f"'{a}' -> '{b}'")))
        elif (isinstance(node, ast.Constant) and type(node.value) in (int, float)):
            new = _new_constant(node.value)
            out.append((i, Mutant(*where, "constant", f"{node.value!r} -> {new!r}")))
        elif isinstance(node, ast.Return) and node.value is not None and not (
                isinstance(node.value, ast.Constant) and node.value.value is None):
            out.append((i, Mutant(*where, "return", "return x -> return -x")))
    return out


def _is_text(node) -> bool:
    """String concatenation (messages): not physics, not mutated."""
    return any(isinstance(n, ast.JoinedStr) or isinstance(n, ast.Constant)
               and isinstance(n.value, str) for n in (node.left, node.right))


def _new_constant(v):
    if isinstance(v, bool):
        return v
    if isinstance(v, int):
        return v + 1
    return 1.0 if v == 0.0 else 2.0 * v


def _apply(node, kind: str):
    """The mutated node (``node`` changed in place, or what replaces it)."""
    if kind == "swap":
        node.op = SWAP_BIN[type(node.op)]()
    elif kind == "drop":
        return node.left
    elif kind == "compare":
        node.ops = [SWAP_CMP[type(node.ops[0])]()]
    elif kind == "constant":
        node.value = _new_constant(node.value)
    else:                                                            # return
        node.value = ast.UnaryOp(op=ast.USub(), operand=node.value)
    return node


def mutated_source(source: str, index: int, kind: str) -> str:
    tree = ast.parse(source)
    target = list(ast.walk(tree))[index]
    tree = copy.deepcopy(tree)
    node = list(ast.walk(tree))[index]
    assert type(node) is type(target)
    for parent in ast.walk(tree):
        for field, value in ast.iter_fields(parent):
            if isinstance(value, list):
                for k, item in enumerate(value):
                    if item is node:
                        value[k] = _apply(node, kind)
                        return ast.unparse(ast.fix_missing_locations(tree))
            elif value is node:
                setattr(parent, field, _apply(node, kind))
                return ast.unparse(ast.fix_missing_locations(tree))
    raise RuntimeError("mutation site not found")


def preload():
    """Import the heavy third-party packages once, in this process, so every forked test
    run starts from them (about 40 % of a short test file's CPU time is imports). The
    project itself is never imported here: each mutant's child imports it afresh."""
    for name in ("numpy", "scipy.sparse", "scipy.sparse.linalg", "scipy.integrate",
                 "scipy.optimize", "scipy.special", "scipy.interpolate", "scipy.linalg",
                 "skfem", "matplotlib", "matplotlib.pyplot", "pytest", "hypothesis"):
        try:
            __import__(name)
        except ImportError:
            pass


def _child(tree_dir: Path, test_args: str) -> int:
    import pytest
    sys.dont_write_bytecode = True
    os.chdir(tree_dir)
    sys.path.insert(0, str(tree_dir))
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    os.dup2(devnull, 2)
    return int(pytest.main(["-x", "-q", "-p", "no:cacheprovider", "-m", "not slow",
                            *shlex.split(test_args)]))


def run_tests(tree_dir: Path, test_args: str, timeout: float) -> tuple[str, float]:
    """Run the tests in a forked child of this (preloaded) process, under ``timeout``."""
    t0 = time.perf_counter()
    pid = os.fork()
    if pid == 0:                                   # the child: never returns
        code = 1
        try:
            code = _child(tree_dir, test_args)
        finally:
            os._exit(code)
    while True:
        done, status = os.waitpid(pid, os.WNOHANG)
        if done:
            code = os.waitstatus_to_exitcode(status)
            return ("survived" if code == 0 else "killed"), time.perf_counter() - t0
        if time.perf_counter() - t0 > timeout:
            os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
            return "timeout", time.perf_counter() - t0
        time.sleep(0.05)


def _existing(tree_dir: Path, test_args: str, first_pass: bool = False) -> str:
    """The pytest arguments without test files that do not exist (yet): a module's
    ``test_mutants_*`` file is written after its first pass (and left out of a
    ``first_pass``, which scores the older tests)."""
    def dropped(a):
        return a.startswith("tests/") and a.endswith(".py") and (
            not (tree_dir / a).exists() or first_pass and a.startswith("tests/test_mutants_"))
    return shlex.join(a for a in shlex.split(test_args) if not dropped(a))


def mutate_module(tree_dir: Path, module: str, test_args: str, timeout: float,
                  only_lines=None, every: int = 1, log=print, record=None,
                  only=None, sample: int | None = None, seed: int = 0,
                  first_pass: bool = False) -> list[Outcome]:
    path = tree_dir / module
    original = path.read_text()
    test_args = _existing(tree_dir, test_args, first_pass)
    status, base = run_tests(tree_dir, test_args, timeout)
    if status != "survived":
        raise RuntimeError(f"{module}: the unmutated tests do not pass ({status})")
    log(f"{module}: tests pass unmutated in {base:.1f} s ({test_args})")
    sites = _sites(ast.parse(original))
    if only_lines:
        sites = [(i, m) for i, m in sites if m.line in only_lines]
    if only is not None:       # (line, col, description): a previous run's survivors
        sites = [(i, m) for i, m in sites if (m.line, m.col, m.description) in only
                 and ((m.line, m.col, m.description, i) in only
                      or (m.line, m.col, m.description, -1) in only)]
    sites = sites[::every]     # an evenly spread sample when time is short
    if sample is not None and sample < len(sites):
        # a seeded random sample: the same seed draws the same mutants in a later run
        import random
        picked = sorted(random.Random(seed).sample(range(len(sites)), sample))
        sites = [sites[k] for k in picked]
    outcomes = []
    try:
        for n, (index, m) in enumerate(sites, 1):
            path.write_text(mutated_source(original, index, m.kind))
            status, secs = run_tests(tree_dir, test_args, timeout)
            outcomes.append(Outcome(module, m.line, m.description, status, round(secs, 1),
                                    m.col, index))
            if record is not None:
                record(outcomes[-1])
            log(f"  [{n}/{len(sites)}] {module}:{m.line}:{m.col} {m.description}: {status} "
                f"({secs:.1f} s)")
    finally:
        path.write_text(original)
    return outcomes


def summary(outcomes: list[Outcome]) -> str:
    lines = ["| module | mutants | killed | survived | timeout | score |",
             "|---|---|---|---|---|---|"]
    for module in dict.fromkeys(o.module for o in outcomes):
        mine = [o for o in outcomes if o.module == module]
        k = sum(o.status == "killed" for o in mine)
        s = sum(o.status == "survived" for o in mine)
        t = sum(o.status == "timeout" for o in mine)
        lines.append(f"| {module} | {len(mine)} | {k} | {s} | {t} | "
                     f"{100 * (k + t) / max(len(mine), 1):.0f} % |")
    lines.append("")
    lines += [f"- {o.module}:{o.line}:{o.col} {o.description}" for o in outcomes
              if o.status == "survived"]
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("modules", nargs="+", help="module paths relative to the project root")
    ap.add_argument("--tests", help="pytest arguments for every module (default: TESTS)")
    ap.add_argument("--timeout", type=float, default=180.0, help="per mutant [s]")
    ap.add_argument("--lines", help="only mutate these lines, e.g. 12,40-55")
    ap.add_argument("--every", type=int, default=1, help="mutate every k-th site only")
    ap.add_argument("--sample", type=int, help="a random sample of this many mutants per "
                    "module (after --lines/--every)")
    ap.add_argument("--seed", type=int, default=0, help="seed of --sample")
    ap.add_argument("--first-pass", action="store_true", help="leave out the tests/"
                    "test_mutants_* files (the score of the tests written before)")
    ap.add_argument("--nice", type=int, default=10, help="niceness added to this process")
    ap.add_argument("--survivors", help="only the mutants that survived in this JSONL file "
                    "(a previous --jsonl): check that new tests kill them")
    ap.add_argument("--jsonl", help="append every outcome, as it comes, to this file")
    args = ap.parse_args(argv)
    only = None
    if args.lines:
        only = set()
        for part in args.lines.split(","):
            lo, _, hi = part.partition("-")
            only.update(range(int(lo), int(hi or lo) + 1))
    def record(o: Outcome):
        if args.jsonl:
            with open(args.jsonl, "a") as f:
                f.write(json.dumps(asdict(o)) + "\n")

    os.nice(args.nice)
    preload()
    outcomes = []
    with tempfile.TemporaryDirectory(prefix="bearingfem-mutants-") as tmp:
        tree_dir = Path(tmp) / "tree"
        shutil.copytree(ROOT, tree_dir, ignore=IGNORE)
        for module in args.modules:
            test_args = args.tests or TESTS.get(module)
            if test_args is None:
                raise SystemExit(f"no tests known for {module}: pass --tests")
            survivors = None
            if args.survivors:
                rows = [json.loads(r) for r in open(args.survivors) if r.strip()]
                mine = [r for r in rows if r["module"] == module and r["status"] == "survived"]
                survivors = {(r["line"], r.get("col", 0), r["description"]) for r in mine}
                # with the node index (recorded since) only that node; without, all nodes
                survivors |= {(r["line"], r.get("col", 0), r["description"], r.get("node", -1))
                              for r in mine}
            outcomes += mutate_module(tree_dir, module, test_args, args.timeout, only,
                                      args.every, log=lambda s: print(s, flush=True),
                                      record=record, only=survivors,
                                      sample=None if survivors else args.sample,
                                      seed=args.seed, first_pass=args.first_pass)
    print(summary(outcomes))


if __name__ == "__main__":
    main()
