"""Figures drawn by the page itself: each is a small JSON spec inside a ``<figure class="pfig">`` (axes with their
units, series of numbers at the precision a figure shows, notes) that the inline script
``templates/_plot.js`` draws as SVG, with values on hover and the page's filters. Nothing is loaded from
anywhere: the data and the script are in the page.

Why drawn in the page rather than as matplotlib SVG: a figure's numbers are a few bytes each here (an SVG path
repeats coordinates with markup), the filters can hide one model's line inside a figure, and hovering a point
shows its values."""

from __future__ import annotations

import html
import json
import math
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

import numpy as np
from markupsafe import Markup

MAX_POINTS = 180  # points kept per line: a 600-pixel axis shows no more; the bins keep each one's extremes
FIGURE_POINTS = 1000  # points kept per figure: a figure of many lines thins each further (to MIN_POINTS at least)
MIN_POINTS = 40
X_DIGITS, Y_DIGITS = 4, 3  # significant digits of positions along an axis and of the values drawn


def number(v, digits: int) -> str:
    """A JSON number to ``digits`` significant digits ('1.23e-5'), ``null`` when not finite."""
    v = float(v)
    if not math.isfinite(v):
        return "null"
    text = f"{v:.{digits}g}"
    return re.sub(r"e([+-])0*(\d)", lambda m: "e" + ("-" if m.group(1) == "-" else "") + m.group(2), text)


def numbers(values, digits: int) -> str:
    return "[" + ",".join(number(v, digits) for v in np.asarray(values, float).ravel()) + "]"


class Raw(str):
    """JSON text written as it is (arrays already formatted)."""


def dumps(obj) -> str:
    """Compact JSON of dicts, lists, strings, numbers and :class:`Raw` pieces."""
    if isinstance(obj, Raw):
        return str(obj)
    if isinstance(obj, dict):
        return "{" + ",".join(f"{json.dumps(str(k))}:{dumps(v)}" for k, v in obj.items()) + "}"
    if isinstance(obj, (list, tuple)):
        return "[" + ",".join(dumps(v) for v in obj) + "]"
    if isinstance(obj, (bool, np.bool_)):
        return "true" if obj else "false"
    if isinstance(obj, (int, np.integer)):
        return str(int(obj))
    if isinstance(obj, (float, np.floating)):
        return number(obj, 6)
    if obj is None:
        return "null"
    return json.dumps(str(obj), ensure_ascii=False)


def positions(x: np.ndarray) -> Raw:
    """An axis' positions: ``{"a": first, "d": step, "n": count}`` for a uniform grid, else the list."""
    x = np.asarray(x, float)
    if len(x) > 2 and np.all(np.isfinite(x)):
        step = (x[-1] - x[0]) / (len(x) - 1)
        if step != 0 and np.allclose(np.diff(x), step, rtol=1e-9, atol=1e-12 * abs(step)):
            return Raw(f'{{"a":{number(x[0], 12)},"d":{number(step, 12)},"n":{len(x)}}}')
    return Raw(numbers(x, X_DIGITS))


def thin(x: np.ndarray, y: np.ndarray, log: bool, limit: int = MAX_POINTS) -> np.ndarray:
    """Indices of at most ``limit`` points of a line that keep its shape: the ends and, in each of limit / 2
    bins, the smallest and largest value (of log10 |y| on a log axis, where the dips to zero matter)."""
    n = len(x)
    if n <= limit:
        return np.arange(n)
    v = np.asarray(y, float)
    if log:
        with np.errstate(divide="ignore", invalid="ignore"):
            v = np.where(v > 0, np.log10(np.where(v > 0, v, 1.0)), -np.inf)
    keep = {0, n - 1}
    for b in np.array_split(np.arange(n), limit // 2):
        seg = v[b]
        finite = np.isfinite(seg)
        if not finite.any():
            keep.add(int(b[0]))
            continue
        keep.add(int(b[np.argmin(np.where(finite, seg, np.inf))]))
        keep.add(int(b[np.argmax(np.where(finite, seg, -np.inf))]))
        if (~finite).any():  # a zero on a log axis: keep one, the line breaks there
            keep.add(int(b[np.argmax(~finite)]))
    return np.array(sorted(keep))


@dataclass
class Series:
    """One line (or set of points) of a figure. ``model``/``variant``: what the page's filters match (empty for
    a guide line, which shows while the figure does); ``colour``: index into the page's palette (-1: grey);
    ``style``: 'line', 'points', 'line+points' or 'dash'; ``labels``: a text per point, shown on hover."""

    name: str
    x: np.ndarray
    y: np.ndarray
    model: str = ""
    variant: str = ""
    colour: int = -1
    style: str = "line"
    labels: Sequence[str] | None = None
    guide: bool = False

    def spec(self, ylog: bool, limit: int = MAX_POINTS) -> dict:
        x, y = np.asarray(self.x, float), np.asarray(self.y, float)
        idx = thin(x, y, ylog, limit)
        labels = self.labels
        if len(idx) < len(x):
            x, y = x[idx], y[idx]
            labels = [labels[i] for i in idx] if labels is not None else None
        out = {"n": self.name, "x": positions(x), "y": Raw(numbers(y, Y_DIGITS)), "c": self.colour}
        if self.style != "line":
            out["k"] = self.style
        if self.guide:
            out["g"] = 1
        else:
            out["m"], out["v"] = self.model, self.variant
        if labels is not None:
            out["pl"] = list(labels)
        return out


@dataclass
class Axis:
    """An axis: its label with its unit ('x (m)'), the unit alone for the hover read-out, log or linear."""

    label: str
    unit: str = ""
    log: bool = False

    def spec(self) -> dict:
        return {"l": self.label, "u": self.unit, "log": 1 if self.log else 0}


@dataclass
class Figure:
    """A figure: title, axes, series, notes (text at a data point: ``(x, y, text, colour)``), ``small`` (a small
    multiple), ``equal`` (equal scales: shapes); ``tags``: the filter attributes of the figure (scene, paper)."""

    title: str
    x: Axis
    y: Axis
    series: list[Series] = field(default_factory=list)
    notes: list[tuple[float, float, str, int]] = field(default_factory=list)
    small: bool = False
    equal: bool = False
    caption: str = ""
    id: str = ""

    def spec(self) -> dict:
        lines = max(1, sum(not s.guide for s in self.series))
        limit = max(MIN_POINTS, min(MAX_POINTS, FIGURE_POINTS // lines))
        out = {"x": self.x.spec(), "y": self.y.spec(), "s": [s.spec(self.y.log, limit) for s in self.series]}
        if self.notes:
            out["a"] = [
                {"x": Raw(number(x, X_DIGITS)), "y": Raw(number(y, Y_DIGITS)), "t": t, "c": c}
                for x, y, t, c in self.notes
            ]
        if self.equal:
            out["eq"] = 1
        return out

    def html(self, tags: str = "") -> Markup:
        """The ``<figure>``: its data as JSON (every ``<`` written ``\\u003c``: a name cannot end the script), a
        caption under it."""
        data = dumps(self.spec()).replace("<", "\\u003c")
        klass = "pfig small" if self.small else "pfig"
        ident = f' id="{html.escape(self.id)}"' if self.id else ""
        caption = f"<figcaption>{html.escape(self.caption)}</figcaption>" if self.caption else ""
        return Markup(
            f'<figure class="{klass}"{ident}{tags}><script type="application/json">{data}</script>'
            f'<div class="ftitle">{html.escape(self.title)}</div><div class="plot"></div>{caption}</figure>'
        )


class Palette:
    """A colour index per key (a model and its variant), the same in every figure of the page."""

    def __init__(self):
        self.keys: dict[str, int] = {}

    def __call__(self, key: str) -> int:
        return self.keys.setdefault(key, len(self.keys))


def positive(values: Iterable[float]) -> bool:
    """Whether any value can be drawn on a log axis."""
    return any(v > 0 for v in np.asarray(list(values), float).ravel() if math.isfinite(v))
