"""Patir & Cheng's pressure flow factor measured on rough cells: the fits against a flow
simulation of its own.

A periodic cell [0, L_x] x [0, L_y] of the local gap h_T(x, y) = max(h + delta(x, y), 0)
(delta the roughness, contact closing the gap) carries the Reynolds equation
div(h_T^3 grad p) = 0 with a mean pressure gradient imposed, p = -x + p~ (p~ periodic),
solved by P1 finite elements (scikit-fem, on a grid of right triangles, the periodic
dofs joined). Its mean flow per unit width and unit gradient,
<q_x> = <h_T^3 (1 - dp~/dx)>, gives

    phi_x = <q_x> / h^3,

the factor Patir & Cheng (1978) computed by flow simulations of their own (on finite
cells with the pressure held at the ends) and fitted. The shear flow factor (Patir &
Cheng 1979) is the mean flow of the rough surface sliding at unit speed over a smooth one
with no mean gradient: div(h_T^3 grad p) = -6 dh_T/dx (the roughness' own squeeze),
sigma Phi_s = -<h_T^3 dp/dx> / 6. Exact checks of the cell solve:
ridges across the flow, h_T = h (1 + a cos(2 pi x / l)), give
phi_x = 1 / (h^3 <h_T^-3>) = 2 (1 - a^2)^(5/2) / (2 + a^2); ridges along it,
h_T = h (1 + a cos(2 pi y / l)), give phi_x = <h_T^3> / h^3 = 1 + 3 a^2 / 2; a
checkerboard of two conductances k1, k2 gives sqrt(k1 k2) (Keller's duality); the
shear flow of ridges across the flow is sigma Phi_s = h - <h_T^-2>/<h_T^-3> (h_T^3 dp/dx
= -6 h_T + C, C fixed by periodicity), of ridges along it 0.

The isotropic rough surface is a periodic Gaussian random field of unit variance with a
Gaussian autocorrelation whose half-height length is ``correlation`` (Patir & Cheng's
lambda_0.5), drawn in Fourier space on a grid of ``correlation`` / 8 and sampled on any
finer grid by zero padding (the same surface on every mesh: a convergence study of the
cell solve alone).

    python -m studies.flow_factors        # the tables of docs/mixed-lubrication.md
    python -m studies.flow_factors --figure docs/img/flow-factors.png
"""
from __future__ import annotations

import argparse
import math
import time

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu
from skfem import Basis, BilinearForm, ElementTriP1, LinearForm, MeshTri, asm
from skfem.helpers import dot, grad

from bearingfem.contact.flow_factors import (PATTERNS, PRESSURE_FIT, mean_gap,
                                             pressure_flow_factor, shear_flow_factor)

__all__ = ["cell_factors", "cell_flow_factor", "gaussian_surface", "transverse_exact",
           "longitudinal_exact", "transverse_shear_exact", "measured_factors"]

#: the coefficient's floor where the surfaces touch (a closed cell carries no flow)
CLOSED = 1e-12


@BilinearForm
def _conduction(u, v, w):
    return w.k * dot(grad(u), grad(v))


@LinearForm
def _driving(v, w):
    return w.k * grad(v)[0]          # int k e_x . grad v: the imposed unit gradient


def _periodic(mesh, lx: float, ly: float):
    """(N x M) sparse map of the periodic dofs onto the mesh's nodes (x = L_x onto 0,
    y = L_y onto 0)."""
    x, y = mesh.p
    nx = len(np.unique(np.round(x / lx * 1e9)))
    ny = len(np.unique(np.round(y / ly * 1e9)))
    i = np.rint(x / lx * (nx - 1)).astype(int) % (nx - 1)
    j = np.rint(y / ly * (ny - 1)).astype(int) % (ny - 1)
    col = i * (ny - 1) + j
    n = mesh.p.shape[1]
    return sp.csr_matrix((np.ones(n), (np.arange(n), col)), shape=(n, (nx - 1) * (ny - 1)))


def cell_factors(gap, nominal: float, size: tuple, cells: tuple,
                 sigma: float = 1.0) -> tuple:
    """(phi_x, Phi_s) of the local gap ``gap(x, y)`` [any unit; clipped at 0, evaluated
    at the quadrature points] on the periodic cell ``size`` = (L_x, L_y) meshed with
    ``cells`` = (n_x, n_y) squares of two triangles, for the nominal gap ``nominal`` and
    the roughness ``sigma`` (module docstring; both flows on one factorisation)."""
    (lx, ly), (nx, ny) = size, cells
    mesh = MeshTri.init_tensor(np.linspace(0.0, lx, nx + 1), np.linspace(0.0, ly, ny + 1))
    basis = Basis(mesh, ElementTriP1())
    x, y = np.asarray(basis.global_coordinates())
    h = np.maximum(gap(x, y), 0.0)
    k = h ** 3 + CLOSED * nominal ** 3
    P = _periodic(mesh, lx, ly)
    K = (P.T @ asm(_conduction, basis, k=k) @ P).tocsc()
    # p~ is defined up to a constant: held at 0 on the first dof
    lu = splu(K[1:, 1:], permc_spec="MMD_AT_PLUS_A")     # symmetric

    def mean_flux(load):
        q = np.zeros(K.shape[0])
        q[1:] = lu.solve(load[1:])
        return float(np.sum(k * basis.interpolate(P @ q).grad[0] * basis.dx)) / (lx * ly)
    # the unit gradient: <q_x> = <h_T^3 (1 - dp~/dx)>
    pressure = (float(np.sum(k * basis.dx)) / (lx * ly)
                - mean_flux(P.T @ asm(_driving, basis, k=k)))
    # the roughness sliding at unit speed over a smooth surface, no mean gradient:
    # div(h_T^3 grad p) = -6 dh_T/dx, weakly int h_T^3 grad p . grad v = -6 int h_T dv/dx
    shear = -mean_flux(-6.0 * (P.T @ asm(_driving, basis, k=h))) / (6.0 * sigma)
    return pressure / nominal ** 3, shear


def cell_flow_factor(gap, nominal: float, size: tuple, cells: tuple) -> float:
    """phi_x of :func:`cell_factors`."""
    return cell_factors(gap, nominal, size, cells)[0]


def transverse_shear_exact(H: float, a: float) -> float:
    """Phi_s of ridges across the flow on the moving surface, h_T = H + a cos(2 pi x / l)
    (sigma = a / sqrt(2)): H - <h_T^-2>/<h_T^-3>, over sigma."""
    t = np.linspace(0.0, 2.0 * np.pi, 20001)[:-1]      # periodic: the rectangle rule
    h = H + a * np.cos(t)
    return (H - np.mean(h ** -2) / np.mean(h ** -3)) / (a / math.sqrt(2.0))


def transverse_exact(a: float) -> float:
    """phi_x of ridges across the flow, h_T = h (1 + a cos): 1 / (h^3 <h_T^-3>)."""
    return 2.0 * (1.0 - a * a) ** 2.5 / (2.0 + a * a)


def longitudinal_exact(a: float) -> float:
    """phi_x of ridges along the flow, h_T = h (1 + a cos): <h_T^3> / h^3."""
    return 1.0 + 1.5 * a * a


def gaussian_surface(length: float, correlation: float, seed: int):
    """A periodic isotropic Gaussian surface of unit variance on [0, length]^2 with a
    Gaussian autocorrelation of half-height length ``correlation``: returns
    ``sample(n)``, the surface on an n x n grid of cell centres (n a multiple of the
    drawing grid's), the same surface for every n."""
    n0 = int(round(8 * length / correlation))
    beta = correlation / math.sqrt(math.log(2.0))      # R(r) = exp(-r^2 / beta^2)
    k = 2.0 * math.pi * np.fft.fftfreq(n0, d=length / n0)
    kx, ky = np.meshgrid(k, k, indexing="ij")
    spectrum = np.exp(-(kx ** 2 + ky ** 2) * beta ** 2 / 8.0)   # sqrt of the PSD
    rng = np.random.default_rng(seed)
    coeff = np.fft.fft2(rng.standard_normal((n0, n0))) * spectrum
    coeff[0, 0] = 0.0
    field = np.real(np.fft.ifft2(coeff))
    scale = 1.0 / field.std()

    def sample(n: int) -> np.ndarray:
        if n % n0:
            raise ValueError(f"n must be a multiple of {n0}, got {n}")
        m = n // n0
        padded = np.zeros((n, n), complex)
        h = n0 // 2
        idx = np.r_[0:h, n - (n0 - h):n]
        src = np.r_[0:h, h:n0]
        padded[np.ix_(idx, idx)] = coeff[np.ix_(src, src)]
        # shift by half a fine cell: the n x n values sit at the cell centres
        f = 2.0 * math.pi * np.fft.fftfreq(n, d=1.0 / n) * (0.5 / n)
        padded *= np.exp(1j * (f[:, None] + f[None, :]))
        return np.real(np.fft.ifft2(padded)) * (m * m) * scale
    return sample


def _cells_gap(values: np.ndarray, length: float, nominal: float, pattern: float = 1.0):
    """The gap nominal + values on the cell [0, pattern length] x [0, length]: the
    surface ``values`` stretched along x by Peklenik's gamma = ``pattern`` (its
    correlation lengths then pattern lambda along x, lambda along y)."""
    n = values.shape[0]

    def gap(x, y):
        i = np.minimum((x / (pattern * length) * n).astype(int), n - 1)
        j = np.minimum((y / length * n).astype(int), n - 1)
        return nominal + values[i, j]
    return gap


def measured_factors(H, seeds=range(4), length: float = 8.0, per_correlation: int = 16,
                     pattern: float = 1.0):
    """phi_x on ``seeds`` Gaussian surfaces (sigma = 1, correlation length 1 across the
    flow and ``pattern`` along it, a cell ``length`` correlation lengths wide each way,
    ``per_correlation`` grid cells per correlation length) at each nominal gap H: arrays
    (H, seeds) of phi_x and of Phi_s (the surface moving, the other smooth)."""
    n = int(length * per_correlation)
    phi, shear = np.zeros((len(H), len(seeds))), np.zeros((len(H), len(seeds)))
    for j, seed in enumerate(seeds):
        values = gaussian_surface(length, 1.0, seed)(n)
        for i, h in enumerate(H):
            phi[i, j], shear[i, j] = cell_factors(_cells_gap(values, length, h, pattern), h,
                                                  (pattern * length, length), (n, n))
    return phi, shear


#: the nominal gaps of the anisotropic cells
ANISOTROPIC_H = (1.0, 1.5, 2.0, 3.0, 4.0)


def anisotropic_factors(seeds=range(4), length: float = 16.0, per_correlation: int = 8):
    """{gamma: (H, phi_x (H, seeds), Phi_s (H, seeds))} of the cells stretched by each
    tabulated gamma != 1, at the H of ANISOTROPIC_H at or above the fit's least H."""
    out = {}
    for g in PATTERNS:
        if g == 1.0:
            continue
        H = np.array([h for h in ANISOTROPIC_H if h >= PRESSURE_FIT[g][2]])
        out[g] = (H, *measured_factors(H, seeds, length, per_correlation, pattern=g))
    return out


def figure(path, H, measured, shear, anisotropic=None) -> None:
    """The fits of Patir & Cheng (phi_x against H for each gamma; phi_y is phi_x of
    1/gamma; Phi_s; the mean gap) and the measured factors (isotropic; the anisotropic
    cells' means as markers on the first panel), to ``path``."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(13, 4))
    names = {1 / 9: "1/9", 1 / 6: "1/6", 1 / 3: "1/3", 1.0: "1", 3.0: "3", 6.0: "6", 9.0: "9"}
    for k, g in enumerate(PATTERNS):
        least = PRESSURE_FIT[g][2]
        h = np.linspace(least, 6.0, 200)
        ax[0].plot(h, pressure_flow_factor(h, g), color=f"C{k}", label=f"gamma {names[g]}")
        h = np.linspace(0.5, 6.0, 200)
        ax[1].plot(h, shear_flow_factor(h, g), color=f"C{k}", label=f"gamma {names[g]}")
        if anisotropic and g in anisotropic:
            Hg, phi, shg = anisotropic[g]
            ax[0].plot(Hg, phi.mean(axis=1), "o", color=f"C{k}", ms=4)
            ax[1].plot(Hg, shg.mean(axis=1), "o", color=f"C{k}", ms=4)
        elif g == 1.0:
            ax[1].plot(H, shear.mean(axis=1), "o", color=f"C{k}", ms=4)
    ax[0].set(xlabel="H = h / sigma", ylabel="phi_x (phi_y = phi_x of 1/gamma)",
              title="pressure flow factor: fits, and cells (dots)")
    ax[1].set(xlabel="H = h / sigma", ylabel="Phi_s  (phi_s = (V_r1 - V_r2) Phi_s)",
              title="shear flow factor: fits, and cells (dots)")
    h = np.linspace(0.5, 6.0, 200)
    ax[2].plot(h, pressure_flow_factor(h, 1.0), "k", label="fit, gamma = 1")
    ax[2].plot(h[h > 1.2], 1 - 1.5 / h[h > 1.2] ** 2, "k:", label="1 - 3/(2 H^2)")
    ax[2].errorbar(H, measured.mean(axis=1), yerr=measured.std(axis=1, ddof=1), fmt="o",
                   color="C3", capsize=3, label="rough cells (mean, std)")
    ax[2].plot(h, mean_gap(h)[0] / h, "C0--", label="E(h_T) / h")
    ax[2].set(xlabel="H = h / sigma", ylim=(0.0, 1.6),
              title="isotropic: the fit against rough cells")
    for a in ax:
        a.grid(alpha=0.3)
        a.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--figure", help="also draw the factors and the measured ones here")
    args = parser.parse_args(argv)
    print("exact checks of the cell solve (H = 1, a = 0.5, ridges of period 1):")
    print("| cells per ridge | phi_x across: measured | exact | phi_x along: measured | "
          "exact | Phi_s across: measured | exact |")
    print("|---|---|---|---|---|---|---|")
    a, sig = 0.5, 0.5 / math.sqrt(2.0)
    for m in (8, 16, 32, 64):
        across, shear = cell_factors(lambda x, y: 1.0 + a * np.cos(2 * np.pi * x), 1.0,
                                     (2.0, 1.0), (2 * m, 4), sig)
        along = cell_flow_factor(lambda x, y: 1.0 + a * np.cos(2 * np.pi * y), 1.0,
                                 (1.0, 1.0), (4, m))
        print(f"| {m} | {across:.6f} | {transverse_exact(a):.6f} | {along:.6f} | "
              f"{longitudinal_exact(a):.6f} | {shear:.6f} | "
              f"{transverse_shear_exact(1.0, a):.6f} |")
    print("\nmesh convergence, one isotropic surface (seed 0, cell 8 x 8 correlation "
          "lengths), H = 1.5:")
    sample = gaussian_surface(8.0, 1.0, 0)
    for per in (8, 16, 32):
        n = 8 * per
        p, sh = cell_factors(_cells_gap(sample(n), 8.0, 1.5), 1.5, (8.0, 8.0), (n, n))
        print(f"  {per} cells per correlation length: phi_x = {p:.5f}, Phi_s = {sh:.5f}")
    H = np.array([1.0, 1.5, 2.0, 3.0, 4.0, 6.0])
    seeds = range(8)
    t = time.perf_counter()
    phi, shear = measured_factors(H, seeds, length=32.0, per_correlation=8)
    print(f"\n{len(seeds)} isotropic surfaces of 32 x 32 correlation lengths, 8 cells each "
          f"({time.perf_counter() - t:.0f} s):")
    print("| H | phi_x of the cells: mean (std of the surfaces) | standard error | "
          "Patir & Cheng's fit | fit - measured | 1 - 3/(2 H^2) | Phi_s of the cells | "
          "fit | fit - measured |")
    print("|---|---|---|---|---|---|---|---|---|")
    for h, row, srow in zip(H, phi, shear):
        m, sd = row.mean(), row.std(ddof=1)
        f, fs, ms = (float(pressure_flow_factor(h, 1.0)), float(shear_flow_factor(h, 1.0)),
                     srow.mean())
        print(f"| {h:g} | {m:.3f} ({sd:.3f}) | {sd / math.sqrt(len(row)):.3f} | {f:.3f} | "
              f"{100 * (f - m) / m:+.1f} % | {1 - 1.5 / h**2:.3f} | {ms:.3f} "
              f"({srow.std(ddof=1):.3f}) | {fs:.3f} | {100 * (fs - ms) / ms:+.1f} % |")
    t = time.perf_counter()
    aniso = anisotropic_factors()
    print(f"\nanisotropic cells: 4 surfaces of 16 x 16 correlation lengths (across the flow; "
          f"gamma times as long along it), 8 cells each ({time.perf_counter() - t:.0f} s):")
    print("| gamma | H | phi_x of the cells: mean (std) | fit | fit - measured | "
          "Phi_s of the cells | fit | fit - measured |")
    print("|---|---|---|---|---|---|---|---|")
    for g, (Hg, values, svalues) in aniso.items():
        for h, row, srow in zip(Hg, values, svalues):
            m, ms = row.mean(), srow.mean()
            f, fs = float(pressure_flow_factor(h, g)), float(shear_flow_factor(h, g))
            print(f"| {g:.3g} | {h:g} | {m:.3f} ({row.std(ddof=1):.3f}) | {f:.3f} | "
                  f"{100 * (f - m) / m:+.1f} % | {ms:.3f} ({srow.std(ddof=1):.3f}) | "
                  f"{fs:.3f} | {100 * (fs - ms) / ms:+.1f} % |")
    if args.figure:
        figure(args.figure, H, phi, shear, aniso)


if __name__ == "__main__":
    main()
