"""ALFRED annotations (bundled) and the task-graph labels interfaces.md derives from their pddl params."""

from __future__ import annotations

import gzip
import json
from dataclasses import dataclass
from functools import cache
from importlib import resources

from models.values import Provenance, TaskGraph, TaskObject

# ALFRED's pddl names that the AI2-THOR catalogue spells differently.
ALFRED_TYPE_NAMES = {"Glassbottle": "Bottle"}
SCENE_ROOMS = ((1, 30, "kitchen"), (201, 230, "living room"), (301, 330, "bedroom"), (401, 430, "bathroom"))


@dataclass(frozen=True)
class Annotation:
    split: str
    task_type: str
    instruction: str
    object_target: str
    parent_target: str
    toggle_target: str
    sliced: bool
    floor_plan: str

    @property
    def room_type(self) -> str:
        n = int(self.floor_plan.removeprefix("FloorPlan"))
        return next(room for lo, hi, room in SCENE_ROOMS if lo <= n <= hi)

    def label_objects(self) -> set[str]:
        """The task's object types: target, receptacle, fridge / microwave, lamp, knife."""
        return {t for t, _, o in self.label_triplets() for t in (t, o)} or {self.target}

    @property
    def target(self) -> str:
        return ALFRED_TYPE_NAMES.get(self.object_target, self.object_target)

    def label_triplets(self) -> set[tuple[str, str, str]]:
        t = self.target
        out = set()
        if self.sliced:
            out.add((t, "sliced_with", "Knife"))
        if self.task_type == "pick_cool_then_place_in_recep":
            out.add((t, "cooled_in", "Fridge"))
        if self.task_type == "pick_heat_then_place_in_recep":
            out.add((t, "heated_in", "Microwave"))
        if self.task_type == "look_at_obj_in_light":
            out.add((t, "examined_under", self.toggle_target))
        else:
            out.add((t, "placed_at", ALFRED_TYPE_NAMES.get(self.parent_target, self.parent_target)))
        return out


    def task_graph(self) -> TaskGraph:
        """The ground-truth task graph of interfaces.md: the target is key, the receptacle or lamp is the
        anchor (and key, as ALFRED annotators name it), the fridge, microwave and knife are inferred."""
        roles: dict[str, list[str]] = {}
        for obj, rel, other in sorted(self.label_triplets(), key=lambda t: RELATION_ORDER.index(t[1])):
            roles.setdefault(obj, ["key"])
            roles.setdefault(other, ["key", "anchor"] if rel in ("placed_at", "examined_under") else ["inference"])
        return TaskGraph(instruction=self.instruction, room_type=self.room_type, task_type=self.task_type,
                         objects=[TaskObject(type=t, roles=r) for t, r in roles.items()],
                         relations=sorted(self.label_triplets(), key=lambda t: RELATION_ORDER.index(t[1])),
                         sliced=self.sliced, provenance=Provenance(stage="task_graph", method="alfred-labels"))


RELATION_ORDER = ("sliced_with", "cooled_in", "heated_in", "placed_at", "examined_under")


@cache
def load_annotations(split: str | None = None) -> tuple[Annotation, ...]:
    """ALFRED rows of one split (train, valid_seen, valid_unseen), or all of them."""
    raw = resources.files("models").joinpath("data/alfred_annotations.jsonl.gz").read_bytes()
    rows = [json.loads(line) for line in gzip.decompress(raw).decode().splitlines() if line]
    return tuple(Annotation(split=r["split"], task_type=r["task_type"], instruction=r["task_desc"],
                            object_target=r["object_target"], parent_target=r["parent_target"],
                            toggle_target=r["toggle_target"], sliced=r["object_sliced"], floor_plan=r["floor_plan"])
                 for r in rows if split is None or r["split"] == split)
