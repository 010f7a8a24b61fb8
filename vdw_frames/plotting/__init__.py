"""Figures (matplotlib, Agg backend: no display needed).  Forces are drawn in kN, displacements in mm.

Every function writes one figure to ``path`` and returns the path it wrote: the format follows the
suffix (``.png``, ``.pdf``, ``.svg``, ...); a path without one gets ``.png`` added; an existing folder
(or a path ending in a separator) gets the function's default file name inside it.

- :mod:`.element`: :func:`plot_loops` (sine tests of a wall);
- :mod:`.response`: one analysis -- :func:`plot_drift_envelope`, :func:`plot_roof_displacement`,
  :func:`plot_wall_hysteresis`, :func:`plot_story_hysteresis`, :func:`plot_energy`;
- :mod:`.walls`: the walls of analyses -- :func:`plot_wall_temperature`, :func:`plot_wall_loops`,
  :func:`plot_wall_amplitude`;
- :mod:`.devices`: the other devices (fluid viscous, friction) -- :func:`plot_device_loops`;
- :mod:`.ida`: :func:`plot_ida_curves`, :func:`plot_fragility`;
- :mod:`.design`: :func:`plot_damping_curve`; code designs -- :func:`plot_design_profiles`,
  :func:`plot_drift_spread`;
- :mod:`.collapse`: FEMA P695 assessments -- :func:`plot_collapse_ida`, :func:`plot_pushover`,
  :func:`plot_collapse_fragility`;
- :mod:`.verification`: ASCE 7-16 verifications -- :func:`plot_suite_spectra`, :func:`plot_story_drifts`.
"""

from .collapse import plot_collapse_fragility, plot_collapse_ida, plot_pushover
from .design import plot_damping_curve, plot_design_profiles, plot_drift_spread
from .devices import plot_device_loops
from .element import plot_loops
from .ida import plot_fragility, plot_ida_curves
from .response import (
                       plot_drift_envelope,
                       plot_energy,
                       plot_roof_displacement,
                       plot_story_hysteresis,
                       plot_wall_hysteresis,
)
from .verification import plot_story_drifts, plot_suite_spectra
from .walls import plot_wall_amplitude, plot_wall_loops, plot_wall_temperature

__all__ = ["plot_collapse_fragility", "plot_collapse_ida", "plot_damping_curve", "plot_design_profiles",
           "plot_device_loops", "plot_drift_envelope", "plot_drift_spread", "plot_energy", "plot_fragility",
           "plot_ida_curves", "plot_loops", "plot_pushover", "plot_roof_displacement", "plot_story_drifts",
           "plot_story_hysteresis", "plot_suite_spectra", "plot_wall_amplitude", "plot_wall_hysteresis",
           "plot_wall_loops", "plot_wall_temperature"]
