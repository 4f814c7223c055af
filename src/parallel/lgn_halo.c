/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The halo of ghost bodies (lignum_halo.h, lgn_halo.h).
 *
 * Creation (collective): each rank sends the owners of its ghosts the
 * global numbers it needs (MPI_Alltoall of the counts, MPI_Alltoallv of
 * the numbers); an owner finds each number among its own bodies (a sorted
 * copy of its global numbers) and answers with the body's kind, or -1.
 * A fault found on any rank fails the creation on every rank (one
 * MPI_Allreduce), reported by the rank that found it.
 *
 * Exchanges: per neighbour a contiguous buffer, nonblocking sends and
 * receives, MPI_Waitall. Forward: owners -> ghosts (receive lists: this
 * rank's ghosts by owner; send lists: its bodies each neighbour holds as
 * ghosts). Reverse: the same lists the other way, the received rows added
 * to the owned ones in a fixed order, so that every run sums alike.
 * Built with MPI only (src/CMakeLists.txt).
 * ---------------------------------------------------------------------------*/

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sundials/sundials_math.h>

#include "groups/lgn_group_impl.h"
#include "lgn_halo.h"

#if defined(SUNDIALS_DOUBLE_PRECISION)
#define HALO_MPI_REAL MPI_DOUBLE
#elif defined(SUNDIALS_SINGLE_PRECISION)
#define HALO_MPI_REAL MPI_FLOAT
#else
#define HALO_MPI_REAL MPI_LONG_DOUBLE
#endif

#define TAG_FORWARD 7101
#define TAG_REVERSE 7102

/* One side of the exchange with the neighbours: for neighbour k (rank
 * rank[k]) the bodies body[ptr[k] ... ptr[k+1]-1] (local leaves). */
typedef struct {
  int n;         /* neighbours                                             */
  int *rank;     /* n                                                      */
  int *ptr;      /* n + 1                                                  */
  int *body;     /* ptr[n]                                                 */
  int *qptr;     /* n + 1: offsets of each neighbour in a q-kind buffer    */
  int *vptr;     /* n + 1: ... in a v-kind buffer                          */
} Side;

struct LGNHaloRec {
  MPI_Comm comm;
  int rank, size;
  LGNGroup G;
  int nbodies, nowned;
  sunindextype *qoff, *voff; /* nbodies + 1 */
  Side send, recv;           /* forward: send = to ghosts' holders, recv = from owners */
  sunrealtype *sbuf, *rbuf;  /* the largest buffers of either kind       */
  MPI_Request *req;          /* send.n + recv.n                          */
};

static void Report(int rank, const char *fmt, ...)
{
  va_list ap;
  fprintf(stderr, "\n[Lignum ERROR]  LGNHalo_Create (rank %d)\n  ", rank);
  va_start(ap, fmt);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
  fprintf(stderr, "\n\n");
}

static void FreeSide(Side *s)
{
  free(s->rank);
  free(s->ptr);
  free(s->body);
  free(s->qptr);
  free(s->vptr);
  memset(s, 0, sizeof *s);
}

static void FreeHalo(LGNHalo H)
{
  if (H == NULL) return;
  FreeSide(&H->send);
  FreeSide(&H->recv);
  free(H->qoff);
  free(H->voff);
  free(H->sbuf);
  free(H->rbuf);
  free(H->req);
  if (H->comm != MPI_COMM_NULL) MPI_Comm_free(&H->comm);
  free(H);
}

/* Side s from the per-rank counts cnt[size] and the bodies listed rank by
 * rank in bodies (ptr order); the buffer offsets of both kinds. */
static int MakeSide(LGNHalo H, Side *s, const int *cnt, const int *bodies)
{
  int p, k = 0, i, total = 0;
  for (p = 0; p < H->size; p++) {
    if (cnt[p] > 0) s->n++;
    total += cnt[p];
  }
  s->rank = (int *)malloc((size_t)(s->n + 1) * sizeof(int));
  s->ptr  = (int *)malloc((size_t)(s->n + 1) * sizeof(int));
  s->qptr = (int *)malloc((size_t)(s->n + 1) * sizeof(int));
  s->vptr = (int *)malloc((size_t)(s->n + 1) * sizeof(int));
  s->body = (int *)malloc((size_t)(total + 1) * sizeof(int));
  if (s->rank == NULL || s->ptr == NULL || s->qptr == NULL || s->vptr == NULL ||
      s->body == NULL)
    return -1;
  s->ptr[0] = s->qptr[0] = s->vptr[0] = 0;
  for (p = 0; p < H->size; p++) {
    if (cnt[p] == 0) continue;
    s->rank[k]    = p;
    s->ptr[k + 1] = s->ptr[k] + cnt[p];
    s->qptr[k + 1] = s->qptr[k];
    s->vptr[k + 1] = s->vptr[k];
    for (i = s->ptr[k]; i < s->ptr[k + 1]; i++) {
      s->body[i] = bodies[i];
      s->qptr[k + 1] += (int)(H->qoff[bodies[i] + 1] - H->qoff[bodies[i]]);
      s->vptr[k + 1] += (int)(H->voff[bodies[i] + 1] - H->voff[bodies[i]]);
    }
    k++;
  }
  return 0;
}

typedef struct {
  long int gid;
  int body;
} GlobalBody;

static int CompareGlobal(const void *a, const void *b)
{
  const long int x = ((const GlobalBody *)a)->gid, y = ((const GlobalBody *)b)->gid;
  return (x > y) - (x < y);
}

/* The local checks of the arguments (no communication): a message and -1. */
static int CheckArguments(int rank, int size, LGNGroup G, int nbodies, int nowned,
                          const long int *global_id, const int *ghost_owner)
{
  int i;
  if (G == NULL) {
    Report(rank, "G = NULL illegal.");
    return -1;
  }
  if (nbodies <= 0) {
    Report(rank, "G must be R^3 x SO(3), SE(3) or a product of them (its leaves are the bodies).");
    return -1;
  }
  if (nowned < 1 || nowned > nbodies) {
    Report(rank, "nowned = %d illegal: 1 ... %d (the bodies of G).", nowned, nbodies);
    return -1;
  }
  if (global_id == NULL) {
    Report(rank, "global_id = NULL illegal.");
    return -1;
  }
  if (ghost_owner == NULL && nbodies > nowned) {
    Report(rank, "ghost_owner = NULL illegal with %d ghosts.", nbodies - nowned);
    return -1;
  }
  for (i = 0; i < nbodies; i++)
    if (global_id[i] < 0) {
      Report(rank, "global_id[%d] = %ld illegal: global numbers are >= 0.", i, global_id[i]);
      return -1;
    }
  for (i = nowned; i < nbodies; i++)
    if (ghost_owner[i - nowned] < 0 || ghost_owner[i - nowned] >= size ||
        ghost_owner[i - nowned] == rank) {
      Report(rank, "ghost_owner[%d] = %d illegal: a ghost's owner is another rank than "
                   "this one (%d), in 0 ... %d.", i - nowned, ghost_owner[i - nowned], rank,
             size - 1);
      return -1;
    }
  return 0;
}

/* Does any rank have fail set? (one reduction) */
static int AnyFailed(MPI_Comm comm, int fail)
{
  int any = 0;
  MPI_Allreduce(&fail, &any, 1, MPI_INT, MPI_MAX, comm);
  return any;
}

/* Each global number is owned by exactly one rank (collective, after the
 * local checks passed on every rank): the owned numbers of all ranks,
 * gathered and sorted, hold no number twice. Every rank finds the same;
 * rank 0 reports it. Returns nonzero on every rank if not. */
static int CheckOneOwner(MPI_Comm comm, int rank, int size, int nowned,
                         const long int *global_id)
{
  int *counts = (int *)malloc(2 * (size_t)size * sizeof(int)), *displs;
  long int *all = NULL;
  GlobalBody *owned = NULL;
  int i, r, total = 0, fail = counts == NULL;
  if (AnyFailed(comm, fail)) {
    free(counts);
    if (rank == 0) Report(rank, "A memory request failed.");
    return -1;
  }
  displs = counts + size;
  MPI_Allgather(&nowned, 1, MPI_INT, counts, 1, MPI_INT, comm);
  for (r = 0; r < size; r++) {
    displs[r] = total;
    total += counts[r];
  }
  all   = (long int *)malloc((size_t)total * sizeof(long int));
  owned = (GlobalBody *)malloc((size_t)total * sizeof(GlobalBody));
  fail  = all == NULL || owned == NULL;
  if (AnyFailed(comm, fail)) {
    if (rank == 0) Report(rank, "A memory request failed.");
    fail = 1;
  } else {
    MPI_Allgatherv(global_id, nowned, MPI_LONG, all, counts, displs, MPI_LONG, comm);
    for (r = 0; r < size; r++) /* (gid, owning rank) */
      for (i = 0; i < counts[r]; i++) {
        owned[displs[r] + i].gid  = all[displs[r] + i];
        owned[displs[r] + i].body = r;
      }
    qsort(owned, (size_t)total, sizeof *owned, CompareGlobal);
    for (i = 1; i < total && !fail; i++)
      if (owned[i].gid == owned[i - 1].gid) {
        const int r1 = SUNMIN(owned[i].body, owned[i - 1].body);
        const int r2 = SUNMAX(owned[i].body, owned[i - 1].body);
        char who[64];
        if (r1 == r2)
          snprintf(who, sizeof who, "rank %d twice", r1);
        else
          snprintf(who, sizeof who, "ranks %d and %d", r1, r2);
        fail = 1;
        if (rank == 0)
          Report(rank, "global_id: the global number %ld is owned by %s: each global "
                       "number is owned by exactly one rank (among its first nowned "
                       "bodies); the others list it as a ghost.", owned[i].gid, who);
      }
  }
  free(all);
  free(owned);
  free(counts);
  return fail ? -1 : 0;
}

/* The ghosts' requests to their owners and the owners' answers: the send
 * side (bodies each neighbour needs) on the owners, and the check of the
 * answers on the requesters. */
static int Connect(LGNHalo H, const long int *global_id, const int *ghost_owner,
                   const sunbooleantype *se3)
{
  const int P = H->size, ng = H->nbodies - H->nowned;
  int *rcnt = (int *)calloc((size_t)P, sizeof(int));
  int *scnt = (int *)calloc((size_t)P, sizeof(int));
  int *rdsp = (int *)calloc((size_t)P + 1, sizeof(int));
  int *sdsp = (int *)calloc((size_t)P + 1, sizeof(int));
  int *order = (int *)malloc((size_t)(ng + 1) * sizeof(int));
  long int *want = (long int *)malloc((size_t)(ng + 1) * sizeof(long int));
  int *answer = (int *)malloc((size_t)(ng + 1) * sizeof(int));
  GlobalBody *own = (GlobalBody *)malloc((size_t)H->nowned * sizeof(GlobalBody));
  long int *asked = NULL;
  int *reply = NULL, *sbodies = NULL;
  int fail = (rcnt == NULL || scnt == NULL || rdsp == NULL || sdsp == NULL ||
              order == NULL || want == NULL || answer == NULL || own == NULL);
  int p, i, j, nasked = 0;

  if (AnyFailed(H->comm, fail)) {
    if (fail) Report(H->rank, "A memory request failed.");
    fail = 1;
    goto done;
  }
  /* the ghosts grouped by owner (stable: in the order of G) */
  for (i = 0; i < ng; i++) rcnt[ghost_owner[i]]++;
  for (p = 0; p < P; p++) rdsp[p + 1] = rdsp[p] + rcnt[p];
  {
    int *fill = sdsp; /* scratch: the next slot per owner */
    memcpy(fill, rdsp, (size_t)P * sizeof(int));
    for (i = 0; i < ng; i++) {
      const int k = fill[ghost_owner[i]]++;
      order[k] = H->nowned + i;
      want[k]  = global_id[H->nowned + i];
    }
  }
  MPI_Alltoall(rcnt, 1, MPI_INT, scnt, 1, MPI_INT, H->comm);
  sdsp[0] = 0;
  for (p = 0; p < P; p++) sdsp[p + 1] = sdsp[p] + scnt[p];
  nasked  = sdsp[P];
  asked   = (long int *)malloc((size_t)(nasked + 1) * sizeof(long int));
  reply   = (int *)malloc((size_t)(nasked + 1) * sizeof(int));
  sbodies = (int *)malloc((size_t)(nasked + 1) * sizeof(int));
  fail = (asked == NULL || reply == NULL || sbodies == NULL);
  if (AnyFailed(H->comm, fail)) {
    if (fail) Report(H->rank, "A memory request failed.");
    fail = 1;
    goto done;
  }
  MPI_Alltoallv(want, rcnt, rdsp, MPI_LONG, asked, scnt, sdsp, MPI_LONG, H->comm);

  /* the owner's answers: the body's kind (0 R^3 x SO(3), 1 SE(3)), or -1 */
  for (i = 0; i < H->nowned; i++) {
    own[i].gid  = global_id[i];
    own[i].body = i;
  }
  qsort(own, (size_t)H->nowned, sizeof *own, CompareGlobal);
  for (i = 1; i < H->nowned && !fail; i++)
    if (own[i].gid == own[i - 1].gid) {
      Report(H->rank, "global_id: the number %ld is given to bodies %d and %d.", own[i].gid,
             own[i - 1].body, own[i].body);
      fail = 1;
    }
  for (j = 0; j < nasked; j++) {
    GlobalBody key, *hit;
    key.gid  = asked[j];
    key.body = 0;
    hit = (GlobalBody *)bsearch(&key, own, (size_t)H->nowned, sizeof *own, CompareGlobal);
    sbodies[j] = hit != NULL ? hit->body : 0;
    reply[j]   = hit != NULL ? (se3[hit->body] ? 1 : 0) : -1;
  }
  MPI_Alltoallv(reply, scnt, sdsp, MPI_INT, answer, rcnt, rdsp, MPI_INT, H->comm);
  for (p = 0; p < P && !fail; p++)
    for (j = rdsp[p]; j < rdsp[p + 1] && !fail; j++) {
      if (answer[j] < 0) {
        Report(H->rank, "ghost body %d (global number %ld): rank %d owns no body of that number.",
               order[j], want[j], p);
        fail = 1;
      } else if ((answer[j] == 1) != (se3[order[j]] ? 1 : 0)) {
        Report(H->rank, "ghost body %d (global number %ld) is %s here but %s on its owner, rank %d.",
               order[j], want[j], se3[order[j]] ? "SE(3)" : "R^3 x SO(3)",
               answer[j] == 1 ? "SE(3)" : "R^3 x SO(3)", p);
        fail = 1;
      }
    }
  for (i = 0; i < ng - 1 && !fail; i++) /* a ghost listed twice */
    for (j = i + 1; j < ng && !fail; j++)
      if (global_id[H->nowned + i] == global_id[H->nowned + j]) {
        Report(H->rank, "global_id: ghosts %d and %d have the same number %ld.",
               H->nowned + i, H->nowned + j, global_id[H->nowned + i]);
        fail = 1;
      }
  if (!fail) fail = MakeSide(H, &H->recv, rcnt, order) != 0 || MakeSide(H, &H->send, scnt, sbodies) != 0;
  fail = AnyFailed(H->comm, fail);

done:
  free(rcnt);
  free(scnt);
  free(rdsp);
  free(sdsp);
  free(order);
  free(want);
  free(answer);
  free(own);
  free(asked);
  free(reply);
  free(sbodies);
  return fail ? -1 : 0;
}

LGNHalo LGNHalo_Create(MPI_Comm comm, LGNGroup G, int nowned, const long int *global_id,
                       const int *ghost_owner)
{
  int initialized = 0, rank = 0, size = 1, nb, fail;
  sunbooleantype *se3 = NULL;
  LGNHalo H;
  MPI_Initialized(&initialized);
  if (!initialized || comm == MPI_COMM_NULL) {
    Report(0, initialized ? "comm = MPI_COMM_NULL illegal." : "MPI is not initialised.");
    return NULL;
  }
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  nb   = G != NULL ? lgnGroupRigidBodies(G, NULL, NULL, NULL) : -1;
  fail = CheckArguments(rank, size, G, nb, nowned, global_id, ghost_owner) != 0;
  H    = fail ? NULL : (LGNHalo)calloc(1, sizeof(*H));
  if (!fail && H == NULL) {
    Report(rank, "A memory request failed.");
    fail = 1;
  }
  if (!fail) {
    H->comm    = MPI_COMM_NULL;
    H->G       = G;
    H->nbodies = nb;
    H->nowned  = nowned;
    H->rank    = rank;
    H->size    = size;
    H->qoff    = (sunindextype *)malloc((size_t)(nb + 1) * sizeof(sunindextype));
    H->voff    = (sunindextype *)malloc((size_t)(nb + 1) * sizeof(sunindextype));
    se3        = (sunbooleantype *)malloc((size_t)(nb + 1) * sizeof(sunbooleantype));
    if (H->qoff == NULL || H->voff == NULL || se3 == NULL) {
      Report(rank, "A memory request failed.");
      fail = 1;
    }
  }
  if (AnyFailed(comm, fail) || CheckOneOwner(comm, rank, size, nowned, global_id) != 0) {
    FreeHalo(H);
    free(se3);
    return NULL;
  }
  lgnGroupRigidBodies(G, H->qoff, H->voff, se3);
  H->qoff[nb] = G->nq;
  H->voff[nb] = G->nv;
  MPI_Comm_dup(comm, &H->comm);
  fail = Connect(H, global_id, ghost_owner, se3) != 0;
  free(se3);
  if (!fail) {
    const int n = SUNMAX(SUNMAX(H->send.qptr[H->send.n], H->recv.qptr[H->recv.n]),
                         SUNMAX(H->send.vptr[H->send.n], H->recv.vptr[H->recv.n]));
    H->sbuf = (sunrealtype *)malloc((size_t)(n + 1) * sizeof(sunrealtype));
    H->rbuf = (sunrealtype *)malloc((size_t)(n + 1) * sizeof(sunrealtype));
    H->req  = (MPI_Request *)malloc((size_t)(H->send.n + H->recv.n + 1) * sizeof(MPI_Request));
    fail    = H->sbuf == NULL || H->rbuf == NULL || H->req == NULL;
    if (fail) Report(rank, "A memory request failed.");
  }
  if (AnyFailed(H->comm, fail)) {
    FreeHalo(H);
    return NULL;
  }
  return H;
}

void LGNHalo_Destroy(LGNHalo *H)
{
  if (H == NULL) return;
  FreeHalo(*H);
  *H = NULL;
}

int LGNHalo_NumOwned(LGNHalo H) { return H != NULL ? H->nowned : 0; }
int LGNHalo_NumGhosts(LGNHalo H) { return H != NULL ? H->nbodies - H->nowned : 0; }
int LGNHalo_NumNeighbours(LGNHalo H)
{
  int n = 0, i, j, found;
  if (H == NULL) return 0;
  n = H->send.n;
  for (i = 0; i < H->recv.n; i++) {
    found = 0;
    for (j = 0; j < H->send.n; j++) found = found || H->send.rank[j] == H->recv.rank[i];
    n += !found;
  }
  return n;
}

LGNGroup lgnHaloGroup(const LGNHalo H) { return H->G; }
MPI_Comm lgnHaloComm(const LGNHalo H) { return H->comm; }

void lgnHaloOwnedLengths(const LGNHalo H, sunindextype *nq_own, sunindextype *nv_own)
{
  *nq_own = H->qoff[H->nowned];
  *nv_own = H->voff[H->nowned];
}

/* The entries of body b of kind (offsets off) to/from a buffer. */
static sunrealtype *Pack(const sunindextype *off, int b, const sunrealtype *x, sunrealtype *buf)
{
  sunindextype i;
  for (i = off[b]; i < off[b + 1]; i++) *buf++ = x[i];
  return buf;
}

/* Post the receives of side r and the sends of side s (buffers of the kind
 * with offsets ptr of each), packing s's bodies of x. */
static void Exchange(LGNHalo H, const Side *r, const int *rptr, const Side *s,
                     const int *sptr, const sunindextype *off, const sunrealtype *x,
                     int tag)
{
  int k, i, nreq = 0;
  for (k = 0; k < r->n; k++)
    MPI_Irecv(H->rbuf + rptr[k], rptr[k + 1] - rptr[k], HALO_MPI_REAL, r->rank[k], tag,
              H->comm, &H->req[nreq++]);
  for (k = 0; k < s->n; k++) {
    sunrealtype *buf = H->sbuf + sptr[k];
    for (i = s->ptr[k]; i < s->ptr[k + 1]; i++) buf = Pack(off, s->body[i], x, buf);
    MPI_Isend(H->sbuf + sptr[k], sptr[k + 1] - sptr[k], HALO_MPI_REAL, s->rank[k], tag,
              H->comm, &H->req[nreq++]);
  }
  MPI_Waitall(nreq, H->req, MPI_STATUSES_IGNORE);
}

void lgnHaloForward(LGNHalo H, int kind, sunrealtype *x)
{
  const sunindextype *off = kind == LGN_HALO_CONFIGURATION ? H->qoff : H->voff;
  const int *rptr = kind == LGN_HALO_CONFIGURATION ? H->recv.qptr : H->recv.vptr;
  const int *sptr = kind == LGN_HALO_CONFIGURATION ? H->send.qptr : H->send.vptr;
  const sunrealtype *buf = H->rbuf;
  int k, i;
  sunindextype j;
  Exchange(H, &H->recv, rptr, &H->send, sptr, off, x, TAG_FORWARD);
  for (k = 0; k < H->recv.n; k++)
    for (i = H->recv.ptr[k]; i < H->recv.ptr[k + 1]; i++) {
      const int b = H->recv.body[i];
      for (j = off[b]; j < off[b + 1]; j++) x[j] = *buf++;
    }
}

void lgnHaloReverse(LGNHalo H, const sunrealtype *src, sunrealtype *owned)
{
  const sunrealtype *buf = H->rbuf;
  int k, i;
  sunindextype j;
  /* the ghosts' rows go to their owners: receive what the holders of this
   * rank's bodies send (the forward send side), send along the receive side */
  Exchange(H, &H->send, H->send.vptr, &H->recv, H->recv.vptr, H->voff, src, TAG_REVERSE);
  for (k = 0; k < H->send.n; k++)
    for (i = H->send.ptr[k]; i < H->send.ptr[k + 1]; i++) {
      const int b = H->send.body[i];
      for (j = H->voff[b]; j < H->voff[b + 1]; j++) owned[j] += *buf++;
    }
}

void lgnHaloClearGhosts(const LGNHalo H, sunrealtype *q, sunrealtype *v)
{
  int b;
  sunindextype i;
  for (b = H->nowned; b < H->nbodies; b++) {
    if (q != NULL) { /* R^3 x SO(3) and SE(3) alike: (x, p), p scalar first */
      for (i = H->qoff[b]; i < H->qoff[b + 1]; i++) q[i] = SUN_RCONST(0.0);
      q[H->qoff[b] + 3] = SUN_RCONST(1.0);
    }
    if (v != NULL)
      for (i = H->voff[b]; i < H->voff[b + 1]; i++) v[i] = SUN_RCONST(0.0);
  }
}

int LGNHalo_UpdateGhosts(LGNHalo H, int kind, sunrealtype *x)
{
  if (H == NULL || x == NULL ||
      (kind != LGN_HALO_CONFIGURATION && kind != LGN_HALO_VELOCITY)) {
    fprintf(stderr, "\n[Lignum ERROR]  LGNHalo_UpdateGhosts\n  %s\n\n",
            H == NULL   ? "H = NULL illegal."
            : x == NULL ? "x = NULL illegal."
                        : "kind illegal: LGN_HALO_CONFIGURATION or LGN_HALO_VELOCITY.");
    return LGN_ILL_INPUT;
  }
  lgnHaloForward(H, kind, x);
  return LGN_SUCCESS;
}
