"""The heavy top from Python against the C program, per step, and the cost
of Python callbacks (doc/python.md, "Overheads"). Not a test: prints a
table and CSV (and writes the CSV with --csv FILE).

  build/python-venv/bin/python bench/python/bench_heavy_top.py \
      --ref build/test/python/heavy_top_ref [--repeat 7] [--csv out.csv]

Runs (each the minimum over --repeat runs of the whole 1 s heavy top,
generalized-alpha(0.9) with rtol = atol = 1e-6, 10 outputs, setup
included):
  C program        test/python/heavy_top_ref (the model's callbacks in C)
  Python, C model  lignum.Multibody: the same callbacks in C, driven from Python
  + applied force  the same with a Python applied force (zero) on top
  Python model     lignum.PythonModel: M, g, Phi, B as Python functions
                   (over [0, 0.1] only, once: it is slow)
"""
import argparse
import pathlib
import subprocess
import sys
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "test" / "python"))
import lignum  # noqa: E402
from conftest import SETTINGS, heavy_top  # noqa: E402
from test_same_as_c import python_heavy_top  # noqa: E402


def run_python(model, outputs=10):
    t0 = time.perf_counter()
    with lignum.Integrator(model, **SETTINGS["adaptive"]) as sim:
        for k in range(1, outputs + 1):
            sim.solve(0.1 * k)
        steps = sim.stats["steps"]
    return time.perf_counter() - t0, steps


def best(fn, repeat):
    runs = [fn() for _ in range(repeat)]
    return min(r[0] for r in runs), runs[0][1]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ref", required=True, help="build/test/python/heavy_top_ref")
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--csv")
    args = ap.parse_args()

    def c_run():
        out = subprocess.run([args.ref, "adaptive", "--repeat", "1"], check=True,
                             capture_output=True, text=True).stdout.split()
        return float(out[0]), int(out[1])

    rows = []
    t_c, n_c = best(c_run, args.repeat)
    rows.append(("C program", t_c, n_c, 0))
    t_py, n_py = best(lambda: run_python(heavy_top()), args.repeat)
    rows.append(("Python, C model", t_py, n_py, 0))
    calls = [0]

    def applied(t, q, v, f):
        calls[0] += 1

    def with_force():
        model = heavy_top()
        model.applied_force = applied
        calls[0] = 0
        return run_python(model)

    t_f, n_f = best(with_force, args.repeat)
    rows.append(("+ applied force in Python", t_f, n_f, calls[0]))
    pm = python_heavy_top()
    counted = {}
    for name in ("mass", "force", "constraints", "jacobian"):
        fn = pm.functions[name]

        def wrapped(*a, _fn=fn, _name=name):
            counted[_name] = counted.get(_name, 0) + 1
            return _fn(*a)
        pm.functions[name] = wrapped
    t_m, n_m = best(lambda: (counted.clear(), run_python(pm, 1))[1], 1)
    rows.append(("Python model (M, g, Phi, B)", t_m, n_m, sum(counted.values())))

    print(f"{'run':30s} {'steps':>6s} {'s/run':>10s} {'us/step':>9s} {'vs C':>7s} "
          f"{'Py calls':>9s} {'us/call':>8s}")
    csv = ["run,steps,seconds_per_run,us_per_step,ratio_to_c,python_calls,us_per_python_call"]
    for name, t, n, ncalls in rows:
        per_step = 1e6 * t / n
        ratio = per_step / (1e6 * t_c / n_c)
        # the cost of a Python call: the time above the same run with the
        # model in C, per call (the applied force: same steps, same work)
        # (the Python model: all of its time per call, the numpy work included)
        base = t_py * n / n_py
        per_call = (1e6 * (t - base) / ncalls) if ncalls else float("nan")
        print(f"{name:30s} {n:6d} {t:10.4f} {per_step:9.2f} {ratio:7.3f} {ncalls:9d} "
              f"{per_call:8.2f}")
        csv.append(f"{name},{n},{t:.6e},{per_step:.4f},{ratio:.4f},{ncalls},{per_call:.4f}")
    print("\n" + "\n".join(csv))
    if args.csv:
        pathlib.Path(args.csv).write_text("\n".join(csv) + "\n")


if __name__ == "__main__":
    main()
