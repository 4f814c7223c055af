/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Restart files (LGNWriteRestart, LGNReadRestart): the integrator's state at
 * t_n written to a file and read into another integrator of the same
 * problem, so that the continued run equals the uninterrupted one bit for
 * bit. The format is doc/restart-format.md's:
 *
 *   header   magic "LGNRSTRT", version, endianness marker, the sizes of
 *            sunrealtype, sunindextype, long int and int, nq, nv, m, nrtfn,
 *            the group's signature, the number of ranks and this rank, the
 *            payload's length
 *   payload  named entries (name, kind, count, values): first the settings
 *            that decide the steps (compared on reading, never restored),
 *            then the state (restored)
 *   trailer  CRC-32 of everything before it
 *
 * The two tables below are the format: a field of the record is one line
 * in one of them (a new state field: one line in StateFields, and the
 * version number LGN_RESTART_VERSION goes up). Reading is in two passes:
 * every check first (format, checksum, sizes, group, settings, every
 * entry's name, kind and count), the state copied only when all passed, so
 * a refused file changes nothing.
 * ---------------------------------------------------------------------------*/

#include <errno.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "groups/lgn_group_impl.h"
#include "lgn_impl.h"

#define LGN_RESTART_MAGIC   "LGNRSTRT"
#define LGN_RESTART_VERSION 1u
#define LGN_RESTART_ENDIAN  0x01020304u
#define HEADER_BYTES        96  /* fixed: see WriteHeader */

/* =============================================================================
 * The tables of fields
 * ===========================================================================*/

typedef enum {
  RS_REAL = 0,  /* sunrealtype                                       */
  RS_LONG,      /* long int                                          */
  RS_INT,       /* int                                               */
  RS_BOOL,      /* sunbooleantype (stored as int)                    */
  RS_REALS,     /* a pointer to sunrealtype (count from its length)  */
  RS_INTS,      /* a pointer to int                                  */
  RS_BOOLS,     /* a pointer to sunbooleantype                       */
  RS_NVECTOR    /* an N_Vector: its rank-local data                  */
} RsKind;

/* The lengths of arrays, from the record's sizes. */
typedef enum {
  LEN_1 = 0, LEN_NQ, LEN_NV, LEN_M, LEN_NRTFN, LEN_T3,
  LEN_HIST, LEN_HIST_NQ, LEN_HIST_NV, LEN_HIST_M, LEN_DD_NV, LEN_ORDERS,
  LEN_GGL_MNV
} RsLen;

typedef struct {
  const char *name;
  size_t offset; /* of the field in struct LGNMemRec */
  RsKind kind;
  RsLen len;     /* scalars and inline arrays: LEN_1 or a fixed length */
  sunbooleantype inline_array; /* the field is an array, not a pointer */
} RsField;

#define OFF(f) offsetof(struct LGNMemRec, f)
#define SCALAR(f, kind)       {#f, OFF(f), kind, LEN_1, SUNFALSE}
#define INLINE(f, kind, len)  {#f, OFF(f), kind, len, SUNTRUE}
#define ARRAY(f, kind, len)   {#f, OFF(f), kind, len, SUNFALSE}

/* The settings that decide the steps: the reading integrator must have the
 * same (set by the user's program as for the run that wrote the file);
 * compared bit for bit, a difference refused naming the setting. */
static const RsField SettingFields[] = {
  SCALAR(family, RS_INT),          SCALAR(bdf_maxord, RS_INT),
  SCALAR(bdf_form, RS_INT),        SCALAR(step_control, RS_INT),
  SCALAR(h, RS_REAL),              SCALAR(rtol, RS_REAL),
  SCALAR(atol, RS_REAL),           ARRAY(atol_vec, RS_REALS, LEN_NV),
  SCALAR(tols_set, RS_BOOL),       SCALAR(maxcor, RS_INT),
  SCALAR(newton_mode, RS_INT),     SCALAR(msbp, RS_LONG),
  SCALAR(mxstep, RS_LONG),         SCALAR(constr_index, RS_INT),
  SCALAR(kinematics, RS_INT),      SCALAR(predictor, RS_INT),
  SCALAR(alpha_m, RS_REAL),        SCALAR(alpha_f, RS_REAL),
  SCALAR(beta, RS_REAL),           SCALAR(gamma, RS_REAL),
  SCALAR(pstart_on, RS_BOOL),      SCALAR(mass_constant, RS_BOOL),
  SCALAR(krylov, RS_BOOL),
  SCALAR(own_klu_solves, RS_BOOL), SCALAR(eplifac, RS_REAL),
  SCALAR(epcon, RS_REAL),          SCALAR(h0_user, RS_REAL),
  SCALAR(hmin, RS_REAL),           SCALAR(hmax, RS_REAL),
  SCALAR(maxnef, RS_INT),          SCALAR(maxncf, RS_INT),
  SCALAR(accept_stalls, RS_BOOL),  ARRAY(rootdir, RS_INTS, LEN_NRTFN),
  SCALAR(out_consistent, RS_BOOL), SCALAR(out_project, RS_INT),
  SCALAR(lambda_errcon, RS_BOOL),  SCALAR(lambda_atol, RS_REAL),
};

/* The state at t_n and everything of the past steps the next ones read:
 * restored from the file. */
static const RsField StateFields[] = {
  /* the state at t_n and the last step (dense output) */
  SCALAR(tn, RS_REAL),              ARRAY(q, RS_NVECTOR, LEN_NQ),
  ARRAY(v, RS_NVECTOR, LEN_NV),     ARRAY(vdot, RS_NVECTOR, LEN_NV),
  ARRAY(a, RS_NVECTOR, LEN_NV),     ARRAY(lambda, RS_NVECTOR, LEN_M),
  ARRAY(q1, RS_NVECTOR, LEN_NQ),    ARRAY(v1, RS_NVECTOR, LEN_NV),
  ARRAY(vdot1, RS_NVECTOR, LEN_NV), ARRAY(lambda1, RS_NVECTOR, LEN_M),
  SCALAR(ic_done, RS_BOOL),         SCALAR(user_vdot0, RS_BOOL),
  SCALAR(user_a0, RS_BOOL),         SCALAR(pstart_done, RS_BOOL),
  SCALAR(pstart_pending, RS_BOOL),  SCALAR(tprev, RS_REAL),
  SCALAR(dense_valid, RS_BOOL),
  /* the Newmark family's increments, predictor and error control */
  ARRAY(sigma, RS_REALS, LEN_NV),   ARRAY(sigma_dot, RS_REALS, LEN_NV),
  ARRAY(sigma_ddot, RS_REALS, LEN_NV), ARRAY(a_pred, RS_REALS, LEN_NV),
  ARRAY(vdot_prev, RS_REALS, LEN_NV), ARRAY(lambda_prev, RS_REALS, LEN_M),
  ARRAY(incr, RS_REALS, LEN_NV),    ARRAY(Tm, RS_REALS, LEN_T3),
  ARRAY(ele, RS_REALS, LEN_NV),     ARRAY(ewt, RS_REALS, LEN_NV),
  ARRAY(a_scaled, RS_REALS, LEN_NV),
  SCALAR(h_prev, RS_REAL),          SCALAR(hlast, RS_REAL),
  SCALAR(hnext, RS_REAL),           SCALAR(h0_actual, RS_REAL),
  SCALAR(err_norm, RS_REAL),        SCALAR(err_prev, RS_REAL),
  SCALAR(nls_rtol, RS_REAL),        SCALAR(nls_atol, RS_REAL),
  SCALAR(tstop, RS_REAL),           SCALAR(tstop_set, RS_BOOL),
  SCALAR(nls_vfac, RS_REAL),        SCALAR(nls_lrtol, RS_REAL),
  SCALAR(nls_latol, RS_REAL),       SCALAR(lambda_err, RS_REAL),
  /* the last output's consistent vdot and lambda (LGNGetAcceleration ...) */
  SCALAR(out_valid, RS_BOOL),       SCALAR(out_t, RS_REAL),
  ARRAY(out_vdot, RS_REALS, LEN_NV), ARRAY(out_lambda, RS_REALS, LEN_M),
  /* GGL */
  ARRAY(ggl_mu, RS_REALS, LEN_M),   ARRAY(ggl_Bn, RS_REALS, LEN_GGL_MNV),
  SCALAR(ggl_Bn_valid, RS_BOOL),    SCALAR(ggl_t1, RS_REAL),
  /* Newton's memory of past iterations */
  SCALAR(newton_rate, RS_REAL),     SCALAR(lambda_noise, RS_REAL),
  SCALAR(lambda_noise_h, RS_REAL),  SCALAR(stall_warned, RS_BOOL),
  /* BDF: history, order and controller */
  SCALAR(bdf_ns, RS_INT),           SCALAR(bdf_hused, RS_REAL),
  SCALAR(bdf_sigck, RS_REAL),       SCALAR(bdf_step_flc, RS_BOOL),
  SCALAR(bdf_order, RS_INT),        SCALAR(bdf_last_order, RS_INT),
  SCALAR(bdf_nhist, RS_INT),        SCALAR(bdf_nsteps_order, RS_INT),
  SCALAR(bdf_phase0, RS_BOOL),      SCALAR(bdf_chart_t, RS_REAL),
  INLINE(bdf_t, RS_REALS, LEN_HIST), INLINE(bdf_vgain, RS_REALS, LEN_HIST),
  SCALAR(bdf_vgain1, RS_REAL),      SCALAR(bdf_vpgain, RS_REAL),
  SCALAR(bdf_c0, RS_REAL),          INLINE(bdf_nord, RS_LONG, LEN_ORDERS),
  ARRAY(bdf_q, RS_REALS, LEN_HIST_NQ), ARRAY(bdf_v, RS_REALS, LEN_HIST_NV),
  ARRAY(bdf_l, RS_REALS, LEN_HIST_M),  ARRAY(bdf_x, RS_REALS, LEN_HIST_NV),
  ARRAY(bdf_rx, RS_REALS, LEN_NV),  ARRAY(bdf_rv, RS_REALS, LEN_NV),
  ARRAY(bdf_xpred, RS_REALS, LEN_NV), ARRAY(bdf_vpred, RS_REALS, LEN_NV),
  ARRAY(bdf_dd, RS_REALS, LEN_DD_NV), ARRAY(bdf_ele_keep, RS_REALS, LEN_NV),
  /* root finding */
  ARRAY(glo, RS_REALS, LEN_NRTFN),  ARRAY(ghi, RS_REALS, LEN_NRTFN),
  ARRAY(grout, RS_REALS, LEN_NRTFN), ARRAY(iroots, RS_INTS, LEN_NRTFN),
  ARRAY(gactive, RS_BOOLS, LEN_NRTFN), SCALAR(tlo, RS_REAL),
  SCALAR(rt_started, RS_BOOL),      SCALAR(rt_pending, RS_BOOL),
  SCALAR(rt_first, RS_BOOL),
  /* counters */
  SCALAR(nst, RS_LONG),   SCALAR(nni, RS_LONG),    SCALAR(nncf, RS_LONG),
  SCALAR(nstall, RS_LONG), SCALAR(nfails, RS_LONG), SCALAR(nre, RS_LONG),
  SCALAR(ndq, RS_LONG),   SCALAR(nje, RS_LONG),    SCALAR(nlsetup, RS_LONG),
  SCALAR(nlsolve, RS_LONG), SCALAR(nreuse, RS_LONG), SCALAR(nrestart, RS_LONG),
  SCALAR(netf, RS_LONG),  SCALAR(nge, RS_LONG),    SCALAR(nli, RS_LONG),
  SCALAR(npe, RS_LONG),   SCALAR(nps, RS_LONG),    SCALAR(njtimes, RS_LONG),
  SCALAR(nlcf, RS_LONG),  SCALAR(nklu_fallback, RS_LONG),
  SCALAR(nklu_copy, RS_LONG), SCALAR(nklu_values, RS_LONG),
  SCALAR(nklu_refactor, RS_LONG), SCALAR(nklu_solve, RS_LONG),
  SCALAR(nklu_newpattern, RS_LONG), SCALAR(nklu_nocopy, RS_LONG),
  SCALAR(last_lin_flag, RS_LONG), SCALAR(nout, RS_LONG),
};

#define NUM_FIELDS(t) (sizeof(t) / sizeof((t)[0]))

/* The number of values of a field in this integrator: 0 for an array the
 * configuration does not use (a NULL pointer, the BDF history under the
 * Newmark family). */
static sunindextype FieldCount(const LGNMem mem, const RsField *f)
{
  const sunindextype H = LGN_BDF_MAXHIST;
  const sunbooleantype bdf_array = strncmp(f->name, "bdf_", 4) == 0 && !f->inline_array;
  if (!f->inline_array && f->kind >= RS_REALS) {
    const void *p = *(void *const *)((const char *)mem + f->offset);
    if (p == NULL) return 0;
    if (bdf_array && mem->family != LGN_FAMILY_BDF) return 0;
  }
  switch (f->len) {
  case LEN_1:       return 1;
  case LEN_NQ:      return mem->nq;
  case LEN_NV:      return mem->nv;
  case LEN_M:       return mem->m;
  case LEN_NRTFN:   return mem->nrtfn;
  case LEN_T3:      return 3 * mem->tlen;
  case LEN_HIST:    return H;
  case LEN_HIST_NQ: return H * mem->nq;
  case LEN_HIST_NV: return H * mem->nv;
  case LEN_HIST_M:  return H * mem->m;
  case LEN_DD_NV:   return (H + 1) * mem->nv;
  case LEN_ORDERS:  return LGN_BDF_MAXORD + 1;
  case LEN_GGL_MNV: return mem->m * mem->nv;
  }
  return 0;
}

/* Bytes per value in the file. */
static size_t KindBytes(RsKind kind)
{
  switch (kind) {
  case RS_REAL: case RS_REALS: case RS_NVECTOR: return sizeof(sunrealtype);
  case RS_LONG: return sizeof(long int);
  default:      return sizeof(int);
  }
}

/* The kind as stored: scalar and array kinds of one type are one. */
static int StoredKind(const RsField *f)
{
  switch (f->kind) {
  case RS_REAL: case RS_REALS: case RS_NVECTOR: return 1;
  case RS_LONG: return 2;
  default:      return 3; /* int and sunbooleantype, stored as int */
  }
}

/* Where the field's values live in the record. */
static void *FieldData(LGNMem mem, const RsField *f)
{
  char *at = (char *)mem + f->offset;
  if (f->kind == RS_NVECTOR) {
    N_Vector x = *(N_Vector *)at;
    return x != NULL ? (void *)lgnData(x) : NULL;
  }
  if (f->inline_array || f->kind < RS_REALS) return at;
  return *(void **)at;
}

/* =============================================================================
 * CRC-32 (IEEE 802.3, the polynomial of zlib and PNG)
 * ===========================================================================*/

static uint32_t Crc32(uint32_t crc, const unsigned char *p, size_t n)
{
  uint32_t table[256];
  uint32_t k;
  size_t i;
  /* the byte table (made per call: 2 kB of work, no shared state) */
  for (k = 0; k < 256; k++) {
    uint32_t c = k;
    int b;
    for (b = 0; b < 8; b++) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    table[k] = c;
  }
  crc = ~crc;
  for (i = 0; i < n; i++) crc = table[(crc ^ p[i]) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

/* The group's signature: CRC-32 of its tree (kind, nq, nv of every node,
 * depth first), so that a file of another group of the same sizes (SE(3)
 * for R^3 x SO(3), or the bodies in another order) is refused. */
static uint32_t GroupSignature(LGNGroup G, uint32_t crc)
{
  int nf, k;
  const LGNGroup *f;
  const sunindextype *qoff, *voff;
  int64_t node[3];
  node[0] = (int64_t)G->kind;
  node[1] = (int64_t)G->nq;
  node[2] = (int64_t)G->nv;
  crc = Crc32(crc, (const unsigned char *)node, sizeof node);
  if (lgnGroupProductFactors(G, &nf, &f, &qoff, &voff) == 0)
    for (k = 0; k < nf; k++) crc = GroupSignature(f[k], crc);
  return crc;
}

/* =============================================================================
 * Writing
 * ===========================================================================*/

/* A growing byte buffer (sized in advance by a counting pass). */
typedef struct {
  unsigned char *p;
  size_t len, cap; /* cap 0: count only */
} Buffer;

static void Put(Buffer *b, const void *x, size_t n)
{
  if (b->cap > 0 && n > 0) memcpy(b->p + b->len, x, n);
  b->len += n;
}

static void PutU32(Buffer *b, uint32_t x) { Put(b, &x, sizeof x); }
static void PutI64(Buffer *b, int64_t x) { Put(b, &x, sizeof x); }

/* One entry: name length (u16), name, stored kind (u8), count (i64),
 * values. */
static void PutField(Buffer *b, LGNMem mem, const RsField *f)
{
  const sunindextype n = FieldCount(mem, f);
  const uint16_t len = (uint16_t)strlen(f->name);
  const uint8_t kind = (uint8_t)StoredKind(f);
  Put(b, &len, sizeof len);
  Put(b, f->name, len);
  Put(b, &kind, sizeof kind);
  PutI64(b, (int64_t)n);
  if (n == 0) return;
  if (f->kind == RS_BOOL || f->kind == RS_BOOLS) {
    /* sunbooleantype is an int in SUNDIALS 6 and 7: stored as int */
    const sunbooleantype *x = (const sunbooleantype *)FieldData(mem, f);
    sunindextype i;
    for (i = 0; i < n; i++) {
      const int v = x[i] ? 1 : 0;
      Put(b, &v, sizeof v);
    }
    return;
  }
  Put(b, FieldData(mem, f), (size_t)n * KindBytes(f->kind));
}

static void PutHeader(Buffer *b, LGNMem mem, uint64_t payload)
{
  const size_t start = b->len;
  unsigned char sizes[4];
  sizes[0] = (unsigned char)sizeof(sunrealtype);
  sizes[1] = (unsigned char)sizeof(sunindextype);
  sizes[2] = (unsigned char)sizeof(long int);
  sizes[3] = (unsigned char)sizeof(int);
  Put(b, LGN_RESTART_MAGIC, 8);                     /*  0 */
  PutU32(b, LGN_RESTART_VERSION);                   /*  8 */
  PutU32(b, LGN_RESTART_ENDIAN);                    /* 12 */
  Put(b, sizes, 4);                                 /* 16 */
  PutU32(b, (uint32_t)(NUM_FIELDS(SettingFields))); /* 20 */
  PutI64(b, (int64_t)mem->nq);                      /* 24 */
  PutI64(b, (int64_t)mem->nv);                      /* 32 */
  PutI64(b, (int64_t)mem->m);                       /* 40 */
  PutI64(b, (int64_t)mem->nrtfn);                   /* 48 */
  PutU32(b, GroupSignature(mem->G, 0));             /* 56 */
  PutU32(b, (uint32_t)lgnParallelSize(mem->par));   /* 60 */
  PutU32(b, (uint32_t)lgnParallelRank(mem->par));   /* 64 */
  PutU32(b, (uint32_t)NUM_FIELDS(StateFields));     /* 68 */
  PutI64(b, (int64_t)payload);                      /* 72 */
  PutI64(b, (int64_t)mem->nst);                     /* 80: informative */
  Put(b, &mem->tn, sizeof(sunrealtype));            /* 88: informative */
  (void)start;
}

static void PutPayload(Buffer *b, LGNMem mem)
{
  size_t k;
  for (k = 0; k < NUM_FIELDS(SettingFields); k++) PutField(b, mem, &SettingFields[k]);
  for (k = 0; k < NUM_FIELDS(StateFields); k++) PutField(b, mem, &StateFields[k]);
}

/* The whole file in memory: header, payload, CRC-32. */
static int BuildImage(LGNMem mem, Buffer *b)
{
  Buffer count = {NULL, 0, 0};
  size_t payload;
  uint32_t crc;
  PutPayload(&count, mem);
  payload = count.len;
  b->cap  = HEADER_BYTES + payload + 4;
  b->len  = 0;
  b->p    = (unsigned char *)malloc(b->cap);
  if (b->p == NULL) return LGN_MEM_FAIL;
  PutHeader(b, mem, (uint64_t)payload);
  PutPayload(b, mem);
  crc = Crc32(0, b->p, b->len);
  PutU32(b, crc);
  return LGN_SUCCESS;
}

/* Write the image to filename through a temporary file renamed at the end,
 * so that a run killed while writing leaves the previous file whole. */
static int WriteImage(LGNMem mem, const Buffer *b, const char *filename)
{
  const size_t n = strlen(filename);
  char *tmp = (char *)malloc(n + 5);
  FILE *fp;
  int ok;
  if (tmp == NULL) {
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  memcpy(tmp, filename, n);
  memcpy(tmp + n, ".tmp", 5);
  fp = fopen(tmp, "wb");
  if (fp == NULL) {
    LGN_ERROR(mem, LGN_IO_FAIL, "The file %s could not be opened for writing (%s).",
              tmp, strerror(errno));
    free(tmp);
    return LGN_IO_FAIL;
  }
  ok = fwrite(b->p, 1, b->len, fp) == b->len;
  ok = (fclose(fp) == 0) && ok;
  if (ok) ok = rename(tmp, filename) == 0;
  if (!ok) {
    LGN_ERROR(mem, LGN_IO_FAIL, "The restart file %s could not be written (%s).",
              filename, strerror(errno));
    (void)remove(tmp);
    free(tmp);
    return LGN_IO_FAIL;
  }
  free(tmp);
  return LGN_SUCCESS;
}

/* The checks both calls begin with: the memory, LGNInit, a file name.
 * Messages name the public function (func). */
static int AccessWithFile(void *lgn_mem, const char *filename, const char *func,
                          LGNMem *mem)
{
  int flag = lgnAccessMem(lgn_mem, func, mem);
  if (flag != LGN_SUCCESS) return flag;
  if (!(*mem)->malloc_done) {
    lgnProcessError(*mem, LGN_NO_MALLOC, __LINE__, func, __FILE__, MSG_NO_MALLOC);
    return LGN_NO_MALLOC;
  }
  if (filename == NULL || filename[0] == '\0') {
    lgnProcessError(*mem, LGN_ILL_INPUT, __LINE__, func, __FILE__, "filename = %s illegal.",
                    filename == NULL ? "NULL" : "\"\"");
    return lgnAgree(*mem, LGN_ILL_INPUT);
  }
  return LGN_SUCCESS;
}

int LGNWriteRestart(void *lgn_mem, const char *filename)
{
  LGNMem mem;
  Buffer b = {NULL, 0, 0};
  int flag = AccessWithFile(lgn_mem, filename, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (!mem->work_done || !mem->ic_done) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "Nothing to write before the first LGNSolve (or after a setting "
              "dropped the work space): the state at t0 is the user's q0, v0.");
    flag = LGN_ILL_INPUT;
  } else if (mem->red_nout > 0) {
    /* the row selection of redundant constraints is not in the format */
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "%lld of the %lld constraint rows are left out as redundant: restart "
              "files of mechanisms with redundant constraints are not supported "
              "(make the constraints independent, or continue with LGNReInit from "
              "the state).", (long long)mem->red_nout, (long long)mem->m_user);
    flag = LGN_ILL_INPUT;
  }
  if (flag == LGN_SUCCESS) {
    flag = BuildImage(mem, &b);
    if (flag != LGN_SUCCESS) LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
  }
  if (flag == LGN_SUCCESS) flag = WriteImage(mem, &b, filename);
  free(b.p);
  return lgnAgree(mem, flag);
}

/* =============================================================================
 * Reading
 * ===========================================================================*/

typedef struct {
  const unsigned char *p;
  size_t len, pos;
} Reader;

static int Get(Reader *r, void *x, size_t n)
{
  if (r->len - r->pos < n) return -1;
  memcpy(x, r->p + r->pos, n);
  r->pos += n;
  return 0;
}

static uint32_t U32At(const unsigned char *p)
{
  uint32_t x;
  memcpy(&x, p, sizeof x);
  return x;
}

static int64_t I64At(const unsigned char *p)
{
  int64_t x;
  memcpy(&x, p, sizeof x);
  return x;
}

/* The whole file into memory. */
static int ReadImage(LGNMem mem, const char *filename, unsigned char **image, size_t *len)
{
  FILE *fp = fopen(filename, "rb");
  long size;
  *image = NULL;
  if (fp == NULL) {
    LGN_ERROR(mem, LGN_IO_FAIL, "The restart file %s could not be opened (%s).",
              filename, strerror(errno));
    return LGN_IO_FAIL;
  }
  if (fseek(fp, 0, SEEK_END) != 0 || (size = ftell(fp)) < 0 || fseek(fp, 0, SEEK_SET) != 0) {
    fclose(fp);
    LGN_ERROR(mem, LGN_IO_FAIL, "The restart file %s could not be read.", filename);
    return LGN_IO_FAIL;
  }
  *image = (unsigned char *)malloc(SUNMAX((size_t)size, 1));
  if (*image == NULL) {
    fclose(fp);
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  if (fread(*image, 1, (size_t)size, fp) != (size_t)size) {
    fclose(fp);
    free(*image);
    *image = NULL;
    LGN_ERROR(mem, LGN_IO_FAIL, "The restart file %s could not be read.", filename);
    return LGN_IO_FAIL;
  }
  fclose(fp);
  *len = (size_t)size;
  return LGN_SUCCESS;
}

/* The file's format: magic, version, endianness, type sizes, length and
 * checksum. LGN_RESTART_BAD_FILE otherwise (reported). */
static int CheckFormat(LGNMem mem, const char *filename, const unsigned char *p, size_t len)
{
  int64_t payload;
  if (len < 8 || memcmp(p, LGN_RESTART_MAGIC, 8) != 0) {
    LGN_ERROR(mem, LGN_RESTART_BAD_FILE, "%s is not a Lignum restart file (no magic %s).",
              filename, LGN_RESTART_MAGIC);
    return LGN_RESTART_BAD_FILE;
  }
  if (len < HEADER_BYTES + 4) {
    LGN_ERROR(mem, LGN_RESTART_BAD_FILE,
              "The restart file %s is truncated: %zu bytes, shorter than its header.",
              filename, len);
    return LGN_RESTART_BAD_FILE;
  }
  if (U32At(p + 12) != LGN_RESTART_ENDIAN) {
    LGN_ERROR(mem, LGN_RESTART_BAD_FILE,
              "The restart file %s was written on a machine of the other byte order.",
              filename);
    return LGN_RESTART_BAD_FILE;
  }
  if (U32At(p + 8) != LGN_RESTART_VERSION) {
    LGN_ERROR(mem, LGN_RESTART_BAD_FILE,
              "The restart file %s has format version %u; this Lignum reads version %u.",
              filename, (unsigned)U32At(p + 8), (unsigned)LGN_RESTART_VERSION);
    return LGN_RESTART_BAD_FILE;
  }
  if (p[16] != sizeof(sunrealtype) || p[17] != sizeof(sunindextype) ||
      p[18] != sizeof(long int) || p[19] != sizeof(int)) {
    LGN_ERROR(mem, LGN_RESTART_BAD_FILE,
              "The restart file %s has other type sizes (real %d, index %d, long %d, "
              "int %d bytes) than this build (%d, %d, %d, %d).",
              filename, p[16], p[17], p[18], p[19], (int)sizeof(sunrealtype),
              (int)sizeof(sunindextype), (int)sizeof(long int), (int)sizeof(int));
    return LGN_RESTART_BAD_FILE;
  }
  payload = I64At(p + 72);
  if (payload < 0 || (uint64_t)payload != (uint64_t)(len - HEADER_BYTES - 4)) {
    LGN_ERROR(mem, LGN_RESTART_BAD_FILE,
              "The restart file %s is truncated or extended: %zu bytes, its header "
              "says %lld.",
              filename, len, (long long)(payload + HEADER_BYTES + 4));
    return LGN_RESTART_BAD_FILE;
  }
  if (Crc32(0, p, len - 4) != U32At(p + len - 4)) {
    LGN_ERROR(mem, LGN_RESTART_BAD_FILE,
              "The restart file %s is corrupt: its CRC-32 does not match its contents.",
              filename);
    return LGN_RESTART_BAD_FILE;
  }
  return LGN_SUCCESS;
}

/* The problem of the file against the integrator's: sizes, group, ranks. */
static int CheckProblem(LGNMem mem, const char *filename, const unsigned char *p)
{
  const int64_t nq = I64At(p + 24), nv = I64At(p + 32), m = I64At(p + 40);
  const int64_t nrtfn = I64At(p + 48);
  const uint32_t size = U32At(p + 60), rank = U32At(p + 64);
  if (size != (uint32_t)lgnParallelSize(mem->par) ||
      rank != (uint32_t)lgnParallelRank(mem->par)) {
    LGN_ERROR(mem, LGN_RESTART_MISMATCH,
              "The restart file %s was written by rank %u of %u; it is read by rank %d "
              "of %d (one file per rank, read on as many ranks).",
              filename, (unsigned)rank, (unsigned)size, lgnParallelRank(mem->par),
              lgnParallelSize(mem->par));
    return LGN_RESTART_MISMATCH;
  }
  if (nq != (int64_t)mem->nq || nv != (int64_t)mem->nv || m != (int64_t)mem->m) {
    LGN_ERROR(mem, LGN_RESTART_MISMATCH,
              "The restart file %s is of a model with nq = %lld, nv = %lld, m = %lld; "
              "this integrator has %lld, %lld, %lld.",
              filename, (long long)nq, (long long)nv, (long long)m, (long long)mem->nq,
              (long long)mem->nv, (long long)mem->m);
    return LGN_RESTART_MISMATCH;
  }
  if (U32At(p + 56) != GroupSignature(mem->G, 0)) {
    LGN_ERROR(mem, LGN_RESTART_MISMATCH,
              "The restart file %s is of another Lie group (of the same sizes: other "
              "factors or another order).",
              filename);
    return LGN_RESTART_MISMATCH;
  }
  if (nrtfn != (int64_t)mem->nrtfn) {
    LGN_ERROR(mem, LGN_RESTART_MISMATCH,
              "The restart file %s has %lld root functions; this integrator has %d "
              "(call LGNRootInit as the run that wrote it did).",
              filename, (long long)nrtfn, mem->nrtfn);
    return LGN_RESTART_MISMATCH;
  }
  if (U32At(p + 20) != (uint32_t)NUM_FIELDS(SettingFields) ||
      U32At(p + 68) != (uint32_t)NUM_FIELDS(StateFields)) {
    LGN_ERROR(mem, LGN_RESTART_BAD_FILE,
              "The restart file %s has %u settings and %u state entries; version %u "
              "has %u and %u.",
              filename, (unsigned)U32At(p + 20), (unsigned)U32At(p + 68),
              (unsigned)LGN_RESTART_VERSION, (unsigned)NUM_FIELDS(SettingFields),
              (unsigned)NUM_FIELDS(StateFields));
    return LGN_RESTART_BAD_FILE;
  }
  return LGN_SUCCESS;
}

/* The next entry's head, checked against field f of this integrator:
 * name, kind and count. *values points to its values. */
static int GetFieldHead(LGNMem mem, const char *filename, Reader *r, const RsField *f,
                        const unsigned char **values, sunbooleantype setting)
{
  uint16_t len;
  uint8_t kind;
  int64_t n;
  char name[64];
  const sunindextype want = FieldCount(mem, f);
  if (Get(r, &len, sizeof len) != 0 || len >= sizeof name || Get(r, name, len) != 0 ||
      Get(r, &kind, sizeof kind) != 0 || Get(r, &n, sizeof n) != 0) {
    LGN_ERROR(mem, LGN_RESTART_BAD_FILE, "The restart file %s ends inside entry %s.",
              filename, f->name);
    return LGN_RESTART_BAD_FILE;
  }
  name[len] = '\0';
  if (strcmp(name, f->name) != 0 || kind != (uint8_t)StoredKind(f) || n < 0) {
    LGN_ERROR(mem, LGN_RESTART_BAD_FILE,
              "The restart file %s has entry '%s' where '%s' belongs.", filename, name,
              f->name);
    return LGN_RESTART_BAD_FILE;
  }
  if (n != (int64_t)want) {
    LGN_ERROR(mem, LGN_RESTART_MISMATCH,
              "The restart file %s has %lld values of %s%s; this integrator has %lld "
              "(another method, constraint formulation or root functions?).",
              filename, (long long)n, setting ? "the setting " : "", f->name,
              (long long)want);
    return LGN_RESTART_MISMATCH;
  }
  if ((size_t)n > (r->len - r->pos) / KindBytes(f->kind)) {
    LGN_ERROR(mem, LGN_RESTART_BAD_FILE, "The restart file %s ends inside entry %s.",
              filename, f->name);
    return LGN_RESTART_BAD_FILE;
  }
  *values = r->p + r->pos;
  r->pos += (size_t)n * KindBytes(f->kind);
  return LGN_SUCCESS;
}

/* A setting of the file against the integrator's, value by value (bits of
 * the reals: the steps depend on them bit for bit). */
static int CompareSetting(LGNMem mem, const char *filename, const RsField *f,
                          const unsigned char *values)
{
  const sunindextype n = FieldCount(mem, f);
  const void *own = FieldData(mem, f);
  sunindextype i;
  /* vector tolerances: atol is their mean, over all ranks after LGNSolve
   * (compared through atol_vec itself) */
  if (f->offset == OFF(atol) && mem->atol_vec != NULL) return LGN_SUCCESS;
  for (i = 0; i < n; i++) {
    int differs;
    double file_value, own_value;
    if (f->kind == RS_REAL || f->kind == RS_REALS) {
      sunrealtype x;
      memcpy(&x, values + (size_t)i * sizeof x, sizeof x);
      differs    = memcmp(&x, (const sunrealtype *)own + i, sizeof x) != 0;
      file_value = (double)x;
      own_value  = (double)((const sunrealtype *)own)[i];
    } else if (f->kind == RS_LONG) {
      long int x;
      memcpy(&x, values + (size_t)i * sizeof x, sizeof x);
      differs    = x != ((const long int *)own)[i];
      file_value = (double)x;
      own_value  = (double)((const long int *)own)[i];
    } else {
      int x, y;
      memcpy(&x, values + (size_t)i * sizeof x, sizeof x);
      y = (f->kind == RS_BOOL || f->kind == RS_BOOLS)
              ? (((const sunbooleantype *)own)[i] ? 1 : 0)
              : ((const int *)own)[i];
      differs    = x != y;
      file_value = (double)x;
      own_value  = (double)y;
    }
    if (differs) {
      LGN_ERROR(mem, LGN_RESTART_MISMATCH,
                "The restart file %s was written with %s%s = %.17g; this integrator "
                "has %.17g. The settings that decide the steps must be those of the "
                "run that wrote the file (set them before LGNReadRestart).",
                filename, f->name, n > 1 ? "[i]" : "", file_value, own_value);
      return LGN_RESTART_MISMATCH;
    }
  }
  return LGN_SUCCESS;
}

/* Pass 1: every entry checked, nothing written; the settings (whose
 * counts do not depend on the work space) before the record is prepared,
 * the state after (PrepareRecord). */
static int CheckEntries(LGNMem mem, const char *filename, const unsigned char *p, size_t len,
                        sunbooleantype state)
{
  Reader r = {p, len - 4, HEADER_BYTES};
  const unsigned char *values;
  size_t k;
  int flag;
  for (k = 0; k < NUM_FIELDS(SettingFields); k++) {
    flag = GetFieldHead(mem, filename, &r, &SettingFields[k], &values, SUNTRUE);
    if (flag == LGN_SUCCESS) flag = CompareSetting(mem, filename, &SettingFields[k], values);
    if (flag != LGN_SUCCESS) return flag;
  }
  if (!state) return LGN_SUCCESS;
  for (k = 0; k < NUM_FIELDS(StateFields); k++) {
    flag = GetFieldHead(mem, filename, &r, &StateFields[k], &values, SUNFALSE);
    if (flag != LGN_SUCCESS) return flag;
  }
  if (r.pos != r.len) {
    LGN_ERROR(mem, LGN_RESTART_BAD_FILE, "The restart file %s has %zu bytes after its entries.",
              filename, r.len - r.pos);
    return LGN_RESTART_BAD_FILE;
  }
  return LGN_SUCCESS;
}

/* Pass 2: the state copied into the record (every entry passed pass 1). */
static void CopyState(LGNMem mem, const unsigned char *p, size_t len)
{
  Reader r = {p, len - 4, HEADER_BYTES};
  const unsigned char *values;
  size_t k;
  for (k = 0; k < NUM_FIELDS(SettingFields); k++)
    (void)GetFieldHead(mem, "", &r, &SettingFields[k], &values, SUNTRUE);
  for (k = 0; k < NUM_FIELDS(StateFields); k++) {
    const RsField *f = &StateFields[k];
    const sunindextype n = FieldCount(mem, f);
    (void)GetFieldHead(mem, "", &r, f, &values, SUNFALSE);
    if (n == 0) continue;
    if (f->kind == RS_BOOL || f->kind == RS_BOOLS) {
      sunbooleantype *x = (sunbooleantype *)FieldData(mem, f);
      sunindextype i;
      for (i = 0; i < n; i++) {
        int v;
        memcpy(&v, values + (size_t)i * sizeof v, sizeof v);
        x[i] = v ? SUNTRUE : SUNFALSE;
      }
    } else {
      memcpy(FieldData(mem, f), values, (size_t)n * KindBytes(f->kind));
    }
  }
}

/* What the state needs allocated before it is copied: the work space (as
 * the first LGNSolve makes it), the BDF history, the root vectors. */
static int PrepareRecord(LGNMem mem)
{
  int flag = lgnEnsureWork(mem);
  if (flag == LGN_SUCCESS && mem->family == LGN_FAMILY_BDF) flag = lgnAgree(mem, lgnAllocBDF(mem));
  if (flag == LGN_SUCCESS && mem->nrtfn > 0) flag = lgnAgree(mem, lgnAllocRootVectors(mem));
  return flag;
}

static int ReadRestart(LGNMem mem, const char *filename)
{
  unsigned char *image = NULL;
  size_t len = 0;
  int flag = ReadImage(mem, filename, &image, &len);
  if (flag == LGN_SUCCESS) flag = CheckFormat(mem, filename, image, len);
  if (flag == LGN_SUCCESS) flag = CheckProblem(mem, filename, image);
  if (flag == LGN_SUCCESS) flag = CheckEntries(mem, filename, image, len, SUNFALSE);
  flag = lgnAgree(mem, flag);
  if (flag == LGN_SUCCESS) flag = PrepareRecord(mem); /* collective */
  if (flag == LGN_SUCCESS)
    flag = lgnAgree(mem, CheckEntries(mem, filename, image, len, SUNTRUE));
  if (flag == LGN_SUCCESS) {
    CopyState(mem, image, len);
    /* what the file cannot hold: the factorised iteration matrix in the
     * linear solver (modified Newton sets one up at the next step), the
     * constant mass matrix (evaluated again) */
    mem->lu_valid     = SUNFALSE;
    mem->klu_valid    = SUNFALSE;
    mem->mass_current = SUNFALSE;
  }
  free(image);
  return flag;
}

int LGNReadRestart(void *lgn_mem, const char *filename)
{
  LGNMem mem;
  int flag = AccessWithFile(lgn_mem, filename, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (mem->G == NULL || mem->G->nq != mem->nq || mem->G->nv != mem->nv) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "The Lie group changed size since LGNInit: call LGNInit.");
    return lgnAgree(mem, LGN_ILL_INPUT);
  }
  return ReadRestart(mem, filename);
}
