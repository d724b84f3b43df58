"""The 3-D wind tunnel from Python (`plumekit localize tunnel`, `evaluate tunnel`)."""
import pytest

import plumekit


def test_ste_3d_finds_the_source_and_repeats_itself():
    run = plumekit.localize_tunnel(source=(1.0, 1.5, 0.6), start=(8.0, 2.5, 1.5), seed=3)
    assert run["method"] == "ste-3d" and run["stopped_by"] == "entropy"
    assert run["error_m"] < 0.5 and len(run["steps"]) == run["samples"]
    again = plumekit.localize_tunnel(source=(1.0, 1.5, 0.6), start=(8.0, 2.5, 1.5), seed=3)
    assert again["estimate"] == run["estimate"]


def test_matches_the_command(cli):
    run = plumekit.localize_tunnel(method="surge-spiral", source=(1.0, 2.0, 1.0), time_limit=60)
    cmd = cli("localize", "tunnel", "--method", "surge-spiral", "--source", "1,2,1",
              "--time-limit", 60)
    assert run["start"] == cmd["start"] and run["estimate"] == cmd["estimate"]
    assert run["stopped_by"] in ("found", "time_limit")


def test_evaluate_and_bad_input():
    summary = plumekit.evaluate_tunnel(method="surge-cast-2d", runs=2, time_limit=30)
    assert summary["runs"] == 2
    with pytest.raises(ValueError, match="tunnel.source"):
        plumekit.localize_tunnel(source=(1.0, 2.0, 2.5))
    with pytest.raises(ValueError, match="tunnel.method"):
        plumekit.localize_tunnel(method="ste")


def test_animate_draws_the_run_from_above_and_the_side(tmp_path):
    out = tmp_path / "run.png"
    run = plumekit.localize_tunnel(method="surge-spiral", source=(1.0, 2.0, 1.0), time_limit=30,
                                   animate=str(out))
    assert run["animation"]["format"] == "apng" and out.exists()
    assert run["animation"]["frames"] == int(run["mission_s"] + 1e-9) + 1
    bare = plumekit.localize_tunnel(method="surge-spiral", source=(1.0, 2.0, 1.0), time_limit=30)
    assert bare["estimate"] == run["estimate"]  # recording changes nothing of the run
