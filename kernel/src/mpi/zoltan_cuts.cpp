#include "zoltan_cuts.hpp"

#include <zoltan.h>

#include <stdexcept>

namespace talus::mpi {

namespace {

void check(int code, const char* call) {
  if (code != ZOLTAN_OK && code != ZOLTAN_WARN) throw std::runtime_error(std::string("Zoltan: ") + call + " failed");
}

}  // namespace

ZoltanCuts::ZoltanCuts(MPI_Comm comm, int dim, const std::string& method, double imbalance) : dim_(dim) {
  static const bool initialised = [] {
    float version = 0.0f;
    return Zoltan_Initialize(0, nullptr, &version) == ZOLTAN_OK;
  }();
  if (!initialised) throw std::runtime_error("Zoltan: Zoltan_Initialize failed");
  MPI_Comm_size(comm, &ranks_);
  MPI_Comm_rank(comm, &rank_);
  zz_ = Zoltan_Create(comm);
  if (!zz_) throw std::runtime_error("Zoltan: Zoltan_Create failed");
  const std::string tol = std::to_string(imbalance);
  Zoltan_Set_Param(zz_, "DEBUG_LEVEL", "0");
  Zoltan_Set_Param(zz_, "LB_METHOD", method.c_str());
  Zoltan_Set_Param(zz_, "NUM_GID_ENTRIES", "1");
  Zoltan_Set_Param(zz_, "NUM_LID_ENTRIES", "1");
  Zoltan_Set_Param(zz_, "OBJ_WEIGHT_DIM", "1");
  // Owners come from the kept cuts (owner()), so Zoltan returns no lists.
  Zoltan_Set_Param(zz_, "RETURN_LISTS", "NONE");
  Zoltan_Set_Param(zz_, "KEEP_CUTS", "1");  // for owner() and ranks_meeting()
  Zoltan_Set_Param(zz_, "IMBALANCE_TOL", tol.c_str());
  // Points that share a cut coordinate go to one side: the caller passes cell
  // centres, so a cell is never split between ranks.
  if (method == "RCB") Zoltan_Set_Param(zz_, "RCB_RECTILINEAR_BLOCKS", "1");

  Zoltan_Set_Num_Obj_Fn(
      zz_, [](void* self, int* ierr) {
        *ierr = ZOLTAN_OK;
        return static_cast<int>(static_cast<ZoltanCuts*>(self)->points_.size());
      },
      this);
  Zoltan_Set_Obj_List_Fn(
      zz_, [](void* self, int, int, ZOLTAN_ID_PTR gids, ZOLTAN_ID_PTR lids, int wdim, float* weights, int* ierr) {
        const auto& cuts = *static_cast<ZoltanCuts*>(self);
        // Zoltan only moves cuts, never objects: the local index serves as
        // both ids.
        for (std::size_t i = 0; i < cuts.points_.size(); ++i) {
          lids[i] = static_cast<ZOLTAN_ID_TYPE>(i);
          gids[i] = static_cast<ZOLTAN_ID_TYPE>(i);
          if (wdim > 0) weights[i] = cuts.weights_.empty() ? 1.0f : cuts.weights_[i];
        }
        *ierr = ZOLTAN_OK;
      },
      this);
  Zoltan_Set_Num_Geom_Fn(
      zz_, [](void* self, int* ierr) {
        *ierr = ZOLTAN_OK;
        return static_cast<ZoltanCuts*>(self)->dim_;
      },
      this);
  Zoltan_Set_Geom_Multi_Fn(
      zz_, [](void* self, int, int, int n, ZOLTAN_ID_PTR, ZOLTAN_ID_PTR lids, int dim, double* xyz, int* ierr) {
        const auto& cuts = *static_cast<ZoltanCuts*>(self);
        for (int k = 0; k < n; ++k) {
          const Vec3& p = cuts.points_[lids[k]];
          for (int a = 0; a < dim; ++a) xyz[k * dim + a] = p[a];
        }
        *ierr = ZOLTAN_OK;
      },
      this);
}

ZoltanCuts::~ZoltanCuts() { Zoltan_Destroy(&zz_); }

std::vector<int> ZoltanCuts::partition(std::span<const Vec3> points, std::span<const float> weights) {
  points_ = points;
  weights_ = weights;
  int changes = 0, gid_entries = 0, lid_entries = 0, imports = 0, exports = 0;
  ZOLTAN_ID_PTR import_gids = nullptr, import_lids = nullptr, export_gids = nullptr, export_lids = nullptr;
  int *import_procs = nullptr, *import_parts = nullptr, *export_procs = nullptr, *export_parts = nullptr;
  const int code = Zoltan_LB_Partition(zz_, &changes, &gid_entries, &lid_entries, &imports, &import_gids,
                                       &import_lids, &import_procs, &import_parts, &exports, &export_gids,
                                       &export_lids, &export_procs, &export_parts);
  points_ = {};
  weights_ = {};
  check(code, "Zoltan_LB_Partition");
  Zoltan_LB_Free_Part(&import_gids, &import_lids, &import_procs, &import_parts);
  Zoltan_LB_Free_Part(&export_gids, &export_lids, &export_procs, &export_parts);
  has_cuts_ = true;
  // Each point goes where the kept cuts place it, not where the partition's
  // lists send it: RIB and HSFC may split points of one place between parts,
  // and the halos (ranks_meeting) and later moves (owner) know only the cuts.
  std::vector<int> owners(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) owners[i] = owner(points[i]);
  return owners;
}

int ZoltanCuts::owner(const Vec3& point) const {
  double xyz[3] = {point.x, point.y, point.z};
  int rank = 0;
  check(Zoltan_LB_Point_Assign(zz_, xyz, &rank), "Zoltan_LB_Point_Assign");
  return rank;
}

void ZoltanCuts::ranks_meeting(const Vec3& lo, const Vec3& hi, std::vector<int>& ranks) const {
  box_ranks_.resize(static_cast<std::size_t>(ranks_));
  int count = 0;
  check(Zoltan_LB_Box_Assign(zz_, lo.x, lo.y, lo.z, hi.x, hi.y, hi.z, box_ranks_.data(), &count),
        "Zoltan_LB_Box_Assign");
  ranks.insert(ranks.end(), box_ranks_.begin(), box_ranks_.begin() + count);
}

}  // namespace talus::mpi
