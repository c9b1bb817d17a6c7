"""The last few values a process made, kept by key: a study asks for the same solve or assembly for several cases
(another load on the same beam, a model's own reference grid). The least recently used go first; a value the caller
does not want kept (too large) is returned and forgotten."""

from __future__ import annotations

from collections import OrderedDict


class Kept:
    """At most ``entries`` values, by key."""

    def __init__(self, entries: int):
        self.entries = entries
        self._values: OrderedDict = OrderedDict()

    def get(self, key, make, keep=lambda value: True):
        """The value kept under ``key``, else ``make()``, kept when ``keep(value)``."""
        if key in self._values:
            self._values.move_to_end(key)
            return self._values[key]
        value = make()
        if keep(value):
            self._values[key] = value
            while len(self._values) > self.entries:
                self._values.popitem(last=False)
        return value

    def clear(self) -> None:
        self._values.clear()

    def __len__(self) -> int:
        return len(self._values)
