"""Results carry typed kinds that serialise exactly as their text."""

from __future__ import annotations

import json

import pytest

from mechgrade.solve.result import ObjectiveResult
from mechgrade.spec.model import ObjectiveKind


def test_a_result_read_from_text_gets_its_kind_type():
    result = ObjectiveResult("v", "vector", "m/s", (1.0, 0.0, 0.0), frame="N")
    assert result.kind is ObjectiveKind.VECTOR
    assert json.dumps({"kind": result.kind}) == '{"kind": "vector"}'


def test_an_unknown_kind_is_refused():
    with pytest.raises(ValueError, match="'matrix' is not a valid ObjectiveKind"):
        ObjectiveResult("v", "matrix", "m/s")
