"""The tutorial's double spherical pendulum (doc/tutorial.md) in Python
(doc/tutorial-python.md): two spinning rods on spherical joints, mod.
LGGalpha (rho_inf = 0.9, exact kinematics, index 3) with error control,
consistent start by calc_ic; prints the C program's table."""
import numpy as np

import lignum

mass, length, rad = 1.0, 1.0, 0.05
J = (0.5 * mass * rad * rad, mass * (3.0 * rad * rad + length * length) / 12.0,
     mass * (3.0 * rad * rad + length * length) / 12.0)
end_a, end_b = (-0.5 * length, 0.0, 0.0), (0.5 * length, 0.0, 0.0)

pendulum = lignum.Multibody(gravity=(0.0, 0.0, -9.81))
rod0 = pendulum.add_body(mass, J, position=(0.5 * length, 0.0, 0.0),
                         angular_velocity=(20.0, 0.0, 3.0))
rod1 = pendulum.add_body(mass, J, position=(1.5 * length, 0.0, 0.0),
                         angular_velocity=(-15.0, 0.0, 6.0))
pendulum.spherical(lignum.GROUND, (0.0, 0.0, 0.0), rod0, end_a)
pendulum.spherical(rod0, end_b, rod1, end_a)

sim = lignum.Integrator(pendulum, method="genalpha", rho_inf=0.9, kinematics="exact",
                        adaptive=True, rtol=1e-6, atol=1e-6)
sim.calc_ic("qv")  # project q0, then v0 onto the constraints
E0 = sum(sim.energy())
print("Double spherical pendulum: mod. LGGalpha(0.9), index 3, rtol = atol = 1e-06\n")
print(f"{'t':>5s} {'x_1':>10s} {'y_1':>10s} {'z_1':>10s} {'energy':>12s} {'drift':>10s} "
      f"{'|Phi|':>9s}")
for k in range(11):
    if k:
        sim.solve(k * 0.2)
    E = sum(sim.energy())
    phi = np.linalg.norm(sim.constraint_residual())
    x1 = sim.q[7:10]
    print(f"{sim.t:5.2f} {x1[0]:10.6f} {x1[1]:10.6f} {x1[2]:10.6f} {E:12.8f} "
          f"{(E - E0) / abs(E0):10.2e} {phi:9.1e}")
print("\n", sim.stats)
