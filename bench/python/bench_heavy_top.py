"""The heavy top from Python against the C program, per step, and the cost
of Python callbacks (doc/python.md, "Overheads"). Not a test: prints a
table and CSV (and writes the CSV with --csv FILE).

  build/python-venv/bin/python bench/python/bench_heavy_top.py \\
      --ref build/test/python/heavy_top_ref [--repeat 15] [--csv out.csv]

Each run is the whole 1 s heavy top (generalized-alpha(0.9), rtol = atol =
1e-6, 7277 steps, 10 outputs), setup included:
  C program        test/python/heavy_top_ref (the model's callbacks in C):
                   a fresh process per run, and --repeat runs in one process
  Python, C model  lignum.Multibody: the same callbacks in C, driven from Python
  + applied force  the same with a Python applied force (zero) on top
  Python model     lignum.PythonModel: M, g, Phi, B as Python functions
                   (over [0, 0.1] only, once: it is slow)
Times are CPU times of the process (the machine is shared: wall times of
a loaded machine measure the other jobs), the minimum over --repeat runs,
C and Python runs interleaved so that both see the same load; and the
median of the run-by-run ratios. With --callgrind, also the instructions
inside LGNSolve of both (independent of the load).
"""
import argparse
import pathlib
import subprocess
import sys
import time

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "test" / "python"))
import lignum  # noqa: E402
from conftest import SETTINGS, heavy_top  # noqa: E402
from test_same_as_c import python_heavy_top  # noqa: E402


def run_python(model, outputs=10):
    """CPU seconds and steps of one run of ``model``."""
    t0 = time.process_time()
    with lignum.Integrator(model, **SETTINGS["adaptive"]) as sim:
        for k in range(1, outputs + 1):
            sim.solve(0.1 * k)
        steps = sim.stats["steps"]
    return time.process_time() - t0, steps


def callgrind(ref):
    """Instructions executed inside LGNSolve (callbacks included), one run of
    the C program and one of the Python package with the model in C."""
    import os
    import re
    import tempfile
    script = ("import sys; sys.path.insert(0, %r)\n"
              "import lignum\nfrom conftest import SETTINGS, heavy_top\n"
              "with lignum.Integrator(heavy_top(), **SETTINGS['adaptive']) as s:\n"
              "    [s.solve(0.1 * k) for k in range(1, 11)]\n"
              % str(HERE.parents[1] / "test" / "python"))
    counts = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, cmd in (("C program", [ref, "adaptive"]),
                          ("Python, C model", [sys.executable, "-c", script])):
            err = subprocess.run(["valgrind", "--tool=callgrind", "--toggle-collect=LGNSolve",
                                  "--callgrind-out-file=" + os.path.join(tmp, "cg.out")] + cmd,
                                 check=True, capture_output=True, text=True).stderr
            counts[name] = int(re.search(r"Collected : (\d+)", err).group(1))
    c, py = counts["C program"], counts["Python, C model"]
    print(f"instructions inside LGNSolve: C program {c}, Python {py} ({py / c:.4f}); "
          f"per step {c / 7277:.0f} and {py / 7277:.0f}\n")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ref", required=True, help="build/test/python/heavy_top_ref")
    ap.add_argument("--repeat", type=int, default=15)
    ap.add_argument("--csv")
    ap.add_argument("--callgrind", action="store_true",
                    help="also count the instructions inside LGNSolve under valgrind's "
                         "callgrind, C program against Python (load-independent; ~2 min)")
    args = ap.parse_args()
    if args.callgrind:
        callgrind(args.ref)

    def c_run(repeat=1):
        out = subprocess.run([args.ref, "adaptive", "--repeat", str(repeat)], check=True,
                             capture_output=True, text=True).stdout.split()
        return float(out[2]), int(out[1])

    calls = [0]

    def applied(t, q, v, f):
        calls[0] += 1

    def with_force():
        model = heavy_top()
        model.applied_force = applied
        calls[0] = 0
        return run_python(model)

    # the C program: a fresh process per run, and --repeat runs in one
    # process (as the Python runs: a process that ran before is slower by a
    # few per cent, the heap no longer fresh)
    runs = {"C program, fresh process": c_run,
            "C program, runs in one process": lambda: c_run(args.repeat),
            "Python, C model": lambda: run_python(heavy_top()),
            "+ applied force in Python": with_force}
    best = {name: (float("inf"), 0) for name in runs}
    pairs = []  # (C fresh process, Python C model) run right after each other
    for r in range(args.repeat):  # interleaved
        this = {}
        for name, fn in runs.items():
            if r > 2 and name == "C program, runs in one process":
                continue  # three times --repeat runs suffice
            t, n = fn()
            this[name] = t
            best[name] = (min(best[name][0], t), n)
        pairs.append(this["Python, C model"] / this["C program, fresh process"])
    pairs.sort()
    median = pairs[len(pairs) // 2]
    quartiles = (pairs[len(pairs) // 4], pairs[(3 * len(pairs)) // 4])
    ncalls = {name: 0 for name in runs}
    ncalls["+ applied force in Python"] = calls[0]

    pm = python_heavy_top()
    counted = [0]
    for name in ("mass", "force", "constraints", "jacobian"):
        def wrapped(*a, _fn=pm.functions[name]):
            counted[0] += 1
            return _fn(*a)
        pm.functions[name] = wrapped
    best["Python model (M, g, Phi, B)"] = run_python(pm, 1)
    ncalls["Python model (M, g, Phi, B)"] = counted[0]

    t_c, n_c = best["C program, runs in one process"]
    t_py, n_py = best["Python, C model"]
    print(f"{'run':32s} {'steps':>6s} {'cpu s/run':>10s} {'us/step':>9s} {'vs C':>7s} "
          f"{'Py calls':>9s} {'us/call':>8s}")
    csv = ["run,steps,cpu_seconds_per_run,us_per_step,ratio_to_c,python_calls,"
           "us_per_python_call"]
    for name, (t, n) in best.items():
        per_step = 1e6 * t / n
        ratio = per_step / (1e6 * t_c / n_c)
        # the cost of a Python call: the time above the same steps with the
        # model in C, per call (the Python model: its numpy work included)
        base = t_py * n / n_py
        per_call = (1e6 * (t - base) / ncalls[name]) if ncalls[name] else float("nan")
        print(f"{name:32s} {n:6d} {t:10.4f} {per_step:9.2f} {ratio:7.3f} {ncalls[name]:9d} "
              f"{per_call:8.2f}")
        csv.append(f"{name},{n},{t:.6e},{per_step:.4f},{ratio:.4f},{ncalls[name]},"
                   f"{per_call:.4f}")
    print(f"\nPython, C model / C program (fresh process), run by run: median {median:.3f}, "
          f"quartiles {quartiles[0]:.3f} .. {quartiles[1]:.3f} ({len(pairs)} pairs)")
    print("\n" + "\n".join(csv))
    if args.csv:
        pathlib.Path(args.csv).write_text("\n".join(csv) + "\n")


if __name__ == "__main__":
    main()
