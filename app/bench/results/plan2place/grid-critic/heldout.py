"""How sure is gate 1? The held-out per-step regret of the chosen critic minus the policy's and minus greedy's,
averaged per plan, with a 95 % bootstrap interval over the held-out plans (read after gate 1; prints heldout.txt).

    PYTHONPATH=. python app/bench/results/plan2place/grid-critic/heldout.py CRITIC.pt DATA.pkl ...
"""
import pickle
import sys
from pathlib import Path

import numpy as np
import torch

sys.path.insert(0, str(Path(__file__).parent))
from fit import GridCritic, predicted, split, tensors  # noqa: E402

from app.bench.paired import interval  # noqa: E402


def main(critic: Path, data: list[Path]) -> None:
    steps = [s for d in data for s in pickle.loads(d.read_bytes())]
    t = tensors(steps)
    _, _, held = split(steps)
    net = GridCritic()
    net.load_state_dict(torch.load(critic))
    with torch.no_grad():
        pick = torch.cat([predicted(net, t, held[i:i + 256]).argmin(1) for i in range(0, len(held), 256)])
    f = torch.where(t["m"][held], t["f"][held], float("inf"))
    best = f.min(1).values
    regret = {"critic": f.gather(1, pick[:, None])[:, 0] - best, "greedy": f[:, 0] - best,
              "policy": f.gather(1, t["policy"][held][:, None])[:, 0] - best}
    differ = (torch.where(t["m"][held], t["f"][held], float("-inf")).max(1).values - best) > 1e-9
    plans = [steps[int(i)]["plan"] for i in held]
    rng = np.random.default_rng(0)
    for other in ("policy", "greedy"):
        diffs: dict[str, list[float]] = {}
        for k in np.flatnonzero(differ.numpy()):
            diffs.setdefault(plans[k], []).append(float(regret["critic"][k] - regret[other][k]))
        mean, lo, hi = interval(diffs, rng)
        print(f"critic - {other}: {mean:+.4f} [{lo:+.4f}, {hi:+.4f}] per step, over {len(diffs)} held-out plans")


if __name__ == "__main__":
    main(Path(sys.argv[1]), [Path(p) for p in sys.argv[2:]])
