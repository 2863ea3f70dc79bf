import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from softimpact_cli.config.expressions import format_multiple, parse_multiple, parse_phase


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


@given(st.one_of(st.text(), st.text(alphabet="0123456789.eE+-*/ piT"), st.integers(),
                 st.floats(allow_nan=True, allow_infinity=True), st.booleans(), st.none()))
def test_parse_multiple_is_a_finite_number_or_a_value_error(value):
    # never another exception (OverflowError on 10**400, ...), never a non-finite result
    for symbol, unit in (("pi", math.pi), ("T", 4.83)):
        try:
            result = parse_multiple(value, symbol, unit)
        except ValueError:
            continue
        assert isinstance(result, float) and math.isfinite(result)


@given(st.floats(-1e12, 1e12, allow_nan=False), st.floats(1e-12, 1e12))
def test_multiple_forms_equal_the_arithmetic(a, b):
    assert parse_phase(f"{a!r}*pi/{b!r}") == pytest.approx(a * math.pi / b, rel=1e-12)
    assert parse_multiple(f"{a!r}*T", "T", 2.5) == pytest.approx(a * 2.5, rel=1e-15)


@pytest.mark.parametrize("text", ["1e308*pi", "pi/0", "--pi", "nan*pi", "inf*pi", "pi/1e-320",
                                  "1e400", 10**400, -(10**400), "pi/-0", "1e308*T/1e-308"])
def test_overflowing_and_malformed_forms_are_refused(text):
    with pytest.raises(ValueError):
        parse_multiple(text, "pi", math.pi)
