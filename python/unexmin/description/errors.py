"""The one error of a robot description that cannot be expanded or read."""


class DescriptionError(ValueError):
    """A robot description that xacro cannot expand, that is not the URDF the simulator reads, or that lacks what a
    reader needs; the message names the file (or parameter), the element and what was expected."""
