"""Reading a run's output back: series.csv, the particle files and the .pvd collection."""
import os

import numpy as np
import pytest

import ryushi


def test_output_reads_back_as_the_state(case, tmp_path):
    """The last particle file of a run holds the state the simulation has, exactly; series.csv
    has a row per output with the measured columns; the .pvd lists every file."""
    with ryushi.Simulation.from_file(case("dam_break_seed.yaml"), output=str(tmp_path),
                                     set={"spacing": 0.0125, "time.end": 0.04}) as sim:
        sim.run(progress=False)
        outputs = ryushi.read_pvd(os.path.join(str(tmp_path), "dam_break_seed.pvd"))
        assert [t for t, _ in outputs] == pytest.approx([0.0, 0.02, 0.04])
        p = ryushi.read_vtp(outputs[-1][1])
        assert p.time == sim.t
        assert p["position"].shape == (sim.n, 3)
        assert np.array_equal(p["position"][:, :2], sim.field("position"))
        assert not p["position"][:, 2].any()
        assert np.array_equal(p["velocity"][:, :2], sim.field("velocity"))
        for name in ("pressure", "density", "mass", "id", "kind", "material"):
            assert np.array_equal(p[name], sim.field(name)), name
        s = ryushi.read_series(os.path.join(str(tmp_path), "series.csv"))
        assert s["t"] == pytest.approx([0.0, 0.02, 0.04])
        assert s["front_x"][-1] == pytest.approx(sim.probe("front_x"), rel=1e-11)  # 12 digits
        assert s["mass"] == pytest.approx(125.0, rel=1e-12)


def test_series_errors(tmp_path):
    """A series with a short row says which line."""
    bad = tmp_path / "series.csv"
    bad.write_text("t,mass\n0,1\n0.1\n")
    with pytest.raises(ValueError, match="series.csv:3"):
        ryushi.read_series(str(bad))
