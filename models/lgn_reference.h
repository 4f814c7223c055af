/*
 * lgn_reference.h -- independent high-accuracy reference solutions for the
 * Lignum tests (internal test library, prefix lgnref_).
 *
 * Method.  The heavy top of doc/accuracy-study.md is the unconstrained ODE
 *
 *     Rdot = R Omega~ ,   J_O Omegadot + Omega x J_O Omega = X x (R^T m gamma_g),
 *
 * integrated with SUNDIALS ARKODE ERKStep (explicit embedded Runge-Kutta,
 * adaptive steps), i.e. by a method that shares nothing with Lignum's
 * implicit Newmark / generalized-alpha steppers (no Lie group update, no
 * constraint, no Newton iteration).  Every output time is hit exactly with
 * ERKStepSetStopTime (no dense-output interpolation).  Two independent
 * Butcher tables are available for cross-checking:
 *     table 0: ARKODE_VERNER_8_5_6    (8 stages, order 6, embedding 5)
 *     table 1: ARKODE_FEHLBERG_13_7_8 (13 stages, order 8, embedding 7)
 * Note: ARKODE names are NAME_stages_embedding_order, so Verner 8_5_6 is a
 * 6th-order table; only Fehlberg 13_7_8 is 8th order.
 *
 * Two formulations of the same ODE (LGNRefOptions.formulation):
 *   LGNREF_SPIN_SEPARATED (default).  J_O = diag(a, b, a) and the torque is
 *     orthogonal to X = e_y, so Omega_y = w_s = 150 is exactly constant.  With
 *     R = S E(t), E(t) = exp(w_s t e_y~) (analytic) and w = E(Omega - w_s e_y):
 *         Sdot = S w~ ,   wdot = (b/a) w_s e_y x w + (e_y x S^T m gamma_g)/a.
 *     S and w only vary on the slow precession/nutation scales (~5 rad/s), so
 *     ~550 steps suffice on [0, 2] s (Fehlberg) and roundoff stays ~1e-13.
 *   LGNREF_DIRECT.  The (R, Omega) ODE above as written; it resolves the
 *     150 rad/s spin, needs ~1e4 (Fehlberg) to ~4e5 (Verner) steps on
 *     [0, 2] s and is roundoff-limited at ~1e-10 in Omega (Fehlberg).  Kept
 *     as the literal form of the published model and as a cross-check of the
 *     transformation (test_reference asserts the two agree).
 * Default tolerances rtol = atol: 1e-13 for Fehlberg, 1e-15 for Verner (the
 * 6th-order table needs the tighter tolerance to reach ~1e-11).
 *
 * Derived quantities at every output time (from the re-orthonormalised R):
 *     x        = R X                                  centre of mass (inertial)
 *     u        = R (Omega x X)                        its velocity
 *     Omegadot = J_O^{-1}(X x (R^T m gamma_g) - Omega x J_O Omega)
 *     lambda   = m(Omega x (Omega x X) + Omegadot x X) - m R^T gamma_g
 *                multiplier of Phi = X - R^T x (the published heavy top).  For the
 *                OpenTurbine/Kynema convention Phi_OT = R X - x use R lambda.
 *     p        = unit quaternion (w,x,y,z), scalar first, w >= 0 (Shepperd).
 *
 * MEASURED ACCURACY (SUNDIALS 6.4.1, gcc 12, x86-64; max-abs norms;
 * test/reference/test_reference.c asserts these with margin):
 *   - Fehlberg, spin-separated, rtol = atol = 1e-13 (the best reference):
 *     differs from itself at tolerances 1e-11 ... 1e-15 by <= 1e-13 in x and
 *     R, <= 7e-13 in Omega, <= 6e-11 in lambda on [0, 2] s.
 *   - Verner vs Fehlberg (both spin-separated, defaults):
 *       t = 1 s: |dx| 6.8e-12, |dOmega| 4.3e-11, |dlambda| 8.5e-9, rot 1.2e-11
 *       t = 2 s: |dx| 3.3e-11, |dOmega| 4.7e-11, |dlambda| 3.2e-9, rot 5.3e-11
 *     (|Omega| ~ 150, |lambda| ~ 650: relative 3e-13 and 1e-11).
 *   - Direct vs spin-separated (Fehlberg 1e-13): |dx| <= 6e-13,
 *     |dOmega| <= 1.6e-10, |dlambda| <= 1.1e-8 on [0, 2] s.
 *   - Torque-free symmetric top (analytic solution, |Omega| = 150),
 *     direct formulation on [0, 2] s: Fehlberg 1e-13 rotation error 5.5e-11,
 *     |dOmega| 1.1e-10; Verner 1e-15 (4e5 steps) 6.6e-10, 2.0e-9.
 *   - Invariants on [0, 2] s (relative drift of energy / of (R J_O Omega)_z;
 *     max |R^T R - I| of the raw integrated R):
 *       Fehlberg spin-separated  3e-16 / 2.4e-15 / 3e-15
 *       Fehlberg direct          8.5e-15 / 2.2e-14 / 1.7e-13
 *       Verner spin-separated    3.1e-12 / 1.0e-11 / 8.6e-11
 *     Omega_y = 150 exactly in all runs.
 *   => Default reference: Fehlberg (table 1) is good to ~1e-13 in x, R,
 *      ~1e-12 in Omega and ~1e-10 absolute in lambda/Omegadot on [0, 2] s;
 *      Verner (table 0) to ~5e-11 in x, R, Omega and ~1e-8 absolute (~1e-11
 *      relative) in lambda.  Prefer table 1 as THE reference, table 0 as the
 *      cross-check.
 *   Cost: [0, 1] s with 1001 output times: ~6 ms (Fehlberg), ~24 ms
 *   (Verner) at -O2.
 */
#ifndef LGN_REFERENCE_H
#define LGN_REFERENCE_H

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------------------
 * Heavy top (the published heavy top): m = 15, J = diag(0.234375, 0.46875, 0.234375) about the
 * centre of mass, X = (0,1,0), gamma_g = (0,0,-9.81), R0 = I,
 * Omega0 = (0, 150, -4.61538).
 * ------------------------------------------------------------------------- */
#define LGNREF_HT_MASS 15.0
#define LGNREF_HT_GRAVITY_Z (-9.81)
#define LGNREF_HT_OMEGA0_Y 150.0
#define LGNREF_HT_OMEGA0_Z (-4.61538)

typedef struct {
    double t;
    double x[3];        /* centre of mass, inertial                         */
    double u[3];        /* centre-of-mass velocity, inertial                */
    double R[9];        /* rotation body -> inertial, row-major             */
    double p[4];        /* quaternion (w,x,y,z), w >= 0                     */
    double Omega[3];    /* body angular velocity                            */
    double Omegadot[3]; /* body angular acceleration                        */
    double lambda[3];   /* multiplier of Phi = X - R^T x                    */
} LGNRefHeavyTop;

enum { LGNREF_VERNER_6 = 0, LGNREF_FEHLBERG_8 = 1 };
enum { LGNREF_SPIN_SEPARATED = 0, LGNREF_DIRECT = 1 };

#define LGNREF_DEFAULT_TOL_VERNER 1e-15
#define LGNREF_DEFAULT_TOL_FEHLBERG 1e-13

/* Solver options; pass NULL for the defaults.  A zero-initialised struct
 * also means defaults (table 0, spin-separated, default tolerances,
 * adaptive steps). */
typedef struct {
    int table;       /* 0 = Verner 8(5)6, 1 = Fehlberg 13(7)8                */
    double rtol;     /* <= 0: default for the table                          */
    double atol;     /* <= 0: default for the table                          */
    double hfixed;   /* > 0: fixed step size (no error control); 0: adaptive */
    int formulation; /* heavy top only: LGNREF_SPIN_SEPARATED/LGNREF_DIRECT  */
} LGNRefOptions;

/* Optional run statistics. */
typedef struct {
    long nsteps;          /* accepted steps                                   */
    long nfevals;         /* right-hand-side evaluations                      */
    double max_orth_err;  /* max over outputs of max|R^T R - I| of the raw
                             integrated R (before re-orthonormalisation)      */
} LGNRefStats;

/* Heavy top at the given output times (non-decreasing, times[0] >= 0; the
 * integration starts at t = 0).  out must hold ntimes entries.
 * table: 0 = Verner 8(5)6, 1 = Fehlberg 13(7)8; spin-separated formulation,
 * default tolerances.  Returns 0 on success,
 * nonzero on bad arguments or a solver failure (message on stderr). */
int lgnref_heavy_top(const double *times, int ntimes, LGNRefHeavyTop *out,
                     int table);

/* Same with explicit options and statistics (either may be NULL). */
int lgnref_heavy_top_ex(const double *times, int ntimes, LGNRefHeavyTop *out,
                        const LGNRefOptions *opt, LGNRefStats *stats);

/* Uniform grid t_k = t_end * k / nsteps, k = 0..nsteps (so t_nsteps == t_end
 * exactly); out must hold nsteps + 1 entries. */
int lgnref_heavy_top_uniform(double t_end, int nsteps, LGNRefHeavyTop *out,
                             int table);

/* Fill all derived fields of *s (x, u, p, Omegadot, lambda) from a rotation
 * R (re-orthonormalised first; the cleaned R is stored in s->R) and Omega. */
void lgnref_heavy_top_from_state(double t, const double R[9],
                                 const double Omega[3], LGNRefHeavyTop *s);

/* Centre-of-mass acceleration udot = R(Omega x (Omega x X) + Omegadot x X). */
void lgnref_heavy_top_udot(const LGNRefHeavyTop *s, double udot[3]);

/* Invariants: total energy 1/2 Omega.J_O Omega - m gamma_g.x, and the
 * inertial angular momentum about the fixed point, pi = R J_O Omega (its
 * z component is conserved). */
double lgnref_heavy_top_energy(const LGNRefHeavyTop *s);
void lgnref_heavy_top_momentum(const LGNRefHeavyTop *s, double pi[3]);

/* ---------------------------------------------------------------------------
 * General rigid body about a fixed point (used for the heavy top and for the
 * torque-free top): principal inertia Jdiag about the fixed
 * point, constant inertial force f acting at body point X (f = 0: free).
 * R_out (9*ntimes, row-major, raw integrated R) and Omega_out (3*ntimes)
 * may be NULL.
 * ------------------------------------------------------------------------- */
typedef struct {
    double Jdiag[3];
    double X[3];
    double f[3];
} LGNRefRigidBody;

int lgnref_rigid_body(const LGNRefRigidBody *body, const double R0[9],
                      const double Omega0[3], const double *times, int ntimes,
                      double *R_out, double *Omega_out,
                      const LGNRefOptions *opt, LGNRefStats *stats);

/* ---------------------------------------------------------------------------
 * SO(3) helpers (row-major 3x3).
 * ------------------------------------------------------------------------- */

/* ||log(R_ref^T R)||, the rotation angle in [0, pi] between the two. */
double lgnref_rotation_error(const double R_ref[9], const double R[9]);

/* Rodrigues: R = exp(w~). */
void lgnref_expso3(const double w[3], double R[9]);

/* Orthonormalise (polar factor, Newton-Schulz iterations) in place;
 * returns max|R^T R - I| of the input. */
double lgnref_orthonormalise(double R[9]);

/* Unit quaternion (w,x,y,z), w >= 0, from a rotation matrix (Shepperd). */
void lgnref_quat_from_R(const double R[9], double p[4]);

/* Method and embedding order of a table (0 or 1); returns 0 on success. */
int lgnref_table_order(int table, int *q, int *p);

#ifdef __cplusplus
}
#endif

#endif /* LGN_REFERENCE_H */
