/* One solve of a stiff problem by a compiled peer, timed inside the process.
 *
 * Built three times by scripts/peers/compiled.py, one program a peer:
 *   -DPEER_CVODE   SUNDIALS CVODE (BDF, Newton with the dense direct solver, analytic Jacobian)
 *   -DPEER_RADAU5  Hairer's RADAU5 (radau_decsol.f, analytic Jacobian)
 *   -DPEER_RODAS   Hairer's RODAS (rodas_decsol.f, analytic Jacobian)
 *
 * Usage: peer PROBLEM RTOL ATOL REPEATS
 * Prints one line: the state at the end (every component, %.17e), the median, least and
 * greatest wall time of the REPEATS solves (s; clock_gettime(CLOCK_MONOTONIC) around the
 * solver call alone, as friction-lab's summary.json times its solve), the evaluations of f,
 * the Jacobians, the accepted and rejected steps; or "failed CODE" on a solver failure.
 *
 * The problems are those of friction-lab's `testset` (integrators::testset; the Test Set for
 * IVP Solvers 2.4) and the two stiff friction cases of scripts/peers/friction_cases.py, with
 * the same equations, initial values and end times.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* ---- the problems: f(t, y) and its Jacobian J[i][j] = ∂f_i/∂y_j, row-major ---- */

typedef void (*rhs_fn)(double t, const double *y, double *f);
typedef void (*jac_fn)(double t, const double *y, double *J);

typedef struct {
    const char *name;
    int n;
    rhs_fn f;
    jac_fn jac;
    double y0[8];
    double t_end;
} problem;

#define J_(i, j) J[(i) * n + (j)]

static void vdp(double t, const double *y, double *f) {
    (void)t;
    f[0] = y[1];
    f[1] = ((1 - y[0] * y[0]) * y[1] - y[0]) / 1e-6;
}
static void vdp_jac(double t, const double *y, double *J) {
    const int n = 2;
    (void)t;
    J_(0, 0) = 0;
    J_(0, 1) = 1;
    J_(1, 0) = (-2 * y[0] * y[1] - 1) / 1e-6;
    J_(1, 1) = (1 - y[0] * y[0]) / 1e-6;
}

static void rober(double t, const double *y, double *f) {
    (void)t;
    double f1 = -0.04 * y[0] + 1e4 * y[1] * y[2], f3 = 3e7 * y[1] * y[1];
    f[0] = f1;
    f[1] = -f1 - f3;
    f[2] = f3;
}
static void rober_jac(double t, const double *y, double *J) {
    const int n = 3;
    (void)t;
    double p1 = 1e4 * y[1], p2 = 1e4 * y[2], p3 = 6e7 * y[1];
    J_(0, 0) = -0.04, J_(0, 1) = p2, J_(0, 2) = p1;
    J_(1, 0) = 0.04, J_(1, 1) = -p2 - p3, J_(1, 2) = -p1;
    J_(2, 0) = 0, J_(2, 1) = p3, J_(2, 2) = 0;
}

static void hires(double t, const double *y, double *f) {
    (void)t;
    f[0] = -1.71 * y[0] + 0.43 * y[1] + 8.32 * y[2] + 0.0007;
    f[1] = 1.71 * y[0] - 8.75 * y[1];
    f[2] = -10.03 * y[2] + 0.43 * y[3] + 0.035 * y[4];
    f[3] = 8.32 * y[1] + 1.71 * y[2] - 1.12 * y[3];
    f[4] = -1.745 * y[4] + 0.43 * y[5] + 0.43 * y[6];
    f[5] = -280 * y[5] * y[7] + 0.69 * y[3] + 1.71 * y[4] - 0.43 * y[5] + 0.69 * y[6];
    f[6] = 280 * y[5] * y[7] - 1.81 * y[6];
    f[7] = -280 * y[5] * y[7] + 1.81 * y[6];
}
static void hires_jac(double t, const double *y, double *J) {
    const int n = 8;
    (void)t;
    memset(J, 0, sizeof(double) * 64);
    J_(0, 0) = -1.71, J_(0, 1) = 0.43, J_(0, 2) = 8.32;
    J_(1, 0) = 1.71, J_(1, 1) = -8.75;
    J_(2, 2) = -10.03, J_(2, 3) = 0.43, J_(2, 4) = 0.035;
    J_(3, 1) = 8.32, J_(3, 2) = 1.71, J_(3, 3) = -1.12;
    J_(4, 4) = -1.745, J_(4, 5) = 0.43, J_(4, 6) = 0.43;
    J_(5, 3) = 0.69, J_(5, 4) = 1.71, J_(5, 5) = -280 * y[7] - 0.43, J_(5, 6) = 0.69,
    J_(5, 7) = -280 * y[5];
    J_(6, 5) = 280 * y[7], J_(6, 6) = -1.81, J_(6, 7) = 280 * y[5];
    J_(7, 5) = -280 * y[7], J_(7, 6) = 1.81, J_(7, 7) = -280 * y[5];
}

#define S_ 77.27
#define Q_ 8.375e-6
#define W_ 0.161
static void orego(double t, const double *y, double *f) {
    (void)t;
    f[0] = S_ * (y[1] + y[0] * (1 - Q_ * y[0] - y[1]));
    f[1] = (y[2] - (1 + y[0]) * y[1]) / S_;
    f[2] = W_ * (y[0] - y[2]);
}
static void orego_jac(double t, const double *y, double *J) {
    const int n = 3;
    (void)t;
    J_(0, 0) = S_ * (1 - 2 * Q_ * y[0] - y[1]), J_(0, 1) = S_ * (1 - y[0]), J_(0, 2) = 0;
    J_(1, 0) = -y[1] / S_, J_(1, 1) = -(1 + y[0]) / S_, J_(1, 2) = 1 / S_;
    J_(2, 0) = W_, J_(2, 1) = 0, J_(2, 2) = -W_;
}

/* The belt m x'' + c x' + k x = -F(x' - v_belt) with the paper's parameters
 * (friction_cases.py). */
#define M_ 1.0
#define K_ 100.0
#define C_ 0.0
#define V_BELT 0.05
#define F_S 7.5
#define F_C 6.0
#define V_S 0.1
#define C1_ 1.5
#define C2_ 1.5
#define SIGMA0 1e5
#define SIGMA2 0.4
#define EPS 1e-4
static const double SIGMA1 = 316.22776601683796; /* sqrt(1e5) */

static void lugre(double t, const double *y, double *f) {
    (void)t;
    double vr = y[1] - V_BELT;
    double g = F_C + (F_S - F_C) * exp(-(vr / V_S) * (vr / V_S));
    double zdot = vr - SIGMA0 * fabs(vr) * y[2] / g;
    double force = SIGMA0 * y[2] + SIGMA1 * zdot + SIGMA2 * vr;
    f[0] = y[1];
    f[1] = (-K_ * y[0] - C_ * y[1] - force) / M_;
    f[2] = zdot;
}
static void lugre_jac(double t, const double *y, double *J) {
    const int n = 3;
    (void)t;
    double vr = y[1] - V_BELT, z = y[2];
    double e = exp(-(vr / V_S) * (vr / V_S));
    double g = F_C + (F_S - F_C) * e;
    double dg = (F_S - F_C) * e * (-2 * vr / (V_S * V_S));
    double sign = vr > 0 ? 1.0 : (vr < 0 ? -1.0 : 0.0);
    double dzdot_dz = -SIGMA0 * fabs(vr) / g;
    double dzdot_dv = 1 - SIGMA0 * z * (sign * g - fabs(vr) * dg) / (g * g);
    double df_dz = SIGMA0 + SIGMA1 * dzdot_dz, df_dv = SIGMA1 * dzdot_dv + SIGMA2;
    J_(0, 0) = 0, J_(0, 1) = 1, J_(0, 2) = 0;
    J_(1, 0) = -K_ / M_, J_(1, 1) = (-C_ - df_dv) / M_, J_(1, 2) = -df_dz / M_;
    J_(2, 0) = 0, J_(2, 1) = dzdot_dv, J_(2, 2) = dzdot_dz;
}

static void regularized(double t, const double *y, double *f) {
    (void)t;
    double vr = y[1] - V_BELT, th = tanh(vr / EPS), e = exp(-(vr / V_S) * (vr / V_S));
    double force = F_C * th + e * (C1_ * (1 + th) / 2 - C2_ * (1 - th) / 2);
    f[0] = y[1];
    f[1] = (-K_ * y[0] - C_ * y[1] - force) / M_;
}
static void regularized_jac(double t, const double *y, double *J) {
    const int n = 2;
    (void)t;
    double vr = y[1] - V_BELT, th = tanh(vr / EPS), dth = (1 - th * th) / EPS;
    double e = exp(-(vr / V_S) * (vr / V_S)), de = e * (-2 * vr / (V_S * V_S));
    double stribeck = C1_ * (1 + th) / 2 - C2_ * (1 - th) / 2;
    double df_dv = F_C * dth + de * stribeck + e * (C1_ + C2_) / 2 * dth;
    J_(0, 0) = 0, J_(0, 1) = 1;
    J_(1, 0) = -K_ / M_, J_(1, 1) = (-C_ - df_dv) / M_;
}

static const problem PROBLEMS[] = {
    {"van-der-pol", 2, vdp, vdp_jac, {2.0, 0.0}, 2.0},
    {"robertson", 3, rober, rober_jac, {1.0, 0.0, 0.0}, 1e11},
    {"hires", 8, hires, hires_jac, {1, 0, 0, 0, 0, 0, 0, 0.0057}, 321.8122},
    {"orego", 3, orego, orego_jac, {1.0, 2.0, 3.0}, 360.0},
    {"belt-lugre", 3, lugre, lugre_jac, {0.0, 0.0, 0.0}, 20.0},
    {"belt-regularized", 2, regularized, regularized_jac, {0.0, 0.0}, 20.0},
};

/* ---- what a solve returns ---- */

typedef struct {
    int failed; /* the solver's failure code, 0 when it reached t_end */
    double y[8];
    long nfev, njac, accepted, rejected;
} outcome;

static const problem *P; /* the problem being solved (the callbacks read it) */

static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

#ifdef PEER_CVODE
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

static int cv_rhs(realtype t, N_Vector y, N_Vector f, void *data) {
    (void)data;
    P->f(t, N_VGetArrayPointer(y), N_VGetArrayPointer(f));
    return 0;
}
static int cv_jac(realtype t, N_Vector y, N_Vector fy, SUNMatrix J, void *data, N_Vector t1,
                  N_Vector t2, N_Vector t3) {
    (void)fy, (void)data, (void)t1, (void)t2, (void)t3;
    double row_major[64];
    int n = P->n;
    P->jac(t, N_VGetArrayPointer(y), row_major);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) SM_ELEMENT_D(J, i, j) = row_major[i * n + j];
    return 0;
}

/* CVODE's BDF from y0 to t_end in one call (CV_NORMAL), as the test set's drivers run it. */
static outcome solve(double rtol, double atol, double *seconds) {
    outcome o = {0};
    SUNContext ctx;
    SUNContext_Create(NULL, &ctx);
    N_Vector y = N_VNew_Serial(P->n, ctx);
    for (int i = 0; i < P->n; i++) NV_Ith_S(y, i) = P->y0[i];
    SUNMatrix A = SUNDenseMatrix(P->n, P->n, ctx);
    SUNLinearSolver LS = SUNLinSol_Dense(y, A, ctx);
    double start = now();
    void *mem = CVodeCreate(CV_BDF, ctx);
    CVodeInit(mem, cv_rhs, 0.0, y);
    CVodeSStolerances(mem, rtol, atol);
    CVodeSetLinearSolver(mem, LS, A);
    CVodeSetJacFn(mem, cv_jac);
    CVodeSetMaxNumSteps(mem, 10000000);
    CVodeSetStopTime(mem, P->t_end);
    realtype t = 0.0;
    int flag = CVode(mem, P->t_end, y, &t, CV_NORMAL);
    *seconds = now() - start;
    o.failed = flag < 0 ? flag : 0;
    for (int i = 0; i < P->n; i++) o.y[i] = NV_Ith_S(y, i);
    long steps, fev, jev, fls, lfev;
    CVodeGetNumSteps(mem, &steps);
    CVodeGetNumRhsEvals(mem, &fev);
    CVodeGetNumLinRhsEvals(mem, &lfev);
    CVodeGetNumJacEvals(mem, &jev);
    CVodeGetNumErrTestFails(mem, &fls);
    long ncf;
    CVodeGetNumNonlinSolvConvFails(mem, &ncf);
    o.nfev = fev + lfev, o.njac = jev, o.accepted = steps, o.rejected = fls + ncf;
    CVodeFree(&mem);
    SUNLinSolFree(LS);
    SUNMatDestroy(A);
    N_VDestroy(y);
    SUNContext_Free(&ctx);
    return o;
}
#else
/* Hairer's codes: Fortran 77 calling convention, every argument by reference. */
static void h_rhs(const int *n, const double *x, const double *y, double *f, double *rpar,
                  int *ipar) {
    (void)n, (void)rpar, (void)ipar;
    P->f(*x, y, f);
}
static void h_jac(const int *n, const double *x, const double *y, double *dfy, const int *ldfy,
                  double *rpar, int *ipar) {
    (void)rpar, (void)ipar;
    double row_major[64];
    P->jac(*x, y, row_major);
    for (int i = 0; i < *n; i++) /* column-major, leading dimension ldfy */
        for (int j = 0; j < *n; j++) dfy[j * *ldfy + i] = row_major[i * *n + j];
}
static void h_none(void) {}

#ifdef PEER_RADAU5
extern void radau5_(const int *n, void *fcn, double *x, double *y, const double *xend,
                    double *h, double *rtol, double *atol, const int *itol, void *jac,
                    const int *ijac, const int *mljac, const int *mujac, void *mas,
                    const int *imas, const int *mlmas, const int *mumas, void *solout,
                    const int *iout, double *work, const int *lwork, int *iwork,
                    const int *liwork, double *rpar, int *ipar, int *idid);
#else
extern void rodas_(const int *n, void *fcn, const int *ifcn, double *x, double *y,
                   const double *xend, double *h, double *rtol, double *atol, const int *itol,
                   void *jac, const int *ijac, const int *mljac, const int *mujac, void *dfx,
                   const int *idfx, void *mas, const int *imas, const int *mlmas,
                   const int *mumas, void *solout, const int *iout, double *work,
                   const int *lwork, int *iwork, const int *liwork, double *rpar, int *ipar,
                   int *idid);
#endif

/* RADAU5 or RODAS from y0 to t_end in one call, every control at its default (WORK and IWORK
 * zero), the initial step 1e-6 as in Hairer's drivers (dr_radau.f, dr_rodas.f). */
static outcome solve(double rtol, double atol, double *seconds) {
    outcome o = {0};
    int n = P->n, itol = 0, ijac = 1, mljac = n, mujac = 0, imas = 0, mlmas = 0, mumas = 0,
        iout = 0, idid = 0, ipar = 0;
    double x = 0.0, h = 1e-6, rpar = 0.0, y[8];
    memcpy(y, P->y0, sizeof y);
    int lwork = n * (4 * n + 12) + 20, liwork = 3 * n + 20; /* RADAU5's bound covers RODAS' */
    double *work = calloc(lwork, sizeof(double));
    int *iwork = calloc(liwork, sizeof(int));
#ifdef PEER_RADAU5
    iwork[1] = 10000000; /* IWORK(2): the most steps */
#else
    iwork[0] = 10000000; /* IWORK(1): the most steps */
#endif
    double start = now();
#ifdef PEER_RADAU5
    radau5_(&n, h_rhs, &x, y, &P->t_end, &h, &rtol, &atol, &itol, h_jac, &ijac, &mljac, &mujac,
            h_none, &imas, &mlmas, &mumas, h_none, &iout, work, &lwork, iwork, &liwork, &rpar,
            &ipar, &idid);
#else
    int ifcn = 0, idfx = 0; /* autonomous: ∂f/∂t = 0 */
    rodas_(&n, h_rhs, &ifcn, &x, y, &P->t_end, &h, &rtol, &atol, &itol, h_jac, &ijac, &mljac,
           &mujac, h_none, &idfx, h_none, &imas, &mlmas, &mumas, h_none, &iout, work, &lwork,
           iwork, &liwork, &rpar, &ipar, &idid);
#endif
    *seconds = now() - start;
    o.failed = idid < 0 ? idid : 0;
    memcpy(o.y, y, sizeof y);
    /* IWORK(14..17): NFCN, NJAC, NSTEP (every step computed), NACCPT; a step not accepted
     * failed its error test or its Newton iteration. */
    o.nfev = iwork[13], o.njac = iwork[14], o.accepted = iwork[16],
    o.rejected = iwork[15] - iwork[16];
    free(work);
    free(iwork);
    return o;
}
#endif

static int by_value(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv) {
    if (argc != 5) {
        fprintf(stderr, "usage: %s PROBLEM RTOL ATOL REPEATS\n", argv[0]);
        return 2;
    }
    for (size_t k = 0; k < sizeof PROBLEMS / sizeof *PROBLEMS; k++)
        if (strcmp(PROBLEMS[k].name, argv[1]) == 0) P = &PROBLEMS[k];
    if (!P) {
        fprintf(stderr, "unknown problem %s\n", argv[1]);
        return 2;
    }
    double rtol = atof(argv[2]), atol = atof(argv[3]);
    int repeats = atoi(argv[4]);
    if (repeats < 1) repeats = 1;
    double *times = malloc(sizeof(double) * repeats);
    outcome o = {0};
    for (int r = 0; r < repeats; r++) o = solve(rtol, atol, &times[r]);
    if (o.failed) {
        printf("failed %d\n", o.failed);
        return 1;
    }
    qsort(times, repeats, sizeof(double), by_value);
    for (int i = 0; i < P->n; i++) printf("%.17e ", o.y[i]);
    printf("| %.9e %.9e %.9e | %ld %ld %ld %ld\n", times[repeats / 2], times[0],
           times[repeats - 1], o.nfev, o.njac, o.accepted, o.rejected);
    free(times);
    return 0;
}
