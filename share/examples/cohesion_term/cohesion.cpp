#include "cohesion.hpp"

namespace example {

talus::ParamSet Cohesion::describe() {
  talus::ParamSet p{"cohesion", "pairwise cohesion a_i += -kappa sum_j m_j (x_i - x_j) W_ij (Becker & Teschner 2007)"};
  p.real("kappa").unit("m^dim/(kg s^2)").greater_than(0.0).doc("cohesion coefficient kappa");
  return p;
}

Cohesion::Cohesion(const talus::ParamValues& v) : kappa_(v.real("kappa")) {}

std::uint64_t Cohesion::add_rates(const talus::sph::PairTermInput& in) {
  struct Sums {
    talus::Vec3 acc;
  };
  const CohesionPair term{in.fluid.mass.data(), kappa_};
  auto start = [](talus::Index) { return Sums{}; };
  auto finish = [&](talus::Index i, const Sums& s) { in.rates.acceleration[i] += s.acc; };
  return talus::sph::fluid_pass(in, start, finish, term);
}

std::string Cohesion::pass_description() const {
  return "cohesion -kappa sum_j m_j (x_i - x_j) W_ij, kappa = " + std::to_string(kappa_);
}

}  // namespace example

TALUS_PLUGIN("example-cohesion", "1.0.0",
             talus::model_entry<example::Cohesion>("pair_term", "cohesion", "pairwise cohesion between fluid particles"));
