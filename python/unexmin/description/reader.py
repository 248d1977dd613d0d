"""Reads the values of one description's XML elements by the simulator's rules (cpp/unexmin/sim/description_reader.h):
numbers are whitespace-separated finite C numbers, an attribute that must be there is there, and every failure is a
DescriptionError "<source>: <problem>" naming the element and the attribute."""

import math
import re

import numpy as np

from unexmin.description.errors import DescriptionError

# What C's strtod reads as a whole token: decimal or hexadecimal, infinities and NaN (the latter rejected as not
# finite). Python's float() also takes "1_000" and other digits; this does not.
_DECIMAL = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")
_HEX = re.compile(r"[+-]?0[xX]([0-9a-fA-F]+\.?[0-9a-fA-F]*|\.[0-9a-fA-F]+)([pP][+-]?\d+)?")
_SPECIAL = re.compile(r"[+-]?(inf|infinity|nan)", re.IGNORECASE)


def c_number(token):
    """The value of `token` as strtod reads a whole token, None when it is not a number."""
    if _DECIMAL.fullmatch(token) or _SPECIAL.fullmatch(token):
        return float(token)
    if _HEX.fullmatch(token):
        return float.fromhex(token)
    return None


def text_of(element, name):
    """Attribute `name` of `element`, "" when missing."""
    return element.get(name, "")


def number_text(value):
    """A number as the simulator's messages write it (formatNumber: 12 significant digits)."""
    return f"{value:.12g}"


class Reader:
    def __init__(self, source):
        self.source = source

    def fail(self, what):
        raise DescriptionError(f"{self.source}: {what}")

    def numbers(self, text, where):
        """The finite numbers of `text` (none when None)."""
        out = []
        for token in (text or "").split():
            v = c_number(token)
            if v is None or not math.isfinite(v):
                self.fail(f"{where}: '{token}' is not a finite number")
            out.append(v)
        return out

    def attr_numbers(self, element, attr, count, where):
        """The numbers of attribute `attr` of `element`, which must exist and hold `count` of them (any when 0)."""
        text = element.get(attr) if element is not None else None
        if text is None:
            self.fail(f"missing {where} attribute '{attr}'")
        values = self.numbers(text, f"{where}@{attr}")
        if count and len(values) != count:
            self.fail(f"{where}@{attr} has {len(values)} numbers, expected {count}")
        return values

    def attr(self, element, name, where):
        return self.attr_numbers(element, name, 1, where)[0]

    def attr_or(self, element, name, where, fallback):
        return self.attr(element, name, where) if element is not None and element.get(name) is not None else fallback

    def vector3(self, element, attr, where):
        return np.array(self.attr_numbers(element, attr, 3, where))

    def child(self, element, name, where):
        """The first child <name> of `element`, which must exist."""
        c = element.find(name)
        if c is None:
            self.fail(f"missing <{name}> in {where}")
        return c

    def value_of(self, element, name, count, where):
        """The numbers of <name value="..."/> under `element`."""
        return self.attr_numbers(self.child(element, name, where), "value", count, f"{where}/{name}")

    def params(self, element, where):
        """{name: [numbers]} of the <param name value> children of `element`."""
        out = {}
        for p in element.findall("param"):
            name = p.get("name")
            if name is None:
                self.fail(f"{where}/param has no 'name'")
            out[name] = self.attr_numbers(p, "value", 0, f"{where}/param[{name}]")
        return out
