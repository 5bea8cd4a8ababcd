"""The energy of a layout: the RL reward's negative and the placers' shared objective (paper, Supp. A-1).

E_total = 4 E_rel + 1.5 E_collision + 0.35 E_oob + 1.5 E_nav + 1.5 E_aff

Two implementations that agree: `exact` on polygons (shapely), for judging a layout, and `vectorised`
(numpy boxes and occupancy grids), which scores every candidate pose of the next object at once.
"""
