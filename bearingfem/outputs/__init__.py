"""What leaves a solve: meshio export (``export``), off-screen renders (``render``), CSV
tables (``tables``), mesh-convergence studies (``convergence``) and the jitter of a sampled
output about a smooth curve (``signal``)."""
