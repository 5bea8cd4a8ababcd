"""The LoRA-or-frozen decision (decision.md) from the two stored evaluations -> result.md.

    python -m models.language.roles.evaluate > frozen-out.txt             (frozen.md / frozen.json: its table / last line)
    python -m models.language.roles.evaluate runs/roles-lora > lora-out.txt  (lora.md / lora.json)
    python app/bench/results/roles-lora/result.py
"""
import json
from pathlib import Path

R = Path(__file__).parent
frozen, lora = (json.loads((R / f"{n}.json").read_text()) for n in ("frozen", "lora"))
lines = ["| set | anchor: frozen / LoRA | learned alone, key (= inference): frozen / LoRA |", "| --- | --- | --- |"]
never_below, above_once = True, False
for s in frozen:
    fa, la = frozen[s]["hybrid"]["anchor_accuracy"], lora[s]["hybrid"]["anchor_accuracy"]
    never_below &= la >= fa
    above_once |= la > fa and not s.endswith("_dedup")
    lines.append(f"| {s} | {100 * fa:.2f} / {100 * la:.2f} | "
                 f"{100 * frozen[s]['minilm']['key_accuracy']:.2f} / {100 * lora[s]['minilm']['key_accuracy']:.2f} |")
verdict = "met: the LoRA encoder replaces the frozen one" if never_below and above_once else \
    "not met: the frozen encoder stays"
(R / "result.md").write_text(
    "Role accuracy given the labelled objects, in % (`python -m models.language.roles.evaluate [RUN]`); the anchor is "
    "`HybridRoles`' (the shipped classifier's), read from the learned model\n\n" + "\n".join(lines) +
    f"\n\ndecision rule (decision.md: LoRA's anchor >= frozen's on all 8 sets and higher on one full set): {verdict}\n")
print((R / "result.md").read_text())
