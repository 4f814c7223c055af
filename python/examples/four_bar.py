"""The spatial four-bar of examples/teach/four_bar.c (revolute, spherical,
universal, revolute: 17 rows, one degree of freedom) from Python: consistent
initial velocities by calc_ic, generalized-alpha with h = 1e-3; plots to
four_bar.png."""
import math

import matplotlib.pyplot as plt
import numpy as np

import lignum


def four_bar():
    """The model; returns it and the rod lengths."""
    lengths = (1.0, math.sqrt(10.0), 2.0)
    centres = ((0.0, 0.5, 0.0), (1.5, 1.5, 0.0), (3.0, 1.0, 0.0))
    angles = (0.5 * math.pi, math.atan2(1.0, 3.0), 0.5 * math.pi)
    mb = lignum.Multibody(gravity=(0.0, -9.81, 0.0))
    for L, c, a in zip(lengths, centres, angles):  # slender rods along body x
        J = (0.5 * L * 0.05 * 0.05, L * L * L / 12.0, L * L * L / 12.0)
        mb.add_body(mass=L, inertia=J, position=c, rotation=lignum.quaternion((0, 0, 1), a))
    lo = [(-0.5 * L, 0.0, 0.0) for L in lengths]
    hi = [(0.5 * L, 0.0, 0.0) for L in lengths]
    ez, ex = (0.0, 0.0, 1.0), (1.0, 0.0, 0.0)
    mb.revolute(lignum.GROUND, (0.0, 0.0, 0.0), ez, 0, lo[0], ez)
    mb.spherical(0, hi[0], 1, lo[1])
    mb.universal(1, hi[1], ez, 2, hi[2], ex)
    mb.revolute(2, lo[2], ez, lignum.GROUND, (3.0, 0.0, 0.0), ez)
    return mb, lengths


def tip(q, k, length):
    """x + R (length/2, 0, 0) of rod k at configuration q."""
    x, (w, a, b, c) = q[7 * k:7 * k + 3], q[7 * k + 3:7 * k + 7]
    first_column = np.array([1 - 2 * (b * b + c * c), 2 * (a * b + w * c), 2 * (a * c - w * b)])
    return x + 0.5 * length * first_column


if __name__ == "__main__":
    mb, lengths = four_bar()
    q0, v0 = mb.initial_state()
    v0[:6] = (-1.0, 0.0, 0.0, 0.0, 0.0, 2.0)  # the crank turns at 2 rad/s about z
    r = lignum.solve_ivp(mb, (0.0, 2.0), t_eval=np.linspace(0.0, 2.0, 201), v0=v0,
                         calc_ic="v", method="genalpha", rho_inf=0.9, step=1e-3)
    print(r, r.stats)
    with lignum.Integrator(mb) as sim:
        E = np.array([sum(sim.energy(q, v)) for q, v in zip(r.q, r.v)])
        drift = [np.linalg.norm(sim.constraint_residual(q)) for q in r.q]
    B = np.array([tip(q, 0, lengths[0]) for q in r.q])
    C = np.array([tip(q, 2, lengths[2]) for q in r.q])
    fig, ax = plt.subplots(2, 2, figsize=(9, 6), constrained_layout=True)
    ax[0, 0].plot(B[:, 0], B[:, 1], label="crank tip B")
    ax[0, 0].plot(C[:, 0], C[:, 1], label="rocker tip C")
    ax[0, 0].legend(); ax[0, 0].set_title("trajectories (x, y)")
    ax[0, 1].plot(r.t, E - E[0]); ax[0, 1].set_title("energy - E(0)")
    ax[1, 0].semilogy(r.t, np.maximum(drift, 1e-18)); ax[1, 0].set_title("|Phi(q)|")
    ax[1, 1].plot(r.t, r.lam[:, :3]); ax[1, 1].set_title("multipliers of joint A")
    for a in ax[1]:
        a.set_xlabel("t")
    fig.savefig("four_bar.png", dpi=90)
