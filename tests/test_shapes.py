"""Procedural object shapes: true size, front +z, more than one box for furniture, closed meshes."""

import numpy as np
import pytest

from models.shapes import FAMILIES, family_of, shape_mesh, shape_parts
from models.world import catalogue

SIZE = (1.2, 0.9, 0.6)


@pytest.mark.parametrize("family", sorted(FAMILIES))
def test_every_family_fills_its_box_and_stays_inside(family):
    object_type = FAMILIES[family][1][0]
    v, f, shades = shape_mesh(object_type, SIZE)
    lo, hi = v.min(axis=0), v.max(axis=0)
    half = np.array(SIZE) / 2
    assert (lo >= -half - 1e-6).all() and (hi <= half + 1e-6).all(), "a part leaves the bounding box"
    assert ((hi - lo) >= 0.85 * np.array(SIZE)).all(), "the shape does not span the asset's size"
    assert len(shades) == len(f) and f.max() < len(v)
    assert len(shape_parts(object_type, SIZE)) > 1


def test_faces_point_outwards():
    """Each part is closed and wound counter-clockwise from outside: the signed volume is positive."""
    for family, (_, types) in FAMILIES.items():
        v, f, _ = shape_mesh(types[0], SIZE)
        a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
        assert np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6 > 0, family


def test_front_is_plus_z():
    """A chair's back, a bed's headboard and a sofa's back are at -z; a fridge's handles at +z."""
    for object_type in ("Chair", "Bed", "Sofa"):
        tallest = max(shape_parts(object_type, SIZE), key=lambda p: p.centre[1] + p.extents[1] / 2)
        assert tallest.centre[2] < 0, object_type
    handles = [p for p in shape_parts("Fridge", SIZE) if p.shade < 1]
    assert handles and all(p.centre[2] > 0 for p in handles)


def test_floor_furniture_types_have_a_shape_family():
    cat = catalogue()
    floor = [t for t in cat.types if cat.is_floor_object(t)]
    shaped = [t for t in floor if family_of(t) != "block"]
    assert len(shaped) >= 0.6 * len(floor), sorted(set(floor) - set(shaped))
    assert family_of("Apple") == "block"


def test_glb_furniture_is_its_shape_at_true_size():
    """In the exported GLB a furniture object is more than one box and spans its asset's size."""
    import io

    import trimesh

    from app.pipeline import Pipeline
    from models.exports.glb import to_glb

    scene = Pipeline().generate("Put a chilled bread on the counter", "kitchen", seed=0).scene
    loaded = trimesh.load(io.BytesIO(to_glb(scene)), file_type="glb")
    furniture = [o for o in scene.objects if family_of(o.type) != "block"]
    assert furniture
    for obj in furniture:
        mesh = loaded.geometry[obj.id]
        assert len(mesh.faces) > 12, f"{obj.id} ({obj.type}) is a single box"
        extents = sorted(mesh.extents)
        assert np.allclose(extents[-1], max(obj.size.x, obj.size.y, obj.size.z), atol=0.02), obj.id
