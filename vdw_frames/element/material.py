"""The trial/commit contract of a "material", after OpenSees's ``UniaxialMaterial``.

``setTrialStrain`` -> ``getStress`` / ``getTangent`` -> ``commitState`` / ``revertToLastCommit``:
an iterating (Newton) integrator asks a material for its force and tangent at trial deformations as
often as it likes, then accepts the last one (``commit``: the state advances) or drops it
(``revert_to_last_commit``).  The walls (:class:`~vdw_frames.element.damper.WallState`, one wall;
:class:`~vdw_frames.element.bank.WallBank`, many) and the story models
(:class:`~vdw_frames.frame.hysteresis.StoryState`) keep it; the frame's compiled integrator uses the
same compiled trial and commit functions inside its loop.

Units: the material's own (walls and stories: deformation mm, force N, tangent N/mm).
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable


@runtime_checkable
class Material(Protocol):
    """Trial/commit: ``trial`` leaves the committed state untouched; ``commit`` accepts the last trial."""

    def trial(self, deformation: float) -> tuple[float, float]:
        """(force, tangent d force / d deformation) at ``deformation``; the committed state is untouched."""
        ...

    def commit(self) -> None:
        """Accept the last trial: the state advances (a ValueError without a trial)."""
        ...

    def revert_to_last_commit(self) -> None:
        """Discard the pending trial."""
        ...
