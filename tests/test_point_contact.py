"""EHL point contact: Love's rectangle kernel, DC-FFT, dry (Hertz) limit, the EHL film.

Tolerances come from the convergence numbers quoted beside each test (measured on this
code; docs/ehl.md, section "Point contact").
"""
import math

import numpy as np
import pytest
import scipy.integrate

from bearingfem.ehl.pointspace import (PointCompliance, dry_point_contact,
                                       hertz_point_deflection)


def test_love_kernel_against_quadrature():
    """Each coefficient (2/pi^2) int int_cell 1/r against adaptive quadrature off the cell
    and against the closed form of the cell's own centre,
    4 [a asinh(b/a) + b asinh(a/b)]. Agreement to 1e-13 (round-off).
    Fails with any corner sign of Love's four-term difference flipped."""
    c = PointCompliance(5, 4, 0.3, 0.2)
    k = c.kernel
    for i, j in [(1, 0), (0, 2), (3, 3), (4, 1)]:
        x, y = i * 0.3, j * 0.2
        q = scipy.integrate.dblquad(lambda t, s: 1 / math.hypot(x - s, y - t),
                                    -0.15, 0.15, -0.1, 0.1, epsabs=1e-13)[0]
        assert k[i, j] == pytest.approx(2 / math.pi**2 * q, rel=1e-11)
    a, b = 0.15, 0.1
    own = 4 * (a * math.asinh(b / a) + b * math.asinh(a / b))
    assert k[0, 0] == pytest.approx(2 / math.pi**2 * own, rel=1e-13)


def test_dc_fft_equals_dense_product():
    """The zero-padded FFT convolution equals the dense Toeplitz-block product to 1e-15
    on a non-square grid. Fails with the padding row dropped (cyclic wrap-around)."""
    rng = np.random.default_rng(1)
    c = PointCompliance(7, 5, 0.3, 0.3)
    P = rng.random((7, 5))
    np.testing.assert_allclose(c.deflection(P).ravel(), c.matrix() @ P.ravel(),
                               rtol=0, atol=1e-14)


def test_deflection_of_hertz_pressure_converges():
    """V of P = sqrt(1 - r^2) against the exact 1 - r^2/2 on r <= 1.

    Measured max errors 3.34e-3, 1.84e-3, 8.02e-4, 4.39e-4 on 21, 41, 81, 161 nodes a
    side (order ~1, the sqrt edge of the pressure cut by the cells).
    Fails with the 2/pi^2 factor taken as 1/pi^2 or 2/pi.
    """
    errors = []
    for n in (21, 41, 81):
        X = np.linspace(-1.5, 1.5, n)
        r = np.hypot(X[:, None], X[None, :])
        d = X[1] - X[0]
        V = PointCompliance(n, n, d, d).deflection(np.sqrt(np.clip(1 - r**2, 0, None)))
        errors.append(np.abs(V[r <= 1] - hertz_point_deflection(r[r <= 1])).max())
    assert errors[0] / errors[1] > 1.6 and errors[1] / errors[2] > 2.0, errors
    assert errors[-1] < 1e-3


def test_dry_contact_tends_to_hertz():
    """The elastic contact alone (load 2 pi/3) against P = sqrt(1 - r^2), H0 = -1 (the
    approach a^2/R).

    Measured on 13, 25, 49, 97 nodes a side over [-1.5, 1.5]^2:
    max-norm 0.142, 0.091, 0.062, 0.043 (order ~0.55, the sqrt edge);
    on r < 0.8: 2.68e-2, 4.13e-3, 8.2e-4, 1.8e-4 (order 2.7, 2.3, 2.2);
    approach 4.8e-4, 2.7e-4, 8.3e-5, 3.3e-5.
    Fails with the kernel's sign flipped (no contact set converges) or the load 2 pi/3
    taken as pi/2.
    """
    e_max, e_in, e_h0 = [], [], []
    for n in (13, 25, 49):
        d = dry_point_contact(n)
        r = np.hypot(d.x[:, None], d.y[None, :])
        err = np.abs(d.pressure - np.sqrt(np.clip(1 - r**2, 0, None)))
        e_max.append(err.max())
        e_in.append(err[r < 0.8].max())
        e_h0.append(abs(d.approach + 1.0))
        assert np.all(d.pressure >= 0) and np.all(d.gap >= 0)
    assert e_max[0] > e_max[1] > e_max[2] and e_max[2] < 0.07, e_max
    assert e_in[0] / e_in[1] > 4 and e_in[1] / e_in[2] > 4 and e_in[2] < 1e-3, e_in
    assert e_h0[2] < 1e-4, e_h0


@pytest.mark.parametrize("kwargs, name", [(dict(nodes=4), "nodes"), (dict(nodes=20.0), "nodes"),
                                          (dict(nodes=20, half_width=0.9), "half_width")])
def test_dry_bad_input_names_the_parameter(kwargs, name):
    with pytest.raises(ValueError, match=name):
        dry_point_contact(**kwargs)
