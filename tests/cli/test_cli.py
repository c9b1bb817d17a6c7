"""The command line itself: --version, -h on every command, the output format from the --out extension, bench's
repeated --points, whole-or-nothing output files and the memory guard (docs/cli.md)."""

import errno
import json
import os
import pathlib
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest
from helpers import ROOT, cli

from pdverify import __version__

SCENE = ROOT / "studies/examples/cantilever_tip_load.toml"
COMMANDS = ["solve", "modes", "models", "study", "advise", "report", "bench", "version"]


def test_version_flag_and_command(capsys):
    for args in (["--version"], ["-V"]):
        code, out, _ = cli(args, capsys)
        assert code == 0 and out.strip() == f"pdverify {__version__}"
    code, out, _ = cli(["version"], capsys)
    assert code == 0 and out.strip() == __version__


def test_python_m_pdverify():
    r = subprocess.run([sys.executable, "-m", "pdverify", "--version"], capture_output=True, text=True, cwd=ROOT)
    assert r.returncode == 0 and r.stdout.strip() == f"pdverify {__version__}"


@pytest.mark.parametrize("flag", ["-h", "--help"])
@pytest.mark.parametrize("command", [None, *COMMANDS])
def test_help_everywhere(command, flag, capsys):
    code, out, err = cli([command, flag] if command else [flag], capsys)
    assert code == 0 and "Usage: pdverify" in out and err == ""
    if command:
        assert f"pdverify {command}" in out


@pytest.mark.parametrize(
    "suffix,check",
    [
        (".csv", lambda p: list(pd.read_csv(p).columns)[:2] == ["x", "w"]),
        (".json", lambda p: json.loads(p.read_text())["model"] == "exact-eb"),
        (".txt", lambda p: p.read_text().startswith("# scene: cantilever, tip load")),
        (".dat", lambda p: p.read_text().startswith("# scene: cantilever, tip load")),  # unknown extension: table
    ],
)
def test_format_from_the_out_extension(suffix, check, tmp_path, capsys):
    out = tmp_path / f"r{suffix}"
    code, stdout, err = cli(["solve", SCENE, "-m", "exact-eb", "--points", "11", "--out", out], capsys)
    assert code == 0 and stdout == "" and err == f"wrote {out}\n"
    assert check(out)


def test_the_file_written_is_named_as_the_shell_would_take_it(tmp_path, capsys):
    """A name ending in a space is a regular file named so; the line says which ("wrote x/ " showed no space)."""
    (tmp_path / "x").mkdir()
    code, _, err = cli(["solve", SCENE, "-m", "exact-eb", "--points", "11", "--out", f"{tmp_path}/x/ "], capsys)
    assert code == 0 and err == f"wrote '{tmp_path}/x/ '\n" and (tmp_path / "x" / " ").is_file()


def test_format_given_and_matching_the_extension(tmp_path, capsys):
    out = tmp_path / "r.json"
    code, _, _ = cli(["solve", SCENE, "-m", "exact-eb", "--points", "11", "--format", "json", "--out", out], capsys)
    assert code == 0 and len(json.loads(out.read_text())["x"]) == 11
    code, _, err = cli(["solve", SCENE, "-m", "exact-eb", "--format", "csv", "--out", tmp_path / "s.json"], capsys)
    assert code == 2 and "--format csv and --out" in err and not (tmp_path / "s.json").exists()


def test_out_creates_missing_folders(tmp_path, capsys):
    out = tmp_path / "a" / "b" / "r.csv"
    code, _, _ = cli(["solve", SCENE, "-m", "exact-eb", "--points", "11", "--out", out], capsys)
    assert code == 0 and len(pd.read_csv(out)) == 11


def test_failed_write_leaves_no_partial_file(tmp_path, capsys, monkeypatch):
    """The disk fills up half way through the write: exit 4, one line, no new file, an old file kept as it was,
    no temporary file left (was: an empty file)."""
    real = pathlib.Path.write_text

    def half_then_full(self, data, *a, **k):
        real(self, data[: len(data) // 2], *a, **k)
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(pathlib.Path, "write_text", half_then_full)
    new = tmp_path / "new.csv"
    code, out, err = cli(["solve", SCENE, "-m", "exact-eb", "--out", new], capsys)
    assert code == 4 and out == "" and err.count("\n") == 1 and "No space left on device" in err
    old = tmp_path / "old.csv"
    monkeypatch.setattr(pathlib.Path, "write_text", real)
    old.write_text("the previous result\n")
    monkeypatch.setattr(pathlib.Path, "write_text", half_then_full)
    code, _, _ = cli(["solve", SCENE, "-m", "exact-eb", "--out", old], capsys)
    assert code == 4 and old.read_text() == "the previous result\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["old.csv"]


def test_bench_points_as_the_readme_writes_them(capsys, monkeypatch):
    """`bench --points 101 201` (several values after one flag) and `--points 101 --points 201` are the same
    (the timed runs are replaced by a recorder: this checks the parsing, test_bench.py the timing)."""
    import pdverify.apps.bench

    calls = []

    def fake(model, points, scene):
        calls.append((model, points))
        return {"model": model, "points": points, "status": "failed", "message": "not run"}

    monkeypatch.setattr(pdverify.apps.bench, "bench_subprocess", fake)
    for args in (
        ["--points", "101", "201"],
        ["--points", "101", "--points", "201"],
        ["--points", "101", "201", "-m", "pd-eb"],
    ):
        calls.clear()
        code, out, err = cli(["bench", "-m", "exact-eb", *args], capsys)
        models = ["exact-eb", "pd-eb"] if "pd-eb" in args else ["exact-eb"]
        assert calls == [(m, p) for m in models for p in (101, 201)]
        # every run failed: each row printed, then one line and exit 3 (a computation failed), not 0
        assert code == 3, err
        assert out.count("failed: not run") == len(calls)
        assert err.strip().splitlines() == [
            f"error: {len(calls)} of {len(calls)} timed runs failed (first: exact-eb at 101 points: not run); "
            "the other rows are printed and written"
        ]
    code, _, err = cli(["bench", "-m", "exact-eb", "--points", "101", "x"], capsys)
    assert code == 2 and "--points" in err


def test_spread_repeats_only_touches_bench_points():
    from pdverify.apps.cliargs import spread_repeats as _spread_repeats

    assert _spread_repeats(["bench", "--points", "1", "2", "-m", "a"]) == [
        "bench",
        "--points",
        "1",
        "--points",
        "2",
        "-m",
        "a",
    ]
    assert _spread_repeats(["solve", "s.toml", "--points", "11"]) == ["solve", "s.toml", "--points", "11"]
    assert _spread_repeats(["solve", "bench", "--points", "11", "x"]) == ["solve", "bench", "--points", "11", "x"]


# Peak resident memory of whole static runs measured by `pdverify bench` (reports/bench/bench.jsonl, MB):
# maximum resident set of `pdverify solve SCENE --model M --points N --format json` (/usr/bin/time -v, 2026-11-25,
# with the round-off bound of every solve): the whole process, interpreter and imports included
MEASURED_PEAK_MB = {
    ("pd-eb", 1_000_000): 1378.8,
    ("pd-timoshenko", 1_000_000): 1174.0,
    ("fem-eb", 1_000_000): 1246.4,
    ("pd-curved", 100_000): 1032.7,
    ("pd-higher-order", 100_000): 391.0,
}


@pytest.mark.parametrize("model,points", list(MEASURED_PEAK_MB), ids=[m for m, _ in MEASURED_PEAK_MB])
def test_memory_estimate_covers_the_measured_peak(model, points):
    """The guard's estimate is above the measured peak, and within 2x of it (a guard that refuses runs that fit
    would be as wrong as none)."""
    from pdverify.core.scene_file import load_scene
    from pdverify.measure.memory import estimate_bytes
    from pdverify.registry import get_model

    scene = load_scene(ROOT / ("studies/paper_curved/semicircle_normal.toml" if model == "pd-curved" else SCENE))
    m = get_model(model)
    need, dofs, band = estimate_bytes(scene, m, m.resolve(scene, {"points": points}))
    peak = MEASURED_PEAK_MB[model, points] * 2**20
    assert peak < need < 2 * peak, (need / 2**20, dofs, band)


def test_memory_guard_refuses_pd_curved_at_ten_million_points(capsys):
    """pd-curved at 10^7 points: refused before the large allocation with the estimate (was: MemoryError after
    allocating 32 GiB)."""
    from pdverify.numerics.memory import available_bytes

    have = available_bytes()
    if have is None or have > 200 * 2**30:
        pytest.skip("needs a Linux machine with less than 200 GiB available for the refusal")
    code, out, err = cli(
        ["solve", ROOT / "studies/paper_curved/semicircle_normal.toml", "-m", "pd-curved", "--points", "10000000"],
        capsys,
    )
    assert code == 3 and out == "" and err.count("\n") == 1
    assert err.startswith("error: points = 10000000: model pd-curved would need about ") and "GiB" in err
    need = float(err.split("about ")[1].split(" GiB")[0])
    assert 100 < need < 200  # 6e7 unknowns x bandwidth 73 x 32 bytes = 131 GiB


def test_out_of_memory_is_one_line(capsys, monkeypatch):
    """A MemoryError the guard did not foresee is still one line and exit code 3."""
    from pdverify import registry

    def no_memory(*a, **k):
        raise MemoryError

    monkeypatch.setattr(registry, "run", no_memory)
    code, out, err = cli(["solve", SCENE, "-m", "exact-eb"], capsys)
    assert code == 3 and err.startswith("error: out of memory") and err.count("\n") == 1


@pytest.mark.parametrize("model", ["exact-eb", "pd-eb"])
def test_an_impossible_grid_from_the_api_is_one_solve_error(model):
    """registry.run, which studies call without the command line's estimate, turns the allocation numpy refuses
    (10^12 points: 7.3 TiB for one array) into one SolveError naming the points and the model."""
    from pdverify.core.errors import SolveError
    from pdverify.core.scene_file import load_scene
    from pdverify.registry import run

    with pytest.raises(SolveError) as got:
        run(load_scene(SCENE), model, points=10**12)
    msg = str(got.value)
    assert msg.startswith(f"points = {10**12}: model {model} ran out of memory") and "\n" not in msg


def test_exit_codes_are_documented():
    """docs/cli.md lists every exit code the CLI uses."""
    text = (ROOT / "docs" / "cli.md").read_text()
    for code in ("0", "1", "2", "3", "4"):
        assert f"| {code} |" in text


def test_units_key_of_a_scene():
    """units = "inch-pound" labels lengths in inches; SI by default; other values are errors."""
    import tomllib

    from pdverify.core.errors import InputError
    from pdverify.core.scene_file import parse_scene

    data = tomllib.loads(SCENE.read_text())
    assert parse_scene(data).length_unit == "m"
    assert parse_scene(dict(data, units="inch-pound")).length_unit == "in"
    with pytest.raises(InputError, match="units = 'imperial'"):
        parse_scene(dict(data, units="imperial"))
    # the numbers do not depend on the label
    from pdverify.registry import run

    a, b = (
        run(parse_scene(data), "exact-eb", points=11),
        run(parse_scene(dict(data, units="inch-pound")), "exact-eb", points=11),
    )
    assert np.array_equal(a.w, b.w)


def test_no_arguments_prints_the_help(capsys):
    code, out, err = cli([], capsys)
    assert code == 2 and "Usage: pdverify" in out and err == ""


def test_closed_stdout_is_no_traceback():
    """`pdverify -h | head -1`: the reader closes the pipe early; no traceback (was: AttributeError on the way out)."""
    p = subprocess.Popen([sys.executable, "-m", "pdverify"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, cwd=ROOT)
    p.stdout.close()
    err = p.stderr.read().decode()
    p.wait(timeout=60)
    assert "Traceback" not in err and p.returncode in (1, 2)


@pytest.mark.parametrize(
    "args",
    [["models"], ["solve", "studies/examples/cantilever_tip_load.toml", "-m", "exact-eb", "--points", "20001"]],
    ids=["models", "solve"],
)
def test_a_reader_that_leaves_early_ends_the_command_quietly_with_exit_1(args):
    """`pdverify solve ... | head -1` with stdout buffered (no PYTHONUNBUFFERED): the write that meets the closed
    pipe, during the command or at its final flush, ends it with exit 1 and nothing on stderr (docs/cli.md)."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONUNBUFFERED"}
    p = subprocess.Popen(
        [sys.executable, "-m", "pdverify", *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, cwd=ROOT, env=env
    )
    p.stdout.close()
    err = p.stderr.read().decode()
    p.wait(timeout=120)
    assert p.returncode == 1 and "error:" not in err and "Exception" not in err, err


# -- the grid's options, the same on every command that takes a grid ----------------------------------------------


def _rod_scene(tmp_path) -> pathlib.Path:
    p = tmp_path / "rod.toml"
    p.write_text(
        'name = "rod"\n[beam]\nlength = 1.0\n[section]\nwidth = 0.05\nheight = 0.05\n'
        "[material]\nyoungs_modulus = 70e9\npoissons_ratio = 0.3\ndensity = 2700\n"
        '[supports]\nleft = "clamped"\nright = "free"\n'
        '[[loads]]\ntype = "point_force"\nposition = 1.0\nvalue = 0.0\naxial = 100.0\n'
    )
    return p


@pytest.mark.parametrize("command", ["solve", "modes"])
def test_points_and_horizon_flags_are_the_model_options(command, tmp_path, capsys):
    """--points 41 --horizon 2 gives what -o points=41 -o horizon=2 gives, on solve and modes alike."""
    scene = str(_rod_scene(tmp_path))
    fmt = ["--format", "json"]
    a = cli([command, scene, "-m", "pd-rod", "--points", "41", "--horizon", "2", *fmt], capsys)
    b = cli([command, scene, "-m", "pd-rod", "-o", "points=41", "-o", "horizon=2", *fmt], capsys)
    c = cli([command, scene, "-m", "pd-rod", "--points", "41", *fmt], capsys)
    assert a[0] == b[0] == c[0] == 0
    strip = lambda d: {k: v for k, v in json.loads(d).items() if k not in ("timings", "info")}  # noqa: E731
    assert strip(a[1]) == strip(b[1]) and strip(a[1]) != strip(c[1])  # the horizon took effect (default 3)


@pytest.mark.parametrize("command", ["solve", "modes"])
def test_horizon_length_is_the_option_horizon_length(command, tmp_path, capsys):
    """--horizon-length 0.05 on 41 points of a 1 m rod is -o horizon_length=0.05, and two spacings: the same
    numbers as --horizon 2."""
    scene = str(_rod_scene(tmp_path))
    fmt = ["--format", "json"]
    a = cli([command, scene, "-m", "pd-rod", "--points", "41", "--horizon-length", "0.05", *fmt], capsys)
    b = cli([command, scene, "-m", "pd-rod", "--points", "41", "-o", "horizon_length=0.05", *fmt], capsys)
    c = cli([command, scene, "-m", "pd-rod", "--points", "41", "--horizon", "2", *fmt], capsys)
    assert a[0] == b[0] == c[0] == 0, (a[2], b[2], c[2])
    strip = lambda d: {k: v for k, v in json.loads(d).items() if k not in ("timings", "info")}  # noqa: E731
    assert strip(a[1]) == strip(b[1])
    for key, value in strip(a[1]).items():
        if isinstance(value, list) and value and isinstance(value[0], float):
            assert np.allclose(value, strip(c[1])[key], rtol=1e-12, atol=0), key


@pytest.mark.parametrize("command", ["solve", "verify"])
def test_horizon_flags_refused_in_one_line(command, tmp_path, capsys):
    """A model without a horizon refuses --horizon-length in one line (exit 2); a flag given twice (also as -o) is
    refused."""
    name = "fem-eb" if command == "verify" else "exact-rod"
    args = [name] if command == "verify" else [str(_rod_scene(tmp_path)), "-m", name]
    code, out, err = cli([command, *args, "--horizon-length", "0.01"], capsys)
    assert code == 2 and out == "" and err.count("\n") == 1 and "horizon_length" in err and name in err, err
    args = ["pd-rod"] if command == "verify" else [str(_rod_scene(tmp_path)), "-m", "pd-rod"]
    code, _, err = cli([command, *args, "--horizon", "2", "-o", "horizon=3"], capsys)
    assert code == 2 and err.startswith("error: --horizon 2") and "-o horizon=3: the same option twice" in err


@pytest.mark.parametrize("command", ["solve", "advise"])
def test_help_keeps_the_scenes_table_names(command, capsys):
    """A help text naming a scene table ([dynamics]) shows it: the help's markup does not take it for a style."""
    code, out, _ = cli([command, "-h"], capsys)
    assert code == 0 and "[dynamics]" in out


def _stub_verify(monkeypatch, verdict="fail"):
    """``pdverify verify`` with its suite replaced by a two-check card written as the real one is (card.json,
    card.html, junit.xml): the command's own handling of --junit, without the suite's solves."""
    import pdverify.verify
    from pdverify.verify.card import write_card

    ran = []

    def fake(name, out, options, **kw):
        ran.append(name)
        checks = [
            {"check": "convergence (straight)", "verdict": verdict, "summary": "order 1.0 < 1.7"},
            {"check": "dynamics", "verdict": "n/a", "summary": "static model"},
        ]
        card = {"model": name, "verdict": verdict, "suite_version": "t", "checks": checks, "wall_s": 0.5}
        page = dict.fromkeys(("title", "theory", "reference", "pdverify_version"), "x")
        page |= {"options": {}, "grids": [], "scenes": [], "curved_reference": None, "cases": 0, "failed_cases": 0}
        write_card(card | page | {"expected_order": 2.0}, out)
        return card

    monkeypatch.setattr(pdverify.verify, "verify", fake)
    return ran


def test_verify_junit_writes_the_cards_checks_to_the_file(tmp_path, capsys, monkeypatch):
    """--junit FILE: the card's JUnit XML (one testcase per check) in FILE, its folder made, the same document as
    junit.xml in --out (which stays); the exit code is the card's."""
    import xml.etree.ElementTree as ET

    _stub_verify(monkeypatch)
    junit = tmp_path / "ci" / "verify.xml"
    code, out, err = cli(["verify", "exact-eb", "--out", tmp_path / "card", "--quiet", "--junit", junit], capsys)
    assert code == 1, err
    assert junit.read_text() == (tmp_path / "card" / "junit.xml").read_text()
    suite = ET.parse(junit).getroot()
    assert suite.get("tests") == "2" and suite.get("failures") == "1" and suite.get("skipped") == "1"
    assert f"junit: {junit}" in err and "exact-eb: fail" in out
    assert not list(junit.parent.glob(".*tmp*")), "no temporary file is left"


def test_verify_junit_refused_before_the_suite_runs(tmp_path, capsys, monkeypatch):
    """A --junit that can never be written (a folder) is refused in one line, exit 4, before the suite runs."""
    ran = _stub_verify(monkeypatch)
    code, out, err = cli(["verify", "exact-eb", "--out", tmp_path / "card", "--junit", tmp_path], capsys)
    assert code == 4 and out == "" and err.count("\n") == 1 and err.startswith(f"error: --junit {tmp_path}"), err
    assert ran == [] and not (tmp_path / "card").exists()


def test_verify_junit_that_fails_to_write_keeps_the_card(tmp_path, capsys, monkeypatch):
    """A --junit write that fails after the suite (no permission by then) is exit 4 in one line naming where the card
    is; nothing partial is left at FILE."""
    import pdverify.apps.cli
    import pdverify.apps.output

    _stub_verify(monkeypatch, verdict="pass")

    def full(path):
        raise OSError(errno.ENOSPC, "No space left on device")

    real = pdverify.apps.output.write_file
    monkeypatch.setattr(pdverify.apps.cli, "write_file", lambda out, write, option: real(out, full, option))
    junit = tmp_path / "j.xml"
    code, out, err = cli(["verify", "exact-eb", "--out", tmp_path / "card", "--quiet", "--junit", junit], capsys)
    assert code == 4 and err.count("\n") == 1 and "No space left on device" in err, err
    assert f"the card is in {tmp_path / 'card'}" in err and (tmp_path / "card" / "card.json").is_file()
    assert not junit.exists() and list(tmp_path.glob(".j.tmp*")) == []


@pytest.mark.slow
def test_verify_junit_of_a_real_suite(tmp_path, capsys):
    """The whole suite on exact-eb with --junit: the file holds every check of the card."""
    import xml.etree.ElementTree as ET

    junit = tmp_path / "verify.xml"
    code, _, err = cli(["verify", "exact-eb", "--out", tmp_path / "card", "--quiet", "--junit", junit], capsys)
    card = json.loads((tmp_path / "card" / "card.json").read_text())
    assert code == 0, err
    assert [c.get("name") for c in ET.parse(junit).getroot()] == [c["check"] for c in card["checks"]]


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="RLIMIT_AS and /proc/self/status: Linux")
def test_the_memory_guard_counts_the_address_space_limit(tmp_path):
    """Under ``ulimit -v`` the memory a run may take is the limit's room, not the machine's MemAvailable (the guard
    read MemAvailable only, so a run in a 2 GiB address space past its estimate was not refused): pd-curved at 10^6
    points (about 13 GiB by its estimate) is refused in one line with exit 3 before allocating."""

    limit = 2 * 2**30
    code = (
        "import resource, sys\n"
        f"resource.setrlimit(resource.RLIMIT_AS, ({limit}, {limit}))\n"
        "from pdverify.numerics.memory import available_bytes\n"
        "print(available_bytes())\n"
    )
    have = int(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout)
    assert 0 < have < limit
    scene = ROOT / "studies/paper_curved/semicircle_normal.toml"
    run = (
        "import resource, sys\n"
        f"resource.setrlimit(resource.RLIMIT_AS, ({limit}, {limit}))\n"
        "from pdverify.apps.cli import main\n"
        f"sys.argv = ['pdverify', 'solve', '{scene}', '-m', 'pd-curved', '--points', '1000000']\n"
        "main()\n"
    )
    done = subprocess.run([sys.executable, "-c", run], capture_output=True, text=True, cwd=tmp_path)
    assert done.returncode == 3 and done.stderr.count("\n") == 1, done.stderr
    assert "would need about" in done.stderr and "GiB is available" in done.stderr


def test_the_memory_guard_extrapolates_a_band_that_grows_with_the_points(capsys, monkeypatch):
    """At a fixed horizon_length the band widens with the grid (m = delta / dx): the guard's probes took the factor the
    full grid resolved to beside horizon_length (refused: both given), so nothing was checked and the run died in
    its allocation (107 GiB for one array at 300,001 points); now the bandwidth is extrapolated with the points and
    the run refused before it, naming the largest grid whose estimate fits (8 GiB available, as if)."""
    from pdverify.core.scene_file import load_scene
    from pdverify.measure import memory
    from pdverify.registry import get_model

    have = 8 * 2**30
    monkeypatch.setattr(memory, "available_bytes", lambda: have)
    scene = ROOT / "studies/paper_yang/ss_uniform.toml"
    argv = ["solve", scene, "-m", "pd-eb", "--points", "300001", "--horizon-length", "0.05"]
    code, out, err = cli(argv, capsys)
    assert code == 3 and out == "" and err.count("\n") == 1 and "would need about" in err, err
    fits = int(err.rsplit("use at most about ", 1)[1].split()[0])
    m, sc = get_model("pd-eb"), load_scene(scene)
    sizes = memory.probe_sizes(sc, m, m.resolve(sc, {"points": 300001, "horizon_length": 0.05}))
    assert sizes[1][2] > sizes[0][2]  # the band grows with the points
    assert memory.need_bytes(sizes, fits) <= have < memory.need_bytes(sizes, fits + 1)
    # probed from 803 points at a fixed horizon_length (from 200,001 otherwise)
    monkeypatch.setattr(memory, "available_bytes", lambda: memory.need_bytes(sizes, 5001) // 2)
    code, _, err = cli(argv[:5] + ["5001"] + argv[6:], capsys)
    assert code == 3 and "would need about" in err
