"""Case records on disk: one file per finished case, written atomically, checked when read.

A record is ``{"case": ..., "row": ..., "curve": ...}``: the case's key material, its row of the results
table and its curves (x, w, w_ref, rotation, point fields, time histories, load steps). On disk
(``DIR/cases/<case id>.case``)::

    b"PDVCASE1"                                    magic and format version (8 bytes)
    <u8 header length> <u8 data length> <u4 crc>   little-endian; crc = zlib.crc32(header + data)
    header                                         UTF-8 JSON: case, row, curve with every array
                                                   replaced by {"@": byte offset in data, "shape": [...]}
    data                                           the arrays' little-endian float64 bytes, in order

Arrays are stored bit for bit (NaN, -0.0, subnormals included). The checksum covers the whole file
after the lengths, so a truncated file, a flipped bit in a number or in an array, or a file of another
kind reads as ``None`` and the case is recomputed. Files of the first format (``<case id>.json``: JSON with
base64 arrays, several times slower to encode) are still read (:func:`case_file`, :func:`read_curve`).
"""

from __future__ import annotations

import base64
import contextlib
import json
import os
import struct
import threading
import zlib
from pathlib import Path

import numpy as np

MAGIC = b"PDVCASE1"
_LENGTHS = struct.Struct("<QQI")
SUFFIX = ".case"
LEGACY_SUFFIX = ".json"
ROW_KEYS = ("case", "row", "curve")


def _scalar(v):
    """JSON fallback for the header: numpy scalars as numbers, anything else as its text."""
    if isinstance(v, np.integer):
        return int(v)
    if isinstance(v, np.floating):
        return float(v)
    if isinstance(v, np.bool_):
        return bool(v)
    return str(v)


def encode_record(rec: dict) -> bytes:
    """The bytes of a case record (format in the module docstring). Arrays anywhere in the curve
    (nested dicts and lists included) go to the data section as float64."""
    chunks: list[bytes] = []
    offset = 0

    def pack(v):
        nonlocal offset
        if isinstance(v, np.ndarray):
            a = np.ascontiguousarray(v, dtype="<f8")
            ref = {"@": offset, "shape": list(a.shape)}
            b = a.tobytes()
            chunks.append(b)
            offset += len(b)
            return ref
        if isinstance(v, dict):
            return {k: pack(x) for k, x in v.items()}
        if isinstance(v, (list, tuple)) and v and isinstance(v[0], (dict, list, tuple, np.ndarray)):
            return [pack(x) for x in v]
        return v

    curve = pack(rec.get("curve", {}))
    header = json.dumps(
        {"case": rec["case"], "row": rec["row"], "curve": curve}, default=_scalar, separators=(",", ":"), allow_nan=True
    ).encode("utf-8")
    data = b"".join(chunks)
    crc = zlib.crc32(data, zlib.crc32(header))
    return b"".join((MAGIC, _LENGTHS.pack(len(header), len(data), crc), header, data))


def decode_record(raw: bytes) -> dict | None:
    """Inverse of :func:`encode_record`; None when the bytes are not a whole, intact record."""
    start = len(MAGIC) + _LENGTHS.size
    if len(raw) < start or raw[: len(MAGIC)] != MAGIC:
        return None
    n_header, n_data, crc = _LENGTHS.unpack_from(raw, len(MAGIC))
    if len(raw) != start + n_header + n_data:
        return None
    view = memoryview(raw)
    header, data = view[start : start + n_header], view[start + n_header :]
    if zlib.crc32(data, zlib.crc32(header)) != crc:
        return None
    try:
        rec = json.loads(bytes(header))
    except (ValueError, RecursionError):
        return None

    def unpack(v):
        if isinstance(v, dict):
            if "@" in v and "shape" in v and len(v) == 2:
                shape = tuple(v["shape"])
                return np.frombuffer(data, "<f8", int(np.prod(shape, dtype=np.int64)), v["@"]).reshape(shape).copy()
            return {k: unpack(x) for k, x in v.items()}
        if isinstance(v, list) and v and isinstance(v[0], (dict, list)):
            return [unpack(x) for x in v]
        return v

    if not isinstance(rec, dict) or any(k not in rec for k in ROW_KEYS):
        return None
    rec["curve"] = unpack(rec["curve"])
    return rec


def write_atomic(path, data) -> None:
    """Write to a temporary file beside ``path`` and rename it over ``path`` (atomic on POSIX): a killed
    process leaves the old file or the new one, never a partial one; an exception (Ctrl-C) mid-write
    removes the temporary file. No fsync: the rename is atomic
    against a killed process, which is what resume needs. The temporary name is unique per process and
    thread (mkstemp's random names cost 0.25 ms a file here)."""
    path = os.fspath(path)
    head, name = os.path.split(path)
    tmp = os.path.join(head, f".tmp-{os.getpid()}-{threading.get_ident()}-{name}")
    if isinstance(data, str):
        data = data.encode("utf-8")
    try:
        try:
            fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
        except FileNotFoundError:
            os.makedirs(head or ".", exist_ok=True)
            fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
        try:
            write_all(fd, [data])
        finally:
            os.close(fd)
        os.replace(tmp, path)
    except BaseException:  # Ctrl-C or a full disk mid-write: no temporary file is left behind
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def write_all(fd: int, parts) -> None:
    """Write the byte buffers ``parts`` to ``fd`` in order with ``writev`` (no copy into one buffer),
    however many calls it takes."""
    views = [v for v in (memoryview(p).cast("B") for p in parts) if v.nbytes]
    while views:
        n = os.writev(fd, views[:1024])
        while views and n >= views[0].nbytes:
            n -= views[0].nbytes
            views.pop(0)
        if n:
            views[0] = views[0][n:]


def case_file(cases_dir: Path, case_id: str, names: set[str] | None = None) -> Path | None:
    """The record of ``case_id`` in ``cases_dir``: this format's file, else a first-format ``.json``
    file (JSON with base64 arrays), else None. ``names``: the directory's file names when the
    caller has listed it once (a resumed study looks up every case; one listing instead of a stat each)."""
    for suffix in (SUFFIX, LEGACY_SUFFIX):
        name = case_id + suffix
        if names is not None and name not in names:  # no path made for a file that is not there
            continue
        p = Path(cases_dir) / name
        if names is not None or p.exists():
            return p
    return None


def read_case(path: Path) -> dict | None:
    """A finished case, or None when the file is missing, partial or corrupt (then it is recomputed)."""
    path = Path(path)
    if not path.is_file():  # a FIFO or a device under a case's name: reading it would block or never end
        return None
    try:
        raw = path.read_bytes()
    except OSError:
        return None
    rec = _read_legacy(raw) if path.suffix == LEGACY_SUFFIX else decode_record(raw)
    if (
        not isinstance(rec, dict)
        or any(k not in rec for k in ROW_KEYS)
        or not isinstance(rec["row"], dict)
        or "status" not in rec["row"]
    ):
        return None
    return rec


def read_curve(path: Path) -> dict:
    """The curve of a finished case file (either format), arrays as numpy arrays."""
    rec = read_case(path)
    if rec is None:
        raise ValueError(f"{path}: not a readable case record")
    return rec["curve"]


# -- the first format: JSON with arrays as base64 (read only) --------------------------------------------


def decode_array(v) -> np.ndarray:
    """A first-format array ({"dtype", "shape", "b64"}) or a plain JSON list, as a float array."""
    if isinstance(v, dict) and "b64" in v:
        return np.frombuffer(base64.b64decode(v["b64"]), dtype=v.get("dtype", "<f8")).reshape(v["shape"]).copy()
    return np.asarray(v, dtype=float)


def _read_legacy(raw: bytes) -> dict | None:
    try:
        rec = json.loads(raw)
    except (ValueError, RecursionError):
        return None
    if not isinstance(rec, dict) or not isinstance(rec.get("curve"), dict):
        return rec
    c = rec["curve"]
    for k in ("x", "w", "w_ref", "rotation"):
        if k in c:
            c[k] = decode_array(c[k])
    if isinstance(c.get("fields"), dict):
        c["fields"] = {k: decode_array(v) for k, v in c["fields"].items()}
    if isinstance(c.get("history"), dict):
        h = c["history"]
        c["history"] = {
            "t": decode_array(h["t"]),
            "series": {k: decode_array(v) for k, v in h.get("series", {}).items()},
            "ylabel": h.get("ylabel", "displacement"),
        }
    return rec
