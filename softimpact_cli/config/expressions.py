"""Parse multiples of a symbol ("5*pi/8", "3*T/4") without evaluating anything.

Allowed forms: a number, ``S``, ``a*S``, ``S/b``, ``a*S/b`` (``a`` may carry a sign;
``a`` and ``b`` are decimal numbers; spaces are ignored).
"""

from __future__ import annotations

import math
import re

_NUMBER = r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?"


def _pattern(symbol: str) -> re.Pattern:
    return re.compile(
        rf"^(?:(?P<sign>[+-])?|(?P<a>{_NUMBER})\*)(?P<sym>{re.escape(symbol)})"
        rf"(?:/(?P<b>{_NUMBER}))?$"
    )


_PATTERNS: dict[str, re.Pattern] = {}


def parse_multiple(value: object, symbol: str, unit: float) -> float:
    """Value of ``value`` where ``symbol`` stands for ``unit``.

    Raises ValueError with a message listing the allowed forms.
    """
    if isinstance(value, bool):
        raise ValueError(f"must be a number or a string like '{symbol}', 'a*{symbol}/b'")
    if isinstance(value, int | float):
        try:
            result = float(value)
        except OverflowError:  # an integer beyond the float range
            raise ValueError(f"{value!r} is not finite") from None
    elif isinstance(value, str):
        text = value.replace(" ", "")
        pattern = _PATTERNS.setdefault(symbol, _pattern(symbol))
        match = pattern.match(text)
        if match is None:
            try:
                result = float(text)
            except ValueError:
                raise ValueError(
                    f"cannot read {value!r}: use a number or one of '{symbol}', "
                    f"'a*{symbol}', '{symbol}/b', 'a*{symbol}/b'"
                ) from None
        else:
            a = float(match["a"]) if match["a"] else (-1.0 if match["sign"] == "-" else 1.0)
            b = float(match["b"]) if match["b"] else 1.0
            if b == 0.0:
                raise ValueError(f"cannot read {value!r}: division by zero")
            result = a * unit / b
    else:
        raise ValueError(f"must be a number or a string like '{symbol}', 'a*{symbol}/b'")
    if not math.isfinite(result):
        raise ValueError(f"{value!r} is not finite")
    return result


def parse_phase(value: object) -> float:
    """A phase in radians: a number or a multiple of pi."""
    return parse_multiple(value, "pi", math.pi)


def format_multiple(x: float, symbol: str, unit: float, max_denominator: int = 64) -> str:
    """Short text for ``x``: 'a*S/b' when x is such a multiple of ``unit``, else '%.6g'."""
    from fractions import Fraction

    ratio = Fraction(x / unit).limit_denominator(max_denominator)
    if ratio.denominator and abs(float(ratio) * unit - x) < 1e-12 * max(1.0, abs(x)):
        a, b = ratio.numerator, ratio.denominator
        if a == 0:
            return "0"
        head = symbol if a == 1 else ("-" + symbol if a == -1 else f"{a}*{symbol}")
        return head if b == 1 else f"{head}/{b}"
    return f"{x:.6g}"
