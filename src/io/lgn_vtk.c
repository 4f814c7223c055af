/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Trajectories for ParaView (lignum_vtk.h): VTK XML PolyData files (.vtp)
 * per output and their .pvd collection. A pure helper: it knows the group
 * (its leaves) and the poses in q, never the integrator.
 *
 * File layout (VTK XML PolyData, version 1.0, binary = base64 of a UInt64
 * byte count followed by the values, little- or big-endian as written):
 *   Points     the shapes' vertices moved to the bodies' poses, then the
 *              frames' end points (Float64)
 *   Lines      three per frame (its axes)
 *   Polys      the shapes' triangles
 *   CellData   "body" (Int32; -1: on the ground), "axis" (Int32; -1 for
 *              triangles)
 *   FieldData  "pose" (Float64, 7 per body: x, quaternion w, x, y, z),
 *              "time" (Float64, 1)
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lignum/lignum_vtk.h>

#include "groups/lgn_group_impl.h"
#include "lgn_err.h"
#include "lgn_parallel.h"

#define CYL_SIDES 24
#define LGN_PI 3.14159265358979323846
#define SPH_RINGS 12
#define SPH_SEGS  24

typedef struct {
  int npts, ntri;
  sunrealtype *pts; /* 3 npts, body frame */
  int *tri;         /* 3 ntri             */
} Shape;

typedef struct {
  int body;             /* -1: ground */
  sunrealtype r[3], R[9], size;
} Frame;

struct LGNVtkRec {
  LGNGroup G;
  char *base;
  int nbody;
  sunindextype *qoff;   /* the q offset of each body */
  Shape *shape;         /* nbody */
  Frame *frame;
  int nframe, capframe;
  long int nout;        /* outputs written */
  sunrealtype *times;   /* their times (capacity captimes) */
  long int captimes;
  LGNErrSink err;
};

static int Fail(const LGNVtk w, int code, const char *func, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  lgnReportV(w != NULL ? &w->err : NULL, code, func, fmt, ap);
  va_end(ap);
  return code;
}

/* ---- the bodies: leaves R^3 x SO(3) and SE(3), depth first ---- */

static int CollectBodies(LGNGroup G, sunindextype qo, sunindextype *qoff, int n)
{
  int nf, k;
  const LGNGroup *f;
  const sunindextype *qo_f, *vo_f;
  if (lgnGroupProductFactors(G, &nf, &f, &qo_f, &vo_f) == 0) {
    for (k = 0; k < nf; k++) n = CollectBodies(f[k], qo + qo_f[k], qoff, n);
    return n;
  }
  if (G->kind == LGN_GROUP_R3XSO3 || G->kind == LGN_GROUP_SE3) {
    if (qoff != NULL) qoff[n] = qo;
    return n + 1;
  }
  return n;
}

LGNVtk LGNVtk_Create(LGNGroup G, const char *basename)
{
  LGNVtk w;
  int n;
  if (G == NULL || basename == NULL || basename[0] == '\0') {
    Fail(NULL, LGN_ILL_INPUT, __func__, "%s illegal.",
         G == NULL ? "G = NULL" : "basename NULL or empty");
    return NULL;
  }
  n = CollectBodies(G, 0, NULL, 0);
  if (n == 0) {
    Fail(NULL, LGN_ILL_INPUT, __func__,
         "The group has no body to draw (no leaf R^3 x SO(3) or SE(3)).");
    return NULL;
  }
  w = (LGNVtk)calloc(1, sizeof *w);
  if (w == NULL) {
    Fail(NULL, LGN_MEM_FAIL, __func__, "A memory request failed.");
    return NULL;
  }
  lgnErrSinkInit(&w->err);
  w->G     = G;
  w->nbody = n;
  w->base  = (char *)malloc(strlen(basename) + 1);
  w->qoff  = (sunindextype *)malloc((size_t)n * sizeof(sunindextype));
  w->shape = (Shape *)calloc((size_t)n, sizeof(Shape));
  if (w->base == NULL || w->qoff == NULL || w->shape == NULL) {
    LGNVtk_Destroy(&w);
    Fail(NULL, LGN_MEM_FAIL, __func__, "A memory request failed.");
    return NULL;
  }
  strcpy(w->base, basename);
  (void)CollectBodies(G, 0, w->qoff, 0);
  return w;
}

void LGNVtk_Destroy(LGNVtk *pw)
{
  LGNVtk w;
  int k;
  if (pw == NULL || *pw == NULL) return;
  w = *pw;
  if (w->shape != NULL)
    for (k = 0; k < w->nbody; k++) {
      free(w->shape[k].pts);
      free(w->shape[k].tri);
    }
  free(w->shape);
  free(w->qoff);
  free(w->base);
  free(w->frame);
  free(w->times);
  free(w);
  *pw = NULL;
}

int LGNVtk_SetErrHandlerFn(LGNVtk w, LGNErrHandlerFn ehfun, void *eh_data)
{
  if (w == NULL) return Fail(NULL, LGN_ILL_INPUT, __func__, "w = NULL illegal.");
  w->err.ehfun   = ehfun;
  w->err.eh_data = eh_data;
  return LGN_SUCCESS;
}

int LGNVtk_GetNumBodies(LGNVtk w, int *nbodies)
{
  if (w == NULL || nbodies == NULL)
    return Fail(w, LGN_ILL_INPUT, __func__, "%s = NULL illegal.", w == NULL ? "w" : "nbodies");
  *nbodies = w->nbody;
  return LGN_SUCCESS;
}

/* ---- shapes ---- */

static int CheckBody(LGNVtk w, int k, const char *func, int allow_ground)
{
  if (w == NULL) return Fail(NULL, LGN_ILL_INPUT, func, "w = NULL illegal.");
  if (k < (allow_ground ? -1 : 0) || k >= w->nbody)
    return Fail(w, LGN_ILL_INPUT, func, "k = %d illegal: the bodies are 0 ... %d%s.", k,
                w->nbody - 1, allow_ground ? " (or -1, the ground)" : "");
  return LGN_SUCCESS;
}

static int CheckLength(LGNVtk w, sunrealtype x, const char *name, const char *func)
{
  if (!(x > 0.0) || !isfinite(x))
    return Fail(w, LGN_ILL_INPUT, func, "%s = %g illegal: positive and finite.", name,
                (double)x);
  return LGN_SUCCESS;
}

/* A new empty shape of npts points and ntri triangles for body k. */
static int NewShape(LGNVtk w, int k, int npts, int ntri, const char *func)
{
  Shape s;
  s.npts = npts;
  s.ntri = ntri;
  s.pts  = (sunrealtype *)malloc((size_t)(3 * npts) * sizeof(sunrealtype));
  s.tri  = (int *)malloc((size_t)(3 * ntri) * sizeof(int));
  if (s.pts == NULL || s.tri == NULL) {
    free(s.pts);
    free(s.tri);
    return Fail(w, LGN_MEM_FAIL, func, "A memory request failed.");
  }
  free(w->shape[k].pts);
  free(w->shape[k].tri);
  w->shape[k] = s;
  return LGN_SUCCESS;
}

static void Tri(int *t, int a, int b, int c)
{
  t[0] = a;
  t[1] = b;
  t[2] = c;
}

int LGNVtk_SetBox(LGNVtk w, int k, sunrealtype lx, sunrealtype ly, sunrealtype lz)
{
  static const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  int flag = CheckBody(w, k, __func__, 0), i;
  if (flag == LGN_SUCCESS) flag = CheckLength(w, lx, "lx", __func__);
  if (flag == LGN_SUCCESS) flag = CheckLength(w, ly, "ly", __func__);
  if (flag == LGN_SUCCESS) flag = CheckLength(w, lz, "lz", __func__);
  if (flag == LGN_SUCCESS) flag = NewShape(w, k, 8, 12, __func__);
  if (flag != LGN_SUCCESS) return flag;
  for (i = 0; i < 8; i++) { /* corner i: bits x, y, z */
    w->shape[k].pts[3 * i + 0] = (i & 1 ? 0.5 : -0.5) * lx;
    w->shape[k].pts[3 * i + 1] = (i & 2 ? 0.5 : -0.5) * ly;
    w->shape[k].pts[3 * i + 2] = (i & 4 ? 0.5 : -0.5) * lz;
  }
  for (i = 0; i < 6; i++) {
    Tri(w->shape[k].tri + 6 * i, faces[i][0], faces[i][1], faces[i][2]);
    Tri(w->shape[k].tri + 6 * i + 3, faces[i][0], faces[i][2], faces[i][3]);
  }
  return LGN_SUCCESS;
}

int LGNVtk_SetCylinder(LGNVtk w, int k, sunrealtype radius, sunrealtype length)
{
  const int n = CYL_SIDES;
  int flag = CheckBody(w, k, __func__, 0), i;
  if (flag == LGN_SUCCESS) flag = CheckLength(w, radius, "radius", __func__);
  if (flag == LGN_SUCCESS) flag = CheckLength(w, length, "length", __func__);
  /* 2 n rim points and the two centres; n sides of 2 triangles, 2 n caps */
  if (flag == LGN_SUCCESS) flag = NewShape(w, k, 2 * n + 2, 4 * n, __func__);
  if (flag != LGN_SUCCESS) return flag;
  for (i = 0; i < n; i++) {
    const double a = 2.0 * LGN_PI * i / n;
    sunrealtype *p = w->shape[k].pts + 6 * i;
    p[0] = p[3] = radius * cos(a);
    p[1] = p[4] = radius * sin(a);
    p[2] = -0.5 * length;
    p[5] = 0.5 * length;
  }
  memset(w->shape[k].pts + 6 * n, 0, 6 * sizeof(sunrealtype));
  w->shape[k].pts[6 * n + 2] = -0.5 * length;
  w->shape[k].pts[6 * n + 5] = 0.5 * length;
  for (i = 0; i < n; i++) {
    const int j = (i + 1) % n;
    int *t = w->shape[k].tri + 12 * i;
    Tri(t, 2 * i, 2 * j, 2 * j + 1);
    Tri(t + 3, 2 * i, 2 * j + 1, 2 * i + 1);
    Tri(t + 6, 2 * n, 2 * j, 2 * i);         /* bottom */
    Tri(t + 9, 2 * n + 1, 2 * i + 1, 2 * j + 1); /* top */
  }
  return LGN_SUCCESS;
}

int LGNVtk_SetSphere(LGNVtk w, int k, sunrealtype radius)
{
  const int nr = SPH_RINGS, ns = SPH_SEGS;
  /* the poles and nr - 1 rings of ns points; ns (2 nr - 2) triangles */
  int flag = CheckBody(w, k, __func__, 0), i, j, t = 0;
  if (flag == LGN_SUCCESS) flag = CheckLength(w, radius, "radius", __func__);
  if (flag == LGN_SUCCESS) flag = NewShape(w, k, 2 + (nr - 1) * ns, ns * (2 * nr - 2), __func__);
  if (flag != LGN_SUCCESS) return flag;
  {
    sunrealtype *p = w->shape[k].pts;
    int *tri       = w->shape[k].tri;
    p[0] = p[1] = 0.0;
    p[2] = -radius;
    p[3] = p[4] = 0.0;
    p[5] = radius;
    for (i = 1; i < nr; i++)
      for (j = 0; j < ns; j++) {
        const double th = LGN_PI * i / nr, ph = 2.0 * LGN_PI * j / ns;
        sunrealtype *x = p + 3 * (2 + (i - 1) * ns + j);
        x[0] = radius * sin(th) * cos(ph);
        x[1] = radius * sin(th) * sin(ph);
        x[2] = -radius * cos(th);
      }
    for (j = 0; j < ns; j++) {
      const int jn = (j + 1) % ns;
      Tri(tri + 3 * t++, 0, 2 + jn, 2 + j);
      Tri(tri + 3 * t++, 1, 2 + (nr - 2) * ns + j, 2 + (nr - 2) * ns + jn);
      for (i = 1; i < nr - 1; i++) {
        const int a = 2 + (i - 1) * ns, b = 2 + i * ns;
        Tri(tri + 3 * t++, a + j, a + jn, b + jn);
        Tri(tri + 3 * t++, a + j, b + jn, b + j);
      }
    }
  }
  return LGN_SUCCESS;
}

int LGNVtk_SetMesh(LGNVtk w, int k, int npoints, const sunrealtype *points, int ntriangles,
                   const int *triangles)
{
  int flag = CheckBody(w, k, __func__, 0), i;
  if (flag != LGN_SUCCESS) return flag;
  if (npoints < 1 || ntriangles < 1 || points == NULL || triangles == NULL)
    return Fail(w, LGN_ILL_INPUT, __func__,
                "npoints = %d, ntriangles = %d, points %s, triangles %s: at least one "
                "point and one triangle, arrays not NULL.",
                npoints, ntriangles, points == NULL ? "NULL" : "given",
                triangles == NULL ? "NULL" : "given");
  for (i = 0; i < 3 * npoints; i++)
    if (!isfinite(points[i]))
      return Fail(w, LGN_ILL_INPUT, __func__, "points[%d] is not finite.", i);
  for (i = 0; i < 3 * ntriangles; i++)
    if (triangles[i] < 0 || triangles[i] >= npoints)
      return Fail(w, LGN_ILL_INPUT, __func__,
                  "triangles[%d] = %d illegal: point numbers are 0 ... %d.", i, triangles[i],
                  npoints - 1);
  flag = NewShape(w, k, npoints, ntriangles, __func__);
  if (flag != LGN_SUCCESS) return flag;
  memcpy(w->shape[k].pts, points, (size_t)(3 * npoints) * sizeof(sunrealtype));
  memcpy(w->shape[k].tri, triangles, (size_t)(3 * ntriangles) * sizeof(int));
  return LGN_SUCCESS;
}

int LGNVtk_AddFrame(LGNVtk w, int k, const sunrealtype r[3], const sunrealtype R[9],
                    sunrealtype size)
{
  Frame f;
  int flag = CheckBody(w, k, __func__, 1), i;
  if (flag != LGN_SUCCESS) return flag;
  if (r == NULL) return Fail(w, LGN_ILL_INPUT, __func__, "r = NULL illegal.");
  flag = CheckLength(w, size, "size", __func__);
  if (flag != LGN_SUCCESS) return flag;
  for (i = 0; i < 9; i++) {
    f.R[i] = R != NULL ? R[i] : (i % 4 == 0 ? 1.0 : 0.0);
    if (!isfinite(f.R[i])) return Fail(w, LGN_ILL_INPUT, __func__, "R[%d] is not finite.", i);
  }
  for (i = 0; i < 3; i++) {
    f.r[i] = r[i];
    if (!isfinite(r[i])) return Fail(w, LGN_ILL_INPUT, __func__, "r[%d] is not finite.", i);
  }
  f.body = k;
  f.size = size;
  if (w->nframe == w->capframe) {
    const int cap = w->capframe > 0 ? 2 * w->capframe : 16;
    Frame *nf = (Frame *)realloc(w->frame, (size_t)cap * sizeof(Frame));
    if (nf == NULL) return Fail(w, LGN_MEM_FAIL, __func__, "A memory request failed.");
    w->frame    = nf;
    w->capframe = cap;
  }
  w->frame[w->nframe++] = f;
  return LGN_SUCCESS;
}

/* ---- writing ---- */

/* x_world = x + R(p) y for the pose (x, p) at q + off. */
static void ToWorld(const sunrealtype *pose, const sunrealtype R[9], const sunrealtype *y,
                    sunrealtype *out)
{
  int i;
  for (i = 0; i < 3; i++)
    out[i] = pose[i] + R[3 * i] * y[0] + R[3 * i + 1] * y[1] + R[3 * i + 2] * y[2];
}

/* base64 of the bytes of a VTK binary block: UInt64 byte count, data. */
static int PutBase64(FILE *fp, const void *data, size_t n)
{
  static const char tab[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const uint64_t count = (uint64_t)n;
  const size_t total = sizeof count + n;
  unsigned char *buf = (unsigned char *)malloc(total);
  char *out = (char *)malloc(4 * ((total + 2) / 3) + 1);
  size_t i, o = 0;
  int ok;
  if (buf == NULL || out == NULL) {
    free(buf);
    free(out);
    return -1;
  }
  memcpy(buf, &count, sizeof count);
  if (n > 0) memcpy(buf + sizeof count, data, n);
  for (i = 0; i < total; i += 3) {
    const unsigned int a = buf[i], b = i + 1 < total ? buf[i + 1] : 0,
                       c = i + 2 < total ? buf[i + 2] : 0;
    const unsigned int v = (a << 16) | (b << 8) | c;
    out[o++] = tab[(v >> 18) & 63];
    out[o++] = tab[(v >> 12) & 63];
    out[o++] = i + 1 < total ? tab[(v >> 6) & 63] : '=';
    out[o++] = i + 2 < total ? tab[v & 63] : '=';
  }
  ok = fwrite(out, 1, o, fp) == o;
  free(buf);
  free(out);
  return ok ? 0 : -1;
}

static int DataArray(FILE *fp, const char *type, const char *name, int ncomp, const void *data,
                     size_t bytes)
{
  const size_t size = strcmp(type, "Float64") == 0 ? 8 : 4;
  /* NumberOfTuples: needed by VTK's reader for field data */
  fprintf(fp, "        <DataArray type=\"%s\" Name=\"%s\" NumberOfComponents=\"%d\" "
              "NumberOfTuples=\"%lu\" format=\"binary\">\n          ",
          type, name, ncomp, (unsigned long)(bytes / (size * (size_t)ncomp)));
  if (PutBase64(fp, data, bytes) != 0) return -1;
  fprintf(fp, "\n        </DataArray>\n");
  return 0;
}

/* The file's geometry and data, built in memory, then written. */
static int WriteVtp(LGNVtk w, const char *name, sunrealtype t, const sunrealtype *q)
{
  long npts = 0, ntri = 0, k, i, p = 0, c = 0;
  const long nline = 3L * w->nframe;
  double *pts, *pose;
  int32_t *conn, *offs, *body, *axis;
  FILE *fp;
  int fail = 0;
  for (k = 0; k < w->nbody; k++) {
    npts += w->shape[k].npts;
    ntri += w->shape[k].ntri;
  }
  npts += 4L * w->nframe;
  pts  = (double *)malloc((size_t)(3 * npts + 1) * sizeof(double));
  pose = (double *)malloc((size_t)(7 * w->nbody) * sizeof(double));
  conn = (int32_t *)malloc((size_t)(3 * ntri + 2 * nline + 1) * sizeof(int32_t));
  offs = (int32_t *)malloc((size_t)(ntri + nline + 1) * sizeof(int32_t));
  body = (int32_t *)malloc((size_t)(ntri + nline + 1) * sizeof(int32_t));
  axis = (int32_t *)malloc((size_t)(ntri + nline + 1) * sizeof(int32_t));
  if (pts == NULL || pose == NULL || conn == NULL || offs == NULL || body == NULL ||
      axis == NULL) {
    fail = LGN_MEM_FAIL;
    goto done;
  }
  /* poses and the shapes' points */
  for (k = 0; k < w->nbody; k++) {
    const sunrealtype *x = q + w->qoff[k];
    sunrealtype R[9];
    LGNQuaternionToRotation(x + 3, R);
    for (i = 0; i < 7; i++) pose[7 * k + i] = x[i];
    for (i = 0; i < w->shape[k].npts; i++) ToWorld(x, R, w->shape[k].pts + 3 * i, pts + 3 * (p + i));
    p += w->shape[k].npts;
  }
  /* frames: origin and three axis ends, lines first (VTK: Lines before Polys) */
  for (k = 0; k < w->nframe; k++) {
    const Frame *f = &w->frame[k];
    sunrealtype R[9], o[3], y[3];
    static const sunrealtype ident[7] = {0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0};
    const sunrealtype *x = f->body >= 0 ? q + w->qoff[f->body] : ident;
    int a;
    LGNQuaternionToRotation(x + 3, R);
    ToWorld(x, R, f->r, o);
    for (i = 0; i < 3; i++) pts[3 * p + i] = o[i];
    for (a = 0; a < 3; a++) {
      for (i = 0; i < 3; i++) y[i] = f->r[i] + f->size * f->R[3 * i + a];
      ToWorld(x, R, y, pts + 3 * (p + 1 + a));
      conn[2 * c] = (int32_t)p;
      conn[2 * c + 1] = (int32_t)(p + 1 + a);
      offs[c] = (int32_t)(2 * (c + 1));
      body[c] = f->body;
      axis[c] = a;
      c++;
    }
    p += 4;
  }
  /* triangles (points of the shapes come first) */
  {
    long base = 0, tc = 0;
    int32_t *tconn = conn + 2 * nline, *toffs = offs + nline;
    for (k = 0; k < w->nbody; k++) {
      for (i = 0; i < w->shape[k].ntri; i++) {
        int j;
        for (j = 0; j < 3; j++) tconn[3 * tc + j] = (int32_t)(base + w->shape[k].tri[3 * i + j]);
        toffs[tc] = (int32_t)(3 * (tc + 1));
        body[nline + tc] = (int32_t)k;
        axis[nline + tc] = -1;
        tc++;
      }
      base += w->shape[k].npts;
    }
  }
  fp = fopen(name, "wb");
  if (fp == NULL) {
    fail = LGN_IO_FAIL;
    goto done;
  }
  {
    const int big = *(const unsigned char *)&(uint16_t){1} == 0;
    fprintf(fp, "<?xml version=\"1.0\"?>\n<!-- written by Lignum (lignum_vtk.h) -->\n"
                "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"%s\" "
                "header_type=\"UInt64\">\n  <PolyData>\n",
            big ? "BigEndian" : "LittleEndian");
  }
  fprintf(fp, "    <FieldData>\n");
  fail |= DataArray(fp, "Float64", "time", 1, &(double){(double)t}, sizeof(double));
  fprintf(fp, "        <!-- pose: x, y, z, w, qx, qy, qz per body -->\n");
  fail |= DataArray(fp, "Float64", "pose", 7, pose, (size_t)(7 * w->nbody) * sizeof(double));
  fprintf(fp, "    </FieldData>\n");
  fprintf(fp, "    <Piece NumberOfPoints=\"%ld\" NumberOfVerts=\"0\" NumberOfLines=\"%ld\" "
              "NumberOfStrips=\"0\" NumberOfPolys=\"%ld\">\n",
          npts, nline, ntri);
  fprintf(fp, "      <Points>\n");
  fail |= DataArray(fp, "Float64", "Points", 3, pts, (size_t)(3 * npts) * sizeof(double));
  fprintf(fp, "      </Points>\n      <CellData Scalars=\"body\">\n");
  /* cell order in VTK PolyData: verts, lines, strips, polys */
  fail |= DataArray(fp, "Int32", "body", 1, body, (size_t)(ntri + nline) * sizeof(int32_t));
  fail |= DataArray(fp, "Int32", "axis", 1, axis, (size_t)(ntri + nline) * sizeof(int32_t));
  fprintf(fp, "      </CellData>\n      <Lines>\n");
  fail |= DataArray(fp, "Int32", "connectivity", 1, conn, (size_t)(2 * nline) * sizeof(int32_t));
  fail |= DataArray(fp, "Int32", "offsets", 1, offs, (size_t)nline * sizeof(int32_t));
  fprintf(fp, "      </Lines>\n      <Polys>\n");
  fail |= DataArray(fp, "Int32", "connectivity", 1, conn + 2 * nline,
                    (size_t)(3 * ntri) * sizeof(int32_t));
  fail |= DataArray(fp, "Int32", "offsets", 1, offs + nline, (size_t)ntri * sizeof(int32_t));
  fprintf(fp, "      </Polys>\n    </Piece>\n  </PolyData>\n</VTKFile>\n");
  fail = (fclose(fp) != 0 || fail) ? LGN_IO_FAIL : 0;
done:
  free(pts);
  free(pose);
  free(conn);
  free(offs);
  free(body);
  free(axis);
  return fail;
}

/* The file name of output j, and the name without its directory. */
static void VtpName(const LGNVtk w, long j, char *buf, size_t len)
{
  snprintf(buf, len, "%s_%06ld.vtp", w->base, j);
}

static int WritePvd(LGNVtk w)
{
  const size_t len = strlen(w->base) + 32;
  char *name = (char *)malloc(len), *file = (char *)malloc(len);
  const char *slash = strrchr(w->base, '/');
  FILE *fp;
  long j;
  int ok;
  if (name == NULL || file == NULL) {
    free(name);
    free(file);
    return LGN_MEM_FAIL;
  }
  snprintf(name, len, "%s.pvd", w->base);
  fp = fopen(name, "w");
  ok = fp != NULL;
  if (ok) {
    fprintf(fp, "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\">\n"
                "  <Collection>\n");
    for (j = 0; j < w->nout; j++) {
      VtpName(w, j, file, len);
      /* relative to the .pvd's directory */
      fprintf(fp, "    <DataSet timestep=\"%.17g\" part=\"0\" file=\"%s\"/>\n",
              (double)w->times[j], slash != NULL ? file + (slash - w->base) + 1 : file);
    }
    fprintf(fp, "  </Collection>\n</VTKFile>\n");
    ok = fclose(fp) == 0;
  }
  free(name);
  free(file);
  return ok ? LGN_SUCCESS : LGN_IO_FAIL;
}

int LGNVtk_Write(LGNVtk w, sunrealtype t, N_Vector q)
{
  char *name;
  const sunrealtype *qd;
  sunindextype i;
  int flag;
  if (w == NULL) return Fail(NULL, LGN_ILL_INPUT, __func__, "w = NULL illegal.");
  if (q == NULL || N_VGetArrayPointer(q) == NULL || lgnLocalLength(q) != w->G->nq)
    return Fail(w, LGN_ILL_INPUT, __func__,
                "q %s: a vector with a data array of the group's length %lld (this "
                "rank's part) is needed.",
                q == NULL ? "= NULL" : "has no data array or another length",
                (long long)w->G->nq);
  if (!isfinite(t)) return Fail(w, LGN_ILL_INPUT, __func__, "t is not finite.");
  qd = N_VGetArrayPointer(q);
  for (i = 0; i < w->G->nq; i++)
    if (!isfinite(qd[i]))
      return Fail(w, LGN_ILL_INPUT, __func__, "q[%lld] is not finite.", (long long)i);
  if (w->nout == w->captimes) {
    const long cap = w->captimes > 0 ? 2 * w->captimes : 64;
    sunrealtype *nt = (sunrealtype *)realloc(w->times, (size_t)cap * sizeof(sunrealtype));
    if (nt == NULL) return Fail(w, LGN_MEM_FAIL, __func__, "A memory request failed.");
    w->times    = nt;
    w->captimes = cap;
  }
  name = (char *)malloc(strlen(w->base) + 32);
  if (name == NULL) return Fail(w, LGN_MEM_FAIL, __func__, "A memory request failed.");
  VtpName(w, w->nout, name, strlen(w->base) + 32);
  flag = WriteVtp(w, name, t, qd);
  if (flag == LGN_SUCCESS) {
    w->times[w->nout++] = t;
    flag = WritePvd(w);
    if (flag != LGN_SUCCESS) w->nout--;
  }
  if (flag == LGN_IO_FAIL)
    Fail(w, LGN_IO_FAIL, __func__, "The file %s (or its .pvd) could not be written.", name);
  else if (flag == LGN_MEM_FAIL)
    Fail(w, LGN_MEM_FAIL, __func__, "A memory request failed.");
  free(name);
  return flag;
}
