"""Maps: reading, validation, rasterization, ROS import, and the output rule on writing."""
import numpy as np
import pytest

import plumekit


def test_read_and_describe(data):
    m = plumekit.read_map(data / "maps" / "cluttered-1.json")
    assert (m.width, m.height) == (10.0, 4.0)
    assert m.sources == [(1.5, 1.0)]
    assert len(m.obstacles) == 2 and all(len(p) >= 3 for p in m.obstacles)
    assert m.openings[0] == {"kind": "inlet", "from": (0.0, 0.0), "to": (0.0, 4.0), "speed": 1.0,
                             "profile": "uniform"}
    assert repr(m) == "<plumekit.Map 'cluttered-1' 10 x 4 m, 2 obstacles, 1 sources>"
    assert m.is_free((0.2, 0.2))
    assert not m.is_free(m.obstacles[0][0])  # a vertex is on the boundary: not free
    labels = plumekit.rasterize(m, 0.1)
    j, i = np.argwhere(labels == 0)[0]  # an obstacle cell: its centre is inside an obstacle
    assert not m.is_free(((i + 0.5) * 0.1, (j + 0.5) * 0.1))


def test_dict_round_trip_and_bad_field(data):
    m = plumekit.read_map(data / "maps" / "cluttered-1.json")
    again = plumekit.Map(m.to_dict())
    assert again.to_dict() == m.to_dict()
    d = m.to_dict()
    d["sources"] = [[50.0, 1.0]]
    with pytest.raises(plumekit.InputError, match="source"):
        plumekit.Map(d, origin="mine.json")


def test_validate_and_rasterize(data):
    m = plumekit.read_map(data / "maps" / "cluttered-1.json")
    check = plumekit.validate_map(m)
    assert check["inlet_reaches_outlet"] and 0.8 < check["free_fraction"] < 1.0
    labels = plumekit.rasterize(m, 0.1)
    assert labels.shape == (40, 100) and labels.dtype == np.uint8
    # The inlet is the whole left wall, the outlet the whole right one.
    assert (labels[:, 0] == 3).all() and (labels[:, -1] == 4).all()
    # The solid share matches the grid check's free share within a cell's rounding.
    assert abs((labels != 0).mean() - check["free_fraction"]) < 0.02


def office(data):
    # The README's import: a door on the left wall, a window on the right.
    return plumekit.import_ros(data / "ros" / "office.yaml", inlets=["0,1.8,0,3.4"],
                               outlets=["11.25,1.0,11.25,4.2"])


def test_import_ros(data):
    m = office(data)
    assert m.width > 0 and m.height > 0 and len(m.obstacles) > 0
    assert plumekit.validate_map(m)["inlet_reaches_outlet"]


def test_write_refuses_a_users_file(tmp_path, data):
    m = plumekit.read_map(data / "maps" / "cluttered-1.json")
    mine = tmp_path / "mine.json"
    mine.write_text("my notes\n")
    with pytest.raises(plumekit.InputError):
        plumekit.write_map(m, mine)
    assert mine.read_text() == "my notes\n"
    ros = office(data)
    out = tmp_path / "office.json"
    plumekit.write_map(ros, out)
    plumekit.write_map(ros, out)  # its own file: replaced
    back = plumekit.read_map(out)
    # The file spells coordinates to a micrometre.
    assert all(np.allclose(a, b, atol=1e-6) for a, b in zip(back.obstacles, ros.obstacles))
    assert len(back.obstacles) == len(ros.obstacles) and len(back.openings) == len(ros.openings)


def test_missing_file_names_it(tmp_path):
    with pytest.raises(plumekit.InputError, match="nothing.json"):
        plumekit.read_map(tmp_path / "nothing.json")
