"""The replay's one error type, and how its commands (and the identification's) end."""


class ReplayError(Exception):
    """A bag or an argument the replay cannot use; the message says which and why."""


def print_summary(lines, outputs):
    """A command's last words: its summary lines, then the line naming its outputs; the exit status 0."""
    for line in lines:
        print(line)
    print(outputs)
    return 0
