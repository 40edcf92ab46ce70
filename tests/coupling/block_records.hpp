// Reads the block records the hdf5 writer stores (Blocks/Step#k/...) back,
// so a test can average a block's force or position over a run.
#pragma once

#include <string>
#include <vector>

#include <hdf5.h>

#include "talus/vec3.hpp"

namespace coupling_test {

struct BlockRecord {
  double time = 0.0;
  talus::Vec3 force, position;
};

// Records of block `index` at every output step of FILE (an .h5part).
inline std::vector<BlockRecord> read_block_records(const std::string& file, std::size_t index) {
  std::vector<BlockRecord> out;
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return out;
  auto read_row = [&](const std::string& path, std::size_t cols, std::size_t row, double* v) {
    const hid_t d = H5Dopen2(f, path.c_str(), H5P_DEFAULT);
    if (d < 0) return false;
    const hid_t space = H5Dget_space(d);
    hsize_t dims[2] = {0, 0};
    H5Sget_simple_extent_dims(space, dims, nullptr);
    std::vector<double> all(dims[0] * (cols ? cols : 1));
    H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, all.data());
    H5Sclose(space);
    H5Dclose(d);
    for (std::size_t c = 0; c < (cols ? cols : 1); ++c) v[c] = all[row * (cols ? cols : 1) + c];
    return true;
  };
  for (int k = 0;; ++k) {
    const std::string step = "/Step#" + std::to_string(k);
    const std::string blocks = "/Blocks/Step#" + std::to_string(k);
    if (H5Lexists(f, step.c_str(), H5P_DEFAULT) <= 0) break;
    BlockRecord r;
    const hid_t g = H5Gopen2(f, step.c_str(), H5P_DEFAULT);
    const hid_t a = H5Aopen(g, "TimeValue", H5P_DEFAULT);
    H5Aread(a, H5T_NATIVE_DOUBLE, &r.time);
    H5Aclose(a);
    H5Gclose(g);
    double v[3];
    if (!read_row(blocks + "/external_force", 3, index, v)) break;
    r.force = {v[0], v[1], v[2]};
    read_row(blocks + "/position", 3, index, v);
    r.position = {v[0], v[1], v[2]};
    out.push_back(r);
  }
  H5Fclose(f);
  return out;
}

}  // namespace coupling_test
