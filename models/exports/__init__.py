"""Scene -> files, one module per exchange format (as trimesh does)."""
