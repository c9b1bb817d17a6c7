"""The last few values a process made, kept by key: a study asks for the same solve or assembly for several cases
(another load on the same beam, a model's own reference grid). The least recently used go first; a value the caller
does not want kept (too large) is returned and forgotten."""

from __future__ import annotations

from collections import OrderedDict


class Kept:
    """At most ``entries`` values, by key; with ``size`` (a value's weight, e.g. its unknowns) at most ``budget`` of
    it together (a value larger than the budget is not kept)."""

    def __init__(self, entries: int, budget: float | None = None, size=None):
        self.entries, self.budget, self.size = entries, budget, size
        self._values: OrderedDict = OrderedDict()
        self._sizes: dict = {}

    def get(self, key, make, keep=lambda value: True):
        """The value kept under ``key``, else ``make()``, kept when ``keep(value)``."""
        if key in self._values:
            self._values.move_to_end(key)
            return self._values[key]
        value = make()
        weight = self.size(value) if self.size is not None else 0
        if keep(value) and (self.budget is None or weight <= self.budget):
            self._values[key], self._sizes[key] = value, weight
            while len(self._values) > self.entries or (
                self.budget is not None and sum(self._sizes.values()) > self.budget
            ):
                self._sizes.pop(self._values.popitem(last=False)[0])
        return value

    def clear(self) -> None:
        self._values.clear()
        self._sizes.clear()

    def __len__(self) -> int:
        return len(self._values)
