"""What a bearing designer asks first, from any film model of :mod:`bearingfem.models`.

equilibrium under a load -> dynamic coefficients (K, C) at that state -> stability of a
rigid rotor on them (Lund), with the dimensionless groups of the design charts.
"""
from .chart import ChartPoint, DesignChart, chart_grading, design_chart
from .coefficients import DynamicCoefficients, coefficients
from .equilibrium import Equilibrium, equilibrium
from .groups import (flow_variable, friction_variable, load_from_sommerfeld,
                     petroff_friction, sommerfeld_number)
from .stability import (Orbit, Stability, ThresholdSpeed, Verdict, journal_orbit,
                        lund_stability, threshold_speed)

__all__ = ["equilibrium", "Equilibrium", "coefficients", "DynamicCoefficients",
           "lund_stability", "Stability", "Verdict", "threshold_speed", "ThresholdSpeed",
           "journal_orbit", "Orbit", "sommerfeld_number", "load_from_sommerfeld",
           "friction_variable", "flow_variable", "petroff_friction", "design_chart",
           "DesignChart", "ChartPoint", "chart_grading"]
