/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The work blocks of the record: each one calloc'ed block of reals cut into
 * slices, the arrays of the sub-records and of the step (mem->sigma ...,
 * mem->ec.ele, mem->dense.work, mem->out.vdot, mem->bdf.q ...). One table per
 * block gives every slice's field and length; allocating, pointing the
 * slices, freeing and counting (lgnWorkSpace, LGNGetWorkSpace) all read it,
 * so that the count cannot drift from the allocation. Adding an array is
 * adding one row.
 * ---------------------------------------------------------------------------*/

#include <stddef.h>
#include <stdlib.h>

#include "lgn_impl.h"

/* The length of a slice, from the record's sizes. */
typedef enum {
  WL_NV,       /* nv                                          */
  WL_4NV,      /* 4 nv                                        */
  WL_M,        /* m                                           */
  WL_GGL_MNV,  /* m nv under LGN_CONSTR_GGL, else 0           */
  WL_SAVE,     /* nq + 3 nv + m: q1, v1, vdot1, lambda1       */
  WL_TLEN,     /* the packed length of T's blocks             */
  WL_3BLKMAX,  /* 3 times the largest block                   */
  WL_HIST_NQ,  /* LGN_BDF_MAXHIST nq                          */
  WL_HIST_NV,  /* LGN_BDF_MAXHIST nv                          */
  WL_HIST_M,   /* LGN_BDF_MAXHIST m                           */
  WL_DD_NV     /* (LGN_BDF_MAXHIST + 1) nv                    */
} WorkLen;

/* When a slice's pointer is set (its reals are allocated in any case). */
typedef enum {
  WS_ALWAYS = 0, /* always (also at length 0)                        */
  WS_NONEMPTY,   /* when its length is > 0, else NULL                */
  WS_GGL         /* under LGN_CONSTR_GGL with m > 0, else NULL       */
} WorkSet;

typedef struct {
  size_t offset; /* of the sunrealtype pointer in struct LGNMemRec */
  WorkLen len;
  WorkSet set;
} WorkSlice;

#define SLICE(f, len, set) {offsetof(struct LGNMemRec, f), len, set}

/* The step's arrays (nv and m each; lgnAllocWork) */
static const WorkSlice StepSlices[] = {
  SLICE(sigma, WL_NV, WS_ALWAYS),        /* the block's start          */
  SLICE(sigma_dot, WL_NV, WS_ALWAYS),    SLICE(sigma_ddot, WL_NV, WS_ALWAYS),
  SLICE(a_pred, WL_NV, WS_ALWAYS),       SLICE(work_nv, WL_NV, WS_ALWAYS),
  SLICE(work2_nv, WL_NV, WS_ALWAYS),     SLICE(vdot_prev, WL_NV, WS_ALWAYS),
  SLICE(mass_diag, WL_NV, WS_ALWAYS),    SLICE(ec.ele, WL_NV, WS_ALWAYS),
  SLICE(ec.ewt, WL_NV, WS_ALWAYS),       SLICE(ec.a_scaled, WL_NV, WS_ALWAYS),
  SLICE(dense.incr, WL_NV, WS_ALWAYS),   SLICE(dense.zero_nv, WL_NV, WS_ALWAYS),
  SLICE(dense.work, WL_4NV, WS_ALWAYS),
  SLICE(lambda_prev, WL_M, WS_NONEMPTY), SLICE(work_m, WL_M, WS_NONEMPTY),
  SLICE(ggl_mu, WL_M, WS_GGL),           SLICE(ggl_Bn, WL_GGL_MNV, WS_GGL),
};

/* T(sigma), the exact kinematics' Tv and Ta (packed blocks), the block
 * routines' scratch (lgn_tangent.c) */
static const WorkSlice TangentSlices[] = {
  SLICE(Tm, WL_TLEN, WS_ALWAYS), SLICE(Tv, WL_TLEN, WS_ALWAYS),
  SLICE(Ta, WL_TLEN, WS_ALWAYS), SLICE(blk_work, WL_3BLKMAX, WS_ALWAYS),
};

/* the outputs (lgn_output.c): vdot, lambda, the kept slots, the iterate's
 * consistent lambda */
static const WorkSlice OutputSlices[] = {
  SLICE(out.vdot, WL_NV, WS_ALWAYS),   SLICE(out.lambda, WL_M, WS_NONEMPTY),
  SLICE(out.save, WL_SAVE, WS_ALWAYS), SLICE(out.lwork, WL_M, WS_NONEMPTY),
};

/* the BDF history and work arrays (lgn_bdf.c; lgnAllocBDF) */
static const WorkSlice BDFSlices[] = {
  SLICE(bdf.q, WL_HIST_NQ, WS_ALWAYS),  SLICE(bdf.v, WL_HIST_NV, WS_ALWAYS),
  SLICE(bdf.x, WL_HIST_NV, WS_ALWAYS),  SLICE(bdf.rx, WL_NV, WS_ALWAYS),
  SLICE(bdf.rv, WL_NV, WS_ALWAYS),      SLICE(bdf.xpred, WL_NV, WS_ALWAYS),
  SLICE(bdf.vpred, WL_NV, WS_ALWAYS),   SLICE(bdf.dd, WL_DD_NV, WS_ALWAYS),
  SLICE(bdf.l, WL_HIST_M, WS_ALWAYS),   SLICE(bdf.ele_keep, WL_NV, WS_ALWAYS),
};

typedef struct {
  const WorkSlice *slice;
  int nslice;
} WorkBlock;

#define BLOCK(t) {t, (int)(sizeof(t) / sizeof((t)[0]))}
static const WorkBlock Blocks[LGN_WORK_NBLOCKS] = {
  BLOCK(StepSlices), BLOCK(TangentSlices), BLOCK(OutputSlices), BLOCK(BDFSlices),
};

static size_t SliceLength(const struct LGNMemRec *mem, WorkLen len)
{
  const size_t nq = (size_t)mem->nq, nv = (size_t)mem->nv, m = (size_t)mem->m;
  const size_t H = LGN_BDF_MAXHIST;
  switch (len) {
  case WL_NV:      return nv;
  case WL_4NV:     return 4 * nv;
  case WL_M:       return m;
  case WL_GGL_MNV: return mem->constr_index == LGN_CONSTR_GGL ? m * nv : 0;
  case WL_SAVE:    return nq + 3 * nv + m;
  case WL_TLEN:    return (size_t)mem->blk.tlen;
  case WL_3BLKMAX: return 3 * (size_t)mem->blk.max;
  case WL_HIST_NQ: return H * nq;
  case WL_HIST_NV: return H * nv;
  case WL_HIST_M:  return H * m;
  case WL_DD_NV:   return (H + 1) * nv;
  }
  return 0;
}

static sunrealtype **SlicePointer(struct LGNMemRec *mem, const WorkSlice *s)
{
  return (sunrealtype **)(void *)((char *)mem + s->offset);
}

size_t lgnWorkBlockLength(const struct LGNMemRec *mem, int block)
{
  const WorkBlock *b = &Blocks[block];
  size_t n = 0;
  int i;
  for (i = 0; i < b->nslice; i++) n += SliceLength(mem, b->slice[i].len);
  return n;
}

sunbooleantype lgnWorkBlockAllocated(const struct LGNMemRec *mem, int block)
{
  const sunrealtype *const *first =
      (const sunrealtype *const *)(const void *)((const char *)mem + Blocks[block].slice[0].offset);
  return *first != NULL;
}

int lgnWorkBlockAlloc(struct LGNMemRec *mem, int block)
{
  const WorkBlock *b = &Blocks[block];
  const sunbooleantype ggl = mem->constr_index == LGN_CONSTR_GGL && mem->m > 0;
  sunrealtype *base, *p;
  int i;
  /* at least one real: the first slice's pointer marks the block as made */
  base = (sunrealtype *)calloc(SUNMAX(lgnWorkBlockLength(mem, block), (size_t)1),
                               sizeof(sunrealtype));
  if (base == NULL) return LGN_MEM_FAIL;
  for (i = 0, p = base; i < b->nslice; i++) {
    const WorkSlice *s = &b->slice[i];
    const size_t n     = SliceLength(mem, s->len);
    const sunbooleantype set = s->set == WS_ALWAYS || i == 0 ||
                               (s->set == WS_NONEMPTY && n > 0) ||
                               (s->set == WS_GGL && ggl);
    *SlicePointer(mem, s) = set ? p : NULL;
    p += n;
  }
  return LGN_SUCCESS;
}

void lgnWorkBlockFree(struct LGNMemRec *mem, int block)
{
  const WorkBlock *b = &Blocks[block];
  int i;
  free(*SlicePointer(mem, &b->slice[0]));
  for (i = 0; i < b->nslice; i++) *SlicePointer(mem, &b->slice[i]) = NULL;
}
