// libFuzzer target: fracdesign's signal CSV reader (fracdesign/io/signal_csv.hpp).
// Bad input may only raise SignalCsvError (one clear message); a table it
// accepts has a strictly increasing finite time column and columns as long
// as it.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "fracdesign/io/signal_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace fracdesign::io;
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        parse_numeric_csv(text, "fuzz");
    } catch (const SignalCsvError&) {
    }
    try {
        const SignalTable s = parse_signal_csv(text, "fuzz");
        for (std::size_t k = 0; k < s.t.size(); k++)
            if (!std::isfinite(s.t[k]) || (k > 0 && !(s.t[k] > s.t[k - 1]))) std::abort();
        for (const auto& c : s.columns)
            if (c.size() != s.t.size()) std::abort();
    } catch (const SignalCsvError& e) {
        if (!*e.what()) std::abort();
    }
    return 0;
}
