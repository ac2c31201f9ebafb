"""The "fem-table" model against direct FE solves of the same film.

Interpolation error on random states, eps <= 0.95, measured with the default grid
(40 eps x 96 phi nodes, FE 96x16 P1): Gumbel L/D 0.2 0.33 %, L/D 2 0.20 %, Reynolds L/D 1
0.34 % (see studies/accuracy_cost.py). The error does not fall further with a finer table:
it is the direct FE force's own roughness (the cavitation front moves by whole elements).
"""
import numpy as np
import pytest

from bearingfem import JournalState
from bearingfem.force_table import build_force_table, cache_dir, force_table, table_force
from bearingfem.reynolds import fe_force
from conftest import table1_bearing

MESH = dict(n_theta=96, n_z=16, element="P1")


def _random_states(n, seed=1, eps_max=0.95):
    rng = np.random.default_rng(seed)
    return [JournalState(eps_max * rng.random(), 50 * rng.normal(), 0.0, 50 * rng.normal(),
                         250.0) for _ in range(n)]


def _errors(bearing, cavitation, states):
    out = []
    for s in states:
        ref = np.array(fe_force(bearing, s, cavitation=cavitation, **MESH)[0])
        got = np.array(table_force(bearing, s, cavitation=cavitation, **MESH))
        out.append(np.linalg.norm(got - ref) / np.linalg.norm(ref))
    return np.array(out)


def test_nodes_reproduce_direct_solves():
    """At a grid node the table is the FE force of the state with that (eps, phi), built
    through JournalState and the load - a second path through the code."""
    b = table1_bearing(0.5)
    t = force_table(b.slenderness, 48, 8, "P1", "gumbel", 12, 32)
    for i, j in [(0, 3), (5, 17), (11, 30)]:
        eps, phi = t.eps[i], t.phi[j]
        w = 2.0 * np.sin(phi) / eps if eps > 0 else 0.0
        s = JournalState(eps, np.cos(phi), 0.0, 0.0, w)
        if eps == 0.0:   # no wedge at eps = 0: only the squeeze part of the direction
            s = JournalState(0.0, np.cos(phi), 0.0, 0.0, 0.0)
            g = np.array(fe_force(b, s, 48, 8)[0]) / b.force_scale
            assert np.allclose(np.array(t.evaluate(0.0, 0.0 if np.cos(phi) > 0 else np.pi))
                               * abs(np.cos(phi)), g, rtol=1e-9, atol=1e-12)
            continue
        ref = np.array(fe_force(b, s, 48, 8)[0]) / b.force_scale
        assert np.allclose(t.evaluate(eps, phi), ref, rtol=1e-9, atol=1e-9 * abs(ref).max())


@pytest.mark.parametrize("ld, cavitation, tol", [(0.2, "gumbel", 5e-3), (2.0, "gumbel", 5e-3),
                                                 (1.0, "reynolds", 5e-3)])
def test_interpolation_error_on_random_states(ld, cavitation, tol):
    err = _errors(table1_bearing(ld), cavitation, _random_states(60 if cavitation == "reynolds"
                                                                 else 150))
    assert err.max() < tol
    # and the table is not trivially exact: the test would see a wrong interpolation
    assert err.max() > 1e-6


def test_coarser_tables_converge_toward_the_fe_force():
    b = table1_bearing(0.2)
    states = _random_states(80, seed=2)
    errs = []
    for n_eps, n_phi in [(10, 24), (20, 48), (40, 96)]:
        e = []
        for s in states:
            ref = np.array(fe_force(b, s, **MESH)[0])
            got = np.array(table_force(b, s, n_eps=n_eps, n_phi=n_phi, **MESH))
            e.append(np.linalg.norm(got - ref) / np.linalg.norm(ref))
        errs.append(max(e))
    assert errs[0] > errs[1] > errs[2]


def test_limits_are_finite():
    b = table1_bearing(0.5)
    assert table_force(b, JournalState(0.3, 0.0, 0.0, 0.0, 0.0)) == (0.0, 0.0)
    f0 = table_force(b, JournalState(0.0, 1.0, 0.0, 0.0, 250.0))
    assert np.all(np.isfinite(f0)) and abs(f0[0]) > 0
    f = [np.hypot(*table_force(b, JournalState(e, 0.0, 0.0, 0.0, 250.0)))
         for e in (0.9, 0.99, 0.995, 0.999)]
    assert np.all(np.isfinite(f)) and np.all(np.diff(f) > 0)   # keeps growing past the table


def test_disk_cache_reuses_and_rebuilds_when_stale(monkeypatch, tmp_path):
    import bearingfem.force_table as ft
    monkeypatch.setenv("BEARINGFEM_CACHE", str(tmp_path))
    args = (0.37, 24, 4, "P1", "gumbel", 8, 16, 0.9)
    ft.force_table.cache_clear()
    t1 = force_table(*args)
    files = list(cache_dir().glob("force-table-*.npz"))
    assert len(files) == 1
    ft.force_table.cache_clear()
    monkeypatch.setattr(ft, "build_force_table", lambda *a: pytest.fail("rebuilt"))
    t2 = force_table(*args)
    assert np.array_equal(t1.g_r, t2.g_r) and t2.key == t1.key
    # another toolkit version makes the file stale: it is rebuilt, not trusted
    monkeypatch.setattr(ft, "build_force_table", build_force_table)
    monkeypatch.setattr("bearingfem.__version__", "0.0.0-other")
    ft.force_table.cache_clear()
    t3 = force_table(*args)
    assert t3.key["version"] == "0.0.0-other"
    ft.force_table.cache_clear()


@pytest.mark.parametrize("kw, match", [(dict(n_eps=3), "n_eps must be an integer >= 6"),
                                       (dict(cavitation="elrod"), "cavitation must be one of"),
                                       (dict(eps_max=0.999999), r"eps_max of the table")])
def test_bad_table_inputs_are_named(kw, match):
    args = dict(slenderness=0.5, n_theta=24, n_z=4)
    args.update(kw)
    with pytest.raises(ValueError, match=match):
        force_table(**args)
