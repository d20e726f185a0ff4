// cli.hpp - subcommand registry and option parsing for fracdesign.
//
// Every subcommand lives in design_tools/src/cli/cmd_<name>.cpp and registers
// itself with a static CommandRegistrar. Conventions (ARCHITECTURE.md):
// every subcommand has --help, prints a human summary, and with --json a
// machine-readable result on stdout; errors go to stderr with a non-zero exit.
#pragma once
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace fracdesign {

// A usage error: printed as "fracdesign <cmd>: <message>" with exit status 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Parsed command line: "--key value", "--key=value", "--flag", positionals.
class Args {
public:
    // `flags` names the options that take no value (e.g. {"json", "help"}).
    Args(const std::vector<std::string>& argv, const std::vector<std::string>& flags);
    bool has(const std::string& key) const;
    std::string str(const std::string& key, const std::string& def) const;
    std::string str(const std::string& key) const;  // required; UsageError if absent
    double num(const std::string& key, double def) const;  // UsageError if not a finite number
    long integer(const std::string& key, long def) const;
    std::vector<double> nums(const std::string& key) const;  // "1,2,3"
    const std::vector<std::string>& positional() const { return pos_; }
    // UsageError naming the first option not in `known` (catches typos).
    void check_known(const std::vector<std::string>& known) const;

private:
    std::map<std::string, std::string> opt_;
    std::vector<std::string> pos_;
};

struct Command {
    std::string name;
    std::string summary;  // one line, shown by `fracdesign --help`
    std::string help;     // full --help text
    std::function<int(const std::vector<std::string>&)> run;  // args after the name
};

std::map<std::string, Command>& command_registry();

// Writes `bytes` to `path` (binary); std::runtime_error "cannot write '<path>'".
void write_file(const std::string& path, const std::string& bytes);

// The command line a subcommand records (e.g. result.json "command") starts
// with "fracdesign <name>"; a program that runs one subcommand as itself
// (gap-plc runs `gap` with the PLC's controller kinds registered) sets its
// own name here, and the record starts with that instead.
std::string& command_program();

struct CommandRegistrar {
    explicit CommandRegistrar(Command c);
};

}  // namespace fracdesign
