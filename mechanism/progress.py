"""Progress of a long run on stderr: a bar on a terminal, a line every few seconds
otherwise (logs, CI, ``make demo`` piped), nothing when switched off."""
from __future__ import annotations

import sys
import time


class Progress:
    """``enabled``: None - a bar on a terminal, else a line every ``every`` seconds;
    True - the bar; False - silent."""

    def __init__(self, total: float, label: str = "", enabled: bool | None = None, stream=None,
                 every: float = 5.0):
        self.stream = stream or sys.stderr
        tty = self.stream.isatty()
        self.mode = ("bar" if enabled or (enabled is None and tty) else
                     "lines" if enabled is None else "off")
        self.total, self.label = float(total), label
        self.every = every if self.mode == "lines" else 0.2
        self.value = 0.0
        self._shown = -float("inf")
        self._start = time.perf_counter()

    def _text(self, now):
        frac = min(max(self.value / self.total, 0.0), 1.0) if self.total > 0 else 1.0
        elapsed = f"{now - self._start:6.1f} s"
        if self.mode == "bar":
            return f"\r{self.label} [{'#' * int(30 * frac):<30}] {100 * frac:5.1f}%  {elapsed}"
        return f"{self.label}: {100 * frac:5.1f}%  {elapsed}\n"

    def update(self, value: float):
        self.value = value
        if self.mode == "off":
            return
        now = time.perf_counter()
        if now - self._shown < self.every:
            return
        self._shown = now
        self.stream.write(self._text(now))
        self.stream.flush()

    def close(self, note: str = "", complete: bool = True):
        """Show the final state: the whole total when ``complete``, else where it stopped."""
        if complete:
            self.value = self.total
        if self.mode == "off":
            return
        text = self._text(time.perf_counter())
        self.stream.write((text.rstrip("\n") + f" {note}\n") if note else text.rstrip("\n") + "\n")
        self.stream.flush()
