// controller.cpp - the registry of controller kinds (controller.hpp).
#include "fracdesign/gap/controller.hpp"

#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>

#include "controllers/kinds.hpp"

namespace fracdesign {
namespace gap {

namespace {

struct Registry {
    std::mutex lock;
    std::map<std::string, ControllerFactory> kinds;
    Registry()
    {
        for (const BuiltinKind& k : builtin_controller_kinds()) kinds[k.kind] = k.make;
    }
};

Registry& registry()
{
    static Registry r;
    return r;
}

// Kinds replayed by programs above design_tools, which links neither
// plc_blocks nor hil (ARCHITECTURE.md): the program to use instead.
const char* provided_elsewhere(const std::string& kind)
{
    if (kind == "armctrl")
        return "the ArmCtrl program runs in the PLC task runtime (plc_blocks), which fracdesign does not link: "
               "run the same command with gap-plc, or fracarm.gap.diagnose in Python";
    return nullptr;
}

}  // namespace

void register_controller_kind(const std::string& kind, ControllerFactory make)
{
    Registry& r = registry();
    std::lock_guard<std::mutex> g(r.lock);
    r.kinds[kind] = std::move(make);
}

std::vector<std::string> controller_kinds()
{
    Registry& r = registry();
    std::lock_guard<std::mutex> g(r.lock);
    std::vector<std::string> v;
    for (const auto& k : r.kinds) v.push_back(k.first);
    return v;
}

std::unique_ptr<Controller> make_controller(const nlohmann::json& doc, const ControllerContext& ctx)
{
    if (!doc.is_object()) throw std::runtime_error(ctx.where + ": must be an object");
    std::string kind = "statespace";
    if (doc.contains("kind")) {
        if (!doc.at("kind").is_string()) throw std::runtime_error(ctx.where + ".kind: must be a string");
        kind = doc.at("kind").get<std::string>();
    }
    ControllerFactory make;
    {
        Registry& r = registry();
        std::lock_guard<std::mutex> g(r.lock);
        const auto it = r.kinds.find(kind);
        if (it != r.kinds.end()) make = it->second;
    }
    if (!make) {
        if (const char* elsewhere = provided_elsewhere(kind))
            throw std::runtime_error(ctx.where + ".kind: '" + kind + "' is not replayed by this program: " + elsewhere);
        std::string list;
        for (const std::string& k : controller_kinds()) list += (list.empty() ? "" : ", ") + k;
        throw std::runtime_error(ctx.where + ".kind: unknown controller kind '" + kind + "' (kinds: " + list + ")");
    }
    // The divider first: the law is built for its own task period n Ts.
    ControllerContext law_ctx = ctx;
    int divider = 1;
    if (doc.contains("divider")) {
        const json& d = doc.at("divider");
        if (!d.is_number() || !std::isfinite(d.get<double>()) || d.get<double>() != std::floor(d.get<double>()) ||
            d.get<double>() < 1 || d.get<double>() > 1e6)
            throw std::runtime_error(ctx.where + ".divider: " + d.dump() +
                                     " is not allowed (an integer >= 1: the law runs every n-th sample)");
        divider = int(d.get<double>());
        law_ctx.Ts = ctx.Ts * divider;
    }
    return with_common_stages(make(doc, law_ctx), doc, law_ctx, divider);
}

}  // namespace gap
}  // namespace fracdesign
