"""Builds the cffi extension ``ogk.bindings._ogk_cffi`` (API mode) in place.

The extension compiles every kernel source (kernel/src/*.c) together with the
harness's C models (harness/csrc/*.c), so Python calls exactly the C the flight
build compiles. The cdefs below are written by hand from kernel/include/ogk/*.h
(cffi cannot read #include); integer macros use ``...`` so their values come
from the headers at compile time, and struct layouts are completed by the C
compiler (``...;``), so a -D override of a capacity limit cannot desynchronise
Python and C.

Run from anywhere:  .venv/bin/python harness/build_ffi.py
(`make ffi` does this whenever a kernel source, harness/csrc or this file changes.)
"""
from __future__ import annotations

import shutil
import sys
from pathlib import Path

import cffi

HARNESS_DIR = Path(__file__).resolve().parent
ROOT = HARNESS_DIR.parent
KERNEL_INCLUDE = ROOT / "kernel" / "include"
KERNEL_SRC = ROOT / "kernel" / "src"
CSRC = HARNESS_DIR / "csrc"
PACKAGE_DIR = HARNESS_DIR / "ogk" / "bindings"
BUILD_DIR = ROOT / "build" / "ffi"
MODULE_NAME = "ogk.bindings._ogk_cffi"

# ----------------------------------------------------------------- cdefs
CDEF_STATUS = """
typedef enum {
    OGK_OK = 0,
    OGK_E_NULL = 1,
    OGK_E_NONFINITE = 2,
    OGK_E_DIM = 3,
    OGK_E_RANGE = 4,
    OGK_E_SINGULAR = 5,
    OGK_E_ILL_CONDITIONED = 6,
    OGK_E_NOT_POSDEF = 7,
    OGK_E_SWITCH_OVERFLOW = 8,
    OGK_E_STEP_LIMIT = 9,
    OGK_E_CALLBACK = 10,
    OGK_E_TABLE_MAGIC = 11,
    OGK_E_TABLE_VERSION = 12,
    OGK_E_TABLE_TYPE = 13,
    OGK_E_TABLE_DIM = 14,
    OGK_E_TABLE_TRUNCATED = 15,
    OGK_E_TABLE_SIZE = 16,
    OGK_E_TABLE_CRC = 17,
    OGK_E_NOT_INIT = 18,
    OGK_E_CONFIG = 19,
    OGK_E_NOT_CONVERGED = 20,
    OGK_E_SAFE_COMMAND = 21,
    OGK_STATUS_COUNT = 22
} ogk_status;

ogk_status ogk_status_name(ogk_status code, const char **name);
"""

CDEF_VERSION = """
#define OGK_VERSION_MAJOR ...
#define OGK_VERSION_MINOR ...
#define OGK_VERSION_PATCH ...
ogk_status ogk_version(const char **text);
"""

CDEF_CONFIG = """
#define OGK_LA_MAX_N ...
#define OGK_LA_MAX_LONG ...
#define OGK_RK4_MAX_STATE ...
#define OGK_RK4_MAX_SWITCHES ...
#define OGK_RK4_MAX_STEPS ...
#define OGK_RK4_MAX_BISECTIONS ...
#define OGK_TABLE_MAX_DIMS ...
"""

CDEF_CRC32 = """
ogk_status ogk_crc32_update(uint32_t *crc, const uint8_t *data, size_t len);
"""

CDEF_TABLE = """
#define OGK_TABLE_HEADER_SIZE ...
#define OGK_TABLE_VERSION ...
#define OGK_TABLE_F64 ...

typedef struct {
    uint32_t kind;
    uint16_t ndims;
    uint32_t dims[...];
    uint32_t min_grid;
    uint32_t max_grid;
    ...;
} ogk_table_spec_t;

typedef struct {
    const uint8_t *buf;
    uint32_t kind;
    uint16_t ndims;
    uint32_t dims[...];
    uint32_t grid_size;
    uint32_t entry_len;
    ...;
} ogk_table_view_t;

ogk_status ogk_table_open(const uint8_t *buf, size_t len,
                          const ogk_table_spec_t *spec, ogk_table_view_t *view);
ogk_status ogk_table_read_grid(const ogk_table_view_t *view, double *grid_out,
                               size_t capacity);
ogk_status ogk_table_read_data(const ogk_table_view_t *view, double *data_out,
                               size_t capacity);
ogk_status ogk_table_get(const ogk_table_view_t *view, uint32_t k,
                         uint32_t index, double *value);
"""

CDEF_INTERP = """
ogk_status ogk_interp_check_grid(const double *grid, size_t n_grid);
ogk_status ogk_interp_linear(const double *grid, size_t n_grid,
                             const double *values, size_t m,
                             double tau, double *out);
ogk_status ogk_interp_pchip_slopes(const double *grid, size_t n_grid,
                                   const double *values, size_t m,
                                   double *slopes);
ogk_status ogk_interp_pchip(const double *grid, size_t n_grid,
                            const double *values, const double *slopes,
                            size_t m, double tau, double *out);
ogk_status ogk_interp_locate(const double *grid, size_t n_grid, double tau,
                             size_t *k);
"""

CDEF_LINALG = """
static const double OGK_LA_RCOND_MIN;

ogk_status ogk_mat_vec(const double *A, size_t rows, size_t cols,
                       const double *x, double *y);
ogk_status ogk_mat_t_vec(const double *A, size_t rows, size_t cols,
                         const double *x, double *y);
ogk_status ogk_mat_mul(const double *A, size_t r, size_t k,
                       const double *B, size_t c, double *C);
ogk_status ogk_mat_mul_at_b(const double *A, size_t k, size_t r,
                            const double *B, size_t c, double *C);
ogk_status ogk_mat_mul_a_bt(const double *A, size_t r, size_t k,
                            const double *B, size_t c, double *C);
ogk_status ogk_mat_transpose(const double *A, size_t rows, size_t cols,
                             double *At);

typedef struct {
    double lu[...];
    size_t perm[...];
    size_t n;
    double anorm1;
    double rcond;
    ...;
} ogk_lu_t;

ogk_status ogk_lu_factor(ogk_lu_t *lu, const double *A, size_t n);
ogk_status ogk_lu_solve(const ogk_lu_t *lu, const double *b, double *x);
ogk_status ogk_lu_inverse(const ogk_lu_t *lu, double *Ainv);

typedef struct {
    double l[...];
    size_t n;
    ...;
} ogk_chol_t;

ogk_status ogk_chol_factor(ogk_chol_t *ch, const double *A, size_t n);
ogk_status ogk_chol_solve(const ogk_chol_t *ch, const double *b, double *x);

typedef struct {
    double qr[...];
    double tau[...];
    size_t long_dim;
    size_t short_dim;
    ...;
} ogk_qr_t;

ogk_status ogk_lstsq(ogk_qr_t *ws, const double *A, size_t m, size_t n,
                     const double *b, double *x);
ogk_status ogk_minnorm(ogk_qr_t *ws, const double *A, size_t m, size_t n,
                       const double *b, double *x);
"""

CDEF_RK4 = """
typedef ogk_status (*ogk_rhs_fn)(void *user, double t, const double *x,
                                 int mode, double *xdot);
typedef ogk_status (*ogk_switch_fn)(void *user, double t, const double *x,
                                    int mode, double *s);

typedef struct {
    size_t n;
    double h;
    ogk_rhs_fn rhs;
    ogk_switch_fn sw;
    void *user;
    double s_tol;
    double t_tol;
    ...;
} ogk_rk4_problem_t;

#define OGK_SWITCH_BY_S_TOL ...
#define OGK_SWITCH_BY_TIME_TOL ...

typedef struct {
    double t;
    double s;
    int mode_after;
    uint8_t how;
    uint16_t bisections;
    size_t dense_index;
    ...;
} ogk_switch_event_t;

typedef struct {
    ogk_switch_event_t sw[...];
    size_t n_switches;
    size_t n_steps;
    size_t n_rhs;
    int mode_final;
    double t_reached;
    ...;
} ogk_rk4_result_t;

typedef struct {
    double *t;
    double *x;
    uint8_t *mode;
    size_t capacity;
    size_t count;
    ...;
} ogk_rk4_dense_t;

ogk_status ogk_rk4_step(const ogk_rk4_problem_t *p, double t, const double *x,
                        double dt, int mode, double *x_next);
ogk_status ogk_rk4_propagate(const ogk_rk4_problem_t *p, double t0,
                             const double *x0, int mode0, double tf,
                             ogk_rk4_result_t *res, double *xf,
                             ogk_rk4_dense_t *dense);
"""

# kernel/include/ogk/cpd.h: constrained PD attitude control (docs/cpd.md).
CDEF_CPD = """
static const double OGK_CPD_ANGLE_LIMIT;

typedef enum {
    OGK_CPD_POINTING_BODY = 0,
    OGK_CPD_POINTING_EULER = 1
} ogk_cpd_pointing_t;

#define OGK_CPD_FLAG_SAT_X ...
#define OGK_CPD_FLAG_SAT_Y ...
#define OGK_CPD_FLAG_SAT_Z ...
#define OGK_CPD_FLAG_SAFE ...
#define OGK_CPD_FLAG_BEHIND ...
#define OGK_CPD_FLAG_YAW_UNDEFINED ...
#define OGK_CPD_INIT_MAGIC ...

typedef struct {
    double k_px;
    double k_dx;
    double k_py;
    double k_dy;
    double k_pz;
    double k_dz;
    double m_xc_max;
    double delta_yc_max;
    double delta_zc_max;
    double tau_x;
    double tau_y;
    double tau_z;
    double phi_c;
    ogk_cpd_pointing_t pointing;
    double approach_accel_x;
    double approach_accel_y;
    double approach_accel_z;
    double ff_period_s;
    double ff_rate_max;
    ...;
} ogk_cpd_config_t;

typedef struct {
    double psi;
    double theta;
    double phi_roll;
    double rate_p;
    double rate_q;
    double rate_r;
    double alpha_c;
    double beta_c;
    double xi;
    double phi;
    ...;
} ogk_cpd_input_t;

typedef struct {
    double m_xc;
    double delta_yc;
    double delta_zc;
    double psi_c;
    double theta_c;
    double phi_c;
    double err_x;
    double err_y;
    double err_z;
    uint32_t flags;
    ...;
} ogk_cpd_output_t;

typedef struct {
    ogk_cpd_config_t cfg;
    ogk_cpd_output_t last;
    uint32_t init_magic;
    ...;
} ogk_cpd_t;

ogk_status ogk_cpd_init(ogk_cpd_t *ctx, const ogk_cpd_config_t *cfg);
ogk_status ogk_cpd_step(ogk_cpd_t *ctx, const ogk_cpd_input_t *in,
                        ogk_cpd_output_t *out);
ogk_status ogk_cpd_commanded_attitude(double alpha_c, double beta_c, double xi,
                                      double phi, double *psi_c,
                                      double *theta_c);
ogk_status ogk_cpd_thrust_angles(double psi, double theta, double phi_roll,
                                 double xi, double phi, double delta_y,
                                 double delta_z, double *alpha_a,
                                 double *beta_a);
ogk_status ogk_cpd_pointing_error_body(double psi, double theta, double phi_roll,
                                       double alpha_c, double beta_c, double xi,
                                       double phi, double *err_y, double *err_z);
ogk_status ogk_cpd_wrap_pi(double angle, double *wrapped);
"""

# harness/csrc/models.h: C models for tests and demos (not flight code).
CDEF_MODELS = """
typedef struct {
    double mu;
    ...;
} ogk_model_two_body_t;

ogk_status ogk_model_two_body_rhs(void *user, double t, const double *x,
                                  int mode, double *xdot);

typedef struct {
    double u_max;
    ...;
} ogk_model_min_fuel_di_t;

#define OGK_MODEL_MIN_FUEL_DI_N ...
ogk_status ogk_model_min_fuel_di_rhs(void *user, double t, const double *x,
                                     int mode, double *xdot);
ogk_status ogk_model_min_fuel_di_switch(void *user, double t, const double *x,
                                        int mode, double *s);

typedef struct {
    double rate;
    double t_fail;
    ...;
} ogk_model_decay_t;

ogk_status ogk_model_decay_rhs(void *user, double t, const double *x,
                               int mode, double *xdot);

typedef struct {
    double omega;
    ...;
} ogk_model_oscillator_t;

ogk_status ogk_model_oscillator_rhs(void *user, double t, const double *x,
                                    int mode, double *xdot);
ogk_status ogk_model_oscillator_switch(void *user, double t, const double *x,
                                       int mode, double *s);
"""

# harness/csrc/sil_batch.h: batch loops of the SIL harness over Monte Carlo runs
# (not flight code; ogk.missions.orbit_injection.attitude, docs/sil.md).
CDEF_SIL_BATCH = """
#define OGK_SIL_CPD_N_IN ...
#define OGK_SIL_CPD_N_OUT ...
ogk_status ogk_sil_cpd_init_batch(ogk_cpd_t *ctx, size_t n_runs,
                                  const ogk_cpd_config_t *cfg, int32_t *status);
ogk_status ogk_sil_cpd_step_batch(ogk_cpd_t *ctx, size_t n_runs,
                                  const uint8_t *active, const double *in,
                                  double *out, int32_t *status,
                                  uint32_t *flags);
"""

CDEF_NOG = """
#define OGK_NOG_NX ...
#define OGK_NOG_TABLE_KIND ...
#define OGK_NOG_ENTRY_LEN ...
#define OGK_NOG_MAX_GRID ...
#define OGK_NOG_FLAG_TERMINATING ...
#define OGK_NOG_FLAG_FROZEN ...
#define OGK_NOG_FLAG_LIMITED ...
#define OGK_NOG_FLAG_SAFE ...
#define OGK_NOG_FLAG_CUTOFF ...
typedef struct {
    double tau[...];
    double entry[...];
    size_t n_grid;
    double t_f_star_s;
    ...;
} ogk_nog_table_t;
typedef struct {
    const ogk_nog_table_t *table;
    double sample_interval_s;
    double dtf_max_s;
    double du_max_rad;
    double tau_freeze;
    ...;
} ogk_nog_config_t;
typedef struct {
    double t_s; double r_m; double xi_rad; double phi_rad;
    double v_r_mps; double v_t_mps; double v_n_mps;
    ...;
} ogk_nog_nav_t;
typedef struct {
    double tau_k; double tau_next; double t_f_s; double dt_f_s; double t_cutoff_s;
    double dx[7]; double alpha_rad; double beta_rad; uint8_t flags;
    ...;
} ogk_nog_sample_t;
typedef struct {
    double tau; double alpha_rad; double beta_rad; uint8_t flags;
    ...;
} ogk_nog_command_t;
typedef struct {
    double t_k_s; double tau_k; double t_f_s;
    uint32_t n_samples; uint8_t flags; uint8_t initialized;
    ...;
} ogk_nog_t;
ogk_status ogk_nog_table_load(ogk_nog_table_t *table, const uint8_t *buf, size_t len);
ogk_status ogk_nog_init(ogk_nog_t *ctx, const ogk_nog_config_t *cfg);
ogk_status ogk_nog_sample(ogk_nog_t *ctx, const ogk_nog_nav_t *nav, ogk_nog_sample_t *out);
ogk_status ogk_nog_command(const ogk_nog_t *ctx, double t_s, ogk_nog_command_t *out);
"""

# harness/csrc/nog_batch.h: VTD-NOG over all runs of a batch (ogk.missions.orbit_injection.nog_guidance).
CDEF_NOG_BATCH = """
ogk_status ogk_sil_nog_init_batch(ogk_nog_t *ctx, size_t n_runs,
                                  const ogk_nog_config_t *cfg, int32_t *status);
ogk_status ogk_sil_nog_sample_batch(ogk_nog_t *ctx, size_t n_runs, const uint8_t *active,
                                    const double *t, const double *nav, double *t_cutoff,
                                    double *t_f, double *tau_k, uint32_t *flags,
                                    int32_t *status);
ogk_status ogk_sil_nog_command_batch(const ogk_nog_t *ctx, size_t n_runs, const double *t,
                                     double *alpha, double *beta, uint32_t *flags,
                                     int32_t *status);
"""

# kernel/include/ogk/mpsp.h: MPSP bang-off-bang low-thrust guidance (docs/mpsp.md).
CDEF_MPSP = """
#define OGK_MPSP_NX ...
#define OGK_MPSP_NX0 ...
#define OGK_MPSP_NU ...
#define OGK_MPSP_NY ...
#define OGK_MPSP_MAX_ORDER ...
#define OGK_MPSP_MAX_STEPS ...
#define OGK_MPSP_MAX_SWITCHES ...
#define OGK_MPSP_MAX_LOG ...
#define OGK_MPSP_MAX_BASIS ...
#define OGK_MPSP_MAX_WEIGHTS ...
#define OGK_MPSP_MAX_UNKNOWNS ...
#define OGK_MPSP_MAX_NODES ...
#define OGK_MPSP_BASIS_FOURIER ...
#define OGK_MPSP_BASIS_COSINE ...
typedef struct {
    double mu; double t_max; double c_exhaust; double t0; double tf;
    double x0_nom[...]; double r_f[...]; double v_f[...];
    uint32_t fourier_order; uint32_t fourier_kind; double fourier_period; double fourier_t_ref;
    double h_max; double delta_max; double delta_tau_0; double delta_tau_min;
    double r_eps[...]; double r_lambda;
    double tol_r; double tol_v; double tol_lambda_m; double s_tol;
    uint32_t max_newton; uint32_t max_outer; uint32_t n_seg_tol; uint32_t n_seg_tol_step;
    double weights_nom[...]; double lambda_m0_nom; uint32_t n_seg_nom;
    ...;
} ogk_mpsp_config_t;
typedef struct {
    double x_f[...]; uint32_t n_switches; double t_switch[...];
    uint32_t n_segments; uint32_t n_thrust_arcs; int mode0; size_t n_nodes;
    ...;
} ogk_mpsp_prop_t;
typedef struct {
    uint8_t converged; uint32_t newton_iterations; uint32_t inner_loops;
    uint32_t outer_steps; uint32_t n_seg_tol; double tau_reached; double dy[...];
    double err_r; double err_v; double lambda_mf; double m_f;
    uint32_t n_segments; uint32_t n_thrust_arcs; uint32_t n_switches; double t_switch[...];
    size_t n_weights; double weights[...]; double lambda_m0;
    uint32_t n_log; double dy_norm_log[...];
    ...;
} ogk_mpsp_result_t;
typedef struct {
    size_t n_basis; size_t n_weights; size_t n_steps; uint32_t n_seg_nom;
    ...;
} ogk_mpsp_t;
ogk_status ogk_mpsp_init(ogk_mpsp_t *ctx, const ogk_mpsp_config_t *cfg);
ogk_status ogk_mpsp_solve(ogk_mpsp_t *ctx, const double *x0, double thrust_scale,
                          const double *target_rv, ogk_mpsp_result_t *res);
ogk_status ogk_mpsp_propagate(ogk_mpsp_t *ctx, const double *weights, double lambda_m0,
                              const double *x0, double thrust_scale, ogk_mpsp_prop_t *out);
ogk_status ogk_mpsp_trajectory(const ogk_mpsp_t *ctx, double *t, double *x,
                               uint8_t *mode, size_t capacity, size_t *count);
ogk_status ogk_mpsp_state_at(const ogk_mpsp_t *ctx, double t, double *x);
ogk_status ogk_mpsp_control(const ogk_mpsp_t *ctx, const double *weights, double t,
                            double *lambda_v, double *lambda_v_dot);
ogk_status ogk_mpsp_sensitivity(ogk_mpsp_t *ctx, double *dy_dw, double *dy_dlm0);
ogk_status ogk_mpsp_newton_update(ogk_mpsp_t *ctx, const double *dy, double *weights,
                                  double *lambda_m0);
ogk_status ogk_mpsp_step_jacobian(const ogk_mpsp_t *ctx, const double *weights,
                                  double thrust_scale, double t, const double *x,
                                  double dt, int mode, double *x_next,
                                  double *dfdx, double *dfdw);
ogk_status ogk_mpsp_switch_jump(const ogk_mpsp_t *ctx, const double *weights,
                                double thrust_scale, double t_s, const double *x_s,
                                int mode_before, double *jx, double *jw,
                                double *dts_dx, double *dts_dw);
"""

CDEF = "".join(
    [CDEF_STATUS, CDEF_VERSION, CDEF_CONFIG, CDEF_CRC32, CDEF_TABLE,
     CDEF_INTERP, CDEF_LINALG, CDEF_RK4, CDEF_CPD, CDEF_MODELS,
     CDEF_SIL_BATCH, CDEF_NOG, CDEF_NOG_BATCH, CDEF_MPSP]
)

HEADERS = ["status", "version", "config", "crc32", "table", "interp", "linalg", "rk4", "cpd", "nog", "mpsp"]
SOURCE = ("".join(f'#include "ogk/{h}.h"\n' for h in HEADERS) + '#include "models.h"\n'
          + '#include "sil_batch.h"\n' + '#include "nog_batch.h"\n')


def kernel_sources() -> list[str]:
    return [str(p) for p in sorted(KERNEL_SRC.glob("*.c"))] + [
        str(p) for p in sorted(CSRC.glob("*.c"))
    ]


def make_builder() -> cffi.FFI:
    ffibuilder = cffi.FFI()
    ffibuilder.cdef(CDEF)
    ffibuilder.set_source(
        MODULE_NAME,
        SOURCE,
        sources=kernel_sources(),
        include_dirs=[str(KERNEL_INCLUDE), str(CSRC)],
        extra_compile_args=["-std=c99", "-O2"],
        libraries=["m"],
    )
    return ffibuilder


def main() -> int:
    BUILD_DIR.mkdir(parents=True, exist_ok=True)
    built = Path(make_builder().compile(tmpdir=str(BUILD_DIR), verbose=False))
    # Install the extension next to the package sources (editable install).
    for old in PACKAGE_DIR.glob("_ogk_cffi*"):
        old.unlink()
    target = PACKAGE_DIR / built.name
    shutil.copy2(built, target)
    print(f"build_ffi: {target.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
