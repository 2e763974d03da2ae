/* nog.c -- VTD-NOG flight law (ogk/nog.h; derivation in docs/design/vtd-nog.md). */
#include "ogk/nog.h"

#include <math.h>
#include <stdbool.h>
#include <string.h>

#include "ogk/interp.h"
#include "ogk/linalg.h"
#include "ogk/table.h"

#include "../ogk_checks.h"
#include "../thrust_cmd_internal.h"

#define NX OGK_NOG_NX
#define N_GAIN_ROWS 8u          /* dlam (7) and dt_f */
#define IDX_R 0u
#define IDX_XI 1u
#define IDX_VR 3u
#define IDX_TIME 6u
#define PI OGK_I_PI

/* Halvings of the costate-correction scale when the direction bound bites:
 * 40 give the scale to 1e-12. */
#define OGK_NOG_LIMIT_ITERATIONS 40u

/* Relative tolerance on the t_f* values a table carries (x*' of the time state)
 * and on its time states against t_f* tau. Float: a table written in double and
 * rounded to float value by value (the ground tools' F32 file, or a user's) is
 * consistent to an ulp of t_f* in each value, and the kernel's float product
 * t_f* tau(k) adds an ulp: 4 eps t_f* accepts both and still refuses a time
 * state one part in a million off (issue 35). */
#if OGK_REAL_SINGLE
#define OGK_NOG_TF_CONSISTENCY (OGK_R(4.0) * OGK_REAL_EPSILON)
#else
#define OGK_NOG_TF_CONSISTENCY OGK_R(1.0e-9)
#endif

static const ogk_real_t *entry_row(const ogk_nog_table_view_t *tbl, size_t k)
{
    return &tbl->entry[k * OGK_NOG_ENTRY_LEN];
}

/* ------------------------------------------------------------------ table */

/* The grid and t_f* checks shared by the loader and the in-place view. */
static ogk_status check_table_content(const ogk_nog_table_view_t *tbl)
{
    const size_t n = tbl->n_grid;
    const ogk_real_t t_f = entry_row(tbl, 0u)[OGK_NOG_OFF_XDOT + IDX_TIME];
    size_t k;
    ogk_status st = ogk_interp_check_grid(tbl->tau, n);

    if ((st != OGK_OK) || (tbl->tau[0] != OGK_R(0.0)) || (tbl->tau[n - 1u] != OGK_R(1.0))) {
        st = OGK_E_TABLE_DIM;
    } else if ((!(t_f > OGK_R(0.0))) || (t_f > OGK_NOG_TF_MAX_S)) {
        st = OGK_E_TABLE_TYPE;
    } else {
        /* Up to the first inconsistent row. */
        for (k = 0u; (k < n) && (st == OGK_OK); ++k) {
            const ogk_real_t *row = entry_row(tbl, k);
            if ((OGK_FABS(row[OGK_NOG_OFF_XDOT + IDX_TIME] - t_f) > (OGK_NOG_TF_CONSISTENCY * t_f)) ||
                (OGK_FABS(row[OGK_NOG_OFF_X + IDX_TIME] - (t_f * tbl->tau[k])) > (OGK_NOG_TF_CONSISTENCY * t_f)) ||
                (!(row[OGK_NOG_OFF_X + IDX_R] > OGK_R(0.0)))) {
                st = OGK_E_TABLE_TYPE;
            }
        }
    }
    return st;
}

/* The file-level checks shared by the loader and the in-place view. */
static ogk_status open_table(const uint8_t *buf, size_t len, ogk_table_view_t *view)
{
    ogk_table_spec_t spec;

    (void)memset(&spec, 0, sizeof spec); /* returns &spec: nothing to check */
    spec.kind = OGK_NOG_TABLE_KIND;
    spec.ndims = 1u;
    spec.dims[0] = OGK_NOG_ENTRY_LEN;
    spec.min_grid = 3u;
    spec.max_grid = OGK_NOG_MAX_GRID;
    return ogk_table_open(buf, len, &spec, view);
}

/* A view of a RAM table (what the context flies from). */
static void view_of_table(const ogk_nog_table_t *table, ogk_nog_table_view_t *view)
{
    (void)memset(view, 0, sizeof *view); /* returns view: nothing to check */
    view->tau = table->tau;
    view->entry = table->entry;
    view->n_grid = table->n_grid;
    view->t_f_star_s = table->t_f_star_s;
    view->init_marker = OGK_NOG_VIEW_MARKER;
    view->generation = table->generation;
}

ogk_status ogk_nog_table_load(ogk_nog_table_t *table, const uint8_t *buf, size_t len)
{
    ogk_table_view_t view;
    ogk_nog_table_view_t tv;
    ogk_status st;

    if (table == NULL) {
        st = OGK_E_NULL;
    } else {
        /* First, whatever follows: a context bound to this table is stale from
         * here on, even if the new bytes turn out to be the old ones. */
        table->generation += 1u;
        table->n_grid = 0u;
        table->t_f_star_s = OGK_R(0.0);
        st = open_table(buf, len, &view);
        if (st == OGK_OK) {
            st = ogk_table_read_grid(&view, table->tau, OGK_NOG_MAX_GRID);
        }
        if (st == OGK_OK) {
            st = ogk_table_read_data(&view, table->entry, (size_t)OGK_NOG_MAX_GRID * OGK_NOG_ENTRY_LEN);
        }
        if (st == OGK_OK) {
            table->n_grid = view.grid_size;
            view_of_table(table, &tv);
            st = check_table_content(&tv);
        }
        if (st != OGK_OK) {
            table->n_grid = 0u;
        } else {
            table->t_f_star_s = table->entry[OGK_NOG_OFF_XDOT + IDX_TIME];
        }
    }
    return st;
}

/* Points the (reset) view into the payload of the opened table buf of
 * grid_size nodes and checks it; on failure the view is reset again, its
 * generation kept. */
static ogk_status view_payload(ogk_nog_table_view_t *view, const uint8_t *buf, size_t grid_size)
{
    const uint32_t generation = view->generation;
    ogk_status st;

    /* Grid then entries, both in the table's little-endian element type
     * (OGK_TABLE_REAL, the target's own representation of ogk_real_t:
     * ogk_table_check_in_place passed). The bytes are only ever read, as
     * ogk_real_t, through these pointers. */
    view->tau = (const ogk_real_t *)(const void *)&buf[OGK_TABLE_HEADER_SIZE];
    view->entry = &view->tau[grid_size];
    view->n_grid = grid_size;
    st = check_table_content(view);
    if (st != OGK_OK) {
        (void)memset(view, 0, sizeof *view); /* returns view: nothing to check */
        view->generation = generation;
    } else {
        view->t_f_star_s = view->entry[OGK_NOG_OFF_XDOT + IDX_TIME];
        view->init_marker = OGK_NOG_VIEW_MARKER;
    }
    return st;
}

/* ogk_nog_table_view past the reset of view (generation already bumped). */
static ogk_status point_view(ogk_nog_table_view_t *view, const uint8_t *buf, size_t len)
{
    ogk_table_view_t tv;
    ogk_status st;

    if (buf == NULL) {
        st = OGK_E_NULL;
    } else if (((uintptr_t)(const void *)buf & (uintptr_t)(sizeof(ogk_real_t) - 1u)) != 0u) {
        /* The payload (offset 48) is read in place as ogk_real_t: buf aligned
         * to its size (8 bytes, 4 in the float build) aligns every value. */
        st = OGK_E_ALIGN;
    } else {
        st = open_table(buf, len, &tv);
        if (st == OGK_OK) {
            /* Read in place only where an ogk_real_t is the file's
             * little-endian element; elsewhere (SPARC/LEON, PowerPC) ogk_nog_table_load
             * decodes the same image. After the file checks: a corrupt image
             * is reported as such on every target. */
            st = ogk_table_check_in_place();
        }
        if (st == OGK_OK) {
            st = view_payload(view, buf, tv.grid_size);
        }
    }
    return st;
}

ogk_status ogk_nog_table_view(ogk_nog_table_view_t *view, const uint8_t *buf, size_t len)
{
    ogk_status st;

    if (view == NULL) {
        st = OGK_E_NULL;
    } else {
        /* Bumped and kept through the reset: bound contexts become stale. */
        const uint32_t generation = view->generation + 1u;
        (void)memset(view, 0, sizeof *view); /* returns view: nothing to check */
        view->generation = generation;
        st = point_view(view, buf, len);
    }
    return st;
}

/* ------------------------------------------------------------------ helpers */

/* Cubic Hermite of n quantities at tau from values at offset off_val and
 * d/dtau at off_der of the bracketing nodes. tau must be inside the grid. */
static void hermite(const ogk_nog_table_view_t *tbl, ogk_real_t tau, size_t off_val, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, argument order of the equation it implements; every caller is in this file and unit-tested */
                    size_t off_der, size_t n, ogk_real_t *out) /* NOLINT(bugprone-easily-swappable-parameters): internal helper, argument order of the equation it implements; every caller is in this file and unit-tested */
{
    size_t k = 0u;
    size_t i;
    ogk_real_t h;
    ogk_real_t s;
    ogk_real_t h00;
    ogk_real_t h10;
    ogk_real_t h01;
    ogk_real_t h11;
    const ogk_real_t *a;
    const ogk_real_t *b;

    (void)ogk_interp_locate(tbl->tau, tbl->n_grid, tau, &k);
    a = entry_row(tbl, k);
    b = entry_row(tbl, k + 1u);
    h = tbl->tau[k + 1u] - tbl->tau[k];
    /* s in [0, 1]: every caller passes tau in [0, 1], which ogk_interp_locate
     * brackets by [tau[k], tau[k+1]], and rounding is monotonic; the clamp
     * changes no value and states the range for the analysis (docs/evidence/eva.md). */
    s = OGK_FMIN(OGK_FMAX((tau - tbl->tau[k]) / h, OGK_R(0.0)), OGK_R(1.0));
    h00 = (OGK_R(1.0) + (OGK_R(2.0) * s)) * (OGK_R(1.0) - s) * (OGK_R(1.0) - s);
    h10 = s * (OGK_R(1.0) - s) * (OGK_R(1.0) - s);
    h01 = s * s * (OGK_R(3.0) - (OGK_R(2.0) * s));
    h11 = s * s * (s - OGK_R(1.0));
    for (i = 0u; i < n; ++i) {
        out[i] = (h00 * a[off_val + i]) + (h10 * h * a[off_der + i]) + (h01 * b[off_val + i]) +
                 (h11 * h * b[off_der + i]);
    }
}

/* Linear interpolation of a block of n values at offset off. */
static void linear_block(const ogk_nog_table_view_t *tbl, ogk_real_t tau, size_t off, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, argument order of the equation it implements; every caller is in this file and unit-tested */
                         size_t n, ogk_real_t *out)
{
    size_t k = 0u;
    size_t i;
    ogk_real_t w;
    const ogk_real_t *a;
    const ogk_real_t *b;

    (void)ogk_interp_locate(tbl->tau, tbl->n_grid, tau, &k);
    a = entry_row(tbl, k);
    b = entry_row(tbl, k + 1u);
    /* w in [0, 1] as hermite's s: a clamp that changes no value. */
    w = OGK_FMIN(OGK_FMAX((tau - tbl->tau[k]) / (tbl->tau[k + 1u] - tbl->tau[k]), OGK_R(0.0)), OGK_R(1.0));
    for (i = 0u; i < n; ++i) {
        out[i] = a[off + i] + (w * (b[off + i] - a[off + i]));
    }
}

/* Thrust direction minimising H: along -lambda_v (eq. 27), as angles. */
static void angles_from_costate(const ogk_real_t *lam, ogk_real_t *alpha, ogk_real_t *beta) /* NOLINT(bugprone-easily-swappable-parameters): internal helper, argument order of the equation it implements; every caller is in this file and unit-tested */
{
    const ogk_real_t l4 = lam[IDX_VR];
    const ogk_real_t l5 = lam[IDX_VR + 1u];
    const ogk_real_t l6 = lam[IDX_VR + 2u];
    const ogk_real_t in_plane = OGK_SQRT((l4 * l4) + (l5 * l5));
    *alpha = OGK_ATAN2(-l4, -l5);
    *beta = OGK_ATAN2(-l6, in_plane);
}

/* Angle between the thrust directions of two costate vectors. */
static ogk_real_t direction_angle(const ogk_real_t *lam_a, const ogk_real_t *lam_b)
{
    const ogk_real_t *a = &lam_a[IDX_VR];
    const ogk_real_t *b = &lam_b[IDX_VR];
    const ogk_real_t cx = (a[1] * b[2]) - (a[2] * b[1]);
    const ogk_real_t cy = (a[2] * b[0]) - (a[0] * b[2]);
    const ogk_real_t cz = (a[0] * b[1]) - (a[1] * b[0]);
    const ogk_real_t dot = (a[0] * b[0]) + (a[1] * b[1]) + (a[2] * b[2]);
    return OGK_ATAN2(OGK_SQRT((cx * cx) + (cy * cy) + (cz * cz)), dot);
}

static void costate_at(const ogk_nog_t *ctx, ogk_real_t tau, ogk_real_t *lam)
{
    ogk_real_t lam_star[NX];
    size_t i;
    hermite(&ctx->tbl, tau, OGK_NOG_OFF_LAM, OGK_NOG_OFF_LAMDOT, NX, lam_star);
    for (i = 0u; i < NX; ++i) {
        lam[i] = lam_star[i] + ctx->dlam_k[i] + (ctx->dlam_rate[i] * (tau - ctx->tau_k));
    }
}

/* Largest scale s in [0, 1] of the correction (dlam, dlam_rate) whose thrust
 * direction at tau_k stays within du_max of the nominal one (bisection: the
 * angle grows with s for the corrections met in practice; s = 0 always fits). */
static ogk_real_t direction_limit_scale(const ogk_real_t *lam_star, const ogk_real_t *dlam, ogk_real_t du_max)
{
    ogk_real_t lam[NX];
    ogk_real_t scale;
    size_t i;

    for (i = 0u; i < NX; ++i) {
        lam[i] = lam_star[i] + dlam[i];
    }
    if (direction_angle(lam, lam_star) <= du_max) {
        scale = OGK_R(1.0);
    } else {
        ogk_real_t lo = OGK_R(0.0);
        ogk_real_t hi = OGK_R(1.0);
        unsigned it;
        for (it = 0u; it < OGK_NOG_LIMIT_ITERATIONS; ++it) {
            const ogk_real_t mid = OGK_R(0.5) * (lo + hi);
            for (i = 0u; i < NX; ++i) {
                lam[i] = lam_star[i] + (mid * dlam[i]);
            }
            if (direction_angle(lam, lam_star) <= du_max) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        scale = lo;
    }
    return scale;
}

/* ------------------------------------------------------------------ API */

ogk_status ogk_nog_config_default(ogk_nog_config_t *cfg)
{
    ogk_status st = OGK_OK;

    if (cfg == NULL) {
        st = OGK_E_NULL;
    } else {
        (void)memset(cfg, 0, sizeof *cfg); /* returns cfg: nothing to check */
        cfg->table = NULL;
        cfg->view = NULL;
        cfg->sample_interval_s = OGK_R(2.0); /* Delta t_S of the paper's sec. 6 */
        cfg->dtf_max_s = OGK_R(40.0);        /* ~17 sigma of the paper's MC t_f spread (2.34 s) */
        cfg->du_max_rad = PI / OGK_R(3.0);   /* 60 deg */
        cfg->tau_freeze = OGK_R(0.0);        /* corrections up to the last gain node */
    }
    return st;
}

/* The just-initialised state: nominal from tau = 0, no sample taken. */
static void start_nominal(ogk_nog_t *ctx)
{
    ogk_real_t lam[NX];
    (void)memset(ctx->dlam_k, 0, sizeof ctx->dlam_k);       /* returns its first argument */
    (void)memset(ctx->dlam_rate, 0, sizeof ctx->dlam_rate); /* returns its first argument */
    ctx->t_k_s = OGK_R(0.0);
    ctx->tau_k = OGK_R(0.0);
    ctx->t_f_s = ctx->tbl.t_f_star_s;
    ctx->n_samples = 0u;
    ctx->flags = 0u;
    /* The held direction before any sample: the nominal at tau = 0 (finite:
     * at a node the Hermite is the node's finite value; 0 if not anyway). */
    costate_at(ctx, OGK_R(0.0), lam);
    angles_from_costate(lam, &ctx->hold_alpha_rad, &ctx->hold_beta_rad);
    if (!isfinite(ctx->hold_alpha_rad) || !isfinite(ctx->hold_beta_rad)) {
        ctx->hold_alpha_rad = OGK_R(0.0);
        ctx->hold_beta_rad = OGK_R(0.0);
    }
}

/* True while the table the context was initialised on is still the one it
 * holds pointers and sizes of: not reloaded since (generation), and still
 * valid. The generation is the check; the others are cheap belt and braces. */
static bool table_current(const ogk_nog_t *ctx)
{
    bool current;

    if (ctx->cfg.table != NULL) {
        current = (ctx->cfg.table->generation == ctx->table_generation) &&
                  (ctx->cfg.table->n_grid == ctx->tbl.n_grid);
    } else {
        /* cfg.view != NULL: with cfg.table NULL, ogk_nog_init required it */
        current = (ctx->cfg.view->generation == ctx->table_generation) &&
                  (ctx->cfg.view->init_marker == OGK_NOG_VIEW_MARKER) &&
                  (ctx->cfg.view->n_grid == ctx->tbl.n_grid) && (ctx->cfg.view->tau == ctx->tbl.tau);
    }
    return current;
}

/* The table cfg binds (exactly one of table and view), into tbl: the
 * binding checks of ogk_nog_init, in its order. */
static ogk_status bound_table(const ogk_nog_config_t *cfg, ogk_nog_table_view_t *tbl)
{
    ogk_status st = OGK_OK;

    if ((cfg->table == NULL) && (cfg->view == NULL)) {
        st = OGK_E_NULL;
    } else if ((cfg->table != NULL) && (cfg->view != NULL)) {
        st = OGK_E_CONFIG;
    } else if (cfg->table != NULL) {
        view_of_table(cfg->table, tbl);
    } else if (cfg->view->init_marker == OGK_NOG_VIEW_MARKER) {
        *tbl = *cfg->view;
    } else {
        st = OGK_E_NOT_INIT;
    }
    if ((st == OGK_OK) &&
        ((tbl->n_grid < 3u) || (tbl->n_grid > OGK_NOG_MAX_GRID) || (!(tbl->t_f_star_s > OGK_R(0.0))))) {
        st = OGK_E_NOT_INIT;
    }
    return st;
}

/* The configuration ranges of ogk/nog.h against the bound table. */
static bool nog_config_valid(const ogk_nog_config_t *cfg, const ogk_nog_table_view_t *tbl)
{
    return !(!isfinite(cfg->sample_interval_s) || !(cfg->sample_interval_s > OGK_R(0.0)) ||
             !isfinite(cfg->dtf_max_s) || !(cfg->dtf_max_s > OGK_R(0.0)) ||
             (cfg->dtf_max_s > (OGK_R(0.5) * tbl->t_f_star_s)) || (cfg->sample_interval_s > tbl->t_f_star_s) ||
             !isfinite(cfg->du_max_rad) || !(cfg->du_max_rad > OGK_R(0.0)) || (cfg->du_max_rad > PI) ||
             !isfinite(cfg->tau_freeze) || (cfg->tau_freeze < OGK_R(0.0)) || !(cfg->tau_freeze < OGK_R(1.0)));
}

ogk_status ogk_nog_init(ogk_nog_t *ctx, const ogk_nog_config_t *cfg)
{
    ogk_nog_table_view_t tbl;
    ogk_status st;

    if ((ctx == NULL) || (cfg == NULL)) {
        st = OGK_E_NULL;
    } else {
        (void)memset(ctx, 0, sizeof *ctx); /* returns ctx: nothing to check */
        st = bound_table(cfg, &tbl);
        if ((st == OGK_OK) && (!nog_config_valid(cfg, &tbl))) {
            st = OGK_E_CONFIG;
        }
        if (st == OGK_OK) {
            ctx->cfg = *cfg;
            ctx->tbl = tbl;
            ctx->table_generation = tbl.generation;
            start_nominal(ctx);
            ctx->init_marker = OGK_NOG_INIT_MARKER;
        }
    }
    return st;
}

ogk_status ogk_nog_reset(ogk_nog_t *ctx)
{
    ogk_status st = OGK_OK;

    if (ctx == NULL) {
        st = OGK_E_NULL;
    } else if (ctx->init_marker != OGK_NOG_INIT_MARKER) {
        st = OGK_E_NOT_INIT;
    } else if (!table_current(ctx)) {
        st = OGK_E_TABLE_STALE; /* the nominal at tau = 0 would be read from it */
    } else {
        start_nominal(ctx);
    }
    return st;
}

/* Moves the current sample to (t_s, tau) keeping the correction in force
 * (dlam continued from its hold, then held constant; t_f unchanged). */
static void hold_correction(ogk_nog_t *ctx, ogk_real_t t_s, ogk_real_t tau) /* NOLINT(bugprone-easily-swappable-parameters): internal helper, argument order of the equation it implements; every caller is in this file and unit-tested */
{
    size_t i;
    for (i = 0u; i < NX; ++i) {
        ctx->dlam_k[i] += ctx->dlam_rate[i] * (tau - ctx->tau_k);
        ctx->dlam_rate[i] = OGK_R(0.0);
    }
    ctx->t_k_s = t_s;
    ctx->tau_k = tau;
}

/* The sample fields that need no table: tau, t_f, cut-off, flags; the
 * angles are the held ones (overwritten by fill_sample). */
static void fill_sample_held(const ogk_nog_t *ctx, ogk_nog_sample_t *out)
{
    out->tau_k = ctx->tau_k;
    out->t_f_s = ctx->t_f_s;
    out->dt_f_s = ctx->t_f_s - ctx->tbl.t_f_star_s;
    out->tau_next = ctx->tau_k + (ctx->cfg.sample_interval_s / ctx->t_f_s);
    out->t_cutoff_s = ctx->t_k_s + (OGK_R(1.0) - ctx->tau_k) * ctx->t_f_s;
    out->alpha_rad = ctx->hold_alpha_rad;
    out->beta_rad = ctx->hold_beta_rad;
    out->flags = ctx->flags;
    if (out->tau_next >= OGK_R(1.0)) {
        out->flags |= OGK_NOG_FLAG_TERMINATING;
    }
    if (ctx->tau_k >= OGK_R(1.0)) {
        out->flags |= OGK_NOG_FLAG_CUTOFF;
    }
}

static void fill_sample(const ogk_nog_t *ctx, ogk_nog_sample_t *out)
{
    ogk_real_t lam[NX];
    const ogk_real_t tau = OGK_FMIN(ctx->tau_k, OGK_R(1.0));

    fill_sample_held(ctx, out);
    costate_at(ctx, tau, lam);
    angles_from_costate(lam, &out->alpha_rad, &out->beta_rad);
}

/* Every double of a sample is finite. */
static bool sample_finite(const ogk_nog_sample_t *out)
{
    const ogk_real_t v[7] = {out->tau_k, out->tau_next, out->t_f_s, out->dt_f_s,
                         out->t_cutoff_s, out->alpha_rad, out->beta_rad};
    return ogk_i_all_finite(v, 7u) && ogk_i_all_finite(out->dx, NX);
}

/* Latest time a sample may carry (the t_s envelope of ogk/nog.h). */
static ogk_real_t t_sample_max(const ogk_nog_t *ctx)
{
    return (OGK_R(2.0) * ctx->tbl.t_f_star_s) + ctx->cfg.dtf_max_s;
}

/* The navigation envelope of ogk/nog.h (all values already finite). */
static bool nog_nav_in_envelope(const ogk_nog_t *ctx, const ogk_nav_state_t *nav)
{
    return (nav->r_m > OGK_R(0.0)) && (nav->r_m <= OGK_NOG_R_MAX_M) &&
           (OGK_FABS(nav->xi_rad) <= OGK_NOG_XI_MAX_RAD) && (OGK_FABS(nav->phi_rad) < OGK_NOG_PHI_MAX_RAD) &&
           (OGK_FABS(nav->v_r_mps) <= OGK_NOG_V_MAX_MPS) && (OGK_FABS(nav->v_t_mps) <= OGK_NOG_V_MAX_MPS) &&
           (OGK_FABS(nav->v_n_mps) <= OGK_NOG_V_MAX_MPS) && (nav->t_s >= OGK_R(0.0)) &&
           (nav->t_s <= t_sample_max(ctx));
}

/* The safe output of a rejected sample (contract in ogk/nog.h): the
 * correction in force, held, at t_s when that time is usable. A usable time
 * up to the predicted cut-off (tau <= 1) moves the context there (dlam
 * continued to it and held, t_f kept), as a good sample would; a time past
 * the cut-off (tau > 1, still inside the envelope) is only shown, on a copy:
 * a wrong time tag must not stop the engine early. An unusable time (not
 * finite, outside the envelope, before the current sample) moves nothing.
 * With a stale table (readable = false) nothing is read from it: held angles. */
static void safe_sample(ogk_nog_t *ctx, ogk_real_t t_s, bool readable, ogk_nog_sample_t *out)
{
    ogk_nog_t at;

    ctx->flags = OGK_NOG_FLAG_SAFE;
    /* t_s >= 0 follows from t_s >= t_k_s >= 0 (t_k_s starts at 0 and takes only
     * times that passed this test or nog_nav_in_envelope's t_s >= 0) */
    if (isfinite(t_s) && (t_s >= ctx->t_k_s) && (t_s <= t_sample_max(ctx))) {
        /* Bounded by the envelope: finite. */
        /* tau >= tau_k as t_s >= t_k_s: the fmax changes no value and
         * keeps tau_k in [0, 1] visible to the analysis (docs/evidence/eva.md). */
        const ogk_real_t tau = OGK_FMAX(ctx->tau_k + ((t_s - ctx->t_k_s) / ctx->t_f_s), ctx->tau_k);
        if (tau <= OGK_R(1.0)) {
            hold_correction(ctx, t_s, tau);
            at = *ctx;
        } else {
            at = *ctx;
            hold_correction(&at, t_s, tau); /* shown, clamped to 1 in the costate */
        }
    } else {
        at = *ctx;
    }
    if (readable) {
        fill_sample(&at, out);
    }
    if ((!readable) || (!sample_finite(out))) {
        fill_sample_held(&at, out);
        if (!sample_finite(out)) {
            fill_sample_held(ctx, out); /* the last good sample's own values */
        }
    }
}

/* The bounds of compute_correction on the finite gain products out8
 * (dlam, dt_f) and dlam_rate, then the correction into ctx. */
static void apply_correction(ogk_nog_t *ctx, const ogk_real_t *out8, const ogk_real_t *dlam_rate) /* NOLINT(bugprone-easily-swappable-parameters): internal helper, argument order of the equation it implements; every caller is in this file and unit-tested */
{
    const ogk_nog_table_view_t *tbl = &ctx->tbl;
    ogk_real_t lam_star[NX];
    ogk_real_t dt_f;
    ogk_real_t scale;
    size_t i;

    /* dt_f clipped to [-dtf_max, dtf_max] (finite: compute_correction
     * checked it), so t_f >= t_f* - dtf_max >= t_f* / 2 > 0 (init's check). */
    dt_f = OGK_FMIN(OGK_FMAX(out8[NX], -ctx->cfg.dtf_max_s), ctx->cfg.dtf_max_s);
    if (dt_f != out8[NX]) {
        ctx->flags |= OGK_NOG_FLAG_LIMITED;
    }
    hermite(tbl, ctx->tau_k, OGK_NOG_OFF_LAM, OGK_NOG_OFF_LAMDOT, NX, lam_star);
    scale = direction_limit_scale(lam_star, out8, ctx->cfg.du_max_rad);
    if (scale < OGK_R(1.0)) {
        ctx->flags |= OGK_NOG_FLAG_LIMITED;
    }
    for (i = 0u; i < NX; ++i) {
        ctx->dlam_k[i] = scale * out8[i];
        ctx->dlam_rate[i] = scale * dlam_rate[i];
    }
    ctx->t_f_s = tbl->t_f_star_s + dt_f;
}

/* out[rows] = a[rows x NX] dx: the gain products of the correction, whose sizes
 * are this file's constants and whose arrays are distinct locals, so nothing can
 * fail (ogk_mat_vec's checks, and its status, would be dead code here: its
 * discarded status once left out8 unproven-initialised for EVA, docs/evidence/eva.md). */
static void gain_times_dx(const ogk_real_t *a, size_t rows, const ogk_real_t *dx, ogk_real_t *out)
{
    size_t i;
    size_t j;
    for (i = 0u; i < rows; ++i) {
        ogk_real_t acc = OGK_R(0.0);
        for (j = 0u; j < NX; ++j) {
            acc += a[(i * NX) + j] * dx[j];
        }
        out[i] = acc;
    }
}

/* The correction at tau_k from the gains (eqs. 29-31) with the end-game
 * bounds. False (context untouched) when the gains times dx overflow. */
static bool compute_correction(ogk_nog_t *ctx, const ogk_real_t *dx)
{
    const ogk_nog_table_view_t *tbl = &ctx->tbl;
    ogk_real_t gain[N_GAIN_ROWS * NX];
    ogk_real_t nrate[NX * NX];
    ogk_real_t out8[N_GAIN_ROWS];
    ogk_real_t dlam_rate[NX];
    bool finite = true;

    linear_block(tbl, ctx->tau_k, OGK_NOG_OFF_GAIN, (size_t)N_GAIN_ROWS * NX, gain);
    linear_block(tbl, ctx->tau_k, OGK_NOG_OFF_NRATE, (size_t)NX * NX, nrate);
    gain_times_dx(gain, N_GAIN_ROWS, dx, out8);
    gain_times_dx(nrate, NX, dx, dlam_rate);
    if (!ogk_i_all_finite(out8, N_GAIN_ROWS) || !ogk_i_all_finite(dlam_rate, NX)) {
        finite = false; /* finite gains and dx whose products overflow */
    } else {
        apply_correction(ctx, out8, dlam_rate);
    }
    return finite;
}

/* ogk_nog_sample from a finite, in-envelope sample at tau <= 1: the
 * correction (or the end-game hold) committed, or the safe output. */
static ogk_status take_sample(ogk_nog_t *ctx, const ogk_nav_state_t *nav, const ogk_real_t *nav_v,
                              ogk_real_t tau, ogk_nog_sample_t *out)
{
    const ogk_nog_table_view_t *tbl = &ctx->tbl;
    ogk_nog_t before;
    bool good = true;
    ogk_status st = OGK_OK;

    before = *ctx;
    ctx->flags = 0u;
    ctx->n_samples += 1u;
    /* End-game: past the last node with gains, or inside the freeze margin. */
    if ((tau >= tbl->tau[tbl->n_grid - 2u]) || ((OGK_R(1.0) - tau) < ctx->cfg.tau_freeze)) {
        hold_correction(ctx, nav->t_s, tau);
        ctx->flags = OGK_NOG_FLAG_FROZEN;
        fill_sample(ctx, out);
    } else {
        ogk_real_t x_star[NX];
        ogk_real_t dx[NX];
        size_t i;
        ctx->t_k_s = nav->t_s;
        ctx->tau_k = tau;
        hermite(tbl, tau, OGK_NOG_OFF_X, OGK_NOG_OFF_XDOT, NX, x_star);
        for (i = 0u; i < NX; ++i) {
            dx[i] = nav_v[i] - x_star[i];
        }
        dx[IDX_XI] = ogk_i_wrap_pi(dx[IDX_XI]);
        /* x*[6] = t_f* tau: dx[6] is the real-time mismatch t_k - t_f* tau_k. */
        good = compute_correction(ctx, dx);
        if (good) {
            fill_sample(ctx, out);
            (void)memcpy(out->dx, dx, sizeof dx); /* returns out->dx: nothing to check */
        }
    }
    if (!good || !sample_finite(out)) {
        /* Finite input, non-finite correction or output: back to the last
         * good sample, and its correction is what flies. */
        *ctx = before;
        (void)memset(out, 0, sizeof *out); /* returns out: nothing to check */
        safe_sample(ctx, nav->t_s, true, out);
        st = OGK_E_SAFE_COMMAND;
    } else {
        ctx->hold_alpha_rad = out->alpha_rad;
        ctx->hold_beta_rad = out->beta_rad;
    }
    return st;
}

/* ogk_nog_sample on an initialised context bound to a current table. */
static ogk_status sample_current(ogk_nog_t *ctx, const ogk_nav_state_t *nav, ogk_nog_sample_t *out)
{
    const ogk_nog_table_view_t *tbl = &ctx->tbl;
    ogk_real_t nav_v[NX];
    ogk_real_t tau;
    ogk_status st;

    nav_v[0] = nav->r_m;
    nav_v[1] = nav->xi_rad;
    nav_v[2] = nav->phi_rad;
    nav_v[3] = nav->v_r_mps;
    nav_v[4] = nav->v_t_mps;
    nav_v[5] = nav->v_n_mps;
    nav_v[6] = nav->t_s;

    if (!ogk_i_all_finite(nav_v, NX)) {
        safe_sample(ctx, nav->t_s, true, out);
        st = OGK_E_NONFINITE;
    } else if ((!nog_nav_in_envelope(ctx, nav)) || ((ctx->n_samples > 0u) && (!(nav->t_s > ctx->t_k_s)))) {
        /* Envelope before any arithmetic: the time bound keeps tau and the
         * cut-off time finite, the others keep gains times dx far from overflow. */
        safe_sample(ctx, nav->t_s, true, out);
        st = OGK_E_RANGE;
    } else {
        /* tau >= tau_k (t_s > t_k_s after the first sample): the fmax, as in
         * safe_sample, changes no value. */
        tau = (ctx->n_samples == 0u) ? (nav->t_s / tbl->t_f_star_s)
                                     : OGK_FMAX(ctx->tau_k + ((nav->t_s - ctx->t_k_s) / ctx->t_f_s), ctx->tau_k);
        if (tau > OGK_R(1.0)) {
            /* Sampled after the predicted cut-off (tau outside [0, 1]): nothing to
             * guide, and nothing to commit (a wrong time tag must not stop the
             * engine; the commands stop it at the predicted cut-off anyway). */
            safe_sample(ctx, nav->t_s, true, out);
            st = OGK_E_RANGE;
        } else {
            st = take_sample(ctx, nav, nav_v, tau, out);
        }
    }
    return st;
}

ogk_status ogk_nog_sample(ogk_nog_t *ctx, const ogk_nav_state_t *nav, ogk_nog_sample_t *out)
{
    ogk_status st;

    if ((ctx == NULL) || (nav == NULL) || (out == NULL)) {
        st = OGK_E_NULL;
    } else {
        (void)memset(out, 0, sizeof *out); /* returns out: nothing to check */
        if (ctx->init_marker != OGK_NOG_INIT_MARKER) {
            st = OGK_E_NOT_INIT;
        } else if (!table_current(ctx)) {
            /* Reloaded since init (maybe failed: n_grid = 0): not one read of it. */
            safe_sample(ctx, nav->t_s, false, out);
            st = OGK_E_TABLE_STALE;
        } else {
            st = sample_current(ctx, nav, out);
        }
    }
    return st;
}

/* tau of eq. (31) at t_s with the t_f in force; st receives the input check. */
static ogk_real_t tau_at(const ogk_nog_t *ctx, ogk_real_t t_s, ogk_status *st)
{
    if (!isfinite(t_s)) {
        *st = OGK_E_NONFINITE;
    } else if (t_s < ctx->t_k_s) {
        *st = OGK_E_RANGE;
    } else {
        *st = OGK_OK;
    }
    /* t_s - t_k_s is finite (both finite, t_s >= t_k_s >= 0) and t_f >=
     * t_f* / 2 > 0: tau is finite or +inf, and +inf is clamped to 1. */
    return (*st == OGK_OK) ? ctx->tau_k + (t_s - ctx->t_k_s) / ctx->t_f_s : ctx->tau_k;
}

/* ogk_nog_thrust_cmd on an initialised context. */
static ogk_status command_at(const ogk_nog_t *ctx, ogk_real_t t_s, ogk_thrust_cmd_t *out)
{
    ogk_real_t tau;
    ogk_real_t alpha;
    ogk_real_t beta;
    uint32_t law;
    uint32_t flags = OGK_THRUST_FLAG_ENGINE_ON;
    ogk_status st;
    bool readable;

    readable = table_current(ctx);
    tau = tau_at(ctx, t_s, &st);
    law = ctx->flags & (OGK_NOG_FLAG_FROZEN | OGK_NOG_FLAG_LIMITED | OGK_NOG_FLAG_SAFE);
    if (!readable) {
        st = OGK_E_TABLE_STALE; /* the cut-off time above needs no table */
    }
    if (st != OGK_OK) {
        law |= OGK_NOG_FLAG_SAFE;
    }
    if (tau >= OGK_R(1.0)) {
        tau = OGK_R(1.0);
        law |= OGK_NOG_FLAG_CUTOFF;
        flags = 0u;
    }
    alpha = ctx->hold_alpha_rad;
    beta = ctx->hold_beta_rad;
    if (readable) {
        ogk_real_t lam[NX];
        costate_at(ctx, tau, lam);
        angles_from_costate(lam, &alpha, &beta);
        if (!isfinite(alpha) || !isfinite(beta)) {
            alpha = ctx->hold_alpha_rad;
            beta = ctx->hold_beta_rad;
            law |= OGK_NOG_FLAG_SAFE;
            if (st == OGK_OK) {
                st = OGK_E_SAFE_COMMAND;
            }
        }
    }
    if ((law & OGK_NOG_FLAG_SAFE) != 0u) {
        flags |= OGK_THRUST_FLAG_SAFE;
    }
    if ((law & OGK_NOG_FLAG_LIMITED) != 0u) {
        flags |= OGK_THRUST_FLAG_LIMITED;
    }
    /* the r-t-n command (full thrust while the engine is on) */
    ogk_i_thrust_cmd_angles(out, (isfinite(t_s) && (t_s >= ctx->t_k_s)) ? t_s : ctx->t_k_s, alpha,
                            beta, OGK_R(1.0), flags, law);
    return st;
}

ogk_status ogk_nog_thrust_cmd(const ogk_nog_t *ctx, ogk_real_t t_s, ogk_thrust_cmd_t *out)
{
    ogk_status st;

    if ((ctx == NULL) || (out == NULL)) {
        st = OGK_E_NULL;
    } else if (ctx->init_marker != OGK_NOG_INIT_MARKER) {
        /* no engine-on flag from an uninitialised context: the safe command */
        ogk_i_thrust_cmd_safe(out, t_s, OGK_FRAME_RTN, OGK_NOG_FLAG_SAFE);
        st = OGK_E_NOT_INIT;
    } else {
        st = command_at(ctx, t_s, out);
    }
    return st;
}

ogk_status ogk_nog_tau_at(const ogk_nog_t *ctx, ogk_real_t t_s, ogk_real_t *tau)
{
    ogk_status st;
    ogk_real_t v;

    if ((ctx == NULL) || (tau == NULL)) {
        st = OGK_E_NULL;
    } else if (ctx->init_marker != OGK_NOG_INIT_MARKER) {
        st = OGK_E_NOT_INIT;
    } else if (!table_current(ctx)) {
        st = OGK_E_TABLE_STALE;
    } else {
        v = tau_at(ctx, t_s, &st);
        if (st == OGK_OK) {
            *tau = OGK_FMIN(v, OGK_R(1.0));
        }
    }
    return st;
}
