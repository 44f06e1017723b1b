/*
 * Workspace carving: every buffer PFT_WS_ALIGN-aligned and inside the caller's buffer, the
 * documented size formula (sum of PFT_WS_ROUND + PFT_WS_ALIGN - 1) is sufficient for any start
 * address and tight for the worst one, an exact fit succeeds and one byte less gives
 * PFT_ERR_NOMEM, and writing every carved byte leaves guard bytes around the buffer intact.
 */
#include <string.h>
#include "pft_test_support.h"

void setUp(void) {}
void tearDown(void) {}

/* 8-aligned arena: guard zone of 64 bytes, then the workspace at offset 64 + off. */
static union {
    uint64_t align;
    uint8_t b[1024];
} arena;
#define GUARD 64u

static const size_t k_sizes[6] = {1u, 13u, 8u, 0u, 5u, 100u};
#define NSIZES 6u

static size_t sum_rounded(void)
{
    size_t s = 0;
    for (unsigned i = 0; i < NSIZES; ++i) {
        s += PFT_WS_ROUND(k_sizes[i]);
    }
    return s;
}

/* Carves k_sizes from buf[0..len); checks alignment, bounds and packing; writes every carved
 * byte (full rounded size). Returns the status. */
static pft_status_t carve_all(uint8_t *buf, size_t len)
{
    pft_ws_t ws;
    uint8_t *prev = NULL;
    size_t prev_sz = 0;
    pft_ws_init(&ws, buf, len);
    for (unsigned i = 0; i < NSIZES; ++i) {
        uint8_t *p = (uint8_t *)pft_ws_take(&ws, k_sizes[i]);
        if (p == NULL) {
            continue;
        }
        TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)((uintptr_t)p % PFT_WS_ALIGN));
        TEST_ASSERT_TRUE(p >= buf);
        TEST_ASSERT_TRUE(p + PFT_WS_ROUND(k_sizes[i]) <= buf + len);
        if (prev != NULL) {
            TEST_ASSERT_TRUE(p == prev + prev_sz); /* packed, in order */
        }
        memset(p, 0x00, PFT_WS_ROUND(k_sizes[i]));
        prev = p;
        prev_sz = PFT_WS_ROUND(k_sizes[i]);
    }
    return pft_ws_status(&ws);
}

static void test_round_macro(void)
{
    TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)PFT_WS_ROUND(0));
    TEST_ASSERT_EQUAL_UINT32(8u, (uint32_t)PFT_WS_ROUND(1));
    TEST_ASSERT_EQUAL_UINT32(8u, (uint32_t)PFT_WS_ROUND(8));
    TEST_ASSERT_EQUAL_UINT32(16u, (uint32_t)PFT_WS_ROUND(9));
}

/* For every start misalignment, the formula size fits; the exact fit (padding + sum) succeeds
 * and one byte less fails; guards outside the buffer stay intact. */
static void test_formula_exact_fit_and_guards(void)
{
    const size_t need = sum_rounded() + PFT_WS_ALIGN - 1u;
    for (size_t off = 0; off < PFT_WS_ALIGN; ++off) {
        uint8_t *buf = arena.b + GUARD + off;
        const size_t pad = (PFT_WS_ALIGN - off % PFT_WS_ALIGN) % PFT_WS_ALIGN;
        /* formula size */
        pft_test_guard_fill(arena.b, sizeof arena.b);
        TEST_ASSERT_EQUAL_INT(PFT_OK, carve_all(buf, need));
        TEST_ASSERT_TRUE(pft_test_guard_intact(arena.b, sizeof arena.b, GUARD + off, GUARD + off + need));
        /* exact fit */
        pft_test_guard_fill(arena.b, sizeof arena.b);
        TEST_ASSERT_EQUAL_INT(PFT_OK, carve_all(buf, pad + sum_rounded()));
        TEST_ASSERT_TRUE(pft_test_guard_intact(arena.b, sizeof arena.b, GUARD + off,
                                               GUARD + off + pad + sum_rounded()));
        /* one byte short */
        pft_test_guard_fill(arena.b, sizeof arena.b);
        TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, carve_all(buf, pad + sum_rounded() - 1u));
        TEST_ASSERT_TRUE(pft_test_guard_intact(arena.b, sizeof arena.b, GUARD + off,
                                               GUARD + off + pad + sum_rounded() - 1u));
    }
    /* the formula is tight: with the worst start (padding ALIGN - 1) one byte less fails */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, carve_all(arena.b + GUARD + 1u, need - 1u));
}

static void test_failure_is_sticky_and_no_wrap(void)
{
    pft_ws_t ws;
    uint8_t *buf = arena.b + GUARD;
    pft_ws_init(&ws, buf, 32);
    TEST_ASSERT_NOT_NULL(pft_ws_take(&ws, 16));
    TEST_ASSERT_NULL(pft_ws_take(&ws, 17)); /* 24 > 16 left */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_ws_status(&ws));
    TEST_ASSERT_NOT_NULL(pft_ws_take(&ws, 16)); /* still fits, but the status stays NOMEM */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_ws_status(&ws));
    TEST_ASSERT_EQUAL_UINT32(32u, (uint32_t)ws.used);
    /* sizes whose rounding would wrap around are refused, not wrapped to 0 */
    pft_ws_init(&ws, buf, 32);
    TEST_ASSERT_NULL(pft_ws_take(&ws, (size_t)-1));
    TEST_ASSERT_NULL(pft_ws_take(&ws, (size_t)-1 - 3u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_ws_status(&ws));
    TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)ws.used);
}

static void test_null_and_tiny_buffers(void)
{
    pft_ws_t ws;
    /* no buffer: empty takes are fine (NULL, no error), anything else is NOMEM */
    pft_ws_init(&ws, NULL, 100);
    TEST_ASSERT_NULL(pft_ws_take(&ws, 0));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_ws_status(&ws));
    TEST_ASSERT_NULL(pft_ws_take(&ws, 1));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_ws_status(&ws));
    /* a buffer shorter than its alignment padding holds nothing */
    pft_test_guard_fill(arena.b, sizeof arena.b);
    pft_ws_init(&ws, arena.b + GUARD + 1u, 3);
    TEST_ASSERT_NULL(pft_ws_take(&ws, 1));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_ws_status(&ws));
    TEST_ASSERT_TRUE(pft_test_guard_intact(arena.b, sizeof arena.b, 0, 0));
    /* zero-length workspace, aligned start: empty take returns the start, nonzero fails */
    pft_ws_init(&ws, arena.b + GUARD, 0);
    TEST_ASSERT_TRUE(pft_ws_take(&ws, 0) == (void *)(arena.b + GUARD));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_ws_status(&ws));
    TEST_ASSERT_NULL(pft_ws_take(&ws, 1));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_ws_status(&ws));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_round_macro);
    RUN_TEST(test_formula_exact_fit_and_guards);
    RUN_TEST(test_failure_is_sticky_and_no_wrap);
    RUN_TEST(test_null_and_tiny_buffers);
    return UNITY_END();
}
