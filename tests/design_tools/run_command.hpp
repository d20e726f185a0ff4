// run_command.hpp - runs a shell command for the CLI tests, stdout and stderr together.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>

// Output of `cmd` (stderr merged into stdout); *status gets its exit status
// (-1 if it did not exit normally or could not be started).
inline std::string run_command(const std::string& cmd, int* status)
{
    FILE* f = popen((cmd + " 2>&1").c_str(), "r");
    std::string out;
    char buf[512];
    while (f && std::fgets(buf, sizeof buf, f)) out += buf;
    const int st = f ? pclose(f) : -1;
    *status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    return out;
}
