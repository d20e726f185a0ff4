// gap_plc_main.cpp - gap-plc: `fracdesign gap` with the PLC's controller
// kinds registered (issue 21 item 2). Same command line, output files
// (DIR/result.json, DIR/report.html, written atomically) and exit codes
// (0 done, 1 error, 2 usage): it runs fracdesign's own `gap` subcommand
// (design_tools/src/cli/cmd_gap.cpp, compiled in), after adding the kind
// "armctrl" (the ArmCtrl program in the task runtime, armctrl_controller.hpp),
// which fracdesign cannot replay since it links no plc_blocks.
#include <exception>
#include <iostream>

#include "fracbench/armctrl_controller.hpp"
#include "fracdesign/cli.hpp"

using namespace fracdesign;

int main(int argc, char** argv)
{
    fracbench::register_armctrl_controller();
    command_program() = "gap-plc";
    const auto it = command_registry().find("gap");
    if (it == command_registry().end()) {
        std::cerr << "gap-plc: the gap subcommand is not compiled in\n";
        return 1;
    }
    std::vector<std::string> args(argv + 1, argv + argc);
    for (const auto& a : args)
        if (a == "--help" || a == "-h") {
            std::cout << "gap-plc: fracdesign gap with the PLC's controller kinds (gap.closed_loop.controller\n"
                         "kind \"armctrl\": the ArmCtrl program from its parameter table, run in the task\n"
                         "runtime's lockstep, docs/gap.md). Options, outputs and exit codes as below.\n\n"
                      << it->second.help;
            return 0;
        }
    if (args.empty()) {
        std::cerr << it->second.help;
        return 2;
    }
    try {
        return it->second.run(args);
    } catch (const UsageError& e) {
        std::cerr << "gap-plc: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "gap-plc: error: " << e.what() << "\n";
        return 1;
    }
}
