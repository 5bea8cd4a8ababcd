"""Layout -> Scene: real assets, surface objects as AI2-THOR children, robot start and VR anchor."""

from models.scene.assemble import assemble_scene

__all__ = ["assemble_scene"]
