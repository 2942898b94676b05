"""The records layer (rotorpillar.records, provenance's writer): how a record
becomes JSON and comes back, how a damaged file is named, and that docs/schema.md is
what the types say.

References: the JSON standard (no NaN: non-finite numbers are written null) and
msgspec's own contract (a field of the wrong type is named by its path, ``$.a.b[0]``).
No tolerance anywhere: a number passes through JSON unchanged (msgspec writes the
shortest repr that reads back to the same double).
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import msgspec
import numpy as np
import pytest
from numpy.typing import NDArray

from rotorpillar import records
from rotorpillar.provenance import Provenance, write_result
from rotorpillar.records import Array, Record

ROOT = Path(__file__).resolve().parents[1]


class Peak(Record):
    omega: float
    amplitude: float | None


class Curve(Record, eq=False):
    speeds: Array
    grid: NDArray[np.float64] | None = None


class Pulse(Record, tag_field="kind", tag="pulse"):
    amplitude: float


class Quiet(Record, tag_field="kind", tag="none"):
    pass


class Holder(Record):
    peaks: tuple[Peak, ...]
    motion: Pulse | Quiet
    where: Path | None = None


def test_non_finite_numbers_are_written_null_and_numpy_as_numbers():
    text = records.encode({"a": math.nan, "b": np.float32(2.5), "c": np.int64(3), "d": np.inf, "e": np.bool_(True)})
    assert json.loads(text) == {"a": None, "b": 2.5, "c": 3, "d": None, "e": True}


def test_arrays_come_back_as_float_arrays_with_nan_for_null():
    c = Curve(np.array([1.0, math.nan, 3.0]), np.arange(6.0).reshape(2, 3))
    back = records.decode(records.encode(c), Curve)
    assert isinstance(back.speeds, np.ndarray) and back.speeds.dtype == float
    assert np.isnan(back.speeds[1]) and back.speeds[[0, 2]].tolist() == [1.0, 3.0]
    assert back.grid is not None and back.grid.shape == (2, 3) and back.grid.tolist() == c.grid.tolist()
    with pytest.raises(msgspec.ValidationError, match=r"\$\.speeds"):
        records.decode(b'{"speeds": 3}', Curve)


def test_a_union_of_records_is_told_apart_by_its_tag():
    h = Holder((Peak(1.5, None),), Pulse(0.3), Path("/tmp/x"))
    back = records.decode(records.encode(h), Holder)
    assert back == h and isinstance(back.motion, Pulse)
    assert json.loads(records.encode(Quiet())) == {"kind": "none"}
    assert records.tag(Pulse(1.0)) == "pulse"
    with pytest.raises(msgspec.ValidationError, match=r"Invalid value 'quake' - at `\$\.motion\.kind`"):
        records.decode(b'{"peaks": [], "motion": {"kind": "quake"}}', Holder)


def test_replace_takes_records_and_frozen_dataclasses():
    from rotorpillar.scene import load_scene

    assert records.replace(Peak(1.0, 2.0), amplitude=None) == Peak(1.0, None)
    scene = load_scene("paper")
    assert records.replace(scene.rotor, mass=1.0).mass == 1.0
    with pytest.raises(AttributeError):
        Peak(1.0, 2.0).omega = 3.0  # type: ignore[misc]  # frozen: the point of the test


def test_a_damaged_file_is_named_with_the_field_at_fault(tmp_path):
    path = tmp_path / "peaks.json"
    path.write_text('{"peaks": [{"omega": "fast", "amplitude": 1}], "motion": {"kind": "none"}}')
    with pytest.raises(ValueError, match=r"peaks\.json: Expected `float`, got `str` - at `\$\.peaks\[0\]\.omega`"):
        records.read(path, Holder)
    path.write_text('{"peaks": [], "motion"')
    with pytest.raises(ValueError, match=r"peaks\.json: not JSON"):
        records.read(path, Holder)
    path.write_text('{"peaks": []}')
    with pytest.raises(ValueError, match="peaks.json: Object missing required field `motion`"):
        records.read(path, Holder)


def test_a_result_file_carries_its_provenance_beside_the_record(tmp_path):
    head = {"command": "test", "scene_source": "paper", "overrides": ["a.b=1"], "scene": {"name": "paper"}}
    path = write_result(tmp_path / "r.json", Peak(2.0, math.inf), head, {"total": 1.25})
    doc = json.loads(path.read_text())
    assert list(doc)[:6] == ["command", "scene_source", "overrides", "scene", "omega", "amplitude"]
    assert doc["amplitude"] is None and doc["timings"] == {"total": 1.25}
    assert records.read(path, Peak) == Peak(2.0, None)
    prov = records.read(path, Provenance)
    assert prov.command == "test" and prov.overrides == ("a.b=1",) and prov.scene == {"name": "paper"}
    assert prov.machine is not None and prov.machine.cores and "python" in prov.versions
    with pytest.raises(ValueError, match="needs its scene"):
        write_result(tmp_path / "s.json", Peak(1.0, 1.0))
    assert not (tmp_path / "s.json").exists()


def test_the_schema_page_is_what_the_types_say():
    p = subprocess.run(
        [sys.executable, str(ROOT / "tools" / "schema_doc.py"), "--check"], capture_output=True, text=True, cwd=ROOT
    )
    assert p.returncode == 0, p.stderr
