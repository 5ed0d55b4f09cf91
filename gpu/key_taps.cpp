#include "gpu/key_taps.h"

#include <algorithm>

namespace tallow::gpu {

void KeyTaps::pressed(int key) {
  if (std::find(presses_.begin(), presses_.end(), key) == presses_.end()) presses_.push_back(key);
}

std::vector<int> KeyTaps::tapsToHold(const std::function<bool(int)>& down) {
  std::vector<int> taps;
  for (const int key : presses_)
    if (!down(key)) taps.push_back(key);
  presses_.clear();
  return taps;
}

}  // namespace tallow::gpu
