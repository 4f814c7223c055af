/* -----------------------------------------------------------------------------
 * The C side of the Python package: one record that owns a model (the body
 * and joint sets, or Python callbacks), its state vectors and an integrator
 * with the dense linear solver, and the model callbacks that Lignum calls.
 * A multibody model runs entirely in C: the model object of lignum_model.h
 * (LGNModel_Attach) installs the body and joint sets' callbacks, spatial or
 * planar (lignum_planar.h); Python is called only for what the user wrote in
 * Python (an applied force, given to the model as its user force; whole
 * models; root functions; drivers given as Python functions).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/
#ifndef LIGNUM_PY_GLUE_H
#define LIGNUM_PY_GLUE_H

#include <stdint.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_model.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

/* Which model callback a Python call is for (argument `which`). */
#define LGNPY_CB_FORCE       0 /* g(q, v, t), whole Python model          */
#define LGNPY_CB_APPLIED     1 /* applied force f added to a C model: g -= f */
#define LGNPY_CB_CONSTR      2 /* Phi(q, t)                               */
#define LGNPY_CB_CURVATURE   3 /* Z(q, v, t)                              */
#define LGNPY_CB_CONSTR_TIME 4 /* Phi_t(q, t)                             */
#define LGNPY_CB_ROOT        5 /* root functions g_i(t, q, v)             */
#define LGNPY_CB_MASS        10
#define LGNPY_CB_JAC         11
#define LGNPY_CB_STIFFNESS   12
#define LGNPY_CB_DAMPING     13
#define LGNPY_CB_APPLIED_DQ  14 /* df/dq of the applied force (along G)  */
#define LGNPY_CB_APPLIED_DV  15 /* df/dv of the applied force            */

/* Python model callbacks present (bit set of LGNPySystem.pyflags). */
#define LGNPY_HAS_STIFFNESS   1
#define LGNPY_HAS_DAMPING     2
#define LGNPY_HAS_CURVATURE   4
#define LGNPY_HAS_CONSTR_TIME 8

/* Built-in drive laws of the drivers (no Python in the loop). */
#define LGNPY_DRIVE_POLYNOMIAL 0 /* f = c0 + c1 t + c2 t^2 + c3 t^3  */
#define LGNPY_DRIVE_HARMONIC   1 /* f = c0 + c1 sin(c2 t + c3)        */
#define LGNPY_DRIVE_PYTHON     2 /* f, f', f'' from a Python function */

/* Group factors (LGNPy_AddGroupFactor, LGNPy_MultibodyInit). */
#define LGNPY_GROUP_RN     0
#define LGNPY_GROUP_SO3    1
#define LGNPY_GROUP_R3XSO3 2
#define LGNPY_GROUP_SE3    3
#define LGNPY_GROUP_SE2    4
#define LGNPY_GROUP_R2XSO2 5

#define LGNPY_MSG_LEN 1024

typedef struct LGNPyDriveRec {
  struct LGNPySystemRec *sys;
  int kind;
  int index;             /* the driver's number, for Python drive laws */
  sunrealtype c[4];
} LGNPyDrive;

typedef struct LGNPySystemRec {
  SUNContext ctx;
  LGNGroup G;            /* the configuration group                   */
  LGNGroup factors[64];  /* its factors when built here (destroyed)   */
  int nfactors;
  LGNBodies bodies;      /* multibody model (NULL for a Python model) */
  LGNJoints joints;
  LGNModel model;        /* the model object on the two sets          */
  LGNPyDrive *drives[256];
  int ndrives;
  void *mem;             /* the integrator                            */
  N_Vector q, v;         /* wrap the Python package's arrays          */
  N_Vector vdot, lambda; /* outputs, wrap Python arrays as well       */
  N_Vector y;            /* linear solver template                    */
  SUNMatrix A;
  SUNLinearSolver LS;
  sunindextype nq, nv, m;
  int python_model;      /* callbacks are Python functions            */
  int planar;            /* a multibody model on SE(2) or R^2 x SO(2) */
  int applied_force;     /* a Python applied force on a C model       */
  int pyflags;           /* LGNPY_HAS_* of a Python model             */
  int nroots;
  void *handle;          /* the Python side of the callbacks          */
  /* the last error and the warnings reported by Lignum's handlers */
  int err_code;
  char err_function[128];
  char err_msg[LGNPY_MSG_LEN];
  int nwarnings;
  char warnings[4 * LGNPY_MSG_LEN];
} LGNPySystem;

LGNPySystem *LGNPy_Create(void *handle);
void LGNPy_Free(LGNPySystem *sys);
void LGNPy_ClearError(LGNPySystem *sys);

int LGNPy_AddGroupFactor(LGNPySystem *sys, int kind, int64_t n);
int LGNPy_MultibodyInit(LGNPySystem *sys, int nbodies, int group);
int LGNPy_PythonModelInit(LGNPySystem *sys, int64_t m, int pyflags);
int LGNPy_SetAppliedForce(LGNPySystem *sys, int on, int has_dq, int has_dv);
int LGNPy_AddDriver(LGNPySystem *sys, int rotation, int a, const double *s_a,
                    const double *axis_a, const double *ref_a, int b,
                    const double *s_b, const double *ref_b, int kind,
                    const double *c);

int LGNPy_Attach(LGNPySystem *sys, double t0, double *q0, double *v0,
                 double *vdot, double *lambda, int mass_constant);
int LGNPy_RootInit(LGNPySystem *sys, int nroots);
int LGNPy_Energy(LGNPySystem *sys, double *q, double *v, double *kinetic,
                 double *potential);
int LGNPy_Residual(LGNPySystem *sys, double t, double *q, double *phi);



/* The Python functions behind the callbacks (extern "Python+C" in the cffi
 * definitions, lignum/_build.py): `which` is one of LGNPY_CB_*, arrays are
 * Lignum's own vectors and column-major dense matrices, valid during the
 * call only. They return 0, or -1 when the Python function raised. */
int lgnpy_vec_cb(void *handle, int which, double t, double *q, double *v,
                 double *out);
int lgnpy_mat_cb(void *handle, int which, double t, double *q, double *v,
                 double *vdot, double *lambda, double *mat);
int lgnpy_drive_cb(void *handle, int index, double t, double *f);
#endif
