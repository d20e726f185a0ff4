// kinds.hpp - the controller kinds built into design_tools (controller.hpp);
// one file per kind in this folder, each listed in builtin_controller_kinds().
#pragma once
#include <vector>

#include "fracdesign/gap/controller.hpp"

namespace fracdesign {
namespace gap {

struct BuiltinKind {
    const char* kind;
    ControllerFactory make;
};
const std::vector<BuiltinKind>& builtin_controller_kinds();

// statespace.cpp: the linear discrete state space of the first document version.
std::unique_ptr<Controller> make_statespace_controller(const nlohmann::json& doc, const ControllerContext& ctx);

}  // namespace gap
}  // namespace fracdesign
