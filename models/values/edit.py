"""A designer's edit, as the edit log stores it with a scene's version (a move, a carry, a constraint edit, a
re-place, a task-graph correction, an undo...): what was done, to what, and the value before and after."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Edit:
    kind: str
    target: str
    before: object
    after: object
