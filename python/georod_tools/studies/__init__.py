"""The studies behind the docs, each a short module: the paper's buckled beam
(:mod:`.paper_cases`, :mod:`.paper`, :mod:`.paper_report`), the arches (:mod:`.arches`,
:mod:`.arches_study`), stability (:mod:`.stability`), the work-precision benchmark
(:mod:`.benchmark`, with Exudyn in :mod:`.exudyn_beam`), the benchmark of the Lyapunov methods
(:mod:`.lyapunov_benchmark`) and the demo (:mod:`.demo`). They run cases through
:mod:`georod_tools.analysis` and write through :mod:`georod_tools.report`."""
