"""Gas maps from readings: the same maps as `plumekit gdm`, and scores that mean something."""
import numpy as np
import pytest

import plumekit


@pytest.fixture(scope="module")
def block(data):
    return plumekit.read_map(data / "test-maps" / "test-1-block.json")


def log_rows(data):
    rows = np.loadtxt(data.parent / "examples" / "python" / "data" / "robot-log.csv",
                      delimiter=",", skiprows=2)
    return rows


def test_gas_map_is_the_cli_map(tmp_path, block, data, cli):
    rows = log_rows(data)
    m = plumekit.gas_map(block, rows)
    assert m["mean"].shape == (40, 100)
    assert np.isnan(m["mean"]).any()  # the block's cells
    assert np.nanmax(m["confidence"]) <= 1.0
    cli("gdm", data / "test-maps" / "test-1-block.json", "--samples",
        data.parent / "examples" / "python" / "data" / "robot-log.csv", "--out", tmp_path / "g")
    assert np.array_equal(np.load(tmp_path / "g" / "mean.npy"), m["mean"], equal_nan=True)
    assert [e[0] for e in m["source_estimates"]][:3] == ["peak mean", "peak variance",
                                                       "peak mean x variance"]


def test_scores_need_a_wind_and_improve_with_readings(block):
    wind = plumekit.flow(block, cell=0.1)
    source = block.sources[0]
    truth = plumekit.plume(wind, source, model="advection-diffusion", cell=0.5)["mean"]
    rows = [((i + 0.5) * 0.5, (j + 0.5) * 0.5, truth[j, i])
            for j in range(truth.shape[0]) for i in range(truth.shape[1])
            if block.is_free(((i + 0.5) * 0.5, (j + 0.5) * 0.5))]
    dense = plumekit.gas_map(block, rows, source=source, wind=wind, background="min")
    sparse = plumekit.gas_map(block, rows[::6], source=source, wind=wind, background="min")
    assert dense["kl_distance"] < sparse["kl_distance"]
    with pytest.raises(TypeError, match="needs wind"):
        plumekit.gas_map(block, rows, source=source)
    with pytest.raises(plumekit.InputError, match="not finite"):
        plumekit.gas_map(block, [(1.0, 1.0, float("nan"))])
    with pytest.raises(plumekit.OptionError):
        plumekit.gas_map(block, rows, kernel_width=-1)


def test_gas_map_names_bad_shapes_and_absurd_values(block):
    with pytest.raises(ValueError, match=r"an \[n, 3\] or \[n, 5\] array.*shape \(3\)"):
        plumekit.gas_map(block, np.array([1.0, 1.0, 5.0]))
    with pytest.raises(ValueError, match=r"shape \(2, 4\)"):
        plumekit.gas_map(block, np.zeros((2, 4)))
    with pytest.raises(ValueError, match="row 1 is 'abc'"):
        plumekit.gas_map(block, [(1.0, 1.0, 5.0), "abc"])
    with pytest.raises(ValueError, match=r"row 0, reading: 1e\+308 is beyond"):
        plumekit.gas_map(block, [(1.0, 1.0, 1e308)])
    with pytest.raises(ValueError, match=r"row 1, x: 1e\+300 m lies more than"):
        plumekit.gas_map(block, [(1.0, 1.0, 5.0), (1e300, 1.0, 5.0)])
    m = plumekit.gas_map(block, [(1.0, 1.0, 5.0), (-0.5, 1.0, 3.0)])
    assert m["samples_outside_arena"] == 1
    assert np.isfinite(m["variance"][~np.isnan(m["variance"])]).all()
