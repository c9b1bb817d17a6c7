"""One solve per (scene, model, options) in a process: a self-converged card's reference grid and its theory-gap case
share it (pdverify/study/solves.py), and both land in one pool batch (Case.operator_group)."""

import os
import time

import numpy as np

from pdverify.registry import run
from pdverify.study import execute, solves
from pdverify.study.spec import Case, _scene

SCENE = """name = "cantilever"
[beam]
length = 2.0
[section]
width = 0.1
height = 0.2
[material]
youngs_modulus = 2e11
poissons_ratio = 0.3
[supports]
left = "clamped"
right = "free"
[[loads]]
type = "point_force"
position = 2.0
value = -1000.0
"""


def test_a_second_call_returns_the_first_result_and_other_options_solve_again():
    a = solves.solve(SCENE, "a.toml", None, "pd-eb", {"points": 41})
    assert solves.solve(SCENE, "a.toml", None, "pd-eb", {"points": 41}) is a
    other = solves.solve(SCENE, "a.toml", None, "pd-eb", {"points": 81})
    assert other is not a and other.x.size == 81
    fresh = run(_scene(SCENE, "a.toml", None), "pd-eb", points=41)  # a kept result is what a new solve gives
    assert np.array_equal(fresh.w, a.w) and np.array_equal(fresh.x, a.x)


def test_the_gap_case_and_the_cases_it_is_the_reference_of_share_a_batch():
    reference = {"model": "pd-eb", "points": 161}
    coarse = [Case("a.toml", SCENE, None, "pd-eb", {"points": n}, reference) for n in (21, 41)]
    gap = Case("a.toml", SCENE, None, "pd-eb", {"points": 161}, {"model": "exact-timoshenko"})
    assert {c.operator_group for c in coarse} == {gap.operator_group}
    other_model = Case("a.toml", SCENE, None, "fem-eb", {"points": 21}, reference)
    assert other_model.operator_group != gap.operator_group


def _record(case, artefacts, cid):
    return {"case": case, "pid": os.getpid(), "started": time.monotonic_ns()}  # one clock for every process (Linux)


def run_order(got) -> list:
    """The ids of a pool's records in the order they ran: the order they come back in is the order the pool saw them
    done, which for batches done before it looks is any (concurrent.futures.as_completed takes those as a set)."""
    return [i for i, record in sorted(got, key=lambda g: g[1]["started"])]


def test_the_largest_batch_by_points_goes_first():
    """A batch of few cases with a large reference (a floor scene: 3 grids, a 4x finer reference) starts before many
    small cases, so the run does not end on it alone."""
    small = [Case("a.toml", SCENE, None, "pd-eb", {"points": 21}, {}) for _ in range(6)]
    large = Case("b.toml", SCENE.replace("cantilever", "floor"), None, "pd-eb", {"points": 641}, {"points": 10241})
    todo = small + [large]
    groups = ["small"] * 6 + ["large"]
    got = list(execute.pool(_record, todo, list(range(7)), None, 1, groups, [c.size for c in todo]))
    assert run_order(got)[0] == 6 and large.size == 641 + 10241 and small[0].size == 21
    by_count = list(execute.pool(_record, todo, list(range(7)), None, 1, groups))
    assert run_order(by_count)[-1] == 6  # by count alone it went last


def test_a_transient_is_as_large_as_the_states_it_records():
    """A time-stepping run on few points outlasts a static one on many: it counts its points times its recorded
    states (end_time / output_interval), so it starts first."""
    dynamic = SCENE + "\n[dynamics]\nend_time = 0.6\noutput_interval = 2.0e-4\n"
    transient = Case("t.toml", dynamic, None, "pd-timoshenko", {"points": 101}, {})
    static = Case("s.toml", SCENE, None, "pd-timoshenko", {"points": 3201}, {})
    assert transient.size == 101 * 3000 > static.size == 3201


def test_scenes_that_differ_in_their_loads_and_names_share_a_batch_scene_by_scene_finest_first():
    """A card's scenes on one support pair differ in their loads and names only: one batch, so one process factorises
    each grid's operator once; inside it each scene's reference grid runs first, then that scene's coarser grids, so
    the kept solve of the reference grid is still there when they ask for it."""
    uniform = SCENE.replace('name = "cantilever"', 'name = "cantilever, uniform"').replace(
        'type = "point_force"\nposition = 2.0', 'type = "distributed"'
    )
    reference = {"model": "pd-eb", "points": 161}
    cases = [
        Case(f, text, None, "pd-eb", {"points": n}, reference if n < 161 else {"model": "exact-timoshenko"})
        for n in (21, 41, 161)
        for f, text in (("a.toml", SCENE), ("b.toml", uniform))
    ]
    assert len({c.operator_group for c in cases}) == 1
    got = list(
        execute.pool(
            _record,
            cases,
            list(range(6)),
            None,
            1,
            [c.operator_group for c in cases],
            None,
            [c.batch_order for c in cases],
        )
    )
    ran = [(r["case"].scene_file, r["case"].given["points"]) for _, r in got]
    assert ran == [("a.toml", 161), ("a.toml", 41), ("a.toml", 21), ("b.toml", 161), ("b.toml", 41), ("b.toml", 21)]


def test_one_worker_runs_the_cases_in_the_pools_batches_and_order():
    """With one worker (a card in the main job) the cases run in the batches and the order the pool would hand out:
    a scene's reference grid right before its coarser grids, whatever order the study lists them in."""
    other = SCENE.replace('left = "clamped"', 'left = "pinned"').replace('right = "free"', 'right = "roller"')
    reference = {"model": "pd-eb", "points": 161}
    cases = [
        Case(f, text, None, "pd-eb", {"points": n}, reference if n < 161 else {"model": "exact-timoshenko"})
        for n in (21, 41, 161)  # grid by grid, as a study lists them
        for f, text in (("a.toml", SCENE), ("b.toml", other))
    ]
    groups, sizes, order = [c.operator_group for c in cases], [c.size for c in cases], [c.batch_order for c in cases]
    serial = list(execute.serial(_record, cases, list(range(6)), None, groups, sizes, order))
    pooled = list(execute.pool(_record, cases, list(range(6)), None, 1, groups, sizes, order))
    ran = [(r["case"].scene_file, r["case"].given["points"]) for _, r in serial]
    assert [i for i, _ in serial] == run_order(pooled)
    assert ran[:3] in (
        [("a.toml", 161), ("a.toml", 41), ("a.toml", 21)],
        [("b.toml", 161), ("b.toml", 41), ("b.toml", 21)],
    )
    assert sorted(ran) == sorted((c.scene_file, c.given["points"]) for c in cases)
    assert [i for i, _ in execute.serial(_record, cases, list(range(6)), None)] == list(range(6))  # no groups: as given
