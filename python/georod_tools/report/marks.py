"""What an animation marks on the rod besides the rod itself: the scene's items, each where it is in
each frame. One function per kind of item reads the scene's entries of that kind and says, for
every frame, the item's station (a fraction of the arc length; NaN while it is off the rod):

- supports (``[[support]]``) and springs (``[[spring]]``) at their stations;
- point loads (``[[load]]`` of kind ``point``, and ``moment``) at theirs;
- moving loads (``kind = "moving"``) at ``s = speed (t - enter)`` in each frame, absent before they
  enter and after they leave.

A further kind (stops, the members of a frame) is one more function in :data:`KINDS` and a style in
:data:`STYLES`. :func:`positions` places any mark on the rod's shape in each frame.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

#: A scene value: a number, or a parameter's name (optionally with a sign), as scene files write
#: their slots; resolved to the value the FMU ran with.
Resolve = Callable[[Any], float]
Scene = dict[str, Any]


@dataclass(frozen=True)
class Style:
    marker: str
    colour: str
    legend: str
    #: Whether each mark carries its name beside it.
    named: bool = True


@dataclass
class Mark:
    kind: str
    name: str
    #: Per frame, the station (fraction of the arc length in [0, 1]); NaN while off the rod.
    stations: np.ndarray


STYLES: dict[str, Style] = {
    "support": Style("^", "k", "supports"),
    "spring": Style("s", "tab:green", "springs"),
    "point load": Style("v", "tab:red", "point loads"),
    "moving load": Style("v", "tab:purple", "moving loads"),
}


def fixed(kind: str, entries: list[dict[str, Any]], times: np.ndarray) -> list[Mark]:
    """Items that stay at their station `at` in every frame."""
    return [Mark(kind, str(e["name"]), np.full(len(times), float(e["at"]))) for e in entries]


def supports(scene: Scene, times: np.ndarray, value: Resolve, length: float) -> list[Mark]:
    return fixed("support", scene.get("support", []), times)


def springs(scene: Scene, times: np.ndarray, value: Resolve, length: float) -> list[Mark]:
    return fixed("spring", scene.get("spring", []), times)


def point_loads(scene: Scene, times: np.ndarray, value: Resolve, length: float) -> list[Mark]:
    loads = [ld for ld in scene.get("load", []) if ld.get("kind") in ("point", "moment")]
    return fixed("point load", loads, times)


def moving_loads(scene: Scene, times: np.ndarray, value: Resolve, length: float) -> list[Mark]:
    """Each moving load at ``speed (t - enter) / length`` in each frame; NaN off the rod."""
    out = []
    for ld in (ld for ld in scene.get("load", []) if ld.get("kind") == "moving"):
        speed, enter = value(ld["speed"]), value(ld.get("enter", 0.0))
        stations = speed * (times - enter) / length
        stations[(stations < 0.0) | (stations > 1.0)] = math.nan
        out.append(Mark("moving load", str(ld["name"]), stations))
    return out


#: Every kind of item an animation marks, in drawing order.
KINDS: tuple[Callable[[Scene, np.ndarray, Resolve, float], list[Mark]], ...] = (
    supports,
    springs,
    point_loads,
    moving_loads,
)


def arc_length(scene: Scene, value: Resolve) -> float:
    """The rod's arc length: the span of a straight rod, the circular arc over span and rise."""
    span = value("L")
    if scene.get("geometry", {}).get("shape") != "arc":
        return span
    rise = value("H")
    radius = (0.25 * span * span + rise * rise) / (2.0 * rise)
    return 2.0 * radius * math.asin(0.5 * span / radius)


def marks(scene: Scene, times: np.ndarray, value: Resolve) -> list[Mark]:
    """Every item of the scene that an animation marks, kind by kind."""
    length = arc_length(scene, value)
    return [m for kind in KINDS for m in kind(scene, times, value, length)]


def positions(mark: Mark, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Where `mark` is in each frame, ``(frames, 2)`` (NaN while off the rod): its station
    interpolated between the two shape samples around it (equally spaced in arc length)."""
    s = np.linspace(0.0, 1.0, x.shape[1])
    out = np.full((len(mark.stations), 2), math.nan)
    for k, station in enumerate(mark.stations):
        if not math.isnan(station):
            out[k] = np.interp(station, s, x[k]), np.interp(station, s, y[k])
    return out


def resolver(start: dict[str, float]) -> Resolve:
    """Scene values resolved against the values the FMU ran with (name -> value)."""

    def value(slot: Any) -> float:
        if isinstance(slot, int | float):
            return float(slot)
        text = str(slot).strip()
        sign = -1.0 if text.startswith("-") else 1.0
        name = text.lstrip("+-").strip()
        if name not in start:
            raise ValueError(f"the scene's value {slot!r} names no parameter of the FMU")
        return sign * start[name]

    return value
