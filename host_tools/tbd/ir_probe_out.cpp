#include "ir_probe_out.hpp"

#include <cinttypes>
#include <cstring>
#include <fstream>

#include "../common/errors.hpp"
#include "../common/real.hpp"

extern "C" {
#include "../../tests/tools/ir_probe_fields.h"
}

namespace pft::host::tbd_ir {

namespace {

uint32_t real_bits(pft_real_t v)
{
    static_assert(sizeof(pft_real_t) == 4, "probe.cfg writes a real as its 32 bits");
    uint32_t u;
    std::memcpy(&u, &v, sizeof u);
    return u;
}

// Written with the struct's own types: U as unsigned long long, I as long long, R as its bits
#define IRP_WRITE_U(sec, c, f) std::fprintf(o, "%s.%s %llu\n", sec, #f, static_cast<unsigned long long>((c).f))
#define IRP_WRITE_I(sec, c, f) std::fprintf(o, "%s.%s %lld\n", sec, #f, static_cast<long long>((c).f))
#define IRP_WRITE_R(sec, c, f) \
    std::fprintf(o, "%s.%s 0x%08" PRIx32 " # %.9g\n", sec, #f, real_bits((c).f), from_real((c).f))

// The listed fields' bytes; on x86-64 Linux the struct's size less them is its padding there
// (a field added to the struct but not to ir_probe_fields.h changes the difference)
#define IRP_SIZE_OF(T, F, K, TYPE) +sizeof(std::declval<T>().F)
#define IRP_PRE_SIZE(F, K, TYPE) IRP_SIZE_OF(pft_pre_config_t, F, K, TYPE)
#define IRP_FLAT_SIZE(F, K, TYPE) IRP_SIZE_OF(pft_pre_flat_config_t, F, K, TYPE)
#define IRP_CL_SIZE(F, K, TYPE) IRP_SIZE_OF(pft_pre_clutter_config_t, F, K, TYPE)
#define IRP_TBD_SIZE(F, K, TYPE) IRP_SIZE_OF(pft_tbd_config_t, F, K, TYPE)
#define IRP_SCENE_SIZE(F, K, TYPE) IRP_SIZE_OF(pft_tbd_scene_config_t, F, K, TYPE)
#if defined(__x86_64__) && defined(__linux__)
#define IRP_PAD_PRE 24u  // bad_map's 8 bytes and 16 of padding
#define IRP_PAD_FLAT 1u
#define IRP_PAD_CLUTTER 3u
#define IRP_PAD_TBD 28u
#define IRP_PAD_SCENE 0u
// pft_pre_config_t: bad_map (8 bytes, not listed) and padding
static_assert(sizeof(pft_pre_config_t) - (0 IRP_PRE_FIELDS(IRP_PRE_SIZE)) == IRP_PAD_PRE,
              "pft_pre_config_t changed: update tests/tools/ir_probe_fields.h and IRP_PAD_PRE");
static_assert(sizeof(pft_pre_flat_config_t) - (0 IRP_FLAT_FIELDS(IRP_FLAT_SIZE)) == IRP_PAD_FLAT,
              "pft_pre_flat_config_t changed: update tests/tools/ir_probe_fields.h and IRP_PAD_FLAT");
static_assert(sizeof(pft_pre_clutter_config_t) - (0 IRP_CLUTTER_FIELDS(IRP_CL_SIZE)) == IRP_PAD_CLUTTER,
              "pft_pre_clutter_config_t changed: update tests/tools/ir_probe_fields.h and IRP_PAD_CLUTTER");
static_assert(sizeof(pft_tbd_config_t) - (0 IRP_TBD_FIELDS(IRP_TBD_SIZE)) == IRP_PAD_TBD,
              "pft_tbd_config_t changed: update tests/tools/ir_probe_fields.h and IRP_PAD_TBD");
static_assert(sizeof(pft_tbd_scene_config_t) - (0 IRP_SCENE_FIELDS(IRP_SCENE_SIZE)) == IRP_PAD_SCENE,
              "pft_tbd_scene_config_t changed: update tests/tools/ir_probe_fields.h and IRP_PAD_SCENE");
#endif

uint64_t fnv1a(uint64_t h, const void *p, std::size_t n)
{
    const unsigned char *b = static_cast<const unsigned char *>(p);
    for (std::size_t i = 0; i < n; ++i)
        h = (h ^ b[i]) * 1099511628211ull;
    return h;
}

}  // namespace

void write_probe_config(const std::string &path, const IrPipeline &pl)
{
    const IrPipeline::ProbeSetup p = pl.probe_setup();
    if (p.pre.bad_map != nullptr)
        throw InputError("--probe-out: the stage has a bad-pixel map; ir_probe reads none");
    std::FILE *o = std::fopen(path.c_str(), "w");
    if (o == nullptr)
        throw InputError("cannot write " + path);
    std::fprintf(o, "# the IR pipeline's library configurations (pft bench --probe-out; tests/tools/ir_probe -c)\n");
#ifdef PFT_NUMERIC_Q16
    std::fprintf(o, "numeric q16\n");
#else
    std::fprintf(o, "numeric float\n");
#endif
    const unsigned long long pipe[] = {static_cast<unsigned long long>(p.bits), p.flat, p.flat_relative,
                                       p.clutter, p.scene, p.scene_tentative, p.integ_shift};
    std::size_t k = 0;
#define IRP_WRITE_PIPE(name) std::fprintf(o, "pipeline.%s %llu\n", #name, pipe[k++]);
    IRP_PIPELINE_FIELDS(IRP_WRITE_PIPE)
#define IRP_W_PRE(F, K, TYPE) IRP_WRITE_##K("pre", p.pre, F);
    IRP_PRE_FIELDS(IRP_W_PRE)
    if (p.flat) {
#define IRP_W_FLAT(F, K, TYPE) IRP_WRITE_##K("flat", p.flat_cfg, F);
        IRP_FLAT_FIELDS(IRP_W_FLAT)
    }
    if (p.clutter) {
#define IRP_W_CL(F, K, TYPE) IRP_WRITE_##K("clutter", p.clutter_cfg, F);
        IRP_CLUTTER_FIELDS(IRP_W_CL)
    }
#define IRP_W_TBD(F, K, TYPE) IRP_WRITE_##K("tbd", p.tbd, F);
    IRP_TBD_FIELDS(IRP_W_TBD)
    if (p.scene) {
#define IRP_W_SCENE(F, K, TYPE) IRP_WRITE_##K("scene", p.scene_cfg, F);
        IRP_SCENE_FIELDS(IRP_W_SCENE)
    }
    std::fprintf(o, "end\n");
    if (std::fclose(o) != 0)
        throw InputError("cannot write " + path);
}

std::string probe_expect_line(uint32_t seq, const IrPipeline &pl, const PipelineOut &po)
{
    const pft_pre_stats_t &st = pl.stats();
    uint64_t h = 14695981039346656037ull;
    const int16_t *m = pl.clutter_output();
    const pft_tbd_config_t &c = pl.config();
    if (m != nullptr)
        h = fnv1a(h, m, static_cast<std::size_t>(c.width) * c.height * sizeof(int16_t));
    char buf[160];
    std::snprintf(buf, sizeof buf, "F %" PRIu32 " flags %" PRIu32 " shift %" PRId32 " %" PRId32 " ev %d map %016" PRIx64
                  " tracks %zu", seq, st.flags, st.shift[0], st.shift[1], pl.evidence() ? 1 : 0, h,
                  po.tbd.tracks.size());
    std::string line = buf;
    for (const tbd::TrackOut &t : po.tbd.tracks) {
        std::snprintf(buf, sizeof buf, " %" PRIu32 ":%08" PRIx32 ",%08" PRIx32 ",%08" PRIx32 ",%08" PRIx32
                      ",%08" PRIx32 ",%08" PRIx32, t.id, real_bits(to_real(t.x)), real_bits(to_real(t.y)),
                      real_bits(to_real(t.vx)), real_bits(to_real(t.vy)), real_bits(to_real(t.intensity)),
                      real_bits(to_real(t.p_exist)));
        line += buf;
    }
    return line + "\n";
}

}  // namespace pft::host::tbd_ir
