"""cffi build script of the extension ``lignum._lignum`` (API mode).

The extension is compiled by the C compiler against Lignum's real headers
(so every declaration below is checked against them) and links the Lignum
library found by :func:`find_lignum`:

1. ``LIGNUM_BUILD_DIR``: a CMake build tree of Lignum (``cmake -B build``);
2. ``LIGNUM_PREFIX``: an installed Lignum (``cmake --install``);
3. otherwise the ``build/`` tree of the repository this package sits in,
   then ``/usr/local`` and ``/usr``.
"""
import os
import pathlib
import re

from cffi import FFI

HERE = pathlib.Path(__file__).resolve().parent


def _from_build_tree(build):
    cache = build / "CMakeCache.txt"
    if not cache.is_file():
        return None
    text = cache.read_text(errors="replace")
    src = re.search(r"^Lignum_SOURCE_DIR:STATIC=(.*)$", text, re.M)
    if not src:
        return None
    libdir = build / "src"
    if not any(libdir.glob("liblignum.so*")):
        raise RuntimeError(f"{build} has no liblignum.so: build it first "
                           f"(cmake --build {build} --target lignum)")
    return ([str(pathlib.Path(src.group(1)) / "include"), str(build / "include")],
            str(libdir))


def _from_prefix(prefix):
    for lib in ("lib", "lib64", "lib/x86_64-linux-gnu"):
        libdir = prefix / lib
        if any(libdir.glob("liblignum.so*")) and (prefix / "include/lignum/lignum.h").is_file():
            return [str(prefix / "include")], str(libdir)
    return None


def find_lignum():
    """Return (include_dirs, library_dir) of the Lignum to build against."""
    if os.environ.get("LIGNUM_BUILD_DIR"):
        found = _from_build_tree(pathlib.Path(os.environ["LIGNUM_BUILD_DIR"]).resolve())
        if not found:
            raise RuntimeError("LIGNUM_BUILD_DIR is not a CMake build tree of Lignum")
        return found
    if os.environ.get("LIGNUM_PREFIX"):
        found = _from_prefix(pathlib.Path(os.environ["LIGNUM_PREFIX"]).resolve())
        if not found:
            raise RuntimeError("LIGNUM_PREFIX holds no installed Lignum "
                               "(include/lignum/lignum.h, lib/liblignum.so)")
        return found
    candidates = [HERE.parent.parent / "build"]
    for build in candidates:
        found = _from_build_tree(build)
        if found:
            return found
    for prefix in ("/usr/local", "/usr"):
        found = _from_prefix(pathlib.Path(prefix))
        if found:
            return found
    raise RuntimeError("Lignum not found: build it (cmake -S . -B build && cmake --build "
                       "build) or set LIGNUM_BUILD_DIR or LIGNUM_PREFIX")


CDEF = r"""
typedef double sunrealtype;
typedef int64_t sunindextype;
typedef int sunbooleantype;
typedef struct _generic_N_Vector *N_Vector;
typedef struct LGNBodiesRec *LGNBodies;
typedef struct LGNJointsRec *LGNJoints;

#define LGN_GROUND ...
#define LGN_NORMAL ...
#define LGN_ONE_STEP ...
#define LGN_STEP_FIXED ...
#define LGN_STEP_ADAPTIVE ...
#define LGN_CONSTR_INDEX3 ...
#define LGN_CONSTR_INDEX2 ...
#define LGN_CONSTR_GGL ...
#define LGN_KINEMATICS_SIMPLIFIED ...
#define LGN_KINEMATICS_EXACT ...
#define LGN_KINEMATICS_SIGMA ...
#define LGN_IC_PROJECT_Q ...
#define LGN_IC_PROJECT_V ...
#define LGN_IC_PROJECT_QV ...
#define LGN_NEWTON_FULL ...
#define LGN_NEWTON_MODIFIED ...
#define LGN_PROJECT_NONE ...
#define LGN_PROJECT_INTERPOLATED ...
#define LGN_PROJECT_ALL ...
#define LGN_TSTOP_RETURN ...
#define LGN_ROOT_RETURN ...
#define LGN_ILL_INPUT ...
#define LGNPY_CB_FORCE ...
#define LGNPY_CB_APPLIED ...
#define LGNPY_CB_CONSTR ...
#define LGNPY_CB_CURVATURE ...
#define LGNPY_CB_CONSTR_TIME ...
#define LGNPY_CB_ROOT ...
#define LGNPY_CB_MASS ...
#define LGNPY_CB_JAC ...
#define LGNPY_CB_STIFFNESS ...
#define LGNPY_CB_DAMPING ...
#define LGNPY_CB_APPLIED_DQ ...
#define LGNPY_CB_APPLIED_DV ...
#define LGNPY_HAS_STIFFNESS ...
#define LGNPY_HAS_DAMPING ...
#define LGNPY_HAS_CURVATURE ...
#define LGNPY_HAS_CONSTR_TIME ...
#define LGNPY_DRIVE_POLYNOMIAL ...
#define LGNPY_DRIVE_HARMONIC ...
#define LGNPY_DRIVE_PYTHON ...
#define LGNPY_GROUP_R3XSO3 ...
#define LGNPY_GROUP_SE2 ...
#define LGNPY_GROUP_R2XSO2 ...

typedef struct LGNPySystemRec {
  LGNBodies bodies;
  LGNJoints joints;
  void *mem;
  N_Vector q, v;
  N_Vector vdot, lambda;
  sunindextype nq, nv, m;
  int nroots;
  int err_code;
  char err_function[128];
  char err_msg[...];
  int nwarnings;
  char warnings[...];
  ...;
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

extern "Python+C" int lgnpy_vec_cb(void *handle, int which, double t, double *q,
                                   double *v, double *out);
extern "Python+C" int lgnpy_mat_cb(void *handle, int which, double t, double *q,
                                   double *v, double *vdot, double *lambda, double *mat);
extern "Python+C" int lgnpy_drive_cb(void *handle, int index, double t, double *f);

/* lignum_bodies.h, lignum_joints.h */
int LGNBodies_SetMass(LGNBodies B, int k, sunrealtype m, const sunrealtype inertia[9]);
int LGNBodies_SetPrincipalInertia(LGNBodies B, int k, sunrealtype m, const sunrealtype J[3]);
int LGNBodies_SetGravity(LGNBodies B, const sunrealtype gravity[3]);
int LGNBodies_AddSpringDamper(LGNBodies B, int a, const sunrealtype sa[3], int b,
                              const sunrealtype sb[3], sunrealtype k, sunrealtype c,
                              sunrealtype L0);
int LGNBodies_AddRotationalSpringDamper(LGNBodies B, int a, int b, sunrealtype kr,
                                        sunrealtype cr, const sunrealtype rest[4]);
int LGNJoints_AddSpherical(LGNJoints J, int a, const sunrealtype sa[3], int b,
                           const sunrealtype sb[3]);
int LGNJoints_AddRevolute(LGNJoints J, int a, const sunrealtype sa[3],
                          const sunrealtype axis_a[3], int b, const sunrealtype sb[3],
                          const sunrealtype axis_b[3]);
int LGNJoints_AddUniversal(LGNJoints J, int a, const sunrealtype sa[3],
                           const sunrealtype axis_a[3], int b, const sunrealtype sb[3],
                           const sunrealtype axis_b[3]);
int LGNJoints_AddPrismatic(LGNJoints J, int a, const sunrealtype sa[3],
                           const sunrealtype axis_a[3], int b, const sunrealtype sb[3],
                           const sunrealtype axis_b[3]);
int LGNJoints_AddCylindrical(LGNJoints J, int a, const sunrealtype sa[3],
                             const sunrealtype axis_a[3], int b, const sunrealtype sb[3],
                             const sunrealtype axis_b[3]);
sunindextype LGNJoints_NumConstraints(LGNJoints J);

/* lignum_planar.h */
int LGNBodies_SetPlanarMass(LGNBodies B, int k, sunrealtype m, sunrealtype J);
int LGNBodies_AddPlanarSpringDamper(LGNBodies B, int a, const sunrealtype sa[2], int b,
                                    const sunrealtype sb[2], sunrealtype k, sunrealtype c,
                                    sunrealtype L0);
int LGNBodies_AddPlanarRotationalSpringDamper(LGNBodies B, int a, int b, sunrealtype kr,
                                              sunrealtype cr, sunrealtype theta0);
int LGNJoints_AddPlanarRevolute(LGNJoints J, int a, const sunrealtype sa[2], int b,
                                const sunrealtype sb[2]);
int LGNJoints_AddPlanarPrismatic(LGNJoints J, int a, const sunrealtype sa[2],
                                 const sunrealtype axis_a[2], int b, const sunrealtype sb[2],
                                 sunrealtype theta0);
int LGNJoints_DescribeConstraint(LGNJoints J, sunindextype row, char *buf, size_t len);

/* lignum.h: settings, solve, outputs */
int LGNSolve(void *lgn_mem, sunrealtype tout, sunrealtype *tret, N_Vector qret,
             N_Vector vret, int itask);
int LGNSetStepSize(void *lgn_mem, sunrealtype h);
int LGNSetNewmark(void *lgn_mem, sunrealtype beta, sunrealtype gamma);
int LGNSetGenAlpha(void *lgn_mem, sunrealtype rho_inf);
int LGNSetGenAlphaParams(void *lgn_mem, sunrealtype alpha_m, sunrealtype alpha_f,
                         sunrealtype beta, sunrealtype gamma);
int LGNSetBDF(void *lgn_mem, int maxord);
int LGNSetConstraintIndex(void *lgn_mem, int index);
int LGNSetKinematics(void *lgn_mem, int kinematics);
int LGNSStolerances(void *lgn_mem, sunrealtype rtol, sunrealtype atol);
int LGNSetMaxNewtonIters(void *lgn_mem, int maxiters);
int LGNSetNewtonMode(void *lgn_mem, int mode);
int LGNSetMaxNumSteps(void *lgn_mem, long int mxsteps);
int LGNSetStepControl(void *lgn_mem, int control);
int LGNSetInitStep(void *lgn_mem, sunrealtype h0);
int LGNSetMinStep(void *lgn_mem, sunrealtype hmin);
int LGNSetMaxStep(void *lgn_mem, sunrealtype hmax);
int LGNSetStopTime(void *lgn_mem, sunrealtype tstop);
int LGNClearStopTime(void *lgn_mem);
int LGNSetProjectOutputs(void *lgn_mem, int which);
int LGNSetRootDirection(void *lgn_mem, int *rootdir);
int LGNSetNoInactiveRootWarn(void *lgn_mem);
int LGNGetRootInfo(void *lgn_mem, int *rootsfound);
int LGNCalcIC(void *lgn_mem, int icopt);
int LGNGetConsistentIC(void *lgn_mem, N_Vector q0, N_Vector v0);
int LGNGetAcceleration(void *lgn_mem, N_Vector vdot);
int LGNGetMultipliers(void *lgn_mem, N_Vector lambda);
int LGNGetCurrentTime(void *lgn_mem, sunrealtype *tcur);
int LGNGetLastStep(void *lgn_mem, sunrealtype *hlast);
int LGNGetCurrentStep(void *lgn_mem, sunrealtype *hcur);
int LGNGetLastOrder(void *lgn_mem, int *order);
int LGNGetNumSteps(void *lgn_mem, long int *nsteps);
int LGNGetNumNewtonIters(void *lgn_mem, long int *nniters);
int LGNGetNumNewtonConvFails(void *lgn_mem, long int *nncfails);
int LGNGetNumStepFails(void *lgn_mem, long int *nfails);
int LGNGetNumErrTestFails(void *lgn_mem, long int *netfails);
int LGNGetNumResEvals(void *lgn_mem, long int *nres);
int LGNGetNumJacEvals(void *lgn_mem, long int *njevals);
int LGNGetNumGEvals(void *lgn_mem, long int *ngevals);
int LGNGetNumOutputSolves(void *lgn_mem, long int *nout);
const char *LGNGetReturnFlagName(long int flag);
"""

ffibuilder = FFI()
ffibuilder.cdef(CDEF)

_include_dirs, _libdir = find_lignum()
ffibuilder.set_source(
    "lignum._lignum",
    '#include "_glue.h"\n#include <lignum/lignum_planar.h>\n',
    sources=["lignum/_glue.c"],  # relative to setup.py, as setuptools wants
    include_dirs=["lignum"] + _include_dirs,
    library_dirs=[_libdir],
    runtime_library_dirs=[_libdir],
    libraries=["lignum", "sundials_nvecserial", "sundials_sunmatrixdense", "m"],
    extra_compile_args=["-std=c11", "-O2"],
)

if __name__ == "__main__":
    ffibuilder.compile(verbose=True)
