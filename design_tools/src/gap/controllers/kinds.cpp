// kinds.cpp - the list of controller kinds built into design_tools (kinds.hpp).
#include "kinds.hpp"

namespace fracdesign {
namespace gap {

const std::vector<BuiltinKind>& builtin_controller_kinds()
{
    static const std::vector<BuiltinKind> k = {
        {"statespace", make_statespace_controller},
    };
    return k;
}

}  // namespace gap
}  // namespace fracdesign
