"""Controllers for the tongue server written in Python on the `tongue` module's BusClient.

The step controller (sequence_player.py) and the equilibrium-point controller (ep_controller.py)
reproduce their C++ counterparts (controllers/sequence_player, controllers/ep_controller) bit for
bit: the same arithmetic in the same order, on the same doubles.
"""
