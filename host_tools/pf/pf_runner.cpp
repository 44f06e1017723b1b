#include "pf_runner.hpp"

#include <cctype>

#include "../common/errors.hpp"
#include "../tbd/tracker.hpp"

namespace pft::host::pf {

EngineSpec parse_engine(const Field &f, bool with_particles)
{
    if (with_particles)
        f.only({"label", "engine", "scheme", "policy", "ess_threshold", "particles", "match_time_of", "budget"});
    else
        f.only({"label", "engine", "scheme", "policy", "ess_threshold", "first_r_sd"});
    EngineSpec e;
    if (with_particles) {
        e.particles = static_cast<uint32_t>(f.integer_in("particles", 0, 0, PFT_CFG_MAX_PARTICLES));
        e.match_time_of = f.string_or("match_time_of", "");
        e.budget = static_cast<uint32_t>(f.integer_in("budget", 0, 0, PFT_CFG_MAX_PARTICLES));
        if ((e.particles == 0) == e.match_time_of.empty())
            f.fail("give exactly one of \"particles\" and \"match_time_of\"");
    }
    e.engine = with_particles ? f.choice_or("engine", "apf", {"sis", "sir", "apf", "rbpf"})
                              : f.choice_or("engine", "apf", {"sis", "sir", "apf"});
    e.scheme = f.choice_or("scheme", "systematic", {"systematic", "stratified", "residual", "multinomial"});
    e.policy = f.choice_or("policy", "", {"", "always", "ess", "never"});
    e.ess_threshold = f.number_in("ess_threshold", 0.5, 1e-6, 1.0);
    e.first_r_sd = f.number_in("first_r_sd", 0.0, 0.0, 10.0);
    std::string up = e.engine;
    for (auto &c : up)
        c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (e.engine == "rbpf")
        up = "RBPF-TBD";
    e.label = f.string_or("label", up);
    return e;
}

pft_pf_config_t engine_config(const EngineSpec &e, uint32_t n, uint64_t seed)
{
    pft_pf_kind_t k = e.engine == "sis" ? PFT_PF_SIS : e.engine == "sir" ? PFT_PF_SIR : PFT_PF_APF;
    pft_pf_config_t c;
    pft_pf_config_default(&c);
    c.kind = k;
    c.n_particles = n;
    c.scheme = e.scheme == "stratified"    ? PFT_RESAMPLE_STRATIFIED
               : e.scheme == "residual"    ? PFT_RESAMPLE_RESIDUAL
               : e.scheme == "multinomial" ? PFT_RESAMPLE_MULTINOMIAL
                                           : PFT_RESAMPLE_SYSTEMATIC;
    if (e.policy == "always")
        c.policy = PFT_PF_RESAMPLE_ALWAYS;
    else if (e.policy == "ess")
        c.policy = PFT_PF_RESAMPLE_ESS;
    else if (e.policy == "never")
        c.policy = PFT_PF_RESAMPLE_NEVER;
    c.ess_threshold = tbd::to_real(e.ess_threshold);
    c.seed = seed;
    return c;
}

nlohmann::json engine_json(const EngineSpec &e)
{
    pft_pf_config_t c = engine_config(e, 1, 0);
    pft_pf_policy_t p = c.policy;
    if (p == PFT_PF_RESAMPLE_AUTO)  // the kind's own policy
        p = c.kind == PFT_PF_APF ? PFT_PF_RESAMPLE_ESS
            : c.kind == PFT_PF_SIR ? PFT_PF_RESAMPLE_ALWAYS
                                   : PFT_PF_RESAMPLE_NEVER;
    const char *pol = p == PFT_PF_RESAMPLE_ALWAYS ? "always"
                      : p == PFT_PF_RESAMPLE_ESS  ? "ess"
                                                  : "never";
    nlohmann::json j = {{"label", e.label}, {"engine", e.engine}, {"scheme", e.scheme},
                        {"policy", e.engine == "sis" ? "never" : pol},
                        {"ess_threshold", e.ess_threshold}};
    if (e.first_r_sd > 0)
        j["first_r_sd"] = e.first_r_sd;
    if (e.budget > 0)
        j["budget"] = e.budget;
    return j;
}

PfRunner::PfRunner(const pft_pf_config_t &cfg, const pft_pf_model_t &model) : cfg_(cfg)
{
    cfg_.model = model;
    const char *field = nullptr;
    pft_status_t st = pft_pf_config_check(&cfg_, &field);
    if (st != PFT_OK)
        throw InputError(std::string("pft_pf_config_check: ") + pft_status_str(st) + " (field " +
                         (field != nullptr ? field : "?") + ")");
    ws_bytes_ = pft_pf_workspace_size(&cfg_);
    work_.assign(ws_bytes_ / 8 + 1, 0);
    st = pft_pf_init(&pf_, &cfg_, work_.data(), work_.size() * 8);
    if (st != PFT_OK)
        throw InputError(std::string("pft_pf_init: ") + pft_status_str(st));
}

void PfRunner::reset(uint64_t seed)
{
    pft_pf_reseed(&pf_, seed);
}

void PfRunner::update(const void *z)
{
    pft_status_t st = cfg_.kind == PFT_PF_SIS   ? pft_host_update_sis(&pf_, z)
                      : cfg_.kind == PFT_PF_SIR ? pft_host_update_sir(&pf_, z)
                                                : pft_host_update_apf(&pf_, z);
    if (st != PFT_OK)
        throw InputError(std::string("pft_pf_update: ") + pft_status_str(st));
}

std::vector<double> PfRunner::estimate() const
{
    std::vector<pft_real_t> e(cfg_.model.dim);
    pft_pf_estimate(&pf_, e.data());
    std::vector<double> d(cfg_.model.dim);
    for (std::size_t i = 0; i < e.size(); ++i)
        d[i] = tbd::from_real(e[i]);
    return d;
}

pft_pf_stats_t PfRunner::stats() const
{
    pft_pf_stats_t s;
    pft_pf_stats(&pf_, &s);
    return s;
}

}  // namespace pft::host::pf

// noipa: neither inlined nor merged by identical-code folding, so each keeps its own cost.
#if defined(__GNUC__) && !defined(__clang__)
#define PFT_HOST_NOIPA __attribute__((noipa))
#else
#define PFT_HOST_NOIPA __attribute__((noinline))
#endif

extern "C" PFT_HOST_NOIPA pft_status_t pft_host_update_sis(pft_pf_t *pf, const void *z)
{
    return pft_pf_update(pf, z);
}
extern "C" PFT_HOST_NOIPA pft_status_t pft_host_update_sir(pft_pf_t *pf, const void *z)
{
    return pft_pf_update(pf, z);
}
extern "C" PFT_HOST_NOIPA pft_status_t pft_host_update_apf(pft_pf_t *pf, const void *z)
{
    return pft_pf_update(pf, z);
}
