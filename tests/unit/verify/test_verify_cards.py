"""A study's ``verify`` key: validated with the study, cards run after its cases into OUT/verify/, listed and
linked in the report, their failures in the exit status only with ``verify_required = true``."""

import json
import re
import shutil
from pathlib import Path

import pytest
from helpers import ROOT, pdverify_process

SCENE = "paper_diyaroglu/clamped_free.toml"


def _study(tmp_path: Path, extra: str) -> Path:
    (tmp_path / "paper_diyaroglu").mkdir(exist_ok=True)
    shutil.copy(ROOT / "studies" / SCENE, tmp_path / SCENE)
    path = tmp_path / "s.toml"
    path.write_text(f'name = "tiny"\nscenes = ["{SCENE}"]\n{extra}\n[[runs]]\nmodel = "exact-eb"\npoints = [11, 21]\n')
    return path


@pytest.mark.slow
def test_bad_verify_entries_are_one_line_each_and_nothing_runs(tmp_path):
    study = _study(
        tmp_path,
        'verify = ["no-such-model", "pd-eb colour=red", "pd-eb points=11", "pd-curved-mms", 5, '
        '"pd-eb variant=paper", "pd-eb variant=paper", "pd-eb variant"]\nverify_required = "yes"',
    )
    r = pdverify_process("study", study, "--out", tmp_path / "out", "--quiet", cwd=tmp_path)
    assert r.returncode == 2 and "Traceback" not in r.stderr
    lines = r.stderr.splitlines()
    assert all(line.startswith("error: ") for line in lines)
    expect = [  # (entry, what the line names)
        ("verify_required", "give true or false"),
        ("verify[0] = 'no-such-model'", "unknown model"),
        ("verify[1] = 'pd-eb colour=red'", "takes no option 'colour'"),
        ("verify[2] = 'pd-eb points=11'", "the suite sets the grids"),
        ("verify[3] = 'pd-curved-mms'", "solves none of the suite's scenes"),
        ("verify[4] = 5", "give a model and its options"),
        ("verify[6] = 'pd-eb variant=paper'", "listed twice"),
        ("verify[7] = 'pd-eb variant'", "write key=value"),
    ]
    assert len(lines) == len(expect), r.stderr
    for entry, why in expect:
        assert sum(entry in line and why in line for line in lines) == 1, (entry, r.stderr)
    assert not (tmp_path / "out").exists()  # validated before anything ran


@pytest.mark.slow
def test_cards_are_written_linked_and_change_the_exit_status_only_when_required(tmp_path):
    """exact-eb passes every check; fem-timoshenko's full-integration element locks (docs/verify.md: 100 % at
    L/h = 1e4), so its card fails. ~15 s on 2 cores."""
    study = _study(tmp_path, 'verify = ["exact-eb", "fem-timoshenko variant=full"]\nverify_required = true')
    out = tmp_path / "out"
    r = pdverify_process("study", study, "--out", out, "--quiet", "--workers", "2", "--report", cwd=tmp_path)
    assert r.returncode == 1, r.stderr  # the study itself passes: the failed card, required, fails it
    assert "Traceback" not in r.stderr
    last = r.stderr.strip().splitlines()[-1]
    assert last.endswith("cards 1 pass, 1 fail (required); exit 1"), last
    folders = {"exact-eb": "exact_eb", "fem-timoshenko": "fem_timoshenko_variant_full"}
    for model, folder in folders.items():
        for name in ("card.html", "card.json", "junit.xml"):
            assert (out / "verify" / folder / name).is_file(), (folder, name)
        assert json.loads((out / "verify" / folder / "card.json").read_text())["model"] == model
    cards = json.loads((out / "verify" / "cards.json").read_text())
    assert cards["required"] is True
    assert [(c["folder"], c["verdict"]) for c in cards["cards"]] == [
        ("exact_eb", "pass"),
        ("fem_timoshenko_variant_full", "fail"),
    ]
    locking = {c["check"].split(" (")[0]: c["verdict"] for c in cards["cards"][1]["checks"]}["locking"]
    assert locking == "fail"
    index = (out / "index.html").read_text()
    assert 'id="cards"' in index
    # the cards' own time and the whole run's, in "What was run" (the study's wall_s counts its cases only); the
    # cards run side by side, so the whole takes at least the longest card's time, not their sum
    assert cards["wall_s"] >= max(c["wall_s"] for c in cards["cards"]) > 0
    run_table = index.split('id="run"', 1)[1]
    assert "cards_s (the verification cards)" in run_table and "cases and cards (s)" in run_table
    for folder in folders.values():
        assert f'href="verify/{folder}/card.html"' in index
    # the summary's row of the failed card (its rows carry the filters' attributes), linking to the failed check
    row = re.search(r'<tr class="f fail" [^>]*>(.*?)</tr>', index.split('id="cards"', 1)[1]).group(1)
    assert "fem-timoshenko" in row and "variant=full" in row
    assert 'href="verify/fem_timoshenko_variant_full/card.html#check-locking-error-vs-slenderness-5-10000"' in row
    card = (out / "verify" / "fem_timoshenko_variant_full" / "card.html").read_text()
    assert "id='check-locking-error-vs-slenderness-5-10000'" in card

    # not required: the same cards are reported, the exit status is the study's; their cases are reused
    case_files = sorted((out / "verify").rglob("cases/**/*.*"))
    stamps = [p.stat().st_mtime_ns for p in case_files]
    study.write_text(study.read_text().replace("verify_required = true", "verify_required = false"))
    r = pdverify_process("study", study, "--out", out, "--quiet", "--workers", "2", "--report", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert r.stderr.strip().splitlines()[-1].endswith("cards 1 pass, 1 fail (not required); exit 0")
    assert case_files and sorted((out / "verify").rglob("cases/**/*.*")) == case_files
    assert [p.stat().st_mtime_ns for p in case_files] == stamps
    assert "do not change the study's exit status" in (out / "index.html").read_text()

    # a study that drops the key: its report lists no card
    study.write_text(re.sub(r"verify.*\n", "", study.read_text()))
    r = pdverify_process("study", study, "--out", out, "--quiet", "--workers", "2", "--report", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert 'id="cards"' not in (out / "index.html").read_text()


@pytest.mark.slow
def test_a_card_in_a_study_is_the_card_of_pdverify_verify(tmp_path):
    """One card one after another (``--workers 1``, or a study with a single card) or side by side (``--workers 2``):
    the same card as ``pdverify verify`` writes (its suite's default grids, its cases and checks), whatever path ran
    it (one card alone, compared with both)."""
    study = _study(tmp_path, 'verify = ["exact-eb"]')
    alone = pdverify_process("verify", "exact-eb", "--out", tmp_path / "alone", "--quiet", cwd=tmp_path)
    assert alone.returncode == 0, alone.stderr
    own = json.loads((tmp_path / "alone" / "card.json").read_text())
    for workers in ("1", "2"):
        out = tmp_path / f"out{workers}"
        r = pdverify_process("study", study, "--out", out, "--quiet", "--workers", workers, cwd=tmp_path)
        assert r.returncode == 0 and "Traceback" not in r.stderr, r.stderr
        card = json.loads((out / "verify" / "exact_eb" / "card.json").read_text())
        assert card["cases"] == own["cases"] and card["verdict"] == own["verdict"] == "pass", workers
        judged = [(c["check"], c["verdict"]) for c in card["checks"] if c["check"] != "cost vs error"]
        assert judged == [(c["check"], c["verdict"]) for c in own["checks"] if c["check"] != "cost vs error"], workers
