/* File port: PGM 8/16-bit and PPM round trips, raw sequences, truncated / bad / missing files,
 * the runner over a file sequence, argument checks. Files are written and read back under the
 * same relative names, so the test works on the host (cwd = build/tests) and under QEMU
 * semihosting (paths relative to QEMU's cwd, which CTest sets to the same folder). */
#include <stdio.h>
#include <string.h>
#include "pft_test_support.h"
#include "pft/pft_port_file.h"

#define W 7u
#define H 5u

static uint8_t buf[4u * W * H * 3u];
static pft_file_source_t fs;

static pft_frame_t frame_of(const void *px, uint16_t w, uint16_t h, pft_pixfmt_t fmt, uint8_t bd)
{
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    f.data = px;
    f.width = w;
    f.height = h;
    f.format = fmt;
    f.bit_depth = bd;
    f.stride_bytes = (uint32_t)w * pft_pixfmt_bytes(fmt);
    return f;
}

/* Writes arbitrary bytes through the port's raw writer (a one-row U8 frame). */
static void write_bytes(const char *path, const void *b, size_t n, bool append)
{
    pft_frame_t f = frame_of(b, (uint16_t)n, 1u, PFT_PIX_U8, 0u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_raw_write(path, &f, append));
}

static void write_text(const char *path, const char *s)
{
    write_bytes(path, s, strlen(s), false);
}

static pft_file_config_t cfg_of(const char *path, pft_file_layout_t layout,
                                pft_file_encoding_t enc)
{
    pft_file_config_t c;
    memset(&c, 0, sizeof c);
    c.path = path;
    c.layout = layout;
    c.encoding = enc;
    c.buffer = buf;
    c.buffer_bytes = sizeof buf;
    c.frame_period_us = 40000u;
    return c;
}

void setUp(void) {}
void tearDown(void)
{
    pft_file_source_close(&fs);
}

static void test_pgm8_sequence_round_trip(void)
{
    static uint8_t px[3][W * H];
    (void)pft_file_remove("pft_tpf_a03.pgm");
    for (uint32_t k = 0; k < 3u; ++k) {
        for (uint32_t i = 0; i < W * H; ++i) {
            px[k][i] = (uint8_t)(k * 50u + i * 7u);
        }
        char name[32];
        pft_frame_t f = frame_of(px[k], W, H, PFT_PIX_U8, 0u);
        (void)snprintf(name, sizeof name, "pft_tpf_a%02u.pgm", (unsigned)k);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pnm_write(name, &f));
    }
    pft_file_config_t c = cfg_of("pft_tpf_a%02u.pgm", PFT_FILE_PER_FRAME, PFT_FILE_PNM);
    c.slots = 2u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_source_init(&fs, &c));
    for (uint32_t k = 0; k < 3u; ++k) {
        pft_frame_t f;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_acquire(&fs, &f, 0u));
        TEST_ASSERT_EQUAL_INT(PFT_PIX_U8, f.format);
        TEST_ASSERT_EQUAL_UINT16(W, f.width);
        TEST_ASSERT_EQUAL_UINT16(H, f.height);
        TEST_ASSERT_EQUAL_UINT32(W, f.stride_bytes);
        TEST_ASSERT_EQUAL_UINT32(k, f.seq);
        TEST_ASSERT_EQUAL_UINT64(40000u * k, f.timestamp_us);
        TEST_ASSERT_EQUAL_UINT8_ARRAY(px[k], f.data, W * H);
        pft_file_release(&fs, &f);
    }
    pft_frame_t f;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, pft_file_acquire(&fs, &f, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, pft_file_acquire(&fs, &f, 0u));
    TEST_ASSERT_NULL(f.data);
    TEST_ASSERT_EQUAL_UINT32(3u, fs.stats.frames);
    TEST_ASSERT_EQUAL_UINT32(3u, fs.stats.released);
    TEST_ASSERT_EQUAL_UINT32(0u, fs.stats.errors);
    for (unsigned k = 0; k < 3u; ++k) {
        char name[32];
        (void)snprintf(name, sizeof name, "pft_tpf_a%02u.pgm", k);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_remove(name));
    }
}

static void test_pgm16_round_trip_and_depth(void)
{
    static uint16_t px[W * H];
    static const uint8_t depths[] = {14u, 0u, 10u};
    for (uint32_t d = 0; d < 3u; ++d) {
        uint32_t maxv = (depths[d] == 0u) ? 65535u : ((1u << depths[d]) - 1u);
        for (uint32_t i = 0; i < W * H; ++i) {
            px[i] = (uint16_t)((i * 2749u + 0x0102u) % (maxv + 1u));
        }
        px[0] = (uint16_t)maxv;
        pft_frame_t f = frame_of(px, W, H, PFT_PIX_U16, depths[d]);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pnm_write("pft_tpf_b.pgm", &f));
        pft_frame_t g;
        pft_file_error_t e = PFT_FILE_E_READ;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pnm_read("pft_tpf_b.pgm", buf, sizeof buf, &g, &e));
        TEST_ASSERT_EQUAL_INT(PFT_FILE_E_NONE, e);
        TEST_ASSERT_EQUAL_INT(PFT_PIX_U16, g.format);
        TEST_ASSERT_EQUAL_UINT8(depths[d] == 0u ? 16u : depths[d], g.bit_depth);
        TEST_ASSERT_EQUAL_UINT32(2u * W, g.stride_bytes);
        TEST_ASSERT_EQUAL_UINT16_ARRAY(px, g.data, W * H);
    }
    (void)pft_file_remove("pft_tpf_b.pgm");
}

static void test_pgm16_is_big_endian_and_comments_skipped(void)
{
    static const char hdr[] = "P5\n# made by hand\n2 # width\n1\n#maxval next\n65535\n";
    uint8_t bytes[sizeof hdr - 1u + 4u];
    memcpy(bytes, hdr, sizeof hdr - 1u);
    bytes[sizeof hdr - 1u] = 0x12u;
    bytes[sizeof hdr] = 0x34u;
    bytes[sizeof hdr + 1u] = 0xABu;
    bytes[sizeof hdr + 2u] = 0xCDu;
    write_bytes("pft_tpf_c.pgm", bytes, sizeof bytes, false);
    pft_frame_t g;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pnm_read("pft_tpf_c.pgm", buf, sizeof buf, &g, NULL));
    const uint16_t *v = (const uint16_t *)g.data;
    TEST_ASSERT_EQUAL_UINT16(2u, g.width);
    TEST_ASSERT_EQUAL_HEX16(0x1234u, v[0]);
    TEST_ASSERT_EQUAL_HEX16(0xABCDu, v[1]);
    /* and the writer produces the same bytes for the same pixels */
    pft_frame_t f = frame_of(v, 2u, 1u, PFT_PIX_U16, 16u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pnm_write("pft_tpf_c.pgm", &f));
    pft_file_config_t c = cfg_of("pft_tpf_c.pgm", PFT_FILE_CONCAT, PFT_FILE_RAW);
    c.width = 17u; /* "P5\n2 1\n65535\n" is 13 bytes, + 4 pixel bytes */
    c.height = 1u;
    c.format = PFT_PIX_U8;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_source_init(&fs, &c));
    pft_frame_t r;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_acquire(&fs, &r, 0u));
    TEST_ASSERT_EQUAL_MEMORY("P5\n2 1\n65535\n\x12\x34\xAB\xCD", r.data, 17u);
    pft_file_release(&fs, &r);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, pft_file_acquire(&fs, &r, 0u));
    pft_file_source_close(&fs);
    (void)pft_file_remove("pft_tpf_c.pgm");
}

static void test_ppm_round_trip_rgb_and_bgr(void)
{
    static uint8_t px[W * H * 3u];
    for (uint32_t i = 0; i < sizeof px; ++i) {
        px[i] = (uint8_t)(i * 13u + 1u);
    }
    pft_frame_t f = frame_of(px, W, H, PFT_PIX_RGB888, 0u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pnm_write("pft_tpf_d.ppm", &f));
    pft_frame_t g;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pnm_read("pft_tpf_d.ppm", buf, sizeof buf, &g, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_PIX_RGB888, g.format);
    TEST_ASSERT_EQUAL_UINT32(3u * W, g.stride_bytes);
    TEST_ASSERT_EQUAL_UINT8_ARRAY(px, g.data, sizeof px);
    f.format = PFT_PIX_BGR888; /* same bytes read as B,G,R: the file holds them swapped */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pnm_write("pft_tpf_d.ppm", &f));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pnm_read("pft_tpf_d.ppm", buf, sizeof buf, &g, NULL));
    const uint8_t *q = (const uint8_t *)g.data;
    for (uint32_t i = 0; i < W * H; ++i) {
        TEST_ASSERT_EQUAL_UINT8(px[3u * i + 2u], q[3u * i]);
        TEST_ASSERT_EQUAL_UINT8(px[3u * i + 1u], q[3u * i + 1u]);
        TEST_ASSERT_EQUAL_UINT8(px[3u * i], q[3u * i + 2u]);
    }
    /* 16-bit PPM is refused clearly */
    write_text("pft_tpf_d.ppm", "P6\n1 1\n65535\n\x01\x02\x03\x04\x05\x06");
    pft_file_error_t e;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pnm_read("pft_tpf_d.ppm", buf, sizeof buf, &g, &e));
    TEST_ASSERT_EQUAL_INT(PFT_FILE_E_UNSUPPORTED, e);
    (void)pft_file_remove("pft_tpf_d.ppm");
}

static void test_truncated_file_then_next_reads(void)
{
    static uint8_t px[W * H];
    memset(px, 0x5A, sizeof px);
    pft_frame_t f = frame_of(px, W, H, PFT_PIX_U8, 0u);
    (void)pft_file_remove("pft_tpf_e4.pgm");
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pnm_write("pft_tpf_e0.pgm", &f));
    write_text("pft_tpf_e1.pgm", "P5\n7 5\n255\nabcde");  /* pixels cut short */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pnm_write("pft_tpf_e2.pgm", &f));
    write_text("pft_tpf_e3.pgm", "P5\n7 ");               /* header cut short */
    pft_file_config_t c = cfg_of("pft_tpf_e%u.pgm", PFT_FILE_PER_FRAME, PFT_FILE_PNM);
    c.first_index = 0u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_source_init(&fs, &c));
    pft_frame_t g;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_acquire(&fs, &g, 0u));
    pft_file_release(&fs, &g);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_file_acquire(&fs, &g, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_FILE_E_TRUNCATED, fs.last_error);
    TEST_ASSERT_EQUAL_STRING("pft_tpf_e1.pgm", fs.name);
    TEST_ASSERT_NULL(g.data);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_acquire(&fs, &g, 0u));
    TEST_ASSERT_EQUAL_UINT32(2u, g.seq);
    TEST_ASSERT_EQUAL_UINT8_ARRAY(px, g.data, W * H);
    pft_file_release(&fs, &g);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_file_acquire(&fs, &g, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_FILE_E_TRUNCATED, fs.last_error);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, pft_file_acquire(&fs, &g, 0u));
    TEST_ASSERT_EQUAL_UINT32(2u, fs.stats.errors);
    TEST_ASSERT_EQUAL_UINT32(2u, fs.stats.frames);
    for (unsigned k = 0; k < 4u; ++k) {
        char name[32];
        (void)snprintf(name, sizeof name, "pft_tpf_e%u.pgm", k);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_remove(name));
    }
}

static void test_bad_magic_and_header(void)
{
    pft_frame_t g;
    pft_file_error_t e;
    write_text("pft_tpf_f.pgm", "P2\n1 1\n255\n0\n");
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pnm_read("pft_tpf_f.pgm", buf, sizeof buf, &g, &e));
    TEST_ASSERT_EQUAL_INT(PFT_FILE_E_MAGIC, e);
    write_text("pft_tpf_f.pgm", "BM6\n");
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pnm_read("pft_tpf_f.pgm", buf, sizeof buf, &g, &e));
    TEST_ASSERT_EQUAL_INT(PFT_FILE_E_MAGIC, e);
    write_text("pft_tpf_f.pgm", "P5\n0 1\n255\n");
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pnm_read("pft_tpf_f.pgm", buf, sizeof buf, &g, &e));
    TEST_ASSERT_EQUAL_INT(PFT_FILE_E_HEADER, e);
    write_text("pft_tpf_f.pgm", "P5\nx 1\n255\n");
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pnm_read("pft_tpf_f.pgm", buf, sizeof buf, &g, &e));
    TEST_ASSERT_EQUAL_INT(PFT_FILE_E_HEADER, e);
    write_text("pft_tpf_f.pgm", "P5\n1 1\n70000\n");
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pnm_read("pft_tpf_f.pgm", buf, sizeof buf, &g, &e));
    TEST_ASSERT_EQUAL_INT(PFT_FILE_E_HEADER, e);
    write_text("pft_tpf_f.pgm", "P5\n200 200\n255\n");
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pnm_read("pft_tpf_f.pgm", buf, sizeof buf, &g, &e));
    TEST_ASSERT_EQUAL_INT(PFT_FILE_E_TOO_BIG, e);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_IO, pft_pnm_read("pft_tpf_nonexistent.pgm", buf, sizeof buf, &g, &e));
    TEST_ASSERT_EQUAL_INT(PFT_FILE_E_OPEN, e);
    /* configured geometry enforced by the source */
    write_text("pft_tpf_f.pgm", "P5\n2 2\n255\nabcd");
    pft_file_config_t c = cfg_of("pft_tpf_f.pgm", PFT_FILE_CONCAT, PFT_FILE_PNM);
    c.width = 3u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_source_init(&fs, &c));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_file_acquire(&fs, &g, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_FILE_E_GEOMETRY, fs.last_error);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, pft_file_acquire(&fs, &g, 0u)); /* stream ends */
    pft_file_source_close(&fs);
    (void)pft_file_remove("pft_tpf_f.pgm");
}

/* Missing pattern files inside the sequence: one PFT_ERR_IO for the whole run of them, then
 * the later file with its own index as seq (the consumer sees the gap); more than
 * PFT_FILE_MAX_GAP missing files end the sequence. */
static void gap_case(uint32_t later, bool found)
{
    static const char a[] = "P5\n1 1\n255\nA";
    static const char c2[] = "P5\n1 1\n255\nC";
    char name[64];
    for (uint32_t i = 1u; i <= PFT_FILE_MAX_GAP + 2u; ++i) {
        (void)snprintf(name, sizeof name, "pft_tpf_g%u.pgm", (unsigned)i);
        (void)pft_file_remove(name);
    }
    write_text("pft_tpf_g0.pgm", a);
    (void)snprintf(name, sizeof name, "pft_tpf_g%u.pgm", (unsigned)later);
    write_text(name, c2);
    pft_file_config_t c = cfg_of("pft_tpf_g%u.pgm", PFT_FILE_PER_FRAME, PFT_FILE_PNM);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_source_init(&fs, &c));
    pft_frame_t g;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_acquire(&fs, &g, 0u));
    TEST_ASSERT_EQUAL_UINT8('A', *(const uint8_t *)g.data);
    TEST_ASSERT_EQUAL_UINT32(0u, g.seq);
    pft_file_release(&fs, &g);
    if (found) {
        TEST_ASSERT_EQUAL_INT(PFT_ERR_IO, pft_file_acquire(&fs, &g, 0u));
        TEST_ASSERT_EQUAL_INT(PFT_FILE_E_OPEN, fs.last_error);
        TEST_ASSERT_EQUAL_UINT32(later - 1u, fs.stats.missing);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_acquire(&fs, &g, 0u));
        TEST_ASSERT_EQUAL_UINT8('C', *(const uint8_t *)g.data);
        TEST_ASSERT_EQUAL_UINT32(later, g.seq);
        TEST_ASSERT_EQUAL_UINT64((uint64_t)later * c.frame_period_us, g.timestamp_us);
        pft_file_release(&fs, &g);
    } else {
        TEST_ASSERT_EQUAL_UINT32(0u, fs.stats.missing);
    }
    TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, pft_file_acquire(&fs, &g, 0u));
    TEST_ASSERT_EQUAL_UINT32(found ? 2u : 1u, fs.stats.frames);
    (void)pft_file_remove("pft_tpf_g0.pgm");
    (void)pft_file_remove(name);
}

static void test_gap_in_pattern_is_io_then_continues(void)
{
    gap_case(2u, true); /* one file missing */
    gap_case(4u, true); /* three files missing: one call */
    gap_case(PFT_FILE_MAX_GAP + 1u, true); /* the longest gap */
    gap_case(PFT_FILE_MAX_GAP + 2u, false); /* one more: the sequence has ended */
}

static void test_raw_concat_u16_and_truncated_tail(void)
{
    static uint16_t px[W * H];
    (void)pft_file_remove("pft_tpf_h.raw");
    for (uint32_t k = 0; k < 3u; ++k) {
        for (uint32_t i = 0; i < W * H; ++i) {
            px[i] = (uint16_t)(k * 1000u + i * 300u);
        }
        pft_frame_t f = frame_of(px, W, H, PFT_PIX_U16, 12u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_raw_write("pft_tpf_h.raw", &f, k > 0u));
    }
    write_bytes("pft_tpf_h.raw", "xyz", 3u, true); /* a partial fourth frame */
    pft_file_config_t c = cfg_of("pft_tpf_h.raw", PFT_FILE_CONCAT, PFT_FILE_RAW);
    c.width = W;
    c.height = H;
    c.format = PFT_PIX_U16;
    c.bit_depth = 12u;
    c.first_index = 10u;
    c.slots = 3u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_source_init(&fs, &c));
    pft_frame_t g[3];
    for (uint32_t k = 0; k < 3u; ++k) { /* hold all three: three slots */
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_acquire(&fs, &g[k], 0u));
        TEST_ASSERT_EQUAL_UINT32(10u + k, g[k].seq);
        TEST_ASSERT_EQUAL_UINT64(40000u * k, g[k].timestamp_us);
        TEST_ASSERT_EQUAL_UINT8(12u, g[k].bit_depth);
    }
    pft_frame_t extra;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_file_acquire(&fs, &extra, 0u));
    for (uint32_t k = 0; k < 3u; ++k) {
        const uint16_t *v = (const uint16_t *)g[k].data;
        for (uint32_t i = 0; i < W * H; ++i) {
            TEST_ASSERT_EQUAL_UINT16((uint16_t)(k * 1000u + i * 300u), v[i]);
        }
        pft_file_release(&fs, &g[k]);
    }
    pft_file_release(&fs, &g[0]); /* twice: ignored, counted */
    TEST_ASSERT_EQUAL_UINT32(1u, fs.stats.bad_releases);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_file_acquire(&fs, &extra, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_FILE_E_TRUNCATED, fs.last_error);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, pft_file_acquire(&fs, &extra, 0u));
    pft_file_source_close(&fs);

    /* the same bytes read big-endian give byte-swapped values */
    c.raw_big_endian = true;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_source_init(&fs, &c));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_acquire(&fs, &extra, 0u));
    TEST_ASSERT_EQUAL_HEX16(0x2C01u, ((const uint16_t *)extra.data)[1]); /* 300 = 0x012C */
    pft_file_release(&fs, &extra);
    pft_file_source_close(&fs);
    (void)pft_file_remove("pft_tpf_h.raw");
}

static void test_pnm_concat_stream(void)
{
    (void)pft_file_remove("pft_tpf_i.pgm");
    write_text("pft_tpf_i.pgm", "P5\n2 1\n255\nab");
    write_bytes("pft_tpf_i.pgm", "P5 # two\n2 1 255\ncd", 19u, true);
    pft_file_config_t c = cfg_of("pft_tpf_i.pgm", PFT_FILE_CONCAT, PFT_FILE_PNM);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_source_init(&fs, &c));
    pft_frame_t g;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_acquire(&fs, &g, 0u));
    TEST_ASSERT_EQUAL_MEMORY("ab", g.data, 2u);
    pft_file_release(&fs, &g);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_acquire(&fs, &g, 0u));
    TEST_ASSERT_EQUAL_MEMORY("cd", g.data, 2u);
    TEST_ASSERT_EQUAL_UINT32(1u, g.seq);
    pft_file_release(&fs, &g);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, pft_file_acquire(&fs, &g, 0u));
    pft_file_source_close(&fs);
    pft_file_source_close(&fs); /* twice is fine */
    (void)pft_file_remove("pft_tpf_i.pgm");
}

static pft_status_t count_consumer(void *ctx, const pft_frame_t *f)
{
    (void)f;
    (*(uint32_t *)ctx)++;
    return PFT_OK;
}

static void test_runner_over_file_sequence(void)
{
    static uint8_t px[W * H];
    memset(px, 3, sizeof px);
    pft_frame_t f = frame_of(px, W, H, PFT_PIX_U8, 0u);
    (void)pft_file_remove("pft_tpf_j4.pgm");
    (void)pft_file_remove("pft_tpf_j5.pgm");
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pnm_write("pft_tpf_j0.pgm", &f));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pnm_write("pft_tpf_j1.pgm", &f));
    write_text("pft_tpf_j2.pgm", "P5\n7 5\n255\n");
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pnm_write("pft_tpf_j3.pgm", &f));
    pft_file_config_t c = cfg_of("pft_tpf_j%u.pgm", PFT_FILE_PER_FRAME, PFT_FILE_PNM);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_source_init(&fs, &c));
    pft_frame_source_t s = pft_file_as_source(&fs);
    pft_runner_stats_t st;
    uint32_t n = 0u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_runner_run(&s, count_consumer, &n, NULL, NULL, &st));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, st.stop);
    TEST_ASSERT_EQUAL_UINT32(3u, st.frames);
    TEST_ASSERT_EQUAL_UINT32(3u, n);
    TEST_ASSERT_EQUAL_UINT32(1u, st.format_errors);
    TEST_ASSERT_EQUAL_UINT32(1u, st.dropped); /* seq 2 is missing from the delivered frames */
    TEST_ASSERT_EQUAL_UINT32(3u, fs.stats.released);
    for (unsigned k = 0; k < 4u; ++k) {
        char name[32];
        (void)snprintf(name, sizeof name, "pft_tpf_j%u.pgm", k);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_remove(name));
    }
}

static void test_argument_checks(void)
{
    pft_file_config_t c = cfg_of("pft_tpf_k%u.pgm", PFT_FILE_PER_FRAME, PFT_FILE_PNM);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(NULL, &c));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, NULL));
    static const char *const bad_patterns[] = {"f.pgm", "f%s.pgm", "f%u_%u.pgm", "f%lu.pgm",
                                               "f%", "f%%.pgm"};
    for (uint32_t i = 0; i < 6u; ++i) {
        c.path = bad_patterns[i];
        TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, &c));
    }
    c.path = "f%%_%05u.pgm";
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_source_init(&fs, &c));
    c.path = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, &c));
    c = cfg_of("pft_tpf_k%u.pgm", PFT_FILE_PER_FRAME, PFT_FILE_PNM);
    c.slots = PFT_FILE_MAX_SLOTS + 1u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, &c));
    c = cfg_of("pft_tpf_k%u.raw", PFT_FILE_PER_FRAME, PFT_FILE_RAW);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, &c)); /* no geometry */
    c.width = 100u;
    c.height = 100u;
    c.format = PFT_PIX_U16;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_file_source_init(&fs, &c));
    c = cfg_of("pft_tpf_nonexistent.raw", PFT_FILE_CONCAT, PFT_FILE_PNM);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_IO, pft_file_source_init(&fs, &c));
    c = cfg_of("pft_tpf_k%u.pgm", PFT_FILE_PER_FRAME, PFT_FILE_PNM);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_source_init(&fs, &c));
    pft_frame_t g;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_acquire(NULL, &g, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_acquire(&fs, NULL, 0u));
    pft_file_release(NULL, &g);
    pft_file_release(&fs, NULL);
    TEST_ASSERT_EQUAL_UINT32(1u, fs.stats.bad_releases);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, pft_file_acquire(&fs, &g, 0u)); /* empty sequence */

    static float fpx[4];
    pft_frame_t f = frame_of(fpx, 2u, 2u, PFT_PIX_F32, 0u);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pnm_write(NULL, &f));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pnm_write("pft_tpf_k.pgm", NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pnm_write("pft_tpf_k.pgm", &f));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_raw_write(NULL, &f, false));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pnm_read(NULL, buf, sizeof buf, &g, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pnm_read("x", NULL, sizeof buf, &g, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_remove(NULL));
    TEST_ASSERT_EQUAL_STRING("file truncated", pft_file_error_str(PFT_FILE_E_TRUNCATED));
    TEST_ASSERT_NOT_NULL(pft_file_error_str((pft_file_error_t)99));
}

/* The whole pattern is checked, not only its first PFT_FILE_NAME_MAX characters: a second
 * conversion (here %s, which would read a missing argument) after a long run of text is
 * refused, and so is any pattern too long to ever give a usable name. A width of more than
 * three digits is refused too (no name is that long; snprintf would pad it for nothing). */
static void test_long_patterns_refused(void)
{
    static char pat[PFT_FILE_NAME_MAX + 64u];
    pft_file_config_t c = cfg_of(pat, PFT_FILE_PER_FRAME, PFT_FILE_PNM);
    /* "%u" + 300 x 'a' + "%s": one integer conversion in the first 256 characters */
    memset(pat, 0, sizeof pat);
    memcpy(pat, "%u", 2u);
    memset(pat + 2, 'a', PFT_FILE_NAME_MAX + 44u);
    memcpy(pat + PFT_FILE_NAME_MAX + 46u, "%s", 2u);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, &c));
    /* a long pattern with one valid conversion: refused too (no name fits) */
    pat[PFT_FILE_NAME_MAX + 46u] = '\0';
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, &c));
    /* the longest pattern accepted: PFT_FILE_NAME_MAX - 1 characters */
    pat[PFT_FILE_NAME_MAX - 1u] = '\0';
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_source_init(&fs, &c));
    pat[PFT_FILE_NAME_MAX] = 'a';
    pat[PFT_FILE_NAME_MAX - 1u] = 'a';
    pat[PFT_FILE_NAME_MAX + 1u] = '\0';
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, &c));
    /* widths */
    c.path = "f%0999u.pgm";
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_source_init(&fs, &c));
    c.path = "f%01000u.pgm";
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, &c));
    c.path = "f%99999999999u.pgm";
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, &c));
    /* a width that makes the name too long: init accepts it, acquire reports the name */
    c.path = "f%0300u.pgm";
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_source_init(&fs, &c));
    pft_frame_t g;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_IO, pft_file_acquire(&fs, &g, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_FILE_E_NAME, fs.last_error);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, pft_file_acquire(&fs, &g, 0u));
}

/* Header corner cases of the PNM parser, each with the status and detail it must give:
 * whitespace of every kind and comments between the fields, numbers of nine digits, a missing
 * or wrong separator before the pixels, a file ending inside the magic or the header, the
 * height checked against the configuration, and the widths and patterns of pattern_ok. */
static void test_pnm_header_corner_cases(void)
{
    static const struct {
        const char *text;
        pft_status_t st;
        pft_file_error_t e;
    } cases[] = {
        {"P5\v2\f2 #c\n#\r255\tABCD", PFT_OK, PFT_FILE_E_NONE},     /* all whitespace kinds */
        {"P5 2 2 255\rABCD", PFT_OK, PFT_FILE_E_NONE},               /* CR before the pixels */
        {"P5\n2 2\n255#\nABCD", PFT_ERR_FORMAT, PFT_FILE_E_HEADER},   /* '#' as the separator */
        {"P5\n123456789 1\n255\n", PFT_ERR_FORMAT, PFT_FILE_E_HEADER}, /* nine digits */
        {"P5\n00000001 1\n255\nA", PFT_OK, PFT_FILE_E_NONE},         /* eight digits */
        {"P5\n1 0\n255\n", PFT_ERR_FORMAT, PFT_FILE_E_HEADER},         /* zero height */
        {"P5\n1 1\n0\n", PFT_ERR_FORMAT, PFT_FILE_E_HEADER},           /* zero maxval */
        {"P5\n1 1\n255", PFT_ERR_FORMAT, PFT_FILE_E_TRUNCATED},        /* no separator */
        {"P5\n1 1", PFT_ERR_FORMAT, PFT_FILE_E_TRUNCATED},              /* ends in the header */
        {"P5\n1 1\n255\n", PFT_ERR_FORMAT, PFT_FILE_E_TRUNCATED},      /* no pixels */
        {"P", PFT_ERR_FORMAT, PFT_FILE_E_TRUNCATED},                    /* ends in the magic */
        {"P5 #only a comment", PFT_ERR_FORMAT, PFT_FILE_E_TRUNCATED},
        {"P6\n1 1\n255\nRGB", PFT_OK, PFT_FILE_E_NONE},
        {"P5\n1 1\n1023\n\x03\xff", PFT_OK, PFT_FILE_E_NONE},         /* 10-bit */
    };
    for (uint32_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        pft_frame_t g;
        pft_file_error_t e = PFT_FILE_E_OPEN;
        write_text("pft_tpf_hc.pgm", cases[i].text);
        pft_status_t st = pft_pnm_read("pft_tpf_hc.pgm", buf, sizeof buf, &g, &e);
        char msg[48];
        (void)snprintf(msg, sizeof msg, "case %u", (unsigned)i);
        TEST_ASSERT_EQUAL_INT_MESSAGE(cases[i].st, st, msg);
        TEST_ASSERT_EQUAL_INT_MESSAGE(cases[i].e, e, msg);
    }
    /* the source checks the height it was configured with */
    write_text("pft_tpf_hc.pgm", "P5\n2 2\n255\nabcd");
    pft_file_config_t c = cfg_of("pft_tpf_hc.pgm", PFT_FILE_CONCAT, PFT_FILE_PNM);
    c.width = 2u;
    c.height = 3u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_source_init(&fs, &c));
    pft_frame_t g;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_file_acquire(&fs, &g, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_FILE_E_GEOMETRY, fs.last_error);
    pft_file_source_close(&fs);
    pft_file_source_close(&fs); /* twice is fine */
    /* the error detail is optional */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pnm_read("pft_tpf_hc.pgm", buf, sizeof buf, &g, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_IO, pft_pnm_read("pft_tpf_none.pgm", buf, sizeof buf, &g, NULL));
    (void)pft_file_remove("pft_tpf_hc.pgm");
    /* patterns: flags, a three-digit width, a conversion at the very end, %% after it */
    static const char *const good[] = {"f%-3u.pgm", "f%+d.pgm", "f% d.pgm", "f%#x.pgm", "f%u",
                                       "f%o%%.pgm", "%X"};
    static const char *const bad[] = {"f%-.pgm", "f%5", "f%5.2u.pgm", "%%", "f%u%%%u.pgm"};
    c = cfg_of(NULL, PFT_FILE_PER_FRAME, PFT_FILE_PNM);
    for (uint32_t i = 0; i < sizeof good / sizeof good[0]; ++i) {
        c.path = good[i];
        TEST_ASSERT_EQUAL_INT_MESSAGE(PFT_OK, pft_file_source_init(&fs, &c), good[i]);
    }
    for (uint32_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        c.path = bad[i];
        TEST_ASSERT_EQUAL_INT_MESSAGE(PFT_ERR_INVAL, pft_file_source_init(&fs, &c), bad[i]);
    }
    /* every detail has a name */
    for (int k = 0; k <= (int)PFT_FILE_E_NAME; ++k) {
        TEST_ASSERT_NOT_NULL(pft_file_error_str((pft_file_error_t)k));
    }
    TEST_ASSERT_EQUAL_STRING("file name too long", pft_file_error_str(PFT_FILE_E_NAME));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_pgm8_sequence_round_trip);
    RUN_TEST(test_pgm16_round_trip_and_depth);
    RUN_TEST(test_pgm16_is_big_endian_and_comments_skipped);
    RUN_TEST(test_ppm_round_trip_rgb_and_bgr);
    RUN_TEST(test_truncated_file_then_next_reads);
    RUN_TEST(test_bad_magic_and_header);
    RUN_TEST(test_gap_in_pattern_is_io_then_continues);
    RUN_TEST(test_raw_concat_u16_and_truncated_tail);
    RUN_TEST(test_pnm_concat_stream);
    RUN_TEST(test_runner_over_file_sequence);
    RUN_TEST(test_argument_checks);
    RUN_TEST(test_long_patterns_refused);
    RUN_TEST(test_pnm_header_corner_cases);
    return UNITY_END();
}
