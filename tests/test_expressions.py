import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from softimpact_cli.expressions import format_multiple, parse_multiple, parse_phase


@pytest.mark.parametrize(
    "text, expected",
    [
        ("pi", math.pi),
        ("-pi", -math.pi),
        ("2*pi", 2 * math.pi),
        ("pi/4", math.pi / 4),
        ("5*pi/8", 5 * math.pi / 8),
        (" 0.573 * pi ", 0.573 * math.pi),
        ("1.5", 1.5),
        (3, 3.0),
        (0.25, 0.25),
    ],
)
def test_phase_forms(text, expected):
    assert parse_phase(text) == pytest.approx(expected, rel=1e-15)


@pytest.mark.parametrize("text", ["5*pie/8", "pi*5", "2pi", "pi/0", "__import__('os')", "pi/",
                                  "", "nan", True, [1.0]])
def test_phase_rejects(text):
    with pytest.raises(ValueError):
        parse_phase(text)


def test_period_symbol():
    assert parse_multiple("3*T/4", "T", 2.0) == 1.5
    assert parse_multiple("T", "T", 2.0) == 2.0
    with pytest.raises(ValueError):
        parse_multiple("3*pi/4", "T", 2.0)


@given(st.integers(-50, 50), st.integers(1, 64))
def test_format_parse_round_trip(a, b):
    x = a * math.pi / b
    text = format_multiple(x, "pi", math.pi)
    assert parse_phase(text) == pytest.approx(x, rel=1e-12, abs=1e-15)
