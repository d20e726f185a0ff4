// ph_system.cpp - linear port-Hamiltonian systems (see fracdesign/models/ph_system.hpp).
#include "fracdesign/models/ph_system.hpp"

#include <algorithm>

namespace fracdesign {

StateSpace PhSystem::state_space() const
{
    StateSpace ss;
    ss.A = A();
    ss.B = B;
    ss.C = B.transpose() * Q;  // y = B^T Q x + D u, seed 004 eq. (3.93b)
    ss.D = D;
    ss.inputs = inputs;
    ss.outputs = outputs;
    ss.states = states;
    return ss;
}

double PhSystem::skew_residual() const
{
    const double scale = J.cwiseAbs().maxCoeff();
    if (scale == 0.0) return 0.0;
    return (J + J.transpose()).cwiseAbs().maxCoeff() / scale;
}

}  // namespace fracdesign
