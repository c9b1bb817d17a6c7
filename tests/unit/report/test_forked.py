"""A function run in a forked copy of the process (pdverify/report/forked.py): its value comes back; a failure in the
copy runs the function here, where its error is raised as usual."""

import os

import pytest

from pdverify.report import forked


def test_the_value_comes_back_from_another_process():
    parent = os.getpid()
    got = forked.start(lambda: (os.getpid(), [1.5, "svg"]))()
    assert got[1] == [1.5, "svg"] and got[0] != parent


def test_a_failure_in_the_copy_is_met_again_here():
    calls = []

    def fails():
        calls.append(os.getpid())
        raise ValueError("bad figure")

    result = forked.start(fails)
    with pytest.raises(ValueError, match="bad figure"):
        result()
    assert calls == [os.getpid()]  # the copy's own call is not seen here: only the parent's
