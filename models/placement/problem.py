"""A placement problem: a plan with its constraints read, its objects ordered, and impossible ones set aside."""

from __future__ import annotations

from collections.abc import Collection
from dataclasses import dataclass, field, replace

from models.constraints import ConstraintSet, read_constraints
from models.values import ConstraintPlan, PlanObject, Unplaced
from models.world import catalogue

DOOR_CLEARANCE = 0.9  # depth of the free rectangle kept inside every door
# The one time-budget rule for every solver (issue 7): this many seconds per object of the plan, unless
# the caller passes a budget. DFS stops at its first complete layout (as Holodeck's does); MILP and Z3
# use what they need of it; nothing may take longer.
PER_OBJECT_BUDGET_S = 0.5


def time_budget(plan: ConstraintPlan, given: float | None = None) -> float:
    """The budget a solver gets for `plan`: `given` if set, else PER_OBJECT_BUDGET_S per object."""
    return given if given is not None else PER_OBJECT_BUDGET_S * max(len(plan.objects), 1)


def plan_constraints(plan: ConstraintPlan) -> ConstraintSet:
    """A plan's constraint text read for its objects; an object without a line gets its type's default placement."""
    cat = catalogue()
    types = {o.id: o.type for o in plan.objects}
    return read_constraints(plan.constraints, list(types),
                            default_placement=lambda oid: cat.default_placement(types[oid]) if types[oid] in cat
                            else "edge")


@dataclass
class PlacementProblem:
    plan: ConstraintPlan
    constraints: ConstraintSet
    order: list[PlanObject]  # targets before the objects constrained to them, task objects early
    impossible: list[Unplaced] = field(default_factory=list)
    clearance: dict[str, float] = field(default_factory=dict)  # object id -> front clearance depth
    fixed: dict[str, tuple[float, float, float]] = field(default_factory=dict)  # kept poses (x, z, rotation)

    @property
    def warnings(self) -> list[str]:
        return self.constraints.warnings

    @classmethod
    def from_plan(cls, plan: ConstraintPlan, fixed: dict[str, tuple[float, float, float]] | None = None,
                  first: Collection[str] = ()) -> PlacementProblem:
        """`fixed`: poses to keep as they are (a designer re-plans from an edited point onwards); `first`: ids to
        place as early as their targets allow (models.placement.reorder)."""
        cat = catalogue()
        constraints = plan_constraints(plan)
        room = plan.room
        impossible, feasible = [], []
        for o in plan.objects:
            small, large = sorted((o.size.x, o.size.z))
            if small > min(room.width, room.depth) or large > max(room.width, room.depth):
                impossible.append(Unplaced(id=o.id, reason=f"larger than the room ({o.size.x} x {o.size.z} m "
                                                           f"in {room.width} x {room.depth} m)"))
            else:
                feasible.append(o)
        clearance = {o.id: cat.front_clearance(o.type) if o.type in cat else 0.0 for o in plan.objects}
        kept = {k: v for k, v in (fixed or {}).items() if any(o.id == k for o in feasible)}
        order = _fixed_first(_order(feasible, constraints, set(first)), kept)
        return cls(plan, constraints, order, impossible, clearance, kept)

    def reordered(self, first: Collection[str]) -> list[PlanObject]:
        """The order `from_plan` gives with `first` placed as early as their targets allow, without reading the plan
        again."""
        return _fixed_first(_order(self.order, self.constraints, set(first)), self.fixed)

    def with_first(self, first: Collection[str]) -> PlacementProblem:
        """This problem in the order `reordered(first)`: what `from_plan` gives with `first`."""
        return replace(self, order=self.reordered(first))


def _fixed_first(order: list[PlanObject], fixed: Collection[str]) -> list[PlanObject]:
    """`order` with the objects of kept poses moved to its front."""
    return [o for o in order if o.id in fixed] + [o for o in order if o.id not in fixed]


def _order(objects: list[PlanObject], constraints: ConstraintSet, first: set[str]) -> list[PlanObject]:
    """Topological order of the 'target before dependent' graph; cycles are broken by priority.

    Priority: the objects of `first`, then task objects, then wall objects, then larger footprints (Holodeck's habit).
    """
    def priority(o: PlanObject) -> tuple:
        oc = constraints.objects[o.id]
        return (o.id not in first, not o.is_task, oc.placement != "edge", -o.size.x * o.size.z, o.id)

    remaining = {o.id: o for o in objects}
    deps = {o.id: {c.target for c in constraints.objects[o.id].relations if c.target in remaining} for o in objects}
    order: list[PlanObject] = []
    while remaining:
        ready = [o for oid, o in remaining.items() if not (deps[oid] & remaining.keys())]
        pick = min(ready or remaining.values(), key=priority)
        order.append(pick)
        del remaining[pick.id]
    return order
