// Warnings a run raises while it goes on (a particle that left the domain, a
// wave gauge that finds no surface): the host prints each as it comes, on
// stderr and also with --quiet, and lists them first in the run summary.
// Stages and writers add to World::warnings; a text already there is kept once.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

namespace talus {

class WarningLog {
 public:
  void add(std::string text) {
    if (std::find(texts_.begin(), texts_.end(), text) == texts_.end()) texts_.push_back(std::move(text));
  }
  const std::vector<std::string>& all() const { return texts_; }

 private:
  std::vector<std::string> texts_;
};

}  // namespace talus
