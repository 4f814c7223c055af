/* -----------------------------------------------------------------------------
 * Lignum fuzz target (libFuzzer): the input bytes are a program, a sequence
 * of public API calls with parameters read from the bytes (NaN, Inf,
 * negative, huge, tiny values, NULLs, vectors and matrices of the wrong
 * size, calls out of order), on up to two integrator objects of small
 * models:
 *   - a heavy body on R^3 x SO(3), free (m = 0) or pinned (m = 3), with
 *     every callback of the API (mass, force, constraint, Jacobian,
 *     stiffness, damping, curvature, constraint force),
 *   - an oscillator on R^n (n = 1..4) with analytic stiffness and damping,
 *   - two bodies on (R^3 x SO(3))^2 held by the joint helpers (a spherical
 *     joint to the ground, a spherical or revolute joint between them),
 *   - two bodies on R^3 x SO(3) x SE(3) built by the body helpers (mass,
 *     inertia, gravity, a spring-damper to the ground, a rotational one
 *     between them) and the joint helpers (a revolute joint to the ground,
 *     optionally driven (rheonomic, Phi_t), a spherical joint between them),
 * with the Newmark family (every kinematics, predictor, Newton mode) or BDF
 * (maxord 1-5, both forms), at index 3, 2 or GGL, with fixed steps or error
 * control, events (root functions, directions, a faulty g), dense or KLU
 * (CSC, CSR) linear solvers or matrix-free Krylov solvers (SPGMR, SPFGMR,
 * SPBCGS, SPTFQMR, PCG) with the block or a user preconditioner, and
 * callbacks whose fault is chosen by the input (return +1 or -1, or write
 * NaN, +-Inf or 1e308 into one entry, at the k-th call from now; the root
 * function and the preconditioner have their own).
 *
 * Invariants (abort() on a violation, so that libFuzzer reports it):
 *   - every call that fails returns a negative flag with a name
 *     (LGNGetReturnFlagName is not "NONE"); with a NULL memory block the
 *     flag is LGN_MEM_NULL; setters and getters return no positive flag;
 *   - a successful LGNSolve returns a finite tret, q and v; LGN_ONE_STEP
 *     advanced the current time (or, after a root, returned the end of that
 *     step), LGN_NORMAL returned at tout; LGN_TSTOP_RETURN only with a stop
 *     time set; under error control no step passes an accepted stop time;
 *   - LGN_ROOT_RETURN only with root functions, at a finite tret inside the
 *     last step and not beyond tout, with finite q, v; LGNGetRootInfo
 *     reports a root, each in a direction that was asked for;
 *   - a successful LGNGetDky has a vector of the right length and a finite
 *     result; at the step's end (k = 0) it is the state there;
 *   - a failed LGNSolve that took no step leaves the state as it was, bit
 *     for bit: current time, number of steps, vdot, lambda, the auxiliary
 *     acceleration, and the q, v it returns equal the last state returned;
 *     one that took steps (LGN_NORMAL) returns the last accepted state
 *     (tret = the current time, finite q and v);
 *   - a restart file read back into the integrator that wrote it changes
 *     none of those outputs; with a byte flipped it is refused with
 *     LGN_RESTART_BAD_FILE and changes nothing either;
 *   - after a fault is removed an object that was set up sanely (the preset
 *     of Create, untouched by setters since) takes the next step.
 *   - LGNGenAlphaFromRhoInf succeeds exactly for rho_inf in [0, 1] with
 *     every output given, with gamma = 1/2 + alpha_f - alpha_m; the body
 *     helpers refuse exactly a non-finite gravity, refuse a q or v of the
 *     wrong length, and their energies are finite for sane parameters.
 * Sanitizers (ASan, UBSan, LeakSanitizer) come with the build.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#define _POSIX_C_SOURCE 200809L /* fileno, dup, dup2 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_config.h>
#include <lignum/lignum_group.h>
#include <lignum/lignum_joints.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_pcg.h>
#include <sunlinsol/sunlinsol_spbcgs.h>
#include <sunlinsol/sunlinsol_spfgmr.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunlinsol/sunlinsol_sptfqmr.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>
#if defined(LGN_HAVE_KLU)
#include <sunlinsol/sunlinsol_klu.h>
#endif

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* ---------------------------------------------------------------------------
 * Invariant violations
 * -------------------------------------------------------------------------*/
#define REQUIRE(cond, ...)                                                     \
  do {                                                                         \
    if (!(cond)) {                                                             \
      fprintf(stderr, "lgn_fuzz: invariant violated (%s:%d): ", __FILE__,      \
              __LINE__);                                                       \
      fprintf(stderr, __VA_ARGS__);                                            \
      fputc('\n', stderr);                                                     \
      abort();                                                                 \
    }                                                                          \
  } while (0)

/* ---------------------------------------------------------------------------
 * The input
 * -------------------------------------------------------------------------*/
typedef struct {
  const uint8_t *d;
  size_t n, i;
} In;

static unsigned U8(In *in) { return in->i < in->n ? in->d[in->i++] : 0u; }
static unsigned U16(In *in) { return U8(in) | (U8(in) << 8); }

/* Any real: specials and ordinary values of all magnitudes. */
static double Real(In *in)
{
  const unsigned s = U8(in);
  switch (s % 20) {
  case 0: return NAN;
  case 1: return INFINITY;
  case 2: return -INFINITY;
  case 3: return 0.0;
  case 4: return -0.0;
  case 5: return 5e-324;
  case 6: return 1e-300;
  case 7: return -1.0;
  case 8: return 1e300;
  case 9: return -1e300;
  case 10: return 1.0;
  default: {
    const double mant = (double)U16(in) / 65535.0;
    const int e = (int)(U8(in) % 13) - 9; /* 1e-9 .. 1e3 */
    return ((s & 1) ? -1.0 : 1.0) * mant * pow(10.0, e);
  }
  }
}

/* Mostly a sane positive value around `typical`, sometimes any real. */
static double Param(In *in, double typical)
{
  const unsigned s = U8(in);
  if (s < 64) return Real(in);
  return typical * pow(10.0, ((double)(s - 64) / 191.0) * 4.0 - 2.0);
}

/* ---------------------------------------------------------------------------
 * Models and faulty callbacks
 * -------------------------------------------------------------------------*/
enum { MOD_BODY0, MOD_BODY3, MOD_OSC, MOD_JOINTS, MOD_BODIES, NMOD };
enum { CB_MASS, CB_FORCE, CB_CONSTR, CB_JAC, CB_STIFF, CB_DAMP, CB_CURV, CB_CFORCE, NCB };
enum { F_RET_POS, F_RET_NEG, F_NAN, F_PINF, F_NINF, F_HUGE, NFAULT };

typedef struct {
  int used;
  int model;
  sunindextype nq, nv, m, n_osc;
  void *mem;
  int freed; /* LGNFree called: mem is NULL */
  LGNGroup G, factors[2];
  LGNJoints J;
  SUNMatrix A;
  SUNLinearSolver LS;
  int solver; /* 0 dense, 1 KLU CSC, 2 KLU CSR, 3.. Krylov (no matrix) */
  LGNBodies B;    /* MOD_BODIES: the body set (mass, forces, springs) */
  SUNMatrix Md;   /* MOD_BODIES: a dense nv x nv scratch for the helpers */
  int driver;     /* MOD_BODIES: a rotation driver (rheonomic, Phi_t) */
#define MAXOLD 6
  SUNMatrix oldA[MAXOLD];
  SUNLinearSolver oldLS[MAXOLD];
  int nold;
  N_Vector q, v, q0, v0, qbad, vbad, tmp, nvv, mv;
  /* fault */
  int fault_cb, fault_kind;
  long fault_at;
  long ncalls[NCB];
  int fault_fired;
  /* the harness's knowledge */
  int sane;        /* preset, untouched by setters since */
  int init_done;   /* LGNInit succeeded once */
  int stop_set;    /* a stop time was accepted */
  int adaptive;    /* step control is adaptive (as far as known) */
  int known;       /* q, v of the state at the current time are known */
  double kq[14], kv[12];
  int nsolves;
  int huge_m; /* m = 2^40 was passed to LGNSetConstraints (finding 2) */
  int nonfinite_start; /* LGNInit / LGNReInit accepted NaN or Inf (finding 3) */
  int own_klu; /* LGNSetOwnKLUSolves was accepted once (finding 4) */
  int vdot0_set; /* LGNSetInitialAcceleration accepted, not yet stepped (finding 5) */
  /* events */
  int nrt;                 /* root functions of the accepted LGNRootInit */
  int rootdir[3];          /* directions accepted by LGNSetRootDirection */
  double rt_time, rt_q, rt_v; /* g = (t - rt_time, q_k - rt_q, v_j - rt_v) */
  int rt_k, rt_j;
  int rt_fault_kind;       /* a fault of g (kind + 1, 0 none) at call rt_fault_at */
  long rt_calls, rt_fault_at;
  /* stop time, checked under error control */
  double tstop;
  int tstop_check;
  int root_returned; /* the last LGNSolve returned LGN_ROOT_RETURN */
  /* a fault of the user preconditioner: 0 none, 1 (2) its setup returns +1
   * (-1), 3 (4) its solve, at call pc_fault_at of that function */
  int pc_fault;
  long pc_setups, pc_solves, pc_fault_at;
} Obj;

static const double MASS = 2.0, JB[3] = {0.3, 0.5, 0.7}, XP[3] = {0.0, 0.0, 0.4};
#define GRAV 9.81

/* The fault of callback cb at this call: 0 none, else the kind + 1. */
static int Fault(Obj *o, int cb)
{
  o->ncalls[cb]++;
  if (o->fault_cb == cb && o->ncalls[cb] == o->fault_at) {
    o->fault_fired = 1;
    return o->fault_kind + 1;
  }
  return 0;
}

static double FaultValue(int kind)
{
  switch (kind) {
  case F_NAN: return NAN;
  case F_PINF: return INFINITY;
  case F_NINF: return -INFINITY;
  default: return 1e308;
  }
}

/* Apply fault f (from Fault) to entry k of x (length n); the return value
 * of the callback. */
static int ApplyVec(int f, double *x, sunindextype n, sunindextype k)
{
  if (!f) return 0;
  f--;
  if (f == F_RET_POS) return 1;
  if (f == F_RET_NEG) return -1;
  if (n > 0) x[k % n] = FaultValue(f);
  return 0;
}

static int ApplyMat(int f, SUNMatrix A)
{
  if (!f) return 0;
  f--;
  if (f == F_RET_POS) return 1;
  if (f == F_RET_NEG) return -1;
  if (SUNMatGetID(A) == SUNMATRIX_DENSE) {
    if (SM_ROWS_D(A) > 0 && SM_COLUMNS_D(A) > 0) SM_ELEMENT_D(A, 0, 0) = FaultValue(f);
  } else {
    const sunindextype np = SUNSparseMatrix_NP(A);
    if (SUNSparseMatrix_IndexPointers(A)[np] > 0) SUNSparseMatrix_Data(A)[0] = FaultValue(f);
  }
  return 0;
}

/* Write a dense rows x cols matrix D (column-major, nonzero pattern P) into
 * A, dense or sparse; -1 if A has other dimensions (the integrator passed a
 * matrix that does not fit this model: a callback failure, not a bug). */
static int Store(SUNMatrix A, const double *D, const int *P, sunindextype rows,
                 sunindextype cols)
{
  sunindextype i, j, k = 0;
  if (A == NULL) return -1;
  if (SUNMatGetID(A) == SUNMATRIX_DENSE) {
    if (SM_ROWS_D(A) != rows || SM_COLUMNS_D(A) != cols) return -1;
    for (j = 0; j < cols; j++)
      for (i = 0; i < rows; i++) SM_ELEMENT_D(A, i, j) = D[i + j * rows];
    return 0;
  }
  if (SUNMatGetID(A) != SUNMATRIX_SPARSE) return -1;
  if (SUNSparseMatrix_Rows(A) != rows || SUNSparseMatrix_Columns(A) != cols) return -1;
  {
    const int csc = SUNSparseMatrix_SparseType(A) == CSC_MAT;
    const sunindextype np = csc ? cols : rows, ni = csc ? rows : cols;
    sunindextype *ptr, *ind, p;
    double *val;
    if (SUNSparseMatrix_NNZ(A) < rows * cols && SUNSparseMatrix_Reallocate(A, rows * cols) != 0)
      return -1;
    ptr = SUNSparseMatrix_IndexPointers(A);
    ind = SUNSparseMatrix_IndexValues(A);
    val = SUNSparseMatrix_Data(A);
    for (p = 0; p < np; p++) {
      ptr[p] = k;
      for (i = 0; i < ni; i++) {
        const sunindextype r = csc ? i : p, c = csc ? p : i;
        if (!P[r + c * rows]) continue;
        ind[k]   = i;
        val[k++] = D[r + c * rows];
      }
    }
    ptr[np] = k;
  }
  return 0;
}

static int LenOk(N_Vector x, sunindextype n) { return x != NULL && N_VGetLength(x) == n; }

static void Rotation(const double *p, double R[9]) { LGNQuaternionToRotation(p, R); }

/* --- heavy body(ies) on R^3 x SO(3): body b's slice of q (7) and v (6) --- */
static void BodyForce(const double *v, double *g)
{
  const double *W = v + 3;
  g[0] = g[1] = 0.0;
  g[2]        = MASS * GRAV;
  g[3]        = W[1] * JB[2] * W[2] - W[2] * JB[1] * W[1];
  g[4]        = W[2] * JB[0] * W[0] - W[0] * JB[2] * W[2];
  g[5]        = W[0] * JB[1] * W[1] - W[1] * JB[0] * W[0];
}

/* MOD_BODIES: the helpers write the dense scratch Md (zeroed first, as
 * their dense forms add); D gets it with a full pattern. */
static void FromScratch(const Obj *o, double *D, int *P)
{
  sunindextype i, j, nv = o->nv;
  for (j = 0; j < nv; j++)
    for (i = 0; i < nv; i++) {
      D[i + nv * j] = SM_ELEMENT_D(o->Md, i, j);
      P[i + nv * j] = 1;
    }
}

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  Obj *o = ud;
  double D[144] = {0};
  int P[144] = {0};
  sunindextype i, nv = o->nv;
  (void)t;
  if (o->model == MOD_BODIES) {
    SUNMatZero(o->Md);
    if (!LenOk(q, o->nq) || LGNBodies_Mass(o->B, q, o->Md) != 0) return -1;
    FromScratch(o, D, P);
  } else
  for (i = 0; i < nv; i++) {
    if (o->model == MOD_OSC) D[i + nv * i] = 1.0 + (double)i;
    else D[i + nv * i] = (i % 6) < 3 ? MASS : JB[i % 6 - 3];
    P[i + nv * i] = 1;
  }
  {
    const int f = Fault(o, CB_MASS);
    const int r = Store(M, D, P, nv, nv);
    return r ? r : ApplyMat(f, M);
  }
}

static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  Obj *o = ud;
  sunindextype i;
  double *gg;
  if (!LenOk(q, o->nq) || !LenOk(v, o->nv) || !LenOk(g, o->nv)) return -1;
  gg = N_VGetArrayPointer(g);
  (void)t;
  if (o->model == MOD_OSC) {
    const double *x = N_VGetArrayPointer(q), *u = N_VGetArrayPointer(v);
    for (i = 0; i < o->nv; i++) gg[i] = (4.0 + (double)i) * x[i] + 0.1 * u[i];
  } else if (o->model == MOD_BODIES) {
    if (LGNBodies_Force(o->B, q, v, g) != 0) return -1;
  } else {
    for (i = 0; i < o->nv / 6; i++) BodyForce(N_VGetArrayPointer(v) + 6 * i, gg + 6 * i);
  }
  return ApplyVec(Fault(o, CB_FORCE), gg, o->nv, 4);
}

static int Phi(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  Obj *o = ud;
  if (!LenOk(q, o->nq) || !LenOk(phi, o->m)) return -1;
  if (o->J != NULL) {
    if (LGNJoints_Residual(o->J, t, q, phi) != 0) return -1;
  } else if (o->model == MOD_BODY3) {
    const double *x = N_VGetArrayPointer(q);
    double R[9], *f = N_VGetArrayPointer(phi);
    int i;
    Rotation(x + 3, R);
    for (i = 0; i < 3; i++)
      f[i] = x[i] + R[3 * i] * XP[0] + R[3 * i + 1] * XP[1] + R[3 * i + 2] * XP[2];
  } else {
    return -1;
  }
  return ApplyVec(Fault(o, CB_CONSTR), N_VGetArrayPointer(phi), o->m, 1);
}

static int Jac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  Obj *o = ud;
  if (!LenOk(q, o->nq)) return -1;
  if (o->J != NULL) {
    if (LGNJoints_Jacobian(o->J, t, q, B) != 0) return -1;
  } else if (o->model == MOD_BODY3) {
    const double S[9] = {0.0, -XP[2], XP[1], XP[2], 0.0, -XP[0], -XP[1], XP[0], 0.0};
    double R[9], D[18] = {0};
    int P[18], i, j, k;
    Rotation(N_VGetArrayPointer(q) + 3, R);
    for (i = 0; i < 3; i++) {
      D[i + 3 * i] = 1.0;
      for (j = 0; j < 3; j++) {
        double rs = 0.0;
        for (k = 0; k < 3; k++) rs += R[3 * i + k] * S[3 * k + j];
        D[i + 3 * (3 + j)] = -rs;
      }
    }
    for (i = 0; i < 18; i++) P[i] = 1;
    if (Store(B, D, P, 3, 6) != 0) return -1;
  } else {
    return -1;
  }
  return ApplyMat(Fault(o, CB_JAC), B);
}

/* K_t, C_t: block-diagonal approximations (body), exact (oscillator) */
static int Stiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot, N_Vector lambda,
                     SUNMatrix K, void *ud)
{
  Obj *o = ud;
  double D[144] = {0};
  int P[144] = {0};
  sunindextype i, nv = o->nv;
  (void)vdot;
  if (o->model == MOD_BODIES) {
    /* the bodies' K_t plus the joints' geometric stiffness d/dq(B^T lambda) */
    SUNMatZero(o->Md);
    if (!LenOk(q, o->nq) || !LenOk(v, nv) || !LenOk(lambda, o->m) ||
        LGNBodies_Stiffness(o->B, q, v, o->Md) != 0 ||
        LGNJoints_Stiffness(o->J, t, q, lambda, o->Md) != 0)
      return -1;
    FromScratch(o, D, P);
  } else
  for (i = 0; i < nv; i++) {
    if (o->model == MOD_OSC) D[i + nv * i] = 4.0 + (double)i;
    P[i + nv * i] = 1;
  }
  {
    const int f = Fault(o, CB_STIFF);
    const int r = Store(K, D, P, nv, nv);
    return r ? r : ApplyMat(f, K);
  }
}

static int Damping(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  Obj *o = ud;
  double D[144] = {0};
  int P[144] = {0};
  sunindextype i, nv = o->nv;
  (void)t;
  if (!LenOk(v, nv)) return -1;
  if (o->model == MOD_BODIES) {
    SUNMatZero(o->Md);
    if (!LenOk(q, o->nq) || LGNBodies_Damping(o->B, q, v, o->Md) != 0) return -1;
    FromScratch(o, D, P);
  } else
  for (i = 0; i < nv; i++) {
    if (o->model == MOD_OSC) D[i + nv * i] = 0.1;
    P[i + nv * i] = 1;
  }
  if (o->model != MOD_OSC && o->model != MOD_BODIES) {
    sunindextype b;
    for (b = 0; b < nv / 6; b++) {
      const double *W = N_VGetArrayPointer(v) + 6 * b + 3;
      const double JW[3]  = {JB[0] * W[0], JB[1] * W[1], JB[2] * W[2]};
      const double Wt[9]  = {0, -W[2], W[1], W[2], 0, -W[0], -W[1], W[0], 0};
      const double JWt[9] = {0, -JW[2], JW[1], JW[2], 0, -JW[0], -JW[1], JW[0], 0};
      int r, c;
      for (r = 0; r < 3; r++)
        for (c = 0; c < 3; c++) {
          const sunindextype ii = 6 * b + 3 + r, jj = 6 * b + 3 + c;
          D[ii + nv * jj] = Wt[3 * r + c] * JB[c] - JWt[3 * r + c];
          P[ii + nv * jj] = 1;
        }
    }
  }
  {
    const int f = Fault(o, CB_DAMP);
    const int r = Store(C, D, P, nv, nv);
    return r ? r : ApplyMat(f, C);
  }
}

static int Curvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  Obj *o = ud;
  if (!LenOk(q, o->nq) || !LenOk(v, o->nv) || !LenOk(z, o->m)) return -1;
  if (o->J != NULL) {
    if (LGNJoints_Curvature(o->J, t, q, v, z) != 0) return -1;
  } else if (o->model == MOD_BODY3) {
    const double *W = N_VGetArrayPointer(v) + 3;
    double R[9], a[3], b[3], *zz = N_VGetArrayPointer(z);
    int i;
    Rotation(N_VGetArrayPointer(q) + 3, R);
    a[0] = XP[1] * W[2] - XP[2] * W[1];
    a[1] = XP[2] * W[0] - XP[0] * W[2];
    a[2] = XP[0] * W[1] - XP[1] * W[0];
    b[0] = W[1] * a[2] - W[2] * a[1];
    b[1] = W[2] * a[0] - W[0] * a[2];
    b[2] = W[0] * a[1] - W[1] * a[0];
    for (i = 0; i < 3; i++)
      zz[i] = -(R[3 * i] * b[0] + R[3 * i + 1] * b[1] + R[3 * i + 2] * b[2]);
  } else {
    return -1;
  }
  return ApplyVec(Fault(o, CB_CURV), N_VGetArrayPointer(z), o->m, 2);
}

static int ConstraintForce(sunrealtype t, N_Vector q, N_Vector lambda, N_Vector f, void *ud)
{
  Obj *o = ud;
  if (!LenOk(q, o->nq) || !LenOk(lambda, o->m) || !LenOk(f, o->nv)) return -1;
  if (o->J != NULL) {
    if (LGNJoints_ConstraintForce(o->J, t, q, lambda, f) != 0) return -1;
  } else if (o->model == MOD_BODY3) {
    const double *l = N_VGetArrayPointer(lambda);
    double R[9], rl[3], *ff = N_VGetArrayPointer(f);
    int i;
    Rotation(N_VGetArrayPointer(q) + 3, R);
    for (i = 0; i < 3; i++) rl[i] = R[i] * l[0] + R[3 + i] * l[1] + R[6 + i] * l[2];
    for (i = 0; i < 3; i++) ff[i] = l[i];
    ff[3] = XP[1] * rl[2] - XP[2] * rl[1];
    ff[4] = XP[2] * rl[0] - XP[0] * rl[2];
    ff[5] = XP[0] * rl[1] - XP[1] * rl[0];
  } else {
    return -1;
  }
  return ApplyVec(Fault(o, CB_CFORCE), N_VGetArrayPointer(f), o->nv, 5);
}

/* Phi_t of the rheonomic model (MOD_BODIES with its rotation driver); the
 * constraint fault applies to it as well. */
static int PhiT(sunrealtype t, N_Vector q, N_Vector phit, void *ud)
{
  Obj *o = ud;
  if (o->J == NULL || !LenOk(q, o->nq) || !LenOk(phit, o->m)) return -1;
  if (LGNJoints_TimeDerivative(o->J, t, q, phit) != 0) return -1;
  return ApplyVec(Fault(o, CB_CONSTR), N_VGetArrayPointer(phit), o->m, 0);
}

/* The driver's law: the angle 2 t (body 0 starts turning at 2 rad/s). */
static int Drive(sunrealtype t, sunrealtype f[3], void *data)
{
  (void)data;
  f[0] = 2.0 * t;
  f[1] = 2.0;
  f[2] = 0.0;
  return 0;
}

/* Root functions: a time event, a coordinate and a velocity crossing a
 * level; the fault chosen by OP_ROOTS (return +-1, or NaN, +-Inf, 1e308
 * in g_0). */
static int Roots(sunrealtype t, N_Vector q, N_Vector v, sunrealtype *g, void *ud)
{
  Obj *o = ud;
  if (!LenOk(q, o->nq) || !LenOk(v, o->nv) || g == NULL) return -1;
  g[0] = t - o->rt_time;
  if (o->nrt > 1) g[1] = N_VGetArrayPointer(q)[o->rt_k % o->nq] - o->rt_q;
  if (o->nrt > 2) g[2] = N_VGetArrayPointer(v)[o->rt_j % o->nv] - o->rt_v;
  o->rt_calls++;
  if (o->rt_fault_kind && o->rt_calls == o->rt_fault_at)
    return ApplyVec(o->rt_fault_kind, g, o->nrt, 0);
  return 0;
}

/* A consistent initial state of the model. */
static void InitialState(Obj *o, double *x, double *u)
{
  memset(x, 0, (size_t)o->nq * sizeof(double));
  memset(u, 0, (size_t)o->nv * sizeof(double));
  if (o->model == MOD_OSC) {
    sunindextype i;
    for (i = 0; i < o->nv; i++) x[i] = 1.0 / (1.0 + (double)i);
  } else if (o->model == MOD_BODIES) {
    /* body 0 at the origin turning about z at 2 rad/s (the revolute joint
     * to the ground and the driver's 2 t), body 1 (SE(3)) hanging 1 below
     * from a spherical joint, turning at -1 rad/s: every point of the
     * joints at rest */
    x[3] = 1.0; u[5] = 2.0;
    x[9] = -1.0; x[10] = 1.0; u[11] = -1.0;
  } else if (o->model == MOD_JOINTS) {
    /* a vertical chain spinning about its axis */
    x[2] = -0.5; x[3] = 1.0; u[5] = 3.0;
    x[9] = -1.5; x[10] = 1.0; u[11] = -2.0;
  } else {
    const double psi0[3] = {0.3, -0.2, 0.5}, W0[3] = {1.0, -2.0, 8.0};
    double R[9], c[3];
    int i;
    LGNQuaternionFromRotationVector(psi0, x + 3);
    if (o->model == MOD_BODY0) {
      for (i = 0; i < 3; i++) u[3 + i] = W0[i];
      return;
    }
    Rotation(x + 3, R);
    c[0] = W0[1] * XP[2] - W0[2] * XP[1];
    c[1] = W0[2] * XP[0] - W0[0] * XP[2];
    c[2] = W0[0] * XP[1] - W0[1] * XP[0];
    for (i = 0; i < 3; i++) {
      x[i]     = -(R[3 * i] * XP[0] + R[3 * i + 1] * XP[1] + R[3 * i + 2] * XP[2]);
      u[i]     = -(R[3 * i] * c[0] + R[3 * i + 1] * c[1] + R[3 * i + 2] * c[2]);
      u[3 + i] = W0[i];
    }
  }
}

/* ---------------------------------------------------------------------------
 * Flags
 * -------------------------------------------------------------------------*/
static int CheckFlag(const Obj *o, int flag, const char *call)
{
  if (o->mem == NULL)
    REQUIRE(flag == LGN_MEM_NULL, "%s with a NULL memory returned %d", call, flag);
  REQUIRE(flag <= 0, "%s returned the positive flag %d", call, flag);
  if (flag < 0)
    REQUIRE(strcmp(LGNGetReturnFlagName(flag), "NONE") != 0,
            "%s returned %d, which has no name", call, flag);
  return flag;
}

/* ---------------------------------------------------------------------------
 * Objects
 * -------------------------------------------------------------------------*/
static SUNContext ctx;
static LGNGroup spare_group; /* a group of other dimensions, alive all input */
static FILE *devnull;
static int null_fd = -1;
static int trace; /* LGN_FUZZ_TRACE=1: the operations on stderr */
/* Bounded work per input: at most 24 LGNSolve calls per object and 200
 * steps in all (a program of long solves on the 12-dof models took 10 s,
 * libFuzzer's timeout, on a loaded machine). */
#define MAX_STEPS_PER_INPUT 200
static long steps_left;

/* Linear solvers replaced by MakeSolver stay alive until the object is
 * destroyed: the integrator may still refer to them (LGNSetLinearSolver
 * may have refused the new one). */
static void ObjFreeSolver(Obj *o)
{
  int i;
  if (o->LS) SUNLinSolFree(o->LS);
  if (o->A) SUNMatDestroy(o->A);
  o->LS = NULL;
  o->A  = NULL;
  for (i = 0; i < o->nold; i++) {
    SUNLinSolFree(o->oldLS[i]);
    if (o->oldA[i]) SUNMatDestroy(o->oldA[i]);
  }
  o->nold = 0;
}

static void ObjDestroy(Obj *o)
{
  if (!o->used) return;
  LGNFree(&o->mem);
  ObjFreeSolver(o);
  N_VDestroy(o->q); N_VDestroy(o->v); N_VDestroy(o->q0); N_VDestroy(o->v0);
  N_VDestroy(o->qbad); N_VDestroy(o->vbad); N_VDestroy(o->tmp); N_VDestroy(o->nvv);
  if (o->mv) N_VDestroy(o->mv);
  LGNJoints_Destroy(&o->J);
  LGNBodies_Destroy(&o->B);
  if (o->Md) SUNMatDestroy(o->Md);
  LGNGroup_Destroy(o->G);
  LGNGroup_Destroy(o->factors[0]);
  LGNGroup_Destroy(o->factors[1]);
  memset(o, 0, sizeof *o);
}

/* (Re)make the linear solver: kind 0 dense, 1 KLU CSC, 2 KLU CSR; the
 * matrix-free Krylov solvers (A = NULL) 3 SPGMR left-preconditioned, 4 SPGMR
 * without a preconditioner, 5 SPFGMR right-preconditioned, 6 SPBCGS left,
 * 7 SPTFQMR left, 8 PCG (refused: A is indefinite); size n. */
static void MakeSolver(Obj *o, int kind, sunindextype n)
{
  N_Vector t;
  if (o->LS) {
    if (o->nold == MAXOLD) return; /* keep the current one */
    o->oldLS[o->nold] = o->LS;
    o->oldA[o->nold++] = o->A;
    o->LS = NULL;
    o->A  = NULL;
  }
  if (n < 1) n = 1;
  t = N_VNew_Serial(n, ctx);
  if (kind >= 3) {
    o->A = NULL;
    if (kind == 3) o->LS = SUNLinSol_SPGMR(t, SUN_PREC_LEFT, 20, ctx);
    else if (kind == 4) o->LS = SUNLinSol_SPGMR(t, SUN_PREC_NONE, 20, ctx);
    else if (kind == 5) o->LS = SUNLinSol_SPFGMR(t, SUN_PREC_RIGHT, 20, ctx);
    else if (kind == 6) o->LS = SUNLinSol_SPBCGS(t, SUN_PREC_LEFT, 20, ctx);
    else if (kind == 7) o->LS = SUNLinSol_SPTFQMR(t, SUN_PREC_LEFT, 20, ctx);
    else o->LS = SUNLinSol_PCG(t, SUN_PREC_LEFT, 20, ctx);
    o->solver = kind;
    N_VDestroy(t);
    return;
  }
#if defined(LGN_HAVE_KLU)
  if (kind != 0) {
    o->A  = SUNSparseMatrix(n, n, n * n, kind == 1 ? CSC_MAT : CSR_MAT, ctx);
    o->LS = SUNLinSol_KLU(t, o->A, ctx);
  } else
#endif
  {
    kind  = 0;
    o->A  = SUNDenseMatrix(n, n, ctx);
    o->LS = SUNLinSol_Dense(t, o->A, ctx);
  }
  o->solver = kind;
  N_VDestroy(t);
}

static void ObjCreate(Obj *o, In *in)
{
  /* sel: the model (bits 0-1), the preset unless bit 7; opt: adaptive
   * (bit 0), modified Newton (1), tangent callbacks (2), a revolute joint
   * (3), the oscillator's n - 1 (4-5), the linear solver (6-7) */
  const unsigned sel = U8(in), opt = U8(in);
  const int preset = (sel & 0x80) == 0; /* mostly the sane preset */
  int flag;
  ObjDestroy(o);
  if (trace) fprintf(stderr, "  create sel 0x%02x opt 0x%02x\n", sel, opt);
  o->used     = 1;
  o->model    = (int)((sel & 0x7f) % NMOD);
  o->fault_cb = -1;
  switch (o->model) {
  case MOD_BODY0:
  case MOD_BODY3:
    o->G = LGNGroup_R3xSO3();
    o->m = o->model == MOD_BODY3 ? 3 : 0;
    break;
  case MOD_OSC:
    o->n_osc = 1 + (sunindextype)((opt >> 4) % 4);
    o->G     = LGNGroup_Rn(o->n_osc);
    o->m     = 0;
    break;
  case MOD_BODIES: {
    /* built by the helpers: bodies with mass, gravity, a spring-damper to
     * the ground and a rotational one between them; joints: a revolute
     * joint to the ground (and, opt bit 3, a rotation driver about its
     * axis), a spherical joint between the bodies */
    const double z[3] = {0, 0, 0}, ez[3] = {0, 0, 1}, ex[3] = {1, 0, 0}, s2[3] = {0, 0, -0.5},
                 s1[3] = {0, 0, 0.5}, anchor[3] = {0.3, 0.0, -1.0}, g[3] = {0, 0, -GRAV},
                 I1[9] = {0.4, 0.01, 0, 0.01, 0.5, 0, 0, 0, 0.6};
    o->factors[0] = LGNGroup_R3xSO3();
    o->factors[1] = LGNGroup_SE3();
    o->G          = LGNGroup_Product(2, o->factors);
    o->B          = LGNBodies_Create(o->G);
    o->J          = LGNJoints_Create(o->G);
    LGNBodies_SetErrFile(o->B, NULL);
    LGNJoints_SetErrFile(o->J, NULL);
    REQUIRE(LGNBodies_SetPrincipalInertia(o->B, 0, MASS, JB) == 0 &&
                LGNBodies_SetMass(o->B, 1, 1.5, I1) == 0 && LGNBodies_SetGravity(o->B, g) == 0 &&
                LGNBodies_AddSpringDamper(o->B, LGN_GROUND, anchor, 1, z, 50.0, 0.5, 0.2) == 0 &&
                LGNBodies_AddRotationalSpringDamper(o->B, 0, 1, 2.0, 0.1, NULL) == 0,
            "the body helpers refused the model");
    REQUIRE(LGNJoints_AddRevolute(o->J, LGN_GROUND, z, ez, 0, z, ez) == 0 &&
                LGNJoints_AddSpherical(o->J, 0, s2, 1, s1) == 0,
            "the joint helpers refused the model");
    o->driver = (opt & 8) != 0;
    if (o->driver)
      REQUIRE(LGNJoints_AddRotationDriver(o->J, LGN_GROUND, ez, ex, 0, ex, Drive, NULL) == 0,
              "the rotation driver was refused");
    o->m = LGNJoints_NumConstraints(o->J);
    break;
  }
  default: {
    const double s0[3] = {0, 0, 0}, s1[3] = {0, 0, 0.5}, s2[3] = {0, 0, -0.5},
                 ax[3] = {0, 0, 1};
    o->factors[0] = LGNGroup_R3xSO3();
    o->factors[1] = LGNGroup_R3xSO3();
    o->G          = LGNGroup_Product(2, o->factors);
    o->J          = LGNJoints_Create(o->G);
    LGNJoints_SetErrFile(o->J, NULL);
    LGNJoints_AddSpherical(o->J, LGN_GROUND, s0, 0, s1);
    if (opt & 8) LGNJoints_AddRevolute(o->J, 0, s2, ax, 1, s1, ax);
    else LGNJoints_AddSpherical(o->J, 0, s2, 1, s1);
    o->m = LGNJoints_NumConstraints(o->J);
  }
  }
  o->nq   = o->G->nq;
  o->nv   = o->G->nv;
  o->q    = N_VNew_Serial(o->nq, ctx);
  o->v    = N_VNew_Serial(o->nv, ctx);
  o->q0   = N_VNew_Serial(o->nq, ctx);
  o->v0   = N_VNew_Serial(o->nv, ctx);
  o->qbad = N_VNew_Serial(o->nq + 1, ctx);
  o->vbad = N_VNew_Serial(o->nv > 1 ? o->nv - 1 : 2, ctx);
  o->tmp  = N_VNew_Serial(o->nv, ctx);
  o->nvv  = N_VNew_Serial(o->nv, ctx);
  o->mv   = o->m > 0 ? N_VNew_Serial(o->m, ctx) : NULL;
  if (o->model == MOD_BODIES) o->Md = SUNDenseMatrix(o->nv, o->nv, ctx);
  N_VConst(1.0, o->qbad);
  N_VConst(1.0, o->vbad);
  InitialState(o, N_VGetArrayPointer(o->q0), N_VGetArrayPointer(o->v0));
  MakeSolver(o, (int)((opt >> 6) % 3), o->nv + o->m);

  o->mem = LGNCreate(ctx);
  REQUIRE(o->mem != NULL, "LGNCreate failed");
  REQUIRE(LGNSetErrFile(o->mem, NULL) == 0, "LGNSetErrFile");
  REQUIRE(LGNSetUserData(o->mem, o) == 0, "LGNSetUserData");
  if (!preset) return; /* the rest is up to the program */
  flag = LGNSetGroup(o->mem, o->G);
  if (!flag) flag = LGNSetMassFn(o->mem, Mass);
  if (!flag) flag = LGNSetForceFn(o->mem, Force);
  if (!flag && o->m > 0) flag = LGNSetConstraints(o->mem, o->m, Phi, Jac);
  if (!flag && o->driver) flag = LGNSetConstraintTimeFn(o->mem, PhiT);
  if (!flag && (opt & 4)) {
    flag = LGNSetStiffnessFn(o->mem, Stiffness);
    if (!flag) flag = LGNSetDampingFn(o->mem, Damping);
    if (!flag && o->m > 0) flag = LGNSetCurvatureFn(o->mem, Curvature);
    if (!flag && o->m > 0) flag = LGNSetConstraintForceFn(o->mem, ConstraintForce);
  }
  if (!flag) flag = LGNInit(o->mem, 0.0, o->q0, o->v0);
  if (!flag) flag = LGNSetLinearSolver(o->mem, o->LS, o->A);
  if (!flag) flag = LGNSetGenAlpha(o->mem, 0.8);
  if (!flag) flag = LGNSetStepSize(o->mem, 1e-3);
  if (!flag) flag = LGNSetMaxNumSteps(o->mem, 50);
  if (!flag) flag = LGNSetNewtonMode(o->mem, (opt & 2) ? LGN_NEWTON_MODIFIED : LGN_NEWTON_FULL);
  if (!flag && (opt & 1)) {
    flag = LGNSetStepControl(o->mem, LGN_STEP_ADAPTIVE);
    if (!flag) flag = LGNSStolerances(o->mem, 1e-6, 1e-6);
    o->adaptive = 1;
  }
  REQUIRE(flag == 0, "the preset of model %d failed: %s", o->model, LGNGetReturnFlagName(flag));
  o->init_done = 1;
  o->sane      = 1;
}

/* ---------------------------------------------------------------------------
 * The state before and after a solve
 * -------------------------------------------------------------------------*/
typedef struct {
  int ft, fs, fa, fl, fx;
  double t;
  long nst;
  double vdot[12], lambda[16], aux[12];
} Snapshot;

static void Snap(Obj *o, Snapshot *s)
{
  memset(s, 0, sizeof *s);
  s->ft = LGNGetCurrentTime(o->mem, &s->t);
  s->fs = LGNGetNumSteps(o->mem, &s->nst);
  N_VConst(0.0, o->nvv);
  s->fa = LGNGetAcceleration(o->mem, o->nvv);
  memcpy(s->vdot, N_VGetArrayPointer(o->nvv), (size_t)o->nv * sizeof(double));
  N_VConst(0.0, o->nvv);
  s->fx = LGNGetAuxAcceleration(o->mem, o->nvv);
  memcpy(s->aux, N_VGetArrayPointer(o->nvv), (size_t)o->nv * sizeof(double));
  if (o->mv) {
    N_VConst(0.0, o->mv);
    s->fl = LGNGetMultipliers(o->mem, o->mv);
    memcpy(s->lambda, N_VGetArrayPointer(o->mv), (size_t)o->m * sizeof(double));
  }
}

static int AllFinite(N_Vector x)
{
  sunindextype i, n = N_VGetLength(x);
  const double *p = N_VGetArrayPointer(x);
  for (i = 0; i < n; i++)
    if (!isfinite(p[i])) return 0;
  return 1;
}

static void Remember(Obj *o)
{
  memcpy(o->kq, N_VGetArrayPointer(o->q), (size_t)o->nq * sizeof(double));
  memcpy(o->kv, N_VGetArrayPointer(o->v), (size_t)o->nv * sizeof(double));
  o->known = 1;
}

static const double SENTINEL = 12345.678;

/* One LGNSolve with every invariant checked. */
static int Solve(Obj *o, double tout, int itask, int badvec)
{
  Snapshot before, after;
  double tret = SENTINEL;
  int root_pending;
  N_Vector q = o->q, v = o->v;
  int flag, i, wrote;
  if (badvec == 1) q = o->qbad;
  if (badvec == 2) v = NULL;
  Snap(o, &before);
  N_VConst(SENTINEL, o->q);
  N_VConst(SENTINEL, o->v);
  o->fault_fired = 0;
  flag = LGNSolve(o->mem, tout, &tret, q, v, itask);
  if (trace) {
    fprintf(stderr, "  LGNSolve(tout %.17g, itask %d, badvec %d) -> %s, tret %.17g\n  q", tout,
            itask, badvec, LGNGetReturnFlagName(flag), tret);
    for (i = 0; i < o->nq; i++) fprintf(stderr, " %g", N_VGetArrayPointer(o->q)[i]);
    fprintf(stderr, "\n  v");
    for (i = 0; i < o->nv; i++) fprintf(stderr, " %g", N_VGetArrayPointer(o->v)[i]);
    {
      double hc = 0.0, en = 0.0;
      LGNGetCurrentStep(o->mem, &hc);
      LGNGetLastErrNorm(o->mem, &en);
      fprintf(stderr, "\n  next h %g, last error norm %g\n", hc, en);
    }
  }
  o->nsolves++;
  root_pending = o->root_returned;
  if (o->mem == NULL) {
    REQUIRE(flag == LGN_MEM_NULL, "LGNSolve(NULL) returned %d", flag);
    return flag;
  }
  Snap(o, &after);
  if (after.nst > before.nst) o->vdot0_set = 0;
  if (after.fs == 0 && before.fs == 0 && after.nst > before.nst)
    steps_left -= after.nst - before.nst;
  /* the rest of the step after a root is pending until a call succeeds or
   * steps (a refused call leaves it pending) */
  o->root_returned = flag == LGN_ROOT_RETURN ||
                     (root_pending && flag < 0 && after.nst == before.nst);
  if (flag == LGN_SUCCESS || flag == LGN_TSTOP_RETURN || flag == LGN_ROOT_RETURN) {
    /* no step goes past an accepted stop time (fixed steps too) */
    if (o->stop_set && o->tstop_check)
      REQUIRE(after.t <= o->tstop + 1e-12 * fmax(1.0, fabs(o->tstop)) && tret <= after.t,
              "LGNSolve (%s) stepped past the stop time %.17g to %.17g",
              LGNGetReturnFlagName(flag), o->tstop, after.t);
  }
  if (flag == LGN_ROOT_RETURN) {
    double hlast = 0.0;
    int found[3] = {0, 0, 0}, any = 0;
    REQUIRE(o->nrt > 0, "LGN_ROOT_RETURN without root functions");
    REQUIRE(badvec == 0 && (itask == LGN_NORMAL || itask == LGN_ONE_STEP),
            "LGNSolve returned a root with bad arguments (%d, itask %d)", badvec, itask);
    REQUIRE(isfinite(tret) && (o->nonfinite_start || (AllFinite(o->q) && AllFinite(o->v))),
            "LGN_ROOT_RETURN with a non-finite tret, q or v (tret %g)", tret);
    /* the root lies in the last step, [t_n - h, t_n], and not beyond tout */
    REQUIRE(LGNGetLastStep(o->mem, &hlast) == 0, "LGNGetLastStep after a root");
    REQUIRE(tret <= after.t + 1e-12 * fmax(1.0, fabs(after.t)) &&
                tret >= after.t - fabs(hlast) * (1.0 + 1e-9) - 1e-12 * fmax(1.0, fabs(after.t)),
            "the root %.17g is outside the last step [%.17g - %g, %.17g]", tret, after.t,
            hlast, after.t);
    if (itask == LGN_NORMAL)
      REQUIRE(tret <= tout + 1e-12 * fmax(1.0, fabs(tout)), "a root %.17g beyond tout %.17g",
              tret, tout);
    REQUIRE(LGNGetRootInfo(o->mem, found) == 0, "LGNGetRootInfo after a root");
    for (i = 0; i < o->nrt; i++) {
      REQUIRE(found[i] >= -1 && found[i] <= 1, "rootsfound[%d] = %d", i, found[i]);
      REQUIRE(found[i] == 0 || o->rootdir[i] == 0 || found[i] == o->rootdir[i],
              "root %d found in direction %d, only %d asked", i, found[i], o->rootdir[i]);
      any |= found[i] != 0;
    }
    REQUIRE(any, "LGN_ROOT_RETURN, but LGNGetRootInfo reports no root");
    if (tret == after.t) Remember(o);
    else o->known = 0;
    return flag;
  }
  if (flag == LGN_SUCCESS || flag == LGN_TSTOP_RETURN) {
    REQUIRE(badvec == 0 && (itask == LGN_NORMAL || itask == LGN_ONE_STEP),
            "LGNSolve succeeded with bad arguments (%d, itask %d)", badvec, itask);
    /* after a non-finite q0 or v0 was accepted (finding 3 in README.md,
     * reproducer crashes/init_nonfinite_q0.c) only tret must be finite */
    REQUIRE(isfinite(tret) && (o->nonfinite_start || (AllFinite(o->q) && AllFinite(o->v))),
            "LGNSolve returned %s with a non-finite tret, q or v (tret %g)",
            LGNGetReturnFlagName(flag), tret);
    REQUIRE(after.ft == 0 && isfinite(after.t), "current time after a success");
    if (flag == LGN_TSTOP_RETURN) {
      REQUIRE(o->stop_set, "LGN_TSTOP_RETURN without a stop time");
      o->stop_set = 0;
    } else if (itask == LGN_ONE_STEP && root_pending && after.nst == before.nst) {
      /* after a root inside the last step: the rest of it, no new step */
      REQUIRE(after.t == before.t && tret == after.t,
              "LGN_ONE_STEP after a root returned %.17g, not the step's end %.17g", tret, after.t);
    } else if (itask == LGN_ONE_STEP) {
      REQUIRE(after.t > before.t, "LGN_ONE_STEP succeeded without advancing t (%.17g)", after.t);
      REQUIRE(after.nst > before.nst, "LGN_ONE_STEP succeeded without a step");
    } else {
      const double tol = 1000.0 * 2.2e-16 * fmax(fabs(tout), fmax(fabs(before.t), 1.0));
      REQUIRE(fabs(tret - tout) <= tol, "LGN_NORMAL returned at %.17g, not tout = %.17g", tret,
              tout);
    }
    if (tret == after.t) Remember(o);
    else o->known = 0; /* interpolated: the state at the current time unknown */
    return flag;
  }
  /* failure */
  REQUIRE(flag < 0 && strcmp(LGNGetReturnFlagName(flag), "NONE") != 0,
          "LGNSolve returned the unnamed flag %d", flag);
  wrote = 0;
  if (badvec == 0 && (itask == LGN_NORMAL || itask == LGN_ONE_STEP)) {
    const double *pq = N_VGetArrayPointer(o->q), *pv = N_VGetArrayPointer(o->v);
    for (i = 0; i < o->nq; i++) wrote |= pq[i] != SENTINEL;
    for (i = 0; i < o->nv; i++) wrote |= pv[i] != SENTINEL;
  }
  if (after.fs == 0 && before.fs == 0 && after.nst == before.nst) {
    /* no step taken: the state as before, bit for bit. Before the first
     * step the getters of vdot, lambda and a report what the last attempt
     * left (zeros, then the consistent initial values once computed, kept
     * even when the call fails later, e.g. with LGN_BAD_TOUT: finding 1 in
     * test/fuzz/README.md, reproducer crashes/bad_tout_changes_vdot.c), so
     * they are compared only once a step has been taken. */
    if (o->vdot0_set) memcpy(after.aux, before.aux, sizeof after.aux); /* finding 5 */
    /* finding 13 (open, README.md): a Krylov solver is checked against the
     * problem only after the work arrays are made anew, so a refusal with
     * LGN_LS_MISMATCH can change the getters' vdot, lambda and a */
    if (before.nst == 0 || (flag == LGN_LS_MISMATCH && o->solver >= 3 && o->solver <= 7)) {
      memcpy(after.vdot, before.vdot, sizeof after.vdot);
      memcpy(after.lambda, before.lambda, sizeof after.lambda);
      memcpy(after.aux, before.aux, sizeof after.aux);
      after.fa = before.fa; /* LGNGetMultipliers: LGN_ILL_INPUT, then 0 */
      after.fl = before.fl;
      after.fx = before.fx;
    }
    REQUIRE(memcmp(&before, &after, sizeof before) == 0,
            "LGNSolve failed (%s) without a step but changed the state: t %.17g -> %.17g, "
            "flags %d %d %d %d %d -> %d %d %d %d %d, vdot %d, lambda %d, aux %d",
            LGNGetReturnFlagName(flag), before.t, after.t, before.ft, before.fs, before.fa,
            before.fl, before.fx, after.ft, after.fs, after.fa, after.fl, after.fx,
            memcmp(before.vdot, after.vdot, sizeof before.vdot) != 0,
            memcmp(before.lambda, after.lambda, sizeof before.lambda) != 0,
            memcmp(before.aux, after.aux, sizeof before.aux) != 0);
    if (wrote) {
      REQUIRE(tret == after.t, "failed LGNSolve: tret %.17g is not t %.17g", tret, after.t);
      if (o->known)
        REQUIRE(memcmp(o->kq, N_VGetArrayPointer(o->q), (size_t)o->nq * sizeof(double)) == 0 &&
                    memcmp(o->kv, N_VGetArrayPointer(o->v), (size_t)o->nv * sizeof(double)) == 0,
                "failed LGNSolve (%s) returned a q, v other than the state before",
                LGNGetReturnFlagName(flag));
      else Remember(o);
    }
  } else if (after.fs == 0 && before.fs == 0) {
    /* LGN_NORMAL took steps, then failed: the last accepted state (so does
     * LGN_ONE_STEP whose root function failed after the step, whose
     * redundant rows were found violated after it, or whose output, the
     * projection and consistent multipliers of lgn_output.c, failed in a
     * callback or a singular saddle-point matrix) */
    const int after_step = flag == LGN_RTFUNC_FAIL || flag == LGN_REDUNDANT_INCONSISTENT ||
                           flag == LGN_REPTD_CALLBACK_ERR || flag == LGN_IC_FAIL ||
                           flag == LGN_MEM_FAIL || (flag <= LGN_MASS_FAIL && flag >= LGN_NONFINITE);
    REQUIRE((itask == LGN_NORMAL || after_step) && after.nst > before.nst &&
                after.t > before.t,
            "LGNSolve(%d) failed (%s) with %ld -> %ld steps, t %.17g -> %.17g", itask,
            LGNGetReturnFlagName(flag), before.nst, after.nst, before.t, after.t);
    REQUIRE(wrote && tret == after.t &&
                (o->nonfinite_start || (AllFinite(o->q) && AllFinite(o->v))),
            "failed LGN_NORMAL returns the last accepted state");
    Remember(o);
  }
  return flag;
}

/* A user preconditioner: the identity, with the fault chosen by OP_KRYLOV. */
static int PrecSetup(sunrealtype t, N_Vector q, N_Vector v, sunrealtype cM, sunrealtype cC,
                     sunrealtype cK, void *ud)
{
  Obj *o = ud;
  (void)t; (void)cM; (void)cC; (void)cK;
  if (!LenOk(q, o->nq) || !LenOk(v, o->nv)) return -1;
  if ((o->pc_fault == 1 || o->pc_fault == 2) && ++o->pc_setups == o->pc_fault_at)
    return o->pc_fault == 1 ? 1 : -1;
  return 0;
}

static int PrecSolve(sunrealtype t, N_Vector q, N_Vector v, N_Vector r, N_Vector z,
                     sunrealtype cM, sunrealtype cC, sunrealtype cK, sunrealtype delta, void *ud)
{
  Obj *o = ud;
  (void)t; (void)q; (void)v; (void)cM; (void)cC; (void)cK; (void)delta;
  if (r == NULL || z == NULL || N_VGetLength(r) != N_VGetLength(z)) return -1;
  N_VScale(1.0, r, z);
  if ((o->pc_fault == 3 || o->pc_fault == 4) && ++o->pc_solves == o->pc_fault_at)
    return o->pc_fault == 3 ? 1 : -1;
  return 0;
}

/* ---------------------------------------------------------------------------
 * The program
 * -------------------------------------------------------------------------*/
static N_Vector PickVec(In *in, Obj *o, N_Vector good)
{
  switch (U8(in) % 6) {
  case 0: return NULL;
  case 1: return o->qbad;
  case 2: return o->vbad;
  case 3: return o->q0;
  default: return good;
  }
}

#define NOBJ 2
enum {
  OP_CREATE, OP_SETGROUP, OP_SETFNS, OP_CONSTRAINTS, OP_TANGENTS, OP_LINSOL, OP_STEPSIZE,
  OP_METHOD, OP_INDEX, OP_KINEMATICS, OP_TOLERANCES, OP_COUNTS, OP_INITIAL, OP_CONTROL,
  OP_STEPBOUNDS, OP_STOPTIME, OP_INIT, OP_REINIT, OP_SOLVE, OP_SOLVE2, OP_SOLVE3, OP_DKY,
  OP_GETTERS, OP_FAULT, OP_HEAL, OP_FREE, OP_CALCIC, OP_MISC, OP_JOINTS, OP_BDF, OP_ROOTS,
  OP_KRYLOV, OP_BODIES, OP_GETTERS2, NOP
};

static void Run(In *in)
{
  Obj objs[NOBJ];
  int steps = 0, k, i, saved_fd = -1;
  memset(objs, 0, sizeof objs);
  while (in->i < in->n && steps < 64) {
    const unsigned op = U8(in) % NOP;
    Obj *o            = &objs[U8(in) % NOBJ];
    void *mem;
    int flag = 0;
    steps++;
    if (trace)
      fprintf(stderr, "op %u on object %d (model %d, solver %d, m %ld, fault cb %d kind %d at %ld)\n",
              op, (int)(o - objs), o->model, o->solver, (long)o->m, o->fault_cb, o->fault_kind,
              o->fault_at);
    if (op == OP_CREATE || !o->used) {
      ObjCreate(o, in);
      continue;
    }
    mem = o->mem;
    /* After LGNFree there is no memory block to silence: Lignum's messages
     * about mem = NULL go to stderr, which is pointed at /dev/null for this
     * operation (a sanitizer report would be lost here, the crash is not:
     * run the saved input again to see it). */
    if (mem == NULL && null_fd >= 0) {
      fflush(stderr);
      saved_fd = dup(2);
      if (saved_fd >= 0) dup2(null_fd, 2);
    }
    switch (op) {
    case OP_SETGROUP: {
      const unsigned s = U8(in) % 3;
      flag = CheckFlag(o, LGNSetGroup(mem, s == 0 ? o->G : s == 1 ? NULL : spare_group),
                       "LGNSetGroup");
      o->sane = 0;
      break;
    }
    case OP_SETFNS: {
      const unsigned s = U8(in);
      CheckFlag(o, LGNSetMassFn(mem, (s & 1) ? Mass : NULL), "LGNSetMassFn");
      CheckFlag(o, LGNSetForceFn(mem, (s & 2) ? Force : NULL), "LGNSetForceFn");
      if (s & 4) CheckFlag(o, LGNSetMassConstant(mem, (s & 8) ? SUNTRUE : SUNFALSE), "LGNSetMassConstant");
      if (s & 16) CheckFlag(o, LGNSetUserData(mem, o), "LGNSetUserData");
      o->sane = 0;
      break;
    }
    case OP_CONSTRAINTS: {
      const unsigned s = U8(in);
      sunindextype m   = o->m;
      switch (s % 6) {
      case 0: m = 0; break;
      case 1: m = -1; break;
      case 2: m = o->m + 1; break;
      case 3: m = (sunindextype)1 << 40; o->huge_m = 1; break;
      default: break;
      }
      CheckFlag(o, LGNSetConstraints(mem, m, (s & 8) ? Phi : NULL, (s & 16) ? Jac : NULL),
                "LGNSetConstraints");
      o->sane = 0;
      break;
    }
    case OP_TANGENTS: {
      const unsigned s = U8(in);
      if (trace) fprintf(stderr, "  tangents 0x%02x\n", s);
      CheckFlag(o, LGNSetStiffnessFn(mem, (s & 1) ? Stiffness : NULL), "LGNSetStiffnessFn");
      CheckFlag(o, LGNSetDampingFn(mem, (s & 2) ? Damping : NULL), "LGNSetDampingFn");
      CheckFlag(o, LGNSetCurvatureFn(mem, (s & 4) ? Curvature : NULL), "LGNSetCurvatureFn");
      CheckFlag(o, LGNSetConstraintForceFn(mem, (s & 8) ? ConstraintForce : NULL),
                "LGNSetConstraintForceFn");
      o->sane = 0;
      break;
    }
    case OP_LINSOL: {
      const unsigned s = U8(in);
      sunindextype n   = o->nv + o->m;
      if (s & 8) n += (s & 16) ? 1 : -1;
      else if (s & 16) n += o->m; /* GGL's nv + 2m */
      MakeSolver(o, (int)(s % 3), n);
      if (trace) fprintf(stderr, "  linear solver %u, n %ld, flags 0x%02x\n", s % 3, (long)n, s);
      if (s & 32) CheckFlag(o, LGNSetLinearSolver(mem, NULL, o->A), "LGNSetLinearSolver");
      else if (s & 64) CheckFlag(o, LGNSetLinearSolver(mem, o->LS, NULL), "LGNSetLinearSolver");
      CheckFlag(o, LGNSetLinearSolver(mem, o->LS, o->A), "LGNSetLinearSolver");
      if (s & 128) {
        flag = CheckFlag(o, LGNSetOwnKLUSolves(mem, (s & 4) ? SUNTRUE : 7), "LGNSetOwnKLUSolves");
        if (flag == 0) o->own_klu = 1;
      }
      o->sane = 0;
      break;
    }
    case OP_STEPSIZE:
      CheckFlag(o, LGNSetStepSize(mem, Param(in, 1e-3)), "LGNSetStepSize");
      o->sane = 0;
      break;
    case OP_METHOD: {
      const unsigned s = U8(in) % 3;
      if (s == 0) CheckFlag(o, LGNSetGenAlpha(mem, Param(in, 0.5)), "LGNSetGenAlpha");
      else if (s == 1) {
        const double b = Param(in, 0.25), g = Param(in, 0.5);
        CheckFlag(o, LGNSetNewmark(mem, b, g), "LGNSetNewmark");
      } else {
        const double am = Real(in), af = Real(in), b = Param(in, 0.3), g = Param(in, 0.6);
        CheckFlag(o, LGNSetGenAlphaParams(mem, am, af, b, g), "LGNSetGenAlphaParams");
      }
      o->sane = 0;
      break;
    }
    case OP_INDEX: {
      /* mostly the three formulations; GGL with bit 3 also gets a dense
       * solver of nv + 2m rows */
      static const int idx[6] = {LGN_CONSTR_INDEX3, LGN_CONSTR_INDEX2, LGN_CONSTR_GGL,
                                 LGN_CONSTR_GGL, 0, LGN_CONSTR_GGL + 1};
      const unsigned s = U8(in);
      flag = CheckFlag(o, LGNSetConstraintIndex(mem, idx[s % 6]), "LGNSetConstraintIndex");
      if (trace) fprintf(stderr, "  constraint index %d -> %d\n", idx[s % 6], flag);
      if (flag == 0 && idx[s % 6] == LGN_CONSTR_GGL && (s & 8)) {
        MakeSolver(o, 0, o->nv + 2 * o->m);
        CheckFlag(o, LGNSetLinearSolver(mem, o->LS, o->A), "LGNSetLinearSolver");
      }
      o->sane = 0;
      break;
    }
    case OP_KINEMATICS: {
      /* the constants, and one illegal value each */
      const unsigned s = U8(in);
      CheckFlag(o, LGNSetKinematics(mem, LGN_KINEMATICS_SIMPLIFIED + (int)(s % 4)),
                "LGNSetKinematics");
      CheckFlag(o, LGNSetPredictor(mem, LGN_PREDICTOR_ZERO + (int)((s >> 2) % 3)),
                "LGNSetPredictor");
      CheckFlag(o, LGNSetNewtonMode(mem, LGN_NEWTON_FULL + (int)((s >> 4) % 3)),
                "LGNSetNewtonMode");
      CheckFlag(o, LGNSetPerturbedStart(mem, (s & 128) ? 5 : (s & 64) ? SUNTRUE : SUNFALSE),
                "LGNSetPerturbedStart");
      o->sane = 0;
      break;
    }
    case OP_TOLERANCES:
      if (U8(in) & 1) {
        const double r = Param(in, 1e-6), a = Param(in, 1e-6);
        CheckFlag(o, LGNSStolerances(mem, r, a), "LGNSStolerances");
      } else {
        const double r = Param(in, 1e-6);
        N_VConst(Param(in, 1e-6), o->tmp);
        if (U8(in) & 1) N_VGetArrayPointer(o->tmp)[0] = Real(in);
        CheckFlag(o, LGNSVtolerances(mem, r, PickVec(in, o, o->tmp)), "LGNSVtolerances");
      }
      o->sane = 0;
      break;
    case OP_COUNTS: {
      const unsigned s = U8(in);
      CheckFlag(o, LGNSetMaxNewtonIters(mem, (int)(s % 12) - 2), "LGNSetMaxNewtonIters");
      CheckFlag(o, LGNSetLSetupFrequency(mem, (long)((s >> 4) % 8) - 2), "LGNSetLSetupFrequency");
      /* never 0 or negative: the default is a million steps, negative unlimited */
      CheckFlag(o, LGNSetMaxNumSteps(mem, 1 + (long)(U8(in) % 100)), "LGNSetMaxNumSteps");
      o->sane = 0;
      break;
    }
    case OP_INITIAL: {
      const unsigned s = U8(in);
      N_VConst(Param(in, 1.0), o->tmp);
      if (s & 1) {
        N_Vector l = o->mv ? o->mv : o->vbad;
        if (o->mv) N_VConst(Real(in), o->mv);
        flag = CheckFlag(o, LGNSetInitialAcceleration(mem, PickVec(in, o, o->tmp), (s & 2) ? l : NULL),
                         "LGNSetInitialAcceleration");
        /* accepted after steps too; the next LGNSolve sets a = vdot0 even
         * when it fails: finding 5 in README.md */
        if (flag == 0) o->vdot0_set = 1;
      } else {
        CheckFlag(o, LGNSetInitialAux(mem, PickVec(in, o, o->tmp)), "LGNSetInitialAux");
      }
      o->sane = 0;
      break;
    }
    case OP_CONTROL: {
      const unsigned s = U8(in) % 4;
      const int c = s == 0 ? LGN_STEP_FIXED : s == 3 ? 7 : LGN_STEP_ADAPTIVE;
      flag = CheckFlag(o, LGNSetStepControl(mem, c), "LGNSetStepControl");
      if (flag == 0) o->adaptive = c == LGN_STEP_ADAPTIVE;
      o->sane = 0;
      break;
    }
    case OP_STEPBOUNDS: {
      const unsigned s = U8(in) % 6;
      const double x = Param(in, 1e-3);
      const int ix = (int)(U8(in) % 8) - 2;
      switch (s) {
      case 0: CheckFlag(o, LGNSetInitStep(mem, x), "LGNSetInitStep"); break;
      case 1: CheckFlag(o, LGNSetMinStep(mem, x * 1e-3), "LGNSetMinStep"); break;
      case 2: CheckFlag(o, LGNSetMaxStep(mem, x * 10.0), "LGNSetMaxStep"); break;
      case 3: CheckFlag(o, LGNSetMaxErrTestFails(mem, ix), "LGNSetMaxErrTestFails"); break;
      case 4: CheckFlag(o, LGNSetMaxConvFails(mem, ix), "LGNSetMaxConvFails"); break;
      default: CheckFlag(o, LGNSetNonlinConvCoef(mem, x * 300.0), "LGNSetNonlinConvCoef"); break;
      }
      o->sane = 0;
      break;
    }
    case OP_STOPTIME: {
      double t = 0.0;
      LGNGetCurrentTime(mem, &t);
      if (U8(in) & 1) {
        const double ts = t + Param(in, 1e-2);
        flag = CheckFlag(o, LGNSetStopTime(mem, ts), "LGNSetStopTime");
        if (flag == 0) {
          o->stop_set    = 1;
          o->tstop       = ts;
          o->tstop_check = ts >= t;
        }
      } else {
        flag = CheckFlag(o, LGNClearStopTime(mem), "LGNClearStopTime");
        if (flag == 0) o->tstop_check = 0;
      }
      /* the stop time does not spoil the sane set-up */
      break;
    }
    case OP_INIT:
    case OP_REINIT: {
      const unsigned s = U8(in);
      double tcur = 0.0, t0;
      LGNGetCurrentTime(mem, &tcur);
      /* t0: any real, the current time (a restart after an event), or 0 */
      t0 = (s & 1) ? Real(in) : (s & 32) ? tcur : 0.0;
      InitialState(o, N_VGetArrayPointer(o->q0), N_VGetArrayPointer(o->v0));
      if (s & 2) N_VGetArrayPointer(o->q0)[U8(in) % o->nq] = Real(in);
      if (s & 4) N_VGetArrayPointer(o->v0)[U8(in) % o->nv] = Real(in);
      {
        N_Vector q0 = (s & 8) ? PickVec(in, o, o->q0) : o->q0;
        N_Vector v0 = (s & 16) ? PickVec(in, o, o->v0) : o->v0;
        /* (own KLU solves, LGNInit again and a new pattern corrupted the
         * heap: finding 4 in README.md, fixed: KLU analyses anew) */
        flag        = op == OP_INIT ? LGNInit(mem, t0, q0, v0) : LGNReInit(mem, t0, q0, v0);
        if (trace) fprintf(stderr, "  init 0x%02x t0 %g -> %d\n", s, t0, flag);
        CheckFlag(o, flag, op == OP_INIT ? "LGNInit" : "LGNReInit");
        if (flag == 0) o->nonfinite_start = !AllFinite(q0) || !AllFinite(v0);
      }
      if (flag == 0) {
        o->init_done = 1;
        o->known     = 0;
        o->root_returned = 0;
        /* a stop time behind the new t0 (issue 31, item 3) is not checked */
        if (!(t0 <= o->tstop)) o->tstop_check = 0;
        o->stop_set  = o->stop_set; /* kept or not: LGN_TSTOP_RETURN stays allowed */
      }
      o->sane = 0;
      break;
    }
    case OP_SOLVE:
    case OP_SOLVE2:
    case OP_SOLVE3: {
      const unsigned s = U8(in);
      double t = 0.0, dt;
      int itask = (s & 1) ? LGN_ONE_STEP : LGN_NORMAL;
      int badvec = (s & 0x70) == 0x70 ? 1 + (int)((s >> 1) & 1) : 0;
      if ((s & 0x0e) == 0x0e) itask = 3;
      LGNGetCurrentTime(mem, &t);
      dt = (s & 0x80) ? Real(in) : Param(in, 2e-3);
      if (o->nsolves >= 24 || steps_left <= 0) break; /* bounded work per input */
      /* m = 2^40 makes LGNSolve allocate terabytes, which ASan and
       * libFuzzer report as a crash before malloc can return NULL */
      if (o->huge_m && o->mem) break;
      /* LGN_NORMAL with fixed steps shortens the last step to land on tout,
       * down to 1e-12 h: a following step of h (a ratio of 1e12) may then
       * legitimately fail to converge at index 3. Not sane any more. */
      if (itask == LGN_NORMAL && !o->adaptive) o->sane = 0;
      /* (error control's first step with tout - t = 1e-300 was 1e-300 and
       * every later step failed: finding 6, fixed: steps of at least
       * 1e-150). A huge tout may fail legitimately. */
      if (!(dt > 0.0 && dt <= 10.0)) o->sane = 0;
      flag = Solve(o, t + dt, itask, badvec);
      break;
    }
    case OP_DKY: {
      double t = 0.0, h = 0.0;
      const unsigned s = U8(in);
      LGNGetCurrentTime(mem, &t);
      LGNGetLastStep(mem, &h);
      /* t at the step's end, inside the last step, at its start and a
       * quarter step before it (outside), or any real; k = -1 ... 6 (BDF's
       * derivatives up to its order, and beyond) */
      const int at_end = s % 5 == 0 && !(s & 0x80);
      N_Vector out;
      t -= (double)(s % 5) * 0.25 * h;
      if (s & 0x80) t = Real(in);
      k   = (int)((s >> 3) % 8) - 1;
      out = (k == 0) ? PickVec(in, o, o->q) : PickVec(in, o, o->v);
      if (out) N_VConst(SENTINEL, out);
      flag = CheckFlag(o, LGNGetDky(mem, t, k, out), "LGNGetDky");
      if (trace) fprintf(stderr, "  LGNGetDky(%.17g, %d) -> %d\n", t, k, flag);
      if (flag == 0) {
        REQUIRE(LenOk(out, k == 0 ? o->nq : o->nv) && k >= 0 &&
                    (o->nonfinite_start || AllFinite(out)),
                "LGNGetDky(t %g, k %d) succeeded with a bad argument or a non-finite result", t,
                k);
        /* the dense output at the step's end is the state there */
        if (at_end && k == 0 && o->known && out == o->q && !o->nonfinite_start) {
          for (i = 0; i < (int)o->nq; i++)
            REQUIRE(fabs(N_VGetArrayPointer(out)[i] - o->kq[i]) <= 1e-9 * (1.0 + fabs(o->kq[i])),
                    "LGNGetDky at the current time: q[%d] = %.17g, the state %.17g", i,
                    N_VGetArrayPointer(out)[i], o->kq[i]);
        }
      }
      break;
    }
    case OP_GETTERS: {
      long l = 0;
      double x = 0.0, am, af, b, g;
      sunindextype nred = 0, rows[8], piv;
      long l1, l2, l3;
      const unsigned s = U8(in);
      long *lp = (s & 1) ? NULL : &l;
      double *xp = (s & 2) ? NULL : &x;
      CheckFlag(o, LGNGetNumSteps(mem, lp), "LGNGetNumSteps");
      CheckFlag(o, LGNGetNumNewtonIters(mem, &l), "LGNGetNumNewtonIters");
      CheckFlag(o, LGNGetNumNewtonConvFails(mem, &l), "LGNGetNumNewtonConvFails");
      CheckFlag(o, LGNGetNumStepFails(mem, &l), "LGNGetNumStepFails");
      CheckFlag(o, LGNGetNumResEvals(mem, &l), "LGNGetNumResEvals");
      CheckFlag(o, LGNGetNumDQEvals(mem, &l), "LGNGetNumDQEvals");
      CheckFlag(o, LGNGetNumJacEvals(mem, lp), "LGNGetNumJacEvals");
      CheckFlag(o, LGNGetNumNewtonStalls(mem, &l), "LGNGetNumNewtonStalls");
      CheckFlag(o, LGNGetNumSparsityAnalyses(mem, &l), "LGNGetNumSparsityAnalyses");
      /* (nv + m)^2 overflows with m = 2^40: finding 2 in README.md,
       * reproducer crashes/iteration_matrix_nnz_overflow.c */
      if (!o->huge_m)
        CheckFlag(o, LGNGetIterationMatrixNnz(mem, &l), "LGNGetIterationMatrixNnz");
      CheckFlag(o, LGNGetNumDQColors(mem, &l), "LGNGetNumDQColors");
      CheckFlag(o, LGNGetWorkSpace(mem, &l, lp), "LGNGetWorkSpace");
      CheckFlag(o, LGNGetNumLinSolvSetups(mem, &l), "LGNGetNumLinSolvSetups");
      CheckFlag(o, LGNGetNumLinSolves(mem, &l), "LGNGetNumLinSolves");
      CheckFlag(o, LGNGetNumMatrixReuses(mem, &l), "LGNGetNumMatrixReuses");
      CheckFlag(o, LGNGetNumNewtonRestarts(mem, &l), "LGNGetNumNewtonRestarts");
      CheckFlag(o, LGNGetLastLinFlag(mem, &l), "LGNGetLastLinFlag");
      CheckFlag(o, LGNGetNumErrTestFails(mem, &l), "LGNGetNumErrTestFails");
      CheckFlag(o, LGNGetCurrentTime(mem, xp), "LGNGetCurrentTime");
      CheckFlag(o, LGNGetLastStep(mem, &x), "LGNGetLastStep");
      CheckFlag(o, LGNGetCurrentStep(mem, xp), "LGNGetCurrentStep");
      CheckFlag(o, LGNGetActualInitStep(mem, &x), "LGNGetActualInitStep");
      CheckFlag(o, LGNGetLastErrNorm(mem, &x), "LGNGetLastErrNorm");
      CheckFlag(o, LGNGetMethodParams(mem, &am, &af, &b, (s & 4) ? NULL : &g), "LGNGetMethodParams");
      CheckFlag(o, LGNGetEstLocalErrors(mem, PickVec(in, o, o->tmp)), "LGNGetEstLocalErrors");
      CheckFlag(o, LGNGetErrWeights(mem, PickVec(in, o, o->tmp)), "LGNGetErrWeights");
      CheckFlag(o, LGNGetAcceleration(mem, PickVec(in, o, o->tmp)), "LGNGetAcceleration");
      CheckFlag(o, LGNGetAuxAcceleration(mem, PickVec(in, o, o->tmp)), "LGNGetAuxAcceleration");
      CheckFlag(o, LGNGetMultipliers(mem, PickVec(in, o, o->mv ? o->mv : o->tmp)), "LGNGetMultipliers");
      CheckFlag(o, LGNGetRedundantConstraints(mem, (s & 8) ? NULL : &nred, (s & 16) ? NULL : rows),
                "LGNGetRedundantConstraints");
      CheckFlag(o, LGNGetZeroPivot(mem, (s & 32) ? NULL : &piv), "LGNGetZeroPivot");
      CheckFlag(o, LGNGetNumKLUFactorCopies(mem, &l1), "LGNGetNumKLUFactorCopies");
      CheckFlag(o, LGNGetNumKLUValueCopies(mem, &l1), "LGNGetNumKLUValueCopies");
      CheckFlag(o, LGNGetNumOwnKLURefactors(mem, &l1), "LGNGetNumOwnKLURefactors");
      CheckFlag(o, LGNGetNumOwnKLUSolves(mem, &l1), "LGNGetNumOwnKLUSolves");
      CheckFlag(o, LGNGetNumKLUFallbacks(mem, &l1, &l2, (s & 64) ? NULL : &l3),
                "LGNGetNumKLUFallbacks");
      if (s & 128) CheckFlag(o, LGNPrintAllStats(mem, devnull, (int)(s % 3)), "LGNPrintAllStats");
      CheckFlag(o, LGNGetConsistentIC(mem, PickVec(in, o, o->q0), PickVec(in, o, o->v0)),
                "LGNGetConsistentIC");
      break;
    }
    case OP_FAULT: {
      const unsigned s = U8(in);
      int cb = (int)(s % NCB);
      o->fault_cb   = cb;
      o->fault_kind = (int)((s >> 3) % NFAULT);
      o->fault_at   = o->ncalls[cb] + 1 + (long)(U8(in) % 8);
      break;
    }
    case OP_HEAL: {
      /* the fault removed: an object set up sanely goes on */
      const int had = o->fault_cb >= 0;
      o->fault_cb   = -1;
      if (had && o->sane && o->mem && U8(in) % 2 == 0 && o->nsolves < 24 && steps_left > 0) {
        double t = 0.0;
        LGNGetCurrentTime(mem, &t);
        flag = Solve(o, t + 1.0, LGN_ONE_STEP, 0);
        /* a root of g on the way is going on too (the level may lie a
         * roundoff away from the start: roots at t ~ 1e-16 are legitimate) */
        REQUIRE(flag == LGN_SUCCESS || flag == LGN_TSTOP_RETURN || flag == LGN_ROOT_RETURN,
                "the sane model %d (solver %d) does not go on after the fault was removed: %s",
                o->model, o->solver, LGNGetReturnFlagName(flag));
      }
      break;
    }
    case OP_FREE:
      LGNFree(&o->mem);
      REQUIRE(o->mem == NULL, "LGNFree did not clear the pointer");
      o->freed = 1;
      o->sane  = 0;
      break;
    case OP_CALCIC: {
      const unsigned s = U8(in);
      /* LGN_IC_PROJECT_Q, _V, _QV, and two illegal options */
      if (!o->huge_m || !o->mem) {
        flag = CheckFlag(o, LGNCalcIC(mem, LGN_IC_PROJECT_Q - 1 + (int)(s % 5)), "LGNCalcIC");
        if (trace) fprintf(stderr, "  LGNCalcIC(%d) -> %d\n", LGN_IC_PROJECT_Q - 1 + (int)(s % 5), flag);
      }
      o->known = 0;
      o->sane  = 0;
      break;
    }
    case OP_MISC: {
      const unsigned s = U8(in);
      double am, af, b, g;
      if (s & 1) CheckFlag(o, LGNResetSparsityPattern(mem), "LGNResetSparsityPattern");
      if (s & 2) CheckFlag(o, LGNSetErrFile(mem, NULL), "LGNSetErrFile");
      if (s & 4) {
        /* rho_inf -0.08 ... 1.2, an output NULL with bit 3; without a memory
         * block its messages go to stderr, pointed at /dev/null here */
        const double rho = ((double)U8(in) - 16.0) / 200.0;
        int fd = -1;
        if (null_fd >= 0 && saved_fd < 0) {
          fflush(stderr);
          fd = dup(2);
          if (fd >= 0) dup2(null_fd, 2);
        }
        flag = LGNGenAlphaFromRhoInf(rho, &am, &af, &b, (s & 8) ? NULL : &g);
        if (fd >= 0) {
          fflush(stderr);
          dup2(fd, 2);
          close(fd);
        }
        REQUIRE(flag == ((rho >= 0.0 && rho <= 1.0 && !(s & 8)) ? 0 : LGN_ILL_INPUT),
                "LGNGenAlphaFromRhoInf(%g) returned %d", rho, flag);
        if (flag == 0)
          REQUIRE(am < 1.0 && af < 1.0 && b > 0.0 && g > 0.0 &&
                      fabs(g - (0.5 + af - am)) <= 1e-14,
                  "LGNGenAlphaFromRhoInf(%g): alpha_m %g alpha_f %g beta %g gamma %g", rho,
                  am, af, b, g);
      }
      if (s & 8) {
        /* a restart file written and read back into the same integrator,
         * one byte flipped (s & 16): a refused file changes nothing, and
         * the integrator's own file read back changes no output */
        char name[64];
        Snapshot sa, sb;
        snprintf(name, sizeof name, "/tmp/lgn_fuzz_%ld.lgr", (long)getpid());
        flag = CheckFlag(o, LGNWriteRestart(mem, name), "LGNWriteRestart");
        if (flag == 0) {
          const unsigned at = U8(in) * 64u + U8(in);
          int flipped = 0;
          if (s & 16) {
            FILE *fp = fopen(name, "r+b");
            int c;
            if (fp != NULL && fseek(fp, (long)at, SEEK_SET) == 0 && (c = fgetc(fp)) != EOF &&
                fseek(fp, (long)at, SEEK_SET) == 0)
              flipped = fputc(c ^ (int)(1u + (s >> 5)), fp) != EOF;
            if (fp != NULL) flipped = fclose(fp) == 0 && flipped;
          }
          Snap(o, &sa);
          flag = CheckFlag(o, LGNReadRestart(mem, name), "LGNReadRestart");
          Snap(o, &sb);
          REQUIRE(memcmp(&sa, &sb, sizeof sa) == 0,
                  "LGNReadRestart (%s, %s file) changed the outputs", LGNGetReturnFlagName(flag),
                  flipped ? "a corrupted" : "its own");
          REQUIRE(!flipped || flag == LGN_RESTART_BAD_FILE,
                  "LGNReadRestart of a file with byte %u flipped returned %s", at,
                  LGNGetReturnFlagName(flag));
          remove(name);
        }
        flag = 0;
      }
      break;
    }
    case OP_JOINTS: {
      /* bad input to the joint helpers of this object (or NULL) */
      const unsigned s = U8(in);
      const double p[3] = {Real(in), 0.0, 0.1}, ax[3] = {0.0, 0.0, (s & 8) ? 0.0 : 1.0};
      char buf[64];
      LGNJoints J = (s & 1) ? o->J : NULL;
      const int a = (int)(s >> 4) % 4 - 2, bb = (int)(U8(in) % 4) - 2;
      if (J == NULL) break; /* J = NULL writes to stderr */
      flag = LGNJoints_DescribeConstraint(J, (sunindextype)(U8(in) % 12) - 1, (s & 2) ? buf : NULL,
                                          (s & 4) ? sizeof buf : (size_t)(U8(in) % 3));
      REQUIRE(flag <= 0, "LGNJoints_DescribeConstraint returned %d", flag);
      if (U8(in) % 4 == 0) {
        /* adds a joint to the set in use: the model's m no longer fits */
        flag = (s & 2) ? LGNJoints_AddSpherical(J, a, p, bb, (s & 4) ? NULL : p)
                       : LGNJoints_AddUniversal(J, a, p, ax, bb, p, ax);
        REQUIRE(flag <= 0, "LGNJoints_Add returned %d", flag);
        o->sane = 0;
      }
      break;
    }
    case OP_BDF: {
      /* maxord -1 ... 6 (-1, 0 and 6 illegal); with bit 6 the form (bits
       * 3-4): the two forms and two illegal values */
      static const int form[4] = {LGN_BDF_VARIABLE_COEFF, LGN_BDF_FIXED_LEADING, 7, -1};
      const unsigned s = U8(in);
      flag = CheckFlag(o, LGNSetBDF(mem, (int)(s & 7) - 1), "LGNSetBDF");
      if (trace) fprintf(stderr, "  LGNSetBDF(%d) -> %d, form %d\n", (int)(s & 7) - 1, flag,
                         form[(s >> 3) & 3]);
      if (s & 0x40) CheckFlag(o, LGNSetBDFForm(mem, form[(s >> 3) & 3]), "LGNSetBDFForm");
      o->sane = 0;
      break;
    }
    case OP_ROOTS: {
      /* nrtfn -1 ... 3 (g NULL with bit 3); the levels; directions (with
       * bit 4; an illegal 2 among them); the fault of g (bit 5) */
      const unsigned s = U8(in);
      const int n = (int)(s % 5) - 1;
      int dir[3];
      o->rt_time = Param(in, 5e-3);
      o->rt_k    = (int)U8(in);
      o->rt_q    = N_VGetArrayPointer(o->q0)[o->rt_k % o->nq] + Real(in) * 1e-3;
      o->rt_j    = (int)U8(in);
      o->rt_v    = N_VGetArrayPointer(o->v0)[o->rt_j % o->nv] + Real(in) * 1e-2;
      /* a level that is not finite makes g so: LGN_RTFUNC_FAIL is then the
       * right answer, and the set-up is not sane any more */
      if (!isfinite(o->rt_time) || !isfinite(o->rt_q) || !isfinite(o->rt_v)) o->sane = 0;
      flag = CheckFlag(o, LGNRootInit(mem, n, (s & 8) ? NULL : Roots), "LGNRootInit");
      if (trace) fprintf(stderr, "  LGNRootInit(%d) -> %d, t %g\n", n, flag, o->rt_time);
      if (flag == 0) {
        o->nrt = n;
        o->rootdir[0] = o->rootdir[1] = o->rootdir[2] = 0;
        o->root_returned = 0;
      }
      if (s & 16) {
        for (i = 0; i < 3; i++) dir[i] = (int)(U8(in) % 4) - 1;
        flag = CheckFlag(o, LGNSetRootDirection(mem, (s & 128) ? NULL : dir),
                         "LGNSetRootDirection");
        if (flag == 0) {
          REQUIRE(!(s & 128), "LGNSetRootDirection(NULL) accepted");
          for (i = 0; i < o->nrt; i++) {
            REQUIRE(dir[i] >= -1 && dir[i] <= 1, "the direction %d accepted", dir[i]);
            o->rootdir[i] = dir[i];
          }
        }
      }
      o->rt_fault_kind = 0;
      if (s & 32) {
        o->rt_fault_kind = 1 + (int)(U8(in) % NFAULT);
        o->rt_fault_at   = o->rt_calls + 1 + (long)(U8(in) % 8);
      }
      if (s & 64) CheckFlag(o, LGNSetNoInactiveRootWarn(mem), "LGNSetNoInactiveRootWarn");
      break;
    }
    case OP_KRYLOV: {
      /* a matrix-free Krylov solver (n = nv + m, or one less; SPTFQMR or PCG
       * with bit 4 of p), given with a matrix (refused) or without; a
       * preconditioner: none, the block
       * preconditioner with nblocks -1 ... 2 (a partition or NULL), the
       * identity as a user preconditioner, or switched off */
      const unsigned s = U8(in), p = U8(in);
      const sunindextype n = o->nv + o->m - ((s & 4) ? 1 : 0);
      const int nb = (int)(p % 4) - 1;
      const long nbodies = o->model == MOD_JOINTS || o->model == MOD_BODIES ? 2 : 1;
      long part[3] = {(p & 128) ? 1 : 0, (long)(p >> 2) % 3, nbodies};
      if (nb == 1) part[1] = nbodies;
      MakeSolver(o, (p & 16) ? 7 + (int)(s & 1) : 3 + (int)(s % 4), n);
      if (trace) fprintf(stderr, "  Krylov %u, n %ld, flags 0x%02x 0x%02x\n", s % 4, (long)n, s, p);
      if (s & 8) CheckFlag(o, LGNSetLinearSolver(mem, o->LS, o->oldA[0]), "LGNSetLinearSolver");
      CheckFlag(o, LGNSetLinearSolver(mem, o->LS, NULL), "LGNSetLinearSolver");
      switch ((s >> 4) % 4) {
      case 1:
        CheckFlag(o, LGNSetBlockPreconditioner(mem, nb, (p & 64) ? part : NULL),
                  "LGNSetBlockPreconditioner");
        break;
      case 2:
        CheckFlag(o, LGNSetPreconditioner(mem, PrecSetup, PrecSolve), "LGNSetPreconditioner");
        /* bit 5 of p: a fault of the setup or the solve at call 1, 6, 11
         * or 16 (the first ones are the initial values') */
        o->pc_fault = (p & 32) ? 1 + (int)((p >> 2) % 4) : 0;
        o->pc_setups = o->pc_solves = 0;
        o->pc_fault_at = 1 + 5 * (long)(p % 4);
        break;
      case 3:
        CheckFlag(o, LGNSetPreconditioner(mem, (p & 128) ? PrecSetup : NULL, NULL),
                  "LGNSetPreconditioner");
        break;
      default: break;
      }
      if (s & 64) CheckFlag(o, LGNSetEpsLin(mem, Param(in, 0.05)), "LGNSetEpsLin");
      if (s & 128) CheckFlag(o, LGNSetAcceptStalls(mem, (p & 1) ? SUNTRUE : 3), "LGNSetAcceptStalls");
      o->sane = 0;
      break;
    }
    case OP_BODIES: {
      /* the body helpers' input checks (on a copy-free path: a body set of
       * the object's group, or the model's own set, whose energies are
       * checked to be finite), and the joint helpers' other joints */
      const unsigned s = U8(in);
      const double x = Real(in), J3[3] = {x, 0.5, (s & 2) ? 5.0 : 0.7},
                   I9[9] = {0.4, x, 0, 0.0, 0.5, 0, 0, 0, 0.6}, pt[3] = {0.1, x, 0.0},
                   ax[3] = {0, (s & 4) ? 0.0 : 1.0, 0}, gv[3] = {0, x, -1},
                   rest[4] = {1.0, x, 0.0, 0.0}; /* a unit quaternion for x = 0 */
      const int a = (int)(U8(in) % 4) - 2, b = (int)(U8(in) % 4) - 2;
      double ek = 0.0, ep = 0.0;
      LGNBodies B;
      if (o->model == MOD_OSC) break; /* R^n: refused with a message on stderr */
      B = LGNBodies_Create(o->G);
      REQUIRE(B != NULL, "LGNBodies_Create refused the model's group");
      LGNBodies_SetErrFile(B, NULL);
      REQUIRE(LGNBodies_NumBodies(B) == LGNBodies_NumOwnedBodies(B), "owned bodies");
      REQUIRE(LGNBodies_SetPrincipalInertia(B, a, x, J3) <= 0, "SetPrincipalInertia");
      REQUIRE(LGNBodies_SetMass(B, b, 1.0, I9) <= 0, "SetMass");
      REQUIRE(LGNBodies_SetGravity(B, gv) == (isfinite(x) ? 0 : LGN_ILL_INPUT), "SetGravity");
      REQUIRE(LGNBodies_AddSpringDamper(B, a, pt, b, pt, x, 0.1, 0.0) <= 0, "AddSpringDamper");
      REQUIRE(LGNBodies_AddRotationalSpringDamper(B, a, b, 1.0, x, (s & 8) ? NULL : rest) <= 0,
              "AddRotationalSpringDamper");
      REQUIRE(LGNBodies_SetGhosts(B, (int)(s >> 4) % 4) <= 0, "SetGhosts");
      REQUIRE(LGNBodies_MassNnz(B) >= 0 && LGNBodies_TangentNnz(B) >= 0, "nnz");
      InitialState(o, N_VGetArrayPointer(o->q0), N_VGetArrayPointer(o->v0));
      flag = LGNBodies_Energy(B, o->q0, o->v0, (s & 1) ? NULL : &ek, &ep);
      REQUIRE(flag <= 0 && (flag < 0 || !(fabs(x) <= 1e100) || (isfinite(ek) && isfinite(ep))),
              "LGNBodies_Energy %d: %g %g", flag, ek, ep);
      REQUIRE(LGNBodies_Mass(B, o->qbad, o->Md ? o->Md : o->A) < 0, "LGNBodies_Mass(bad q)");
      REQUIRE(LGNBodies_Force(B, o->q0, o->vbad, o->tmp) < 0, "LGNBodies_Force(bad v)");
      if (o->Md) {
        SUNMatZero(o->Md);
        REQUIRE(LGNBodies_Stiffness(B, o->q0, o->v0, o->Md) <= 0 &&
                    LGNBodies_Damping(B, o->q0, o->v0, o->Md) <= 0 &&
                    LGNBodies_MassFn(0.0, o->q0, o->Md, B) <= 0 &&
                    LGNBodies_StiffnessFn(0.0, o->q0, o->v0, NULL, NULL, o->Md, B) <= 0 &&
                    LGNBodies_DampingFn(0.0, o->q0, o->v0, o->Md, B) <= 0 &&
                    LGNBodies_ForceFn(0.0, o->q0, o->v0, o->tmp, B) <= 0,
                "the body helpers' callbacks");
      }
      LGNBodies_Destroy(&B);
      REQUIRE(B == NULL, "LGNBodies_Destroy did not clear the pointer");
      if (o->J && U8(in) % 4 == 0) {
        /* other joint types on the object's set: the model's m no longer fits */
        const double off[3] = {0.0, 0.0, 0.2};
        switch (s % 5) {
        case 0: flag = LGNJoints_AddPrismatic(o->J, a, pt, ax, b, off, ax); break;
        case 1: flag = LGNJoints_AddCylindrical(o->J, a, pt, ax, b, off, ax); break;
        case 2: flag = LGNJoints_AddTranslationDriver(o->J, a, pt, ax, b, off, Drive, NULL); break;
        case 3: flag = LGNJoints_AddRevolute(o->J, a, pt, ax, b, off, ax); break;
        default: flag = LGNJoints_AddUniversal(o->J, a, pt, ax, b, off, gv); break;
        }
        REQUIRE(flag <= 0, "LGNJoints_Add returned %d", flag);
        o->sane = 0;
      }
      break;
    }
    case OP_GETTERS2: {
      /* the getters of the settings, BDF's orders, events and Krylov */
      long l = 0, l2 = 0, l3 = 0, l4 = 0, nst[6];
      double x = 0.0, y = 0.0, z = 0.0, w = 0.0;
      int ival = 0, found[4];
      const unsigned s = U8(in);
      long *lp = (s & 1) ? NULL : &l;
      flag = CheckFlag(o, LGNGetCurrentOrder(mem, (s & 2) ? NULL : &ival), "LGNGetCurrentOrder");
      if (flag == 0 && !(s & 2)) REQUIRE(ival >= 0 && ival <= 5, "order %d", ival);
      CheckFlag(o, LGNGetLastOrder(mem, &ival), "LGNGetLastOrder");
      CheckFlag(o, LGNGetNumStepsAtOrder(mem, (s & 4) ? NULL : nst), "LGNGetNumStepsAtOrder");
      CheckFlag(o, LGNGetIntegratorStats(mem, lp, &l2, &l3, &l4, &x, &y, &z, (s & 8) ? NULL : &w),
                "LGNGetIntegratorStats");
      CheckFlag(o, LGNGetNewtonStats(mem, &l, lp), "LGNGetNewtonStats");
      CheckFlag(o, LGNGetStepSize(mem, &x), "LGNGetStepSize");
      CheckFlag(o, LGNGetKinematics(mem, &ival), "LGNGetKinematics");
      CheckFlag(o, LGNGetConstraintIndex(mem, &ival), "LGNGetConstraintIndex");
      CheckFlag(o, LGNGetNewtonMode(mem, &ival), "LGNGetNewtonMode");
      CheckFlag(o, LGNGetStepControl(mem, &ival), "LGNGetStepControl");
      CheckFlag(o, LGNGetTolerances(mem, &x, (s & 16) ? NULL : &y), "LGNGetTolerances");
      CheckFlag(o, LGNGetNumGEvals(mem, lp), "LGNGetNumGEvals");
      CheckFlag(o, LGNGetRootInfo(mem, (s & 32) ? NULL : found), "LGNGetRootInfo");
      CheckFlag(o, LGNGetNumLinIters(mem, lp), "LGNGetNumLinIters");
      CheckFlag(o, LGNGetNumPrecEvals(mem, &l), "LGNGetNumPrecEvals");
      CheckFlag(o, LGNGetNumPrecSolves(mem, &l), "LGNGetNumPrecSolves");
      CheckFlag(o, LGNGetNumJtimesEvals(mem, &l), "LGNGetNumJtimesEvals");
      CheckFlag(o, LGNGetNumLinConvFails(mem, &l), "LGNGetNumLinConvFails");
      if (s & 64) CheckFlag(o, LGNPrintAllStats(mem, devnull, (int)(s >> 7)), "LGNPrintAllStats");
      break;
    }
    default: break;
    }
    if (saved_fd >= 0) {
      fflush(stderr);
      dup2(saved_fd, 2);
      close(saved_fd);
      saved_fd = -1;
    }
    (void)flag;
  }
  for (k = 0; k < NOBJ; k++) ObjDestroy(&objs[k]);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  In in = {data, size, 0};
  trace  = getenv("LGN_FUZZ_TRACE") != NULL;
  if (devnull == NULL) {
    devnull = fopen("/dev/null", "w");
    if (devnull) null_fd = fileno(devnull);
  }
  if (SUNContext_Create(NULL, &ctx) != 0) abort();
  spare_group = LGNGroup_Rn(5);
  steps_left = MAX_STEPS_PER_INPUT;
  Run(&in);
  LGNGroup_Destroy(spare_group);
  SUNContext_Free(&ctx);
  return 0;
}
