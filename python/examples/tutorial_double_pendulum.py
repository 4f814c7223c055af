"""The tutorial's double spherical pendulum in Python (doc/tutorial-python.md
explains every step; doc/tutorial.md is the C program): two spinning rods on
spherical joints under gravity, mod. LGGalpha (rho_inf = 0.9, exact
kinematics, index 3) with error control, a consistent start by calc_ic. It
prints the C program's table and, with --plot, draws tutorial_python.png."""
import sys

import numpy as np

import lignum

# ---- Step 1: the data
mass, length, rad = 1.0, 1.0, 0.05
J = (0.5 * mass * rad * rad, mass * (3.0 * rad * rad + length * length) / 12.0,
     mass * (3.0 * rad * rad + length * length) / 12.0)
end_a, end_b = (-0.5 * length, 0.0, 0.0), (0.5 * length, 0.0, 0.0)

# ---- Step 2: the bodies, horizontal along x, spinning, centres at rest
pendulum = lignum.Multibody(gravity=(0.0, 0.0, -9.81))
rod0 = pendulum.add_body(mass, J, position=(0.5 * length, 0.0, 0.0),
                         angular_velocity=(20.0, 0.0, 3.0))
rod1 = pendulum.add_body(mass, J, position=(1.5 * length, 0.0, 0.0),
                         angular_velocity=(-15.0, 0.0, 6.0))

# ---- Step 3: the joints
pendulum.spherical(lignum.GROUND, (0.0, 0.0, 0.0), rod0, end_a)
pendulum.spherical(rod0, end_b, rod1, end_a)

# ---- Step 4: the integrator: mod. LGGalpha with error control
sim = lignum.Integrator(pendulum, method="genalpha", rho_inf=0.9, kinematics="exact",
                        adaptive=True, rtol=1e-6, atol=1e-6)

# ---- Step 5: consistent initial values: project q0, then v0
sim.calc_ic("qv")
E0 = sum(sim.energy())

# ---- Step 6: the time loop and the outputs
print("Double spherical pendulum: mod. LGGalpha(0.9), index 3, rtol = atol = 1e-06\n")
print(f"{'t':>5s} {'x_1':>10s} {'y_1':>10s} {'z_1':>10s} {'energy':>12s} {'drift':>10s} "
      f"{'|Phi|':>9s}")
rows = []
for k in range(11):
    if k > 0:
        sim.solve(k * 0.2)
    E = sum(sim.energy())
    phi = np.max(np.abs(sim.constraint_residual()))  # |Phi|_inf
    x1 = sim.q[7:10]
    rows.append((sim.t, *x1, E))
    print(f"{sim.t:5.2f} {x1[0]:10.6f} {x1[1]:10.6f} {x1[2]:10.6f} {E:12.8f} "
          f"{(E - E0) / abs(E0):10.2e} {phi:9.1e}")

# ---- Step 7: the statistics
print()
print(sim.stats)
sim.close()

# ---- Step 8: a picture (python tutorial_double_pendulum.py --plot)
if "--plot" in sys.argv:
    import matplotlib.pyplot as plt
    rows = np.array(rows)
    fig, ax = plt.subplots(1, 2, figsize=(9, 3.5), constrained_layout=True)
    ax[0].plot(rows[:, 1], rows[:, 3], "o-")
    ax[0].set_title("centre of rod 1 (x, z)")
    ax[1].plot(rows[:, 0], (rows[:, 4] - E0) / abs(E0), "o-")
    ax[1].set_title("relative energy drift")
    ax[1].set_xlabel("t")
    fig.savefig("tutorial_python.png", dpi=90)
