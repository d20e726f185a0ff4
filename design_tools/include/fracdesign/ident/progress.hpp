// progress.hpp - a one-line progress display for long fits and sweeps.
//
// Writes "\r<label> i/n <message>" to stderr and a newline at the end; does
// nothing when disabled. The CLI enables it when stderr is a terminal or with
// --progress, so pipes and logs stay clean and results never depend on it.
#pragma once
#include <string>

namespace fracdesign {
namespace ident {

class Progress {
public:
    Progress(bool enabled, std::string label, int total);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;
    // Marks item `done` (1-based) of `total` as finished with a short message.
    void update(int done, const std::string& message);
    bool enabled() const { return enabled_; }

private:
    bool enabled_;
    std::string label_;
    int total_;
    bool printed_ = false;
};

// True when stderr is a terminal (the default for showing progress).
bool stderr_is_terminal();

}  // namespace ident
}  // namespace fracdesign
