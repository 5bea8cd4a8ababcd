"""The compact text form of a task graph that the language model writes, and its validation.

    <task> | <whole|sliced> | <Target> | <Destination>        e.g.  cool | whole | Bread | CounterTop

`task` is one word per ALFRED task type (place, look, cool, heat); the destination is the final
receptacle, or the lamp of a look-at task. The rest of the graph follows from these four fields by
ALFRED's task semantics: a cool task adds the fridge, a heat task the microwave, a sliced target the
knife. Four fields keep generation short (about 8 tokens with SmolLM2's tokenizer), which is most of
the parser's latency on a CPU.
"""

from __future__ import annotations

from dataclasses import dataclass

from models.language.alfred import RELATION_ORDER, Annotation
from models.values import Provenance, TaskGraph, TaskObject
from models.world import LAMPS, catalogue

TASK_WORDS: dict[str, str] = {
    "place": "pick_and_place_simple",
    "look": "look_at_obj_in_light",
    "cool": "pick_cool_then_place_in_recep",
    "heat": "pick_heat_then_place_in_recep",
}
WORD_OF_TASK = {v: k for k, v in TASK_WORDS.items()}
SLICE_WORDS = ("whole", "sliced")
SEPARATOR = " | "
PROCESS = {"pick_cool_then_place_in_recep": ("Fridge", "cooled_in"),
           "pick_heat_then_place_in_recep": ("Microwave", "heated_in")}
ROLE_ORDER = ("key", "anchor", "inference")


class GraphTextError(ValueError):
    """Model output that is not a valid compact task graph; the message says which field is wrong."""


@dataclass(frozen=True)
class GraphFields:
    task_type: str
    sliced: bool
    target: str
    destination: str

    def text(self) -> str:
        return SEPARATOR.join(self.words())

    def words(self) -> tuple[str, str, str, str]:
        return (WORD_OF_TASK[self.task_type], SLICE_WORDS[self.sliced], self.target, self.destination)

    def triplets(self) -> list[tuple[str, str, str]]:
        out = []
        if self.sliced:
            out.append((self.target, "sliced_with", "Knife"))
        if self.task_type in PROCESS:
            appliance, rel = PROCESS[self.task_type]
            out.append((self.target, rel, appliance))
        rel = "examined_under" if self.task_type == "look_at_obj_in_light" else "placed_at"
        out.append((self.target, rel, self.destination))
        return sorted(out, key=lambda t: RELATION_ORDER.index(t[1]))


def target_types() -> tuple[str, ...]:
    """Catalogue types the model may name as the target: everything a robot can pick up."""
    cat = catalogue()
    return tuple(sorted(t for t in cat.types if cat[t].pickupable))


def destination_types(task_type: str | None = None) -> tuple[str, ...]:
    """Catalogue types allowed as the destination: the lamps for a look-at task, else any type that is
    not a lamp (small receptacles such as a plate or a pot included) and not part of the room's
    structure (the floor, a mirror: no asset to place)."""
    if task_type == "look_at_obj_in_light":
        return LAMPS
    cat = catalogue()
    return tuple(sorted(t for t in cat.types if t not in LAMPS and cat.placeable(t)))


def fields_of(row: Annotation) -> GraphFields:
    """The training target of an ALFRED annotation."""
    dest = row.toggle_target if row.task_type == "look_at_obj_in_light" else row.task_graph().relations[-1][2]
    return GraphFields(row.task_type, row.sliced, row.target, dest)


def parse_fields(text: str) -> GraphFields:
    """`cool | whole | Bread | CounterTop` -> GraphFields, or GraphTextError naming the bad field."""
    parts = [p.strip() for p in text.strip().split("|")]
    parts = [p for p in parts if p]
    if len(parts) != 4:
        raise GraphTextError(f"expected 4 fields 'task | whole/sliced | Target | Destination', got {text!r}")
    task, sliced, target, dest = parts
    if task not in TASK_WORDS:
        raise GraphTextError(f"unknown task word {task!r}; expected one of {', '.join(TASK_WORDS)}")
    if sliced not in SLICE_WORDS:
        raise GraphTextError(f"second field must be 'whole' or 'sliced', not {sliced!r}")
    task_type = TASK_WORDS[task]
    if target not in target_types():
        raise GraphTextError(f"target {target!r} is not a pickupable AI2-THOR type")
    if dest not in destination_types(task_type):
        raise GraphTextError(f"destination {dest!r} is not allowed for a {task} task")
    return GraphFields(task_type, sliced == "sliced", target, dest)


def graph_of(fields: GraphFields, instruction: str, room_type: str, named: set[str], method: str) -> TaskGraph:
    """The TaskGraph of the fields. Roles follow interfaces.md: key when the instruction names the
    type (`named`, by any synonym), inference when it is required but unnamed; the destination is the
    anchor."""
    roles: dict[str, set[str]] = {}
    for subj, rel, obj in fields.triplets():
        roles.setdefault(subj, set()).add("key" if subj in named or not named else "inference")
        r = roles.setdefault(obj, set())
        r.add("key" if obj in named else "inference")
        if rel in ("placed_at", "examined_under"):
            r.add("anchor")
    return TaskGraph(instruction=instruction, room_type=room_type, task_type=fields.task_type,
                     sliced=fields.sliced, relations=fields.triplets(),
                     objects=[TaskObject(type=t, roles=sorted(r, key=ROLE_ORDER.index)) for t, r in roles.items()],
                     provenance=Provenance(stage="task_graph", method=method))
