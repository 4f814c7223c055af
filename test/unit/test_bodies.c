/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Unit test of the body helpers (lignum_bodies.h):
 *  1. M, g, K_t and C_t against the hand-written callbacks of the example
 *     model models/rigid_bodies.c (a separate formulation), on
 *     R^3 x SO(3) and SE(3), at random states;
 *  2. on R^3xSO(3) x SE(3) x R^3xSO(3) x SE(3) with full inertia tensors,
 *     for the bodies alone, the translational spring-dampers alone (body -
 *     body of both kinds, body - ground, ground - body), the rotational ones
 *     alone and all together: K_t against central differences of g along
 *     the group (q o exp(e w)), C_t against central differences in v,
 *     g(q, 0) without damping against the differences of the potential
 *     energy, and the sparse M, K_t, C_t (CSC, CSR) against the dense ones;
 *  3. energies under a Lignum run: a free spinning body under gravity
 *     (drift falling as h^2), springs with c = 0 (conserved, drift falling)
 *     and with c > 0 (lost);
 *  4. bad input.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include "models/rigid_bodies.h"
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "rigid_test_util.h"

static int failures = 0;

static void Check(const char *what, double err, double tol)
{
  printf("%-58s %.3e (tol %.1e) %s\n", what, err, tol, err <= tol ? "ok" : "FAIL");
  if (!(err <= tol)) failures++;
}

static double MaxDiff(SUNMatrix A, SUNMatrix B)
{
  sunindextype k;
  double e = 0;
  for (k = 0; k < SM_ROWS_D(A) * SM_COLUMNS_D(A); k++)
    e = fmax(e, fabs(SM_DATA_D(A)[k] - SM_DATA_D(B)[k]));
  return e;
}

static double MaxAbs(SUNMatrix A)
{
  sunindextype k;
  double e = 0;
  for (k = 0; k < SM_ROWS_D(A) * SM_COLUMNS_D(A); k++) e = fmax(e, fabs(SM_DATA_D(A)[k]));
  return e;
}

/* ------------------------------------------------------------------------
 * 1. against rigid_bodies.c
 * --------------------------------------------------------------------- */
static void AgainstExample(SUNContext ctx, RigidFormulation form)
{
  RigidSystem *sys = rigid_create(3, form, ctx);
  RigidCallbacks cb;
  LGNBodies Bd = LGNBodies_Create(sys->G);
  const sunindextype nv = sys->G->nv;
  N_Vector q = N_VClone(sys->q0), v = N_VClone(sys->v0), g1 = N_VClone(sys->v0),
           g2 = N_VClone(sys->v0), lam = N_VNew_Serial(0, ctx), vd = N_VClone(sys->v0);
  SUNMatrix A1 = SUNDenseMatrix(nv, nv, ctx), A2 = SUNDenseMatrix(nv, nv, ctx);
  double eM = 0, eg = 0, eK = 0, eC = 0, sM = 0, sg = 0, sK = 0, sC = 0, eE = 0;
  const double grav[3] = {0.5, -2.0, -9.81};
  int k, trial, i;
  char what[96];
  rigid_get_callbacks(&cb);
  for (k = 0; k < 3; k++) {
    double J[3];
    rigid_set_cylinder(sys, k, 1.0 + 0.5 * k, 2.0 + k, 0.1 + 0.05 * k);
    for (i = 0; i < 3; i++) J[i] = sys->inertia[3 * k + i];
    LGNBodies_SetPrincipalInertia(Bd, k, sys->mass[k], J);
  }
  memcpy(sys->gravity, grav, sizeof grav);
  LGNBodies_SetGravity(Bd, grav);
  N_VConst(0.0, vd);
  for (trial = 0; trial < 10; trial++) {
    double T, V;
    RandomConfiguration(3, N_VGetArrayPointer(q));
    for (i = 0; i < nv; i++) N_VGetArrayPointer(v)[i] = 3 * Rand();
    SUNMatZero(A1); SUNMatZero(A2);
    cb.mass(0.0, q, A1, sys);
    LGNBodies_Mass(Bd, q, A2);
    eM = fmax(eM, MaxDiff(A1, A2)); sM = fmax(sM, MaxAbs(A1));
    cb.force(0.0, q, v, g1, sys);
    LGNBodies_Force(Bd, q, v, g2);
    N_VLinearSum(1.0, g1, -1.0, g2, g2);
    eg = fmax(eg, N_VMaxNorm(g2)); sg = fmax(sg, N_VMaxNorm(g1));
    SUNMatZero(A1); SUNMatZero(A2);
    cb.stiffness(0.0, q, v, vd, lam, A1, sys);
    LGNBodies_Stiffness(Bd, q, v, A2);
    eK = fmax(eK, MaxDiff(A1, A2)); sK = fmax(sK, MaxAbs(A1));
    SUNMatZero(A1); SUNMatZero(A2);
    cb.damping(0.0, q, v, A1, sys);
    LGNBodies_Damping(Bd, q, v, A2);
    eC = fmax(eC, MaxDiff(A1, A2)); sC = fmax(sC, MaxAbs(A1));
    /* energy: rigid_energy uses the R^3 x SO(3) u, the same |U| on SE(3) */
    LGNBodies_Energy(Bd, q, v, &T, &V);
    eE = fmax(eE, fabs(T + V - rigid_energy(sys, q, v)) / fabs(rigid_energy(sys, q, v)));
  }
  printf("%s (scales: M %.1f, g %.1f, K %.1f, C %.1f)\n", form == RB_SE3 ? "SE(3)" : "R^3 x SO(3)",
         sM, sg, sK, sC);
  snprintf(what, sizeof what, "%s: M vs rigid_bodies.c (rel.)", form == RB_SE3 ? "SE(3)" : "R3xSO(3)");
  Check(what, eM / sM, 1e-15);
  snprintf(what, sizeof what, "%s: g vs rigid_bodies.c (rel.)", form == RB_SE3 ? "SE(3)" : "R3xSO(3)");
  Check(what, eg / sg, 1e-15);
  snprintf(what, sizeof what, "%s: K_t vs rigid_bodies.c (rel.)", form == RB_SE3 ? "SE(3)" : "R3xSO(3)");
  Check(what, sK > 0 ? eK / sK : eK, 1e-15);
  snprintf(what, sizeof what, "%s: C_t vs rigid_bodies.c (rel.)", form == RB_SE3 ? "SE(3)" : "R3xSO(3)");
  Check(what, eC / sC, 1e-15);
  snprintf(what, sizeof what, "%s: energy vs rigid_energy (rel.)", form == RB_SE3 ? "SE(3)" : "R3xSO(3)");
  Check(what, eE, 1e-14);
  N_VDestroy(q); N_VDestroy(v); N_VDestroy(g1); N_VDestroy(g2); N_VDestroy(lam); N_VDestroy(vd);
  SUNMatDestroy(A1); SUNMatDestroy(A2);
  LGNBodies_Destroy(&Bd);
  rigid_free(&sys);
}

/* ------------------------------------------------------------------------
 * 2. difference quotients
 * --------------------------------------------------------------------- */
static const double s1[3] = {0.1, -0.2, 0.5}, s2[3] = {-0.3, 0.2, -0.4}, s3[3] = {0.6, 0.1, 0.2};

/* set: 0 bodies only, 1 translational spring-dampers, 2 rotational, 3 all */
static LGNBodies MakeSet(LGNGroup G, int set, double c)
{
  LGNBodies Bd = LGNBodies_Create(G);
  const double grav[3] = {0.3, 1.0, -9.81};
  int k;
  for (k = 0; k < 4; k++) {
    /* a full SPD inertia: A A^T + I */
    double A[9], J[9];
    int i, j, l;
    for (i = 0; i < 9; i++) A[i] = Rand();
    for (i = 0; i < 3; i++)
      for (j = 0; j < 3; j++) {
        J[3 * i + j] = i == j ? 1.0 : 0.0;
        for (l = 0; l < 3; l++) J[3 * i + j] += A[3 * i + l] * A[3 * j + l];
      }
    LGNBodies_SetMass(Bd, k, 1.0 + k, J);
  }
  LGNBodies_SetGravity(Bd, grav);
  if (set == 1 || set == 3) {
    LGNBodies_AddSpringDamper(Bd, 0, s1, 1, s2, 30.0, c, 0.4);         /* R3xSO3 - SE3 */
    LGNBodies_AddSpringDamper(Bd, 1, s2, 3, s3, 20.0, 2 * c, 0.0);     /* SE3 - SE3 */
    LGNBodies_AddSpringDamper(Bd, 2, s3, 0, s1, 10.0, c, 1.5);         /* R3 - R3 */
    LGNBodies_AddSpringDamper(Bd, LGN_GROUND, s3, 3, s1, 15.0, c, 0.3);
    LGNBodies_AddSpringDamper(Bd, 1, s1, LGN_GROUND, s2, 25.0, c, 0.2);
  }
  if (set == 2 || set == 3) {
    /* two with a rest rotation (a's rows and columns through R0) */
    const double rest1[4] = {0.5, 0.5, -0.5, 0.5}, rest2[4] = {0.8, 0.0, 0.6, 0.0};
    LGNBodies_AddRotationalSpringDamper(Bd, 0, 1, 50.0, 5 * c, rest1);
    LGNBodies_AddRotationalSpringDamper(Bd, 3, 2, 70.0, 2.5 * c, NULL);
    LGNBodies_AddRotationalSpringDamper(Bd, LGN_GROUND, 2, 30.0, 5 * c, NULL);
    LGNBodies_AddRotationalSpringDamper(Bd, 3, LGN_GROUND, 40.0, 5 * c, rest2);
  }
  return Bd;
}

static void DifferenceQuotients(SUNContext ctx)
{
  LGNGroup body[2], f4[4], G;
  const char *names[4] = {"bodies (gyroscopic, gravity)", "translational spring-dampers",
                          "rotational spring-dampers", "all"};
  int set;
  body[0] = LGNGroup_R3xSO3();
  body[1] = LGNGroup_SE3();
  f4[0] = body[0]; f4[1] = body[1]; f4[2] = body[0]; f4[3] = body[1];
  G = LGNGroup_Product(4, f4);
  for (set = 0; set < 4; set++) {
    const sunindextype nv = G->nv;
    LGNBodies Bd = MakeSet(G, set, 1.5), B0 = NULL;
    N_Vector q = N_VNew_Serial(G->nq, ctx), qp = N_VClone(q), qm = N_VClone(q),
             v = N_VNew_Serial(nv, ctx), vp = N_VClone(v), gp = N_VClone(v), gm = N_VClone(v),
             z = N_VClone(v);
    SUNMatrix K = SUNDenseMatrix(nv, nv, ctx), C = SUNDenseMatrix(nv, nv, ctx),
              M = SUNDenseMatrix(nv, nv, ctx), S;
    double eK = 0, eC = 0, sK = 0, sC = 0, eS = 0, eV = 0, sV = 0, w[24];
    const double eps = 1e-6;
    sunindextype i, j;
    int trial, fmt;
    char what[96];
    srand(100 + set);
    B0 = MakeSet(G, set, 0.0); /* same inertias (same seed), no damping */
    srand(7);
    for (trial = 0; trial < 4; trial++) {
      RandomConfiguration(4, N_VGetArrayPointer(q));
      for (i = 0; i < nv; i++) N_VGetArrayPointer(v)[i] = 2 * Rand();
      SUNMatZero(K); SUNMatZero(C); SUNMatZero(M);
      if (LGNBodies_Stiffness(Bd, q, v, K) || LGNBodies_Damping(Bd, q, v, C) ||
          LGNBodies_Mass(Bd, q, M))
        failures++;
      sK = fmax(sK, MaxAbs(K));
      sC = fmax(sC, MaxAbs(C));
      for (j = 0; j < nv; j++) {
        for (i = 0; i < nv; i++) w[i] = i == j ? eps : 0.0;
        LGNGroup_ComposeExp(G, N_VGetArrayPointer(q), w, N_VGetArrayPointer(qp));
        for (i = 0; i < nv; i++) w[i] = -w[i];
        LGNGroup_ComposeExp(G, N_VGetArrayPointer(q), w, N_VGetArrayPointer(qm));
        LGNBodies_Force(Bd, qp, v, gp);
        LGNBodies_Force(Bd, qm, v, gm);
        for (i = 0; i < nv; i++)
          eK = fmax(eK, fabs((N_VGetArrayPointer(gp)[i] - N_VGetArrayPointer(gm)[i]) / (2 * eps) -
                             SM_ELEMENT_D(K, i, j)));
        /* C: in v */
        N_VScale(1.0, v, vp);
        N_VGetArrayPointer(vp)[j] += eps;
        LGNBodies_Force(Bd, q, vp, gp);
        N_VGetArrayPointer(vp)[j] -= 2 * eps;
        LGNBodies_Force(Bd, q, vp, gm);
        for (i = 0; i < nv; i++)
          eC = fmax(eC, fabs((N_VGetArrayPointer(gp)[i] - N_VGetArrayPointer(gm)[i]) / (2 * eps) -
                             SM_ELEMENT_D(C, i, j)));
        /* g(q, 0) of the undamped set = dV/dw */
        {
          double Vp, Vm;
          N_VConst(0.0, z);
          LGNBodies_Energy(B0, qp, z, NULL, &Vp);
          LGNBodies_Energy(B0, qm, z, NULL, &Vm);
          LGNBodies_Force(B0, q, z, gp);
          eV = fmax(eV, fabs((Vp - Vm) / (2 * eps) - N_VGetArrayPointer(gp)[j]));
          sV = fmax(sV, fabs(N_VGetArrayPointer(gp)[j]));
        }
      }
      for (fmt = 0; fmt < 2; fmt++) {
        const int type = fmt == 0 ? CSC_MAT : CSR_MAT;
        /* each term into an empty matrix: the helpers add to what a
         * matrix holds (lignum_bodies.h, "Matrices") */
        S = SUNSparseMatrix(nv, nv, 1, type, ctx);
        LGNBodies_Stiffness(Bd, q, v, S);
        eS = fmax(eS, SparseVsDense(S, K));
        if (SUNSparseMatrix_IndexPointers(S)[nv] != LGNBodies_TangentNnz(Bd)) eS = HUGE_VAL;
        SUNMatDestroy(S);
        S = SUNSparseMatrix(nv, nv, 1, type, ctx);
        LGNBodies_Damping(Bd, q, v, S);
        eS = fmax(eS, SparseVsDense(S, C));
        SUNMatDestroy(S);
        S = SUNSparseMatrix(nv, nv, 1, type, ctx);
        LGNBodies_Mass(Bd, q, S);
        eS = fmax(eS, SparseVsDense(S, M));
        if (SUNSparseMatrix_IndexPointers(S)[nv] != LGNBodies_MassNnz(Bd)) eS = HUGE_VAL;
        SUNMatDestroy(S);
      }
    }
    printf("%s: |K| %.1f, |C| %.1f\n", names[set], sK, sC);
    snprintf(what, sizeof what, "K_t vs DQ of g along the group (rel.), %d", set);
    Check(what, eK / sK, 1e-8);
    snprintf(what, sizeof what, "C_t vs DQ of g in v (rel.), %d", set);
    Check(what, eC / sC, 1e-8);
    snprintf(what, sizeof what, "g(q, 0) vs DQ of the potential (rel.), %d", set);
    Check(what, eV / sV, 1e-8);
    snprintf(what, sizeof what, "sparse M, K_t, C_t (CSC, CSR) = dense, %d", set);
    Check(what, eS, 0.0);
    N_VDestroy(q); N_VDestroy(qp); N_VDestroy(qm); N_VDestroy(v); N_VDestroy(vp);
    N_VDestroy(gp); N_VDestroy(gm); N_VDestroy(z);
    SUNMatDestroy(K); SUNMatDestroy(C); SUNMatDestroy(M);
    LGNBodies_Destroy(&Bd);
    LGNBodies_Destroy(&B0);
  }
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body[0]);
  LGNGroup_Destroy(body[1]);
}

/* ------------------------------------------------------------------------
 * 3. energies under Lignum runs (the body set as user data: the callbacks
 *    of lignum_bodies.h as they are)
 * --------------------------------------------------------------------- */

/* max |E(t) - E(0)| over 50 samples of [0, tend], E the total energy */
static double Drift(SUNContext ctx, LGNGroup G, LGNBodies Bd, N_Vector q0, N_Vector v0,
                    double h, double tend, double *Eend, double *E0out)
{
  const sunindextype nv = G->nv;
  N_Vector q = N_VClone(q0), v = N_VClone(v0), tmpl = N_VNew_Serial(nv, ctx);
  SUNMatrix A = SUNDenseMatrix(nv, nv, ctx);
  SUNLinearSolver LS = SUNLinSol_Dense(tmpl, A, ctx);
  void *mem = LGNCreate(ctx);
  double T, V, E0, drift = 0, t = 0;
  int f, n;
  N_VScale(1.0, q0, q);
  N_VScale(1.0, v0, v);
  LGNBodies_Energy(Bd, q, v, &T, &V);
  E0 = T + V;
  f = LGNSetGroup(mem, G);
  if (!f) f = LGNSetUserData(mem, Bd);
  if (!f) f = LGNSetMassFn(mem, LGNBodies_MassFn);
  if (!f) f = LGNSetForceFn(mem, LGNBodies_ForceFn);
  if (!f) f = LGNSetStiffnessFn(mem, LGNBodies_StiffnessFn);
  if (!f) f = LGNSetDampingFn(mem, LGNBodies_DampingFn);
  if (!f) f = LGNInit(mem, 0.0, q, v);
  if (!f) f = LGNSetLinearSolver(mem, LS, A);
  if (!f) f = LGNSetNewmark(mem, 0.25, 0.5);
  if (!f) f = LGNSetStepSize(mem, h);
  for (n = 1; n <= 50 && !f; n++) {
    f = LGNSolve(mem, tend * n / 50, &t, q, v, LGN_NORMAL);
    LGNBodies_Energy(Bd, q, v, &T, &V);
    drift = fmax(drift, fabs(T + V - E0));
  }
  if (f) {
    printf("run failed: flag %d\n", f);
    drift = HUGE_VAL;
  }
  if (Eend) *Eend = T + V;
  if (E0out) *E0out = E0;
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(q); N_VDestroy(v); N_VDestroy(tmpl);
  return drift;
}

static void Energies(SUNContext ctx)
{
  /* a free asymmetric SE(3) body spinning under gravity */
  {
    LGNGroup G = LGNGroup_SE3();
    LGNBodies Bd = LGNBodies_Create(G);
    N_Vector q = N_VNew_Serial(7, ctx), v = N_VNew_Serial(6, ctx);
    const double J[3] = {0.2, 0.5, 0.7}, grav[3] = {0, 0, -9.81};
    const double vv[6] = {1.0, 0.5, 2.0, 3.0, 0.1, 1.0};
    double d[3], E0;
    int i;
    LGNBodies_SetPrincipalInertia(Bd, 0, 1.5, J);
    LGNBodies_SetGravity(Bd, grav);
    LGNGroup_Identity(G, N_VGetArrayPointer(q));
    memcpy(N_VGetArrayPointer(v), vv, sizeof vv);
    for (i = 0; i < 3; i++) d[i] = Drift(ctx, G, Bd, q, v, 0.01 / (1 << i), 2.0, NULL, &E0);
    printf("free body: E0 = %.4f, drift at h = 0.01, 0.005, 0.0025: %.3e %.3e %.3e (ratios %.2f %.2f)\n",
           E0, d[0], d[1], d[2], d[0] / d[1], d[1] / d[2]);
    Check("free body: energy drift at h = 0.0025 (rel.)", d[2] / fabs(E0), 1e-3);
    Check("free body: drift falls as h^2 (|log2 ratio - 2|, worst)",
          fmax(fabs(log2(d[0] / d[1]) - 2), fabs(log2(d[1] / d[2]) - 2)), 0.3);
    N_VDestroy(q); N_VDestroy(v);
    LGNBodies_Destroy(&Bd);
    LGNGroup_Destroy(G);
  }
  /* two bodies on springs: c = 0 conserves, c > 0 loses energy */
  {
    LGNGroup f2[2], G;
    f2[0] = LGNGroup_R3xSO3();
    f2[1] = LGNGroup_SE3();
    G = LGNGroup_Product(2, f2);
    {
      N_Vector q = N_VNew_Serial(14, ctx), v = N_VNew_Serial(12, ctx);
      const double J[3] = {0.3, 0.4, 0.5}, grav[3] = {0, 0, -9.81}, top[3] = {0, 0, 2};
      const double vv[12] = {0.5, 0, 0.2, 1.0, -0.5, 0.3, 0, 0.4, 0, 0.2, 0.7, -0.4};
      double *qd = N_VGetArrayPointer(q), d[2], E0, Eend, dd;
      int damped, i;
      for (damped = 0; damped < 2; damped++) {
        const double c = damped ? 0.5 : 0.0;
        LGNBodies Bd = LGNBodies_Create(G);
        LGNBodies_SetPrincipalInertia(Bd, 0, 1.0, J);
        LGNBodies_SetPrincipalInertia(Bd, 1, 2.0, J);
        LGNBodies_SetGravity(Bd, grav);
        LGNBodies_AddSpringDamper(Bd, LGN_GROUND, top, 0, s1, 100.0, c, 0.5);
        LGNBodies_AddSpringDamper(Bd, 0, s2, 1, s3, 80.0, c, 0.6);
        LGNBodies_AddRotationalSpringDamper(Bd, 0, 1, 2.0, c, NULL);
        LGNBodies_AddRotationalSpringDamper(Bd, LGN_GROUND, 0, 1.0, c, NULL);
        LGNGroup_Identity(G, qd);
        qd[0] = 0.1; qd[1] = 0.0; qd[2] = 1.0;
        qd[7] = 0.3; qd[8] = 0.2; qd[9] = 0.2;
        memcpy(N_VGetArrayPointer(v), vv, sizeof vv);
        if (!damped) {
          for (i = 0; i < 2; i++) d[i] = Drift(ctx, G, Bd, q, v, 0.002 / (1 << i), 2.0, NULL, &E0);
          printf("springs, c = 0: E0 = %.4f, drift at h = 0.002, 0.001: %.3e %.3e (ratio %.2f)\n",
                 E0, d[0], d[1], d[0] / d[1]);
          Check("springs, c = 0: energy drift at h = 0.001 (rel.)", d[1] / fabs(E0), 1e-3);
          Check("springs, c = 0: drift falls as h^2 (|log2 ratio - 2|)", fabs(log2(d[0] / d[1]) - 2), 0.5);
        } else {
          dd = Drift(ctx, G, Bd, q, v, 0.001, 2.0, &Eend, &E0);
          printf("springs, c = 0.5: E0 = %.4f, E(2) = %.4f\n", E0, Eend);
          Check("springs, c = 0.5: energy lost (E(2) - E0 + 1, < 1)", Eend - E0 + 1.0, 1.0 - 1e-3);
          (void)dd;
        }
        LGNBodies_Destroy(&Bd);
      }
      N_VDestroy(q); N_VDestroy(v);
    }
    LGNGroup_Destroy(G);
    LGNGroup_Destroy(f2[0]);
    LGNGroup_Destroy(f2[1]);
  }
}

/* ------------------------------------------------------------------------
 * 4. bad input
 * --------------------------------------------------------------------- */
static int nerr = 0;
static void Count(int code, const char *module, const char *function, const char *msg, void *d)
{
  (void)code; (void)module; (void)d;
  printf("  (expected) %s: %s\n", function, msg);
  nerr++;
}

static void BadInput(SUNContext ctx)
{
  LGNGroup G = LGNGroup_R3xSO3(), Rn = LGNGroup_Rn(3);
  LGNBodies Bd = LGNBodies_Create(G);
  const double nsym[9] = {1, 0.5, 0, 0, 1, 0, 0, 0, 1}, nspd[9] = {1, 2, 0, 2, 1, 0, 0, 0, 1};
  const double Jn[3] = {1, -1, 1}, o[3] = {0, 0, 0}, nan3[3] = {NAN, 0, 0};
  N_Vector q = N_VNew_Serial(7, ctx), v = N_VNew_Serial(6, ctx), g = N_VNew_Serial(6, ctx);
  int bad = 0;
  LGNBodies_SetErrHandlerFn(Bd, Count, NULL);
  bad += LGNBodies_Create(Rn) != NULL;
  bad += LGNBodies_SetMass(Bd, 0, 1.0, nsym) != LGN_ILL_INPUT;
  bad += LGNBodies_SetMass(Bd, 0, 1.0, nspd) != LGN_ILL_INPUT;
  bad += LGNBodies_SetMass(Bd, 1, 1.0, nspd) != LGN_ILL_INPUT;
  bad += LGNBodies_SetPrincipalInertia(Bd, 0, 0.0, Jn) != LGN_ILL_INPUT;
  bad += LGNBodies_SetPrincipalInertia(Bd, 0, 1.0, Jn) != LGN_ILL_INPUT;
  bad += LGNBodies_SetGravity(Bd, nan3) != LGN_ILL_INPUT;
  bad += LGNBodies_AddSpringDamper(Bd, 0, o, 0, o, 1, 0, 0) != LGN_ILL_INPUT;
  bad += LGNBodies_AddSpringDamper(Bd, 0, o, LGN_GROUND, o, -1, 0, 0) != LGN_ILL_INPUT;
  bad += LGNBodies_AddRotationalSpringDamper(Bd, LGN_GROUND, LGN_GROUND, 1, 0, NULL) != LGN_ILL_INPUT;
  {
    const double notunit[4] = {1.0, 0.1, 0.0, 0.0};
    bad += LGNBodies_AddRotationalSpringDamper(Bd, 0, LGN_GROUND, 1, 0, notunit) != LGN_ILL_INPUT;
  }
  /* zero length: the spring's direction is undefined */
  bad += LGNBodies_AddSpringDamper(Bd, 0, o, LGN_GROUND, o, 1, 0, 0) != LGN_SUCCESS;
  LGNGroup_Identity(G, N_VGetArrayPointer(q));
  N_VConst(0.0, v);
  bad += LGNBodies_Force(Bd, q, v, g) != LGN_ILL_INPUT;
  bad += LGNBodies_ForceFn(0.0, q, v, g, Bd) != -1;
  bad += LGNBodies_Force(Bd, v, v, g) != LGN_ILL_INPUT;
  bad += LGNBodies_Mass(Bd, q, NULL) != LGN_ILL_INPUT;
  bad += LGNBodies_Force(NULL, q, v, g) != LGN_ILL_INPUT;
  printf("bad input: %d messages through the handler\n", nerr);
  Check("bad input refused (count of accepted)", bad, 0);
  /* all but LGNBodies_Create(Rn) and B = NULL, which go to stderr */
  Check("messages through the set's handler (14 expected: |n - 14|)", abs(nerr - 14), 0);
  N_VDestroy(q); N_VDestroy(v); N_VDestroy(g);
  LGNBodies_Destroy(&Bd);
  if (Bd != NULL) failures++;
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(Rn);
}

/* The rest rotation means what it says: at R_b = R_a R0 the rotational
 * spring is relaxed (no torque, no energy), and turned by phi about an axis
 * from there its energy is k phi^2 / 2 and the torque on b is -k phi n. */
static void RestRotation(SUNContext ctx)
{
  const double rest[4] = {0.5, 0.5, -0.5, 0.5}, n[3] = {0.6, 0.0, 0.8}, k = 7.0;
  const double Jp[3] = {1, 2, 3}, phi = 0.3;
  LGNGroup body = LGNGroup_R3xSO3(), f2[2], G;
  LGNBodies Bd;
  N_Vector q, v, g;
  double *qd, pb[4], turn[4], err = 0, V;
  int i;
  f2[0] = body;
  f2[1] = body;
  G  = LGNGroup_Product(2, f2);
  Bd = LGNBodies_Create(G);
  LGNBodies_SetPrincipalInertia(Bd, 0, 1.0, Jp);
  LGNBodies_SetPrincipalInertia(Bd, 1, 1.0, Jp);
  LGNBodies_AddRotationalSpringDamper(Bd, 0, 1, k, 0.0, rest);
  q = N_VNew_Serial(G->nq, ctx);
  v = N_VNew_Serial(G->nv, ctx);
  g = N_VNew_Serial(G->nv, ctx);
  qd = N_VGetArrayPointer(q);
  N_VConst(0.0, v);
  RandomConfiguration(2, qd);
  LGNQuaternionMultiply(qd + 3, rest, qd + 10);
  LGNBodies_Force(Bd, q, v, g);
  LGNBodies_Energy(Bd, q, v, NULL, &V);
  err = fmax(N_VMaxNorm(g), fabs(V));
  /* turned by phi about n (b's axes) */
  memcpy(pb, qd + 10, sizeof pb);
  turn[0] = cos(phi / 2);
  for (i = 0; i < 3; i++) turn[1 + i] = sin(phi / 2) * n[i];
  LGNQuaternionMultiply(pb, turn, qd + 10);
  LGNBodies_Force(Bd, q, v, g);
  LGNBodies_Energy(Bd, q, v, NULL, &V);
  err = fmax(err, fabs(V - 0.5 * k * phi * phi));
  for (i = 0; i < 3; i++) err = fmax(err, fabs(NV_Ith_S(g, 9 + i) - k * phi * n[i]));
  Check("rest rotation: relaxed at R_a R0, k phi^2/2 and k phi n when turned", err, 1e-14);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(g);
  LGNBodies_Destroy(&Bd);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
}

int main(void)
{
  SUNContext ctx;
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  srand(42);
  AgainstExample(ctx, RB_R3XSO3);
  AgainstExample(ctx, RB_SE3);
  DifferenceQuotients(ctx);
  Energies(ctx);
  RestRotation(ctx);
  BadInput(ctx);
  SUNContext_Free(&ctx);
  printf("%s\n", failures == 0 ? "PASSED" : "FAILED");
  return failures == 0 ? 0 : 1;
}
