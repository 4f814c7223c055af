"""Shared models of the Python package's tests."""
import os
import pathlib
import sys

import numpy as np
import pytest

import lignum

SOURCE_DIR = pathlib.Path(os.environ.get("LIGNUM_SOURCE_DIR",
                                         pathlib.Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(SOURCE_DIR / "python" / "examples"))

X = np.array([0.0, 1.0, 0.0])
OMEGA = np.array([0.0, 150.0, -4.61538])
J = (0.234375, 0.46875, 0.234375)
GRAVITY = (0.0, 0.0, -9.81)


def heavy_top(gravity=GRAVITY):
    """The heavy top of examples/teach/heavy_top.c."""
    mb = lignum.Multibody(gravity=gravity)
    b = mb.add_body(mass=15.0, inertia=J, position=X, velocity=np.cross(OMEGA, X),
                    angular_velocity=OMEGA)
    mb.spherical(lignum.GROUND, (0.0, 0.0, 0.0), b, -X)
    return mb


SETTINGS = {
    "adaptive": dict(method="genalpha", rho_inf=0.9, adaptive=True, rtol=1e-6, atol=1e-6,
                     step=1e-3, max_steps=100000),
    "fixed": dict(method="genalpha", rho_inf=0.9, step=1e-3, max_steps=100000),
    "bdf": dict(method="bdf", bdf_order=5, adaptive=True, rtol=1e-6, atol=1e-6, step=1e-3,
                max_steps=100000),
}


@pytest.fixture
def top():
    return heavy_top()
