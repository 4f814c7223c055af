/* Restart files (LGNWriteRestart, LGNReadRestart) on a chain of three rods
 * (R^3 x SO(3), spherical joints, m = 9; models/chain.c):
 *
 *  (a) bit for bit: a run stopped after a random number of LGNSolve calls
 *      (LGN_ONE_STEP), written, read into a fresh integrator (LGNCreate,
 *      the same settings, LGNInit with a q0, v0 of zeros and identities)
 *      and continued ends with the same q, v, vdot, a, lambda, t and
 *      counters (memcmp) as the uninterrupted run, for
 *        - the Newmark family: generalized-alpha with simplified, exact and
 *          sigma kinematics, Newmark (beta, gamma) with simplified,
 *        - BDF (maxord 5; fixed and error-controlled steps),
 *        - index 3, index 2 and GGL,
 *        - fixed and error-controlled steps,
 *      and in special states: the perturbed start (written after one step),
 *      root finding (written right after a root return: the rest of the
 *      step is still to be searched), a stop time ahead, LGN_NORMAL output
 *      times (error control: the state is past tout, the output
 *      interpolated), dense KLU instead of dense LU.
 *  (b) refused files leave the integrator as it was (every getter below
 *      equal before and after): a missing file, a file that is not a
 *      restart file, truncated files (header, inside an entry, the last
 *      byte), a flipped byte (CRC-32), another format version (CRC made
 *      right), another model size, another group of the same sizes (SE(3)
 *      for R^3 x SO(3)), other settings (the method parameter, the
 *      constraint index, the step size, the number of root functions), a
 *      mismatching rank count in the header; each with its flag
 *      (LGN_IO_FAIL, LGN_RESTART_BAD_FILE, LGN_RESTART_MISMATCH);
 *      and bad arguments (NULL, empty name, before LGNInit, before the
 *      first step).
 *
 * The random stop: seed LGN_TEST_SEED (environment; default 36), printed. */

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_joints.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#if defined(LGN_HAVE_KLU)
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>
#endif

#include "models/chain.h"
#include "test_util.h"

#define NBODY 3
#define FILE_NAME "test_restart.lgr"

typedef struct {
  const char *name;
  int bdf;          /* maxord (0: the Newmark family)                */
  int newmark;      /* 1: LGNSetNewmark(0.3, 0.55), 0: gen-alpha 0.8 */
  int kinematics;
  int index;
  int adaptive;
  int pstart;       /* LGNSetPerturbedStart                          */
  int roots;        /* a root function                               */
  int tstop;        /* a stop time ahead                             */
  int normal;       /* LGN_NORMAL to output times instead of ONE_STEP */
  int klu;
  int calls;        /* LGNSolve calls in all                         */
} Case;

/* ---- the model's callbacks (the system as user data) ---- */

static RigidCallbacks cbs;
static SUNContext gctx;

static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((RigidSystem *)ud)->joints, t, q, phi) == 0 ? 0 : -1;
}

static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((RigidSystem *)ud)->joints, t, q, B) == 0 ? 0 : -1;
}

/* Events: the height of the last rod's centre crosses -1.2. */
static int Roots(sunrealtype t, N_Vector q, N_Vector v, sunrealtype *g, void *ud)
{
  (void)t;
  (void)v;
  g[0] = N_VGetArrayPointer(q)[7 * (((RigidSystem *)ud)->n - 1) + 2] + 1.2;
  return 0;
}

typedef struct {
  RigidSystem *sys;
  void *mem;
  SUNMatrix A;
  SUNLinearSolver LS;
} Run;

static void FreeRun(Run *r)
{
  LGNFree(&r->mem);
  if (r->LS != NULL) SUNLinSolFree(r->LS);
  if (r->A != NULL) SUNMatDestroy(r->A);
  r->LS = NULL;
  r->A  = NULL;
}

/* An integrator with the case's settings; fresh: LGNInit with zeros and
 * identities instead of the chain's initial state. */
static int MakeRun(Run *r, RigidSystem *sys, const Case *c, int fresh, SUNContext ctx)
{
  const sunindextype nv = sys->G->nv, m = LGNJoints_NumConstraints(sys->joints);
  N_Vector q0 = N_VClone(sys->q0), v0 = N_VClone(sys->v0);
  int flag;
  memset(r, 0, sizeof *r);
  r->sys = sys;
  if (fresh) {
    sunrealtype *q = N_VGetArrayPointer(q0);
    int k;
    N_VConst(0.0, q0);
    N_VConst(0.0, v0);
    for (k = 0; k < sys->n; k++) q[7 * k + 3] = 1.0;
  } else {
    N_VScale(1.0, sys->q0, q0);
    N_VScale(1.0, sys->v0, v0);
  }
  r->mem = LGNCreate(ctx);
  flag   = r->mem == NULL ? -1 : LGNSetGroup(r->mem, sys->G);
  if (!flag) flag = LGNInit(r->mem, 0.0, q0, v0);
  if (!flag) flag = LGNSetUserData(r->mem, sys);
  if (!flag) flag = LGNSetMassFn(r->mem, cbs.mass);
  if (!flag) flag = LGNSetForceFn(r->mem, cbs.force);
  if (!flag) flag = LGNSetMassConstant(r->mem, SUNTRUE);
  if (!flag) flag = LGNSetConstraints(r->mem, m, Constr, ConstrJac);
  {
    /* the iteration matrix: nv + m, or nv + 2 m under GGL (lambda and mu) */
    const sunindextype n = nv + (c->index == LGN_CONSTR_GGL ? 2 * m : m);
    N_Vector y = N_VNew_Serial(n, ctx);
#if defined(LGN_HAVE_KLU)
    if (c->klu) {
      r->A  = SUNSparseMatrix(n, n, 40 * n, CSC_MAT, ctx);
      r->LS = SUNLinSol_KLU(y, r->A, ctx);
    } else
#endif
    {
      r->A  = SUNDenseMatrix(n, n, ctx);
      r->LS = SUNLinSol_Dense(y, r->A, ctx);
    }
    N_VDestroy(y);
  }
  if (!flag) flag = LGNSetConstraintIndex(r->mem, c->index);
  if (!flag) flag = LGNSetLinearSolver(r->mem, r->LS, r->A);
  if (!flag) flag = c->newmark ? LGNSetNewmark(r->mem, 0.3, 0.55) : LGNSetGenAlpha(r->mem, 0.8);
  if (!flag) flag = LGNSetKinematics(r->mem, c->kinematics);
  if (!flag && c->bdf > 0) flag = LGNSetBDF(r->mem, c->bdf);
  if (!flag) flag = LGNSetStepSize(r->mem, 2.0e-3);
  if (!flag) flag = LGNSStolerances(r->mem, 1.0e-6, 1.0e-6);
  if (!flag && c->adaptive) flag = LGNSetStepControl(r->mem, LGN_STEP_ADAPTIVE);
  if (!flag && c->adaptive) flag = LGNSetInitStep(r->mem, 1.0e-3);
  if (!flag && c->pstart) flag = LGNSetPerturbedStart(r->mem, SUNTRUE);
  if (!flag && c->roots) flag = LGNRootInit(r->mem, 1, Roots);
  if (!flag && c->tstop) flag = LGNSetStopTime(r->mem, 0.1234);
  N_VDestroy(q0);
  N_VDestroy(v0);
  return flag;
}

/* What is compared: the state at t_n and the counters. */
typedef struct {
  sunrealtype t, hlast, hcur;
  sunrealtype *q, *v, *vdot, *a, *lambda;
  long int c[12];
  int order;
} Snapshot;

static void Take(Run *r, Snapshot *s)
{
  const sunindextype nq = r->sys->G->nq, nv = r->sys->G->nv;
  const sunindextype m = LGNJoints_NumConstraints(r->sys->joints);
  N_Vector q = N_VNew_Serial(nq, gctx), v = N_VClone(r->sys->v0);
  N_Vector l = N_VNew_Serial(m, gctx);
  N_Vector vd = N_VClone(r->sys->v0), a = N_VClone(r->sys->v0);
  memset(s, 0, sizeof *s);
  /* a getter that refuses (no step yet) leaves zeros */
  N_VConst(0.0, q);
  N_VConst(0.0, v);
  N_VConst(0.0, l);
  N_VConst(0.0, vd);
  N_VConst(0.0, a);
  s->q = calloc((size_t)nq, sizeof(sunrealtype));
  s->v = calloc((size_t)nv, sizeof(sunrealtype));
  s->vdot = calloc((size_t)nv, sizeof(sunrealtype));
  s->a = calloc((size_t)nv, sizeof(sunrealtype));
  s->lambda = calloc((size_t)(m > 0 ? m : 1), sizeof(sunrealtype));
  LGNGetCurrentTime(r->mem, &s->t);
  LGNGetLastStep(r->mem, &s->hlast);
  LGNGetCurrentStep(r->mem, &s->hcur);
  LGNGetCurrentOrder(r->mem, &s->order);
  LGNGetDky(r->mem, s->t, 0, q);
  LGNGetDky(r->mem, s->t, 1, v);
  LGNGetAcceleration(r->mem, vd);
  LGNGetAuxAcceleration(r->mem, a);
  LGNGetMultipliers(r->mem, l);
  memcpy(s->q, N_VGetArrayPointer(q), (size_t)nq * sizeof(sunrealtype));
  memcpy(s->v, N_VGetArrayPointer(v), (size_t)nv * sizeof(sunrealtype));
  memcpy(s->vdot, N_VGetArrayPointer(vd), (size_t)nv * sizeof(sunrealtype));
  memcpy(s->a, N_VGetArrayPointer(a), (size_t)nv * sizeof(sunrealtype));
  memcpy(s->lambda, N_VGetArrayPointer(l), (size_t)m * sizeof(sunrealtype));
  LGNGetNumSteps(r->mem, &s->c[0]);
  LGNGetNumNewtonIters(r->mem, &s->c[1]);
  LGNGetNumNewtonConvFails(r->mem, &s->c[2]);
  LGNGetNumStepFails(r->mem, &s->c[3]);
  LGNGetNumResEvals(r->mem, &s->c[4]);
  LGNGetNumDQEvals(r->mem, &s->c[5]);
  LGNGetNumJacEvals(r->mem, &s->c[6]);
  LGNGetNumErrTestFails(r->mem, &s->c[7]);
  LGNGetNumGEvals(r->mem, &s->c[8]);
  LGNGetNumLinSolvSetups(r->mem, &s->c[9]);
  LGNGetNumLinSolves(r->mem, &s->c[10]);
  LGNGetNumNewtonStalls(r->mem, &s->c[11]);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(l);
  N_VDestroy(vd);
  N_VDestroy(a);
}

static int Same(const Snapshot *x, const Snapshot *y, sunindextype nq, sunindextype nv,
                sunindextype m)
{
  return memcmp(&x->t, &y->t, sizeof x->t) == 0 &&
         memcmp(&x->hlast, &y->hlast, sizeof x->hlast) == 0 &&
         memcmp(&x->hcur, &y->hcur, sizeof x->hcur) == 0 && x->order == y->order &&
         memcmp(x->q, y->q, (size_t)nq * sizeof(sunrealtype)) == 0 &&
         memcmp(x->v, y->v, (size_t)nv * sizeof(sunrealtype)) == 0 &&
         memcmp(x->vdot, y->vdot, (size_t)nv * sizeof(sunrealtype)) == 0 &&
         memcmp(x->a, y->a, (size_t)nv * sizeof(sunrealtype)) == 0 &&
         memcmp(x->lambda, y->lambda, (size_t)m * sizeof(sunrealtype)) == 0 &&
         memcmp(x->c, y->c, sizeof x->c) == 0;
}

static void Drop(Snapshot *s)
{
  free(s->q);
  free(s->v);
  free(s->vdot);
  free(s->a);
  free(s->lambda);
}

/* LGNSolve call number k of a run: one step, or to the next output time. */
static int Advance(Run *r, const Case *c, int k, long int *roots)
{
  sunrealtype t;
  N_Vector q = N_VClone(r->sys->q0), v = N_VClone(r->sys->v0);
  const sunrealtype tout = c->normal ? 0.01 * (k + 1) : 10.0;
  int flag = LGNSolve(r->mem, tout, &t, q, v, c->normal ? LGN_NORMAL : LGN_ONE_STEP);
  if (flag == LGN_ROOT_RETURN) (*roots)++;
  N_VDestroy(q);
  N_VDestroy(v);
  return flag < 0 ? flag : 0;
}

static unsigned int seed_state;
static int RandomStop(int calls)
{
  seed_state = seed_state * 1103515245u + 12345u;
  return 1 + (int)((seed_state >> 8) % (unsigned)(calls - 2));
}

/* (a) for one case. */
static void BitForBit(RigidSystem *sys, const Case *c, SUNContext ctx)
{
  const sunindextype nq = sys->G->nq, nv = sys->G->nv;
  const sunindextype m = LGNJoints_NumConstraints(sys->joints);
  const int stop = c->pstart ? 1 : RandomStop(c->calls);
  Run ref, w, cont;
  Snapshot sref, scont;
  long int rref = 0, rw = 0, rcont = 0;
  int k, flag = 0, fr = 0;

  /* the uninterrupted run */
  fr = MakeRun(&ref, sys, c, 0, ctx);
  for (k = 0; k < c->calls && !fr; k++) fr = Advance(&ref, c, k, &rref);
  CHECK(fr == 0, "%s: the uninterrupted run failed (%d)", c->name, fr);
  /* the run that stops and writes */
  flag = MakeRun(&w, sys, c, 0, ctx);
  for (k = 0; k < stop && !flag; k++) flag = Advance(&w, c, k, &rw);
  if (c->roots) {
    /* go on to the first root return, then write there */
    for (; k < c->calls - 1 && !flag && rw == 0; k++) flag = Advance(&w, c, k, &rw);
  }
  if (!flag) flag = LGNWriteRestart(w.mem, FILE_NAME);
  CHECK(flag == 0, "%s: the run stopped after %d calls could not write (%d)", c->name, k, flag);
  FreeRun(&w);
  /* the continued run */
  flag = MakeRun(&cont, sys, c, 1, ctx);
  if (!flag) flag = LGNReadRestart(cont.mem, FILE_NAME);
  CHECK(flag == 0, "%s: LGNReadRestart failed (%d)", c->name, flag);
  rcont = rw;
  for (; k < c->calls && !flag; k++) flag = Advance(&cont, c, k, &rcont);
  CHECK(flag == 0, "%s: the continued run failed (%d)", c->name, flag);
  if (fr == 0 && flag == 0) {
    Take(&ref, &sref);
    Take(&cont, &scont);
    if (c->klu) {
      /* KLU: the continued run factors afresh where the uninterrupted one
       * refactors with the pivots of its first factorisation (not in the
       * file): equal to round-off, the same steps */
      double dq = 0.0, dl = 0.0;
      sunindextype i;
      for (i = 0; i < nq; i++) dq = fmax(dq, fabs(sref.q[i] - scont.q[i]));
      for (i = 0; i < m; i++) dl = fmax(dl, fabs(sref.lambda[i] - scont.lambda[i]));
      CHECK(sref.c[0] == scont.c[0] && dq < 1e-9 && dl < 1e-6,
            "%s: the continued run differs beyond round-off: steps %ld / %ld, |dq| %.3g, "
            "|dlambda| %.3g", c->name, sref.c[0], scont.c[0], dq, dl);
      printf("%-44s written after call %3d of %d: %ld steps, |dq| = %.2g, |dlambda| = %.2g "
             "(KLU: round-off)\n", c->name, stop, c->calls, sref.c[0], dq, dl);
    } else
    CHECK(Same(&sref, &scont, nq, nv, m),
          "%s: the continued run (written after call %d) differs from the uninterrupted "
          "one: t %.17g / %.17g, steps %ld / %ld, q0 %.17g / %.17g, lambda0 %.17g / %.17g",
          c->name, stop, sref.t, scont.t, sref.c[0], scont.c[0], sref.q[0], scont.q[0],
          sref.lambda[0], scont.lambda[0]);
    CHECK(rref == rcont, "%s: %ld root returns uninterrupted, %ld with the restart", c->name,
          rref, rcont);
    if (c->roots) CHECK(rref > 0, "%s: no root found: the case tests nothing", c->name);
    if (!c->klu)
    printf("%-44s written after call %3d of %d: t = %.6f, %ld steps, order %d: %s\n",
           c->name, stop, c->calls, sref.t, sref.c[0], sref.order,
           Same(&sref, &scont, nq, nv, m) ? "equal bit for bit" : "DIFFERENT");
    Drop(&sref);
    Drop(&scont);
  }
  FreeRun(&ref);
  FreeRun(&cont);
}

/* ---- (b) refused files ---- */

static unsigned char *Slurp(const char *name, size_t *len)
{
  FILE *fp = fopen(name, "rb");
  unsigned char *p;
  long n;
  if (fp == NULL) return NULL;
  fseek(fp, 0, SEEK_END);
  n = ftell(fp);
  fseek(fp, 0, SEEK_SET);
  p = malloc((size_t)n);
  if (p != NULL && fread(p, 1, (size_t)n, fp) != (size_t)n) {
    free(p);
    p = NULL;
  }
  fclose(fp);
  *len = (size_t)n;
  return p;
}

static void Spit(const char *name, const unsigned char *p, size_t len)
{
  FILE *fp = fopen(name, "wb");
  if (fp == NULL) return;
  fwrite(p, 1, len, fp);
  fclose(fp);
}

/* The file's CRC-32 made right after an edit (so that a later check is
 * reached): the same polynomial as the library's. */
static void FixCrc(unsigned char *p, size_t len)
{
  uint32_t crc = 0xFFFFFFFFu;
  size_t i;
  int k;
  for (i = 0; i + 4 < len; i++) {
    crc ^= p[i];
    for (k = 0; k < 8; k++) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  crc = ~crc;
  memcpy(p + len - 4, &crc, 4);
}

/* Expect LGNReadRestart of this file to fail with want, leaving the
 * integrator's outputs as they were. */
static void Refused(Run *r, const char *name, int want, const char *what)
{
  Snapshot before, after;
  const sunindextype nq = r->sys->G->nq, nv = r->sys->G->nv;
  const sunindextype m = LGNJoints_NumConstraints(r->sys->joints);
  int flag;
  Take(r, &before);
  flag = LGNReadRestart(r->mem, name);
  Take(r, &after);
  CHECK(flag == want, "%s: LGNReadRestart returned %s, expected %s", what,
        LGNGetReturnFlagName(flag), LGNGetReturnFlagName(want));
  CHECK(Same(&before, &after, nq, nv, m), "%s: the refused file changed the integrator "
        "(t %g / %g, h %g / %g, steps %ld / %ld, q0 %g / %g)", what, before.t, after.t,
        before.hcur, after.hcur, before.c[0], after.c[0], before.q[0], after.q[0]);
  Drop(&before);
  Drop(&after);
}

static void ErrHandler(int code, const char *module, const char *function, const char *msg,
                       void *data)
{
  (void)code;
  (void)module;
  (void)data;
  printf("    [%s] %s\n", function, msg);
}

static void RefusedFiles(RigidSystem *sys, SUNContext ctx)
{
  const Case c = {"refused", 0, 0, LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX3, 0, 0, 0, 0,
                  0, 0, 10};
  Case other = c;
  Run w, r;
  unsigned char *img, *bad;
  size_t len = 0;
  long int roots = 0;
  int k, flag;
  RigidSystem *se3 = chain_create(NBODY, RB_SE3, ctx);
  RigidSystem *longer = chain_create(NBODY + 1, RB_R3XSO3, ctx);

  flag = MakeRun(&w, sys, &c, 0, ctx);
  /* bad arguments, and nothing to write before the first step */
  CHECK(LGNWriteRestart(NULL, FILE_NAME) == LGN_MEM_NULL, "write: mem NULL");
  CHECK(LGNReadRestart(NULL, FILE_NAME) == LGN_MEM_NULL, "read: mem NULL");
  CHECK(LGNWriteRestart(w.mem, FILE_NAME) == LGN_ILL_INPUT, "write before the first step");
  for (k = 0; k < 5 && !flag; k++) flag = Advance(&w, &c, k, &roots);
  CHECK(LGNWriteRestart(w.mem, NULL) == LGN_ILL_INPUT, "write: filename NULL");
  CHECK(LGNWriteRestart(w.mem, "") == LGN_ILL_INPUT, "write: filename empty");
  CHECK(LGNWriteRestart(w.mem, "/nonexistent-dir/x.lgr") == LGN_IO_FAIL,
        "write into a missing directory");
  if (!flag) flag = LGNWriteRestart(w.mem, FILE_NAME);
  CHECK(flag == 0, "write (%d)", flag);
  {
    void *bare = LGNCreate(ctx);
    CHECK(LGNReadRestart(bare, FILE_NAME) == LGN_NO_MALLOC, "read before LGNInit");
    LGNFree(&bare);
  }
  img = Slurp(FILE_NAME, &len);
  CHECK(img != NULL && len > 200, "the file was read back (%zu bytes)", len);
  if (img == NULL) return;
  bad = malloc(len);

  /* the integrator that refuses: run a few steps of its own, so that
   * "unchanged" is not trivially the initial state */
  flag = MakeRun(&r, sys, &c, 0, ctx);
  LGNSetErrHandlerFn(r.mem, ErrHandler, NULL);
  for (k = 0; k < 3 && !flag; k++) flag = Advance(&r, &c, k, &roots);
  CHECK(LGNReadRestart(r.mem, NULL) == LGN_ILL_INPUT, "read: filename NULL");
  CHECK(LGNReadRestart(r.mem, "") == LGN_ILL_INPUT, "read: filename empty");
  Refused(&r, "no-such-file.lgr", LGN_IO_FAIL, "missing file");
  memcpy(bad, img, len);
  memcpy(bad, "NOTLIGNU", 8);
  Spit("bad.lgr", bad, len);
  Refused(&r, "bad.lgr", LGN_RESTART_BAD_FILE, "no magic");
  Spit("bad.lgr", img, 50);
  Refused(&r, "bad.lgr", LGN_RESTART_BAD_FILE, "truncated in the header");
  Spit("bad.lgr", img, len / 2);
  Refused(&r, "bad.lgr", LGN_RESTART_BAD_FILE, "truncated in the middle");
  Spit("bad.lgr", img, len - 1);
  Refused(&r, "bad.lgr", LGN_RESTART_BAD_FILE, "truncated by one byte");
  memcpy(bad, img, len);
  bad[len / 2] ^= 0x10;
  Spit("bad.lgr", bad, len);
  Refused(&r, "bad.lgr", LGN_RESTART_BAD_FILE, "one bit flipped (CRC-32)");
  memcpy(bad, img, len);
  bad[8] = 99; /* version */
  FixCrc(bad, len);
  Spit("bad.lgr", bad, len);
  Refused(&r, "bad.lgr", LGN_RESTART_BAD_FILE, "another format version");
  memcpy(bad, img, len);
  bad[12] = 0x01; /* the byte order marker reversed */
  bad[13] = 0x02;
  bad[14] = 0x03;
  bad[15] = 0x04;
  FixCrc(bad, len);
  Spit("bad.lgr", bad, len);
  Refused(&r, "bad.lgr", LGN_RESTART_BAD_FILE, "the other byte order");
  memcpy(bad, img, len);
  bad[60] = 2; /* written by 2 ranks */
  FixCrc(bad, len);
  Spit("bad.lgr", bad, len);
  Refused(&r, "bad.lgr", LGN_RESTART_MISMATCH, "written on 2 ranks");
  Spit("good.lgr", img, len);
  FreeRun(&r);

  /* another problem: sizes, group, settings */
  flag = MakeRun(&r, longer, &c, 1, ctx);
  LGNSetErrHandlerFn(r.mem, ErrHandler, NULL);
  Refused(&r, "good.lgr", LGN_RESTART_MISMATCH, "a chain of 4 rods");
  FreeRun(&r);
  flag = MakeRun(&r, se3, &c, 1, ctx);
  LGNSetErrHandlerFn(r.mem, ErrHandler, NULL);
  Refused(&r, "good.lgr", LGN_RESTART_MISMATCH, "SE(3) instead of R^3 x SO(3)");
  FreeRun(&r);
  other.newmark = 1;
  flag = MakeRun(&r, sys, &other, 1, ctx);
  LGNSetErrHandlerFn(r.mem, ErrHandler, NULL);
  Refused(&r, "good.lgr", LGN_RESTART_MISMATCH, "Newmark instead of generalized-alpha");
  FreeRun(&r);
  other = c;
  other.index = LGN_CONSTR_INDEX2;
  flag = MakeRun(&r, sys, &other, 1, ctx);
  LGNSetErrHandlerFn(r.mem, ErrHandler, NULL);
  Refused(&r, "good.lgr", LGN_RESTART_MISMATCH, "index 2 instead of 3");
  FreeRun(&r);
  other = c;
  other.roots = 1;
  flag = MakeRun(&r, sys, &other, 1, ctx);
  LGNSetErrHandlerFn(r.mem, ErrHandler, NULL);
  Refused(&r, "good.lgr", LGN_RESTART_MISMATCH, "a root function more");
  FreeRun(&r);
  flag = MakeRun(&r, sys, &c, 1, ctx);
  LGNSetErrHandlerFn(r.mem, ErrHandler, NULL);
  if (!flag) flag = LGNSetStepSize(r.mem, 1.0e-3);
  Refused(&r, "good.lgr", LGN_RESTART_MISMATCH, "another step size");
  /* ... and the right file is then accepted by the same integrator */
  if (!flag) flag = LGNSetStepSize(r.mem, 2.0e-3);
  CHECK(LGNReadRestart(r.mem, "good.lgr") == LGN_SUCCESS, "the good file after refusals");
  FreeRun(&r);
  FreeRun(&w);
  free(bad);
  free(img);
  remove("bad.lgr");
  remove("good.lgr");
  rigid_free(&se3);
  rigid_free(&longer);
}

int main(void)
{
  const char *env = getenv("LGN_TEST_SEED");
  SUNContext ctx;
  RigidSystem *sys;
  const int S = LGN_KINEMATICS_SIMPLIFIED, E = LGN_KINEMATICS_EXACT,
            G = LGN_KINEMATICS_SIGMA;
  const int I3 = LGN_CONSTR_INDEX3, I2 = LGN_CONSTR_INDEX2, GGL = LGN_CONSTR_GGL;
  const Case cases[] = {
    /* name                               bdf nm kin idx ad ps rt ts no klu calls */
    {"gen-alpha simplified, index 3, fixed", 0, 0, S, I3, 0, 0, 0, 0, 0, 0, 40},
    {"gen-alpha exact, index 3, fixed",      0, 0, E, I3, 0, 0, 0, 0, 0, 0, 40},
    {"gen-alpha sigma, index 3, fixed",      0, 0, G, I3, 0, 0, 0, 0, 0, 0, 40},
    {"Newmark simplified, index 3, fixed",   0, 1, S, I3, 0, 0, 0, 0, 0, 0, 40},
    {"gen-alpha simplified, index 2, fixed", 0, 0, S, I2, 0, 0, 0, 0, 0, 0, 40},
    {"gen-alpha exact, GGL, fixed",          0, 0, E, GGL, 0, 0, 0, 0, 0, 0, 40},
    {"gen-alpha simplified, index 3, adaptive", 0, 0, S, I3, 1, 0, 0, 0, 0, 0, 40},
    {"gen-alpha exact, index 2, adaptive",   0, 0, E, I2, 1, 0, 0, 0, 0, 0, 40},
    {"gen-alpha simplified, GGL, adaptive",  0, 0, S, GGL, 1, 0, 0, 0, 0, 0, 40},
    {"BDF, index 3, fixed",                  5, 0, S, I3, 0, 0, 0, 0, 0, 0, 40},
    {"BDF, index 2, fixed",                  5, 0, S, I2, 0, 0, 0, 0, 0, 0, 40},
    {"BDF, index 3, adaptive",               5, 0, S, I3, 1, 0, 0, 0, 0, 0, 60},
    {"BDF, index 2, adaptive",               5, 0, S, I2, 1, 0, 0, 0, 0, 0, 60},
    {"BDF, GGL, adaptive",                   5, 0, S, GGL, 1, 0, 0, 0, 0, 0, 60},
    {"gen-alpha, perturbed start",           0, 0, S, I3, 0, 1, 0, 0, 0, 0, 20},
    {"gen-alpha, adaptive, at a root",       0, 0, S, I3, 1, 0, 1, 0, 0, 0, 200},
    {"BDF, adaptive, at a root",             5, 0, S, I3, 1, 0, 1, 0, 0, 0, 300},
    {"gen-alpha, adaptive, stop time ahead", 0, 0, S, I3, 1, 0, 0, 1, 0, 0, 60},
    {"gen-alpha, adaptive, LGN_NORMAL",      0, 0, E, I3, 1, 0, 0, 0, 1, 0, 20},
    {"BDF, adaptive, LGN_NORMAL",            5, 0, S, I2, 1, 0, 0, 0, 1, 0, 20},
#if defined(LGN_HAVE_KLU)
    {"gen-alpha, index 3, KLU",              0, 0, S, I3, 0, 0, 0, 0, 0, 1, 40},
    {"BDF, adaptive, KLU",                   5, 0, S, I3, 1, 0, 0, 0, 0, 1, 60},
#endif
  };
  size_t i;
  seed_state = env != NULL ? (unsigned int)strtoul(env, NULL, 10) : 36u;
  printf("seed %u (LGN_TEST_SEED)\n", seed_state);
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  gctx = ctx;
  rigid_get_callbacks(&cbs);
  sys = chain_create(NBODY, RB_R3XSO3, ctx);
  for (i = 0; i < sizeof cases / sizeof cases[0]; i++) BitForBit(sys, &cases[i], ctx);
  RefusedFiles(sys, ctx);
  remove(FILE_NAME);
  rigid_free(&sys);
  SUNContext_Free(&ctx);
  return test_summary("test_restart");
}
