"""What an FMU's own scene file (``resources/scene.toml``) says the analysis tools can sample:
its displacement sensors and their velocity partners (the velocity of the same dof at the same
station; without one the velocity is sampled from the sensor), and whether it is forced by a
harmonic load (``Omega``) or needs a sampling period.
A scene that cannot be analysed is refused with the reason and what to add, before any case
runs."""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from pathlib import Path

from georod_tools.fmu import FmuModel

#: The velocity quantity of each displacement quantity.
PARTNER = {"u1": "v1", "u2": "v2", "w": "vw"}


class NotAnalysableError(ValueError):
    """The scene cannot be analysed as asked: the message says why and what to add."""


@dataclass(frozen=True)
class Sensor:
    name: str
    #: Where it reads: ``("", at)`` on a rod, ``(joint, None)`` at a frame's joint, ``(member,
    #: at)`` on a frame's member.
    place: tuple[str, float | None]
    quantity: str

    def same_place(self, other: Sensor) -> bool:
        (a, x), (b, y) = self.place, other.place
        if x is None or y is None:
            return a == b and x == y
        return a == b and abs(x - y) < 1e-12


def place(entry: dict) -> tuple[str, float | None]:
    """A scene entry's place: its joint, or its member (none on a rod) and station."""
    if "joint" in entry and "member" not in entry:
        return str(entry["joint"]), None
    if "joint" in entry:  # a member's end section at a joint
        return f"{entry['member']}@{entry['joint']}", None
    return str(entry.get("member", "")), float(entry["at"])


@dataclass(frozen=True)
class Sampled:
    """The displacement sensor sampled, its velocity partner ("" when it has none) and whether
    the FMU is forced."""

    sensor: str
    velocity: str
    forced: bool


def scene_sensors(model: FmuModel) -> list[Sensor]:
    """The ``[[sensor]]`` entries of the FMU's scene file, in order."""
    path = Path(model.unzipdir) / "resources" / "scene.toml"
    try:
        scene = tomllib.loads(path.read_text())
    except (OSError, tomllib.TOMLDecodeError) as e:
        raise NotAnalysableError(
            f"{model.identifier}: cannot read its scene file {path}: {e}"
        ) from e
    return [Sensor(s["name"], place(s), s["quantity"]) for s in scene.get("sensor", [])]


def pick(model: FmuModel, sensor: str | None) -> Sampled:
    """The sensor to sample (`sensor`, or the scene's first displacement sensor) and its velocity
    partner ("" without one); NotAnalysableError with the reason and what to add otherwise."""
    sensors = scene_sensors(model)
    moving = [s for s in sensors if s.quantity in PARTNER]
    if sensor is None:
        if not moving:
            raise NotAnalysableError(
                f"{model.identifier} has no displacement sensor: add a [[sensor]] with quantity "
                '"u1", "u2" or "w" (and best its velocity, "v1", "v2" or "vw", at the same '
                "station)"
            )
        chosen = moving[0]
    else:
        found = [s for s in sensors if s.name == sensor]
        if not found:
            names = ", ".join(s.name for s in moving) or "none"
            raise NotAnalysableError(
                f"--sensor {sensor}: not a sensor of {model.identifier} (its displacement "
                f"sensors: {names})"
            )
        chosen = found[0]
        if chosen.quantity not in PARTNER:
            raise NotAnalysableError(
                f"--sensor {sensor}: reads {chosen.quantity}, not a displacement (u1, u2, w)"
            )
    want = PARTNER[chosen.quantity]
    partner = next((s for s in sensors if s.quantity == want and s.same_place(chosen)), None)
    return Sampled(chosen.name, partner.name if partner else "", "Omega" in model.parameters)
