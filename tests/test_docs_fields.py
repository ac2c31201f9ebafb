"""docs/fields.md's Python snippets run as written (a snippet that drifts from the API
fails here)."""
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SNIPPETS = re.findall(r"```python\n(.*?)```", (ROOT / "docs" / "fields.md").read_text(), re.S)


def test_fields_doc_has_snippets():
    assert len(SNIPPETS) >= 2


@pytest.mark.parametrize("code", SNIPPETS, ids=[f"snippet{i}" for i in range(len(SNIPPETS))])
def test_fields_doc_snippet_runs(code, monkeypatch):
    monkeypatch.chdir(ROOT)
    exec(compile(code, "docs/fields.md", "exec"), {"__name__": "docs"})
