"""A mission's replay from Python: localize(animate=...) draws it, replay() redraws a CLI run's."""
import json
import os
import subprocess

import pytest

import plumekit


@pytest.fixture(scope="module")
def block(data):
    return plumekit.read_map(data / "test-maps" / "test-1-block.json")


def test_localize_animates_the_run_it_returns(block, tmp_path):
    plain = plumekit.localize(block, block.sources[0], seed=2, plume_model="physics",
                              stop={"max_samples": 8})
    out = tmp_path / "run.png"
    r = plumekit.localize(block, block.sources[0], seed=2, plume_model="physics",
                          stop={"max_samples": 8}, animate=str(out))
    # Recording changes nothing of the run.
    for key in ("estimate", "samples", "mission_s"):
        assert r[key] == plain[key], key
    drop = lambda steps: [{k: v for k, v in s.items() if k != "compute_s"} for s in steps]
    assert drop(r["steps"]) == drop(plain["steps"])
    a = r["animation"]
    assert a["format"] == "apng" and a["file"] == str(out) and out.exists()
    assert a["frames"] == int(r["mission_s"] + 1e-9) + 1
    with pytest.raises(plumekit.InputError, match="animate"):
        plumekit.localize(block, block.sources[0], plume_model="physics", animate="run.gif")


def test_replay_redraws_a_command_line_run(data, tmp_path):
    exe = os.environ.get("PLUMEKIT_EXE")
    if not exe:
        pytest.skip("PLUMEKIT_EXE is not set (ctest sets it)")
    run_dir, video = tmp_path / "run", tmp_path / "run.png"
    subprocess.run([exe, "localize", str(data / "test-maps" / "test-1-block.json"),
                    "--source", "7,1.5", "--plume-model", "physics", "--max-samples", "6",
                    "--out", str(run_dir), "--animate", str(video), "--json"],
                   check=True, capture_output=True)
    r = plumekit.replay(str(run_dir), str(tmp_path / "again.png"), fps=5, size=(640, 360))
    assert r["format"] == "apng" and r["frames"] > 1
    assert r["title"].startswith("test-1-block: ste (physics)")
    with pytest.raises(plumekit.InputError, match="holds no replay.json"):
        plumekit.replay(str(tmp_path), str(tmp_path / "x.png"))
