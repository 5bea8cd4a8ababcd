"""Undo / redo of a designer's edits in one tab: whole snapshots of the (immutable) session values."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

LIMIT = 100  # snapshots kept for undo


@dataclass(frozen=True)
class Snapshot:
    label: str  # what the edit that followed this snapshot did ("move fridge-0", "constraints"...)
    values: Any  # the session's values before that edit


class History:
    def __init__(self, limit: int = LIMIT):
        self.limit = limit
        self.done: list[Snapshot] = []
        self.undone: list[Snapshot] = []

    def record(self, label: str, before: Any) -> None:
        """Call before an edit with the values it is about to change; a new edit clears redo."""
        self.done.append(Snapshot(label, before))
        del self.done[:-self.limit]
        self.undone.clear()

    def undo(self, current: Any) -> Snapshot | None:
        """The snapshot to restore (None when there is nothing to undo); `current` becomes redoable."""
        if not self.done:
            return None
        snap = self.done.pop()
        self.undone.append(Snapshot(snap.label, current))
        return snap

    def redo(self, current: Any) -> Snapshot | None:
        if not self.undone:
            return None
        snap = self.undone.pop()
        self.done.append(Snapshot(snap.label, current))
        return snap

    def clear(self) -> None:
        self.done.clear()
        self.undone.clear()
