"""Rows of results (dicts) to CSV: the one table writer of the toolkit."""
from __future__ import annotations

import csv

__all__ = ["write_csv"]


def write_csv(rows, path, columns=None) -> None:
    """Write ``rows`` (dicts) to ``path``; the columns are ``columns`` or every key seen, in
    first-seen order (a row without a key leaves its cell empty). No rows: no file."""
    if not rows:
        return
    keys = list(columns) if columns is not None else list(dict.fromkeys(k for r in rows for k in r))
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
