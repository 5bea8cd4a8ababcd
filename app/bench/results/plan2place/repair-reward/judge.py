"""decision.md's two steps, by lookahead-critic/judge.py's code (the same tables and the same rule), here with the
fresh plans at 1/8.

    PYTHONPATH=. python app/bench/results/plan2place/repair-reward/judge.py select runs/repair-reward/repair-ep-*.npz
    PYTHONPATH=. python app/bench/results/plan2place/repair-reward/judge.py fresh CHOSEN.npz runs/repair-reward/control-ep-2000.npz
"""

import sys
from pathlib import Path

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "lookahead-critic"))
from judge import main, offset_plans  # noqa: E402  (lookahead-critic/judge.py)

if __name__ == "__main__":
    sys.exit(main(sys.argv[1], [Path(p) for p in sys.argv[2:]], here=HERE, fresh=lambda ds: offset_plans(ds, "1/8")))
