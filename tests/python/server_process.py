"""A real sim_server on a loopback udpm port for the bus tests (SIM_SERVER names the program)."""
import os
import subprocess

PROJECT = os.environ["PROJECT_DIR"]
# Generous for a loaded 2-core machine: the runs below take well under a second alone.
PROCESS_TIMEOUT_S = 120


def url(port):
    return f"udpm://239.255.76.67:{port}?ttl=0"


def path(*parts):
    return os.path.join(PROJECT, *parts)


class Server:
    """sim_server running a scene into a run file; stop() waits for its exit."""

    def __init__(self, port, scene, output, *args):
        self.process = subprocess.Popen(
            [os.environ["SIM_SERVER"], path("scenes", scene), "--lcm-url", url(port), "--output",
             str(output), *args], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)

    def wait(self):
        out, _ = self.process.communicate(timeout=PROCESS_TIMEOUT_S)
        return self.process.returncode, out

    def kill(self):
        if self.process.poll() is None:
            self.process.kill()
            self.process.communicate()


def run_controller(port, scene, output, controller, server_args=()):
    """The scene through sim_server (lock-step) driven by the command `controller` (a list, the
    URL appended); returns (controller exit code, its stderr, the server's output)."""
    server = Server(port, scene, output, *server_args)
    try:
        done = subprocess.run([*controller, "--lcm-url", url(port)], capture_output=True,
                              text=True, timeout=PROCESS_TIMEOUT_S)
        code, out = server.wait()
        assert code == 0, out
        return done.returncode, done.stderr, out
    finally:
        server.kill()
