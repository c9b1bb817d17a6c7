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
kind reads as ``None`` and the case is recomputed. The format exists because the first one (JSON with
base64 arrays) cost ~0.32 ms to encode a 1,200-point case on a 2-core machine; this one costs 56 us in a
tight loop and ~150 us inside a run, where the caches are cold after each solve (``benchmarks/runner_overhead.py``).
Files of that first format (``<case id>.json``) are still read (:func:`case_file`, :func:`read_curve`).
"""

from __future__ import annotations

import base64
import json
import os
import struct
import sys
import zlib
from pathlib import Path

import numpy as np

from ._case_writer import MESSAGE, write_all, write_atomic  # noqa: F401 (write_atomic re-exported)

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
    header = json.dumps({"case": rec["case"], "row": rec["row"], "curve": curve}, default=_scalar,
                        separators=(",", ":"), allow_nan=True).encode("utf-8")
    data = b"".join(chunks)
    crc = zlib.crc32(data, zlib.crc32(header))
    return b"".join((MAGIC, _LENGTHS.pack(len(header), len(data), crc), header, data))


def decode_record(raw: bytes) -> dict | None:
    """Inverse of :func:`encode_record`; None when the bytes are not a whole, intact record."""
    start = len(MAGIC) + _LENGTHS.size
    if len(raw) < start or raw[:len(MAGIC)] != MAGIC:
        return None
    n_header, n_data, crc = _LENGTHS.unpack_from(raw, len(MAGIC))
    if len(raw) != start + n_header + n_data:
        return None
    view = memoryview(raw)
    header, data = view[start:start + n_header], view[start + n_header:]
    if zlib.crc32(data, zlib.crc32(header)) != crc:
        return None
    try:
        rec = json.loads(bytes(header))
    except ValueError:
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


def write_record(path: Path, rec: dict) -> None:
    """A case record, encoded (:func:`encode_record`) and written atomically (:func:`write_atomic`)."""
    write_atomic(path, encode_record(rec))


class WriterProcess:
    """Case files written by a child process (``_case_writer.py``, started with ``posix_spawn``), so the file
    system's latency leaves the solving thread: creating a file cost 0.1-1.5 ms on the 2-core VM this was
    measured on, up to several times the whole 5 % budget of a 6 ms case. The runner encodes the record
    (:func:`encode_record`) and puts it into a pipe (~90 us inside a run); the child makes the system calls. A
    thread cannot do this (it waits for the GIL after each call while the solver runs Python), and forking the
    runner and waiting for it cost 10 ms even with nothing to write; the spawned child is a bare interpreter
    that starts while the first case is solved. The pipe's buffer (64 kB: one or two records) is all that can
    wait, so a killed run loses the cases in flight and nothing else; the child ignores SIGINT, so after
    Ctrl-C it still writes what it was given. ``close`` waits for it and raises the first failed write (disk
    full, permissions) as OSError, as does ``put`` once the child has stopped. POSIX only (``available``)."""

    available = hasattr(os, "posix_spawn")

    def __init__(self):
        r, w = os.pipe()
        status_r, status_w = os.pipe()
        script = str(Path(__file__).with_name("_case_writer.py"))
        try:
            self._pid = os.posix_spawn(sys.executable, [sys.executable, "-S", "-I", script], os.environ,
                                       file_actions=[(os.POSIX_SPAWN_DUP2, r, 0), (os.POSIX_SPAWN_DUP2, status_w, 1)])
        finally:
            os.close(r)
            os.close(status_w)
        self._fd, self._status = w, status_r

    def put(self, path: Path, data: bytes) -> None:
        p = os.fsencode(str(path))
        try:
            write_all(self._fd, MESSAGE.pack(len(p), len(data)) + p)
            write_all(self._fd, data)
        except BrokenPipeError:  # the child stopped: its own message says why
            self.close()
            raise

    def close(self) -> float:
        """Wait for the child; its CPU seconds."""
        if self._fd < 0:
            return 0.0
        os.close(self._fd)
        self._fd = -1
        _, code, usage = os.wait4(self._pid, 0)
        message = b"".join(iter(lambda: os.read(self._status, 65536), b""))
        os.close(self._status)
        if message or code:
            raise OSError(f"writing a case file failed: {message.decode('utf-8', 'replace') or f'writer exit status {code}'}")
        return usage.ru_utime + usage.ru_stime


def case_file(cases_dir: Path, case_id: str, names: set[str] | None = None) -> Path | None:
    """The record of ``case_id`` in ``cases_dir``: this format's file, else a first-format ``.json``
    file (studies run before the change), else None. ``names``: the directory's file names when the
    caller has listed it once (a resumed study looks up every case; one listing instead of a stat each)."""
    for suffix in (SUFFIX, LEGACY_SUFFIX):
        p = Path(cases_dir) / f"{case_id}{suffix}"
        if (p.name in names) if names is not None else p.exists():
            return p
    return None


def read_case(path: Path) -> dict | None:
    """A finished case, or None when the file is missing, partial or corrupt (then it is recomputed)."""
    path = Path(path)
    try:
        raw = path.read_bytes()
    except OSError:
        return None
    rec = _read_legacy(raw) if path.suffix == LEGACY_SUFFIX else decode_record(raw)
    if not isinstance(rec, dict) or any(k not in rec for k in ROW_KEYS) or not isinstance(rec["row"], dict) \
            or "status" not in rec["row"]:
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
    except ValueError:
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
        c["history"] = {"t": decode_array(h["t"]), "series": {k: decode_array(v) for k, v in h.get("series", {}).items()},
                        "ylabel": h.get("ylabel", "displacement")}
    return rec
