"""Exceptions of fracarm; their messages are the fracdesign CLI's."""


class FracarmError(RuntimeError):
    """A failure the CLI reports with exit status 1 (bad file, bad document, numerical failure)."""


class UsageError(FracarmError, ValueError):
    """A bad option or argument: the CLI reports it with exit status 2."""
