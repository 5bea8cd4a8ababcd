"""Plan2Place (paper's f_theta3): an actor-critic placer over scored candidate poses.

torch and torch_geometric are imported only by `network`, `agent` and `solver`, which the solver
registry loads lazily, so the CLI and the studio start fast.
"""
