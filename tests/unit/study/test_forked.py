"""A function run in a forked copy of the process (pdverify/study/forked.py): its value comes back; a failure in the
copy runs the function here, where its error is raised as usual."""

import os

import pytest

from pdverify.study import forked


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


def test_a_copy_that_starts_another_runs_it_itself():
    """A copy cannot fork (it is daemonic): a function it starts runs in it, inline, and both values come back."""
    parent = os.getpid()

    def outer():
        inner = forked.start(lambda: os.getpid())
        return os.getpid(), inner()

    got = forked.start(outer)()
    assert got[0] != parent and got[1] == got[0]
