// libFuzzer target: fracdesign's frequency-response CSV reader
// (fracdesign/io/frf_csv.hpp). Bad input may only raise SignalCsvError; an
// accepted table has finite frequencies and as many responses as frequencies.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "fracdesign/io/frf_csv.hpp"
#include "fracdesign/io/signal_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace fracdesign::io;
    try {
        const FrfTable f = parse_frf_csv(std::string(reinterpret_cast<const char*>(data), size), "fuzz");
        for (double w : f.w)
            if (!std::isfinite(w)) std::abort();
        if (f.G.size() != f.w.size()) std::abort();
    } catch (const SignalCsvError& e) {
        if (!*e.what()) std::abort();
    }
    return 0;
}
