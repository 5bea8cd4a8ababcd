"""Parser accuracy on ALFRED: object F1 and triplet recall against labels from the pddl params.

Object F1 is micro-averaged over annotations (set of predicted types vs set of label types); triplet
recall is the share of label triplets the parser produced exactly; task-type accuracy is printed too.
"""

from __future__ import annotations

import time
from collections import Counter

from models.language import InstructionError, RuleParser
from models.language.alfred import Annotation, load_annotations


def score(parser, rows: tuple[Annotation, ...], room_given: bool = True) -> dict[str, float]:
    tp = fp = fn = 0
    trip_hit = trip_all = task_ok = failures = 0
    per_task: Counter[str] = Counter()
    per_task_ok: Counter[str] = Counter()
    start = time.perf_counter()
    for row in rows:
        labels, triplets = row.label_objects(), row.label_triplets()
        try:
            graph = parser.parse(row.instruction, row.room_type if room_given else None)
            pred = {o.type for o in graph.objects}
            pred_trip = {tuple(r) for r in graph.relations}
            ok_task = graph.task_type == row.task_type
        except InstructionError:
            pred, pred_trip, ok_task = set(), set(), False
            failures += 1
        tp += len(pred & labels)
        fp += len(pred - labels)
        fn += len(labels - pred)
        trip_hit += len(pred_trip & triplets)
        trip_all += len(triplets)
        task_ok += ok_task
        per_task[row.task_type] += 1
        per_task_ok[row.task_type] += ok_task
    elapsed = time.perf_counter() - start
    precision, recall = tp / max(tp + fp, 1), tp / max(tp + fn, 1)
    out = {"n": len(rows), "object_precision": precision, "object_recall": recall,
           "object_f1": 2 * precision * recall / max(precision + recall, 1e-12),
           "triplet_recall": trip_hit / max(trip_all, 1), "task_type_accuracy": task_ok / max(len(rows), 1),
           "unparsed": failures, "ms_per_instruction": 1000 * elapsed / max(len(rows), 1)}
    for t in per_task:
        out[f"task_acc[{t}]"] = per_task_ok[t] / per_task[t]
    return out


def main(args) -> int:
    rows = load_annotations(args.split)
    parser = RuleParser()
    print(f"rule-based parser on ALFRED {args.split} ({len(rows)} annotations, labels from pddl_params)")
    for room_given in (True, False):
        result = score(parser, rows, room_given)
        print(f"  room type {'given' if room_given else 'inferred'}:")
        for k, v in result.items():
            print(f"    {k:42s} {v:.4f}" if isinstance(v, float) else f"    {k:42s} {v}")
    return 0
