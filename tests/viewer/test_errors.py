"""tongue_viewer's errors: a bad or missing run file, a port in use, a bad option. Each ends it
with status 1 (the project's convention for bad input or an I/O error, docs/exit_codes.md) and
one line on stderr naming the file or the address. And its end on SIGINT or SIGTERM: status 130
(the project's convention for an interrupted program)."""
import shutil
import signal
import socket
import subprocess

import h5py
import pytest

from conftest import program

TIMEOUT_S = 60  # it should fail at once


def run_viewer(*args):
    done = subprocess.run([program("TONGUE_VIEWER"), *args], capture_output=True, text=True,
                          stdin=subprocess.DEVNULL, timeout=TIMEOUT_S)
    print(f"tongue_viewer {' '.join(args)}: exit {done.returncode}, stderr {done.stderr!r}")
    return done


def assert_one_line_error(done, names):
    """Status 1 and one line on stderr that holds `names`; no serving line on stdout."""
    assert done.returncode == 1, (done.returncode, done.stderr)
    lines = [line for line in done.stderr.splitlines() if line.strip()]
    assert len(lines) == 1, f"expected one line on stderr, got {done.stderr!r}"
    assert names in lines[0], f"{names!r} not named in {lines[0]!r}"
    assert "serving" not in done.stdout, done.stdout


@pytest.fixture
def bad_files(tmp_path):
    text = tmp_path / "notes.h5"
    text.write_text("this is not HDF5\n")
    empty = tmp_path / "empty.h5"
    with h5py.File(empty, "w") as f:
        f.attrs["note"] = "an HDF5 file, but no run file"
    return {"text": str(text), "empty": str(empty), "missing": str(tmp_path / "missing.h5")}


@pytest.mark.parametrize("kind", ["text", "empty", "missing"])
def test_bad_run_file_is_named(bad_files, kind):
    done = run_viewer("--run", bad_files[kind], "--listen", "127.0.0.1:0")
    assert_one_line_error(done, bad_files[kind])


def test_bad_reference_run_file_is_named(runs, bad_files):
    done = run_viewer("--run", runs["sg"], "--run", bad_files["text"], "--listen", "127.0.0.1:0")
    assert_one_line_error(done, bad_files["text"])


@pytest.mark.parametrize("dataset", ["muscles/length", "activations", "positions"])
def test_run_file_lacking_a_series_is_named(runs, tmp_path, dataset):
    """A run file cut short of a series the page draws is refused before anything is served."""
    cut = tmp_path / "cut.h5"
    shutil.copy(runs["sg"], cut)
    with h5py.File(cut, "a") as f:
        del f[dataset]
    done = run_viewer("--run", str(cut), "--listen", "127.0.0.1:0")
    assert_one_line_error(done, str(cut))
    assert "/" + dataset in done.stderr, done.stderr


def test_port_in_use_is_named(runs):
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen(1)
        address = f"127.0.0.1:{taken.getsockname()[1]}"
        done = run_viewer("--run", runs["sg"], "--listen", address)
    assert_one_line_error(done, address)


def test_bad_option_is_a_usage_error():
    done = run_viewer("--no-such-option")
    assert done.returncode == 1, (done.returncode, done.stderr)
    assert "--no-such-option" in done.stderr


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT])
def test_signal_ends_it_with_status_130(runs, processes, signum):
    viewer = processes.viewer("--run", runs["sg"], "--listen", "127.0.0.1:0")
    assert viewer.get("/api/session")[0] == 200
    viewer.popen.send_signal(signum)
    assert viewer.wait(TIMEOUT_S) == 130, (
        f"tongue_viewer ended with {viewer.popen.returncode} on {signal.Signals(signum).name}, "
        f"not 130 as the contract says; stderr: {viewer.stderr()!r}")


def raw_request(port, data, timeout_s=TIMEOUT_S):
    """Sends data on a fresh connection; returns what came back before the viewer closed it.
    The viewer may close it before all of data is sent (a header past its limit): a reset or a
    closed socket on our side is that answer, not a failure."""
    reply = b""
    with socket.create_connection(("127.0.0.1", port), timeout=timeout_s) as s:
        try:
            s.sendall(data)
            s.shutdown(socket.SHUT_WR)
            while chunk := s.recv(65536):
                reply += chunk
        except TimeoutError:
            raise
        except OSError:  # reset, broken pipe, not connected: closed by the viewer
            pass
    return reply


def test_hostile_requests_leave_the_viewer_serving(runs, processes):
    """Bytes that are not HTTP, a header beyond the limit, a body on a GET, a WebSocket upgrade
    with nothing behind it: each is answered with an error or the connection closed, and the
    viewer goes on serving."""
    viewer = processes.viewer("--run", runs["sg"], "--listen", "127.0.0.1:0")
    hostile = [
        b"\x00\xff\x13garbage that is not HTTP\r\n\r\n",
        b"GET / HTTP/1.1\r\nHost: x\r\nX-Long: " + b"a" * 20000 + b"\r\n\r\n",
        b"GET /api/session HTTP/1.1\r\nHost: x\r\nContent-Length: 100000\r\n\r\n" + b"b" * 5000,
        b"GET /ws HTTP/1.1\r\nHost: x\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
        b"Sec-WebSocket-Version: 13\r\nSec-WebSocket-Key: AAAAAAAAAAAAAAAAAAAAAA==\r\n\r\n",
        b"POST /api/session HTTP/1.1\r\nHost: x\r\nContent-Length: 3\r\n\r\nabc",
        b"GET /%00%2e%2e/etc/passwd HTTP/1.1\r\nHost: x\r\n\r\n",
    ]
    for data in hostile:
        reply = raw_request(viewer.port, data)
        assert b"root:" not in reply
        assert reply == b"" or reply.startswith(b"HTTP/1.1 4"), reply[:200]
        code, session = viewer.get("/api/session")
        assert code == 200 and session["mode"] == "replay", (data[:40], session)
    assert viewer.running(), viewer.stderr()
