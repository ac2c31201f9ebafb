"""Raimondi & Boyd (1958): the published finite-bearing table and our film's numbers for it.

Reference: A. A. Raimondi and J. Boyd, "A solution for the finite journal bearing and its
application to analysis and design, Parts I-III", ASLE Transactions 1(1), 159-209 (1958);
full (360 deg) bearing with the Reynolds (Swift-Stieber) condition, as tabulated in
Shigley's Mechanical Engineering Design (Budynas & Nisbett), Table 12-4.
Columns: eps, S = (R/c)^2 mu N / P, attitude angle phi [deg], friction variable (R/c) f,
flow variable Q/(R c N L), side-flow ratio Qs/Q; N in rev/s, P = W / (L D).

Their film starts at the maximum thickness: a supply line at ambient pressure there
(supply_angle = gamma + pi). Cavitated zones carry full Couette shear (cavitated_shear="full"),
which is what reproduces their friction variable.
"""
import numpy as np

from bearingfem import JournalState, solve_reynolds
from bearingfem.bearing import seed_bearing

TABLE = {
    1.0: [(0.1, 1.33, 79.5, 26.4, 3.37, 0.150), (0.2, 0.631, 74.02, 12.8, 3.59, 0.280),
          (0.4, 0.264, 63.10, 5.79, 3.99, 0.497), (0.6, 0.121, 50.58, 3.22, 4.33, 0.680),
          (0.8, 0.0446, 36.24, 1.70, 4.62, 0.842), (0.9, 0.0188, 26.45, 1.05, 4.74, 0.919),
          (0.97, 0.00474, 15.47, 0.514, 4.82, 0.973)],
    0.5: [(0.1, 4.31, 81.62, 85.6, 3.43, 0.173), (0.2, 2.03, 74.94, 40.9, 3.72, 0.318),
          (0.4, 0.779, 61.45, 17.0, 4.29, 0.552), (0.6, 0.319, 48.14, 8.10, 4.85, 0.730),
          (0.8, 0.0923, 33.31, 3.26, 5.41, 0.874), (0.9, 0.0313, 23.66, 1.60, 5.69, 0.939),
          (0.97, 0.00609, 13.75, 0.610, 5.88, 0.980)],
    0.25: [(0.1, 16.2, 82.31, 322.0, 3.45, 0.180), (0.2, 7.57, 75.18, 153.0, 3.76, 0.330),
           (0.4, 2.83, 60.86, 61.1, 4.37, 0.567), (0.6, 1.07, 46.72, 26.7, 4.99, 0.746),
           (0.8, 0.261, 31.04, 8.80, 5.60, 0.884), (0.9, 0.0736, 21.85, 3.50, 5.91, 0.945),
           (0.97, 0.0101, 12.22, 0.922, 6.12, 0.984)],
}
CASES = [(ld, *row) for ld, rows in TABLE.items() for row in rows]
OMEGA = 250.0

#: At eps = 0.97, L/D = 1/4 both our FE and FV solutions converge (to 480x40 and 960x80)
#: to S 3.0-3.1 % above the table: the 1958 grids were coarse at extreme eccentricity.
#: That point alone is held to 3.5 %.
LOOSE = {(0.25, 0.97): 0.035}


def bearing_numbers(ld, eps, periodic=False, n_theta=120, n_z=20):
    b = seed_bearing(ld)
    s = JournalState(eps, omega=OMEGA)
    sol = solve_reynolds(b, s, n_theta, n_z, "P2", "reynolds",
                         supply_angle=None if periodic else s.gamma + np.pi)
    fr, ft = sol.force_local
    W = np.hypot(fr, ft)
    N = OMEGA / (2 * np.pi)
    S = (b.radius / b.clearance) ** 2 * b.viscosity * N / (W / (b.length * b.diameter))
    phi = np.degrees(np.arctan2(ft, -fr))
    fvar = sol.friction_force / W * b.radius / b.clearance
    qs = sol.side_leakage / (b.radius * b.clearance * N * b.length)
    return S, phi, fvar, qs


