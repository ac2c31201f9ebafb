"""The transient grooved JFO film on the mesh fixed in the bearing
(:mod:`bearingfem.fe.jfo_grooved`): :class:`~bearingfem.fe.jfo.JFOFilm`'s backward-Euler
steps of the content, with the balance's data of each new journal angle shifted onto the
one mesh and operator instead of a mesh and operator built per angle. The volumes are
fixed in the bearing on both meshes, so nothing is carried between steps either way; the
two films agree to the solver's tolerance (tests/test_jfo_grooved.py)."""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..bearing import Bearing, JournalState
from ..solution import FilmSolution
from .grooved import groove_operator_for, grooved_operator
from .jfo import JFOFilm
from .jfo_balance import FilmAdvance, boundary_values, kept_set_pressure
from .jfo_grooved import grooved_films, grooved_jfo_force_of, grooved_jfo_solution

__all__ = ["GroovedJFOFilm"]


class GroovedJFOFilm(JFOFilm):
    """A transient JFO film with axial grooves (flooded or starved) on the bearing-fixed
    mesh, half length, rigid journal: the parameters of
    :class:`~bearingfem.fe.jfo.JFOFilm` less fields and tilt (``grooves`` required)."""

    def __init__(self, bearing: Bearing, state: JournalState, n_theta: int = 96,
                 n_z: int = 16, *, grooves, fraction=1.0, ambient_pressure: float = 0.0,
                 time: float = 0.0):
        if not grooves:
            raise ValueError("grooves must hold at least one Groove (the bearing-fixed mesh "
                             "is the grooves')")
        super().__init__(bearing, state, n_theta, n_z, grooves=grooves, fraction=fraction,
                         ambient_pressure=ambient_pressure, time=time)
        op = groove_operator_for(bearing, n_theta, n_z, "P1", self.grooves).op
        self._operator = lambda s: op
        # the same nodes in the bearing as the moving mesh's; the content from this mesh
        self.content = self.fraction * self._full_content(op, state, self.time)

    def _films(self, state: JournalState, time: float):
        return grooved_films(state)

    def _solution(self, state: JournalState, a: FilmAdvance, dt: float) -> FilmSolution:
        return grooved_jfo_solution(self.bearing, state, a.op, a.solve)

    def instant(self, state: JournalState, warm: np.ndarray | None = None,
                time: float | None = None):
        """As :meth:`JFOFilm.instant`: the Reynolds film of this instant's motion on the
        volumes full at the kept step, the others cavities at zero pressure."""
        op = self._operator(state)
        gop = grooved_operator(op)
        mesh = op.mesh
        P, _ = boundary_values(self.bearing, mesh, self.grooves, self.ambient_pressure)
        K = sp.csr_matrix((gop.values(state.eps, state.gamma), op.indices, op.indptr),
                          shape=op.shape)
        load = gop.load(state.eps, state.eps_dot, state.wedge_speed, state.gamma)
        P, cav = kept_set_pressure(K, load, P, mesh, self.cavitated, warm)
        return grooved_jfo_force_of(self.bearing, op, P, state.gamma), cav
