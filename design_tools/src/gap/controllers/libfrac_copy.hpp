// libfrac_copy.hpp - copying a libfrac object whose state lives in caller
// storage (Controller::clone() copies parameters and state).
//
// libfrac objects hold pointers into the storage they were built in
// (frac_gl: weights and history; frac_sos: coefficients and state;
// frac_fodamp: its own coefficient arrays). A byte copy of the object and
// of its storage is the same object once every such pointer is moved by
// the distance between the old and the new block; pointers elsewhere (NULL,
// tables shared read-only) are left alone.
#pragma once
#include <cstddef>

#include "frac/fo_op.h"

namespace fracdesign {
namespace gap {

// Moves p from [old_base, old_base + bytes) to the same offset from new_base.
template <class T>
void rebase(T*& p, const void* old_base, std::size_t bytes, const void* new_base)
{
    const char* c = reinterpret_cast<const char*>(p);
    const char* o = static_cast<const char*>(old_base);
    if (p == nullptr || c < o || c >= o + bytes) return;
    p = reinterpret_cast<T*>(const_cast<char*>(static_cast<const char*>(new_base)) + (c - o));
}

// The pointers of a fractional operator (fo_op.h) into a moved block.
inline void rebase_fo(frac_fo& op, const void* old_base, std::size_t bytes, const void* new_base)
{
    rebase(op.gl.wrev, old_base, bytes, new_base);
    rebase(op.gl.hist, old_base, bytes, new_base);
    rebase(op.sos.coeffs, old_base, bytes, new_base);
    rebase(op.sos.state, old_base, bytes, new_base);
}

}  // namespace gap
}  // namespace fracdesign
