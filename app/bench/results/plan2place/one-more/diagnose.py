"""A look before the gate's rule: Plan2Place and greedy without Z3's window in larger rooms (`ONE_MORE_AT = 0`) and
with it where one constraint stays broken (`1`), on 20 diagnosis plans per set x 2 seeds, alternating in one process;
writes `diagnose.json` and `diagnose.md` here:

    PYTHONPATH=. python app/bench/results/plan2place/one-more/diagnose.py
"""
from pathlib import Path

from app.bench.gates import diagnose
from models.placement import exact_finish

if __name__ == "__main__":
    print(diagnose(Path(__file__).parent, "Z3's window where one constraint stays broken", exact_finish, "ONE_MORE_AT",
                   {"without": 0, "one broken": 1}, ("plan2place", "greedy")))
