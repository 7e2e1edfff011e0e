"""Read and patch the georod FMU's serialized state (``fmi2SerializeFMUstate``) in Python.

Why: the Lyapunov exponent needs the perturbed trajectory put at "reference + small separation".
The FMU has no setter for its internal displacements and velocities, but its serialized state is a
documented byte layout (src/fmi/fmu_state.rs): decode the vectors, patch them, and
``fmi2DeSerializeFMUstate`` the bytes into the second instance.

Layout (a fixed prefix, then bincode 1.3 default options: little endian, fixed-width integers,
u64 length prefixes, u8 Option tags, u32 enum variant indices, f64 as 8 bytes)::

    Prefix { magic: [u8; 8] = b"GEOROD\\0S", format_version: u32 (= 4),
             crc32: u32 (zlib.crc32 of the whole buffer with these 4 bytes zero),
             length: u64 (of the whole buffer) }
    Header { guid: String, scene: String, elements: u64 }
    Body   { fmi_state: enum (u32), experiment: { tolerance: Option<f64>, start_time: f64,
             stop_time: Option<f64> }, params: Vec<(String, f64)>, inputs: Vec<Option<f64>>,
             snapshot: Option<Snapshot> }
    Snapshot { version: u32 (= 3), scene: String, elements: u64, time: f64,
               displacements: Vec<f64>, velocities: Vec<f64>, values: Vec<f64>,
               inputs: Vec<f64>, reactions: Vec<[f64; 3]>, last_newton_iterations: u32,
               energy: { external_work, input_work, support_work, dissipated,
                         initial_energy: f64 },
               clock: { origin: f64, step: f64, count: u64 } }

The vectors hold 3 entries per node (u1, u2, w), held ones included (src/model/rod.rs). Which
dofs the supports hold is read from the scene file the FMU carries (resources/scene.toml).
Patching replaces values in place, so the layout and length never change; the checksum is then
recomputed (:func:`sign`), as the FMU refuses a state whose CRC-32 does not match.
"""

from __future__ import annotations

import struct
import tomllib
import zlib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

MAGIC = b"GEOROD\x00S"
FORMAT_VERSION = 5
CRC_AT = 12  # offset of the CRC-32 (u32) in the prefix
PREFIX_LEN = 24  # magic, version, CRC-32, length
SNAPSHOT_VERSION = 4
DOFS_PER_NODE = 3
DOF_NAMES = ("u1", "u2", "w")


class StateFormatError(ValueError):
    """The bytes are not a serialized georod state this module understands."""


def checksum(blob: bytes) -> int:
    """The CRC-32 of a serialized state with its own checksum field taken as zero."""
    b = bytes(blob)
    return zlib.crc32(b[:CRC_AT] + b"\x00" * 4 + b[CRC_AT + 4 :])


def sign(blob: bytes) -> bytes:
    """`blob` with its recorded length and CRC-32 recomputed (after patching it)."""
    out = bytearray(blob)
    out[16:PREFIX_LEN] = struct.pack("<Q", len(out))
    out[CRC_AT : CRC_AT + 4] = struct.pack("<I", checksum(bytes(out)))
    return bytes(out)


class _Reader:
    def __init__(self, data: bytes) -> None:
        self.data = data
        self.pos = 0

    def take(self, n: int) -> bytes:
        if self.pos + n > len(self.data):
            raise StateFormatError(
                f"truncated serialized state: need {n} bytes at offset {self.pos}, "
                f"have {len(self.data) - self.pos}"
            )
        b = self.data[self.pos : self.pos + n]
        self.pos += n
        return b

    def u8(self) -> int:
        return self.take(1)[0]

    def u32(self) -> int:
        return int(struct.unpack("<I", self.take(4))[0])

    def u64(self) -> int:
        return int(struct.unpack("<Q", self.take(8))[0])

    def f64(self) -> float:
        return float(struct.unpack("<d", self.take(8))[0])

    def string(self) -> str:
        return self.take(self.u64()).decode("utf-8")

    def option_f64(self) -> float | None:
        tag = self.u8()
        if tag not in (0, 1):
            raise StateFormatError(f"bad Option tag {tag} at offset {self.pos - 1}")
        return self.f64() if tag else None

    def f64_vec(self) -> tuple[int, np.ndarray]:
        n = self.u64()
        start = self.pos
        return start, np.frombuffer(self.take(8 * n), dtype="<f8").astype(float)


@dataclass
class DecodedState:
    """The parts of a serialized state the analyses use, with where the vectors sit.

    u_offset / v_offset: byte offsets of the first f64 of the displacement / velocity vectors.
    """

    scene: str
    elements: int
    time: float
    displacements: np.ndarray
    velocities: np.ndarray
    params: dict[str, float]
    u_offset: int
    v_offset: int
    guid: str = ""

    @property
    def dofs(self) -> int:
        return self.displacements.size


def decode_state(blob: bytes) -> DecodedState:
    """Decodes a serialized georod FMU state; raises :class:`StateFormatError` on anything
    unexpected (wrong magic, version, truncation, trailing bytes, checksum, no simulation
    snapshot)."""
    r = _Reader(bytes(blob))
    if r.take(8) != MAGIC:
        raise StateFormatError("not a serialized georod FMU state (wrong magic bytes)")
    version = r.u32()
    if version != FORMAT_VERSION:
        raise StateFormatError(
            f"serialized state format {version}, this module reads {FORMAT_VERSION}"
        )
    crc = r.u32()
    length = r.u64()
    if length > len(r.data):
        raise StateFormatError(f"truncated serialized state: {len(r.data)} of {length} bytes")
    if length < len(r.data):
        raise StateFormatError(f"{len(r.data) - length} unexpected trailing bytes")
    if crc != checksum(r.data):
        raise StateFormatError("checksum mismatch: the serialized state is corrupt")
    guid = r.string()
    scene = r.string()
    elements = r.u64()
    r.u32()  # fmi_state
    r.option_f64()  # experiment.tolerance
    r.f64()  # experiment.start_time
    r.option_f64()  # experiment.stop_time
    params = {}
    for _ in range(r.u64()):
        name = r.string()
        params[name] = r.f64()
    for _ in range(r.u64()):  # inputs the host set
        r.option_f64()
    if r.u8() != 1:
        raise StateFormatError("the state holds no simulation (taken before initialization)")
    snap_version = r.u32()
    if snap_version != SNAPSHOT_VERSION:
        raise StateFormatError(
            f"snapshot version {snap_version}, this module reads {SNAPSHOT_VERSION}"
        )
    if r.string() != scene:
        raise StateFormatError("snapshot and header disagree on the scene")
    if r.u64() != elements:
        raise StateFormatError("snapshot and header disagree on the number of elements")
    time = r.f64()
    u_off, u = r.f64_vec()
    v_off, v = r.f64_vec()
    r.f64_vec()  # parameter values
    r.f64_vec()  # inputs
    r.take(24 * r.u64())  # reactions, 3 per support
    r.u32()  # last_newton_iterations
    for _ in range(5):  # energy ledger
        r.f64()
    r.f64()  # clock.origin
    r.f64()  # clock.step
    r.u64()  # clock.count
    if r.u8() == 1:  # Lyapunov tangent vectors and growth
        r.f64_vec()
        r.f64_vec()
        r.f64_vec()
        r.f64()
    if r.pos != len(r.data):
        raise StateFormatError(f"{len(r.data) - r.pos} unexpected trailing bytes")
    dofs = DOFS_PER_NODE * (elements + 1)
    if u.size != dofs or v.size != dofs:
        raise StateFormatError(f"vectors of length {u.size}/{v.size}, expected {dofs}")
    return DecodedState(scene, elements, time, u, v, params, u_off, v_off, guid)


def encode_state(template: bytes, displacements: np.ndarray, velocities: np.ndarray) -> bytes:
    """`template` (a serialized state) with its displacement and velocity vectors replaced."""
    st = decode_state(template)
    u = np.asarray(displacements, dtype="<f8")
    v = np.asarray(velocities, dtype="<f8")
    if u.shape != (st.dofs,) or v.shape != (st.dofs,):
        raise ValueError(f"vectors must have shape ({st.dofs},), got {u.shape} and {v.shape}")
    if not (np.all(np.isfinite(u)) and np.all(np.isfinite(v))):
        raise ValueError("non-finite displacement or velocity")
    out = bytearray(template)
    out[st.u_offset : st.u_offset + 8 * st.dofs] = u.tobytes()
    out[st.v_offset : st.v_offset + 8 * st.dofs] = v.tobytes()
    return sign(bytes(out))


def free_mask(scene_file: Path, elements: int) -> np.ndarray:
    """True for every degree of freedom that the supports of the scene (its TOML file, e.g. an
    unzipped FMU's resources/scene.toml) do not hold, for a mesh of `elements` elements."""
    scene = tomllib.loads(Path(scene_file).read_text(encoding="utf-8"))
    nodes = elements + 1
    mask = np.ones(DOFS_PER_NODE * nodes, dtype=bool)
    for support in scene.get("support", []):
        node = round(float(support["at"]) * elements)
        for dof in support["fix"]:
            mask[DOFS_PER_NODE * node + DOF_NAMES.index(dof)] = False
    return mask


def _w_string(s: str) -> bytes:
    b = s.encode("utf-8")
    return struct.pack("<Q", len(b)) + b


def build_state(
    scene: str,
    elements: int,
    time: float,
    displacements: np.ndarray,
    velocities: np.ndarray,
    params: dict[str, float] | None = None,
    guid: str = "",
) -> bytes:
    """A complete serialized state in the same layout (for unit tests of the codec without an
    FMU; the FMU would also accept it if `guid` were its GUID and `params` listed every
    parameter of the scene, in its order)."""
    u = np.asarray(displacements, dtype="<f8")
    v = np.asarray(velocities, dtype="<f8")
    out = bytearray(MAGIC)
    out += struct.pack("<IIQ", FORMAT_VERSION, 0, 0)  # CRC and length: sign() below
    out += _w_string(guid) + _w_string(scene) + struct.pack("<Q", elements)
    out += struct.pack("<I", 2)  # fmi_state = StepComplete
    out += b"\x00" + struct.pack("<d", 0.0) + b"\x00"  # experiment
    params = params or {}
    out += struct.pack("<Q", len(params))
    for name, value in params.items():
        out += _w_string(name) + struct.pack("<d", value)
    out += struct.pack("<Q", 0)  # inputs
    out += b"\x01" + struct.pack("<I", SNAPSHOT_VERSION) + _w_string(scene)
    out += struct.pack("<Qd", elements, time)
    out += struct.pack("<Q", u.size) + u.tobytes() + struct.pack("<Q", v.size) + v.tobytes()
    values = np.array(list(params.values()), dtype="<f8")
    out += struct.pack("<Q", values.size) + values.tobytes()
    out += struct.pack("<QQ", 0, 0)  # inputs, reactions
    out += struct.pack("<I", 0)  # last_newton_iterations
    out += struct.pack("<ddddd", 0.0, 0.0, 0.0, 0.0, 0.0)  # energy ledger
    out += struct.pack("<ddQ", time, 0.0, 0)  # clock: origin = time, no sub-steps counted
    out += b"\x00"  # no Lyapunov data
    return sign(bytes(out))
