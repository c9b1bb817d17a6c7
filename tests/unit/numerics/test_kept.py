"""The last few values a process made (pdverify/numerics/kept.py)."""

from pdverify.numerics.kept import Kept


def test_the_least_recently_used_goes_first_and_a_value_not_wanted_is_not_kept():
    made = []

    def make(v):
        return lambda: made.append(v) or v

    kept = Kept(2)
    assert [kept.get(k, make(k)) for k in ("a", "b", "a", "c")] == ["a", "b", "a", "c"]
    assert made == ["a", "b", "c"] and len(kept) == 2  # "a" used again, so "b" went when "c" came
    kept.get("a", make("a2"))
    kept.get("b", make("b"))
    assert made == ["a", "b", "c", "b"]
    assert kept.get("big", make("big"), keep=lambda v: False) == "big" and kept.get("big", make("big")) == "big"
    assert made[-2:] == ["big", "big"]
    kept.clear()
    assert len(kept) == 0


def test_a_budget_keeps_the_values_whose_sizes_fit_together():
    kept = Kept(10, budget=10, size=len)
    for k in ("aaaa", "bbbb", "cc"):
        kept.get(k, lambda k=k: k)
    assert len(kept) == 3
    kept.get("ddd", lambda: "ddd")  # 13 > 10: the least recently used goes
    assert len(kept) == 3 and "aaaa" not in kept._values
    kept.get("x" * 11, lambda: "x" * 11)  # larger than the budget: returned, not kept
    assert len(kept) == 3 and "x" * 11 not in kept._values
