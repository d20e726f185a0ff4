// libFuzzer target: fracdesign's model-JSON reader (fracdesign/model_json.hpp).
// Any JSON document must be taken or refused with ModelFormatError (one
// message naming the field); a model it takes must write back to JSON that
// reads back to the same document.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "fracdesign/model_json.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace fracdesign;
    const nlohmann::json j = nlohmann::json::parse(data, data + size, nullptr, false);
    if (j.is_discarded()) return 0;
    ModelSpec m;
    try {
        m = model_from_json(j);
    } catch (const ModelFormatError& e) {
        if (!*e.what()) std::abort();
        return 0;
    }
    const nlohmann::json out = model_to_json(m);
    if (model_to_json(model_from_json(out)) != out) std::abort();
    return 0;
}
