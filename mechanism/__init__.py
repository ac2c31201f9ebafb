"""Slider-crank mechanism with a clearance joint (seed Eq. 1-5), driven by scene files.

Film forces come from bearingfem's registry (:mod:`bearingfem.models`), read through the
film-model contract (:mod:`bearingfem.contract`); the joint effects
(:mod:`mechanism.effects`) apply them, with contact and friction.
"""
from .parameters import Mechanism
from .result import SimulationResult, load_result
from .scene import Scene, load_scene, parse_scene
from .simulate import simulate

__all__ = ["Mechanism", "Scene", "SimulationResult", "load_scene", "parse_scene", "simulate",
           "load_result"]
