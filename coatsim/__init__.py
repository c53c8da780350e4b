"""coatsim: a digital twin for robotic coating and plasma spraying.

Stages (each importable and testable on its own): ``geometry`` (curves, polysegments),
``program`` (AS robot programs), ``robot`` (MuJoCo arm), ``spray`` (deposition),
``report`` (metrics, plots, gates).
"""

__version__ = "0.1.0"
