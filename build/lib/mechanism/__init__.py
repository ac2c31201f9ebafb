"""Slider-crank mechanism with a clearance joint (seed Eq. 1-5), driven by scene files.

The mechanism meets bearingfem only through :mod:`mechanism.lubrication` (film models by
name) and the joint-effect interface of :mod:`mechanism.effects`.
"""
from .parameters import Mechanism
from .result import SimulationResult, load_result
from .scene import Scene, load_scene, parse_scene
from .simulate import simulate

__all__ = ["Mechanism", "Scene", "SimulationResult", "load_scene", "parse_scene", "simulate",
           "load_result"]
