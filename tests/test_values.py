"""The JSON formats of interfaces.md load into the typed values and come back out unchanged."""

import json

import pytest
from pydantic import ValidationError

from models.values import ConstraintPlan, Layout, TaskGraph

TASK_GRAPH = {"instruction": "Put a chilled bread on the counter", "room_type": "kitchen",
              "task_type": "pick_cool_then_place_in_recep",
              "objects": [{"type": "Bread", "roles": ["key"]}, {"type": "CounterTop", "roles": ["key", "anchor"]},
                          {"type": "Fridge", "roles": ["inference"]}],
              "relations": [["Bread", "cooled_in", "Fridge"], ["Bread", "placed_at", "CounterTop"]]}
PLAN = {"id": "p01",
        "room": {"type": "kitchen", "width": 4.2, "depth": 5.0,
                 "doors": [{"wall": "south", "center": 1.1, "width": 0.9}],
                 "windows": [{"wall": "north", "center": 2.0, "width": 1.2}]},
        "objects": [{"id": "fridge-0", "type": "Fridge", "size": {"x": 0.75, "y": 1.85, "z": 0.7}, "role": "inference"},
                    {"id": "countertop-0", "type": "CounterTop", "size": {"x": 2.4, "y": 0.9, "z": 0.65},
                     "role": "anchor"}],
        "constraints": "fridge-0 | edge | near, countertop-0\ncountertop-0 | edge"}
LAYOUT = {"plan_id": "p01", "solver": "plan2place", "seed": 0,
          "placements": [{"id": "fridge-0", "type": "Fridge", "x": 0.4, "z": 4.6, "rotation": 180,
                          "size": {"x": 0.75, "y": 1.85, "z": 0.7}}],
          "unplaced": [{"id": "stool-1", "reason": "no collision-free position left"}],
          "warnings": ["line 7: unknown constraint 'next to' read as 'near'"],
          "timing": {"total_s": 0.08, "per_object_s": 0.006}}


@pytest.mark.parametrize("model,doc", [(TaskGraph, TASK_GRAPH), (ConstraintPlan, PLAN), (Layout, LAYOUT)])
def test_interface_examples_round_trip(model, doc):
    value = model.model_validate(doc)
    back = json.loads(json.dumps(value.model_dump(mode="json", exclude_none=True)))
    for key, expected in doc.items():
        assert back[key] == expected or json.loads(json.dumps(expected)) == back[key]


def test_round_trip_keeps_optional_extensions():
    value = TaskGraph.model_validate({**TASK_GRAPH, "sliced": True})
    assert TaskGraph.model_validate_json(value.model_dump_json()) == value


@pytest.mark.parametrize("patch,field", [
    ({"objects": [{"id": "a", "type": "Chair", "size": {"x": -1, "y": 1, "z": 1}}]}, "size"),
    ({"room": {"type": "kitchen", "width": 3, "depth": 3, "doors": [{"wall": "up", "center": 1, "width": 1}]}}, "wall"),
    ({"room": {"type": "kitchen", "width": 3, "depth": 3, "doors": [{"wall": "south", "center": 2.9, "width": 1}]}},
     "does not fit"),
    ({"objects": [{"id": "a", "type": "Chair", "size": {"x": 1, "y": 1, "z": 1}}] * 2}, "appears twice"),
])
def test_bad_plans_are_rejected_with_the_field_named(patch, field):
    with pytest.raises(ValidationError, match=field):
        ConstraintPlan.model_validate({**PLAN, **patch})


def test_unknown_relation_is_rejected():
    with pytest.raises(ValidationError, match="unknown relation"):
        TaskGraph.model_validate({**TASK_GRAPH, "relations": [["Bread", "next_to", "Fridge"]]})
