"""The heavy top (Bruls and Cardona) with error control; plots to heavy_top.png."""
import matplotlib.pyplot as plt
import numpy as np

import lignum

X, Omega = np.array([0.0, 1.0, 0.0]), np.array([0.0, 150.0, -4.61538])
top = lignum.Multibody(gravity=(0.0, 0.0, -9.81))
b = top.add_body(mass=15.0, inertia=(0.234375, 0.46875, 0.234375), position=X,
                 velocity=np.cross(Omega, X), angular_velocity=Omega)
top.spherical(lignum.GROUND, (0.0, 0.0, 0.0), b, -X)  # tip held at the origin

r = lignum.solve_ivp(top, (0.0, 1.0), method="genalpha", rho_inf=0.9,
                     adaptive=True, rtol=1e-6, atol=1e-6)
print(r, r.stats)
with lignum.Integrator(top) as sim:  # energy and |Phi| of each output
    E = [sum(sim.energy(q, v)) for q, v in zip(r.q, r.v)]
    drift = [np.linalg.norm(sim.constraint_residual(q)) for q in r.q]

fig, ax = plt.subplots(2, 2, figsize=(9, 6), constrained_layout=True)
ax[0, 0].plot(r.q[:, 0], r.q[:, 1]); ax[0, 0].set_title("centre of mass (x, y)")
ax[0, 1].plot(r.t, np.array(E) - E[0]); ax[0, 1].set_title("energy - E(0)")
ax[1, 0].semilogy(r.t, np.maximum(drift, 1e-18)); ax[1, 0].set_title("|Phi(q)|")
ax[1, 1].semilogy(r.t[1:], r.h[1:]); ax[1, 1].set_title("step size")
ax[1, 1].set_xlabel("t"); ax[1, 0].set_xlabel("t")
fig.savefig("heavy_top.png", dpi=90)
