"""step_controller --schedule FILE [common options]

Plays an activation sequence (steps and ramps per muscle or group, in levels or newtons: the
C++ sequence_player's file format) into a tongue server in lock-step or real time; written in
Python on the `tongue` module's BusClient, its runs equal sequence_player's bit for bit."""
import sys

from tongue_controllers.activation_sequence import SequenceSpec
from tongue_controllers.program import run_controller
from tongue_controllers.sequence_player import SequencePlayer

if __name__ == "__main__":
    sys.exit(run_controller(
        "step_controller.py", "--schedule FILE",
        "  --schedule FILE   activation sequence (YAML: duration, entries of muscle, start, end,\n"
        "                    level or force, or a ramp's level_from/level_to, force_from/force_to)\n",
        ["--schedule"], ["--schedule"],
        lambda values: SequencePlayer(SequenceSpec(values["--schedule"]))))
