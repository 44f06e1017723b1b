#include "registry.hpp"

#include <cstdio>
#include <map>

#include "errors.hpp"

namespace pft::host {

namespace {
std::map<std::string, KindFactory> &table()
{
    static std::map<std::string, KindFactory> t;  // filled by static registrars before main
    return t;
}
std::map<std::string, std::string> &aliases()
{
    static std::map<std::string, std::string> a;  // old kind name -> current name
    return a;
}
}  // namespace

void register_kind_alias(const std::string &old_name, const std::string &kind) { aliases()[old_name] = kind; }

void register_kind(const std::string &kind, KindFactory factory) { table()[kind] = std::move(factory); }

std::vector<std::string> registered_kinds()
{
    std::vector<std::string> v;
    for (auto &kv : table())
        v.push_back(kv.first);
    return v;
}

std::unique_ptr<KindHandler> make_handler(const std::string &requested)
{
    std::string kind = requested;
    auto al = aliases().find(requested);
    if (al != aliases().end() && table().find(requested) == table().end()) {
        kind = al->second;
        std::fprintf(stderr, "pft: note: scenario kind \"%s\" is now called \"%s\"\n", requested.c_str(),
                     kind.c_str());
    }
    auto it = table().find(kind);
    if (it == table().end()) {
        std::string list;
        for (auto &k : registered_kinds())
            list += (list.empty() ? "" : ", ") + k;
        throw InputError("unknown scenario kind \"" + kind + "\" (known: " + list + ")");
    }
    auto h = it->second();
    h->kind_ = kind;
    return h;
}

void KindHandler::unsupported(const Options &o) const
{
    throw InputError("kind \"" + kind_ + "\" has no `" + o.command + "` command");
}

int KindHandler::sim(const Options &o) { unsupported(o); }
int KindHandler::run(const Options &o) { unsupported(o); }
int KindHandler::eval(const Options &o) { unsupported(o); }
int KindHandler::bench(const Options &o) { unsupported(o); }
int KindHandler::demo(const Options &o) { unsupported(o); }
int KindHandler::track(const Options &o) { unsupported(o); }
int KindHandler::merge(const Options &o, const MergedRuns &) { unsupported(o); }
int KindHandler::selftest(const Options &) { return 0; }

}  // namespace pft::host
