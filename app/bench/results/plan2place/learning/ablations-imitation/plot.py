"""The README's ablation figure from the stored bench tables (<set>/plan2place.md, the rows with the repairs): final
energy and constraints met of greedy, the untrained network and each ablation, per set.

    python app/bench/results/plan2place/learning/ablations-imitation/plot.py   # -> ablations.png
"""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

HERE = Path(__file__).parent
SETS = ("seen", "unseen_a", "dense")
METRICS = (("energy", "final energy (lower is better)"), ("constraints", "constraints met, % (higher is better)"))
LABELS = {"plan2place_untrained": "untrained", "abl-im-cross (400 ep)": "cross (full)"}


def rows(name: str) -> dict[str, dict[str, float]]:
    lines = [ln for ln in (HERE / name / "plan2place.md").read_text().splitlines() if ln.startswith("| ")]
    head = [c.strip() for c in lines[0].strip("|").split("|")]
    out = {}
    for ln in lines[2:]:
        cells = [c.strip() for c in ln.strip("|").split("|")]
        if "no repair" not in cells[0]:
            name = LABELS.get(cells[0], cells[0].replace(" (400 ep)", "").replace("abl-im-", ""))
            out[name] = {h: float(c) for h, c in zip(head[1:], cells[1:])}
    return out


tables = {s: rows(s) for s in SETS}
solvers = list(tables["seen"])
fig, axes = plt.subplots(len(METRICS), len(SETS), figsize=(13, 5.5))
for i, (key, label) in enumerate(METRICS):
    for j, s in enumerate(SETS):
        ax = axes[i][j]
        vals = [tables[s][n][key] for n in solvers]
        ax.scatter(np.arange(len(solvers)), vals, color=["#888", "#888"] + ["#47a"] * (len(solvers) - 2), zorder=3)
        ax.grid(axis="y", alpha=0.4)
        ax.set_xticks(np.arange(len(solvers)), solvers, rotation=35, fontsize=8)
        ax.set_title(f"{s}: {label}", fontsize=9)
fig.suptitle("Ablations under the imitation set-up, 400 episodes each, with the repairs (grey: greedy and the untrained network)",
             fontsize=10)
fig.tight_layout()
fig.savefig(HERE / "ablations.png", dpi=90)
