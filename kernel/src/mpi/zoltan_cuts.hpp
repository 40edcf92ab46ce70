// Zoltan's geometric partition of the particles over the ranks (recursive
// coordinate bisection by default, RIB or HSFC on request): which rank owns a
// point, and which ranks' regions a box reaches. The cuts are Zoltan's; this
// class only feeds it coordinates and weights and keeps its handle.
#pragma once

#include <mpi.h>

#include <array>
#include <span>
#include <string>
#include <vector>

#include "talus/config.hpp"
#include "talus/vec3.hpp"

struct Zoltan_Struct;

namespace talus::mpi {

class TALUS_API ZoltanCuts {
 public:
  // method: "RCB", "RIB" or "HSFC"; imbalance: Zoltan's IMBALANCE_TOL (1.1 = 10 %).
  ZoltanCuts(MPI_Comm comm, int dim, const std::string& method, double imbalance);
  ~ZoltanCuts();
  ZoltanCuts(const ZoltanCuts&) = delete;
  ZoltanCuts& operator=(const ZoltanCuts&) = delete;

  // New cuts for this rank's points (each rank passes its own, none twice):
  // returns the rank each point goes to.
  std::vector<int> partition(std::span<const Vec3> points, std::span<const float> weights);
  bool has_cuts() const { return has_cuts_; }
  int owner(const Vec3& point) const;
  // Ranks whose region meets the box [lo, hi], appended to `ranks`.
  void ranks_meeting(const Vec3& lo, const Vec3& hi, std::vector<int>& ranks) const;

 private:
  Zoltan_Struct* zz_ = nullptr;
  int dim_ = 3;
  int rank_ = 0, ranks_ = 1;
  bool has_cuts_ = false;
  mutable std::vector<int> box_ranks_;  // Zoltan writes up to one entry per rank
  // What the callbacks read during partition().
  std::span<const Vec3> points_;
  std::span<const float> weights_;
};

}  // namespace talus::mpi
