"""The documentation runs as written: README.md and docs/*.md.

- Every ```python block runs (a page's blocks in order in one namespace, cwd = the repository root,
  MPLBACKEND=Agg; in-process, so the imports are paid once and the file stays within ~30 s),
  as scikit-fem runs its documentation examples: a block that drifts from the API fails here.
  A block preceded by ``<!-- skip-test: why -->`` is not run (long runs only, with the reason).
- Every ``bearingfem COMMAND ...`` in a ```bash block is a subcommand of the real parser
  (bearingfem_app/cli.py) and its options parse there, every ``python -m studies.X`` / ``benchmarks.X`` a module with a
  ``__main__`` entry, every ``make TARGET`` a Makefile target.
- Every relative link and image points at an existing file (and a ``#fragment`` at a heading
  of it), except the pages still being written on other branches (COMING, below).

Checked against broken documentation: a snippet calling ``coefficients(..., frame="lod")``
fails ``test_python_blocks_run``; ``bearingfem simulat`` and ``python -m studies.papr``
fail ``test_shell_commands_exist``; a link to ``docs/verificaton.md`` or to
``#film-and-closed-form`` fails ``test_relative_links_resolve``.
"""
from __future__ import annotations

import contextlib
import io
import re
import shlex
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]

#: Pages linked from the README that other branches add: a link to one of them may point
#: nowhere until it lands. Remove each name when its page is merged (an existing page's links
#: are checked like any other's even while it is listed).
COMING: set = set()

#: README.md stays a newcomer's page; the detail lives in docs/.
README_MAX_CHARS = 11_000

FENCE = re.compile(r"^```(\w*)[^\n]*\n(.*?)^```", re.M | re.S)
SKIP = re.compile(r"<!--\s*skip-test\b(.*?)-->\s*$", re.S)


def _blocks(lang):
    """(page, line, code, skip reason or None) of every fenced block in ``lang``."""
    out = []
    for page in PAGES:
        text = page.read_text()
        for m in FENCE.finditer(text):
            if m.group(1) != lang:
                continue
            line = text.count("\n", 0, m.start()) + 1
            before = SKIP.search(text[:m.start()].rstrip() + "\n")
            reason = before.group(1).strip(" :") if before else None
            out.append((page.relative_to(ROOT).as_posix(), line, m.group(2), reason))
    return out


def _python_pages():
    """One param per page with python blocks: its (line, code, skip reason) in order."""
    pages = {}
    for page, line, code, reason in _blocks("python"):
        pages.setdefault(page, []).append((line, code, reason))
    return [pytest.param(blocks, id=page) for page, blocks in pages.items()]


def test_readme_is_short():
    n = len((ROOT / "README.md").read_text())
    assert n <= README_MAX_CHARS, f"README.md has {n} characters (at most {README_MAX_CHARS})"


def test_skip_markers_give_a_reason():
    """A skipped block says why (a long run), so a skip is never a silent way out."""
    for page, line, _, reason in _blocks("python"):
        assert reason is None or len(reason) > 10, f"{page}:{line}: skip-test without a reason"


@pytest.mark.parametrize("blocks", _python_pages())
def test_python_blocks_run(blocks, monkeypatch, tmp_path):
    """A page's blocks in order in one namespace, as a reader runs a walk-through (a later
    block may use an earlier one's names), from the repository root; skip-test blocks are
    left out."""
    monkeypatch.chdir(ROOT)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.setenv("BEARINGFEM_CACHE", str(tmp_path / "cache"))
    from bearingfem.models import FILM_MODELS
    registered = dict(FILM_MODELS)   # a walk-through may register a model: not for later tests
    namespace = {"__name__": "__docs__"}
    try:
        _run_blocks(blocks, namespace)
    finally:
        FILM_MODELS.clear()
        FILM_MODELS.update(registered)


def _run_blocks(blocks, namespace):
    for line, code, reason in blocks:
        if reason is not None:
            continue
        out = io.StringIO()
        try:
            with contextlib.redirect_stdout(out):
                exec(compile(code, f"<docs block at line {line}>", "exec"), namespace)
        except Exception as exc:
            raise AssertionError(f"the block at line {line} fails: {exc!r}") from exc
        _check_claims(line, code, out.getvalue())


#: a print line whose comment starts with the numbers it prints: ``print(x, y)  # 0.918, 0.624``
CLAIMED = re.compile(r"^\s*print\(.*#\s*((?:[-+]?\d[\d.]*(?:e[-+]?\d+)?[ \t,;/]*)+)", re.M)
NUMBER = re.compile(r"[-+]?\d+(?:\.\d*)?(?:e[-+]?\d+)?")


def _check_claims(line, code, printed):
    """Each number a print line's comment says it prints is printed by the block, to the
    digits the comment gives (a claimed 4.320 is any printed value within 5e-4 of it), so a
    walk-through's quoted output cannot drift from what the code now prints."""
    values = [float(v) for v in NUMBER.findall(printed)]
    for m in CLAIMED.finditer(code):
        for claim in NUMBER.findall(m.group(1)):
            mantissa = claim.lower().split("e")[0]
            decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
            scale = 10.0 ** int(claim.lower().split("e")[1]) if "e" in claim.lower() else 1.0
            half = 0.5 * 10.0 ** -decimals * scale
            assert any(abs(v - float(claim)) <= half * (1 + 1e-9) for v in values), (
                f"the block at line {line} says it prints {claim}; it printed: "
                f"{printed.strip()[:300]}")


def _subcommands():
    import argparse
    from bearingfem_app.cli import build_parser
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return set(sub.choices)


def _parse_error(args):
    """The parser's complaint about ``bearingfem ARGS`` (options, arity), or None."""
    from bearingfem_app.cli import build_parser
    err = io.StringIO()
    try:
        with contextlib.redirect_stderr(err):
            build_parser().parse_args(args)
    except SystemExit:
        return err.getvalue().strip().splitlines()[-1]
    return None


def _make_targets():
    text = (ROOT / "Makefile").read_text()
    return set(re.findall(r"^([A-Za-z][\w-]*)\s*:(?!=)", text, re.M))


def _commands(code):
    """Each shell command of a block as a token list (continuation lines joined, comments cut)."""
    code = code.replace("\\\n", " ")
    for raw in code.splitlines():
        raw = raw.split(" #")[0].strip()
        if raw and not raw.startswith("#"):
            yield shlex.split(raw.replace("[", "").replace("]", ""))


def _shell_blocks():
    return [b for lang in ("bash", "sh", "shell") for b in _blocks(lang)]


def test_there_is_something_to_check():
    assert len(_blocks("python")) >= 3 and len(_shell_blocks()) >= 2


def test_shell_commands_exist():
    commands, targets, bad = _subcommands(), _make_targets(), []
    for page, line, code, _ in _shell_blocks():
        for tokens in _commands(code):
            where = f"{page}:{line}: {' '.join(tokens)}"
            for i, tok in enumerate(tokens):
                nxt = tokens[i + 1] if i + 1 < len(tokens) else ""
                if Path(tok).name == "bearingfem" and nxt and not nxt.startswith("-"):
                    if nxt not in commands:
                        bad.append(f"{where}: no command {nxt!r} (have {sorted(commands)})")
                    elif (err := _parse_error(tokens[i + 1:])) is not None:
                        bad.append(f"{where}: {err}")
                if tok == "-m" and nxt.split(".")[0] in ("studies", "benchmarks"):
                    path = ROOT / (nxt.replace(".", "/") + ".py")
                    if not path.is_file():
                        bad.append(f"{where}: no module {nxt}")
                    elif 'if __name__ == "__main__"' not in path.read_text():
                        bad.append(f"{where}: {nxt} cannot be run with -m")
                if tok == "make" and i == 0:
                    bad += [f"{where}: no make target {t!r}" for t in tokens[1:]
                            if not t.startswith("-") and "=" not in t and t not in targets]
    assert not bad, "\n".join(bad)


LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")


def _slug(heading):
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens."""
    s = re.sub(r"[`*_]", "", heading.strip().lower())
    s = re.sub(r"[^\w\- ]", "", s)
    return s.replace(" ", "-")


def _anchors(page):
    text = FENCE.sub("", page.read_text())
    return {_slug(h) for h in re.findall(r"^#{1,6}\s+(.*)$", text, re.M)}


def test_relative_links_resolve():
    bad = []
    for page in PAGES:
        text = FENCE.sub("", page.read_text())   # code is not a link
        for target in LINK.findall(text):
            if re.match(r"[a-z]+:", target):      # http:, https:, mailto:
                continue
            path, _, frag = target.partition("#")
            dest = (page.parent / path).resolve() if path else page
            rel = dest.relative_to(ROOT).as_posix() if dest.is_relative_to(ROOT) else str(dest)
            if rel in COMING and not dest.exists():
                continue
            if not dest.exists():
                bad.append(f"{page.relative_to(ROOT)}: {target} (no {rel})")
            elif frag and dest.suffix == ".md" and frag not in _anchors(dest):
                bad.append(f"{page.relative_to(ROOT)}: {target} (no heading #{frag})")
    assert not bad, "broken links:\n" + "\n".join(bad)


def test_every_film_model_is_named_where_the_models_are_listed():
    """docs/usage.md's 'Lubrication models' names every registered film model (it listed
    eight of the eleven: no fem-ehd, fem-jfo-compressible, fem-thd)."""
    from bearingfem.models import FILM_MODELS
    text = (ROOT / "docs" / "usage.md").read_text()
    section = text.split("## Lubrication models", 1)[1].split("\n## ", 1)[0]
    missing = [m for m in FILM_MODELS if f"`{m}`" not in section]
    assert not missing, f"docs/usage.md's Lubrication models does not name {missing}"
