"""Read after gate 1 failed: the same regrets on the *training* steps (the plans the critic was fitted on), before and
after each epoch: can the inputs carry the look-ahead's ranking at all, or only not to other plans?

    PYTHONPATH=. python app/bench/results/plan2place/afterstate-critic/seen.py OUT.pt DATA.pkl ...   # -> seen.log
"""

import pickle
import sys
from pathlib import Path

import numpy as np
import torch

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE))
from fit import SEED, regrets  # noqa: E402

from models.placement.plan2place.agent import start_from  # noqa: E402
from models.placement.plan2place.network import Plan2PlaceNet  # noqa: E402
from models.placement.plan2place.policy import SHIPPED, shipped_weights  # noqa: E402

out, data = Path(sys.argv[1]), [Path(p) for p in sys.argv[2:]]
steps = [s for d in data for s in pickle.loads(d.read_bytes())]
plans = sorted({s["plan"] for s in steps})
held = set(np.random.default_rng(SEED).permutation(plans)[: len(plans) // 5])
train = [s for s in steps if s["plan"] not in held][:1500]
net = Plan2PlaceNet(shipped_weights().net)
start_from(net, Path("models") / SHIPPED)
print("training steps, epoch 0 (shipped critic):", regrets(net, train), flush=True)
for e in range(1, 5):
    net.load_state_dict(torch.load(out.with_name(f"{out.stem}-e{e}.pt"), weights_only=True))
    print(f"training steps, epoch {e}:", regrets(net, train), flush=True)
