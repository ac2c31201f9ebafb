"""Finite elements on the unwrapped film (scikit-fem): mesh -> assembly -> Reynolds solve.

``mesh`` builds the periodic (theta, z/R) mesh, ``assembly`` the state-independent matrices
K_k and loads, ``reynolds`` the solve (:func:`solve_reynolds`, via :mod:`bearingfem.solvers`)
with nested iteration from ``multilevel``; ``sensitivity`` differentiates the discrete
force; ``force_table`` tabulates it for time integration.
"""
