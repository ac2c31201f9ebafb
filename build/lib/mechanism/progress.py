"""A small progress bar over simulated time (stderr, only on a terminal unless forced)."""
from __future__ import annotations

import sys
import time


class Progress:
    def __init__(self, total: float, label: str = "", enabled: bool | None = None, stream=None):
        self.stream = stream or sys.stderr
        self.enabled = self.stream.isatty() if enabled is None else enabled
        self.total, self.label = float(total), label
        self._last = 0.0
        self._start = time.perf_counter()

    def update(self, value: float):
        if not self.enabled:
            return
        now = time.perf_counter()
        if now - self._last < 0.2:
            return
        self._last = now
        frac = min(max(value / self.total, 0.0), 1.0)
        bar = "#" * int(30 * frac)
        self.stream.write(f"\r{self.label} [{bar:<30}] {100 * frac:5.1f}%  {now - self._start:6.1f} s")
        self.stream.flush()

    def close(self, note: str = ""):
        if self.enabled:
            self._last = 0.0
            self.update(self.total if not note else self._last)
            self.stream.write(f" {note}\n")
            self.stream.flush()
