"""docs/extending.md runs as written (from the repository root): its Python blocks, in
order, in one namespace (each builds on the last); the model it registers is removed."""
import re
from pathlib import Path

from bearingfem.models import FILM_MODELS

ROOT = Path(__file__).resolve().parent.parent
BLOCKS = re.findall(r"```python\n(.*?)```", (ROOT / "docs" / "extending.md").read_text(), re.S)


def test_extending_walkthrough_runs(monkeypatch):
    assert len(BLOCKS) >= 4
    monkeypatch.chdir(ROOT)
    namespace = {"__name__": "extending"}
    try:
        for i, code in enumerate(BLOCKS):
            exec(compile(code, f"docs/extending.md block {i}", "exec"), namespace)
        assert "short-hot" in FILM_MODELS
    finally:
        FILM_MODELS.pop("short-hot", None)
