/*
 * A QEMU TCG plugin (user or system mode) that counts the guest instructions executed between
 * two marker functions of the program under test: every call of `pft_work_mark_begin` starts
 * a region, the next call of `pft_work_mark_end` closes it, and the region's instruction count
 * is appended to the output file, one decimal number per line, in execution order. The soak
 * program (pft_soak.c) calls the markers around every tracker update, so this gives, on a
 * Cortex-M or AArch64 guest, what `valgrind --tool=callgrind --toggle-collect` gives on the
 * host: the instructions of each update (tests/soak/run_soak.sh work-qemu).
 *
 * Counting: every translated block adds its instruction count to a counter when it starts
 * executing (an inline operation, cheap); a region's count is the difference of the counter at
 * the two markers. It includes a constant number of instructions of the markers themselves
 * and of the calls (a few), never data-dependent ones.
 *
 * Built by run_soak.sh against the `qemu-plugin.h` of the installed QEMU's own source (the
 * header is not part of this repository):
 *   gcc -shared -fPIC -O2 -I<dir with qemu-plugin.h> tests/soak/qemu_marks.c -o qemu_marks.so
 * Use: qemu-aarch64 -plugin ./qemu_marks.so,out=counts.txt prog ...   (one vCPU guests only)
 *
 * Optional profile, prof=FILE: the instructions of every function (the symbol of each translated
 * block's first instruction: inlined code counts in its caller, a block without a symbol under
 * "?") inside the odd-numbered regions (1st, 3rd, ...) and inside the even-numbered ones, one
 * line per function "odd even name", largest first; a program that alternates two measured
 * calls (tests/tools/ir_probe: stage, manager) gets one profile of each
 * (docs/results/ir_clutter.md, "Branch ira53", gives the command).
 */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <qemu-plugin.h>

QEMU_PLUGIN_EXPORT int qemu_plugin_version = QEMU_PLUGIN_VERSION;

static uint64_t g_count;     /* instructions executed so far (inline, per translated block) */
static uint64_t g_start;     /* g_count at the open region's begin marker */
static int g_open;           /* a region is open */
static FILE *g_out;
static uint64_t g_regions;
static uint64_t g_unmatched; /* an end without a begin, or a begin inside an open region */

/* prof=FILE: per-function counts (a linear table: a few hundred functions, looked up at
 * translation only) */
#define PROF_MAX 8192
typedef struct {
    char *name;
    uint64_t count;   /* instructions so far (inline, per translated block) */
    uint64_t start;   /* count at the open region's begin */
    uint64_t in[2];   /* inside odd- and even-numbered regions */
} prof_t;
static prof_t g_prof[PROF_MAX];
static size_t g_nprof;
static FILE *g_prof_out;

static prof_t *prof_of(const char *name)
{
    for (size_t i = 0; i < g_nprof; ++i) {
        if (strcmp(g_prof[i].name, name) == 0) {
            return &g_prof[i];
        }
    }
    if (g_nprof == PROF_MAX) {
        return NULL;
    }
    prof_t *p = &g_prof[g_nprof++];
    p->name = strdup(name);
    p->count = p->start = 0;
    p->in[0] = p->in[1] = 0;
    return p;
}

static int prof_cmp(const void *a, const void *b)
{
    const prof_t *x = a, *y = b;
    const uint64_t sx = x->in[0] + x->in[1], sy = y->in[0] + y->in[1];
    return sx < sy ? 1 : sx > sy ? -1 : 0;
}

static void on_begin(unsigned int vcpu, void *udata)
{
    (void)vcpu;
    (void)udata;
    if (g_open) {
        g_unmatched++;
    }
    g_open = 1;
    g_start = g_count;
    for (size_t i = 0; i < g_nprof; ++i) {
        g_prof[i].start = g_prof[i].count;
    }
}

static void on_end(unsigned int vcpu, void *udata)
{
    (void)vcpu;
    (void)udata;
    if (!g_open) {
        g_unmatched++;
        return;
    }
    g_open = 0;
    fprintf(g_out, "%" PRIu64 "\n", g_count - g_start);
    for (size_t i = 0; i < g_nprof; ++i) {
        g_prof[i].in[g_regions % 2u] += g_prof[i].count - g_prof[i].start;
    }
    g_regions++;
}

static void on_trans(qemu_plugin_id_t id, struct qemu_plugin_tb *tb)
{
    (void)id;
    size_t n = qemu_plugin_tb_n_insns(tb);
    qemu_plugin_register_vcpu_tb_exec_inline(tb, QEMU_PLUGIN_INLINE_ADD_U64, &g_count, n);
    if (n == 0u) {
        return;
    }
    /* a marker is entered by a call, so its first instruction starts a translated block */
    struct qemu_plugin_insn *first = qemu_plugin_tb_get_insn(tb, 0);
    const char *sym = qemu_plugin_insn_symbol(first);
    if (g_prof_out != NULL) {
        prof_t *p = prof_of(sym != NULL ? sym : "?");
        if (p != NULL) {
            qemu_plugin_register_vcpu_tb_exec_inline(tb, QEMU_PLUGIN_INLINE_ADD_U64, &p->count, n);
        }
    }
    if (sym == NULL) {
        return;
    }
    if (strcmp(sym, "pft_work_mark_begin") == 0) {
        qemu_plugin_register_vcpu_insn_exec_cb(first, on_begin, QEMU_PLUGIN_CB_NO_REGS, NULL);
    } else if (strcmp(sym, "pft_work_mark_end") == 0) {
        qemu_plugin_register_vcpu_insn_exec_cb(first, on_end, QEMU_PLUGIN_CB_NO_REGS, NULL);
    }
}

static void on_atexit(qemu_plugin_id_t id, void *udata)
{
    (void)id;
    (void)udata;
    char line[160];
    (void)snprintf(line, sizeof line,
                   "qemu_marks: %" PRIu64 " regions, %" PRIu64 " unmatched markers, %" PRIu64
                   " instructions in all\n",
                   g_regions, g_unmatched, g_count);
    qemu_plugin_outs(line);
    fclose(g_out);
    if (g_prof_out != NULL) {
        qsort(g_prof, g_nprof, sizeof g_prof[0], prof_cmp);
        for (size_t i = 0; i < g_nprof; ++i) {
            if (g_prof[i].in[0] + g_prof[i].in[1] > 0u) {
                fprintf(g_prof_out, "%" PRIu64 " %" PRIu64 " %s\n", g_prof[i].in[0], g_prof[i].in[1],
                        g_prof[i].name);
            }
        }
        fclose(g_prof_out);
    }
}

QEMU_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info, int argc,
                                           char **argv)
{
    (void)info;
    const char *path = NULL;
    for (int i = 0; i < argc; ++i) {
        if (strncmp(argv[i], "out=", 4) == 0) {
            path = argv[i] + 4;
        } else if (strncmp(argv[i], "prof=", 5) == 0) {
            g_prof_out = fopen(argv[i] + 5, "w");
            if (g_prof_out == NULL) {
                fprintf(stderr, "qemu_marks: cannot write %s\n", argv[i] + 5);
                return -1;
            }
        } else {
            fprintf(stderr, "qemu_marks: unknown argument %s (expected out=FILE or prof=FILE)\n", argv[i]);
            return -1;
        }
    }
    if (path == NULL) {
        fprintf(stderr, "qemu_marks: out=FILE is required\n");
        return -1;
    }
    g_out = fopen(path, "w");
    if (g_out == NULL) {
        fprintf(stderr, "qemu_marks: cannot write %s\n", path);
        return -1;
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, on_trans);
    qemu_plugin_register_atexit_cb(id, on_atexit, NULL);
    return 0;
}
