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
 *
 * Optional block profile, blocks=FILE: every translated block, one line "vaddr n odd even
 * name" (guest address in hex, its instruction count, how often it was entered inside the
 * odd- and the even-numbered regions, the symbol of its first instruction or "?"; every block
 * entered at least once, also outside the regions); a block
 * translated more than once has a line per translation. host_tools/scripts/a53_mca.py maps
 * the counts onto the disassembly to find the hot loops (docs/results/ir_clutter.md,
 * "Branch irmca").
 *
 * Optional cache model, mem=FILE (with prof=): every data access inside the regions goes
 * (and, uncounted, every other access of the program) goes
 * through a model of a Cortex-A53's data caches (L1 32 KB 4-way, L2 512 KB 16-way, 64-byte
 * lines, LRU, every access allocates; sizes by l1=BYTES and l2=BYTES), counted per function
 * and region parity: one line "function parity accesses l1_misses l1_misses_strided l2_misses
 * l2_misses_strided", where a strided miss is one whose line lies 1 or 2 lines from the line
 * of the same instruction's previous miss (what a stride prefetcher would have fetched). A
 * model, not the A53: no prefetcher, no write streaming mode, no instruction fetches.
 *
 * from=I, to=J: prof=, blocks= and mem= count only the regions I..J (1-based); out= still
 * lists every region (tests/target/tbd_cycles runs three trackers one after the other).
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
static uint64_t g_first = 1u, g_last = UINT64_MAX; /* from=, to=: the regions profiled */

/* prof=, blocks= and mem= count only regions g_first..g_last (1-based; all by default): a
 * program that runs several trackers one after the other gets a profile of each */
static int g_profiled(void)
{
    return g_regions + 1u >= g_first && g_regions + 1u <= g_last;
}
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
/* mem=FILE: the cache model */
#define WAYS_MAX 16
typedef struct {
    uint64_t tag[WAYS_MAX]; /* line address + 1 (0: empty), most recent first */
} set_t;
typedef struct {
    set_t *sets;
    unsigned nsets, ways;
} cache_t;
typedef struct {
    uint64_t acc, l1, l1s, l2, l2s;
} memc_t;
typedef struct {
    uint64_t last1, last2; /* line of this instruction's previous L1 / L2 miss, + 1 */
    size_t prof;           /* index into g_prof */
} insn_t;
static FILE *g_mem_out;
static cache_t g_l1, g_l2;
static uint64_t g_l1_bytes = 32768u, g_l2_bytes = 524288u;
static memc_t g_memc[PROF_MAX][2];

static void cache_init(cache_t *c, uint64_t bytes, unsigned ways)
{
    c->ways = ways;
    c->nsets = (unsigned)(bytes / 64u / ways);
    c->sets = calloc(c->nsets, sizeof *c->sets);
}

/* returns 1 on a hit; on a miss the line is brought in (LRU way out) */
static int cache_access(cache_t *c, uint64_t line)
{
    set_t *s = &c->sets[line % c->nsets];
    unsigned w;
    for (w = 0; w < c->ways; ++w) {
        if (s->tag[w] == line + 1u) {
            break;
        }
    }
    int hit = w < c->ways;
    if (!hit) {
        w = c->ways - 1u;
    }
    for (; w > 0; --w) {
        s->tag[w] = s->tag[w - 1u];
    }
    s->tag[0] = line + 1u;
    return hit;
}

static prof_t g_prof[PROF_MAX];
static size_t g_nprof;
static FILE *g_prof_out;

/* blocks=FILE: per translated block entry counts (a fixed table: a few thousand blocks) */
#define BLK_MAX 65536
typedef struct {
    uint64_t vaddr;
    uint64_t count; /* entries so far (inline) */
    uint64_t start; /* count at the open region's begin */
    uint64_t in[2]; /* entries inside odd- and even-numbered regions */
    size_t n;       /* instructions */
    const char *name;
} blk_t;
static blk_t g_blk[BLK_MAX];
static size_t g_nblk;
static size_t g_blk_lost; /* blocks past BLK_MAX, not profiled */
static FILE *g_blk_out;

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
    for (size_t i = 0; i < g_nblk; ++i) {
        g_blk[i].start = g_blk[i].count;
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
    for (size_t i = 0; g_profiled() && i < g_nprof; ++i) {
        g_prof[i].in[g_regions % 2u] += g_prof[i].count - g_prof[i].start;
    }
    for (size_t i = 0; g_profiled() && i < g_nblk; ++i) {
        g_blk[i].in[g_regions % 2u] += g_blk[i].count - g_blk[i].start;
    }
    g_regions++;
}

static int near_line(uint64_t last, uint64_t line)
{
    if (last == 0u) {
        return 0;
    }
    const uint64_t prev = last - 1u;
    const uint64_t d = line > prev ? line - prev : prev - line;
    return d >= 1u && d <= 2u;
}

static void on_mem(unsigned int vcpu, qemu_plugin_meminfo_t info, uint64_t vaddr, void *udata)
{
    (void)vcpu;
    (void)info;
    /* every access moves the caches (the code between the regions evicts lines too), only
     * those inside a region are counted */
    insn_t *in = udata;
    memc_t dummy = {0, 0, 0, 0, 0};
    memc_t *m = g_open && g_profiled() ? &g_memc[in->prof][g_regions % 2u] : &dummy;
    const uint64_t line = vaddr >> 6;
    m->acc++;
    if (cache_access(&g_l1, line)) {
        return;
    }
    m->l1++;
    m->l1s += (uint64_t)near_line(in->last1, line);
    in->last1 = line + 1u;
    if (cache_access(&g_l2, line)) {
        return;
    }
    m->l2++;
    m->l2s += (uint64_t)near_line(in->last2, line);
    in->last2 = line + 1u;
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
    if (g_mem_out != NULL) {
        prof_t *p = prof_of(sym != NULL ? sym : "?");
        for (size_t i = 0; p != NULL && i < n; ++i) {
            insn_t *in = calloc(1, sizeof *in);
            in->prof = (size_t)(p - g_prof);
            qemu_plugin_register_vcpu_mem_cb(qemu_plugin_tb_get_insn(tb, i), on_mem, QEMU_PLUGIN_CB_NO_REGS,
                                             QEMU_PLUGIN_MEM_RW, in);
        }
    }
    if (g_blk_out != NULL) {
        if (g_nblk < BLK_MAX) {
            blk_t *b = &g_blk[g_nblk++];
            b->vaddr = qemu_plugin_tb_vaddr(tb);
            b->n = n;
            b->name = strdup(sym != NULL ? sym : "?");
            qemu_plugin_register_vcpu_tb_exec_inline(tb, QEMU_PLUGIN_INLINE_ADD_U64, &b->count, 1);
        } else {
            g_blk_lost++;
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
    /* before the profile's sort: g_memc is indexed as g_prof was built */
    if (g_mem_out != NULL) {
        for (size_t i = 0; i < g_nprof; ++i) {
            for (unsigned r = 0; r < 2u; ++r) {
                const memc_t *m = &g_memc[i][r];
                if (m->acc > 0u) {
                    fprintf(g_mem_out, "%s %u %" PRIu64 " %" PRIu64 " %" PRIu64 " %" PRIu64 " %" PRIu64 "\n",
                            g_prof[i].name, r, m->acc, m->l1, m->l1s, m->l2, m->l2s);
                }
            }
        }
        fclose(g_mem_out);
    }
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
    if (g_blk_out != NULL) {
        for (size_t i = 0; i < g_nblk; ++i) {
            const blk_t *b = &g_blk[i];
            if (b->count > 0u) {
                fprintf(g_blk_out, "%" PRIx64 " %zu %" PRIu64 " %" PRIu64 " %s\n", b->vaddr, b->n, b->in[0],
                        b->in[1], b->name);
            }
        }
        if (g_blk_lost > 0u) {
            fprintf(g_blk_out, "# %zu blocks past the table, not profiled\n", g_blk_lost);
        }
        fclose(g_blk_out);
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
        } else if (strncmp(argv[i], "mem=", 4) == 0) {
            g_mem_out = fopen(argv[i] + 4, "w");
            if (g_mem_out == NULL) {
                fprintf(stderr, "qemu_marks: cannot write %s\n", argv[i] + 4);
                return -1;
            }
        } else if (strncmp(argv[i], "from=", 5) == 0) {
            g_first = strtoull(argv[i] + 5, NULL, 10);
        } else if (strncmp(argv[i], "to=", 3) == 0) {
            g_last = strtoull(argv[i] + 3, NULL, 10);
        } else if (strncmp(argv[i], "l1=", 3) == 0) {
            g_l1_bytes = strtoull(argv[i] + 3, NULL, 10);
        } else if (strncmp(argv[i], "l2=", 3) == 0) {
            g_l2_bytes = strtoull(argv[i] + 3, NULL, 10);
        } else if (strncmp(argv[i], "blocks=", 7) == 0) {
            g_blk_out = fopen(argv[i] + 7, "w");
            if (g_blk_out == NULL) {
                fprintf(stderr, "qemu_marks: cannot write %s\n", argv[i] + 7);
                return -1;
            }
        } else {
            fprintf(stderr, "qemu_marks: unknown argument %s (expected out=FILE, prof=FILE, blocks=FILE, mem=FILE, l1=, l2=, from=, to=)\n",
                    argv[i]);
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
    if (g_mem_out != NULL) {
        if (g_prof_out == NULL || g_l1_bytes < 4096u || g_l2_bytes < 65536u) {
            fprintf(stderr, "qemu_marks: mem= needs prof= (and l1 >= 4096, l2 >= 65536)\n");
            return -1;
        }
        cache_init(&g_l1, g_l1_bytes, 4u);
        cache_init(&g_l2, g_l2_bytes, 16u);
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, on_trans);
    qemu_plugin_register_atexit_cb(id, on_atexit, NULL);
    return 0;
}
