"""The library's caches in one register, so that one call empties them all.

Meshes, operators, assembly tables, compliances and force tables are built once per key and
kept (``functools.lru_cache``). Every such cache is declared with :func:`cached`, which
registers it here; :func:`clear_caches` (``bearingfem.clear_caches``) empties every
registered cache, so a "cold" timing means the same thing wherever it is measured. Caches
of modules not yet imported are not registered yet, and hold nothing. Force tables also
kept on disk (:mod:`bearingfem.fe.force_table`) stay there: only their loaded copies go.
"""
from __future__ import annotations

from functools import lru_cache

__all__ = ["cached", "kept", "clear_caches", "registered"]

_REGISTER: list = []
_STORES: list = []     # other mappings kept between calls (e.g. the accuracy memo)


def cached(maxsize: int):
    """``functools.lru_cache(maxsize=maxsize)``, registered for :func:`clear_caches`."""
    def register(function):
        memo = lru_cache(maxsize=maxsize)(function)
        _REGISTER.append(memo)
        return memo
    return register


def kept(store):
    """Register ``store`` (a mapping kept between calls, with ``clear()``) for
    :func:`clear_caches`; returns it."""
    _STORES.append(store)
    return store


def registered() -> tuple:
    """The registered caches (the ``lru_cache`` wrappers), in the order they were declared."""
    return tuple(_REGISTER)


def clear_caches() -> None:
    """Empty every registered cache of the library (the start of every cold timing)."""
    for memo in _REGISTER:
        memo.cache_clear()
    for store in _STORES:
        store.clear()
