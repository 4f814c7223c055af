/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Private header of the planar body and joint sets (lignum_planar.h): what
 * lgn_bodies.c and lgn_joints.c dispatch to when their group is planar,
 * and the kinematics and matrix assembly the two share
 * (lgn_planar_assembly.c).
 *
 * A body k has q_k = (x, y, theta), R = R(theta), v_k = (u, omega) with u
 * inertial (R^2 x SO(2)) or body-fixed (SE(2): xdot = R u). Along
 * q o exp(e w) a body point p = x + R s moves by dp = H w,
 *   H = [P, R J s],  P = I or R,  J = [[0, -1], [1, 0]],
 * and the derivative of H u along w is E(u) w_theta with
 *   E(u) = R J u_x [SE(2) only] - R s u_theta.
 * Every constraint row and force element is evaluated locally on its two
 * bodies (6 directions: a's then b's): value, gradient and the Hessian
 * Hs[u, w] = D_w (D_u phi) (row-major, Hs[6 u + w]), from which B, the
 * curvature v^T Hs v and the stiffness lambda Hs follow.
 * ---------------------------------------------------------------------------*/

#ifndef LGN_PLANAR_H
#define LGN_PLANAR_H

#include <math.h>

#include <lignum/lignum_planar.h>

#include "lgn_err.h"

/* ---------------------------------------------------------------------------
 * Kinematics
 * ------------------------------------------------------------------------ */

typedef struct {
  sunbooleantype ground, se2;
  sunrealtype x[2], c, s;   /* position, cos and sin of the angle */
  sunrealtype th;           /* the angle (0 for the ground)       */
  sunrealtype v[3];         /* velocity (0 for the ground)        */
  sunindextype voff;        /* offset in v (-1 for the ground)    */
} lgnPlanarPose;

/* p = x + R s and, with H not NULL, H = dp/dw (2 x 3, row-major; zero for
 * the ground). */
static inline void lgnPlanarPoint(const lgnPlanarPose *P, const sunrealtype s[2],
                                  sunrealtype p[2], sunrealtype H[6])
{
  const sunrealtype rs0 = P->c * s[0] - P->s * s[1], rs1 = P->s * s[0] + P->c * s[1];
  p[0] = P->x[0] + rs0;
  p[1] = P->x[1] + rs1;
  if (H == NULL) return;
  if (P->ground) {
    H[0] = H[1] = H[2] = H[3] = H[4] = H[5] = 0;
    return;
  }
  H[0] = P->se2 ? P->c : 1;
  H[1] = P->se2 ? -P->s : 0;
  H[3] = P->se2 ? P->s : 0;
  H[4] = P->se2 ? P->c : 1;
  H[2] = -rs1; /* R J s = J R s */
  H[5] = rs0;
}

/* Hs[o + i, o + 2] += sign * cv . E(e_i) for the point s of the body at
 * local offset o (0 or 3): the second derivative of sign * cv . p. */
static inline void lgnPlanarPointHessian(const lgnPlanarPose *P, const sunrealtype s[2],
                                         const sunrealtype cv[2], sunrealtype sign,
                                         int o, sunrealtype *Hs)
{
  const sunrealtype rs0 = P->c * s[0] - P->s * s[1], rs1 = P->s * s[0] + P->c * s[1];
  if (P->ground) return;
  if (P->se2) { /* E(e_0) = R J e_0 = (-sin, cos), E(e_1) = (-cos, -sin) */
    Hs[6 * o + o + 2] += sign * (-cv[0] * P->s + cv[1] * P->c);
    Hs[6 * (o + 1) + o + 2] += sign * (-cv[0] * P->c - cv[1] * P->s);
  }
  Hs[6 * (o + 2) + o + 2] += -sign * (cv[0] * rs0 + cv[1] * rs1);
}

/* ---------------------------------------------------------------------------
 * Matrix assembly: entries emitted in a fixed order (pattern independent of
 * q), into a dense matrix (added or set) or a sparse one (CSC or CSR,
 * overwritten; its pattern built at the first call by collecting the
 * entries, duplicates summed)
 * ------------------------------------------------------------------------ */

typedef struct {
  int fmt;                     /* -1: none; CSC_MAT or CSR_MAT          */
  sunindextype nent;           /* entries emitted per evaluation         */
  sunindextype nnz;            /* distinct entries                       */
  sunindextype nmajor;         /* columns (CSC) or rows (CSR)            */
  sunindextype *ptr, *ind;     /* the pattern                            */
  sunindextype *pos;           /* data position of each emitted entry    */
  SUNMatrix work;              /* a sparse term added to a matrix that
                                  holds entries (lgnSparseAdd)           */
} lgnPlanarPattern;

typedef enum { LGN_PA_COLLECT, LGN_PA_DENSE_ADD, LGN_PA_DENSE_SET, LGN_PA_SPARSE } lgnPlanarMode;

typedef struct {
  lgnPlanarMode mode;
  SUNMatrix A;
  lgnPlanarPattern *pat;
  sunindextype k, cap;         /* entries so far; collect capacity      */
  sunindextype *row, *col;     /* collect mode                          */
  sunrealtype *data;           /* sparse mode                           */
  int memfail;
} lgnPlanarSink;

void lgnPlanarEmit(lgnPlanarSink *s, sunindextype r, sunindextype c, sunrealtype v);

/* Generates every entry of a matrix through lgnPlanarEmit; returns
 * LGN_SUCCESS or a failure flag (already reported). */
typedef int (*lgnPlanarGenFn)(void *ctx, lgnPlanarSink *s);

/* Write A (rows x cols) from gen: set = SUNTRUE, A is overwritten (dense
 * entry by entry, sparse with the pattern); set = SUNFALSE, the term is
 * added, the helpers' one rule for dense and sparse matrices
 * (lignum_bodies.h, "Matrices": a sparse A that holds entries gets the
 * union of the patterns). LGN_MEM_FAIL is reported here. */
int lgnPlanarWrite(lgnPlanarPattern *pat, SUNMatrix A, sunbooleantype set,
                   lgnPlanarGenFn gen, void *ctx, const LGNErrSink *err,
                   const char *func);

/* Forget the pattern (an element was added). */
void lgnPlanarPatternFree(lgnPlanarPattern *pat);

/* The number of distinct entries gen emits (builds the CSC pattern with q
 * = NULL allowed by gen); -1 on a memory failure. */
sunindextype lgnPlanarCount(lgnPlanarPattern *pat, sunindextype ncols,
                            lgnPlanarGenFn gen, void *ctx);

/* Is A a dense or sparse rows x cols matrix? Reports otherwise. */
int lgnPlanarCheckMat(SUNMatrix A, sunindextype rows, sunindextype cols,
                      const char *name, const LGNErrSink *err, const char *func);

/* ---------------------------------------------------------------------------
 * The sets (owned by an LGNJoints or LGNBodies, reporting to its sink)
 * ------------------------------------------------------------------------ */

typedef struct lgnPlanarJointsRec lgnPlanarJoints;
typedef struct lgnPlanarBodiesRec lgnPlanarBodies;

/* Create the planar set of G (lgnGroupPlanarBodies(G) > 0), reporting to
 * err (the owner's sink); NULL on a memory failure (reported). */
lgnPlanarJoints *lgnPlanarJointsCreate(LGNGroup G, const LGNErrSink *err, const char *func);
void lgnPlanarJointsDestroy(lgnPlanarJoints *P);
sunindextype lgnPlanarJointsNumConstraints(const lgnPlanarJoints *P);
int lgnPlanarJointsNumDrivers(const lgnPlanarJoints *P);
sunindextype lgnPlanarJointsJacobianNnz(lgnPlanarJoints *P);
sunindextype lgnPlanarJointsStiffnessNnz(lgnPlanarJoints *P);
int lgnPlanarJointsDescribe(const lgnPlanarJoints *P, sunindextype row, char *buf,
                            size_t len, const char *func);
int lgnPlanarJointsResidual(lgnPlanarJoints *P, sunrealtype t, N_Vector q, N_Vector phi,
                            const char *func);
int lgnPlanarJointsJacobian(lgnPlanarJoints *P, sunrealtype t, N_Vector q, SUNMatrix B,
                            const char *func);
int lgnPlanarJointsConstraintForce(lgnPlanarJoints *P, sunrealtype t, N_Vector q,
                                   N_Vector lambda, N_Vector f, const char *func);
int lgnPlanarJointsCurvature(lgnPlanarJoints *P, sunrealtype t, N_Vector q, N_Vector v,
                             N_Vector z, const char *func);
int lgnPlanarJointsTimeDerivative(lgnPlanarJoints *P, sunrealtype t, N_Vector q,
                                  N_Vector phit, const char *func);
int lgnPlanarJointsStiffness(lgnPlanarJoints *P, sunrealtype t, N_Vector q,
                             N_Vector lambda, SUNMatrix K, const char *func);
/* The planar joints (lgn_planar_api.c has the public calls). */
int lgnPlanarJointsAddRevolute2(lgnPlanarJoints *P, int a, const sunrealtype sa[2], int b,
                                const sunrealtype sb[2], const char *func);
int lgnPlanarJointsAddPrismatic(lgnPlanarJoints *P, int a, const sunrealtype sa[2],
                                const sunrealtype axis_a[2], int b, const sunrealtype sb[2],
                                sunrealtype theta0, const char *func);
int lgnPlanarJointsAddRotationDriver(lgnPlanarJoints *P, int a, int b, LGNDriveFn f,
                                     void *drive_data, const char *func);
int lgnPlanarJointsAddTranslationDriver(lgnPlanarJoints *P, int a, const sunrealtype sa[2],
                                        const sunrealtype axis_a[2], int b,
                                        const sunrealtype sb[2], LGNDriveFn f,
                                        void *drive_data, const char *func);
/* The spatial LGNJoints_AddRevolute on a planar set: axes along z. */
int lgnPlanarJointsAddRevolute3(lgnPlanarJoints *P, int a, const sunrealtype sa[3],
                                const sunrealtype axis_a[3], int b,
                                const sunrealtype sb[3], const sunrealtype axis_b[3],
                                const char *func);

/* The planar part of a joint or body set (NULL: a spatial set or NULL) and
 * its sink (NULL for NULL): defined in lgn_joints.c and lgn_bodies.c, for
 * the public planar calls (lgn_planar_api.c). */
lgnPlanarJoints *lgnJointsPlanarPart(LGNJoints J);
const LGNErrSink *lgnJointsSink(LGNJoints J);
lgnPlanarBodies *lgnBodiesPlanarPart(LGNBodies B);
const LGNErrSink *lgnBodiesSink(LGNBodies B);

lgnPlanarBodies *lgnPlanarBodiesCreate(LGNGroup G, const LGNErrSink *err, const char *func);
void lgnPlanarBodiesDestroy(lgnPlanarBodies *P);
int lgnPlanarBodiesSetMass(lgnPlanarBodies *P, int k, sunrealtype m, sunrealtype Jz,
                           const char *func);
int lgnPlanarBodiesSetGravity(lgnPlanarBodies *P, const sunrealtype gravity[3],
                              const char *func);
int lgnPlanarBodiesAddSpring2(lgnPlanarBodies *P, int a, const sunrealtype sa[2], int b,
                              const sunrealtype sb[2], sunrealtype k, sunrealtype c,
                              sunrealtype L0, const char *func);
int lgnPlanarBodiesAddRotSpring(lgnPlanarBodies *P, int a, int b, sunrealtype kr,
                                sunrealtype cr, sunrealtype theta0, const char *func);
int lgnPlanarBodiesAddSpring3(lgnPlanarBodies *P, int a, const sunrealtype sa[3], int b,
                              const sunrealtype sb[3], sunrealtype k, sunrealtype c,
                              sunrealtype L0, const char *func);
int lgnPlanarBodiesAddRotSpringQuat(lgnPlanarBodies *P, int a, int b, sunrealtype kr,
                                    sunrealtype cr, const sunrealtype rest[4],
                                    const char *func);
sunindextype lgnPlanarBodiesMassNnz(lgnPlanarBodies *P);
sunindextype lgnPlanarBodiesTangentNnz(lgnPlanarBodies *P);
int lgnPlanarBodiesMass(lgnPlanarBodies *P, N_Vector q, SUNMatrix M, const char *func);
int lgnPlanarBodiesForce(lgnPlanarBodies *P, N_Vector q, N_Vector v, N_Vector g,
                         const char *func);
int lgnPlanarBodiesTangent(lgnPlanarBodies *P, N_Vector q, N_Vector v, SUNMatrix A,
                           sunbooleantype damping, const char *func);
int lgnPlanarBodiesEnergy(lgnPlanarBodies *P, N_Vector q, N_Vector v, sunrealtype *kin,
                          sunrealtype *pot, const char *func);

#endif
