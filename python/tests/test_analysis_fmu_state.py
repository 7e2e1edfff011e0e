"""The Python codec of the serialized FMU state (src/fmi/fmu_state.rs layout): synthetic bytes
without an FMU, and real states of the BuckledBeam FMU (built by the session fixture if missing)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from georod_tools.fmu_state import (
    StateFormatError,
    build_state,
    decode_state,
    encode_state,
    free_mask,
)

BEAM_FMU = Path(__file__).resolve().parents[2] / "target" / "fmu" / "BuckledBeam.fmu"
needs_fmu = pytest.mark.usefixtures("fmu_paths")  # builds the FMUs when missing or stale


def synthetic(elements: int = 4) -> tuple[bytes, np.ndarray, np.ndarray]:
    n = 3 * (elements + 1)
    u = np.linspace(-1.0, 1.0, n)
    v = np.linspace(5.0, -7.0, n)
    blob = build_state("BuckledBeam", elements, 0.25, u, v, {"E": 1.2e4, "F": 0.7})
    return blob, u, v


def test_decode_synthetic() -> None:
    blob, u, v = synthetic()
    st = decode_state(blob)
    assert (st.scene, st.elements, st.time) == ("BuckledBeam", 4, 0.25)
    assert np.array_equal(st.displacements, u) and np.array_equal(st.velocities, v)
    assert st.params == {"E": 1.2e4, "F": 0.7}


def test_encode_patches_in_place() -> None:
    blob, u, v = synthetic()
    new = encode_state(blob, u + 1e-3, -v)
    assert len(new) == len(blob)
    st = decode_state(new)
    assert np.array_equal(st.displacements, u + 1e-3) and np.array_equal(st.velocities, -v)
    assert encode_state(blob, u, v) == blob
    with pytest.raises(ValueError, match="shape"):
        encode_state(blob, u[:-1], v)
    with pytest.raises(ValueError, match="non-finite"):
        encode_state(blob, np.full_like(u, math.nan), v)


@pytest.mark.parametrize(
    "mangle, match",
    [
        (lambda b: b"X" + b[1:], "magic"),
        (lambda b: b[:40], "truncated"),
        (lambda b: b + b"\x00", "trailing"),
        (lambda b: b[:8] + b"\x63" + b[9:], "format"),  # format version 99
        (lambda b: b[:-1] + bytes([b[-1] ^ 1]), "checksum"),
    ],
)
def test_bad_bytes_are_refused(mangle, match: str) -> None:  # noqa: ANN001
    blob, _, _ = synthetic()
    with pytest.raises(StateFormatError, match=match):
        decode_state(mangle(blob))


SCENES = Path(__file__).resolve().parents[2] / "scenes"


def test_free_mask() -> None:
    assert free_mask(SCENES / "BuckledBeam.toml", 4).sum() == 15 - 4
    assert free_mask(SCENES / "ClampedArch.toml", 4).sum() == 15 - 6
    m = free_mask(SCENES / "PinnedArch.toml", 2)
    assert list(np.nonzero(~m)[0]) == [0, 1, 6, 7]


@needs_fmu
def test_real_state_roundtrip() -> None:
    """A real state decodes (time, parameters, prescribed values), re-encodes to the same bytes,
    and a patched state deserialized into a second instance reads back as patched."""
    from georod_tools.runner import FmuModel, Instance, advance_periods

    model = FmuModel.load(BEAM_FMU)
    params = {"F": 0.9, "Omega": 3500.0, "elements": 6}
    a = Instance(model, params, 3500.0, 10, name="a")
    b = Instance(model, params, 3500.0, 10, name="b")
    try:
        advance_periods(a, 3)
        blob = a.serialize()
        st = decode_state(blob)
        assert (st.scene, st.elements) == ("BuckledBeam", 6)
        assert st.time == pytest.approx(3 * 2 * math.pi / 3500.0, rel=1e-12)
        assert st.params["F"] == 0.9 and st.params["pre_shortening"] == 0.11
        assert st.displacements[-3] == pytest.approx(-0.11)  # right end pushed in and held
        assert encode_state(blob, st.displacements, st.velocities) == blob
        mask = free_mask(SCENES / "BuckledBeam.toml", 6)
        u = st.displacements + np.where(mask, 1e-6, 0.0)
        b.restore(encode_state(blob, u, st.velocities), a.k)
        got = decode_state(b.serialize())
        assert np.array_equal(got.displacements, u)
        assert got.time == st.time
        a.step()
        b.step()  # both continue at the same communication point; the states differ slightly
        wa, wb = a.outputs()[0], b.outputs()[0]
        assert wa != wb and abs(wa - wb) < 1e-4
    finally:
        a.close()
        b.close()
