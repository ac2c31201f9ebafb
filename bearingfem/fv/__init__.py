"""Finite volumes: the independent reference discretisation of the same film
(:func:`fvm_reynolds`), solved by the same complementarity solvers."""
