/*
 * lgn_reference.c -- see lgn_reference.h for the method and its measured
 * accuracy.
 */
#include "lgn_reference.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <arkode/arkode_erkstep.h>
#include <arkode/arkode_butcher_erk.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

/* ------------------------------------------------------------------ helpers */

static void cross3(const double a[3], const double b[3], double c[3])
{
    double c0 = a[1] * b[2] - a[2] * b[1];
    double c1 = a[2] * b[0] - a[0] * b[2];
    double c2 = a[0] * b[1] - a[1] * b[0];
    c[0] = c0;
    c[1] = c1;
    c[2] = c2;
}

static void matvec(const double R[9], const double v[3], double w[3])
{
    for (int i = 0; i < 3; ++i)
        w[i] = R[3 * i] * v[0] + R[3 * i + 1] * v[1] + R[3 * i + 2] * v[2];
}

static void matTvec(const double R[9], const double v[3], double w[3])
{
    for (int j = 0; j < 3; ++j)
        w[j] = R[j] * v[0] + R[3 + j] * v[1] + R[6 + j] * v[2];
}

static double orth_err(const double R[9])
{
    double e = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double s = R[i] * R[j] + R[3 + i] * R[3 + j] + R[6 + i] * R[6 + j];
            double d = fabs(s - (i == j ? 1.0 : 0.0));
            if (d > e)
                e = d;
        }
    return e;
}

double lgnref_orthonormalise(double R[9])
{
    double e0 = orth_err(R);
    /* Newton-Schulz for the polar factor: R <- R (3I - R^T R)/2; quadratic
     * convergence, R is within ~1e-12 of SO(3) here. */
    for (int it = 0; it < 6; ++it) {
        double S[9], Rn[9];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                double s = R[i] * R[j] + R[3 + i] * R[3 + j] + R[6 + i] * R[6 + j];
                S[3 * i + j] = 0.5 * ((i == j ? 3.0 : 0.0) - s);
            }
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                Rn[3 * i + j] = R[3 * i] * S[j] + R[3 * i + 1] * S[3 + j] +
                                R[3 * i + 2] * S[6 + j];
        for (int k = 0; k < 9; ++k)
            R[k] = Rn[k];
        if (orth_err(R) < 4e-16)
            break;
    }
    return e0;
}

void lgnref_quat_from_R(const double R[9], double p[4])
{
    double r00 = R[0], r01 = R[1], r02 = R[2];
    double r10 = R[3], r11 = R[4], r12 = R[5];
    double r20 = R[6], r21 = R[7], r22 = R[8];
    double tr = r00 + r11 + r22;
    double w, x, y, z;
    if (tr >= r00 && tr >= r11 && tr >= r22) {
        w = 0.5 * sqrt(1.0 + tr);
        double f = 0.25 / w;
        x = (r21 - r12) * f;
        y = (r02 - r20) * f;
        z = (r10 - r01) * f;
    } else if (r00 >= r11 && r00 >= r22) {
        x = 0.5 * sqrt(1.0 + r00 - r11 - r22);
        double f = 0.25 / x;
        w = (r21 - r12) * f;
        y = (r01 + r10) * f;
        z = (r02 + r20) * f;
    } else if (r11 >= r22) {
        y = 0.5 * sqrt(1.0 - r00 + r11 - r22);
        double f = 0.25 / y;
        w = (r02 - r20) * f;
        x = (r01 + r10) * f;
        z = (r12 + r21) * f;
    } else {
        z = 0.5 * sqrt(1.0 - r00 - r11 + r22);
        double f = 0.25 / z;
        w = (r10 - r01) * f;
        x = (r02 + r20) * f;
        y = (r12 + r21) * f;
    }
    double n = sqrt(w * w + x * x + y * y + z * z);
    if (w < 0.0)
        n = -n;
    p[0] = w / n;
    p[1] = x / n;
    p[2] = y / n;
    p[3] = z / n;
}

void lgnref_expso3(const double w[3], double R[9])
{
    double th2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    double th = sqrt(th2);
    double a, b;
    if (th < 1e-4) {
        a = 1.0 - th2 / 6.0 * (1.0 - th2 / 20.0);
        b = 0.5 * (1.0 - th2 / 12.0 * (1.0 - th2 / 30.0));
    } else {
        a = sin(th) / th;
        b = (1.0 - cos(th)) / th2;
    }
    double W[9] = {0.0, -w[2], w[1], w[2], 0.0, -w[0], -w[1], w[0], 0.0};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double W2 = W[3 * i] * W[j] + W[3 * i + 1] * W[3 + j] +
                        W[3 * i + 2] * W[6 + j];
            R[3 * i + j] = (i == j ? 1.0 : 0.0) + a * W[3 * i + j] + b * W2;
        }
}

double lgnref_rotation_error(const double R_ref[9], const double R[9])
{
    /* A = R_ref^T R; angle = atan2(|vee(A - A^T)|/2, (tr A - 1)/2), accurate
     * for small and large angles alike. */
    double A[9];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            A[3 * i + j] = R_ref[i] * R[j] + R_ref[3 + i] * R[3 + j] +
                           R_ref[6 + i] * R[6 + j];
    double v0 = 0.5 * (A[7] - A[5]);
    double v1 = 0.5 * (A[2] - A[6]);
    double v2 = 0.5 * (A[3] - A[1]);
    double s = sqrt(v0 * v0 + v1 * v1 + v2 * v2);
    double c = 0.5 * (A[0] + A[4] + A[8] - 1.0);
    return atan2(s, c);
}

static ARKODE_ERKTableID table_id(int table)
{
    return table == 1 ? ARKODE_FEHLBERG_13_7_8 : ARKODE_VERNER_8_5_6;
}

int lgnref_table_order(int table, int *q, int *p)
{
    if (table != 0 && table != 1)
        return 1;
    ARKodeButcherTable B = ARKodeButcherTable_LoadERK(table_id(table));
    if (!B)
        return 1;
    if (q)
        *q = B->q;
    if (p)
        *p = B->p;
    ARKodeButcherTable_Free(B);
    return 0;
}

/* ---------------------------------------------------------- rigid body ODE */

static int rb_rhs(realtype t, N_Vector yv, N_Vector ydotv, void *user_data)
{
    (void)t;
    const LGNRefRigidBody *b = (const LGNRefRigidBody *)user_data;
    const double *y = N_VGetArrayPointer(yv);
    double *yd = N_VGetArrayPointer(ydotv);
    const double *R = y;
    const double *Om = y + 9;
    /* Rdot = R Omega~ : row i of Rdot = (row i of R) x Omega */
    for (int i = 0; i < 3; ++i)
        cross3(R + 3 * i, Om, yd + 3 * i);
    double JOm[3] = {b->Jdiag[0] * Om[0], b->Jdiag[1] * Om[1],
                     b->Jdiag[2] * Om[2]};
    double gyro[3], fb[3], tq[3];
    cross3(Om, JOm, gyro);
    matTvec(R, b->f, fb);
    cross3(b->X, fb, tq);
    for (int k = 0; k < 3; ++k)
        yd[9 + k] = (tq[k] - gyro[k]) / b->Jdiag[k];
    return 0;
}

static LGNRefOptions resolve_options(const LGNRefOptions *opt)
{
    LGNRefOptions o = {0, 0.0, 0.0, 0.0, 0};
    if (opt)
        o = *opt;
    double def = o.table == 1 ? LGNREF_DEFAULT_TOL_FEHLBERG
                              : LGNREF_DEFAULT_TOL_VERNER;
    if (!(o.rtol > 0.0))
        o.rtol = def;
    if (!(o.atol > 0.0))
        o.atol = def;
    return o;
}

/* Integrate y' = rhs(t, y), y in R^12 (9 entries of a rotation matrix first),
 * y(0) = y0, and store y at every output time into Y (12*ntimes). */
static int integrate12(ARKRhsFn rhs, void *udata, const double y0[12],
                       const double *times, int ntimes, double *Y,
                       const LGNRefOptions *opt, LGNRefStats *stats)
{
    LGNRefOptions o = resolve_options(opt);
    if (!times || ntimes < 1 || (o.table != 0 && o.table != 1)) {
        fprintf(stderr, "lgnref: bad arguments\n");
        return 1;
    }
    for (int k = 0; k < ntimes; ++k)
        if (!(times[k] >= 0.0) || (k > 0 && times[k] < times[k - 1])) {
            fprintf(stderr, "lgnref: times must be >= 0 and "
                            "non-decreasing\n");
            return 1;
        }
    if (stats) {
        stats->nsteps = 0;
        stats->nfevals = 0;
        stats->max_orth_err = 0.0;
    }

    SUNContext ctx = NULL;
    N_Vector y = NULL;
    void *mem = NULL;
    int ret = 1;

    if (SUNContext_Create(NULL, &ctx) != 0) {
        fprintf(stderr, "lgnref: SUNContext_Create failed\n");
        return 1;
    }
    y = N_VNew_Serial(12, ctx);
    if (!y)
        goto done;
    double *yd = N_VGetArrayPointer(y);
    for (int k = 0; k < 12; ++k)
        yd[k] = y0[k];

    mem = ERKStepCreate(rhs, 0.0, y, ctx);
    if (!mem)
        goto done;
    if (ERKStepSetTableNum(mem, table_id(o.table)) != 0 ||
        ERKStepSStolerances(mem, o.rtol, o.atol) != 0 ||
        ERKStepSetUserData(mem, udata) != 0 ||
        ERKStepSetMaxNumSteps(mem, 100000000L) != 0 ||
        (o.hfixed > 0.0 && ERKStepSetFixedStep(mem, o.hfixed) != 0)) {
        fprintf(stderr, "lgnref: ERKStep setup failed\n");
        goto done;
    }

    double tcur = 0.0;
    for (int k = 0; k < ntimes; ++k) {
        double tout = times[k];
        if (tout > tcur) {
            double tret = tcur;
            if (ERKStepSetStopTime(mem, tout) != 0) {
                fprintf(stderr, "lgnref: SetStopTime failed\n");
                goto done;
            }
            int flag = ERKStepEvolve(mem, tout, y, &tret, ARK_NORMAL);
            if (flag < 0) {
                fprintf(stderr, "lgnref: ERKStepEvolve failed "
                                "(flag %d) at t = %.17g\n", flag, tret);
                goto done;
            }
            if (tret != tout) {
                fprintf(stderr, "lgnref: output time missed "
                                "(%.17g != %.17g)\n", tret, tout);
                goto done;
            }
            tcur = tout;
        }
        yd = N_VGetArrayPointer(y);
        if (stats) {
            double e = orth_err(yd);
            if (e > stats->max_orth_err)
                stats->max_orth_err = e;
        }
        for (int j = 0; j < 12; ++j)
            Y[12 * k + j] = yd[j];
    }
    if (stats) {
        long n = 0;
        ERKStepGetNumSteps(mem, &n);
        stats->nsteps = n;
        ERKStepGetNumRhsEvals(mem, &n);
        stats->nfevals = n;
    }
    ret = 0;

done:
    if (ret != 0 && !mem)
        fprintf(stderr, "lgnref: allocation failed\n");
    if (mem)
        ERKStepFree(&mem);
    if (y)
        N_VDestroy(y);
    SUNContext_Free(&ctx);
    return ret;
}

int lgnref_rigid_body(const LGNRefRigidBody *body, const double R0[9],
                      const double Omega0[3], const double *times, int ntimes,
                      double *R_out, double *Omega_out,
                      const LGNRefOptions *opt, LGNRefStats *stats)
{
    if (!body || !R0 || !Omega0 || !times || ntimes < 1)
        return 1;
    LGNRefRigidBody bcopy = *body;
    double y0[12];
    for (int k = 0; k < 9; ++k)
        y0[k] = R0[k];
    for (int k = 0; k < 3; ++k)
        y0[9 + k] = Omega0[k];
    double *Y = malloc(sizeof(double) * 12 * (size_t)ntimes);
    if (!Y)
        return 1;
    int ret = integrate12(rb_rhs, &bcopy, y0, times, ntimes, Y, opt, stats);
    if (ret == 0)
        for (int k = 0; k < ntimes; ++k) {
            if (R_out)
                for (int j = 0; j < 9; ++j)
                    R_out[9 * k + j] = Y[12 * k + j];
            if (Omega_out)
                for (int j = 0; j < 3; ++j)
                    Omega_out[3 * k + j] = Y[12 * k + 9 + j];
        }
    free(Y);
    return ret;
}

/* --------------------------------------------------------------- heavy top */

static const double HT_X[3] = {0.0, 1.0, 0.0};

static void ht_JO(double JO[3])
{
    /* J_O = J + m(|X|^2 I - X X^T), J = diag(0.234375, 0.46875, 0.234375) */
    const double J[3] = {0.234375, 0.46875, 0.234375};
    double X2 = HT_X[0] * HT_X[0] + HT_X[1] * HT_X[1] + HT_X[2] * HT_X[2];
    for (int k = 0; k < 3; ++k)
        JO[k] = J[k] + LGNREF_HT_MASS * (X2 - HT_X[k] * HT_X[k]);
}

void lgnref_heavy_top_from_state(double t, const double R[9],
                                 const double Omega[3], LGNRefHeavyTop *s)
{
    const double m = LGNREF_HT_MASS;
    const double g[3] = {0.0, 0.0, LGNREF_HT_GRAVITY_Z};
    double JO[3];
    ht_JO(JO);

    s->t = t;
    for (int k = 0; k < 9; ++k)
        s->R[k] = R[k];
    lgnref_orthonormalise(s->R);
    for (int k = 0; k < 3; ++k)
        s->Omega[k] = Omega[k];

    matvec(s->R, HT_X, s->x);
    double OxX[3];
    cross3(s->Omega, HT_X, OxX);
    matvec(s->R, OxX, s->u);

    double Rtg[3], mRtg[3], tq[3], JOm[3], gyro[3];
    matTvec(s->R, g, Rtg);
    for (int k = 0; k < 3; ++k)
        mRtg[k] = m * Rtg[k];
    cross3(HT_X, mRtg, tq);
    for (int k = 0; k < 3; ++k)
        JOm[k] = JO[k] * s->Omega[k];
    cross3(s->Omega, JOm, gyro);
    for (int k = 0; k < 3; ++k)
        s->Omegadot[k] = (tq[k] - gyro[k]) / JO[k];

    double OOX[3], OdX[3];
    cross3(s->Omega, OxX, OOX);
    cross3(s->Omegadot, HT_X, OdX);
    for (int k = 0; k < 3; ++k)
        s->lambda[k] = m * (OOX[k] + OdX[k]) - mRtg[k];

    lgnref_quat_from_R(s->R, s->p);
}

void lgnref_heavy_top_udot(const LGNRefHeavyTop *s, double udot[3])
{
    double OxX[3], OOX[3], OdX[3], a[3];
    cross3(s->Omega, HT_X, OxX);
    cross3(s->Omega, OxX, OOX);
    cross3(s->Omegadot, HT_X, OdX);
    for (int k = 0; k < 3; ++k)
        a[k] = OOX[k] + OdX[k];
    matvec(s->R, a, udot);
}

double lgnref_heavy_top_energy(const LGNRefHeavyTop *s)
{
    double JO[3];
    ht_JO(JO);
    double T = 0.5 * (JO[0] * s->Omega[0] * s->Omega[0] +
                      JO[1] * s->Omega[1] * s->Omega[1] +
                      JO[2] * s->Omega[2] * s->Omega[2]);
    /* V = -m gamma_g . x */
    double V = -LGNREF_HT_MASS * LGNREF_HT_GRAVITY_Z * s->x[2];
    return T + V;
}

void lgnref_heavy_top_momentum(const LGNRefHeavyTop *s, double pi[3])
{
    double JO[3];
    ht_JO(JO);
    double L[3] = {JO[0] * s->Omega[0], JO[1] * s->Omega[1],
                   JO[2] * s->Omega[2]};
    matvec(s->R, L, pi);
}

/* Spin-separated heavy top.  J_O = diag(a, b, a) and the torque
 * X x (R^T m gamma_g) with X = e_y is orthogonal to e_y, so Omega_y = w_s
 * = 150 is exactly constant.  Write R = S E(t), E(t) = exp(w_s t e_y~), and
 * w = E (Omega - w_s e_y).  Then
 *     Sdot = S w~,   wdot = (b/a) w_s e_y x w + (e_y x S^T m gamma_g)/a,
 * whose solution varies only on the slow precession/nutation time scales
 * (~5 rad/s instead of 150 rad/s): far fewer steps, far less roundoff. */
typedef struct {
    double a, c, f[3];
} SpinSep;

static int ss_rhs(realtype t, N_Vector yv, N_Vector ydotv, void *user_data)
{
    (void)t;
    const SpinSep *d = (const SpinSep *)user_data;
    const double *y = N_VGetArrayPointer(yv);
    double *yd = N_VGetArrayPointer(ydotv);
    const double *w = y + 9;
    for (int i = 0; i < 3; ++i)
        cross3(y + 3 * i, w, yd + 3 * i);
    double Stf[3], tq[3];
    const double ey[3] = {0.0, 1.0, 0.0};
    matTvec(y, d->f, Stf);
    cross3(ey, Stf, tq);
    /* e_y x w = (w_z, 0, -w_x) */
    yd[9] = d->c * w[2] + tq[0] / d->a;
    yd[10] = tq[1] / d->a;
    yd[11] = -d->c * w[0] + tq[2] / d->a;
    return 0;
}

int lgnref_heavy_top_ex(const double *times, int ntimes, LGNRefHeavyTop *out,
                        const LGNRefOptions *opt, LGNRefStats *stats)
{
    if (!times || !out || ntimes < 1)
        return 1;
    LGNRefRigidBody b;
    ht_JO(b.Jdiag);
    for (int k = 0; k < 3; ++k)
        b.X[k] = HT_X[k];
    b.f[0] = 0.0;
    b.f[1] = 0.0;
    b.f[2] = LGNREF_HT_MASS * LGNREF_HT_GRAVITY_Z;
    const double R0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    const double Om0[3] = {0.0, LGNREF_HT_OMEGA0_Y, LGNREF_HT_OMEGA0_Z};

    if (!opt || opt->formulation == LGNREF_SPIN_SEPARATED) {
        const double ws = LGNREF_HT_OMEGA0_Y;
        SpinSep d = {b.Jdiag[0], b.Jdiag[1] * ws / b.Jdiag[0],
                     {b.f[0], b.f[1], b.f[2]}};
        /* E(0) = I: S0 = R0, w0 = Omega0 - ws e_y */
        double y0[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, Om0[0], 0.0, Om0[2]};
        double *Y = malloc(sizeof(double) * 12 * (size_t)ntimes);
        if (!Y)
            return 1;
        int ret = integrate12(ss_rhs, &d, y0, times, ntimes, Y, opt, stats);
        if (ret == 0)
            for (int k = 0; k < ntimes; ++k) {
                const double *S = Y + 12 * k, *w = S + 9;
                double th = ws * times[k], cs = cos(th), sn = sin(th);
                /* E = [[c,0,s],[0,1,0],[-s,0,c]], R = S E, Omega = ws e_y + E^T w */
                double R[9], Om[3];
                for (int i = 0; i < 3; ++i) {
                    R[3 * i] = S[3 * i] * cs - S[3 * i + 2] * sn;
                    R[3 * i + 1] = S[3 * i + 1];
                    R[3 * i + 2] = S[3 * i] * sn + S[3 * i + 2] * cs;
                }
                Om[0] = cs * w[0] - sn * w[2];
                Om[1] = ws + w[1];
                Om[2] = sn * w[0] + cs * w[2];
                lgnref_heavy_top_from_state(times[k], R, Om, out + k);
            }
        free(Y);
        return ret;
    }

    double *Rs = malloc(sizeof(double) * 9 * (size_t)ntimes);
    double *Os = malloc(sizeof(double) * 3 * (size_t)ntimes);
    int ret = 1;
    if (Rs && Os) {
        ret = lgnref_rigid_body(&b, R0, Om0, times, ntimes, Rs, Os, opt, stats);
        if (ret == 0)
            for (int k = 0; k < ntimes; ++k)
                lgnref_heavy_top_from_state(times[k], Rs + 9 * k, Os + 3 * k,
                                            out + k);
    }
    free(Rs);
    free(Os);
    return ret;
}

int lgnref_heavy_top(const double *times, int ntimes, LGNRefHeavyTop *out,
                     int table)
{
    LGNRefOptions o = {table, 0.0, 0.0, 0.0, LGNREF_SPIN_SEPARATED};
    return lgnref_heavy_top_ex(times, ntimes, out, &o, NULL);
}

int lgnref_heavy_top_uniform(double t_end, int nsteps, LGNRefHeavyTop *out,
                             int table)
{
    if (nsteps < 1 || !(t_end > 0.0) || !out)
        return 1;
    double *ts = malloc(sizeof(double) * (size_t)(nsteps + 1));
    if (!ts)
        return 1;
    for (int k = 0; k <= nsteps; ++k)
        ts[k] = t_end * (double)k / (double)nsteps;
    ts[nsteps] = t_end;
    int ret = lgnref_heavy_top(ts, nsteps + 1, out, table);
    free(ts);
    return ret;
}
