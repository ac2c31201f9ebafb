"""The tabulated FE film ("fem-table"): forces interpolated in a table of FE solves."""
from __future__ import annotations

from ..fe.force_table import TABLE_DEFAULTS, force_table, table_force
from .registry import FilmModel, register

__all__ = ["ForceTableModel"]


class ForceTableModel(FilmModel):
    name = "fem-table"
    defaults = dict(TABLE_DEFAULTS)
    numeric = True
    disk_cache = True

    def _film_force(self, bearing, state, **options):
        return table_force(bearing, state, **options)

    def _run_notes(self, bearing, **options) -> dict:
        """The table's own measured mesh error (the table the run used: cached)."""
        return {"fem_table_mesh_error": force_table(bearing.length_ratio, **options).mesh_error}


register(ForceTableModel())
