"""pytest configuration: one BLAS thread, repeatable property tests, the tiers (tests/README.md) and their time
guard."""

import os

import pytest
from hypothesis import settings

# as the command line does (pdverify/apps/cli.py): one BLAS thread per process, set before numpy is imported (this
# file imports nothing that imports it); the test workers (pytest-xdist) are the parallelism
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

# Property tests draw the same examples on every run (a CI failure reproduces on any machine, and a green
# run means the same thing each time); `pytest --hypothesis-profile=explore` searches afresh.
settings.register_profile("repeatable", derandomize=True, database=None)
settings.register_profile("explore", derandomize=False)
settings.load_profile("repeatable")


@pytest.fixture
def make_scene():
    from helpers import scene_dict  # deferred: helpers imports numpy, after the BLAS setting above

    from pdverify.core.scene_file import parse_scene

    def make(left="clamped", right="free", loads=(), **over):
        return parse_scene(scene_dict(left, right, loads, **over))

    return make


# -- the tiers' time budget ------------------------------------------------------------------------------
# A default-tier test should take under TIER_BUDGET_S seconds (tests/README.md). Over-budget tests are listed at the
# end of every run; with --tier-guard (on a quiet machine, when moving tests between tiers) they fail the run. A
# plain run never fails on time: no test may pass or fail with the machine's load.
TIER_BUDGET_S = 3.0
_OVER_BUDGET: list[tuple[str, float]] = []


def pytest_addoption(parser):
    parser.addoption(
        "--tier-guard",
        action="store_true",
        help=f"fail the run when a default-tier test takes over {TIER_BUDGET_S:g} s (use on a quiet machine)",
    )


def pytest_runtest_logreport(report):
    if report.when == "call" and report.duration > TIER_BUDGET_S and "slow" not in report.keywords:
        _OVER_BUDGET.append((report.nodeid, report.duration))


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    if _OVER_BUDGET:
        terminalreporter.section(f"default-tier tests over {TIER_BUDGET_S:g} s (mark them slow or make them faster)")
        for nodeid, took in sorted(_OVER_BUDGET, key=lambda r: -r[1]):
            terminalreporter.write_line(f"{took:6.2f} s  {nodeid}")


def pytest_sessionfinish(session, exitstatus):
    if _OVER_BUDGET and session.config.getoption("--tier-guard") and exitstatus == 0:
        session.exitstatus = 1


# -- record_property values cross the worker boundary (pytest-xdist serialises plain Python only) -----------------
def _plain(value):
    if hasattr(value, "tolist"):  # numpy scalars and arrays
        return value.tolist()
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value if isinstance(value, (int, float, str, bool, type(None))) else str(value)


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    report = outcome.get_result()
    report.user_properties = [(name, _plain(value)) for name, value in report.user_properties]
