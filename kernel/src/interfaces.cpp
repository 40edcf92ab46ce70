// Key functions of the SDK's polymorphic types: defining the virtual
// destructors here puts their type information in libtalus only, so
// dynamic_cast and exceptions work across plugins built with hidden
// visibility (DESIGN.md, "Shape of the runtime").
#include "talus/blocks.hpp"
#include "talus/boundary.hpp"
#include "talus/dda/contact_model.hpp"
#include "talus/eos.hpp"
#include "talus/error.hpp"
#include "talus/rheology.hpp"
#include "talus/smoothing_kernel.hpp"
#include "talus/sph/boundary_pass.hpp"
#include "talus/sph/pair_term.hpp"
#include "talus/stage.hpp"
#include "talus/writer.hpp"

namespace talus {

namespace {
std::string without_nul(const std::string& what) {
  std::string text;
  for (char c : what) text += c == '\0' ? std::string("\\u0000") : std::string(1, c);
  return text;
}
}  // namespace

Error::Error(const std::string& what) : std::runtime_error(without_nul(what)) {}
Error::Error(const char* what) : std::runtime_error(what) {}
Error::~Error() = default;
InputError::~InputError() = default;
RunError::~RunError() = default;
Model::~Model() = default;
SmoothingKernel::~SmoothingKernel() = default;
EquationOfState::~EquationOfState() = default;
Rheology::~Rheology() = default;
Boundary::~Boundary() = default;
Stage::~Stage() = default;
Writer::~Writer() = default;
BlockSet::~BlockSet() = default;
dda::ContactModel::~ContactModel() = default;
sph::SphBoundary::~SphBoundary() = default;
sph::PairTerm::~PairTerm() = default;

void Rheology::apparent_viscosity(std::span<const Index>, const ViscosityInputs&, double*) const {
  throw RunError("this rheology model has no apparent viscosity (it is a basal-stress model only)");
}

void Rheology::basal_shear(std::span<const Index>, const BasalInputs&, double*) const {
  throw RunError("this rheology model has no basal shear stress for depth-integrated flow");
}

}  // namespace talus
