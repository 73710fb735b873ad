"""A run of a scene in-process through tongue.Simulation.

Parameters: `scene` (path), `duration_s` or `steps`, `levels.<muscle or group>` (level in
[0, 1], held from the first step), `release_s` (optional: from then on the named levels are 0).
"""
import threading
import warnings

import numpy as np

from .landmarks import LandmarkTracker

# One Simulation per scene and thread, reused with reset(): building and settling a scene costs
# about as much as 100 steps, and a reset run is the fresh run bit for bit, its warnings too.
_cache = threading.local()


def simulation_for(scene, first_levels):
    """The scene's Simulation at time 0; when it is reset, the first step's factorization is
    made under first_levels(dt) (muscles and groups by name), as a fresh one makes it at its
    first step: the same states either way."""
    import tongue
    sims = getattr(_cache, "sims", None)
    if sims is None:
        sims = _cache.sims = {}
    if scene not in sims:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            sims[scene] = tongue.Simulation(scene)  # built and settled: about 90 ms
    # About 8 ms, and the first step then forms no factorization (a sixth of a 0.2 s run of the
    # tongue). A new Simulation is reset too: its factor was formed with every muscle off, and
    # its first run would count a factorization that the runs after it do not, making a row
    # depend on which worker did the run before.
    sims[scene].reset(first_levels(sims[scene].dt))
    return sims[scene]


def step_count(params, dt):
    if "steps" in params:
        return int(params["steps"])
    if "duration_s" in params:
        return int(round(float(params["duration_s"]) / dt))
    raise ValueError("a simulation run needs duration_s or steps")


def run_simulation(params):
    on = {name[len("levels."):]: float(v) for name, v in params.items()
          if name.startswith("levels.")}
    off = {name: 0.0 for name in on}
    release = float(params.get("release_s", float("inf")))

    def levels_at(t):
        return on if t <= release + 1e-9 else off

    sim = simulation_for(params["scene"], levels_at)
    steps = step_count(params, sim.dt)
    tracker = LandmarkTracker(sim.node_sets, sim.positions)
    totals = dict(newton_iterations=0, factorizations=0, step_cuts=0, physics_wall_s=0.0)
    notes = []
    with warnings.catch_warnings():
        # The library's warnings are counted from the figures, not printed by every worker.
        warnings.simplefilter("ignore", RuntimeWarning)
        for k in range(1, steps + 1):
            # Levels given for a step are those at its end, as in a scene's schedule.
            figures = sim.step(levels_at(k * sim.dt))
            totals["newton_iterations"] += figures.iterations
            totals["factorizations"] += figures.factorizations
            totals["step_cuts"] += figures.cuts
            totals["physics_wall_s"] += figures.wall_seconds
            notes.extend(figures.warnings)
            tracker.add(sim.positions)
        notes.extend(sim.finish_checks())  # the last state's, which no step reports
    return {"steps": steps, "simulated_s": float(sim.time), **totals,
            "warnings": len(notes), "first_warning": notes[0] if notes else "",
            **tracker.figures()}
