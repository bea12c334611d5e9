"""parallel_map: typed errors, a Dask scheduler reached with a timeout, workers that die
with their parent (issue 12).

Every socket here is on 127.0.0.1, made by the test, bounded in time and closed.
"""

import os
import signal
import socket
import subprocess
import sys
import threading
import time
from contextlib import contextmanager
from pathlib import Path

import pytest

import tiremesh as tm
from tiremesh.parallel import (
    SchedulerError,
    check_scheduler,
    connect_scheduler,
    parallel_map,
    watch_parent,
)

ROOT = Path(__file__).resolve().parents[2]


def square(x, offset=0):
    return x * x + offset


def record_pid_and_sleep(path):
    """Worker task for the parent-death test: say who runs it, then block."""
    Path(path).write_text(str(os.getpid()))
    time.sleep(120)
    return path


def _closed_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@contextmanager
def _server(handler=None, *, seconds=10.0):
    """A TCP server on 127.0.0.1 that runs ``handler(conn)`` for each connection
    (None: accept nothing, just listen), for at most ``seconds``."""
    srv = socket.socket()
    srv.bind(("127.0.0.1", 0))
    srv.listen(8)
    srv.settimeout(0.1)
    stop = threading.Event()
    deadline = time.monotonic() + seconds

    def serve():
        while not stop.is_set() and time.monotonic() < deadline:
            try:
                conn, _ = srv.accept()
            except OSError:
                continue
            with conn:
                conn.settimeout(2.0)
                try:
                    handler(conn)
                except OSError:
                    pass

    thread = threading.Thread(target=serve, daemon=True) if handler else None
    if thread:
        thread.start()
    try:
        yield f"tcp://127.0.0.1:{srv.getsockname()[1]}"
    finally:
        stop.set()
        if thread:
            thread.join(timeout=5)
        srv.close()


def _http_reply(conn):
    """A tiny HTTP responder: reads the request (if any comes), answers 200."""
    try:
        conn.recv(1024)
    except OSError:
        pass
    conn.sendall(b"HTTP/1.1 200 OK\r\nContent-Length: 2\r\n\r\nok")


def _http_greeting(conn):
    """A service that answers HTTP at once, before any request."""
    conn.sendall(b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n")
    time.sleep(0.5)


@pytest.mark.parametrize("workers", [0, -1, 1.5, True, "2"])
def test_parallel_map_workers_below_one_is_a_typed_error(workers):
    with pytest.raises(tm.InvalidParameter, match="workers"):
        parallel_map(square, [1, 2, 3], workers=workers)


@pytest.mark.parametrize("timeout", [0, -1, float("nan"), "soon"])
def test_parallel_map_scheduler_timeout_must_be_positive(timeout):
    with pytest.raises(tm.InvalidParameter, match="scheduler_timeout"):
        parallel_map(square, [1], scheduler="tcp://127.0.0.1:8786", scheduler_timeout=timeout)


def test_parallel_map_local_results_and_kwargs():
    got = dict(parallel_map(square, [1, 2, 3, 4], workers=2, kwargs={"offset": 1}))
    assert got == {0: 2, 1: 5, 2: 10, 3: 17}
    assert dict(parallel_map(square, [3], workers=1)) == {0: 9}


def test_parallel_map_refused_scheduler_is_clear_and_fast():
    address = f"tcp://127.0.0.1:{_closed_port()}"
    t0 = time.monotonic()
    with pytest.raises(SchedulerError, match="refused") as info:
        parallel_map(square, [1, 2], scheduler=address, scheduler_timeout=5)
    assert time.monotonic() - t0 < 3  # before: a raw OSError after 30 s
    assert info.value.address == address and address in str(info.value)
    assert isinstance(info.value, ConnectionError) and isinstance(info.value, tm.TireModelError)


def test_parallel_map_silent_service_times_out():
    with _server(None) as address:  # listens (the kernel accepts), never answers
        t0 = time.monotonic()
        with pytest.raises(SchedulerError, match=r"no Dask handshake within 0\.5 s") as info:
            parallel_map(square, [1, 2], scheduler=address, scheduler_timeout=0.5)
        assert time.monotonic() - t0 < 3  # before: hung for good
    assert address in str(info.value)


def test_parallel_map_http_service_is_not_a_scheduler():
    # the usual HTTP server waits for a request: silent to a Dask client
    with _server(_http_reply) as address:
        t0 = time.monotonic()
        with pytest.raises(SchedulerError, match="HTTP server") as info:
            parallel_map(square, [1, 2], scheduler=address, scheduler_timeout=0.5)
        assert time.monotonic() - t0 < 3  # before: MemoryError (a 3 EiB frame)
    assert address in str(info.value)
    # one that answers at once is named as HTTP
    with (
        _server(_http_greeting) as address,
        pytest.raises(SchedulerError, match="HTTP server answered"),
    ):
        check_scheduler(address, timeout=2)


def test_parallel_map_empty_items_still_checks_the_scheduler():
    address = f"127.0.0.1:{_closed_port()}"
    with pytest.raises(SchedulerError, match=address):
        parallel_map(square, [], scheduler=address)


@pytest.mark.parametrize("address", ["tcp://127.0.0.1:notaport", "tcp://:8786", "tcp://h:0"])
def test_check_scheduler_malformed_address(address):
    with pytest.raises(SchedulerError, match="tcp://HOST:8786"):
        check_scheduler(address, timeout=1)


def test_parallel_map_on_a_local_dask_scheduler():
    from dask.distributed import LocalCluster

    with LocalCluster(
        n_workers=1,
        threads_per_worker=2,
        processes=False,
        protocol="tcp://",
        host="127.0.0.1",
        dashboard_address=None,
    ) as cluster:
        address = cluster.scheduler_address
        assert check_scheduler(address, timeout=5) == address
        got = dict(parallel_map(square, [1, 2, 3], scheduler=address, kwargs={"offset": 1}))
        assert got == {0: 2, 1: 5, 2: 10}
        with connect_scheduler(address, timeout=5) as client:  # a client is used, not closed
            assert dict(parallel_map(square, [4], scheduler=client)) == {0: 16}
            assert client.status == "running"


def _state(pid: int) -> str:
    """'' when gone, else the /proc state letter (Z: a zombie, dead too)."""
    try:
        text = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return ""
    return next(line.split()[1] for line in text.splitlines() if line.startswith("State:"))


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_parallel_map_workers_die_with_their_parent(tmp_path):
    marks = [tmp_path / "a", tmp_path / "b"]
    script = (
        "import sys\n"
        f"sys.path.insert(0, {str(ROOT)!r})\n"
        "from tiremesh.parallel import parallel_map\n"
        "from tests.tiremesh.test_parallel import record_pid_and_sleep\n"
        f"list(parallel_map(record_pid_and_sleep, {[str(m) for m in marks]!r}, workers=2))\n"
    )
    parent = subprocess.Popen([sys.executable, "-c", script], cwd=ROOT)
    pids = []
    try:
        deadline = time.monotonic() + 60
        while not all(m.exists() and m.read_text() for m in marks):
            assert time.monotonic() < deadline and parent.poll() is None, "workers did not start"
            time.sleep(0.1)
        pids = [int(m.read_text()) for m in marks]
        parent.send_signal(signal.SIGKILL)
        parent.wait(timeout=10)
        deadline = time.monotonic() + 15
        while any(_state(p) not in ("", "Z") for p in pids) and time.monotonic() < deadline:
            time.sleep(0.2)
        assert all(_state(p) in ("", "Z") for p in pids), "workers outlived their parent"
    finally:
        if parent.poll() is None:
            parent.kill()
            parent.wait(timeout=10)
        for p in pids:  # our own workers, should the test fail
            if _state(p) not in ("", "Z"):
                os.kill(p, signal.SIGKILL)


def test_watch_parent_needs_no_watcher_for_itself_or_twice():
    # in-process path: the "parent" is this process; no thread, no exit
    assert watch_parent(os.getpid()) is False
    parent = os.getppid()  # the pytest runner's parent: alive for the whole run
    watch_parent(parent, interval=60.0)
    assert watch_parent(parent) is False  # at most one watcher per parent
