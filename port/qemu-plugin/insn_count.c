/* insn_count.c -- QEMU TCG plugin (API v1, QEMU 7.2): counts executed guest
 * instructions, in total, per address range, and per function call.
 *
 * Arguments (each `key=value`, after the library path in -plugin):
 *   fn=NAME@0xENTRY     inclusive count of each call of the function at ENTRY:
 *                       every instruction from its first one up to its return,
 *                       callees included (libm, other kernel functions).
 *                       The return is recognised as the execution of the
 *                       address that follows the call instruction (the end of
 *                       the translation block that branched to ENTRY). Only
 *                       entries by a call (bl/blx) are counted; entries by a
 *                       tail branch are reported as `skipped` (their return
 *                       address is unknown). Not for recursive functions.
 *                       Up to 16.
 *   range=NAME@0xLO-0xHI  instructions executed with LO <= address < HI
 *                       (exclusive cost: callees outside the range not
 *                       counted). Up to 16.
 *   out=PATH            append the report to PATH (default: qemu_plugin_outs,
 *                       which needs `-d plugin` and goes to QEMU's log).
 *   calls=PATH          also write every completed call of every fn item to
 *                       PATH, one line `NAME COUNT` each, in the order the
 *                       calls return (processor in the loop, docs/guides/pil.md: the
 *                       k-th line of a function is its k-th step's count, so
 *                       a campaign keeps the maximum with its run and step).
 *
 * Report lines (one per item, at exit):
 *   insn_count total N
 *   insn_count fn NAME entry 0x... calls C total T min A max B [skipped S] [unterminated 1]
 *   insn_count range NAME 0x...-0x... executed N
 *
 * The counts are instructions, not cycles, and identical on every run of
 * the same ELF (single vCPU, deterministic guest). port/qemu-plugin/
 * count_insns.sh resolves names with arm-none-eabi-nm and runs QEMU. */
#include "qemu_plugin_api.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

QEMU_PLUGIN_EXPORT int qemu_plugin_version = QEMU_PLUGIN_VERSION;

#define MAX_ITEMS 16
#define NAME_LEN 96

typedef struct {
    char name[NAME_LEN];
    uint64_t entry;
    int active;
    uint64_t return_addr;
    uint64_t start_total;
    uint64_t calls;
    uint64_t total;
    uint64_t min;
    uint64_t max;
    uint64_t skipped;
} fn_counter;

typedef struct {
    char name[NAME_LEN];
    uint64_t lo;
    uint64_t hi;
    uint64_t executed;
} range_counter;

static uint64_t total_insns;
static fn_counter fns[MAX_ITEMS];
static size_t n_fns;
static range_counter ranges[MAX_ITEMS];
static size_t n_ranges;
static uint64_t previous_ret; /* return address of the call that ended the previous block, or 0 */
static int sparc_guest;        /* SPARC: a call returns to its address + 8 (after the delay slot) */
static char out_path[4096];
static FILE *calls_file; /* calls=PATH: one line per completed call */

/* Translation block start and, for a block that ends with a call, the call's
 * return address (0 otherwise), packed in the callback's userdata: guest
 * addresses are 32-bit. */
static void *pack_tb(uint64_t start, uint64_t ret)
{
    return (void *)(uintptr_t)(((start & 0xFFFFFFFFu) << 32) | (ret & 0xFFFFFFFFu));
}

/* Thumb BL / BLX (immediate) / BLX (register) (ARMv7-M ARM A7.7.18-19). */
static int is_thumb_call(const struct qemu_plugin_insn *insn)
{
    const uint8_t *bytes = qemu_plugin_insn_data(insn);
    const size_t size = qemu_plugin_insn_size(insn);
    if (bytes == NULL) {
        return 0;
    }
    const unsigned hw1 = (unsigned)bytes[0] | ((unsigned)bytes[1] << 8);
    if (size == 2) {
        return (hw1 & 0xFF87u) == 0x4780u; /* blx Rm */
    }
    if (size == 4) {
        const unsigned hw2 = (unsigned)bytes[2] | ((unsigned)bytes[3] << 8);
        return (hw1 & 0xF800u) == 0xF000u && ((hw2 & 0xD000u) == 0xD000u ||  /* bl */
                                             (hw2 & 0xD001u) == 0xC000u);   /* blx imm */
    }
    return 0;
}

/* SPARC V8 call (format 1) or jmpl with rd = %o7 (a call through a register);
 * instructions are big-endian words (SPARC Architecture Manual V8, B.24, B.25). */
static int is_sparc_call(const struct qemu_plugin_insn *insn)
{
    const uint8_t *b = qemu_plugin_insn_data(insn);
    if (b == NULL || qemu_plugin_insn_size(insn) != 4) {
        return 0;
    }
    const uint32_t w = ((uint32_t)b[0] << 24) | ((uint32_t)b[1] << 16) | ((uint32_t)b[2] << 8) | b[3];
    return (w >> 30) == 1u || ((w >> 30) == 2u && ((w >> 19) & 0x3Fu) == 0x38u && ((w >> 25) & 0x1Fu) == 15u);
}

static void on_tb_exec(unsigned int vcpu_index, void *userdata)
{
    (void)vcpu_index;
    const uint64_t packed = (uint64_t)(uintptr_t)userdata;
    const uint64_t start = packed >> 32;
    const uint64_t ret = packed & 0xFFFFFFFFu;
    for (size_t i = 0; i < n_fns; ++i) {
        fn_counter *fn = &fns[i];
        if (fn->active && start == fn->return_addr) {
            const uint64_t count = total_insns - fn->start_total;
            fn->total += count;
            if (fn->calls == 1 || count < fn->min) {
                fn->min = count;
            }
            if (count > fn->max) {
                fn->max = count;
            }
            if (calls_file != NULL) {
                fprintf(calls_file, "%s %" PRIu64 "\n", fn->name, count);
            }
            fn->active = 0;
        }
        if (!fn->active && start == fn->entry && previous_ret == 0u) {
            fn->skipped += 1; /* tail branch or fall-through: return unknown */
        } else if (!fn->active && start == fn->entry) {
            fn->active = 1;
            fn->return_addr = previous_ret;
            fn->start_total = total_insns; /* this block's instructions not yet counted */
            fn->calls += 1;
        }
    }
    /* A SPARC call whose delay slot QEMU translated as a block of its own: the
     * call is still pending while that block (at the return address - 4) runs. */
    if (ret != 0u || !(sparc_guest && previous_ret != 0u && start + 4u == previous_ret)) {
        previous_ret = ret;
    }
}

static void on_tb_translate(qemu_plugin_id_t id, struct qemu_plugin_tb *tb)
{
    (void)id;
    const size_t n = qemu_plugin_tb_n_insns(tb);
    uint64_t ret = 0u;
    for (size_t k = 0; k < n; ++k) {
        struct qemu_plugin_insn *insn = qemu_plugin_tb_get_insn(tb, k);
        const uint64_t addr = qemu_plugin_insn_vaddr(insn);
        qemu_plugin_register_vcpu_insn_exec_inline(insn, QEMU_PLUGIN_INLINE_ADD_U64,
                                                   &total_insns, 1);
        for (size_t r = 0; r < n_ranges; ++r) {
            if (addr >= ranges[r].lo && addr < ranges[r].hi) {
                qemu_plugin_register_vcpu_insn_exec_inline(
                    insn, QEMU_PLUGIN_INLINE_ADD_U64, &ranges[r].executed, 1);
            }
        }
        if (sparc_guest) {
            /* the call is the last instruction, or the last but its delay slot */
            if (k + 2 >= n && is_sparc_call(insn)) {
                ret = addr + 8u;
            }
        } else if (k + 1 == n && is_thumb_call(insn)) {
            ret = addr + qemu_plugin_insn_size(insn);
        }
    }
    if (n_fns > 0) {
        qemu_plugin_register_vcpu_tb_exec_cb(tb, on_tb_exec, QEMU_PLUGIN_CB_NO_REGS,
                                             pack_tb(qemu_plugin_tb_vaddr(tb), ret));
    }
}

static void emit(FILE *file, const char *line)
{
    if (file != NULL) {
        fputs(line, file);
    } else {
        qemu_plugin_outs(line);
    }
}

static void on_exit_report(qemu_plugin_id_t id, void *userdata)
{
    (void)id;
    (void)userdata;
    FILE *file = NULL;
    if (out_path[0] != '\0') {
        file = fopen(out_path, "a");
        if (file == NULL) {
            qemu_plugin_outs("insn_count: cannot open out= file; report follows\n");
        }
    }
    char line[4096];
    snprintf(line, sizeof line, "insn_count total %" PRIu64 "\n", total_insns);
    emit(file, line);
    for (size_t i = 0; i < n_fns; ++i) {
        const fn_counter *fn = &fns[i];
        const uint64_t done = fn->calls - (fn->active ? 1u : 0u);
        char skipped[64] = "";
        if (fn->skipped > 0) {
            snprintf(skipped, sizeof skipped, " skipped %" PRIu64, fn->skipped);
        }
        snprintf(line, sizeof line,
                 "insn_count fn %s entry 0x%08" PRIx64 " calls %" PRIu64 " total %" PRIu64
                 " min %" PRIu64 " max %" PRIu64 "%s%s\n",
                 fn->name, fn->entry, done, fn->total, done > 0 ? fn->min : 0, fn->max,
                 skipped, fn->active ? " unterminated 1" : "");
        emit(file, line);
    }
    for (size_t r = 0; r < n_ranges; ++r) {
        snprintf(line, sizeof line,
                 "insn_count range %s 0x%08" PRIx64 "-0x%08" PRIx64 " executed %" PRIu64 "\n",
                 ranges[r].name, ranges[r].lo, ranges[r].hi, ranges[r].executed);
        emit(file, line);
    }
    if (file != NULL) {
        fclose(file);
    }
    if (calls_file != NULL) {
        fclose(calls_file);
        calls_file = NULL;
    }
}

/* "NAME@rest": copies NAME, returns rest (NULL if malformed). */
static const char *split_name(const char *value, char name[NAME_LEN])
{
    const char *at = strchr(value, '@');
    if (at == NULL || at == value || (size_t)(at - value) >= NAME_LEN) {
        return NULL;
    }
    memcpy(name, value, (size_t)(at - value));
    name[at - value] = '\0';
    return at + 1;
}

static int parse_u64(const char *text, char **rest, uint64_t *value)
{
    char *end = NULL;
    *value = strtoull(text, &end, 0);
    if (end == text) {
        return -1;
    }
    *rest = end;
    return 0;
}

static int parse_argument(const char *arg)
{
    if (strncmp(arg, "fn=", 3) == 0) {
        if (n_fns >= MAX_ITEMS) {
            return -1;
        }
        fn_counter *fn = &fns[n_fns];
        const char *rest = split_name(arg + 3, fn->name);
        char *end = NULL;
        if (rest == NULL || parse_u64(rest, &end, &fn->entry) != 0 || *end != '\0') {
            return -1;
        }
        fn->entry &= ~(uint64_t)1u; /* Thumb bit */
        n_fns += 1;
        return 0;
    }
    if (strncmp(arg, "range=", 6) == 0) {
        if (n_ranges >= MAX_ITEMS) {
            return -1;
        }
        range_counter *range = &ranges[n_ranges];
        const char *rest = split_name(arg + 6, range->name);
        char *end = NULL;
        if (rest == NULL || parse_u64(rest, &end, &range->lo) != 0 || *end != '-' ||
            parse_u64(end + 1, &end, &range->hi) != 0 || *end != '\0' ||
            range->hi <= range->lo) {
            return -1;
        }
        range->lo &= ~(uint64_t)1u;
        n_ranges += 1;
        return 0;
    }
    if (strncmp(arg, "calls=", 6) == 0) {
        if (calls_file != NULL || arg[6] == '\0') {
            return -1;
        }
        calls_file = fopen(arg + 6, "w");
        return calls_file != NULL ? 0 : -1;
    }
    if (strncmp(arg, "out=", 4) == 0) {
        const size_t len = strlen(arg + 4);
        if (len == 0 || len >= sizeof out_path) {
            return -1;
        }
        memcpy(out_path, arg + 4, len + 1);
        return 0;
    }
    return -1;
}

QEMU_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info,
                                           int argc, char **argv)
{
    if (info->version.cur < QEMU_PLUGIN_VERSION || info->version.min > QEMU_PLUGIN_VERSION) {
        fprintf(stderr, "insn_count: QEMU plugin API %d..%d, built for %d\n",
                info->version.min, info->version.cur, QEMU_PLUGIN_VERSION);
        return -1;
    }
    for (int i = 0; i < argc; ++i) {
        if (parse_argument(argv[i]) != 0) {
            fprintf(stderr,
                    "insn_count: bad argument '%s' (fn=NAME@0xADDR, "
                    "range=NAME@0xLO-0xHI, out=PATH, calls=PATH; at most %d fn and %d range)\n",
                    argv[i], MAX_ITEMS, MAX_ITEMS);
            return -1;
        }
    }
    sparc_guest = info->target_name != NULL && strncmp(info->target_name, "sparc", 5) == 0;
    qemu_plugin_register_vcpu_tb_trans_cb(id, on_tb_translate);
    qemu_plugin_register_atexit_cb(id, on_exit_report, NULL);
    return 0;
}
