// The episodes (and events) of one realization, for the regression tests.
#pragma once
#include <vector>

#include "stickslip/episode.hpp"

namespace stickslip::regression {

struct recorded {
  std::vector<episode> episodes;
  std::vector<event> events;
  void on_event(const event& e) { events.push_back(e); }
  void on_segment(const segment&) {}
  void on_episode(const episode& e) { episodes.push_back(e); }
};

}  // namespace stickslip::regression
