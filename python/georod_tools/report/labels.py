"""Axis labels that say what is shown and in which unit: ``w_mid [m]``, ``F [N/m]``.

Units come from the FMU's model description (every variable declares one); names an FMU does not
declare fall back to the units of the repository's scenes.
"""

from __future__ import annotations

from pathlib import Path

#: Units of the quantities the analyses plot, when no FMU says otherwise.
FALLBACK = {
    "t": "s",
    "w_mid": "m",
    "v_mid": "m/s",
    "F": "N",
    "Omega": "rad/s",
    "lyapunov_per_period": "1/period",
    "lyapunov": "1/s",
}


def unit(name: str, fmu: str | Path | None = None) -> str:
    """The unit of `name`: the FMU's declaration when `fmu` is a readable FMU that has one; the
    rate ``d(<output>)/dt`` of an output has the output's unit per second."""
    if name.startswith("d(") and name.endswith(")/dt"):
        return f"{unit(name[2:-4], fmu)}/s"
    if fmu is not None and Path(fmu).is_file():
        from georod_tools.fmu import FmuModel

        v = FmuModel.load(fmu).variables.get(name)
        if v is not None and v.unit:
            return v.unit
    return FALLBACK.get(name, "1")


def label(name: str, fmu: str | Path | None = None, what: str = "") -> str:
    """``w_mid [m]`` (with `what` in front when given: ``midspan deflection w_mid [m]``)."""
    text = f"{what} {name}" if what else name
    return f"{text} [{unit(name, fmu)}]"
