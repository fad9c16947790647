"""Renders through long-lived `renderer serve` processes, one per render running at once. A
server keeps the scenes it built, so a profile's renders pay process start-up, asset loading
and acceleration-structure builds once per scene and server instead of once per render; each
render's integrator is built afresh and its outputs are those of `renderer render` with the
same arguments (tests/test_serve.py).

Servers are started on demand and stopped by close_all (at exit at the latest): the CPU time
of a child process is counted (RUSAGE_CHILDREN) only once it has exited, so whoever measures
CPU time closes the servers first."""
import atexit
import json
import subprocess
import threading
from collections.abc import Sequence

from . import paths
from .errors import HarnessFailure


class RenderServer:
    """One `renderer serve` process: a request is the arguments of `renderer render`, the
    reply its exit status and messages. Its stderr is the harness's (a crash's report)."""

    def __init__(self) -> None:
        # One cached scene: a server renders one experiment's scene at a time, and every job
        # slot holding several large scenes (environment maps) could exhaust memory.
        self.proc = subprocess.Popen([str(paths.renderer_binary()), "serve", "--cached-scenes", "1"],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True,
                                     encoding="utf-8")

    def request(self, args: Sequence[object]) -> tuple[int, list[str]]:
        assert self.proc.stdin and self.proc.stdout
        self.proc.stdin.write(json.dumps([str(a) for a in args]) + "\n")
        self.proc.stdin.flush()
        line = self.proc.stdout.readline()
        if not line:
            raise HarnessFailure(f"renderer serve exited with status {self.proc.wait()} while "
                                 f"rendering {' '.join(map(str, args[:1]))}")
        reply = json.loads(line)
        return reply["status"], reply["messages"]

    def close(self) -> None:
        """Ends the server at the end of its input; kills it if it does not exit in time."""
        try:
            if self.proc.stdin:
                self.proc.stdin.close()
        except OSError:  # it died with requests unread
            pass
        try:
            self.proc.wait(timeout=60)
        except subprocess.TimeoutExpired:
            self.kill()
        if self.proc.stdout:
            self.proc.stdout.close()

    def kill(self) -> None:
        """Stops the server at once (an interrupted or failed request leaves it unusable)."""
        self.proc.kill()
        self.proc.wait()
        for pipe in (self.proc.stdin, self.proc.stdout):
            try:
                if pipe:
                    pipe.close()
            except OSError:
                pass


_lock = threading.Lock()
_idle: list[RenderServer] = []


def _take() -> RenderServer:
    with _lock:
        server = _idle.pop() if _idle else None
    if server is not None and server.proc.poll() is not None:
        server.close()  # exited while idle: release its pipes
        server = None
    return server or RenderServer()


def _give_back(server: RenderServer, reusable: bool) -> None:
    if reusable:
        with _lock:
            _idle.append(server)
    else:
        server.close()


def render(args: Sequence[object]) -> None:
    """`renderer render ARGS` on an idle server. Raises HarnessFailure as jobs.run_command
    does: with the status and the last message."""
    server = _take()
    try:
        status, messages = server.request(args)
    except BaseException:
        server.kill()  # in an unknown state (Ctrl-C, a crash): nothing it writes is wanted
        raise
    # A render interrupted by Ctrl-C (130) ends its server.
    _give_back(server, reusable=status != 130)
    if status != 0:
        raise HarnessFailure(f"renderer render ... exited with status {status}: "
                             f"{messages[-1] if messages else '(no message)'}")


def close_all() -> None:
    """Stops every idle server and waits for it (servers still rendering are left alone)."""
    with _lock:
        servers = list(_idle)
        _idle.clear()
    for server in servers:
        server.close()


atexit.register(close_all)
