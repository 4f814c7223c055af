/* -----------------------------------------------------------------------------
 * The step-failure policy both families share (lgn_failure.c, IDA's
 * IDAHandleNFlag): an iteration matrix that is singular at a large step is
 * retried with smaller steps under error control, in the Newmark family as
 * under BDF; a matrix that stays singular ends the run with LGN_LSETUP_FAIL
 * and the state at t_n kept (fixed steps; error control at hmin).
 *
 * The model: a linear spring on R^1, M = 1, g = k q (k = 100), so that
 * q(t) = cos(10 t) from q0 = 1, v0 = 0. The linear solver is SUNDIALS'
 * dense one whose setup refuses (SUNLS_LUFACT_FAIL, a recoverable failure,
 * as a zero pivot is) every matrix whose entry A(0,0) exceeds 2: the
 * scaled iteration matrix's entry is about M (1 - am)/(1 - af) + beta h^2 k
 * (Newmark family) or M + k / c0^2 (BDF), so every step longer than about
 * 0.17 (Newmark) or 0.1 (BDF) meets a "singular" matrix.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_group.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

static int failures = 0;
#define CHECK(cond, ...)                                  \
  do {                                                    \
    if (!(cond)) {                                        \
      printf("FAIL %s:%d: ", __FILE__, __LINE__);         \
      printf(__VA_ARGS__);                                \
      printf("\n");                                       \
      failures++;                                         \
    }                                                     \
  } while (0)

#define K_SPRING   100.0
#define A00_LIMIT  2.0

static char last_msg[1024];
static long refused = 0; /* setups refused by RefusingSetup */
static int (*dense_setup)(SUNLinearSolver, SUNMatrix) = NULL;

static void Capture(int code, const char *module, const char *fn, const char *msg, void *d)
{
  (void)code; (void)module; (void)d;
  snprintf(last_msg, sizeof last_msg, "%s: %s", fn, msg);
}

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  (void)t; (void)q; (void)ud;
  SM_ELEMENT_D(M, 0, 0) = 1.0;
  return 0;
}

static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  (void)t; (void)v; (void)ud;
  NV_Ith_S(g, 0) = K_SPRING * NV_Ith_S(q, 0);
  return 0;
}

static int Stiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot, N_Vector lambda,
                     SUNMatrix K, void *ud)
{
  (void)t; (void)q; (void)v; (void)vdot; (void)lambda; (void)ud;
  SM_ELEMENT_D(K, 0, 0) = K_SPRING;
  return 0;
}

/* the dense setup, refusing a matrix with A(0,0) > A00_LIMIT as singular */
static int RefusingSetup(SUNLinearSolver LS, SUNMatrix A)
{
  if (SM_ELEMENT_D(A, 0, 0) > A00_LIMIT) {
    refused++;
    return SUNLS_LUFACT_FAIL;
  }
  return dense_setup(LS, A);
}

typedef struct {
  int flag;          /* LGNSolve's                                   */
  double t, q;       /* where it stopped, q there                    */
  double h0;         /* the first step size tried (error control)    */
  long refused;      /* singular setups                              */
} Result;

/* family: 0 Newmark (generalized-alpha, the default), 1 BDF; h > 0: fixed
 * steps of h, else error control from the initial step 1 (hmin: its
 * minimum, 0 for none). */
static Result Run(int family, double h, double hmin, double tout)
{
  SUNContext ctx = NULL;
  N_Vector q0, v0, tmp, qo, vo;
  SUNMatrix A;
  SUNLinearSolver LS;
  LGNGroup G;
  void *mem;
  Result r;
  sunrealtype t = 0.0, h0 = 0.0;
  int flag;
  memset(&r, 0, sizeof r);
  SUNContext_Create(NULL, &ctx);
  q0  = N_VNew_Serial(1, ctx);
  v0  = N_VNew_Serial(1, ctx);
  qo  = N_VNew_Serial(1, ctx);
  vo  = N_VNew_Serial(1, ctx);
  tmp = N_VNew_Serial(1, ctx);
  NV_Ith_S(q0, 0) = 1.0;
  NV_Ith_S(v0, 0) = 0.0;
  A  = SUNDenseMatrix(1, 1, ctx);
  LS = SUNLinSol_Dense(tmp, A, ctx);
  dense_setup     = LS->ops->setup;
  LS->ops->setup  = RefusingSetup;
  refused         = 0;
  G    = LGNGroup_Rn(1);
  mem  = LGNCreate(ctx);
  flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetErrHandlerFn(mem, Capture, NULL);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetStiffnessFn(mem, Stiffness);
  if (!flag) flag = LGNInit(mem, 0.0, q0, v0);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag && family == 1) flag = LGNSetBDF(mem, 5);
  if (!flag && h > 0.0) flag = LGNSetStepSize(mem, h);
  if (!flag && h <= 0.0) {
    flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
    if (!flag) flag = LGNSStolerances(mem, 1e-7, 1e-7);
    if (!flag) flag = LGNSetInitStep(mem, 1.0);
    if (!flag && hmin > 0.0) flag = LGNSetMinStep(mem, hmin);
  }
  last_msg[0] = '\0';
  if (!flag) {
    flag = LGNSolve(mem, tout, &t, qo, vo, LGN_NORMAL);
    LGNGetCurrentTime(mem, &t);
    LGNGetActualInitStep(mem, &h0);
  }
  r.flag    = flag;
  r.t       = t;
  r.q       = NV_Ith_S(qo, 0);
  r.h0      = h0;
  r.refused = refused;
  LGNFree(&mem);
  LGNGroup_Destroy(G);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(q0);
  N_VDestroy(v0);
  N_VDestroy(qo);
  N_VDestroy(vo);
  N_VDestroy(tmp);
  SUNContext_Free(&ctx);
  return r;
}

int main(void)
{
  static const char *name[2] = {"Newmark family", "BDF"};
  int family;
  for (family = 0; family < 2; family++) {
    /* error control from h0 = 1: singular at 1 and 1/4, recovered by cuts */
    Result r = Run(family, 0.0, 0.0, 1.0);
    const double err = fabs(r.q - cos(10.0));
    printf("%s, error control from h0 = 1: flag %d, t = %g, |q - cos(10)| = %.2e, "
           "%ld singular setups\n", name[family], r.flag, r.t, err, r.refused);
    CHECK(r.flag == LGN_SUCCESS, "%s: recovered from the singular matrix: flag %d (%s)",
          name[family], r.flag, last_msg);
    CHECK(r.h0 == 1.0, "%s: the first step tried is 1 (got %g)", name[family], r.h0);
    CHECK(r.refused >= 2, "%s: singular at h = 1 and 1/4 (%ld refused)", name[family],
          r.refused);
    CHECK(r.flag == LGN_SUCCESS && err < 1e-4, "%s: q(1) = %.10f, cos(10) = %.10f",
          name[family], r.q, cos(10.0));

    /* error control with hmin = 0.3: singular at hmin, LGN_LSETUP_FAIL */
    r = Run(family, 0.0, 0.3, 1.0);
    printf("%s, error control, hmin = 0.3: flag %d, t = %g\n", name[family], r.flag, r.t);
    CHECK(r.flag == LGN_LSETUP_FAIL, "%s, hmin 0.3: LGN_LSETUP_FAIL expected, got %d",
          name[family], r.flag);
    CHECK(r.t == 0.0, "%s, hmin 0.3: the state at t = 0 kept (t = %g)", name[family], r.t);
    CHECK(strstr(last_msg, "singular") != NULL && strstr(last_msg, "minimum step") != NULL,
          "%s, hmin 0.3: the message names the singular matrix at hmin: %s", name[family],
          last_msg);

    /* fixed steps of 0.5: no smaller step to try, the run stops at t = 0 */
    r = Run(family, 0.5, 0.0, 1.0);
    printf("%s, fixed h = 0.5: flag %d, t = %g\n", name[family], r.flag, r.t);
    CHECK(r.flag == LGN_LSETUP_FAIL, "%s, fixed h: LGN_LSETUP_FAIL expected, got %d",
          name[family], r.flag);
    CHECK(r.t == 0.0, "%s, fixed h: the state at t = 0 kept (t = %g)", name[family], r.t);
  }
  if (failures) printf("%d check(s) failed\n", failures);
  else printf("test_step_failure: all checks passed\n");
  return failures ? 1 : 0;
}
