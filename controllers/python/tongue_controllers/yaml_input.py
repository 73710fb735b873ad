"""Reading a controller's YAML input with errors that name the file and the key."""
import math

import yaml

from tongue_controllers.program import InputError


class YamlInput:
    def __init__(self, path):
        self.source = path
        try:
            with open(path, encoding="utf-8") as file:
                self.root = yaml.safe_load(file)
        except OSError as error:
            raise InputError(path, "", f"cannot be read: {error.strerror}") from None
        except yaml.YAMLError as error:
            raise InputError(path, "", f"not YAML: {error}") from None

    def fail(self, key_path, reason):
        raise InputError(self.source, key_path, reason)

    def mapping(self, node, key_path, keys):
        """node as a dict whose keys are all in `keys`."""
        if not isinstance(node, dict):
            self.fail(key_path or "(top level)", "expected a map")
        for key in node:
            if key not in keys:
                self.fail(join(key_path, str(key)), f"unknown key (known: {', '.join(keys)})")
        return node

    def number(self, node, key_path):
        if isinstance(node, str):  # YAML 1.1 reads 1e-3 (no dot) as text; the C++ reader does not
            try:
                node = float(node)
            except ValueError:
                pass
        if isinstance(node, bool) or not isinstance(node, (int, float)) or not math.isfinite(node):
            self.fail(key_path, f"expected a finite number, got {node!r}")
        return float(node)

    def non_negative(self, node, key_path, unit):
        value = self.number(node, key_path)
        if value < 0.0:
            self.fail(key_path, f"must be >= 0 {unit}, got {value:g} {unit}")
        return value

    def required(self, node, key_path, key):
        if node.get(key) is None:
            self.fail(join(key_path, key), "is required")
        return node[key]


def join(path, key):
    return f"{path}.{key}" if path else key
