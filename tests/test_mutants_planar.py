"""The planar JFO film (bearingfem.fe.planar) and its inputs (bearingfem.planar): mutants of
the mesh-to-mesh interpolation its coarse starts use and of the inputs' checks survived the
planar JFO tests (docs/mutation.md)."""
import pytest

from bearingfem.fe.planar import _interpolation, planar_mesh

L, W = 0.03, 0.01


@pytest.mark.parametrize("coarse, fine", [((6, 3), (12, 6)), ((12, 6), (6, 3)),
                                          ((5, 2), (15, 7))])
def test_interpolation_reproduces_a_bilinear_field(coarse, fine):
    """Bilinear interpolation between two planar meshes reproduces a bilinear function
    a + b x + c y + d x y exactly (to round-off), either way and on meshes whose nodes do
    not nest. Fails with the upper row of a cell taken one row too high (planar.py:223)."""
    def f(x, y):
        return 1.0 + 40.0 * x - 70.0 * y + 900.0 * x * y
    src = planar_mesh(L, W, *coarse, "closed")
    dst = planar_mesh(L, W, *fine, "closed")
    M = _interpolation(L, W, *coarse, "closed", *fine)
    assert M @ f(src.x, src.y) == pytest.approx(f(dst.x, dst.y), rel=1e-12, abs=1e-12)


def test_volume_content_is_the_exact_integral_of_a_quadratic_gap():
    """Oil content of each control volume for a gap quadratic in x, against the exact
    integral of h over the volume's x-extent (Simpson's rule, which the content uses, is
    exact for it: to round-off). Fails with the volume's midpoint taken at half its lower
    edge (planar.py:131)."""
    from bearingfem.fe.planar import _Discretisation
    from bearingfem.planar import PlanarFilm

    h0 = 1e-5
    film = PlanarFilm(length=L, width=W, viscosity=0.01, speed=1.0,
                      gap=lambda x, y, t: h0 * (1.0 + 2.0 * x / L + 3.0 * (x / L) ** 2)
                      + 0.0 * y)
    m = planar_mesh(L, W, 10, 2, "closed")
    cv = m.volumes

    def primitive(x):
        return h0 * (x + x ** 2 / L + x ** 3 / L ** 2)
    exact = cv.area / (cv.x_hi - cv.x_lo) * (primitive(cv.x_hi) - primitive(cv.x_lo))
    assert _Discretisation(film, m, 0.0).content == pytest.approx(exact, rel=1e-12)


@pytest.mark.parametrize("bad, name", [
    (dict(inlet_fraction=1.5), "inlet_fraction"), (dict(inlet_fraction=-0.1), "inlet_fraction"),
    (dict(outlet_pressure=-1.0), "outlet_pressure"), (dict(sides="open"), "sides"),
    (dict(gap=1e-5), "gap"), (dict(width=0.0), "width")])
def test_planar_film_refuses_bad_input_naming_it(bad, name):
    """A planar film's inputs outside their range raise ValueError naming the parameter
    before any work: a supplied film fraction above 1 (more oil than the gap holds) is
    one. Fails with the fraction's range widened to [0, 2] (1.5 was taken)."""
    from bearingfem.planar import PlanarFilm
    args = dict(length=L, width=W, viscosity=0.01, gap=lambda x, y, t: 1e-5 + 0 * x,
                speed=1.0)
    with pytest.raises(ValueError, match=name):
        PlanarFilm(**{**args, **bad})
