# python app/bench/results/plan2place/polish-tuning.py > app/bench/results/plan2place/polish-tuning.md
"""Polish variants on plans no benchmark table uses: 40 varied-room validation plans, 20 unseen_a and 20 dense
plans off the benchmark's sample (records 5::25 and 7::15); greedy's layout after make-room and restore-access,
then the variant. CPU ms per object of the polish alone. Written for the polish of its time (free moves only in
crowded rooms): since crowded rooms get one-pose make-way moves (make-way-strips/), its "free moves only" and
"crowded rooms too" variants no longer mean what they say, and polish-tuning.md stays as that code measured it."""
import sys, time, numpy as np, statistics
from models.datasets.varied import varied_plan
from models.datasets import load_dataset
from app.bench.placement import score
from models.placement.greedy import Episode
import models.placement.repair as R
from models.placement import polish as PL

VARIANTS = {"none": None, "free moves only": dict(make_way=False), "shipped (3 poses per make-way move)": {},
            "5 poses per make-way move": dict(tries=5), "make-way moves in crowded rooms too": dict(crowded=False)}
sets = [("varied", [varied_plan(0, e, "validation") for e in range(40)]),
        ("unseen_a (off-sample)", [r.plan for r in load_dataset("unseen_a")[5::25][:20]]),
        ("dense (off-sample)", [r.plan for r in load_dataset("dense")[7::15][:20]])]
print("| variant | set | constraints | energy | polish ms/object mean | p50 |\n| --- | --- | --- | --- | --- | --- |")
for name, v in VARIANTS.items():
    for sname, plans in sets:
        T, rows = [], []
        for p in plans:
            ep = Episode(p); ep.finish_greedily(); R.make_room(ep); R.restore_access(ep)
            if v is not None:
                PL.MAKE_WAY_POSES = v.get("tries", 3)
                orig_crowded = PL.crowded
                if v.get("crowded") is False:
                    PL.crowded = lambda plan: False
                if v.get("make_way") is False:
                    PL.crowded = lambda plan: True
                t = time.process_time(); PL.polish(ep); T.append((time.process_time() - t) / len(p.objects))
                PL.crowded = orig_crowded
            rows.append(score(p, ep.layout("g", 0, 0.0)))
        c = 100 * statistics.mean(r["constraint_satisfaction"] for r in rows)
        e = statistics.mean(r["energy"] for r in rows)
        tm = f"{1000*np.mean(T):.2f} | {1000*np.median(T):.2f}" if T else "- | -"
        print(f"| {name} | {sname} | {c:.2f} | {e:.3f} | {tm} |", flush=True)
