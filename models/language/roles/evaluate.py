"""Role accuracy of the rule baseline, the learned head and the hybrid (rules' key / inference, the
head's anchor) on every language set and its de-duplicated part, given the labelled objects.

    python -m models.language.roles.evaluate [HEAD.pt | LORA_RUN_DIR] [FEATURE_CACHE_DIR]

The features are cached (default: runs/roles/eval-features for the frozen encoder, LORA_RUN_DIR/eval-features).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from models.datasets.language_sets import load_language_set
from models.language.roles import RuleRoles, decode
from models.language.roles.model import LearnedRoles
from models.language.roles.train import cached_features, pairs_of
from models.metrics.language import RoleCounts

SETS = ("id_eval", "valid_unseen", "ts", "os")
METHODS = ("rules", "minilm", "hybrid")
FROZEN_CACHE = Path("runs/roles/eval-features")


def evaluate(weights: str | None = None, cache: Path | None = None) -> dict:
    import torch
    learned, rules, out = LearnedRoles(weights), RuleRoles(), {}
    cache = cache or (Path(weights) / "eval-features" if learned.encoder is not None else FROZEN_CACHE)
    for name in SETS:
        rows = load_language_set(name)
        with torch.no_grad():
            x = cached_features(pairs_of(rows)[0], cache / name, compute=learned.features)
            p = torch.sigmoid(learned.head(x)).tolist()
        dedup = {r.instruction for r in load_language_set(name + "_dedup")}
        for sub in ("", "_dedup"):
            counts, k = {m: RoleCounts() for m in METHODS}, 0
            for r in rows:
                types = [o.type for o in r.label.objects]
                pr, k = p[k:k + len(types)], k + len(types)
                if sub and r.instruction not in dedup:
                    continue
                ruled = rules.predict(r.instruction, types)
                anchor = max(range(len(types)), key=lambda i: pr[i][1])
                preds = {"rules": ruled, "minilm": decode(*([q[c] for q in pr] for c in range(3))),
                         "hybrid": [(a - {"anchor"}) | ({"anchor"} if i == anchor else set())
                                    for i, a in enumerate(ruled)]}
                for m in METHODS:
                    for o, roles in zip(r.label.objects, preds[m], strict=True):
                        counts[m].add(roles, o.roles)
            out[name + sub] = {"pairs": sum(counts["rules"].counts["key"].values()),
                               **{m: counts[m].summary() for m in METHODS}}
    return out


def table(results: dict) -> str:
    lines = ["| set | pairs | " + " | ".join(f"{m} key / anchor / inference" for m in METHODS) + " |",
             "| --- | --- |" + " --- |" * len(METHODS)]
    for name, r in results.items():
        cells = [" / ".join(f"{100 * r[m][f'{c}_accuracy']:.2f}" for c in ("key", "anchor", "inference"))
                 for m in METHODS]
        lines.append(f"| {name} | {r['pairs']} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


if __name__ == "__main__":
    res = evaluate(sys.argv[1] if len(sys.argv) > 1 else None, Path(sys.argv[2]) if len(sys.argv) > 2 else None)
    print(table(res))
    print(json.dumps(res))
