"""A finished study as JUnit XML, the test report every CI system displays.

One ``testsuite`` per study: one ``testcase`` per benchmark row (classname ``<study>.benchmarks``), one per
order-check row (``<study>.checks``, one per series a check matches) and one ``every case ran``
(``<study>.cases``) whose ``error`` lists the cases that failed outside an expected-fail row. A ``fail`` or
``missing`` verdict is a ``failure`` whose message holds the target, computed value, ratio and case id; an
``expected-fail`` row passes and says so in ``system-out``, as does an ``unexpected-pass``.
"""

from __future__ import annotations

import time
import xml.etree.ElementTree as ET
from pathlib import Path

from ..core.version import __version__
from .checks import FAILING, Outcome, benchmark_message, check_message
from .store import write_atomic

NOTES = {
    "expected-fail": "expected-fail: the row documents a known defect, and it still fails (counted as a pass)",
    "unexpected-pass": "unexpected-pass: the row documents a known defect, and it now passes: review the row",
}


def _testcase(suite: ET.Element, classname: str, name: str, verdict: str, message: str) -> None:
    case = ET.SubElement(suite, "testcase", classname=classname, name=name, time="0")
    if verdict in FAILING:
        ET.SubElement(case, "failure", message=f"{verdict}: {message}", type=verdict).text = message
    else:
        ET.SubElement(case, "system-out").text = f"{NOTES[verdict]}: {message}" if verdict in NOTES else message


def junit_xml(outcome: Outcome, wall: float = 0.0) -> ET.ElementTree:
    """The JUnit tree of a finished study (:class:`Outcome`); ``wall``: the run's seconds."""
    study = outcome.study
    suite = ET.Element(
        "testsuite", name=study.name, timestamp=time.strftime("%Y-%m-%dT%H:%M:%S", time.gmtime()), time=f"{wall:.3f}"
    )
    props = ET.SubElement(suite, "properties")
    for k, v in (("pdverify", __version__), ("study_file", str(study.path)), ("cases", str(len(outcome.results)))):
        ET.SubElement(props, "property", name=k, value=v)
    for _, b in outcome.benchmarks.iterrows():
        _testcase(suite, f"{study.name}.benchmarks", str(b["name"]), b["verdict"], benchmark_message(b))
    for _, c in outcome.checks.iterrows():
        scene = f" [{c['scene']}]" if isinstance(c.get("scene"), str) else ""
        _testcase(suite, f"{study.name}.checks", f"{c['name']}{scene}", c["verdict"], check_message(c))
    ran = ET.SubElement(suite, "testcase", classname=f"{study.name}.cases", name="every case ran", time="0")
    if outcome.unexcused:
        text = "\n".join(
            f"case {r['case_id']} ({r['model']} on {r['scene_file']}): {r['message']}" for r in outcome.unexcused
        )
        ET.SubElement(
            ran, "error", message=f"{len(outcome.unexcused)} of {len(outcome.results)} cases failed", type="failed"
        ).text = text
    excused = len(outcome.failed_cases) - len(outcome.unexcused)
    if excused:
        ET.SubElement(ran, "system-out").text = f"{excused} failed case(s) belong to expected-fail rows"
    cases = suite.findall("testcase")
    counts = {
        "tests": len(cases),
        "failures": sum(c.find("failure") is not None for c in cases),
        "errors": sum(c.find("error") is not None for c in cases),
        "skipped": 0,
    }
    suite.attrib.update({k: str(v) for k, v in counts.items()})
    root = ET.Element(
        "testsuites", name="pdverify", time=f"{wall:.3f}", **{k: str(v) for k, v in counts.items() if k != "skipped"}
    )
    root.append(suite)
    ET.indent(root)
    return ET.ElementTree(root)


def write_junit(outcome: Outcome, path: Path, wall: float = 0.0) -> None:
    """Write the JUnit file atomically (a killed run leaves the old file or the new one). Raises OSError."""
    tree = junit_xml(outcome, wall)
    data = ET.tostring(tree.getroot(), encoding="unicode", xml_declaration=False)
    write_atomic(path, '<?xml version="1.0" encoding="UTF-8"?>\n' + data + "\n")
