"""A parameter study from Python: Martin & Moyce's dam break (a column of width a and height 2a)
at three resolutions, its surge front against the experiment, and a Matplotlib figure.

    python3 examples/python/parameter_study.py [--output DIR] [--quick]

Runs a/20, a/40 and a/80 (--quick: a/10 and a/20) to T = t sqrt(2g/a) = 3 on two threads,
samples the front through the probe front_x every millisecond, prints its deviation from the
experiment (Z = front/a, the points of Martin & Moyce's Table 2 up to T = 3) and draws
DIR/front.png (needs python3-matplotlib; without it the table alone).
"""
import argparse
import os
import time

import numpy as np

import ryushi

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
A, G = 0.05715, 9.81  # the column's width [m], gravity [m/s^2]


def front(divisions, out):
    """The front's history (T, Z) of the column at a/divisions."""
    T_end = 3.0
    t_end = T_end / np.sqrt(2 * G / A)
    with ryushi.Simulation.from_file(os.path.join(ROOT, "cases", "dam_break_mm.yaml"),
                                     output=os.path.join(out, "a%d" % divisions), threads=2,
                                     set={"spacing": A / divisions, "time.end": t_end,
                                          "output.vtk": False}) as sim:
        t, x = [sim.t], [sim.probe("front_x")]
        wall = time.perf_counter()
        while sim.t < t_end - 1e-12:
            sim.run_until(min(sim.t + 0.001, t_end))
            t.append(sim.t)
            x.append(sim.probe("front_x"))
        wall = time.perf_counter() - wall
        print("a/%-3d %6d particles, %5d steps in %.1f s, %.3g particle-steps/s" % (
            divisions, sim.n, sim.steps, wall, sim.n * sim.steps / wall))
    return np.asarray(t) * np.sqrt(2 * G / A), np.asarray(x) / A


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--output", default="out/parameter_study")
    ap.add_argument("--quick", action="store_true", help="a/10 and a/20 only")
    args = ap.parse_args()
    ref = np.loadtxt(os.path.join(ROOT, "data", "reference",
                                  "martin_moyce1952_n2_2_surge_front_table2.csv"),
                     delimiter=",", skiprows=1)
    ref = ref[ref[:, 0] <= 3.0]
    runs = {}
    for divisions in ((10, 20) if args.quick else (20, 40, 80)):
        T, Z = front(divisions, args.output)
        dev = np.interp(ref[:, 0], T, Z) - ref[:, 1]
        print("      front against Martin & Moyce: max |dZ| %.3f, rms %.3f (%d points)" % (
            np.abs(dev).max(), np.sqrt(np.mean(dev ** 2)), len(dev)))
        runs[divisions] = (T, Z)
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("no figure: matplotlib is not installed (apt install python3-matplotlib)")
        return
    fig, ax = plt.subplots(figsize=(6, 4))
    for divisions, (T, Z) in runs.items():
        ax.plot(T, Z, label="ryushi, a/%d" % divisions)
    ax.plot(ref[:, 0], ref[:, 1], "ko", label="Martin & Moyce (1952)")
    ax.set_xlabel("T = t (2g/a)$^{1/2}$")
    ax.set_ylabel("Z = front / a")
    ax.legend()
    fig.tight_layout()
    path = os.path.join(args.output, "front.png")
    fig.savefig(path, dpi=120)
    print("figure: " + path)


if __name__ == "__main__":
    main()
