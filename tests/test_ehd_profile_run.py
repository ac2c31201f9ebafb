"""A bush edge profile (bearingfem.fields.EdgeProfile) in the "fem-ehd" mechanism film:
its modal-state coupling ("states"), its kept film ("kept", "tangent") and the scene
option [effects.lubrication.profile]."""
import dataclasses
from pathlib import Path

import numpy as np
import pytest
import tomllib

from bearingfem import Bearing, ElasticBush, JournalState, solve_reynolds
from bearingfem.contact import Roughness
from bearingfem.ehd.states import ModalStateEHD
from bearingfem.ehd.transient import TransientEHD
from bearingfem.fe.assembly import fe_operator
from bearingfem.fields import EdgeProfile
from bearingfem.film import film_thickness
from bearingfem.models.ehd import ehd_run_film
from mechanism.scene import parse_scene

B = Bearing(radius=0.01, length=0.004, clearance=20e-6, viscosity=0.0117)
SOLID = ElasticBush(outer_radius=0.016, modulus=110e9, poisson=0.34, model="solid")
CROWN = EdgeProfile("crown", 4e-6)              # 0.2 c at the ends
CHAMFER = EdgeProfile("chamfer", 3e-6, 0.001)   # the outer millimetre at each end
NT, NZ, M = 24, 4, 8


def formula(z):
    """h_p / c of CROWN and CHAMFER at z [m] (written out, not EdgeProfile.gap)."""
    half = 0.5 * B.length
    crown = 4e-6 * (2 * z / B.length) ** 2
    chamfer = 3e-6 * np.maximum(0.0, np.abs(z) - (half - 0.001)) / 0.001
    return crown / B.clearance, chamfer / B.clearance


@pytest.mark.parametrize("which", [0, 1])
def test_the_states_film_with_a_stiff_bush_is_the_profiled_rigid_film(which):
    """A bush 1e10 times stiffer, q = 0, a moving journal: the states film's force is the
    rigid Reynolds-condition film's with the same profile (solve_reynolds' general-field
    film, checked against finite volumes in tests/test_profile.py) to 1e-8 (8e-10 and 1e-9
    measured: the bush's squeeze at its relaxation rate), and its nodal
    gap is the rigid gap plus the profile's formula to 1e-12. Fails when the profile is
    left out of the flow's gap at the points (the force is then the plain bore's: 65 % or
    more off) or out of the nodal gap."""
    profile = (CROWN, CHAMFER)[which]
    stiff = dataclasses.replace(SOLID, modulus=110e19)
    s = JournalState(eps=0.7, eps_dot=30.0, gamma=0.4, gamma_dot=-5.0, omega=62.5)
    film = ModalStateEHD(B, None, stiff, NT, NZ, M, relaxation=1e-6, profile=profile)
    F, _ = film.rates(s, np.zeros(M))
    rigid = solve_reynolds(B, s, NT, NZ, "P1", "reynolds", half=False, profile=profile)
    plain = solve_reynolds(B, s, NT, NZ, "P1", "reynolds", half=False)
    assert np.allclose(F, rigid.force_local, rtol=1e-8, atol=0)
    assert not np.allclose(F, plain.force_local, rtol=0.1, atol=0)
    sol = film.solution(s, np.zeros(M))
    z = np.asarray(sol.z)
    expected = film_thickness(np.asarray(sol.theta), s.eps) + formula(z)[which]
    assert np.allclose(np.asarray(sol.film_thickness) / B.clearance, expected,
                       rtol=0, atol=1e-12)


def test_the_kept_film_carries_the_profile_at_its_points():
    """The kept film ("kept" coupling) of a crowned bush: its gap at the film's points at
    the state of the film step is the plain kept film's plus the crown's formula (1e-14),
    and its force there is the full solve's to round-off (1e-12; 1e-16 measured): the kept
    film is that solve's film, crown included. Fails when the kept film drops the crown
    (its force is then some twice the solve's)."""
    s = JournalState(eps=0.8, gamma=0.3, omega=250.0)
    run = TransientEHD(B, None, SOLID, None, NT, NZ, M, profile=CROWN)
    plain = TransientEHD(B, None, SOLID, None, NT, NZ, M)
    run.start(s, 0.0)
    plain.start(s, 0.0)
    op = fe_operator(B, s, NT, NZ, "P1", None, False)
    g = run._kept.fields(B, s, op, None).gap
    g0 = dataclasses.replace(run._kept, profile=None).fields(B, s, op, None).gap
    assert np.allclose(g - g0, formula(B.radius * op.qp_zeta)[0], rtol=0, atol=1e-14)
    total = np.add(run._solution.force_local, run._solution.asperity_force_local)
    assert np.allclose(run.kept_force(s), total, rtol=1e-12, atol=0)
    assert not np.allclose(plain.kept_force(s), total, rtol=0.1, atol=0)


def _short_run(profile, coupling):
    from benchmarks.ehd_run import scene
    from mechanism import simulate
    rough = Roughness(sigma=0.2e-6, contact_modulus=80.8e9, elastic_factor=1e-3)
    extra = dict(relaxation=1e-5, film_step=0.0) if coupling == "states" else dict(
        film_step=2e-5)
    sc = scene("paper-short-ehd-sharp", 250.0, 0.004, n_theta=NT, n_z=NZ, modes=M,
               lubricant=None, coupling=coupling, roughness=rough, profile=profile, **extra)
    return simulate(sc, progress=False)


@pytest.mark.parametrize("coupling", ["states", "kept"])
def test_a_zero_profile_is_todays_run_bit_for_bit(coupling):
    """The seed pin's first 0.4 % of a turn, 24 x 4, 8 modes: a crown of depth 0 gives the
    run without a profile to the last bit (every saved state, force and film record row);
    a 2 um crown changes it (the check sees the option at all)."""
    a, b = _short_run(None, coupling), _short_run(EdgeProfile("crown", 0.0), coupling)
    assert not a.partial and not b.partial
    for name in ("t", "eps", "e_x", "e_y", "force_x", "force_y", "film_min", "film_record"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)
    c = _short_run(EdgeProfile("crown", 2e-6), coupling)
    assert not np.array_equal(a.film_min, c.film_min)


def test_the_scene_takes_the_profile_and_names_what_it_refuses():
    """[effects.lubrication.profile] kind/depth/length is the model's EdgeProfile; bad
    values are named with their table; the transient EHD-JFO film refuses one by name, as
    does a profile longer than half the bush."""
    data = tomllib.loads(Path("scenes/paper-short-ehd-sharp.toml").read_text())
    data["effects"]["lubrication"]["profile"] = dict(kind="chamfer", depth=1e-6,
                                                     length=5e-4)
    sc = parse_scene(data)
    assert sc.lubrication.options["profile"] == EdgeProfile("chamfer", 1e-6, 5e-4)
    data["effects"]["lubrication"]["profile"] = dict(kind="taper", depth=1e-6)
    with pytest.raises(ValueError, match=r"lubrication\.profile: kind must be one of"):
        parse_scene(data)
    data["effects"]["lubrication"]["profile"] = dict(kind="crown", depth=-1e-6)
    with pytest.raises(ValueError, match=r"lubrication\.profile: depth must be >= 0"):
        parse_scene(data)
    with pytest.raises(ValueError, match="profile takes cavitation 'reynolds'"):
        ehd_run_film(B, bush=SOLID, modes=4, cavitation="jfo", profile=CROWN)
    with pytest.raises(ValueError, match=r"length must lie in \(0, L/2\]"):
        ehd_run_film(B, bush=SOLID, modes=4, coupling="states",
                     profile=EdgeProfile("chamfer", 1e-6, 0.003))
