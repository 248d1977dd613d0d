"""The one error of world_from_scan (docs/world_from_scan.md): a scan that cannot make a world."""


class ScanError(ValueError):
    """The scan cannot make a world; the message names the input and what was expected."""
