// What `stickslip plot` is asked to draw: its flags as plain values
// (plot.hpp plans the figure from them, docs/plot.md).
#pragma once
#include <string>
#include <vector>

namespace stickslip::study {

struct plot_request {
  std::string y, x, by;          // --y, --x, --by ("" when not given)
  std::vector<std::string> at;   // each --at: "NAME=VALUE[,NAME=VALUE...]"
  std::string histogram;         // --histogram STAT
  std::string survival;          // --survival stick|slip
  bool time = false, map = false, logx = false;
};

}  // namespace stickslip::study
