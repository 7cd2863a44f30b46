// Private forwarding header, not installed: src/core/fast_lanes.cpp and
// src/core/episode.cpp still include this old path. The header is public now
// as stickslip/fast_math.hpp; delete this file once they include that.
#pragma once
#include "stickslip/fast_math.hpp"
