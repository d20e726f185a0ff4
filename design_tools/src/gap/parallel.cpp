// parallel.cpp - run_jobs(): independent fits on the machine's cores
// (stages.hpp). Used by which (every candidate alone) and how far (the
// trial sets of one selection step).
#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "stages.hpp"

namespace fracdesign {
namespace gap {

void run_jobs(size_t n, int threads, const std::function<void(size_t)>& job)
{
    if (n == 0) return;
    const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
    const size_t workers = std::min<size_t>(n, threads > 0 ? size_t(threads) : size_t(hw));
    std::atomic<size_t> next{0};
    std::mutex mu;
    std::exception_ptr failure;
    // Each worker takes the next job until none is left; a job that throws
    // does not stop the others (their slots are then simply not used).
    const auto work = [&]() {
        for (size_t i = next++; i < n; i = next++) {
            try {
                job(i);
            } catch (...) {
                std::lock_guard<std::mutex> lk(mu);
                if (!failure) failure = std::current_exception();
            }
        }
    };
    std::vector<std::thread> pool;
    for (size_t t = 1; t < workers; ++t) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
}

}  // namespace gap
}  // namespace fracdesign
