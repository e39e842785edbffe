"""ryushi.Simulation: set-up, stepping, fields, probes and errors through libryushi.so."""
import os
import signal
import subprocess
import threading

import numpy as np
import pytest
import yaml

import ryushi

SEED = {"spacing": 0.0125, "time.end": 0.05, "output.vtk": False}


def tolerance(root, name, key):
    """A tolerance of validation/NAME.yaml, where ryushi validate and the C tests read it."""
    with open(os.path.join(root, "validation", name + ".yaml")) as f:
        return float(yaml.safe_load(f)["tolerances"][key])


def test_dam_break_mass_and_front(root, case, tmp_path):
    """Martin & Moyce's column at a/20 stepped from Python: the fluid's mass is what the case
    put in at every stop, and the surge front, sampled through the probe every millisecond,
    follows the experiment within the tolerances the C test and `ryushi validate dam_break`
    use (Z = front/a against T = t sqrt(2g/a), T <= 3, time origin not fitted)."""
    a, g = 0.05715, 9.81
    with ryushi.Simulation.from_file(case("dam_break_mm.yaml"), output=str(tmp_path), threads=1,
                                     set={"spacing": a / 20, "time.end": 0.18,
                                          "output.vtk": False}) as sim:
        fluid = sim.field("kind") == ryushi.KINDS["fluid"]
        m0 = sim.field("mass")[fluid].sum()
        assert m0 == pytest.approx(1000.0 * a * 2 * a, rel=1e-12)
        ts, front = [0.0], [sim.probe("front_x")]
        while sim.t < 0.18 - 1e-12:
            sim.run_until(round(sim.t + 0.001, 9))
            ts.append(sim.t)
            front.append(sim.probe("front_x"))
            fluid = sim.field("kind") == ryushi.KINDS["fluid"]
            mass = sim.field("mass")[fluid].sum()
            assert abs(mass - m0) <= tolerance(root, "dam_break", "mass_drift") * m0
        assert sim.probe("outside") <= tolerance(root, "dam_break", "escaped")
    ref = np.loadtxt(os.path.join(root, "data", "reference",
                                  "martin_moyce1952_n2_2_surge_front_table2.csv"),
                     delimiter=",", skiprows=1)
    T = np.asarray(ts) * np.sqrt(2 * g / a)
    Z = np.asarray(front) / a
    keep = ref[:, 0] <= 3.0
    dev = np.interp(ref[keep, 0], T, Z) - ref[keep, 1]
    assert keep.sum() >= tolerance(root, "dam_break", "front_points_min")
    assert np.abs(dev).max() <= tolerance(root, "dam_break", "front_max_dev")
    assert np.sqrt(np.mean(dev ** 2)) <= tolerance(root, "dam_break", "front_rms_dev")


def test_fields_have_their_shapes(case, tmp_path):
    """Every name fields() lists reads back with its documented shape, type and unit;
    single fields are read-only views of the particles, vectors (n, dimension) copies."""
    with ryushi.Simulation.from_file(case("dam_break_seed.yaml"), output=str(tmp_path),
                                     set=SEED) as sim:
        assert (sim.scheme, sim.dimension, sim.n) == ("wcsph", 2, 1340)
        sim.step()
        infos = {f.name: f for f in sim.fields()}
        for name in ("position", "velocity", "x", "vy", "pressure", "density", "mass", "id",
                     "kind", "material"):
            assert name in infos
        for f in infos.values():
            a = sim.field(f.name)
            assert a.dtype == f.dtype
            assert a.shape == ((sim.n,) if f.components == 1 else (sim.n, sim.dimension))
        assert infos["position"].unit == "m" and infos["pressure"].unit == "Pa"
        x = sim.field("x")
        assert not x.flags.writeable
        with pytest.raises(ValueError):
            x[0] = 1.0
        assert np.array_equal(sim.field("position")[:, 0], x)
        assert np.array_equal(np.sort(sim.field("id")), np.arange(sim.n))
        assert sim.field("kind").max() == ryushi.KINDS["wall"]
    with ryushi.Simulation.from_file(case("mps_drop_rest_3d.yaml"), output=str(tmp_path / "3d"),
                                     set={"output.vtk": False}) as sim:
        assert sim.dimension == 3
        assert sim.field("position").shape == (sim.n, 3)
        assert sim.field("velocity").shape == (sim.n, 3)


def test_probes_and_statistics(case, tmp_path):
    """The probes ryushi.probes() lists, the run's statistics and its state."""
    names = ryushi.probes()
    assert "front_x" in names and "mass" in names and all(names.values())
    with ryushi.Simulation.from_file(case("dam_break_seed.yaml"), output=str(tmp_path),
                                     set=SEED) as sim:
        dt = sim.step()
        assert dt > 0 and sim.t == dt and sim.steps == 1
        sim.run_until(0.01)
        assert sim.t == pytest.approx(0.01, abs=1e-12)
        assert sim.stat("steps") == sim.steps - 1
        assert sim.probe("mass") == pytest.approx(125.0, rel=1e-12)
        sim.run(progress=False)
        assert sim.t == pytest.approx(sim.end_time, abs=1e-12)
        assert sim.step() == 0.0
        assert sim.stat("bytes_per_particle") > 0
        assert "closed" not in repr(sim)
    assert "closed" in repr(sim)


def test_bad_input_raises_error_naming_the_key(case, tmp_path):
    """A bad override, a bad value in a case text, a missing file, an unknown field or probe
    and a closed simulation raise ryushi.Error with the message naming what is wrong."""
    with pytest.raises(ryushi.Error) as e:
        ryushi.Simulation.from_file(case("dam_break_seed.yaml"), output=str(tmp_path),
                                    set={"time.nonsense": 1})
    assert e.value.code == 2 and "time.nonsense" in str(e.value)
    text = open(case("dam_break_seed.yaml")).read().replace("spacing: 0.00625", "spacing: -1")
    line = text[:text.index("spacing: -1")].count("\n") + 1
    with pytest.raises(ryushi.Error) as e:
        ryushi.Simulation.from_yaml(text, name="mine.yaml", output=str(tmp_path))
    assert e.value.code == 2 and "mine.yaml:%d" % line in str(e.value)
    assert "spacing" in str(e.value)
    with pytest.raises(ryushi.Error) as e:
        ryushi.Simulation.from_file(str(tmp_path / "absent.yaml"))
    assert "absent.yaml" in str(e.value)
    with ryushi.Simulation.from_file(case("dam_break_seed.yaml"), output=str(tmp_path),
                                     set=SEED) as sim:
        with pytest.raises(ryushi.Error, match="no field of doubles 'temperature'"):
            sim.field("temperature")
        with pytest.raises(ryushi.Error, match="no probe 'nothing'"):
            sim.probe("nothing")
        with pytest.raises(ryushi.Error, match="threads"):
            sim.set_threads(-1)
    with pytest.raises(ryushi.Error, match="closed"):
        sim.step()


def test_stepped_from_python_equals_the_program(binary, case, tmp_path):
    """The seed's dam break stepped one step at a time from Python writes the same files, byte
    for byte, as `ryushi run` with the same overrides (2 threads against 1)."""
    sets = {"spacing": 0.0125, "time.end": 0.06, "time.output_interval": 0.02}
    cmd = [binary, "run", case("dam_break_seed.yaml"), "-o", str(tmp_path / "program")]
    for k, v in sets.items():
        cmd += ["--set", "%s=%s" % (k, v)]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, env=dict(os.environ, OMP_NUM_THREADS="1"))
    with ryushi.Simulation.from_file(case("dam_break_seed.yaml"), output=str(tmp_path / "py"),
                                     threads=2, set=sets) as sim:
        steps = 0
        while sim.step() > 0:
            steps += 1
        assert steps == sim.steps
    files = sorted(f for f in os.listdir(tmp_path / "program")
                   if f.endswith((".vtp", ".pvd", ".csv")))
    assert len(files) >= 6 and "series.csv" in files
    assert files == sorted(f for f in os.listdir(tmp_path / "py")
                           if f.endswith((".vtp", ".pvd", ".csv")))
    for f in files:
        a = (tmp_path / "program" / f).read_bytes()
        b = (tmp_path / "py" / f).read_bytes()
        assert a == b, f


def test_ctrl_c_stops_after_a_step(case, tmp_path):
    """SIGINT during run() stops the run after the current step with a checkpoint and raises
    KeyboardInterrupt; the simulation goes on from there afterwards."""
    with ryushi.Simulation.from_file(case("dam_break_seed.yaml"), output=str(tmp_path),
                                     set={"spacing": 0.0125, "time.end": 5.0,
                                          "output.vtk": False}) as sim:
        timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
        timer.start()
        with pytest.raises(KeyboardInterrupt):
            sim.run(progress=False)
        timer.join()
        t = sim.t
        assert 0 < t < 5.0
        assert os.listdir(tmp_path / "checkpoints")
        sim.run_until(t + 0.01)
        assert sim.t == pytest.approx(t + 0.01, abs=1e-12)


def test_unstable_run_raises_with_its_last_good_state(case, tmp_path):
    """The seed's dam break under 200 g goes unstable: run() raises ryushi.Error with code 4
    and the diagnosis, after writing the last good state into the output folder."""
    with ryushi.Simulation.from_file(case("dam_break_seed.yaml"), output=str(tmp_path),
                                     set={"spacing": 0.0125, "time.end": 0.2,
                                          "gravity": [0, -2000]}) as sim:
        with pytest.raises(ryushi.Error) as e:
            sim.run(progress=False)
        assert e.value.code == 4 and "unstable" in e.value.kind
    assert any("last_good" in f for f in os.listdir(tmp_path)), os.listdir(tmp_path)
