"""How jagged a sampled output is: its residual about a smooth curve, and its smoothed peak.

The smooth curve is a local polynomial fit (Savitzky-Golay, generalised to unevenly
spaced samples: Savitzky & Golay 1964; Cleveland 1979 with a uniform kernel): at each
sample, the least-squares polynomial of degree ``order`` through the samples within
``window / 2`` of it, evaluated there. A local fit rather than a Fourier series truncated
at some harmonic, because the joint forces of a slider-crank have narrow peaks at the load
reversals: a truncated series rings (Gibbs) around them over the whole turn, a local fit
only biases the peak, by ~ y^(order+1) (window/2)^(order+1), which the window bounds.

The residual of pure noise about such a fit is smaller than the noise by the fit's
leverage h (the centre weight of the fit, ~ (order+1)/n for n samples in a window), so
the noise is estimated as sqrt(mean(r^2 / (1 - h))), unbiased for white noise.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Smoothing:
    """A local polynomial fit: ``window`` the width of the fitting window, in the units of
    the abscissa (e.g. crank angle [deg]); ``order`` the polynomial degree (0-4)."""

    window: float
    order: int = 2

    def __post_init__(self):
        if not (np.isfinite(self.window) and self.window > 0.0):
            raise ValueError(f"window must be a finite number > 0, got {self.window!r}")
        if not (isinstance(self.order, (int, np.integer)) and 0 <= self.order <= 4):
            raise ValueError(f"order must be an integer in 0..4, got {self.order!r}")


@dataclass(frozen=True)
class Jitter:
    """A signal about its smooth curve: ``smooth`` (the fit at each sample) and
    ``residual`` (signal minus fit), in the signal's units; ``rms`` the noise estimated from
    the residual (leverage-corrected, see the module), ``max`` the largest |residual|;
    ``peak_raw`` / ``peak_smooth`` the largest value of the signal / of its smooth curve,
    at abscissae ``at_raw`` / ``at_smooth``."""

    smooth: np.ndarray
    residual: np.ndarray
    rms: float
    max: float
    peak_raw: float
    peak_smooth: float
    at_raw: float
    at_smooth: float


def local_fit(x, y, smoothing: Smoothing, period: float | None = None):
    """The local polynomial fit of samples ``y`` at abscissae ``x`` (increasing) and its
    leverage at each sample (the weight of the sample itself in its fitted value).

    ``period``: the signal repeats with it (windows wrap around, e.g. 360 deg of a whole
    turn); without it, windows at the ends are cut short (the fit there is one-sided).
    Raises ValueError if a window holds fewer than order + 2 samples (the fit would pass
    through them: no residual to measure)."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    if x.ndim != 1 or x.shape != y.shape:
        raise ValueError(f"x and y must be 1-D of one length, got {x.shape} and {y.shape}")
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
        raise ValueError("x and y must be finite")
    if np.any(np.diff(x) <= 0.0):
        raise ValueError("x must be strictly increasing")
    if period is not None and not (np.isfinite(period) and period >= x[-1] - x[0] > 0.0
                                   and smoothing.window < period):
        raise ValueError(f"period must be >= the span of x ({x[-1] - x[0]:g}) and > the "
                         f"window ({smoothing.window:g}), got {period!r}")
    half = 0.5 * smoothing.window
    if period is None:
        xs, ys = x, y
    else:     # one copy either side: windows that wrap see the samples of the next turn
        before, after = x - period < x[0], x + period > x[-1]   # a sample at both ends once
        xs = np.concatenate([x[before] - period, x, x[after] + period])
        ys = np.concatenate([y[before], y, y[after]])
    edge = half * (1.0 + 1e-9)     # samples on the window's edge in, despite round-off
    lo = np.searchsorted(xs, x - edge, side="left")
    hi = np.searchsorted(xs, x + edge, side="right")
    need = smoothing.order + 2
    if np.any(hi - lo < need):
        i = int(np.argmin(hi - lo))
        raise ValueError(f"window {smoothing.window:g} holds {hi[i] - lo[i]} samples at "
                         f"x = {x[i]:g}; a degree-{smoothing.order} fit needs >= {need}")
    fit, leverage = np.empty_like(y), np.empty_like(y)
    powers = np.arange(smoothing.order + 1)
    for i in range(len(x)):           # one small least-squares fit per sample (not a mesh)
        u = (xs[lo[i]:hi[i]] - x[i]) / half
        V = u[:, None] ** powers
        pinv = np.linalg.pinv(V)      # row 0: the weights giving the fit's value at u = 0
        fit[i] = pinv[0] @ ys[lo[i]:hi[i]]
        leverage[i] = pinv[0, np.argmin(np.abs(u))]
    return fit, leverage


def jitter(x, y, smoothing: Smoothing, period: float | None = None,
           measured=None) -> Jitter:
    """The residual of ``y`` about its local polynomial fit (:func:`local_fit`) and the
    peaks of both: the converged value of a jagged output is the smooth curve's peak.

    ``measured``: a boolean mask of the samples whose residual is the jitter (default all),
    e.g. to leave out a narrow feature of the physics the window does not resolve; the
    peaks are over all samples."""
    fit, h = local_fit(x, y, smoothing, period)
    y = np.asarray(y, float)
    r = y - fit
    m = np.ones(y.shape, bool) if measured is None else np.asarray(measured, bool)
    if m.shape != y.shape or not m.any():
        raise ValueError(f"measured must be a boolean mask of {y.shape} samples with at "
                         "least one set")
    i, k = int(np.argmax(y)), int(np.argmax(fit))
    return Jitter(smooth=fit, residual=r,
                  rms=float(np.sqrt(np.mean(r[m] ** 2 / (1.0 - h[m])))),
                  max=float(np.max(np.abs(r[m]))), peak_raw=float(y[i]),
                  peak_smooth=float(fit[k]), at_raw=float(np.asarray(x)[i]),
                  at_smooth=float(np.asarray(x)[k]))
