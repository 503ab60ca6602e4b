"""Unit text is allow-listed, normalised and converted through one pint registry."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from mechgrade.errors import UnitError
from mechgrade.units import (Quantity, describe_dimension, dimension, from_si, normalize_unit,
                             parse_quantity, registry, si_unit, to_si)


@pytest.mark.parametrize("text, canonical", [
    ("m/s", "m / s"), ("ft/s^2", "ft / s ** 2"), ("ft/s²", "ft / s ** 2"), ("ft/s2", "ft / s ** 2"),
    ("m*s^-2", "m * s ** -2"), ("kg m²/s²", "kg * m ** 2 / s ** 2"), ("1/s", "1 / s"),
    ("°", "deg"), ("rpm", "rpm"), ("", ""), ("1", ""), ("dimensionless", ""),
    ("N·m", "N * m"), ("(m/s)/s", "(m / s) / s"),
])
def test_unit_text_is_normalised(text, canonical):
    assert normalize_unit(text) == canonical


@pytest.mark.parametrize("text, message", [
    ("furlongz", "('furlongz' is not a unit)"),
    ("m/s**9**9", "(misplaced power)"),
    ("m/s^99", "expected a power of at most 12"),
    ("m/s^x", "expected a whole-number power after '^'"),
    ("m 2", "found 'm «2»' (a number inside a unit)"),
    ("m/", "expected a complete unit"),
    ("m" * 70, "expected a unit of at most 64 characters"),
    ("__import__", "('__import__' is not a unit)"),
    ("m;s", "found 'm«;»s' (cannot read it)"),
    ("m - s", "found 'm «-» s' (a minus sign between units)"),
    ("m)", "expected a complete unit such as 'm/s^2', found 'm)'"),
    ("(m", "expected a complete unit such as 'm/s^2', found '(m'"),
    ("*m", "found '«*»m' (an operator with nothing before it)"),
    ("m/*s", "found 'm/«*»s' (an operator with nothing before it)"),
])
def test_bad_unit_text_is_refused(text, message):
    with pytest.raises(UnitError) as info:
        normalize_unit(text)
    assert message in str(info.value)


def test_conversions_and_dimensions():
    assert to_si(30, "deg") == pytest.approx(0.5235987755982988)
    assert to_si(12, "rpm") == pytest.approx(1.2566370614)
    assert from_si(1.0, "cm") == pytest.approx(100.0)
    assert dimension("ft/s^2") == dimension("m/s^2")
    assert describe_dimension(dimension("m/s^2")) == "an acceleration ([length]/[time]²)"
    assert si_unit("in/s") == "m / s"
    assert registry() is registry()


@pytest.mark.parametrize("text, quantity", [
    ("98.5 ft/s²", Quantity(98.5, "ft / s ** 2")), ("4.9e1 m/s", Quantity(49.0, "m / s")),
    ("-1.4 rad/s", Quantity(-1.4, "rad / s")), (".5 m", Quantity(0.5, "m")), ("7", Quantity(7.0, "")),
])
def test_quantities(text, quantity):
    assert parse_quantity(text) == quantity


@pytest.mark.parametrize("text", ["m/s", "nan m", "inf m", "", "1e999 m"])
def test_bad_quantities(text):
    with pytest.raises(UnitError):
        parse_quantity(text)


@given(st.floats(-1e6, 1e6, allow_nan=False), st.sampled_from(["ft", "in", "cm", "deg", "rpm", "mm/s^2"]))
def test_si_round_trip(value, unit):
    assert from_si(to_si(value, unit), unit) == pytest.approx(value, rel=1e-12, abs=1e-9)


@pytest.mark.parametrize("text, message", [
    ("e", "found 'e' in 'e' (not a unit here: the elementary charge"),
    ("k", "not a unit here: Boltzmann's constant"),
    ("Nm", "write N*m for newton metres"),
    ("fts^-2", "found 'fts' in 'fts^-2' (ambiguous: write ft or ft*s)"),
    ("lbs", "ambiguous: write lb or lb*s"),
    ("ft//s^2", "found 'ft/«/»s^2' (an operator with nothing before it)"),
    ("m*/s", "(an operator with nothing before it)"),
    ("ft/s-2", "a negative power after '/' is ambiguous"),
    ("degC", "expected an absolute temperature (K or degR), found 'degC'"),
    ("°F", "found 'degF' (an offset scale: convert to K first)"),
    ("celsius", "an offset scale"),
])
def test_units_a_student_does_not_mean_are_refused(text, message):
    with pytest.raises(UnitError) as info:
        normalize_unit(text)
    assert message in info.value.message


@pytest.mark.parametrize("text, canonical", [("g0", "g_0"), ("g_0", "g_0"), ("m s-2", "m * s ** -2"),
                                             ("K", "K"), ("degR", "degR"), ("ms", "ms"),
                                             ("meters", "meters"), ("km/h", "km / h")])
def test_standard_gravity_absolute_temperatures_and_full_plurals_are_units(text, canonical):
    assert normalize_unit(text) == canonical
    assert to_si(1.0, "g0") == pytest.approx(9.80665)


@pytest.mark.parametrize("unit, name", [
    ("N", "a force"), ("lbf", "a force"), ("kg*m/s^2", "a force"), ("J", "an energy or moment"),
    ("N*m", "an energy or moment"), ("W", "a power"), ("kg*m^2/s", "an angular momentum")])
def test_dynamics_dimensions_are_named_whatever_unit_wrote_them(unit, name):
    assert describe_dimension(dimension(unit)).startswith(name + " (")


def test_revolutions_are_written_rev():
    assert normalize_unit("rev/s") == "revolution / s"
    assert to_si(0.69, "rev/s") == pytest.approx(0.69 * 2 * math.pi)
    assert to_si(41.4, "rev/min") == pytest.approx(to_si(41.4, "rpm"))


def test_pound_mass_is_written_lbm():
    assert normalize_unit("lbm") == "pound"
    assert to_si(20, "lbm") == pytest.approx(20 * 0.45359237)
    assert to_si(1, "lbm*ft/s") == pytest.approx(0.45359237 * 0.3048)


@pytest.mark.parametrize("unit, si", [("G", 1e-4), ("gauss", 1e-4), ("mG", 1e-7),
                                      ("kG", 0.1), ("dpt", 1.0), ("dioptre", 1.0),
                                      ("diopter", 1.0)])
def test_engineering_meanings_of_gauss_and_dioptre(unit, si):
    # engineering's gauss (1e-4 T, as WeBWorK's lib/Units.pm), not pint's CGS-Gaussian one;
    # dpt the dioptre (1/m, as STACK's units), not pint's deci-pint
    assert si_unit(unit) in ("kg / A / s ** 2", "1 / m")
    assert to_si(1.0, unit) == pytest.approx(si)
    assert normalize_unit(unit) == unit
