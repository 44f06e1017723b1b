/*
 * Port conformance check: runs a pft_frame_source_t through the lend-and-return contract of
 * docs/porting.md and reports every rule it breaks. Any port can run it (see
 * docs/porting.md, "Running the conformance test against your port"): describe what the
 * source should produce in a pft_conf_spec_t, call pft_conf_run, and require a report with
 * no violation. Plain C99 (string.h and snprintf only), no allocation: it runs on the host,
 * under qemu-user and on bare-metal Cortex-M like the unit tests.
 *
 * What it does, in order (each frame lent anywhere is checked the same way: descriptor,
 * seq, timestamp, and a checksum of its pixels at acquire compared at release):
 *   1. lend probe: acquire max_lent frames without releasing; all distinct, non-overlapping
 *      memory; one more must give PFT_ERR_STATE; while they are held, `tick` runs (time
 *      passes, the producer works) and their pixels must not change;
 *   2. releases of frames that are not lent: a copy of a frame already released (double
 *      release) and a foreign descriptor. They must be refused (the source's `bad_releases`
 *      counter, when given, goes up by one each) or be no-ops, and must not corrupt the
 *      source: the lend probe is repeated and must still pass, and while frames are held a
 *      foreign release must not let the producer write into them;
 *   3. timeout probe (when `starve` is given): with no frame coming, acquire must return
 *      PFT_ERR_TIMEOUT and lend nothing (the lend probe is repeated once more);
 *   4. the stream: acquire, `tick` a few times while the frame is lent, release, until
 *      PFT_ERR_EOF (finite sources) or `endless_frames` frames (endless ones);
 *   5. after the end (finite sources): acquire keeps returning PFT_ERR_EOF, also after a
 *      stray release; the number of frames lent equals `frames`.
 */
#ifndef PFT_PORT_CONFORMANCE_H
#define PFT_PORT_CONFORMANCE_H

#include <stdbool.h>
#include <stdint.h>

#include "pft/pft_port.h"

#ifdef __cplusplus
extern "C" {
#endif

/** pft_conf_spec_t::frames: the source never ends. */
#define PFT_CONF_ENDLESS 0u
/** pft_conf_spec_t::frames: the source ends (PFT_ERR_EOF), after a number of frames that is
 *  not known in advance (e.g. a camera stopped after a while, with frames dropped). */
#define PFT_CONF_FINITE 0xFFFFFFFFu
/** pft_conf_spec_t::max_lent: the source has no lend limit (never PFT_ERR_STATE). */
#define PFT_CONF_NO_LIMIT 0xFFFFFFFFu
/** Most frames the check holds at once (a larger finite max_lent is refused). */
#define PFT_CONF_MAX_HELD 16u

/** What the source under test should do. pft_conf_spec_default, then fill it in. */
typedef struct {
    uint16_t width, height;  /**< every frame's size; 0: the first frame's size, for all */
    uint32_t fmt_mask;       /**< accepted formats (PFT_FMT_BIT); 0: any known format */
    uint32_t frames;         /**< frames lent before PFT_ERR_EOF; PFT_CONF_ENDLESS;
                                  PFT_CONF_FINITE */
    uint32_t endless_frames; /**< endless sources: frames the stream phase takes (default 48) */
    uint32_t max_lent;       /**< frames lendable at once (the documented limit; the next
                                  acquire gives PFT_ERR_STATE); PFT_CONF_NO_LIMIT; default 1 */
    bool can_timeout;        /**< PFT_ERR_TIMEOUT is allowed (a camera); else a violation */
    bool may_lose;           /**< PFT_ERR_IO / PFT_ERR_FORMAT (lost or unreadable frame) are
                                  allowed; else a violation */
    uint32_t timeout_ms;     /**< passed to every acquire (default 0: poll) */
    uint32_t ticks_while_lent; /**< tick calls while each stream frame is lent (default 2) */
    uint32_t max_attempts;   /**< bound on acquire calls in all (0: 8 * n + 256, n being
                                  frames, endless_frames, or 8192 for PFT_CONF_FINITE) */
    void *hook_ctx;          /**< passed to the hooks */
    /** Optional: time passes (a simulated ISR delivers a frame, a producer pushes one). It is
     *  called while frames are lent, so a source that writes into lent memory is caught. */
    void (*tick)(void *ctx);
    /** Optional (only with can_timeout): `on` true: no new frame arrives until called with
     *  false (frames already waiting may still be lent); then acquire must time out. */
    void (*starve)(void *ctx, bool on);
    /** Optional: the source's count of releases it refused. NULL: such releases are
     *  documented no-ops (only "state not corrupted" is checked). */
    uint32_t (*bad_releases)(void *ctx);
} pft_conf_spec_t;

/** Rules the check reports. */
typedef enum {
    PFT_CONF_SPEC = 0,       /**< bad arguments or spec: nothing was checked */
    PFT_CONF_DESCRIPTOR = 1, /**< a lent frame fails pft_frame_check or the expected size/format */
    PFT_CONF_SEQ = 2,        /**< seq not strictly increasing (gaps are allowed, counted) */
    PFT_CONF_TIMESTAMP = 3,  /**< timestamp went back */
    PFT_CONF_EOF = 4,        /**< after PFT_ERR_EOF, an acquire returned something else; an
                                  endless source ended; a finite one never ended */
    PFT_CONF_RELEASE = 5,    /**< a release of a frame not lent was not refused, or it
                                  corrupted the source (lend rule or lent pixels broken after) */
    PFT_CONF_LEND = 6,       /**< lend rule: acquire beyond max_lent not PFT_ERR_STATE, refused
                                  below it, or two lent frames sharing memory */
    PFT_CONF_TIMEOUT = 7,    /**< timeout when the source cannot time out, a starved source
                                  not returning PFT_ERR_TIMEOUT, or a timeout that lent something */
    PFT_CONF_DATA = 8,       /**< pixels of a lent frame changed before its release */
    PFT_CONF_STATUS = 9,     /**< acquire returned a status the contract does not allow here */
    PFT_CONF_COUNT = 10,     /**< a finite source lent a different number of frames */
    PFT_CONF_RULES = 11
} pft_conf_rule_t;

/** What the check saw. */
typedef struct {
    uint32_t violations[PFT_CONF_RULES]; /**< per rule */
    uint32_t total;          /**< sum of violations; 0: the source conforms */
    pft_conf_rule_t first_rule;
    char first[128];         /**< the first violation in words ("" if none) */
    uint32_t frames;         /**< frames lent (all phases) */
    uint32_t gaps;           /**< seq numbers missing between lent frames (dropped frames) */
    uint32_t first_seq, last_seq;
    uint32_t attempts;       /**< acquire calls */
    uint32_t timeouts;       /**< PFT_ERR_TIMEOUT answers */
    uint32_t lost;           /**< PFT_ERR_IO / PFT_ERR_FORMAT answers */
    uint32_t refused;        /**< PFT_ERR_STATE answers of the lend probes */
    uint32_t bad_releases;   /**< releases of frames not lent that the check made */
    bool ended;              /**< PFT_ERR_EOF seen */
} pft_conf_report_t;

/** Defaults: any size and format, endless, 48 frames, max_lent 1, no timeouts, 2 ticks. */
void pft_conf_spec_default(pft_conf_spec_t *spec);

/**
 * Runs the check. Returns true when the source broke no rule (report->total == 0). The
 * source must be freshly initialised (and started); it is left at its end or, for an endless
 * source, with nothing lent. `report` is required; bad arguments count as PFT_CONF_SPEC.
 */
bool pft_conf_run(const pft_frame_source_t *src, const pft_conf_spec_t *spec,
                  pft_conf_report_t *report);

/** Short name of a rule ("descriptor", "seq", ...; "?" if unknown). */
const char *pft_conf_rule_name(pft_conf_rule_t rule);

#ifdef __cplusplus
}
#endif
#endif
