"""The paper's energy weights (lambda_1..5) and the constants of each term."""

WEIGHTS = {"rel": 4.0, "collision": 1.5, "oob": 0.35, "nav": 1.5, "aff": 1.5, "missing": 8.0}
# "missing" is this project's addition to the paper's five terms: the share of the plan's objects that
# were not placed. Without it an empty layout scores 0, the lowest energy of all. Its weight is twice
# E_rel's, so that one object of a 10-object plan left out (0.8) costs more than placing it with a
# typical violation (a 0.3 m^2 overlap costs 0.13; one broken relation of ten with energy 1 costs 0.38).
PRIOR_LAMBDA = 1.0  # lambda of E_rel's data prior factor (1 + lambda * prior)
AFF_OUTSIDE = 1.0  # lambda_1 of E_aff: the clearance region leaves the room
AFF_BLOCKED = 1.0  # lambda_2 of E_aff: per object that stands in the clearance region
ROBOT_RADIUS = 0.2
NAV_CELL = 0.05  # occupancy grid resolution, metres
ACCESS_DEPTH = 0.6  # depth of the strip in front of an object where the robot must be able to stand
EPS = 1e-8
