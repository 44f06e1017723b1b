/* The file port (port/file) passes the conformance check: a PGM sequence (one file per frame,
 * 2 slots), a concatenated raw U16 file (3 slots), and a sequence with a missing file (one
 * PFT_ERR_IO, one gap). On host and AArch64 Linux the files go to a fresh temporary folder
 * (mkdtemp, removed afterwards); on bare metal (MPS2 under QEMU) they are written and read
 * over semihosting through the qemu_mps2 port's adapter, in QEMU's working folder. */
#if !defined(PFT_PORT_MPS2)
#define _POSIX_C_SOURCE 200809L /* mkdtemp, rmdir */
#include <stdlib.h>
#include <unistd.h>
#endif
#include <stdio.h>
#include <string.h>
#include "pft_test_support.h"
#include "pft_port_conformance.h"
#include "pft/pft_port_file.h"
#if defined(PFT_PORT_MPS2)
#include "pft/pft_port_mps2.h"
#endif

#define W 9u
#define H 5u
#define N 12u

static char dir[128];
static uint8_t pool[3u * (W * H * 2u + 4u)]; /* slots are 4-byte aligned */
static pft_file_source_t fs;

/* File name in the test's folder. */
static const char *path_of(char *out, size_t n, const char *name)
{
    if (dir[0] != '\0') {
        (void)snprintf(out, n, "%s/%s", dir, name);
    } else {
        (void)snprintf(out, n, "%s", name);
    }
    return out;
}

static void make_dir(void)
{
#if !defined(PFT_PORT_MPS2)
    const char *tmp = getenv("TMPDIR");
    (void)snprintf(dir, sizeof dir, "%s/pft_conf_XXXXXX",
                   (tmp != NULL && tmp[0] != '\0' && strlen(tmp) < 64u) ? tmp : "/tmp");
    TEST_ASSERT_NOT_NULL_MESSAGE(mkdtemp(dir), "mkdtemp");
#else
    dir[0] = '\0'; /* semihosting: QEMU's working folder */
#endif
}

static void remove_dir(void)
{
#if !defined(PFT_PORT_MPS2)
    TEST_ASSERT_EQUAL_INT(0, rmdir(dir));
#endif
}

static void pixels(uint8_t *p, size_t n, uint32_t k)
{
    for (size_t i = 0; i < n; ++i) {
        p[i] = (uint8_t)(k * 29u + i * 3u);
    }
}

static void write_pgm_sequence(const char *fmt, uint32_t skip)
{
    static uint8_t px[W * H];
    for (uint32_t k = 0; k < N; ++k) {
        if (k == skip) {
            continue;
        }
        char name[64], path[200];
        pixels(px, sizeof px, k);
        pft_frame_t f;
        memset(&f, 0, sizeof f);
        f.data = px;
        f.width = W;
        f.height = H;
        f.stride_bytes = W;
        f.format = PFT_PIX_U8;
        (void)snprintf(name, sizeof name, fmt, (unsigned)k);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pnm_write(path_of(path, sizeof path, name), &f));
    }
}

static void remove_pgm_sequence(const char *fmt, uint32_t skip)
{
    for (uint32_t k = 0; k < N; ++k) {
        char name[64], path[200];
        (void)snprintf(name, sizeof name, fmt, (unsigned)k);
        TEST_ASSERT_EQUAL_INT(k == skip ? PFT_ERR_IO : PFT_OK,
                              pft_file_remove(path_of(path, sizeof path, name)));
    }
}

static pft_frame_source_t open_source(const pft_file_config_t *c)
{
    pft_frame_source_t src;
#if defined(PFT_PORT_MPS2)
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mps2_file_source_init(&fs, c, &src));
#else
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_source_init(&fs, c));
    src = pft_file_as_source(&fs);
#endif
    return src;
}

static uint32_t file_bad(void *ctx) { return ((pft_file_source_t *)ctx)->stats.bad_releases; }

static pft_conf_spec_t spec(pft_pixfmt_t fmt, uint32_t frames, uint32_t slots)
{
    pft_conf_spec_t s;
    pft_conf_spec_default(&s);
    s.width = W;
    s.height = H;
    s.fmt_mask = PFT_FMT_BIT(fmt);
    s.frames = frames;
    s.max_lent = slots;
    s.can_timeout = false; /* files never wait */
    s.hook_ctx = &fs;
    s.bad_releases = file_bad;
    return s;
}

static pft_file_config_t config(const char *path, pft_file_layout_t layout,
                                pft_file_encoding_t enc, uint32_t slots)
{
    pft_file_config_t c;
    memset(&c, 0, sizeof c);
    c.path = path;
    c.layout = layout;
    c.encoding = enc;
    c.frame_period_us = 40000u;
    c.buffer = pool;
    c.buffer_bytes = sizeof pool;
    c.slots = slots;
    return c;
}

static void check(const pft_frame_source_t *src, const pft_conf_spec_t *s, pft_conf_report_t *r)
{
    bool ok = pft_conf_run(src, s, r);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, r->total, r->first);
    TEST_ASSERT_TRUE(ok);
    TEST_ASSERT_TRUE(r->ended);
    TEST_ASSERT_EQUAL_UINT32(r->frames, fs.stats.frames);
    TEST_ASSERT_EQUAL_UINT32(r->frames, fs.stats.released);
    TEST_ASSERT_EQUAL_UINT32(r->bad_releases, fs.stats.bad_releases);
}

void setUp(void) { make_dir(); }
void tearDown(void)
{
    pft_file_source_close(&fs);
    remove_dir();
}

static void test_pgm_sequence(void)
{
    write_pgm_sequence("f%03u.pgm", N);
    char pattern[200];
    pft_file_config_t c = config(path_of(pattern, sizeof pattern, "f%03u.pgm"),
                                 PFT_FILE_PER_FRAME, PFT_FILE_PNM, 2u);
    pft_frame_source_t src = open_source(&c);
    pft_conf_spec_t s = spec(PFT_PIX_U8, N, 2u);
    pft_conf_report_t r;
    check(&src, &s, &r);
    TEST_ASSERT_EQUAL_UINT32(N, r.frames);
    TEST_ASSERT_EQUAL_UINT32(0u, r.gaps);
    TEST_ASSERT_EQUAL_UINT32(N - 1u, r.last_seq);
    TEST_ASSERT_EQUAL_UINT32(2u, r.refused); /* the lend probes hit the 2-slot limit */
    remove_pgm_sequence("f%03u.pgm", N);
}

static void test_raw_concat_u16(void)
{
    static uint16_t px[W * H];
    char path[200];
    path_of(path, sizeof path, "all.raw");
    for (uint32_t k = 0; k < N; ++k) {
        pixels((uint8_t *)px, sizeof px, k);
        pft_frame_t f;
        memset(&f, 0, sizeof f);
        f.data = px;
        f.width = W;
        f.height = H;
        f.stride_bytes = W * 2u;
        f.format = PFT_PIX_U16;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_raw_write(path, &f, k > 0u));
    }
    pft_file_config_t c = config(path, PFT_FILE_CONCAT, PFT_FILE_RAW, 3u);
    c.width = W;
    c.height = H;
    c.format = PFT_PIX_U16;
    c.bit_depth = 12u;
    pft_frame_source_t src = open_source(&c);
    pft_conf_spec_t s = spec(PFT_PIX_U16, N, 3u);
    pft_conf_report_t r;
    check(&src, &s, &r);
    TEST_ASSERT_EQUAL_UINT32(N, r.frames);
    pft_file_source_close(&fs);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_remove(path));
}

/* A missing file is one PFT_ERR_IO (allowed with may_lose) and one gap; without may_lose the
 * same run is reported. */
static void test_missing_file_is_a_gap(void)
{
    write_pgm_sequence("g%03u.pgm", 5u);
    char pattern[200];
    path_of(pattern, sizeof pattern, "g%03u.pgm");
    pft_file_config_t c = config(pattern, PFT_FILE_PER_FRAME, PFT_FILE_PNM, 1u);
    pft_frame_source_t src = open_source(&c);
    pft_conf_spec_t s = spec(PFT_PIX_U8, N - 1u, 1u);
    s.may_lose = true;
    pft_conf_report_t r;
    check(&src, &s, &r);
    TEST_ASSERT_EQUAL_UINT32(1u, r.lost);
    TEST_ASSERT_EQUAL_UINT32(1u, r.gaps);

    src = open_source(&c);
    s.may_lose = false;
    TEST_ASSERT_FALSE(pft_conf_run(&src, &s, &r));
    TEST_ASSERT_EQUAL_UINT32(1u, r.violations[PFT_CONF_STATUS]);
    remove_pgm_sequence("g%03u.pgm", 5u);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_pgm_sequence);
    RUN_TEST(test_raw_concat_u16);
    RUN_TEST(test_missing_file_is_a_gap);
    return UNITY_END();
}
