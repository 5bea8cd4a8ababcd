"""The world model: what AI2-THOR objects exist, how big they are, where they go, what people call them."""

from models.world.catalogue import LAMPS, Catalogue, ObjectType, catalogue
from models.world.rooms import INFER, ROOM_TYPES, UnknownRoomType, normalise_room_type, requested_room_type

__all__ = ["Catalogue", "INFER", "LAMPS", "ObjectType", "ROOM_TYPES", "UnknownRoomType", "catalogue",
           "normalise_room_type", "requested_room_type"]
