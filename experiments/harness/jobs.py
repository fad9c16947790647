"""Runs independent jobs in parallel (bounded by the number of cores) with a progress line
and an ETA, and turns a failing command into a HarnessFailure carrying its stderr."""
import os
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor, as_completed
from typing import TypeVar

from .errors import HarnessFailure

T = TypeVar("T")


def default_jobs() -> int:
    return max(1, len(os.sched_getaffinity(0)))


def run_process(args: Sequence[object]) -> subprocess.CompletedProcess[str]:
    """Runs a command to its end, capturing its output, whatever its exit status."""
    return subprocess.run([str(a) for a in args], capture_output=True, text=True)


def failure(proc: subprocess.CompletedProcess[str]) -> HarnessFailure:
    """A failed command as a HarnessFailure carrying the last line of its stderr."""
    message = proc.stderr.strip().splitlines()
    return HarnessFailure(f"{' '.join(proc.args[:2])} ... exited with status {proc.returncode}: "
                          f"{message[-1] if message else '(no message)'}")


def run_command(args: Sequence[object]) -> str:
    """Runs a command; returns its stdout. Raises HarnessFailure with its stderr."""
    proc = run_process(args)
    if proc.returncode != 0:
        raise failure(proc)
    return proc.stdout


class Progress:
    """`[label] done/total jobs, elapsed, ETA`. The ETA weighs each job by its expected cost
    (render samples or seconds), calibrated by the jobs already finished."""

    def __init__(self, label: str, costs: Sequence[float]):
        self.label, self.costs = label, costs
        self.total_cost, self.done_cost, self.done = sum(costs), 0.0, 0
        self.start = time.monotonic()
        self.tty = sys.stderr.isatty()
        self.last_print = 0.0
        self.lock = threading.Lock()

    def finished(self, index: int) -> None:
        with self.lock:
            self.done += 1
            self.done_cost += self.costs[index]
            now = time.monotonic()
            if self.tty or now - self.last_print > 10 or self.done == len(self.costs):
                self.last_print = now
                self._print(now - self.start)

    def _print(self, elapsed: float) -> None:
        eta = elapsed * (self.total_cost - self.done_cost) / max(self.done_cost, 1e-12)
        text = (f"[{self.label}] {self.done}/{len(self.costs)} jobs, {elapsed:5.0f} s elapsed, "
                f"ETA {eta:4.0f} s")
        end = "\n" if not self.tty or self.done == len(self.costs) else ""
        print(("\r" if self.tty else "") + text, end=end, file=sys.stderr, flush=True)


def run_parallel(label: str, jobs: Sequence[Callable[[], T]], costs: Sequence[float],
                 workers: int) -> list[T]:
    """Calls each job (a no-argument callable) on `workers` threads; returns their results in
    job order. The first failure cancels what has not started and is re-raised."""
    progress = Progress(label, costs)
    results: dict[int, T] = {}
    with ThreadPoolExecutor(max_workers=workers) as pool:
        futures = {pool.submit(job): i for i, job in enumerate(jobs)}
        try:
            for future in as_completed(futures):
                i = futures[future]
                results[i] = future.result()
                progress.finished(i)
        except BaseException:
            for f in futures:
                f.cancel()
            raise
    return [results[i] for i in range(len(jobs))]
