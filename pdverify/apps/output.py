"""Where a command's output goes: its format (``--format``, else the ``--out`` extension, else a table), the check
that ``--out`` can be written before anything is computed, the write itself (atomic: a failure leaves no partial
file), and a solve's result as a table."""

from __future__ import annotations

import errno
import os
import stat
from enum import Enum
from pathlib import Path

from ..core.errors import InputError, OutputError
from ..core.result import one_line


class Format(str, Enum):  # noqa: UP042 (typer reads str-Enum choices)
    table = "table"
    json = "json"
    csv = "csv"


def result_table(result) -> str:
    """A solve's result as the table format prints it: ``#`` header lines (scene, model, dofs, version,
    parameters, timings, info, warnings, outputs), then one column per output at each point."""
    cols = result.columns()
    names = list(cols)
    lines = [f"# scene: {result.scene}   model: {result.model}   dofs: {result.dofs}   version: {result.version}"]
    lines.append("# parameters: " + ", ".join(f"{k}={v}" for k, v in result.parameters.items()))
    lines.append("# timings: " + ", ".join(f"{k}={v:.4g}" for k, v in result.timings.items()))
    for k, v in result.info.items():
        if not isinstance(v, (list, dict)):
            lines.append(f"# {k}: {v}")
    lines += [f"# {w}" for w in result.warning_lines()]
    lines += [f"# {w}" for w in result.output_lines()]
    lines = [one_line(line) for line in lines]
    lines.append("".join(f"{n:>16}" for n in names))
    n = len(cols["x"])
    for i in range(n):
        lines.append("".join(f"{float(cols[c][i]):16.8g}" for c in names))
    return "\n".join(lines) + "\n"


_SUFFIX_FORMAT = {".csv": Format.csv, ".json": Format.json, ".txt": Format.table}


def out_format(out: Path | None, fmt: Format | None) -> Format:
    """The output format: --format if given, else the one the --out extension names, else table; a --format that
    contradicts the extension is an error (``--out r.json --format csv`` would write CSV into a .json file)."""
    implied = _SUFFIX_FORMAT.get(out.suffix.lower()) if out is not None else None
    if fmt is not None and implied is not None and fmt != implied:
        raise InputError(
            f"--format {fmt.value} and --out {out}: the extension {out.suffix} means {implied.value}; "
            f"drop --format or name the file *{next(k for k, v in _SUFFIX_FORMAT.items() if v == fmt)}"
        )
    return fmt or implied or Format.table


def target(out: Path, option: str) -> Path:
    """The file a write to ``out`` replaces: ``out``, or the file a symlink at ``out`` names. Only a regular file, or
    one that does not exist yet, is ever written: a folder, a device (``/dev/full``), a FIFO or a socket, a symlink to
    one, or a symlink to nothing, is refused (OutputError, exit 4) before anything is computed."""
    if out.is_symlink() and _loops(out):
        raise OutputError(f"{option} {out}: a symlink that leads back to itself; give a file path")
    real = Path(os.path.realpath(out)) if out.is_symlink() else out
    via = f" (a symlink to {real})" if real != out else ""
    if via and str(real).startswith("/proc/") and not real.is_file():  # /dev/stdout: a pipe or a terminal
        raise OutputError(
            f"{option} {out}{via}: not a regular file (a process's stream); pdverify writes regular files only: "
            "give a file path, or leave --out out to write to standard output"
        )
    if via and not os.path.lexists(real):  # writing there would make its folders anywhere the link points
        raise OutputError(f"{option} {out}{via}: a symlink to nothing; give a file path, or make {real} first")
    if real.is_dir():
        example = "pdverify.xml" if option == "--junit" else "result.csv"
        raise OutputError(f"{option} {out}{via}: is a folder; give a file name, e.g. {out / example}")
    if os.path.lexists(real) and not real.is_file():
        raise OutputError(
            f"{option} {out}{via}: not a regular file (a device, FIFO or socket); pdverify writes regular files "
            "only: give a file path"
        )
    return real


def check_writable(out: Path, option: str) -> None:
    """Before any computation: ``out`` can be created or replaced as a regular file (its folder may be missing: it
    is made), and its name (and that of the temporary file written beside it) is not too long for its folder."""
    try:
        out = target(out, option)
        limit, tmp = _name_max(out.parent), f".{out.stem}.tmp-{os.getpid()}{out.suffix}"  # write_file's temporary
        if len(tmp.encode()) > limit:
            raise OutputError(
                f"{option} {out}: a file name of {len(out.name.encode())} bytes, where this folder takes names of up "
                f"to {limit} and pdverify first writes a temporary file {len(tmp) - len(out.name)} bytes longer "
                "beside it; give a shorter name"
            )
    except OSError as exc:
        raise OutputError(f"{option} {out}: cannot write ({exc.strerror or exc}); choose another path") from None
    parent = out.parent
    while not parent.exists() and parent != parent.parent:
        parent = parent.parent
    if not parent.is_dir():
        raise OutputError(f"{option} {out}: {parent} is {_kind(parent)}, not a folder; choose another path")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise OutputError(f"{option} {out}: no permission to write in {parent}; choose another path")


def check_apart(junit: Path, out: Path, own_files: tuple[str, ...], own_folders: tuple[str, ...]) -> None:
    """Before any computation: ``--junit`` is not one of the files the command writes into ``out`` (its
    ``own_files``, or anything under its ``own_folders``), which the XML would replace or be replaced by."""
    j, o = Path(os.path.realpath(junit)), Path(os.path.realpath(out))
    inside = j.parent == o and (j.name in own_files or j.name.endswith(".html"))
    inside = inside or any(o / f in j.parents for f in own_folders)
    if inside:
        raise OutputError(
            f"--junit {junit}: one of the files the command writes into --out {out}; give another name (e.g. "
            f"{out / 'junit.xml'}) or another folder"
        )


def _kind(path: Path) -> str:
    """'a file', 'a FIFO', 'a device' or 'a socket': what ``path`` (which exists and is not a folder) is."""
    mode = os.stat(path).st_mode if os.path.exists(path) else 0
    if stat.S_ISFIFO(mode):
        return "a FIFO"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    return "a socket" if stat.S_ISSOCK(mode) else "a file"


def _name_max(folder: Path) -> int:
    """The longest file name (bytes) the file system of ``folder`` (or of its nearest existing parent) takes."""
    while not folder.exists() and folder != folder.parent:
        folder = folder.parent
    try:
        return os.pathconf(folder, "PC_NAME_MAX")
    except (OSError, ValueError, AttributeError):  # no pathconf (Windows) or no answer: the common limit
        return 255


def _loops(path: Path) -> bool:
    """True when the symlink ``path`` leads back to itself (a loop: resolving it never ends)."""
    try:
        path.resolve(strict=True)
    except RuntimeError:  # Python < 3.13: a loop
        return True
    except OSError as exc:  # ELOOP (Python 3.13 and later), or missing
        return exc.errno == errno.ELOOP
    return False


def check_folder(out: Path, option: str) -> None:
    """Before any computation: ``out`` is a folder pdverify can write into, or can be made as one."""
    if os.path.islink(out) and _loops(out):
        raise OutputError(f"{option} {out}: a symlink that leads back to itself; give a folder (it is made if missing)")
    if os.path.islink(out) and not os.path.exists(out):  # mkdir would fail on the link itself
        raise OutputError(f"{option} {out}: a symlink to nothing; give a folder (it is made if missing)")
    real = Path(os.path.realpath(out))
    if os.path.lexists(real) and not real.is_dir():
        raise OutputError(f"{option} {out}: is {_kind(real)}, not a folder; give a folder (it is made if missing)")
    parent = real
    while not parent.exists() and parent != parent.parent:
        parent = parent.parent
    if not parent.is_dir():
        raise OutputError(f"{option} {out}: {parent} is {_kind(parent)}, not a folder; choose another path")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise OutputError(f"{option} {out}: no permission to write in {parent}; choose another path")


def write_file(out: Path, write, option: str) -> None:
    """``write(path)`` into a temporary file beside ``out``, then renamed over it: a failed write leaves no empty or
    partial file (and an existing ``out`` as it was). OSError -> OutputError (exit code 4)."""
    out = target(out, option)
    tmp = out.parent / f".{out.stem}.tmp-{os.getpid()}{out.suffix}"  # same suffix: writers choose by it
    try:
        out.parent.mkdir(parents=True, exist_ok=True)
        write(str(tmp))
        os.replace(tmp, out)
    except OSError as exc:
        where = f"a file in {out.parent}" if exc.filename in (str(tmp), str(out.parent)) else "it"
        why = exc.strerror or str(exc)
        if exc.errno == errno.ENOENT and out.parent.is_dir():  # a folder that exists and takes no new file: /proc
            why = "the folder exists but takes no new files: a virtual file system such as /proc or /sys"
        raise OutputError(f"{option} {out}: cannot write {where} ({why}); nothing was written") from None
    finally:
        try:
            tmp.unlink(missing_ok=True)
        except OSError:  # (a name too long to exist)
            pass


def with_warnings(result, suffix: str):
    """The result's writer of ``suffix``; a CSV (a transient's histories) gets the result's warnings as ``# warning:``
    lines before its header, as ``solve --format csv`` does (read with ``pandas.read_csv(path, comment="#")``)."""
    write = result.writers[suffix]
    lines = [one_line(f"# {w}") for w in result.warning_lines()]
    if suffix != ".csv" or not lines:
        return write

    def written(path: str) -> None:
        write(path)
        body = Path(path).read_text(encoding="utf-8")
        Path(path).write_text("\n".join(lines) + "\n" + body, encoding="utf-8")

    return written
