"""Results equal to the C library's on the same models: bit for bit where
the arithmetic is the same (the model's callbacks run in C either way)."""
import os
import subprocess

import numpy as np
import pytest

import lignum
from conftest import SETTINGS, SOURCE_DIR, heavy_top


def reference(mode):
    exe = os.environ.get("LIGNUM_HEAVY_TOP_REF")
    if not exe:
        pytest.skip("LIGNUM_HEAVY_TOP_REF not set (run through ctest -R python)")
    out = subprocess.run([exe, mode], check=True, capture_output=True, text=True).stdout
    return np.array([[float.fromhex(x) for x in line.split()] for line in out.splitlines()])


@pytest.mark.parametrize("mode", ["adaptive", "fixed", "bdf"])
def test_heavy_top_bit_for_bit(mode):
    ref = reference(mode)
    assert ref.shape == (10, 17)
    with lignum.Integrator(heavy_top(), **SETTINGS[mode]) as sim:
        for k in range(1, 11):
            assert sim.solve(0.1 * k) == "tout"
            got = np.concatenate([[sim.t], sim.q, sim.v, sim.multipliers()])
            np.testing.assert_array_equal(got, ref[k - 1], err_msg=f"{mode}, output {k}")


def answer_rows(name):
    """The numeric rows of an example's answer file examples/teach/NAME.out."""
    rows = []
    for line in (SOURCE_DIR / "examples" / "teach" / f"{name}.out").read_text().splitlines():
        parts = line.split()
        try:
            rows.append([float(x) for x in parts])
        except ValueError:
            continue
    return [r for r in rows if len(r) > 4]


def test_heavy_top_example_answer():
    """The printed table of examples/teach/heavy_top (6 decimals)."""
    rows = answer_rows("heavy_top")
    assert len(rows) == 11
    with lignum.Integrator(heavy_top(), **SETTINGS["adaptive"]) as sim:
        for row in rows[1:]:
            sim.solve(row[0])
            kin, pot = sim.energy()
            got = [sim.t, *sim.q[:3], kin + pot]
            assert [f"{x:.6f}" for x in got[1:4]] == [f"{x:.6f}" for x in row[1:4]]
            assert f"{got[4]:.6f}" == f"{row[4]:.6f}"
        assert sim.stats["steps"] == 7277


def test_four_bar_example_answer():
    """The printed table of examples/teach/four_bar (tips to 6 decimals,
    energy to 8), through calc_ic and solve_ivp."""
    from four_bar import four_bar, tip
    rows = answer_rows("four_bar")
    assert len(rows) == 9
    mb, lengths = four_bar()
    q0, v0 = mb.initial_state()
    v0[:6] = (-1.0, 0.0, 0.0, 0.0, 0.0, 2.0)
    r = lignum.solve_ivp(mb, (0.0, 2.0), t_eval=[row[0] for row in rows], v0=v0, calc_ic="v",
                         method="genalpha", rho_inf=0.9, step=1e-3, raise_on_failure=True)
    with lignum.Integrator(mb) as sim:
        for k, row in enumerate(rows):
            b, c = tip(r.q[k], 0, lengths[0]), tip(r.q[k], 2, lengths[2])
            got = [f"{x:.6f}" for x in (b[0], b[1], c[0], c[1])]
            assert got == [f"{x:.6f}" for x in row[1:5]], f"t = {row[0]}"
            assert f"{sum(sim.energy(r.q[k], r.v[k])):.8f}" == f"{row[5]:.8f}"
    assert r.stats["steps"] == 2000


def test_applied_force_equals_gravity_bit_for_bit():
    """A Python applied force m g (on a model without gravity) gives the
    same numbers as the bodies' own gravity: g - f = -m g exactly, with
    its Jacobians given (zero: a constant force), so that the iteration
    matrix is the bodies' own too."""
    free = heavy_top(gravity=(0.0, 0.0, 0.0))
    free.applied_force = lambda t, q, v, f: f.__setitem__(slice(0, 3), (0.0, 0.0, -9.81 * 15.0))
    free.applied_force_dq = free.applied_force_dv = lambda t, q, v, D: None
    with lignum.Integrator(heavy_top(), **SETTINGS["fixed"]) as a, \
            lignum.Integrator(free, **SETTINGS["fixed"]) as b:
        a.solve(0.05)
        b.solve(0.05)
        np.testing.assert_array_equal(a.q, b.q)
        np.testing.assert_array_equal(a.v, b.v)


def python_heavy_top():
    """The heavy top written as Python functions (M, g, Phi, B; no
    stiffness: Lignum's difference quotients)."""
    from conftest import GRAVITY, J, OMEGA, X
    m, Jd, gvec = 15.0, np.array(J), np.array(GRAVITY)

    def rot(p):
        w, a, b, c = p
        return np.array([[1 - 2 * (b * b + c * c), 2 * (a * b - w * c), 2 * (a * c + w * b)],
                         [2 * (a * b + w * c), 1 - 2 * (a * a + c * c), 2 * (b * c - w * a)],
                         [2 * (a * c - w * b), 2 * (b * c + w * a), 1 - 2 * (a * a + b * b)]])

    def skew(x):
        return np.array([[0, -x[2], x[1]], [x[2], 0, -x[0]], [-x[1], x[0], 0]])

    def mass(t, q, M):
        M[:3, :3] = m * np.eye(3)
        M[3:, 3:] = np.diag(Jd)

    def force(t, q, v, g):
        g[:3] = -m * gvec
        g[3:] = np.cross(v[3:], Jd * v[3:])

    def constraints(t, q, phi):  # x - R X  (the body point -X at the origin)
        phi[:] = q[:3] - rot(q[3:]) @ X

    def jacobian(t, q, B):  # d(x - R X) = u - R (dtheta x X) = u + R X~ dtheta
        B[:, :3] = np.eye(3)
        B[:, 3:] = rot(q[3:]) @ skew(X)

    q0 = np.r_[X, 1.0, 0.0, 0.0, 0.0]
    v0 = np.r_[np.cross(OMEGA, X), OMEGA]
    return lignum.PythonModel("R3xSO3", q0, v0, mass, force, nconstraints=3,
                              constraints=constraints, jacobian=jacobian, mass_constant=True)


def test_python_model_agrees_with_c_model():
    """Same equations, other arithmetic: agreement to round-off growth."""
    with lignum.Integrator(heavy_top(), **SETTINGS["fixed"]) as a, \
            lignum.Integrator(python_heavy_top(), **SETTINGS["fixed"]) as b:
        a.solve(0.1)
        b.solve(0.1)
        assert np.max(np.abs(a.q - b.q)) < 1e-9
        assert np.max(np.abs(a.v - b.v)) < 1e-6
        assert a.q[2] != 0.0  # the top did move


def test_tutorial_twin_prints_the_c_table():
    """python/examples/tutorial_double_pendulum.py prints the C tutorial's
    table, digit for digit, and takes its 6431 steps."""
    import subprocess
    import sys
    script = SOURCE_DIR / "python" / "examples" / "tutorial_double_pendulum.py"
    out = subprocess.run([sys.executable, str(script)], check=True, capture_output=True,
                         text=True, timeout=120).stdout.splitlines()
    want = (SOURCE_DIR / "examples" / "tutorial_double_pendulum.out").read_text().splitlines()
    assert len(want) > 14 and out[:14] == want[:14]
    assert "'steps': 6431" in out[-1]


def test_tutorial_python_quotes_script():
    """doc/tutorial-python.md quotes the script: each ```python block
    verbatim, each line of its ```text block a line of the script's output."""
    import re
    import subprocess
    import sys
    script = SOURCE_DIR / "python" / "examples" / "tutorial_double_pendulum.py"
    doc = (SOURCE_DIR / "doc" / "tutorial-python.md").read_text()
    src = script.read_text()
    blocks = re.findall(r"```(\w+)\n(.*?)```", doc, re.S)
    assert sum(lang == "python" for lang, _ in blocks) >= 8
    out = subprocess.run([sys.executable, str(script)], check=True, capture_output=True,
                         text=True, timeout=120).stdout.splitlines()
    for lang, text in blocks:
        if lang == "python":
            assert text in src, f"not in the script:\n{text}"
        elif lang == "text":
            for line in text.splitlines():
                assert line in out, f"not in the output: {line!r}"


def test_applied_force_jacobians_against_difference_quotients():
    """A spring force f = -k x on the top's centre of mass, with its
    Jacobians (on R^3 x SO(3), x o exp(dx, .) = x + dx: df/dq = -k I in
    the x block; df/dv = 0) or without (the model's difference quotients
    for K_t, C_t): the same motion to the Newton tolerance, and the
    analytic run needs no more Newton iterations."""
    k = 200.0

    def spring(t, q, v, f):
        f[0:3] = -k * q[0:3]

    def spring_dq(t, q, v, D):  # x o exp(dx, .) = x + dx on R^3 x SO(3)
        D[0:3, 0:3] = -k * np.eye(3)

    runs = []
    for jacobians in (False, True):
        mb = heavy_top()
        mb.applied_force = spring
        if jacobians:
            mb.applied_force_dq = spring_dq
            mb.applied_force_dv = lambda t, q, v, D: None
        with lignum.Integrator(mb, **SETTINGS["fixed"]) as sim:
            sim.solve(0.1)
            runs.append((sim.q.copy(), sim.stats["newton_iters"]))
    np.testing.assert_allclose(runs[1][0], runs[0][0], rtol=0, atol=1e-7)
    assert runs[1][1] <= runs[0][1]
