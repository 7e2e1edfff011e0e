"""What a case does before its forcing starts: push the rod with one of its inputs into another
equilibrium than the FMU's initial state, through FMU variables only.

:class:`Prelude`: with the harmonic forcing off (``F = 0``), an input force rises linearly to
`peak` (beyond a limit load the rod snaps through), is held while the snap's motion dies down,
falls linearly back to 0 (slowly, so the rod follows its new equilibrium branch quasi-statically)
and the rod is left to settle under its damping. Every phase lasts whole forcing periods, one
communication step each; the input follows its first derivative over each step (the FMU
interpolates inputs), so the force is a continuous piecewise-linear ramp. The forcing then starts
at a period boundary, with the phase it has at ``t = 0``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from georod_tools.fmu import Instance


@dataclass(frozen=True)
class Prelude:
    """Input `input` ramped to `peak` over `rise` periods, held `hold`, ramped to 0 over
    `release`, then `settle` periods at 0."""

    input: str
    peak: float
    rise: int = 10
    hold: int = 20
    release: int = 40
    settle: int = 80

    def __post_init__(self) -> None:
        if not math.isfinite(self.peak):
            raise ValueError(f"prelude peak = {self.peak} must be finite")
        if min(self.rise, self.hold, self.release, self.settle) < 0 or self.rise < 1:
            raise ValueError("prelude phases must be >= 0 periods (rise >= 1)")

    @property
    def periods(self) -> int:
        return self.rise + self.hold + self.release + self.settle

    def force(self, k: float) -> float:
        """The input at period `k` (piecewise linear; 0 after the release)."""
        if k <= self.rise:
            return self.peak * k / self.rise
        if k <= self.rise + self.hold:
            return self.peak
        if self.release and k <= self.rise + self.hold + self.release:
            return self.peak * (1.0 - (k - self.rise - self.hold) / self.release)
        return 0.0

    def run(self, inst: Instance, period: float) -> None:
        """Steps `inst` through the prelude from ``t = 0`` (one step per period), leaving the
        input at 0."""
        for k in range(self.periods):
            a, b = self.force(k), self.force(k + 1)
            inst.ramp(self.input, a, (b - a) / period)
            inst.step(k * period, period)
        inst.ramp(self.input, 0.0, 0.0)
