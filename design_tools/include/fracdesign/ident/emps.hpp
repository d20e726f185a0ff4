// emps.hpp - the EMPS benchmark records (Janot, Gautier & Brunot 2019) as
// stored in data/real/emps/*.mat: measured motor position qm (m, load side),
// reference qg (m), controller output vir (V), optional pulses (V, see the
// README: injected into the voltage command despite the "_N" name), and the
// scalars gtau (N/V), kp (1/s), kv (V/(m/s)).
#pragma once
#include <string>
#include <vector>

#include "fracdesign/ident/servo.hpp"

namespace fracdesign {
namespace ident {

struct EmpsRecord {
    std::vector<double> t, qm, qg, vir, pulses;  // pulses empty in DATA_EMPS.mat
    double dt = 0.0;                              // mean sample time, s
    ServoController controller;                   // kp, kv, gtau from the file; u_max 10 V, delay 1
    std::vector<double> force() const;            // gtau * vir, N
};

// Reads a .mat file with the EMPS variables; throws fracdesign::io::MatError
// naming a missing variable, std::invalid_argument for vectors of different
// lengths, non-finite samples, or a time base that is not uniform to 1e-3.
EmpsRecord load_emps_mat(const std::string& path);

// Path of an EMPS file in the shared data folder (FRAC_SHARED_DIR).
std::string emps_data_path(const std::string& file);

}  // namespace ident
}  // namespace fracdesign
