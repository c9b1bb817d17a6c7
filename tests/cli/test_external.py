"""External-command models: a manifest, a separate script, and every way the script can fail."""

import json
import os
import subprocess
import sys
import textwrap

import numpy as np
import pandas as pd
import pytest
from helpers import ROOT

from pdverify.core.errors import InputError, SolveError
from pdverify.core.scene_file import load_scene
from pdverify.registry import run
from pdverify.registry.external import load_manifest

SCENE = ROOT / "studies" / "examples" / "cantilever_tip_load.toml"

# A script that answers with the cantilever's exact tip-load deflection w = P x^2 (3L - x) / (6 EI)
# (Timoshenko & Gere), or fails as its `mode` option says.
SCRIPT = textwrap.dedent("""
    import json, sys, time
    job = json.load(open(sys.argv[1])) if len(sys.argv) > 1 else json.load(sys.stdin)
    mode, n = job["options"]["mode"], job["options"]["points"]
    s = job["scene"]
    L, P = s["beam"]["length"], s["loads"][0]["value"]
    EI = s["material"]["youngs_modulus"] * s["section"]["width"] * s["section"]["height"] ** 3 / 12
    x = [L * i / (n - 1) for i in range(n)]
    w = [P * xi**2 * (3 * L - xi) / (6 * EI) for xi in x]
    if mode == "crash":
        sys.stderr.write("Traceback (most recent call last):\\nZeroDivisionError: boom in my solver\\n")
        sys.exit(3)
    if mode == "garbage":
        print("hello, I am not JSON")
        sys.exit(0)
    if mode == "hang":
        time.sleep(60)
    if mode == "nan":
        w[2] = float("nan")
    if mode == "short":
        w = w[:-1]
    out = json.dumps({"x": x, "w": w, "timings": {"solve_s": 0.001}})
    if len(sys.argv) > 2:
        open(sys.argv[2], "w").write(out)
    else:
        print(out)
""")

MODES = ["ok", "crash", "garbage", "hang", "nan", "short"]


def manifest(tmp_path, name="ext-tip", command=("{python}", "model.py"), timeout=2.0):
    (tmp_path / "model.py").write_text(SCRIPT)
    cmd = ", ".join(json.dumps(c) for c in command)
    text = f'''name = "{name}"\ncommand = [{cmd}]\ntimeout = {timeout}\n[capabilities]\ntheory = "euler-bernoulli"
[options.points]\ntype = "int"\ndefault = 11\nminimum = 3
[options.mode]\ntype = "str"\ndefault = "ok"\nchoices = {json.dumps(MODES)}\n'''
    path = tmp_path / f"{name}.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("command", [("{python}", "model.py"), ("{python}", "model.py", "{input}", "{output}")])
def test_external_model_matches_the_exact_solution(tmp_path, command):
    model = load_manifest(manifest(tmp_path, command=command))
    scene = load_scene(SCENE)
    res = run(scene, model, points=21)
    ref = run(scene, "exact-eb", points=21)
    np.testing.assert_allclose(res.x, ref.x, rtol=1e-15)
    np.testing.assert_allclose(res.w, ref.w, rtol=1e-12, atol=1e-15)  # the same formula, round-off apart
    assert res.timings["solve_s"] == 0.001 and res.timings["command_s"] > 0


@pytest.mark.parametrize(
    "mode, words",
    [
        ("crash", "exited with status 3: ZeroDivisionError: boom in my solver"),
        ("garbage", "the result is not JSON (starts 'hello, I am not JSON')"),
        ("hang", "no result after the timeout of 1 s"),
        ("nan", "result w holds NaN or infinite values (first at index 2)"),
        ("short", "result w has 20 values, x has 21"),
    ],
)
def test_each_failure_is_one_line_naming_model_and_case(tmp_path, mode, words):
    model = load_manifest(manifest(tmp_path, timeout=1))
    with pytest.raises(SolveError) as exc:
        run(load_scene(SCENE), model, points=21, mode=mode)
    (line,) = exc.value.lines
    assert line.startswith("model ext-tip on scene 'cantilever, tip load' (points=21, mode=" + mode + ")")
    assert words in line and "\n" not in line


@pytest.mark.slow
def test_cli_solve_with_a_manifest_path(tmp_path):
    path = manifest(tmp_path)
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    cmd = [sys.executable, "-m", "pdverify.apps.cli", "solve", str(SCENE), "--model", str(path), "--format", "json"]
    ok = subprocess.run(cmd + ["--points", "5"], capture_output=True, text=True, env=env, timeout=120)
    assert ok.returncode == 0, ok.stderr
    assert json.loads(ok.stdout)["model"] == "ext-tip" and len(json.loads(ok.stdout)["w"]) == 5
    bad = subprocess.run(cmd + ["--option", "mode=garbage"], capture_output=True, text=True, env=env, timeout=120)
    assert bad.returncode == 3 and bad.stdout == ""
    assert bad.stderr.splitlines() == [
        "error: model ext-tip on scene 'cantilever, tip load' (points=11, mode=garbage): "
        "the result is not JSON (starts 'hello, I am not JSON')"
    ]


def test_bad_manifest_is_one_line(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text('name = "x"\ncommand = "model.py"\n')
    with pytest.raises(InputError, match=r"m.toml: command = 'model.py': give a list of strings"):
        load_manifest(path)


@pytest.mark.slow
def test_study_goes_on_past_every_failure(tmp_path):
    """A study naming the manifest: the good case is measured, each failure is a row, nothing is lost."""
    manifest(tmp_path, timeout=1)
    (tmp_path / "scene.toml").write_text(SCENE.read_text())
    (tmp_path / "study.toml").write_text(
        textwrap.dedent(f"""
        name = "external"
        scenes = ["scene.toml"]
        external = ["ext-tip.toml"]
        reference = "exact-eb"
        [[runs]]
        model = "ext-tip"
        points = 21
        mode = {json.dumps(MODES)}
    """)
    )
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    env.pop("PDVERIFY_MODELS_PATH", None)
    out = tmp_path / "out"
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "pdverify.apps.cli",
            "study",
            str(tmp_path / "study.toml"),
            "--out",
            str(out),
            "--quiet",
            "--workers",
            "2",
        ],
        capture_output=True,
        text=True,
        env=env,
        timeout=300,
    )
    assert r.returncode == 1, r.stderr  # the study ran to its end; failed cases make it exit 1 (docs/ci.md)
    df = pd.read_csv(out / "results.csv")
    assert len(df) == len(MODES)
    by_mode = dict(
        zip(
            df["options"].map(lambda o: json.loads(o)["mode"]),
            zip(df["status"], df["message"].fillna(""), strict=True),
            strict=True,
        )
    )
    assert by_mode["ok"][0] == "ok"
    assert df.loc[df["status"] == "ok", "err_max"].iloc[0] < 1e-12  # the exact formula, round-off apart
    for mode in MODES[1:]:
        assert by_mode[mode][0] == "failed" and f"mode={mode})" in by_mode[mode][1]
    failed = [line for line in r.stderr.splitlines() if line.startswith("failed: ext-tip")]
    assert len(failed) == len(MODES) - 1


@pytest.mark.slow
def test_models_path_lists_manifests_and_warns_once_for_a_bad_one(tmp_path):
    manifest(tmp_path)
    (tmp_path / "bad.toml").write_text('name = "bad one"\ncommand = ["x"]\n')
    env = {**os.environ, "PYTHONPATH": str(ROOT), "PDVERIFY_MODELS_PATH": str(tmp_path)}
    r = subprocess.run(
        [sys.executable, "-m", "pdverify.apps.cli", "models"], capture_output=True, text=True, env=env, timeout=120
    )
    assert r.returncode == 0, r.stderr
    assert any(line.startswith("ext-tip ") for line in r.stdout.splitlines())
    assert r.stderr.splitlines() == [
        f"warning: external model manifest {tmp_path / 'bad.toml'}: name = 'bad one': "
        "give the model a name without spaces; skipped"
    ]


@pytest.mark.slow
def test_the_example_command_reads_plain_json_without_pdverify(tmp_path):
    """examples/external_model: the command runs with pdverify not importable (the scene is plain JSON, as any
    language reads it), and the manifest's model gives the example plug-in's numbers through pdverify."""
    example = ROOT / "examples" / "external_model"
    scene = load_scene(SCENE)
    job = json.dumps({"model": "fd-eb-command", "scene": scene.to_dict(), "options": {"points": 41}})
    blocked = "import sys, runpy; sys.modules['pdverify'] = None; runpy.run_path(sys.argv[1], run_name='__main__')"
    out = subprocess.run(
        [sys.executable, "-c", blocked, str(example / "fd_beam_command.py")],
        input=job,
        capture_output=True,
        text=True,
        timeout=60,
        cwd=example,
    )
    assert out.returncode == 0, out.stderr
    got = json.loads(out.stdout)
    res = run(scene, load_manifest(example / "fd_beam_command.toml"), points=41)
    ref = run(scene, "exact-eb", points=41)
    assert got["w"] == res.w.tolist() and len(got["x"]) == 41
    assert 0 < np.abs(res.w - ref.w).max() / np.abs(ref.w).max() < 1e-2  # second-order FD, not the exact formula
