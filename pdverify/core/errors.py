"""Errors that reach the user as one clear line each (no traceback)."""


class PdverifyError(Exception):
    """Base class: bad input or a failed computation, explained to the user.

    ``lines`` holds one message per problem; each names the field, the value and the fix.
    """

    exit_code = 2

    def __init__(self, lines):
        if isinstance(lines, str):
            lines = [lines]
        self.lines = list(lines)
        super().__init__("\n".join(self.lines))


class InputError(PdverifyError):
    """A scene, study or option is invalid (exit code 2)."""

    exit_code = 2


class SolveError(PdverifyError):
    """The numerical solution failed: singular system, blow-up, no convergence (exit code 3)."""

    exit_code = 3


class OutputError(PdverifyError):
    """Results could not be written: disk full, permissions, a file where a directory should be (exit code 4)."""

    exit_code = 4


class MissingQuantity(InputError, KeyError):
    """A result asked for a quantity its model does not give (exit code 2); a KeyError too, for a caller that looks
    a quantity up as it would a key."""

    def __str__(self) -> str:  # KeyError's quotes its message
        return "\n".join(self.lines)
