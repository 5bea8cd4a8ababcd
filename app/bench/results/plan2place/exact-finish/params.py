"""`plan2place_exact`'s settings (it is opt-in, so its time matters less than the default's): as first shipped (at most
9 objects free, Z3 at 0.1 s per object, never in a crowded room) against Z3 at 0.25 s per object and crowded rooms
allowed (shipped since), on the `human` rooms where the `bench-human/` run found Z3 meeting more at a lower energy (5
seeds), and on 20 `dense` diagnosis plans x 2 seeds (its time in crowded rooms); writes `params.md` here:

    PYTHONPATH=. python app/bench/results/plan2place/exact-finish/params.py
"""
import statistics
import time
from pathlib import Path

from app.bench.gates import diagnosis_plans
from app.bench.placement import score
from models.datasets import load_dataset
from models.placement import exact_finish, get_solver
from models.placement.polish import crowded

HERE = Path(__file__).parent
ROOMS = ("FloorPlan1", "FloorPlan2", "FloorPlan16", "FloorPlan17", "FloorPlan27", "FloorPlan316", "FloorPlan318",
         "FloorPlan326", "FloorPlan424", "FloorPlan428")
SMALL = exact_finish.small  # at most MAX_OBJECTS free
VARIANTS = {"first shipped": (0.1, lambda plan, fixed=0: SMALL(plan, fixed) and not crowded(plan)),
            "0.25 s, crowded too": (0.25, SMALL)}


def run(plans, seeds) -> dict[str, list[dict]]:
    out = {name: [] for name in VARIANTS}
    solver = get_solver("plan2place_exact")
    for plan in plans:
        for seed in seeds:
            for name, (budget, small) in VARIANTS.items():
                exact_finish.BUDGET_S, exact_finish.small = budget, small
                t0 = time.perf_counter()
                layout = solver.solve(plan, seed)
                m = score(plan, layout)
                out[name].append({"cs": m["constraint_satisfaction"], "energy": m["energy"],
                                  "ms": 1000 * (time.perf_counter() - t0) / len(plan.objects)})
    exact_finish.BUDGET_S, exact_finish.small = VARIANTS["0.25 s, crowded too"]
    return out


if __name__ == "__main__":
    human = [r.plan for r in load_dataset("human") if r.plan.id.removeprefix("human-") in ROOMS]
    lines = ["`plan2place_exact`'s settings; mean constraints met (x 100), mean energy, PTO p50 / mean (ms per object)",
             "", "| plans | variant | constraints | energy | PTO p50 | PTO mean |",
             "| --- | --- | --- | --- | --- | --- |"]
    for label, plans, seeds in (("human, 10 rooms x 5 seeds", human, range(5)),
                                ("dense, 20 diagnosis plans x 2 seeds", diagnosis_plans("dense", 20), range(2))):
        for name, rows in run(plans, seeds).items():
            ms = [r["ms"] for r in rows]
            lines.append(f"| {label} | {name} | {100 * statistics.mean(r['cs'] for r in rows):.2f} | "
                         f"{statistics.mean(r['energy'] for r in rows):.3f} | {statistics.median(ms):.1f} | "
                         f"{statistics.mean(ms):.1f} |")
    (HERE / "params.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
