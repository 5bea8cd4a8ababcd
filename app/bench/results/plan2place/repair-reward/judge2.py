"""decision2.md's two steps, by lookahead-critic/judge.py's code, on fresh2.py's plans (-> selection2.md, fresh2.md).

    PYTHONPATH=. python app/bench/results/plan2place/repair-reward/judge2.py select runs/repair-reward/repair*-ep-*.npz
    PYTHONPATH=. python app/bench/results/plan2place/repair-reward/judge2.py fresh CHOSEN.npz runs/repair-reward/control-ep-2000.npz
"""

import sys
from pathlib import Path

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "lookahead-critic"))
from fresh2 import fresh2  # noqa: E402
from judge import main  # noqa: E402  (lookahead-critic/judge.py)

if __name__ == "__main__":
    sys.exit(main(sys.argv[1], [Path(p) for p in sys.argv[2:]], here=HERE, fresh=lambda ds: list(fresh2(ds)), tag="2"))
