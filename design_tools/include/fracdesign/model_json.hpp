// model_json.hpp - the one versioned JSON model format of fracdesign (docs/model_format.md).
//
//   {"schema": "frac.model", "version": 1, "kind": "<kind>", "units": "SI", ...kind fields...}
//
// kinds: "beam" (PS Timoshenko beam, seed 004), "arm" (drive + beam, full or Krylov-reduced),
// "antenna" (seed 000 eq. (25), structures I-VI), "collocated" (seed 002), "foprocess" (seed 001) and
// "statespace" (a plain LTI model, continuous or discrete). Read and written by `fracdesign model` and
// by the gap diagnosis. Every error is one line naming the offending field, e.g.
//   model: field 'beam.L': must be a finite number > 0
#pragma once
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <variant>

#include "fracdesign/models/antenna.hpp"
#include "fracdesign/models/arm.hpp"
#include "fracdesign/models/collocated.hpp"
#include "fracdesign/models/foprocess.hpp"
#include "fracdesign/models/lti.hpp"
#include "fracdesign/models/timoshenko_beam.hpp"

namespace fracdesign {

constexpr const char* kModelSchema = "frac.model";
constexpr int kModelVersion = 1;
// Largest collocation count N of a beam or arm document (4N beam states; also the arm document's bound).
constexpr int kModelNMax = 200;

// A malformed or inconsistent model document; what() is one line and names the field.
struct ModelFormatError : std::runtime_error {
    ModelFormatError(const std::string& field, const std::string& problem);
    std::string field;
};

struct BeamModelSpec {
    TimoshenkoParams beam;
    int N = 9;
    Collocation collocation = Collocation::GaussLegendre;
};

struct ArmModelSpec {
    TimoshenkoParams beam;
    DriveParams drive;
    ArmOptions options;  // options.reduce false: the full 4N + 4 model
};

struct AntennaModelSpec {
    AntennaLink link;
    AntennaStructure structure = AntennaStructure::VI;
    AntennaDamping<double> damping{0, 0, 0, 0};  // must respect the structure's fixed values (Table 2)
};

// The seed 002 collocated arm: the paper's printed robot (document fields m2_lb, m2_range_lb) or a
// physical two-lumped-mass arm (link, masses, moment_gain, inner_loop, damping); docs/model_format.md.
struct CollocatedModelSpec {
    CollocatedArm arm = feliu_robot_arm();  // the plant is arm.plant(arm.m2_nominal)
    bool damped = true;
    CollocatedModelSpec() = default;
    CollocatedModelSpec(double m2_lb, bool damped_) : damped(damped_) { arm.m2_nominal = m2_lb; }
    CollocatedModelSpec(const CollocatedArm& a, bool damped_) : arm(a), damped(damped_) {}
};

struct FoProcessModelSpec {
    FoProcess process;
};

using ModelSpec =
    std::variant<BeamModelSpec, ArmModelSpec, AntennaModelSpec, CollocatedModelSpec, FoProcessModelSpec, StateSpace>;

// "beam", "arm", "antenna", "collocated", "foprocess" or "statespace".
std::string model_kind(const ModelSpec& m);

// Writes the document (schema, version, kind, units and the kind's fields).
nlohmann::json model_to_json(const ModelSpec& m);
// Reads and validates a document; throws ModelFormatError.
ModelSpec model_from_json(const nlohmann::json& j);
// Files: ModelFormatError also for unreadable files and invalid JSON (field "<file>").
ModelSpec read_model_file(const std::string& path);
void write_model_file(const std::string& path, const ModelSpec& m);

// The LTI model of a rational kind (beam: the 4N-state PH model; arm: 4 + r states; collocated: the
// modal model of P; statespace: itself). Throws std::invalid_argument for antenna and foprocess, whose
// transfer functions are irrational.
StateSpace model_state_space(const ModelSpec& m);

// Structure names "I".."VI" <-> enum.
std::string antenna_structure_name(AntennaStructure s);
AntennaStructure antenna_structure_from_name(const std::string& s);  // std::invalid_argument if unknown

}  // namespace fracdesign
