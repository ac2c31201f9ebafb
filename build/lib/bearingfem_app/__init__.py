"""The application layer: the ``bearingfem`` command line and the Dask sweep runner.

It stands above both libraries - :mod:`bearingfem` (films, designer's numbers) and
:mod:`mechanism` (the slider-crank that carries them) - and nothing below imports it.
"""
