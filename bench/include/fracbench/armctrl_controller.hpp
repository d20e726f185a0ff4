// armctrl_controller.hpp - the gap replay's controller kind "armctrl": the
// plc_blocks ArmCtrl program, loaded from the binary parameter table the PLC
// loads, run in the task runtime's lockstep (plc_rt.h) one task cycle per
// record sample (issue 21 item 2; docs/gap.md "ArmCtrl as the controller").
//
// design_tools links neither plc_blocks nor the task runtime
// (ARCHITECTURE.md), so this kind lives above it: a program that wants to
// replay ArmCtrl records (gap-plc, the Python package) calls
// register_armctrl_controller() once before it reads a nominal document;
// fracdesign itself refuses the kind with a pointer to gap-plc.
//
// Document object (gap.closed_loop.controller):
//   {"kind": "armctrl",
//    "table": "ctrl.bin",                      FRPT file, relative to the model document
//    "inputs": {"MotorAngle": "motor_angle",   each a closed_loop.measured output
//               "MotorVelocity": "motor_velocity",   or a closed_loop.references column
//               "TipRate": "imu_rate",
//               "Start": "start",              optional: Start = (value != 0) per sample
//               "Run": "run"},                 optional: the tasks cycle from its first nonzero sample
//    "output": "torque_cmd"}                   the plant input TorqueSetpoint drives (default: the first)
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fracbench {

// Adds the kind "armctrl" to the gap diagnosis's controller registry
// (fracdesign::gap::register_controller_kind). Idempotent, thread-safe.
void register_armctrl_controller();

// Why ArmCtrl's _INIT refuses the parameter table `bytes`, as the PLC's
// ParTable and armctrl_params_from_table name it: the FRPT field that failed
// validation (frac_ptable_open: "crc32", "entry.rows of entry 3 'ff'", ...), else
// the entry of ArmCtrl's layout that is missing, of the wrong size or out of
// range, else the StatusID of the block that refused a value; "" when _INIT
// accepts the table. `ts` is set to the table's cycle time when accepted.
std::string armctrl_table_refusal(const std::vector<std::uint8_t>& bytes, double* ts = nullptr);

}  // namespace fracbench
