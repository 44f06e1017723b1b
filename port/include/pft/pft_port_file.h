/**
 * @file pft_port_file.h
 * @brief Frame sources reading raw and PGM/PPM sequences with C stdio, and writers.
 *
 * Layouts: one file per frame, named by a printf pattern with one unsigned conversion
 * (`"seq/f%04u.pgm"`), or one file holding every frame back to back (raw frames of a given
 * geometry, or PGM/PPM images concatenated, as netpbm allows).
 *
 * Encodings:
 * - PNM: P5 (PGM) 8-bit (maxval <= 255) -> PFT_PIX_U8; P5 16-bit big-endian (maxval > 255)
 *   -> PFT_PIX_U16 with bit_depth = bits of maxval (1023 -> 10, 16383 -> 14, 65535 -> 16);
 *   P6 (PPM) 8-bit -> PFT_PIX_RGB888. Header comments (`#` to end of line) are skipped.
 *   P6 16-bit and the ASCII variants (P2/P3) are refused (PFT_ERR_FORMAT).
 * - RAW: packed rows, no header; geometry from the configuration. U16 little-endian unless
 *   `raw_big_endian`; F32 in the host's byte order.
 *
 * Pixels go into caller memory (no allocation), split in `slots` equal parts, one per frame
 * lent at once; U16 pixels are converted to the host's byte order in place.
 *
 * Status of acquire (the detail is in pft_file_source_t::last_error, see pft_file_error_str):
 * - PFT_ERR_EOF: the pattern's next file does not exist and neither does any of the
 *   PFT_FILE_MAX_GAP files after it, or the concatenated file ended cleanly at a frame
 *   boundary. Sticky.
 * - PFT_ERR_IO: pattern files are missing but a later one (at most PFT_FILE_MAX_GAP on)
 *   exists: the gap is skipped in this one call (stats.missing counts the files), and the
 *   next acquire reads that later file, whose seq is its index, so the consumer sees the gap
 *   in seq. Or a read error: the next acquire goes on with the next file.
 * - PFT_ERR_FORMAT: bad magic, malformed header, unsupported variant, geometry not as
 *   configured, frame larger than a slot, or a truncated file (fewer pixel bytes than the
 *   header announces). With one file per frame the next acquire reads the next file; a
 *   concatenated file cannot be resynchronised, so it ends (next acquire: PFT_ERR_EOF).
 * - PFT_ERR_STATE: every slot is lent. PFT_ERR_INVAL: NULL arguments.
 * Timestamps are synthetic: (seq - first_index) * frame_period_us; seq is the file index
 * (one file per frame) or first_index + frame number (concatenated).
 *
 * Works on bare metal wherever newlib's stdio works; under QEMU semihosting, fopen goes to the
 * host file system, relative to QEMU's working directory.
 */
#ifndef PFT_PORT_FILE_H
#define PFT_PORT_FILE_H

#include "pft/pft_port.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Longest file name a pattern may produce (including the terminating zero). */
#define PFT_FILE_NAME_MAX 256u
/** Longest run of missing pattern files taken as a gap (more: the sequence has ended). */
#define PFT_FILE_MAX_GAP 64u
/** Most frames lent at once by one file source. */
#define PFT_FILE_MAX_SLOTS 4u

/** How the frames are laid out in files. */
typedef enum {
    PFT_FILE_PER_FRAME = 0, /**< one file per frame, `path` is a printf pattern */
    PFT_FILE_CONCAT = 1     /**< one file, frames back to back, `path` is its name */
} pft_file_layout_t;

/** How a frame is encoded. */
typedef enum {
    PFT_FILE_PNM = 0, /**< binary PGM (P5) or PPM (P6) */
    PFT_FILE_RAW = 1  /**< headerless packed pixels */
} pft_file_encoding_t;

/** Why the last acquire failed (detail of the status code). */
typedef enum {
    PFT_FILE_E_NONE = 0,
    PFT_FILE_E_OPEN,        /**< file could not be opened */
    PFT_FILE_E_READ,        /**< read error reported by the C library */
    PFT_FILE_E_TRUNCATED,   /**< file ends inside a header or before all pixels */
    PFT_FILE_E_MAGIC,       /**< not P5 / P6 */
    PFT_FILE_E_HEADER,      /**< malformed header: missing or out-of-range number */
    PFT_FILE_E_UNSUPPORTED, /**< valid netpbm variant this port does not take (P6 16-bit) */
    PFT_FILE_E_GEOMETRY,    /**< width/height differ from the configured ones */
    PFT_FILE_E_TOO_BIG,     /**< frame larger than one slot of the buffer */
    PFT_FILE_E_NAME         /**< pattern result longer than PFT_FILE_NAME_MAX */
} pft_file_error_t;

/** Static description of a detail code (never NULL). */
const char *pft_file_error_str(pft_file_error_t e);

/** Configuration of a file source. */
typedef struct {
    const char *path;          /**< pattern (PER_FRAME) or file name (CONCAT); kept by pointer */
    pft_file_layout_t layout;  /**< one file per frame (pattern) or one concatenated file */
    pft_file_encoding_t encoding; /**< PNM (PGM/PPM headers) or RAW (headerless pixels) */
    uint32_t first_index;      /**< first pattern index; seq of the first frame */
    uint16_t width;            /**< RAW: required. PNM: 0 = any, else must match */
    uint16_t height;           /**< rows; same rule as `width` */
    pft_pixfmt_t format;       /**< RAW only */
    uint8_t bit_depth;         /**< RAW U16 significant bits (0: 16) */
    bool raw_big_endian;       /**< RAW U16 stored big-endian */
    uint64_t frame_period_us;  /**< synthetic timestamp step */
    void *buffer;              /**< pixel memory, caller-owned */
    size_t buffer_bytes;       /**< size of `buffer`: slots x the largest frame */
    uint32_t slots;            /**< frames lent at once, 1..PFT_FILE_MAX_SLOTS (0: 1) */
} pft_file_config_t;

/** Counters of a file source. */
typedef struct {
    uint32_t frames;       /**< frames lent */
    uint32_t errors;       /**< acquires that failed with IO or FORMAT */
    uint32_t missing;      /**< pattern files missing inside the sequence (gaps skipped) */
    uint32_t released;     /**< frames given back */
    uint32_t bad_releases; /**< releases of frames that were not lent (ignored) */
} pft_file_stats_t;

/** File source state; allocate it, then pft_file_source_init. Members are private to the
 *  port: read the counters, change nothing. */
typedef struct {
    pft_file_config_t cfg;     /**< copy of the configuration */
    void *fp;                  /**< FILE * of a concatenated file */
    uint8_t *slot[PFT_FILE_MAX_SLOTS]; /**< start of each slot in `buffer` */
    uint8_t lent[PFT_FILE_MAX_SLOTS];  /**< 1 while the slot's frame is lent */
    uint32_t slot_bytes;       /**< bytes per slot */
    uint32_t index;            /**< next file index / seq */
    bool ended;                /**< the sequence has ended (acquire returns PFT_ERR_EOF) */
    pft_file_error_t last_error; /**< detail of the last failure (PFT_FILE_OK if none) */
    char name[PFT_FILE_NAME_MAX]; /**< file of the last acquire */
    pft_file_stats_t stats;    /**< counters */
} pft_file_source_t;

/**
 * Initialises a source. PFT_ERR_INVAL: NULL, bad layout/encoding/slots, a pattern or file name
 * of PFT_FILE_NAME_MAX characters or more, a pattern without exactly one integer conversion
 * (`%u`, `%04u`, `%d`, `%x`...: flags and a width of at most three digits, no precision, no
 * length modifier; `%%` allowed), RAW without a geometry or with an unknown format.
 * PFT_ERR_NOMEM: a RAW frame does not fit one slot. PFT_ERR_IO: a concatenated file cannot be
 * opened. On any error `fs` is left as it was. Close with pft_file_source_close.
 */
pft_status_t pft_file_source_init(pft_file_source_t *fs, const pft_file_config_t *cfg);

/** Closes a concatenated file (safe to call twice; a no-op for per-frame files). */
void pft_file_source_close(pft_file_source_t *fs);

/** The pft_frame_source_t view of `fs` (ctx = fs). */
pft_frame_source_t pft_file_as_source(pft_file_source_t *fs);

/** acquire of the source interface (usable directly with ctx = fs). */
pft_status_t pft_file_acquire(void *ctx, pft_frame_t *out, uint32_t timeout_ms);
/** release of the source interface: gives back a lent frame (others ignored and counted). */
void pft_file_release(void *ctx, const pft_frame_t *frame);

/**
 * Reads one PGM/PPM image from `path` into `buf` (packed rows) and describes it in `*out`
 * (seq 0, timestamp 0). Same statuses as acquire; `err` (may be NULL) gets the detail.
 */
pft_status_t pft_pnm_read(const char *path, void *buf, size_t buf_bytes, pft_frame_t *out,
                          pft_file_error_t *err);

/**
 * Writes a frame as binary PGM/PPM: U8 -> P5 maxval 255; U16 -> P5 big-endian, maxval
 * 2^bit_depth - 1 for bit depths 9..16, else 65535 (pixel values are written as they are);
 * RGB888 -> P6; BGR888 -> P6 with channels swapped. PFT_ERR_FORMAT for F32 or a bad frame,
 * PFT_ERR_IO if the file cannot be written, PFT_ERR_INVAL for NULL.
 */
pft_status_t pft_pnm_write(const char *path, const pft_frame_t *frame);

/**
 * Writes a frame's packed pixels (no header) to `path`, appending when `append`; U16 is
 * written little-endian, other formats byte for byte. Builds RAW sequences and test files.
 */
pft_status_t pft_raw_write(const char *path, const pft_frame_t *frame, bool append);

/** Deletes a file (test and tool housekeeping). PFT_ERR_IO if it could not be removed. */
pft_status_t pft_file_remove(const char *path);

#ifdef __cplusplus
}
#endif
#endif
