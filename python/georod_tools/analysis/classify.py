"""Classify a steady motion from its stroboscopic (Poincaré) samples and its largest Lyapunov
exponent: period-k, quasi-periodic, chaotic, or unresolved.

Decision, in this order (see :class:`ClassifySettings` for the numbers and why):

1. **period-k**: the smallest ``k <= k_max`` such that every sample repeats after ``k`` samples,
   ``|x_{n+k} - x_n| <= period_tol * size`` in each coordinate, ``size`` being the extent of the
   attractor in that coordinate. Direct evidence from the samples, so it is checked first.
2. **chaotic**: the largest exponent exceeds ``chaos_threshold`` (per forcing period). Not a sign
   test: this rod has almost undamped modes (damping acts on the translations only), so a stable
   periodic or quasi-periodic motion shows an exponent near zero, slightly on either side within the
   estimator's noise.
3. **quasi-periodic**: no period, ``|exponent| <= zero_band``, and the samples fill a 1-D ring:
   correlation dimension within ``ring_dimension``. A torus cut by the section is an invariant
   closed curve; the dimension test separates it from a finite set of points (long period,
   dimension ~0) and from a set that covers an area (dimension ~2, e.g. a motion that has not
   settled).
4. otherwise **unresolved** (period above ``k_max``, transient not died out, no exponent computed
   and no period found).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

FloatArray = np.ndarray

PERIODIC = "periodic"
QUASI_PERIODIC = "quasi-periodic"
CHAOTIC = "chaotic"
UNRESOLVED = "unresolved"


@dataclass(frozen=True)
class ClassifySettings:
    """Thresholds of the classifier.

    k_max: largest period looked for (the paper shows period 24 in its Figure 4d).
    period_tol: 1e-3 of the attractor size. A settled periodic orbit repeats to the integrator's
        accuracy (Newton converges to ~1e-10 relative), far below this; what remains is the slow
        approach along the orbit's least stable direction and the residue of the almost undamped
        rotation/shear modes, which the tolerance must absorb (measured: 4e-6 to 1e-5 for the
        BuckledBeam's period-1 and period-3 orbits after 200 periods). 1e-3 is ten times below
        what a plot of the section resolves (a dot is ~1e-2 of an axis). A quasi-periodic ring with
        rotation number rho returns after k samples to ``~2 pi ||k rho|| * size``; it passes as
        period-k only when rho lies within ~1.6e-4 / k of p / k, i.e. when it is locked in practice.
    chaos_threshold: exponent per forcing period above which the motion is chaotic: 0.05, a
        separation growing e-fold in 20 periods. Measured on the BuckledBeam (10 elements,
        200 + 200 periods, sweeps F = 0.4..2 at Omega = 3500 and Omega = 3400..4300 at F = 0.7):
        all 8 periodic orbits (periods 1, 3, 4, 6) give -0.011 to -0.005 per period (not clearly
        negative: the rotations are almost undamped, so the least stable direction decays at only
        3-6 1/s); all 19 chaotic motions give 0.30 to 1.0. The spread of the per-interval growths
        suggests a standard error of 0.01-0.03 for periodic orbits, which overstates the error of
        the mean (around a periodic orbit consecutive growths telescope), and the observed
        scatter of the periodic means is ~0.003. 0.05 lies well clear of both groups. (For scale:
        the translational damping alone contracts at ``d / (2 rho A) * T`` = 0.45 per period.)
    zero_band: ``|exponent| <= zero_band`` counts as zero for the quasi-periodic test (0.05, same
        evidence; a quasi-periodic motion has exactly 0 as its largest exponent).
    ring_dimension: closed interval of correlation dimensions accepted as a 1-D ring. A smooth
        closed curve measures 1.0-1.08 with 64-1000 samples (see `correlation_dimension`); an
        area measures 1.7-1.9, a finite point set ~0. A chaotic section may measure ~1.1-1.3 but
        is caught by its exponent first.
    """

    k_max: int = 32
    period_tol: float = 1e-3
    chaos_threshold: float = 0.05
    zero_band: float = 0.05
    ring_dimension: tuple[float, float] = (0.8, 1.2)
    min_ring_samples: int = 64

    def __post_init__(self) -> None:
        if self.k_max < 1:
            raise ValueError(f"k_max = {self.k_max} must be >= 1")
        if not 0.0 < self.period_tol < 1.0:
            raise ValueError(f"period_tol = {self.period_tol} must lie in (0, 1)")
        if not self.chaos_threshold > 0.0:
            raise ValueError(f"chaos_threshold = {self.chaos_threshold} must be > 0")
        if not self.zero_band > 0.0:
            raise ValueError(f"zero_band = {self.zero_band} must be > 0")


@dataclass
class Classification:
    """What the motion is, with the evidence.

    kind: ``periodic``, ``quasi-periodic``, ``chaotic`` or ``unresolved``.
    period: k for a periodic motion, else None.
    exponent: largest Lyapunov exponent per forcing period used (None if not computed).
    dimension: correlation dimension of the samples (NaN when too few samples / not needed).
    mismatch: ``max |x_{n+k} - x_n| / size`` for k = 1..k_max (index k - 1; NaN if untestable).
    note: why, in words (conflicts are reported here).
    """

    kind: str
    period: int | None
    exponent: float | None
    dimension: float
    mismatch: FloatArray
    note: str = ""

    @property
    def label(self) -> str:
        """Short label: ``period-3``, ``chaotic``, ..."""
        return f"period-{self.period}" if self.kind == PERIODIC else self.kind


def _as_samples(samples: FloatArray) -> FloatArray:
    x = np.asarray(samples, dtype=float)
    if x.ndim == 1:
        x = x[:, None]
    if x.ndim != 2 or x.shape[0] == 0:
        raise ValueError(f"samples must be a non-empty (n,) or (n, dim) array, got {x.shape}")
    if not np.all(np.isfinite(x)):
        raise ValueError("samples contain non-finite values")
    return x


def attractor_size(samples: FloatArray, size: FloatArray | None = None) -> FloatArray:
    """Per-coordinate size of the attractor: `size` when given (e.g. the range of the continuous
    trajectory, which is nonzero even for a period-1 orbit whose samples are one point), else the
    range of the samples."""
    x = _as_samples(samples)
    s = np.ptp(x, axis=0) if size is None else np.broadcast_to(np.asarray(size, float), x.shape[1:])
    if np.any(s < 0) or not np.all(np.isfinite(s)):
        raise ValueError(f"attractor size must be finite and >= 0, got {s}")
    return np.asarray(s, dtype=float)


def period_mismatch(samples: FloatArray, k_max: int, size: FloatArray | None = None) -> FloatArray:
    """``e_k = max_n max_j |x_{n+k,j} - x_{n,j}| / size_j`` for k = 1..k_max.

    A period k is testable only with at least two full repeats (``n_samples >= 3 k``); untestable
    entries are NaN. Coordinates of zero size are ignored (they do not move at all).
    """
    x = _as_samples(samples)
    s = attractor_size(x, size)
    moving = s > 0
    out = np.full(k_max, np.nan)
    for k in range(1, k_max + 1):
        if x.shape[0] < 3 * k:
            break
        if not np.any(moving):
            out[k - 1] = 0.0
            continue
        diff = np.abs(x[k:, moving] - x[:-k, moving]) / s[moving]
        out[k - 1] = float(diff.max())
    return out


def detect_period(
    samples: FloatArray, k_max: int = 32, tol: float = 1e-3, size: FloatArray | None = None
) -> int | None:
    """The smallest period ``k <= k_max`` of the samples to `tol` (relative to the attractor
    size), or None."""
    e = period_mismatch(samples, k_max, size)
    hits = np.nonzero(e <= tol)[0]
    return int(hits[0]) + 1 if hits.size else None


def correlation_dimension(
    samples: FloatArray,
    size: FloatArray | None = None,
    c_range: tuple[float, float] | None = None,
    max_points: int = 1500,
) -> float:
    """Grassberger-Procaccia correlation dimension of the samples.

    Coordinates are scaled by the attractor size (w and v have different units). ``C(r)`` is the
    fraction of sample pairs closer than r; the slope of ``log C`` against ``log r`` is fitted for
    C in `c_range` (r taken as the quantiles of the pair distances). The default range is
    ``(max(0.002, 8 / n), 0.2)``: from about four neighbours on each side of a point (below that,
    ``C(r)`` of n points on a curve is a staircase set by the gaps between neighbours) to a fifth of
    the set (beyond that, the curvature of the ring bends the slope). With it a closed curve
    measures 1.0-1.08 for 64-1000 samples, the Henon attractor 1.1-1.2, a filled square 1.7-1.9.
    Samples beyond `max_points` are thinned evenly (deterministic). NaN for fewer than 16 points.
    """
    x = _as_samples(samples)
    s = attractor_size(x, size)
    s = np.where(s > 0, s, 1.0)
    x = x / s
    if x.shape[0] > max_points:
        x = x[np.linspace(0, x.shape[0] - 1, max_points).astype(int)]
    if x.shape[0] < 16:
        return math.nan
    if c_range is None:
        c_range = (max(0.002, 8.0 / x.shape[0]), 0.2)
    diff = x[:, None, :] - x[None, :, :]
    d = np.sqrt((diff**2).sum(axis=-1))[np.triu_indices(x.shape[0], k=1)]
    c = np.geomspace(c_range[0], c_range[1], 12)
    r = np.quantile(d, c)
    ok = r > 0
    if ok.sum() < 4 or np.ptp(np.log(r[ok])) == 0.0:
        return 0.0  # a finite set of points: most pairs at distance zero
    slope = np.polyfit(np.log(r[ok]), np.log(c[ok]), 1)[0]
    return float(slope)


def classify(
    samples: FloatArray,
    exponent: float | None,
    settings: ClassifySettings | None = None,
    size: FloatArray | None = None,
) -> Classification:
    """Classifies the motion from its stroboscopic `samples` (n, dim) and its largest Lyapunov
    `exponent` per forcing period. Without an exponent (None) only a period can be recognized:
    the section of a chaotic attractor may measure a correlation dimension near 1 too (the
    BuckledBeam at F = 0.7 does), so a ring alone does not prove quasi-periodicity."""
    st = settings or ClassifySettings()
    x = _as_samples(samples)
    mismatch = period_mismatch(x, st.k_max, size)
    hits = np.nonzero(mismatch <= st.period_tol)[0]
    if hits.size:
        k = int(hits[0]) + 1
        note = f"samples repeat after {k} to {mismatch[k - 1]:.1e} of the attractor size"
        if exponent is not None and exponent > st.chaos_threshold:
            note += f"; but exponent {exponent:.3g} > {st.chaos_threshold} (transient chaos?)"
        return Classification(PERIODIC, k, exponent, math.nan, mismatch, note)
    if exponent is not None and exponent > st.chaos_threshold:
        note = f"exponent {exponent:.3g} per period > {st.chaos_threshold}"
        return Classification(CHAOTIC, None, exponent, math.nan, mismatch, note)
    dim = correlation_dimension(x, size) if x.shape[0] >= st.min_ring_samples else math.nan
    lo, hi = st.ring_dimension
    near_zero = exponent is not None and abs(exponent) <= st.zero_band
    if near_zero and lo <= dim <= hi:
        note = (
            f"no period <= {st.k_max}, correlation dimension {dim:.2f} (a ring), "
            f"exponent {exponent:.2g} ~ 0"
        )
        return Classification(QUASI_PERIODIC, None, exponent, dim, mismatch, note)
    why = [f"no period <= {st.k_max}"]
    why.append(
        "no Lyapunov exponent (needed for chaos or quasi-periodicity)"
        if exponent is None
        else f"exponent {exponent:.3g} per period"
    )
    why.append(f"correlation dimension {dim:.2f}")
    return Classification(UNRESOLVED, None, exponent, dim, mismatch, ", ".join(why))
