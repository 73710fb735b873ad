"""The main() of a Python controller, as the C++ controllers' (controllers/controller):
the common command line, the controller built from its input files, the session with the server,
the summary line on stderr and the same exit codes (docs/exit_codes.md)."""
import signal
import sys

import tongue


class InputError(Exception):
    """A controller input that cannot be used: '<file>: <key path>: <reason>'."""

    def __init__(self, source, key_path, reason):
        super().__init__(f"{source}: {key_path}: {reason}" if key_path else f"{source}: {reason}")


def _terminate(_signum, _frame):
    # SIGTERM ends the session as Ctrl-C does (exit 130), with the summary line.
    raise KeyboardInterrupt


def drive(client, controller):
    """Runs the session of `client` for `controller` (start, observe, command, last_step,
    summary: the C++ Controller's interface) until it ends; client.exit_code says how."""
    model = client.connect()
    if model is None:
        return
    try:
        controller.start(model)
        last = controller.last_step()
        if last is not None:
            client.end_after(last)
        for state in client:
            controller.observe(state)
            if client.awaiting_answer:
                client.send(controller.command(state.step + 1))
    except (InputError, ValueError, ArithmeticError) as error:
        client.fail(str(error))


def run_controller(name, synopsis, options_usage, options, required, make_controller, argv=None):
    """Parses the command line (the common options and `options`, of which `required` must be
    given), builds the controller with make_controller({option: value}), drives it and returns
    the exit code. make_controller raises tongue.UsageError for a bad value, InputError for a bad
    file."""
    argv = sys.argv[1:] if argv is None else argv
    usage = f"usage: {name} {synopsis} [common options]\n{options_usage}{tongue.controller_usage()}"
    try:
        common, values, wants_help = tongue.parse_controller_command_line(argv, options)
        if wants_help:
            print(usage, end="")
            return 0
        for option in required:
            if option not in values:
                raise tongue.UsageError(f"{option} is required")
        controller = make_controller(values)
    except tongue.UsageError as error:
        print(f"{name}: {error}\n{usage}", end="", file=sys.stderr)
        return 1
    except (InputError, OSError) as error:
        print(f"{name}: error: {error}", file=sys.stderr)
        return 1
    signal.signal(signal.SIGTERM, _terminate)
    try:
        client = tongue.BusClient(common, program=name)
    except RuntimeError as error:
        print(f"{name}: error: {error}", file=sys.stderr)
        return 1
    try:
        drive(client, controller)
    except KeyboardInterrupt:
        pass  # the session ended with exit code 130
    print(client.summary(controller.summary()), file=sys.stderr)
    return client.exit_code
