"""Where a scene's items sit among its shape samples: a rod is one piece, a frame one piece per
member (``[[member]]``, in the order of the file, as its ``shape_x[i]`` are: ``points`` samples
per member, from its ``from`` joint to its ``to`` joint, equally spaced in arc length).

A place is ``(piece, station)``: the piece's index and a fraction of its arc length. An item names
it as the scene file does: ``at`` on a rod; ``joint = "B"`` (the end of the first member that
reaches B: every member there has that end at the same point), or ``member = "beam"`` with ``at``
on a frame. A moving load runs along a route of pieces (the rod, a ``member``, or a ``path`` of
members end to end) at its speed. Each piece knows its reference curve (a straight line or a
circular arc between its ends), from which an item fixed in space (a stop) is placed.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

Resolve = Callable[[Any], float]
Scene = dict[str, Any]


@dataclass(frozen=True)
class Piece:
    """A rod, or one member of a frame."""

    name: str
    #: The joints at its start and end (empty on a rod).
    start: str
    end: str
    length: float
    #: Its hinged ends, of "start" and "end".
    hinges: tuple[str, ...] = ()
    #: Its reference curve: from `head` to `tail`, a circular arc of `rise` to the left of the
    #: chord (a straight line when 0).
    head: tuple[float, float] = (0.0, 0.0)
    tail: tuple[float, float] = (0.0, 0.0)
    rise: float = 0.0

    def reference(self, station: float) -> tuple[float, float]:
        """The point at `station` (a fraction of the arc length) of the reference curve."""
        (x0, y0), (x1, y1) = self.head, self.tail
        if self.rise == 0.0:
            return x0 + station * (x1 - x0), y0 + station * (y1 - y0)
        chord = math.hypot(x1 - x0, y1 - y0)
        # The left normal of the chord; the centre lies on it, R - |rise| from the chord's middle,
        # on the side away from the bulge.
        nx, ny = -(y1 - y0) / chord, (x1 - x0) / chord
        radius = (0.25 * chord * chord + self.rise * self.rise) / (2.0 * abs(self.rise))
        offset = self.rise - math.copysign(radius, self.rise)
        cx, cy = 0.5 * (x0 + x1) + offset * nx, 0.5 * (y0 + y1) + offset * ny
        # A bulge to the left runs clockwise about the centre.
        angle = math.atan2(y0 - cy, x0 - cx) - math.copysign(
            station * self.length / radius, self.rise
        )
        return cx + radius * math.cos(angle), cy + radius * math.sin(angle)


def arc(chord: float, rise: float) -> float:
    """The length of a circular arc over `chord` with `rise` (the straight chord when 0)."""
    if rise == 0.0:
        return chord
    radius = (0.25 * chord * chord + rise * rise) / (2.0 * abs(rise))
    half = math.asin(min(1.0, 0.5 * chord / radius))
    # A rise above half the chord is more than a half circle.
    return 2.0 * radius * (math.pi - half if abs(rise) > 0.5 * chord else half)


@dataclass(frozen=True)
class Layout:
    pieces: tuple[Piece, ...]

    @classmethod
    def of(cls, scene: Scene, value: Resolve) -> Layout:
        """The pieces of `scene`: its members, or its one rod."""
        members = scene.get("member", [])
        if not members:
            rise = value("H") if scene.get("geometry", {}).get("shape") == "arc" else 0.0
            span = value("L")
            name = str(scene.get("name", "rod"))
            return cls((Piece(name, "", "", arc(span, rise), (), (0.0, 0.0), (span, 0.0), rise),))
        joints = {str(j["name"]): (float(j["x"]), float(j["y"])) for j in scene.get("joint", [])}
        pieces = []
        for m in members:
            (x0, y0), (x1, y1) = joints[str(m["from"])], joints[str(m["to"])]
            rise = float(m.get("H", 0.0)) if m.get("shape") == "arc" else 0.0
            pieces.append(
                Piece(
                    str(m["name"]),
                    str(m["from"]),
                    str(m["to"]),
                    arc(math.hypot(x1 - x0, y1 - y0), rise),
                    tuple(str(h) for h in m.get("hinges", [])),
                    (x0, y0),
                    (x1, y1),
                    rise,
                )
            )
        return cls(tuple(pieces))

    @property
    def is_frame(self) -> bool:
        return bool(self.pieces[0].start)

    def index(self, member: str) -> int:
        for i, p in enumerate(self.pieces):
            if p.name == member:
                return i
        raise ValueError(f"the scene names member {member!r}, which it does not have")

    def joint(self, name: str) -> tuple[int, float]:
        """The place of joint `name`: the start or end of the first member reaching it."""
        for i, p in enumerate(self.pieces):
            if name in (p.start, p.end):
                return i, 0.0 if p.start == name else 1.0
        raise ValueError(f"the scene names joint {name!r}, which no member reaches")

    def place(self, entry: dict[str, Any]) -> tuple[int, float]:
        """The place of a scene entry (a support, a load, a link's end, ...)."""
        if "member" in entry and "at" in entry:
            return self.index(str(entry["member"])), float(entry["at"])
        if "member" in entry and "joint" in entry:
            i = self.index(str(entry["member"]))
            return i, 0.0 if self.pieces[i].start == str(entry["joint"]) else 1.0
        if "joint" in entry:
            return self.joint(str(entry["joint"]))
        return 0, float(entry["at"])

    def route(self, load: dict[str, Any]) -> list[int]:
        """The pieces a moving load runs along, in order."""
        if "path" in load:
            return [self.index(str(m)) for m in load["path"]]
        if "member" in load:
            return [self.index(str(load["member"]))]
        return [0]

    def along(self, route: list[int], s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The places at arc lengths `s` along `route`: pieces and stations (NaN off the route)."""
        lengths = np.array([self.pieces[i].length for i in route])
        ends = np.cumsum(lengths)
        leg = np.minimum(np.searchsorted(ends, s, side="left"), len(route) - 1)
        starts = ends[leg] - lengths[leg]
        stations = (s - starts) / lengths[leg]
        stations[(s < 0.0) | (s > ends[-1]) | np.isnan(s)] = math.nan
        return np.array(route)[leg], stations
