// One H5Part file that grows by one `Step#N` group per frame and is always a
// complete, closed HDF5 file on disk.
//
// HDF5 cannot append to a file crash-safely, so the series keeps two copies:
// the published file NAME (never opened for writing) and a working copy
// NAME.tmp that lags it by one frame. A frame is written as
//   1. open NAME.tmp, copy into it the frames it lacks from NAME (H5Ocopy,
//      normally just the previous one), write the new frame, close (flush);
//   2. hard-link NAME to NAME.prev, fsync and rename NAME.tmp over NAME
//      (atomic), rename NAME.prev to NAME.tmp: the old published copy becomes
//      the next working copy.
// A crash at any point leaves NAME as the last complete file; each frame is
// written twice (2x I/O, and 2x disk until close(), which removes NAME.tmp).
//
// Shared by several MPI ranks, step 1 opens NAME.tmp on every rank through
// parallel HDF5 for the rows each rank owns; rank 0 alone readies the copy
// before, adds what it holds whole (the blocks) after, and publishes.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace talus {
class Parallel;
}

namespace talus::writers {

// What a resume learns about each kept frame.
struct FrameInfo {
  double time = 0.0;
  std::uint64_t step = 0;
  std::uint64_t particles = 0;
};

class H5PartSeries {
 public:
  // Fills a fresh file's root attributes (called once per created copy).
  using RootWriter = std::function<void(hid_t file, const std::string& path)>;
  // Writes frame `index` into the open working file (groups Step#index, ...).
  using FrameWriter = std::function<void(hid_t file, std::uint64_t index, const std::string& path)>;

  // Starts a series at `path`. With `resume_step` (a restart), frames of an
  // existing file whose "step" attribute is <= *resume_step are kept and the
  // later ones dropped; otherwise the series starts empty. With `shared_by`
  // (several ranks, parallel HDF5), every rank of it starts and appends.
  void start(std::string path, bool sync, RootWriter root, const std::uint64_t* resume_step = nullptr,
             const Parallel* shared_by = nullptr);
  // One frame: `rows` writes each rank's rows (on every rank when shared);
  // `whole`, when given, what rank 0 holds whole.
  void append(const FrameWriter& rows, const FrameWriter& whole = {});
  // Removes the working copy; the published file stays.
  void finish();

  const std::string& path() const { return path_; }
  std::uint64_t frames() const { return frames_; }
  // The frames kept by a resume (empty otherwise).
  const std::vector<FrameInfo>& resumed_frames() const { return resumed_; }

 private:
  bool writes_files() const;
  void catch_up(hid_t working);
  // Opens (or creates) the working copy alone, brings it up to the published
  // frames, runs `write` on it and closes it.
  void write_working(const std::function<void(hid_t)>& write);
  void write_shared_rows(const FrameWriter& rows, std::uint64_t index);
  void publish_frame(std::uint64_t index);

  std::string path_, working_, previous_;
  bool sync_ = true;
  RootWriter root_;
  const Parallel* ranks_ = nullptr;  // set when several ranks share the file
  std::uint64_t frames_ = 0;          // frames in the published file
  std::uint64_t working_frames_ = 0;  // frames already in the working copy
  bool working_exists_ = false;
  bool published_has_later_ = false;  // a resume dropped frames still in the published file
  std::vector<FrameInfo> resumed_;
};

// Group names of the layout: "Step#N" and "Blocks/Step#N".
std::string step_group(std::uint64_t index);

}  // namespace talus::writers
