"""ep_controller --plan FILE [--delay-ms D] [--velocity-factor on|off] [--force-lag-ms T]
[common options]

Drives a tongue server with Feldman's lambda model (the equilibrium-point controller), written
in Python on the `tongue` module's BusClient; its runs equal the C++ ep_controller's bit for
bit."""
import sys

import tongue
from tongue_controllers.ep_controller import EpController
from tongue_controllers.motor_plan import MotorPlanSpec
from tongue_controllers.program import run_controller


def milliseconds(values, option, default_s, largest_ms):
    if option not in values:
        return default_s
    try:
        ms = float(values[option])
    except ValueError:
        raise tongue.UsageError(f"{option}: '{values[option]}' is not a number") from None
    if not 0.0 <= ms <= largest_ms:
        raise tongue.UsageError(f"{option} must be in [0, {largest_ms:g}] ms, "
                                f"not '{values[option]}'")
    return ms * 1e-3


def make(values):
    factor = values.get("--velocity-factor", "on")
    if factor not in ("on", "off"):
        raise tongue.UsageError(f"--velocity-factor must be on or off, not '{factor}'")
    return EpController(MotorPlanSpec(values["--plan"]),
                        delay_s=milliseconds(values, "--delay-ms", 0.012, 1000.0),
                        velocity_factor=factor == "on",
                        force_lag_s=milliseconds(values, "--force-lag-ms", 0.1, 10000.0))


if __name__ == "__main__":
    sys.exit(run_controller(
        "ep_controller.py", "--plan FILE [--delay-ms D] [--velocity-factor on|off] "
        "[--force-lag-ms T]",
        "  --plan FILE       motor plan: Delta-lambda targets (mm) per muscle or group\n"
        "  --delay-ms D      reflex delay, ms (default 12; at least one step is used)\n"
        "  --velocity-factor on (default) or off: the force's dependence on velocity\n"
        "  --force-lag-ms T  force development: the levels follow the law through a first-order\n"
        "                    lag of T ms (default 100; 0: the bare lambda model)\n",
        ["--plan", "--delay-ms", "--velocity-factor", "--force-lag-ms"], ["--plan"], make))
