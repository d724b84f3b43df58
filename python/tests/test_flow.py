"""Wind: numpy views without copies, conservation, options and errors, saving and reading back."""
import numpy as np
import pytest

import plumekit


@pytest.fixture(scope="module")
def cluttered(data):
    return plumekit.read_map(data / "maps" / "cluttered-1.json")


@pytest.fixture(scope="module")
def wind(cluttered):
    return plumekit.flow(cluttered, cell=0.1)


def test_arrays_are_views_of_the_solver(wind):
    u = wind.u
    assert u.shape == (wind.ny, wind.nx) == (40, 100)
    assert not u.flags.owndata and not u.flags.writeable
    assert np.shares_memory(u, wind.u)  # the same buffer each time: nothing copied
    with pytest.raises(ValueError):
        u[0, 0] = 1.0
    assert wind.face_u.shape == (40, 101) and wind.face_v.shape == (41, 100)


def test_mass_is_conserved(wind):
    # Inflow through the left faces equals outflow through the right ones (incompressible).
    dy = wind.cell[1]
    inflow = wind.face_u[:, 0].sum() * dy
    outflow = wind.face_u[:, -1].sum() * dy
    assert inflow == pytest.approx(4.0, rel=1e-6)  # 1 m/s over the 4 m inlet
    assert outflow == pytest.approx(inflow, rel=1e-6)
    assert (wind.u[wind.solid == 1] == 0).all()


def test_summary_and_interpolation(wind):
    assert wind.summary["iterations"] > 0
    assert wind.at((0.2, 2.0))[0] > 0.5
    assert wind.extent == (0.0, 10.0, 0.0, 4.0)


def test_options_errors(cluttered):
    with pytest.raises(plumekit.OptionError) as e:
        plumekit.flow(cluttered, cell=-1)
    assert e.value.field == "flow.cell"
    with pytest.raises(TypeError, match="no option named 'cel'"):
        plumekit.flow(cluttered, cel=0.1)
    with pytest.raises(plumekit.OptionError, match="flow.convection"):
        plumekit.flow(cluttered, convection="fast")


def test_options_object_and_kwargs_agree(cluttered, wind):
    o = plumekit.FlowOptions()
    assert o.cell == 0.0 and o.convection == "central"  # the library's defaults
    o.cell = 0.1
    again = plumekit.flow(cluttered, options=o)
    assert np.array_equal(again.u, wind.u)


def test_save_and_read_back(tmp_path, cluttered, wind, cli):
    wind.save(tmp_path / "wind")
    back = plumekit.read_wind(tmp_path / "wind", cluttered)
    assert np.array_equal(back.u, wind.u) and np.array_equal(back.v, wind.v)
    assert np.allclose(back.p, wind.p, rtol=1e-6, atol=1e-9)
    # The command line solves the same wind, bit for bit (its files hold float32).
    cli("flow", cluttered_path(cluttered), "--cell", "0.1", "--out", tmp_path / "cli")
    assert np.array_equal(np.load(tmp_path / "cli" / "u.npy"), wind.u.astype(np.float32))


def cluttered_path(m):
    return plumekit.data_dir() + "/maps/cluttered-1.json"


# Ctrl-C during a long call (issue 44): the solve stops at its next Newton iteration with
# KeyboardInterrupt, long before it would have ended. The child process times the whole solve
# first, then is interrupted a quarter of the way into the same solve.
_CHILD = r"""
import os, signal, sys, time
import plumekit
signal.signal(signal.SIGINT, signal.default_int_handler)  # even where the parent ignores it
m = plumekit.read_map(sys.argv[1])
t0 = time.monotonic()
plumekit.flow(m, cell=float(sys.argv[2]), sequencing=False)
print("full", time.monotonic() - t0, flush=True)
sys.stdin.readline()  # the parent is ready to interrupt
print("start", flush=True)
t0 = time.monotonic()
try:
    plumekit.flow(m, cell=float(sys.argv[2]), sequencing=False)
    print("finished", time.monotonic() - t0, flush=True)
except KeyboardInterrupt:
    print("interrupted", time.monotonic() - t0, flush=True)
"""


def test_ctrl_c_stops_a_long_flow_with_keyboard_interrupt(data):
    import os
    import signal
    import subprocess
    import sys
    import time
    child = subprocess.Popen(
        [sys.executable, "-c", _CHILD, str(data / "floors" / "depot.json"), "0.1"],
        stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        env=os.environ)
    try:
        full = float(child.stdout.readline().split()[1])
        child.stdin.write("go\n")
        child.stdin.flush()
        assert child.stdout.readline().strip() == "start"
        time.sleep(full / 4)
        child.send_signal(signal.SIGINT)
        word, seconds = child.stdout.readline().split()
        child.wait(timeout=60)
    finally:
        child.kill()
    assert word == "interrupted", child.stderr.read()
    assert float(seconds) < 0.75 * full  # it stopped; it did not run to the end
