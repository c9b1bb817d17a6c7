"""benchmarks/card_table.py: docs/verify.md's table row of a card, from the card's own fields."""

import importlib.util

from helpers import ROOT

spec = importlib.util.spec_from_file_location("card_table", ROOT / "benchmarks" / "card_table.py")
card_table = importlib.util.module_from_spec(spec)
spec.loader.exec_module(card_table)


def test_a_cards_row_names_its_checks_order_error_and_grids():
    checks = [
        {"check": "convergence (straight)", "verdict": "fail", "lowest_order": -0.6412},
        {"check": "error at the finest grid", "verdict": "fail", "largest": 0.01234},
        {"check": "grids within 1 % and 0.1 %", "verdict": "info", "points": {"0.01": 41, "0.001": None}},
        {"check": "dynamics (natural frequencies)", "verdict": "pass"},
    ]
    card = {"model": "pd-eb", "options": {"variant": "paper"}, "verdict": "fail", "checks": checks}
    row = card_table.row(card)
    assert row[:3] == ["pd-eb (variant=paper)", "**fail**", "fail"] and row[3] == "fail"
    assert row[4:9] == ["–"] * 5 and row[9] == "pass"  # checks the card does not have: a dash
    assert row[10:] == ["-0.64", "1.2e-02", "41 / –"]
    exact = {**card, "options": {}, "checks": [{"check": "convergence (straight)", "verdict": "pass"}]}
    assert card_table.row(exact)[0] == "pd-eb" and card_table.row(exact)[10:] == ["exact", "–", "– / –"]
    failed = {
        **exact,
        "checks": [{"check": "convergence (straight)", "verdict": "fail"}],
    }  # no order: every solve failed
    assert card_table.row(failed)[10] == "–"
