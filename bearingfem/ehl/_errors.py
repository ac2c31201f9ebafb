"""The error an EHL solve raises when it does not converge."""
try:  # the project's shared error type, once bearingfem.errors exists
    from ..errors import ConvergenceError
except ImportError:  # pragma: no cover - until then, the same contract locally
    class ConvergenceError(RuntimeError):
        """A solve that did not converge (names the solve, iterations and residual)."""

__all__ = ["ConvergenceError"]
