"""The floor critic of decision.md (not in the paper, not shipped: gate 2 failed): a small convolutional network over
a raster of a candidate's after-state, predicting how much energy the objects still to come will add if the
candidate is taken; its inference in float32 numpy (equal to fit.py's torch module to 3e-8), the rasters and numbers
gen.py stores, and Plan2Place's placing loop with the critic's choice (`place_with_floor`), which gate2.py runs.
"""

from __future__ import annotations

import numpy as np

from models.energy import navigation as nav
from models.placement.greedy import WALLS_OFF, Episode, place_stepwise
from models.placement.plan2place.features import choose_subset, observe

SIDE = 32  # raster cells per room side
ROOM_SCALE = 8.0  # m: room sides are given to the critic over this
LAYERS = 5  # unstandable cells, reached cells, the candidate's body, front strips, doorways
NUMBERS = 9


def _bins(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Adaptive average pooling's bin edges from n cells onto SIDE (floor(i n / SIDE), ceil((i + 1) n / SIDE))."""
    i = np.arange(SIDE)
    return (i * n) // SIDE, -((-(i + 1) * n) // SIDE)


def pooled(layers: np.ndarray) -> np.ndarray:
    """(C, nx, nz) -> (C, SIDE, SIDE): each cell the mean of its bin of the grid, as torch's adaptive_avg_pool2d."""
    c, nx, nz = layers.shape
    integral = np.zeros((c, nx + 1, nz + 1))
    integral[:, 1:, 1:] = layers.cumsum(1).cumsum(2)
    (x0, x1), (z0, z1) = _bins(nx), _bins(nz)
    total = (integral[:, x1][:, :, z1] - integral[:, x0][:, :, z1] - integral[:, x1][:, :, z0]
             + integral[:, x0][:, :, z0])
    return total / ((x1 - x0)[:, None] * (z1 - z0)[None, :])


def raster(ep: Episode) -> np.ndarray:
    """(LAYERS, SIDE, SIDE) uint8 of the episode's state after its last placing (x 255)."""
    setup = ep.setup
    grid = setup.grid

    def boxes(bs) -> np.ndarray:
        out = np.zeros_like(setup.blocked)
        for b in bs:
            out |= nav.in_box_mask(grid, b)
        return out

    layers = np.stack([setup.blocked, setup.reach, nav.in_box_mask(grid, ep.placed[-1].body),
                       boxes(setup.zones.values()), boxes(setup.door_boxes)]).astype(np.float64)
    return np.round(pooled(layers) * 255).astype(np.uint8)


def numbers(ep: Episode, gap: float, logp: float) -> np.ndarray:
    """The after-state's NUMBERS: room sides, share of objects still to come, their footprint over the free floor,
    the largest of them over the room's longer side, free and reached floor shares, the candidate's step energy
    above the step's lowest (x 10), and the actor's log-probability of it."""
    room = ep.problem.plan.room
    w, d = room.width, room.depth
    rest = ep.order[ep.i:]
    free = max(w * d - sum(p.width * p.depth for p in ep.placed), 1e-3)
    largest = max((max(o.size.x, o.size.z) for o in rest), default=0.0) / max(w, d)
    return np.array([w / ROOM_SCALE, d / ROOM_SCALE, len(rest) / ep.n, sum(o.size.x * o.size.z for o in rest) / free,
                     largest, 1 - ep.setup.blocked.mean(), ep.setup.reach.mean(), gap, logp], np.float32)


def _conv(x: np.ndarray, w: np.ndarray, b: np.ndarray) -> np.ndarray:
    """3 x 3 convolution, padding 1: (B, C, H, W) -> (B, O, H, W)."""
    bsz, c, h, wd = x.shape
    padded = np.pad(x, ((0, 0), (0, 0), (1, 1), (1, 1)))
    patches = np.lib.stride_tricks.sliding_window_view(padded, (3, 3), axis=(2, 3))  # B, C, H, W, 3, 3
    cols = patches.transpose(0, 2, 3, 1, 4, 5).reshape(bsz * h * wd, c * 9)
    out = cols @ w.reshape(len(w), -1).T + b
    return out.reshape(bsz, h, wd, len(w)).transpose(0, 3, 1, 2)


def _pool2(x: np.ndarray) -> np.ndarray:
    b, c, h, w = x.shape
    return x.reshape(b, c, h // 2, 2, w // 2, 2).max((3, 5))


class FloorCritic:
    """Rasters (B, LAYERS, SIDE, SIDE) uint8 and numbers (B, NUMBERS) -> (B,) the energy still to come."""

    def __init__(self, arrays: dict[str, np.ndarray]):
        self.a = {k: np.asarray(v, np.float32) for k, v in arrays.items()}

    def __call__(self, rasters: np.ndarray, nums: np.ndarray) -> np.ndarray:
        a, relu = self.a, lambda v: np.maximum(v, 0)  # noqa: E731
        h = rasters.astype(np.float32) / 255
        h = _pool2(relu(_conv(h, a["conv.0.weight"], a["conv.0.bias"])))
        h = _pool2(relu(_conv(h, a["conv.3.weight"], a["conv.3.bias"])))
        h = relu(_conv(h, a["conv.6.weight"], a["conv.6.bias"]))
        x = np.concatenate([h.mean((2, 3)), h.max((2, 3)), nums.astype(np.float32)], 1)
        x = relu(x @ a["head.0.weight"].T + a["head.0.bias"])
        return (x @ a["head.2.weight"].T + a["head.2.bias"])[:, 0]


JUDGED = 8  # the step's lowest-energy candidates the critic judges, with the actor's pick
ROOMIER = "the floor critic expects it to leave more room for the objects still to come"  # a step's reason


def after_states(ep: Episode, opts, subset: np.ndarray, judged: np.ndarray, logits: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For the candidates `subset[judged]` of the step (`logits`: the actor's over `subset`): the rasters and the
    numbers of their after-states, and their energies after the step."""
    logp = logits - np.logaddexp.reduce(logits)
    step = opts.terms["total"][subset[judged]]
    rasters, nums, after = [], [], []
    for j, e in zip(judged, step):
        twin = ep.fork()
        twin.apply(opts, int(subset[j]))
        rasters.append(raster(twin))
        nums.append(numbers(twin, 10 * (e - step.min()), float(logp[j])))
        after.append(twin.energy)
    return np.stack(rasters), np.stack(nums), np.array(after)


def floor_choice(ep: Episode, opts, subset: np.ndarray, logits: np.ndarray, a: int, critic: FloorCritic,
                 guard: bool) -> int:
    """Of the step's JUDGED lowest-energy candidates and the actor's pick `a` (indices into `subset`, sorted by
    energy), the one of lowest predicted final energy (its energy after the step + the critic's energy still to
    come) among those that keep every task object reachable (with `guard`; if none does, `a`)."""
    judged = np.array(sorted({*range(min(JUDGED, len(subset))), a}))
    rasters, nums, after = after_states(ep, opts, subset, judged, logits)
    predicted = after + critic(rasters, nums)
    if guard:
        keep = ep.keeping(opts, subset[judged])
        if not keep.any():
            return a
        predicted[~keep] = np.inf
    return int(judged[int(np.argmin(predicted))])


def place_with_floor(critic: FloorCritic):
    """`models.placement.plan2place.policy.place` with the critic's choice after the reach guard (the same
    signature, so that gate2.py can put it in the solver's place)."""
    def place(policy, plan, rng, use_global=True, fixed=None, observer=None, repair=True, guard=True) -> Episode:
        def choose(ep: Episode, opts, rng: np.random.Generator):
            if opts.obj.id in ep.problem.fixed:
                return 0, np.ones(1), ""
            subset = choose_subset(opts, rng)
            logits = policy(observe(ep, opts, subset, use_global))
            a = int(np.argmax(logits))
            p = np.exp(logits - logits[a])
            probs = np.zeros(len(opts.feasible))
            probs[subset] = p / p.sum()
            pick, why = int(subset[a]), ""
            if guard and pick != (guarded := ep.guarded(opts, subset[np.argsort(-logits, kind="stable")])):
                pick, why = guarded, WALLS_OFF
            chosen = int(subset[floor_choice(ep, opts, subset, logits, int(np.flatnonzero(subset == pick)[0]),
                                             critic, guard)])
            return (chosen, probs, ROOMIER) if chosen != pick else (pick, probs, why)

        return place_stepwise(plan, rng, choose, fixed, observer, repair)

    return place
