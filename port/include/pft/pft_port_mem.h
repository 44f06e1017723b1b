/**
 * @file pft_port_mem.h
 * @brief Ring-buffer frame source over caller memory, with fault injection.
 *
 * N slots of one frame geometry live in a buffer the caller provides (no allocation). A
 * producer (a test, a simulator, an ISR standing in for a camera) writes frames into free
 * slots; the consumer side is a pft_frame_source_t that lends the oldest queued frame and gets
 * it back. Slot states: FREE -> WRITING (producer) -> QUEUED -> LENT (consumer) -> FREE.
 *
 * Rules enforced and counted:
 * - acquire while `max_lent` frames are lent (default: every slot) -> PFT_ERR_STATE;
 * - release of something that is not lent (double release, foreign pointer, NULL) -> ignored,
 *   counted in pft_mem_stats_t::bad_releases;
 * - producer write with no free slot (ring full: the consumer is too slow) -> PFT_ERR_NOMEM,
 *   the frame is lost and its sequence number consumed (the consumer sees a seq gap).
 *
 * Fault injection (the test fixture for the runner and for trackers), decided once per frame
 * when the producer commits it, either at given sequence numbers or at random with a
 * probability and a private seed (xorshift32; deterministic, independent of any other RNG):
 * - PFT_FAULT_DROP: frame discarded inside the source; the consumer sees a seq gap.
 * - PFT_FAULT_SHORT: lent with fewer rows than configured (`short_height`, default height/2);
 *   a one-row frame gets a stride smaller than a row instead.
 * - PFT_FAULT_CORRUPT: lent with a bad header: even seq -> format 0 (unknown), odd seq ->
 *   width 0. `data` stays valid so the frame can be released normally.
 * - PFT_FAULT_LATE: lent with its timestamp moved `late_us` into the future (a jump).
 * - PFT_FAULT_TIMEOUT: the first acquire that reaches it returns PFT_ERR_TIMEOUT and lends
 *   nothing; the frame stays queued and the next acquire lends it (it arrived late).
 * After any fault the source keeps working.
 */
#ifndef PFT_PORT_MEM_H
#define PFT_PORT_MEM_H

#include "pft/pft_port.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest number of ring slots. */
#define PFT_MEM_MAX_SLOTS 16u

/** Kinds of injected faults. */
typedef enum {
    PFT_FAULT_NONE = 0,
    PFT_FAULT_DROP = 1,
    PFT_FAULT_SHORT = 2,
    PFT_FAULT_CORRUPT = 3,
    PFT_FAULT_LATE = 4,
    PFT_FAULT_TIMEOUT = 5,
    PFT_FAULT_COUNT = 6
} pft_fault_kind_t;

/** One scheduled fault: the frame with sequence number `seq` gets `kind`. */
typedef struct {
    uint32_t seq;          /**< sequence number of the frame that gets the fault */
    pft_fault_kind_t kind; /**< what goes wrong with it */
} pft_fault_at_t;

/** Fault-injection plan. Zero-initialised: no faults. */
typedef struct {
    const pft_fault_at_t *at;  /**< schedule by seq (kept by pointer: must outlive the source) */
    uint32_t at_count;         /**< entries in `at` (first match wins) */
    uint32_t prob_ppm[PFT_FAULT_COUNT]; /**< chance per frame in parts per million, indexed by
                                             kind (index 0 unused); the sum must be <= 1000000 */
    uint32_t seed;             /**< private RNG seed (0 is replaced by a fixed non-zero value) */
    uint16_t short_height;     /**< rows of a SHORT frame; 0: height / 2 */
    uint64_t late_us;          /**< timestamp jump of a LATE frame; 0: 1000000 */
} pft_mem_faults_t;

typedef struct pft_mem_source pft_mem_source_t;

/** Most calls of the fill hook per acquire. */
#define PFT_MEM_FILL_CALLS 8u

/**
 * Called by acquire while no frame is queued and the source is not closed (at most
 * PFT_MEM_FILL_CALLS times per acquire, so a frame dropped by fault injection does not turn
 * into a timeout): it may push frames (pft_mem_push / write_begin + commit) or close.
 * Returning PFT_ERR_EOF closes the source; any other error is returned by that acquire.
 */
typedef pft_status_t (*pft_mem_fill_fn)(void *ctx, pft_mem_source_t *src);

/** Configuration of a ring source. */
typedef struct {
    void *buffer;             /**< slots * stride_bytes * height bytes, caller-owned */
    size_t buffer_bytes;      /**< size of `buffer` */
    uint32_t slots;           /**< 1..PFT_MEM_MAX_SLOTS */
    uint16_t width;           /**< frame geometry of every slot */
    uint16_t height;          /**< rows */
    pft_pixfmt_t format;      /**< pixel format of every slot */
    uint8_t bit_depth;        /**< U16 significant bits (0: 16) */
    uint32_t stride_bytes;    /**< 0: packed (width * bytes per pixel) */
    uint32_t max_lent;        /**< frames lent at once; 0: slots */
    uint32_t first_seq;       /**< sequence number of the first frame */
    pft_mem_fill_fn fill;     /**< optional producer pulled on demand */
    void *fill_ctx;           /**< passed to `fill` */
    pft_mem_faults_t faults;  /**< fault injection (copied; `at` kept by pointer) */
} pft_mem_config_t;

/** Counters of a ring source (read them, do not write). */
typedef struct {
    uint32_t pushed;        /**< frames committed by the producer (including dropped ones) */
    uint32_t overruns;      /**< producer writes refused because the ring was full */
    uint32_t acquired;      /**< frames lent */
    uint32_t released;      /**< frames given back */
    uint32_t bad_releases;  /**< releases of frames that were not lent (ignored) */
    uint32_t state_errors;  /**< acquires refused with PFT_ERR_STATE */
    uint32_t lent;          /**< frames lent right now */
    uint32_t lent_max;      /**< most frames lent at once */
    uint32_t injected[PFT_FAULT_COUNT]; /**< faults injected, by kind */
} pft_mem_stats_t;

/** Ring source state: allocate it (static or on the stack), then pft_mem_source_init. Members
 *  are private to the port: read the counters with the functions below. */
struct pft_mem_source {
    pft_mem_config_t cfg;   /**< copy of the configuration */
    uint8_t *base;          /**< first slot */
    uint32_t slot_bytes;    /**< stride_bytes * height */
    uint32_t next_seq;      /**< sequence number of the next frame committed */
    uint32_t rng;           /**< state of the fault-injection generator */
    int32_t writing;        /**< slot being written, -1 if none */
    bool closed;            /**< pft_mem_close was called */
    uint8_t state[PFT_MEM_MAX_SLOTS];        /**< free / being written / queued / lent, per slot */
    uint8_t fault[PFT_MEM_MAX_SLOTS];        /**< fault kind scheduled for the slot's frame */
    uint8_t fault_served[PFT_MEM_MAX_SLOTS]; /**< the fault was applied when lent */
    uint32_t seq[PFT_MEM_MAX_SLOTS];         /**< sequence number of the slot's frame */
    uint64_t ts[PFT_MEM_MAX_SLOTS];          /**< timestamp of the slot's frame, us */
    pft_mem_stats_t stats;  /**< counters */
};

/**
 * Initialises `m` over `cfg->buffer`. PFT_ERR_INVAL: NULL arguments, 0 or too many slots, zero
 * size, unknown format, stride below a row, max_lent > slots, fault probabilities above 1e6 in
 * sum or a schedule with at_count > 0 and NULL `at`. PFT_ERR_NOMEM: buffer too short.
 */
pft_status_t pft_mem_source_init(pft_mem_source_t *m, const pft_mem_config_t *cfg);

/** The pft_frame_source_t view of `m` (ctx = m). */
pft_frame_source_t pft_mem_as_source(pft_mem_source_t *m);

/**
 * Producer, zero-copy: reserves a free slot and returns its pixels (stride = slot stride).
 * PFT_ERR_STATE if a write is already open or the source is closed, PFT_ERR_NOMEM if the ring
 * is full (overrun: the frame is lost, its seq consumed), PFT_ERR_INVAL for NULL.
 */
pft_status_t pft_mem_write_begin(pft_mem_source_t *m, void **pixels);

/** Queues the slot reserved by write_begin with the next seq and `timestamp_us`. */
pft_status_t pft_mem_write_commit(pft_mem_source_t *m, uint64_t timestamp_us);

/** Gives back the slot reserved by write_begin without queuing it (no seq consumed). */
pft_status_t pft_mem_write_abort(pft_mem_source_t *m);

/**
 * Producer, copying: write_begin + copy `height` rows of width * bytes-per-pixel bytes from
 * `pixels` (rows `src_stride` bytes apart, 0: packed) + commit.
 */
pft_status_t pft_mem_push(pft_mem_source_t *m, const void *pixels, uint32_t src_stride,
                          uint64_t timestamp_us);

/** No more frames: once the queue is empty, acquire returns PFT_ERR_EOF. */
void pft_mem_close(pft_mem_source_t *m);

/** Frames queued and not yet lent. */
uint32_t pft_mem_queued(const pft_mem_source_t *m);

/** acquire of the source interface (usable directly with ctx = m). */
pft_status_t pft_mem_acquire(void *ctx, pft_frame_t *out, uint32_t timeout_ms);
/** release of the source interface: gives back a lent frame (others ignored and counted). */
void pft_mem_release(void *ctx, const pft_frame_t *frame);

#ifdef __cplusplus
}
#endif
#endif
