"""The replay's one error type."""


class ReplayError(Exception):
    """A bag or an argument the replay cannot use; the message says which and why."""
