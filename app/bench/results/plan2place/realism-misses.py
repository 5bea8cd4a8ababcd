"""Which realism checks Plan2Place fails, and whether the plan or the energy's prior could have told it: each failed
check of its layouts on the diagnosis plans (20 per set, seed 0), by kind (wall habit, free-standing habit,
companion); a habit split by whether the plan's own placement asks the opposite (`middle` for a wall-standing type,
`edge` for a free-standing one), a companion by whether the prior (the 92 training rooms) holds the pair as
companions at all (`RelationPrior.companion_gap`) where the judge (the 28 held-out rooms) does. Writes
realism-misses.md beside this script:

    PYTHONPATH=. python app/bench/results/plan2place/realism-misses.py
"""

from collections import Counter
from pathlib import Path

from app.bench.gates import SETS, diagnosis_plans
from models.constraints import read_constraints
from models.energy.prior import relation_prior
from models.metrics.realism import checks
from models.placement import get_solver

KINDS = ("habit", "habit, the plan asks the opposite", "companion, a companion in the prior too",
         "companion, not in the prior")
OPPOSITE = {"wall": "middle", "free": "edge"}  # the plan's placement that contradicts each habit
BLIND = (KINDS[1], KINDS[3])  # what the plan contradicts or the prior does not ask the placer for


def kind(plan, placements: dict[str, str], check, prior) -> str:
    if check.kind != "companion":
        return KINDS[1] if placements.get(check.object_id) == OPPOSITE[check.kind] else KINDS[0]
    obj = plan.object(check.object_id)
    held = prior.companion_gap(plan.room.type, obj.type, check.other) is not None
    return KINDS[2] if held else KINDS[3]


def main() -> str:
    prior, solver = relation_prior(), get_solver("plan2place")
    lines = ["Plan2Place's realism checks on the diagnosis plans (20 per set, seed 0): failed / all, by kind. A habit "
             "(a wall-standing type against a wall facing into the room, a free-standing one off the walls) split by "
             "whether the plan's placement asks the opposite; a companion (near enough) by whether the energy's prior "
             "(92 training rooms) holds the pair as companions.", "",
             "| set | " + " | ".join(KINDS) + " | failed checks the plan contradicts or the prior does not ask for |",
             "| --- |" + " --- |" * (len(KINDS) + 1)]
    for ds in SETS:
        failed, total = Counter(), Counter()
        for plan in diagnosis_plans(ds, 20):
            placements = {oid: oc.placement for oid, oc in
                          read_constraints(plan.constraints, [o.id for o in plan.objects]).objects.items()}
            for check in checks(plan, solver.solve(plan, seed=0)):
                k = kind(plan, placements, check, prior)
                total[k] += 1
                failed[k] += not check.passed
        blind = sum(failed[k] for k in BLIND) / max(sum(failed.values()), 1)
        lines.append(f"| {ds} | " + " | ".join(f"{failed[k]} / {total[k]}" for k in KINDS) + f" | {100 * blind:.0f} % |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    text = main()
    (Path(__file__).parent / "realism-misses.md").write_text(text)
    print(text)
