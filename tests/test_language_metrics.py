"""Task-graph and role metrics: exact values on small graphs, no points for refusals or empty graphs."""

import pytest

from models.datasets.language_sets import load_language_set
from models.language import InstructionError, RuleParser
from models.metrics.language import graph_edit_distance, score, score_graphs, score_roles
from models.values import TaskGraph, TaskObject

LABEL = TaskGraph(instruction="Put a chilled bread on the counter", room_type="kitchen",
                  task_type="pick_cool_then_place_in_recep",
                  objects=[TaskObject(type="Bread", roles=["key"]), TaskObject(type="CounterTop", roles=["key", "anchor"]),
                           TaskObject(type="Fridge", roles=["inference"])],
                  relations=[("Bread", "cooled_in", "Fridge"), ("Bread", "placed_at", "CounterTop")])


class Row:
    def __init__(self, label):
        self.instruction, self.room_type, self.label = label.instruction, label.room_type, label


def test_perfect_graph_scores_full_marks():
    m = score_graphs([LABEL], [Row(LABEL)])
    assert m["object_f1"] == 1 and m["irecall"] == 1 and m["ged"] == 0
    assert all(m[f"{r}_accuracy"] == 1 for r in ("key", "anchor", "inference"))


def test_edit_distance_counts_each_edit():
    wrong = LABEL.model_copy(update={
        "objects": [TaskObject(type="Bread", roles=["key"]), TaskObject(type="DiningTable", roles=["key", "anchor"]),
                    TaskObject(type="Fridge", roles=["key"])],
        "relations": [("Bread", "cooled_in", "Fridge"), ("Bread", "placed_at", "DiningTable")]})
    # CounterTop out, DiningTable in (2 nodes), Fridge roles differ (1), placed_at edge swapped (2)
    assert graph_edit_distance(wrong, LABEL) == 5
    assert graph_edit_distance(None, LABEL) == 3 + 2


def test_refusal_and_empty_graph_earn_nothing():
    def refuse(text, room):
        raise InstructionError("no")
    m = score(refuse, [Row(LABEL)])
    assert m["object_f1"] == 0 and m["irecall"] == 0 and m["ged"] == 5 and m["unparsed"] == 1
    assert m["key_recall"] == 0 and m["anchor_f1"] == 0
    empty = LABEL.model_copy(update={"objects": [], "relations": []})
    assert score_graphs([empty], [Row(LABEL)])["object_f1"] == 0


def test_role_metrics_of_a_classifier():
    m = score_roles(lambda text, types: [{"key"}] * len(types), [Row(LABEL)])
    assert m["n_pairs"] == 3
    assert m["key_recall"] == 1 and m["key_precision"] == pytest.approx(2 / 3)
    assert m["anchor_accuracy"] == pytest.approx(2 / 3) and m["inference_recall"] == 0


def test_rule_parser_on_a_real_set():
    rows = load_language_set("id_eval")[:60]
    m = score(RuleParser(), rows)
    assert 0.8 < m["object_f1"] <= 1 and 0.5 < m["irecall"] <= 1 and m["n"] == 60
