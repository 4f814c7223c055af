"""A chain of six rods on spherical joints released from the horizontal,
Lie group BDF with error control; plots the motion, energy, constraint drift,
step size and BDF order to chain.png."""
import matplotlib.pyplot as plt
import numpy as np

import lignum

N, L, MASS = 6, 0.5, 1.0
chain = lignum.Multibody(gravity=(0.0, 0.0, -9.81))
for k in range(N):  # rod k along the x axis, from x = k L to (k + 1) L
    chain.add_body(mass=MASS, inertia=(1e-4, MASS * L * L / 12.0, MASS * L * L / 12.0),
                   position=((k + 0.5) * L, 0.0, 0.0))
half = 0.5 * L
chain.spherical(lignum.GROUND, (0.0, 0.0, 0.0), 0, (-half, 0.0, 0.0))
for k in range(1, N):
    chain.spherical(k - 1, (half, 0.0, 0.0), k, (-half, 0.0, 0.0))

r = lignum.solve_ivp(chain, (0.0, 2.0), method="bdf", bdf_order=5, adaptive=True,
                     rtol=1e-6, atol=1e-6, step=1e-4)
print(r, r.stats)
with lignum.Integrator(chain) as sim:
    E = np.array([sum(sim.energy(q, v)) for q, v in zip(r.q, r.v)])
    drift = [np.linalg.norm(sim.constraint_residual(q)) for q in r.q]

fig, ax = plt.subplots(2, 2, figsize=(9, 6), constrained_layout=True)
for t in np.linspace(0.0, 2.0, 9):  # snapshots of the rods' centres
    i = np.searchsorted(r.t, t).clip(0, len(r.t) - 1)
    ax[0, 0].plot(np.r_[0.0, r.q[i, 0::7]], np.r_[0.0, r.q[i, 2::7]], ".-", lw=0.8)
ax[0, 0].set_title("centres of the rods (x, z)"); ax[0, 0].set_aspect("equal")
ax[0, 1].plot(r.t, E - E[0]); ax[0, 1].set_title("energy - E(0)")
ax[1, 0].semilogy(r.t, np.maximum(drift, 1e-18)); ax[1, 0].set_title("|Phi(q)|")
ax[1, 1].semilogy(r.t[1:], r.h[1:], label="step size")
ax2 = ax[1, 1].twinx(); ax2.step(r.t[1:], r.order[1:], "C1", lw=0.8, label="order")
ax[1, 1].set_title("step size (left), BDF order (right)")
for a in ax[1]:
    a.set_xlabel("t")
fig.savefig("chain.png", dpi=90)
