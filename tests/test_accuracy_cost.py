"""Smoke + sense checks of the accuracy-cost study's static part (small meshes)."""
import numpy as np

from studies.accuracy_cost import cost_exponents, run_static


def test_static_rows_converge_and_the_table_carries_its_mesh_accuracy():
    rows = run_static(quick=True)
    p1 = sorted((r["dofs"], r["force_err"]) for r in rows if r["model"] == "FE P1")
    errs = [e for _, e in p1]
    # P1 force converges at second order: error / 4 per mesh doubling (observed 3.6-3.9)
    assert all(a / b > 3.0 for a, b in zip(errs, errs[1:]))
    by_mesh = {r["mesh"]: r["force_err"] for r in rows if r["model"] == "FE P1"}
    for r in rows:
        if r["model"] == "FE table" and r["mesh"] in by_mesh:
            assert abs(r["force_err"] - by_mesh[r["mesh"]]) < 0.1 * by_mesh[r["mesh"]]
    k = cost_exponents(rows)
    assert set(k) == {"FE P1", "FE P2", "FVM"} and all(np.isfinite(list(k.values())))
