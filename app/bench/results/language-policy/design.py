"""Design figures of the combination policy `rules-first-fieldwise`, on the design sets only: the 1,000
policy rows of `h3ds bench language` and the development sets of language-augment/dev.py (dev ts and
dev os, seed 13; dev id is a subset of the policy rows). No evaluation or confirmation row is read.

    PYTHONPATH=. python app/bench/results/language-policy/design.py

From the shipped adapter's cached readings only (no decoding). Writes design.md next to this file:
per field, where the rules' and the model's readings differ, who was right (the analysis the policy
was built from); every policy on the design sets; the fieldwise policy's FIELD_CONFIDENCE varied.
"""

from __future__ import annotations

import math
import sys
from collections import Counter
from pathlib import Path

from app.bench.language import POLICY_ROWS, lora_readings, read_all, readings_cache, score_parsers, unseen_train_rows

HERE = Path(__file__).parent
FIELDS = ("task_type", "sliced", "target", "destination")
THRESHOLDS = (0.7, 0.8, 0.9, 0.95)


class _Cached:
    """Stands in for the model: every reading must already be cached."""

    def load(self):
        raise RuntimeError("a reading is missing from the cache")


def design_sets() -> dict[str, list]:
    """The policy rows and the TS / OS development sets (dev.py, seed 13)."""
    sys.path.insert(0, str(HERE.parent / "language-augment"))
    from dev import dev_sets
    dev = dev_sets()
    return {"policy rows": unseen_train_rows(POLICY_ROWS), "dev ts": dev["dev ts"], "dev os": dev["dev os"]}


def field_disagreements(rows, readings, rules) -> dict[str, Counter]:
    """Per field, over rows the rules read with a relation and do not flag: where the two readings differ,
    who is right ("rules", "model", "neither"), split by whether each reading's type is named in the
    text (targets, destinations) or by the model's probability (task type, slicing: sure = p >=
    FIELD_CONFIDENCE)."""
    from models.language import InstructionError
    from models.language.alfred import named_types
    from models.language.combined import FIELD_CONFIDENCE, rule_fields
    from models.language.llm.graph_text import GraphFields
    out = {f: Counter() for f in FIELDS}
    for row in rows:
        text = " ".join(row.instruction.split())
        rec = readings[text, row.room_type]
        model = GraphFields(rec["fields"][0], bool(rec["fields"][1]), *rec["fields"][2:])
        try:
            ruled = rules.parse(text, row.room_type)
        except InstructionError:
            continue
        theirs, label, named = rule_fields(ruled), rule_fields(row.label), named_types(text)
        if theirs is None or ruled.uncertain:
            continue
        for i, f in enumerate(FIELDS):
            r, m, truth = getattr(theirs, f), getattr(model, f), getattr(label, f)
            if r == m:
                continue
            right = "rules" if r == truth else "model" if m == truth else "neither"
            if f in ("target", "destination"):
                case = f"rules' {'named' if r in named else 'unnamed'}, model's {'named' if m in named else 'unnamed'}"
            else:
                case = f"model {'sure' if math.exp(rec['logprob'][i]) >= FIELD_CONFIDENCE else 'unsure'}"
            out[f][case, right] += 1
    return out


def main() -> int:
    from models.language import RuleParser
    from models.language import combined as policies
    from models.language.combined import FIELDWISE, POLICIES, CombinedParser
    from models.language.llm.parser import default_adapter

    sets = design_sets()
    rows = [r for s in sets.values() for r in s]
    readings = lora_readings(rows, _Cached(), readings_cache(default_adapter()), progress=False)
    rules = RuleParser()
    lines = ["Design sets of the combination policy (no evaluation or confirmation row): the 1,000 policy rows, "
             "dev ts / dev os (seed 13, language-augment/dev.py); shipped adapter, cached readings, room type given",
             "",
             "Where the rules' and the model's fields differ (rows the rules read with a relation, not flagged), "
             "who was right: rules / model / neither", "",
             "| set | field | case | rules | model | neither |", "| --- | --- | --- | ---: | ---: | ---: |"]
    for name, set_rows in sets.items():
        for field, counts in field_disagreements(set_rows, readings, rules).items():
            for case in sorted({c for c, _ in counts}):
                lines.append(f"| {name} | {field} | {case} | " + " | ".join(
                    str(counts[case, who]) for who in ("rules", "model", "neither")) + " |")
    combined = {p: CombinedParser(rules=rules, policy=p) for p in POLICIES}
    graphs, seconds = read_all(rows, readings, rules, combined)
    scored = {k: score_parsers(v, graphs, seconds) for k, v in sets.items()}
    columns = ["rules", "lora", *POLICIES]
    lines += ["", "Policies (object F1 / iRecall / GED)", "", "| set | n | " + " | ".join(columns) + " |",
              "| --- | ---: |" + " --- |" * len(columns)]
    lines += [f"| {k} | {r['rules']['n']} | " + " | ".join(
        f"{100 * r[c]['object_f1']:.2f} / {100 * r[c]['irecall']:.2f} / {r[c]['ged']:.3f}" for c in columns) + " |"
        for k, r in scored.items()]
    lines += ["", f"{FIELDWISE} with FIELD_CONFIDENCE varied (object F1 / iRecall / GED; "
              f"shipped: {policies.FIELD_CONFIDENCE})", "", "| FIELD_CONFIDENCE | " + " | ".join(sets) + " |",
              "| ---: |" + " --- |" * len(sets)]
    chosen = policies.FIELD_CONFIDENCE
    for threshold in THRESHOLDS:
        policies.FIELD_CONFIDENCE = threshold
        graphs, seconds = read_all(rows, readings, rules, {"fieldwise": combined[FIELDWISE]})
        cells = [score_parsers(v, graphs, seconds)["fieldwise"] for v in sets.values()]
        lines.append(f"| {threshold} | " + " | ".join(
            f"{100 * r['object_f1']:.2f} / {100 * r['irecall']:.2f} / {r['ged']:.3f}" for r in cells) + " |")
    policies.FIELD_CONFIDENCE = chosen
    print("\n".join(lines))
    (HERE / "design.md").write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
