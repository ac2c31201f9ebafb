"""What leaves a solve: meshio export (``export``), off-screen renders (``render``), CSV
tables (``tables``) and mesh-convergence studies (``convergence``)."""
