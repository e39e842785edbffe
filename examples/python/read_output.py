"""Reading a run's output back with NumPy: the series of measured quantities, every particle
file of the run, and the particles of one of them.

    python3 examples/python/read_output.py OUTPUT_DIR

OUTPUT_DIR is the folder of a finished run (e.g. out/dam_break_seed after `make demo`, or the
run this script makes in out/read_output when the folder does not exist yet).
"""
import glob
import os
import sys

import numpy as np

import ryushi

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out/read_output"
    if not os.path.isdir(out):
        with ryushi.Simulation.from_file(os.path.join(ROOT, "cases", "dam_break_seed.yaml"),
                                         output=out, set={"spacing": 0.0125, "time.end": 0.3}) as sim:
            sim.run()
    series = ryushi.read_series(os.path.join(out, "series.csv"))
    print("series.csv: %d rows, columns %s" % (len(series["t"]), ", ".join(series)))
    if "front_x" in series:
        k = int(np.argmax(series["front_x"]))
        print("  the front is furthest, %.4f m, at t = %.3f s" % (series["front_x"][k],
                                                                 series["t"][k]))
    pvd = glob.glob(os.path.join(out, "*.pvd"))
    outputs = ryushi.read_pvd(pvd[0])
    print("%s: %d particle files, t = %.3g .. %.3g s" % (os.path.basename(pvd[0]), len(outputs),
                                                          outputs[0][0], outputs[-1][0]))
    t, path = outputs[-1]
    p = ryushi.read_vtp(path)
    fluid = p["kind"] == ryushi.KINDS["fluid"]
    speed = np.linalg.norm(p["velocity"][fluid], axis=1)
    print("%s at t = %.3g s: %d particles, %d fluid" % (os.path.basename(path), p.time,
                                                        len(p["id"]), fluid.sum()))
    print("  fluid mass %.6g, mean speed %.4g m/s, highest particle at y = %.4f m, "
          "mean pressure %.4g Pa" % (p["mass"][fluid].sum(), speed.mean(),
                                     p["position"][fluid, 1].max(), p["pressure"][fluid].mean()))


if __name__ == "__main__":
    main()
