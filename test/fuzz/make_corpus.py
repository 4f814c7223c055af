#!/usr/bin/env python3
"""Write the seed corpus of lgn_fuzz (test/fuzz/corpus/): small programs in
the byte language of lgn_fuzz.c (one operation = opcode, object, arguments).
Run from anywhere: python3 test/fuzz/make_corpus.py"""
import os

(CREATE, SETGROUP, SETFNS, CONSTRAINTS, TANGENTS, LINSOL, STEPSIZE, METHOD, INDEX,
 KINEMATICS, TOLERANCES, COUNTS, INITIAL, CONTROL, STEPBOUNDS, STOPTIME, INIT, REINIT,
 SOLVE, SOLVE2, SOLVE3, DKY, GETTERS, FAULT, HEAL, FREE, CALCIC, MISC, JOINTS, BDF, ROOTS,
 KRYLOV, BODIES, GETTERS2) = range(34)
BODY0, BODY3, OSC, JOINTS_MODEL, BODIES_MODEL = range(5)

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

# ---- BDF, GGL, events, Krylov, the body helpers, LGNCalcIC (issue 31) ----
DT_LONG, DT_MID = 250, 220   # Param(): about 0.16 and 0.04


def dky_all(obj):
    """LGNGetDky at the step's end, inside and before the last step, k = -1 ... 6."""
    p = []
    for k in range(-1, 7):
        p += [DKY, obj, ((k + 1) << 3) | (k % 5 if k >= 0 else 0), 4]
    return p


def bdf(obj, maxord, form):
    return [BDF, obj, (maxord + 1) | form << 3 | 0x40]


GETALL = [GETTERS, 0, 0, 4, 4, 4, 4, 4, 4, 4, 4, GETTERS2, 0, 0]
models = [OSC, BODY3, JOINTS_MODEL, BODIES_MODEL, BODY0]
for maxord in range(1, 6):
    for form in range(2):
        for adaptive in range(2):
            model = models[(maxord + form + adaptive) % 5]
            p = create(0, model, adaptive=adaptive, solver=(maxord + adaptive) % 3,
                       n=1 + maxord % 4, tangents=form, modified=adaptive and maxord % 2)
            p += bdf(0, maxord, form) + solve(0, NORMAL, DT_MID) + solve(0) + solve(0)
            p += dky_all(0) + GETALL
            seeds[f"bdf{maxord}_{'fixed_leading' if form else 'variable'}_{'adaptive' if adaptive else 'fixed'}_m{model}"] = p
# GGL with both families (the dense solver of nv + 2m rows), index 2, the kinematics
for model in (BODY3, JOINTS_MODEL, BODIES_MODEL):
    for fam in range(4):
        adaptive = fam % 2
        p = create(0, model, adaptive=adaptive, revolute=fam == 2)
        p += [INDEX, 0, 8]     # GGL with a dense solver of nv + 2m rows
        if fam >= 2:
            p += bdf(0, 2 + fam, fam - 2)
        else:
            p += [KINEMATICS, 0, fam]    # simplified / exact
        p += solve(0, NORMAL, DT_MID) + solve(0) + dky_all(0)[:16] + GETALL
        seeds[f"ggl_m{model}_{['newmark', 'newmark_exact', 'bdf_var', 'bdf_fixed'][fam]}"] = p
    for kin in range(3):
        p = create(0, model, adaptive=kin == 1) + [INDEX, 0, 1, KINEMATICS, 0, kin | (kin << 2) | 0x40]
        p += solve(0, NORMAL, DT_MID) + solve(0) + [CALCIC, 0, 3] + solve(0)
        seeds[f"index2_m{model}_kin{kin}"] = p
# events: a time event, a coordinate and a velocity level, directions,
# LGN_ROOT_RETURN, LGNReInit after an event, g failing
for model in (OSC, BODY3, JOINTS_MODEL, BODIES_MODEL):
    for variant in range(4):
        adaptive = variant != 1
        p = create(0, model, adaptive=adaptive, solver=variant % 3)
        if variant == 2:
            p += bdf(0, 3, 1)
        dirs = [16, 1, 2, 0] if variant == 3 else []
        p += [ROOTS, 0, 4 | (16 if dirs else 0) | 64, 130, variant, 10, model, 3] + dirs[1:]
        p += solve(0, NORMAL, DT_LONG) + [GETTERS2, 0, 0] + solve(0, NORMAL, DT_LONG)
        p += solve(0) + [DKY, 0, 8 | 2, 4, REINIT, 0, 32] + solve(0, NORMAL, DT_LONG) + solve(0)
        seeds[f"roots_m{model}_v{variant}"] = p
    p = create(0, model, adaptive=1) + [ROOTS, 0, 2 | 32, 130, 0, 10, 0, 3, 2, 3]
    p += solve(0, NORMAL, DT_LONG) + solve(0) + [ROOTS, 0, 0x88, 160, 0, 3, 0, 3] + [ROOTS, 0, 1, 160, 0, 3, 0, 3] + solve(0)
    seeds[f"roots_fault_m{model}"] = p
seeds["roots_bad"] = create(0, BODY3) + [ROOTS, 0, 0, 0, 0, 0, 0, 0, ROOTS, 0, 0x90, 0, 0, 0, 0, 0, 1, 1, 1,
                                          ROOTS, 0, 0x13, 160, 0, 3, 0, 3, 5, 5, 3,
                                          ROOTS, 0, 0x13, 160, 0, 3, 0, 3, 0, 1, 2] + solve(0, NORMAL, DT_MID)
# Krylov: SPGMR with the block preconditioner (1 and 2 blocks), SPFGMR with a
# user preconditioner, SPBCGS, SPGMR without a preconditioner
for model in (BODY3, JOINTS_MODEL, BODIES_MODEL):
    for variant in range(6):
        adaptive = variant % 2
        p = create(0, model, adaptive=adaptive)
        s, pp = [(0x10, 2), (0x10, 3 | 64), (0x22, 0), (0x13, 2), (0x01, 0), (0x20 | 0x40 | 0x80, 1)][variant]
        p += [KRYLOV, 0, s, pp] + ([160] if s & 64 else [])
        if variant == 3:
            p += bdf(0, 2, 0)
        p += solve(0, NORMAL, DT_MID) + solve(0) + [GETTERS2, 0, 0]
        seeds[f"krylov_m{model}_v{variant}"] = p
seeds["krylov_bad"] = create(0, JOINTS_MODEL) + [KRYLOV, 0, 0x18, 0, KRYLOV, 0, 0x14, 0x43] + solve(0) + [KRYLOV, 0, 0x10, 7] + solve(0)
# the body and joint helpers: every linear solver, fixed and adaptive, with the driver
for solver in range(3):
    for driver in range(2):
        p = create(0, BODIES_MODEL, adaptive=driver, revolute=driver, solver=solver, modified=solver == 1)
        p += solve(0, NORMAL, DT_MID) + solve(0) + dky_all(0)[:12] + GETALL
        seeds[f"bodies_{solvers[solver]}_{'driver' if driver else 'plain'}"] = p
for cb in range(8):
    p = create(0, BODIES_MODEL, revolute=cb % 2, adaptive=cb % 2) + solve(0)
    p += [FAULT, 0, cb | (cb % 6) << 3, 1] + solve(0) + solve(0) + [HEAL, 0, 0] + solve(0)
    seeds[f"bodies_fault_cb{cb}"] = p
for s in range(5):
    p = create(0, BODIES_MODEL) + [BODIES, 0, s | 16 * s, 10, 2, 3, 0] + [BODIES, 0, 1 | 2 | 8, 0, 3, 2, 1]
    p += create(1, BODY3) + [BODIES, 1, 4, 12, 200, 2, 3, 1] + solve(0)
    seeds[f"bodies_helpers_{s}"] = p
# LGNCalcIC: each option, after a perturbed LGNReInit, and after steps
for model in (BODY3, JOINTS_MODEL, BODIES_MODEL):
    for opt in (1, 2, 3):
        p = create(0, model, revolute=opt == 2) + [INIT, 0, 2 | 4, 0, 10, 1, 10, CALCIC, 0, opt]
        p += [GETTERS, 0, 0, 4, 4, 4, 4, 4, 4, 4] + solve(0) + [CALCIC, 0, opt, INDEX, 0, 1, CALCIC, 0, opt] + solve(0)
        seeds[f"calcic_m{model}_opt{opt}"] = p
# stop times under error control (Newmark and BDF) and with fixed steps
for fam in range(3):
    p = create(0, [BODY3, JOINTS_MODEL, BODIES_MODEL][fam], adaptive=fam != 2)
    if fam == 1:
        p += bdf(0, 4, 0)
    p += [STOPTIME, 0, 1, 150] + solve(0, NORMAL, DT_LONG) + solve(0) + [STOPTIME, 0, 1, 100]
    p += solve(0) + solve(0) + solve(0) + [STOPTIME, 0, 0] + solve(0, NORMAL, DT_MID)
    seeds[f"stop_time_{fam}"] = p
# the Newmark family's settings: kinematics (simplified, exact, sigma), the
# predictor, the Newton mode and the perturbed start
for i in range(12):
    kin, pred, newton, pstart = i % 3, (i // 3) % 2, (i // 6) % 2, (i // 2) % 2
    model = [BODY3, JOINTS_MODEL, BODIES_MODEL, OSC][i % 4]
    p = create(0, model, adaptive=(i // 4) % 2, solver=i % 3)
    p += [KINEMATICS, 0, kin | pred << 2 | newton << 4 | pstart << 6]
    p += solve(0, NORMAL, DT_MID) + solve(0) + [CALCIC, 0, 3] + solve(0) + solve(0)
    seeds[f"settings_{i}"] = p
# BDF over longer spans (order and step changes), tight tolerances, the
# perturbed start, faults in every callback
for form in range(2):
    for model in (BODY3, JOINTS_MODEL, BODIES_MODEL):
        p = create(0, model, adaptive=1, solver=form) + bdf(0, 5, form)
        p += [TOLERANCES, 0, 1, 120, 120, KINEMATICS, 0, 0x40] + solve(0, NORMAL, DT_LONG) + solve(0)
        p += [STOPTIME, 0, 1, 100] + solve(0, NORMAL, DT_LONG) + dky_all(0)
        seeds[f"bdf_long_{'fixed_leading' if form else 'variable'}_m{model}"] = p
for cb in range(8):
    p = create(0, BODIES_MODEL if cb % 2 else BODY3, adaptive=cb < 6, solver=cb % 3) + bdf(0, 1 + cb % 5, cb % 2)
    p += solve(0) + solve(0) + [FAULT, 0, cb | (cb % 6) << 3, 0] + solve(0) + solve(0, NORMAL)
    p += [HEAL, 0, 0] + solve(0) + solve(0)
    seeds[f"bdf_fault_cb{cb}"] = p
# error control's limits: the error test failing at the first step (a large
# initial step, tight tolerances, maxnef 1), repeated convergence failures
# (maxncf 1 and a failing force), hmin, hmax
seeds["adaptive_maxnef"] = create(0, BODY3, adaptive=1) + [STEPBOUNDS, 0, 0, 250, 3, STEPBOUNDS, 0, 3, 100, 3,
                                                           TOLERANCES, 0, 1, 70, 70] + solve(0) + solve(0, NORMAL, DT_LONG)
seeds["adaptive_maxncf"] = create(0, JOINTS_MODEL, adaptive=1) + [STEPBOUNDS, 0, 4, 100, 3, FAULT, 0, 1, 0] + solve(0) + solve(0) + [HEAL, 0, 0] + solve(0)
seeds["adaptive_hmin_hmax"] = create(0, BODIES_MODEL, adaptive=1) + [STEPBOUNDS, 0, 1, 250, 3, STEPBOUNDS, 0, 2, 70, 3,
                                                                  STEPBOUNDS, 0, 5, 100, 3] + solve(0, NORMAL, DT_LONG)
seeds["bdf_maxnef"] = create(0, BODY3, adaptive=1) + bdf(0, 3, 1) + [STEPBOUNDS, 0, 0, 250, 3, STEPBOUNDS, 0, 3, 100, 3,
                                                                     TOLERANCES, 0, 1, 70, 70] + solve(0) + solve(0, NORMAL, DT_LONG)
# the user preconditioner failing in its setup or its solve (+1, -1)
for f in range(4):
    for model in (BODY3, BODIES_MODEL):
        p = create(0, model, adaptive=f % 2) + [KRYLOV, 0, 0x22, 32 | f << 2 | (2 + f % 2)] + solve(0) + solve(0)
        p += solve(0, NORMAL, DT_MID)
        seeds[f"krylov_pfail{f}_m{model}"] = p
# calls out of order and bad arguments to the new functions
seeds["raw_new_calls"] = create(0, BODY3, raw=1) + [CALCIC, 0, 3, ROOTS, 0, 0x13, 160, 0, 3, 0, 3, 1, 1, 1,
                                                    BDF, 0, 3, KRYLOV, 0, 0x10, 2, GETTERS2, 0, 0, DKY, 0, 8, 4]
seeds["krylov_bad_partitions"] = (create(0, BODY3) + [KRYLOV, 0, 0x10, 3] + solve(0) + [KRYLOV, 0, 0x11, 2] + solve(0)
                                  + create(1, JOINTS_MODEL) + [KRYLOV, 1, 0x10, 3 | 64 | 128] + solve(1)
                                  + [KRYLOV, 1, 0x10, 3 | 64 | 4] + solve(1) + [KRYLOV, 1, 0x50, 2, 0, 7] + solve(1))
seeds["krylov_sptfqmr_pcg"] = (create(0, BODY3) + [KRYLOV, 0, 0x00, 16 | 2] + solve(0) + solve(0)
                               + [KRYLOV, 0, 0x01, 16] + solve(0) + [KRYLOV, 0, 0x31, 0x80] + solve(0))
seeds["krylov_ggl_refused"] = create(0, JOINTS_MODEL) + [KRYLOV, 0, 0x10, 2, INDEX, 0, 2] + solve(0) + [CALCIC, 0, 3]
seeds["ggl_sigma_refused"] = create(0, BODY3) + [INDEX, 0, 8, KINEMATICS, 0, 2] + solve(0) + [LINSOL, 0, 0x01, INDEX, 0, 8] + solve(0)
seeds["roots_before_init"] = create(0, OSC, raw=1) + [ROOTS, 0, 0x14, 160, 0, 3, 0, 3, 1, 1, 1, GETTERS2, 0, 0x20]
seeds["dky_outside"] = create(0, BODY3, adaptive=1) + solve(0) + solve(0) + [DKY, 0, 0x84, 4, 10, DKY, 0, 0x8c, 4, 9,
                                                                            DKY, 0, 0x0c, 4, DKY, 0, 0x3c, 4] + bdf(0, 2, 0) + solve(0) + dky_all(0)
seeds["calcic_bad"] = create(0, JOINTS_MODEL) + [KINEMATICS, 0, 0x80, CALCIC, 0, 0, CALCIC, 0, 4, SETFNS, 0, 0, CALCIC, 0, 3,
                                                 SETFNS, 0, 3, CONSTRAINTS, 0, 4, CALCIC, 0, 1]
# the life cycle out of order: no group, non-finite t0, NULL q0, missing
# callbacks, no linear solver, tout behind t, an illegal itask, a stop time
# left behind by LGNReInit, LGNGetConsistentIC(NULL, NULL)
seeds["lifecycle_bad"] = (create(0, BODY3, raw=1) + solve(0) + [CALCIC, 0, 3, INIT, 0, 0, SETGROUP, 0, 0,
                          INIT, 0, 1, 0, INIT, 0, 8, 0, INIT, 0, 0, CALCIC, 0, 3] + solve(0)
                          + [SETFNS, 0, 1] + solve(0) + [SETFNS, 0, 3, CONSTRAINTS, 0, 4, CALCIC, 0, 3] + solve(0)
                          + [CONSTRAINTS, 0, 4 | 8 | 16, CALCIC, 0, 3] + solve(0) + [LINSOL, 0, 0] + solve(0)
                          + [SOLVE, 0, 0x80, 7, SOLVE, 0, 0x0f, 160, STOPTIME, 0, 1, 150, REINIT, 0, 1, 10]
                          + solve(0) + [GETTERS, 0, 0, 4, 4, 4, 4, 4, 0, 0])
seeds["adaptive_bad_tout"] = create(0, OSC, adaptive=1) + solve(0) + [SOLVE, 0, 0x80, 7, STOPTIME, 0, 1, 150,
                                                                     REINIT, 0, 1, 10] + solve(0)
# illegal method parameters (non-finite, alpha_m >= 1, alpha_f >= 1, beta,
# gamma <= 0), rho_inf outside [0, 1], a NULL output
seeds["method_bad"] = (create(0, BODY3) + [METHOD, 0, 2, 0, 3, 160, 160, METHOD, 0, 2, 10, 3, 160, 160,
                       METHOD, 0, 2, 3, 10, 160, 160, METHOD, 0, 2, 3, 3, 7, 7, METHOD, 0, 2, 3, 3, 160, 7, 7,
                       METHOD, 0, 1, 160, 160, METHOD, 0, 0, 7, 7, MISC, 0, 4, 0, MISC, 0, 4, 255,
                       MISC, 0, 12, 100, MISC, 0, 4, 100] + solve(0))
# more of the life cycle: a zero quaternion in q0, a group of other
# dimensions before LGNReInit, no linear solver, vector tolerances, tout
# inside the last step (error control, and BDF's fixed steps past tout)
BEHIND = [SOLVE, 0, 0x80, 11, 0x00, 0x80, 4]   # tout = t - 5e-6
seeds["zero_quaternion"] = create(0, BODIES_MODEL) + [INIT, 0, 2, 3, 3] + solve(0) + [REINIT, 0, 2, 3, 3] + solve(0)
seeds["group_changed"] = create(0, OSC) + solve(0) + [SETGROUP, 0, 2, REINIT, 0, 0] + solve(0) + [SETGROUP, 0, 0, REINIT, 0, 0] + solve(0)
seeds["no_linear_solver"] = create(0, OSC, raw=1) + [SETGROUP, 0, 0, SETFNS, 0, 3, INIT, 0, 0, STEPSIZE, 0, 160] + solve(0) + [CALCIC, 0, 1, LINSOL, 0, 0] + solve(0)
seeds["vector_tolerances"] = create(0, JOINTS_MODEL, adaptive=1) + [TOLERANCES, 0, 0, 120, 120, 0, 4] + solve(0, NORMAL, DT_MID) + solve(0)
seeds["tout_inside_last_step"] = (create(0, BODY3, adaptive=1) + solve(0, NORMAL, DT_MID) + BEHIND + solve(0)
                                  + create(1, BODY3) + bdf(1, 2, 0) + solve(1, NORMAL) + solve(1, NORMAL)
                                  + [SOLVE, 1, 0x80, 11, 0x00, 0x80, 4])

out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")
os.makedirs(out, exist_ok=True)
for name, prog in seeds.items():
    with open(os.path.join(out, name), "wb") as f:
        f.write(bytes(b & 0xFF for b in prog))
print(f"{len(seeds)} seeds in {out}")
