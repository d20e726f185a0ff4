// progress.cpp - one-line stderr progress display (see progress.hpp).
#include "fracdesign/ident/progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace fracdesign {
namespace ident {

Progress::Progress(bool enabled, std::string label, int total)
    : enabled_(enabled), label_(std::move(label)), total_(total)
{
}

Progress::~Progress()
{
    if (enabled_ && printed_) std::fputc('\n', stderr);
}

void Progress::update(int done, const std::string& message)
{
    if (!enabled_) return;
    std::fprintf(stderr, "\r%s %d/%d %-60.60s", label_.c_str(), done, total_, message.c_str());
    std::fflush(stderr);
    printed_ = true;
}

bool stderr_is_terminal() { return isatty(fileno(stderr)) != 0; }

}  // namespace ident
}  // namespace fracdesign
