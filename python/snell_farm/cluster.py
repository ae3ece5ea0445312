"""Connecting to Ray: a local instance on this machine, an existing cluster, or the one
already initialised in this process (tests)."""

import logging
import os
import signal
import threading
from contextlib import contextmanager
from typing import Iterator, Optional

from .errors import FarmError


@contextmanager
def connected(address: Optional[str], workers: Optional[int]) -> Iterator[None]:
    """Ray, ready for the job, and shut down after it if this call started it.

    With no ``address``, a local instance with ``workers`` CPUs (all by default); with one
    (``auto`` or ``HOST:PORT``), that cluster, sent this package as a ``py_modules``
    runtime environment so workers need not have it installed (snell they do need).
    """
    import ray

    if ray.is_initialized():
        yield
        return
    previous = signal.getsignal(signal.SIGTERM)
    try:
        if address:
            package = os.path.dirname(os.path.abspath(__file__))
            ray.init(address=address, logging_level=logging.WARNING, runtime_env={"py_modules": [package]})
        else:
            # "local": a new instance even when RAY_ADDRESS or a `ray start` here names another
            ray.init(address="local", num_cpus=workers, include_dashboard=False, logging_level=logging.WARNING)
    except Exception as err:  # Ray raises ConnectionError, RuntimeError, ValueError ...
        where = f"the Ray cluster at {address}" if address else "a local Ray instance"
        raise FarmError(f"cannot start or reach {where}: {err}")
    if callable(previous) and threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGTERM, previous)  # Ray installs its own; keep the caller's
    try:
        yield
    finally:
        ray.shutdown()


def task_slots(cpus_per_task: int) -> int:
    """How many tasks of ``cpus_per_task`` CPUs the cluster runs at once.

    Raises FarmError when no node has that many CPUs (the tasks would wait forever).
    """
    import ray

    cpus = [node.get("Resources", {}).get("CPU", 0) for node in ray.nodes() if node.get("Alive")]
    slots = sum(int(n // cpus_per_task) for n in cpus)
    if slots < 1:
        raise FarmError(f"--cpus-per-task {cpus_per_task}: no node of the cluster has that many CPUs "
                        f"(the largest has {max(cpus, default=0):g})", 2)
    return slots
