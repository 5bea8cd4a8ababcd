"""The candidate grid's spacing as a variant: `CandidateScorer.__init__` with the spacing given (the shipped
rule: 0.1 m in rooms up to 30 m^2, else 0.15 m). A probe of whether a coarser grid keeps the layouts' quality
and saves time; DFS, MILP and Z3 are not run by it."""
from models.placement.candidates import CandidateScorer

SHIPPED = CandidateScorer.__init__


def spaced(step: float):
    """`CandidateScorer.__init__` with `step` m between candidate centres in every room (wall-flush kept)."""
    def init(self, problem, step_=None, like=None):
        SHIPPED(self, problem, step_ or step, like)
    return init


def coarse_steps(step: float):
    """`greedy._steps` whose steps choose among candidates `step` m apart (its episode's scorer while stepping), the
    repairs after them on the shipped grid (the scorer is swapped back when the steps are done)."""
    from models.placement import greedy
    shipped = greedy._steps

    def steps(plan, rng, choose, fixed, observer, first, shares=None, how=None):
        def make(problem, like=None):
            return CandidateScorer(problem, like=shares.coarse) if shares is not None else CandidateScorer(problem, step)
        greedy.CandidateScorer = make
        try:
            ep = shipped(plan, rng, choose, fixed, observer, first, shares, how)
        finally:
            greedy.CandidateScorer = CandidateScorer
        ep.coarse = ep.scorer
        ep.scorer = CandidateScorer(ep.problem, like=shares.scorer) if shares is not None else CandidateScorer(ep.problem)
        return ep
    return steps


def coarse_steps_off_crowded(step: float):
    """`coarse_steps(step)` in rooms that are not `crowded` (polish.crowded); the shipped steps in those that are."""
    from models.placement import greedy
    from models.placement.polish import crowded
    shipped, coarse = greedy._steps, coarse_steps(step)

    def steps(plan, *args, **kwargs):
        return (shipped if crowded(plan) else coarse)(plan, *args, **kwargs)
    return steps
