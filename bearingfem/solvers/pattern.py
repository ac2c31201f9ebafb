"""Sparse matrices on a fixed pattern: a film's stiffness at a new state is new values
on the same rows and columns.

scipy's ``csr_matrix((data, indices, indptr))`` checks the index arrays and their dtype on
every call (~20 us, about a tenth of a small film's solve); a film builds tens of such
matrices per equilibrium on one pattern. :class:`Pattern` checks its arrays once and then
only puts values on them: the structure arrays are shared (never written), each matrix
gets its own value array.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

__all__ = ["Pattern"]


@dataclass(frozen=True, eq=False)
class Pattern:
    """A checked CSR sparsity pattern (sorted, no duplicates) of ``shape``."""

    indptr: np.ndarray
    indices: np.ndarray
    shape: tuple

    def __post_init__(self):
        template = sp.csr_matrix((np.zeros(len(self.indices)), self.indices, self.indptr),
                                 shape=self.shape)
        template.check_format(full_check=True)
        if not template.has_canonical_format:
            raise ValueError("indices must be sorted within each row, without duplicates")
        object.__setattr__(self, "_template", template)

    @property
    def nnz(self) -> int:
        return len(self.indices)

    def matrix(self, data: np.ndarray) -> sp.csr_matrix:
        """The CSR matrix with ``data`` (nnz,) on this pattern; ``data`` is taken as is
        (not copied), the structure arrays are the pattern's."""
        data = np.asarray(data)
        if data.shape != (self.nnz,):
            raise ValueError(f"data must have shape ({self.nnz},) (one value per entry of "
                             f"the pattern), got {data.shape}")
        m = sp.csr_matrix.__new__(sp.csr_matrix)
        # the checked template's attributes (shape, structure, format flags), new values
        m.__dict__.update(self._template.__dict__)
        m.data = data
        return m
