#!/usr/bin/env python3
"""Write the seed corpus of lgn_fuzz (test/fuzz/corpus/): small programs in
the byte language of lgn_fuzz.c (one operation = opcode, object, arguments).
Run from anywhere: python3 test/fuzz/make_corpus.py"""
import os

(CREATE, SETGROUP, SETFNS, CONSTRAINTS, TANGENTS, LINSOL, STEPSIZE, METHOD, INDEX,
 KINEMATICS, TOLERANCES, COUNTS, INITIAL, CONTROL, STEPBOUNDS, STOPTIME, INIT, REINIT,
 SOLVE, SOLVE2, SOLVE3, DKY, GETTERS, FAULT, HEAL, FREE, CALCIC, MISC, JOINTS) = range(29)

SANE_DT = 160     # Param(): about 2e-3
ONE, NORMAL = 1, 0


def create(obj, model, adaptive=0, modified=0, tangents=1, revolute=0, n=1, solver=0, raw=0):
    opt = adaptive | modified << 1 | tangents << 2 | revolute << 3 | (n - 1) << 4 | solver << 6
    return [CREATE, obj, model | (0x80 if raw else 0), opt]


def solve(obj, itask=ONE, dt=SANE_DT):
    return [SOLVE, obj, itask, dt]


seeds = {}
names = ["body0", "body3", "osc", "joints"]
solvers = ["dense", "csc", "csr"]
# every model with every linear solver, fixed and adaptive steps
for model in range(4):
    for solver in range(3):
        adaptive = (model + solver) % 2
        p = create(0, model, adaptive=adaptive, modified=solver == 1, revolute=solver == 2,
                   n=1 + solver, solver=solver)
        p += solve(0) + solve(0, NORMAL) + solve(0) + [DKY, 0, 0x08, 4, DKY, 0, 0x11, 4]
        p += [GETTERS, 0, 0, 4, 4, 4, 4, 4, 4, 4, 4]
        seeds[f"{names[model]}_{solvers[solver]}_{'adaptive' if adaptive else 'fixed'}"] = p
# a fault of every callback of the pinned body, each kind once, then healed
for cb in range(8):
    kind = cb % 6
    p = create(0, 1, adaptive=cb % 2, solver=cb % 3) + solve(0)
    p += [FAULT, 0, cb | kind << 3, 1] + solve(0) + solve(0) + [HEAL, 0, 0] + solve(0)
    seeds[f"fault_cb{cb}_kind{kind}"] = p
# the joints model with faults in its constraint callbacks
for cb in (2, 3, 6):
    p = create(1, 3, revolute=1, solver=1) + [FAULT, 1, cb | 2 << 3, 2] + solve(1, NORMAL) + [HEAL, 1, 0] + solve(1)
    seeds[f"joints_fault_cb{cb}"] = p
# out of order and bad arguments
seeds["init_twice"] = create(0, 0) + [INIT, 0, 0, INIT, 0, 0] + solve(0)
seeds["reinit_after_solve"] = create(0, 2, n=3) + solve(0) + solve(0) + [REINIT, 0, 1, 3] + solve(0)
seeds["free_then_calls"] = create(0, 1) + solve(0) + [FREE, 0] + solve(0) + [GETTERS, 0, 0, STEPSIZE, 0, 100, INIT, 0, 0]
seeds["setters_after_solve"] = create(0, 1) + solve(0) + [STEPSIZE, 0, 150, METHOD, 0, 0, 150, INDEX, 0, 2,
                                                          KINEMATICS, 0, 0x41] + solve(0)
seeds["raw_create"] = create(0, 0, raw=1) + solve(0) + [SETGROUP, 0, 0, SETFNS, 0, 3, INIT, 0, 0, LINSOL, 0, 0] + solve(0)
seeds["wrong_linsol"] = create(0, 1) + [LINSOL, 0, 0x18] + solve(0) + [LINSOL, 0, 0x01] + solve(0)
seeds["bad_constraints"] = create(0, 1) + [CONSTRAINTS, 0, 2 | 8 | 16] + solve(0) + [CONSTRAINTS, 0, 1] + solve(0)
seeds["stop_time"] = create(0, 1, adaptive=1) + [STOPTIME, 0, 1, 120] + solve(0, NORMAL, 200) + solve(0, NORMAL)
seeds["adaptive_tolerances"] = create(0, 3, adaptive=1) + [TOLERANCES, 0, 1, 100, 100, TOLERANCES, 0, 0, 120, 120, 1, 0, 4] + solve(0, NORMAL, 220)
seeds["nan_tout"] = create(0, 2) + [SOLVE, 0, 0x80, 0] + solve(0, ONE, 0x80) + [SOLVE, 0, 0x80, 7]
seeds["calcic"] = create(0, 3, revolute=1) + [INIT, 0, 4, 1, 11, 0x40, 3, CALCIC, 0, 3] + solve(0)
seeds["nonfinite_init"] = create(0, 2, n=2) + [INIT, 0, 2, 0, 1] + solve(0)
seeds["two_objects"] = create(0, 1) + create(1, 3, solver=1) + solve(0) + solve(1) + [FREE, 0] + solve(1)
seeds["step_bounds"] = create(0, 1, adaptive=1) + [STEPBOUNDS, 0, 0, 150, 3, STEPBOUNDS, 0, 2, 100, 3, COUNTS, 0, 0x35, 5] + solve(0, NORMAL, 250)
seeds["initial_acceleration"] = create(0, 1) + [INITIAL, 0, 3, 150, 10, 5, INITIAL, 0, 0, 150, 5] + solve(0)
seeds["joints_bad_input"] = create(0, 3, revolute=1) + [JOINTS, 0, 0x27, 20, 1, 3, 0] + solve(0) + [JOINTS, 0, 0x11, 11, 2, 5, 0]
seeds["misc"] = create(0, 1, solver=1) + [MISC, 0, 7, 128, LINSOL, 0, 0x81] + solve(0) + [MISC, 0, 1] + solve(0)
seeds["control_switch"] = create(0, 0) + solve(0) + [CONTROL, 0, 1] + solve(0) + [CONTROL, 0, 0] + solve(0, NORMAL)

out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")
os.makedirs(out, exist_ok=True)
for name, prog in seeds.items():
    with open(os.path.join(out, name), "wb") as f:
        f.write(bytes(b & 0xFF for b in prog))
print(f"{len(seeds)} seeds in {out}")
