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

static void on_begin(unsigned int vcpu, void *udata)
{
    (void)vcpu;
    (void)udata;
    if (g_open) {
        g_unmatched++;
    }
    g_open = 1;
    g_start = g_count;
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
}

QEMU_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info, int argc,
                                           char **argv)
{
    (void)info;
    const char *path = NULL;
    for (int i = 0; i < argc; ++i) {
        if (strncmp(argv[i], "out=", 4) == 0) {
            path = argv[i] + 4;
        } else {
            fprintf(stderr, "qemu_marks: unknown argument %s (expected out=FILE)\n", argv[i]);
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
