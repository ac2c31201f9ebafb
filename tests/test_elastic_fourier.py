"""The solid bush per circumferential harmonic (bearingfem.elastic.fourier, the default
``ElasticBush(model="solid")``): its strains against the rigid-body modes, its harmonic
blocks against the exact plane-strain ring, its film compliance against the 3-D solid
(``model="solid-3d"``) and the EHD film on it against the one on the 3-D solid."""
import numpy as np
import pytest
from skfem import Basis, ElementQuad1, ElementVector, MeshQuad1, asm

from bearingfem import ElasticBush, JournalState, solve_reynolds
from bearingfem.bearing import seed_bearing
from bearingfem.elastic import bush_compliance
from bearingfem.elastic.fourier import harmonic_forms, section_system
from bearingfem.elastic.surface import FilmGrid
from test_ehd_mixed import michell
from test_elastic_bush import lame_exact, ring_exact
from bearingfem.elastic import fourier

R, B, L = 0.010, 0.016, 0.004
BRONZE = dict(outer_radius=B, modulus=110e9, poisson=0.34)


@pytest.mark.parametrize("mode", ["translation", "tilt"])
def test_rigid_body_modes_strain_nothing(mode):
    """Harmonic 1 of a rigid motion: a translation along x (U = 1, V = -1, W = 0) and a
    tilt about y (U = z, V = -z, W = -r) have zero energy, K_1 x = 0 to round-off
    (1e-12 of |K_1| |x|), on a section without held dofs; a radial stretch (U = r) does
    not. Fails with g_rt's -m U / r or g_tz's -m W / r sign flipped, or eps_tt's m V."""
    mesh = MeshQuad1.init_tensor(np.linspace(R, B, 4), np.linspace(-L / 2, L / 2, 4))
    basis = Basis(mesh, ElementVector(ElementQuad1(), dim=3), intorder=3)
    k = sum(asm(form, basis) for form in harmonic_forms(*ElasticBush(**BRONZE).lame))
    r, z = mesh.p
    u = {"translation": (1.0 + 0 * r, -1.0 + 0 * r, 0 * r), "tilt": (z, -z, -r)}[mode]
    x = np.zeros(basis.N)
    for c in range(3):
        x[basis.nodal_dofs[c]] = u[c]
    scale = abs(k).max() * np.abs(x).max()
    assert np.abs(k @ x).max() <= 1e-12 * scale
    stretch = np.zeros(basis.N)
    stretch[basis.nodal_dofs[0]] = r
    assert np.abs(k @ stretch).max() > 1e-3 * scale


def ring_errors(n_radial):
    """Relative error of the plane-strain solid's harmonic blocks G_m under a
    z-independent pressure cos(m theta) (the sum of the film's hats along z: every row of
    G_m summed over the loads) against the exact ring, m = 0 .. 5."""
    bush = ElasticBush(**BRONZE, ends="plane-strain")
    lam, mu = bush.lame
    system = section_system(bush, R, FilmGrid(16, 3, L), 1, n_radial, 4.0)
    exact = [lame_exact(R, B, lam, mu), ring_exact(1, R, B, lam, mu)] + [
        michell(m, R, B, lam, mu) for m in range(2, 6)]
    return np.array([np.max(np.abs(system.block(m).sum(axis=1) / e - 1.0))
                     for m, e in enumerate(exact)])


def test_plane_strain_harmonics_are_the_exact_ring():
    """Plane-strain ends under a z-independent load: harmonic m's radial deflection is the
    exact plane-strain ring's (Lame m = 0, the m = 1 ring, Michell m >= 2) at every film
    node along z, converging at second order in the section mesh (measured, n_radial 4 /
    8 / 16 / 32: m = 0 2.3e-3 .. 3.5e-5, m = 4 2.1e-2 .. 3.5e-4, orders 1.93-2.00), so
    the test asserts orders > 1.9 from 8 to 16 cells and < 1 % at 16. Fails with the
    traction's sign flipped, the r weight of the energy left out, lambda and mu swapped,
    or the torsion V held at m > 0."""
    coarse, fine = ring_errors(8), ring_errors(16)
    assert np.all(np.log2(coarse / fine) > 1.9)
    assert np.all(fine < 1e-2)


def load(n_theta, n_z):
    """A smooth film pressure [Pa]: a Gaussian 3 mm arc, falling to half at the ends."""
    theta = 2 * np.pi * np.arange(n_theta) / n_theta
    s = R * np.where(theta > np.pi, theta - 2 * np.pi, theta)
    z = np.linspace(-L / 2, L / 2, n_z)
    return 8e8 * np.exp(-(s / 3e-3) ** 2)[:, None] * (1 - 0.5 * (2 * z / L) ** 2)[None, :]


def solid_difference(n_theta, n_z):
    """max |w_fourier - w_3d| / max |w_3d| under :func:`load`, free ends."""
    p = load(n_theta, n_z)
    w = [bush_compliance(ElasticBush(**BRONZE, model=model), R, L, n_theta, n_z)
         .deflection(p) for model in ("solid", "solid-3d")]
    return np.max(np.abs(w[0] - w[1])) / np.max(np.abs(w[1]))


def test_free_ends_is_the_3d_solid():
    """Free ends: the Fourier solid's film deflection against the 3-D solid's (hexahedra
    on the same radial and axial lines, one cell per film cell around) under a smooth
    load. Measured 1.8e-2 / 1.9e-3 / 6.9e-4 on 24 x 5 / 48 x 9 / 96 x 17 (orders 3.2, 1.5)
    while either is 17 % / 7.3 % / 2.6 % from a 384 x 65 Fourier reference: the two
    differ by their theta discretisation only, far below their common (r, z) error (the
    trigonometric interpolation instead of the alias sum: 7.2e-2 / 2.2e-2 / 5.9e-3).
    Asserts a fall by > 4 from 24 to 48 and < 3e-3 at 48. Fails with the load read at the
    film nodes' neighbours (z shifted by one), or the axial shear g_rz's W_r left out."""
    coarse, fine = solid_difference(24, 5), solid_difference(48, 9)
    assert coarse / fine > 4.0
    assert fine < 3e-3


@pytest.mark.slow
def test_free_ends_is_the_3d_solid_finer():
    """The next refinement of :func:`test_free_ends_is_the_3d_solid` (measured 6.9e-4 at
    96 x 17: order 1.5)."""
    assert solid_difference(96, 17) < 1e-3


SEED = seed_bearing(0.2)
HEAVY = JournalState(eps=0.995, gamma=0.2, omega=250.0)


def test_ehd_film_is_the_3d_solids():
    """The seed pin's heavy state (eps 0.995, bronze bush, Reynolds' condition, the bush
    carries the film) on the Fourier solid and on the 3-D solid: load, peak pressure and
    deflection agree to the discretisation's difference (measured 48 x 4 / 96 x 8: load
    1.9e-4 / 1.2e-4, pressure 7.3e-3 / 1.9e-3, deflection 1.1e-2 / 2.3e-3 of their
    maxima; the mesh's own error in the load is 7.6e-2 / 1.6e-2, docs/ehd.md), asserted
    at 48 x 4 with bounds 2x the measurement. Fails with the deflection's sign flipped or
    the plane-strain ends' axial hold applied to the free ends."""
    films = [solve_reynolds(SEED, HEAVY, 48, 4, bush=ElasticBush(**BRONZE, model=model))
             for model in ("solid", "solid-3d")]
    new, old = films
    force = np.linalg.norm(new.force) / np.linalg.norm(old.force) - 1.0
    assert abs(force) < 4e-4
    assert np.max(np.abs(new.pressure - old.pressure)) < 1.5e-2 * old.pressure_max
    assert np.max(np.abs(new.deformation - old.deformation)) < 2.2e-2 * np.max(
        np.abs(old.deformation))


def test_rigid_limit():
    """E = 1e30 Pa: the Fourier solid does not move (< 1e-20 m) and the EHD film is the
    rigid film (load to 1e-9) at a light state. Fails with the section's Lame parameters
    fixed at bronze's (the bush's modulus ignored)."""
    light = JournalState(eps=0.6, gamma=0.2, omega=250.0)
    stiff = ElasticBush(outer_radius=B, modulus=1e30, poisson=0.34)
    ehd = solve_reynolds(SEED, light, 48, 4, bush=stiff)
    rigid = solve_reynolds(SEED, light, 48, 4)
    assert np.max(np.abs(ehd.deformation)) < 1e-20
    assert np.allclose(ehd.force, rigid.force, rtol=1e-9, atol=0.0)


def test_names_and_refine_theta():
    """"solid-3d" is a model; the Fourier solid is exact in theta, so ``refine_theta``
    does not change it; its columns are real and even in theta (the bush's mirror).
    Fails with the columns turned by one film cell."""
    bush = ElasticBush(**BRONZE)
    a = bush_compliance(bush, R, L, 16, 3, n_radial=2).columns
    b = bush_compliance(bush, R, L, 16, 3, n_radial=2, refine_theta=2).columns
    assert np.array_equal(a, b)
    assert np.allclose(a, a[(-np.arange(16)) % 16], rtol=0, atol=1e-12 * np.abs(a).max())
    assert ElasticBush(model="solid-3d").model == "solid-3d"
    with pytest.raises(ValueError, match="model must be one of"):
        ElasticBush(model="fourier")


def test_high_harmonics_held_below_their_decay():
    """Harmonic m is solved on the radial lines above the depth 16 R / m only (its field
    decays like (1 + m d / R) e^(-m d / R)): on a 96 x 17 grid (16 radial cells) every
    block, m = 0 .. 48 and the aliases' 96, 144, 192, equals the one solved on the whole
    wall to 2e-5 of its largest entry (measured 2.0e-7; all harmonics of 240 x 41 and
    480 x 81 at their default walls: 4.2e-7, 2.9e-7), while m = 192 is solved on under
    half the wall's unknowns. Fails with the reach taken as 16 / m [m] (R left out), with
    10 R / m, or with the deep lines not held (the whole wall solved). Holding the line
    below the reach or leaving it free changes the blocks by less than the bound (the
    field has decayed there), so that variant survives."""
    bush = ElasticBush(**BRONZE)
    film = FilmGrid(96, 17, L)
    m = np.r_[0:49, 96, 144, 192]
    system = section_system(bush, R, film, 1, 16, 4.0)
    whole = section_system(bush, R, film, 1, 16, 4.0, decay=None)
    cut, full = system.blocks(m), whole.blocks(m)
    scale = np.abs(full).max(axis=(1, 2))
    assert np.all(np.abs(cut - full).max(axis=(1, 2)) < 2e-5 * scale)
    assert system.lines(192) <= system.depth.size // 2
    assert system.banded(192).unit.shape[0] < 0.5 * whole.banded(192).unit.shape[0]


def test_octaves_interpolate_the_solved_blocks():
    """From m = 16 on, the blocks are interpolated per octave [a, 2a) from m G_m at 13
    Chebyshev points, solved on the octave's deepest lines: on a 96 x 17 grid (8 radial
    cells; octaves [16, 32), [32, 49)) every block equals the one solved at its own m on
    the same lines to 1e-9 of the operator's 2-norm (measured 4.0e-11; 192 x 33 4.0e-11,
    the seed pin's 480 x 81 bush 6.2e-11 against the whole wall, where the held lines of
    every harmonic solved give 3.3e-9), and the blocks below 16 are the solved ones
    exactly. Fails with G_m interpolated for m G_m, the end points' barycentric weights
    not halved, or the octave solved on the lines of its top harmonic."""
    bush = ElasticBush(**BRONZE)
    system = section_system(bush, R, FilmGrid(96, 17, L), 1, 8, 4.0)
    m = np.arange(49)
    got = system.blocks(m)
    solved = np.empty_like(got)
    solved[:16] = section_system(bush, R, FilmGrid(96, 17, L), 1, 8, 4.0,
                                 octave=None).blocks(m[:16])
    for low in (16, 32):
        band = system.banded(low)
        for k in m[(m >= low) & (m < 2 * low)]:
            solved[k] = band.block(k)
    norm = max(np.linalg.norm(g, 2) for g in solved)
    assert np.array_equal(got[:16], solved[:16])
    error = max(np.linalg.norm(a - b, 2) for a, b in zip(got, solved)) / norm
    assert 0.0 < error < 1e-9


def test_ehd_film_on_octaves_is_every_harmonic_solved(monkeypatch):
    """The seed pin's heavy EHD state (eps 0.995, gamma 0.2, 250 rad/s, 192 x 16 cells:
    harmonics 16 .. 96 interpolated) on the default solid against the one with every
    harmonic solved (the toolkit before the octaves): load and peak pressure to 1e-9
    (measured 5.8e-14, 4.1e-12). Fails with G_m interpolated for m G_m or the end points'
    barycentric weights not halved; the octave solved on the lines of its top harmonic
    (~1e-7 in the high harmonics' blocks) moves this film by less and is caught by the
    blocks' test above."""
    seed = seed_bearing(0.2)
    state = JournalState(eps=0.995, gamma=0.2, omega=250.0)
    bush = ElasticBush(**BRONZE)
    octaves = solve_reynolds(seed, state, 192, 16, bush=bush_compliance(bush, R, L, 192, 17))
    monkeypatch.setattr(fourier, "OCTAVES", None)
    every = solve_reynolds(seed, state, 192, 16, bush=bush_compliance(bush, R, L, 192, 17))
    assert abs(np.linalg.norm(octaves.force) / np.linalg.norm(every.force) - 1.0) < 1e-9
    assert abs(octaves.pressure_max / every.pressure_max - 1.0) < 1e-9
    assert octaves.pressure_max != every.pressure_max      # the octaves did run
