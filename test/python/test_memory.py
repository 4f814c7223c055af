"""Reference counting and memory: create/solve/free cycles with flat RSS;
an integrator dropped without close() is collected and freed."""
import gc
import sys
import weakref

import lignum
from conftest import heavy_top


def rss_kib():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * 4  # resident pages of 4 KiB


def cycle(model):
    with lignum.Integrator(model, step=1e-3) as sim:
        sim.solve(0.002)
        sim.multipliers()


def test_10000_cycles_flat_memory():
    model = heavy_top()
    refs = sys.getrefcount(model)
    for _ in range(1000):  # warm up the allocators
        cycle(model)
    gc.collect()
    before = rss_kib()
    for _ in range(9000):
        cycle(model)
    gc.collect()
    grown = rss_kib() - before
    assert grown < 1024, f"RSS grew by {grown} KiB over 9000 cycles"
    assert sys.getrefcount(model) == refs


def test_dropped_integrator_is_freed():
    model = heavy_top()
    model.applied_force = lambda t, q, v, f: None
    sim = lignum.Integrator(model, step=1e-3)
    sim.solve(0.002)
    ref = weakref.ref(sim)
    del sim
    gc.collect()
    assert ref() is None
