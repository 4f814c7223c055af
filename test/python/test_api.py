"""The Python-style API: states as numpy views, stop times, events with
Python root functions, calc_ic, statistics, solve_ivp, examples."""
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import lignum
from conftest import SETTINGS, SOURCE_DIR, heavy_top


def test_state_arrays_are_updated_in_place():
    with lignum.Integrator(heavy_top(), **SETTINGS["fixed"]) as sim:
        q = sim.q
        sim.solve(0.01)
        assert q is sim.q and q[2] != 0.0
        assert sim.stats["steps"] == 10
        assert sim.last_step() == pytest.approx(1e-3)
        assert sim.acceleration().shape == (6,) and sim.multipliers().shape == (3,)
        assert np.linalg.norm(sim.constraint_residual()) < 1e-12


def test_stop_time_and_one_step():
    with lignum.Integrator(heavy_top(), **SETTINGS["adaptive"]) as sim:
        sim.set_stop_time(0.0123)
        assert sim.solve(1.0) == "tstop"
        assert sim.t == 0.0123
        sim.clear_stop_time()
        assert sim.solve(1.0, one_step=True) == "step"
        assert 0.0123 < sim.t < 1.0


def test_event_located():
    """The centre of mass first crosses z = -0.5 (terminal event)."""
    def below(t, q, v):
        return q[2] + 0.5
    below.terminal, below.direction = True, -1
    r = lignum.solve_ivp(heavy_top(), (0.0, 1.0), t_eval=np.linspace(0, 1, 11), events=below,
                         **SETTINGS["adaptive"])
    assert r.status == 1 and r.success
    assert len(r.t_events[0]) == 1
    te = r.t_events[0][0]
    assert 0.1 < te < 0.2  # z(0.1) = -0.149, z(0.2) = -0.524 (heavy_top.out)
    assert abs(r.q_events[0][0][2] + 0.5) < 1e-6
    assert r.t[-1] == te and r.stats["root_evals"] > 0


def test_calc_ic_projects_velocities():
    from four_bar import four_bar
    mb, _ = four_bar()
    q0, v0 = mb.initial_state()
    v0[:6] = (-1.0, 0.0, 0.0, 0.0, 0.0, 2.0)
    with lignum.Integrator(mb, v0=v0) as sim:
        before = sim.v.copy()
        sim.calc_ic("v")
        assert not np.array_equal(before, sim.v)
        with pytest.raises(ValueError):
            sim.calc_ic("w")


def test_solve_ivp_equals_integrator_loop():
    r = lignum.solve_ivp(heavy_top(), (0.0, 0.05), t_eval=[0.0, 0.02, 0.05],
                         **SETTINGS["fixed"])
    with lignum.Integrator(heavy_top(), **SETTINGS["fixed"]) as sim:
        for k, t in enumerate([0.02, 0.05]):
            sim.solve(t)
            np.testing.assert_array_equal(r.q[k + 1], sim.q)
            np.testing.assert_array_equal(r.lam[k + 1], sim.multipliers())
    assert r.q.shape == (3, 7) and r.lam.shape == (3, 3) and np.isnan(r.lam[0]).all()
    every = lignum.solve_ivp(heavy_top(), (0.0, 0.01), **SETTINGS["bdf"])
    assert np.all(np.diff(every.t) > 0) and every.t[-1] == 0.01
    assert len(every.t) == every.stats["steps"] + 1 and np.all(every.order[1:] >= 1)
    with pytest.raises(ValueError):
        lignum.solve_ivp(heavy_top(), (0.0, 1.0), t_eval=[0.5, 0.2])


def test_solve_ivp_failure_status():
    r = lignum.solve_ivp(heavy_top(), (0.0, 1.0), t_eval=[0.5, 1.0], max_steps=5, step=1e-3)
    assert r.status == -1 and not r.success and r.error.name == "LGN_TOO_MUCH_WORK"
    with pytest.raises(lignum.LignumError):
        lignum.solve_ivp(heavy_top(), (0.0, 1.0), t_eval=[1.0], max_steps=5, step=1e-3,
                         raise_on_failure=True)


def test_drivers_in_c():
    """A motor at constant speed (polynomial law in C) turns a body
    on a revolute joint: its angle is the law's."""
    mb = lignum.Multibody()
    b = mb.add_body(mass=1.0, inertia=(0.1, 0.1, 0.1), position=(1, 0, 0),
                    velocity=(0, 2.0, 0), angular_velocity=(0, 0, 2.0))
    mb.revolute(lignum.GROUND, (0, 0, 0), (0, 0, 1), b, (-1, 0, 0), (0, 0, 1))
    mb.rotation_driver(lignum.GROUND, (0, 0, 1), (1, 0, 0), b, (1, 0, 0),
                       lignum.polynomial(0.0, 2.0))
    with lignum.Integrator(mb, step=1e-3) as sim:
        sim.solve(0.5)
        assert np.arctan2(sim.q[1], sim.q[0]) == pytest.approx(1.0, abs=1e-8)


def test_examples_run(tmp_path):
    """The examples write their figures; the heavy top fits in 30 lines."""
    ex = SOURCE_DIR / "python" / "examples"
    assert len((ex / "heavy_top.py").read_text().splitlines()) <= 30
    env = dict(os.environ, MPLBACKEND="Agg")
    names = ("heavy_top", "four_bar", "chain")
    runs = [subprocess.Popen([sys.executable, str(ex / f"{name}.py")], cwd=tmp_path, env=env,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE) for name in names]
    for name, run in zip(names, runs):  # side by side
        out, err = run.communicate(timeout=180)
        assert run.returncode == 0, f"{name}.py: {err.decode()}"
        assert b"status=0" in out
        assert (tmp_path / f"{name}.png").stat().st_size > 10000


def test_lignum_warnings_become_python_warnings():
    """A redundant mechanism (two revolute joints on one axis): Lignum's
    warning arrives as a LignumWarning, the run goes on."""
    mb = lignum.Multibody(gravity=(0.0, -9.81, 0.0))
    b = mb.add_body(mass=1.0, inertia=(0.1, 0.1, 0.1), position=(1, 0, 0))
    mb.revolute(lignum.GROUND, (0, 0, 0), (0, 0, 1), b, (-1, 0, 0), (0, 0, 1))
    mb.revolute(lignum.GROUND, (0, 0, 1), (0, 0, 1), b, (-1, 0, 1), (0, 0, 1))
    with lignum.Integrator(mb, step=1e-3) as sim:
        with pytest.warns(lignum.LignumWarning, match="redundant constraints"):
            sim.solve(0.01)
        assert sim.q[1] < 0.0  # it falls, turning about z


def test_every_public_call_has_a_docstring():
    import inspect
    for name in lignum.__all__:
        obj = getattr(lignum, name)
        if callable(obj):
            assert inspect.getdoc(obj), name
        if inspect.isclass(obj):
            for attr, member in vars(obj).items():
                if not attr.startswith("_") and (callable(member) or isinstance(member,
                                                                                 property)):
                    assert inspect.getdoc(member), f"{name}.{attr}"


def test_spring_damper_settles_at_equilibrium():
    """A body hanging from the ground on a damped spring (no joints):
    it settles where k (L - L0) = m g."""
    m, k, c, L0, g = 2.0, 400.0, 40.0, 1.0, 9.81
    mb = lignum.Multibody(gravity=(0.0, 0.0, -g))
    b = mb.add_body(mass=m, inertia=(0.1, 0.1, 0.1), position=(0.0, 0.0, -L0))
    mb.spring_damper(lignum.GROUND, (0, 0, 0), b, (0, 0, 0), k, c, L0)
    r = lignum.solve_ivp(mb, (0.0, 5.0), t_eval=[5.0], method="bdf", adaptive=True,
                         rtol=1e-9, atol=1e-9, raise_on_failure=True)
    assert r.q[-1, 2] == pytest.approx(-(L0 + m * g / k), abs=1e-7)


def test_rotational_spring_turns_back():
    """A free body tied to the ground's frame by a rotational spring: its
    spin about z reverses within a half period sqrt(J / k) pi."""
    mb = lignum.Multibody()
    b = mb.add_body(mass=1.0, inertia=(1.0, 1.0, 1.0), angular_velocity=(0, 0, 1.0))
    mb.rotational_spring_damper(lignum.GROUND, b, 4.0, 0.0)
    with lignum.Integrator(mb, step=1e-3) as sim:
        sim.solve(0.5 * np.pi / 2.0)  # a quarter period: at rest, turned by 1/2 rad
        assert abs(sim.v[5]) < 1e-3
        sim.solve(np.pi / 2.0)  # half a period: spinning back
        assert sim.v[5] == pytest.approx(-1.0, abs=1e-3)


def test_translation_driver_harmonic():
    """An actuator on a prismatic joint moves the body by a harmonic law
    evaluated in C."""
    mb = lignum.Multibody()
    b = mb.add_body(mass=1.0, inertia=(0.1, 0.1, 0.1), position=(0.5, 0, 0))
    ex = (1.0, 0.0, 0.0)
    mb.prismatic(lignum.GROUND, (0, 0, 0), ex, b, (0, 0, 0), ex)
    mb.translation_driver(lignum.GROUND, (0, 0, 0), ex, b, (0, 0, 0),
                          lignum.harmonic(0.5, 0.2, 3.0, 0.0))
    with lignum.Integrator(mb, step=1e-3, v0=[0.6, 0, 0, 0, 0, 0]) as sim:
        sim.solve(1.0)
        assert sim.q[0] == pytest.approx(0.5 + 0.2 * np.sin(3.0), abs=1e-9)
        assert sim.v[0] == pytest.approx(0.6 * np.cos(3.0), abs=1e-6)
