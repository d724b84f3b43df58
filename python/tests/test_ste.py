"""Localization: the same runs as the command line, and a mission driven with given readings."""
import pytest

import plumekit


@pytest.fixture(scope="module")
def block(data):
    return plumekit.read_map(data / "test-maps" / "test-1-block.json")


@pytest.fixture(scope="module")
def run(block):
    return plumekit.localize(block, block.sources[0], seed=3, plume_model="physics",
                             stop={"max_samples": 15}, protocol="thesis")


def test_localize_is_the_cli_run(block, run, cli):
    s = block.sources[0]
    c = cli("localize", plumekit.data_dir() + "/test-maps/test-1-block.json",
            "--source", f"{s[0]!r},{s[1]!r}", "--seed", 3, "--plume-model", "physics",
            "--max-samples", 15, "--protocol", "thesis")
    for key in ("estimate", "samples", "error_m", "distance_m", "start", "stopped_by", "times"):
        assert run[key] == c[key], key
    assert run["samples"] == len(run["steps"]) <= 15
    # The field's time metrics: the declaration is the mission's end, and a robot within 0.5 m
    # was within 1 m no later.
    t = run["times"]
    assert t["declared_s"] == run["mission_s"]
    assert t["optimum_s"] > 0 and t["over_optimum"] == pytest.approx(run["mission_s"] / t["optimum_s"])
    if t["within_0_5m_s"] is not None:
        assert t["within_1m_s"] <= t["within_0_5m_s"] <= run["mission_s"]
    assert t["gsl_bench_success"] == (t["within_1m_s"] is not None and t["within_1m_s"] <= 300)


def test_a_mission_fed_the_runs_readings_reaches_its_estimate(block, run):
    sc = plumekit.Scenario(block, plume_model="physics", stop={"max_samples": 15},
                           protocol="thesis")
    mission = sc.mission(seed=3)
    with pytest.raises(plumekit.InputError, match="no sample yet"):
        mission.next(run["start"])
    with pytest.raises(plumekit.InputError, match="no sample yet"):
        mission.posterior
    with pytest.raises(plumekit.InputError, match="reading: not a finite number"):
        mission.add(run["start"], float("nan"))
    assert mission.samples == 0  # the bad reading was not taken
    for k, step in enumerate(run["steps"]):
        post = mission.add(step["recorded_position"], step["value"])
        assert list(post["estimate"]) == pytest.approx(step["estimate"], abs=1e-12)
        assert post["entropy"] == pytest.approx(step["entropy"], abs=1e-12)
        if not mission.stopped:
            goal = mission.next(step["position"])["goal"]
            # The run went where the mission says to go.
            assert list(goal) == pytest.approx(run["steps"][k + 1]["position"], abs=1e-9)
    assert mission.stopped and mission.stopped_by == run["stopped_by"]
    assert mission.samples == run["samples"]
    with pytest.raises(plumekit.InputError, match="stopped"):
        mission.next(run["steps"][-1]["position"])
    marginal = mission.posterior["marginal"]
    assert marginal.sum() == pytest.approx(1.0)


def test_a_mission_fed_the_readings_on_the_way_follows_the_run(block):
    moving = {"plume_model": "physics", "stop": {"max_samples": 8}}  # the default protocol
    run = plumekit.localize(block, block.sources[0], seed=3, **moving)
    mission = plumekit.Scenario(block, **moving).mission(seed=3)
    taken = 0
    for step in run["steps"]:
        way = [((r[2], r[3]), r[4], r[5]) for r in step.get("on_the_way", [])]
        taken += len(way)
        post = mission.add(step["recorded_position"], step["value"], on_the_way=way)
        assert list(post["estimate"]) == pytest.approx(step["estimate"], abs=1e-12)
        assert post["entropy"] == pytest.approx(step["entropy"], abs=1e-12)
    assert taken > 10
    assert mission.samples == run["samples"]  # readings on the way are no samples
    with pytest.raises(plumekit.InputError, match="on_the_way: each reading"):
        mission.add(run["start"], 0.0, on_the_way=[((1.0, 1.0), 0.5)])


def test_the_protocol_is_a_preset_whose_halves_can_be_set(block):
    o = plumekit.SteOptions()
    assert o.protocol == "moving" and o.world.read_while_moving and o.world.adaptive_stop
    assert o.stop.confidence_radius == 0.3 and o.approach
    # Applied first, whatever the keywords' order: the half given wins.
    sc = plumekit.Scenario(block, plume_model="physics", world={"adaptive_stop": True},
                           protocol="thesis")
    assert sc.options.protocol == "thesis"
    assert not sc.options.world.read_while_moving and sc.options.world.adaptive_stop
    assert sc.options.stop.confidence_radius == 0.0 and not sc.options.approach
    thesis = plumekit.localize(block, block.sources[0], seed=3, plume_model="physics",
                               stop={"max_samples": 3}, protocol="thesis")
    assert all("on_the_way" not in step for step in thesis["steps"])
    with pytest.raises(plumekit.OptionError) as e:
        plumekit.Scenario(block, plume_model="physics", protocol="drive-by")
    assert e.value.field == "ste.protocol"


def test_options_reach_the_library(block):
    o = plumekit.SteOptions()
    assert o.plume_model == "surrogate" and o.stop.max_samples == 0
    assert o.likelihood.sigma_m is None
    with pytest.raises(TypeError, match="stop: no option named 'samples'"):
        plumekit.Scenario(block, plume_model="physics", stop={"samples": 3})
    with pytest.raises(plumekit.OptionError) as e:
        plumekit.localize(block, block.sources[0], plume_model="physics",
                          stop={"entropy_fraction": -1.0})
    assert e.value.field == "ste.stop.entropy_fraction"


def test_options_are_the_tables_and_old_keywords_still_work():
    # Bound from the options tables: the keyword is the option's name, the doc says the default.
    assert plumekit.WorldOptions().wind_direction_noise == 0.0
    assert "150 for physics" in plumekit.SteLikelihood.sigma_m.__doc__
    o = plumekit.SteOptions()
    assert o.source_cell is None and o.margin == 0.15
    f = plumekit.FilamentOptions()
    assert f.filaments_per_second == 200.0
    # The old field names still set the same option, with a DeprecationWarning.
    with pytest.warns(DeprecationWarning, match="use filaments_per_second"):
        f.release_per_second = 150.0
    assert f.filaments_per_second == 150.0
    w = plumekit.WorldOptions()
    with pytest.warns(DeprecationWarning, match="use wind_direction_noise"):
        w.wind_direction_noise_deg = 10.0
    assert w.wind_direction_noise == 10.0 and w.wind_direction_noise_deg == 10.0


def test_source_in_obstacle(block):
    import numpy as np
    inside = tuple(np.mean(block.obstacles[0], axis=0))
    with pytest.raises(plumekit.InputError, match="ste.source"):
        plumekit.localize(block, inside, plume_model="physics")


def test_a_mission_refuses_points_the_cli_refuses(block):
    import numpy as np
    sc = plumekit.Scenario(block, plume_model="physics")
    mission = sc.mission(seed=1)
    inside = tuple(float(v) for v in np.mean(block.obstacles[0], axis=0))
    # The CLI's words for such a --source: "(x, y) is inside obstacles[0] of map NAME".
    with pytest.raises(plumekit.OptionError,
                       match=r"^p: \(.*\) is inside obstacles\[0\] of map " + block.name):
        mission.add(inside, 0.0)
    with pytest.raises(ValueError, match=r"^p: \(12, 1\) is outside the arena \(0\.\.\.10 x 0\.\.\.4\)"):
        mission.add((12.0, 1.0), 0.0)
    with pytest.raises(ValueError, match=r"^shared point: \(5, -1\) is outside the arena"):
        mission.add((8.0, 2.0), 0.0, shared=[((5.0, -1.0), 0.0)])
    assert mission.samples == 0  # nothing was taken


def test_evaluate_matches_cli(tmp_path, data, cli):
    folder = tmp_path / "maps"
    folder.mkdir()
    (folder / "block.json").write_bytes((data / "test-maps" / "test-1-block.json").read_bytes())
    seen = []
    r = plumekit.evaluate(folder, runs=2, threads=2, source_count=1, plume_model="physics",
                          stop={"max_samples": 10}, progress=lambda d, t: seen.append((d, t)))
    c = cli("evaluate", "--map-dir", folder, "--runs", 2, "--threads", 2, "--plume-model",
            "physics", "--max-samples", 10, "--sources", 1, "--out", tmp_path / "eval")
    for key in ("success_0_5m", "median_error_m", "median_samples", "median_distance_m"):
        assert r["overall"][key] == c["overall"][key], key
    assert seen[-1] == (2, 2) and r["overall"]["runs"] == 2
    assert r["timings"]["median_step_compute_s"] > 0


def test_several_methods_in_one_world_are_each_alone(tmp_path, data):
    folder = tmp_path / "maps"
    folder.mkdir()
    (folder / "block.json").write_bytes((data / "test-maps" / "test-1-block.json").read_bytes())
    common = dict(runs=1, threads=2, source_count=1, plume_model="gaussian",
                  stop={"max_samples": 6})
    both = plumekit.evaluate(folder, method=["ste", "zigzag"], **common)
    assert list(both) == ["ste", "zigzag"]
    for name in ("ste", "zigzag"):
        alone = plumekit.evaluate(folder, method=name, **common)
        assert both[name]["overall"] == alone["overall"], name
    with pytest.raises(ValueError, match="named twice"):
        plumekit.evaluate(folder, method=["zigzag", "zigzag"], **common)


def test_a_given_start_is_the_cli_start(block, cli):
    s, start = block.sources[0], (1.0, 3.5)
    r = plumekit.localize(block, s, start=start, seed=4, plume_model="physics",
                          stop={"max_samples": 5})
    c = cli("localize", plumekit.data_dir() + "/test-maps/test-1-block.json",
            "--source", f"{s[0]!r},{s[1]!r}", "--start", "1.0,3.5", "--seed", 4,
            "--plume-model", "physics", "--max-samples", 5)
    assert r["start"] == c["start"] and r["estimate"] == c["estimate"]
    assert r["steps"][0]["position"] == pytest.approx(list(start))


def test_any_method_runs_as_the_cli_runs_it(cli):
    # Issue 20: the seeds' methods through the same call and options as STE.
    path = plumekit.data_dir() + "/test-maps/test-3-two-blocks.json"
    m = plumekit.read_map(path)
    run = plumekit.localize(m, (7.5, 2.0), start=(9.5, 0.5), seed=2, method="surge-cast")
    c = cli("localize", path, "--source", "7.5,2", "--start", "9.5,0.5", "--seed", 2,
            "--method", "surge-cast")
    assert run["method"] == "surge-cast"
    for key in ("estimate", "samples", "distance_m", "stopped_by", "reached_source_box"):
        assert run[key] == c[key], key
    sc = plumekit.Scenario(m, method="pf-sweep")
    with pytest.raises(plumekit.InputError, match="method ste"):
        sc.mission(seed=1)
    with pytest.raises(plumekit.OptionError, match="unknown method"):
        plumekit.localize(m, (7.5, 2.0), method="infotaxis")


def test_a_team_runs_as_the_cli_runs_it(block, cli):
    s = block.sources[0]
    run = plumekit.localize(block, s, start=(9.0, 2.0), seed=5, plume_model="physics",
                            stop={"max_samples": 12},
                            team={"robots": 2, "strategy": "collaborative"})
    c = cli("localize", plumekit.data_dir() + "/test-maps/test-1-block.json",
            "--source", f"{s[0]!r},{s[1]!r}", "--start", "9,2", "--seed", 5, "--plume-model",
            "physics", "--max-samples", 12, "--robots", 2, "--team", "collaborative")
    def untimed(team):  # the measured decision times differ from run to run
        for m in team["members"]:
            for step in m["steps"]:
                del step["compute_s"]
        return team

    assert untimed(run["team"]) == untimed(c["team"])
    assert run["team"]["robots"] == 2 and run["team"]["strategy"] == "collaborative"
    assert run["samples"] == sum(m["samples"] for m in run["team"]["members"])
    with pytest.raises(plumekit.OptionError, match="ste.team.strategy"):
        plumekit.localize(block, s, plume_model="physics", team={"strategy": "swarm"})


def test_a_mission_takes_teammates_samples_and_goals(block):
    sc = plumekit.Scenario(block, plume_model="physics", stop={"max_samples": 2})
    alone, shared = sc.mission(seed=1), sc.mission(seed=1)
    alone.add((8.0, 2.0), 0.0)
    post = shared.add((8.0, 2.0), 0.0, shared=[((6.0, 2.0), 0.0), ((6.0, 3.0), 0.0)])
    assert shared.samples == 3 and not shared.stopped  # a budget of 2 of its own
    assert post["entropy"] < alone.posterior["entropy"]
    goal = alone.next((8.0, 2.0))["goal"]
    assert alone.next((8.0, 2.0), teammate_goals=[goal])["goal"] != goal


def test_methods_come_from_the_registry():
    names = [m["name"] for m in plumekit.methods()]
    assert names[0] == "ste" and len(names) == len(set(names))
    assert {"surge-cast", "pf-gradient", "levy-taxis"} <= set(names)
    assert all(m["description"] and m["source"] for m in plumekit.methods())
    assert [m["name"] for m in plumekit.methods() if m["uses_plume_model"]] == ["ste"]


def test_the_default_surrogate_is_the_hybrid_on_any_map_and_the_thesis_model_is_named(data, cli):
    # The thesis's 64 x 64 model, named, refuses a 19.2 m floor saying what to pass instead.
    small = plumekit.read_map(data / "floors" / "tb3_world.json")
    with pytest.raises(plumekit.InputError, match='model_path="hybrid".*plume_model="physics"'):
        plumekit.Scenario(small, model_path="thesis")
    block = plumekit.read_map(data / "test-maps" / "test-1-block.json")
    s = block.sources[0]
    run = plumekit.localize(block, s, seed=2, stop={"max_samples": 4})
    c = cli("localize", plumekit.data_dir() + "/test-maps/test-1-block.json", "--source",
            f"{s[0]!r},{s[1]!r}", "--seed", 2, "--max-samples", 4)
    assert c["cnn"] == "plume-unet-v3.pkcnn"
    assert run["estimate"] == c["estimate"]
    thesis = plumekit.localize(block, s, seed=2, stop={"max_samples": 4}, model_path="thesis")
    assert thesis["estimate"] != run["estimate"]
