"""The paper's section 6.1 as data: every panel of its Figures 2-5 with what the paper says about
it (:data:`PAPER_CASES`), and the fine sweeps around the structures that our model shows at
shifted parameters (:data:`WINDOWS`)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

PERIODIC, CHAOTIC, LONG = "periodic", "chaotic", "long-period"


@dataclass(frozen=True)
class PaperCase:
    """One panel of the paper's Figures 2-5 with what the paper says about it.

    kind: ``periodic`` (with `period`), ``chaotic`` or ``long-period`` (a period too long to name).
    wells: ``one``, ``both`` or None when the paper does not say whether the motion stays in one
        potential well or visits both.
    """

    figure: int
    panel: str
    F: float
    Omega: float
    description: str
    kind: str
    period: int | None = None
    wells: str | None = None

    @property
    def name(self) -> str:
        return f"fig{self.figure}{self.panel}"

    @property
    def paper_label(self) -> str:
        return f"period-{self.period}" if self.kind == PERIODIC else self.kind


def _fig(figure: int, fixed: dict[str, float], rows: Sequence[tuple]) -> list[PaperCase]:
    out = []
    for panel, value, desc, kind, period, wells in rows:
        var = {"F": value} if "Omega" in fixed else {"Omega": value}
        out.append(
            PaperCase(
                figure,
                panel,
                **fixed,
                **var,
                description=desc,
                kind=kind,
                period=period,
                wells=wells,
            )
        )
    return out


#: Figures 2-5 of section 6.1, captions quoted (periods in brackets are implied, not stated).
PAPER_CASES: tuple[PaperCase, ...] = tuple(
    _fig(
        2,
        {"Omega": 3500.0},
        [
            ("a", 0.4, "small orbit around the right equilibrium [period-1]", PERIODIC, 1, "one"),
            ("b", 0.6, "chaotic motion around both stable equilibria", CHAOTIC, None, "both"),
            ("c", 0.7, "globally three-period motion", PERIODIC, 3, "both"),
            ("d", 0.9, "chaotic, period-doubling of the odd-period motion", CHAOTIC, None, None),
            ("e", 1.5, "globally chaotic motion", CHAOTIC, None, "both"),
            (
                "f",
                2.0,
                "periodic large orbit around all equilibria [period-1]",
                PERIODIC,
                1,
                "both",
            ),
        ],
    )
    + _fig(
        3,
        {"F": 0.7},
        [
            ("a", 4200.0, "two-period motion", PERIODIC, 2, None),
            ("b", 4050.0, "locally chaotic, period-doubling of (a)", CHAOTIC, None, "one"),
            ("c", 4000.0, "chaotic around both equilibrium positions", CHAOTIC, None, "both"),
            ("d", 3600.0, "three-period motion", PERIODIC, 3, None),
            ("e", 3550.0, "doubling of the three-period motion [period-6]", PERIODIC, 6, None),
            ("f", 3400.0, "globally chaotic, period-doubling of (e)", CHAOTIC, None, "both"),
        ],
    )
    + _fig(
        4,
        {"F": 0.7},
        [
            ("a", 3500.0, "three-period motion", PERIODIC, 3, "both"),
            ("b", 3480.0, "(2x3)-period motion", PERIODIC, 6, None),
            ("c", 3465.0, "(4x3)-period motion", PERIODIC, 12, None),
            ("d", 3460.0, "(8x3)-period motion", PERIODIC, 24, None),
            ("e", 3450.0, "a very long period", LONG, None, None),
            ("f", 3430.0, "chaos due to the period-doubling", CHAOTIC, None, None),
            ("g", 3420.0, "chaos due to the period-doubling", CHAOTIC, None, None),
            ("h", 3400.0, "globally chaotic", CHAOTIC, None, "both"),
        ],
    )
    + _fig(
        5,
        {"F": 0.7},
        [
            ("a", 4300.0, "two-period motion", PERIODIC, 2, "one"),
            ("b", 4200.0, "two-period motion", PERIODIC, 2, "one"),
            ("c", 4150.0, "four-period motion", PERIODIC, 4, "one"),
            ("d", 4120.0, "large period motion", LONG, None, "one"),
            ("e", 4050.0, "locally chaotic", CHAOTIC, None, "one"),
            ("f", 4000.0, "globally chaotic due to symmetry", CHAOTIC, None, "both"),
        ],
    )
)


@dataclass(frozen=True)
class Window:
    """A fine sweep around a structure of the paper that we find at shifted parameters."""

    name: str
    param: str
    start: float
    stop: float
    F: float
    Omega: float
    paper: str


#: Fine sweeps: where our model shows the paper's sequences (Figures 2, 4 and 5).
WINDOWS: tuple[Window, ...] = (
    Window(
        "F_onset",
        "F",
        0.50,
        0.70,
        0.7,
        3500.0,
        "Fig. 2a-2c: small orbit (0.4), chaos (0.6), period-3 (0.7)",
    ),
    Window(
        "Omega_period3",
        "Omega",
        3530.0,
        3610.0,
        0.7,
        3500.0,
        "Fig. 4: period 3, 6, 12, 24 at Omega = 3500, 3480, 3465, 3460, chaos below",
    ),
    Window(
        "Omega_period2",
        "Omega",
        4220.0,
        4300.0,
        0.7,
        3500.0,
        "Fig. 5: period 2 (4300, 4200), 4 (4150), long (4120), local chaos (4050)",
    ),
)


#: Parameter swept by each fine sweep.
SWEPT: dict[str, str] = {w.name: w.param for w in WINDOWS}
