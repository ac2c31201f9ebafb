"""Wall time of one sweep on a local Dask cluster of 1 and of 2 workers (same run).

    python -m benchmarks.sweep_scaling                       # sweeps/mechanism-clearance.toml
    python -m benchmarks.sweep_scaling sweeps/capacity.toml --workers 1 2
"""
from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

from bearingfem_app.sweep import load_sweep, run_sweep

ROOT = Path(__file__).resolve().parent.parent


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sweep", nargs="?", default=str(ROOT / "sweeps/mechanism-clearance.toml"))
    ap.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    a = ap.parse_args(argv)
    sweep = load_sweep(a.sweep)
    rows = []
    for w in a.workers:
        with tempfile.TemporaryDirectory() as d:   # fresh: every case is computed
            r = run_sweep(sweep, d, workers=w, progress=False)
        rows.append((w, r.computed, r.wall_time))
    print("workers | cases | wall s | speed-up vs first")
    for w, n, t in rows:
        print(f"{w} | {n} | {t:.1f} | {rows[0][2] / t:.2f}")
    return rows


if __name__ == "__main__":
    main()
