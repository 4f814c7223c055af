/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Unit test of the joint sets' own error reporting (lignum_joints.h, issue
 * 18 item 3: a joint set kept the integrator's memory only to report errors,
 * and read it after LGNFree). Checked:
 *  - a joint set used with an integrator that is then freed (LGNFree), and
 *    one with no integrator at all: a bad call returns LGN_ILL_INPUT and the
 *    message reaches the joint set's handler, under the public function's
 *    name, naming the bad argument; the integrator's handler sees nothing
 *    (and no freed memory is read: run under valgrind and ASan);
 *  - every checking function reports under its own public name (never an
 *    internal helper's) and names the argument;
 *  - the default handler writes "[LGN ERROR]  function\n  message" to
 *    stderr, LGNJoints_SetErrFile redirects it, NULL silences it;
 *  - a handler replaced by another, and NULL restoring the default;
 *  - J = NULL to the setters (and the other functions): LGN_ILL_INPUT, no
 *    crash, the message on stderr; LGNJoints_Create(NULL) and a group
 *    without rigid bodies: NULL, the message on stderr.
 * stderr is captured in a temporary file around the calls that write to it.
 * ---------------------------------------------------------------------------*/

#define _POSIX_C_SOURCE 200809L /* dup, dup2, fileno */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <lignum/lignum.h>
#include <lignum/lignum_joints.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

static int failures = 0;

static void Expect(int ok, const char *what)
{
  printf("%-72s %s\n", what, ok ? "ok" : "FAIL");
  if (!ok) failures++;
}

/* What an error handler saw (its eh_data). */
typedef struct {
  int count;
  int code;
  char function[128];
  char msg[512];
} ErrRecord;

/* LGNErrHandlerFn recording the last error in the ErrRecord eh_data. */
static void RecordError(int error_code, const char *module, const char *function,
                        const char *msg, void *eh_data)
{
  ErrRecord *rec = (ErrRecord *)eh_data;
  (void)module;
  rec->count++;
  rec->code = error_code;
  snprintf(rec->function, sizeof rec->function, "%s", function);
  snprintf(rec->msg, sizeof rec->msg, "%s", msg);
}

/* The last call was refused with flag and reported once more to rec under
 * function, with a message containing text. */
static void ExpectReported(const char *what, int flag, const ErrRecord *rec,
                           int count_before, const char *function, const char *text)
{
  char line[256];
  const int ok = flag == LGN_ILL_INPUT && rec->count == count_before + 1 &&
                 rec->code == LGN_ILL_INPUT && strcmp(rec->function, function) == 0 &&
                 strstr(rec->msg, text) != NULL;
  snprintf(line, sizeof line, "%s", what);
  Expect(ok, line);
  if (!ok)
    printf("  flag %d, %d reports, last: %s: %s\n", flag, rec->count - count_before,
           rec->function, rec->msg);
}

/* Contents of a stream written so far (at most len - 1 characters). */
static void ReadBack(FILE *fp, char *buf, size_t len)
{
  size_t n;
  fflush(fp);
  rewind(fp);
  n = fread(buf, 1, len - 1, fp);
  buf[n] = '\0';
}

/* Capture what is written to stderr between StderrBegin and StderrEnd. */
typedef struct {
  FILE *tmp;
  int saved;
} StderrCapture;

static int StderrBegin(StderrCapture *c)
{
  fflush(stderr);
  c->tmp   = tmpfile();
  c->saved = dup(fileno(stderr));
  if (c->tmp == NULL || c->saved < 0 || dup2(fileno(c->tmp), fileno(stderr)) < 0) return -1;
  return 0;
}

static void StderrEnd(StderrCapture *c, char *buf, size_t len)
{
  fflush(stderr);
  dup2(c->saved, fileno(stderr));
  close(c->saved);
  ReadBack(c->tmp, buf, len);
  fclose(c->tmp);
}

static const sunrealtype s[3] = {0.0, 0.0, 0.5}, axis[3] = {0.0, 0.0, 1.0};
static const sunrealtype zero[3] = {0.0, 0.0, 0.0};

/* A joint set used with an integrator that is freed before the bad call. */
static void CheckAfterLGNFree(SUNContext ctx, LGNGroup G)
{
  ErrRecord rec = {0}, mem_rec = {0};
  void *mem = LGNCreate(ctx);
  LGNJoints J;
  int flag;
  Expect(mem != NULL && LGNSetErrHandlerFn(mem, RecordError, &mem_rec) == LGN_SUCCESS,
         "LGNCreate, LGNSetErrHandlerFn");
  J = LGNJoints_Create(G);
  Expect(J != NULL, "LGNJoints_Create(G) beside an integrator");
  Expect(LGNJoints_SetErrHandlerFn(J, RecordError, &rec) == LGN_SUCCESS,
         "LGNJoints_SetErrHandlerFn");
  flag = LGNJoints_AddSpherical(J, 7, s, 0, s);
  ExpectReported("bad body, integrator alive: the joint set's handler", flag, &rec, 0,
                 "LGNJoints_AddSpherical", "a = 7");
  Expect(mem_rec.count == 0, "  ... and not the integrator's");
  LGNFree(&mem);
  Expect(mem == NULL, "LGNFree");
  flag = LGNJoints_AddSpherical(J, 0, s, 9, s);
  ExpectReported("bad body after LGNFree: the joint set's handler", flag, &rec, 1,
                 "LGNJoints_AddSpherical", "b = 9");
  flag = LGNJoints_AddRevolute(J, 0, s, zero, 1, s, axis);
  ExpectReported("zero axis after LGNFree: names axis_a", flag, &rec, 2,
                 "LGNJoints_AddRevolute", "axis_a");
  Expect(mem_rec.count == 0, "the freed integrator's handler saw nothing");
  Expect(LGNJoints_NumConstraints(J) == 0, "refused joints add no constraint");
  Expect(LGNJoints_AddSpherical(J, LGN_GROUND, s, 0, s) == LGN_SUCCESS && rec.count == 3,
         "a good joint after LGNFree: LGN_SUCCESS, no report");
  LGNJoints_Destroy(&J);
}

/* Every checking function, on a set never used with an integrator: its own
 * public name and the argument in the message. */
static void CheckEveryFunction(SUNContext ctx, LGNGroup G)
{
  ErrRecord rec = {0};
  LGNJoints J = LGNJoints_Create(G);
  N_Vector q = N_VNew_Serial(G->nq, ctx), v = N_VNew_Serial(G->nv, ctx);
  N_Vector phi, lam, f = N_VNew_Serial(G->nv, ctx), bad = N_VNew_Serial(2, ctx);
  SUNMatrix B, K, wrong = SUNDenseMatrix(2, 2, ctx);
  sunindextype m;
  int n = 0, k;

  if (J == NULL || LGNJoints_SetErrHandlerFn(J, RecordError, &rec) != LGN_SUCCESS) {
    Expect(0, "LGNJoints_Create, LGNJoints_SetErrHandlerFn (no integrator)");
    return;
  }
  N_VConst(0.0, q);
  N_VConst(0.0, v);
  for (k = 0; k < 2; k++) {
    N_VGetArrayPointer(q)[7 * k + 3] = 1.0; /* identity rotations */
  }
  LGNJoints_AddRevolute(J, 0, s, axis, 1, s, axis);
  m   = LGNJoints_NumConstraints(J);
  phi = N_VNew_Serial(m, ctx);
  lam = N_VNew_Serial(m, ctx);
  N_VConst(1.0, lam);
  B = SUNDenseMatrix(m, G->nv, ctx);
  K = SUNDenseMatrix(G->nv, G->nv, ctx);

  ExpectReported("AddSpherical a = b", LGNJoints_AddSpherical(J, 1, s, 1, s), &rec, n++,
                 "LGNJoints_AddSpherical", "a = 1, b = 1");
  ExpectReported("AddSpherical sb = NULL", LGNJoints_AddSpherical(J, 0, s, 1, NULL), &rec,
                 n++, "LGNJoints_AddSpherical", "sb = NULL");
  ExpectReported("AddRevolute axis_b = NULL",
                 LGNJoints_AddRevolute(J, 0, s, axis, 1, s, NULL), &rec, n++,
                 "LGNJoints_AddRevolute", "axis_b = NULL");
  ExpectReported("AddUniversal bad body", LGNJoints_AddUniversal(J, -3, s, axis, 1, s, axis),
                 &rec, n++, "LGNJoints_AddUniversal", "a = -3");
  ExpectReported("AddUniversal zero axis_b", LGNJoints_AddUniversal(J, 0, s, axis, 1, s, zero),
                 &rec, n++, "LGNJoints_AddUniversal", "axis_b is zero");
  ExpectReported("Residual phi of the wrong length", LGNJoints_Residual(J, 0.0, q, bad), &rec, n++,
                 "LGNJoints_Residual", "phi is NULL or does not have length 5");
  ExpectReported("Residual q = NULL", LGNJoints_Residual(J, 0.0, NULL, phi), &rec, n++,
                 "LGNJoints_Residual", "q is NULL");
  ExpectReported("Jacobian B of the wrong size", LGNJoints_Jacobian(J, 0.0, q, wrong), &rec, n++,
                 "LGNJoints_Jacobian", "B must be");
  ExpectReported("ConstraintForce lambda of the wrong length",
                 LGNJoints_ConstraintForce(J, 0.0, q, bad, f), &rec, n++,
                 "LGNJoints_ConstraintForce", "lambda");
  ExpectReported("ConstraintForce f = NULL", LGNJoints_ConstraintForce(J, 0.0, q, lam, NULL), &rec,
                 n++, "LGNJoints_ConstraintForce", "f is NULL");
  ExpectReported("Curvature v of the wrong length", LGNJoints_Curvature(J, 0.0, q, bad, phi), &rec,
                 n++, "LGNJoints_Curvature", "v is NULL");
  ExpectReported("Curvature z of the wrong length", LGNJoints_Curvature(J, 0.0, q, v, bad), &rec,
                 n++, "LGNJoints_Curvature", "z is NULL");
  ExpectReported("Stiffness K of the wrong size", LGNJoints_Stiffness(J, 0.0, q, lam, wrong), &rec,
                 n++, "LGNJoints_Stiffness", "K must be");
  ExpectReported("Stiffness lambda of the wrong length", LGNJoints_Stiffness(J, 0.0, q, bad, K),
                 &rec, n++, "LGNJoints_Stiffness", "lambda");
  /* good calls report nothing */
  SUNMatZero(B);
  Expect(LGNJoints_Residual(J, 0.0, q, phi) == LGN_SUCCESS &&
             LGNJoints_Jacobian(J, 0.0, q, B) == LGN_SUCCESS &&
             LGNJoints_ConstraintForce(J, 0.0, q, lam, f) == LGN_SUCCESS &&
             LGNJoints_Curvature(J, 0.0, q, v, phi) == LGN_SUCCESS &&
             LGNJoints_Stiffness(J, 0.0, q, lam, K) == LGN_SUCCESS && rec.count == n,
         "good calls: LGN_SUCCESS, no report");

  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(phi);
  N_VDestroy(lam);
  N_VDestroy(f);
  N_VDestroy(bad);
  SUNMatDestroy(B);
  SUNMatDestroy(K);
  SUNMatDestroy(wrong);
  LGNJoints_Destroy(&J);
}

/* The default handler, its stream, and handlers replaced. */
static void CheckHandlersAndStreams(LGNGroup G)
{
  ErrRecord r1 = {0}, r2 = {0};
  LGNJoints J = LGNJoints_Create(G);
  StderrCapture cap;
  FILE *fp = tmpfile();
  char buf[2048];
  int flag;

  if (J == NULL || fp == NULL) {
    Expect(0, "LGNJoints_Create, tmpfile");
    return;
  }
  /* default: stderr, in the integrator's format */
  if (StderrBegin(&cap) == 0) {
    flag = LGNJoints_AddSpherical(J, 4, s, 0, s);
    StderrEnd(&cap, buf, sizeof buf);
    Expect(flag == LGN_ILL_INPUT &&
               strstr(buf, "[LGN ERROR]  LGNJoints_AddSpherical\n  bodies a = 4") != NULL,
           "default handler: \"[LGN ERROR]  LGNJoints_AddSpherical ...\" on stderr");
  } else {
    Expect(0, "capture stderr");
  }
  /* to a file, then silenced */
  Expect(LGNJoints_SetErrFile(J, fp) == LGN_SUCCESS, "LGNJoints_SetErrFile(J, fp)");
  flag = LGNJoints_AddSpherical(J, 0, s, 5, s);
  ReadBack(fp, buf, sizeof buf);
  Expect(flag == LGN_ILL_INPUT && strstr(buf, "[LGN ERROR]  LGNJoints_AddSpherical\n") != NULL &&
             strstr(buf, "b = 5") != NULL,
         "LGNJoints_SetErrFile: the message in the file");
  Expect(LGNJoints_SetErrFile(J, NULL) == LGN_SUCCESS, "LGNJoints_SetErrFile(J, NULL)");
  {
    const size_t before = strlen(buf);
    char out[2048] = "";
    if (StderrBegin(&cap) == 0) {
      flag = LGNJoints_AddSpherical(J, 0, s, 6, s);
      StderrEnd(&cap, out, sizeof out);
    } else {
      flag = LGNJoints_AddSpherical(J, 0, s, 6, s);
    }
    ReadBack(fp, buf, sizeof buf);
    Expect(flag == LGN_ILL_INPUT && strlen(buf) == before && out[0] == '\0',
           "LGNJoints_SetErrFile(J, NULL) silences (nothing in the file or on stderr)");
  }
  /* handlers: set, replaced, removed (back to the silenced stream) */
  Expect(LGNJoints_SetErrHandlerFn(J, RecordError, &r1) == LGN_SUCCESS, "handler 1 set");
  flag = LGNJoints_AddSpherical(J, 0, s, 8, s);
  ExpectReported("  handler 1 sees the error", flag, &r1, 0, "LGNJoints_AddSpherical", "b = 8");
  Expect(LGNJoints_SetErrHandlerFn(J, RecordError, &r2) == LGN_SUCCESS, "handler 2 replaces it");
  flag = LGNJoints_AddSpherical(J, 0, s, 10, s);
  ExpectReported("  handler 2 sees the error", flag, &r2, 0, "LGNJoints_AddSpherical", "b = 10");
  Expect(r1.count == 1, "  handler 1 no longer called");
  Expect(LGNJoints_SetErrFile(J, fp) == LGN_SUCCESS &&
             LGNJoints_SetErrHandlerFn(J, NULL, NULL) == LGN_SUCCESS,
         "handler NULL: the default again, on fp");
  flag = LGNJoints_AddSpherical(J, 0, s, 11, s);
  ReadBack(fp, buf, sizeof buf);
  Expect(flag == LGN_ILL_INPUT && r2.count == 1 && strstr(buf, "b = 11") != NULL,
         "  the default handler writes to fp, handler 2 not called");
  fclose(fp);
  LGNJoints_Destroy(&J);
  Expect(J == NULL, "LGNJoints_Destroy sets J to NULL");
}

/* NULL arguments with no joint set to report through: flags, no crash,
 * messages on stderr. */
static void CheckNoJointSet(SUNContext ctx, LGNGroup G)
{
  ErrRecord rec = {0};
  StderrCapture cap;
  LGNGroup Rn = LGNGroup_Rn(3);
  LGNJoints JR = NULL, JN = NULL;
  N_Vector q = N_VNew_Serial(G->nq, ctx);
  char buf[4096] = "";
  int f1 = 0, f2 = 0, f3 = 0, captured = StderrBegin(&cap) == 0;

  f1 = LGNJoints_SetErrHandlerFn(NULL, RecordError, &rec);
  f2 = LGNJoints_SetErrFile(NULL, stdout);
  f3 = LGNJoints_Residual(NULL, 0.0, q, q);
  JN = LGNJoints_Create(NULL);
  JR = LGNJoints_Create(Rn);
  if (captured) StderrEnd(&cap, buf, sizeof buf);
  Expect(f1 == LGN_ILL_INPUT && f2 == LGN_ILL_INPUT && rec.count == 0,
         "setters with J = NULL: LGN_ILL_INPUT, no handler called");
  Expect(f3 == LGN_ILL_INPUT, "LGNJoints_Residual(NULL, 0.0, ...): LGN_ILL_INPUT");
  Expect(JN == NULL && JR == NULL, "LGNJoints_Create(NULL), on R^3: NULL");
  if (captured) {
    Expect(strstr(buf, "[LGN ERROR]  LGNJoints_SetErrHandlerFn\n  J = NULL illegal.") != NULL &&
               strstr(buf, "[LGN ERROR]  LGNJoints_SetErrFile\n  J = NULL illegal.") != NULL &&
               strstr(buf, "[LGN ERROR]  LGNJoints_Residual\n  J = NULL illegal.") != NULL,
           "  J = NULL reported on stderr under the public names");
    Expect(strstr(buf, "[LGN ERROR]  LGNJoints_Create\n  G = NULL illegal.") != NULL &&
               strstr(buf, "[LGN ERROR]  LGNJoints_Create\n  G: the joint helpers need") != NULL,
           "  LGNJoints_Create's failures reported on stderr");
  } else {
    Expect(0, "capture stderr");
  }
  Expect(LGNJoints_NumBodies(NULL) == 0 && LGNJoints_NumConstraints(NULL) == 0 &&
             LGNJoints_JacobianNnz(NULL) == 0 && LGNJoints_StiffnessNnz(NULL) == 0,
         "sizes of J = NULL: 0");
  LGNJoints_Destroy(NULL);
  LGNJoints_Destroy(&JN);
  N_VDestroy(q);
  LGNGroup_Destroy(Rn);
}

int main(void)
{
  SUNContext ctx;
  LGNGroup body, G, factors[2];

  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  body       = LGNGroup_R3xSO3();
  factors[0] = factors[1] = body;
  G          = LGNGroup_Product(2, factors);
  if (body == NULL || G == NULL) return 1;

  CheckAfterLGNFree(ctx, G);
  CheckEveryFunction(ctx, G);
  CheckHandlersAndStreams(G);
  CheckNoJointSet(ctx, G);

  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  SUNContext_Free(&ctx);
  printf("%s\n", failures == 0 ? "PASSED" : "FAILED");
  return failures == 0 ? 0 : 1;
}
