/*
 * Raw and PGM/PPM frame sources and writers over C stdio (see pft_port_file.h).
 * stdio is fine here: this is port code, never linked into lib/.
 */
#include <stdio.h>
#include <string.h>

#include "pft/pft_port_file.h"

#define PNM_MAX_NUMBER 65535u
#define PNM_MAX_COMMENT 4096u /* bound on one comment line */
#define PNM_MAX_SPACE 4096u   /* bound on whitespace/comment runs in a header */

const char *pft_file_error_str(pft_file_error_t e)
{
    switch (e) {
    case PFT_FILE_E_NONE: return "no error";
    case PFT_FILE_E_OPEN: return "cannot open file";
    case PFT_FILE_E_READ: return "read error";
    case PFT_FILE_E_TRUNCATED: return "file truncated";
    case PFT_FILE_E_MAGIC: return "bad magic (not P5/P6)";
    case PFT_FILE_E_HEADER: return "malformed header";
    case PFT_FILE_E_UNSUPPORTED: return "unsupported netpbm variant";
    case PFT_FILE_E_GEOMETRY: return "size differs from configuration";
    case PFT_FILE_E_TOO_BIG: return "frame larger than buffer slot";
    case PFT_FILE_E_NAME: return "file name too long";
    default: return "unknown file error";
    }
}

/* ------------------------------------------------------------------------------------------ */
/* helpers                                                                                    */

#define PATTERN_MAX_WIDTH_DIGITS 3u /* a width above 999 could never give a usable name */

/* Exactly one integer conversion (flags and a width of at most three digits, no precision, no
 * length modifier), %% allowed, and shorter than PFT_FILE_NAME_MAX characters. The whole
 * pattern is checked: whatever reaches snprintf has been seen here. */
static bool pattern_ok(const char *p)
{
    uint32_t conversions = 0u;
    size_t i = 0u;
    while (i < PFT_FILE_NAME_MAX && p[i] != '\0') {
        if (p[i] != '%') {
            ++i;
            continue;
        }
        ++i;
        if (i < PFT_FILE_NAME_MAX && p[i] == '%') {
            ++i;
            continue;
        }
        while (i < PFT_FILE_NAME_MAX &&
               (p[i] == '0' || p[i] == '-' || p[i] == '+' || p[i] == ' ' || p[i] == '#')) {
            ++i;
        }
        uint32_t digits = 0u;
        while (i < PFT_FILE_NAME_MAX && p[i] >= '0' && p[i] <= '9') {
            ++i;
            ++digits;
        }
        if (i >= PFT_FILE_NAME_MAX || digits > PATTERN_MAX_WIDTH_DIGITS || p[i] == '\0' ||
            strchr("udixXo", p[i]) == NULL) {
            return false;
        }
        ++i;
        conversions++;
    }
    /* stopped at the terminator (i < PFT_FILE_NAME_MAX), or the pattern is too long */
    return i < PFT_FILE_NAME_MAX && conversions == 1u;
}

/* The pattern is the user's, checked by pattern_ok to hold one integer conversion. */
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wformat-nonliteral"
#endif
static bool make_name(char *dst, const char *pattern, uint32_t index)
{
    int n = snprintf(dst, PFT_FILE_NAME_MAX, pattern, (unsigned)index);
    return n > 0 && (unsigned)n < PFT_FILE_NAME_MAX;
}
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

/* Converts n 16-bit samples stored with the given byte order to host order, in place. */
static void u16_to_host(uint8_t *p, size_t n, bool big_endian)
{
    for (size_t i = 0; i < n; ++i) {
        uint8_t b0 = p[2u * i];
        uint8_t b1 = p[2u * i + 1u];
        uint16_t v = big_endian ? (uint16_t)(((unsigned)b0 << 8) | b1)
                                : (uint16_t)(((unsigned)b1 << 8) | b0);
        memcpy(p + 2u * i, &v, 2u);
    }
}

/* Reads exactly n bytes: PFT_OK, or FORMAT (truncated) / IO (read error) with the detail. */
static pft_status_t read_exact(FILE *fp, void *dst, size_t n, pft_file_error_t *err)
{
    size_t got = fread(dst, 1u, n, fp);
    if (got == n) {
        return PFT_OK;
    }
    if (ferror(fp) != 0) {
        *err = PFT_FILE_E_READ;
        return PFT_ERR_IO;
    }
    *err = PFT_FILE_E_TRUNCATED;
    return PFT_ERR_FORMAT;
}

/* Skips whitespace and comments, then reads a decimal number in 0..PNM_MAX_NUMBER. */
static pft_status_t pnm_number(FILE *fp, uint32_t *v, pft_file_error_t *err)
{
    int c = fgetc(fp);
    for (uint32_t n = 0; n < PNM_MAX_SPACE; ++n) {
        if (c == '#') {
            uint32_t k = 0;
            while (c != '\n' && c != '\r' && c != EOF && k < PNM_MAX_COMMENT) {
                c = fgetc(fp);
                ++k;
            }
        }
        if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f') {
            c = fgetc(fp);
        } else {
            break;
        }
    }
    if (c == EOF) {
        *err = (ferror(fp) != 0) ? PFT_FILE_E_READ : PFT_FILE_E_TRUNCATED;
        return (ferror(fp) != 0) ? PFT_ERR_IO : PFT_ERR_FORMAT;
    }
    if (c < '0' || c > '9') {
        *err = PFT_FILE_E_HEADER;
        return PFT_ERR_FORMAT;
    }
    uint32_t x = 0u;
    for (uint32_t n = 0; n < 8u && c >= '0' && c <= '9'; ++n) {
        x = x * 10u + ((uint32_t)c - (uint32_t)'0');
        c = fgetc(fp);
    }
    if (c >= '0' && c <= '9') { /* more than 8 digits */
        *err = PFT_FILE_E_HEADER;
        return PFT_ERR_FORMAT;
    }
    if (c != EOF) {
        (void)ungetc(c, fp);
    }
    if (x > PNM_MAX_NUMBER) {
        *err = PFT_FILE_E_HEADER;
        return PFT_ERR_FORMAT;
    }
    *v = x;
    return PFT_OK;
}

static uint8_t bits_of(uint32_t maxval)
{
    uint32_t v = maxval;
    uint8_t b = 0u;
    while (v != 0u && b < 16u) {
        v >>= 1;
        ++b;
    }
    return b;
}

/* Reads one PNM image at the current position. want_w/want_h: 0 = any. */
static pft_status_t pnm_read_fp(FILE *fp, uint8_t *buf, size_t cap, uint16_t want_w,
                                uint16_t want_h, pft_frame_t *out, pft_file_error_t *err)
{
    int c0 = fgetc(fp);
    int c1 = fgetc(fp);
    if (c0 == EOF || c1 == EOF) {
        *err = (ferror(fp) != 0) ? PFT_FILE_E_READ : PFT_FILE_E_TRUNCATED;
        return (ferror(fp) != 0) ? PFT_ERR_IO : PFT_ERR_FORMAT;
    }
    if (c0 != 'P' || (c1 != '5' && c1 != '6')) {
        *err = PFT_FILE_E_MAGIC;
        return PFT_ERR_FORMAT;
    }
    uint32_t w = 0u, h = 0u, maxval = 0u;
    pft_status_t st = pnm_number(fp, &w, err);
    if (st == PFT_OK) {
        st = pnm_number(fp, &h, err);
    }
    if (st == PFT_OK) {
        st = pnm_number(fp, &maxval, err);
    }
    if (st != PFT_OK) {
        return st;
    }
    int sep = fgetc(fp); /* exactly one whitespace before the pixels */
    if (sep == EOF) {
        *err = (ferror(fp) != 0) ? PFT_FILE_E_READ : PFT_FILE_E_TRUNCATED;
        return (ferror(fp) != 0) ? PFT_ERR_IO : PFT_ERR_FORMAT;
    }
    if (w == 0u || h == 0u || maxval == 0u ||
        (sep != ' ' && sep != '\t' && sep != '\n' && sep != '\r')) {
        *err = PFT_FILE_E_HEADER;
        return PFT_ERR_FORMAT;
    }
    pft_pixfmt_t fmt;
    uint8_t depth = 0u;
    if (c1 == '5') {
        fmt = (maxval <= 255u) ? PFT_PIX_U8 : PFT_PIX_U16;
        depth = (maxval <= 255u) ? 0u : bits_of(maxval);
    } else {
        if (maxval > 255u) {
            *err = PFT_FILE_E_UNSUPPORTED;
            return PFT_ERR_FORMAT;
        }
        fmt = PFT_PIX_RGB888;
    }
    if ((want_w != 0u && w != want_w) || (want_h != 0u && h != want_h)) {
        *err = PFT_FILE_E_GEOMETRY;
        return PFT_ERR_FORMAT;
    }
    uint32_t row = w * pft_pixfmt_bytes(fmt);
    uint64_t bytes = (uint64_t)row * h;
    if (bytes > (uint64_t)cap) {
        *err = PFT_FILE_E_TOO_BIG;
        return PFT_ERR_FORMAT;
    }
    st = read_exact(fp, buf, (size_t)bytes, err);
    if (st != PFT_OK) {
        return st;
    }
    if (fmt == PFT_PIX_U16) {
        u16_to_host(buf, (size_t)w * h, true);
    }
    memset(out, 0, sizeof *out);
    out->data = buf;
    out->width = (uint16_t)w;
    out->height = (uint16_t)h;
    out->stride_bytes = row;
    out->format = fmt;
    out->bit_depth = depth;
    *err = PFT_FILE_E_NONE;
    return PFT_OK;
}

static pft_status_t raw_read_fp(const pft_file_config_t *c, FILE *fp, uint8_t *buf,
                                pft_frame_t *out, pft_file_error_t *err)
{
    uint32_t row = (uint32_t)c->width * pft_pixfmt_bytes(c->format);
    size_t bytes = (size_t)row * c->height;
    pft_status_t st = read_exact(fp, buf, bytes, err);
    if (st != PFT_OK) {
        return st;
    }
    if (c->format == PFT_PIX_U16) {
        u16_to_host(buf, (size_t)c->width * c->height, c->raw_big_endian);
    }
    memset(out, 0, sizeof *out);
    out->data = buf;
    out->width = c->width;
    out->height = c->height;
    out->stride_bytes = row;
    out->format = c->format;
    out->bit_depth = c->bit_depth;
    *err = PFT_FILE_E_NONE;
    return PFT_OK;
}

/* ------------------------------------------------------------------------------------------ */
/* source                                                                                     */

pft_status_t pft_file_source_init(pft_file_source_t *fs, const pft_file_config_t *cfg)
{
    if (fs == NULL || cfg == NULL || cfg->path == NULL || cfg->buffer == NULL) {
        return PFT_ERR_INVAL;
    }
    uint32_t slots = (cfg->slots == 0u) ? 1u : cfg->slots;
    if (slots > PFT_FILE_MAX_SLOTS ||
        (cfg->layout != PFT_FILE_PER_FRAME && cfg->layout != PFT_FILE_CONCAT) ||
        (cfg->encoding != PFT_FILE_PNM && cfg->encoding != PFT_FILE_RAW)) {
        return PFT_ERR_INVAL;
    }
    if (cfg->layout == PFT_FILE_PER_FRAME && !pattern_ok(cfg->path)) {
        return PFT_ERR_INVAL;
    }
    if (cfg->layout == PFT_FILE_CONCAT && strlen(cfg->path) >= PFT_FILE_NAME_MAX) {
        return PFT_ERR_INVAL;
    }
    size_t slot_bytes = (cfg->buffer_bytes / slots) & ~(size_t)3u; /* 4-byte aligned slots */
    if (slot_bytes > 0xFFFFFFFFu) {
        slot_bytes = 0xFFFFFFFCu;
    }
    if (cfg->encoding == PFT_FILE_RAW) {
        uint32_t bpp = pft_pixfmt_bytes(cfg->format);
        if (bpp == 0u || cfg->width == 0u || cfg->height == 0u ||
            (cfg->format == PFT_PIX_U16 && cfg->bit_depth > 16u)) {
            return PFT_ERR_INVAL;
        }
        if ((uint64_t)cfg->width * cfg->height * bpp > (uint64_t)slot_bytes) {
            return PFT_ERR_NOMEM;
        }
    }
    /* the only step that can still fail comes first: a refused init changes nothing in fs */
    FILE *fp = NULL;
    if (cfg->layout == PFT_FILE_CONCAT) {
        fp = fopen(cfg->path, "rb");
        if (fp == NULL) {
            return PFT_ERR_IO;
        }
    }
    memset(fs, 0, sizeof *fs);
    fs->cfg = *cfg;
    fs->cfg.slots = slots;
    fs->slot_bytes = (uint32_t)slot_bytes;
    for (uint32_t i = 0; i < slots; ++i) {
        fs->slot[i] = (uint8_t *)cfg->buffer + (size_t)i * slot_bytes;
    }
    fs->index = cfg->first_index;
    if (cfg->layout == PFT_FILE_CONCAT) {
        (void)snprintf(fs->name, sizeof fs->name, "%s", cfg->path);
        fs->fp = fp;
    }
    return PFT_OK;
}

void pft_file_source_close(pft_file_source_t *fs)
{
    if (fs != NULL && fs->fp != NULL) {
        (void)fclose((FILE *)fs->fp);
        fs->fp = NULL;
    }
}

pft_frame_source_t pft_file_as_source(pft_file_source_t *fs)
{
    pft_frame_source_t s;
    s.ctx = fs;
    s.acquire = pft_file_acquire;
    s.release = pft_file_release;
    return s;
}

static pft_status_t read_one(pft_file_source_t *fs, FILE *fp, uint8_t *buf, pft_frame_t *out)
{
    if (fs->cfg.encoding == PFT_FILE_RAW) {
        return raw_read_fp(&fs->cfg, fp, buf, out, &fs->last_error);
    }
    return pnm_read_fp(fp, buf, fs->slot_bytes, fs->cfg.width, fs->cfg.height, out,
                       &fs->last_error);
}

static bool file_exists(const char *name)
{
    FILE *fp = fopen(name, "rb");
    if (fp == NULL) {
        return false;
    }
    (void)fclose(fp);
    return true;
}

pft_status_t pft_file_acquire(void *ctx, pft_frame_t *out, uint32_t timeout_ms)
{
    pft_file_source_t *fs = (pft_file_source_t *)ctx;
    (void)timeout_ms; /* files never wait */
    if (fs == NULL || out == NULL) {
        return PFT_ERR_INVAL;
    }
    memset(out, 0, sizeof *out);
    if (fs->ended) {
        return PFT_ERR_EOF;
    }
    uint32_t s = 0u;
    while (s < fs->cfg.slots && fs->lent[s] != 0u) {
        ++s;
    }
    if (s == fs->cfg.slots) {
        return PFT_ERR_STATE;
    }
    fs->last_error = PFT_FILE_E_NONE;
    uint32_t seq = fs->index;
    pft_status_t st;
    if (fs->cfg.layout == PFT_FILE_PER_FRAME) {
        if (!make_name(fs->name, fs->cfg.path, seq)) {
            fs->last_error = PFT_FILE_E_NAME;
            fs->ended = true;
            fs->stats.errors++;
            return PFT_ERR_IO;
        }
        FILE *fp = fopen(fs->name, "rb");
        if (fp == NULL) {
            /* the end of the sequence, or a gap of up to PFT_FILE_MAX_GAP files if a later
               file is there: skipped in this one call, the next acquire reads that file */
            char next[PFT_FILE_NAME_MAX];
            /* the index must not wrap, and every name must fit */
            bool more = true;
            for (uint32_t j = 1u; more && j <= PFT_FILE_MAX_GAP; ++j) {
                more = seq + j > seq;
                if (more) {
                    more = make_name(next, fs->cfg.path, seq + j);
                }
                if (more && file_exists(next)) {
                    fs->index = seq + j;
                    fs->last_error = PFT_FILE_E_OPEN;
                    fs->stats.errors++;
                    fs->stats.missing += j;
                    return PFT_ERR_IO;
                }
            }
            fs->ended = true;
            return PFT_ERR_EOF;
        }
        st = read_one(fs, fp, fs->slot[s], out);
        (void)fclose(fp);
        fs->index++; /* good or bad, the next acquire reads the next file */
    } else {
        FILE *fp = (FILE *)fs->fp;
        if (fp == NULL) {
            fs->ended = true;
            return PFT_ERR_EOF;
        }
        int c = fgetc(fp);
        if (c == EOF) {
            fs->ended = true;
            if (ferror(fp) != 0) {
                fs->last_error = PFT_FILE_E_READ;
                fs->stats.errors++;
                return PFT_ERR_IO;
            }
            return PFT_ERR_EOF;
        }
        (void)ungetc(c, fp);
        st = read_one(fs, fp, fs->slot[s], out);
        fs->index++;
        if (st != PFT_OK) {
            fs->ended = true; /* a stream cannot be resynchronised after a bad frame */
        }
    }
    if (st != PFT_OK) {
        memset(out, 0, sizeof *out);
        fs->stats.errors++;
        return st;
    }
    out->seq = seq;
    out->timestamp_us = (uint64_t)(seq - fs->cfg.first_index) * fs->cfg.frame_period_us;
    fs->lent[s] = 1u;
    fs->stats.frames++;
    return PFT_OK;
}

void pft_file_release(void *ctx, const pft_frame_t *frame)
{
    pft_file_source_t *fs = (pft_file_source_t *)ctx;
    if (fs == NULL) {
        return;
    }
    if (frame != NULL) {
        for (uint32_t s = 0; s < fs->cfg.slots; ++s) {
            if (frame->data == (const void *)fs->slot[s] && fs->lent[s] != 0u) {
                fs->lent[s] = 0u;
                fs->stats.released++;
                return;
            }
        }
    }
    fs->stats.bad_releases++;
}

pft_status_t pft_pnm_read(const char *path, void *buf, size_t buf_bytes, pft_frame_t *out,
                          pft_file_error_t *err)
{
    pft_file_error_t e = PFT_FILE_E_NONE;
    if (err != NULL) {
        *err = PFT_FILE_E_NONE;
    }
    if (path == NULL || buf == NULL || out == NULL) {
        return PFT_ERR_INVAL;
    }
    memset(out, 0, sizeof *out);
    FILE *fp = fopen(path, "rb");
    if (fp == NULL) {
        if (err != NULL) {
            *err = PFT_FILE_E_OPEN;
        }
        return PFT_ERR_IO;
    }
    pft_status_t st = pnm_read_fp(fp, (uint8_t *)buf, buf_bytes, 0u, 0u, out, &e);
    (void)fclose(fp);
    if (st != PFT_OK) {
        memset(out, 0, sizeof *out);
    }
    if (err != NULL) {
        *err = e;
    }
    return st;
}

/* ------------------------------------------------------------------------------------------ */
/* writers                                                                                    */

enum { CHUNK = 192 }; /* multiple of 2 and 3 */

/* Writes one row, converting: U16 to big- or little-endian, BGR to RGB. */
static bool write_row(FILE *fp, const uint8_t *row, uint32_t width, pft_pixfmt_t fmt,
                      bool u16_big, bool swap_rb)
{
    uint32_t bpp = pft_pixfmt_bytes(fmt);
    size_t n = (size_t)width * bpp;
    if (fmt != PFT_PIX_U16 && !swap_rb) {
        return fwrite(row, 1u, n, fp) == n;
    }
    uint8_t tmp[CHUNK];
    for (size_t off = 0; off < n; off += CHUNK) {
        size_t len = (n - off < CHUNK) ? n - off : CHUNK;
        if (fmt == PFT_PIX_U16) {
            for (size_t i = 0; i + 1u < len; i += 2u) { /* len is even */
                uint16_t v;
                memcpy(&v, row + off + i, 2u);
                tmp[i] = (uint8_t)(u16_big ? (v >> 8) : (v & 0xFFu));
                tmp[i + 1u] = (uint8_t)(u16_big ? (v & 0xFFu) : (v >> 8));
            }
        } else {
            for (size_t i = 0; i + 2u < len; i += 3u) { /* len is a multiple of 3 */
                tmp[i] = row[off + i + 2u];
                tmp[i + 1u] = row[off + i + 1u];
                tmp[i + 2u] = row[off + i];
            }
        }
        if (fwrite(tmp, 1u, len, fp) != len) {
            return false;
        }
    }
    return true;
}

static pft_status_t write_frame(const char *path, const char *mode, const pft_frame_t *f,
                                const char *header, bool u16_big, bool swap_rb)
{
    FILE *fp = fopen(path, mode);
    if (fp == NULL) {
        return PFT_ERR_IO;
    }
    bool ok = true;
    if (header != NULL) {
        size_t hl = strlen(header);
        ok = fwrite(header, 1u, hl, fp) == hl;
    }
    for (uint32_t y = 0; ok && y < f->height; ++y) {
        ok = write_row(fp, pft_frame_row(f, y), f->width, f->format, u16_big, swap_rb);
    }
    if (fclose(fp) != 0) {
        ok = false;
    }
    return ok ? PFT_OK : PFT_ERR_IO;
}

pft_status_t pft_pnm_write(const char *path, const pft_frame_t *frame)
{
    if (path == NULL || frame == NULL) {
        return PFT_ERR_INVAL;
    }
    uint32_t mask = PFT_FMT_BIT(PFT_PIX_U8) | PFT_FMT_BIT(PFT_PIX_U16) |
                    PFT_FMT_BIT(PFT_PIX_RGB888) | PFT_FMT_BIT(PFT_PIX_BGR888);
    pft_status_t st = pft_frame_check(frame, 0u, 0u, mask);
    if (st != PFT_OK) {
        return st;
    }
    char header[64];
    unsigned maxval = 255u;
    char magic = '5';
    if (frame->format == PFT_PIX_U16) {
        uint8_t bd = frame->bit_depth;
        maxval = (bd >= 9u && bd <= 16u) ? (unsigned)((1UL << bd) - 1u) : 65535u;
    } else if (frame->format != PFT_PIX_U8) {
        magic = '6';
    } else {
        /* U8: P5, maxval 255 */
    }
    (void)snprintf(header, sizeof header, "P%c\n%u %u\n%u\n", magic, (unsigned)frame->width,
                   (unsigned)frame->height, maxval);
    return write_frame(path, "wb", frame, header, true, frame->format == PFT_PIX_BGR888);
}

pft_status_t pft_raw_write(const char *path, const pft_frame_t *frame, bool append)
{
    if (path == NULL || frame == NULL) {
        return PFT_ERR_INVAL;
    }
    pft_status_t st = pft_frame_check(frame, 0u, 0u, 0xFFFFFFFFu);
    if (st != PFT_OK) {
        return st;
    }
    return write_frame(path, append ? "ab" : "wb", frame, NULL, false, false);
}

pft_status_t pft_file_remove(const char *path)
{
    if (path == NULL) {
        return PFT_ERR_INVAL;
    }
    return (remove(path) == 0) ? PFT_OK : PFT_ERR_IO;
}
