#define _POSIX_C_SOURCE 200809L
/* Trajectories for ParaView (lignum_vtk.h), the writing half of the test
 * vtk_readback (check_vtk.py reads the files with VTK's own reader):
 *
 *   test_vtk_write DIR          four bodies (a box, a cylinder, a sphere, a
 *                               tetrahedron mesh) of a product of R^3 x SO(3)
 *                               and SE(3) leaves with an R^2 leaf between
 *                               (not drawn), joint frames on a body and on
 *                               the ground, at 3 output times with random
 *                               poses; the poses written to DIR/poses.txt
 *                               (%.17g) for the check; bad input refused
 *   test_vtk_write DIR N        N cylinders with a frame each, one output:
 *                               the time to write it (bench: N = 10000)
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lignum/lignum.h>
#include <lignum/lignum_vtk.h>
#include <nvector/nvector_serial.h>

static int failures = 0;
#define CHECK(c, ...)                                       \
  do {                                                      \
    if (!(c)) {                                             \
      failures++;                                           \
      printf("FAIL %s:%d: ", __FILE__, __LINE__);           \
      printf(__VA_ARGS__);                                  \
      printf("\n");                                         \
    }                                                       \
  } while (0)

static void Quiet(int code, const char *module, const char *func, const char *msg, void *d)
{
  (void)code; (void)module; (void)func; (void)msg;
  ++*(int *)d;
}

static double Uniform(unsigned int *s)
{
  *s = *s * 1103515245u + 12345u;
  return ((*s >> 8) & 0xFFFFFF) / (double)0x1000000;
}

/* A random pose at q + o: position in [-1, 1]^3, unit quaternion. */
static void RandomPose(unsigned int *s, sunrealtype *x)
{
  double n = 0.0;
  int i;
  for (i = 0; i < 3; i++) x[i] = 2.0 * Uniform(s) - 1.0;
  for (i = 3; i < 7; i++) {
    x[i] = 2.0 * Uniform(s) - 1.0;
    n += x[i] * x[i];
  }
  for (i = 3; i < 7; i++) x[i] /= sqrt(n);
}

static int Bench(const char *dir, int n, SUNContext ctx)
{
  LGNGroup body = LGNGroup_R3xSO3(), G;
  LGNGroup *f = malloc((size_t)n * sizeof(LGNGroup));
  const sunrealtype r[3] = {0.0, 0.0, 0.5};
  char base[512];
  unsigned int s = 7;
  N_Vector q;
  LGNVtk w;
  int k, flag = 0;
  struct timespec t0, t1;
  for (k = 0; k < n; k++) f[k] = body;
  G = LGNGroup_Product(n, f);
  q = N_VNew_Serial(G->nq, ctx);
  for (k = 0; k < n; k++) RandomPose(&s, N_VGetArrayPointer(q) + 7 * k);
  snprintf(base, sizeof base, "%s/bench", dir);
  w = LGNVtk_Create(G, base);
  for (k = 0; k < n && !flag; k++) flag = LGNVtk_SetCylinder(w, k, 0.02, 1.0);
  for (k = 0; k < n && !flag; k++) flag = LGNVtk_AddFrame(w, k, r, NULL, 0.1);
  clock_gettime(CLOCK_MONOTONIC, &t0);
  if (!flag) flag = LGNVtk_Write(w, 0.0, q);
  clock_gettime(CLOCK_MONOTONIC, &t1);
  printf("%d bodies (cylinders of 24 sides, one frame each): one output written in %.3f s "
         "(flag %d)\n", n, (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec),
         flag);
  LGNVtk_Destroy(&w);
  N_VDestroy(q);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  free(f);
  return flag == 0 ? 0 : 1;
}

int main(int argc, char **argv)
{
  SUNContext ctx;
  LGNGroup leaves[5], G;
  N_Vector q, qbad;
  LGNVtk w;
  FILE *fp;
  char base[512], name[600];
  unsigned int s = 36;
  int k, j, nmsg = 0, nb = -1;
  const sunrealtype tet[12] = {0, 0, 0, 0.3, 0, 0, 0, 0.2, 0, 0, 0, 0.1};
  const int tri[12]         = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  const int badtri[3]       = {0, 1, 4};
  const sunrealtype r[3] = {0.1, -0.2, 0.3}, R[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1};
  const sunrealtype qoff[4] = {0, 7, 16, 23}; /* q offsets of the bodies */
  if (argc < 2) return 2;
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  if (argc > 2) {
    int rc = Bench(argv[1], atoi(argv[2]), ctx);
    SUNContext_Free(&ctx);
    return rc;
  }
  leaves[0] = LGNGroup_R3xSO3();
  leaves[1] = LGNGroup_SE3();
  leaves[2] = LGNGroup_Rn(2);
  leaves[3] = LGNGroup_R3xSO3();
  leaves[4] = LGNGroup_SE3();
  G = LGNGroup_Product(5, leaves);
  q    = N_VNew_Serial(G->nq, ctx);
  qbad = N_VNew_Serial(G->nq - 1, ctx);
  snprintf(base, sizeof base, "%s/bodies", argv[1]);

  /* bad input */
  CHECK(LGNVtk_Create(NULL, base) == NULL, "G NULL accepted");
  CHECK(LGNVtk_Create(G, "") == NULL, "empty basename accepted");
  CHECK(LGNVtk_Create(leaves[2], base) == NULL, "a group without bodies accepted");
  w = LGNVtk_Create(G, base);
  CHECK(w != NULL, "LGNVtk_Create failed");
  if (w == NULL) return 1;
  LGNVtk_SetErrHandlerFn(w, Quiet, &nmsg);
  CHECK(LGNVtk_GetNumBodies(w, &nb) == 0 && nb == 4, "%d bodies, 4 expected", nb);
  CHECK(LGNVtk_SetBox(w, 4, 1, 1, 1) == LGN_ILL_INPUT, "body 4 accepted");
  CHECK(LGNVtk_SetBox(w, 0, 1, -1, 1) == LGN_ILL_INPUT, "ly < 0 accepted");
  CHECK(LGNVtk_SetCylinder(w, 1, NAN, 1) == LGN_ILL_INPUT, "radius NaN accepted");
  CHECK(LGNVtk_SetMesh(w, 3, 4, tet, 1, badtri) == LGN_ILL_INPUT, "point 4 of 4 accepted");
  CHECK(LGNVtk_AddFrame(w, -2, r, R, 0.1) == LGN_ILL_INPUT, "body -2 accepted");
  CHECK(LGNVtk_AddFrame(w, 0, NULL, R, 0.1) == LGN_ILL_INPUT, "r NULL accepted");
  CHECK(LGNVtk_Write(w, 0.0, qbad) == LGN_ILL_INPUT, "q of another length accepted");
  CHECK(nmsg == 7, "%d messages for 7 refusals", nmsg);

  /* the scene */
  CHECK(LGNVtk_SetBox(w, 0, 0.4, 0.2, 0.1) == 0, "box");
  CHECK(LGNVtk_SetCylinder(w, 1, 0.05, 0.8) == 0, "cylinder");
  CHECK(LGNVtk_SetSphere(w, 2, 0.15) == 0, "sphere");
  CHECK(LGNVtk_SetMesh(w, 3, 4, tet, 4, tri) == 0, "mesh");
  CHECK(LGNVtk_AddFrame(w, 0, r, R, 0.1) == 0, "frame on body 0");
  CHECK(LGNVtk_AddFrame(w, -1, r, NULL, 0.2) == 0, "frame on the ground");
  snprintf(name, sizeof name, "%s/poses.txt", argv[1]);
  fp = fopen(name, "w");
  for (j = 0; j < 3 && fp != NULL; j++) {
    sunrealtype *x = N_VGetArrayPointer(q);
    N_VConst(0.0, q);
    for (k = 0; k < 4; k++) RandomPose(&s, x + (int)qoff[k]);
    x[14] = 5.0; /* the R^2 leaf: not drawn */
    CHECK(LGNVtk_Write(w, 0.1 * j, q) == 0, "output %d", j);
    fprintf(fp, "%.17g", 0.1 * j);
    for (k = 0; k < 4; k++) {
      int i;
      for (i = 0; i < 7; i++) fprintf(fp, " %.17g", x[(int)qoff[k] + i]);
    }
    fprintf(fp, "\n");
  }
  if (fp != NULL) fclose(fp);
  /* a directory that does not exist: LGN_IO_FAIL, nothing counted */
  {
    LGNVtk bad = LGNVtk_Create(G, "/nonexistent-dir/x");
    LGNVtk_SetErrHandlerFn(bad, Quiet, &nmsg);
    CHECK(LGNVtk_Write(bad, 0.0, q) == LGN_IO_FAIL, "a missing directory accepted");
    LGNVtk_Destroy(&bad);
  }
  LGNVtk_Destroy(&w);
  CHECK(w == NULL, "LGNVtk_Destroy did not clear the pointer");
  N_VDestroy(q);
  N_VDestroy(qbad);
  LGNGroup_Destroy(G);
  for (k = 0; k < 5; k++) LGNGroup_Destroy(leaves[k]);
  SUNContext_Free(&ctx);
  printf("test_vtk_write: %d failures\n", failures);
  return failures == 0 ? 0 : 1;
}
