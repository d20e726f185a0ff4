// main.cpp - fracdesign entry point: dispatches to the registered subcommands.
#include <exception>
#include <iostream>

#include "fracdesign/cli.hpp"

using namespace fracdesign;

static void usage(std::ostream& os)
{
    os << "usage: fracdesign <command> [options]   (fracdesign <command> --help)\n\n"
          "Offline design tool for fractional-order and LQG control of flexible-link arms.\n\n"
          "commands:\n";
    for (const auto& kv : command_registry()) os << "  " << kv.first << std::string(kv.first.size() < 12 ? 12 - kv.first.size() : 1, ' ') << kv.second.summary << "\n";
}

int main(int argc, char** argv)
{
    if (argc < 2) {
        usage(std::cerr);
        return 2;
    }
    std::string name = argv[1];
    if (name == "--version") {
        std::cout << "fracdesign " << FRACDESIGN_VERSION << "\n";
        return 0;
    }
    if (name == "--help" || name == "-h" || name == "help") {
        usage(std::cout);
        return 0;
    }
    auto it = command_registry().find(name);
    if (it == command_registry().end()) {
        std::cerr << "fracdesign: unknown command '" << name << "'\n";
        usage(std::cerr);
        return 2;
    }
    std::vector<std::string> args(argv + 2, argv + argc);
    for (const auto& a : args)
        if (a == "--help" || a == "-h") {
            std::cout << it->second.help;
            return 0;
        }
    try {
        return it->second.run(args);
    } catch (const UsageError& e) {
        std::cerr << "fracdesign " << name << ": " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "fracdesign " << name << ": error: " << e.what() << "\n";
        return 1;
    }
}
