/* -----------------------------------------------------------------------------
 * Lignum study tool: the data of the manual's pictures (scripts/figures).
 *
 *   chain_movie [--n 6] [--t-end 4] [--tol 1e-6] [--fps 25] [--prefix chain_movie]
 *
 * The spherical-joint chain of models/chain.c with n rods, released
 * from rest, integrated with error control (rtol = atol = tol) by
 * generalized-alpha (rho_inf = 0.9) and by BDF (orders 1-5), both at index
 * 3 with KLU-free dense LU. Each accepted step is taken with LGN_ONE_STEP;
 * the outputs at fps frames per second come from the dense output
 * (LGNGetDky) inside the steps. Writes
 *   PREFIX_frames.dat   BDF run: one gnuplot data block per frame (index
 *                       = frame number): x and z of the support and of each
 *                       rod's lower end (the side view)
 *   PREFIX_outputs.csv  method, t, energy, energy - energy(0), max |Phi|
 *   PREFIX_steps.csv    method, t, h, order (every accepted step)
 * and prints a summary. The gnuplot scripts chain_movie.gp (GIF) and
 * chain_plots.gp (energy, constraint drift, step size and order) draw them.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_joints.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "models/chain.h"

static RigidCallbacks cbs;

static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((RigidSystem *)ud)->joints, t, q, phi) == 0 ? 0 : -1;
}

static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((RigidSystem *)ud)->joints, t, q, B) == 0 ? 0 : -1;
}

/* The +z end of rod k: its centre plus half its axis (body z). */
static void LowerEnd(const sunrealtype *q, int k, double out[3])
{
  sunrealtype R[9];
  int i;
  LGNQuaternionToRotation(q + 7 * k + 3, R);
  for (i = 0; i < 3; i++) out[i] = q[7 * k + i] + 0.5 * R[3 * i + 2];
}

/* Which end of a rod is its lower one, +z or -z of the body: rod 0 hangs
 * from the origin, so its lower end is the one farther from it. */
static double Sign(const sunrealtype *q)
{
  double e[3];
  LowerEnd(q, 0, e);
  return e[0] * e[0] + e[1] * e[1] + e[2] * e[2] > q[0] * q[0] + q[1] * q[1] + q[2] * q[2]
             ? 1.0
             : -1.0;
}

static int Run(RigidSystem *sys, int bdf, double tend, double tol, int fps, FILE *frames,
               FILE *outputs, FILE *steps)
{
  const char *name = bdf ? "BDF" : "gen-alpha";
  const sunindextype nv = sys->G->nv, m = LGNJoints_NumConstraints(sys->joints);
  N_Vector q = N_VClone(sys->q0), v = N_VClone(sys->v0), qo = N_VClone(sys->q0),
           vo = N_VClone(sys->v0), phi, y;
  SUNContext ctx = NULL;
  SUNMatrix A;
  SUNLinearSolver LS;
  void *mem;
  double e0 = 0.0, s = 1.0, maxphi = 0.0, maxde = 0.0;
  sunrealtype t = 0.0, tprev;
  long int nst = 0;
  int flag = 0, frame = 0, order = 0, k, i;

  SUNContext_Create(NULL, &ctx);
  phi = N_VNew_Serial(m, ctx);
  y   = N_VNew_Serial(nv + m, ctx);
  A   = SUNDenseMatrix(nv + m, nv + m, ctx);
  LS  = SUNLinSol_Dense(y, A, ctx);
  mem = LGNCreate(ctx);
  flag = LGNSetGroup(mem, sys->G);
  if (!flag) flag = LGNInit(mem, 0.0, sys->q0, sys->v0);
  if (!flag) flag = LGNSetUserData(mem, sys);
  if (!flag) flag = LGNSetMassFn(mem, cbs.mass);
  if (!flag) flag = LGNSetForceFn(mem, cbs.force);
  if (!flag) flag = LGNSetMassConstant(mem, SUNTRUE);
  if (!flag) flag = LGNSetConstraints(mem, m, Constr, ConstrJac);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = bdf ? LGNSetBDF(mem, 5) : LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
  if (!flag) flag = LGNSStolerances(mem, tol, tol);
  if (!flag) flag = LGNSetInitStep(mem, 1e-4);
  if (!flag) flag = LGNSetStopTime(mem, tend);
  e0 = rigid_energy(sys, sys->q0, sys->v0);
  s  = Sign(N_VGetArrayPointer(sys->q0));
  while (!flag && t < tend) {
    tprev = t;
    flag  = LGNSolve(mem, tend, &t, q, v, LGN_ONE_STEP);
    if (flag == LGN_TSTOP_RETURN) flag = 0;
    if (flag) break;
    LGNGetLastOrder(mem, &order);
    {
      sunrealtype h;
      LGNGetLastStep(mem, &h);
      fprintf(steps, "%s,%.9g,%.6e,%d\n", name, (double)t, (double)h, bdf ? order : 2);
    }
    /* the outputs inside (tprev, t] */
    for (; frame <= (int)floor(tend * fps + 0.5) && (double)frame / fps <= t + 1e-12; frame++) {
      const sunrealtype tf = (sunrealtype)frame / fps;
      const sunrealtype *qd;
      double e, pmax = 0.0, end[3];
      if (tf < tprev - 1e-12) continue;
      if (LGNGetDky(mem, tf, 0, qo) != 0 || LGNGetDky(mem, tf, 1, vo) != 0) {
        N_VScale(1.0, q, qo);
        N_VScale(1.0, v, vo);
      }
      qd = N_VGetArrayPointer(qo);
      e  = rigid_energy(sys, qo, vo);
      LGNJoints_Residual(sys->joints, tf, qo, phi);
      for (i = 0; i < m; i++) pmax = fmax(pmax, fabs(N_VGetArrayPointer(phi)[i]));
      maxphi = fmax(maxphi, pmax);
      maxde  = fmax(maxde, fabs(e - e0));
      fprintf(outputs, "%s,%.6f,%.12g,%.6e,%.6e\n", name, (double)tf, e, e - e0, pmax);
      if (frames != NULL) { /* one gnuplot data block per frame */
        fprintf(frames, "%s# frame %d t = %.4f\n0 0\n", frame > 0 ? "\n\n" : "", frame,
                (double)tf);
        for (k = 0; k < sys->n; k++) {
          LowerEnd(qd, k, end);
          for (i = 0; i < 3; i++) end[i] = qd[7 * k + i] + s * (end[i] - qd[7 * k + i]);
          fprintf(frames, "%.5f %.5f\n", end[0], end[2]);
        }
      }
    }
  }
  LGNGetNumSteps(mem, &nst);
  printf("%-10s %6ld steps, max |E - E0| = %.3e J, max |Phi| = %.3e m%s%s\n", name, nst,
         maxde, maxphi, flag ? ", failed: " : "", flag ? LGNGetReturnFlagName(flag) : "");
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(y);
  N_VDestroy(phi);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(qo);
  N_VDestroy(vo);
  SUNContext_Free(&ctx);
  return flag;
}

int main(int argc, char **argv)
{
  int n = 6, fps = 25, i, flag;
  double tend = 4.0, tol = 1e-6;
  const char *prefix = "chain_movie";
  char name[512];
  FILE *frames, *outputs, *steps;
  SUNContext ctx;
  RigidSystem *sys;
  for (i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--n") && i + 1 < argc) n = atoi(argv[++i]);
    else if (!strcmp(argv[i], "--t-end") && i + 1 < argc) tend = atof(argv[++i]);
    else if (!strcmp(argv[i], "--tol") && i + 1 < argc) tol = atof(argv[++i]);
    else if (!strcmp(argv[i], "--fps") && i + 1 < argc) fps = atoi(argv[++i]);
    else if (!strcmp(argv[i], "--prefix") && i + 1 < argc) prefix = argv[++i];
    else {
      fprintf(stderr, "usage: chain_movie [--n 6] [--t-end 4] [--tol 1e-6] [--fps 25] "
                      "[--prefix chain_movie]\n");
      return 2;
    }
  }
  if (n < 1 || fps < 1 || !(tend > 0.0) || !(tol > 0.0)) return 2;
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  rigid_get_callbacks(&cbs);
  sys = chain_create(n, RB_R3XSO3, ctx);
  snprintf(name, sizeof name, "%s_frames.dat", prefix);
  frames = fopen(name, "w");
  snprintf(name, sizeof name, "%s_outputs.csv", prefix);
  outputs = fopen(name, "w");
  snprintf(name, sizeof name, "%s_steps.csv", prefix);
  steps = fopen(name, "w");
  if (frames == NULL || outputs == NULL || steps == NULL) return 1;
  fprintf(outputs, "method,t,energy,energy_change,max_phi\n");
  fprintf(steps, "method,t,h,order\n");
  printf("chain of %d rods, %g s, rtol = atol = %g\n", n, tend, tol);
  flag = Run(sys, 0, tend, tol, fps, NULL, outputs, steps);
  if (!flag) flag = Run(sys, 1, tend, tol, fps, frames, outputs, steps);
  fclose(frames);
  fclose(outputs);
  fclose(steps);
  rigid_free(&sys);
  SUNContext_Free(&ctx);
  return flag ? 1 : 0;
}
