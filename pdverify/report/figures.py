"""Figures as inline SVG strings (matplotlib, Agg; deterministic: fixed hash salt, no date)."""

from __future__ import annotations

import io
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

plt.rcParams["svg.hashsalt"] = "pdverify"
plt.rcParams["svg.fonttype"] = "none"
plt.rcParams["text.parse_math"] = False  # names and labels are text: a scene named "$x^{$" is not TeX


def _svg(fig) -> str:
    buf = io.StringIO()
    fig.savefig(buf, format="svg", bbox_inches="tight", metadata={"Date": None, "Creator": None})
    plt.close(fig)
    text = buf.getvalue()
    text = re.sub(r"<metadata>.*?</metadata>", "", text, flags=re.S)  # RDF namespaces, no content
    return text[text.index("<svg") :]


def _finish(fig, ax, xlabel: str, ylabel: str, title: str, which: str = "major") -> str:
    """The labels, title, grid and legend every figure shares; then the SVG."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=9)
    ax.grid(alpha=0.3, which=which)
    labelled = len(ax.get_legend_handles_labels()[0])
    if labelled > 6:  # many curves: the legend beside the axes, not over the data
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    elif labelled:  # none (every case's curve gone): no legend, and no matplotlib warning
        ax.legend(fontsize=7)
    return _svg(fig)


def deflection(
    curves: list[tuple[str, np.ndarray, np.ndarray]],
    ref: tuple[np.ndarray, np.ndarray] | None,
    title: str,
    ylabel: str = "w",
    unit: str = "m",
    yunit: str | None = None,
    ylim: tuple[float, float] | None = None,
) -> str:
    """Deflection (or another point field) along the axis; lengths in the scene's ``unit`` (Scene.length_unit),
    the field in ``yunit`` (default: ``unit``); ``ylim``: the vertical range drawn (curves beyond it leave it)."""
    fig, ax = plt.subplots(figsize=(6.4, 3.4))
    if ref is not None:
        ax.plot(ref[0], ref[1], "k-", lw=2.5, alpha=0.35, label="reference")
    for label, x, w in curves:
        ax.plot(x, w, "-", lw=1.2, marker="o" if len(x) <= 30 else None, ms=3, label=label)
    if ylim is not None:
        ax.set_ylim(*ylim)
    return _finish(fig, ax, f"x ({unit})", f"{ylabel} ({yunit or unit})", title)


def load_deflection(
    curves: list[tuple[str, np.ndarray, np.ndarray, float]],
    title: str,
    unit: str = "m",
    ylabel: str = "load factor (–)",
) -> str:
    """Load factor (or ``ylabel``'s quantity) against the deflection at one point, one line per run (label, load,
    deflections, the point): a load path's loading and unloading branches."""
    fig, ax = plt.subplots(figsize=(6.4, 3.4))
    for label, load, w, x in curves:
        ax.plot(w, load, "-", lw=1.2, marker="o" if len(w) <= 40 else None, ms=3, label=f"{label} (x = {x:.4g})")
    return _finish(fig, ax, f"w at x ({unit})", ylabel, title)


def moment_curvature(
    curves: list[tuple[str, np.ndarray, np.ndarray]],
    ref: tuple[np.ndarray, np.ndarray] | None,
    title: str,
    units: str,
    unit: str = "m",
) -> str:
    """A section's moment against its curvature, one line per run (label, kappa, M) over the classical fibre law
    ``ref``; ``units``: the moment's (e.g. "N m"), ``unit``: the length's."""
    fig, ax = plt.subplots(figsize=(6.4, 3.4))
    if ref is not None:
        ax.plot(ref[0], ref[1], "k-", lw=2.5, alpha=0.35, label="fibre theory (exact-eb, fem-eb)")
    for label, kappa, m in curves:
        ax.plot(kappa, m, "-", lw=1.2, label=label)
    return _finish(fig, ax, f"curvature (1/{unit})", f"M ({units})", title)


def convergence(series: list[tuple[str, np.ndarray, np.ndarray, float]], title: str, unit: str = "m") -> str:
    """log-log error vs spacing, fitted slope printed on each line."""
    fig, ax = plt.subplots(figsize=(6.4, 3.8))
    for label, h, e, p in series:
        (line,) = ax.loglog(h, e, "o-", ms=4, label=f"{label} (slope {p:.2f})")
        ax.annotate(
            f"{p:.2f}",
            (h[len(h) // 2], e[len(e) // 2]),
            color=line.get_color(),
            fontsize=8,
            xytext=(4, 4),
            textcoords="offset points",
        )
    return _finish(fig, ax, f"spacing ({unit})", "max relative error (–)", title, which="both")


def scatter(
    groups: list[tuple[str, np.ndarray, np.ndarray]],
    xlabel: str,
    ylabel: str,
    title: str,
    front: tuple[np.ndarray, np.ndarray] | None = None,
    logx=True,
    connect: bool = False,
) -> str:
    """Points per group (``connect``: joined in the given order, e.g. a sweep)."""
    fig, ax = plt.subplots(figsize=(6.4, 3.8))
    for label, x, y in groups:
        ax.plot(x, y, "o-" if connect else "o", ms=4, lw=1, label=label)
    if front is not None and len(front[0]):
        o = np.argsort(front[0])
        ax.plot(front[0][o], front[1][o], "k--", lw=1, label="Pareto front")
    ax.set_yscale("log")
    if logx:
        ax.set_xscale("log")
    return _finish(fig, ax, xlabel, ylabel, title, which="both")


def deformed_shapes(
    steps: list[dict], title: str, exact: list[tuple[np.ndarray, np.ndarray]] | None = None, unit: str = "m"
) -> str:
    """Deformed axis (x, z) at the recorded load steps of a nonlinear solve, equal axes."""
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for s in steps:
        ax.plot(s["x"], s["z"], "-", lw=1.5, label=f"load factor {s['factor']:.2f}")
    for i, (xe, ze) in enumerate(exact or []):
        ax.plot(xe, ze, "k:", lw=1, label="exact elastica" if i == 0 else None)
    ax.set_aspect("equal")
    return _finish(fig, ax, f"x ({unit})", f"z ({unit})", title)


def time_history(t: np.ndarray, series: dict[str, np.ndarray], title: str, ylabel: str = "displacement") -> str:
    """Responses against time (dynamic examples)."""
    fig, ax = plt.subplots(figsize=(6.4, 3.4))
    for label, y in series.items():
        ax.plot(t, y, "-", lw=1.0, label=label)
    return _finish(fig, ax, "t (s)", ylabel, title)


def histories_overlay(
    curves: list[tuple[str, np.ndarray, np.ndarray]],
    title: str,
    ylabel: str = "displacement",
    until: float | None = None,
) -> str:
    """Several runs' responses at one probe on one axis (each its own times), up to ``until`` seconds."""
    fig, ax = plt.subplots(figsize=(6.4, 3.4))
    for label, t, y in curves:
        keep = slice(None) if until is None else np.asarray(t) <= until
        ax.plot(np.asarray(t)[keep], np.asarray(y)[keep], "-", lw=1.0, label=label)
    return _finish(fig, ax, "t (s)", ylabel, title)


def cost(
    groups: list[tuple[str, np.ndarray, np.ndarray]], limits: list[tuple[str, np.ndarray, np.ndarray]], title: str
) -> str:
    """log-log total seconds vs points per model; dashed: the banded-solve limit of the same matrix."""
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    for label, n, t in groups:
        (line,) = ax.loglog(n, t, "o-", ms=4, label=label)
        for lab, nl, tl in limits:
            if lab == label and len(nl):
                ax.loglog(nl, tl, "--", lw=1, color=line.get_color(), label=f"{label}: banded-solve limit")
    return _finish(fig, ax, "points (–)", "total time (s)", title, which="both")


def dispersion(
    discrete: list[tuple[str, np.ndarray, np.ndarray]],
    continuum: list[tuple[str, np.ndarray, np.ndarray]],
    title: str,
    unit: str = "m",
) -> str:
    """Frequency against wavenumber (in 1/``unit``): the discrete branches (solid) over the continuum's (black:
    dashed, dotted)."""
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for label, k, w in discrete:
        ax.plot(k, w, "-", lw=1.2, label=label)
    for (label, k, w), style in zip(continuum, ("k--", "k:"), strict=False):
        ax.plot(k, w, style, lw=1.4, label=label)
    return _finish(fig, ax, f"wavenumber k (1/{unit})", "ω (rad/s)", title)


LEDGER_LABELS = {
    "kinetic": "kinetic T",
    "strain": "strain U",
    "load_work": "work of the loads",
    "support_work": "work of the supports",
    "damping": "dissipated: damping",
    "stabilisation": "dissipated: stabilisation",
    "balance": "balance T + U + D - W",
}


def energy_ledger(energy: dict, title: str, unit: str = "J") -> str:
    """The energy ledger of a transient against time (columns that stay zero are left out)."""
    fig, ax = plt.subplots(figsize=(6.4, 3.4))
    for key, label in LEDGER_LABELS.items():
        y = np.asarray(energy.get(key, []), float)
        if len(y) and np.any(y != 0):
            ax.plot(energy["t"], y, ":" if key == "balance" else "-", lw=1.0, label=label)
    return _finish(fig, ax, "t (s)", f"energy ({unit})", title)
