"""Landmark motion as the runner's summary reports it: a landmark is the first node of its node
set, its displacement taken from the first frame (the settled tongue at t = 0)."""
import numpy as np

LANDMARKS = ("tip", "blade", "palatal_dorsum", "velar_dorsum", "root")


class LandmarkTracker:
    def __init__(self, node_sets, first_positions):
        self.nodes = {n: int(node_sets[n][0]) for n in LANDMARKS
                      if n in node_sets and len(node_sets[n])}
        self.first = {n: np.array(first_positions[i]) for n, i in self.nodes.items()}
        self.peak = {n: 0.0 for n in self.nodes}
        self.last = {n: np.zeros(3) for n in self.nodes}

    def add(self, positions):
        for name, i in self.nodes.items():
            d = positions[i] - self.first[name]
            self.last[name] = d
            self.peak[name] = max(self.peak[name], float(np.linalg.norm(d)))

    def figures(self):
        """m: the last frame's dx, dy, dz and the peak distance over the run."""
        out = {}
        for name in self.nodes:
            for axis, value in zip("xyz", self.last[name]):
                out[f"{name}_d{axis}_m"] = float(value)
            out[f"{name}_peak_m"] = self.peak[name]
        return out
