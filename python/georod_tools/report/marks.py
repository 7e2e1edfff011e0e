"""What an animation marks on the structure besides its shape: the scene's items, each where it is
in each frame. One function per kind of item reads the scene's entries of that kind and says, for
every frame, the item's place (:mod:`georod_tools.report.places`: a piece, the rod or a member,
and a station along it; the station NaN while the item is off the structure):

- supports (``[[support]]``) and springs (``[[spring]]``) at their places;
- point loads (``[[load]]`` of kind ``point``, and ``moment``) at theirs;
- moving loads (``kind = "moving"``) at the arc length ``speed (t - enter)`` along their route
  (the rod, a member, or a path of members), absent before they enter and after they leave;
- stops (``[[stop]]``) where they stand in space: the reference position of their node moved
  by the gap towards their side along their dof (the point the node touches);
- on a frame, hinged member ends (a pin drawn at the joint) and links (a dashed line between
  their two ends).

A further kind is one more function in :data:`KINDS` and a style in :data:`STYLES`.
:func:`positions` places any mark in each frame.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from georod_tools.report.places import Layout

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
    #: Whether the marker is filled (a hinge is an open circle).
    filled: bool = True
    #: Whether the marks come in pairs joined by a dashed line (a link's two ends).
    paired: bool = False


@dataclass
class Mark:
    kind: str
    name: str
    #: Per frame, the station (fraction of the piece's arc length in [0, 1]); NaN while off.
    stations: np.ndarray
    #: Per frame, the piece the mark is on (the rod: 0; a frame: the member's index).
    pieces: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    #: A point fixed in space where the mark stands in every frame instead (a stop's surface);
    #: its place is then the node it faces.
    anchor: tuple[float, float] | None = None

    def __post_init__(self) -> None:
        if len(self.pieces) != len(self.stations):
            self.pieces = np.zeros(len(self.stations), dtype=int)


STYLES: dict[str, Style] = {
    "support": Style("^", "k", "supports"),
    "spring": Style("s", "tab:green", "springs"),
    "point load": Style("v", "tab:red", "point loads"),
    "moving load": Style("v", "tab:purple", "moving loads"),
    "stop": Style("D", "tab:brown", "stops"),
    "hinge": Style("o", "k", "hinges", named=False, filled=False),
    "link": Style("o", "tab:olive", "links", paired=True),
}


def fixed(
    kind: str, entries: list[dict[str, Any]], times: np.ndarray, layout: Layout
) -> list[Mark]:
    """Items that stay at their place in every frame."""
    out = []
    for e in entries:
        piece, station = layout.place(e)
        frames = len(times)
        out.append(
            Mark(kind, str(e["name"]), np.full(frames, station), np.full(frames, piece, dtype=int))
        )
    return out


def supports(scene: Scene, times: np.ndarray, value: Resolve, layout: Layout) -> list[Mark]:
    return fixed("support", scene.get("support", []), times, layout)


def springs(scene: Scene, times: np.ndarray, value: Resolve, layout: Layout) -> list[Mark]:
    return fixed("spring", scene.get("spring", []), times, layout)


def point_loads(scene: Scene, times: np.ndarray, value: Resolve, layout: Layout) -> list[Mark]:
    loads = [ld for ld in scene.get("load", []) if ld.get("kind") in ("point", "moment")]
    return fixed("point load", loads, times, layout)


def moving_loads(scene: Scene, times: np.ndarray, value: Resolve, layout: Layout) -> list[Mark]:
    """Each moving load at the arc length ``speed (t - enter)`` along its route; NaN off it."""
    out = []
    for ld in (ld for ld in scene.get("load", []) if ld.get("kind") == "moving"):
        speed, enter = value(ld["speed"]), value(ld.get("enter", 0.0))
        pieces, stations = layout.along(layout.route(ld), speed * (times - enter))
        out.append(Mark("moving load", str(ld["name"]), stations, pieces))
    return out


def stops(scene: Scene, times: np.ndarray, value: Resolve, layout: Layout) -> list[Mark]:
    """Each stop at the point its node touches: the node's reference position moved by `gap`
    along e1 (``dof = "u1"``) or e2 towards `side`."""
    entries = scene.get("stop", [])
    out = []
    for m, e in zip(fixed("stop", entries, times, layout), entries, strict=True):
        x, y = layout.pieces[int(m.pieces[0])].reference(float(m.stations[0]))
        reach = (1.0 if e["side"] == "+" else -1.0) * value(e.get("gap", 0.0))
        m.anchor = (x + reach, y) if e["dof"] == "u1" else (x, y + reach)
        out.append(m)
    return out


def hinges(scene: Scene, times: np.ndarray, value: Resolve, layout: Layout) -> list[Mark]:
    """A frame's hinged member ends, at their joints."""
    ends = [
        {"name": f"{p.name}_{end}", "member": p.name, "at": 0.0 if end == "start" else 1.0}
        for p in layout.pieces
        for end in p.hinges
    ]
    return fixed("hinge", ends, times, layout)


def links(scene: Scene, times: np.ndarray, value: Resolve, layout: Layout) -> list[Mark]:
    """A frame's links: two marks each, its `from` end and its `to` end."""
    ends = []
    for link in scene.get("link", []):
        for end in ("from", "to"):
            where = link[end]
            entry = dict(where) if isinstance(where, dict) else {"joint": where}
            ends.append({**entry, "name": str(link["name"])})
    return fixed("link", ends, times, layout)


#: Every kind of item an animation marks, in drawing order.
KINDS: tuple[Callable[[Scene, np.ndarray, Resolve, Layout], list[Mark]], ...] = (
    supports,
    springs,
    point_loads,
    moving_loads,
    stops,
    hinges,
    links,
)


def marks(scene: Scene, times: np.ndarray, value: Resolve) -> list[Mark]:
    """Every item of the scene that an animation marks, kind by kind."""
    layout = Layout.of(scene, value)
    return [m for kind in KINDS for m in kind(scene, times, value, layout)]


def positions(mark: Mark, x: np.ndarray, y: np.ndarray, pieces: int = 1) -> np.ndarray:
    """Where `mark` is in each frame, ``(frames, 2)``: its anchor, or :func:`on_shape`."""
    if mark.anchor is not None:
        return np.tile(np.array(mark.anchor, dtype=float), (len(mark.stations), 1))
    return on_shape(mark, x, y, pieces)


def on_shape(mark: Mark, x: np.ndarray, y: np.ndarray, pieces: int = 1) -> np.ndarray:
    """Where the place of `mark` is in each frame, ``(frames, 2)`` (NaN while off the
    structure): its station interpolated between the two shape samples of its piece around it
    (`x`, `y` hold `pieces` pieces' samples one after the other, each equally spaced in arc
    length)."""
    points = x.shape[1] // pieces
    s = np.linspace(0.0, 1.0, points)
    out = np.full((len(mark.stations), 2), math.nan)
    for k, (station, piece) in enumerate(zip(mark.stations, mark.pieces, strict=True)):
        if not math.isnan(station):
            cut = slice(piece * points, (piece + 1) * points)
            out[k] = np.interp(station, s, x[k, cut]), np.interp(station, s, y[k, cut])
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
