"""udpm ports for experiment runs: each run in flight holds one, so that no two parallel runs
share a port (LCM 1.3.1 delivers traffic between multicast groups on the same port)."""


def parse_ports(text):
    """'7985-7994' or '7985,7990' -> a list of ports."""
    ports = []
    for part in str(text).split(","):
        low, _, high = part.strip().partition("-")
        first, last = int(low), int(high or low)
        if not 1024 <= first <= last <= 65535:
            raise ValueError(f"bad port range '{part}' (in [1024, 65535], low-high)")
        ports.extend(range(first, last + 1))
    if len(set(ports)) != len(ports):
        raise ValueError(f"ports '{text}' repeat a port")
    return ports


class PortPool:
    def __init__(self, ports):
        self.free = list(ports)

    def take(self):
        return self.free.pop(0) if self.free else None

    def give_back(self, port):
        if port is not None:
            self.free.append(port)
