"""What one studio tab holds: the undoable values (scene, steps, edits) and the tab's own settings."""

from __future__ import annotations

from dataclasses import dataclass, field

from app.pipeline import Generation
from models.checks import Finding
from models.metrics import SceneMetrics
from models.placement import DEFAULT_SOLVER, PlacementStep
from models.values.apartment import Apartment
from models.values.edit import Edit


@dataclass(frozen=True)
class Values:
    """What undo restores: the scene and everything derived from the designer's edits."""

    gen: Generation | None = None
    steps: tuple[PlacementStep, ...] = ()
    edits: tuple[Edit, ...] = ()
    reference: SceneMetrics | None = None  # the placer's result the designer started from
    moved: tuple[tuple[str, tuple[float, float, float]], ...] = ()  # the designer's moves: id, pose put at
    apartment: Apartment | None = None  # the apartment on screen; `gen` is then its room being edited
    room: int | None = None  # that room's index in the apartment's floorplan order


@dataclass
class State:
    values: Values = field(default_factory=Values)
    shown: int = 0  # objects shown so far in the step animation
    playing: bool = False
    scene_id: int | None = None
    seed: int = 0
    solver: str = DEFAULT_SOLVER
    runs: int = 0  # scenes shown in this tab so far (numbers the status line)
    findings: list[Finding] = field(default_factory=list)
    busy: bool = False
    unsaved: bool = False
    view: str = "fit"  # fit | top | vr: what a refit after a window resize restores
    canvas: tuple[int, int] = (0, 0)

    @property
    def gen(self) -> Generation | None:
        return self.values.gen

    @property
    def steps(self) -> tuple[PlacementStep, ...]:
        return self.values.steps

    @property
    def edits(self) -> tuple[Edit, ...]:
        return self.values.edits
