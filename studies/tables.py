"""Rows of results (dicts) to a CSV file: the columns are every key seen, in first-seen order."""
from __future__ import annotations

import csv


def write_csv(rows, path) -> None:
    if not rows:
        return
    keys = list(dict.fromkeys(k for r in rows for k in r))
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
