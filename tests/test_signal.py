"""The jitter measure (bearingfem.outputs.signal) against closed forms and known noise."""
import numpy as np
import pytest

from bearingfem.outputs.signal import Smoothing, jitter, local_fit

Q = np.arange(720) * 0.5          # a turn at the study's 720 samples [deg]


def force_like(q):
    """A smooth joint-force-like curve [N]: a few harmonics and a narrow load-reversal
    peak (40 deg wide, like the seed pin's at top dead centre)."""
    r = np.radians(q)
    return (1500 + 900 * np.sin(r) + 400 * np.cos(2 * r) + 150 * np.sin(3 * r)
            + 2000 * np.exp(-0.5 * ((q - 200.0) / 20.0) ** 2))


def test_centre_weight_is_savitzky_golay():
    """On evenly spaced samples the fit is Savitzky-Golay's: a unit spike's fitted value at
    itself is the quadratic filter's centre weight 3(3n^2 - 7) / (4n(n^2 - 4)) for the
    n = 31 samples within +-7.5 deg. Fails if the window is taken as a half-width or in
    other units (n = 61 or 1+), or if the fit's degree is not the one asked for."""
    n = 31
    y = np.zeros_like(Q)
    y[100] = 1.0
    fit, h = local_fit(Q, y, Smoothing(15.0, 2))
    c0 = 3 * (3 * n ** 2 - 7) / (4 * n * (n ** 2 - 4))
    assert fit[100] == pytest.approx(c0, rel=1e-12) and h[100] == pytest.approx(c0, rel=1e-12)
    # a quadratic passes through unchanged (also where a window wraps the turn's end)
    quad = 3.0 + 0.2 * Q - 1e-3 * Q ** 2
    assert np.allclose(local_fit(Q, quad, Smoothing(15.0, 2))[0], quad, rtol=0, atol=1e-9)
    per = np.cos(np.radians(Q))
    assert np.allclose(local_fit(Q, per, Smoothing(15.0, 2), period=360.0)[0], per, atol=1e-4)


@pytest.mark.parametrize("sigma", [5.0, 40.0])
def test_recovers_known_noise_and_smooth_peak(sigma):
    """White noise of a known RMS on a smooth force-like curve: the measure recovers the
    RMS within 10 % (0.93 and 1.02 of it here) and the smooth curve's peak within 0.5 %
    (the raw maximum sits up to 2 % above it). Fails with a window 4x too wide (60 deg:
    the fit cuts the peak by 1.7 %, and the residual takes it: 4.3x the RMS of the
    smaller noise)."""
    rng = np.random.default_rng(7)
    clean = force_like(Q)
    y = clean + sigma * rng.standard_normal(Q.size)
    j = jitter(Q, y, Smoothing(15.0, 2), period=360.0)
    assert j.rms == pytest.approx(sigma, rel=0.10)
    assert j.peak_smooth == pytest.approx(clean.max(), rel=0.005)
    assert j.peak_raw == y.max() and j.max == pytest.approx(np.abs(y - j.smooth).max())
    wide = jitter(Q, y, Smoothing(60.0, 2), 360.0)     # the window 4x too wide
    assert abs(wide.peak_smooth / clean.max() - 1) > 0.01
    assert sigma > 10 or wide.rms > 2 * sigma


def test_the_smooth_peak_is_the_smooth_curves_not_the_fit_at_the_raw_maximum():
    """One wild sample (+4000 N at 100 deg, a glitch of a film solve) far from the load
    peak (3447 N at 194 deg): the raw maximum is the glitch, but the smooth peak is the
    largest value of the smooth curve, within 0.5 % of the clean curve's maximum (1e-4
    measured) and at its angle (within a sample), the glitch lifting its neighbourhood
    by at most the fit's centre weight, 0.073 of it. Fails when the smooth peak or its
    angle is read at the raw maximum's sample (2171 N at 100 deg)."""
    clean = force_like(Q)
    y = clean.copy()
    y[200] += 4000.0                  # Q[200] = 100 deg
    j = jitter(Q, y, Smoothing(15.0, 2), period=360.0)
    assert j.at_raw == 100.0 and j.peak_raw == y[200]
    assert j.peak_smooth == pytest.approx(clean.max(), rel=0.005)
    assert j.at_smooth == pytest.approx(Q[np.argmax(clean)], abs=0.5)


def test_measured_mask():
    """Samples left out of the jitter (a narrow feature of the physics) are left out of its
    RMS and maximum, not of the fit or the peaks. Fails if the mask is ignored."""
    y = np.zeros_like(Q)
    y[300] = 100.0
    whole = jitter(Q, y, Smoothing(15.0, 2), 360.0)
    away = jitter(Q, y, Smoothing(15.0, 2), 360.0, measured=np.abs(Q - 150.0) > 10.0)
    assert whole.max > 90.0 and away.max < 1e-12 and away.rms < 1e-12
    assert away.peak_raw == 100.0 and np.array_equal(away.smooth, whole.smooth)


def test_refusals():
    with pytest.raises(ValueError, match="window"):
        Smoothing(0.0)
    with pytest.raises(ValueError, match="order"):
        Smoothing(10.0, order=7)
    with pytest.raises(ValueError, match="holds 1 samples"):
        local_fit(Q, Q, Smoothing(0.6, 2))
    with pytest.raises(ValueError, match="increasing"):
        local_fit(Q[::-1], Q, Smoothing(15.0))
    with pytest.raises(ValueError, match="measured"):
        jitter(Q, Q, Smoothing(15.0), measured=np.zeros(Q.size, bool))
    with pytest.raises(ValueError, match="period"):
        local_fit(Q, Q, Smoothing(15.0), period=100.0)
