"""Connecting to Ray: a local instance on this machine, an existing cluster, or the one
already initialised in this process (tests)."""

import logging
import os
import signal
import socket
import sys
import threading
import time
from contextlib import contextmanager
from typing import Callable, Iterator, Optional

from .errors import FarmError



@contextmanager
def connected(address: Optional[str], workers: Optional[int], timeout: float = 30.0) -> Iterator[None]:
    """Ray, ready for the job, and shut down after it if this call started it.

    With no ``address``, a local instance with ``workers`` CPUs (all by default); with one
    (``auto`` or ``HOST:PORT``), that cluster, sent this package as a ``py_modules``
    runtime environment so workers need not have it installed (snell they do need).
    Ray that has not started or answered in ``timeout`` seconds ends the job (Ray itself
    retries for minutes, printing a warning every few seconds).
    """
    import ray

    if ray.is_initialized():
        yield
        return
    previous = signal.getsignal(signal.SIGTERM)
    where = f"the Ray cluster at {address}" if address else "a local Ray instance"
    try:
        if address:
            probe(address)
            package = os.path.dirname(os.path.abspath(__file__))
            start = lambda: ray.init(address=address, logging_level=logging.WARNING,  # noqa: E731
                                     runtime_env={"py_modules": [package]})
        else:
            # A local instance of this job's own, with Ray's default token authentication,
            # without the warning Ray prints about that default on every run.
            logging.getLogger("ray._private.authentication.authentication_token_setup").setLevel(logging.ERROR)
            # "local": a new instance even when RAY_ADDRESS or a `ray start` here names another
            start = lambda: ray.init(address="local", num_cpus=workers,  # noqa: E731
                                     include_dashboard=False, logging_level=logging.WARNING)
        within_deadline(start, where, timeout)
    except FarmError:
        raise
    except Exception as err:  # Ray raises ConnectionError, RuntimeError, ValueError ...
        raise FarmError(f"cannot start or reach {where}: {err}")
    if callable(previous) and threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGTERM, previous)  # Ray installs its own; keep the caller's
    try:
        yield
    except BaseException:
        if not address:
            hurry_local_shutdown()
        ray.shutdown()
        raise
    ray.shutdown()


def hurry_local_shutdown() -> None:
    """After an interrupt, lets Ray's shutdown kill the local instance's processes at once
    instead of asking each to stop and waiting for it (five seconds and more, after tasks
    were cancelled). Through Ray's private node object; where that has changed, the
    shutdown is as Ray makes it, only slower."""
    try:
        from ray._private import worker

        node = getattr(worker, "_global_node", None)
        if node is None or not node.is_head():
            return
        kill = node.kill_all_processes

        def at_once(*args, **kwargs):
            kwargs["allow_graceful"] = False
            return kill(*args, **kwargs)

        node.kill_all_processes = at_once
    except Exception:  # a Ray whose internals differ
        pass


def probe(address: str) -> None:
    """Fails at once, with a message, where nothing listens at ``HOST:PORT`` (``auto`` is
    Ray's to find). Ray would retry such an address for minutes."""
    if address == "auto" or ":" not in address:
        return
    host, _, port = address.rpartition(":")
    try:
        port_number = int(port)
    except ValueError:
        raise FarmError(f"--address {address}: the port is not a number (give HOST:PORT)", 2)
    try:
        with socket.create_connection((host.strip("[]"), port_number), timeout=5):
            pass
    except OSError as err:
        raise FarmError(f"cannot reach the Ray cluster at {address}: {err.strerror or err} "
                        f"(is `ray start --head` running there, and is {port_number} its port?)")


def within_deadline(start: Callable[[], object], where: str, timeout: float) -> None:
    """Runs ``start`` (``ray.init``), which may block in Ray's own code for minutes without
    returning to Python, so that neither a Python signal handler nor a timeout could act:
    SIGINT and SIGTERM are held from the main thread meanwhile and waited for by another,
    which ends the process at once (nothing has been rendered yet), as it does when
    ``start`` has not returned within ``timeout`` seconds."""
    main = threading.current_thread() is threading.main_thread()
    if not main or not hasattr(signal, "pthread_sigmask"):
        start()
        return
    held = {signal.SIGINT, signal.SIGTERM}
    done = threading.Event()

    def watch() -> None:
        deadline = time.monotonic() + timeout
        while not done.is_set():
            left = deadline - time.monotonic()
            if left <= 0:
                print(f"snell-farm: error: cannot reach {where}: no answer within {timeout:g} s "
                      "(--connect-timeout)", file=sys.stderr, flush=True)
                os._exit(1)
            got = signal.sigtimedwait(held, min(left, 0.2))
            if got is not None and not done.is_set():
                print(f"snell-farm: interrupted while joining {where}; nothing was rendered",
                      file=sys.stderr, flush=True)
                os._exit(130)

    signal.pthread_sigmask(signal.SIG_BLOCK, held)
    watcher = threading.Thread(target=watch, name="snell-farm connect watch", daemon=True)
    watcher.start()
    try:
        start()
    finally:
        done.set()
        watcher.join()
        signal.pthread_sigmask(signal.SIG_UNBLOCK, held)


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
