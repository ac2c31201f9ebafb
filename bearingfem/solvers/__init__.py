"""Complementarity and linear solvers shared by the discretisations: the Swift-Stieber
problem by active set or projected SOR (``cavitation``), inactive-block solves that reuse
factors (``blocksolve``), SPD solves on stale factors (``linsolve``)."""
