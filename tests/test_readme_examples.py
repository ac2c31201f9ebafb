"""The README's Python snippets run as written (from the repository root), as scikit-fem
runs its documentation examples: a snippet that drifts from the API fails here."""
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SNIPPETS = re.findall(r"```python\n(.*?)```", (ROOT / "README.md").read_text(), re.S)


def _params():
    for i, code in enumerate(SNIPPETS):
        # a whole mechanism run takes ~15 s: part of the full suite only
        marks = [pytest.mark.slow] if "simulate(" in code else []
        yield pytest.param(code, id=f"snippet{i}", marks=marks)


def test_readme_has_snippets():
    assert len(SNIPPETS) >= 3


@pytest.mark.parametrize("code", list(_params()))
def test_readme_snippet_runs(code, monkeypatch):
    monkeypatch.chdir(ROOT)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    exec(compile(code, "README.md", "exec"), {"__name__": "readme"})
