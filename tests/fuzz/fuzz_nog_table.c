/* fuzz_nog_table.c -- ogk_nog_table_load and ogk_nog_table_view on the same arbitrary bytes.
 * Input: one mode byte (bit 0: re-seal the CRCs), then the table bytes (8-byte aligned copy).
 * Oracle (nog.h: the view "validates exactly as ogk_nog_table_load"): both give the same status;
 * an accepted table has 2..OGK_NOG_MAX_GRID nodes from tau 0 to 1 strictly increasing, a t_f* in
 * (0, OGK_NOG_TF_MAX_S], the same grid and rows in both, and a NOG context initialises on it; a
 * rejected one leaves the table empty and the view zeroed; every call bumps the generation. */
#include "fuzz_common.h"

static union {
    double align;
    uint8_t b[FZ_MAX_LEN];
} tbuf;
static ogk_nog_table_t table;
static ogk_nog_table_view_t view;
static ogk_nog_t nog;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    ogk_status st_load;
    ogk_status st_view;
    uint32_t gen_table;
    uint32_t gen_view;
    size_t len;
    size_t k;
    if (size < 1u || size - 1u > FZ_MAX_LEN) {
        return 0;
    }
    len = size - 1u;
    memcpy(tbuf.b, data + 1, len);
    if ((data[0] & 1u) != 0u) {
        fz_reseal(tbuf.b, len);
    }
    gen_table = table.generation;
    gen_view = view.generation;
    st_load = ogk_nog_table_load(&table, tbuf.b, len);
    st_view = ogk_nog_table_view(&view, tbuf.b, len);
    FZ_CHECK(table.generation == gen_table + 1u);
    FZ_CHECK(view.generation == gen_view + 1u);
    FZ_CHECK(st_load == st_view);
    if (st_load != OGK_OK) {
        FZ_CHECK(table.n_grid == 0u);
        FZ_CHECK(view.n_grid == 0u && view.tau == NULL && view.entry == NULL &&
                 view.init_marker != OGK_NOG_VIEW_MARKER);
        return 0;
    }
    FZ_CHECK(view.init_marker == OGK_NOG_VIEW_MARKER);
    FZ_CHECK(table.n_grid >= 2u && table.n_grid <= OGK_NOG_MAX_GRID && table.n_grid == view.n_grid);
    FZ_CHECK(table.t_f_star_s > 0.0 && table.t_f_star_s <= OGK_NOG_TF_MAX_S);
    FZ_CHECK(table.t_f_star_s == view.t_f_star_s);
    FZ_CHECK(table.tau[0] == 0.0 && table.tau[table.n_grid - 1u] == 1.0);
    for (k = 0u; k < table.n_grid; ++k) {
        FZ_CHECK(table.tau[k] == view.tau[k]);
        FZ_CHECK(k == 0u || table.tau[k] > table.tau[k - 1u]);
    }
    FZ_CHECK(memcmp(table.entry, view.entry,
                    table.n_grid * OGK_NOG_ENTRY_LEN * sizeof table.entry[0]) == 0);
    {
        ogk_nog_config_t cfg;
        (void)ogk_nog_config_default(&cfg);
        cfg.view = &view;
        if (cfg.sample_interval_s > view.t_f_star_s) {
            cfg.sample_interval_s = view.t_f_star_s;
        }
        if (cfg.dtf_max_s > 0.5 * view.t_f_star_s) {
            cfg.dtf_max_s = 0.5 * view.t_f_star_s;
        }
        {
            /* OGK_E_CONFIG only when t_f* is too small for any positive dtf_max_s. */
            const ogk_status st = ogk_nog_init(&nog, &cfg);
            FZ_CHECK(st == OGK_OK || (st == OGK_E_CONFIG && !(cfg.dtf_max_s > 0.0)));
        }
    }
    return 0;
}
