#include "h5part_series.hpp"

#include <unistd.h>

#include <cerrno>
#include <utility>

#include "file_io.hpp"
#include "h5_ranks.hpp"
#include "h5_util.hpp"
#include "talus/parallel.hpp"

namespace talus::writers {

std::string step_group(std::uint64_t index) { return "Step#" + std::to_string(index); }

namespace {
bool file_exists(const std::string& path) { return ::access(path.c_str(), F_OK) == 0; }

// Frames 0.. of an existing file whose step attribute is <= last_step; `later`
// tells whether the file holds more frames after them.
std::vector<FrameInfo> frames_up_to(const std::string& path, std::uint64_t last_step, bool& later) {
  h5::QuietErrors quiet;
  std::vector<FrameInfo> out;
  later = false;
  h5::Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.valid()) return out;
  for (std::uint64_t n = 0;; ++n) {
    const std::string name = step_group(n);
    if (!h5::exists(file, name)) break;
    h5::Handle group(H5Gopen2(file, name.c_str(), H5P_DEFAULT), H5Gclose);
    FrameInfo f;
    if (!group.valid() || !h5::read_attribute(group, "step", f.step) || f.step > last_step) {
      later = true;
      break;
    }
    h5::read_attribute(group, "TimeValue", f.time);
    h5::read_attribute(group, "particles", f.particles);
    out.push_back(f);
  }
  return out;
}
}  // namespace

void H5PartSeries::start(std::string path, bool sync, RootWriter root, const std::uint64_t* resume_step,
                         const Parallel* shared_by) {
  path_ = std::move(path);
  working_ = path_ + ".tmp";
  previous_ = path_ + ".prev";
  sync_ = sync;
  root_ = std::move(root);
  ranks_ = shared_by && shared_by->ranks() > 1 ? shared_by : nullptr;
  working_exists_ = false;
  working_frames_ = 0;
  frames_ = 0;
  resumed_.clear();
  if (writes_files()) ::unlink(previous_.c_str());  // left over from a crash between two renames
  published_has_later_ = false;
  if (resume_step && file_exists(path_)) resumed_ = frames_up_to(path_, *resume_step, published_has_later_);
  frames_ = resumed_.size();
}

// The one process that creates, renames and removes the files.
bool H5PartSeries::writes_files() const { return !ranks_ || ranks_->rank() == 0; }

void H5PartSeries::catch_up(hid_t working) {
  if (working_frames_ >= frames_) return;
  h5::Handle published(h5::check(H5Fopen(path_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "cannot reopen", path_),
                       H5Fclose);
  const bool published_blocks = h5::exists(published, "Blocks");
  for (std::uint64_t i = working_frames_; i < frames_; ++i) {
    const std::string name = step_group(i);
    if (h5::exists(working, name)) H5Ldelete(working, name.c_str(), H5P_DEFAULT);  // from a failed attempt
    h5::check(H5Ocopy(published, name.c_str(), working, name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
              "cannot copy " + name + " into", working_);
    const std::string blocks = "Blocks/" + name;
    if (published_blocks && H5Lexists(published, blocks.c_str(), H5P_DEFAULT) > 0) {
      if (!h5::exists(working, "Blocks")) h5::create_group(working, "Blocks", working_);
      if (H5Lexists(working, blocks.c_str(), H5P_DEFAULT) > 0) H5Ldelete(working, blocks.c_str(), H5P_DEFAULT);
      h5::check(H5Ocopy(published, blocks.c_str(), working, blocks.c_str(), H5P_DEFAULT, H5P_DEFAULT),
                "cannot copy " + blocks + " into", working_);
    }
  }
  working_frames_ = frames_;
}

void H5PartSeries::write_working(const std::function<void(hid_t)>& write) {
  try {
    h5::Handle file;
    if (working_exists_) {
      file = h5::Handle(H5Fopen(working_.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose);
      // Unreadable (a crash while it was written) or locked (a reader still
      // holds this old copy open): start a fresh copy under a new inode.
      if (!file.valid()) {
        working_exists_ = false;
        ::unlink(working_.c_str());
      }
    }
    if (!working_exists_) {
      file = h5::create_file(working_);
      working_exists_ = true;
      working_frames_ = 0;
      root_(file, working_);
    }
    catch_up(file);
    write(file);
    h5::check(H5Fflush(file, H5F_SCOPE_GLOBAL), "cannot write", working_);
    if (!file.close()) h5::check(herr_t(-1), "cannot write", working_);
  } catch (...) {
    // Never reuse a copy whose write failed; HDF5 may even keep it open
    // internally, so the next attempt must create a new inode, not truncate.
    working_exists_ = false;
    ::unlink(working_.c_str());
    throw;
  }
}

// Collective: every rank opens the working copy and writes its rows. An error
// on any rank stops the run on every rank (ranks::abort_all), so no rank waits
// for one that gave up.
void H5PartSeries::write_shared_rows(const FrameWriter& rows, std::uint64_t index) {
  try {
    h5::Handle access = h5::shared_file_access(*ranks_, working_);
    h5::Handle file(h5::check(H5Fopen(working_.c_str(), H5F_ACC_RDWR, access), "cannot open", working_), H5Fclose);
    rows(file, index, working_);
    if (!file.close()) h5::check(herr_t(-1), "cannot write", working_);
  } catch (...) {
    if (writes_files()) {
      working_exists_ = false;
      ::unlink(working_.c_str());
    }
    throw;
  }
}

void H5PartSeries::append(const FrameWriter& rows, const FrameWriter& whole) {
  h5::QuietErrors quiet;
  const std::uint64_t index = frames_;
  if (!ranks_) {
    write_working([&](hid_t file) {
      rows(file, index, working_);
      if (whole) whole(file, index, working_);
    });
    publish_frame(index);
    return;
  }
  // Rank 0 readies the copy (root attributes, earlier frames) alone; the
  // ranks meet before each step, so that no rank opens a file another has open.
  if (writes_files()) write_working([](hid_t) {});
  ranks_->max(0.0);
  write_shared_rows(rows, index);
  ranks_->max(0.0);
  if (!writes_files()) {
    frames_ = index + 1;
    return;
  }
  if (whole) write_working([&](hid_t file) { whole(file, index, working_); });
  publish_frame(index);
}

void H5PartSeries::publish_frame(std::uint64_t index) {
  // Keep the old published copy (it lacks only this frame) as the next
  // working copy; without hard links the next frame rebuilds it from scratch.
  // Not when it still holds the interrupted run's frames after a resume's: the
  // next frame would meet its own name there.
  bool kept = false;
  if (frames_ > 0 && !published_has_later_) kept = ::link(path_.c_str(), previous_.c_str()) == 0;
  published_has_later_ = false;
  working_exists_ = false;
  publish(working_, path_, sync_);
  frames_ = index + 1;
  if (kept) {
    if (::rename(previous_.c_str(), working_.c_str()) == 0) {
      working_exists_ = true;
      working_frames_ = index;
    } else {
      ::unlink(previous_.c_str());
    }
  }
}

void H5PartSeries::finish() {
  if (!writes_files()) return;
  ::unlink(working_.c_str());
  ::unlink(previous_.c_str());
  working_exists_ = false;
}

}  // namespace talus::writers
