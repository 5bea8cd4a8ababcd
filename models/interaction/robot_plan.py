"""The robot's task plan as AI2-THOR actions, and the checker that runs a plan on the exported house's
symbolic state and says whether the task's goal holds at the end (ALFRED's goal conditions).

The plan for the four ALFRED task types (with the knife first when the task slices):
  pick_and_place_simple          fetch target -> put in/on receptacle
  pick_cool_then_place_in_recep  fetch -> fridge: open, put, close (cooled), open, take, close -> put
  pick_heat_then_place_in_recep  fetch -> microwave: open, put, close, on (heated), off, open, take, close -> put
  look_at_obj_in_light           fetch -> walk to the lamp -> switch it on, holding the target
                                 (a lamp alone, "Turn on the lamp", names nothing to hold: walk to it, switch it on)
  sliced                         fetch knife -> slice target -> put the knife back -> the slice is the target
Navigation is a TeleportFull to free floor in front of the object, connected to the robot's start (a
stand-in for a navigation mesh path: the symbolic checker verifies the floor is free and connected).
Object ids are read from the exported house, never invented; a slice's id is AI2-THOR's
`<target id>|<Type>Sliced_1`, which exists once SliceObject has run.
"""

from __future__ import annotations

import math

import numpy as np
import shapely

from models.interaction.symbolic import (
    INTERACT_RANGE,
    SymbolicState,
    _sliced_type,
    execute_step,
    slice_id,
)
from models.geometry import front
from models.values import Scene, TaskGraph
from models.values.interaction import PlanCheck, PlanStep, RobotPlan, StepResult
from models.world import catalogue

CAMERA_HEIGHT = 1.5  # of the default AI2-THOR agent, metres above the floor
APPROACH = 1.0  # the robot stands at most this far from the object (it can act up to INTERACT_RANGE)
BEHIND_PENALTY = 0.5  # metres of detour a cell beside or behind a front-used holder counts as


def house_roles(scene: Scene | None, room: int = 1) -> dict[str, str]:
    """house id -> the scene role of that object (so the task's own objects are chosen over context ones);
    `room` is the number the house gives the scene's room (1 for a single room)."""
    if scene is None:
        return {}
    from models.exports.procthor_house import thor_id
    out = {}
    for o in scene.objects:
        out[thor_id(o, False, room)] = o.role
        for c in o.children:
            out[thor_id(c, True, room)] = c.role
    return out


def _task_parts(graph: TaskGraph) -> dict[str, str]:
    """role in the plan -> object type, from the graph's relations; a look-at graph without one is the lamp alone
    (the parsers' reading of "Turn on the lamp": no target)."""
    if graph.lamp_alone:
        return {"lamp": graph.with_role("key")[0].type}
    parts = {}
    for subject, rel, other in graph.relations:
        parts.setdefault("target", subject)
        key = {"placed_at": "receptacle", "cooled_in": "fridge", "heated_in": "microwave",
               "examined_under": "lamp", "sliced_with": "knife"}[rel]
        parts[key] = other
    if "target" not in parts:
        keys = graph.with_role("key")
        if keys:
            parts["target"] = keys[0].type
    return parts


class _Builder:
    """Writes the plan step by step while running it on a symbolic state, so every step is possible in
    the state the earlier steps leave (an impossible one is recorded as a problem)."""

    def __init__(self, state: SymbolicState, force_action: bool):
        self.state, self.force = state, force_action
        self.steps: list[PlanStep] = []
        self.problems: list[str] = []
        self.at: str | None = None  # floor object the robot stands at

    def act(self, name: str, object_id: str, description: str, **extra) -> bool:
        action = {"action": name, "objectId": object_id, "forceAction": self.force, **extra}
        step = PlanStep(index=len(self.steps), action=action, description=description, target=object_id)
        new, result = execute_step(self.state, step)
        if not result.ok:
            self.problems.append(f"{name} {object_id}: {result.message}")
            return False
        self.steps.append(step)
        self.state = new
        return True

    def goto(self, object_id: str) -> bool:
        root = self.state.root(object_id)
        if self.at == root.id and self.state.distance_to(object_id) <= INTERACT_RANGE:
            return True
        pose = approach_pose(self.state, object_id)
        if pose is None:
            self.problems.append(f"no free floor reachable from the start within {APPROACH} m of {object_id}")
            return False
        x, z, rotation, horizon = pose
        action = {"action": "TeleportFull", "position": {"x": x, "y": self.state.agent_y, "z": z},
                  "rotation": {"x": 0, "y": rotation, "z": 0}, "horizon": horizon, "standing": True}
        step = PlanStep(index=len(self.steps), action=action, description=f"go to {root.id}", target=root.id)
        new, result = execute_step(self.state, step)
        if not result.ok:
            self.problems.append(f"TeleportFull to {root.id}: {result.message}")
            return False
        self.steps.append(step)
        self.state, self.at = new, root.id
        return True

    def fetch(self, object_id: str) -> bool:
        if not self.goto(object_id):
            return False
        o = self.state.objects[object_id]
        container = self.state.objects.get(o.parent) if o.parent else None
        opened = container is not None and container.openable and not container.is_open
        if opened and not self.act("OpenObject", container.id, f"open {container.id}"):
            return False
        if not self.act("PickupObject", object_id, f"pick up {object_id}"):
            return False
        return not opened or self.act("CloseObject", container.id, f"close {container.id}")

    def put(self, receptacle_id: str, close: bool = True) -> bool:
        if not self.goto(receptacle_id):
            return False
        r = self.state.objects[receptacle_id]
        opened = r.openable and not r.is_open
        if opened and not self.act("OpenObject", r.id, f"open {r.id}"):
            return False
        if not self.act("PutObject", r.id, f"put {self.state.held} in/on {r.id}", placeStationary=True):
            return False
        return not (opened and close) or self.act("CloseObject", r.id, f"close {r.id}")


def approach_pose(state: SymbolicState, object_id: str) -> tuple[float, float, float, float] | None:
    """Where the robot stands to use an object: the reachable free cell nearest the object, within
    APPROACH of it, on the front side of its floor holder when that is used from the front; facing it."""
    grid, reachable = state.navigation()
    root, obj = state.root(object_id), state.objects[object_id]
    usable = reachable & state.in_room(state.room_at(root.x, root.z))  # not through a wall from the next room
    gx, gz = grid.mesh()
    xs, zs = gx[usable] + state.room[0], gz[usable] + state.room[1]
    if not len(xs):
        return None
    d = shapely.distance(obj.footprint().polygon(), shapely.points(xs, zs))
    fx, fz = front(root.rotation)
    in_front = (xs - root.x) * fx + (zs - root.z) * fz >= root.depth / 2 - 1e-6
    cat = catalogue()
    front_used = root.type in cat and cat.front_clearance(root.type) > 0
    score = d + np.where(in_front | (not front_used), 0.0, BEHIND_PENALTY) + np.where(d <= APPROACH, 0.0, np.inf)
    k = int(np.argmin(score))
    if not np.isfinite(score[k]):
        return None
    x, z = float(xs[k]), float(zs[k])
    rotation = round(math.degrees(math.atan2(obj.x - x, obj.z - z)) % 360, 1)
    flat = max(math.hypot(obj.x - x, obj.z - z), 1e-3)
    horizon = float(np.clip(round(math.degrees(math.atan2(CAMERA_HEIGHT - obj.y, flat))), -30, 60))
    return round(x, 3), round(z, 3), rotation, horizon


def _choose(state: SymbolicState, type_name: str | None, roles: dict[str, str], prefer: tuple[str, ...],
            exclude: set[str] = frozenset()) -> str | None:
    if type_name is None:
        return None
    found = [o for o in state.of_type(type_name) if o.id not in exclude]
    if not found:
        return None
    return min(found, key=lambda o: (roles.get(o.id) not in prefer, o.id)).id


def robot_plan(scene: Scene | None, house: dict, graph: TaskGraph | None = None,
               force_action: bool = True) -> RobotPlan:
    """The plan for the scene's task on its exported house. `forceAction` is True by default, as ALFRED's
    executor sends it; the symbolic checker still requires the robot within reach of every object."""
    return plan_on_house(house, graph or (scene.task_graph if scene else None), house_roles(scene), force_action)


def plan_on_house(house: dict, graph: TaskGraph | None, roles: dict[str, str], force_action: bool = True) -> RobotPlan:
    """The plan for a task on an exported house (one room or several); `roles`: house id -> scene role."""
    if graph is None:
        return RobotPlan(task_type="", instruction="", steps=[], problems=["the scene has no task graph"])
    state = SymbolicState.from_house(house)
    parts = _task_parts(graph)
    ids = {"target": _choose(state, parts["target"], roles, ("key",))} if "target" in parts else {}
    for part, prefer in (("receptacle", ("anchor", "key")), ("fridge", ("inference",)),
                         ("microwave", ("inference",)), ("lamp", ("anchor", "key")), ("knife", ("inference",))):
        if part in parts:
            ids[part] = _choose(state, parts[part], roles, prefer, exclude={ids.get("target") or ""})
    b = _Builder(state, force_action)
    missing = [f"no {parts[p]} in the exported house (the task's {p})" for p, i in ids.items() if i is None]
    b.problems.extend(missing if parts else ["the task graph names no object to act on"])
    if parts and not missing:
        _write(b, graph, ids)
    objects = {k: v for k, v in ids.items() if v is not None}
    if graph.sliced and ids.get("target"):
        objects["slice"] = slice_id(ids["target"], parts["target"])
    return RobotPlan(task_type=graph.task_type, instruction=graph.instruction, steps=b.steps, objects=objects,
                     problems=b.problems)


def _put_back_place(state: SymbolicState, knife: str) -> str | None:
    """Where the knife goes after slicing: where it came from if that is a receptacle (a knife on a Sink
    asset is not: its basin is), else the nearest open-topped receptacle on the floor."""
    home = state.objects[knife].parent
    if home is not None and state.objects[home].receptacle:
        return home
    k = state.objects[knife]
    surfaces = [o for o in state.objects.values() if o.on_floor and o.receptacle and not o.openable]
    return min(surfaces, key=lambda o: (math.hypot(o.x - k.x, o.z - k.z), o.id)).id if surfaces else None


def _write(b: _Builder, graph: TaskGraph, ids: dict[str, str]) -> None:
    if "target" not in ids:  # the lamp alone
        lamp = ids["lamp"]
        if b.goto(lamp):
            b.act("ToggleObjectOn", lamp, f"switch {lamp} on (the instruction names nothing to look at)")
        return
    target = ids["target"]
    if graph.sliced or "knife" in ids:
        knife = ids.get("knife")
        if knife is None:
            b.problems.append("the task slices but names no knife")
            return
        home = _put_back_place(b.state, knife)
        if not b.fetch(knife) or not b.goto(target):
            return
        t = b.state.objects[target]
        container = b.state.objects.get(t.parent) if t.parent else None
        if container is not None and container.openable and not container.is_open:
            if not b.act("OpenObject", container.id, f"open {container.id}"):
                return
        if not b.act("SliceObject", target, f"slice {target} with {knife}"):
            return
        if home is None:
            b.problems.append(f"nowhere to put {knife} down after slicing")
            return
        if not b.put(home):
            return
        target = slice_id(target, b.state.objects[target].type)
    if not b.fetch(target):
        return
    if graph.task_type == "pick_cool_then_place_in_recep":
        f = ids["fridge"]
        if not (b.put(f, close=False) and b.act("CloseObject", f, f"close {f}: {target} cools")
                and b.act("OpenObject", f, f"open {f}") and b.act("PickupObject", target, f"take {target}")
                and b.act("CloseObject", f, f"close {f}")):
            return
    if graph.task_type == "pick_heat_then_place_in_recep":
        m = ids["microwave"]
        if not (b.put(m, close=False) and b.act("CloseObject", m, f"close {m}")
                and b.act("ToggleObjectOn", m, f"switch {m} on: {target} heats")
                and b.act("ToggleObjectOff", m, f"switch {m} off") and b.act("OpenObject", m, f"open {m}")
                and b.act("PickupObject", target, f"take {target}") and b.act("CloseObject", m, f"close {m}")):
            return
    if graph.task_type == "look_at_obj_in_light":
        lamp = ids["lamp"]
        if b.goto(lamp):
            b.act("ToggleObjectOn", lamp, f"switch {lamp} on and look at {target} in its light")
        return
    b.put(ids["receptacle"])


def goal_conditions(state: SymbolicState, graph: TaskGraph) -> tuple[str, dict[str, bool]]:
    """ALFRED's goal for the task, checked on a state: (description, condition -> holds)."""
    parts = _task_parts(graph)
    t = parts.get("target", "?")
    kind = _sliced_type(t) if graph.sliced else t
    candidates = state.of_type(kind)
    conds: dict[str, list] = {}
    if graph.sliced:
        conds[f"a {t} is sliced"] = [o for o in state.objects.values() if o.type == t and o.sliced]
    if "fridge" in parts:
        conds[f"a {kind} is cooled (was inside a closed {parts['fridge']})"] = [o for o in candidates if o.cooled]
    if "microwave" in parts:
        conds[f"a {kind} is heated (was inside a {parts['microwave']} while on)"] = \
            [o for o in candidates if o.heated]
    if "receptacle" in parts:
        recep = parts["receptacle"]
        conds[f"a {kind} was put in/on a {recep} by the robot"] = [
            o for o in candidates if o.picked and o.parent in state.objects and state.objects[o.parent].type == recep]
    if "lamp" in parts:
        lamp = parts["lamp"]
        held = state.objects.get(state.held) if state.held else None
        if "target" in parts:  # the lamp alone asks only for the light
            conds[f"the robot holds a {kind}"] = [held] if held is not None and held.type == kind else []
        conds[f"a {lamp} within reach is on"] = [o for o in state.of_type(lamp)
                                                  if o.is_on and state.distance_to(o.id) <= INTERACT_RANGE]
    holds = {name: bool(found) for name, found in conds.items()}
    object_conds = [found for name, found in conds.items() if name.startswith(f"a {kind} ")]
    if len(object_conds) > 1:
        common = set.intersection(*({o.id for o in found} for found in object_conds))
        holds[f"one {kind} meets all of these"] = bool(common)
    description = f"{graph.task_type}: " + "; ".join(conds) if conds else f"{graph.task_type}: nothing to check"
    if not conds:
        holds["the task has a goal to check"] = False
    return description, holds


def check_plan(house: dict, plan: RobotPlan, task_graph: TaskGraph) -> PlanCheck:
    """Run every step of the plan on the house's symbolic state, then check the task's goal."""
    state = SymbolicState.from_house(house)
    results: list[StepResult] = []
    failure = None
    for step in plan.steps:
        new, result = execute_step(state, step)
        results.append(result)
        if not result.ok:
            failure = f"step {step.index} {result.action} {step.target or ''}: {result.message}".replace("  ", " ")
            break
        state = new
    goal, holds = goal_conditions(state, task_graph)
    if not plan.steps:
        holds["the plan has steps"] = False
    unmet = [name for name, ok in holds.items() if not ok]
    if failure is None and unmet:
        failure = "goal not met: " + "; ".join(unmet)
        if plan.problems:
            failure += " (plan problems: " + "; ".join(plan.problems) + ")"
    return PlanCheck(ok=failure is None, goal=goal, steps=results, failure=failure, goal_conditions=holds)
