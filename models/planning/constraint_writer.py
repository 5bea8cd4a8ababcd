"""RoomPlan -> ConstraintPlan: Holodeck-vocabulary constraints from the placement priors.

Each floor object gets a global placement (`edge` if the catalogue's prior says it stands against a
wall, else `middle`) and relations to the objects it belongs with: chairs around their table, a
nightstand beside the bed, the fridge near the counter. An inference object with no such relation is
kept near the anchor, so that everything the task needs is at hand.
"""

from __future__ import annotations

from models.constraints import Constraint, ObjectConstraints, write_constraints
from models.values import ConstraintPlan, Provenance, RoomPlan
from models.world import catalogue
from models.world.catalogue import Catalogue

# constrained type -> [(target type, relations)], first matching target wins.
PAIR_RULES: dict[str, list[tuple[str, tuple[str, ...]]]] = {
    "Chair": [("DiningTable", ("around",)), ("Desk", ("in front of", "face to")), ("CounterTop", ("near",))],
    "Stool": [("CounterTop", ("in front of", "face to")), ("DiningTable", ("around",))],
    "SideTable": [("Bed", ("side of",)), ("Sofa", ("side of",)), ("ArmChair", ("side of",))],
    "CoffeeTable": [("Sofa", ("in front of",)), ("ArmChair", ("in front of",))],
    "ArmChair": [("CoffeeTable", ("near", "face to")), ("Sofa", ("near",)), ("Bed", ("far",))],
    "Ottoman": [("ArmChair", ("in front of",)), ("Sofa", ("in front of",))],
    "FloorLamp": [("ArmChair", ("side of",)), ("Sofa", ("side of",)), ("Desk", ("near",))],
    "Sofa": [("TVStand", ("face to", "far")), ("CoffeeTable", ("face to",))],
    "Fridge": [("CounterTop", ("near",))],
    "Sink": [("CounterTop", ("near",)), ("Toilet", ("near",))],
    "GarbageCan": [("CounterTop", ("near",)), ("Desk", ("near",)), ("Toilet", ("near",)), ("Sink", ("near",))],
    "Toilet": [("Sink", ("near",))],
    "ClothesDryer": [("WashingMachine", ("side of",))],
    "LaundryHamper": [("WashingMachine", ("near",)), ("Dresser", ("near",))],
    "DogBed": [("Sofa", ("near",)), ("Bed", ("near",))],
    "Desk": [("Bed", ("far",))],
}
MAX_RELATIONS = 3


class ConstraintWriter:
    name = "prior-rules"

    def __init__(self, cat: Catalogue | None = None):
        self.cat = cat or catalogue()

    def write(self, plan: RoomPlan) -> ConstraintPlan:
        by_type: dict[str, list[str]] = {}
        for o in plan.objects:
            by_type.setdefault(o.type, []).append(o.id)
        anchor = next((o for o in plan.objects if o.role == "anchor"), None)
        chairs_at_table = sum(1 for o in plan.objects if o.type == "Chair") if "DiningTable" in by_type else 0

        lines = []
        for o in plan.objects:
            placement = self.cat.default_placement(o.type)
            if o.type == "DiningTable" and chairs_at_table >= 3:
                placement = "middle"
            relations: list[Constraint] = []
            for target_type, names in PAIR_RULES.get(o.type, []):
                targets = [t for t in by_type.get(target_type, []) if t != o.id]
                if targets:
                    relations = [Constraint(n, targets[0]) for n in names]
                    break
            if not relations and o.role == "inference" and anchor is not None and anchor.id != o.id:
                relations = [Constraint("near", anchor.id)]
            lines.append(ObjectConstraints(o.id, placement, relations[:MAX_RELATIONS]))
        return ConstraintPlan(id=plan.id, room=plan.room, objects=plan.objects, constraints=write_constraints(lines),
                              provenance=Provenance(stage="constraint_plan", method=self.name,
                                                    seed=plan.provenance.seed if plan.provenance else None))
