/* test_nog_input_checks.c -- VTD-NOG paths test_nog.c leaves unrun (make coverage, docs/evidence/coverage.md):
 * the table content checks one by one, NULL and uninitialised arguments of every entry point,
 * each configuration bound, bound structs that are not what init accepted (hand-edited or
 * overwritten by a copy of another table), the freeze margin, an overflowing costate-rate gain,
 * and a table whose costate went bad in RAM after it was validated.
 *
 * The table is the closed-form one of test_nog.c (straight-line nominal, constant costate with
 * thrust angle ALPHA0, sparse gains), written here again with the nodes as a parameter, in the
 * build's element type (table_writer.h). Float tolerances: angles 4 eps (ANG_EPS, test_nog.c),
 * tau one rounding of the quotient, bounds crossed by 2 eps. */
#include "ogk_test.h"

#include <float.h>
#include <string.h>

#include "ogk/nog.h"
#include "nog_fixture.h"
#include "table_writer.h"

#define GRID_MAX 5u
#define N_VALUES(n) ((n) * (1u + OGK_NOG_ENTRY_LEN))
#define TABLE_BYTES(n) (OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * N_VALUES(n))
#define ROW(n, k, i) (OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * ((n) + (k) * OGK_NOG_ENTRY_LEN + (i)))
#define ANG_EPS (4.0 * FLT_EPSILON) /* float: an angle from the unit costate */
/* The 4-node table's t_f*: 96 s in float, where t_f* k / 3 is exact (test_table_content_rejections) */
#define TF_STAR_THIRDS OGK_TEST_PICK(TF_STAR, 96.0)


/* Two table images (5 and 4 nodes), 8-byte aligned for the in-place view. */
static union {
    double align;
    uint8_t b[TABLE_BYTES(GRID_MAX)];
} img5, img4, img5b;
static ogk_nog_table_t table;
static ogk_nog_table_t table_other; /* loaded once, never bound: a struct to copy over */
static ogk_nog_t nog;

/* n nodes at tau = k / (n - 1), time state and its rate scaled by t_f (so t_f* = t_f). */
static void build(uint8_t *buf, uint32_t n, double t_f)
{
    const uint32_t dims[1] = {OGK_NOG_ENTRY_LEN};
    uint32_t k;
    size_t i;
    (void)memset(buf, 0, TABLE_BYTES(n));
    tw_header(buf, OGK_NOG_TABLE_KIND, 1u, dims, n);
    for (k = 0u; k < n; ++k) {
        const double tau = (double)k / (double)(n - 1u);
        double row[OGK_NOG_ENTRY_LEN];
        (void)memset(row, 0, sizeof row);
        nominal_state(tau, &row[OGK_NOG_OFF_X]);
        row[OGK_NOG_OFF_X + 6u] = t_f * tau;
        for (i = 0u; i < 7u; ++i) {
            row[OGK_NOG_OFF_XDOT + i] = x_rate[i];
        }
        row[OGK_NOG_OFF_XDOT + 6u] = t_f;
        row[OGK_NOG_OFF_LAM + 3u] = -sin(ALPHA0);
        row[OGK_NOG_OFF_LAM + 4u] = -cos(ALPHA0);
        if (k + 1u < n) {
            row[OGK_NOG_OFF_GAIN + 5u * 7u + 5u] = K_L6_VN;
        }
        tw_put_real(buf + OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * k, tau);
        for (i = 0u; i < OGK_NOG_ENTRY_LEN; ++i) {
            tw_put_real(buf + ROW(n, k, i), row[i]);
        }
    }
    tw_seal(buf, N_VALUES(n));
}

static ogk_nog_config_t config(void)
{
    return nog_fixture_config(&table);
}

static ogk_nog_nav_t nav_at(ogk_real_t t, ogk_real_t tau)
{
    return nog_fixture_nav_at(t, tau);
}

static int setup(void **state)
{
    ogk_nog_config_t cfg;
    (void)state;
    build(img5.b, 5u, TF_STAR);
    if (ogk_nog_table_load(&table, img5.b, TABLE_BYTES(5u)) != OGK_OK) {
        return -1;
    }
    cfg = config();
    return (ogk_nog_init(&nog, &cfg) == OGK_OK) ? 0 : -1;
}

/* Loads the damaged image, expects the status and an emptied table. */
static void expect_load(ogk_status expected)
{
    tw_seal(img5.b, N_VALUES(5u));
    OGK_ASSERT_STATUS(ogk_nog_table_load(&table, img5.b, TABLE_BYTES(5u)), expected);
    assert_int_equal(table.n_grid, 0u);
    OGK_ASSERT_NEAR(table.t_f_star_s, 0.0, 0.0);
}

/* req: OGK-NOG-001 */
static void test_table_content_rejections(void **state)
{
    size_t k;
    (void)state;
    OGK_ASSERT_STATUS(ogk_nog_table_load(NULL, img5.b, TABLE_BYTES(5u)), OGK_E_NULL);
    /* grid not strictly increasing (node 2 repeats node 1) */
    tw_put_real(img5.b + OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * 2u, 0.25);
    expect_load(OGK_E_TABLE_DIM);
    /* grid not starting at tau = 0 */
    build(img5.b, 5u, TF_STAR);
    tw_put_real(img5.b + OGK_TABLE_HEADER_SIZE, 0.1);
    expect_load(OGK_E_TABLE_DIM);
    /* t_f* = 0 and t_f* over OGK_NOG_TF_MAX_S (consistent in every row) */
    build(img5.b, 5u, 0.0);
    expect_load(OGK_E_TABLE_TYPE);
    build(img5.b, 5u, 2.0 * OGK_NOG_TF_MAX_S);
    expect_load(OGK_E_TABLE_TYPE);
    /* the time state of node 2 is not t_f* tau */
    build(img5.b, 5u, TF_STAR);
    tw_put_real(img5.b + ROW(5u, 2u, OGK_NOG_OFF_X + 6u), 0.5 * TF_STAR + 1e-3);
    expect_load(OGK_E_TABLE_TYPE);
    /* a node with r <= 0 */
    build(img5.b, 5u, TF_STAR);
    tw_put_real(img5.b + ROW(5u, 3u, OGK_NOG_OFF_X), 0.0);
    expect_load(OGK_E_TABLE_TYPE);
    /* and the undamaged image loads */
    build(img5.b, 5u, TF_STAR);
    OGK_ASSERT_STATUS(ogk_nog_table_load(&table, img5.b, TABLE_BYTES(5u)), OGK_OK);
    assert_int_equal(table.n_grid, 5u);
    for (k = 0u; k < 5u; ++k) {
        OGK_ASSERT_NEAR(table.tau[k], 0.25 * (double)k, 0.0);
    }
#if OGK_REAL_SINGLE
    /* Float: a table on the grid k / 3 with t_f* = 100 s, each time state t_f* tau rounded
     * once to float, differs from the kernel's float product t_f* tau(k) by an ulp (3.8e-6 s
     * at 33 s): consistent within OGK_NOG_TF_CONSISTENCY (4 eps t_f*, nog.c), it loads, as
     * does t_f* = 96 s, where each t_f* tau is exact. A time state 8 eps t_f* off (two ulps
     * beyond the tolerance) is refused. */
    build(img4.b, 4u, TF_STAR);
    OGK_ASSERT_STATUS(ogk_nog_table_load(&table_other, img4.b, TABLE_BYTES(4u)), OGK_OK);
    build(img4.b, 4u, TF_STAR_THIRDS);
    OGK_ASSERT_STATUS(ogk_nog_table_load(&table_other, img4.b, TABLE_BYTES(4u)), OGK_OK);
    build(img4.b, 4u, TF_STAR);
    tw_put_real(img4.b + ROW(4u, 2u, OGK_NOG_OFF_X + 6u),
                (2.0 / 3.0) * TF_STAR + 8.0 * (double)FLT_EPSILON * TF_STAR);
    tw_seal(img4.b, N_VALUES(4u));
    OGK_ASSERT_STATUS(ogk_nog_table_load(&table_other, img4.b, TABLE_BYTES(4u)), OGK_E_TABLE_TYPE);
#endif
}

/* req: OGK-NOG-004 OGK-NOG-012 */
static void test_null_and_uninitialised(void **state)
{
    ogk_nog_t zero;
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    ogk_thrust_cmd_t c;
    ogk_real_t tau = -7.0;
    (void)state;
    (void)memset(&zero, 0, sizeof zero);
    OGK_ASSERT_STATUS(ogk_nog_init(&zero, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nog_sample(NULL, &nav, &s), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, NULL, &s), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, NULL), OGK_E_NULL);
    assert_int_equal(nog.n_samples, 0u); /* nothing taken */
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(NULL, 1.0, &c), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&nog, 1.0, NULL), OGK_E_NULL);
    (void)memset(&c, 0x5A, sizeof c);
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&zero, 1.0, &c), OGK_E_NOT_INIT);
    /* the safe command: no engine-on flag from an uninitialised context */
    assert_int_equal(c.flags, OGK_THRUST_FLAG_SAFE);
    assert_int_equal(c.law_flags, OGK_NOG_FLAG_SAFE);
    assert_int_equal((int)c.frame, (int)OGK_FRAME_RTN);
    OGK_ASSERT_NEAR(c.alpha_rad, 0.0, 0.0);
    OGK_ASSERT_NEAR(c.beta_rad, 0.0, 0.0);
    OGK_ASSERT_NEAR(c.u[0], 0.0, 0.0);
    OGK_ASSERT_NEAR(c.u[1], 1.0, 0.0);
    OGK_ASSERT_NEAR(c.u[2], 0.0, 0.0);
    OGK_ASSERT_NEAR(c.throttle, 0.0, 0.0);
    OGK_ASSERT_NEAR(c.t_s, 1.0, 0.0);
    OGK_ASSERT_STATUS(ogk_nog_tau_at(NULL, 1.0, &tau), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nog_tau_at(&zero, 1.0, &tau), OGK_E_NOT_INIT);
    OGK_ASSERT_NEAR(tau, -7.0, 0.0);
    OGK_ASSERT_STATUS(ogk_nog_tau_at(&nog, 1.0, &tau), OGK_OK);
    OGK_ASSERT_NEAR(tau, 1.0 / TF_STAR, OGK_TEST_TOL(1e-17, 2.0 * FLT_EPSILON * 0.01));
}

/* Every bound of ogk_nog_config_t on its own (ogk/nog.h). */
/* req: OGK-NOG-004 */
static void test_config_bounds(void **state)
{
    ogk_nog_t ctx;
    unsigned k;
    (void)state;
    for (k = 0u; k < 10u; ++k) {
        ogk_nog_config_t cfg = config();
        switch (k) {
        case 0u: cfg.sample_interval_s = NAN; break;
        case 1u: cfg.sample_interval_s = TF_STAR * (1.0 + OGK_TEST_TOL(1e-15, 2.0 * FLT_EPSILON)); break; /* > t_f* */
        case 2u: cfg.dtf_max_s = INFINITY; break;
        case 3u: cfg.dtf_max_s = -1.0; break;
        case 4u: cfg.du_max_rad = 0.0; break;
        case 5u: cfg.du_max_rad = OGK_TEST_NEXTAFTER(3.141592653589793, 4.0); break; /* next real above pi */
        case 6u: cfg.tau_freeze = NAN; break;
        case 7u: cfg.tau_freeze = -OGK_REAL_MIN; break;
        case 8u: cfg.sample_interval_s = -2.0; break;
        default: cfg.dtf_max_s = 0.0; break;
        }
        (void)memset(&ctx, 0x5A, sizeof ctx);
        OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_E_CONFIG);
        assert_true(ctx.init_marker != OGK_NOG_INIT_MARKER);
    }
    {
        /* on the bounds: accepted */
        ogk_nog_config_t cfg = config();
        cfg.sample_interval_s = TF_STAR;
        cfg.dtf_max_s = 0.5 * TF_STAR;
        cfg.du_max_rad = 3.141592653589793;
        OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_OK);
    }
}

/* A view or table struct is caller memory: one edited by hand (marker kept) is refused. */
/* req: OGK-NOG-003 OGK-NOG-004 */
static void test_bound_struct_out_of_range(void **state)
{
    ogk_nog_table_view_t view;
    ogk_nog_table_view_t edited;
    ogk_nog_config_t cfg = config();
    ogk_nog_t ctx;
    (void)state;
    (void)memset(&view, 0, sizeof view);
    OGK_ASSERT_STATUS(ogk_nog_table_view(&view, img5.b, TABLE_BYTES(5u)), OGK_TEST_VIEW_OK);
    if (OGK_TEST_BIG_ENDIAN) {
        return; /* no in-place view on this target (test_nog's test_table_view_in_place) */
    }
    cfg.table = NULL;
    cfg.view = &edited;
    edited = view;
    edited.n_grid = OGK_NOG_MAX_GRID + 1u;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_E_NOT_INIT);
    edited = view;
    edited.t_f_star_s = 0.0;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_E_NOT_INIT);
    edited = view;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_OK);
}

static void expect_stale(ogk_nog_t *ctx)
{
    ogk_nog_nav_t nav = nav_at(10.0, 0.1);
    ogk_nog_sample_t s;
    ogk_thrust_cmd_t c;
    OGK_ASSERT_STATUS(ogk_nog_sample(ctx, &nav, &s), OGK_E_TABLE_STALE);
    assert_true((s.flags & OGK_NOG_FLAG_SAFE) != 0u);
    OGK_ASSERT_NEAR(s.alpha_rad, ALPHA0, OGK_TEST_TOL(1e-12, ANG_EPS)); /* the held (nominal) direction */
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(ctx, 11.0, &c), OGK_E_TABLE_STALE);
    assert_true((c.flags & OGK_THRUST_FLAG_SAFE) != 0u);
    OGK_ASSERT_NEAR(c.alpha_rad, ALPHA0, OGK_TEST_TOL(1e-12, ANG_EPS));
}

/* The views of test_stale_after_struct_copy copied over the bound one (little-endian targets:
 * elsewhere there is no in-place view to bind). */
static void stale_views(const ogk_nog_table_view_t *v5, const ogk_nog_table_view_t *v4,
                        const ogk_nog_table_view_t *v5b, const ogk_nog_table_view_t *failed)
{
    ogk_nog_table_view_t bound;
    ogk_nog_config_t cfg = config();
    ogk_nog_t ctx;
    cfg.table = NULL;
    cfg.view = &bound;
    /* a failed view copied over it (no marker) */
    bound = *v5;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_OK);
    bound = *failed;
    expect_stale(&ctx);
    /* a good view of another grid size */
    bound = *v5;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_OK);
    bound = *v4;
    expect_stale(&ctx);
    /* a good view of the same size in other bytes */
    bound = *v5;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_OK);
    bound = *v5b;
    expect_stale(&ctx);
}

/* A bound view or table overwritten by a struct copy of another one that happens to carry
 * the same generation count: the generation alone does not see it, the other fields do. */
/* req: OGK-NOG-003 */
static void test_stale_after_struct_copy(void **state)
{
    ogk_nog_table_view_t v5;
    ogk_nog_table_view_t v4;
    ogk_nog_table_view_t v5b;
    ogk_nog_table_view_t failed;
    ogk_nog_config_t cfg = config();
    ogk_nog_t ctx;
    (void)state;
    build(img4.b, 4u, TF_STAR_THIRDS);
    (void)memcpy(img5b.b, img5.b, TABLE_BYTES(5u));
    (void)memset(&v5, 0, sizeof v5);
    (void)memset(&v4, 0, sizeof v4);
    (void)memset(&v5b, 0, sizeof v5b);
    (void)memset(&failed, 0, sizeof failed);
    OGK_ASSERT_STATUS(ogk_nog_table_view(&v5, img5.b, TABLE_BYTES(5u)), OGK_TEST_VIEW_OK);
    OGK_ASSERT_STATUS(ogk_nog_table_view(&v4, img4.b, TABLE_BYTES(4u)), OGK_TEST_VIEW_OK);
    OGK_ASSERT_STATUS(ogk_nog_table_view(&v5b, img5b.b, TABLE_BYTES(5u)), OGK_TEST_VIEW_OK);
    OGK_ASSERT_STATUS(ogk_nog_table_view(&failed, img5.b, 20u), OGK_E_TABLE_TRUNCATED);
    assert_int_equal(failed.generation, v5.generation); /* all viewed once */
    if (!OGK_TEST_BIG_ENDIAN) {
        stale_views(&v5, &v4, &v5b, &failed);
    }
    /* the RAM table: a copy of another table loaded as often, of another grid size */
    build(img5.b, 5u, TF_STAR);
    OGK_ASSERT_STATUS(ogk_nog_table_load(&table_other, img4.b, TABLE_BYTES(4u)), OGK_OK);
    while (table.generation < table_other.generation) {
        OGK_ASSERT_STATUS(ogk_nog_table_load(&table, img5.b, TABLE_BYTES(5u)), OGK_OK);
    }
    while (table_other.generation < table.generation) {
        OGK_ASSERT_STATUS(ogk_nog_table_load(&table_other, img4.b, TABLE_BYTES(4u)), OGK_OK);
    }
    cfg = config();
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_OK);
    table = table_other;
    expect_stale(&ctx);
}

/* 1 - tau < tau_freeze before the last gain node: frozen, the gains are not used. */
/* req: OGK-NOG-009 */
static void test_freeze_margin(void **state)
{
    ogk_nog_config_t cfg = config();
    ogk_nog_t ctx;
    ogk_nog_nav_t nav;
    ogk_nog_sample_t s;
    (void)state;
    cfg.tau_freeze = 0.5;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_OK);
    nav = nav_at(40.0, 0.4);
    nav.v_n_mps = 2.0; /* 1 - 0.4 >= 0.5: corrected, dlam_vn = 0.02 */
    OGK_ASSERT_STATUS(ogk_nog_sample(&ctx, &nav, &s), OGK_OK);
    assert_true((s.flags & OGK_NOG_FLAG_FROZEN) == 0u);
    OGK_ASSERT_NEAR(s.beta_rad, atan2(-K_L6_VN * 2.0, 1.0), OGK_TEST_TOL(1e-14, ANG_EPS));
    nav = nav_at(60.0, 0.6);
    nav.v_n_mps = 50.0; /* 1 - 0.6 < 0.5 (and 0.6 < 0.75, the last gain node): frozen */
    OGK_ASSERT_STATUS(ogk_nog_sample(&ctx, &nav, &s), OGK_OK);
    assert_true((s.flags & OGK_NOG_FLAG_FROZEN) != 0u);
    OGK_ASSERT_NEAR(s.beta_rad, atan2(-K_L6_VN * 2.0, 1.0), OGK_TEST_TOL(1e-14, ANG_EPS)); /* correction held */
}

/* Finite gains, a costate-rate gain of 1e308 (float: 1e38): dlam' overflows while dlam does not. */
/* req: OGK-NOG-011 */
static void test_overflowing_rate_gain(void **state)
{
    ogk_nog_config_t cfg = config();
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    size_t k;
    (void)state;
    for (k = 0u; k + 1u < 5u; ++k) {
        tw_put_real(img5.b + ROW(5u, k, OGK_NOG_OFF_NRATE + 5u * 7u + 5u), OGK_TEST_PICK(1.0e308, 1.0e38));
    }
    tw_seal(img5.b, N_VALUES(5u));
    OGK_ASSERT_STATUS(ogk_nog_table_load(&table, img5.b, TABLE_BYTES(5u)), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nog_init(&nog, &cfg), OGK_OK);
    nav.v_n_mps = 10.0;
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_E_SAFE_COMMAND);
    assert_true((s.flags & OGK_NOG_FLAG_SAFE) != 0u);
    OGK_ASSERT_NEAR(s.beta_rad, 0.0, OGK_TEST_TOL(1e-15, ANG_EPS)); /* nominal held: no correction taken */
    OGK_ASSERT_NEAR(s.alpha_rad, ALPHA0, OGK_TEST_TOL(1e-12, ANG_EPS));
    OGK_ASSERT_NEAR(s.t_f_s, TF_STAR, 0.0);
    assert_int_equal(nog.n_samples, 0u);
}

/* The RAM table's costate turned NaN after it was validated (memory upset): init holds the
 * zero direction, every command and sample flies a finite held direction and says so. */
/* req: OGK-NOG-011 */
static void test_costate_corrupted_after_load(void **state)
{
    ogk_nog_config_t cfg = config();
    ogk_nog_t ctx;
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    ogk_thrust_cmd_t c;
    size_t k;
    (void)state;
    for (k = 0u; k < table.n_grid; ++k) {
        table.entry[k * OGK_NOG_ENTRY_LEN + OGK_NOG_OFF_LAM + 3u] = NAN;
    }
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_NEAR(ctx.hold_alpha_rad, 0.0, 0.0);
    OGK_ASSERT_NEAR(ctx.hold_beta_rad, 0.0, 0.0);
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&ctx, 1.0, &c), OGK_E_SAFE_COMMAND);
    OGK_ASSERT_NEAR(c.alpha_rad, 0.0, 0.0);
    OGK_ASSERT_NEAR(c.beta_rad, 0.0, 0.0);
    assert_true((c.law_flags & OGK_NOG_FLAG_SAFE) != 0u);
    assert_true((c.flags & OGK_THRUST_FLAG_SAFE) != 0u);
    assert_true((c.flags & OGK_THRUST_FLAG_ENGINE_ON) != 0u);
    /* an input error keeps its own status, the direction is still the held one */
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&ctx, NAN, &c), OGK_E_NONFINITE);
    OGK_ASSERT_NEAR(c.alpha_rad, 0.0, 0.0);
    assert_true((c.flags & OGK_THRUST_FLAG_SAFE) != 0u);
    /* a sample computes a finite correction but a NaN direction: rolled back, held */
    OGK_ASSERT_STATUS(ogk_nog_sample(&ctx, &nav, &s), OGK_E_SAFE_COMMAND);
    assert_true((s.flags & OGK_NOG_FLAG_SAFE) != 0u);
    OGK_ASSERT_NEAR(s.alpha_rad, 0.0, 0.0);
    OGK_ASSERT_NEAR(s.beta_rad, 0.0, 0.0);
    OGK_ASSERT_NEAR(s.t_f_s, TF_STAR, 0.0);
    assert_int_equal(ctx.n_samples, 0u);
}

/* As above with only the out-of-plane costate bad: alpha is finite, beta is not; the whole
 * direction is held, never half of it. */
/* req: OGK-NOG-011 */
static void test_out_of_plane_costate_corrupted(void **state)
{
    ogk_nog_config_t cfg = config();
    ogk_nog_t ctx;
    ogk_thrust_cmd_t c;
    size_t k;
    (void)state;
    for (k = 0u; k < table.n_grid; ++k) {
        table.entry[k * OGK_NOG_ENTRY_LEN + OGK_NOG_OFF_LAM + 5u] = NAN;
    }
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_NEAR(ctx.hold_alpha_rad, 0.0, 0.0);
    OGK_ASSERT_NEAR(ctx.hold_beta_rad, 0.0, 0.0);
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&ctx, 1.0, &c), OGK_E_SAFE_COMMAND);
    OGK_ASSERT_NEAR(c.alpha_rad, 0.0, 0.0);
    OGK_ASSERT_NEAR(c.beta_rad, 0.0, 0.0);
    assert_true((c.flags & OGK_THRUST_FLAG_SAFE) != 0u);
}

/* A NaN time tag: rejected, and the context does not move (no time to move it to). */
/* req: OGK-NOG-010 */
static void test_nan_time_tag(void **state)
{
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    (void)state;
    nav.v_n_mps = 2.0;
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    nav = nav_at(2.0, 0.02);
    nav.t_s = NAN;
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_E_NONFINITE);
    assert_true((s.flags & OGK_NOG_FLAG_SAFE) != 0u);
    OGK_ASSERT_NEAR(s.tau_k, 0.0, 0.0); /* still the first sample's */
    OGK_ASSERT_NEAR(nog.t_k_s, 0.0, 0.0);
    OGK_ASSERT_NEAR(s.beta_rad, atan2(-K_L6_VN * 2.0, 1.0), OGK_TEST_TOL(1e-14, ANG_EPS)); /* its correction flies */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_table_content_rejections, setup),
        cmocka_unit_test_setup(test_null_and_uninitialised, setup),
        cmocka_unit_test_setup(test_config_bounds, setup),
        cmocka_unit_test_setup(test_bound_struct_out_of_range, setup),
        cmocka_unit_test_setup(test_stale_after_struct_copy, setup),
        cmocka_unit_test_setup(test_freeze_margin, setup),
        cmocka_unit_test_setup(test_overflowing_rate_gain, setup),
        cmocka_unit_test_setup(test_costate_corrupted_after_load, setup),
        cmocka_unit_test_setup(test_out_of_plane_costate_corrupted, setup),
        cmocka_unit_test_setup(test_nan_time_tag, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
