from hypothesis import given
from hypothesis import strategies as st

from models.constraints import read_constraints, write_constraints

IDS = ["fridge-0", "countertop-0", "chair-0"]


def read(text):
    return read_constraints(text, IDS, default_placement=lambda oid: "middle" if oid == "chair-0" else "edge")


def test_reads_the_holodeck_format():
    cs = read("fridge-0 | edge | near, countertop-0\ncountertop-0 | edge\nchair-0 | middle | face to, fridge-0")
    assert cs.warnings == []
    assert [c.text() for c in cs.objects["fridge-0"].relations] == ["near, countertop-0"]
    assert cs.objects["chair-0"].placement == "middle"


def test_misspelled_names_map_to_the_nearest_and_say_so():
    cs = read("fridge-0 | edge | next to, countertop-0 | infront of, chair-0 | Face To , chair-0")
    assert [c.name for c in cs.objects["fridge-0"].relations] == ["near", "in front of", "face to"]
    assert any("line 1" in w and "'next to' read as 'near'" in w for w in cs.warnings)
    assert any("'infront of' read as 'in front of'" in w for w in cs.warnings)


def test_unknown_targets_self_targets_and_unknown_names_are_ignored_with_a_warning():
    cs = read("fridge-0 | edge | near, stove-9 | near, fridge-0 | hovering over, chair-0\nghost-1 | edge")
    assert cs.objects["fridge-0"].relations == []
    text = "\n".join(cs.warnings)
    assert "'stove-9' does not exist" in text and "itself" in text and "'hovering over'" in text
    assert "unknown object id 'ghost-1'" in text


def test_objects_without_a_line_get_the_prior_placement():
    cs = read("fridge-0 | edge")
    assert cs.objects["chair-0"].placement == "middle" and cs.objects["countertop-0"].placement == "edge"


def test_id_case_and_underscores_are_forgiven():
    cs = read("Fridge_0 | edge | near, COUNTERTOP-0")
    assert cs.objects["fridge-0"].relations[0].target == "countertop-0"


def test_write_then_read_is_identity():
    cs = read("fridge-0 | edge | near, countertop-0 | face to, chair-0\ncountertop-0 | edge\nchair-0 | middle")
    again = read(write_constraints(cs))
    assert again.objects == cs.objects and again.warnings == []


@given(st.text(max_size=300))
def test_never_raises_on_any_text(text):
    cs = read(text)
    assert set(cs.objects) == set(IDS)
