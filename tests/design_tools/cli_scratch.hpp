// cli_scratch.hpp - what the fracdesign CLI tests share: a scratch folder per
// test process, writing a file, and running a command with its stderr kept
// apart from its stdout (the refusal tests check stderr holds one line).
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace cli_scratch {

// A fresh folder <tmp>/<prefix>_<pid>, emptied once per process.
inline std::filesystem::path dir(const std::string& prefix)
{
    const std::filesystem::path p = std::filesystem::temp_directory_path() / (prefix + "_" + std::to_string(::getpid()));
    static std::set<std::string> emptied;
    if (emptied.insert(prefix).second) std::filesystem::remove_all(p);
    std::filesystem::create_directories(p);
    return p;
}

inline void write(const std::filesystem::path& p, const std::string& text) { std::ofstream(p) << text; }

inline std::string read(const std::filesystem::path& p)
{
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

struct Outcome {
    int status;       // std::system's status: 0 when the command exited 0
    std::string err;  // what it wrote to stderr
};

// Runs `cmd` with stdout discarded and stderr captured through the file `err`.
inline Outcome run(const std::string& cmd, const std::filesystem::path& err)
{
    const int rc = std::system((cmd + " > /dev/null 2> " + err.string()).c_str());
    return {rc, read(err)};
}

}  // namespace cli_scratch
