"""Procedural low-poly shapes per object family, at an asset's true size, front facing +z.

A shape is a few parts (boxes and 8-sided cylinders) in the object's own frame: the origin is the
centre of its bounding box (as `SceneObject.x, y, z`), x is the width, y the height, z the depth and the
front is +z (a chair's seat faces +z, so its back is at -z). Every part stays inside the bounding box,
so the collision and navigation footprints are unchanged. Pure numpy: the studio draws the mesh with
viser and the GLB export writes the same triangles with trimesh.

These are stand-ins for AI2-THOR's asset meshes (not shipped): recognisable silhouettes, not the assets.
"""

from models.shapes.build import FAMILIES, Part, family_of, shape_mesh, shape_parts

__all__ = ["FAMILIES", "Part", "family_of", "shape_mesh", "shape_parts"]
