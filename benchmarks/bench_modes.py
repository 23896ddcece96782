"""What accuracy costs: the number modes against their peers.

The measurement itself lives in :mod:`quadric_contact.interfaces.benchmark` so that the
installed command runs it too; this script is the same thing from a checkout::

    PYTHONPATH=src python benchmarks/bench_modes.py [--profile smoke|quick|full] [--huge]

which is ``quadric-contact bench`` with the same options: a table per mode and
peer (time per test, wrong, undecided) on random pairs and on the near-tangent
ladder, throughput against batch size with peak memory, the memory-bandwidth
limit of reading the inputs, escalation rates, a summary of ratios against the peers and
the read bandwidth measured in the same run, and a plot of time against error, written to
``--out`` (default: the user cache directory, ``~/.cache/quadric-contact/bench`` on Linux).
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

from quadric_contact.interfaces.cli import main

if __name__ == "__main__":
    sys.exit(main(["bench", *sys.argv[1:]]))
