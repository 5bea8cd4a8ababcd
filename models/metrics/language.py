"""Task-graph and role metrics for instruction parsers and role classifiers (issue 10).

A row is anything with `instruction`, `room_type` and `label` (a TaskGraph), e.g. a
`models.datasets.language_sets.LabelledInstruction`. A parser that raises InstructionError on a row
earns an empty graph there: no objects, no triplets, no roles (a refusal never scores).

- object F1: micro-averaged over rows, predicted object types vs labelled types (as sets);
- iRecall: the share of labelled (subject, relation, object) triplets predicted exactly (micro);
- GED: graph edit distance per row, averaged. Nodes are identified by their type (types are unique
  within a task graph) and labelled with their role set; edges are keyed by (subject, object) and
  labelled with the relation. GED = nodes in only one graph + shared nodes whose role sets differ
  + edges in only one graph + shared edges whose relation differs (every edit costs 1);
- roles: for each class (key, anchor, inference), over the (row, object type) pairs of the union of
  labelled and predicted objects (a missing or invented object has the empty role set on one side):
  accuracy, precision, recall and F1 of "has this role".
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Protocol

from models.language.base import InstructionError
from models.values import ROLES, TaskGraph


class LabelledRow(Protocol):
    instruction: str
    room_type: str
    label: TaskGraph


ParserFn = Callable[[str, "str | None"], TaskGraph]


def graph_edit_distance(pred: TaskGraph | None, label: TaskGraph) -> int:
    """The edit distance defined in the module docstring (pred None = the empty graph)."""
    p_nodes = {o.type: frozenset(o.roles) for o in pred.objects} if pred else {}
    l_nodes = {o.type: frozenset(o.roles) for o in label.objects}
    p_edges = {(s, o): r for s, r, o in pred.relations} if pred else {}
    l_edges = {(s, o): r for s, r, o in label.relations}
    nodes = len(p_nodes.keys() ^ l_nodes.keys()) + sum(p_nodes[t] != l_nodes[t] for t in p_nodes.keys() & l_nodes.keys())
    edges = len(p_edges.keys() ^ l_edges.keys()) + sum(p_edges[e] != l_edges[e] for e in p_edges.keys() & l_edges.keys())
    return nodes + edges


class RoleCounts:
    """Per-class confusion counts of role predictions over (row, object) pairs."""

    def __init__(self) -> None:
        self.counts = {r: {"tp": 0, "fp": 0, "fn": 0, "tn": 0} for r in ROLES}

    def add(self, pred: Iterable[str], label: Iterable[str]) -> None:
        pred, label = set(pred), set(label)
        for r in ROLES:
            c = self.counts[r]
            c[("t" if (r in pred) == (r in label) else "f") + ("p" if r in pred else "n")] += 1

    def add_graphs(self, pred: TaskGraph | None, label: TaskGraph) -> None:
        p = {o.type: o.roles for o in pred.objects} if pred else {}
        lab = {o.type: o.roles for o in label.objects}
        for t in p.keys() | lab.keys():
            self.add(p.get(t, ()), lab.get(t, ()))

    def summary(self) -> dict[str, float]:
        out: dict[str, float] = {}
        for r, c in self.counts.items():
            n = sum(c.values())
            precision = c["tp"] / (c["tp"] + c["fp"]) if c["tp"] + c["fp"] else 0.0
            recall = c["tp"] / (c["tp"] + c["fn"]) if c["tp"] + c["fn"] else 0.0
            out[f"{r}_accuracy"] = (c["tp"] + c["tn"]) / n if n else 0.0
            out[f"{r}_precision"], out[f"{r}_recall"] = precision, recall
            out[f"{r}_f1"] = 2 * precision * recall / (precision + recall) if precision + recall else 0.0
        return out


def _as_fn(parser) -> ParserFn:
    return parser.parse if hasattr(parser, "parse") else parser


def score_graphs(preds: list[TaskGraph | None], rows: list[LabelledRow]) -> dict[str, float]:
    """Every metric for predictions already made (None = the parser refused the row)."""
    tp = fp = fn = hit = wanted = task_ok = 0
    ged = 0
    roles = RoleCounts()
    for pred, row in zip(preds, rows, strict=True):
        label = row.label
        p_types = {o.type for o in pred.objects} if pred else set()
        l_types = {o.type for o in label.objects}
        tp, fp, fn = tp + len(p_types & l_types), fp + len(p_types - l_types), fn + len(l_types - p_types)
        p_trip = {tuple(r) for r in pred.relations} if pred else set()
        l_trip = {tuple(r) for r in label.relations}
        hit, wanted = hit + len(p_trip & l_trip), wanted + len(l_trip)
        ged += graph_edit_distance(pred, label)
        task_ok += bool(pred) and pred.task_type == label.task_type
        roles.add_graphs(pred, label)
    n = len(rows)
    precision, recall = tp / (tp + fp) if tp + fp else 0.0, tp / (tp + fn) if tp + fn else 0.0
    return {"n": n, "object_precision": precision, "object_recall": recall,
            "object_f1": 2 * precision * recall / (precision + recall) if precision + recall else 0.0,
            "irecall": hit / wanted if wanted else 0.0, "ged": ged / n if n else float("nan"),
            "task_type_accuracy": task_ok / n if n else 0.0,
            "unparsed": sum(p is None for p in preds), "uncertain": sum(bool(p and p.uncertain) for p in preds),
            **roles.summary()}


def score(parser, rows: Iterable[LabelledRow], room_given: bool = True) -> dict[str, float]:
    """Every metric of a parser (an object with .parse or a function (instruction, room_type) ->
    TaskGraph) over labelled rows; the room type is passed unless room_given is False."""
    fn, rows = _as_fn(parser), list(rows)
    preds: list[TaskGraph | None] = []
    for row in rows:
        try:
            preds.append(fn(row.instruction, row.room_type if room_given else None))
        except InstructionError:
            preds.append(None)
    return score_graphs(preds, rows)


def score_roles(predict: Callable[[str, list[str]], list[set[str]]], rows: Iterable[LabelledRow]) -> dict[str, float]:
    """Role metrics of a role classifier given the labelled objects (as the paper evaluates f_theta2):
    predict(instruction, object types) -> one role set per type."""
    counts = RoleCounts()
    for row in rows:
        types = [o.type for o in row.label.objects]
        for obj, pred in zip(row.label.objects, predict(row.instruction, types), strict=True):
            counts.add(pred, obj.roles)
    return {"n_pairs": sum(counts.counts["key"].values()), **counts.summary()}
