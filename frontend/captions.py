"""The studio's words: status notes, step captions and read-out tables, as pure functions of the values shown
(tested without a browser)."""

from __future__ import annotations

import re

from frontend.replay import RoomOf, one_room, repeated
from models.exports.glb import ROLE_COLOURS
from models.metrics import SceneMetrics
from models.metrics.realism import Check, passed_share
from models.placement import ALL_OBJECTS, EXACT_FINISH, PlacementStep
from models.placement.exact_finish import MIN_MET, small
from models.placement.reach_kept import WALLS
from models.values import ConstraintPlan, TaskGraph, Unplaced

ROLE_MARK = {role: f'<span style="color:rgb{tuple(ROLE_COLOURS[role][:3])}">&#9632;</span>'
             for role in ("key", "anchor", "inference")}
HABIT = {"wall": "stands against a wall, facing into the room", "free": "stands free of the walls",
         "companion": "stands by a {}"}


def placing_progress(steps: list[PlacementStep]) -> str:
    """The progress line while the placer works: how many steps so far and whether the last one placed an object
    or repaired one placed before in the same solve (frontend.replay.repeated)."""
    doing = "repairing" if repeated(steps, len(steps)) else "placing"
    return f"⏳ Placing objects: step {len(steps)}, {doing} (last `{steps[-1].object_id}`)…"


def unplaced_note(unplaced: list[Unplaced]) -> str:
    """What the placer left out and why; for an object left out to keep a task object reachable, the solver that
    places it anyway."""
    if not unplaced:
        return ""
    lines = [f"- `{u.id}`: {u.reason}" for u in unplaced]
    if any(u.reason == WALLS for u in unplaced):
        lines.append(f"The solver `{ALL_OBJECTS}` places every object it can, even one that cuts a task object off.")
    return "Left out:\n" + "\n".join(lines)


def exact_note(m: SceneMetrics, plan: ConstraintPlan, solver: str) -> str:
    """For a layout in a small room meeting under `MIN_MET` of its constraints, where the default's repairs do not ask
    Z3, the solver that does."""
    if solver == EXACT_FINISH or m.constraint_satisfaction >= MIN_MET or not small(plan):
        return ""
    return (f"\n\nMost constraints are not met: the default asks Z3 over a small room only where it meets at least "
            f"{MIN_MET:.0%} of them (in rooms this crowded Z3 rarely did better); the solver `{EXACT_FINISH}` "
            "(Task tab) asks it here too.")


def habits_note(found: list[Check]) -> str:
    """The realism judge's checks the layout fails, each as the habit of the iTHOR rooms it misses (a stand-in for a
    human or VLM judge: models.metrics.realism)."""
    missed = [c for c in found if not c.passed]
    if not missed:
        return ""
    lines = [f"- `{c.object_id}` {HABIT[c.kind].format(c.other)}" for c in missed]
    return "\n\nHabits of the iTHOR rooms not kept here:\n" + "\n".join(lines)


def metrics_table(m: SceneMetrics, energy: float, habits: list[Check]) -> str:
    """The Constraints tab's metrics of a layout (models.metrics), its realism habits and total energy."""
    return ("| metric | value |\n| --- | --- |\n"
            f"| CNT | {100 * m.cnt:.0f} % |\n| SR | {pct(m.sr)} |\n| NAV | {100 * m.nav:.1f} % |\n"
            f"| Key_NAV | {pct(m.key_nav)} |\n| OOB | {100 * m.oob:.0f} % |\n| collisions | {m.collisions} |\n"
            f"| constraints met | {100 * m.constraint_satisfaction:.0f} % |\n"
            f"| realism (iTHOR habits) | {pct(passed_share(habits))} |\n"
            f"| energy (total) | {energy:.3f} |" + habits_note(habits))


def graph_summary(graph: TaskGraph) -> str:
    """The Task tab's reading of the task graph: room, task, the objects of each role and the relations."""
    lines = [f"**Room:** {graph.room_type} · **task:** `{graph.task_type}`", ""]
    for role, title in (("key", "Key objects"), ("anchor", "Anchor object"), ("inference", "Inference objects")):
        names = [o.type for o in graph.objects if role in o.roles]
        lines.append(f"{ROLE_MARK[role]} **{title}:** {', '.join(names) if names else '—'}")
    lines += ["", "**Relations:** " + ("; ".join(f"{a} *{r}* {b}" for a, r, b in graph.relations) or "—")]
    return "\n\n".join(lines)


def step_caption(steps: list[PlacementStep], shown: int, obj, room: str = "", room_of: RoomOf = one_room) -> str:
    """The Placement tab's line for step number `shown` (1-based) of `steps`: the object, where it went (`obj`:
    the object as displayed, None if unplaced) and, for a repair's move or a guarded choice, its reason. A step
    placing an object already placed in the same solve of its room is a repair's (frontend.replay.repeated)."""
    step = steps[shown - 1]
    where = "no valid position (unplaced)" if obj is None else \
        f"x {obj.x:.2f} m, z {obj.z:.2f} m, facing {obj.rotation:.0f}°"
    doing = "repair: placing" if repeated(steps, shown, room_of) else "placing"
    why = f" ({step.why})" if step.why else ""
    return f"**Step {shown} / {len(steps)}**: {room}{doing} `{step.object_id}` at {where}{why}"


def parser_note(graph: TaskGraph) -> str:
    """The parser's doubts in words (several tasks, not English, unknown objects), shown with the scene."""
    if not graph.uncertain:
        return ""
    messages = graph.messages or ["the parser is unsure about this instruction"]
    return "⚠ **Check the task graph:** " + " ".join(messages)


def slug(text: str) -> str:
    """A file-name stem from a scene's name or instruction."""
    return re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-")[:48]


def pct(value: float | None) -> str:
    """A metric in percent, or n/a when the plan has nothing for it to check (no task object)."""
    return "n/a" if value is None else f"{100 * value:.0f} %"
