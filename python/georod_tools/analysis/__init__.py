"""Analyses of the FMUs' motion: one case (:mod:`.case`: stroboscopic samples, the core's
Lyapunov exponent, classification by :mod:`.classify`), the two-instance cross-check of the
exponent (:mod:`.twin`), what happens before the forcing starts (:mod:`.prelude`), and sweeps on
Dask (:mod:`.sweep`)."""
