"""The paper's energy weights (lambda_1..5) and the constants of each term."""

WEIGHTS = {"rel": 4.0, "collision": 1.5, "oob": 0.35, "nav": 1.5, "aff": 1.5}
PRIOR_LAMBDA = 1.0  # lambda of E_rel's data prior factor (1 + lambda * prior)
AFF_OUTSIDE = 1.0  # lambda_1 of E_aff: the clearance region leaves the room
AFF_BLOCKED = 1.0  # lambda_2 of E_aff: per object that stands in the clearance region
ROBOT_RADIUS = 0.2
NAV_CELL = 0.05  # occupancy grid resolution, metres
ACCESS_DEPTH = 0.6  # depth of the strip in front of an object where the robot must be able to stand
EPS = 1e-8
