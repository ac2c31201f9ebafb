"""Lund & Thomsen's (1978) two-axial-groove bearing: their coefficients and ours.

Reference: J. W. Lund and K. K. Thomsen, "A calculation method and data for the dynamic
coefficients of oil-lubricated journal bearings", in *Topics in Fluid Film Bearing and Rotor
Bearing System Design and Optimization*, ASME (1978), pp. 1-28: the cylindrical bearing with
two axial grooves, each 20 deg wide, at the horizontal split (two 160 deg pads), the load
vertical (through the middle of the lower pad); isoviscous, laminar, Reynolds' (Swift-Stieber)
condition at the film's rupture. Rows as transcribed (10 of them, five at L/D 0.5 and five at
L/D 1; their L/D 1 row at S = 0.358 prints a Kyy off its column's trend and is left out).

Dimensionless groups (the same as Someya's): S = mu N L D (R/c)^2 / W, N in rev/s; eps =
e/c; phi the attitude angle from the load line [deg]; K_ij c / W and B_ij c omega / W in the
load frame (x along the load, y turned +90 deg with the rotation). The table gives Bxx, Bxy
and Byy (their damping is symmetric, Byx = Bxy).

What it shows (``python -m studies.lund_thomsen -o out``, table + CSV + figure):

- eps, attitude, K and B agree with the table to about 1 % of each matrix's largest entry
  (largest gaps printed by the study), on meshes whose nodes fall on the grooves' edges.
- Their stiffness is ours with the grooves *fixed in the bearing* (``kc.K``, the force's
  exact Jacobian). The turning-grooves form ``kc.K - kc.K_groove_shift``, which Someya's data
  book matches (studies/someya.py), misses theirs by up to ~180 % of an entry (Kyx at light
  load). Published tables differ in this convention: check which one before comparing.
"""
from __future__ import annotations

import math

from .published_coefficients import (LOAD_DIRECTION, K_NAMES, OMEGA, Published, axial_grooves,
                                     bearing, case, largest_entry_error)

__all__ = ["TABLE", "GROOVES", "OMEGA", "LOAD_DIRECTION", "LUND_THOMSEN", "bearing", "table_case",
           "largest_entry_error"]

#: L/D -> rows (S, eps, phi [deg], Kxx, Kxy, Kyx, Kyy, Bxx, Bxy, Byy), as published
TABLE = {
    0.5: [(1.656, 0.244, 65.85, 1.69, 5.06, -2.20, 1.95, 9.93, 2.15, 4.80),
          (0.917, 0.372, 57.45, 2.12, 4.01, -1.30, 1.85, 7.70, 2.06, 3.23),
          (0.580, 0.477, 51.01, 2.67, 3.70, -0.78, 1.75, 6.96, 1.94, 2.40),
          (0.379, 0.570, 45.43, 3.33, 3.64, -0.43, 1.68, 6.76, 1.87, 1.89),
          (0.244, 0.655, 40.25, 4.21, 3.74, -0.13, 1.64, 6.87, 1.82, 1.54)],
    1.0: [(0.991, 0.150, 70.58, 1.56, 7.29, -2.16, 1.52, 14.66, 1.58, 4.49),
          (0.635, 0.224, 63.54, 1.62, 5.33, -1.57, 1.56, 10.80, 1.70, 3.41),
          (0.235, 0.460, 49.27, 2.19, 3.57, -0.80, 1.55, 7.36, 1.89, 2.19),
          (0.159, 0.559, 44.33, 2.73, 3.36, -0.48, 1.48, 6.94, 1.78, 1.74),
          (0.108, 0.650, 39.72, 3.45, 3.34, -0.23, 1.44, 6.89, 1.72, 1.43)],
}
B_NAMES = ("Bxx", "Bxy", "Byy")


def _line(r) -> str:
    return (f"L/D {r['ld']:<4g} S {r['S']:<6g} eps {r['eps']:.4f} ({r['eps_table']:.3f})"
            f"  phi {r['phi']:6.2f} ({r['phi_table']:.2f})  K {100 * r['K_error']:5.2f} %"
            f"  B {100 * r['B_error']:5.2f} %  | turning K {100 * r['K_turning_error']:6.1f} %")


GROOVES = axial_grooves(math.radians(20.0))

LUND_THOMSEN = Published(
    name="lund_thomsen", source="Lund & Thomsen (1978)", table=TABLE,
    grooves=GROOVES, b_names=B_NAMES, tag="table", other="turning",
    errors=True, line=_line,
    header="ours (table); K, B: largest entry error; turning K: kc.K - kc.K_groove_shift",
    convergence_rows=(0, 4), convergence_column=0, panels=K_NAMES + B_NAMES + ("phi",),
    title=("Two-axial-groove bearing (20 deg grooves): K c / W, B c omega / W, load frame;"
           " solid: grooves fixed in the bearing (kc.K)"))


def table_case(ld: float, sommerfeld: float, n_theta: int = 144,
               element: str = "P1") -> dict:
    """eps, attitude [deg], dimensionless K (grooves fixed in the bearing), K of grooves
    turning with the line of centres, and B (Bxx, Bxy, Byy), load frame, at ``sommerfeld``."""
    return case(ld, sommerfeld, n_theta, LUND_THOMSEN.grooves, element, B_NAMES)


def main(argv=None):
    LUND_THOMSEN.main(argv, __doc__.splitlines()[0])


if __name__ == "__main__":
    main()
