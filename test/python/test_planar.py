"""Planar mechanisms from Python (PlanarMultibody) against the same model
built in C on the model object (test/python/planar_ref.c): bit for bit,
since the callbacks run in C either way; and bad input."""
import math
import os
import subprocess

import numpy as np
import pytest

import lignum
from conftest import SETTINGS

L1, L2 = 1.0, 3.0


def reference(group):
    exe = os.environ.get("LIGNUM_PLANAR_REF")
    if not exe:
        pytest.skip("LIGNUM_PLANAR_REF not set (run through ctest -R python)")
    out = subprocess.run([exe, group.lower()], check=True, capture_output=True,
                         text=True).stdout
    return np.array([[float.fromhex(x) for x in line.split()] for line in out.splitlines()])


def slider_crank(group):
    """The slider-crank of planar_ref.c, with the same arithmetic for q0."""
    mb = lignum.PlanarMultibody(gravity=(0.0, -9.81), group=group)
    a = 0.25 * math.acos(-1.0)
    bx, by = L1 * math.cos(a), L1 * math.sin(a)
    cx = bx + math.sqrt(L2 * L2 - by * by)
    crank = mb.add_body(1.0, L1 * L1 / 12.0, position=(0.5 * bx, 0.5 * by), angle=a)
    rod = mb.add_body(3.0, 3.0 * L2 * L2 / 12.0, position=(0.5 * (bx + cx), 0.5 * by),
                      angle=math.atan2(-by, cx - bx))
    slider = mb.add_body(2.0, 0.1, position=(cx, 0.0))
    o = (0.0, 0.0)
    mb.revolute(lignum.GROUND, o, crank, (-0.5 * L1, 0.0))
    mb.revolute(crank, (0.5 * L1, 0.0), rod, (-0.5 * L2, 0.0))
    mb.revolute(rod, (0.5 * L2, 0.0), slider, o)
    mb.prismatic(lignum.GROUND, o, (1.0, 0.0), slider, o, angle=0.0)
    mb.spring_damper(slider, o, lignum.GROUND, (6.0, 0.0), k=50.0, c=0.5, length=2.0)
    mb.rotational_spring_damper(lignum.GROUND, crank, k=2.0, c=0.1, rest=0.3)
    return mb


@pytest.mark.parametrize("group", ["SE2", "R2xSO2"])
def test_planar_slider_crank_bit_for_bit(group):
    ref = reference(group)
    assert ref.shape == (10, 1 + 9 + 9 + 8)
    with lignum.Integrator(slider_crank(group), **SETTINGS["fixed"]) as sim:
        assert (sim.nq, sim.nv, sim.m) == (9, 9, 8)
        for k in range(1, 11):
            assert sim.solve(0.1 * k) == "tout"
            got = np.concatenate([[sim.t], sim.q, sim.v, sim.multipliers()])
            np.testing.assert_array_equal(got, ref[k - 1], err_msg=f"{group}, output {k}")
        # the crank moved, the joints hold
        assert abs(sim.q[2] - 0.25 * math.pi) > 1e-2
        assert np.max(np.abs(sim.constraint_residual())) < 1e-8


def test_planar_driver_turns_the_crank():
    """A rotation driver theta_crank = 2 t (a motor) prescribes the angle
    the integrator returns, on both groups."""
    for group in ("SE2", "R2xSO2"):
        mb = lignum.PlanarMultibody(group=group)
        crank = mb.add_body(1.0, 0.1, position=(0.5, 0.0), velocity=(0.0, 1.0),
                            angular_velocity=2.0)
        mb.revolute(lignum.GROUND, (0.0, 0.0), crank, (-0.5, 0.0))
        mb.rotation_driver(lignum.GROUND, crank, lignum.polynomial(0.0, 2.0))
        with lignum.Integrator(mb, **SETTINGS["fixed"]) as sim:
            assert sim.solve(0.5) == "tout"
            assert sim.q[2] == pytest.approx(1.0, abs=1e-9)
            assert math.hypot(sim.q[0], sim.q[1]) == pytest.approx(0.5, abs=1e-9)


def test_planar_bad_input():
    with pytest.raises(ValueError, match="group"):
        lignum.PlanarMultibody(group="SE3")
    mb = lignum.PlanarMultibody()
    with pytest.raises(ValueError, match="mass"):
        mb.add_body(-1.0, 1.0)
    with pytest.raises(ValueError, match="inertia"):
        mb.add_body(1.0, 0.0)
    with pytest.raises(ValueError, match="position"):
        mb.add_body(1.0, 1.0, position=(0.0, 0.0, 0.0))
    body = mb.add_body(1.0, 1.0)
    with pytest.raises(ValueError, match="b"):
        mb.revolute(lignum.GROUND, (0.0, 0.0), 3, (0.0, 0.0))
    with pytest.raises(TypeError, match="planar"):
        mb.spherical(lignum.GROUND, (0.0, 0.0, 0.0), body, (0.0, 0.0, 0.0))
    # refused by the C library (LGN_ILL_INPUT): a zero axis, a negative
    # stiffness, a joint of a body with itself
    for add in (lambda m: m.prismatic(lignum.GROUND, (0.0, 0.0), (0.0, 0.0), 0, (0.0, 0.0)),
                lambda m: m.spring_damper(lignum.GROUND, (0.0, 0.0), 0, (1.0, 0.0), -1.0, 0.0,
                                          1.0),
                lambda m: m.revolute(0, (0.0, 0.0), 0, (1.0, 0.0))):
        bad = lignum.PlanarMultibody()
        bad.add_body(1.0, 1.0)
        add(bad)
        with pytest.raises(lignum.LignumError):
            lignum.Integrator(bad, **SETTINGS["fixed"])
