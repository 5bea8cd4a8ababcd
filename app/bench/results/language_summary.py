"""The README's summary of the shipped language default, from the stored bench (language.json): object F1 / iRecall /
GED of the rules, the model alone and `combined` (the default policy) on the evaluation sets and their
de-duplicated parts, the default's role accuracy end to end and its latency.

    python app/bench/results/language_summary.py   # -> language-summary.md
"""

import json
from pathlib import Path

HERE = Path(__file__).parent
SETS = ("id_eval", "id_eval_dedup", "valid_unseen", "valid_unseen_dedup", "ts", "os")
sets = json.loads((HERE / "language.json").read_text())["sets"]


def triple(m: dict) -> str:
    return f"{100 * m['object_f1']:.2f} / {100 * m['irecall']:.2f} / {m['ged']:.2f}"


lines = ["| set | n | rules | model alone (LoRA) | **default** (`combined`) | default roles: key / anchor / inference acc. "
         "| default p50 / p90 (ms) |", "| --- | ---: | --- | --- | --- | --- | --- |"]
for name in SETS:
    r = sets[name]
    d = r["combined"]
    roles = " / ".join(f"{100 * d[f'{c}_accuracy']:.1f}" for c in ("key", "anchor", "inference"))
    lines.append(f"| {name} | {d['n']} | {triple(r['rules'])} | {triple(r['lora'])} | **{triple(d)}** | {roles} | "
                 f"{d['p50_ms']:.0f} / {d['p90_ms']:.0f} |")
(HERE / "language-summary.md").write_text("object F1 / iRecall / GED (x 100 but GED); `ts_dedup` and `os_dedup` "
                                          "equal `ts` and `os`\n\n" + "\n".join(lines) + "\n")
print("\n".join(lines))
