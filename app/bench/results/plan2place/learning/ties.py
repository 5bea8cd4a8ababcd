"""Where does the learned policy act? At each step of its own episode (no guard, no repairs), how often it leaves
greedy's choice (takes a candidate of higher immediate energy than the lowest) and by how much, how often several
candidates tie for the lowest immediate energy, and how often it takes another of those than greedy's first; for the
shipped and the untrained network, on 16 plans per set off the benchmarks' samples x 2 seeds. From the root:
python app/bench/results/plan2place/learning/ties.py seen,unseen_a,unseen_b,dense,human [RUN.npz,...] > ties.md"""
import sys
from pathlib import Path

import numpy as np

from models.datasets import load_dataset
from models.placement.greedy import Episode
from models.placement.plan2place.agent import fast_policy, load_run, untrained_network
from models.placement.plan2place.features import choose_subset, observe
from models.placement.plan2place.policy import shipped_policy
pols = {"trained": shipped_policy(), "untrained": fast_policy(untrained_network())}
for run in (sys.argv[2].split(",") if len(sys.argv) > 2 else []):  # further runs' weights, by their file name
    pols[Path(run).stem] = fast_policy(load_run(Path(run))[0])
for ds in sys.argv[1].split(","):
    recs = load_dataset(ds, "validation" if ds == "seen" else None); k = max(len(recs) // 20, 1)
    plans = [r.plan for i, r in enumerate(recs) if i % k == k // 2][:16]
    for name, pol in pols.items():
        left, extra, steps, tied, other_tie = 0, [], 0, 0, 0
        for p in plans:
            for seed in (0, 1):
                rng = np.random.default_rng(seed); ep = Episode(p)
                while not ep.done:
                    opts = ep.options()
                    if not len(opts.feasible):
                        ep.apply(opts, None); continue
                    subset = choose_subset(opts, rng)
                    logits = pol(observe(ep, opts, subset, True))
                    pick = int(subset[int(np.argmax(logits))])
                    best = int(np.argmin(opts.terms["total"]))
                    steps += 1
                    ties = np.flatnonzero(opts.terms["total"] <= opts.terms["total"][best] + 1e-12)
                    tied += len(ties) > 1
                    other_tie += len(ties) > 1 and pick != best and pick in ties
                    if opts.terms["total"][pick] > opts.terms["total"][best] + 1e-12:
                        left += 1; extra.append(opts.terms["total"][pick] - opts.terms["total"][best])
                    ep.apply(opts, pick)
        print(ds, name, f"steps {steps} leaves greedy's pick {100*left/steps:.1f} %, immediate energy given up per such step: median {np.median(extra) if extra else 0:.4f}; steps with tied lowest candidates {100*tied/steps:.1f} %, another of them taken {100*other_tie/steps:.1f} %")
