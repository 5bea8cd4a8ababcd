"""A stored scene of either kind (a single room or an apartment) -> its house JSON or GLB."""

from __future__ import annotations

from models.exports.apartment import apartment_glb, apartment_house
from models.exports.procthor_house import to_house
from models.values import Scene
from models.values.apartment import Apartment


def house_of(value: Scene | Apartment) -> dict:
    return apartment_house(value) if isinstance(value, Apartment) else to_house(value)


def glb_of(value: Scene | Apartment) -> bytes:
    if isinstance(value, Apartment):
        return apartment_glb(value)
    from models.exports.glb import to_glb  # trimesh takes ~0.6 s to import
    return to_glb(value)
