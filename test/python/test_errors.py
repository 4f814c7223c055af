"""Bad input raises (TypeError/ValueError on the Python side, LignumError
with Lignum's flag name and message from the library); callbacks that raise
propagate their exception; a failed call leaves the state as it was."""
import math

import numpy as np
import pytest

import lignum
from conftest import SETTINGS, heavy_top
from test_same_as_c import python_heavy_top


def test_lignum_flag_and_message():
    with pytest.raises(lignum.LignumError) as err:
        lignum.Integrator(heavy_top(), rho_inf=1.5)
    assert err.value.name == "LGN_ILL_INPUT" and err.value.flag == -22
    assert err.value.function == "LGNSetGenAlpha"
    assert "rho_inf" in err.value.message
    with pytest.raises(lignum.LignumError) as err:
        lignum.Integrator(heavy_top(), adaptive=True, rtol=-1.0)
    assert err.value.name == "LGN_ILL_INPUT" and "rtol" in err.value.message
    with pytest.raises(lignum.LignumError) as err:
        lignum.Integrator(heavy_top(), step=-1e-3)
    assert err.value.name == "LGN_ILL_INPUT"
    with pytest.raises(lignum.LignumError) as err:
        lignum.Integrator(heavy_top(), method="bdf", bdf_order=9)
    assert err.value.name == "LGN_ILL_INPUT"
    assert lignum.flag_name(-26) == "LGN_BAD_TOUT"


@pytest.mark.parametrize("kwargs, exc", [
    (dict(method="rk4"), ValueError), (dict(kinematics="fast"), ValueError),
    (dict(constraints="index1"), ValueError), (dict(rho_inf="0.9"), TypeError),
    (dict(method="bdf", rho_inf=0.5), ValueError), (dict(step=float("nan")), ValueError),
    (dict(h0=1e-3), ValueError), (dict(method="newmark", bdf_order=2), ValueError),
    (dict(alpha_m=0.1, alpha_f=0.1, beta=0.3, gamma=0.6, rho_inf=0.5), ValueError),
    (dict(t0=float("inf")), ValueError), (dict(model_kinematics=1), TypeError),
    (dict(max_steps=1.5), TypeError), (dict(adaptive="yes"), TypeError),
    (dict(q0=np.zeros(6)), ValueError), (dict(q0=[1, 2, 3, 1, 0, 0, math.nan]), ValueError),
    (dict(v0=[[1.0] * 6]), ValueError), (dict(v0="abc"), TypeError),
    (dict(alpha_m=0.1), ValueError), (dict(newton="quasi"), ValueError),
])
def test_bad_settings_raise(kwargs, exc):
    with pytest.raises(exc):
        lignum.Integrator(heavy_top(), **kwargs)


def test_bad_model_input_raises():
    mb = lignum.Multibody()
    with pytest.raises(ValueError, match="mass"):
        mb.add_body(mass=-1.0, inertia=(1, 1, 1))
    with pytest.raises(ValueError, match="inertia"):
        mb.add_body(mass=1.0, inertia=(1, 1))
    with pytest.raises(ValueError, match="position"):
        mb.add_body(mass=1.0, inertia=(1, 1, 1), position=(0, 0))
    with pytest.raises(ValueError, match="no body"):
        mb.spherical(lignum.GROUND, (0, 0, 0), 3, (0, 0, 0))
    with pytest.raises(TypeError):
        mb.spherical(lignum.GROUND, (0, 0, 0), 0.0, (0, 0, 0))
    with pytest.raises(ValueError):
        lignum.Integrator(mb)  # no bodies
    with pytest.raises(TypeError):
        lignum.Integrator("a model")
    with pytest.raises(ValueError):
        lignum.quaternion((0, 0, 0), 1.0)
    mb.add_body(mass=1.0, inertia=(-1, 1, 1))  # Lignum checks the inertia
    with pytest.raises(lignum.LignumError) as err:
        lignum.Integrator(mb)
    assert err.value.name == "LGN_ILL_INPUT"


def test_failed_solve_leaves_state():
    with lignum.Integrator(heavy_top(), **SETTINGS["fixed"]) as sim:
        sim.solve(0.01)
        t, q, v = sim.t, sim.q.copy(), sim.v.copy()
        with pytest.raises(lignum.LignumError) as err:
            sim.solve(0.005)
        assert err.value.name == "LGN_BAD_TOUT"
        assert sim.t == t
        np.testing.assert_array_equal(sim.q, q)
        np.testing.assert_array_equal(sim.v, v)
        with pytest.raises(TypeError):
            sim.solve("later")
        sim.solve(0.02)  # still usable
        assert sim.t == pytest.approx(0.02)
    with pytest.raises(ValueError, match="closed"):
        sim.solve(0.03)


class Boom(Exception):
    pass


def test_applied_force_that_raises_propagates():
    mb = heavy_top()
    calls = []

    def force(t, q, v, f):
        calls.append(t)
        if t > 0.0105:
            raise Boom("from the force")

    mb.applied_force = force
    with lignum.Integrator(mb, **SETTINGS["fixed"]) as sim:
        sim.solve(0.01)
        q = sim.q.copy()
        with pytest.raises(Boom, match="from the force"):
            sim.solve(0.02)
        np.testing.assert_array_equal(sim.q, q)  # the failed step was undone
        assert sim.t == pytest.approx(0.01)
    assert calls


def test_python_model_errors():
    model = python_heavy_top()
    model.functions["force"] = lambda t, q, v, g: 1 / 0
    with pytest.raises(ZeroDivisionError):
        lignum.Integrator(model, **SETTINGS["fixed"]).solve(0.01)
    model = python_heavy_top()
    model.functions["force"] = lambda t, q, v, g: g.__setitem__(slice(None), np.nan)
    with pytest.raises(lignum.LignumError) as err:
        lignum.Integrator(model, **SETTINGS["fixed"]).solve(0.01)
    assert err.value.name == "LGN_NONFINITE"
    model = python_heavy_top()
    model.functions["constraints"] = lambda t, q, phi: phi.__setitem__(slice(None), [1.0, 2.0])
    with pytest.raises(ValueError):  # wrong shape: numpy's error comes through
        lignum.Integrator(model, **SETTINGS["fixed"]).solve(0.01)
    with pytest.raises(ValueError, match="group"):
        lignum.PythonModel("SO4", [1, 0, 0, 0], [0, 0, 0], print, print)
    with pytest.raises(TypeError, match="mass"):
        lignum.PythonModel("SO3", [1, 0, 0, 0], [0, 0, 0], None, print)


def test_root_and_drive_functions_that_raise():
    with lignum.Integrator(heavy_top(), **SETTINGS["fixed"]) as sim:
        sim.set_events([lambda t, q, v: q[2] + 0.1 if t < 0.005 else [][0]])
        with pytest.raises(IndexError):
            sim.solve(0.01)
        with pytest.raises(TypeError):
            sim.set_events([1.0])
    mb = lignum.Multibody()
    b = mb.add_body(mass=1.0, inertia=(1, 1, 1), position=(1, 0, 0))
    mb.revolute(lignum.GROUND, (0, 0, 0), (0, 0, 1), b, (-1, 0, 0), (0, 0, 1))

    def law(t):
        if t > 0.003:
            raise Boom("drive")
        return (t, 1.0, 0.0)

    mb.rotation_driver(lignum.GROUND, (0, 0, 1), (1, 0, 0), b, (1, 0, 0), law)
    with lignum.Integrator(mb, step=1e-3) as sim:
        with pytest.raises(Boom):
            sim.solve(0.01)
    with pytest.raises(TypeError):
        mb.rotation_driver(lignum.GROUND, (0, 0, 1), (1, 0, 0), b, (1, 0, 0), 3.0)


def test_reentry_and_read_only_state():
    """A callback that calls back into its own integrator is refused (a
    RuntimeError through the callback); the state arrays are read-only."""
    mb = heavy_top()
    holder = {}

    def force(t, q, v, f):
        holder["sim"].stats  # reading the integrator while it runs

    mb.applied_force = force
    with lignum.Integrator(mb, **SETTINGS["fixed"]) as sim:
        holder["sim"] = sim
        with pytest.raises(RuntimeError, match="running"):
            sim.solve(0.01)
        with pytest.raises(ValueError):
            sim.q[0] = 1.0
        with pytest.raises(AttributeError):
            sim.q = np.zeros(7)
        assert sim.t == 0.0 and sim.stats["steps"] == 0


def test_bad_drive_laws():
    mb = lignum.Multibody()
    b = mb.add_body(mass=1.0, inertia=(1, 1, 1), position=(1, 0, 0))
    for law in [(7, [0, 0, 0, 0]), (0, [1, 2]), (0, ["a", 0, 0, 0]), "sin"]:
        with pytest.raises(TypeError):
            mb.rotation_driver(lignum.GROUND, (0, 0, 1), (1, 0, 0), b, (1, 0, 0), law)
    mb.revolute(lignum.GROUND, (0, 0, 0), (0, 0, 1), b, (-1, 0, 0), (0, 0, 1))
    mb.rotation_driver(lignum.GROUND, (0, 0, 1), (1, 0, 0), b, (1, 0, 0),
                       lambda t: (np.nan, 0.0, 0.0))
    with lignum.Integrator(mb, step=1e-3) as sim:
        with pytest.raises(ValueError, match="non-finite"):
            sim.solve(0.01)


def test_callback_inputs_are_read_only():
    """A callback cannot write Lignum's q or v behind its back."""
    mb = heavy_top()

    def force(t, q, v, f):
        q[0] = 0.0

    mb.applied_force = force
    with lignum.Integrator(mb, **SETTINGS["fixed"]) as sim:
        with pytest.raises(ValueError, match="read-only"):
            sim.solve(0.01)


def test_failure_after_steps_leaves_a_consistent_state():
    """Steps succeed, then a callback raises: t, q, v are the state after
    the last good step (as the step left it, not projected), equal to a
    run that stopped there without projecting its outputs."""
    mb = heavy_top()

    def force(t, q, v, f):
        if t > 0.0025:
            raise KeyboardInterrupt  # as a Ctrl-C inside a callback

    mb.applied_force = force
    mb.applied_force_dq = mb.applied_force_dv = lambda t, q, v, D: None  # f = 0
    with lignum.Integrator(mb, **SETTINGS["fixed"]) as sim, \
            lignum.Integrator(heavy_top(), project_outputs="none", **SETTINGS["fixed"]) as ref:
        with pytest.raises(KeyboardInterrupt):
            sim.solve(0.01)
        assert sim.stats["steps"] == 2
        ref.solve(sim.t)
        assert ref.stats["steps"] == 2
        np.testing.assert_array_equal(sim.q, ref.q)
        np.testing.assert_array_equal(sim.v, ref.v)
