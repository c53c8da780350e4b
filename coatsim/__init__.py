"""coatsim: a digital twin for robotic coating and plasma spraying.

Stages, each importable and testable on its own: ``geometry`` (curves, polysegments, drawings,
curves in space, passes on 3-D parts), ``path`` (programs as plans, process records, the
language interface), ``languages`` (one package per robot language and their registry),
``robot`` (the MuJoCo arm), ``spray`` (deposition), ``run`` (scenarios), ``report`` (metrics,
figures, gates), ``sweep`` (parameter sweeps on Dask); ``core`` holds what they share and
``cli`` the commands. The names in ``__all__`` are the entry points a Python user needs; they
load on first use, so ``import coatsim`` stays cheap.
"""

from importlib import import_module
from typing import Any

__version__ = "0.1.0"

#: Entry point -> the module that defines it.
_ENTRY_POINTS = {
    "builtin_curve": "coatsim.geometry",
    "make_curve": "coatsim.geometry",
    "segment_curve": "coatsim.geometry",
    "load_part": "coatsim.geometry.surface",
    "PlanOptions": "coatsim.geometry.surface",
    "plan": "coatsim.geometry.surface",
    "language": "coatsim.languages.registry",
    "language_of": "coatsim.languages.registry",
    "LANGUAGES": "coatsim.languages.registry",
    "execute": "coatsim.robot.execute",
    "coat": "coatsim.spray.coat",
    "run_scenario": "coatsim.run.pipeline",
    "CoatsimError": "coatsim.core.errors",
    "InputError": "coatsim.core.errors",
    "ExecutionError": "coatsim.core.errors",
    "GateFailure": "coatsim.core.errors",
}

__all__ = sorted(_ENTRY_POINTS)


def __getattr__(name: str) -> Any:
    """An entry point, imported from its module on first use (PEP 562)."""
    if name not in _ENTRY_POINTS:
        raise AttributeError(f"module 'coatsim' has no attribute {name!r}; its entry points: {', '.join(__all__)}")
    value = getattr(import_module(_ENTRY_POINTS[name]), name)
    globals()[name] = value
    return value
