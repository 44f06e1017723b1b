/* libFuzzer harness: the file port's parsers (port/file): PGM/PPM headers and pixels through
 * pft_pnm_read and a concatenated PNM stream, raw frames of a fuzzed geometry, file-name
 * patterns of one-file-per-frame sequences (the pattern is the fuzzer's), and a per-frame
 * sequence with gaps. The first byte picks the mode; the input's bytes are written to files in
 * a private temporary folder. Properties checked (FZ_CHECK aborts):
 *  - a lent frame passes pft_frame_check and lies inside its buffer slot;
 *  - a failed acquire lends nothing (the frame is all zero) and counts as an error;
 *  - every lent frame can be released, and the counters add up;
 *  - and, through ASan + UBSan, no out-of-bounds access and no undefined behaviour. */
#include <unistd.h>

#include "fuzz_common.h"
#include "pft/pft_port_file.h"

uint8_t fz_pix[FZ_PIX_BYTES];
uint8_t fz_snap_ws[FZ_SNAP_BYTES];
uint8_t fz_snap_inst[1u << 16];

static char g_dir[128];
static char g_name[192];
static uint8_t g_buf[4u * 64u * 64u * 3u + 16u];

static void cleanup_(void)
{
    char cmd[160];
    (void)snprintf(cmd, sizeof cmd, "rm -rf '%s'", g_dir);
    (void)system(cmd);
}

static const char *dir_(void)
{
    if (g_dir[0] == '\0') {
        const char *t = getenv("TMPDIR"); /* else /dev/shm (tmpfs: fast) where it exists */
        if (t == NULL && access("/dev/shm", W_OK) == 0) {
            t = "/dev/shm";
        }
        (void)snprintf(g_dir, sizeof g_dir, "%s/pft_fuzz_file_%ld", (t != NULL) ? t : "/tmp",
                       (long)getpid());
        char cmd[160];
        (void)snprintf(cmd, sizeof cmd, "mkdir -p '%s'", g_dir);
        FZ_CHECK(system(cmd) == 0);
        (void)atexit(cleanup_);
    }
    return g_dir;
}

static void write_file(const char *name, const uint8_t *p, size_t n)
{
    FILE *fp = fopen(name, "wb");
    FZ_CHECK(fp != NULL);
    FZ_CHECK(fwrite(p, 1u, n, fp) == n);
    FZ_CHECK(fclose(fp) == 0);
}

static bool zero_frame(const pft_frame_t *f)
{
    static const pft_frame_t z;
    return memcmp(f, &z, sizeof z) == 0;
}

/* A lent frame is well formed and inside [base, base + cap). */
static void check_lent(const pft_frame_t *fr, const uint8_t *base, size_t cap)
{
    uint32_t all = PFT_FMT_BIT(PFT_PIX_U8) | PFT_FMT_BIT(PFT_PIX_U16) | PFT_FMT_BIT(PFT_PIX_F32) |
                   PFT_FMT_BIT(PFT_PIX_RGB888) | PFT_FMT_BIT(PFT_PIX_BGR888) |
                   PFT_FMT_BIT(PFT_PIX_RES16);
    FZ_CHECK(pft_frame_check(fr, 0u, 0u, all) == PFT_OK);
    const uint8_t *d = (const uint8_t *)fr->data;
    uint64_t span = (uint64_t)fr->stride_bytes * (fr->height - 1u) +
                    (uint64_t)fr->width * pft_pixfmt_bytes(fr->format);
    FZ_CHECK(d >= base && (uint64_t)(d - base) + span <= cap);
}

/* Acquires up to `max` frames, holding a few at times, releasing everything at the end. */
static void drain(fz_t *f, pft_file_source_t *fs, size_t cap, uint32_t max)
{
    pft_frame_t held[PFT_FILE_MAX_SLOTS];
    uint32_t nheld = 0u, lent_total = 0u, failed = 0u;
    for (uint32_t k = 0; k < max; ++k) {
        pft_frame_t fr;
        memset(&fr, 0x5A, sizeof fr);
        pft_status_t st = pft_file_acquire(fs, &fr, 0u);
        if (st == PFT_OK) {
            check_lent(&fr, g_buf, cap);
            lent_total++;
            if (nheld < PFT_FILE_MAX_SLOTS && (fz_u8(f) & 1u) != 0u) {
                held[nheld++] = fr;
            } else {
                pft_file_release(fs, &fr);
            }
            continue;
        }
        FZ_CHECK(zero_frame(&fr));
        if (st == PFT_ERR_EOF) {
            break;
        }
        if (st == PFT_ERR_STATE) { /* every slot lent: give one back */
            FZ_CHECK(nheld > 0u);
            pft_file_release(fs, &held[--nheld]);
            continue;
        }
        FZ_CHECK(st == PFT_ERR_IO || st == PFT_ERR_FORMAT);
        failed++;
    }
    while (nheld > 0u) {
        pft_file_release(fs, &held[--nheld]);
    }
    FZ_CHECK(fs->stats.frames == lent_total && fs->stats.released == lent_total);
    FZ_CHECK(fs->stats.errors == failed && fs->stats.bad_releases == 0u);
    pft_file_source_close(fs);
}

static pft_file_config_t cfg_(fz_t *f, const char *path, pft_file_layout_t lay,
                              pft_file_encoding_t enc)
{
    pft_file_config_t c;
    memset(&c, 0, sizeof c);
    c.path = path;
    c.layout = lay;
    c.encoding = enc;
    c.buffer = g_buf;
    c.buffer_bytes = 1u + fz_u16(f) % sizeof g_buf;
    c.slots = fz_u8(f) % 6u;
    c.first_index = fz_u8(f) % 3u;
    c.frame_period_us = fz_u8(f);
    return c;
}

static void pnm_read_mode(fz_t *f)
{
    size_t cap = 1u + fz_u16(f) % sizeof g_buf;
    (void)snprintf(g_name, sizeof g_name, "%s/r.pnm", dir_());
    write_file(g_name, f->p, f->n);
    pft_frame_t fr;
    pft_file_error_t e;
    pft_status_t st = pft_pnm_read(g_name, g_buf, cap, &fr, &e);
    if (st == PFT_OK) {
        FZ_CHECK(e == PFT_FILE_E_NONE);
        check_lent(&fr, g_buf, cap);
    } else {
        FZ_CHECK(zero_frame(&fr) && e != PFT_FILE_E_NONE);
    }
}

static void concat_mode(fz_t *f, pft_file_encoding_t enc)
{
    (void)snprintf(g_name, sizeof g_name, "%s/c.bin", dir_());
    pft_file_config_t c = cfg_(f, g_name, PFT_FILE_CONCAT, enc);
    if (enc == PFT_FILE_RAW) {
        c.width = (uint16_t)(fz_u8(f) % 65u);
        c.height = (uint16_t)(fz_u8(f) % 65u);
        c.format = (pft_pixfmt_t)(fz_u8(f) % 7u);
        c.bit_depth = (uint8_t)(fz_u8(f) % 18u);
        c.raw_big_endian = fz_bool(f);
    } else {
        c.width = (uint16_t)((fz_u8(f) & 1u) ? fz_u8(f) % 8u : 0u);
        c.height = (uint16_t)((fz_u8(f) & 1u) ? fz_u8(f) % 8u : 0u);
    }
    write_file(g_name, f->p, f->n);
    pft_file_source_t fs;
    if (pft_file_source_init(&fs, &c) != PFT_OK) {
        return;
    }
    drain(f, &fs, c.buffer_bytes, 64u);
}

/* The pattern is the fuzzer's (after the private folder): init must refuse anything but one
 * integer conversion, and an accepted pattern must be safe to expand for any index. */
static void pattern_mode(fz_t *f)
{
    char pat[PFT_FILE_NAME_MAX + 96u];
    size_t at = (size_t)snprintf(pat, sizeof pat, "%s/", dir_());
    size_t len = fz_u16(f) % (sizeof pat - at);
    for (size_t i = 0; i < len; ++i) {
        uint8_t ch = fz_u8(f);
        pat[at + i] = (char)((ch == 0u) ? 'a' : ch);
    }
    pat[at + len] = '\0';
    pft_file_config_t c = cfg_(f, pat, PFT_FILE_PER_FRAME, PFT_FILE_PNM);
    c.first_index = fz_u32(f);
    pft_file_source_t fs;
    if (pft_file_source_init(&fs, &c) != PFT_OK) {
        return;
    }
    drain(f, &fs, c.buffer_bytes, 3u);
}

/* A per-frame PGM sequence: up to 6 files from the input, some missing (gaps). */
static void sequence_mode(fz_t *f)
{
    char pat[160];
    (void)snprintf(pat, sizeof pat, "%s/s%%02u.pgm", dir_());
    uint32_t n = fz_u8(f) % 7u;
    uint8_t present = fz_u8(f);
    for (uint32_t k = 0; k < 8u; ++k) {
        (void)snprintf(g_name, sizeof g_name, pat, (unsigned)k);
        (void)remove(g_name);
        if (k < n && (present & (1u << k)) != 0u) {
            size_t len = fz_u16(f) % 512u;
            len = (len > f->n) ? f->n : len;
            write_file(g_name, f->p, len);
            f->p += len;
            f->n -= len;
        }
    }
    pft_file_config_t c = cfg_(f, pat, PFT_FILE_PER_FRAME, PFT_FILE_PNM);
    c.first_index = 0u;
    pft_file_source_t fs;
    FZ_CHECK(pft_file_source_init(&fs, &c) == PFT_OK || c.slots > PFT_FILE_MAX_SLOTS);
    if (c.slots <= PFT_FILE_MAX_SLOTS) {
        drain(f, &fs, c.buffer_bytes, 16u);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_t f = {data, size};
    switch (fz_u8(&f) % 5u) {
    case 0: pnm_read_mode(&f); break;
    case 1: concat_mode(&f, PFT_FILE_PNM); break;
    case 2: concat_mode(&f, PFT_FILE_RAW); break;
    case 3: pattern_mode(&f); break;
    default: sequence_mode(&f); break;
    }
    return 0;
}
