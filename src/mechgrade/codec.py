"""One codec between mechgrade's frozen dataclasses and plain JSON, driven by their types.

:func:`encode` turns a value into what :func:`json.dumps` writes (a dataclass as an object of
its fields, tuples and sets as arrays, an enum as its value, an error of mechgrade's as its
kind, message and place); :func:`decode` reads it back as the type named, and checks every
part against that type on the way: a text where a number belongs, a field the type lacks, an
error that is not mechgrade's, a number that is not finite is a :class:`CodecError`, never a
value of another shape. What the disk cache keeps (solutions, symbolic answers, ``check``
reports) and ``results.json`` go through it, so a file is read with the same rules as it was
written.

A field's ``metadata`` may ask for a form of its own: :data:`MAPPING` (a tuple of
``(key, value)`` pairs written as a JSON object), :data:`OMIT_DEFAULT` (left out when it holds
its default, so files written before the field existed read the same) and :func:`absent` (the
value taken when the field is not there, for a field without a default).

>>> from mechgrade.errors import AuthorWarning, Location
>>> w = AuthorWarning("T moves", Location("p.yaml", 3, 1))
>>> encode(w)
{'message': 'T moves', 'where': {'file': 'p.yaml', 'line': 3, 'column': 1, 'field': None}}
>>> decode(AuthorWarning, encode(w)) == w
True
>>> decode(tuple[float, ...], [1, 2.5])
(1.0, 2.5)
>>> decode(AuthorWarning, {"message": 3})
Traceback (most recent call last):
...
mechgrade.codec.CodecError: AuthorWarning.message: expected a text, found int
"""

from __future__ import annotations

import dataclasses
import enum
import math
import sys
import types
import typing
from collections.abc import Sequence
from functools import lru_cache
from typing import Any, Callable

from . import errors
from .errors import Location, MechgradeError


class CodecError(ValueError):
    """JSON that is not a value of the type asked for."""


MAPPING = {"codec": "mapping"}
"""Field metadata: a tuple of ``(key, value)`` pairs written as a JSON object.

>>> @dataclasses.dataclass(frozen=True)
... class Tagged:
...     tags: tuple[tuple[str, str], ...] = dataclasses.field(default=(), metadata=MAPPING)
>>> encode(Tagged((("a", "1"),)))
{'tags': {'a': '1'}}
>>> decode(Tagged, {"tags": {"a": "1"}})
Tagged(tags=(('a', '1'),))
"""
OMIT_DEFAULT = {"codec": "omit_default"}
"""Field metadata: left out of the JSON when the field holds its default."""


def absent(value: Any) -> dict:
    """Field metadata: ``value`` is read when the field is not in the JSON.

    >>> @dataclasses.dataclass(frozen=True)
    ... class Named:
    ...     id: str
    ...     name: str = dataclasses.field(metadata=absent(""))
    >>> decode(Named, {"id": "a"})
    Named(id='a', name='')
    """
    return {"codec_absent": value}


def encode(value: Any) -> Any:
    """``value`` as plain JSON (see the module's docstring).

    >>> from mechgrade.errors import SolveError
    >>> encode(SolveError("no", where=Location("p.yaml")))["error"]
    'SolveError'
    """
    if value is None or isinstance(value, (str, bool, int, float)):
        return value
    if isinstance(value, enum.Enum):
        return value.value
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        out = {}
        for name, form, default in _field_forms(type(value)):
            item = getattr(value, name)
            if form is None:
                out[name] = encode(item)
            elif form == "mapping":
                out[name] = {key: encode(v) for key, v in item}
            elif item != default:  # omit_default
                out[name] = encode(item)
        return out
    if isinstance(value, (frozenset, set)):
        return sorted(encode(item) for item in value)
    if isinstance(value, Sequence):  # tuples, lists, sequences worked out when read
        return [encode(item) for item in value]
    if isinstance(value, MechgradeError):
        return {"error": type(value).__name__, "message": value.message,
                "where": encode(value.where)}
    raise TypeError(f"cannot encode a {type(value).__name__}")


def decode(kind: Any, data: Any) -> Any:
    """``data`` (plain JSON) read as a value of ``kind``, a type or a type hint; raises
    :class:`CodecError` on anything else.

    >>> decode(Location | None, None), decode(frozenset[str], ["b", "a"]) == {"a", "b"}
    (None, True)
    >>> decode(tuple[int, int], [1, 2, 3])
    Traceback (most recent call last):
    ...
    mechgrade.codec.CodecError: expected 2 items, found 3
    """
    return _decoder(kind)(data)


@lru_cache(maxsize=None)
def _field_forms(cls: type) -> tuple[tuple[str, str | None, Any], ...]:
    """Each field's name, form (``None``: plain, ``"mapping"``, ``"omit_default"``) and
    default."""
    return tuple((f.name, f.metadata.get("codec"),
                  f.default_factory() if f.default_factory is not dataclasses.MISSING
                  else f.default) for f in dataclasses.fields(cls))


Decoder = Callable[[Any], Any]


@lru_cache(maxsize=None)
def _decoder(kind: Any) -> Decoder:
    """The decoder of ``kind``, made once per type."""
    origin = typing.get_origin(kind)
    args = typing.get_args(kind)
    if kind is type(None):
        return _none
    if kind in _PLAIN:
        return _PLAIN[kind]
    if origin in (typing.Union, types.UnionType):
        return _union(args)
    if origin is tuple:
        if len(args) == 2 and args[1] is Ellipsis:
            return _sequence(_decoder(args[0]), tuple)
        return _fixed(tuple(_decoder(a) for a in args))
    if origin in (list, Sequence):
        return _sequence(_decoder(args[0]), tuple if origin is Sequence else list)
    if origin is frozenset:
        return _sequence(_decoder(args[0]), frozenset)
    if isinstance(kind, type) and issubclass(kind, enum.Enum):
        return _enum(kind)
    if isinstance(kind, type) and issubclass(kind, MechgradeError):
        return _error(kind)
    if isinstance(kind, type) and dataclasses.is_dataclass(kind):
        return _dataclass(kind)
    raise TypeError(f"no decoder for {kind!r}")


def _none(data: Any) -> None:
    if data is not None:
        raise CodecError(f"expected nothing (null), found {type(data).__name__}")


def _text(data: Any) -> str:
    if type(data) is not str:
        raise CodecError(f"expected a text, found {type(data).__name__}")
    return data


def _integer(data: Any) -> int:
    if type(data) is not int:
        raise CodecError(f"expected a whole number, found {type(data).__name__}")
    return data


def _number(data: Any) -> float:
    if type(data) not in (float, int):
        raise CodecError(f"expected a number, found {type(data).__name__}")
    value = float(data)
    if not math.isfinite(value):
        raise CodecError(f"expected a finite number, found {value}")
    return value


def _flag(data: Any) -> bool:
    if type(data) is not bool:
        raise CodecError(f"expected true or false, found {type(data).__name__}")
    return data


_PLAIN: dict[Any, Decoder] = {str: _text, int: _integer, float: _number, bool: _flag}


def _union(members: tuple) -> Decoder:
    decoders = tuple(_decoder(m) for m in members)

    def decode_union(data: Any) -> Any:
        for decoder in decoders:
            try:
                return decoder(data)
            except CodecError:
                continue
        raise CodecError(f"expected one of {_names(members)}, found {type(data).__name__}")

    return decode_union


def _names(members: tuple) -> str:
    return ", ".join(getattr(m, "__name__", None) or str(m) for m in members)


def _sequence(item: Decoder, make: type) -> Decoder:
    def decode_sequence(data: Any) -> Any:
        if type(data) is not list:
            raise CodecError(f"expected a list, found {type(data).__name__}")
        return make(item(value) for value in data)

    return decode_sequence


def _fixed(items: tuple[Decoder, ...]) -> Decoder:
    def decode_fixed(data: Any) -> tuple:
        if type(data) is not list:
            raise CodecError(f"expected a list, found {type(data).__name__}")
        if len(data) != len(items):
            raise CodecError(f"expected {len(items)} items, found {len(data)}")
        return tuple(item(value) for item, value in zip(items, data))

    return decode_fixed


def _enum(kind: type[enum.Enum]) -> Decoder:
    def decode_enum(data: Any) -> enum.Enum:
        try:
            return kind(data)
        except (ValueError, TypeError):
            raise CodecError(f"expected a {kind.__name__}, found {data!r:.40}") from None

    return decode_enum


def _error(kind: type[MechgradeError]) -> Decoder:
    where = _decoder(Location)

    def decode_error(data: Any) -> MechgradeError:
        if type(data) is not dict or set(data) != {"error", "message", "where"}:
            raise CodecError("expected an error (error, message, where)")
        found = getattr(errors, _text(data["error"]), None)
        if not (isinstance(found, type) and issubclass(found, kind)):
            raise CodecError(f"expected an error of mechgrade's, found {data['error']!r:.40}")
        try:
            return found(_text(data["message"]), where=where(data["where"]))
        except TypeError:  # an error made of others (SpecErrors): not kept whole
            raise CodecError(f"cannot rebuild a {found.__name__}") from None

    return decode_error


def _dataclass(cls: type) -> Decoder:
    hints = typing.get_type_hints(cls, vars(sys.modules[cls.__module__]))
    fields = [(f.name, _mapping(hints[f.name]) if f.metadata.get("codec") == "mapping"
               else _decoder(hints[f.name]),
               f.default is not dataclasses.MISSING or f.default_factory is not dataclasses.MISSING,
               f.metadata.get("codec_absent", _NOTHING))
              for f in dataclasses.fields(cls) if f.init]
    known = frozenset(name for name, _, _, _ in fields)

    def decode_dataclass(data: Any) -> Any:
        if type(data) is not dict:
            raise CodecError(f"expected a {cls.__name__} (an object), found "
                             f"{type(data).__name__}")
        unknown = data.keys() - known
        if unknown:
            raise CodecError(f"{cls.__name__}: no field {sorted(unknown)[0]!r}")
        values = {}
        for name, decoder, optional, missing in fields:
            if name in data:
                try:
                    values[name] = decoder(data[name])
                except CodecError as err:
                    raise CodecError(f"{cls.__name__}.{name}: {err}") from None
            elif missing is not _NOTHING:
                values[name] = missing
            elif not optional:
                raise CodecError(f"{cls.__name__}: no {name!r}")
        try:
            return cls(**values)
        except (TypeError, ValueError) as err:  # the class's own checks (__post_init__)
            raise CodecError(f"{cls.__name__}: {err}") from None

    return decode_dataclass


_NOTHING = object()
"""No :func:`absent` value given."""


def _mapping(kind: Any) -> Decoder:
    """The decoder of a :data:`MAPPING` field of type ``tuple[tuple[K, V], ...]``."""
    key, value = typing.get_args(typing.get_args(kind)[0])
    read_key, read_value = _decoder(key), _decoder(value)

    def decode_mapping(data: Any) -> tuple:
        if type(data) is not dict:
            raise CodecError(f"expected an object, found {type(data).__name__}")
        return tuple((read_key(k), read_value(v)) for k, v in data.items())

    return decode_mapping
