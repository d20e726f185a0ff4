// families.cpp - the registry of gap-bench's plant families (families.hpp).
#include "fracbench/families.hpp"

#include <stdexcept>

namespace fracbench {

const std::vector<Family>& families()
{
    static const std::vector<Family> v = {twomass_family(), servo_family(), foprocess_family(), arm_family()};
    return v;
}

const Family& family(const std::string& name)
{
    std::string names;
    for (const Family& f : families()) {
        if (f.name == name) return f;
        names += (names.empty() ? "" : ", ") + f.name;
    }
    throw std::invalid_argument("gap-bench: --family '" + name + "' is not a family (allowed: " + names + ")");
}

}  // namespace fracbench
