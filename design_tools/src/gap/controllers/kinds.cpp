// kinds.cpp - the list of controller kinds built into design_tools (kinds.hpp).
#include "kinds.hpp"

namespace fracdesign {
namespace gap {

const std::vector<BuiltinKind>& builtin_controller_kinds()
{
    static const std::vector<BuiltinKind> k = {
        {"cascade", make_cascade_controller},
        {"collocated", make_collocated_controller},
        {"fopid", make_fopid_controller},
        {"statespace", make_statespace_controller},
    };
    return k;
}

}  // namespace gap
}  // namespace fracdesign
