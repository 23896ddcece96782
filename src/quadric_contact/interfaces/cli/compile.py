"""``quadric-contact compile``: fill numba's on-disk cache with every array kernel, now.

Without it the package fills the cache by itself, in a background process started by the first
call that misses a kernel (answering small calls with the kernels' Python twins meanwhile); this
command does the same work in the foreground, with a line for each call that compiled."""

from __future__ import annotations

import argparse
from typing import Any

from quadric_contact.interfaces.cli.exits import EXIT_OK
from quadric_contact.modes.kernels import _jit


def register(sub: Any) -> None:
    p = sub.add_parser(
        "compile",
        help="compile every array kernel into the on-disk cache now (minutes, once per machine)",
    )
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from quadric_contact.interfaces import warmup  # the compile command loads the warm-up only when it runs

    print(f"quadric-contact compile: the cache is {_jit._cache_root()}", flush=True)
    with _jit.warmup_lock() as held:
        if not held:
            print("quadric-contact compile: the background warm-up is running; waiting for it", flush=True)
    # the lock is taken again, waiting this time, so that the two never compile the same kernel
    with _jit.warmup_lock(wait=True):
        warmup.run(log=lambda line: print(line, flush=True))
        _jit.warmup_done()
    return EXIT_OK
